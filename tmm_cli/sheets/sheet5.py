"""Sheet 5: the gear mesh - both whole wheels with their pitch, rolling, base, tip and root
circles, teeth at the mesh (the report's tooth outline), the line of action N1N2 with the
active part B1B2 and the pole P, at a GOST 2.302 scale."""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from .. import locales
from ..report.figures import scale_mark
from .frame import FRAME, length_scale

if TYPE_CHECKING:
    from ..task import Task

TXT = locales.table("sheets", "sheet5")
LAMBDA_LO, LAMBDA_HI = -5.0, 1.5       # the course draws λ over this range (the report's figure too)
TEETH = 5          # teeth drawn of each wheel, centred on the mesh


def working_parts(w, axis_angle: float, centre, r_low) -> list[np.ndarray]:
    """The working part of each flank of the window's teeth (Wheel.outline's teeth): its points
    from the radius of the lowest point of contact r_low (results: gears.lowest_active.r_p)
    up to the tip circle, in m."""
    if r_low is None:
        return []
    fl = w.flank()
    on = np.asarray(fl.r) >= float(r_low) * (1 - 1e-12)
    r, psi = np.asarray(fl.r)[on], np.asarray(fl.psi)[on]
    out = []
    for k in range(-(TEETH // 2), TEETH - TEETH // 2):
        ax = axis_angle + 2.0 * np.pi * k / w.z
        for ang in (ax - psi, ax + psi):
            out.append(np.c_[centre[0] + r * np.cos(ang), centre[1] + r * np.sin(ang)])
    return out


def closed_window(X, Y, centre, rf: float, step_deg: float = 1.0) -> np.ndarray:
    """The outline of a window of teeth (Wheel.outline: tooth after tooth, root point to root
    point) as a closed contour: the spaces between the teeth along the root circle (arcs, not
    chords) and the window closed under its teeth by the root circle, so that each tooth,
    the end ones too, is a closed outline standing on the rim."""
    c = np.asarray(centre, float)
    P = np.c_[np.asarray(X, float), np.asarray(Y, float)]
    r = np.hypot(*(P - c).T)
    on_root = np.abs(r - rf) <= 1e-9 * rf

    def arc(p, q):                 # root-circle points strictly between p and q, the short way
        a0 = np.arctan2(*(p - c)[::-1])
        d = (np.arctan2(*(q - c)[::-1]) - a0 + np.pi) % (2 * np.pi) - np.pi
        n = int(abs(np.degrees(d)) / step_deg)
        t = a0 + d * np.arange(1, n + 1) / (n + 1)
        return c + rf * np.c_[np.cos(t), np.sin(t)]

    out = [P[:1]]
    for k in range(1, len(P)):
        if on_root[k - 1] and on_root[k] and np.hypot(*(P[k] - P[k - 1])) > 1e-12:
            out.append(arc(P[k - 1], P[k]))
        out.append(P[k:k + 1])
    out.append(arc(P[-1], P[0]))    # under the window's teeth back to its first point
    return np.concatenate(out)


def build(cv, results: dict, task: Task | None, lang: str = "en") -> dict:
    from ..gears import mesh_layout
    from ..report.figures import place_labels
    from ..drawings.mesh import action_points, wheels
    g = results["gears"]
    T = TXT[lang]
    x0f, y0f, x1f, y1f = FRAME
    w1, w2 = wheels(g)
    (c1, a1), (c2, a2) = mesh_layout((w1, w2), g["aw"], 0.0)
    # the whole wheels: wheel 1 at the origin, wheel 2 above it at aw
    box = (x0f + 10.0, y0f + 65.0, x1f - x0f - 20.0, y1f - y0f - 95.0)
    ra1, ra2 = g["ra"]
    lo = np.array([-max(ra1, ra2), -ra1])
    hi = np.array([max(ra1, ra2), g["aw"] + ra2])
    unit, label = length_scale(max((hi - lo)[0] * 1000.0 / box[2], (hi - lo)[1] * 1000.0 / box[3]))
    O = np.array([box[0] + box[2] / 2, box[1] + box[3] / 2]) - (lo + hi) / 2 * 1000.0 / unit

    def M(p):
        return O + np.asarray(p, float) * 1000.0 / unit

    cv.mtext(x0f + 5, y1f - 6, T["mesh"], 5.0, bold=True)
    mu_l = unit / 1000.0
    cv.mtext(x0f + 5, y1f - 13, "μ", 3.5, sub="l", after=f" = {mu_l:g} {T['m']}/{T['mm']}   ({scale_mark(lang)} {label})")
    # each number named (z1, z2, x1, x2), the items apart as the language lists numbers ("; " where
    # the decimal comma is written: "x = 0,44944, -0,155323" read as one list)
    from ..numfmt import list_sep
    sep = list_sep(lang)
    cv.mtext(x0f + 5, y1f - 19, sep.join((
        f"m = {g['m'] * 1000:g} {T['mm']}", f"z1 = {g['z'][0]}", f"z2 = {g['z'][1]}", f"x1 = {g['x'][0]:g}",
        f"x2 = {g['x'][1]:g}", f"αw = {g['alpha_w']:.3f}°", f"aw = {g['aw'] * 1000:.3f} {T['mm']}",
        f"εα = {g['eps_alpha']:.3f}")), 3.5)
    drawn = {}
    for i, (c, ax_ang, w) in enumerate(((c1, a1, w1), (c2, a2, w2))):
        cv.layer = "contour"
        X, Y = w.outline(axis_angle=ax_ang, teeth=TEETH, centre=c)
        cv.polyline([M(p) for p in closed_window(X, Y, c, g["rf"][i])], width=0.7, closed=True)
        # the working parts of the profiles: each flank from the lowest point of contact up
        work = working_parts(w, ax_ang, c, (g.get("lowest_active") or {}).get("r_p", [None, None])[i])
        for part in work:
            cv.polyline([M(p) for p in part], width=1.4)
        drawn[(i, "working")] = work
        cv.layer = "thin"
        for key in ("rw", "r", "rb", "ra", "rf"):
            R = g[key][i] * 1000.0 / unit
            cv.circle(M(c), R, fill=None, width=0.25)
            drawn[(i, key)] = R
    cv.layer = "dimensions"
    pts = {k: M(v) for k, v in action_points(g, c2).items()}
    cv.line(pts["N1"], pts["N2"], width=0.3)
    cv.line(pts["B1"], pts["B2"], width=1.0)
    for p in pts.values():
        cv.circle(p, 0.8, width=0.3)
    names = list(pts) + ["O1", "O2"]
    anchors = [(*pts[k], None) for k in pts] + [(*M(c1), (1.0, -1.0)), (*M(c2), (1.0, -1.0))]
    pos = place_labels(anchors, 60.0, avoid=[a[:2] for a in anchors], step=5.0,
                       segments=[(pts["N1"], pts["N2"])])
    for name, (x, y) in zip(names, pos):
        cv.mtext(x, y, name[0], 3.5, anchor="middle", italic=True, sub=name[1:] or None, halo=True)   # over the teeth
    cv.layer = "contour"
    for c in (c1, c2):
        cv.circle(M(c), 1.2, width=0.5)
    sliding = draw_sliding(cv, g, (x0f + 10.0, y0f + 70.0, 280.0, 220.0), lang) if g.get("sliding") else None
    return {"unit": unit, "scale": label, "mu_l": mu_l, "points": pts, "M": M, "drawn": drawn, "sliding": sliding}


def draw_sliding(cv, g, box, lang="en") -> dict:
    """The specific-sliding diagrams λ1, λ2 over X along the line of action from N1 (X at a
    GOST 2.302 scale, λ at a standard μλ, over -5 <= λ <= 1.5), the ends of the active
    part B1, B2 and the pole P marked."""
    from .frame import std_mu
    from .graph import draw_graph
    T = TXT[lang]
    sl = g["sliding"]
    x0, y0, w, h = box
    X = np.asarray(sl["X"], float)
    unit, label = length_scale(float(X.max()) * 1000.0 / (w - 30.0))
    mu_x = unit / 1000.0                                    # m per mm
    mu_l = std_mu((LAMBDA_HI - LAMBDA_LO) / (h - 30.0))
    origin = (x0 + 12.0, y0 + 8.0 - LAMBDA_LO / mu_l)
    cv.mtext(x0 + 2.0, y0 + h - 2.0, T["sliding"], 5.0, bold=True)
    curves = []
    for key, col in (("lambda1", "#1f5fbf"), ("lambda2", "#b03a2e")):
        v = np.array([np.nan if y is None else y for y in sl[key]], float)
        v = np.where((v < LAMBDA_LO) | (v > LAMBDA_HI), np.nan, v)
        curves.append((X, v, col))
    pts = draw_graph(cv, origin, curves, mu_x, mu_l, x_len=float(X.max()) / mu_x, y_up=LAMBDA_HI / mu_l + 4.0,
                     y_down=-LAMBDA_LO / mu_l + 2.0, x_sym="X", y_sym="λ",
                     mu_text=f"μλ = {mu_l:g} 1/{T['mm']},  μX = {mu_x:g} {T['m']}/{T['mm']} ({scale_mark(lang)} {label})")
    for p, (_, _, col), name in zip(pts, curves, ("1", "2")):
        if len(p):
            end = p[np.argmax(p[:, 0])] if name == "1" else p[np.argmin(p[:, 0])]
            cv.mtext(end[0] + (2.0 if name == "1" else -2.0), end[1] + 3.0, "λ", 3.5, italic=True, sub=name,
                     anchor="start" if name == "1" else "end", color=col)
    cv.layer = "thin"
    marks = {}
    for name, x in sl["marks"].items():
        if x is None:
            continue
        xm = origin[0] + float(x) / mu_x
        cv.line((xm, origin[1] + LAMBDA_LO / mu_l), (xm, origin[1] + LAMBDA_HI / mu_l), width=0.18, dash="3 1.5")
        cv.mtext(xm + 1.0, origin[1] + LAMBDA_LO / mu_l - 3.5, name[0], 3.5, italic=True, sub=name[1:] or None)
        marks[name] = xm
    return {"unit": unit, "scale": label, "mu_x": mu_x, "mu_lambda": mu_l, "origin": origin, "pts": pts,
            "curves": curves, "marks": marks}
