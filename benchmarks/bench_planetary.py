"""Planetary synthesis at z_max = 300 (issue 12, target <= 0.1 s for every scheme A-D):
the whole stage (synthesize_planetary(...).to_dict()) timed interleaved with the full
enumeration of the same search (every (z1, z2, z3) of the grid checked against every
condition, the reference the tests compare the pruned search with), >= 5 rounds; medians,
spread (min-max) and their ratio.

Run: python benchmarks/bench_planetary.py [--repeat 5]
"""
from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path
from types import SimpleNamespace as NS

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from tmm_cli.gears import planetary as P  # noqa: E402
from tmm_cli.gears import synthesize_planetary  # noqa: E402

CASES = {
    "A  i=3.24  k=3": NS(scheme="A", ratio=3.24, satellites=3, tolerance=0.05, z_max=300),
    "B  i=12    k=3": NS(scheme="B", ratio=12.0, satellites=3, tolerance=0.05, z_max=300),
    "C  i=-2.24 k=3": NS(scheme="C", ratio=-2.24, satellites=3, tolerance=0.05, z_max=300),
    "D  i=0.1   k=3": NS(scheme="D", ratio=0.1, satellites=3, tolerance=0.05, z_max=300),
    "C  i=0.3   k=3 (81,000 feasible sets)": NS(scheme="C", ratio=0.3, satellites=3, tolerance=0.05, z_max=300),
}


def _t(fn) -> float:
    t0 = time.perf_counter()
    fn()
    return time.perf_counter() - t0


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=5)
    n = max(5, ap.parse_args().repeat)
    synthesize_planetary(CASES["A  i=3.24  k=3"])                    # warm-up
    print(f"planetary synthesis, z_max = 300, {n} interleaved rounds; ms: median [min-max]")
    for name, sp in CASES.items():
        stage, full = [], []
        for _ in range(n):
            stage.append(_t(lambda: synthesize_planetary(sp).to_dict()))
            full.append(_t(lambda: P._candidates(sp.scheme, sp.ratio, sp.tolerance, sp.satellites,
                                                 P.Limits(), 300, prune=False)))
        r = [b / a for a, b in zip(stage, full)]
        med = statistics.median(stage)
        print(f"  {name:40s} stage {med * 1e3:7.1f} [{min(stage) * 1e3:.1f}-{max(stage) * 1e3:.1f}]"
              f"   full enumeration {statistics.median(full) * 1e3:7.1f}   speed-up {statistics.median(r):5.1f}"
              f" [{min(r):.1f}-{max(r):.1f}]   (target <= 100 ms) {'ok' if med <= 0.1 else 'OVER'}")


if __name__ == "__main__":
    main()
