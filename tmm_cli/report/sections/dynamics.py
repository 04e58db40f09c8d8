"""Report section 'dynamics' (docs/methods.md §4): reduced moments M_d, M_c, works A_d, A_c,
dT(phi), reduced inertia J_red(phi), the energy-mass (Wittenbauer) diagram dT vs J_red
drawn to scale with the tangents at psi_max, psi_min and the segment giving the
flywheel, omega(phi) and epsilon(phi) of the steady motion, the comparison of the
methods, the flywheel's size and the accuracy/speed table.  Writes ``flywheel.csv``
beside the report.  Reads numbers only from results["flywheel"].
"""
from __future__ import annotations

import math

import numpy as np

from ... import locales
from ..notation import Term

I18N = locales.table("dynamics", "words")


def _arr(d, key):
    a = (d.get("arrays") or {}).get(key)
    if a is None:
        return None
    return np.array([np.nan if v is None else v for v in a], float)


def _pct(x, ref):
    if x is None or ref is None or ref == 0:
        return None
    return 100.0 * (x - ref) / abs(ref)


def _diagrams(ctx, d, q):
    from ..svgchart import subplots
    fig, axes = subplots(180, 120, nrows=2, ncols=2, sharex=True)
    (a1, a2), (a3, a4) = axes
    a1.plot(q, _arr(d, "M_d"), color="#1e8449", label=ctx.t("dyn.Md"))
    a1.plot(q, _arr(d, "M_c"), color="#c0392b", label=ctx.t("dyn.Mc"))
    a1.set_ylabel(ctx.t("dyn.M_axis"))
    a2.plot(q, _arr(d, "A_d"), color="#1e8449", label=ctx.t("dyn.Ad"))
    a2.plot(q, _arr(d, "A_c"), color="#c0392b", label=ctx.t("dyn.Ac"))
    a2.set_ylabel(ctx.t("dyn.A_axis"))
    a3.plot(q, _arr(d, "dT"), color="k", label=ctx.t("dyn.dT"))
    a3.set_ylabel(ctx.t("dyn.T_axis"))
    a4.plot(q, _arr(d, "J_red"), color="#1f5fbf", label=ctx.t("dyn.Jred"))
    a4.plot(q, _arr(d, "J_var"), color="#1f5fbf", ls="--", label=ctx.t("dyn.Jvar"))
    a4.set_ylabel(ctx.t("dyn.J_axis"))
    for ax in (a1, a2, a3, a4):
        ax.axhline(0, color="0.6", lw=0.5)
        ax.grid(True, lw=0.3, alpha=0.5)
        ax.legend(loc="best")
        ax.set_xlim(0, q[-1])
    for ax in (a3, a4):
        ax.set_xlabel(ctx.t("dyn.phi_axis"))
        ax.set_xticks(np.arange(0, q[-1] + 1, 60 if q[-1] <= 360 else 120))
    ctx.figures.std_graph(fig, (a1, a2, a3, a4), ctx.t("kin.mm"), x_axis=a3)     # μM, μA, μT, μJ, μφ
    return ctx.svg(fig, "dynamics-diagrams")


def _wittenbauer(ctx, d):
    """dT vs J_red to scale (axes in mm of the drawing, equal aspect), the tangents of
    slopes omega_m^2 (1 +/- delta)/2 and the segment kl they cut on the dT axis."""
    J = _arr(d, "J_red")
    T = _arr(d, "dT")
    em = d.get("energy_mass") or {}
    wm, delta, Jc = d.get("omega_m"), d.get("delta"), d.get("J_const")
    aw, bw = em.get("a_wittenbauer"), em.get("b_wittenbauer")
    if J is None or T is None or None in (wm, delta, Jc, aw, bw):
        return None, None
    s_up = wm**2 * (1 + delta) / 2
    s_lo = wm**2 * (1 - delta) / 2
    k = aw - Jc * s_up          # where the tangents cut the dT axis (J_red = 0)
    l_ = bw - Jc * s_lo
    Jmax = float(np.nanmax(J)) * 1.08 if np.nanmax(J) > 0 else 1.0
    ylo = min(float(np.nanmin(T)), k, l_)
    yhi = max(float(np.nanmax(T)), k, l_)
    span_T = max(yhi - ylo, 1e-300)
    from ..svgchart import subplots
    fig, ax = subplots(120, 150)
    # laid out first (the labels with a scale of their length), then the scales chosen for the
    # axes' own length on the paper: a millimetre of the axes is a millimetre of the page, so
    # kl and the tangents measure with a ruler as the caption states them (the axes were
    # stretched to the figure: 23 mm a 20-mm grid)
    ax.set_xlabel(ctx.t("dyn.witt_x", mu="0.0025"))
    ax.set_ylabel(ctx.t("dyn.witt_y", mu="0.0025"))
    fig.tight_layout()
    pos = ax.get_position()
    len_x = pos.width * fig.get_figwidth() * 25.4
    len_y = pos.height * fig.get_figheight() * 25.4
    muJ = ctx.figures.nice_scale(Jmax / len_x)
    muT = ctx.figures.nice_scale(span_T * 1.08 / len_y)
    x = J / muJ
    y = T / muT
    ax.plot(x, y, color="k", lw=1.0)
    xe = Jmax / muJ
    xs = np.array([0.0, xe])
    ax.plot(xs, (k + xs * muJ * s_up) / muT, color="#c0392b", lw=0.8, label=Term("ψ_max"))
    ax.plot(xs, (l_ + xs * muJ * s_lo) / muT, color="#1f5fbf", lw=0.8, label=Term("ψ_min"))
    ax.plot([0, 0], [l_ / muT, k / muT], color="#1e8449", lw=2.0, label="kl")
    ax.annotate("k", (0, k / muT), xytext=(3, 0), textcoords="offset points", color="#1e8449")
    ax.annotate("l", (0, l_ / muT), xytext=(3, 0), textcoords="offset points", color="#1e8449")
    ax.axhline(0, color="0.6", lw=0.5)
    ax.axvline(0, color="0.3", lw=0.6)
    ax.set_xlabel(ctx.t("dyn.witt_x", mu=f"{muJ:g}"))
    ax.set_ylabel(ctx.t("dyn.witt_y", mu=f"{muT:g}"))
    # the limits span the axes' length in mm (one unit a millimetre both ways), the data centred
    ex, ey = (len_x - xe) / 2, (len_y - (yhi - ylo) / muT) / 2
    ax.set_xlim(-ex, xe + ex)
    ax.set_ylim(ylo / muT - ey, yhi / muT + ey)
    ax.grid(True, lw=0.3, alpha=0.5)
    ax.legend(loc="best")
    pmax = math.degrees(math.atan(muJ / muT * s_up))
    pmin = math.degrees(math.atan(muJ / muT * s_lo))
    kl = (k - l_) / muT
    # J = kl mu_T / (omega_m^2 delta): the stage's value of the construction
    cap = ctx.t("dyn.witt_caption", muJ=f"{muJ:g}", muT=f"{muT:g}", pmax=pmax, pmin=pmin, kl=kl,
                J=ctx.fmt(d.get("J_wittenbauer"), 5))
    return ctx.svg(fig, "energy-mass"), cap


def _motion(ctx, d, q):
    w = _arr(d, "omega")
    e = _arr(d, "epsilon")
    if w is None:
        return None
    from ..svgchart import subplots
    fig, (a1, a2) = subplots(170, 95, nrows=2, sharex=True)
    a1.plot(q, w, color="k")
    sg = -1.0 if d.get("direction") == "cw" else 1.0
    for key, ls in (("omega_max", "--"), ("omega_min", "--"), ("omega_m", ":")):
        if d.get(key) is not None:
            a1.axhline(sg * d[key], color="0.4", lw=0.6, ls=ls)
            # the symbol as the language's table writes it (the Russian mean speed as the text beside the figure)
            a1.annotate(Term(ctx.t(f"dyn.{key}").split(",")[0].strip()), (q[-1], sg * d[key]), xytext=(2, 0),
                        textcoords="offset points", fontsize=6, va="center")
    a1.set_ylabel(ctx.t("dyn.omega_axis"))
    a2.plot(q, e, color="#8e44ad")
    a2.axhline(0, color="0.6", lw=0.5)
    a2.set_ylabel(ctx.t("dyn.eps_axis"))
    a2.set_xlabel(ctx.t("dyn.phi_axis"))
    for ax in (a1, a2):
        ax.grid(True, lw=0.3, alpha=0.5)
        ax.set_xlim(0, q[-1])
    a2.set_xticks(np.arange(0, q[-1] + 1, 30 if q[-1] <= 360 else 60))
    ctx.figures.std_graph(fig, (a1, a2), ctx.t("kin.mm"), x_axis=a2, zero=False)   # μω, με, μφ
    return ctx.svg(fig, "motion")


def build(ctx) -> str | None:
    d = ctx.results.get("flywheel")
    if not d:
        return None
    f = ctx.fmt
    q = _arr(d, "phi_cycle")
    method = d.get("method", "energy-mass")
    shape = d.get("shape") or {}
    summary = [
        (ctx.t("dyn.method"), ctx.t(f"dyn.m_{method}")),
        (ctx.t("dyn.constant"), ctx.t(f"dyn.constant_{d.get('constant', 'driving')}")),
        (ctx.t("dyn.M_constant"), f(d.get("M_constant"), 6)),
        (ctx.t("dyn.delta"), f(d.get("delta"), 5)),
        (ctx.t("dyn.omega_m"), f(d.get("omega_m"), 6)),
        (ctx.t("dyn.J_const"), f(d.get("J_const"), 6)),
        (ctx.t("dyn.const_links"), ", ".join(d.get("constant_links") or []) or "—"),
        (ctx.t("dyn.J_n"), f(d.get("J_n"), 6)),
        (ctx.t("dyn.J"), f(d.get("J"), 6)),
        (ctx.t("dyn.delta_achieved"), f(d.get("delta_achieved"), 5)),
        (ctx.t("dyn.omega_max"), f(d.get("omega_max"), 6)),
        (ctx.t("dyn.omega_min"), f(d.get("omega_min"), 6)),
        (ctx.t("dyn.shape"), ctx.t(f"dyn.{shape.get('type', 'disk')}")),
        (ctx.t("dyn.rho"), f(shape.get("density"), 5)),
        (ctx.t("dyn.psi"), f(shape.get("width_ratio"), 4)),
        (ctx.t("dyn.D"), f(d.get("diameter"), 4)),
        (ctx.t("dyn.b"), f(d.get("width"), 4)),
        (ctx.t("dyn.m"), f(d.get("mass"), 4)),
        (ctx.t("dyn.v"), f(d.get("rim_speed"), 4)),
    ]
    Jn = d.get("J_n_methods") or {}
    Jc = d.get("J_const") or 0.0
    ex = Jn.get("exact")
    methods = []
    for key in ("energy-mass", "wittenbauer", "merzalov", "exact"):
        v = Jn.get(key)
        jf = None if v is None else v - Jc
        ref = None if ex is None else ex - Jc
        methods.append((ctx.t(f"dyn.m_{key}"), f(v, 6), f(jf, 6), f(_pct(jf, ref), 3)))
    note = ctx.t("dyn.methods_note", jmin=f(d.get("J_var_min"), 4), jmax=f(d.get("J_var_max"), 4))
    acc = d.get("accuracy") or {}
    acc_rows = []
    for x in acc.get("rows") or []:
        acc_rows.append((x["resolution"], f(x.get("J"), 7), f(x.get("err_J"), 2),
                         f(x.get("omega_max"), 7), f(x.get("err_omega_max"), 2),
                         f(x.get("omega_min"), 7), f(x.get("err_omega_min"), 2),
                         f(x.get("delta_true"), 5), f(x.get("time_ms"), 3)))
    hand = d.get("hand") or acc.get("hand")
    hand_text = None
    if hand:
        err = hand.get("err_J")
        hand_text = ctx.t("dyn.hand", n=hand.get("positions"), step=f(hand.get("step"), 3), J=f(hand.get("J"), 6),
                          Jem=f(hand.get("J_energy_mass"), 6), Jm=f(hand.get("J_merzalov"), 6),
                          err=f(None if err is None else 100 * err, 3),
                          Jacc=f((hand.get("accurate") or {}).get("J"), 6))
    fig_d = fig_w = cap_w = fig_m = None
    if q is not None and q.size > 1:
        fig_d = _diagrams(ctx, d, q)
        fig_w, cap_w = _wittenbauer(ctx, d)
        fig_m = _motion(ctx, d, q)
        arrays = d.get("arrays") or {}
        cols = [k for k in ("phi_cycle", "phi", "M_d", "M_c", "M_red", "A_d", "A_c", "dT", "J_red",
                            "J_var", "dT_I", "T_II", "omega", "epsilon") if arrays.get(k) is not None]
        ctx.write_csv("flywheel.csv", cols, zip(*[arrays[k] for k in cols]))
    return ctx.render("sections/dynamics.html.j2", summary=summary, methods=methods, methods_note=note,
                      acc_rows=acc_rows, acc_ref=acc.get("reference_resolution"), hand_text=hand_text,
                      fig_diagrams=fig_d, fig_witt=fig_w, cap_witt=cap_w, fig_motion=fig_m)
