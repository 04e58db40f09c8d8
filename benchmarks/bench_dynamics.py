"""Dynamics stage timings (targets from issue 4):

* full dynamics (kinematics + loads + reduced quantities + all three methods + steady
  motion) at 360 positions: under 50 ms;
* the exact method alone (root finding on J with the steady-state T0 at every trial):
  under 1 s (measured at 360 and 3600 nodes).

Run: python benchmarks/bench_dynamics.py [TASK.yaml]   (median of 7 runs, CPU time)
"""
from __future__ import annotations

import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from _dyn_tasks import prepare  # noqa: E402


def median_ms(fn, repeat=7, fresh=None) -> float:
    """Median CPU time of fn(*fresh()) in ms (fresh(): its arguments, made untimed before
    every call: a new linkage, with nothing an earlier call found; CPU, not wall: the
    machine is shared)."""
    fresh = fresh or (lambda: ())
    fn(*fresh())   # warm-up (imports)
    times = []
    for _ in range(repeat):
        args = fresh()
        t0 = time.process_time()
        fn(*args)
        times.append((time.process_time() - t0) * 1e3)
    return statistics.median(times)


def main() -> None:
    from tmm_cli.linkage import dynamics
    from tmm_cli.linkage.dynamics import flywheel as fw
    path = sys.argv[1] if len(sys.argv) > 1 else None
    task, linkage = prepare(path)
    res = task.flywheel.resolution
    rows = [(f"full dynamics, {res} positions (no accuracy table)",
             median_ms(lambda t, lk: dynamics.analyze(lk, t.flywheel, accuracy=False), fresh=lambda: prepare(path)),
             50.0),
            ("full dynamics + accuracy table (12..3600 and the hand row)",
             median_ms(lambda t, lk: dynamics.analyze(lk, t.flywheel, accuracy=True), 3, fresh=lambda: prepare(path)),
             None)]
    for n in (360, 3600):
        task_n = task.model_copy(update={"flywheel": task.flywheel.model_copy(update={"resolution": n})})
        r = dynamics.analyze(linkage, task_n.flywheel, accuracy=False)
        c = r.cycle
        rows.append((f"exact method alone, {c.q.size} nodes",
                     median_ms(lambda: fw.exact_flywheel(c.work.dT, c.J_var, c.omega_m, c.delta,
                                                         guess=c.J_n["energy-mass"])), 1000.0))
    print(f"task: {task.title}")
    ok = True
    for name, ms, target in rows:
        verdict = "" if target is None else ("ok" if ms < target else "SLOW")
        ok &= target is None or ms < target
        tgt = "" if target is None else f"(target < {target:.0f} ms)"
        print(f"  {name:62s} {ms:9.2f} ms CPU  {tgt} {verdict}")
    if not ok:
        raise SystemExit(1)


if __name__ == "__main__":
    main()
