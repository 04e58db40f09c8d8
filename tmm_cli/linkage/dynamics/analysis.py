"""Dynamics stage: reduced quantities over the cycle, the flywheel by three methods,
the steady motion omega(phi), epsilon(phi), the accuracy-against-resolution table.

Entry points
------------
``solve_cycle(q, M_given, J_links, ...)``   the whole flywheel calculation on arrays
``analyze_sampler(sampler, section, ...)``  chooses the grid and calls a sampler
``analyze(mech, kin_fn, loads_fn, section, drive, *, phi0, switch_angles)``
``analyze_task(mech, task, positions)``     the pipeline's call

The grid: ``resolution`` equal steps over the cycle (360 or 720 deg of crank rotation
from position 0 in the direction of motion) plus every crank angle where a load
jumps, inserted twice (left and right limits: the loads are evaluated 1e-7 deg
before and after it, the node keeps the exact angle), so the trapezoid of the works
is exact for piecewise-linear loads and the extrema at the jumps are on the grid.
The first node (position 0) carries the right limit, the last (one cycle later) the
left limit.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace
from typing import Callable

import numpy as np

from ...errors import StageError
from ...messages import Message
from . import flywheel as fw
from .reduce import Sample, sample as sample_mech

STAGE = "dynamics"
EPS_DEG = 1e-5   # one-sided evaluation offset at a jump, deg (coarser than the loads' 1e-9 snapping)
ACCURACY_RESOLUTIONS = (12, 24, 36, 72, 180, 360, 3600)
FLYWHEEL_METHODS = ("energy-mass", "merzalov", "exact")
GAUSS_DEFAULT = 2   # Gauss-Legendre points per grid interval for the works (order 4)
CHECK_BELOW = 180   # a coarser grid is checked against twice its positions ...
TARGET_REL = 1e-6   # ... and a warning given when J_n moves by more than this

Sampler = Callable[[np.ndarray, np.ndarray], Sample]
"""sampler(q_deg, side) -> Sample: reduced quantities at the cycle angles q_deg (deg of
crank rotation from position 0 along the motion), each evaluated at q + side*EPS_DEG
(side -1: left limit, +1: right limit, 0: exactly)."""


# ------------------------------------------------------------------ grid
def grid(resolution: int, cycle: float, switch_q: tuple | list = (), insert: bool = True
         ) -> tuple[np.ndarray, np.ndarray]:
    """Nodes (q_deg, side) of the cycle: resolution + 1 equal steps over [0, cycle] and
    the jump angles switch_q (deg, from position 0 along the motion) twice each.
    With insert=False: the plain equal steps, every node evaluated exactly
    (what a hand calculation over the positions does)."""
    n = int(resolution)
    if n < 2:
        raise StageError(STAGE, f"resolution must be at least 2 (got {resolution})")
    C = float(cycle)
    q = np.linspace(0.0, C, n + 1)
    if not insert:
        return q, np.zeros_like(q)
    side = np.zeros_like(q)
    side[0], side[-1] = 1.0, -1.0
    tol = 2 * EPS_DEG
    sw = []
    for s in switch_q:
        s = float(s) % C
        if s < tol or C - s < tol:
            continue
        if all(abs(s - t) >= tol for t in sw):
            sw.append(s)
    if sw:
        sw = np.asarray(sorted(sw))
        keep = np.ones(q.size, bool)
        for s in sw:
            keep &= ~((np.abs(q - s) < tol) & (side == 0))
        q, side = q[keep], side[keep]
        q = np.concatenate([q, sw, sw])
        side = np.concatenate([side, -np.ones(sw.size), np.ones(sw.size)])
        order = np.lexsort((side, q))
        q, side = q[order], side[order]
    return q, side


# ------------------------------------------------------------------ array core
@dataclass
class CycleResult:
    """The flywheel calculation on one grid (all arrays along the nodes q)."""
    q: np.ndarray                  # rad
    work: fw.CycleWork
    J_links: dict[str, np.ndarray]
    J_extra: float
    J_red: np.ndarray              # total reduced inertia of the machine without flywheel
    J_const: float
    J_var: np.ndarray
    dJ_var: np.ndarray             # dJ_var/dq
    const_links: list[str]
    omega_m: float
    delta: float
    method: str
    J_n: dict[str, float]          # per method (+ 'wittenbauer')
    a: float
    b: float
    a_w: float
    b_w: float
    dT_I: np.ndarray
    T_II: np.ndarray
    J_fly: dict[str, float]        # J_n - J_const per method
    J: float                       # chosen flywheel (>= 0)
    motion: fw.Motion
    epsilon: np.ndarray            # d|omega|/dt along the motion, rad/s^2
    M_by_kind: dict[str, np.ndarray]
    warnings: list[str]
    J_var_min: float = 0.0         # extremes of J_var over the cycle (nodes and the located
    J_var_max: float = 0.0         # extrema between them)

    @property
    def J_n_primary(self) -> float:
        return self.J_n[self.method]

    @property
    def J_total(self) -> np.ndarray:
        """Reduced inertia of the machine with the chosen flywheel."""
        return self.J_const + self.J + self.J_var


def _dq_numeric(q: np.ndarray, y: np.ndarray) -> np.ndarray:
    """dy/dq by finite differences on the distinct nodes (fallback without d2/a2)."""
    uq, first = np.unique(q, return_index=True)
    if uq.size < 3:
        return np.zeros_like(y)
    # periodic central differences: the cycle closes (y[last] == y[first])
    yu = y[first]
    h = np.diff(uq)
    d = np.empty_like(yu)
    d[1:-1] = ((yu[2:] - yu[1:-1]) / h[1:] * h[:-1] + (yu[1:-1] - yu[:-2]) / h[:-1] * h[1:]) \
        / (h[:-1] + h[1:])
    end = ((yu[1] - yu[0]) / h[0] * h[-1] + (yu[-1] - yu[-2]) / h[-1] * h[0]) / (h[0] + h[-1])
    d[0] = d[-1] = end
    return np.interp(q, uq, d)


def _extrema_between_nodes(q, dT, M_red, J_var, dJ_var, omega_m, delta) -> np.ndarray:
    """Crank angles (rad) between the nodes where the energy functions of the methods,
    dT - J_var omega^2/2 at omega_max, omega_min and omega_m, have their maxima and minima
    (Hermite critical points, see `flywheel.hermite_critical`)."""
    out = []
    for w in (omega_m * (1 + delta / 2), omega_m * (1 - delta / 2), omega_m):
        c = w * w / 2
        out.append(fw.hermite_critical(q, dT - J_var * c, M_red - dJ_var * c))
        if not np.any(J_var):
            break
    return np.unique(np.concatenate(out))


def solve_cycle(q: np.ndarray, M_given: np.ndarray, J_links: dict[str, np.ndarray] | np.ndarray,
                *, omega_m: float, delta: float, constant: str = "driving",
                method: str = "energy-mass", J_extra: float = 0.0,
                dJ_links: dict[str, np.ndarray | None] | None = None,
                M_by_kind: dict[str, np.ndarray] | None = None,
                const_tol: float = 1e-9, increments: np.ndarray | None = None,
                refine: bool = True, polish: Callable | None = None) -> CycleResult:
    """The whole flywheel calculation on arrays.

    q: nodes (rad) from 0 to the cycle, non-decreasing (duplicates at jumps);
    M_given: reduced moment of the given loads along the motion (N,);
    J_links: reduced inertia per link (dict of (N,)) or one (N,) array (treated as one
    link named 'mechanism'); J_extra: constant reduced inertia given in the task
    (flywheel.reduced_J); dJ_links: d/dq of each link's J_red (else finite differences).
    A link whose reduced inertia varies by less than const_tol of its maximum goes to
    J_const (docs/methods.md §4: crank, rotor, gears), the rest to J_var.
    increments: the integrals of M_given over every interval of q (else the trapezoid);
    refine: locate the extrema of the energy functions between the nodes (critical points
    of their cubic Hermite interpolants with the exact slopes M_red - J_var' omega^2/2)
    and include them in the maxima and minima of every method (the hand calculation:
    False, the extrema at the nodes); polish(points, work, const_links) -> (dT, J_var)
    evaluates these two exactly at the located points (else: the Hermite interpolants).
    """
    if method not in FLYWHEEL_METHODS:
        raise StageError(STAGE, f"unknown method {method!r}")
    q = np.asarray(q, float)
    if isinstance(J_links, np.ndarray) or not isinstance(J_links, dict):
        J_links = {"mechanism": np.broadcast_to(np.asarray(J_links, float), q.shape).copy()}
    warnings: list[str] = []
    work = fw.cycle_work(q, M_given, constant, increments)
    n = q.size
    J_const = float(J_extra)
    J_var = np.zeros(n)
    dJ_var = np.zeros(n)
    const_links: list[str] = []
    numeric = []
    for name, arr in J_links.items():
        arr = np.broadcast_to(np.asarray(arr, float), (n,))
        if not np.all(np.isfinite(arr)):
            raise StageError(STAGE, f"reduced moment of inertia of '{name}' is not finite")
        if float(np.min(arr)) < 0:
            raise StageError(STAGE, f"reduced moment of inertia of '{name}' is negative")
        top = float(np.max(arr))
        if float(np.ptp(arr)) <= const_tol * top:
            const_links.append(name)
            J_const += float(np.mean(arr))
            continue
        J_var = J_var + arr
        d = None if dJ_links is None else dJ_links.get(name)
        if d is None:
            numeric.append(name)
            d = _dq_numeric(q, arr)
        dJ_var = dJ_var + np.broadcast_to(np.asarray(d, float), (n,))
    J_red = J_const + J_var

    dTx, Jx = work.dT, J_var
    if refine:
        ext = _extrema_between_nodes(q, work.dT, work.M_red, J_var, dJ_var, omega_m, delta)
        if ext.size:
            if polish is not None:
                dTe, Je = polish(ext, work, const_links)
            else:
                dTe, Je = fw.hermite_at(q, work.dT, work.M_red, ext), fw.hermite_at(q, J_var, dJ_var, ext)
            dTx = np.concatenate([work.dT, dTe])
            Jx = np.concatenate([J_var, Je])
    Jn_em, a, b = fw.energy_mass(dTx, Jx, omega_m, delta)
    Jn_w, a_w, b_w = fw.wittenbauer(dTx, Jx, omega_m, delta)
    Jn_m, dT_I, T_II = fw.merzalov(dTx, Jx, omega_m, delta)
    dT_I, T_II = dT_I[:n], T_II[:n]
    Jn_ex = fw.exact_flywheel(dTx, Jx, omega_m, delta, guess=Jn_em)
    J_n = {"energy-mass": Jn_em, "merzalov": Jn_m, "exact": Jn_ex, "wittenbauer": Jn_w}
    J_fly = {k: v - J_const for k, v in J_n.items()}
    primary = J_fly[method]
    scale = max(J_const, float(np.max(J_red)), abs(J_n[method]), 1e-300)
    if primary < 0:
        J = 0.0
        if primary < -1e-12 * scale:
            warnings.append(Message("flywheel.not_needed_exceeds", J_const=J_const, J_needed=J_n[method],
                                    delta=delta, method=method))
    else:
        J = float(primary)
        if primary <= 1e-12 * scale:
            J = 0.0
            if float(np.ptp(work.dT)) == 0.0 and float(np.ptp(J_var)) == 0.0:
                warnings.append(Message("flywheel.not_needed_no_work"))
            else:
                warnings.append(Message("flywheel.not_needed_equal", J_const=J_const, J_needed=J_n[method],
                                        delta=delta, method=method))
    motion = fw.steady_motion(dTx, Jx, J_const + J, omega_m)
    motion = replace(motion, omega=motion.omega[:n])
    J_tot = J_const + J + J_var
    num = work.M_red - dJ_var * motion.omega**2 / 2
    eps = np.divide(num, J_tot, out=np.zeros_like(num), where=J_tot > 0)
    if not np.all(np.isfinite(eps)):
        raise StageError(STAGE, "angular acceleration of the crank is not finite")

    span_w = max(float(np.max(np.abs(work.A_d))), float(np.max(np.abs(work.A_c))), 1e-300)
    if constant == "driving" and work.M_constant < -1e-12 * span_w:
        warnings.append(Message("flywheel.net_positive_work", M=work.M_constant))
    if constant == "resistance" and work.M_constant > 1e-12 * span_w:
        warnings.append(Message("flywheel.net_negative_work", M=-work.M_constant))
    return CycleResult(q=q, work=work, J_links=dict(J_links), J_extra=float(J_extra), J_red=J_red,
                       J_const=J_const, J_var=J_var, dJ_var=dJ_var, const_links=const_links,
                       omega_m=float(omega_m), delta=float(delta), method=method, J_n=J_n,
                       a=a, b=b, a_w=a_w, b_w=b_w, dT_I=dT_I, T_II=T_II, J_fly=J_fly, J=J,
                       motion=motion, epsilon=eps, M_by_kind=dict(M_by_kind or {}),
                       warnings=warnings, J_var_min=float(np.min(Jx)), J_var_max=float(np.max(Jx)))


# ------------------------------------------------------------------ result
def _f(x):
    """Plain float, None for non-finite."""
    if x is None:
        return None
    x = float(x)
    return x + 0.0 if math.isfinite(x) else None     # + 0.0: no negative zero in the results


def _l(a):
    return [_f(v) for v in np.asarray(a, float).ravel()]


@dataclass
class DynamicsResult:
    cycle: CycleResult
    cycle_deg: float
    resolution: int
    phi0: float
    sign: float
    constant: str
    shape: dict
    size: fw.FlywheelSize
    accuracy: dict | None
    warnings: list[str]
    q_deg: np.ndarray
    side: np.ndarray
    sampler: Sampler | None = field(default=None, repr=False)
    map_cycle: float | None = None   # how motion_at reads crank angles (default: the cycle)
    hand: dict | None = None         # the 12-position hand method beside the accurate result
    quadrature_points: int = GAUSS_DEFAULT

    # ---- the numbers
    @property
    def J_fly(self) -> float:
        """The chosen flywheel's own moment of inertia (>= 0), kg*m^2."""
        return self.cycle.J

    @property
    def J(self) -> float:
        return self.cycle.J

    @property
    def phi(self) -> np.ndarray:
        """Absolute crank angles of the nodes, deg in [0, 360)."""
        return np.mod(self.phi0 + self.sign * self.q_deg, 360.0)

    # ---- the steady motion at arbitrary crank angles
    def _q_of(self, phi) -> np.ndarray:
        c = self.map_cycle or self.cycle_deg
        return np.mod(self.sign * (np.asarray(phi, float) - self.phi0), c)

    def motion_at(self, phi) -> tuple[np.ndarray, np.ndarray]:
        """(omega1, epsilon1), signed (ccw positive), of the steady motion with the
        chosen flywheel at absolute crank angles phi (deg), read as the rotation
        sign*(phi - phi0) mod `map_cycle`: the cycle, or, from analyze_task, the cycle the
        loads module uses for the same positions (360 when the positions carry none: the
        first turn of a 720-deg cycle), so that the loads at these positions match.  With a sampler the reduced moment and inertia
        are evaluated exactly at phi (so eps satisfies the equation of motion exactly
        there and the balancing moment of kinetostatics equals the constant driving
        moment); only dT is interpolated (cubic Hermite with slope M_red)."""
        phi = np.atleast_1d(np.asarray(phi, float))
        c = self.cycle
        q = self._q_of(phi)
        qr = np.deg2rad(q)
        dT = fw.hermite_at(c.q, c.work.dT, c.work.M_red, qr)
        if self.sampler is not None:
            s = self.sampler(q, np.zeros_like(q))
            M = s.M_given + c.work.M_constant
            names = [k for k in s.J_links if k not in c.const_links]
            J_var = np.zeros_like(q)
            for k in names:
                J_var = J_var + s.J_links[k]
            ds = [(s.dJ_links or {}).get(k) for k in names]
            if all(d is not None for d in ds):
                dJ = np.zeros_like(q)
                for d in ds:
                    dJ = dJ + d
            else:   # no second-order analogues: the grid's finite differences
                dJ = np.interp(qr, c.q, c.dJ_var)
        else:
            M = np.interp(qr, c.q, c.work.M_red)
            J_var = np.interp(qr, c.q, c.J_var)
            dJ = np.interp(qr, c.q, c.dJ_var)
        J_tot = c.J_const + c.J + J_var
        pos = J_tot > 0
        Js = np.where(pos, J_tot, 1.0)
        # no inertia at all (massless links, no flywheel): steady_motion allows this only
        # when nothing changes over the cycle, and then the motion is uniform at omega_m
        w = np.where(pos, np.sqrt(np.maximum(2 * (c.motion.T0 + dT), 0.0) / Js), c.omega_m)
        eps = np.where(pos, (M - dJ * w**2 / 2) / Js, 0.0)
        return self.sign * w, self.sign * eps

    def omega_of(self, phi) -> np.ndarray:
        """Signed omega1(phi) of the steady motion (rad/s)."""
        return self.motion_at(phi)[0]

    def epsilon_of(self, phi) -> np.ndarray:
        """Signed epsilon1(phi) of the steady motion (rad/s^2), from the equation of
        motion eps = (M_red - J' omega^2/2)/J."""
        return self.motion_at(phi)[1]

    # ---- results.json
    def to_dict(self) -> dict:
        c = self.cycle
        w = c.work
        m = c.motion
        d = {
            "J": _f(c.J),
            "J_energy_mass": _f(c.J_fly["energy-mass"]),
            "J_merzalov": _f(c.J_fly["merzalov"]),
            "J_exact": _f(c.J_fly["exact"]),
            "J_n": _f(c.J_n[c.method]),
            "J_const": _f(c.J_const),
            "delta_achieved": _f(m.delta),
            "omega_max": _f(m.omega_max),
            "omega_min": _f(m.omega_min),
            "M_constant": _f(w.M_constant),
            "diameter": _f(self.size.diameter),
            "width": _f(self.size.width),
            "mass": _f(self.size.mass),
            # extensions
            "method": c.method,
            "constant": self.constant,
            "delta": _f(c.delta),
            "omega_m": _f(c.omega_m),
            "cycle": _f(self.cycle_deg),
            "resolution": int(self.resolution),
            "phi0": _f(self.phi0),
            "direction": "ccw" if self.sign > 0 else "cw",
            "J_wittenbauer": _f(c.J_fly["wittenbauer"]),
            "J_n_methods": {k: _f(v) for k, v in c.J_n.items()},
            "J_fly_primary": _f(c.J_fly[c.method]),
            "J_extra": _f(c.J_extra),
            "J_var_min": _f(c.J_var_min),
            "J_var_max": _f(c.J_var_max),
            "constant_links": list(c.const_links),
            "energy_mass": {"a": _f(c.a), "b": _f(c.b),
                            "omega_max": _f(c.omega_m * (1 + c.delta / 2)),
                            "omega_min": _f(c.omega_m * (1 - c.delta / 2)),
                            "a_wittenbauer": _f(c.a_w), "b_wittenbauer": _f(c.b_w)},
            "work_cycle": _f(w.A_given),
            "T0": _f(m.T0),
            "rim_speed": _f(self.size.rim_speed),
            "shape": dict(self.shape),
            "thickness": _f(self.size.thickness) if self.size.thickness is not None else None,
            "arrays": {
                "phi_cycle": _l(self.q_deg),
                "phi": _l(self.phi),
                "M_red": _l(w.M_red),
                "M_d": _l(w.M_d),
                "M_c": _l(w.M_c),
                "M_given": _l(w.M_given),
                "M_by_kind": {k: _l(v) for k, v in c.M_by_kind.items()},
                "A_d": _l(w.A_d),
                "A_c": _l(w.A_c),
                "dT": _l(w.dT),
                "J_red": _l(c.J_red),
                "J_var": _l(c.J_var),
                "J_links": {k: _l(v) for k, v in c.J_links.items()},
                "dT_I": _l(c.dT_I),
                "T_II": _l(c.T_II),
                "omega": _l(self.sign * m.omega),
                "epsilon": _l(self.sign * c.epsilon),
            },
            "quadrature": _quadrature_of(self),
            "hand": self.hand,
            "accuracy": self.accuracy,
            "warnings": list(self.warnings),
        }
        return d


def _quadrature_of(r: "DynamicsResult") -> str:
    n = r.quadrature_points
    return "trapezoid" if n == 0 else f"gauss-legendre {n} points per interval"


# ------------------------------------------------------------------ drivers
def _split(s: Sample, n: int) -> tuple[Sample, Sample]:
    """A Sample over n + m angles as (the first n, the other m)."""
    def cut(a, sl):
        return None if a is None else np.asarray(a)[sl]

    def part(sl):
        return Sample(M_by_kind={k: cut(v, sl) for k, v in s.M_by_kind.items()},
                      M_given=cut(s.M_given, sl),
                      J_links={k: cut(v, sl) for k, v in s.J_links.items()},
                      dJ_links={k: cut(v, sl) for k, v in (s.dJ_links or {}).items()},
                      J_links_total=cut(s.J_links_total, sl), dJ_total=cut(s.dJ_total, sl))
    return part(slice(0, n)), part(slice(n, None))


def _run_grid(sampler: Sampler, section, omega_m: float, cycle: float, resolution: int,
              switch_q, insert: bool = True, gauss: int | None = None
              ) -> tuple[CycleResult, np.ndarray, np.ndarray]:
    """The flywheel on the grid.  gauss: Gauss-Legendre points per interval for the works
    (default: the section's `quadrature`; 0: the trapezoid on the nodes and the extrema
    at the nodes, as by hand; insert=False implies 0)."""
    q_deg, side = grid(resolution, cycle, switch_q, insert)
    n_g = int(getattr(section, "quadrature", GAUSS_DEFAULT)) if gauss is None else int(gauss)
    if not insert:
        n_g = 0
    inc = None
    if n_g > 0:
        xg = fw.gauss_points(q_deg, n_g).ravel()
        s, sg = _split(sampler(np.concatenate([q_deg, xg]),
                               np.concatenate([side, np.zeros(xg.size)])), q_deg.size)
        inc = fw.gauss_increments(np.deg2rad(q_deg), sg.M_given, n_g)
    else:
        s = sampler(q_deg, side)
    qr = np.deg2rad(q_deg)

    def polish(ext, work, const_links):
        """dT and J_var exactly at the located extrema (rad): the sampler there and the
        Gauss rule from the interval's left node."""
        i = np.clip(np.searchsorted(qr, ext, side="right") - 1, 0, qr.size - 2)
        xg = (q_deg[i][:, None] + (np.rad2deg(ext) - q_deg[i])[:, None] * fw.gauss_legendre(n_g)[0])
        se, sg2 = _split(sampler(np.concatenate([np.rad2deg(ext), xg.ravel()]),
                                 np.zeros(ext.size * (1 + n_g))), ext.size)
        h = ext - qr[i]
        dT = work.dT[i] + h * (sg2.M_given.reshape(-1, n_g) @ fw.gauss_legendre(n_g)[1]) \
            + work.M_constant * h
        Jv = np.zeros(ext.size)
        for k, v in se.J_links.items():
            if k not in const_links:
                Jv = Jv + v
        return dT, Jv

    res = solve_cycle(qr, s.M_given, s.J_links, omega_m=omega_m,
                      delta=float(section.delta), constant=section.constant,
                      method=section.method, J_extra=float(getattr(section, "reduced_J", 0.0)),
                      dJ_links=s.dJ_links, M_by_kind=s.M_by_kind, increments=inc,
                      refine=n_g > 0, polish=polish if n_g > 0 else None)
    return res, q_deg, side


def _rel(x, ref):
    if ref is None or x is None:
        return None
    den = abs(ref)
    if den == 0:
        return 0.0 if x == 0 else None
    return abs(x - ref) / den


def hand_row(sampler: Sampler, section, omega_m: float, cycle: float, switch_q,
             ref: CycleResult, ref_resolution: int) -> dict:
    """The course's hand method: 12 positions every 30 deg (24 over 720 deg), the trapezoid
    of the works, no inserted jump points, the extrema at the positions; beside the
    accurate result `ref` (deterministic: no timing)."""
    n_hand = int(round(cycle / 30.0))
    hand = _run_grid(sampler, section, omega_m, cycle, n_hand, switch_q, insert=False)[0]
    J_ref = ref.J_fly[ref.method]
    return {"method": "hand: trapezoid over the positions", "positions": n_hand, "step": 30.0,
            "J_energy_mass": _f(hand.J_fly["energy-mass"]), "J_merzalov": _f(hand.J_fly["merzalov"]),
            "J_exact": _f(hand.J_fly["exact"]), "J": _f(hand.J_fly[hand.method]),
            "M_constant": _f(hand.work.M_constant), "J_const": _f(hand.J_const),
            "J_n": _f(hand.J_n[hand.method]),
            "err_J": _f(_rel(hand.J_fly[hand.method], J_ref)),
            "err_J_n": _f(_rel(hand.J_n[hand.method], ref.J_n[ref.method])),
            "err_M_constant": _f(_rel(hand.work.M_constant, ref.work.M_constant)),
            "delta_true": _f(fw.achieved_delta(ref.work.dT, ref.J_var,
                                               ref.J_const + max(hand.J_fly[hand.method], 0.0),
                                               omega_m)),
            "accurate": {"resolution": int(ref_resolution), "J": _f(J_ref),
                         "J_n": _f(ref.J_n[ref.method]), "M_constant": _f(ref.work.M_constant)}}


def accuracy_table(sampler: Sampler, section, omega_m: float, cycle: float = 360.0,
                   switch_q=(), resolutions=ACCURACY_RESOLUTIONS, *, known: dict | None = None
                   ) -> dict:
    """J (primary method) and omega_max/min against the resolution, with the relative error
    to the converged value (the finest resolution) and the time taken.

    Per row: J and its error; omega_max/min of the motion with the *converged* flywheel
    computed on that grid (how well the grid resolves the speed extremes) and their errors;
    delta_true = the fluctuation the row's J really gives (evaluated on the finest grid);
    time_ms.  `hand`: the 12-position (every 30 deg) trapezoid without inserted jump
    points, i.e. the course's hand calculation, beside the converged result.
    known: {resolution: CycleResult} already computed (reused, its time not measured)."""
    known = dict(known or {})
    res_list = sorted(set(int(r) for r in resolutions))
    cycles: dict[int, CycleResult] = {}
    times: dict[int, float | None] = {}
    for r in res_list:
        if r in known:
            cycles[r], times[r] = known[r], None
            continue
        t0 = time.perf_counter()
        cycles[r] = _run_grid(sampler, section, omega_m, cycle, r, switch_q)[0]
        times[r] = (time.perf_counter() - t0) * 1e3
    ref_r = res_list[-1]
    ref = cycles[ref_r]
    J_ref = ref.J_fly[ref.method]
    Jn_ref = ref.J_const + max(J_ref, 0.0)
    rows = []
    for r in res_list:
        c = cycles[r]
        mo = fw.steady_motion(c.work.dT, c.J_var, Jn_ref, omega_m)
        Jr = c.J_fly[c.method]
        d_true = fw.achieved_delta(ref.work.dT, ref.J_var, ref.J_const + max(Jr, 0.0), omega_m)
        rows.append({"resolution": r, "nodes": int(c.q.size), "J": _f(Jr),
                     "err_J": _f(_rel(Jr, J_ref)),
                     "omega_max": _f(mo.omega_max), "omega_min": _f(mo.omega_min),
                     "err_omega_max": _f(_rel(mo.omega_max, ref.motion.omega_max)),
                     "err_omega_min": _f(_rel(mo.omega_min, ref.motion.omega_min)),
                     "delta_true": _f(d_true), "time_ms": _f(times[r]),
                     "reference": r == ref_r})
    hd = hand_row(sampler, section, omega_m, cycle, switch_q, ref, ref_r)
    return {"method": ref.method, "reference_resolution": ref_r, "rows": rows, "hand": hd}


def analyze_sampler(sampler: Sampler, section, omega_m: float, *, cycle: float = 360.0,
                    switch_q=(), phi0: float = 0.0, sign: float = 1.0,
                    accuracy: bool = True) -> DynamicsResult:
    """The dynamics stage over a sampler (see `Sampler`)."""
    if not (omega_m > 0 and math.isfinite(omega_m)):
        raise StageError(STAGE, f"the drive speed must be positive (got {omega_m})")
    if cycle not in (360, 720, 360.0, 720.0):
        raise StageError(STAGE, f"the cycle must be 360 or 720 deg (got {cycle})")
    resolution = int(section.resolution)
    c, q_deg, side = _run_grid(sampler, section, omega_m, cycle, resolution, switch_q)
    shape = section.shape
    shp = {"type": shape.type, "density": float(shape.density), "width_ratio": float(shape.width_ratio)}
    sz = fw.size(c.J, shp["type"], shp["density"], shp["width_ratio"], c.motion.omega_max)
    warnings = list(c.warnings) + list(sz.warnings)
    hand = hand_row(sampler, section, omega_m, cycle, switch_q, c, resolution)
    acc = None
    if not accuracy and resolution < CHECK_BELOW:
        # a coarse grid: its error estimated against twice the positions (cheap here)
        c2 = _run_grid(sampler, section, omega_m, cycle, 2 * resolution, switch_q)[0]
        est = _rel(c.J_n[c.method], c2.J_n[c2.method])
        if est is not None and est > TARGET_REL:
            warnings.append(Message("flywheel.coarse_resolution", resolution=resolution, rel=est,
                                    doubled=2 * resolution, target=TARGET_REL))
    if accuracy:
        acc = accuracy_table(sampler, section, omega_m, cycle, switch_q,
                             resolutions=tuple(sorted(set(ACCURACY_RESOLUTIONS) | {resolution})),
                             known={resolution: c})
        err = next(r for r in acc["rows"] if r["resolution"] == resolution)["err_J"]
        acc["resolution"] = resolution
        acc["err_J"] = _f(err)
        if err is not None and err > 0.01 and resolution < acc["reference_resolution"]:
            warnings.append(Message("flywheel.resolution_error", resolution=resolution, percent=100 * err))
    return DynamicsResult(cycle=c, cycle_deg=float(cycle), resolution=resolution, phi0=float(phi0),
                          sign=float(sign), constant=section.constant, shape=shp, size=sz,
                          accuracy=acc, warnings=warnings, q_deg=q_deg, side=side, sampler=sampler,
                          hand=hand, quadrature_points=int(getattr(section, "quadrature", GAUSS_DEFAULT)))


def mechanism_sampler(mech, kin_fn, loads_fn, *, phi0: float, sign: float) -> Sampler:
    """Sampler over a mechanism: kin_fn(phi_deg array) -> KinematicsResult at the absolute
    crank angles phi0 + sign*(q + side*EPS_DEG) (unwrapped: they run monotonically over
    the cycle and may leave [0, 360), beyond 360 deg for a 720-deg cycle), and
    loads_fn(kin) -> Loads (external loads, no inertia)."""
    def sampler(q_deg, side):
        q_deg = np.asarray(q_deg, float)
        phi = phi0 + sign * (q_deg + np.asarray(side, float) * EPS_DEG)
        kin = kin_fn(phi)
        loads = loads_fn(kin)
        return sample_mech(mech, kin, loads, sign)
    return sampler


def analyze(mech, kin_fn, loads_fn, section, drive, *, phi0: float = 0.0, switch_angles=(),
            accuracy: bool = True) -> DynamicsResult:
    """The dynamics stage of a linkage.

    kin_fn(phi_deg: ndarray) -> KinematicsResult (analogues d1, a1, d2, a2 used);
    loads_fn(kin) -> Loads (without inertia loads); section: FlywheelSection;
    drive: DriveSection (speed, direction, cycle); phi0: crank angle of position 0 (deg);
    switch_angles: absolute crank angles (deg) where a load jumps (inserted into the grid;
    for a 720-deg cycle they are inserted in both turns)."""
    sign = 1.0 if getattr(drive, "direction", "ccw") == "ccw" else -1.0
    cycle = float(getattr(drive, "cycle", 360) or 360)
    sw = []
    for s in switch_angles or ():
        qs = (sign * (float(s) - phi0)) % 360.0
        sw.append(qs)
        if cycle == 720:
            sw.append(qs + 360.0)
    sampler = mechanism_sampler(mech, kin_fn, loads_fn, phi0=phi0, sign=sign)
    return analyze_sampler(sampler, section, float(drive.speed), cycle=cycle, switch_q=sw,
                           phi0=phi0, sign=sign, accuracy=accuracy)


class _WithCycle:
    """The positions seen by the loads, carrying the drive's cycle (for phi-diagrams over
    720 deg) when the PositionsResult has none."""

    def __init__(self, positions, cycle: float):
        self._p = positions
        self.cycle = cycle

    def __getattr__(self, name):
        return getattr(self._p, name)


def analyze_task(mech, task, positions, *, accuracy: bool = True) -> DynamicsResult:
    """The pipeline's call: kinematics.solve and loads.evaluate(inertia=False) over the
    dynamics grid; inserted into the grid: the switch angles of loads.switch_angles and
    both extreme positions of the output (where stroke loads start and stop) and the
    kinks of the load diagrams (so that every grid interval is smooth and the Gauss rule
    keeps its order)."""
    from .. import kinematics, loads as loads_mod
    omega1 = task.drive.omega1
    cycle = float(task.drive.cycle)
    pos_l = positions
    if getattr(positions, "cycle", None) in (None, 0):
        pos_l = _WithCycle(positions, cycle)

    def kin_fn(phi):
        return kinematics.solve(mech, np.asarray(phi, float), omega1)

    def loads_fn(kin):
        return loads_mod.evaluate(mech, task.loads, kin, pos_l, inertia=False)

    sw = list(loads_mod.switch_angles(mech, task.loads, pos_l, kinks=True))
    sw += [float(x) for x in (getattr(positions, "extreme", None) or [])]
    res = analyze(mech, kin_fn, loads_fn, task.flywheel, task.drive, phi0=float(positions.phi0),
                  switch_angles=sw, accuracy=accuracy)
    # read crank angles in motion_at as loads.evaluate reads them for these positions
    res.map_cycle = float(getattr(positions, "cycle", None) or 360.0)
    return res
