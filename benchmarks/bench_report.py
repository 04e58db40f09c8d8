"""Benchmark: the HTML + PDF report.

Run:  python benchmarks/bench_report.py [repeat] [task,task...]
      (budget: < 10 s wall for `tmm run`; the tasks default to the two whole projects below,
      e.g. `1 cam_rocker,gears_shifted,impact_rotor` times the figures of the other chapters)

1. the closed-form 12-position slider-crank of tests/test_report.py (report only);
2. whole-project tasks (kinematics + kinetostatics + flywheel): `tmm run TASK --out DIR`
   wall time (a fresh process, as a student runs it), and the split of the report's
   time into HTML (figures, tables) and PDF, with the PDF engines side by side on the
   same HTML (Typst, the report's engine, and weasyprint, the previous one, where it is
   installed: it is no dependency of tmm any more, `pip install weasyprint` and the
   system's Pango), measured in one process without the helper process.
"""
from __future__ import annotations

import os
import re
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


_SVG = re.compile(r"<svg\b.*?</svg>", re.S)
_W = re.compile(r'\bwidth="([0-9.]+)pt"')


def _svg_as_images(html: str) -> str:
    """For weasyprint: inline <svg> -> <img src="data:image/svg+xml;base64,...">
    (the SVG nodes stay out of the HTML style cascade: about twice as fast)."""
    import base64

    def repl(m):
        s = m.group(0)
        w = _W.search(s[:400])
        style = f' style="width:{w.group(1)}pt"' if w else ""
        return f'<img class="fig"{style} alt="" src="data:image/svg+xml;base64,' \
               f'{base64.b64encode(s.encode("utf-8")).decode("ascii")}">'

    return _SVG.sub(repl, html)


def split(name: str) -> None:
    """Phases of one report in one warm process (no helper), and the two PDF engines
    side by side on the same HTML: weasyprint (layout, paint) and Typst (the report's
    engine: translation to Typst markup, compilation).  CPU seconds (the machine is
    shared: wall time is noisy)."""
    import logging

    import tmm_cli
    import tmm_cli.report as R
    from tmm_cli.report import typst_pdf
    cpu = time.process_time
    task = tmm_cli.load_task(ROOT / "tasks" / f"{name}.yaml")
    t0 = cpu()
    r = tmm_cli.run(task)
    t1 = cpu()
    with tempfile.TemporaryDirectory() as d:
        html, _ = R.render_html(r, task, Path(d), "en")
        t2 = cpu()
        src, files = typst_pdf.to_typst(html)
        t3 = cpu()
        pdf_t = typst_pdf.pdf_bytes(html)
        t4 = cpu()
        try:
            import weasyprint
        except (ImportError, OSError) as exc:        # not installed, or no Pango
            weasyprint = None
            why = (str(exc).strip().splitlines() or [type(exc).__name__])[0]
    if weasyprint is None:
        print(f"  {name}: pipeline {t1 - t0:.2f} s, html {t2 - t1:.2f} s; typst: translate {t3 - t2:.2f} s + "
              f"compile {t4 - t3 - (t3 - t2):.2f} s, {len(pdf_t) / 1e6:.2f} MB (weasyprint not compared: {why})")
        return
    with tempfile.TemporaryDirectory() as d:
        for n in ("weasyprint", "fontTools"):
            logging.getLogger(n).setLevel(logging.ERROR)
        t5 = cpu()
        doc = weasyprint.HTML(string=_svg_as_images(html), base_url=d).render()
        t6 = cpu()
        pdf_w = doc.write_pdf()
        t7 = cpu()
    print(f"  {name}: pipeline {t1 - t0:.2f} s, html {t2 - t1:.2f} s ({html.count('<td')} cells, "
          f"{html.count('<svg')} figures), cpu s")
    print(f"    typst:      translate {t3 - t2:.2f} s + compile {t4 - t3 - (t3 - t2):.2f} s = "
          f"{t4 - t2:.2f} s, {len(pdf_t) / 1e6:.2f} MB")
    print(f"    weasyprint: import {t5 - t4:.2f} s, layout {t6 - t5:.2f} s ({len(doc.pages)} pages), "
          f"paint {t7 - t6:.2f} s = {t7 - t4:.2f} s, {len(pdf_w) / 1e6:.2f} MB")


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


def main(repeat: int = 1, tasks=TASKS) -> float:
    synthetic(repeat)
    worst = 0.0
    for name in tasks:
        worst = max(worst, cli(name, repeat))
        split(name)
    print(f"worst whole-project wall time {worst:.2f} s (budget {BUDGET_S:.0f} s)")
    return worst


if __name__ == "__main__":
    t = main(int(sys.argv[1]) if len(sys.argv) > 1 else 1,
             tuple(sys.argv[2].split(",")) if len(sys.argv) > 2 else TASKS)
    sys.exit(0 if t < BUDGET_S else 1)
