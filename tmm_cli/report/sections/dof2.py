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

I18N = {
    "en": {
        "dof2.title": "Machine with two degrees of freedom: rotary impact mechanism",
        "dof2.scheme": "Scheme and parameters",
        "dof2.sketch_caption": "Kinematic scheme at t = 0 (solid) and at the hit (dashed), {mm} mm grid; thin "
                               "lines: paths of O₁ and M over the motion.",
        "dof2.l": "l = OO₁ (rotor), m", "dof2.m1": "rotor mass m₁, kg", "dof2.s1": "OS₁ (rotor's centre of mass), m",
        "dof2.J_O": "rotor inertia about O, J_O, kg·m²", "dof2.l_M": "O₁M (striker), m",
        "dof2.l_c": "l_c = O₁C (striker's centre of mass), m", "dof2.m2": "striker mass m₂, kg",
        "dof2.J_C": "striker inertia about C, J_C, kg·m²",
        "dof2.coeffs": "a = J_O + m₂l², b = m₂l·l_c, d = J_C + m₂l_c², kg·m²",
        "dof2.gravity": "gravity", "dof2.gravity_on": "g = 9.81 m/s² along −y",
        "dof2.gravity_off": "not taken (horizontal machine)",
        "dof2.drive": "drive",
        "dof2.drive_speed": "rotor held at ω₁ = {w} rad/s = const by the motor: only ψ is free",
        "dof2.drive_moment": "constant driving moment M = {M} N·m on the rotor",
        "dof2.drive_free": "free motion (no driving moment)",
        "dof2.initial": "initial state", "dof2.duration": "duration, s",
        "dof2.convention": "Angles: φ is the rotor O→O₁ from +x, ccw; ψ is the striker O₁→M relative to the "
                           "rotor (ψ = 0 along O→O₁; the paper's ψ equals ψ − 180°). Reactions R_ij: force of "
                           "link i on link j (0 frame, 1 rotor, 2 striker).",
        "dof2.method": "Equations of motion",
        "dof2.method_text": "Generalised coordinates φ and ψ; the kinetic energy and Lagrange's equations of "
                            "the second kind:",
        "dof2.method_react": "The dynamic reactions follow from the theorem on the motion of the centre of mass "
                             "of each link:",
        "dof2.integration": "Integrated numerically (DOP853, relative tolerance 1e-10), {n} right-hand side "
                            "evaluations.",
        "dof2.motion": "Motion",
        "dof2.fig_angles": "Rotor angle φ(t) and striker angle ψ(t)",
        "dof2.fig_speeds": "Angular speeds: ω₁ of the rotor, ψ̇ relative, ω₂ = ω₁ + ψ̇ of the striker",
        "dof2.t_axis": "t, s", "dof2.phi_axis": "φ, deg", "dof2.psi_axis": "ψ, deg", "dof2.w_axis": "ω, rad/s",
        "dof2.R_axis": "R, N", "dof2.E_axis": "energy, J", "dof2.err_axis": "error, J", "dof2.M_axis": "M, N·m",
        "dof2.w1": "ω₁ rotor", "dof2.pd": "ψ̇ relative", "dof2.w2": "ω₂ striker",
        "dof2.reactions": "Dynamic reactions in the pairs",
        "dof2.fig_reactions": "Reactions R₀₁ (frame on rotor, at O) and R₁₂ (rotor on striker, at O₁): "
                              "magnitudes and components",
        "dof2.R01": "|R₀₁| at O", "dof2.R12": "|R₁₂| at O₁",
        "dof2.Md": "driving moment on the rotor",
        "dof2.energy": "Energy balance",
        "dof2.fig_energy": "Kinetic energy T, potential energy V, work W of the driving moment and the "
                           "balance error T + V − W − E₀",
        "dof2.T": "T kinetic", "dof2.V": "V potential", "dof2.W": "W work of the moment",
        "dof2.bal": "T + V − W − E₀",
        "dof2.energy_text": "Energy balance: max |T + V − W − E₀| = {err} J, {rel} of the energy.",
        "dof2.maxima": "Extreme values", "dof2.col_q": "Quantity", "dof2.col_v": "Value", "dof2.col_t": "t, s",
        "dof2.max_R01": "largest |R₀₁|, N", "dof2.max_R12": "largest |R₁₂|, N", "dof2.max_vM": "largest v_M, m/s",
        "dof2.omega_max": "largest ω₁, rad/s", "dof2.omega_min": "smallest ω₁, rad/s",
        "dof2.psi_max": "largest ψ, deg", "dof2.psi_min": "smallest ψ, deg",
        "dof2.psi_dot_max": "largest |ψ̇|, rad/s", "dof2.Md_max": "largest driving moment, N·m",
        "dof2.Md_min": "smallest driving moment, N·m",
        "dof2.impact": "State at the hit (φ = {phi}°)",
        "dof2.no_impact": "The rotor does not reach the hit angle φ = {phi}° within the motion.",
        "dof2.imp_t": "time t, s", "dof2.imp_psi": "ψ, deg", "dof2.imp_theta": "striker angle φ + ψ, deg",
        "dof2.imp_w": "ω₁, rad/s", "dof2.imp_pd": "ψ̇, rad/s", "dof2.imp_w2": "ω₂, rad/s",
        "dof2.imp_vM": "speed of M, m/s", "dof2.imp_M": "position of M (x, y), m",
        "dof2.imp_T2": "kinetic energy of the striker, J", "dof2.imp_T": "kinetic energy of the machine, J",
        "dof2.imp_R01": "|R₀₁|, N", "dof2.imp_R12": "|R₁₂|, N", "dof2.imp_Md": "driving moment, N·m",
        "dof2.imp_more": "The rotor passes the hit angle {n} times; the first pass is shown.",
        "dof2.centrifugal": "With ω₁ = const and no gravity the striker is a centrifugal pendulum: "
                            "(J_C + m₂l_c²) ψ̈ + m₂ l l_c ω₁² sin ψ = 0; small oscillations about ψ = {about}° "
                            "have ω_n = ω₁·√(|b|/d) = {wn} rad/s (period {T} s, {r} of ω₁).",
        "dof2.csv_note": "All arrays over time: dof2.csv.",
    },
    "ru": {
        "dof2.title": "Движение машины с двумя степенями подвижности: роторный ударный механизм",
        "dof2.scheme": "Схема и параметры",
        "dof2.sketch_caption": "Кинематическая схема при t = 0 (сплошные линии) и в момент удара (штриховые), "
                               "сетка {mm} мм; тонкие линии — траектории точек O₁ и M.",
        "dof2.l": "l = OO₁ (ротор), м", "dof2.m1": "масса ротора m₁, кг", "dof2.s1": "OS₁ (центр масс ротора), м",
        "dof2.J_O": "момент инерции ротора относительно O, J_O, кг·м²", "dof2.l_M": "O₁M (ударник), м",
        "dof2.l_c": "l_c = O₁C (центр масс ударника), м", "dof2.m2": "масса ударника m₂, кг",
        "dof2.J_C": "момент инерции ударника относительно C, J_C, кг·м²",
        "dof2.coeffs": "a = J_O + m₂l², b = m₂l·l_c, d = J_C + m₂l_c², кг·м²",
        "dof2.gravity": "сила тяжести", "dof2.gravity_on": "g = 9,81 м/с² вдоль −y",
        "dof2.gravity_off": "не учитывается (горизонтальная машина)",
        "dof2.drive": "привод",
        "dof2.drive_speed": "двигатель удерживает ω₁ = {w} рад/с = const: свободна только координата ψ",
        "dof2.drive_moment": "постоянный движущий момент M = {M} Н·м на роторе",
        "dof2.drive_free": "свободное движение (движущий момент не приложен)",
        "dof2.initial": "начальное состояние", "dof2.duration": "продолжительность, с",
        "dof2.convention": "Углы: φ — угол ротора O→O₁ от оси +x против часовой стрелки; ψ — угол ударника "
                           "O₁→M относительно ротора (ψ = 0 — по направлению O→O₁; в статье угол равен ψ − 180°). "
                           "Реакции R_ij — сила действия звена i на звено j (0 — стойка, 1 — ротор, 2 — ударник).",
        "dof2.method": "Уравнения движения",
        "dof2.method_text": "Обобщённые координаты φ и ψ; кинетическая энергия и уравнения Лагранжа "
                            "второго рода:",
        "dof2.method_react": "Динамические реакции — по теореме о движении центра масс каждого звена:",
        "dof2.integration": "Численное интегрирование (DOP853, относительная погрешность 10⁻¹⁰), {n} вычислений "
                            "правых частей.",
        "dof2.motion": "Закон движения",
        "dof2.fig_angles": "Угол поворота ротора φ(t) и угол ударника ψ(t)",
        "dof2.fig_speeds": "Угловые скорости: ω₁ ротора, относительная ψ̇, ω₂ = ω₁ + ψ̇ ударника",
        "dof2.t_axis": "t, с", "dof2.phi_axis": "φ, град", "dof2.psi_axis": "ψ, град", "dof2.w_axis": "ω, рад/с",
        "dof2.R_axis": "R, Н", "dof2.E_axis": "энергия, Дж", "dof2.err_axis": "погрешность, Дж",
        "dof2.M_axis": "M, Н·м",
        "dof2.w1": "ω₁ ротора", "dof2.pd": "ψ̇ относительная", "dof2.w2": "ω₂ ударника",
        "dof2.reactions": "Динамические реакции в кинематических парах",
        "dof2.fig_reactions": "Реакции R₀₁ (стойки на ротор, в шарнире O) и R₁₂ (ротора на ударник, в шарнире "
                              "O₁): модули и проекции",
        "dof2.R01": "|R₀₁| в O", "dof2.R12": "|R₁₂| в O₁",
        "dof2.Md": "движущий момент на роторе",
        "dof2.energy": "Энергетический баланс",
        "dof2.fig_energy": "Кинетическая энергия T, потенциальная энергия V, работа W движущего момента и "
                           "погрешность баланса T + V − W − E₀",
        "dof2.T": "T кинетическая", "dof2.V": "V потенциальная", "dof2.W": "W работа момента",
        "dof2.bal": "T + V − W − E₀",
        "dof2.energy_text": "Энергетический баланс: max |T + V − W − E₀| = {err} Дж, доля от энергии {rel}.",
        "dof2.maxima": "Наибольшие и наименьшие значения", "dof2.col_q": "Величина", "dof2.col_v": "Значение",
        "dof2.col_t": "t, с",
        "dof2.max_R01": "наибольшая |R₀₁|, Н", "dof2.max_R12": "наибольшая |R₁₂|, Н",
        "dof2.max_vM": "наибольшая v_M, м/с",
        "dof2.omega_max": "наибольшая ω₁, рад/с", "dof2.omega_min": "наименьшая ω₁, рад/с",
        "dof2.psi_max": "наибольший ψ, град", "dof2.psi_min": "наименьший ψ, град",
        "dof2.psi_dot_max": "наибольшая |ψ̇|, рад/с", "dof2.Md_max": "наибольший движущий момент, Н·м",
        "dof2.Md_min": "наименьший движущий момент, Н·м",
        "dof2.impact": "Состояние в момент удара (φ = {phi}°)",
        "dof2.no_impact": "Ротор не доходит до угла удара φ = {phi}° за время движения.",
        "dof2.imp_t": "время t, с", "dof2.imp_psi": "ψ, град", "dof2.imp_theta": "угол ударника φ + ψ, град",
        "dof2.imp_w": "ω₁, рад/с", "dof2.imp_pd": "ψ̇, рад/с", "dof2.imp_w2": "ω₂, рад/с",
        "dof2.imp_vM": "скорость точки M, м/с", "dof2.imp_M": "положение точки M (x, y), м",
        "dof2.imp_T2": "кинетическая энергия ударника, Дж", "dof2.imp_T": "кинетическая энергия машины, Дж",
        "dof2.imp_R01": "|R₀₁|, Н", "dof2.imp_R12": "|R₁₂|, Н", "dof2.imp_Md": "движущий момент, Н·м",
        "dof2.imp_more": "Ротор проходит угол удара {n} раз(а); показан первый проход.",
        "dof2.centrifugal": "При ω₁ = const без силы тяжести ударник — центробежный маятник: "
                            "(J_C + m₂l_c²) ψ̈ + m₂ l l_c ω₁² sin ψ = 0; малые колебания около ψ = {about}° "
                            "происходят с ω_n = ω₁·√(|b|/d) = {wn} рад/с (период {T} с, {r} от ω₁).",
        "dof2.csv_note": "Все массивы по времени: dof2.csv.",
    },
}

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
                      sketch_cap=sketch_cap, equations=EQUATIONS, reactions=REACTIONS,
                      integration=t("dof2.integration", n=d.get("nfev")), figs=figs,
                      energy_text=t("dof2.energy_text", err=f(E["max_abs_error"], 3), rel=f(E["relative_error"], 2)),
                      maxima=_maxima(ctx, d), impact_head=impact_head, impact_rows=impact_rows,
                      impact_none=impact_none, impact_more=impact_more, centrifugal=centrifugal)
