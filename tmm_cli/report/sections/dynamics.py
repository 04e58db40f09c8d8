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

I18N = {
    "en": {"dyn.title": "Dynamics and the flywheel",
           "dyn.summary": "Result", "dyn.method": "Primary method",
           "dyn.m_energy-mass": "energy-mass (exact analytic form)", "dyn.m_merzalov": "Merzalov",
           "dyn.m_exact": "exact integration of the equation of motion",
           "dyn.constant_driving": "constant driving moment (motor-driven machine)",
           "dyn.constant_resistance": "constant resistance moment (engine)",
           "dyn.constant": "Constant reduced moment", "dyn.M_constant": "M_constant, N·m",
           "dyn.delta": "required δ", "dyn.delta_achieved": "δ achieved", "dyn.omega_m": "ω_m, rad/s",
           "dyn.omega_max": "ω_max, rad/s", "dyn.omega_min": "ω_min, rad/s",
           "dyn.J_const": "J_const (constant part of J_red), kg·m²", "dyn.J_n": "J_n (needed constant inertia), kg·m²",
           "dyn.J": "J_fly (flywheel), kg·m²", "dyn.shape": "Flywheel shape", "dyn.disk": "solid disk",
           "dyn.rim": "rim", "dyn.D": "diameter D, m", "dyn.b": "width b, m", "dyn.m": "mass m, kg",
           "dyn.v": "rim speed, m/s", "dyn.rho": "density ρ, kg/m³", "dyn.psi": "ψ_b = b/D",
           "dyn.const_links": "links of constant reduced inertia",
           "dyn.diagrams": "Reduced moments, works, kinetic energy and reduced inertia",
           "dyn.phi_axis": "crank rotation from position 0, deg",
           "dyn.witt_x": "J_red, mm (μ_J = {mu} kg·m²/mm)", "dyn.witt_y": "ΔT, mm (μ_T = {mu} J/mm)",
           "dyn.M_axis": "M, N·m", "dyn.A_axis": "A, J", "dyn.T_axis": "ΔT, J", "dyn.J_axis": "J_red, kg·m²",
           "dyn.Md": "M_d (driving)", "dyn.Mc": "M_c (resistance)", "dyn.Ad": "A_d", "dyn.Ac": "A_c",
           "dyn.dT": "ΔT = A_d − A_c", "dyn.Jred": "J_red", "dyn.Jvar": "J_var",
           "dyn.wittenbauer": "Energy-mass (Wittenbauer) diagram",
           "dyn.witt_caption": "ΔT against J_red to scale: μ_J = {muJ} kg·m²/mm, μ_T = {muT} J/mm; "
                               "tan ψ_max,min = (μ_J/μ_T) ω_m² (1 ± δ)/2: ψ_max = {pmax:.3f}°, "
                               "ψ_min = {pmin:.3f}°. The tangents cut the segment kl = {kl:.1f} mm on the "
                               "ΔT axis: J_fly = kl·μ_T/(ω_m² δ) = {J} kg·m².",
           "dyn.motion": "Steady motion with the flywheel",
           "dyn.omega_axis": "ω₁, rad/s", "dyn.eps_axis": "ε₁, rad/s²",
           "dyn.motion_caption": "ω₁(φ) from T = T₀ + ΔT, ω = √(2T/J); ε₁ = (M_red − J′ω²/2)/J (signed, ccw positive).",
           "dyn.methods": "Comparison of the methods", "dyn.col_method": "Method",
           "dyn.col_Jn": "J_n, kg·m²", "dyn.col_J": "J_fly, kg·m²", "dyn.col_diff": "vs exact, %",
           "dyn.m_wittenbauer": "Wittenbauer tangents (1 ± δ)/2 (graphical)",
           "dyn.methods_note": "Bounds: J_Merzalov − J_exact lies between min and max of J_var "
                               "({jmin} … {jmax} kg·m²); the graphical tangents differ from the exact form by at most "
                               "(max J_var − min J_var)·δ/8.",
           "dyn.accuracy": "Accuracy against the number of positions",
           "dyn.col_res": "positions", "dyn.col_errJ": "error J", "dyn.col_wmax": "ω_max",
           "dyn.col_wmin": "ω_min", "dyn.col_err": "error", "dyn.col_dtrue": "δ really",
           "dyn.col_time": "time, ms",
           "dyn.acc_note": "Errors relative to the finest grid ({ref} positions); ω_max/ω_min of the motion with "
                           "the converged flywheel computed on each grid; “δ really” is what the row's J gives.",
           "dyn.hand": "Hand calculation ({n} positions every {step}°, trapezoid): J = {J} kg·m² "
                       "(energy-mass {Jem}, Merzalov {Jm}); error {err} %; the accurate value is {Jacc} kg·m².",
           "dyn.csv_note": "All arrays: flywheel.csv."},
    "ru": {"dyn.title": "Динамика и маховик",
           "dyn.summary": "Результат", "dyn.method": "Основной метод",
           "dyn.m_energy-mass": "энергомасс (точная аналитическая форма)", "dyn.m_merzalov": "Мерцалова",
           "dyn.m_exact": "точное интегрирование уравнения движения",
           "dyn.constant_driving": "постоянный движущий момент (машина с двигателем)",
           "dyn.constant_resistance": "постоянный момент сопротивления (двигатель)",
           "dyn.constant": "Постоянный приведённый момент", "dyn.M_constant": "M_пост, Н·м",
           "dyn.delta": "заданный δ", "dyn.delta_achieved": "полученный δ", "dyn.omega_m": "ω_ср, рад/с",
           "dyn.omega_max": "ω_max, рад/с", "dyn.omega_min": "ω_min, рад/с",
           "dyn.J_const": "J_пост (постоянная часть J_пр), кг·м²",
           "dyn.J_n": "J_н (необходимый постоянный момент инерции), кг·м²",
           "dyn.J": "J_м (маховик), кг·м²", "dyn.shape": "Форма маховика", "dyn.disk": "сплошной диск",
           "dyn.rim": "обод", "dyn.D": "диаметр D, м", "dyn.b": "ширина b, м", "dyn.m": "масса m, кг",
           "dyn.v": "окружная скорость, м/с", "dyn.rho": "плотность ρ, кг/м³", "dyn.psi": "ψ_b = b/D",
           "dyn.const_links": "звенья с постоянным приведённым моментом инерции",
           "dyn.diagrams": "Приведённые моменты, работы, кинетическая энергия и приведённый момент инерции",
           "dyn.phi_axis": "поворот кривошипа от положения 0, град",
           "dyn.witt_x": "J_пр, мм (μ_J = {mu} кг·м²/мм)", "dyn.witt_y": "ΔT, мм (μ_T = {mu} Дж/мм)",
           "dyn.M_axis": "M, Н·м", "dyn.A_axis": "A, Дж", "dyn.T_axis": "ΔT, Дж", "dyn.J_axis": "J_пр, кг·м²",
           "dyn.Md": "M_д (движущий)", "dyn.Mc": "M_с (сопротивления)", "dyn.Ad": "A_д", "dyn.Ac": "A_с",
           "dyn.dT": "ΔT = A_д − A_с", "dyn.Jred": "J_пр", "dyn.Jvar": "J_перем",
           "dyn.wittenbauer": "Диаграмма энергомасс (Виттенбауэра)",
           "dyn.witt_caption": "ΔT в функции J_пр в масштабе: μ_J = {muJ} кг·м²/мм, μ_T = {muT} Дж/мм; "
                               "tg ψ_max,min = (μ_J/μ_T) ω_ср² (1 ± δ)/2: ψ_max = {pmax:.3f}°, "
                               "ψ_min = {pmin:.3f}°. Касательные отсекают на оси ΔT отрезок kl = {kl:.1f} мм: "
                               "J_м = kl·μ_T/(ω_ср² δ) = {J} кг·м².",
           "dyn.motion": "Установившееся движение с маховиком",
           "dyn.omega_axis": "ω₁, рад/с", "dyn.eps_axis": "ε₁, рад/с²",
           "dyn.motion_caption": "ω₁(φ) из T = T₀ + ΔT, ω = √(2T/J); ε₁ = (M_пр − J′ω²/2)/J (со знаком, "
                                 "против часовой стрелки положительно).",
           "dyn.methods": "Сравнение методов", "dyn.col_method": "Метод",
           "dyn.col_Jn": "J_н, кг·м²", "dyn.col_J": "J_м, кг·м²", "dyn.col_diff": "отличие от точного, %",
           "dyn.m_wittenbauer": "касательные Виттенбауэра (1 ± δ)/2 (графически)",
           "dyn.methods_note": "Оценки: J_Мерцалов − J_точн лежит между min и max J_перем "
                               "({jmin} … {jmax} кг·м²); графические касательные отличаются от точной формы не более "
                               "чем на (max J_перем − min J_перем)·δ/8.",
           "dyn.accuracy": "Точность в зависимости от числа положений",
           "dyn.col_res": "положений", "dyn.col_errJ": "погрешность J", "dyn.col_wmax": "ω_max",
           "dyn.col_wmin": "ω_min", "dyn.col_err": "погрешность", "dyn.col_dtrue": "δ фактический",
           "dyn.col_time": "время, мс",
           "dyn.acc_note": "Погрешности относительно самой мелкой сетки ({ref} положений); ω_max/ω_min движения "
                           "со сходящимся маховиком на каждой сетке; «δ фактический» даёт J данной строки.",
           "dyn.hand": "Ручной расчёт ({n} положений через {step}°, трапеции): J = {J} кг·м² "
                       "(энергомасс {Jem}, Мерцалов {Jm}); погрешность {err} %; точное значение {Jacc} кг·м².",
           "dyn.csv_note": "Все массивы: flywheel.csv."},
}


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
    muJ = ctx.figures.nice_scale(Jmax / 90.0)
    muT = ctx.figures.nice_scale(span_T / 110.0)
    x = J / muJ
    y = T / muT
    from ..svgchart import subplots
    fig, ax = subplots(120, 150)
    ax.plot(x, y, color="k", lw=1.0)
    xe = Jmax / muJ
    xs = np.array([0.0, xe])
    ax.plot(xs, (k + xs * muJ * s_up) / muT, color="#c0392b", lw=0.8, label="ψ_max")
    ax.plot(xs, (l_ + xs * muJ * s_lo) / muT, color="#1f5fbf", lw=0.8, label="ψ_min")
    ax.plot([0, 0], [l_ / muT, k / muT], color="#1e8449", lw=2.0, label="kl")
    ax.annotate("k", (0, k / muT), xytext=(3, 0), textcoords="offset points", color="#1e8449")
    ax.annotate("l", (0, l_ / muT), xytext=(3, 0), textcoords="offset points", color="#1e8449")
    ax.axhline(0, color="0.6", lw=0.5)
    ax.axvline(0, color="0.3", lw=0.6)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(ctx.t("dyn.witt_x", mu=f"{muJ:g}"))
    ax.set_ylabel(ctx.t("dyn.witt_y", mu=f"{muT:g}"))
    ax.grid(True, lw=0.3, alpha=0.5)
    ax.legend(loc="best")
    fig.tight_layout()
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
            a1.annotate(key.replace("omega_", "ω_"), (q[-1], sg * d[key]), xytext=(2, 0),
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
