"""The gear pair as the report's mesh figure and sheet 5 draw it: its two wheels and the
points of its line of action."""
from __future__ import annotations

import math

import numpy as np


def wheels(g) -> list:
    """The two wheels of the results' gear pair (gears.drawing.wheels: the tooth outlines)."""
    from ..gears.drawing import wheels as made
    return list(made(g))


def action_points(g, c2) -> dict:
    """N1, N2, B1, B2, P on the line of action (m), wheel 1 at the origin, wheel 2 at c2."""
    awa = math.radians(g["alpha_w"])
    P = np.array([0.0, g["rw"][0]])
    d = np.array([math.cos(awa), -math.sin(awa)])
    la = g["line_of_action"]
    s_n1 = -(P @ d)
    sg = math.copysign(1.0, (np.array(c2) - P) @ d - s_n1)
    return {name: P + (s_n1 + sg * q) * d for name, q in
            (("N1", 0.0), ("N2", la["N1N2"]), ("B1", la["N1B1"]), ("B2", la["N1B2"]), ("P", la["N1P"]))}
