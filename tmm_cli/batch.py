"""`tmm batch`: run and check many variants; one failure never stops the rest."""
from __future__ import annotations

import csv
import glob
import html
import io
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

from .errors import StageError, TaskError

CODES = {"ok": 0, "wrong": 1, "invalid": 2, "failed": 3}
FIELDS = ["file", "title", "variant", "student", "group", "status", "answers", "correct", "worst_quantity",
          "worst_error", "seconds", "message"]


def find_tasks(source: str) -> list[Path]:
    p = Path(source)
    if p.is_dir():
        files = sorted(list(p.glob("*.yaml")) + list(p.glob("*.yml")))
    else:
        files = sorted(Path(f) for f in glob.glob(source, recursive=True))
    return [f for f in files if f.is_file()]


def one(path: Path, out: Path, formats: set[str], lang: str) -> dict:
    """Run one variant; never raises. Returns its summary row."""
    from .check import check_task, rows_csv
    from .io import atomic_write
    from .results import dumps

    t0 = time.perf_counter()
    row = {k: "" for k in FIELDS}
    row["file"] = str(path)
    vout = out / path.stem
    try:
        from .pipeline import PartialResults, run
        from .task import load_task
        task = load_task(path)
        row["title"] = task.title
        row["variant"] = "" if task.variant is None else str(task.variant)
        if task.student is not None:
            row["student"] = task.student.name or ""
            row["group"] = task.student.group or ""
        try:
            results = run(task)
        except PartialResults as exc:
            atomic_write(vout / "results.json", dumps(exc.partial))
            raise
        from .cli import write_outputs
        write_outputs(task, results, vout, formats, lang)
        if task.answers:
            rows = check_task(results, dict(task.answers), dict(task.tolerance))
            atomic_write(vout / "check.csv", rows_csv(rows))
            ok = [r for r in rows if r["verdict"] == "ok"]
            row["answers"], row["correct"] = len(rows), len(ok)
            errs = [r for r in rows if r["rel_error"] is not None]
            if errs:
                worst = max(errs, key=lambda r: r["rel_error"] / max(r["tolerance"], 1e-300))
                row["worst_quantity"], row["worst_error"] = worst["quantity"], f"{worst['rel_error']:.4g}"
            row["status"] = "ok" if len(ok) == len(rows) else "wrong"
            if row["status"] == "wrong":
                bad = [r["quantity"] for r in rows if r["verdict"] != "ok"]
                row["message"] = "outside tolerance: " + ", ".join(bad)
        else:
            row["status"] = "ok"
            row["message"] = "computed (no answers to check)"
    except TaskError as exc:
        row["status"], row["message"] = "invalid", exc.render().replace("\n", "; ")
    except StageError as exc:
        row["status"], row["message"] = "failed", str(exc)
    except Exception as exc:  # one broken variant must not stop the batch
        row["status"], row["message"] = "failed", f"internal error: {type(exc).__name__}: {exc}"
    row["seconds"] = f"{time.perf_counter() - t0:.2f}"
    return row


def _one_star(args):
    return one(*args)


def summary_csv(rows: list[dict]) -> str:
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=FIELDS, lineterminator="\n")
    w.writeheader()
    for r in rows:
        w.writerow(r)
    return buf.getvalue()


def summary_html(rows: list[dict], source: str) -> str:
    colour = {"ok": "#dff0d8", "wrong": "#fcf8e3", "invalid": "#f2dede", "failed": "#f2dede"}
    head = "".join(f"<th>{html.escape(f)}</th>" for f in FIELDS)
    body = []
    for r in rows:
        cells = "".join(f"<td>{html.escape(str(r[f]))}</td>" for f in FIELDS)
        body.append(f'<tr style="background:{colour.get(r["status"], "#fff")}">{cells}</tr>')
    counts = {s: sum(r["status"] == s for r in rows) for s in CODES}
    stat = ", ".join(f"{k}: {v}" for k, v in counts.items())
    return ("<!DOCTYPE html><html><head><meta charset='utf-8'><title>tmm batch summary</title>"
            "<style>body{font-family:sans-serif}table{border-collapse:collapse;font-size:13px}"
            "td,th{border:1px solid #999;padding:3px 6px;text-align:left}</style></head><body>"
            f"<h1>tmm batch: {html.escape(source)}</h1><p>{len(rows)} variants; {stat}</p>"
            f"<table><tr>{head}</tr>{''.join(body)}</table></body></html>\n")


def run_batch(source: str, out: Path, *, jobs: int = 1, formats: set[str] = frozenset({"json"}),
              lang: str = "en") -> int:
    from rich.console import Console
    from rich.progress import Progress

    from .io import atomic_write

    con = Console(stderr=True)
    files = find_tasks(source)
    if not files:
        con.print(f"error: no task files match '{source}'")
        return 2
    out.mkdir(parents=True, exist_ok=True)
    rows: list[dict] = []
    with Progress(console=con, transient=True) as prog:
        bar = prog.add_task("variants", total=len(files))
        if jobs > 1:
            with ProcessPoolExecutor(max_workers=jobs) as ex:
                for row in ex.map(_one_star, [(f, out, set(formats), lang) for f in files]):
                    rows.append(row)
                    prog.advance(bar)
        else:
            for f in files:
                rows.append(one(f, out, set(formats), lang))
                prog.advance(bar)
    atomic_write(out / "summary.csv", summary_csv(rows))
    atomic_write(out / "summary.html", summary_html(rows, source))
    from rich.table import Table
    t = Table(title=f"tmm batch: {len(rows)} variants")
    for c in ("file", "status", "answers", "correct", "message"):
        t.add_column(c)
    for r in rows:
        t.add_row(r["file"], r["status"], str(r["answers"]), str(r["correct"]), r["message"][:80])
    Console().print(t)
    Console().print(f"wrote {out / 'summary.csv'} and {out / 'summary.html'}")
    return max(CODES.get(r["status"], 3) for r in rows)
