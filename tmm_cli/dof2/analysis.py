"""The stage ``dof2``: integrate Lagrange's equations of the rotary impact mechanism
(model.py) with scipy's DOP853 (rtol 1e-10) and report the motion, the dynamic
reactions in the pairs O and O1, the energy balance and the state at the hit.

``analyze(section) -> Dof2Result``; ``Dof2Result.to_dict()`` is the results.json
section ``dof2``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ..errors import StageError
from ..messages import Message
from . import model
from .model import Params

if TYPE_CHECKING:
    from .spec import Dof2Section

RTOL = 1e-10
ATOL = 1e-12
MAX_NFEV = 500_000   # ~5 s of integration: a longer run is a mistake in t_end / turns


class _TooLong(Exception):
    pass


@dataclass
class Dof2Result:
    """Time histories (radians internally; degrees in to_dict) and derived numbers."""

    params: Params
    drive: str                      # 'free' | 'moment' | 'speed'
    moment: float | None            # the constant driving moment, N*m
    omega1: float | None            # the held rotor speed (signed), rad/s
    state: dict                     # arrays over the output instants (see _evaluate)
    impacts: list = field(default_factory=list)    # states at the hits (dicts of floats)
    impact_phi: float | None = None               # deg
    centrifugal: dict | None = None
    energy: dict = field(default_factory=dict)
    nfev: int = 0
    warnings: list = field(default_factory=list)

    # ------------------------------------------------------------------
    def to_dict(self) -> dict:
        s, p = self.state, self.params
        L = _list
        out = {
            "convention": {"phi": "rotor angle O->O1 from +x, ccw, continuous (not reduced to [0, 360))",
                           "psi": "striker O1->M relative to the rotor (0: along O->O1); "
                                  "paper's psi = psi - 180",
                           "reactions": "R01: ground on rotor at O; R12: rotor on striker at O1 (R_ij = -R_ji)"},
            "parameters": {"l": p.l, "m1": p.m1, "s1": p.s1, "J_O": p.J_O, "l_M": p.l_M, "l_c": p.l_c,
                           "m2": p.m2, "J_C": p.J_C, "g": p.g,
                           "a": p.a, "b": p.b, "d": p.d,
                           "drive": self.drive, "moment": self.moment, "omega1": self.omega1},
            "t": L(s["t"]),
            "phi": L(np.degrees(s["phi"])), "psi": L(np.degrees(s["psi"])),
            "theta2": L(np.degrees(s["phi"] + s["psi"])),
            "omega": L(s["w"]), "psi_dot": L(s["pd"]), "omega2": L(s["w"] + s["pd"]),
            "epsilon": L(s["wd"]), "psi_ddot": L(s["pdd"]), "epsilon2": L(s["wd"] + s["pdd"]),
            "driving_moment": L(s["Md"]),
            "points": {name: {"x": L(s[name][:, 0]), "y": L(s[name][:, 1]),
                              "vx": L(s["v" + name][:, 0]), "vy": L(s["v" + name][:, 1]),
                              "v": L(np.hypot(*s["v" + name].T))}
                       for name in ("O1", "C", "M")},
            "reactions": {k: {"x": L(s[k][:, 0]), "y": L(s[k][:, 1]), "R": L(np.hypot(*s[k].T))}
                          for k in ("R01", "R12")},
            "energy": dict(self.energy),
            "max": self._maxima(),
            "impact_phi": self.impact_phi,
            "impact": self.impacts[0] if self.impacts else None,
            "impacts": list(self.impacts),
            "centrifugal": self.centrifugal,
            "samples": int(len(s["t"])),
            "t_end": float(s["t"][-1]),
            "nfev": int(self.nfev),
            "warnings": list(self.warnings),
        }
        return out

    def _maxima(self) -> dict:
        s = self.state
        t = s["t"]

        def at(arr, fn):
            i = int(fn(arr))
            return {"value": float(arr[i]), "t": float(t[i])}
        out = {}
        for k in ("R01", "R12"):
            out[k] = at(np.hypot(*s[k].T), np.argmax)
        vM = np.hypot(*s["vM"].T)
        out["v_M"] = at(vM, np.argmax)
        out["omega_max"] = at(s["w"], np.argmax)
        out["omega_min"] = at(s["w"], np.argmin)
        out["psi_max"] = {"value": float(np.degrees(s["psi"].max())), "t": float(t[np.argmax(s["psi"])])}
        out["psi_min"] = {"value": float(np.degrees(s["psi"].min())), "t": float(t[np.argmin(s["psi"])])}
        out["psi_dot_max"] = at(np.abs(s["pd"]), np.argmax)
        out["driving_moment_max"] = at(s["Md"], np.argmax)
        out["driving_moment_min"] = at(s["Md"], np.argmin)
        return out


def _list(a) -> list:
    a = np.asarray(a, dtype=float)
    return [float(x) if math.isfinite(x) else None for x in a.tolist()]


def _evaluate(p: Params, drive: str, moment: float, t, Y) -> dict:
    """Every derived quantity at the instants t (states Y: (5, N) = phi, psi, w, pd, W)."""
    phi, psi, w, pd, W = (np.asarray(Y[i], float) for i in range(5))
    if drive == "speed":
        pdd, Md = model.held_speed(p, phi, psi, w, pd)
        wd = np.zeros_like(phi)
    else:
        Md = np.full_like(phi, moment)
        wd, pdd = model.accelerations(p, phi, psi, w, pd, Md)
    out = {"t": np.asarray(t, float), "phi": phi, "psi": psi, "w": w, "pd": pd, "wd": wd, "pdd": pdd,
           "Md": Md, "W": W}
    for name, (r1, r2) in {"O1": (p.l, 0.0), "C": (p.l, p.l_c), "M": (p.l, p.l_M)}.items():
        r, v, a = model.point_kinematics(r1, r2, phi, psi, w, pd, wd, pdd)
        out[name], out["v" + name], out["a" + name] = r, v, a
    out["R01"], out["R12"] = model.reactions(p, phi, psi, w, pd, wd, pdd)
    out["T"], out["V"] = model.energy(p, phi, psi, w, pd)
    return out


def _event_state(p: Params, s: dict, i: int) -> dict:
    """The state at one instant as a dict of plain floats (degrees for angles)."""
    th = s["phi"][i] + s["psi"][i]
    om2 = s["w"][i] + s["pd"][i]
    vC = s["vC"][i]
    T2 = 0.5 * p.m2 * float(vC @ vC) + 0.5 * p.J_C * om2 ** 2
    return {"t": float(s["t"][i]), "phi": float(np.degrees(s["phi"][i])), "psi": float(np.degrees(s["psi"][i])),
            "theta2": float(np.degrees(th)), "omega": float(s["w"][i]), "psi_dot": float(s["pd"][i]),
            "omega2": float(om2), "epsilon": float(s["wd"][i]), "psi_ddot": float(s["pdd"][i]),
            "M": {"x": float(s["M"][i, 0]), "y": float(s["M"][i, 1]),
                  "vx": float(s["vM"][i, 0]), "vy": float(s["vM"][i, 1]), "v": float(np.hypot(*s["vM"][i]))},
            "striker_energy": float(T2), "kinetic_energy": float(s["T"][i]),
            "driving_moment": float(s["Md"][i]),
            "R01": {"x": float(s["R01"][i, 0]), "y": float(s["R01"][i, 1]), "R": float(np.hypot(*s["R01"][i]))},
            "R12": {"x": float(s["R12"][i, 0]), "y": float(s["R12"][i, 1]), "R": float(np.hypot(*s["R12"][i]))}}


def centrifugal_pendulum(p: Params, omega1: float) -> dict | None:
    """Small oscillations of the striker about its relative equilibrium.

    Parameters
    ----------
    p : Params
        The mechanism (SI units).
    omega1 : float
        The rotor's constant speed, rad/s.

    Returns
    -------
    dict or None
        ``omega_n`` (rad/s), ``period`` (s), ``ratio`` = omega_n/|omega1| and ``about_psi``
        (deg) of d psi'' + b omega1^2 sin psi = 0 (:func:`.model.held_speed` with
        phi' = omega1, g = 0): omega_n = |omega1| sqrt(b/d) about psi = 0 (b > 0: the centre
        of mass C ahead of the hinge) or about psi = 180 deg (b < 0); None for b = 0, a
        rotor at rest or with gravity.

    References
    ----------
    Frolov (ed.), *Teoriya mekhanizmov i mashin*: the centrifugal pendulum; docs/methods.md §7.
    """
    if p.g != 0 or p.b == 0 or omega1 == 0:
        return None
    ratio = math.sqrt(abs(p.b) / p.d)
    wn = abs(omega1) * ratio
    return {"omega_n": wn, "period": 2 * math.pi / wn, "ratio": ratio, "about_psi": 0.0 if p.b > 0 else 180.0}


def analyze(section: Dof2Section) -> Dof2Result:
    """Integrate the motion of the rotary impact mechanism.

    Parameters
    ----------
    section : Dof2Section
        The task's ``dof2`` section: the rotor (length l, mass, centre of mass, J_O; m,
        kg, kg*m^2), the striker (length to M, l_c, mass, J_C), gravity, the drive (a
        constant moment, N*m, or a held speed, rad/s; none: free motion), the initial state
        (deg, rad/s), the duration (``t_end``, s, or ``turns``) and the output ``samples``.

    Returns
    -------
    Dof2Result
        The time histories of the angles (deg), speeds (rad/s), accelerations, the dynamic
        reactions in O and O1 (N), the energy balance (J) and the state at the hit;
        ``to_dict()`` is the results.json ``dof2`` section.

    Raises
    ------
    StageError
        A singular mass matrix, a failed integration, or a rotor that does not make the
        asked ``turns`` within ``t_max``.

    Notes
    -----
    Lagrange's equations of the second kind (:mod:`.model`) are integrated by
    ``scipy.integrate.solve_ivp`` (DOP853, rtol 1e-10, atol 1e-12) with the work of the
    driving moment as a fifth state, then sampled at ``samples`` equal steps over the
    duration.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*; Frolov (ed.), *Teoriya mekhanizmov i
    mashin*: Lagrange's equations of the second kind for a machine with two degrees of freedom;
    V. V. Voronkin, the rotary impact mechanism (the derivation re-done in the module's
    docstring); docs/methods.md §7.
    """
    from scipy.integrate import solve_ivp  # lazy: scipy.integrate costs import time

    p = Params.from_section(section)
    dr = section.drive
    if dr is None:
        drive, moment, omega1 = "free", 0.0, None
    elif dr.speed is not None:
        drive, moment, omega1 = "speed", 0.0, dr.omega1
    else:
        drive, moment, omega1 = "moment", float(dr.moment), None
    p.check(speed_held=drive == "speed")

    ini = section.initial
    phi0, psi0 = math.radians(ini.phi), math.radians(ini.psi)
    w0 = omega1 if drive == "speed" else float(ini.omega)
    y0 = np.array([phi0, psi0, w0, float(ini.psi_dot), 0.0])

    f = model.rhs_scalar(p, drive == "speed", moment)
    calls = [0]

    def rhs(t, y):
        calls[0] += 1
        if calls[0] > MAX_NFEV:
            raise _TooLong(t)
        return f(t, y)

    events = []
    turns_event = None
    if section.turns is not None and drive != "speed":
        target = 2 * math.pi * float(section.turns)

        def turns_event(t, y):
            return abs(y[0] - phi0) - target
        turns_event.terminal = True
        turns_event.direction = 1
        events.append(turns_event)
        t_stop = float(section.t_max)
    elif section.turns is not None:
        t_stop = 2 * math.pi * float(section.turns) / abs(omega1)
    else:
        t_stop = float(section.t_end)

    imp = section.impact
    impact_event = None
    if imp is not None:
        phi_i = math.radians(imp.phi)

        def impact_event(t, y):
            return math.sin(0.5 * (y[0] - phi_i))
        impact_event.terminal = False
        events.append(impact_event)

    try:
        with np.errstate(all="ignore"):
            sol = solve_ivp(rhs, (0.0, t_stop), y0, method="DOP853", rtol=RTOL, atol=ATOL, dense_output=True,
                            events=events or None)
    except _TooLong as exc:
        raise StageError("dof2", Message("dof2.fail.too_long", rtol=RTOL, nfev=MAX_NFEV, t=exc.args[0],
                                         t_stop=t_stop)) from None
    if sol.status == -1:
        raise StageError("dof2", Message("dof2.fail.integration", why=str(sol.message)))
    t_final = float(sol.t[-1])
    if turns_event is not None and sol.status != 1:
        turned = abs(sol.y[0, -1] - phi0) / (2 * math.pi)
        raise StageError("dof2", Message("dof2.fail.turns", turned=turned, turns=float(section.turns), t_stop=t_stop))
    hits = []
    if impact_event is not None:
        k = events.index(impact_event)
        hits = [float(x) for x in sol.t_events[k] if 0 < x <= t_final]
        if imp.stop and hits:
            t_final = hits[0]
            hits = hits[:1]
    if t_final <= 0:
        raise StageError("dof2", Message("dof2.fail.zero_duration"))

    t = np.linspace(0.0, t_final, int(section.samples))
    with np.errstate(all="ignore"):
        Y = sol.sol(t)
        Y[:, 0] = y0
        s = _evaluate(p, drive, moment, t, Y)
    if not all(np.all(np.isfinite(s[k])) for k in ("phi", "psi", "w", "pd", "wd", "pdd", "R01", "R12", "T")):
        raise StageError("dof2", Message("dof2.fail.not_finite"))

    warnings: list[str] = []
    impacts: list[dict] = []
    if hits:
        with np.errstate(all="ignore"):
            se = _evaluate(p, drive, moment, np.array(hits), sol.sol(np.array(hits)))
        impacts = [_event_state(p, se, i) for i in range(len(hits))]
    elif imp is not None:
        warnings.append(Message("dof2.no_impact", phi=imp.phi, t=t_final))

    # energy balance: T + V - W = const (W = work of the driving moment)
    E = s["T"] + s["V"] - s["W"]
    err = E - E[0]
    scale = max(float(np.max(np.abs(s["T"]))), float(np.ptp(s["V"])), float(np.max(np.abs(s["W"]))), 1e-300)
    rel = float(np.max(np.abs(err)) / scale)
    energy = {"T": _list(s["T"]), "V": _list(s["V"]), "W": _list(s["W"]), "E0": float(E[0]),
              "balance": _list(err), "max_abs_error": float(np.max(np.abs(err))), "relative_error": rel}
    if drive == "moment":
        exact_W = moment * (s["phi"] - phi0)
        energy["W_exact_error"] = float(np.max(np.abs(s["W"] - exact_W)))
    if rel > 1e-6:
        warnings.append(Message("dof2.energy_balance", rel=rel))
    if drive == "moment" and np.any(np.diff(np.sign(s["w"][np.abs(s["w"]) > 0])) != 0):
        warnings.append(Message("dof2.rotor_reverses"))

    return Dof2Result(params=p, drive=drive, moment=moment if drive == "moment" else None, omega1=omega1,
                      state=s, impacts=impacts, impact_phi=None if imp is None else float(imp.phi),
                      centrifugal=centrifugal_pendulum(p, omega1) if drive == "speed" else None,
                      energy=energy, nfev=int(sol.nfev), warnings=warnings)
