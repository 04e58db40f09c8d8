"""The table at the division points of the rise and of the return (the course divides each
moving phase into 6 or 8 equal parts and builds the diagrams and the profile on them)."""
from __future__ import annotations

import math

import numpy as np

from .motion import RETURN, RISE, Motion


def division_table(motion: Motion, divisions: int, rocker: bool, pressure_angle=None) -> list[dict]:
    """Entries {phase, k, phi, s, ds, d2s, pressure_angle} for k = 0..divisions, rise then return.

    Each value is that of the phase's own law (one-sided at the phase's ends).  ``phi`` is in
    deg from the start of the rise; s in m (rocker: deg), ds and d2s per rad.
    ``pressure_angle(s, s1)`` gives the unsigned pressure angle in rad (None: 0, flat face)."""
    out = []
    x = np.arange(divisions + 1) / divisions
    for ph, name, start, span in ((RISE, "rise", motion.starts[0], motion.rise),
                                  (RETURN, "return", motion.starts[2], motion.ret)):
        s, s1, s2, _ = motion.phase(ph, x)
        th = np.zeros_like(s) if pressure_angle is None else np.degrees(pressure_angle(s, s1))
        for k in range(divisions + 1):
            out.append({"phase": name, "k": k, "phi": round(math.degrees(start + x[k] * span), 9),
                        "s": float(math.degrees(s[k]) if rocker else s[k]),
                        "ds": float(s1[k]), "d2s": float(s2[k]), "pressure_angle": float(th[k])})
    return out
