"""Benchmark: the HTML + PDF report.

Run:  python benchmarks/bench_report.py [repeat]      (budget: < 10 s wall for `tmm run`)

1. the closed-form 12-position slider-crank of tests/test_report.py (report only);
2. whole-project tasks (kinematics + kinetostatics + flywheel): `tmm run TASK --out DIR`
   wall time (a fresh process, as a student runs it), and the split of the report's
   time into HTML (figures, tables), weasyprint layout and paint, measured in one
   process without the helper process.
"""
from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT), str(ROOT / "tests")]

BUDGET_S = 10.0
TASKS = ("forging_sixbar", "shaper_slotted_lever")


def synthetic(repeat: int) -> float:
    from test_report import make_task, slider_crank_results
    from tmm_cli.report import render

    results, task = slider_crank_results(12), make_task()
    best = float("inf")
    for _ in range(repeat):
        with tempfile.TemporaryDirectory() as d:
            t0 = time.perf_counter()
            paths = render(results, task, Path(d), {"html", "pdf"}, "ru")
            dt = time.perf_counter() - t0
            sizes = {p.name: p.stat().st_size for p in paths if p.suffix in (".html", ".pdf")}
        best = min(best, dt)
    print(f"slider-crank, 12 positions, report html+pdf: best {best:.2f} s  {sizes}")
    return best


def split(name: str) -> None:
    """Phases of one report in one warm process (no helper; imports already done)."""
    import logging

    import tmm_cli
    import tmm_cli.report as R
    task = tmm_cli.load_task(ROOT / "tasks" / f"{name}.yaml")
    t0 = time.perf_counter()
    r = tmm_cli.run(task)
    t1 = time.perf_counter()
    with tempfile.TemporaryDirectory() as d:
        html, _ = R.render_html(r, task, Path(d), "en")
        t2 = time.perf_counter()
        import weasyprint
        for n in ("weasyprint", "fontTools"):
            logging.getLogger(n).setLevel(logging.ERROR)
        t3 = time.perf_counter()
        doc = weasyprint.HTML(string=R._svg_as_images(html), base_url=d).render()
        t4 = time.perf_counter()
        doc.write_pdf()
        t5 = time.perf_counter()
    print(f"  {name}: pipeline {t1 - t0:.2f} s, html {t2 - t1:.2f} s ({html.count('<td')} cells, "
          f"{html.count('<svg')} figures), weasyprint import {t3 - t2:.2f} s, layout {t4 - t3:.2f} s "
          f"({len(doc.pages)} pages), paint {t5 - t4:.2f} s")


def cli(name: str, repeat: int) -> float:
    best = float("inf")
    for _ in range(repeat):
        with tempfile.TemporaryDirectory() as d:
            t0 = time.perf_counter()
            subprocess.run([sys.executable, "-m", "tmm_cli", "run", str(ROOT / "tasks" / f"{name}.yaml"),
                            "--quiet", "--out", d], check=True, cwd=str(ROOT),
                           env={**os.environ, "PYTHONPATH": str(ROOT)})
            best = min(best, time.perf_counter() - t0)
    print(f"tmm run {name} (json + html + pdf): best {best:.2f} s wall (budget {BUDGET_S:.0f} s)")
    return best


def main(repeat: int = 1) -> float:
    synthetic(repeat)
    worst = 0.0
    for name in TASKS:
        worst = max(worst, cli(name, repeat))
        split(name)
    print(f"worst whole-project wall time {worst:.2f} s (budget {BUDGET_S:.0f} s)")
    return worst


if __name__ == "__main__":
    t = main(int(sys.argv[1]) if len(sys.argv) > 1 else 1)
    sys.exit(0 if t < BUDGET_S else 1)
