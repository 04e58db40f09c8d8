"""Benchmark: gears stage (geometry + checks + rack-generated teeth + blocking contour) and
planetary synthesis.

Run:  python benchmarks/bench_gears.py      (median of 10 runs per case)
"""
from __future__ import annotations

import statistics
import time
from types import SimpleNamespace as NS

from tmm_cli.gears import ainv, analyze, synthesize_planetary

import numpy as np

GEARS = {
    "shifted pair 12/42 (high shifts)": NS(m=0.003, z=(12, 42), x=(0.63, 0.67)),
    "zero shift 12/30 (undercut)": NS(m=0.003, z=(12, 30), x=(0.0, 0.0)),
    "x: auto, equal_sliding": NS(m=0.003, z=(12, 42), x="auto", rule="equal_sliding"),
    "x: auto, table (moved into contour)": NS(m=0.002, z=(8, 60), x="auto", rule="table"),
}
PLANETARY = {
    "A  i=3.24 k=3": NS(scheme="A", ratio=3.24, satellites=3, tolerance=0.05),
    "B  i=12   k=3": NS(scheme="B", ratio=12.0, satellites=3, tolerance=0.05),
    "C  i=-2.24 k=3": NS(scheme="C", ratio=-2.24, satellites=3, tolerance=0.05),
    "D  i=0.1  k=3": NS(scheme="D", ratio=0.1, satellites=3, tolerance=0.05),
}


def median_time(fn, n=10):
    ts = []
    for _ in range(n):
        t = time.perf_counter()
        fn()
        ts.append(time.perf_counter() - t)
    return statistics.median(ts)


def main() -> None:
    analyze(GEARS["shifted pair 12/42 (high shifts)"]).to_dict()      # warm-up (imports)
    v = np.random.default_rng(1).uniform(1e-6, 0.7, 1_000_000)
    print(f"inverse involute, 1e6 values: {median_time(lambda: ainv(v), 3) * 1e3:8.1f} ms")
    print(f"{'gears case':40s} {'median, ms':>11s}")
    for name, sp in GEARS.items():
        print(f"{name:40s} {median_time(lambda: analyze(sp).to_dict()) * 1e3:11.1f}")
    print(f"{'planetary case':40s} {'median, ms':>11s}")
    for name, sp in PLANETARY.items():
        print(f"{name:40s} {median_time(lambda: synthesize_planetary(sp).to_dict(), 3) * 1e3:11.1f}")


if __name__ == "__main__":
    main()
