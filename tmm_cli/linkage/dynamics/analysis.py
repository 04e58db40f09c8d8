"""The dynamics stage (docs/methods.md §4): reduced quantities over the cycle, the
flywheel by three methods, the steady motion omega(phi), epsilon(phi).

Entry points
------------
``analyze(linkage, section)``               the stage of a linkage
``analyze_sampler(sampler, section, ...)``  the same over any sampler of reduced quantities
``cycle.solve_cycle(q, M_given, J_links, ...)``   the whole flywheel calculation on arrays

The modules: ``cycle`` (the grid, the sampler, the solution on the grid), ``result``
(DynamicsResult, results.json ``flywheel``), ``convergence`` (J against the resolution,
the hand method), ``flywheel`` (the methods), ``reduce`` (reduced moment and inertia).
"""
from __future__ import annotations

import math

import numpy as np

from ...errors import StageError
from ...messages import Message
from . import flywheel as fw
from .convergence import (ACCURACY_RESOLUTIONS, CHECK_BELOW, TARGET_REL, _rel, accuracy_table, hand_positions,
                          hand_row)
from .cycle import STAGE, Sampler, _Reuse, grid, mechanism_sampler, run_grid, switch_q
from .result import DynamicsResult, _f


def analyze_sampler(sampler: Sampler, section, omega_m: float, *, cycle: float = 360.0,
                    switch_q=(), phi0: float = 0.0, sign: float = 1.0,
                    accuracy: bool = True, map_cycle: float | None = None) -> DynamicsResult:
    """The dynamics stage over a sampler of the reduced moment and inertia.

    Parameters
    ----------
    sampler : Sampler
        The reduced moment (N*m) and inertia (kg*m^2) at any cycle angles.
    section : FlywheelSection
        The task's ``flywheel`` section (delta, the constant moment's kind, the method, the
        resolution, the quadrature).
    omega_m : float
        The crank's mean speed, rad/s (> 0).
    cycle : float
        The cycle, deg (360 or 720).
    switch_q : sequence of float
        The jumps of the loads, deg of rotation from position 0.
    phi0 : float
        The crank angle of position 0, deg.
    sign : float
        +1 for a ccw crank, -1 for cw.
    accuracy : bool
        True: add the timed accuracy table.
    map_cycle : float or None
        How :meth:`DynamicsResult.motion_at` reads crank angles (None: the cycle).

    Returns
    -------
    DynamicsResult
        The flywheel's moment of inertia (kg*m^2), the constant moment (N*m), the motion over
        the cycle (rad/s, rad/s^2) and the energy diagrams (J).

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: the reduced moment and moment of
    inertia, the energy-mass (Wittenbauer) method, Merzalov's method; docs/methods.md §4.
    """
    if not (omega_m > 0 and math.isfinite(omega_m)):
        raise StageError(STAGE, Message("flywheel.fail.drive_speed", value=omega_m))
    if cycle not in (360, 720, 360.0, 720.0):
        raise StageError(STAGE, Message("flywheel.fail.cycle", value=cycle))
    resolution = int(section.resolution)
    given = sampler          # the hand method's positions are sampled with the grid's
    sampler = _Reuse(sampler, grid(hand_positions(cycle), cycle, switch_q, insert=False))
    c, q_deg, side = run_grid(sampler, section, omega_m, cycle, resolution, switch_q)
    shape = section.shape
    shp = {"type": shape.type, "density": float(shape.density), "width_ratio": float(shape.width_ratio)}
    sz = fw.size(c.J, shp["type"], shp["density"], shp["width_ratio"], c.motion.omega_max)
    warnings = list(c.warnings) + list(sz.warnings)
    hand = hand_row(sampler, section, omega_m, cycle, switch_q, c, resolution)
    acc = None
    if not accuracy and resolution < CHECK_BELOW:
        # a coarse grid: its error estimated against twice the positions (cheap here)
        c2 = run_grid(sampler, section, omega_m, cycle, 2 * resolution, switch_q)[0]
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
                          accuracy=acc, warnings=warnings, q_deg=q_deg, side=side, sampler=given,
                          hand=hand, quadrature_points=int(section.quadrature), map_cycle=map_cycle)


def grid_switch_angles(linkage) -> list[float]:
    """The crank angles the dynamics grid must hold as breakpoints.

    Parameters
    ----------
    linkage : Linkage
        The linkage (its loads and positions).

    Returns
    -------
    list of float
        The absolute crank angles, deg: the loads' jumps and kinks
        (:func:`..loads.switch_angles`) and both extreme positions of the output.
    """
    from .. import loads as loads_mod
    drive, positions = linkage.drive, linkage.positions
    sw = list(loads_mod.switch_angles(linkage.mechanism, linkage.loads, positions, sign=drive.sign,
                                      cycle=drive.cycle, kinks=True, roots=positions._roots))
    return sw + [float(x) for x in (positions.extreme or [])]


def analyze(linkage, section, *, accuracy: bool = True) -> DynamicsResult:
    """The dynamics stage of a linkage: the flywheel for the given coefficient of speed
    fluctuation and the steady motion with it.

    Parameters
    ----------
    linkage : Linkage
        The mechanism, its loads, positions (position 0, the extremes) and drive: the
        mean speed ``drive.speed`` (rad/s), ``drive.sign`` and ``drive.cycle`` (deg).
    section : FlywheelSection
        The task's ``flywheel``: ``delta``, ``constant``, ``method``, ``resolution``,
        ``quadrature``, ``shape``, ``reduced_J`` (kg*m^2).
    accuracy : bool
        Add the timed accuracy-against-resolution table (`tmm study`).

    Returns
    -------
    DynamicsResult
        The flywheel's moment of inertia J (kg*m^2) by the energy-mass (Wittenbauer),
        Merzalov and exact methods, its size (m, kg), M_red (N*m), J_red (kg*m^2), the works
        (J), and omega1(phi) (rad/s), epsilon1(phi) (rad/s^2) of the steady motion.

    Notes
    -----
    The loads are evaluated without inertia at the absolute crank angles
    phi0 + sign*q, q over the cycle (unwrapped: beyond 360 deg for a 720-deg cycle).
    Inserted into the grid: the switch angles of the loads and their kinks (every grid
    interval is smooth, so the Gauss rule keeps its order) and both extreme positions of
    the output (where stroke loads start and stop). ``motion_at`` reads the reported
    positions (in [0, 360)) in the first turn after position 0, as the loads do.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: the reduced moment and moment of
    inertia, the energy-mass (Wittenbauer) method; Merzalov's method of the flywheel;
    docs/methods.md §4.
    """
    from .. import kinematics, loads as loads_mod
    mech, drive, positions = linkage.mechanism, linkage.drive, linkage.positions
    sign, cycle, phi0 = drive.sign, drive.cycle, float(positions.phi0)

    def kin_fn(phi):
        return kinematics.solve(mech, np.asarray(phi, float), drive.omega)

    def loads_fn(kin):
        return loads_mod.evaluate(linkage, kin, inertia=False)

    sw = switch_q(grid_switch_angles(linkage), phi0, sign, cycle)
    sampler = mechanism_sampler(mech, kin_fn, loads_fn, phi0=phi0, sign=sign)
    return analyze_sampler(sampler, section, drive.speed, cycle=cycle, switch_q=sw, phi0=phi0, sign=sign,
                           accuracy=accuracy, map_cycle=360.0)

