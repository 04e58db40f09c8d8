"""Report section 'drive_train': the stages with their ratios and speeds, the candidates, the
motor and the flywheel on its shaft, and the drawings of tmm_cli.drawings.train (the sheet draws
them too) -- the kinematic scheme of the train, the linear-velocity picture beside it (same
length scale) and the angular-velocity plan, whose segments give every ratio, compared with the
analytic one."""
from __future__ import annotations

import math

from ... import locales
from ...numfmt import localize, num

I18N = locales.table("drive_train", "words")


def scheme_and_picture(d: dict, lang_t) -> str:
    """The kinematic scheme (left) and the linear-velocity picture (right) on one length scale."""
    from ...drawings import train
    from ..svgdraw import Canvas
    return train.scheme_and_picture(Canvas, d)[0].to_svg()


def angular_plan(d: dict) -> str:
    """The plan of angular velocities."""
    from ...drawings import train
    from ..svgdraw import Canvas
    return train.angular_plan(Canvas, d)[0].to_svg()


def _pct(x) -> str:
    s = f"{100 * x:.3f} %"
    return localize(s[1:] if s.startswith("-0.000") else s)


def build(ctx) -> str | None:
    d = (ctx.results or {}).get("drive_train")
    if not d:
        return None
    f, t = ctx.fmt, ctx.t
    vp = d["velocity_plan"]
    rows = []
    for i, (s, pr) in enumerate(zip(d["stages"], vp["stages"])):
        kind = (t("train.pair_int") if s.get("internal") else t("train.pair")) if s["type"] == "pair" \
            else t("train.planetary", s=s["scheme"])
        rows.append((i + 1, kind, " / ".join(str(v) for v in s["z"]), f(s["ratio"], 8), f(pr["ratio_plan"], 8),
                     num(abs(pr['ratio_plan'] - s['ratio']), ".1e")))
    info = [(t("train.overall"), f(d["ratio"], 8))]
    if d.get("required") is not None:
        info += [(t("train.required"), f(d["required"], 6)), (t("train.error"), _pct(d["ratio_error"])),
                 (t("train.best"), _pct(d["best_ratio_error"]))]
    if d.get("split"):
        info.append((t("train.split"), "; ".join(f"{s['stage'] + 1}: {f(s['ratio'], 5)}" for s in d["split"])))
    shafts = []
    for i, w in enumerate(d["shafts"]):
        shafts.append((t("train.input") if i == 0 else t("train.out_of", i=i), f(w, 6),
                       f(abs(w) * 30 / math.pi, 6), ctx.sense(w)))
    # the stages numbered from 1, as the task file lists them (results.json: from 0)
    sats = [(i + 1, f(s["omega_carrier"], 6), f(s["omega_satellite"], 6), f(s["omega_satellite_rel"], 6),
             ", ".join(f"{t('train.c.' + k)}: {t('train.yes') if v else t('train.no')}" for k, v in s["checks"].items()))
            for i, s in enumerate(d["stages"]) if s["type"] == "planetary"]
    cands = [(" | ".join("/".join(str(v) for v in z) for z in c["z"]), f(c["ratio"], 6),
              "—" if c.get("ratio_error") is None else _pct(c["ratio_error"]), c["size"])
             for c in d.get("candidates", [])] if d.get("synthesised") else []
    motor = []
    fw = (ctx.results or {}).get("flywheel") or {}
    if "J_motor_shaft" in fw:
        motor = [(t("train.J"), f(fw["J"], 5)), (t("train.J_motor"), f(fw["J_motor_shaft"], 5)),
                 (t("train.Jn_motor"), f(fw["J_n_motor_shaft"], 5)), (t("train.GD2"), f(fw["GD2_motor_shaft"], 5))]
        if d.get("motor_power_computed"):
            motor.insert(0, (t("train.power"), f(d["motor_power"], 5)))
    from .. import figures
    figs = [(figures.named(scheme_and_picture(d, t), "train-scheme"), t("train.scheme")),
            (figures.named(angular_plan(d), "train-angular-plan"), t("train.plan"))]
    return ctx.render("sections/drive_train.html.j2", info=info, rows=rows, shafts=shafts, sats=sats,
                      cands=cands, motor=motor, figs=figs, rank=rank_words(d.get("rank", "size"), ctx.lang))


def rank_words(rank: str, lang: str) -> str:
    """The candidates' order in words ('by size', in the report's language), as in the task data table."""
    from .task import WORDS
    return WORDS.get(lang, {}).get(rank, rank)
