"""Sheet 8: balancing -- the linkage in position 0 with its counterweights at a GOST 2.302
length scale (each counterweight a disc at its radius and angle from its link's axis, the
disc's area in proportion to its mass), the hodograph of the shaking force over a turn at a
standard μF with the reported positions marked (and the force left with the counterweights),
and a rotor's balancing: the imbalances m·r reduced to each correction plane laid head to tail
at a standard μ, the correction closing each polygon (one plane: static balancing; two:
dynamic, U_i (z2 - z_i)/(z2 - z1) in plane 1 and U_i (z_i - z1)/(z2 - z1) in plane 2)."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..drawings.balancing import counterweight_points
from ..report.figures import scale_mark
from .sheet1 import _xy
from .frame import FRAME, TB_H, fit_text, length_scale, std_mu

ROTOR_W = 240.0      # mm: the rotor's column beside the linkage's two panels


def _linkage(cv, ctx, results, box) -> dict:
    """The linkage at position 0 with its counterweights in ``box`` (x0, y0, x1, y1; mm)."""
    x0, y0, x1, y1 = box
    e = results["kinematics"][0]
    links = results["structure"]["links"]
    ground = list((results["structure"].get("ground") or {}))
    cws = counterweight_points(results)
    b = results["balancing"]
    pts = {p: _xy(e, p) for lk in links for p in lk["points"]} | {p: _xy(e, p) for p in ground if p in e["points"]}
    every = np.array(list(pts.values()) + [x for _, x in cws.values()])
    lo, hi = every.min(axis=0), every.max(axis=0)
    span = np.maximum(hi - lo, 1e-9)
    unit, label = length_scale(max(span[0] * 1000.0 / (x1 - x0 - 40.0), span[1] * 1000.0 / (y1 - y0 - 50.0)))
    k = 1000.0 / unit                                                  # sheet mm per m
    c_model, c_sheet = (lo + hi) / 2, np.array([(x0 + x1) / 2, (y0 + y1) / 2 - 8.0])

    def M(p):
        return c_sheet + (np.asarray(p, float) - c_model) * k

    cv.layer = "text"
    fit_text(cv, x0, y1 - 2.0, ctx.t("bal.sheet_linkage"), 5.0, x1 - x0, bold=True)
    cv.mtext(x0, y1 - 9.0, "μ", 3.5, sub="l", after=f" = {unit / 1000.0:g} {ctx.t('bal.m_per_mm')}   ({scale_mark(ctx.lang)} {label})")
    cv.layer = "contour"
    for lk in links:
        q = [M(pts[p]) for p in lk["points"] if p in pts]
        if len(q) >= 2:
            cv.polyline(q, width=0.7, closed=len(q) > 2)
    drawn = {}
    for p, xy in pts.items():
        s = M(xy)
        drawn[p] = s
        if p in ground:
            cv.layer = "thin"
            cv.polyline([s, s + (-3.0, -5.0), s + (3.0, -5.0)], width=0.35, closed=True)
            cv.hatch(s + (-5.0, -5.0), s + (5.0, -5.0), (0.0, -1.0), depth=2.0, step=1.6, width=0.25)
            cv.layer = "contour"
        cv.circle(s, 1.0, width=0.5)
        cv.layer = "text"
        cv.mtext(s[0] + 2.0, s[1] + 2.5, p, 3.5, italic=True)
        cv.layer = "contour"
    mmax = max((float(c["m"]) for c in (b.get("counterweights") or {}).values()), default=1.0) or 1.0
    discs = {}
    for role, (P, X) in cws.items():
        c = b["counterweights"][role]
        sp, sx = M(P), M(X)
        rad = 2.5 + 5.0 * math.sqrt(float(c["m"]) / mmax)
        cv.polyline([sp, sx], width=0.7)
        cv.circle(sx, rad, stroke="#000", fill="#bbbbbb", width=0.5)
        cv.layer = "text"
        cv.mtext(sx[0] + rad + 1.5, sx[1] - 1.5, f"{c['link']}: m = {float(c['m']):.4g} {ctx.t('bal.unit_kg')}, "
                 f"r = {float(c['r']) * 1000:.4g} {ctx.t('bal.unit_mm')}", 3.5)
        cv.layer = "contour"
        discs[role] = (sx, rad)
    return {"unit": unit, "scale": label, "mu_l": unit / 1000.0, "points": drawn, "discs": discs, "M": M}


def _hodograph(cv, ctx, results, box) -> dict:
    """The shaking force's hodograph (Fx, Fy) over a turn at μF, its positions marked."""
    x0, y0, x1, y1 = box
    b = results["balancing"]
    h = b["hodograph"]
    fx, fy = np.asarray(h["Fx"], float), np.asarray(h["Fy"], float)
    # the curve's box with the origin in it, at the largest standard μF that fits the panel
    lo = np.array([min(float(fx.min()), 0.0), min(float(fy.min()), 0.0)])
    hi = np.array([max(float(fx.max()), 0.0), max(float(fy.max()), 0.0)])
    span = np.maximum(hi - lo, 1e-12)
    mu = std_mu(max(span[0] / (x1 - x0 - 40.0), span[1] / (y1 - y0 - 70.0)))
    centre = np.array([(x0 + x1) / 2 - 6.0, (y0 + y1) / 2 - 20.0])
    o = centre - (lo + hi) / 2 / mu
    a0, a1 = o + lo / mu - 10.0, o + hi / mu + 12.0         # the axes beyond the curve
    cv.layer = "text"
    fit_text(cv, x0, y1 - 2.0, ctx.t("bal.sheet_hodograph"), 5.0, x1 - x0, bold=True)
    cv.mtext(x0, y1 - 9.0, "μ", 3.5, sub="F", after=f" = {mu:g} {ctx.t('bal.N_per_mm')}")
    cv.layer = "dimensions"
    cv.arrow((a0[0], o[1]), (a1[0], o[1]), width=0.3, head=2.5)
    cv.arrow((o[0], a0[1]), (o[0], a1[1]), width=0.3, head=2.5)
    cv.layer = "text"
    cv.mtext(a1[0] + 1.0, o[1] - 4.0, "F", 3.5, italic=True, sub="x")
    cv.mtext(o[0] + 2.0, a1[1] - 1.0, "F", 3.5, italic=True, sub="y")
    cv.layer = "contour"
    curve = o + np.c_[fx, fy] / mu
    cv.polyline(curve, width=0.6)
    marks = {}
    idx = list((results.get("positions") or {}).get("index") or range(len(b["shaking"])))
    from ..report.course import grid_size
    from .sheet1 import shown_index
    n_grid = grid_size(results)
    for i, s in zip(idx, b["shaking"]):
        p = o + np.array([float(s["Fx"]), float(s["Fy"])]) / mu
        cv.circle(p, 0.8, width=0.4, fill="#000")
        cv.layer = "text"
        cv.mtext(p[0] + 1.8, p[1] + 1.8, shown_index({"index": i}, n_grid), 2.5)     # an extra: '12*' 
        cv.layer = "contour"
        marks[i] = p
    after = None
    if "Fx_balanced" in h:
        fb = o + np.c_[np.asarray(h["Fx_balanced"], float), np.asarray(h["Fy_balanced"], float)] / mu
        if float(np.max(np.hypot(*(fb - o).T))) < 0.5:      # nothing left to draw: the point O
            cv.circle(o, 1.6, stroke="#c00000", fill="#c00000", width=0.4)
        else:
            cv.polyline(fb, color="#c00000", width=0.6)
        left = float(b["max"].get("F_balanced", 0.0))      # round-off of zero is 0 in the results already
        cv.layer = "text"
        cv.mtext(x0, y1 - 22.0, f"{ctx.t('bal.sheet_after')}: F", 3.5, sub="max",
                 after=f" = {left:.4g} {ctx.t('bal.unit_N')}", color="#c00000")
        cv.layer = "contour"
        after = fb
    cv.layer = "text"
    cv.mtext(x0, y1 - 16.0, f"{ctx.t('bal.sheet_before')}: F", 3.5, sub="max",
             after=f" = {float(b['max']['F']):.4g} {ctx.t('bal.unit_N')}")
    return {"origin": o, "mu_F": mu, "curve": curve, "marks": marks, "after": after}


def reduced_imbalances(rotor: dict) -> list[list[complex]]:
    """Per correction plane, the imbalances U_i = m_i r_i e^{i angle_i} (kg*m) as that plane
    takes them: all of them with one plane; U_i (z2 - z_i)/(z2 - z1) and U_i (z_i - z1)/(z2 - z1)
    with two."""
    U = [float(m["m"]) * float(m["r"]) * complex(math.cos(math.radians(float(m["angle"]))),
                                                 math.sin(math.radians(float(m["angle"]))))
         for m in rotor["masses"]]
    zs = [float(c["z"]) for c in rotor["corrections"]]
    if len(zs) == 1:
        return [U]
    z1, z2 = zs
    return [[u * (z2 - float(m["z"])) / (z2 - z1) for u, m in zip(U, rotor["masses"])],
            [u * (float(m["z"]) - z1) / (z2 - z1) for u, m in zip(U, rotor["masses"])]]


def _rotor(cv, ctx, results, box) -> dict:
    """The polygons of the imbalances per correction plane, each closed by its correction."""
    x0, y0, x1, y1 = box
    r = results["balancing"]["rotor"]
    red = reduced_imbalances(r)
    corr = [float(c["mr"]) * complex(math.cos(math.radians(float(c["angle"]))), math.sin(math.radians(float(c["angle"]))))
            for c in r["corrections"]]
    n = len(red)
    cell_h = (y1 - y0 - 26.0) / n
    seqs = [np.cumsum([0j] + list(us) + [c]) for us, c in zip(red, corr)]
    wide = max(float(np.ptp(q.real)) for q in seqs)
    tall = max(float(np.ptp(q.imag)) for q in seqs)
    mu = std_mu(max(wide / (x1 - x0 - 30.0), tall / (cell_h - 26.0), 1e-300))
    cv.layer = "text"
    fit_text(cv, x0, y1 - 2.0, ctx.t("bal.sheet_rotor"), 5.0, x1 - x0, bold=True)
    cv.mtext(x0, y1 - 9.0, "μ", 3.5, sub="U", after=f" = {mu:g} {ctx.t('bal.kgm_per_mm')}")
    polys = []
    for k, (us, c, seq) in enumerate(zip(red, corr, seqs)):
        top = y1 - 16.0 - k * cell_h
        cv.layer = "text"
        head = ctx.t("bal.sheet_plane", k=k + 1) if n == 2 else ctx.t("bal.sheet_static")
        fit_text(cv, x0, top - 2.0, head, 3.5, x1 - x0)
        # the polygon's points from its start, then placed so its box sits in the cell
        P = np.c_[seq.real, seq.imag] / mu
        lo, hi = P.min(axis=0), P.max(axis=0)
        start = np.array([(x0 + x1) / 2, top - 14.0 - (cell_h - 14.0) / 2]) - (lo + hi) / 2
        P = P + start
        cv.layer = "contour"
        for i in range(len(us)):
            cv.arrow(P[i], P[i + 1], width=0.5, head=2.5)
            mid = (P[i] + P[i + 1]) / 2
            cv.layer = "text"
            cv.mtext(mid[0] + 1.5, mid[1] + 1.5, f"U{i + 1}", 3.5, italic=True)
            cv.layer = "contour"
        cv.arrow(P[-2], P[-1], color="#c00000", width=0.7, head=3.0)
        mid = (P[-2] + P[-1]) / 2
        cv.layer = "text"
        cv.mtext(mid[0] + 1.5, mid[1] - 4.0, "U", 3.5, italic=True, color="#c00000",
                 sub=f"{ctx.t('bal.correction_sub')}{k + 1}")
        cv.mtext(x0, top - 8.0, f"m = {float(r['corrections'][k]['m']):.4g} {ctx.t('bal.unit_kg')}, "
                 f"r = {float(r['corrections'][k]['r']) * 1000:.4g} {ctx.t('bal.unit_mm')}, "
                 f"α = {float(r['corrections'][k]['angle']):.4g}°", 3.5)
        polys.append(P)
    return {"mu_U": mu, "polygons": polys}


def build(cv, results, task, lang="en") -> dict:
    from ..report.context import ReportContext
    from ..report.sections import load
    load("balancing")                # registers its texts in the three languages
    ctx = ReportContext(results=results, task=task, lang=lang, out_dir=Path("."), env=None)
    b = results["balancing"]
    x0f, y0f, x1f, y1f = FRAME
    out: dict = {"scale": "—"}
    has_linkage = "shaking" in b and results.get("kinematics")
    right = x1f - 5.0
    if b.get("rotor"):
        left_of_rotor = right - ROTOR_W if has_linkage else x0f + 5.0
        out["rotor"] = _rotor(cv, ctx, results, (left_of_rotor, y0f + TB_H + 8.0, right, y1f - 5.0))
        right = left_of_rotor - 15.0
    if has_linkage:
        mid = x0f + 5.0 + (right - x0f - 5.0) * 0.52
        out["linkage"] = _linkage(cv, ctx, results, (x0f + 5.0, y0f + 8.0, mid - 8.0, y1f - 5.0))
        out["hodograph"] = _hodograph(cv, ctx, results, (mid + 8.0, y0f + 8.0, right, y1f - 5.0))
        out["scale"] = out["linkage"]["scale"]
    return out
