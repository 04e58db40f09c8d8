"""Benchmark: the explanatory note (`--format note`) of every example.

Run:  python benchmarks/bench_note.py [--lang ru] [--repeat 3] [TASK.yaml ...]

For each task (default: every tasks/*.yaml) the results and the report's HTML are made once,
then the note is compiled ``repeat`` times in this process (after one warm-up compile, so
the Typst engine's first load is not counted against the first task): the figure is the
best time of ``note.pdf_bytes`` (HTML -> Typst source -> PDF), beside the time of the report's
own PDF from the same HTML (``report._pdf_bytes``) measured in the same loop, so the ratio is
meaningful on a busy machine. The budget is 2 s per note.
"""
from __future__ import annotations

import argparse
import os
import re
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
os.environ.setdefault("SOURCE_DATE_EPOCH", "1700000000")

BUDGET_S = 2.0


def _best(fn, repeat: int) -> tuple[float, object]:
    best, out = float("inf"), None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def _pages(pdf: bytes) -> int:
    """The page count (pdfinfo from poppler-utils where present; else -1)."""
    import shutil
    import subprocess
    if not shutil.which("pdfinfo"):
        return -1
    out = subprocess.run(["pdfinfo", "-"], input=pdf, capture_output=True, check=False).stdout.decode()
    m = re.search(r"^Pages:\s+(\d+)", out, re.M)
    return int(m.group(1)) if m else -1


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("tasks", nargs="*", type=Path)
    ap.add_argument("--lang", default="ru", choices=("en", "ru", "uk"))
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args(argv)

    from tmm_cli import numfmt, pipeline, report
    from tmm_cli.report import note
    from tmm_cli.task import load_task

    tasks = a.tasks or sorted((ROOT / "tasks").glob("*.yaml"))
    warm = False
    worst = 0.0
    print(f"{'task':34s} {'pages':>5s} {'note, s':>8s} {'report.pdf, s':>13s} {'ratio':>6s}")
    for path in tasks:
        task = load_task(path)
        results = pipeline.run_listed(task)
        with tempfile.TemporaryDirectory() as d, numfmt.language(a.lang):
            html, ctx = report.render_html(results, task, Path(d), a.lang)
            if not warm:
                note.pdf_bytes(html, ctx.results, ctx.task, a.lang)
                warm = True
            t_note, pdf = _best(lambda: note.pdf_bytes(html, ctx.results, ctx.task, a.lang), a.repeat)
            t_rep, _ = _best(lambda: report._pdf_bytes(html, a.lang), a.repeat)
        pages = _pages(pdf)
        worst = max(worst, t_note)
        print(f"{path.stem:34s} {pages:5d} {t_note:8.2f} {t_rep:13.2f} {t_note / t_rep:6.2f}")
    print(f"slowest note: {worst:.2f} s (budget {BUDGET_S:.0f} s): {'within' if worst <= BUDGET_S else 'OVER'}")
    return 0 if worst <= BUDGET_S else 1


if __name__ == "__main__":
    sys.exit(main())
