"""Accuracy against computing time, per stage (`tmm study TASK`, `tmm run --study`).

For every stage present in the task the setting that trades time for accuracy is swept;
each row is compared with a converged reference, and the reference itself is checked
(computed again at a finer setting: refined until two successive references agree to
`REF_TOL`, or the study says it did not converge; where the reference is exact, the check
says how it was located).  The result, `study.json`:

    {"<stage>": {"setting": NAME, "reference": {<values>, "setting": VALUE,
                                                 "check": {"setting": V2, "difference": d}},
                 "rows": [{"setting": VALUE, <values>, "error": e, "time_ms": t}],
                 "order": p, "theory": q}}

`error` is the row's relative error against the reference; `order` is the measured
convergence order: the slope of log(error) against log(1/step) fitted over the four finest
rows whose error is above the rounding floor (the asymptotic range; null when fewer than
three rows are, or the setting is not a resolution, as for the planetary search); `theory`
is the order of the rule used.
The timings live here only: results.json stays deterministic. Each row is timed after one
untimed call (no cold start). `default` is the setting a run uses (where the stage has one);
`trade()` says the coarsest row against it (else the finest) in one plain sentence, which
study.html and `tmm study` print first.

Stages and settings (the rule, its theoretical order):
* flywheel: `resolution` (grid intervals; two-point Gauss-Legendre per interval: 4), values
  J_n of the three methods; the trapezoid (`quadrature: 0`, order 2) on the same grids
  beside it in the report's plot (not in study.json);
* curves: `points` of the output's s, v, a curves over a turn; the curves drawn through
  them (linear interpolation: 2) against the exact kinematics at `KST_EVAL` angles; error:
  the largest deviation relative to the curve's largest value (s: the stroke); `output`:
  'slider' (m, m/s, m/s^2) or 'rocker' (deg, rad/s, rad/s^2);
* kinetostatics: `positions` per turn (equal steps plus the load jumps and kinks, the
  extreme positions and, with friction, the reversals of the pairs' relative motion and
  the sign changes of the sliders' normal forces, each as both one-sided limits); the
  diagrams of M_b and of the reactions drawn through them (linear interpolation: 2)
  against the exact solution at `KST_EVAL` angles (at the constant crank speed, also for
  `motion: true`); error: the largest deviation over the cycle relative to the largest
  |M_b| and the largest reaction; `balancing`: 'moment' (N*m) or 'force' (N, on a slider);
* dof2: the integrator's `rtol` (DOP853); values the final speeds and angle (error
  proportional to the tolerance: 1);
* cam: the profile's angular `step` (deg; `tmm_cli.cam.polygon`): the polygon's deviation
  from the exact working profile (a chord's sagitta: 2) relative to r0 and rho_min of
  three successive vertices (2 inside a phase, 1 at a phase boundary);
* gears: the blocking contour's `grid` (nodes per axis): the traced contour's deviation
  from the exact zero levels, in units of x (marching squares, linear along an edge: 2
  where the check is smooth);
* planetary: `z_max` of the search; values the best ratio found and its `ratio_error`, the
  relative deviation from the `required` ratio (the task's); the row's `error` is the change of
  these against the reference search (no order).
"""
from __future__ import annotations

import math
import time
from contextlib import contextmanager
from typing import Callable

import numpy as np

REF_TOL = 1e-10
FLOOR = 1e-13
KST_EVAL = 3600
ASYMPTOTIC = 4     # the order is fitted over the 4 finest rows above the rounding floor
THEORY = {"flywheel": 4, "curves": 2, "kinetostatics": 2, "dof2": 1, "cam": 2, "gears": 2,
          "planetary": None}


def _rel(x: float, ref: float) -> float:
    den = abs(ref)
    if den == 0:
        return abs(x)
    return abs(x - ref) / den


def _err(vals: dict, ref: dict) -> float:
    return max(_rel(vals[k], ref[k]) for k in vals)


def fit_order(settings, errors, floor: float = FLOOR, inverse: bool = False,
              last: int | None = ASYMPTOTIC) -> float | None:
    """Slope p of error ~ setting^-p (least squares in log-log) over the errors above
    `floor`, of the `last` finest such rows (the asymptotic range; None: all rows); None
    with fewer than three such rows.  inverse: error ~ setting^p (a tolerance or a step
    as the setting)."""
    pts = [(s, e) for s, e in zip(settings, errors) if e is not None and e > floor and s > 0]
    pts.sort(key=lambda p: p[0], reverse=inverse)
    if last:
        pts = pts[-last:]
    if len(pts) < 3:
        return None
    x = np.log([p[0] for p in pts])
    y = np.log([p[1] for p in pts])
    slope = float(np.polyfit(x, y, 1)[0])
    return round(slope if inverse else -slope, 2)


def _timed(fn: Callable[[], dict], repeat: int = 3) -> tuple[dict, float]:
    """(fn(), the best of ``repeat`` timed calls in ms) after one untimed call: a first
    call's imports and caches (a cold start) are not the setting's cost."""
    best = math.inf
    out = fn()
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return out, best * 1e3


def sweep(name: str, values_at: Callable, settings: list, ref_settings: list,
          inverse: bool = False, repeat: int = 3, stage: str | None = None) -> dict:
    """The study of one stage: values_at(setting) -> {name: float}.  The reference is the
    first of ref_settings whose values agree with the next one's to REF_TOL (else the
    last), so that the reference is checked for convergence."""
    ref_vals = values_at(ref_settings[0])
    ref_set = ref_settings[0]
    converged = False
    check = None
    for nxt in ref_settings[1:]:
        v = values_at(nxt)
        check = {"setting": nxt, "difference": _err(ref_vals, v)}
        if check["difference"] <= REF_TOL:
            converged = True
            break
        ref_vals, ref_set = v, nxt
    from .errors import StageError
    rows = []
    for s in settings:
        try:
            vals, t = _timed(lambda: values_at(s), repeat)
        except StageError:       # e.g. a search range with no solution: no row
            continue
        rows.append({"setting": s, **vals, "error": _err(vals, ref_vals), "time_ms": round(t, 3)})
    order = fit_order([r["setting"] for r in rows], [r["error"] for r in rows], inverse=inverse)
    out = {"setting": name, "reference": {**ref_vals, "setting": ref_set, "check": check},
           "rows": rows, "order": order, "theory": THEORY.get(stage or "")}
    if not converged:
        out["reference"]["converged"] = False
    return out


@contextmanager
def _patched(module, name: str, value):
    old = getattr(module, name)
    setattr(module, name, value)
    try:
        yield
    finally:
        setattr(module, name, old)


# ------------------------------------------------------------------ stages
def flywheel_values(task, linkage, resolution: int, quadrature: int | None = None) -> dict:
    from .linkage import dynamics
    upd = {"resolution": int(resolution)}
    if quadrature is not None:
        upd["quadrature"] = int(quadrature)
    c = dynamics.analyze(linkage, task.flywheel.model_copy(update=upd), accuracy=False).cycle
    return {"J_n": c.J_n[c.method], "J_n_merzalov": c.J_n["merzalov"], "J_n_exact": c.J_n["exact"]}


def study_flywheel(task, linkage, quadrature: int | None = None, repeat: int = 3) -> dict:
    settings = sorted({12, 18, 24, 36, 48, 72, 96, 144, 180, 360, int(task.flywheel.resolution)})
    refs = [2880, 5760, 11520] if quadrature != 0 else [23040, 46080]
    out = sweep("resolution", lambda r: flywheel_values(task, linkage, r, quadrature),
                settings, refs, repeat=repeat, stage="flywheel")
    out["default"] = int(task.flywheel.resolution)
    if quadrature == 0:
        out["theory"] = 2
    return out


def _interp_errors(q, v: np.ndarray, qe, ex: np.ndarray) -> np.ndarray:
    """Per column: the largest deviation of the polyline through (q, v) from the exact
    values ex at qe (NaN, e.g. undefined at a change point, left out)."""
    return np.array([np.nanmax(np.abs(np.interp(qe, q, v[:, k]) - ex[:, k])) for k in range(v.shape[1])])


def curve_values(linkage, n: int, turn=None) -> np.ndarray:
    """(points, 3): s, v, a of the output over a turn at n equal steps (or at `turn`)."""
    from .linkage.kinematics import output_curve
    c = output_curve(linkage, int(n), turn)
    return np.column_stack([np.asarray(x, float) for x in (c.s, c.v, c.a)])


def study_curves(linkage, repeat: int = 3) -> dict:
    """The s, v, a diagrams drawn through n points over a turn (linear interpolation)
    against the exact kinematics at KST_EVAL angles; error: the largest deviation relative
    to each curve's largest value (s: its range)."""
    settings = [13, 25, 37, 73, 145, 361, 721, 1441]
    qe = (np.arange(KST_EVAL) + 0.5) * 360.0 / KST_EVAL
    ex = curve_values(linkage, 0, qe)
    scale = np.array([np.ptp(ex[:, 0]), *np.nanmax(np.abs(ex[:, 1:]), axis=0)])

    def errs(v, qe=qe, ex=ex, n=None):
        q = np.linspace(0.0, 360.0, n)
        e = _interp_errors(q, v, qe, ex) / np.where(scale > 0, scale, 1.0)
        return {"err_s": float(e[0]), "err_v": float(e[1]), "err_a": float(e[2])}

    rows = []
    for n in settings:
        v, t = _timed(lambda: curve_values(linkage, n), repeat)
        e = errs(v, n=n)
        rows.append({"setting": n, **e, "error": max(e.values()), "time_ms": round(t, 3)})
    n0 = 361                        # the report's curves (pipeline.run's kinematics_curve)
    q2 = (np.arange(2 * KST_EVAL) + 0.5) * 360.0 / (2 * KST_EVAL)
    v0 = curve_values(linkage, n0)
    e1, e2 = errs(v0, n=n0), errs(v0, q2, curve_values(linkage, 0, q2), n=n0)
    diff = max(abs(e1[k] - e2[k]) / max(e2[k], 1e-300) for k in e1)
    ref = {"stroke": float(scale[0]), "v_max": float(scale[1]), "a_max": float(scale[2]),
           "setting": KST_EVAL, "check": {"setting": 2 * KST_EVAL, "points": n0, "difference": diff}}
    return {"setting": "points", "reference": ref, "rows": rows, "default": n0,
            "order": fit_order(settings, [r["error"] for r in rows]), "theory": THEORY["curves"],
            "output": linkage.positions.output_kind}      # 'slider' (m, m/s, m/s^2) | 'rocker' (deg, rad/s, rad/s^2)


class KinetostaticDiagrams:
    """M_b and the reactions over the cycle at any positions (constant crank speed), and
    the error of the diagrams drawn through N positions (see the module docstring)."""

    def __init__(self, linkage, section):
        from .linkage.dynamics import analysis as dyn, cycle
        self.linkage, self.section = linkage, section
        self.mech = linkage.mechanism
        self.cycle = float(linkage.drive.cycle)
        self.sign = float(linkage.drive.sign)
        self.phi0 = float(linkage.positions.phi0)
        self.switch = cycle.switch_q(dyn.grid_switch_angles(linkage), self.phi0, self.sign, self.cycle)
        self.singular = None       # found by the first analysis, then reused
        if section.friction is not None:
            # friction changes sign where a pair's relative motion reverses: breakpoints too
            self.switch = sorted(self.switch + self.reversals())
        # the exact diagrams at KST_EVAL angles strictly inside the grid cells (off every jump)
        self.q_eval = (np.arange(KST_EVAL) + 0.5) * self.cycle / KST_EVAL
        self.exact = self.at(self.q_eval, np.zeros(KST_EVAL))
        if section.friction is not None:
            # a slider's friction f |N| has a kink where its normal force N changes sign
            self.switch = sorted(self.switch + self.normal_zeros())

    def normal_zeros(self, tol: float = 1e-9) -> list[float]:
        """Cycle angles q (deg) where a prismatic pair's normal force changes sign: sign
        changes at the KST_EVAL angles, each refined by bisection to `tol` deg."""
        cols = [1 + 2 * k for k, j in enumerate(self.mech.joints) if j.kind == "P"]
        out: list[float] = []
        q = self.q_eval
        for c in cols:
            v = self.exact[:, c]
            i = np.flatnonzero(np.isfinite(v[:-1]) & np.isfinite(v[1:]) & (np.sign(v[:-1]) * np.sign(v[1:]) < 0))
            if i.size == 0:
                continue
            lo, hi, flo = q[i], q[i + 1], v[i]
            for _ in range(int(np.ceil(np.log2((q[1] - q[0]) / tol)))):
                mid = 0.5 * (lo + hi)
                fm = self.at(mid, np.zeros(mid.size))[:, c]
                left = np.sign(fm) == np.sign(flo)
                lo, flo, hi = np.where(left, mid, lo), np.where(left, fm, flo), np.where(left, hi, mid)
            out.extend(float(x) for x in 0.5 * (lo + hi))
        return out

    def _relative(self, q) -> np.ndarray:
        from .linkage.kinetostatics.equations import geometry
        from .linkage.kinetostatics.solve import relative_motion
        from .linkage.kinematics import solve
        phi = self.phi0 + self.sign * np.asarray(q, float)
        kin = solve(self.mech, phi, self.linkage.drive.omega)
        return relative_motion(self.mech, geometry(self.mech, kin))

    def reversals(self, n: int = 1440, tol: float = 1e-9) -> list[float]:
        """Cycle angles q (deg) where a pair's relative motion reverses: sign changes on n
        equal steps, each refined by bisection to `tol` deg."""
        q = np.linspace(0.0, self.cycle, n + 1)
        r = self._relative(q)
        scale = np.max(np.abs(r), axis=0)
        i, k = np.nonzero((np.sign(r[:-1]) * np.sign(r[1:]) < 0) & (scale > 1e-9 * scale.max()))
        if i.size == 0:
            return []
        lo, hi, flo = q[i], q[i + 1], r[i, k]
        rows = np.arange(i.size)
        for _ in range(int(np.ceil(np.log2(self.cycle / n / tol)))):
            mid = 0.5 * (lo + hi)
            fm = self._relative(mid)[rows, k]
            left = np.sign(fm) == np.sign(flo)
            lo, flo, hi = np.where(left, mid, lo), np.where(left, fm, flo), np.where(left, hi, mid)
        out: list[float] = []
        for x in np.sort(0.5 * (lo + hi)):
            if not out or x - out[-1] > 1e-6:
                out.append(float(x))
        return out

    def at(self, q, side) -> np.ndarray:
        """(positions, 1 + 2 * pairs): M_b and the reaction components at cycle angles q (deg),
        one-sided (side -1 / +1) at the jumps."""
        from .linkage import kinetostatics, loads as loads_mod
        from .linkage.dynamics import EPS_DEG
        from .linkage.kinematics import solve
        phi = self.phi0 + self.sign * (np.asarray(q, float) + np.asarray(side, float) * EPS_DEG)
        kin = solve(self.mech, phi, self.linkage.drive.omega)
        ks = self.section
        lds = loads_mod.evaluate(self.linkage, kin, inertia=ks.inertia)
        res = kinetostatics.equilibrium(self.mech, self.linkage.structure, kin, lds, ks, singular=self.singular)
        self.singular = list(res.singular)
        return np.column_stack([np.asarray(res.M_b, float), np.asarray(res.reactions, float)])

    def grid(self, n: int):
        from .linkage.dynamics import grid
        return grid(int(n), self.cycle, self.switch)

    def errors(self, n: int, values: np.ndarray | None = None, q_eval=None, exact=None) -> dict:
        """{err_M_b, err_R}: the largest deviation of the diagrams through the grid of n
        positions from the exact ones, relative to the largest |M_b| and the largest
        reaction component."""
        q, side = self.grid(n)
        v = self.at(q, side) if values is None else values
        qe = self.q_eval if q_eval is None else q_eval
        ex = self.exact if exact is None else exact
        ok = np.all(np.isfinite(ex), axis=1)
        dev = _interp_errors(q, v, qe[ok], ex[ok])
        sm = np.max(np.abs(ex[ok, 0]))
        sr = np.max(np.abs(ex[ok, 1:])) if ex.shape[1] > 1 else 0.0
        return {"err_M_b": float(dev[0] / sm) if sm > 0 else 0.0,
                "err_R": float(np.max(dev[1:]) / sr) if sr > 0 else 0.0}


def study_kinetostatics(task, linkage, repeat: int = 3) -> dict:
    d = KinetostaticDiagrams(linkage, task.kinetostatics)
    settings = [12, 24, 36, 72, 144, 360, 720]
    rows = []
    for n in settings:
        q, side = d.grid(n)
        vals, t = _timed(lambda: d.at(q, side), repeat)
        e = d.errors(n, vals)
        rows.append({"setting": n, **e, "error": max(e.values()), "time_ms": round(t, 3)})
    # the check: the largest deviation sampled at twice the angles (at the task's count)
    n0 = int((task.positions.count if task.positions is not None else 12) or 12)
    q2 = (np.arange(2 * KST_EVAL) + 0.5) * d.cycle / (2 * KST_EVAL)
    e1 = d.errors(n0)
    e2 = d.errors(n0, q_eval=q2, exact=d.at(q2, np.zeros(q2.size)))
    diff = max(abs(e1[k] - e2[k]) / max(e2[k], 1e-300) for k in e1)
    ok = np.all(np.isfinite(d.exact), axis=1)
    ref = {"M_b_max": float(np.max(np.abs(d.exact[ok, 0]))),
           "R_max": float(np.max(np.abs(d.exact[ok, 1:]))) if d.exact.shape[1] > 1 else 0.0,
           "setting": KST_EVAL, "check": {"setting": 2 * KST_EVAL, "positions": n0, "difference": diff}}
    from .linkage.kinetostatics import balance_index
    balancing = "force" if linkage.mechanism.link(balance_index(linkage.mechanism, task.kinetostatics)).kind == "slider" \
        else "moment"       # M_b: a balancing force (N) on a slider, else a moment (N*m)
    return {"setting": "positions", "reference": ref, "rows": rows, "default": n0,
            "order": fit_order(settings, [r["error"] for r in rows]), "theory": THEORY["kinetostatics"],
            "balancing": balancing}


def cam_values(result, step: float) -> dict:
    from .cam import polygon
    rho = polygon.polygon_rho_min(result, step)
    return {"deviation": polygon.polygon_deviation(result, step), "rho_min": rho if math.isfinite(rho) else None}


def _cam_error(result, vals: dict) -> float:
    e = vals["deviation"] / result.r0
    if math.isfinite(result.rho_min) and vals["rho_min"] is not None:
        e = max(e, _rel(vals["rho_min"], result.rho_min))
    return e


def study_cam(task, repeat: int = 3) -> dict:
    """The profile polygon at steps from 10 deg to 0.1 deg against the exact profile (the
    reference: deviation 0 and rho_min located over continuous cam angle)."""
    from . import cam
    from .cam import polygon
    r = cam.synthesize(task.cam)
    settings = [10.0, 5.0, 3.0, 2.0, 1.0, 0.5, 0.25, 0.1]
    rows = []
    for h in settings:
        _, t = _timed(lambda: polygon.polygon(r, h), repeat)
        v = cam_values(r, h)
        rows.append({"setting": h, **v, "error": _cam_error(r, v), "time_ms": round(t, 3)})
    fine = 0.01
    check = {"setting": fine, "difference": _cam_error(r, cam_values(r, fine)),
             "sampling": abs(polygon.polygon_deviation(r, 1.0, sub=64) / max(rows[4]["deviation"], 1e-300) - 1)}
    ref = {"deviation": 0.0, "rho_min": r.rho_min if math.isfinite(r.rho_min) else None, "r0": r.r0,
           "setting": 0.0, "check": check}
    order = fit_order(settings, [x["error"] for x in rows], inverse=True)
    orders = {"deviation": fit_order(settings, [x["deviation"] / r.r0 for x in rows], inverse=True)}
    if ref["rho_min"]:     # a rho_min on a dwell (an arc) is exact: its errors are rounding
        orders["rho_min"] = fit_order(settings, [None if x["rho_min"] is None else _rel(x["rho_min"], r.rho_min)
                                                 for x in rows], floor=1e-9, inverse=True)
    return {"setting": "step", "reference": ref, "rows": rows, "order": order, "orders": orders,
            "theory": THEORY["cam"]}


def study_gears(task, repeat: int = 3) -> dict:
    """The blocking contour traced on grids of 21 to 641 nodes per axis against the exact
    zero levels of its checks (located along each grid edge by bisection to 1e-13)."""
    from . import gears
    from .gears import shifts
    g = gears.analyze(task.gears)
    cd = g.contour
    args = (g.m, g.z[0], g.z[1], g.alpha, g.ha, g.c, g.sa_min, g.rho_f)
    rng = (tuple(cd["x1_range"]), tuple(cd["x2_range"]))
    settings = [21, 41, 81, 161, 321, 641]
    rows = []
    for n in settings:
        bc, t = _timed(lambda: shifts.blocking_contour(*args, *rng, n=n), repeat if n <= 161 else 1)
        dev = shifts.contour_deviation(bc, *args)
        rows.append({"setting": n, "deviation_x": max(dev.values()), "error": max(dev.values()),
                     "time_ms": round(t, 3)})
    bc = shifts.blocking_contour(*args, *rng, n=161)
    d1 = max(shifts.contour_deviation(bc, *args, tol=1e-13).values())
    d2 = max(shifts.contour_deviation(bc, *args, tol=1e-15).values())
    ref = {"deviation_x": 0.0, "setting": 0,
           "check": {"setting": 1e-15, "grid": 161, "difference": abs(d1 - d2)}}
    return {"setting": "grid", "reference": ref, "rows": rows,
            "order": fit_order([n - 1 for n in settings], [r["error"] for r in rows]),
            "theory": THEORY["gears"]}


def dof2_values(section, rtol: float) -> dict:
    from .dof2 import analysis
    with _patched(analysis, "RTOL", float(rtol)), _patched(analysis, "ATOL", float(rtol) * 1e-2):
        d = analysis.analyze(section).to_dict()
    return {"omega_end": float(d["omega"][-1]), "psi_end": float(d["psi"][-1]),
            "psi_dot_end": float(d["psi_dot"][-1])}


def study_dof2(task, repeat: int = 1) -> dict:
    settings = [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10]
    return sweep("rtol", lambda r: dof2_values(task.dof2, r), settings, [1e-12, 1e-13],
                 inverse=True, repeat=repeat, stage="dof2")


def planetary_values(section, z_max: int) -> dict:
    from . import gears
    sec = section.model_copy(update={"z_max": int(z_max)})
    d = gears.synthesize_planetary(sec).to_dict()
    return {"ratio": float(d["ratio"]), "ratio_error": abs(float(d["ratio_error"]))}


def study_planetary(task, repeat: int = 1) -> dict:
    z0 = int(task.planetary.z_max)
    settings = sorted({s for s in (30, 40, 60, 80, 100, 120, 150, 200, z0) if s >= task.planetary.z_min})
    out = sweep("z_max", lambda z: planetary_values(task.planetary, z), settings, [z0, 300],
                repeat=repeat, stage="planetary")
    out["order"] = None      # a search, not a discretisation: no order
    out["default"] = z0      # the search a run makes
    out["required"] = float(task.planetary.ratio)   # the ratio_error of a row is against it
    return out


# the task's sections that compute something: named when none of them has a setting to sweep
SECTIONS = ("mechanism", "synthesis", "cam", "gears", "planetary", "drive_train", "balancing",
            "differential", "dof2")


def nothing_to_sweep(task, study: dict, extra: dict):
    """The note (a Message) when the study of ``task`` swept nothing and has nothing to say (a
    differential, a drive train, a rotor's balancing alone): which sections the study sweeps and
    which the task has. None when a stage was swept or the linkage's study was left out with its
    reason (``extra["left_out"]``). `tmm study` then writes no study.json or study.html and exits
    0 (as `tmm sheets` with no sheet to draw); `tmm run --study` gives it as a warning."""
    if study or extra.get("left_out"):
        return None
    from .messages import Message
    return Message("study.nothing_to_sweep", sections=[s for s in SECTIONS if getattr(task, s, None) is not None])


def run_study(task, progress: Callable[[str], None] | None = None, repeat: int = 3
              ) -> tuple[dict, dict]:
    """(study, trapezoid): the study of every stage present in `task` (see the module
    docstring) and, for the report, the flywheel's trapezoid swept on the same grids."""
    say = progress or (lambda s: None)
    out: dict = {}
    extra: dict = {}
    over = None                 # a function generator over its input range: no turn to study
    if task.synthesis is not None:
        from .linkage.synthesis import generate
        over = generate(task)[1].crank_range
        if over is not None and task.mechanism is not None:    # said in the study, never silently
            extra["left_out"] = {"start": float(over.start), "end": float(over.start + over.span)}
    if task.mechanism is not None and over is None:
        from .linkage.context import build
        linkage = build(task)
        say("study: curves")
        out["curves"] = study_curves(linkage, repeat)
        if task.flywheel is not None:
            say("study: flywheel")
            out["flywheel"] = study_flywheel(task, linkage, repeat=repeat)
            tr = study_flywheel(task, linkage, quadrature=0, repeat=1)
            extra["flywheel"] = {"rows": [{k: r[k] for k in ("setting", "J_n", "error")}
                                          for r in tr["rows"]], "order": tr["order"], "theory": 2}
        if task.kinetostatics is not None:
            say("study: kinetostatics")
            out["kinetostatics"] = study_kinetostatics(task, linkage, repeat)
    if task.cam is not None:
        say("study: cam")
        out["cam"] = study_cam(task, repeat)
    if task.gears is not None:
        say("study: gears")
        out["gears"] = study_gears(task, repeat)
    if task.dof2 is not None:
        say("study: dof2")
        out["dof2"] = study_dof2(task)
    if task.planetary is not None:
        say("study: planetary")
        out["planetary"] = study_planetary(task)
    return out, extra
