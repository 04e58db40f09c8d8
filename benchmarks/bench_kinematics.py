"""Benchmark: kinematics of the six-bar (tasks/forging_sixbar.yaml) at 10^5 positions.

Prints wall time, CPU time and the peak memory traced by tracemalloc (numpy arrays
are traced). Targets: < 0.2 s, < 200 MB.
"""
from __future__ import annotations

import sys
import time
import tracemalloc
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from tmm_cli.linkage.kinematics import solve  # noqa: E402
from tmm_cli.linkage.mechanism import build_mechanism  # noqa: E402
from tmm_cli.task import load_task  # noqa: E402


def main(n: int = 100_000, repeat: int = 5) -> None:
    m = build_mechanism(load_task(ROOT / "tasks" / "forging_sixbar.yaml"))
    phi = np.linspace(0.0, 360.0, n, endpoint=False)
    solve(m, phi[:10], 5.236)                  # closures chosen once (cached per mechanism)
    walls, cpus = [], []
    for _ in range(repeat):
        t0, c0 = time.perf_counter(), time.process_time()
        solve(m, phi, 5.236)
        walls.append(time.perf_counter() - t0)
        cpus.append(time.process_time() - c0)
    tracemalloc.start()
    solve(m, phi, 5.236)
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    print(f"kinematics six-bar, {n} positions: wall best {min(walls):.3f} s (median {np.median(walls):.3f} s), "
          f"cpu best {min(cpus):.3f} s, peak traced memory {peak / 2**20:.1f} MB")


if __name__ == "__main__":
    main()
