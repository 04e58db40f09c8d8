"""Benchmark: full HTML + PDF report of a 12-position slider-crank task.

Run:  python benchmarks/bench_report.py   (budget: < 10 s for html + pdf)
Uses the closed-form slider-crank results of tests/test_report.py, so it does
not depend on the kinematics stage.
"""
from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT), str(ROOT / "tests")]

BUDGET_S = 10.0


def main(repeat: int = 1) -> float:
    from test_report import make_task, slider_crank_results
    from tmm_cli.report import render

    results, task = slider_crank_results(12), make_task()
    best = float("inf")
    for _ in range(repeat):
        with tempfile.TemporaryDirectory() as d:
            t0 = time.perf_counter()
            paths = render(results, task, Path(d), {"html", "pdf"}, "ru")
            dt = time.perf_counter() - t0
            sizes = {p.name: p.stat().st_size for p in paths}
        best = min(best, dt)
        print(f"report html+pdf, 12 positions: {dt:.2f} s  {sizes}")
    print(f"best {best:.2f} s (budget {BUDGET_S:.0f} s)")
    return best


if __name__ == "__main__":
    t = main(int(sys.argv[1]) if len(sys.argv) > 1 else 1)
    sys.exit(0 if t < BUDGET_S else 1)
