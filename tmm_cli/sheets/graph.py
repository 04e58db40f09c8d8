"""Diagrams on a sheet: axes with arrows, ticks, the scale factors and curves, every
point drawn at value / μ from its axis."""
from __future__ import annotations

import numpy as np


def draw_graph(cv, origin, curves, mu_x: float, mu_y: float, *, x_len: float, y_up: float, y_down: float,
               x_sym: str, y_sym: str, mu_text: str, ticks=(), x0_value: float = 0.0) -> list[np.ndarray]:
    """Axes at origin (mm) and the curves [(x values, y values, colour)], x from
    x0_value at mu_x per mm, y at mu_y per mm; ticks: [(x value, label)].
    Returns the drawn points (mm) of each curve."""
    ox, oy = origin
    cv.layer = "dimensions"
    cv.arrow((ox, oy), (ox + x_len + 8.0, oy), width=0.3, head=2.5)
    cv.arrow((ox, oy - y_down), (ox, oy + y_up), width=0.3, head=2.5)
    base, _, sub = x_sym.partition("_")          # 'J_var': the letter and its subscript
    cv.mtext(ox + x_len + 10.0, oy - 3.5, base, 3.5, italic=True, sub=sub or None)
    cv.mtext(ox - 2.0, oy + y_up - 2.0, y_sym, 3.5, anchor="end", italic=True)
    cv.mtext(ox + 3.0, oy + y_up - 2.0, mu_text, 2.5)
    for xv, lab in ticks:
        xt = ox + (xv - x0_value) / mu_x
        cv.line((xt, oy - 1.0), (xt, oy + 1.0), width=0.25)
        if lab:
            cv.mtext(xt + 1.2, oy - 3.0, lab, 2.5)
    cv.layer = "contour"
    out = []
    for xs, ys, color in curves:
        pts = np.c_[ox + (np.asarray(xs, float) - x0_value) / mu_x, oy + np.asarray(ys, float) / mu_y]
        pts = pts[np.isfinite(pts).all(axis=1)]
        cv.polyline(pts, color=color, width=0.6)
        out.append(pts)
    return out
