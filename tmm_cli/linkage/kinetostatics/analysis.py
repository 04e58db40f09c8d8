"""Kinetostatic analysis: ``analyze`` (the stage: a linkage at its positions),
``equilibrium`` (per position, on given kinematics and loads) and ``find_singular``
(over a turn).

Sign conventions (stated in the report): R_ij is the force of link i on link j, keyed
``R<i><j>`` with i < j (R_ji = -R_ij); moments ccw positive; the balancing moment M_b
is the couple the drive applies to the balance link to keep the prescribed motion;
P_b = M_b / l is the balancing force at the end of the balance link's arm l (the crank:
l = l_OA at the crank pin), perpendicular to it; on a slider the balancing force acts
along its guide (positive along the guide direction).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ...errors import StageError, field_error
from ...messages import Message
from .. import loads as loads_mod
from ..loads import AppliedCouple, Loads
from .entries import lazy_entries
from .equations import Geometry, geometry, load_vector, scaled_det
from .solve import (balance_lever, balance_rate, condition_numbers, friction_loads, group_by_group,
                    lever_moments, matrix_method, point_velocities, powers, unit_balance_q)

NEAR_DEG = 1.0
DETAIL_MAX = 400        # positions up to which to_dict lists every applied load


def balance_index(mech, section) -> int:
    """The index of the balance link.

    Parameters
    ----------
    mech : Mechanism
        The mechanism.
    section : KinetostaticsSection or None
        The task's ``kinetostatics`` section (its ``balance``, a name the task model checked).

    Returns
    -------
    int
        The balance link's index (1..n): the section's, or the drive link's (also when
        ``section`` is None).
    """
    name = section.balance if section is not None else None
    return mech.drive if name is None else mech.link(name).index


@dataclass
class KinetostaticsResult:
    """The force analysis at each position: the reactions and the balancing moment three ways."""

    index: list[int]
    phi: np.ndarray
    balance: str
    balance_kind: str                      # 'moment' | 'force'
    arm: float | None
    M_b: np.ndarray                        # group-by-group balancing moment (or force)
    M_matrix: np.ndarray
    M_zhukovsky: np.ndarray
    M_virtual: np.ndarray
    reactions: np.ndarray                  # (N, 2p) group by group
    reactions_matrix: np.ndarray
    ok: np.ndarray                         # (N,) not singular to working precision
    near: np.ndarray                       # (N,) within 1 deg of a singular angle
    singular: list[float]
    mech: object = None
    geo: Geometry | None = None
    loads: Loads | None = None
    efficiency: np.ndarray | None = None
    friction_power: np.ndarray | None = None
    friction_pairs: np.ndarray | None = None
    driving_power: np.ndarray | None = None
    groups: list[list[int]] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    # link index -> (N,) the positions where the link's velocities have no limit by continuity
    # (its omega or a point's velocity null in the kinematics, at a change point): the
    # velocities of the loads on it are null there, not the singular solve's numbers
    undefined_velocity: dict[int, np.ndarray] = field(default_factory=dict)

    @property
    def cond(self) -> np.ndarray:
        """The 2-norm condition number of the matrix method's scaled system per position
        (computed when asked: the stage only needs whether it is below COND_MAX)."""
        return condition_numbers(self.mech, self.geo, self.mech.link(self.balance).index)

    # ------------------------------------------------------------------
    def discrepancy(self) -> np.ndarray:
        tiny = 1e-9 * self._scale()
        return np.abs(self.M_zhukovsky - self.M_b) / np.maximum(np.abs(self.M_b), tiny)

    def _scale(self) -> np.ndarray:
        """A moment scale per position: sum |F| Lc + sum |M| of the loads."""
        s = np.zeros(len(self.phi))
        Lc = self.geo.Lc if self.geo is not None else 1.0
        if self.loads is not None:
            for f in self.loads.forces:
                s += np.linalg.norm(f.F, axis=1) * Lc
            for c in self.loads.couples:
                s += np.abs(c.M)
        if self.balance_kind == "force":
            s = s / Lc
        return np.maximum(s, 1e-300)

    def to_dict(self, detail: bool | None = None) -> dict:
        """The results.json sections of the stage: ``kinetostatics`` (one entry per
        position: a :class:`tmm_cli.results.LazyEntries`, made from this result's arrays
        when read), ``kinetostatics_info`` (balance link, conventions, groups, joints, the
        load diagrams) and ``singular`` (crank angles, deg); the warnings are
        ``self.warnings``. ``detail``: include per position the applied loads with their
        points and velocities (``loads``, ``couples``: the report's force plans and
        Zhukovsky lever); default: when there are at most 400 positions."""
        if detail is None:
            detail = len(self.phi) <= DETAIL_MAX
        mech = self.mech
        names = self._link_names()
        jkeys = [f"R{j.a}{j.b}" for j in mech.joints]
        return {"kinetostatics": lazy_entries(self, detail), "kinetostatics_info": {
            "balance": self.balance,
            "balance_kind": self.balance_kind,
            "arm": self.arm,
            "convention": "R_ij = force of link i on link j (i < j), R_ji = -R_ij; moments ccw positive",
            "groups": [[names[l] for l in g] for g in self.groups],
            "joints": [{"key": jkeys[k], "kind": j.kind, "a": j.a, "b": j.b, "point": j.point,
                        "slider": j.slider} for k, j in enumerate(mech.joints)],
            "load_diagrams": [{"name": d["name"], "link": d["link"], "kind": d["kind"], "type": d["type"],
                               "stroke": d["stroke"], "abscissa": d.get("abscissa"), "curve": d.get("curve")}
                              for d in self.loads.info],
        }, "singular": [float(a) for a in self.singular]}

    def _link_names(self) -> dict[int, str]:
        names = {lk.index: lk.name for lk in self.mech.links}
        names[0] = "ground"
        return names


def _with_inertia(mech, kin, loads: Loads | None, inertia: bool, crank_inertia: float) -> Loads:
    n = len(np.atleast_1d(kin.phi))
    if loads is None:
        loads = Loads(phi=np.atleast_1d(np.asarray(kin.phi, float)))
    has = any(f.kind == "inertia" for f in loads.forces) or any(c.kind == "inertia" for c in loads.couples)
    forces = [f for f in loads.forces if inertia or f.kind != "inertia"]
    couples = [c for c in loads.couples if inertia or c.kind != "inertia"]
    if inertia and not has:
        extra = loads_mod.link_loads(mech, kin, gravity=False, inertia=True)
        forces += extra.forces
        couples += extra.couples
    if crank_inertia:
        e1 = np.broadcast_to(np.asarray(kin.eps1, float), (n,)).astype(float)
        couples.append(AppliedCouple(mech.drive, "Mfly", -float(crank_inertia) * e1, "inertia"))
    return Loads(loads.phi, forces, couples, loads.info)


def select_rows(spec, positions) -> list[int]:
    """The rows of the positions the kinetostatics section names.

    Parameters
    ----------
    spec : str or list of int
        ``kinetostatics.positions``: ``all`` or position numbers.
    positions : PositionsResult
        The reported positions.

    Returns
    -------
    list of int
        Row numbers into ``positions.phi``.

    Raises
    ------
    TaskError
        A position the cycle does not have.
    """
    idx = list(positions.index)
    if spec == "all":
        return list(range(len(idx)))
    rows = []
    for k, i in enumerate(spec):
        if i not in idx:
            raise field_error(f"kinetostatics.positions[{k}]",
                              f"position {i} does not exist (positions are {idx[0]}..{idx[-1]})")
        rows.append(idx.index(i))
    return rows


def analyze(linkage, section, kin, *, motion=None) -> KinetostaticsResult:
    """The kinetostatics stage: reactions in the pairs and the balancing moment (or force)
    at the positions ``section.positions``, by three methods.

    Parameters
    ----------
    linkage : Linkage
        The mechanism, its Assur groups, positions, loads and drive.
    section : KinetostaticsSection
        The task's ``kinetostatics``: ``positions``, ``inertia``, ``balance``,
        ``friction`` (pin radius in m, coefficients), ``motion``.
    kin : KinematicsResult
        The kinematics at the reported positions (the kinematics stage, omega1 constant).
    motion : DynamicsResult or None
        With ``motion: true``: the steady motion with the flywheel, omega1(phi) (rad/s)
        and epsilon1(phi) (rad/s^2); the flywheel and ``flywheel.reduced_J`` (kg*m^2) add
        the couple -(J_fly + J_extra) epsilon1 on the crank.

    Returns
    -------
    KinetostaticsResult
        Per position: reactions R_ij (N), the balancing moment (N*m) or force (N) group by
        group, by Zhukovsky's lever, by virtual power and by the matrix of all equations;
        friction losses and the instantaneous efficiency; the singular crank angles (deg).

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: force analysis by Assur groups
    (d'Alembert's principle), Zhukovsky's lever; docs/methods.md §3.
    """
    from ..kinematics import solve
    rows = select_rows(section.positions, linkage.positions)
    kin_k, crank_J = kin, 0.0
    if section.motion is True:
        phi = np.asarray(linkage.positions.phi, dtype=float)
        kin_k = solve(linkage.mechanism, phi, motion.omega_of(phi), motion.epsilon_of(phi))
        crank_J = motion.crank_inertia
    lds = loads_mod.evaluate(linkage, kin_k, inertia=section.inertia)
    singular = None
    if linkage.positions.span is not None:      # over a crank range (a function generator): there only
        mech = linkage.mechanism
        singular = find_singular(mech, linkage.structure, mech.link(balance_index(mech, section)).name,
                                 over=(float(linkage.positions.phi0), float(linkage.positions.span)))
    return equilibrium(linkage.mechanism, linkage.structure, kin_k, lds, section, indices=rows,
                       crank_inertia=crank_J, singular=singular)


def equilibrium(mech, structure, kin, loads, section, *, indices=None, crank_inertia: float = 0.0,
                solver=None, singular: list[float] | None = None) -> KinetostaticsResult:
    """Kinetostatic analysis on given kinematics and loads.

    Parameters
    ----------
    mech : Mechanism
        The mechanism.
    structure : StructureResult
        Its Assur groups.
    kin : KinematicsResult
        The kinematics (it may carry arrays omega1, eps1 in rad/s, rad/s^2).
    loads : Loads
        The loads at the positions of ``kin`` (N, N*m); inertia loads are added here when
        ``section.inertia`` and absent, dropped when not wanted.
    section : KinetostaticsSection
        The task's ``kinetostatics`` section (inertia, balance link, friction).
    indices : sequence of int or None
        The rows of ``kin`` (None: all).
    crank_inertia : float
        An extra constant moment of inertia on the drive link (the flywheel), kg*m^2, whose
        couple -J eps1 is added.
    solver : callable or None
        The kinematics function for the singular positions (None:
        :func:`tmm_cli.linkage.kinematics.solve`).
    singular : list of float or None
        The singular crank angles, deg, when known (skips the search).

    Returns
    -------
    KinetostaticsResult
        The reactions in the pairs (N), the balancing moment (N*m) or force (N), Zhukovsky's
        lever check, the powers (W) and the friction losses.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: force analysis by Assur groups
    (d'Alembert's principle), Zhukovsky's lever; docs/methods.md §3.
    """
    with np.errstate(all="ignore"):
        return _analyze(mech, structure, kin, loads, section, indices=indices, crank_inertia=crank_inertia,
                        solver=solver, singular=singular)


def _analyze(mech, structure, kin, loads, section, *, indices=None, crank_inertia: float = 0.0,
             solver=None, singular: list[float] | None = None) -> KinetostaticsResult:
    """See :func:`equilibrium`."""
    phi_all = np.atleast_1d(np.asarray(kin.phi, float))
    rows = np.arange(len(phi_all)) if indices is None else np.asarray(list(indices), int)
    b = balance_index(mech, section)
    blk = mech.link(b)
    inertia = True if section is None else bool(section.inertia)
    lds = _with_inertia(mech, kin, loads, inertia, crank_inertia).select(rows)
    geo = geometry(mech, kin, rows)
    N = geo.n_pos
    q = load_vector(mech, geo, lds)
    qU = unit_balance_q(mech, geo, b) if b != mech.drive else None

    def solve_groups(qq):
        xL, M1L = group_by_group(mech, structure, geo, qq)
        if qU is None:
            return xL, M1L, np.ones(N)
        xU, M1U = group_by_group(mech, structure, geo, qU)
        with np.errstate(divide="ignore", invalid="ignore"):
            Mb = -M1L / M1U
        return xL + Mb[:, None] * xU, Mb, M1U

    fr = section.friction if section is not None else None
    loss = None
    locked = np.zeros(N, bool)
    if fr is not None and (fr.f_pin > 0 or fr.f_slide > 0):
        x, Mb, M1U = solve_groups(q)
        finite0 = np.all(np.isfinite(x), axis=1)
        row_change = np.zeros(N)
        for _ in range(200):
            ff, fc, _ = friction_loads(mech, geo, x, fr.f_pin, fr.pin_radius, fr.f_slide, losses=False)
            qf = q + load_vector(mech, geo, Loads(lds.phi, ff, fc))
            x_new, Mb, M1U = solve_groups(qf)
            row_change = np.max(np.abs(x_new - x), axis=1)
            change = np.nanmax(row_change) if np.any(np.isfinite(row_change)) else 0.0
            x = x_new
            if not change > 1e-12 * max(float(np.nanmax(np.abs(x))) if np.any(np.isfinite(x)) else 1.0, 1e-300):
                break
        # self-locking: where the fixed-point iteration of the friction loads diverges (the
        # friction the reactions cause grows faster than the reactions), no finite solution
        # exists; those positions are flagged and left without numbers, never filled with
        # the 1e300-sized iterates (Artobolevsky: self-braking, eta <= 0)
        row_scale = np.max(np.abs(np.where(np.isfinite(x), x, 0.0)), axis=1)
        locked = finite0 & ~(row_change <= 1e-8 * np.maximum(row_scale, 1e-300))
        if np.any(locked):
            x[locked] = np.nan
        ff, fc, loss = friction_loads(mech, geo, x, fr.f_pin, fr.pin_radius, fr.f_slide)
        lds = Loads(lds.phi, lds.forces + ff, lds.couples + fc, lds.info)
        q = load_vector(mech, geo, lds)
    x, Mb, M1U = solve_groups(q)
    geo.__dict__.pop("_group_plan", None)      # the groups' inverses: not needed past here
    geo.__dict__.pop("_relative_motion", None)
    geo.__dict__.pop("_motion_signs", None)
    if np.any(locked):
        x[locked] = np.nan
        Mb = np.where(locked, np.nan, Mb)
    xm, Mm, well, _ = matrix_method(mech, geo, q, b, with_det=False)
    vel, arms = point_velocities(geo, lds), {}       # shared by the lever and the powers
    lever = lever_moments(mech, geo, lds, vel, arms)
    blev = balance_lever(mech, geo, b, arms)
    P, each = powers(mech, geo, lds, vel)
    rate = balance_rate(mech, geo, b)
    Lc = geo.Lc
    unit = 1.0 if blk.kind != "slider" else Lc
    with np.errstate(divide="ignore", invalid="ignore"):
        Mzh = -lever / blev
        Mvp = -P / rate
    w1 = np.abs(geo.omega1)
    ok = well & np.isfinite(Mb) & np.all(np.isfinite(x), axis=1) \
        & (np.abs(M1U) > 1e-12 * unit) & (np.abs(rate) > 1e-12 * w1 * unit)
    raw = _untrusted_kinematics(kin, rows)
    untrusted = raw & ok & ~locked
    ok &= ~untrusted
    undefined_velocity: dict[int, np.ndarray] = {}
    if np.any(raw):                  # (also where the balance solve failed first: the same nulls)
        lds, undefined_velocity = _without_undefined(lds, mech, kin, rows)
    # singular crank angles of the balance link over one turn
    warnings: list[str] = []
    if singular is None:
        singular = find_singular(mech, structure, blk.name, solver=solver)
        if solver is None:  # a change point of the linkage is singular for every balance link
            from ..kinematics.changepoints import change_points, distance_deg
            from ..kinematics.solver import get_solver
            extra = [c.phi for c in change_points(get_solver(mech))]
            singular = sorted(list(singular) + [a for a in extra if distance_deg([a], singular)[0] > 1e-6])
    sing = np.asarray(singular, float)
    phi = phi_all[rows]
    if sing.size:
        d = np.abs((phi[:, None] % 360.0) - sing[None, :]) % 360.0
        d = np.minimum(d, 360.0 - d)
        near = np.min(d, axis=1) <= NEAR_DEG
    else:
        near = np.zeros(N, bool)
    for i in np.nonzero(locked)[0]:
        warnings.append(Message("kinetostatics.self_locking", position=int(rows[i]), phi=phi[i] % 360,
                                f_pin=fr.f_pin, f_slide=fr.f_slide, pin_radius=fr.pin_radius,
                                balancing="moment" if blk.kind != "slider" else "force"))
    for i in np.nonzero(~ok & ~locked)[0]:
        # a position whose kinematics has no limit is a change point for every balance link, said
        # so even where the balance link's equations failed before the kinematics was looked at
        warnings.append(Message("kinetostatics.no_kinematics" if raw[i] else "kinetostatics.singular_balance",
                                position=int(rows[i]), phi=phi[i] % 360,
                                link=blk.name, balancing="moment" if blk.kind != "slider" else "force"))
    eff = fpow = dpow = None
    if loss is not None:
        fpow = loss.sum(axis=1)
        # driving power: the sum of the positive powers of all loads except friction,
        # the balancing moment included (Artobolevsky: driving forces do positive work);
        # since their total equals the friction loss, 0 <= eta <= 1
        dpow = np.maximum(Mb * rate, 0.0)
        items = list(lds.forces) + list(lds.couples)
        for it, pw in zip(items, each):
            if it.kind != "friction":
                dpow = dpow + np.maximum(pw, 0.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            eff = np.where(dpow > 1e-12 * np.maximum(fpow, 1e-300), 1.0 - fpow / dpow, np.nan)
    arm = None
    if blk.kind != "slider":
        arm = float(blk.length) if blk.length else None
        if b == mech.drive:
            p0 = np.asarray(blk.local[mech.crank_pivot], float)
            p1 = np.asarray(blk.local[mech.crank_pin], float)
            arm = float(np.hypot(*(p1 - p0)))
    from .solve import _group_links
    return KinetostaticsResult(
        index=[int(r) for r in rows], phi=phi, balance=blk.name,
        balance_kind="force" if blk.kind == "slider" else "moment", arm=arm,
        M_b=Mb, M_matrix=Mm, M_zhukovsky=Mzh, M_virtual=Mvp, reactions=x, reactions_matrix=xm,
        ok=ok, near=near, singular=list(singular), mech=mech, geo=geo, loads=lds,
        efficiency=eff, friction_power=fpow, friction_pairs=loss, driving_power=dpow,
        groups=_group_links(mech, structure) + [[mech.drive]], warnings=warnings,
        undefined_velocity=undefined_velocity)


def _without_undefined(lds: Loads, mech, kin, rows: np.ndarray) -> tuple[Loads, dict[int, np.ndarray]]:
    """What the kinematics leaves without a limit by continuity (``kin.undefined``, null in the
    kinematics, at a change point), for the loads: ``lds`` with each link's inertia force NaN
    where its centre of mass's acceleration has none (``a:S<i>``) and its inertia couple NaN where
    its angular acceleration has none (the singular solve's accelerations had given the
    Grashof-limit four-bar's coupler 1.9e8 N), the other links' (the crank's) as computed; and,
    link index -> (N,) mask, where a link's velocities have none (its omega or a point's
    velocity), for the velocities of the loads on it."""
    import dataclasses
    und = kin.undefined or {}

    def mask(*keys):
        m = np.zeros(len(rows), bool)
        for key in keys:
            if key in und:
                m |= np.asarray(und[key], bool)[rows]
        return m if m.any() else None

    forces = []
    for f in lds.forces:
        m = mask(f"a:S{f.link}") if f.kind == "inertia" else None
        forces.append(f if m is None else dataclasses.replace(f, F=np.where(m[:, None], np.nan, f.F)))
    names = {lk.index: lk.name for lk in mech.links}
    couples = []
    for c in lds.couples:
        m = mask(f"epsilon:{names.get(c.link)}") if c.kind == "inertia" else None
        couples.append(c if m is None else dataclasses.replace(c, M=np.where(m, np.nan, c.M)))
    velocity = {lk.index: m for lk in mech.links
                if (m := mask(f"omega:{lk.name}", *(f"v:{p}" for p in lk.local))) is not None}
    return Loads(lds.phi, forces, couples, lds.info), velocity


def _untrusted_kinematics(kin, rows: np.ndarray) -> np.ndarray:
    """(len(rows),) the positions whose kinematics cannot carry a force analysis: a velocity or
    acceleration there has no limit by continuity (null in the kinematics), or a group's
    velocity equations -- whose transpose are its equilibrium equations -- are singular to
    working precision (``kin.singular``): the loads and reactions there are not finite."""
    bad = np.zeros(len(rows), bool)
    if kin.singular is not None:
        bad |= np.asarray(kin.singular, bool)[rows]
    for mask in (kin.undefined or {}).values():
        bad |= np.asarray(mask, bool)[rows]
    return bad


def analyze_at(linkage, section, phi_deg, *, motion=None, singular: list[float] | None = None
               ) -> KinetostaticsResult:
    """The kinetostatics stage at given crank angles.

    Parameters
    ----------
    linkage : Linkage
        The linkage context.
    section : KinetostaticsSection
        The task's ``kinetostatics`` section.
    phi_deg : array_like
        The crank angles, deg (instead of the reported positions).
    motion : DynamicsResult or None
        With ``motion: true``: the flywheel's omega1(phi), eps1(phi) and the crank's couple.
    singular : list of float or None
        The singular crank angles, deg, when known (skips the search).

    Returns
    -------
    KinetostaticsResult
        As :func:`equilibrium`: the same loads (stroke states from ``linkage.positions``) at
        these angles (the report's mechanism in motion uses it at 360 angles).

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: force analysis by Assur groups;
    docs/methods.md §3.
    """
    from ..kinematics import solve
    phi = np.atleast_1d(np.asarray(phi_deg, float))
    crank_J = 0.0
    if section.motion is True:
        kin = solve(linkage.mechanism, phi, motion.omega_of(phi), motion.epsilon_of(phi))
        crank_J = motion.crank_inertia
    else:
        kin = solve(linkage.mechanism, phi, linkage.drive.omega)
    lds = loads_mod.evaluate(linkage, kin, inertia=section.inertia)
    return equilibrium(linkage.mechanism, linkage.structure, kin, lds, section, crank_inertia=crank_J,
                       singular=singular)


def _kin_solver(solver):
    if solver is not None:
        return solver
    from .. import kinematics
    return kinematics.solve


def singular_function(mech, balance: int, solver=None, grid=None):
    """The scaled determinant of the equilibrium system against the crank angle.

    Parameters
    ----------
    mech : Mechanism
        The mechanism.
    balance : int
        The balance link's index.
    solver : callable or None
        The kinematics function (None: the general solver).
    grid : array_like or None
        The crank angles, deg, at which kinematics are precomputed.

    Returns
    -------
    callable
        f(phi_deg) -> the scaled determinant (dimensionless).
    """
    solve = _kin_solver(solver)

    def f(phi_deg: np.ndarray) -> np.ndarray:
        kin = solve(mech, np.atleast_1d(np.asarray(phi_deg, float)), 1.0)
        return scaled_det(mech, geometry(mech, kin), balance)
    return f


def _range_zeros(mech, b: int, solve, start: float, span: float) -> list[float]:
    """find_singular over the crank range [start, start + span] (deg)."""
    from ...lazy import brentq
    grid = start + span * np.linspace(0.0, 1.0, max(2, int(math.ceil(abs(span) / 0.5)) + 1))
    f = scaled_det(mech, geometry(mech, solve(mech, np.mod(grid, 360.0), 1.0)), b)

    def F(phi):
        return float(scaled_det(mech, geometry(mech, solve(mech, np.array([phi % 360.0]), 1.0)), b)[0])
    out = [float(a) for a, v in zip(grid, f) if v == 0.0]
    for a, c, fa, fc in zip(grid[:-1], grid[1:], f[:-1], f[1:]):
        if fa * fc < 0.0:
            out.append(float(brentq(F, min(a, c), max(a, c), xtol=1e-10)))
    return sorted(x % 360.0 for x in out)


def find_singular(mech, structure=None, balance=None, *, solver=None, n_grid: int = 720,
                  over: tuple[float, float] | None = None) -> list[float]:
    """The crank angles where the equilibrium equations are singular.

    Parameters
    ----------
    mech : Mechanism
        The mechanism.
    structure : StructureResult or None
        Its structure.
    balance : str or int or None
        The balance link (name or index; None: the drive link).
    solver : callable or None
        The kinematics function.
    n_grid : int
        The grid's points over a turn.
    over : (float, float) or None
        (start, span), deg: only over this crank range (a linkage that works over it only,
        docs/methods.md §0): a 0.5-deg grid from its start to its end, its sign changes
        refined by Brent's method (touching zeros are not sought).

    Returns
    -------
    list of float
        The angles in [0, 360), deg: the roots of the scaled determinant of A(phi), bracketed
        on the grid and refined by Brent's method to 1e-9 deg; touching (double) roots by a
        bounded minimisation.
    """
    if balance is None:
        b = mech.drive
    elif isinstance(balance, int):
        b = balance
    else:
        b = mech.link(balance).index
    solve = _kin_solver(solver)
    if over is not None:
        return _range_zeros(mech, b, solve, *over)
    grid = np.linspace(0.0, 360.0, n_grid + 1)
    try:
        kin = solve(mech, grid, 1.0)
        f = scaled_det(mech, geometry(mech, kin), b)
    except ValueError as exc:
        raise StageError("kinetostatics", str(exc)) from exc
    fmax = float(np.max(np.abs(f)))
    if not np.isfinite(fmax) or fmax == 0.0:
        raise StageError("kinetostatics", Message("kinetostatics.fail.singular_everywhere"))

    def F(phi, start):
        k = solve(mech, np.array([start, phi]), 1.0)
        return float(scaled_det(mech, geometry(mech, k), b)[-1]) / fmax

    from ..kinematics.changepoints import circle_zeros
    return circle_zeros(grid, f / fmax, F)
