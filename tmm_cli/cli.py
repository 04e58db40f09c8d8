"""The `tmm` command line (README, *Commands*).

Exit codes: 0 success; 1 answers outside tolerance; 2 invalid task (file, line and
field named, no traceback); 3 a stage failed on valid input (stage and position named).
"""
from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import List, Optional

import typer

from .errors import StageError, TaskError

app = typer.Typer(
    name="tmm",
    help=("Course-project calculator for the Theory of Machines and Mechanisms (TMM): "
          "structural analysis, 12-position kinematics with velocity and acceleration plans, "
          "kinetostatics with the Zhukovsky lever, the flywheel by the energy-mass method, cam "
          "synthesis, involute gears and planetary synthesis - from one YAML task file.\n\n"
          "Start with `tmm new full` (a commented task), `tmm fields` (every task-file field) and "
          "`tmm run TASK.yaml`.\n\n"
          "Exit codes: 0 success; 1 answers outside tolerance; 2 invalid task; 3 a stage failed."),
    invoke_without_command=True,
    add_completion=False,
    pretty_exceptions_enable=False,
    rich_markup_mode=None,
)

EXIT_OK, EXIT_ANSWERS, EXIT_INVALID, EXIT_STAGE = 0, 1, 2, 3
FORMATS = {"json", "html", "pdf", "sheets"}


def _version(value: bool) -> None:
    if value:
        from . import __version__
        typer.echo(f"tmm {__version__}")
        raise typer.Exit(EXIT_OK)


@app.callback()
def _root(ctx: typer.Context,
          version: bool = typer.Option(False, "--version", callback=_version, is_eager=True,
                                       help="print the version and exit")) -> None:
    # `tmm` with no command: the help, and success (it is what the user asked for)
    if ctx.invoked_subcommand is None:
        typer.echo(ctx.get_help())
        raise typer.Exit(EXIT_OK)


def _err(msg: str) -> None:
    typer.echo(msg, err=True)


def _fail_task(exc: TaskError) -> "typer.Exit":
    _err(f"error: invalid task\n{exc.render()}")
    return typer.Exit(EXIT_INVALID)


def _fail_stage(exc: StageError, file: str | None = None) -> "typer.Exit":
    where = f"{file}: " if file else ""
    _err(f"error: {where}{exc}")
    return typer.Exit(EXIT_STAGE)


def _fail_write(exc: OSError) -> "typer.Exit":
    """The output folder or a file in it cannot be written (--out names a file, no
    permission, disk full): the writing stage failed, exit 3, no traceback."""
    where = exc.filename if exc.filename is not None else ""
    reason = exc.strerror or str(exc)
    if isinstance(exc, (FileExistsError, NotADirectoryError)):
        reason += " (a file is in the way of the output folder)"
    _err(f"error: stage 'output' failed: cannot write {where}: {reason}")
    return typer.Exit(EXIT_STAGE)


def _load(path: Path):
    from .task import load_task
    return load_task(path)


def _parse_formats(text: str) -> set[str]:
    fm = {f.strip().lower() for f in text.split(",") if f.strip()}
    bad = fm - FORMATS
    if bad or not fm:
        raise typer.BadParameter(f"unknown format(s) {', '.join(sorted(bad)) or '(none)'}; "
                                 f"choose from json, html, pdf, sheets (comma-separated)")
    return fm


def write_outputs(task, results: dict, out: Path, formats: set[str], lang: str,
                  notes: list[str] | None = None) -> list[Path]:
    """results.json and the reports, each written atomically; the run's manifest in
    `out` then lists them, and the files of the previous run into `out` that were not
    written again are removed (tmm_cli.io.Manifest).  `notes` receives one line per
    output skipped (the PDF where its engine cannot run)."""
    from .io import Manifest, atomic_write
    from .results import dumps

    manifest = Manifest(out)
    written = []
    if "json" in formats or True:  # results.json is always written: the reports are made from it
        written.append(atomic_write(out / "results.json", dumps(results)))
    rep = formats & {"html", "pdf"}
    if rep:
        from .report import render
        written.extend(render(results, task, out, rep, lang, notes=notes))
    if "sheets" in formats:   # the A1 drawing sheets (README, Drawing sheets)
        from .sheets import build_sheets, write_sheets
        written.extend(write_sheets(build_sheets(results, task, lang), out / "sheets", {"pdf", "svg", "dxf"}))
    manifest.commit(written)
    return written


@app.command()
def run(
    task_file: Path = typer.Argument(..., metavar="TASK.yaml", help="the task file (README: The task file)"),
    out: Optional[Path] = typer.Option(None, "--out", "-o", help="output folder (default: out/<task name>/)"),
    format: str = typer.Option("json,html,pdf", "--format", "-f",
                               help="comma-separated outputs: json, html, pdf, sheets (the A1 drawing sheets in "
                                    "sheets/; results.json is always written)"),
    lang: str = typer.Option("en", "--lang", "-l", help="report language: en | ru"),
    quiet: bool = typer.Option(False, "--quiet", "-q", help="no progress and summary on the terminal"),
):
    """Run every stage present in the task; write results.json and the report(s).

    Example: tmm run tasks/engine_slider_crank.yaml --out out/engine --lang ru
    """
    formats = _parse_formats(format)
    if lang not in ("en", "ru"):
        raise typer.BadParameter("--lang must be en or ru")
    try:
        task = _load(task_file)
    except TaskError as exc:
        raise _fail_task(exc)
    out = out or Path("out") / task.name
    from .pipeline import PartialResults, run as run_pipeline

    progress = None
    if not quiet:
        def progress(stage: str) -> None:
            _err(f"  {stage}...")
    failure = None
    try:
        results = run_pipeline(task, progress=progress)
    except PartialResults as exc:
        # keep what was computed: results.json and the report with every computed
        # section and, in place of a failed one, what failed; then exit 3
        results, failure = exc.partial, exc
    except StageError as exc:
        raise _fail_stage(exc, task.file)
    except TaskError as exc:
        raise _fail_task(exc)
    notes: list[str] = []
    try:
        paths = write_outputs(task, results, out, formats, lang, notes=notes)
    except StageError as exc:
        raise _fail_stage(failure or exc, task.file)
    except OSError as exc:
        raise _fail_write(exc)
    for note in notes:
        _err(f"warning: {note}")
    if failure is not None:
        for e in results.get("errors", [])[1:]:
            _err(f"error: {task.file}: {StageError(e['stage'], e['message'], e['position'])}")
        raise _fail_stage(failure, task.file)
    if not quiet:
        from .summary import print_summary
        print_summary(results, paths)


@app.command()
def sheets(
    task_file: Path = typer.Argument(..., metavar="TASK.yaml", help="the task file"),
    out: Optional[Path] = typer.Option(None, "--out", "-o", help="output folder (default: out/<task name>/)"),
    format: str = typer.Option("pdf,svg,dxf", "--format", "-f", help="comma-separated: pdf, svg, dxf"),
    lang: str = typer.Option("en", "--lang", "-l", help="sheet language: en | ru"),
):
    """The A1 drawing sheets (frame, ГОСТ 2.104 title block, standard scales) as PDF, SVG and DXF.

    Example: tmm sheets tasks/forging_sixbar.yaml --out out/forging --format pdf,dxf
    """
    fm = {f.strip().lower() for f in format.split(",") if f.strip()}
    if not fm or fm - {"pdf", "svg", "dxf"}:
        raise typer.BadParameter("choose from pdf, svg, dxf (comma-separated)")
    if lang not in ("en", "ru"):
        raise typer.BadParameter("--lang must be en or ru")
    try:
        task = _load(task_file)
    except TaskError as exc:
        raise _fail_task(exc)
    from .pipeline import run as run_pipeline
    from .sheets import build_sheets, write_sheets
    try:
        results = run_pipeline(task)
    except StageError as exc:
        raise _fail_stage(exc, task.file)
    try:
        paths = write_sheets(build_sheets(results, task, lang), out or Path("out") / task.name, fm)
    except OSError as exc:
        raise _fail_write(exc)
    if not paths:
        _err("note: no sheets: the task has no linkage, cam or gear pair to draw")
    for p in paths:
        typer.echo(str(p))


@app.command()
def validate(
    task_files: List[Path] = typer.Argument(..., metavar="TASK.yaml...", help="one or more task files"),
    no_assembly: bool = typer.Option(False, "--no-assembly", help="schema only: skip the check that the "
                                                                  "linkage assembles over the whole cycle"),
):
    """Check task files: the schema, the references, and (for a linkage) that it
    assembles at every crank angle of the cycle. Does not run the pipeline."""
    code = EXIT_OK
    for f in task_files:
        try:
            task = _load(f)
            if task._synthesis_error is not None:
                raise task._synthesis_error
            if task.mechanism is not None:
                from .validation import check_feasible
                check_feasible(task, assembly=not no_assembly)
            typer.echo(f"{f}: ok")
        except TaskError as exc:
            _err(f"error: invalid task\n{exc.render()}")
            code = max(code, EXIT_INVALID) if code != EXIT_STAGE else code
        except StageError as exc:
            _err(f"error: {f}: {exc}")
            code = EXIT_STAGE if code == EXIT_OK else max(code, EXIT_STAGE)
    raise typer.Exit(code)


@app.command()
def check(
    task_file: Path = typer.Argument(..., metavar="TASK.yaml"),
    answers: Optional[Path] = typer.Option(None, "--answers", "-a",
                                           help="a YAML file with `answers:` (and optional `tolerance:`); "
                                                "default: the task's own `answers` section"),
    out: Optional[Path] = typer.Option(None, "--out", "-o", help="also write check.csv / results.json here"),
):
    """Compare a student's answers with the computed results: a table of quantity,
    student value, reference, relative error and verdict. Exit 1 if any answer is
    outside its tolerance."""
    from .check import check_task, load_answers
    try:
        task = _load(task_file)
        ans, tol = load_answers(task, answers)
    except TaskError as exc:
        raise _fail_task(exc)
    from .pipeline import PartialResults, run as run_pipeline
    try:
        results = run_pipeline(task)
    except (PartialResults, StageError) as exc:
        raise _fail_stage(exc, task.file)
    rows = check_task(results, ans, tol)
    from .summary import print_check
    print_check(rows, task_file)
    if out:
        from .check import rows_csv
        from .io import atomic_write
        from .results import dumps
        try:
            atomic_write(out / "check.csv", rows_csv(rows))
            atomic_write(out / "results.json", dumps(results))
        except OSError as exc:
            raise _fail_write(exc)
    raise typer.Exit(EXIT_OK if all(r["verdict"] == "ok" for r in rows) else EXIT_ANSWERS)


@app.command()
def batch(
    source: str = typer.Argument(..., metavar="DIR_OR_GLOB", help="a folder of task files or a glob"),
    out: Path = typer.Option(..., "--out", "-o", help="output folder: <out>/<variant>/ and summary files"),
    jobs: int = typer.Option(1, "--jobs", "-j", min=1, help="variants computed in parallel (processes)"),
    format: str = typer.Option("json", "--format", "-f", help="outputs per variant: json, html, pdf"),
    lang: str = typer.Option("en", "--lang", "-l", help="report language: en | ru"),
):
    """Run and check many variants; one failing variant never stops the rest.
    Writes summary.csv and summary.html (one row per variant). Exit code: the worst
    of the variants' codes (0 all pass, 1 some answers wrong, 2 some invalid, 3 some failed)."""
    from .batch import run_batch
    formats = _parse_formats(format)
    try:
        code = run_batch(source, out, jobs=jobs, formats=formats, lang=lang)
    except OSError as exc:
        raise _fail_write(exc)
    raise typer.Exit(code)


@app.command()
def schema(
    out: Optional[Path] = typer.Option(None, "--out", "-o", help="write to a file instead of stdout"),
):
    """Print the task file's JSON Schema (for editor completion: e.g. a
    `# yaml-language-server: $schema=tmm.schema.json` line at the top of a task)."""
    from .task import Task
    s = Task.model_json_schema(by_alias=True)
    s["$schema"] = "https://json-schema.org/draft/2020-12/schema"
    s["title"] = "tmm task file (schema tmm/1)"
    text = json.dumps(s, indent=2, ensure_ascii=False)
    if out:
        from .io import atomic_write
        try:
            atomic_write(out, text + "\n")
        except OSError as exc:
            raise _fail_write(exc)
    else:
        typer.echo(text)


@app.command()
def fields(section: Optional[str] = typer.Argument(None, help="only this section, e.g. flywheel")):
    """List every task-file field: its path, default and meaning (units: SI base units,
    angles in degrees; a string may carry its own unit, e.g. '300 mm', '50 rpm')."""
    from rich.console import Console
    from rich.table import Table

    from .task import field_docs
    rows = [r for r in field_docs() if section is None or r[0] == section or r[0].startswith(section + ".")
            or r[0].startswith(section + "[")]
    if not rows:
        _err(f"error: no section or field '{section}'")
        raise typer.Exit(EXIT_INVALID)
    t = Table(title="tmm task file fields (schema tmm/1)")
    t.add_column("field", overflow="fold")
    t.add_column("default", overflow="fold")
    t.add_column("meaning", overflow="fold")
    from rich.markup import escape      # '[x, y]' in a meaning is text, not Rich markup
    for path, default, text in rows:
        t.add_row(escape(path), escape(default), escape(text))
    Console().print(t)


STARTERS = ("linkage", "cam", "gears", "full", "synthesis")
STARTERS += ("cam_rocker", "cam_flat", "cam_knife")      # one starter for each cam follower


@app.command()
def new(kind: str = typer.Argument(..., metavar="KIND", help="linkage | cam | cam_rocker | cam_flat | cam_knife | "
                                                            "gears | full | synthesis")):
    """Print a commented starter task of the given kind."""
    if kind not in STARTERS:
        _err(f"error: unknown kind '{kind}'; choose from {', '.join(STARTERS)}")
        raise typer.Exit(EXIT_INVALID)
    from importlib.resources import files
    typer.echo(files("tmm_cli.starters").joinpath(f"{kind}.yaml").read_text(encoding="utf-8"), nl=False)


def main() -> None:
    try:
        app(standalone_mode=True)
    except KeyboardInterrupt:
        _err("interrupted")
        sys.exit(130)
    except SystemExit:
        raise
    except Exception as exc:  # a defect of ours: say so plainly, still no traceback
        _err(f"error: internal error ({type(exc).__name__}: {exc}); please report it with the task file. "
             f"Run `python -m tmm_cli ...` with TMM_DEBUG=1 for the traceback.")
        if __import__("os").environ.get("TMM_DEBUG"):
            raise
        sys.exit(EXIT_STAGE)


if __name__ == "__main__":
    main()
