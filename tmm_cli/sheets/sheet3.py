"""Sheet 3: the dynamics - the reduced moments, the works, the change of kinetic
energy over the cycle, the reduced moment of inertia and the energy-mass diagram
(Wittenbauer) with its tangents at ψmax, ψmin, each at a standard μ."""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from .. import locales
from ..report.figures import mu_text
from .frame import FRAME, std_mu
from .graph import draw_graph

if TYPE_CHECKING:
    from ..task import Task

TXT = locales.table("sheets", "sheet3")


def curve_name(key: str, lang: str) -> str:
    """A curve's name in the language's notation (M_d with the Cyrillic subscript of the driving
    moment in Russian and Ukrainian; the catalogue's ``curve`` table)."""
    from ..messages import catalogue
    return catalogue(lang)["terms"].get("curve", {}).get(key, key)


def build(cv, results: dict, task: Task | None, lang: str = "en") -> dict:
    f = results["flywheel"]
    a = f["arrays"]
    T = TXT[lang]
    mm = T["mm"]
    x0f, y0f, x1f, y1f = FRAME
    phi = np.asarray(a["phi_cycle"], float)
    # the φ axis 360 mm long over the cycle: μφ = 1 °/mm for a turn, 2 °/mm for a four-stroke
    # engine's 720° (drawn at 1 °/mm, its second turn ran 360 mm past the axis, over the
    # energy-mass diagram); a tick each 30 mm, labelled in degrees
    span = float(phi[-1] - phi[0]) if len(phi) > 1 else 360.0
    mu_phi = std_mu(span / 360.0)
    x_len = span / mu_phi
    ticks = [(30.0 * mu_phi * i, f"{30.0 * mu_phi * i:g}" if 30.0 * (i + 1) <= x_len else "")
             for i in range(int(x_len // 30.0 + 1e-9) + 1)]
    rows = [("M", [("M_d", "#7a1f1f"), ("M_c", "#1f5fbf"), ("M_red", "#000")], T["Nm"]),
            ("A", [("A_d", "#7a1f1f"), ("A_c", "#1f5fbf")], T["J"]),
            ("ΔT", [("dT", "#000")], T["J"])]
    # the reduced moment of inertia J_red(φ) and the angular speed ω(φ) of the crank, drawn
    # about its mean ωm (its deviation is a few per cent of it)
    # ω signed as the crank turns (negative clockwise), ωm its mean's magnitude: the mean taken
    # away with ω's sign (a clockwise press drew ω + ωm, 21 rad/s below its axis)
    omega = np.asarray(a["omega"], float) if a.get("omega") is not None else np.zeros(0)
    turn = -1.0 if omega.size and np.nanmean(omega) < 0 else 1.0
    omega_m = turn * abs(float(f.get("omega_m") or (np.nanmean(omega) if omega.size else 0.0)))
    arrays = dict(a, omega_dev=omega - omega_m)
    if a.get("J_red") is not None:
        rows.append(("J", [("J_red", "#000")], T["kgm2"]))
    if a.get("omega") is not None:
        rows.append((T["omega_dev"], [("omega_dev", "#000")], T["rads"]))   # ω − ω_mean
    box_h = (y1f - y0f - 20.0) / len(rows)
    info = {"mu_phi": mu_phi, "x_len": x_len, "graphs": {}, "scale": "—"}   # diagrams only: no length scale
    cv.mtext(x0f + 5, y1f - 6, T["title"], 5.0, bold=True)
    for k, (sym, keys, unit) in enumerate(rows):
        ys = [np.asarray(arrays[key], float) for key, _ in keys]
        hi = max(0.0, *(float(np.nanmax(y)) for y in ys))
        lo = min(0.0, *(float(np.nanmin(y)) for y in ys))
        mu = std_mu(max(hi - lo, 1e-12) / (box_h - 22.0))
        top = y1f - 14.0 - k * box_h
        yc = top - 6.0 - hi / mu
        dev = keys[0][0] == "omega_dev"           # ω − ω_mean: its scale is μω
        msym = "ω" if dev else sym.split()[0]
        mean = T["omega_mean"].format(w=f"{omega_m:.4g} {unit}") if dev else ""
        pts = draw_graph(cv, (x0f + 20.0, yc), [(phi, y, c) for y, (_, c) in zip(ys, keys)], mu_phi, mu,
                         x_len=x_len, y_up=hi / mu + 5.0, y_down=-lo / mu + 3.0, x_sym="φ",
                         y_sym=sym, mu_text=f"{mu_text(msym, mu, unit, mm)},  μφ = {mu_phi:g} °/{mm}"
                         + mean, ticks=ticks)
        # the names of the curves at their right ends
        ends = sorted(((p[-1][1], key) for p, (key, _) in zip(pts, keys)), reverse=True) if k < 3 else []
        last = None
        for yv, key in ends:
            yy = yv if last is None else min(yv, last - 4.0)
            base, _, low = curve_name(key, lang).partition("_")      # M with the subscript after "_"
            colour = dict(keys)[key]                        # the name in its curve's colour
            cv.mtext(x0f + 20.0 + x_len + 15.0, yy, base, 2.5, sub=low or None, color=colour)   # past φ
            last = yy
        info["graphs"][sym] = {"mu": mu, "pts": pts, "origin": (x0f + 20.0, yc),
                               "values": [y for y in ys]}
    # energy-mass diagram: ΔT against the variable part of the reduced moment of inertia,
    # the one the tangents' intercepts a, b of the flywheel stage refer to
    dT = np.asarray(a["dT"], float)
    J = np.asarray(a["J_var"], float)
    em = f.get("energy_mass") or {}
    bx0, by0, bw, bh = 430.0, 80.0, 380.0, y1f - 80.0 - 10.0
    # the ΔT axis reaches down to the lower tangent's intercept b (b <= min ΔT): the segment ab
    # on it is what the student measures (b lay below the axis's end, on nothing)
    low = min(0.0, float(dT.min()), *([float(em["b"])] if em.get("b") is not None else []))
    mu_T = std_mu((float(dT.max()) - low) / (bh - 40.0))
    mu_J = std_mu(float(J.max()) / (bw - 60.0))
    origin = (bx0 + 20.0, by0 + 15.0 - low / mu_T)
    cv.mtext(bx0 + 5, y1f - 6, T["em"], 5.0, bold=True)
    pts, = draw_graph(cv, origin, [(J, dT, "#000")], mu_J, mu_T, x_len=float(J.max()) / mu_J + 10.0,
                      y_up=float(dT.max()) / mu_T + 12.0, y_down=-low / mu_T + 5.0,
                      x_sym=locales.of("dynamics", "words", lang).get("dyn.Jvar", "J_var"), y_sym="ΔT",
                      mu_text=f"μT = {mu_T:g} {T['J']}/{mm},  μJ = {mu_J:g} {T['kgm2']}/{mm}")
    info["energy_mass"] = {"mu_T": mu_T, "mu_J": mu_J, "pts": pts, "origin": origin,
                           "axis_low": origin[1] - (-low / mu_T + 5.0)}
    # the tangents: ΔT = a + J ω_max²/2 and ΔT = b + J ω_min²/2 (Popov & Timofeev)
    if em.get("a") is not None and em.get("omega_max"):
        cv.layer = "thin"
        jj = np.array([0.0, float(J.max()) * 1.05])
        for c, w, name in ((em["a"], em["omega_max"], "a"), (em["b"], em["omega_min"], "b")):
            yy = float(c) + jj * float(w) ** 2 / 2.0
            q = np.c_[origin[0] + jj / mu_J, origin[1] + yy / mu_T]
            cv.line(q[0], q[1], width=0.3, dash="4 1.5")
            cv.mtext(q[0][0] - 2.0, q[0][1], name, 3.5, anchor="end", italic=True)
            info["energy_mass"].setdefault("tangents", []).append((float(c), float(w) ** 2 / 2.0))
    return info
