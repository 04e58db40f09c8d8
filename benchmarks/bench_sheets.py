"""Benchmark: the A1 drawing sheets (`tmm run TASK --format ...,sheets`).

Run:  python benchmarks/bench_sheets.py [repeat]        (budget: the sheets add < 3 s to a run)

1. `tmm run TASK --format json,html,pdf` and the same with `,sheets`, each a fresh
   process as a student runs it, interleaved, best of `repeat`: the difference is what
   the sheets add to a run;
2. in one warm process, the phases of the sheets: building the primitives, SVG, DXF
   and the PDF (weasyprint), wall and CPU time (CPU time does not count the waits for
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


def one_run(task: str, fmt: str) -> float:
    with tempfile.TemporaryDirectory() as d:
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-m", "tmm_cli", "run", str(ROOT / "tasks" / f"{task}.yaml"), "--out", d,
                        "--format", fmt, "--quiet"], check=True, cwd=ROOT)
        return time.perf_counter() - t0


def added(task: str, repeat: int) -> float:
    base = sheets = float("inf")
    for _ in range(repeat):
        base = min(base, one_run(task, "json,html,pdf"))
        sheets = min(sheets, one_run(task, "json,html,pdf,sheets"))
    print(f"{task}: tmm run json,html,pdf {base:.2f} s; with sheets {sheets:.2f} s; "
          f"added {sheets - base:+.2f} s")
    return sheets - base


def phases(task: str) -> float:
    import ezdxf  # noqa: F401  (imported once, as in a run)
    import weasyprint  # noqa: F401

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
    worst_cpu = max(phases(t) for t in TASKS)
    worst = max(added(t, repeat) for t in TASKS)
    ok = worst <= BUDGET_S
    print(f"the sheets add at most {worst:.2f} s wall ({worst_cpu:.2f} s cpu) to a run: "
          f"{'within' if ok else 'OVER'} the {BUDGET_S:g} s budget")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
