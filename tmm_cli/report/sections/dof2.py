"""Report section 'dof2' (docs/methods.md §7): a machine with two degrees of freedom, the rotary
impact mechanism (rotor O-O1 + striker hinged at O1).  The scheme (at t = 0 and at the
hit, with the paths of O1 and M), the parameters, the equations of motion (Lagrange's
equations of the second kind), phi(t) and psi(t), the speeds, the dynamic reactions in
O and O1 over time, the energy balance, the extreme values, the state at the hit and
the centrifugal-pendulum frequency.  Writes ``dof2.csv`` beside the report.  Reads
numbers only from results["dof2"].
"""
from __future__ import annotations

import math

import numpy as np

from ... import locales
from ..notation import Term

I18N = locales.table("dof2", "words")

EQUATIONS = (
    "T = ½·a·φ̇² + ½·d·(φ̇ + ψ̇)² + b·cos ψ·φ̇·(φ̇ + ψ̇)",
    "(a + d + 2b cos ψ)·φ̈ + (d + b cos ψ)·ψ̈ − b sin ψ·ψ̇·(2φ̇ + ψ̇) = M − ∂V/∂φ",
    "(d + b cos ψ)·φ̈ + d·ψ̈ + b sin ψ·φ̇² = −∂V/∂ψ",
    "V = g·[(m₁·OS₁ + m₂·l)·sin φ + m₂·l_c·sin(φ + ψ)]",
)
REACTIONS = (
    "m₂·a_C = R₁₂ + G₂   ⇒   R₁₂ = m₂·a_C − G₂",
    "m₁·a_S₁ = R₀₁ − R₁₂ + G₁   ⇒   R₀₁ = m₁·a_S₁ + R₁₂ − G₁",
)


def _arr(x):
    return np.array([np.nan if v is None else v for v in x], dtype=float)


def _geometry(p, phi_deg, psi_deg):
    """O, O1, S1, C, M (m) for one state."""
    f, th = math.radians(phi_deg), math.radians(phi_deg + psi_deg)
    e1, e2 = np.array([math.cos(f), math.sin(f)]), np.array([math.cos(th), math.sin(th)])
    O1 = p["l"] * e1
    return {"O": np.zeros(2), "O1": O1, "S1": p["s1"] * e1, "C": O1 + p["l_c"] * e2, "M": O1 + p["l_M"] * e2}


def sketch(ctx, d):
    fp = ctx.figures
    p = d["parameters"]
    k = 1e3                                     # m -> mm
    reach = (abs(p["l"]) + max(abs(p["l_M"]), abs(p["l_c"]))) * k
    fig, ax = fp.new_figure(110, 100)
    ax.set_aspect("equal")
    th = np.linspace(0, 2 * math.pi, 181)
    ax.plot(p["l"] * k * np.cos(th), p["l"] * k * np.sin(th), color="0.6", lw=0.5, ls=":")
    mx, my = _arr(d["points"]["M"]["x"]) * k, _arr(d["points"]["M"]["y"]) * k
    ax.plot(mx, my, color="0.55", lw=0.6)
    states = [(d["phi"][0], d["psi"][0], "-", True)]
    if d.get("impact"):
        states.append((d["impact"]["phi"], d["impact"]["psi"], "--", False))
    r = 0.05 * reach
    for phi, psi, ls, labels in states:
        g = {n: v * k for n, v in _geometry(p, phi, psi).items()}
        ax.plot([g["O"][0], g["O1"][0]], [g["O"][1], g["O1"][1]], "k", lw=2.0, ls=ls, zorder=3)
        ax.plot([g["O1"][0], g["M"][0]], [g["O1"][1], g["M"][1]], color="C0", lw=2.6, ls=ls, zorder=3)
        ax.plot(*g["C"], "o", color="C0", ms=4, zorder=6)
        ax.plot(*g["M"], "s", color="C3", ms=4, zorder=6)
        fp.draw_joint(ax, g["O1"], r * 0.6)
        if labels:
            for name, text in (("O1", "O₁"), ("C", "C"), ("M", "M")):
                v = g[name] / (np.linalg.norm(g[name]) or 1.0)
                ax.annotate(text, g[name] + v * 2.2 * r, ha="center", va="center", fontsize=8)
            if p["s1"] and p["m1"]:
                ax.plot(*g["S1"], "k^", ms=3, zorder=6)
    # the frame's hatch and the label O away from the rotor in every drawn state
    used = [math.radians(s[0]) for s in states]
    cands = np.radians(np.arange(0, 360, 15))
    gap = [min(abs(math.remainder(c - u, 2 * math.pi)) for u in used) for c in cands]
    a_g = float(cands[int(np.argmax(gap))])
    fp.draw_ground(ax, (0.0, 0.0), r, angle_deg=math.degrees(a_g))
    fp.draw_joint(ax, (0.0, 0.0), r * 0.6)
    a_l = a_g + math.pi / 2
    ax.annotate("O", (2.2 * r * math.cos(a_l), 2.2 * r * math.sin(a_l)), ha="center", va="center", fontsize=8)
    if d.get("impact_phi") is not None:
        a = math.radians(d["impact_phi"])
        ax.plot([0, 1.15 * reach * math.cos(a)], [0, 1.15 * reach * math.sin(a)], color="C3", lw=0.6, ls="-.")
    lim = 1.2 * reach
    ax.set_xlim(-lim, lim)
    ax.set_ylim(-lim, lim)
    step = ctx.figures.nice_scale(lim / 4)
    ax.set_xticks(np.arange(-math.floor(lim / step), math.floor(lim / step) + 1) * step)
    ax.set_yticks(np.arange(-math.floor(lim / step), math.floor(lim / step) + 1) * step)
    ax.grid(True, lw=0.3, color="0.85")
    ax.tick_params(labelsize=6)
    return fig, step


def plots(ctx, d):
    fp, t = ctx.figures, ctx.t
    tt = _arr(d["t"])
    out = {}
    fig, (a1, a2) = fp.new_figure(170, 95, nrows=2, sharex=True)
    a1.plot(tt, _arr(d["phi"]), "k", lw=1.0)
    a1.set_ylabel(t("dof2.phi_axis"))
    a2.plot(tt, _arr(d["psi"]), color="C0", lw=1.0)
    a2.set_ylabel(t("dof2.psi_axis"))
    a2.set_xlabel(t("dof2.t_axis"))
    if d.get("impact"):
        for ax in (a1, a2):
            ax.axvline(d["impact"]["t"], color="C3", lw=0.6, ls="--")
    for ax in (a1, a2):
        ax.grid(True, lw=0.3, color="0.85")
    fig.tight_layout()                    # the axis labels inside the figure
    out["angles"] = ctx.svg(fig, "dof2-angles")

    fig, ax = fp.new_figure(170, 70)
    ax.plot(tt, _arr(d["omega"]), "k", lw=1.0, label=t("dof2.w1"))
    ax.plot(tt, _arr(d["psi_dot"]), color="C0", lw=1.0, label=t("dof2.pd"))
    ax.plot(tt, _arr(d["omega2"]), color="C1", lw=0.8, ls="--", label=t("dof2.w2"))
    ax.set_xlabel(t("dof2.t_axis"))
    ax.set_ylabel(t("dof2.w_axis"))
    ax.grid(True, lw=0.3, color="0.85")
    ax.legend(fontsize=6)
    fig.tight_layout()                    # the axis labels inside the figure
    out["speeds"] = ctx.svg(fig, "dof2-speeds")

    R = d["reactions"]
    fig, (a1, a2) = fp.new_figure(170, 100, nrows=2, sharex=True)
    for key, sym, color, lab in (("R01", "R₀₁", "k", t("dof2.R01")), ("R12", "R₁₂", "C0", t("dof2.R12"))):
        a1.plot(tt, _arr(R[key]["R"]), color=color, lw=1.0, label=lab)
        a1.plot(tt, _arr(R[key]["x"]), color=color, lw=0.5, ls="--", label=f"{sym}, x")
        a1.plot(tt, _arr(R[key]["y"]), color=color, lw=0.5, ls=":", label=f"{sym}, y")
    a1.set_ylabel(t("dof2.R_axis"))
    a1.legend(fontsize=6, ncol=3)
    a2.plot(tt, _arr(d["driving_moment"]), color="C2", lw=1.0, label=t("dof2.Md"))
    a2.set_ylabel(t("dof2.M_axis"))
    a2.set_xlabel(t("dof2.t_axis"))
    a2.legend(fontsize=6)
    for ax in (a1, a2):
        ax.grid(True, lw=0.3, color="0.85")
    fig.tight_layout()                    # the axis labels inside the figure
    out["reactions"] = ctx.svg(fig, "dof2-reactions")

    E = d["energy"]
    fig, (a1, a2) = fp.new_figure(170, 90, nrows=2, sharex=True, gridspec_kw={"height_ratios": [2, 1]})
    a1.plot(tt, _arr(E["T"]), "k", lw=1.0, label=t("dof2.T"))
    a1.plot(tt, _arr(E["V"]), color="C1", lw=0.8, label=t("dof2.V"))
    a1.plot(tt, _arr(E["W"]), color="C2", lw=0.8, ls="--", label=t("dof2.W"))
    a1.set_ylabel(t("dof2.E_axis"))
    a1.legend(fontsize=6)
    a2.plot(tt, _arr(E["balance"]), color="C3", lw=0.8, label=t("dof2.bal"))
    a2.set_ylabel(t("dof2.err_axis"))
    a2.set_xlabel(t("dof2.t_axis"))
    a2.legend(fontsize=6)
    for ax in (a1, a2):
        ax.grid(True, lw=0.3, color="0.85")
    fig.tight_layout()                    # the axis labels inside the figure
    out["energy"] = ctx.svg(fig, "dof2-energy")
    return out


def _params(ctx, d):
    f, t = ctx.fmt, ctx.t
    p = d["parameters"]
    rows = [(t("dof2.l"), f(p["l"])), (t("dof2.m1"), f(p["m1"])), (t("dof2.s1"), f(p["s1"])),
            (t("dof2.J_O"), f(p["J_O"])), (t("dof2.l_M"), f(p["l_M"])), (t("dof2.l_c"), f(p["l_c"])),
            (t("dof2.m2"), f(p["m2"])), (t("dof2.J_C"), f(p["J_C"])),
            (t("dof2.coeffs"), f"a = {f(p['a'])}; b = {f(p['b'])}; d = {f(p['d'])}"),
            (t("dof2.gravity"), t("dof2.gravity_on") if p["g"] else t("dof2.gravity_off"))]
    if p["drive"] == "speed":
        drive = t("dof2.drive_speed", w=f(p["omega1"]))
    elif p["drive"] == "moment":
        drive = t("dof2.drive_moment", M=f(p["moment"]))
    else:
        drive = t("dof2.drive_free")
    rows.append((t("dof2.drive"), drive))
    rows.append((t("dof2.initial"), f"φ₀ = {f(d['phi'][0])}°, ψ₀ = {f(d['psi'][0])}°, "
                                     f"ω₀ = {f(d['omega'][0])}, ψ̇₀ = {f(d['psi_dot'][0])}"))
    rows.append((t("dof2.duration"), f(d["t_end"])))
    return rows


def _maxima(ctx, d):
    f, t = ctx.fmt, ctx.t
    mx = d["max"]
    keys = [("R01", "dof2.max_R01"), ("R12", "dof2.max_R12"), ("v_M", "dof2.max_vM"),
            ("omega_max", "dof2.omega_max"), ("omega_min", "dof2.omega_min"), ("psi_max", "dof2.psi_max"),
            ("psi_min", "dof2.psi_min"), ("psi_dot_max", "dof2.psi_dot_max")]
    if d["parameters"]["drive"] == "speed":
        keys += [("driving_moment_max", "dof2.Md_max"), ("driving_moment_min", "dof2.Md_min")]
    return [(t(label), f(mx[k]["value"]), f(mx[k]["t"])) for k, label in keys if k in mx]


def _impact(ctx, imp):
    f, t = ctx.fmt, ctx.t
    return [(t("dof2.imp_t"), f(imp["t"], 6)), (t("dof2.imp_psi"), f(imp["psi"])),
            (t("dof2.imp_theta"), f(imp["theta2"])), (t("dof2.imp_w"), f(imp["omega"])),
            (t("dof2.imp_pd"), f(imp["psi_dot"])), (t("dof2.imp_w2"), f(imp["omega2"])),
            (t("dof2.imp_vM"), f(imp["M"]["v"])), (t("dof2.imp_M"), f"{f(imp['M']['x'])}; {f(imp['M']['y'])}"),
            (t("dof2.imp_T2"), f(imp["striker_energy"])), (t("dof2.imp_T"), f(imp["kinetic_energy"])),
            (t("dof2.imp_R01"), f(imp["R01"]["R"])), (t("dof2.imp_R12"), f(imp["R12"]["R"])),
            (t("dof2.imp_Md"), f(imp["driving_moment"]))]


def _csv(ctx, d):
    R, E, P = d["reactions"], d["energy"], d["points"]["M"]
    cols = [("t", d["t"]), ("phi_deg", d["phi"]), ("psi_deg", d["psi"]), ("omega1", d["omega"]),
            ("psi_dot", d["psi_dot"]), ("omega2", d["omega2"]), ("epsilon1", d["epsilon"]),
            ("psi_ddot", d["psi_ddot"]), ("epsilon2", d["epsilon2"]), ("M_drive", d["driving_moment"]),
            ("xM", P["x"]), ("yM", P["y"]), ("vM", P["v"]),
            ("R01x", R["R01"]["x"]), ("R01y", R["R01"]["y"]), ("R01", R["R01"]["R"]),
            ("R12x", R["R12"]["x"]), ("R12y", R["R12"]["y"]), ("R12", R["R12"]["R"]),
            ("T", E["T"]), ("V", E["V"]), ("W", E["W"]), ("balance", E["balance"])]
    ctx.write_csv("dof2.csv", [c for c, _ in cols], zip(*[v for _, v in cols]))


def build(ctx) -> str | None:
    d = (ctx.results or {}).get("dof2")
    if not d:
        return None
    f, t = ctx.fmt, ctx.t
    fig, step = sketch(ctx, d)
    fig_sketch, sketch_cap = ctx.svg(fig, "dof2-sketch"), t("dof2.sketch_caption", mm=f(step))
    figs = plots(ctx, d)
    imp = d.get("impact")
    impact_rows = _impact(ctx, imp) if imp else None
    impact_head = t("dof2.impact", phi=f(d["impact_phi"])) if d.get("impact_phi") is not None else None
    impact_none = t("dof2.no_impact", phi=f(d["impact_phi"])) if impact_head and not imp else None
    impact_more = t("dof2.imp_more", n=len(d["impacts"])) if imp and len(d.get("impacts", [])) > 1 else None
    c = d.get("centrifugal")
    centrifugal = (t("dof2.centrifugal", about=f(c["about_psi"]), wn=f(c["omega_n"]), T=f(c["period"]),
                     r=f(c["ratio"])) if c else None)
    E = d["energy"]
    _csv(ctx, d)
    return ctx.render("sections/dof2.html.j2", params=_params(ctx, d), fig_sketch=fig_sketch,
                      sketch_cap=sketch_cap, equations=[Term(e) for e in EQUATIONS],
                      reactions=[Term(e) for e in REACTIONS],
                      integration=t("dof2.integration", n=d.get("nfev")), figs=figs,
                      energy_text=t("dof2.energy_text", err=f(E["max_abs_error"], 3), rel=f(E["relative_error"], 2)),
                      maxima=_maxima(ctx, d), impact_head=impact_head, impact_rows=impact_rows,
                      impact_none=impact_none, impact_more=impact_more, centrifugal=centrifugal)
