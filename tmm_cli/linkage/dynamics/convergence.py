"""The convergence of the flywheel calculation: J against the grid's resolution
(``accuracy_table``, timed: `tmm study`), the course's 12-position hand method beside the
accurate value (``hand_row``, in every result) and the check of a coarse grid against
twice its positions (``coarse_check``)."""
from __future__ import annotations

import time

from . import flywheel as fw
from .cycle import CycleResult, Sampler, run_grid
from .result import _f

ACCURACY_RESOLUTIONS = (12, 24, 36, 72, 180, 360, 3600)
CHECK_BELOW = 180   # a coarser grid is checked against twice its positions ...
TARGET_REL = 1e-6   # ... and a warning given when J_n moves by more than this


def _rel(x, ref):
    if ref is None or x is None:
        return None
    den = abs(ref)
    if den == 0:
        return 0.0 if x == 0 else None
    return abs(x - ref) / den


def hand_positions(cycle: float) -> int:
    """The number of positions of the hand method.

    Parameters
    ----------
    cycle : float
        The cycle, deg.

    Returns
    -------
    int
        One position every 30 deg: 12, or 24 over 720 deg.
    """
    return int(round(cycle / 30.0))


def hand_row(sampler: Sampler, section, omega_m: float, cycle: float, switch_q,
             ref: CycleResult, ref_resolution: int) -> dict:
    """The course's hand method beside the accurate result.

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
    switch_q : sequence of float
        The loads' jumps, deg from position 0.
    ref : CycleResult
        The accurate result.
    ref_resolution : int
        Its resolution.

    Returns
    -------
    dict
        J (kg*m^2) and omega_max/min (rad/s) of 12 positions every 30 deg (24 over 720 deg),
        the trapezoid of the works, no inserted jump points, the extrema at the positions,
        with their errors relative to ``ref`` (deterministic: no timing).

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: the flywheel by the energy-mass
    method at the positions of the plans; docs/methods.md §4.
    """
    n_hand = hand_positions(cycle)
    hand = run_grid(sampler, section, omega_m, cycle, n_hand, switch_q, insert=False)[0]
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
    """The flywheel's results against the resolution of the grid.

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
    switch_q : sequence of float
        The loads' jumps, deg from position 0.
    resolutions : sequence of int
        The resolutions (intervals per cycle) tabulated.
    known : dict or None
        {resolution: CycleResult} already computed (reused, its time not measured).

    Returns
    -------
    dict
        Per row: J (kg*m^2) and its relative error to the converged value (the finest
        resolution); omega_max/min (rad/s) of the motion with the converged flywheel computed
        on that grid and their errors; ``delta_true``, the fluctuation the row's J really
        gives (on the finest grid); ``time_ms``.  ``hand``: the course's hand calculation
        (:func:`hand_row`).
    """
    known = dict(known or {})
    res_list = sorted(set(int(r) for r in resolutions))
    cycles: dict[int, CycleResult] = {}
    times: dict[int, float | None] = {}
    for r in res_list:
        if r in known:
            cycles[r], times[r] = known[r], None
            continue
        t0 = time.perf_counter()
        cycles[r] = run_grid(sampler, section, omega_m, cycle, r, switch_q)[0]
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
