"""The accuracy figures the README quotes, measured on every example task (tasks/*.yaml)
and on the forging machine of the dynamics benchmarks; every claim is checked (PASS/FAIL).

1. The flywheel at the defaults: per task with a flywheel the converged J_n (primary
   method; reference at 5760 positions, checked against 2880), the relative error of the
   task's setting (Gauss-Legendre, two points per interval) for energy-mass, Merzalov and
   the exact motion, the CPU time of the dynamics stage (median of 5), the error of the
   12-position hand method, the trapezoid's error at 360 positions, and the convergence
   orders of Gauss-Legendre and of the trapezoid (`tmm_cli.study`).
2. The claims of the README's Methods section on every example task: the extreme positions
   are roots of the output's analogue to 1e-10 deg; the four balancing moments agree; energy-mass and the exact motion agree on the same grid; Wittenbauer's
   bound; Merzalov's bound; the flywheel within 1e-9 of the converged value.
3. The convergence order of every stage of every example task (`tmm study`), against the
   theoretical order of the rule used, with the error at the default setting.

Run: python benchmarks/accuracy_all.py [--no-study] [TASK.yaml ...]
"""
from __future__ import annotations

import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402
from _dyn_tasks import prepare  # noqa: E402

DEFAULT = {"curves": 361, "cam": 1.0, "gears": 161, "dof2": 1e-10}


def flywheel_row(path):
    from tmm_cli import study
    from tmm_cli.linkage import dynamics
    task, linkage = prepare(path)
    ref = study.flywheel_values(task, linkage, 2880)
    ref2 = study.flywheel_values(task, linkage, 5760)
    check = max(abs(ref[k] / ref2[k] - 1) for k in ref)
    cpu = []
    for _ in range(5):
        # a fresh linkage each time: the stage as a run meets it (the kink angles of the loads
        # not yet found by an earlier call)
        task, linkage = prepare(path)
        t0 = time.process_time()
        r = dynamics.analyze(linkage, task.flywheel, accuracy=False)
        cpu.append((time.process_time() - t0) * 1e3)
    c = r.cycle
    errs = {m: abs(c.J_n[m] / ref2[k] - 1) for m, k in
            (("energy-mass", "J_n"), ("merzalov", "J_n_merzalov"), ("exact", "J_n_exact"))}
    fly = study.study_flywheel(task, linkage, repeat=1)
    trap = study.study_flywheel(task, linkage, quadrature=0, repeat=1)
    return {"title": task.title, "delta": task.flywheel.delta, "J_n": ref2["J_n"], "ref_check": check,
            "resolution": task.flywheel.resolution, "errors": errs, "cpu_ms": statistics.median(cpu),
            "hand": r.hand["err_J_n"], "hand_positions": r.hand["positions"],
            "order_gauss": fly["order"], "order_trapezoid": trap["order"],
            "trap_360": next(x["error"] for x in trap["rows"] if x["setting"] == 360)}


def claims(paths) -> list[tuple[str, float, float, bool]]:
    """(claim, worst value over the example tasks, bound, holds)."""
    import tmm_cli
    from tmm_cli.pipeline import run
    mb, em_ex, witt, merz, ext = 0.0, 0.0, 0.0, 0.0, True
    for p in paths:
        task = tmm_cli.load_task(p)
        if task.synthesis is not None:       # the mechanism it generates
            from tmm_cli.linkage.synthesis import generate
            task, _ = generate(task)
        if task.mechanism is not None:
            # the extreme positions bracket a root of the output's analogue ds/dphi to 1e-10 deg
            from tmm_cli.linkage.context import build
            pos = build(task).positions
            for e in pos.extreme or []:
                lo, hi = pos._f(np.array([e - 1e-10, e + 1e-10]))[1]
                ext &= bool(lo * hi <= 0)
        d = run(task, kinematics_curve=0)
        ks = d.get("kinetostatics") or []
        vals = [[e.get(k) for k in ("balancing_moment", "zhukovsky_moment", "virtual_power_moment",
                                    "matrix_moment")] for e in ks]
        vals = [v for v in vals if None not in v]
        if vals:
            scale = max(abs(x) for v in vals for x in v) or 1.0
            mb = max(mb, max(max(v) - min(v) for v in vals) / scale)
        f = d.get("flywheel")
        if f:
            em_ex = max(em_ex, abs(f["J_energy_mass"] / f["J_exact"] - 1))
            jv = f["J_var_max"] - f["J_var_min"]
            bound = jv * f["delta"] / 8
            witt = max(witt, abs(f["J_wittenbauer"] - f["J_exact"]) / bound if bound > 0 else 0.0)
            m = f["J_merzalov"] - f["J_exact"]
            # Merzalov exceeds the exact J by between min and max of J_var (rounding allowed)
            lo, hi = f["J_var_min"], f["J_var_max"]
            merz = max(merz, max(lo - m, m - hi, 0.0) / max(hi, 1e-300))
    return [("the extreme positions are roots of ds/dphi to 1e-10 deg (1: all)", float(ext), 1.0, ext),
            ("the four balancing moments agree (relative to max |M_b|)", mb, 1e-9, mb <= 1e-9),
            ("energy-mass = exact motion on the same grid (relative)", em_ex, 1e-9, em_ex <= 1e-9),
            ("|J_wittenbauer - J_exact| / ((J_var,max - J_var,min) delta / 8)", witt, 1.0, witt <= 1.0),
            ("Merzalov - exact outside [J_var,min, J_var,max] (relative)", merz, 1e-9, merz <= 1e-9)]


def stage_orders(paths):
    import tmm_cli
    from tmm_cli import study
    out = []
    for p in paths:
        task = tmm_cli.load_task(p)
        st, _ = study.run_study(task, repeat=1)
        for stage, d in st.items():
            default = DEFAULT.get(stage)
            if stage == "flywheel":
                default = task.flywheel.resolution
            elif stage == "kinetostatics":
                default = (task.positions.count if task.positions is not None else None) or 12
            elif stage == "planetary":
                default = task.planetary.z_max
            row = next((r for r in d["rows"] if r["setting"] == default), None)
            out.append((Path(p).stem, stage, d["setting"], d["order"], d.get("theory"),
                        default, None if row is None else row["error"]))
    return out


def main() -> None:
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    tasks = args or sorted(str(p) for p in (ROOT / "tasks").glob("*.yaml"))
    fly_paths = ([None] if not args else []) + [p for p in tasks if "\nflywheel:" in Path(p).read_text()]
    print("1. The flywheel at the task's settings (errors relative to the converged J_n)")
    print(f"{'task':<46} {'delta':>7} {'J_n converged':>15} {'ref check':>9} {'res':>4} {'err EM':>8} "
          f"{'err Merz':>8} {'err exact':>9} {'CPU ms':>7} {'hand':>11} {'trap 360':>8} "
          f"{'p GL2':>6} {'p trap':>6}")
    worst = 0.0
    for p in fly_paths:
        x = flywheel_row(p)
        e = x["errors"]
        worst = max(worst, *e.values())
        print(f"{x['title'][:46]:<46} {x['delta']:>7.4g} {x['J_n']:>15.9g} {x['ref_check']:>9.1e} "
              f"{x['resolution']:>4} {e['energy-mass']:>8.1e} {e['merzalov']:>8.1e} {e['exact']:>9.1e} "
              f"{x['cpu_ms']:>7.1f} {100 * x['hand']:>6.2f}% ({x['hand_positions']}) {x['trap_360']:>8.1e} "
              f"{x['order_gauss']!s:>6} {x['order_trapezoid']!s:>6}")
    print("\n2. Claims (worst over the example tasks)")
    rows = claims(tasks) + [("the flywheel at the task's settings, relative to the converged J_n", worst,
                             1e-9, worst <= 1e-9)]
    for name, val, bound, ok in rows:
        print(f"  {'PASS' if ok else 'FAIL'}  {name:<68} {val:9.2e}  (bound {bound:g})")
    if "--no-study" in sys.argv:
        return
    print("\n3. Convergence order per stage (tmm study; fitted over the four finest rows)")
    print(f"{'task':<32} {'stage':<14} {'setting':<11} {'order':>6} {'theory':>6} {'default':>8} {'error there':>11}")
    for name, stage, setting, order, theory, default, err in stage_orders(tasks):
        print(f"{name:<32} {stage:<14} {setting:<11} {order!s:>6} {theory!s:>6} {default!s:>8} "
              f"{'—' if err is None else f'{err:.1e}':>11}")


if __name__ == "__main__":
    main()
