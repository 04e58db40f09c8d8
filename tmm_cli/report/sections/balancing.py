"""Report section 'balancing': the shaking force and moment at the positions (with the
counterweights beside), their hodograph over a turn, the counterweights and what they leave,
the rotor's imbalance and correction masses. Reads numbers only from results["balancing"];
its words are the catalogues' topic 'balancing'
(tmm_cli/locales/<lang>/balancing.yaml)."""
from __future__ import annotations

import math

from ...drawings.balancing import counterweight_points
from ... import locales

I18N = locales.table("balancing", "words")


def hodograph(ctx, b):
    from ..svgchart import subplots
    h = b["hodograph"]
    fig, ax = subplots(150, 110)
    ax.plot(h["Fx"], h["Fy"], lw=1.2, label=ctx.t("bal.before"))
    if "Fx_balanced" in h:
        ax.plot(h["Fx_balanced"], h["Fy_balanced"], "ro", ms=2.5, label=ctx.t("bal.after"))
    ax.plot([0.0], [0.0], "k+", ms=6)
    ax.set_aspect("equal")
    ax.set_xlabel(ctx.t("bal.Fx"))
    ax.set_ylabel(ctx.t("bal.Fy"))
    ax.grid(True)
    ax.legend(fontsize=6)
    return fig


def counterweights_figure(ctx, b, results):
    """The linkage at position 0 with each counterweight drawn on its link: a disc at its radius
    and angle from the link's axis (fixed pivot -> other pair point), its area in proportion to its
    mass, labelled with m (kg)."""
    from ..svgchart import subplots
    e = (results.get("kinematics") or [None])[0]
    links = (results.get("structure") or {}).get("links") or []
    if e is None or not links:
        return None
    P = {k: (v["x"], v["y"]) for k, v in e["points"].items()}
    fig, ax = subplots(120, 90)
    for lk in links:
        pts = [P[q] for q in lk["points"] if q in P]
        if len(pts) >= 2:
            ax.plot([q[0] for q in pts], [q[1] for q in pts], "k-", lw=1.4)
    ground = [q for q in (results.get("structure") or {}).get("ground", {}) or {}]
    for q in ground:
        if q in P:
            ax.plot([P[q][0]], [P[q][1]], "ko", ms=5)
    cw = b.get("counterweights") or {}
    mmax = max((c["m"] for c in cw.values()), default=1.0) or 1.0
    placed_x, placed_y = [], []
    places = counterweight_points(results)
    for role, c in cw.items():
        if role not in places:
            continue
        (px, py), (x, y) = places[role]
        placed_x.append(x)
        placed_y.append(y)
        ax.plot([px, x], [py, y], color="r", lw=1.2)
        ax.plot([x], [y], "ro", ms=4 + 6 * math.sqrt(c["m"] / mmax))
        ax.annotate(ctx.t("bal.kg", m=ctx.fmt(c["m"])), (x, y), xytext=(4, 3))
    xs = [q[0] for q in P.values()] + placed_x
    ys = [q[1] for q in P.values()] + placed_y
    span = max(max(xs) - min(xs), max(ys) - min(ys), 1e-9)
    ax.set_xlim(min(xs) - 0.12 * span, max(xs) + 0.3 * span)        # room for the labels on the right
    ax.set_ylim(min(ys) - 0.12 * span, max(ys) + 0.12 * span)
    ax.set_aspect("equal")
    ax.grid(True)
    ax.set_xlabel(ctx.t("bal.x"))
    ax.set_ylabel(ctx.t("bal.y"))
    return fig


def rotor_figure(ctx, r, masses):
    from ..svgchart import subplots
    fig, ax = subplots(100, 100)
    for m in masses:
        mr, a = m["m"] * m["r"], math.radians(m["angle"])
        ax.plot([0.0, mr * math.cos(a)], [0.0, mr * math.sin(a)], color="0.55", lw=1.4)
    for c in r["corrections"]:
        a = math.radians(c["angle"])
        x, y = c["mr"] * math.cos(a), c["mr"] * math.sin(a)
        ax.plot([0.0, x], [0.0, y], color="r", lw=1.6)
        ax.annotate(str(c["plane"]), (x, y), xytext=(3, 2))
    ax.set_aspect("equal")
    ax.grid(True)
    ax.set_xlabel(ctx.t("bal.Ux"))
    ax.set_ylabel(ctx.t("bal.Uy"))
    return fig


def build(ctx) -> str | None:
    b = (ctx.results or {}).get("balancing")
    if not b:
        return None
    f, t = ctx.fmt, ctx.t
    parts = {}
    if "shaking" in b:
        idx = list((ctx.results.get("positions") or {}).get("index") or range(len(b["shaking"])))
        after = b.get("shaking_balanced")
        rows = []
        for k, e in enumerate(b["shaking"]):
            row = [idx[k] if k < len(idx) else k, f(e["phi"], 5), f(e["Fx"]), f(e["Fy"]), f(e["F"]), f(e["M"])]
            if after:
                row += [f(after[k]["F"]), f(after[k]["M"])]
            rows.append(row)
        head = [t("bal.pos"), t("bal.phi"), t("bal.Fx"), t("bal.Fy"), t("bal.F"), t("bal.M")]
        if after:
            head += [t("bal.F_after"), t("bal.M_after")]
        notes = [t("bal.maxima", F=f(b["max"]["F"]), M=f(b["max"]["M"]))]
        if after:
            notes.append(t("bal.maxima_after", F=f(b["max"]["F_balanced"]), M=f(b["max"]["M_balanced"])))
        cw = b.get("counterweights")
        cw_rows, cw_text = None, []
        if cw:
            names = ((ctx.results.get("structure") or {}).get("links") or [])
            number = {lk["name"]: lk["index"] for lk in names}
            cw_rows = [(f"{c['link']} ({number.get(c['link'], '')})", f(c["m"]), f(c["r"]), f(c["angle"], 5),
                        f(c["m"] * c["r"])) for c in cw.values()]
            rem = b.get("remains") or {}
            if rem:
                cw_text.append(t("bal.cw_crank", share=f"{100 * rem['reciprocating_share']:g} %",
                                 m_rec=f(rem["reciprocating_mass"])))
                cw_text.append(t("bal.remains", p=f(rem["primary_amplitude"]), s=f(rem["secondary_amplitude"]),
                                 lam=f(rem["lambda"])))
            else:
                cw_text.append(t("bal.cw_full"))
        cw_fig = counterweights_figure(ctx, b, ctx.results) if cw else None
        applied = b.get("applied")
        if applied:
            # what took them: the kinetostatics, the flywheel or both (it said both of a task with
            # no flywheel)
            res = ctx.results or {}
            key = {(True, True): "bal.applied", (True, False): "bal.applied_kst",
                   (False, True): "bal.applied_fly"}.get((bool(res.get("kinetostatics")), bool(res.get("flywheel"))),
                                                         "bal.applied")
            parts.update(applied_text=t(key), applied_rows=[
                (f"{name} ({number.get(name, '')})", f(a["mass"]), f"({f(a['com'][0])}; {f(a['com'][1])})", f(a["J"]))
                for name, a in applied.items()])
        parts.update(head=head, rows=rows, notes=notes, method=t("bal.method", about=b.get("about", "O")),
                     hodo=ctx.svg(hodograph(ctx, b), "balancing-hodograph"), cw_rows=cw_rows, cw_text=cw_text,
                     cw_fig=ctx.svg(cw_fig, "balancing-counterweights") if cw_fig is not None else None)
    r = b.get("rotor")
    if r:
        masses = r.get("masses") or []
        im = r["imbalance"]
        parts.update(
            rotor_text=[t("bal.imbalance", mr=f(im["mr"]), angle=f(im["angle"], 5),
                          z=f(im["z"]) if im["z"] is not None else "—", c=f(im["couple"])),
                        t("bal.rotor_static", c=f(r["couple_left"])) if r["method"] == "static"
                        else t("bal.rotor_dynamic")],
            rotor_rows=[(c["plane"], f(c["z"]), f(c["m"]), f(c["r"]), f(c["angle"], 5), f(c["mr"]))
                        for c in r["corrections"]],
            rotor_fig=ctx.svg(rotor_figure(ctx, r, masses), "balancing-rotor"))
    return ctx.render("sections/balancing.html.j2", **parts)
