"""Benchmark: the A1 drawing sheets (`tmm run TASK --format ...,sheets`).

Run:  python benchmarks/bench_sheets.py [repeat]        (budget: the sheets add < 3 s to a run)

1. `tmm run TASK --format json,html,pdf` and the same with `,sheets`, each a fresh
   process as a student runs it, interleaved, best of `repeat`: the difference is what
   the sheets add to a run, in wall time and in CPU time (user + system of the run and
   its helper process: the cost itself, where a busy machine makes the wall time wait);
2. in one warm process, the phases of the sheets: building the primitives, SVG, DXF
   and the PDF (Typst), wall and CPU time (CPU time does not count the waits for
   a busy machine's other processes).
"""
from __future__ import annotations

import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT)]

BUDGET_S = 3.0
TASKS = ("forging_sixbar", "cam_offset", "gears_shifted")


def one_run(task: str, fmt: str) -> tuple[float, float]:
    """(wall, cpu) seconds of one `tmm run` (cpu: user + system of the process and the
    report's helper process it forks, as the kernel counts them)."""
    import resource
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    with tempfile.TemporaryDirectory() as d:
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-m", "tmm_cli", "run", str(ROOT / "tasks" / f"{task}.yaml"), "--out", d,
                        "--format", fmt, "--quiet"], check=True, cwd=ROOT)
        wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def added(task: str, repeat: int) -> tuple[float, float]:
    base = sheets = (float("inf"), float("inf"))
    for _ in range(repeat):
        b, s = one_run(task, "json,html,pdf"), one_run(task, "json,html,pdf,sheets")
        base = (min(base[0], b[0]), min(base[1], b[1]))
        sheets = (min(sheets[0], s[0]), min(sheets[1], s[1]))
    print(f"{task}: tmm run json,html,pdf {base[0]:.2f} s wall, {base[1]:.2f} s cpu; with sheets "
          f"{sheets[0]:.2f} s wall, {sheets[1]:.2f} s cpu; added {sheets[0] - base[0]:+.2f} s wall, "
          f"{sheets[1] - base[1]:+.2f} s cpu")
    return sheets[0] - base[0], sheets[1] - base[1]


def phases(task: str) -> float:
    import ezdxf  # noqa: F401  (imported once, as in a run)

    import tmm_cli
    from tmm_cli.sheets import build_sheets
    from tmm_cli.sheets.frame import SHEET_H, SHEET_W
    from tmm_cli.sheets.writers import to_dxf, to_pdf, to_svg
    t = tmm_cli.load_task(ROOT / "tasks" / f"{task}.yaml")
    r = tmm_cli.run(t)
    marks = [(time.perf_counter(), time.process_time())]
    sheets = build_sheets(r, t, "en")
    marks.append((time.perf_counter(), time.process_time()))
    svgs = [to_svg(cv) for cv, _ in sheets]
    marks.append((time.perf_counter(), time.process_time()))
    for cv, _ in sheets:
        to_dxf(cv)
    marks.append((time.perf_counter(), time.process_time()))
    to_pdf(svgs, SHEET_W, SHEET_H)
    marks.append((time.perf_counter(), time.process_time()))
    names = ("build", "svg", "dxf", "pdf")
    parts = ", ".join(f"{n} {b[0] - a[0]:.2f} s (cpu {b[1] - a[1]:.2f})" for n, a, b in zip(names, marks, marks[1:]))
    total = marks[-1][1] - marks[0][1]
    print(f"{task}: {len(sheets)} sheets: {parts}; cpu total {total:.2f} s")
    return total


def main() -> int:
    repeat = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    for t in TASKS:
        phases(t)
    runs = [added(t, repeat) for t in TASKS]
    wall, cpu = max(r[0] for r in runs), max(r[1] for r in runs)
    # on a shared machine the wall time waits for the other processes: the CPU time is the
    # cost of the sheets themselves (on an idle 2-core machine wall ~ cpu for this serial part)
    ok = cpu <= BUDGET_S
    print(f"the sheets add at most {cpu:.2f} s cpu ({wall:.2f} s wall on this machine now) to a run: "
          f"{'within' if ok else 'OVER'} the {BUDGET_S:g} s budget")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
