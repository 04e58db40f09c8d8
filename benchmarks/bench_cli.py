"""Process wall time of the command line (targets from issue 2):

* `tmm validate` of one task: under 0.5 s (lazy imports);
* `tmm run --format json` of a 12-position task: under 1.5 s;
* the full HTML + PDF report: under 10 s.

Run: python benchmarks/bench_cli.py [TASK.yaml]   (median of 5 runs; 3 for the report)
"""
from __future__ import annotations

import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def wall(args: list[str], repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        p = subprocess.run([sys.executable, "-m", "tmm_cli", *args], capture_output=True, text=True)
        times.append(time.perf_counter() - t0)
        if p.returncode != 0:
            raise SystemExit(f"tmm {' '.join(args)} failed ({p.returncode}):\n{p.stderr}")
    return statistics.median(times)


def main() -> None:
    task = sys.argv[1] if len(sys.argv) > 1 else str(ROOT / "tasks" / "engine_slider_crank.yaml")
    with tempfile.TemporaryDirectory() as tmp:
        rows = [
            ("tmm validate (schema + assembly)", wall(["validate", task], 5), 0.5),
            ("tmm run --format json", wall(["run", task, "--format", "json", "--quiet", "--out", tmp], 5), 1.5),
            ("tmm run (json + html + pdf)", wall(["run", task, "--quiet", "--out", tmp], 3), 10.0),
        ]
    print(f"task: {Path(task).name}")
    print(f"{'command':40s} {'median wall, s':>15s} {'target, s':>10s}")
    for name, t, target in rows:
        flag = "ok" if t <= target else "SLOW"
        print(f"{name:40s} {t:15.3f} {target:10.1f}  {flag}")


if __name__ == "__main__":
    main()
