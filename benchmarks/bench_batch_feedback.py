"""`tmm batch` of a group with feedback pages: N variants (default 300) of the shipped crank
press (examples/instructor), each answered by one student, graded with `--format json,html
--jobs 2`. Prints the wall time of the batch (the variants and answers are made before the
clock starts).

    .venv/bin/python benchmarks/bench_batch_feedback.py [--n 300] [--jobs 2]

The target: 300 variants within 60 s on 2 free cores. On a shared machine compare runs side
by side (the same N, one after the other) and report their ratio.
"""
from __future__ import annotations

import argparse
import csv
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
EX = ROOT / "examples" / "instructor"
TMM = [sys.executable, "-m", "tmm_cli"]


def make_group(folder: Path, n: int) -> tuple[Path, Path]:
    """N variants (the shipped table's rows in turn, numbered 1..N) and an answers file each."""
    with open(EX / "press_variants.csv", encoding="utf-8-sig", newline="") as fh:
        rows = list(csv.reader(fh, delimiter=";"))
    head, body = rows[0], rows[1:]
    vi = head.index("variant")
    table = folder / "table.csv"
    with open(table, "w", encoding="utf-8", newline="") as fh:
        w = csv.writer(fh, delimiter=";")
        w.writerow(head)
        for i in range(n):
            r = list(body[i % len(body)])
            r[vi] = str(i + 1)
            w.writerow(r)
    tasks = folder / "tasks"
    subprocess.run(TMM + ["variants", str(EX / "press_template.yaml"), str(table), "--out", str(tasks)],
                   check=True, capture_output=True)
    ans = folder / "answers"
    ans.mkdir()
    for i in range(n):
        (ans / f"s{i + 1:03d}.yaml").write_text(
            f"variant: {i + 1}\nstudent: {{name: Student {i + 1:03d}, group: MT-31}}\nanswers:\n"
            "  positions.K: 1.05\n  positions.working_stroke_angle: 186.5\n  flywheel.J: 150\n"
            '  kinematics[1].links.crank.omega: "120 rpm"\n  kinematics[1].points.B.v: 0.6\n', encoding="utf-8")
    return tasks, ans


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=300)
    ap.add_argument("--jobs", type=int, default=2)
    a = ap.parse_args()
    with tempfile.TemporaryDirectory(prefix="tmm-bench-batch-") as d:
        tasks, ans = make_group(Path(d), a.n)
        t0 = time.perf_counter()
        p = subprocess.run(TMM + ["batch", str(tasks), "--answers", str(ans), "--out", str(Path(d) / "graded"),
                                  "--format", "json,html", "--jobs", str(a.jobs)], capture_output=True, text=True)
        wall = time.perf_counter() - t0
        pages = len(list((Path(d) / "graded").rglob("feedback-*.html")))
    print(f"{a.n} variants, {pages} feedback pages, --jobs {a.jobs}: {wall:.1f} s "
          f"({wall / a.n:.3f} s a variant; exit {p.returncode})")


if __name__ == "__main__":
    main()
