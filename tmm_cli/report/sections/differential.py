"""Report section 'differential': the members' speeds (Willis), the satellite's, the torques
and powers with the loss in the meshes, the conditions of the given teeth and the velocity
picture (Smirnov's method). Reads numbers only from results["differential"]; its words are
the catalogues' topic 'differential'
(tmm_cli/locales/<lang>/differential.yaml)."""
from __future__ import annotations

from ...numfmt import num
from ... import locales

I18N = locales.table("differential", "words")


def figure(ctx, d):
    """The velocity picture: v(y) of every member on the radial line through a satellite's centre."""
    from ..svgchart import subplots
    vp = d["velocity_plan"]
    fig, ax = subplots(150, 90)
    ys = [pt["y"] for pt in vp["points"]]
    top = max(ys) * 1.08
    last = d["last"]
    for name, ln in vp["lines"].items():
        if name == "satellite":
            y0, y1 = min(ys[1], ys[3], vp["aw"]), max(ys[1], ys[3], vp["aw"])
            yy = [y0, y1]
            vv = [ln["v_centre"] + ln["slope"] * (y - vp["aw"]) for y in yy]
            label = ctx.t("diff.satellite")
        else:
            r = {"1": ys[1], last: ys[3], "H": vp["aw"]}[name]
            yy, vv = [0.0, r], [0.0, ln["slope"] * r]
            label = ctx.t("diff.carrier") if name == "H" else ctx.t("diff.wheel", k=name)
        ax.plot(vv, [y * 1e3 for y in yy], lw=1.2, label=label)
    for pt in vp["points"]:
        ax.plot([pt["v"]], [pt["y"] * 1e3], "ko", ms=3)
        ax.annotate(pt["name"], (pt["v"], pt["y"] * 1e3), xytext=(3, 2))
    ax.axvline(0.0, color="k", lw=0.6)
    ax.set_ylim(0.0, top * 1e3)
    ax.set_xlabel(ctx.t("diff.v_axis"))
    ax.set_ylabel(ctx.t("diff.y_axis"))
    ax.grid(True)
    ax.legend(fontsize=6)
    return fig


def build(ctx) -> str | None:
    d = (ctx.results or {}).get("differential")
    if not d:
        return None
    f, t = ctx.fmt, ctx.t
    last = d["last"]
    given = set(d["given"]["speeds"])
    ch = d["checks"]
    info = [(t("diff.scheme", s=d["scheme"], n=d["satellites"]), ""),
            (t("diff.z"), ", ".join(f"{k} = {v}" for k, v in d["z"].items())),
            (t("diff.u", last=last), f(d["u"], 6))]
    names = {"1": t("diff.wheel", k="1"), last: t("diff.wheel", k=last), "H": t("diff.carrier"),
             "satellite": t("diff.satellite")}
    speeds = [(names[k], f(w, 6), f(d["speeds_rpm"][k], 6), t("diff.given") if k in given else t("diff.computed"))
              for k, w in d["speeds"].items()]
    torques = None
    notes = [t("diff.sat_rel", w=f(d["satellite_relative"], 6))]
    if d.get("torques"):
        torques = [(names[k], f(d["torques"][k], 6), f(d["powers"][k], 6)) for k in d["torques"]]
        p_in = sum(p for p in d["powers"].values() if p > 0)
        share = num(100 * d["power_loss"] / p_in, ".2f") + " %" if p_in > 0 else "0 %"
        notes.append(t("diff.loss", p=f(d["power_loss"], 4), share=share))
        if d.get("relative_driver"):
            notes.append(t("diff.driver", k="1" if d["relative_driver"] == "1" else last))
    yes, no = t("common.yes"), t("common.no")
    conds = [(t("diff.coaxial"), yes if ch["coaxial"] else no),
             (t("diff.assembly", k=d["satellites"]), yes if ch["assembly"] else no),
             (t("diff.adjacency", m=f(ch["adjacency_margin"], 3)), yes if ch["adjacency"] else no),
             (t("diff.limits"), yes if ch["tooth_limits"] else no)]
    plan_notes = [t("diff.plan_check", wp=f(d["velocity_plan"]["satellite_omega_plan"], 6),
                    w=f(d["speeds"]["satellite"], 6))]
    if not d.get("m_given"):
        plan_notes.append(t("diff.m_nominal"))
    fig = ctx.svg(figure(ctx, d), "differential-velocity")
    return ctx.render("sections/differential.html.j2", info=info, speeds=speeds, torques=torques, notes=notes,
                      conds=conds, fig=fig, plan_notes=plan_notes, last=last)
