"""Four-bar synthesis by positions and by points of a path (issue 43: path generation of 10
points <= 5 s on one core, every other synthesis <= 50 ms): each type's design (the task
section -> the generated linkage, what `tmm validate` and `tmm run` do first) timed over
several rounds after one untimed call; wall time and this process's CPU time, medians and
spread. Pin it to one core for the issue's figure: taskset -c 0 python benchmarks/bench_synthesis.py

Run: python benchmarks/bench_synthesis.py [--repeat 3]
"""
from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")     # one core: no BLAS threads
os.environ.setdefault("OMP_NUM_THREADS", "1")
ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import yaml  # noqa: E402

from tmm_cli.linkage.synthesis import design  # noqa: E402
from tmm_cli.schemacache import validator  # noqa: E402
from tmm_cli.task import SynthesisSection  # noqa: E402

TASKS = ("synthesis_positions", "synthesis_function", "synthesis_crank_rocker", "synthesis_offset_slider_crank",
         "synthesis_path")


def section(name: str):
    d = yaml.safe_load((ROOT / "tasks" / f"{name}.yaml").read_text(encoding="utf-8"))
    return validator(SynthesisSection).validate_python(d["synthesis"])


def timed(fn, repeat: int):
    from tmm_cli.linkage import synthesis_path

    fn()                                         # untimed: imports
    wall, cpu = [], []
    for _ in range(repeat):
        synthesis_path._FOUND.clear()            # a path searched anew, not the remembered answer
        w, c = time.perf_counter(), time.process_time()
        fn()
        wall.append(time.perf_counter() - w)
        cpu.append(time.process_time() - c)
    return wall, cpu


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    print(f"cores allowed: {len(os.sched_getaffinity(0))}; load average {os.getloadavg()[0]:.1f}")
    print(f"{'task':34s} {'wall median':>12s} {'cpu median':>11s} {'wall min-max':>18s}")
    for name in TASKS:
        sec = section(name)
        wall, cpu = timed(lambda: design(sec, 1.0), args.repeat if name != "synthesis_path" else max(1, args.repeat))
        print(f"{name:34s} {statistics.median(wall) * 1e3:10.1f} ms {statistics.median(cpu) * 1e3:8.1f} ms "
              f"{min(wall) * 1e3:8.1f}-{max(wall) * 1e3:.1f} ms")


if __name__ == "__main__":
    main()
