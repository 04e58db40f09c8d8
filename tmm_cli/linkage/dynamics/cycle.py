"""The flywheel calculation over one cycle: the grid of crank angles, the sampler
that evaluates the reduced quantities there, and the solution on the grid
(docs/methods.md §4).

The grid: ``resolution`` equal steps over the cycle (360 or 720 deg of crank rotation
from position 0 in the direction of motion) plus every crank angle where a load
jumps, inserted twice (left and right limits: the loads are evaluated EPS_DEG
before and after it, the node keeps the exact angle), so the trapezoid of the works
is exact for piecewise-linear loads and the extrema at the jumps are on the grid.
The first node (position 0) carries the right limit, the last (one cycle later) the
left limit.
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Callable

import numpy as np

from ...errors import StageError
from ...lazy import unique
from ...messages import Message
from . import flywheel as fw
from .reduce import Sample, sample as sample_mech

STAGE = "dynamics"
EPS_DEG = 1e-5   # one-sided evaluation offset at a jump, deg (coarser than the loads' 1e-9 snapping)
FLYWHEEL_METHODS = ("energy-mass", "merzalov", "exact")
# the coefficients of speed fluctuation machines are given (Artobolevsky's table: pumps 1/5-1/30,
# machine tools 1/20-1/50, compressors 1/50-1/100, generators 1/100-1/300): one outside is told
DELTA_USUAL = (1 / 300, 1 / 5)
GAUSS_DEFAULT = 2   # Gauss-Legendre points per grid interval for the works (order 4)

Sampler = Callable[[np.ndarray, np.ndarray], Sample]
"""sampler(q_deg, side) -> Sample: reduced quantities at the cycle angles q_deg (deg of
crank rotation from position 0 along the motion), each evaluated at q + side*EPS_DEG
(side -1: left limit, +1: right limit, 0: exactly)."""


# ------------------------------------------------------------------ grid
def grid(resolution: int, cycle: float, switch_q: tuple | list = (), insert: bool = True
         ) -> tuple[np.ndarray, np.ndarray]:
    """The nodes of the cycle.

    Parameters
    ----------
    resolution : int
        Equal steps over the cycle.
    cycle : float
        The cycle, deg.
    switch_q : sequence of float
        The jump angles, deg from position 0 along the motion.
    insert : bool
        True: the jump angles inserted twice each (the two sides of a jump); False: the plain
        equal steps, every node evaluated exactly (what a hand calculation does).

    Returns
    -------
    q_deg : numpy.ndarray
        The nodes, deg, non-decreasing.
    side : numpy.ndarray
        The side evaluated: -1 before and +1 after a jump at its two nodes, +1 at the
        cycle's start, -1 at its end, 0 elsewhere (all 0 with ``insert`` False).
    """
    n = int(resolution)
    if n < 2:
        raise StageError(STAGE, Message("flywheel.fail.resolution", value=resolution))
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
    return unique(np.concatenate(out))


def solve_cycle(q: np.ndarray, M_given: np.ndarray, J_links: dict[str, np.ndarray] | np.ndarray,
                *, omega_m: float, delta: float, constant: str = "driving",
                method: str = "energy-mass", J_extra: float = 0.0,
                dJ_links: dict[str, np.ndarray | None] | None = None,
                M_by_kind: dict[str, np.ndarray] | None = None,
                const_tol: float = 1e-9, increments: np.ndarray | None = None,
                refine: bool = True, polish: Callable | None = None) -> CycleResult:
    """The whole flywheel calculation on arrays.

    Parameters
    ----------
    q : numpy.ndarray
        Nodes from 0 to the cycle, rad, non-decreasing (duplicates at jumps).
    M_given : numpy.ndarray
        The reduced moment of the given loads along the motion, N*m (N,).
    J_links : dict or numpy.ndarray
        The reduced inertia per link (dict of (N,)) or one (N,) array (one link named
        ``mechanism``), kg*m^2.
    omega_m : float
        The crank's mean speed, rad/s.
    delta : float
        The allowed coefficient of speed fluctuation.
    constant : str
        The constant moment's kind: ``driving`` or ``resistance``.
    method : str
        ``energy-mass``, ``merzalov`` or ``exact``.
    J_extra : float
        A constant reduced inertia given in the task (``flywheel.reduced_J``), kg*m^2.
    dJ_links : dict or None
        d/dq of each link's reduced inertia, kg*m^2/rad: required for every link whose
        inertia varies (the exact derivative, from the second transmission functions;
        finite differences are never used), not needed for a constant one.
    M_by_kind : dict or None
        The reduced moments by load kind, N*m.
    const_tol : float
        A link whose reduced inertia varies by less than this fraction of its maximum goes to
        J_const (crank, rotor, gears), the rest to J_var.
    increments : numpy.ndarray or None
        The integrals of M_given over every interval of q, J (None: the trapezoid).
    refine : bool
        True: locate the extrema of the energy functions between the nodes (critical points of
        their cubic Hermite interpolants with the exact slopes M_red - J_var' omega^2/2) and
        include them in every method's maxima and minima; False: the extrema at the nodes
        (the hand calculation).
    polish : callable or None
        polish(points, work, const_links) -> (dT, J_var) evaluated exactly at the located
        points (None: the Hermite interpolants).

    Returns
    -------
    CycleResult
        The works (J), the energy functions, J and J_n of the flywheel (kg*m^2), the constant
        moment (N*m) and the motion (rad/s) along q.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: the energy-mass (Wittenbauer) method,
    Merzalov's method, the exact periodic solution; docs/methods.md §4.
    """
    if method not in FLYWHEEL_METHODS:
        raise StageError(STAGE, Message("flywheel.fail.method", method=str(method)))
    q = np.asarray(q, float)
    if isinstance(J_links, np.ndarray) or not isinstance(J_links, dict):
        J_links = {"mechanism": np.broadcast_to(np.asarray(J_links, float), q.shape).copy()}
    warnings: list[str] = []
    if not DELTA_USUAL[0] <= delta <= DELTA_USUAL[1]:     # sized all the same, and said
        warnings.append(Message("flywheel.delta_unusual", delta=delta, inverse=1 / delta,
                                lo=1 / DELTA_USUAL[1], hi=1 / DELTA_USUAL[0]))
    work = fw.cycle_work(q, M_given, constant, increments)
    n = q.size
    J_const = float(J_extra)
    J_var = np.zeros(n)
    dJ_var = np.zeros(n)
    const_links: list[str] = []
    for name, arr in J_links.items():
        arr = np.broadcast_to(np.asarray(arr, float), (n,))
        if not np.all(np.isfinite(arr)):
            raise StageError(STAGE, Message("flywheel.fail.J_not_finite", link=name))
        if float(np.min(arr)) < 0:
            raise StageError(STAGE, Message("flywheel.fail.J_negative", link=name))
        top = float(np.max(arr))
        if float(np.ptp(arr)) <= const_tol * top:
            const_links.append(name)
            J_const += float(np.mean(arr))
            continue
        J_var = J_var + arr
        d = None if dJ_links is None else dJ_links.get(name)
        if d is None:
            raise ValueError(f"solve_cycle: the reduced inertia of {name!r} varies along the cycle but "
                             "dJ_links gives no derivative of it (dJ/dq is taken exactly, never by "
                             "finite differences)")
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
        raise StageError(STAGE, Message("flywheel.fail.eps_not_finite"))

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


# ------------------------------------------------------------------ the grid through a sampler
def _take(s: Sample, sl) -> Sample:
    """The Sample at the angles `sl` (a slice or an index array) of s."""
    def cut(a):
        return None if a is None else np.asarray(a)[sl]

    return Sample(M_by_kind={k: cut(v) for k, v in s.M_by_kind.items()}, M_given=cut(s.M_given),
                  J_links={k: cut(v) for k, v in s.J_links.items()},
                  dJ_links={k: cut(v) for k, v in (s.dJ_links or {}).items()},
                  J_links_total=cut(s.J_links_total), dJ_total=cut(s.dJ_total))


def _split(s: Sample, n: int) -> tuple[Sample, Sample]:
    """A Sample over n + m angles as (the first n, the other m)."""
    return _take(s, slice(0, n)), _take(s, slice(n, None))


def _concat(a: Sample, b: Sample) -> Sample:
    """The Samples a and b over their angles one after the other."""
    def cat(x, y):
        return None if x is None or y is None else np.concatenate([np.asarray(x), np.asarray(y)])

    return Sample(M_by_kind={k: cat(v, b.M_by_kind.get(k)) for k, v in a.M_by_kind.items()},
                  M_given=cat(a.M_given, b.M_given),
                  J_links={k: cat(v, b.J_links.get(k)) for k, v in a.J_links.items()},
                  dJ_links={k: cat(v, (b.dJ_links or {}).get(k)) for k, v in (a.dJ_links or {}).items()},
                  J_links_total=cat(a.J_links_total, b.J_links_total), dJ_total=cat(a.dJ_total, b.dJ_total))


class _Reuse:
    """A sampler that keeps its first sample, taken together with the angles `extra` (the
    hand method's positions): a later call is answered from it at the angles it holds and
    by the sampler at the others (one kinematics call fewer; the same values)."""

    def __init__(self, sampler: Sampler, extra=None):
        self.sampler = sampler
        self.index: dict | None = None
        self.sample: Sample | None = None
        self.extra = extra       # (q, side) sampled with the first call, kept for later ones

    def __call__(self, q_deg, side):
        q = np.asarray(q_deg, float)
        sd = np.asarray(side, float)
        if self.index is None and self.extra is not None:
            n = q.size
            (qx, sx), self.extra = self.extra, None
            self(np.concatenate([q, qx]), np.concatenate([sd, sx]))
            return _take(self.sample, slice(0, n))
        if self.index is not None:
            idx = [self.index.get((a, b)) for a, b in zip(q.tolist(), sd.tolist())]
            miss = np.array([i is None for i in idx])
            if miss.all():
                return self.sampler(q, sd)
            if not miss.any():
                return _take(self.sample, np.asarray(idx, int))
            # the sample kept, then the angles not among them; put back in the asked order
            known = np.array([-1 if i is None else i for i in idx])
            both = _concat(_take(self.sample, known[~miss]), self.sampler(q[miss], sd[miss]))
            order = np.empty(q.size, int)
            order[np.flatnonzero(~miss)] = np.arange(int((~miss).sum()))
            order[np.flatnonzero(miss)] = int((~miss).sum()) + np.arange(int(miss.sum()))
            return _take(both, order)
        out = self.sampler(q, sd)
        self.index = {key: i for i, key in enumerate(zip(q.tolist(), sd.tolist()))}
        self.sample = out
        return out


def run_grid(sampler: Sampler, section, omega_m: float, cycle: float, resolution: int,
              switch_q, insert: bool = True, gauss: int | None = None
              ) -> tuple[CycleResult, np.ndarray, np.ndarray]:
    """The flywheel on a grid.

    Parameters
    ----------
    sampler : Sampler
        The reduced moment and inertia.
    section : FlywheelSection
        The task's ``flywheel`` section (delta, the constant moment's kind, the method, the
        resolution, the quadrature).
    omega_m : float
        The crank's mean speed, rad/s.
    cycle : float
        The cycle, deg.
    resolution : int
        Equal steps over the cycle.
    switch_q : sequence of float
        The loads' jumps, deg from position 0.
    insert : bool
        True: the jumps inserted as nodes (False implies ``gauss`` = 0).
    gauss : int or None
        Gauss-Legendre points per interval for the works (None: the section's
        ``quadrature``; 0: the trapezoid on the nodes and the extrema at the nodes, as by
        hand).

    Returns
    -------
    tuple
        (CycleResult, the nodes q in deg, the nodes' sides).
    """
    q_deg, side = grid(resolution, cycle, switch_q, insert)
    n_g = int(section.quadrature) if gauss is None else int(gauss)
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
                      method=section.method, J_extra=float(section.reduced_J),
                      dJ_links=s.dJ_links, M_by_kind=s.M_by_kind, increments=inc,
                      refine=n_g > 0, polish=polish if n_g > 0 else None)
    return res, q_deg, side


def mechanism_sampler(mech, kin_fn, loads_fn, *, phi0: float, sign: float) -> Sampler:
    """A sampler of the reduced quantities over a mechanism.

    Parameters
    ----------
    mech : Mechanism
        The mechanism.
    kin_fn : callable
        kin_fn(phi_deg array) -> KinematicsResult at the absolute crank angles
        phi0 + sign (q + side EPS_DEG) (unwrapped: monotonic over the cycle, beyond 360 deg
        for a 720-deg cycle).
    loads_fn : callable
        loads_fn(kin) -> Loads (the external loads, no inertia).
    phi0 : float
        The crank angle of position 0, deg.
    sign : float
        +1 for a ccw crank, -1 for cw.

    Returns
    -------
    Sampler
        The reduced moment (N*m) and inertia (kg*m^2) at cycle angles q (deg).
    """
    def sampler(q_deg, side):
        q_deg = np.asarray(q_deg, float)
        phi = phi0 + sign * (q_deg + np.asarray(side, float) * EPS_DEG)
        kin = kin_fn(phi)
        loads = loads_fn(kin)
        return sample_mech(mech, kin, loads, sign)
    return sampler


def switch_q(switch_angles, phi0: float, sign: float, cycle: float) -> list[float]:
    """The loads' jumps as cycle angles.

    Parameters
    ----------
    switch_angles : sequence of float
        Absolute crank angles where a load jumps, deg.
    phi0 : float
        The crank angle of position 0, deg.
    sign : float
        +1 for a ccw crank, -1 for cw.
    cycle : float
        The cycle, deg.

    Returns
    -------
    list of float
        The angles q, deg from position 0 along the motion (for a 720-deg cycle in both
        turns).
    """
    sw = []
    for s in switch_angles or ():
        qs = (sign * (float(s) - phi0)) % 360.0
        sw.append(qs)
        if cycle == 720:
            sw.append(qs + 360.0)
    return sw
