"""Accuracy of the flywheel at the default settings on every example task with a flywheel
(and the forging machine of the dynamics benchmarks), the hand method's error, and the
measured convergence orders — the figures the README quotes.

Per task: the converged J_n (primary method; the reference at 2880 / 5760 positions,
checked against each other), the relative error of the default (resolution 360, two
Gauss-Legendre points per interval) for energy-mass, Merzalov and the exact motion, the
computing time of the default dynamics stage (median of 5, process CPU time), the error of
the 12-position hand method (trapezoid over the positions), and the convergence orders of
Gauss-Legendre and of the trapezoid (`tmm_cli.study`).

Run: python benchmarks/accuracy_all.py [TASK.yaml ...]
"""
from __future__ import annotations

import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(ROOT))

from _dyn_tasks import prepare  # noqa: E402


def one(path):
    from tmm_cli import study
    from tmm_cli.linkage import dynamics
    task, linkage = prepare(path)
    ref = study.flywheel_values(task, linkage, 2880)
    ref2 = study.flywheel_values(task, linkage, 5760)
    check = max(abs(ref[k] / ref2[k] - 1) for k in ref)
    cpu = []
    for _ in range(5):
        t0 = time.process_time()
        r = dynamics.analyze(linkage, task.flywheel, accuracy=False)
        cpu.append((time.process_time() - t0) * 1e3)
    c = r.cycle
    errs = {m: abs(c.J_n[m] / ref2[k] - 1) for m, k in
            (("energy-mass", "J_n"), ("merzalov", "J_n_merzalov"), ("exact", "J_n_exact"))}
    hand = r.hand
    fly = study.study_flywheel(task, linkage, repeat=1)
    trap = study.study_flywheel(task, linkage, quadrature=0, repeat=1)
    return {"title": task.title, "delta": task.flywheel.delta, "J_n": ref2["J_n"], "ref_check": check,
            "errors": errs, "cpu_ms": statistics.median(cpu), "hand": hand["err_J_n"],
            "order_gauss": fly["order"], "order_trapezoid": trap["order"],
            "trap_360": next(x["error"] for x in trap["rows"] if x["setting"] == 360)}


def main() -> None:
    paths = sys.argv[1:] or [None] + sorted(str(p) for p in (ROOT / "tasks").glob("*.yaml")
                                             if "flywheel:" in p.read_text())
    print(f"{'task':<46} {'delta':>7} {'J_n converged':>15} {'ref check':>9} {'err EM':>8} "
          f"{'err Merz':>8} {'err exact':>9} {'CPU ms':>7} {'hand 12':>8} {'trap 360':>8} "
          f"{'p GL2':>6} {'p trap':>6}")
    for p in paths:
        x = one(p)
        e = x["errors"]
        print(f"{x['title'][:46]:<46} {x['delta']:>7.4g} {x['J_n']:>15.9g} {x['ref_check']:>9.1e} "
              f"{e['energy-mass']:>8.1e} {e['merzalov']:>8.1e} {e['exact']:>9.1e} {x['cpu_ms']:>7.1f} "
              f"{100 * x['hand']:>7.2f}% {x['trap_360']:>8.1e} {x['order_gauss']!s:>6} "
              f"{x['order_trapezoid']!s:>6}")


if __name__ == "__main__":
    main()
