"""Sheet 7: the differential -- a planetary scheme with no member fixed, drawn as sheet 6 draws a
planetary gear (half section above the axis, the wheels at their pitch radii, the carrier H) at
a GOST 2.302 scale, beside it the picture of linear velocities at the members' own speeds (each
member a straight line from the axis, negative speeds to the left) at a standard μv on the same
radii; Willis' ratio u read from the picture as the ratio of the differences of the lines'
tangents, u = (tg ψ1 - tg ψH)/(tg ψlast - tg ψH)."""
from __future__ import annotations

from pathlib import Path

from .frame import FRAME, TB_H
from .sheet6 import draw_train


def tangents(info: dict) -> dict[str, float]:
    """tg ψ of every drawn member line: its run along v over its rise along r (sheet mm),
    proportional to the member's angular speed (v = ω r)."""
    out = {}
    for name, ((xa, ya), (xb, yb)) in info["lines"].items():
        if abs(yb - ya) > 1e-9:
            out[name] = (xb - xa) / (yb - ya)
    return out


def build(cv, results, task, lang="en") -> dict:
    from ..report.context import ReportContext
    from ..report.sections import load
    P = load("planetary")            # the scheme's rows and the planetary words the drawing shares
    load("differential")
    ctx = ReportContext(results=results, task=task, lang=lang, out_dir=Path("."), env=None)
    d = results["differential"]
    p = {**d, "aw": d["velocity_plan"]["aw"]}
    rows, a = P._rows_of(p)
    rows = [(name, y0, y1, col, False) for name, y0, y1, col, _ in rows]      # no member is fixed
    heading = f"{ctx.t('diff.title')}: {ctx.t('diff.scheme', s=d['scheme'], n=d['satellites'])}"
    info = draw_train(cv, ctx, p, rows, a, heading, ctx.t("diff.v_axis"), lang)
    last = d["last"]
    tg = tangents(info)
    den = tg[last] - tg["H"]
    # the picture gives u only where the last wheel turns relative to the carrier (nothing
    # turning at all, or the train turning as one body, leaves 0/0: Willis' u alone is written)
    u_plan = (tg["1"] - tg["H"]) / den if den != 0 else None
    from .. import locales
    t = locales.of("sheets", "sheet6", lang)["tan"]          # tan, or tg as the course writes it
    _, y0f, _, _ = FRAME
    vx = info["points"]["O"][0]
    willis = f"{ctx.t('diff.willis')}: u = {float(d['u']):.4g}"
    cv.mtext(vx - 20.0, y0f + TB_H + 12.0,
             f"u = ({t} ψ₁ − {t} ψH) / ({t} ψ{last} − {t} ψH) = {u_plan:.4g}   ({willis})" if u_plan is not None
             else willis, 3.5)
    info["u_plan"] = u_plan
    return info
