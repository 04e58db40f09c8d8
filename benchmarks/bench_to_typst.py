"""Benchmark: the PDF's translation of the report's HTML to Typst (typst_pdf.to_typst),
this tree against another, in fresh processes taken in turn (the first call of a process,
as in a report run: its caches empty), CPU of the call and of its _read.

Run:  python benchmarks/bench_to_typst.py --against DIR [--task forging_sixbar] [--lang en]
      [--repeat 9]
(DIR: the other tree, e.g. `git -C /work/main archive main | tar -x -C DIR`.)  The HTML is
the one the PDF is made from (render_html + _figure_files, one process, no helper), made
once by this tree.
"""
from __future__ import annotations

import argparse
import os
import statistics as st
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

ONE = """
import sys, time
from tmm_cli.report import typst_pdf as T
html = open(sys.argv[1], encoding="utf-8").read()
reads = []
read = T._read
def timed(h):
    t = time.process_time(); r = read(h); reads.append(time.process_time() - t); return r
T._read = timed
t = time.process_time(); T.to_typst(html, sys.argv[2]); d = time.process_time() - t
print(d, reads[0])
"""


def pdf_html(task: str, lang: str, into: Path) -> Path:
    os.environ["TMM_REPORT_JOBS"] = "1"
    sys.path.insert(0, str(ROOT))
    import tmm_cli
    from tmm_cli.report import _figure_files, render_html
    t = tmm_cli.load_task(ROOT / "tasks" / f"{task}.yaml")
    html, ctx = render_html(tmm_cli.run(t), t, into / "out", lang)
    path = into / "report.html"
    path.write_text(_figure_files(ctx, html)[0], encoding="utf-8")
    return path


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--against", required=True)
    ap.add_argument("--task", default="forging_sixbar")
    ap.add_argument("--lang", default="en")
    ap.add_argument("--repeat", type=int, default=9)
    a = ap.parse_args()
    trees = {"this": str(ROOT), "other": str(Path(a.against).resolve())}
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    with tempfile.TemporaryDirectory() as tmp:
        html = pdf_html(a.task, a.lang, Path(tmp))
        res = {k: [] for k in trees}
        for r in range(a.repeat):
            for k in (("this", "other") if r % 2 == 0 else ("other", "this")):
                out = subprocess.run([sys.executable, "-c", ONE, str(html), a.lang], cwd=tmp, check=True,
                                     env={**env, "PYTHONPATH": trees[k]}, capture_output=True, text=True)
                res[k].append(tuple(map(float, out.stdout.split())))

    def fmt(xs):
        return f"{st.median(xs) * 1e3:.1f} ms [{min(xs) * 1e3:.1f}-{max(xs) * 1e3:.1f}]"

    for k in trees:
        print(f"{k:5s} to_typst {fmt([x for x, _ in res[k]])}  _read {fmt([y for _, y in res[k]])}")
    for i, name in ((0, "to_typst"), (1, "_read")):
        q = [a[i] / b[i] for a, b in zip(res["this"], res["other"])]
        print(f"this / other {name}: {st.median(q):.3f} [{min(q):.3f}-{max(q):.3f}]")


if __name__ == "__main__":
    main()
