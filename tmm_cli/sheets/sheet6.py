"""Sheet 6: the planetary gear - its scheme (half section above the axis, the wheels at
their pitch radii, the carrier H, the fixed wheel hatched) at a GOST 2.302 scale and,
beside it on the same radii, the picture of linear velocities (Kutzbach) at a standard
μv, each link's velocity line from the axis; i1H read from the picture as the ratio of
the tangents of the lines of wheel 1 and the carrier (ψ1, ψH)."""
from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .. import locales
from ..report.figures import scale_mark
from .frame import FRAME, TB_H, length_scale, std_mu

if TYPE_CHECKING:
    from ..task import Task

COL_W, WHEEL_W = 34.0, 22.0      # mm: a row of wheels' column, a wheel's width in the scheme


def build(cv, results: dict, task: Task | None, lang: str = "en") -> dict:
    from ..report.context import ReportContext
    from ..report.sections import load
    P = load("planetary")            # registers its texts in the three languages
    ctx = ReportContext(results=results, task=task, lang=lang, out_dir=Path("."), env=None)
    p = results["planetary"]
    rows, a = P._rows_of(p)
    info = draw_train(cv, ctx, p, rows, a, ctx.t("plan.sketch"), ctx.t("plan.v_axis"), lang)
    vx, y0f = info["points"]["O"][0], FRAME[1]
    # the ratio from the picture: tan ψ1 / tan ψH
    tg = locales.of("sheets", "sheet6", lang)["tan"]          # tan, or tg as the course writes it
    vp = p["velocity_plan"]
    cv.mtext(vx - 20.0, y0f + TB_H + 12.0, f"i₁H = {tg} ψ₁ / {tg} ψH = {float(vp['tan_psi_1']):.4g} / "
             f"{float(vp['tan_psi_H']):.4g} = {float(p['ratio_plan']):.4g}", 3.5)
    return info


def draw_train(cv, ctx, p, rows, a, heading: str, v_axis: str, lang: str) -> dict:
    """The scheme of a planetary train (``rows``: its wheels as (name, r_bottom, r_top, column,
    fixed) in m, ``a`` the satellites' axle radius) at a GOST 2.302 scale and its picture of
    linear velocities (``p["velocity_plan"]``) at a standard μv on the same radii; returns the
    drawn points, lines and wheels with the scales (sheet mm)."""
    from .sheet1 import UNITS
    U = UNITS[lang]
    mm = ctx.t("plan.mm")
    x0f, y0f, x1f, y1f = FRAME
    top = max(y1 for _, _, y1, _, _ in rows)                       # m
    axis_y = y0f + TB_H + 40.0                                     # the axis of rotation on the sheet
    unit, label = length_scale(top * 1000.0 / (y1f - axis_y - 60.0))
    k = 1000.0 / unit                                              # sheet mm per m

    def Y(r):
        return axis_y + r * k

    # the scheme
    sx = x0f + 40.0
    ncol = max(c for *_, c, _ in rows) + 1
    cv.mtext(x0f + 5, y1f - 7, heading, 5.0, bold=True)
    cv.mtext(x0f + 5, y1f - 14, "μ", 3.5, sub="l", after=f" = {unit / 1000.0:g} {U['m']}/{mm}   ({scale_mark(lang)} {label})")
    cv.layer = "thin"
    right = sx + ncol * COL_W + 30.0
    cv.line((sx - 15.0, axis_y), (right + 10.0, axis_y), width=0.25, dash="6 1.5 1 1.5")
    cv.layer = "contour"
    wheels = {}
    for name, y0, y1, col, fixed in rows:
        x = sx + col * COL_W
        cv.polyline([(x, Y(y0)), (x + WHEEL_W, Y(y0)), (x + WHEEL_W, Y(y1)), (x, Y(y1))], width=0.7, closed=True)
        if fixed:
            cv.hatch((x - 2.0, Y(y1)), (x + WHEEL_W + 2.0, Y(y1)), (0.0, 1.0), depth=3.0, step=2.5, width=0.35)
        cv.mtext(x - 3.0, (Y(y0) + Y(y1)) / 2, name, 3.5, anchor="end")
        wheels[name] = (x, Y(y0), x + WHEEL_W, Y(y1))
    # the carrier: from the axis at the right, up to the satellites' axle, to their middle
    hx = sx + ncol * COL_W + 12.0
    cv.polyline([(hx, axis_y), (hx, Y(a)), (sx + WHEEL_W / 2, Y(a))], width=0.7)
    cv.circle((sx + WHEEL_W / 2, Y(a)), 1.2, width=0.5)
    cv.mtext(hx + 3.0, (axis_y + Y(a)) / 2, "H", 3.5, italic=True)
    zs = ",  ".join(f"z{key[1:]} = {v}" for key, v in p["z"].items())
    cv.mtext(x0f + 5, y1f - 21, f"{zs},  m = {float(p['m']) * 1000:g} {mm},  k = {p.get('satellites', '')}", 3.5)
    # the velocity picture: v to the right of its axis, the radii as in the scheme
    vp = p["velocity_plan"]
    vmax = max(abs(float(q["v"])) for q in vp["points"]) or 1.0
    mu_v = std_mu(vmax / 160.0)
    vneg = max(0.0, -min(float(q["v"]) for q in vp["points"])) / mu_v    # a differential's lines go left too
    vx = right + 80.0 + vneg
    cv.mtext(vx + 4.0, Y(top) + 12.0, v_axis, 3.5)
    cv.mtext(vx + 4.0, Y(top) + 5.0, "μ", 3.5, sub="v", after=f" = {mu_v:g} ({U['m/s']})/{mm}")
    cv.layer = "thin"
    cv.arrow((vx, axis_y), (vx, Y(top) + 15.0), width=0.3, head=2.5)
    cv.arrow((vx - 30.0 - vneg, axis_y), (vx + vmax / mu_v + 30.0, axis_y), width=0.3, head=2.5)
    cv.mtext(vx + vmax / mu_v + 32.0, axis_y - 4.0, "v", 3.5, italic=True)
    pts = {}
    for q in vp["points"]:
        y, v = Y(float(q["y"])), vx + float(q["v"]) / mu_v
        cv.line((sx - 10.0, y), (max(vx, v) + 6.0, y), width=0.18, dash="3 1.5")    # the radius carried over
        cv.circle((v, y), 0.8, width=0.4)
        name = q["name"].split()[0]
        if name != "O":
            cv.mtext(v + 2.5, y + 3.0, name, 3.5, italic=True)
        pts[name] = (v, y)
    cv.layer = "contour"
    lines = {}
    for name, ln in vp["lines"].items():
        slope = float(ln["slope"])
        # v = slope (y - y0); a link that only translates (a differential's satellite standing
        # still while its centre moves: no y0) has v = its centre's speed at every y
        y0 = None if ln.get("y0") is None else float(ln["y0"])
        const = float(ln.get("v_centre") or 0.0)

        def v_of(y, slope=slope, y0=y0, const=const):
            return slope * (y - y0) if y0 is not None else const + 0.0 * y
        # the line over the radii of the points of its link (those it passes through)
        on = [float(q["y"]) for q in vp["points"] if abs(float(q["v"]) - v_of(float(q["y"]))) <= 1e-9 * vmax]
        on += [y0] if y0 is not None else []
        if not on:
            continue
        ys = np.array([min(on), max(on)])
        vs = v_of(ys)
        seg = [(vx + v / mu_v, Y(y)) for v, y in zip(vs, ys)]
        cv.line(seg[0], seg[1], width=0.6)
        tag = {"H": "H", "satellite": "2"}.get(name, name)
        at = np.asarray(seg[0]) + 0.55 * (np.asarray(seg[1]) - np.asarray(seg[0]))
        cv.mtext(at[0] + 3.0, at[1], tag, 3.5, italic=True)
        lines[name] = seg
    return {"unit": unit, "scale": label, "mu_l": unit / 1000.0, "mu_v": mu_v, "points": pts, "lines": lines,
            "wheels": wheels, "axis_y": axis_y, "k": k}
