"""Sheet 9: the gear train of the drive (the task's ``drive_train``: pairs and planetary
stages from the motor to the crank) -- its kinematic scheme with the picture of linear
velocities beside it on one length scale (left), the plan of angular velocities (right), each
at a standard scale as large as its part of the sheet allows (the drawings of
tmm_cli.drawings.train, the report's too), and above the title block the stages: tooth
numbers, the ratio computed and the one read from the plan."""
from __future__ import annotations

from typing import TYPE_CHECKING

from .. import locales
from .frame import FRAME, TB_H, length_scale
from .prims import PrimCanvas, place

if TYPE_CHECKING:
    from ..task import Task

LEFT = 0.55          # the scheme and the picture's share of the sheet's width


def build(cv, results: dict, task: Task | None, lang: str = "en") -> dict:
    from ..drawings import train
    d = results["drive_train"]
    W = locales.of("drive_train", "words", lang)
    x0f, y0f, x1f, y1f = FRAME

    def make(w, h):
        c = PrimCanvas(w, h)
        c.layer = "contour"
        return c
    # the scheme and the picture: the left part, the frame's whole height
    left_w = (x1f - x0f) * LEFT
    scheme, sc = train.scheme_and_picture(make, d, frame=left_w - 15.0, height=y1f - y0f - 25.0, k_max=50.0)
    sx, sy = x0f + 8.0, y1f - 14.0 - scheme.h
    cv.mtext(x0f + 5, y1f - 7, W["train.scheme"], 5.0, bold=True)
    place(cv, scheme, sx, sy)
    # the plan of angular velocities: the right part, above the stages and the title block
    rows = [f"{W['train.stage']} {i + 1}: z = {' / '.join(str(v) for v in s['z'])},  u = {float(s['ratio']):.6g},  "
            f"{W['train.ratio_plan']} = {float(pr['ratio_plan']):.6g}"
            for i, (s, pr) in enumerate(zip(d["stages"], d["velocity_plan"]["stages"]))]
    rows.append(f"{W['train.overall']} = {float(d['ratio']):.6g}")
    rx = x0f + left_w + 10.0
    table_top = y0f + TB_H + 8.0 + 6.0 * len(rows)
    plan, sp = train.angular_plan(make, d, frame=x1f - rx - 10.0, height=y1f - table_top - 30.0, scales=sc)
    px, py = rx + 5.0, y1f - 14.0 - plan.h
    cv.mtext(rx, y1f - 7, W["train.plan_title"], 5.0, bold=True)
    place(cv, plan, px, py)
    for k, line in enumerate(rows):          # left of the title block's width: a row is long
        cv.mtext(rx, table_top - 6.0 * (k + 1), line, 3.5)
    unit, label = length_scale(sc["mu_l"] * 1000.0)        # the scheme's μl: a GOST 2.302 scale
    return {"scale": label, "unit": unit, "mu_l": sc["mu_l"], "mu_v": sc["mu_v"], "mu_omega": sp["mu_omega"],
            "H": sp["H"], "scheme": (sx, sy, scheme), "plan": (px, py, plan)}
