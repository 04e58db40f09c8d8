"""`tmm batch` of a group with feedback pages: N variants (default 300) of the shipped crank
press (examples/instructor), each answered by one student, graded with `--format json,html
--jobs 2`. Prints the wall and CPU time of the batch (the variants and answers are made
before the clock starts; CPU: the batch, its workers and their helpers together).

    .venv/bin/python benchmarks/bench_batch_feedback.py [--n 300] [--jobs 2]
    .venv/bin/python benchmarks/bench_batch_feedback.py --n 60 --repeat 3 --against DIR [--diff]

The target: 300 variants within 60 s on 2 free cores. On a shared machine the absolute
times move with the load: ``--against DIR`` (another checkout of tmm, e.g. `git archive
main | tar -x -C DIR`) runs DIR's batch of the same group interleaved with this
checkout's (this, base, this, base, ... ``--repeat`` rounds) and prints each side's
median [min-max] and the ratio this / base of every round; ``--diff`` then compares the
two last output trees file by file (the batch's and the runs' manifests left out: they
hold modification times) and names every file that differs.
"""
from __future__ import annotations

import argparse
import csv
import filecmp
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
EX = ROOT / "examples" / "instructor"
TMM = [sys.executable, "-m", "tmm_cli"]
MANIFESTS = {".tmm-batch.json", ".tmm-manifest.json"}


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
                   check=True, capture_output=True, cwd=ROOT)
    ans = folder / "answers"
    ans.mkdir()
    for i in range(n):
        (ans / f"s{i + 1:03d}.yaml").write_text(
            f"variant: {i + 1}\nstudent: {{name: Student {i + 1:03d}, group: MT-31}}\nanswers:\n"
            "  positions.K: 1.05\n  positions.working_stroke_angle: 186.5\n  flywheel.J: 150\n"
            '  kinematics[1].links.crank.omega: "120 rpm"\n  kinematics[1].points.B.v: 0.6\n', encoding="utf-8")
    return tasks, ans


def _child_cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run_batch(tree: Path, tasks: Path, ans: Path, out: Path, jobs: int, formats: str) -> tuple[float, float, int]:
    """(wall, cpu, exit code) of one `tmm batch` by the checkout ``tree`` (``python -m
    tmm_cli`` run in it takes its tmm_cli) into ``out``."""
    c0, t0 = _child_cpu(), time.perf_counter()
    p = subprocess.run(TMM + ["batch", str(tasks), "--answers", str(ans), "--out", str(out),
                              "--format", formats, "--jobs", str(jobs)], capture_output=True, text=True, cwd=tree)
    wall, cpu = time.perf_counter() - t0, _child_cpu() - c0
    if p.returncode not in (0, 1):           # 1: some answers outside their tolerance (expected)
        raise SystemExit(f"{tree}: tmm batch failed ({p.returncode}):\n{p.stderr[-2000:]}")
    return wall, cpu, p.returncode


def differing(a: Path, b: Path) -> list[str]:
    """The files (relative paths) that differ between the trees ``a`` and ``b``, or that only
    one has; the manifests left out."""
    def files(root: Path) -> set[str]:
        return {p.relative_to(root).as_posix() for p in root.rglob("*")
                if p.is_file() and p.name not in MANIFESTS}
    fa, fb = files(a), files(b)
    out = sorted(fa ^ fb)
    out += sorted(r for r in fa & fb if not filecmp.cmp(a / r, b / r, shallow=False))
    return out


def _stat(xs: list[float]) -> str:
    return f"{statistics.median(xs):6.2f} [{min(xs):.2f}-{max(xs):.2f}]"


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=300)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--format", default="json,html")
    ap.add_argument("--repeat", type=int, default=1, help="rounds (each: this checkout, then DIR's)")
    ap.add_argument("--against", metavar="DIR", help="another checkout of tmm, timed in the same rounds")
    ap.add_argument("--diff", action="store_true", help="with --against: compare the two output trees")
    a = ap.parse_args()
    trees = {"this": ROOT}
    if a.against:
        trees["base"] = Path(a.against).resolve()
    print(f"{os.cpu_count()} cores, load average {os.getloadavg()[0]:.2f}; {a.n} variants, --jobs {a.jobs}, "
          f"--format {a.format}, {a.repeat} round(s)")
    with tempfile.TemporaryDirectory(prefix="tmm-bench-batch-") as d:
        tasks, ans = make_group(Path(d), a.n)
        times: dict[str, list[tuple[float, float]]] = {k: [] for k in trees}
        for r in range(a.repeat):
            for tag, tree in trees.items():
                out = Path(d) / f"graded-{tag}-{r}"
                wall, cpu, code = run_batch(tree, tasks, ans, out, a.jobs, a.format)
                pages = len(list(out.rglob("feedback-*.html")))
                times[tag].append((wall, cpu))
                print(f"  round {r + 1} {tag:4s}: {wall:6.1f} s wall, {cpu:6.1f} s CPU "
                      f"({wall / a.n:.3f} s a variant; {pages} feedback pages; exit {code})", flush=True)
        for tag, v in times.items():
            print(f"{tag:4s} wall {_stat([w for w, _ in v])} s   CPU {_stat([c for _, c in v])} s")
        if "base" in times:
            for i, kind in ((0, "wall"), (1, "CPU")):
                ratios = [x[i] / y[i] for x, y in zip(times["this"], times["base"])]
                print(f"this / base ({kind}): median {statistics.median(ratios):.3f} "
                      f"[{min(ratios):.3f}-{max(ratios):.3f}]")
            if a.diff:
                last = a.repeat - 1
                diff = differing(Path(d) / f"graded-this-{last}", Path(d) / f"graded-base-{last}")
                print(f"output trees: {'the same, file by file (manifests left out)' if not diff else ''}"
                      f"{f'{len(diff)} files differ:' if diff else ''}")
                for r in diff[:50]:
                    print(f"  {r}")


if __name__ == "__main__":
    main()
