"""Report section 'planetary': chosen tooth numbers, ratio check, candidates, the scheme
(half section above the axis) and the velocity (Kutzbach) plan."""
from __future__ import annotations

import numpy as np

from ... import locales
from ...numfmt import num

I18N = locales.table("planetary", "words")


def _rows_of(p):
    """Wheels as (name, y_bottom, y_top, x_position, internal) rectangles in a half section."""
    s, z, m = p["scheme"], p["z"], p["m"]
    r = {k: m * v / 2 for k, v in z.items()}
    a = p["aw"]
    if s == "A":
        return [("1", 0, r["z1"], 0, False), ("2", a - r["z2"], a + r["z2"], 0, False),
                ("3", r["z3"], r["z3"] + 0.15 * a, 0, True)], a
    if s == "B":
        return [("1", 0, r["z1"], 0, False), ("2", a - r["z2"], a + r["z2"], 0, False),
                ("3", a - r["z3"], a + r["z3"], 1, False), ("4", r["z4"], r["z4"] + 0.15 * a, 1, True)], a
    if s == "C":
        return [("1", 0, r["z1"], 0, False), ("2", a - r["z2"], a + r["z2"], 0, False),
                ("3", a - r["z3"], a + r["z3"], 1, False), ("4", 0, r["z4"], 1, True)], a
    return [("1", r["z1"], r["z1"] + 0.15 * a, 0, False), ("2", a - r["z2"], a + r["z2"], 0, False),
            ("3", a - r["z3"], a + r["z3"], 1, False), ("4", r["z4"], r["z4"] + 0.15 * a, 1, True)], a


def figure(ctx, p):
    fp = ctx.figures
    fig, (ax, av) = fp.new_figure(170, 90, ncols=2, gridspec_kw={"width_ratios": [1.2, 1]})
    rows, a = _rows_of(p)
    for name, y0, y1, col, fixed in rows:
        x0 = col * 1.2
        ax.rectangle((x0, y0 * 1e3), 0.8, (y1 - y0) * 1e3, fill=False, lw=1.2, hatch="///" if fixed else None)
        ax.annotate(name, (x0 + 0.4, (y0 + y1) / 2 * 1e3), ha="center", va="center")
    ax.plot([-0.3, 2.3], [0, 0], "k-.", lw=0.6)
    ax.plot([2.2, 2.2, 0.4], [0, a * 1e3, a * 1e3], "k-", lw=1.0)
    ax.annotate("H", (2.25, a * 0.5e3))
    ax.set_xlim(-0.5, 2.6)
    ax.set_ylabel(ctx.t("plan.mm"))
    ax.set_xticks([])
    vp = p["velocity_plan"]
    for pt in vp["points"]:
        av.plot([0, pt["v"]], [pt["y"] * 1e3, pt["y"] * 1e3], color="0.6", lw=0.5)
        av.plot(pt["v"], pt["y"] * 1e3, "ko", ms=2.5)
        av.annotate(pt["name"].split()[0], (pt["v"], pt["y"] * 1e3), textcoords="offset points", xytext=(3, 2))
    ys = np.array([0, max(pt["y"] for pt in vp["points"])])
    for name, ln in vp["lines"].items():
        yy = np.linspace(0, ys[1], 20)
        lab = {"H": ctx.t("plan.carrier"), "satellite": ctx.t("plan.satellite")}.get(name, name)
        av.plot(ln["slope"] * (yy - ln["y0"]), yy * 1e3, label=lab)
    av.axvline(0, color="k", lw=0.6)
    av.set_xlabel(ctx.t("plan.v_axis"))
    av.legend(fontsize=6)
    return fig


def build(ctx) -> str | None:
    p = (ctx.results or {}).get("planetary")
    if not p:
        return None
    f, t = ctx.fmt, ctx.t
    ch = p.get("checks", {})
    sname = t(f"plan.scheme_{p.get('scheme', '')}")
    if sname.startswith("plan.scheme_"):
        sname = p.get("scheme_name", "")
    info = [(t("plan.scheme", s=p.get("scheme", ""), name=sname), ""),
            (t("plan.z"), ", ".join(f"{k} = {v}" for k, v in p["z"].items())),
            (t("plan.required"), f(p.get("required"), 6)), (t("plan.ratio"), f(p["ratio"], 6)),
            (t("plan.error"), num(100 * p['ratio_error'], ".3f") + " %"),
            *([(t("plan.best"), num(100 * p['best_ratio_error'], ".3f") + " %")] if p.get("best_ratio_error") is not None
              else []),
            (t("plan.plan_ratio"), f(p.get("ratio_plan"), 6))]
    conds = [(t("plan.coaxial"), bool(ch.get("coaxial"))),
             (t("plan.assembly", p=ch.get("assembly_p")), bool(ch.get("assembly"))),
             (t("plan.adjacency", m=f(ch.get("adjacency_margin"), 3)), bool(ch.get("adjacency"))),
             (t("plan.undercut"), bool(ch.get("undercut")))]
    conds = [(k, t("common.yes") if v else t("common.no")) for k, v in conds]
    cands = [(", ".join(str(v) for v in c["z"].values()), f(c["ratio"], 6),
              num(100 * c['ratio_error'], ".3f") + " %", c["size"]) for c in p.get("candidates", [])]
    fig = ctx.svg(figure(ctx, p), "planetary-scheme")
    return ctx.render("sections/planetary.html.j2", info=info, conds=conds, cands=cands, fig=fig,
                      ratio_head=t("plan.ratio"))
