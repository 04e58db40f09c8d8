"""The `tmm` commands: the Typer app (README, *Commands*); the entry point is
:func:`tmm_cli.cli.main`.

Exit codes: 0 success; 1 answers outside tolerance; 2 invalid task (file, line and
field named, no traceback); 3 a stage failed on valid input (stage and position named).
"""
from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import List, Optional

import typer

from . import console
from .console import EXIT_ANSWERS, EXIT_INVALID, EXIT_OK, EXIT_STAGE, FORMATS  # noqa: F401
from .errors import StageError, TaskError
from .messages import Message, in_lang

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


def _fail_task(exc: TaskError, lang: str = "en") -> "typer.Exit":
    return typer.Exit(console.fail_task(exc, typer.echo, lang))


def _fail_stage(exc: StageError, file: str | None = None, lang: str = "en") -> "typer.Exit":
    return typer.Exit(console.fail_stage(exc, file, typer.echo, lang))


def _check_lang(lang: str) -> str:
    """--lang: one of the report languages, in any case (RU is ru); a usage error otherwise."""
    if lang.strip().lower() not in console.LANGS:
        raise typer.BadParameter(f"--lang must be {', '.join(console.LANGS[:-1])} or {console.LANGS[-1]}")
    return lang.strip().lower()


def _check_csv_style(style: str) -> None:
    from .tables import CSV_STYLES
    if style not in CSV_STYLES:
        raise typer.BadParameter(" or ".join(CSV_STYLES), param_hint="--csv")


def _fail_write(exc: OSError) -> "typer.Exit":
    """The output folder or a file in it cannot be written: exit 3, no traceback."""
    return typer.Exit(console.fail_write(exc, typer.echo))


def _load(path: Path):
    """Load and validate a task as every command does (exit 2 / 3 the same everywhere): an
    invalid task exits 2, a valid one that cannot be computed (a synthesis whose requirements
    no mechanism meets, a linkage that does not assemble) exits 3 with the message of
    `tmm run`."""
    from .orchestrate import prepare
    try:
        return prepare(path)
    except TaskError as exc:
        raise _fail_task(exc)
    except StageError as exc:
        raise _fail_stage(exc, str(path))


def _parse_formats(text: str) -> set[str]:
    fm = console.parse_formats(text)
    if fm is None:
        bad = {f.strip().lower() for f in text.split(",") if f.strip()} - FORMATS
        raise typer.BadParameter(f"unknown format(s) {', '.join(sorted(bad)) or '(none)'}; "
                                 f"choose from json, html, pdf, sheets, note (comma-separated)")
    return fm


def write_outputs(task, results: dict, out: Path, formats: set[str], lang: str,
                  notes: list[str] | None = None,
                  study: tuple[dict, dict] | None = None) -> list[Path]:
    """results.json and the reports (tmm_cli.orchestrate.write_outputs)."""
    from .orchestrate import write_outputs as write
    return write(task, results, out, formats, lang, notes=notes, study=study)


@app.command()
def run(
    task_file: Path = typer.Argument(..., metavar="TASK.yaml",
                                     help="the task file (docs/task-file.md; every field: tmm fields)"),
    out: Optional[Path] = typer.Option(None, "--out", "-o", help="output folder (default: out/<task name>/)"),
    format: str = typer.Option("json,html,pdf", "--format", "-f",
                               help="comma-separated outputs: json, html, pdf, sheets (the A1 drawing sheets in "
                                    "sheets/), note (note.pdf: the explanatory note in the ESKD frame; the task's "
                                    "student and course headers fill its title page); results.json is always "
                                    "written"),
    lang: str = typer.Option("en", "--lang", "-l", help="language of the report and of the terminal output "
                             "(summary, warnings, errors): en | ru | uk"),
    quiet: bool = typer.Option(False, "--quiet", "-q", help="no progress and summary on the terminal"),
    study: bool = typer.Option(False, "--study", help="also write study.json and study.html: "
                                                      "accuracy against computing time per stage"),
):
    """Run every stage present in the task; write results.json and the report(s).

    Example: tmm run tasks/engine_slider_crank.yaml --out out/engine --lang ru (or uk)
    """
    formats = _parse_formats(format)
    lang = _check_lang(lang)
    code = console.run_task(task_file, out, formats, lang, quiet, study, typer.echo)
    if code != EXIT_OK:
        raise typer.Exit(code)


def _run_study(task, progress=None, repeat: int = 3) -> tuple[dict, dict]:
    from . import study as study_mod
    try:
        return study_mod.run_study(task, progress=progress, repeat=repeat)
    except StageError as exc:
        raise _fail_stage(exc, task.file)


@app.command("study")
def study_cmd(
    task_file: Path = typer.Argument(..., metavar="TASK.yaml", help="the task file"),
    out: Optional[Path] = typer.Option(None, "--out", "-o", help="output folder (default: out/<task name>/)"),
    repeat: int = typer.Option(3, "--repeat", help="timed repeats per row (the best is kept)", min=1, max=50),
    lang: str = typer.Option("en", "--lang", "-l", help="language of study.html: en | ru | uk"),
):
    """Accuracy against computing time: for each stage present, sweep the setting that
    trades time for accuracy (flywheel resolution, curve points, kinetostatic positions,
    dof2 rtol, cam profile step, blocking-contour grid, planetary z_max); write study.json
    (errors against a converged reference, measured and theoretical convergence order,
    times) and study.html (tables and log-log plots).

    Example: tmm study tasks/forging_sixbar.yaml --out out/forging --lang ru
    """
    lang = _check_lang(lang)
    task = _load(task_file)
    out = out or Path("out") / task.name
    st, trap = _run_study(task, lambda s: _err(f"  {console.stage_progress(s, lang)}..."), repeat)
    from . import study as study_mod
    note = study_mod.nothing_to_sweep(task, st, trap)
    if note is not None:           # no empty page; exit 0, as `tmm sheets` with no sheet to draw
        from .messages import localize
        text = localize(note.to_dict(), lang)
        _err(text[0].upper() + text[1:] + ".")
        return
    from .report.sections import study as study_page
    try:
        paths = study_page.write(st, out, trap, lang)
    except OSError as exc:
        raise _fail_write(exc)
    for line in study_page.trades(st, lang):      # the trade in plain words first, then the files
        typer.echo(line[0].upper() + line[1:] + ".")
    if trap.get("left_out"):
        typer.echo(study_page.left_out(trap["left_out"], lang))
    for p in paths:
        typer.echo(str(p))


@app.command()
def sheets(
    task_file: Path = typer.Argument(..., metavar="TASK.yaml", help="the task file"),
    out: Optional[Path] = typer.Option(None, "--out", "-o", help="output folder (default: out/<task name>/)"),
    format: str = typer.Option("pdf,svg,dxf", "--format", "-f", help="comma-separated: pdf, svg, dxf"),
    lang: str = typer.Option("en", "--lang", "-l", help="sheet language: en | ru | uk"),
):
    """The A1 drawing sheets (frame, GOST 2.104 title block, standard scales) as PDF, SVG and DXF.

    Sheets: 1 kinematics (mechanism, plans, s-v-a diagrams), 2 kinetostatics (groups, force
    polygons, Zhukovsky's lever of one or two positions), 3 dynamics, 4 cam, 5 gear mesh, 6 planetary gear;
    only those the task has.

    Example: tmm sheets tasks/forging_sixbar.yaml --out out/forging --format pdf,dxf
    """
    fm = {f.strip().lower() for f in format.split(",") if f.strip()}
    if not fm or fm - {"pdf", "svg", "dxf"}:
        raise typer.BadParameter("choose from pdf, svg, dxf (comma-separated)")
    lang = _check_lang(lang)
    task = _load(task_file)
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
        _err(f"{console.run_words(lang)['note']}: {in_lang(Message('sheets.none'), lang)}")
    for p in paths:
        typer.echo(str(p))


@app.command()
def validate(
    task_files: List[Path] = typer.Argument(..., metavar="TASK.yaml...",
                                            help="task files, folders of them or quoted patterns ('group21/*.yaml')"),
    no_assembly: bool = typer.Option(False, "--no-assembly", help="schema only: skip the check that the "
                                                                  "linkage assembles over the whole cycle"),
    lang: str = typer.Option("en", "--lang", "-l", help="language of the errors and warnings: en | ru | uk"),
):
    """Check task files: the schema, the references, and (for a linkage) that it
    assembles at every crank angle of the cycle. Does not run the pipeline."""
    lang = _check_lang(lang)
    raise typer.Exit(console.validate_tasks(task_files, no_assembly, typer.echo, lang))


@app.command()
def check(
    task_file: Path = typer.Argument(..., metavar="TASK.yaml"),
    answers: Optional[Path] = typer.Option(None, "--answers", "-a",
                                           help="answers: a YAML file with `answers:`, a folder of them, or a CSV "
                                                "with a row per student (student, group, variant, one column per "
                                                "path); default: the task's own `answers` section"),
    out: Optional[Path] = typer.Option(None, "--out", "-o", help="also write check.csv / results.json here"),
    tolerance: Optional[Path] = typer.Option(None, "--tolerance", "-t",
                                             help="a YAML file of tolerances per path or prefix (overrides the "
                                                  "task's): 0.05 (relative) or {rel: 0.02, abs: 0.5}"),
    quantities: Optional[str] = typer.Option(None, "--quantities", "-q",
                                             help="required quantities: result paths and presets, comma-separated "
                                                  "(a required path not answered is missing)"),
    latest: bool = typer.Option(False, "--latest", help="of several submissions of one student for the variant, "
                                                        "grade only the newest (by modification time)"),
    csv_style: str = typer.Option("plain", "--csv", metavar="plain|excel-ru",
                                  help="check.csv: plain (`,`, decimal points) or excel-ru (`;`, decimal commas, BOM)"),
    lang: str = typer.Option("en", "--lang", "-l", help="language of the table and the messages on the terminal "
                                                        "(check.csv stays English): en | ru | uk"),
):
    """Compare a student's answers with the computed results: path, answer, reference,
    error and status (ok, sign, outside, missing, unknown_path, not_computed, invalid: an answer
    that cannot be read). Exit 1 if any answer is not ok (or an answers file holds none), 2
    invalid input or no answers at all (the task has no `answers:` and no --answers is given),
    3 a stage failed."""
    from .check import (check_csv, grade, load_sources, load_tolerance_file, repeats, set_code, set_status,
                        task_answer_set, tolerances, variant_order)
    from .orchestrate import compute, prepare
    from .pipeline import PartialResults
    _check_csv_style(csv_style)
    lang = _check_lang(lang)
    warn, note = console.run_words(lang)["warning"], console.run_words(lang)["note"]
    try:
        task = prepare(task_file, stage_errors=False)
        tol_override = load_tolerance_file(tolerance) if tolerance is not None else None
        single = answers is not None and answers.is_file() and answers.suffix.lower() != ".csv"
        if answers is None:
            own = task_answer_set(task)
            if own is None:
                raise TaskError(Message("answers.none_in_task"), file=str(task_file), kind="no answers")
            sets = [own]
        else:
            sets = load_sources(answers)
            if not single:
                # a file of the folder that cannot be read is named (whose variant it is, nobody knows),
                # never counted among the other variants' sets
                for a in sets:
                    if a.error and not a.matches(task):
                        _err(f"{warn}: {in_lang(Message('answers.not_read', reason=a.error), lang)}")
                readable = [a for a in sets if not a.error or a.matches(task)]
                mine = [a for a in readable if a.matches(task)]
                if len(mine) < len(readable):   # a table or folder of the whole group: the others are not this task's
                    kept = {id(a) for a in mine}
                    other = variant_order({str(a.variant) if a.variant not in (None, "") else a.stem or "?"
                                            for a in readable if id(a) not in kept})
                    _err(f"{note}: " + in_lang(Message("answers.other_variants", count=len(readable) - len(mine),
                                                               variants=other[:8], more=", ..." if len(other) > 8 else ""),
                                                       lang))
                sets, dropped = repeats(mine, latest)
                for n in dropped:
                    _err(f"{note}: {in_lang(n, lang)}")
                for a in sets:
                    if a.flags:
                        others = [f.split("=", 1)[1] for f in a.flags if f.startswith("repeat=")]
                        _err(f"{warn}: {in_lang(Message('answers.repeat', file=a.answers_file, student=a.student, others=others), lang)}")
        for a in sets:
            if single and a.variant not in (None, "") and task.variant is not None and not a.matches(task):
                # graded all the same (one FILE is taken as given), but a form of another variant
                # grades every answer outside: say why
                _err(f"{warn}: " + in_lang(Message("answers.other_variant_file", file=str(answers),
                                                           variant=str(a.variant), task=str(task.variant)), lang))
            for n in a.notes:
                _err(f"{warn}: {in_lang(n, lang)}")
    except TaskError as exc:
        raise _fail_task(exc, lang)
    try:
        results = compute(task)
    except (PartialResults, StageError) as exc:
        raise _fail_stage(exc, str(task_file), lang)
    except TaskError as exc:
        raise _fail_task(exc, lang)
    required = None
    if quantities:
        from .forms import expand
        try:
            required = expand(quantities, results)
        except TaskError as exc:
            exc.file, exc.kind = str(task_file), "quantities"      # the option's, of this task's results
            raise _fail_task(exc, lang)
    from .summary import print_check
    if not sets:
        _err(in_lang(Message("answers.none_for_variant", source=str(answers),
                                     variant=str(task.variant if task.variant is not None else task.name)), lang))
    code, all_rows = (EXIT_ANSWERS if not sets else EXIT_OK), []
    tol = tolerances(task, tol_override, results)
    from .check import unused_tolerance_keys
    for w in unused_tolerance_keys(set(task.tolerance or {}) | set(tol_override or {}), results):
        _err(f"{warn}: {in_lang(w, lang)}")
    for a in sets:
        if a.error:          # one malformed row or file of a class: named, the others graded
            _err(f"{console.run_words(lang)['error']}: {in_lang(a.error, lang)}")
            code = max(code, EXIT_INVALID)
            continue
        rows = grade(results, a, tol, required)
        if task.variant is not None:        # a set matched by its file's name: the task's variant
            for r in rows:
                if r["variant"] in ("", None):
                    r["variant"] = task.variant
        print_check(rows, a.source, lang)
        all_rows.extend(rows)
        code = max(code, set_code(set_status(rows)))
    from .check import angle_tolerance_note
    if (wide := angle_tolerance_note(all_rows, tol)) is not None:      # for the instructor, once
        _err(f"{note}: {in_lang(wide, lang)}")
    if out:
        from .io import atomic_write, folder_lock
        from .results import dump
        try:
            from .tables import csv_styled
            with folder_lock(out):          # never interleaved with a run into the same folder
                atomic_write(out / "check.csv", csv_styled(check_csv(all_rows), csv_style))
                atomic_write(out / "results.json", lambda write: dump(results, write))
        except OSError as exc:
            raise _fail_write(exc)
    raise typer.Exit(code)


@app.command()
def batch(
    source: str = typer.Argument(..., metavar="DIR_OR_GLOB", help="a folder of task files or a glob"),
    out: Path = typer.Option(..., "--out", "-o", help="output folder: <out>/<variant>/ and summary files"),
    jobs: int = typer.Option(1, "--jobs", "-j", min=1, help="variants computed in parallel (processes)"),
    format: str = typer.Option("json", "--format", "-f", help="outputs per variant: json, html, pdf"),
    lang: str = typer.Option("en", "--lang", "-l", help="language of the reports, the summary and the terminal table: en | ru | uk"),
    answers: Optional[Path] = typer.Option(None, "--answers", "-a",
                                           help="students' answers: a YAML file, a folder of them, or a CSV; "
                                                "default: each task's own `answers`"),
    tolerance: Optional[Path] = typer.Option(None, "--tolerance", "-t", help="a YAML file of tolerances"),
    quantities: Optional[str] = typer.Option(None, "--quantities", "-q",
                                             help="required quantities: result paths and presets"),
    timeout: float = typer.Option(120.0, "--timeout", min=0,
                                  help="seconds one variant may run (0 = no limit); over it: a failed row"),
    memory: int = typer.Option(4096, "--memory", min=0,
                               help="MB of address space per variant (0 = no limit); over it: a failed row"),
    latest: bool = typer.Option(False, "--latest", help="of several submissions of one student for one variant, "
                                                        "grade only the newest (by modification time)"),
    grades: Optional[str] = typer.Option(None, "--grades", metavar="5:0.9,4:0.75,3:0.6",
                                         help="a `grade` column: grade:least score, highest first (below the "
                                              "last: the next lower grade)"),
    gradebook: Optional[str] = typer.Option(None, "--gradebook", metavar="moodle",
                                            help="also write gradebook-moodle.csv for Moodle's grade import"),
    feedback: str = typer.Option("key", "--feedback", metavar="key|no-key",
                                 help="feedback pages with the reference values (key) or without (no-key)"),
    csv_style: str = typer.Option("plain", "--csv", metavar="plain|excel-ru",
                                  help="every CSV of the run: plain (`,`, decimal points) or excel-ru (`;`, "
                                       "decimal commas, a UTF-8 BOM)"),
):
    """Run and grade many variants; one failing variant never stops the rest.
    Writes summary.csv, summary.html and check.csv (and <out>/<variant>/...). Exit code:
    the worst of the rows (0 all ok, 1 some answers wrong or missing, 2 some invalid,
    3 some failed)."""
    from .batch import run_batch
    from .copies import parse_grades
    formats = _parse_formats(format)
    lang = _check_lang(lang)
    try:
        scale = parse_grades(grades) if grades is not None else None
    except ValueError as exc:
        raise typer.BadParameter(str(exc), param_hint="--grades") from None
    if gradebook not in (None, "moodle"):
        raise typer.BadParameter("the gradebook format is moodle", param_hint="--gradebook")
    if feedback not in ("key", "no-key"):
        raise typer.BadParameter("key or no-key", param_hint="--feedback")
    _check_csv_style(csv_style)
    try:
        code = run_batch(source, out, jobs=jobs, formats=formats, lang=lang, answers=answers, tolerance=tolerance,
                         quantities=quantities, timeout=timeout, memory_mb=memory or None, latest=latest,
                         grades=scale, gradebook=gradebook, feedback=feedback, csv_style=csv_style)
    except OSError as exc:
        raise _fail_write(exc)
    raise typer.Exit(code)


@app.command()
def variants(
    template: Path = typer.Argument(..., metavar="TEMPLATE.yaml", help="a task file with {column} placeholders"),
    table: Path = typer.Argument(..., metavar="TABLE.csv", help="one row per variant; a `variant` column"),
    out: Path = typer.Option(..., "--out", "-o", help="folder for <variant>.yaml and variants.csv"),
    lang: str = typer.Option("en", "--lang", "-l", help="language of the messages on the terminal "
                                                        "(variants.csv stays English): en | ru | uk"),
):
    """Write one validated task per table row (DIR/<variant>.yaml) and DIR/variants.csv.
    A row whose task is invalid or does not assemble over the cycle is reported as
    TABLE:<line>: variant <v>: <reason> and not written. Exit 0 when every row is
    written, else 2."""
    from .variants import make_variants
    lang = _check_lang(lang)
    try:
        code, report, messages = make_variants(template, table, out)
    except TaskError as exc:
        raise _fail_task(exc, lang)
    except OSError as exc:
        raise _fail_write(exc)
    for m in messages:
        _err(in_lang(m, lang))
    n = sum(r["status"] == "written" for r in report)
    _err(in_lang(Message("variants.wrote", n=n, total=len(report), out=str(out), csv=str(out / "variants.csv")), lang))
    raise typer.Exit(code)


@app.command()
def paths(
    task_file: Path = typer.Argument(..., metavar="TASK.yaml"),
    prefix: Optional[str] = typer.Option(None, "--prefix", "-p", help="only paths starting with this"),
    format: str = typer.Option("text", "--format", "-f", help="text (PATH<TAB>VALUE) | json"),
    group: bool = typer.Option(False, "--group", "-g", help="each array of more than 12 numbers (per position or "
                                                              "degree) as one line: its index range, count, min .. max"),
    index: Optional[str] = typer.Option(None, "--index", "-i", metavar="I,J,A-B",
                                        help="of those arrays and of the positions (kinematics[i], "
                                             "kinetostatics[i]) only these elements, e.g. 0,90,180 or 1-3"),
):
    """Run the task and list every result path with its value (the paths `answers`,
    `--quantities` and tolerances use). `--group` and `--index` shorten the long arrays."""
    from .results import leaf_paths
    from .orchestrate import compute, prepare
    from .pipeline import PartialResults
    if format not in ("text", "json"):
        raise typer.BadParameter("--format must be text or json")
    from .forms import group_leaves, parse_indices
    try:
        chosen = parse_indices(index) if index is not None else None
    except ValueError as exc:
        raise typer.BadParameter(f"'{exc.args[0]}' is not an index or a range A-B", param_hint="--index") from None
    try:
        task = prepare(task_file, stage_errors=False)
        results = compute(task)
    except TaskError as exc:
        raise _fail_task(exc)
    except (PartialResults, StageError) as exc:
        raise _fail_stage(exc, str(task_file))
    every = leaf_paths(results)
    leaves = [(p, v) for p, v in every if prefix is None or p.startswith(prefix)]
    if prefix is not None and not leaves:       # a misspelt prefix printed nothing and exit 0
        import difflib
        heads = sorted({p[:len(prefix)] for p, _ in every})
        # the sections the paths start with ('mechanism' is not one: the results name it 'structure')
        secs = list(dict.fromkeys(p.split(".")[0].split("[")[0] for p, _ in every))
        near = ("." not in prefix and difflib.get_close_matches(prefix, secs, n=1, cutoff=0.6)) \
            or difflib.get_close_matches(prefix, heads, n=1, cutoff=0.6)
        raise typer.BadParameter(f"no result path of this task starts with '{prefix}'; did you mean "
                                 + (f"'{near[0]}'?" if near else "one of: " + ", ".join(secs) + "?"),
                                 param_hint="--prefix")
    if group or chosen is not None:
        leaves = group_leaves(leaves, chosen, group)
    if format == "json":
        typer.echo(json.dumps(dict(leaves), indent=1, ensure_ascii=False))
    else:
        from .results import reference

        def txt(v):                     # as tmm check takes it: a round-off zero (8.7e-17) is 0.0
            v = reference(v)
            return json.dumps(v) if isinstance(v, bool) else (repr(v) if isinstance(v, float) else str(v))
        sys.stdout.write("".join(f"{p}\t{txt(v)}\n" for p, v in leaves))


@app.command()
def form(
    source: Path = typer.Argument(..., metavar="TASK_OR_DIR", help="a task file or a folder of them"),
    quantities: str = typer.Option(..., "--quantities", "-q",
                                   help="result paths and presets, comma-separated: positions, kinematics, "
                                        "kinetostatics, flywheel, cam, gears, planetary, drive_train, synthesis, "
                                        "synthesis_function, synthesis_positions, synthesis_path, balancing, differential"),
    out: Path = typer.Option(Path("forms"), "--out", "-o", help="output folder (default: forms/)"),
    lang: str = typer.Option("en", "--lang", "-l", help="language of the comments: en | ru | uk"),
    csv_style: str = typer.Option("plain", "--csv", metavar="plain|excel-ru",
                                  help="form.csv and key.csv: plain (`,`, decimal points) or excel-ru (`;`, "
                                       "decimal commas, a UTF-8 BOM)"),
):
    """Write per task a blank answer form NAME.form.yaml and an answer key NAME.key.yaml,
    and for the set form.csv and key.csv."""
    from .batch import find_tasks
    from .forms import expand, form_text, forms_csv, position_angles
    from .io import atomic_write
    from .orchestrate import classify, compute, prepare
    from .results import lookup
    lang = _check_lang(lang)
    _check_csv_style(csv_style)
    if source.is_dir():
        found, _ = find_tasks(str(source))
        files = [f for f, why in found if why is None]
    else:
        files = [source]
    from .safepath import UniqueNames, safe_name
    code, frows, krows, all_paths = EXIT_OK, [], [], []
    names = UniqueNames()       # v1.yaml and V1.yaml: one form file on Windows and macOS
    for f in files:
        try:
            task = prepare(f, stage_errors=False)
            results = compute(task)
            qp = expand(quantities, results)
            name = names.take(safe_name(task.name, "task"))
            angles = position_angles(qp, results)
            atomic_write(out / f"{name}.form.yaml", form_text(task, qp, None, lang, angles))
            atomic_write(out / f"{name}.key.yaml", form_text(task, qp, results, lang, angles))
            if name != task.name:
                _err(in_lang(Message("form.renamed", file=str(f), name=name), lang))
        except TaskError as exc:
            exc.file = exc.file or str(f)          # a quantity the results lack: name the task
            coded = exc.coded() if lang != "en" else None
            _err(f"{console.run_words(lang)['error']}: " + (in_lang(coded, lang) if coded is not None else exc.render()))
            code = max(code, EXIT_INVALID)
            continue
        except BaseException as exc:
            if isinstance(exc, KeyboardInterrupt):
                raise
            c, _, msg = classify(exc)
            from .batch import stage_failure_message
            coded = stage_failure_message(exc)
            shown = in_lang(coded, lang) if coded is not None and str(coded) == msg else msg
            _err(f"{console.run_words(lang)['error']}: {f}: {shown}")
            code = max(code, c)
            continue
        all_paths += [p for p in qp if p not in all_paths]
        v = task.variant if task.variant is not None else task.name
        who = dict(zip(("student", "group"), task.who))
        frows.append({**who, "variant": v})
        krow = {**who, "variant": v}
        for p in qp:
            krow[p] = lookup(results, p)
        krows.append(krow)
    if frows:        # with no form written, an earlier run's form.csv and key.csv stay as they were
        try:
            from .tables import csv_styled
            atomic_write(out / "form.csv", csv_styled(forms_csv(frows, all_paths, lang), csv_style))
            atomic_write(out / "key.csv", csv_styled(forms_csv(krows, all_paths), csv_style))
        except OSError as exc:
            raise _fail_write(exc)
    _err(in_lang(Message("form.wrote", n=len(frows), out=str(out)), lang))
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
def fields(section: Optional[str] = typer.Argument(None, help="only this section, e.g. flywheel"),
           lang: str = typer.Option("en", "--lang", "-l", help="language of the table: en | ru | uk")):
    """List every task-file field: its path, default and meaning (units: SI base units,
    angles in degrees; a string may carry its own unit, e.g. '300 mm', '50 rpm')."""
    lang = _check_lang(lang)
    from rich.console import Console
    from rich.table import Table

    from . import locales
    from .task import field_docs
    W = locales.of("fields", "terminal", lang)
    topics = {lg: locales.topic(lg, "fields") for lg in locales.LANGS}
    meaning = topics[lang].get("fields") or {}                      # en: the schema's own texts
    docs = field_docs()
    if section is not None:      # a section in a course language's words (the fields topic's sections)
        word = "_".join(section.strip().lower().split())
        section = next((t["sections"][word] for t in topics.values() if word in (t.get("sections") or {})),
                       section)
    rows = [r for r in docs if section is None or r[0] == section or r[0].startswith(section + ".")
            or r[0].startswith(section + "[")]
    if not rows:
        import difflib
        names = sorted({r[0] for r in docs} | {r[0].split(".")[0].split("[")[0] for r in docs})
        near = difflib.get_close_matches(section, names, n=1, cutoff=0.6)
        _err(W["no_such"].format(section=section) + (W["did_you_mean"].format(near=near[0]) if near else ""))
        raise typer.Exit(EXIT_INVALID)
    t = Table(title=W["title"])
    t.add_column(W["field"], overflow="fold")
    t.add_column(W["default"], overflow="fold")
    t.add_column(W["meaning"], overflow="fold")
    from rich.markup import escape      # '[x, y]' in a meaning is text, not Rich markup
    for path, default, text in rows:
        t.add_row(escape(path), escape(W["required"] if default == "required" else default),
                  escape(meaning.get(path, text)))
    Console().print(t)


STARTERS = ("linkage", "cam", "gears", "full", "synthesis")
STARTERS += ("cam_rocker", "cam_flat", "cam_knife")      # one starter for each cam follower
STARTERS += ("differential", "balancing")
STARTERS += ("synthesis_function", "synthesis_positions", "synthesis_path")


@app.command()
def new(kind: str = typer.Argument(..., metavar="KIND", help="linkage | cam | cam_rocker | cam_flat | cam_knife | "
                                                            "gears | full | synthesis | synthesis_function | "
                                                            "synthesis_positions | synthesis_path | "
                                                            "differential | balancing"),
        lang: str = typer.Option("en", "--lang", "-l", help="language of the comments and the title: en | ru | uk")):
    """Print a commented starter task of the given kind (its comments in --lang; the data the
    same in every language)."""
    lang = _check_lang(lang)
    if kind not in STARTERS:
        import difflib
        # 'path' is the starter synthesis_path, 'rocker' cam_rocker: the kind a starter ends with
        near = [s for s in STARTERS if s.endswith("_" + kind.strip().lower())] \
            or difflib.get_close_matches(kind, STARTERS, n=1, cutoff=0.6)
        from . import locales
        W = locales.of("starters", "terminal", lang)
        hint = W["did_you_mean"].format(near=near[0]) if near else "; "
        _err(W["unknown"].format(kind=kind) + hint + W["choose"].format(kinds=", ".join(STARTERS)))
        raise typer.Exit(EXIT_INVALID)
    from importlib.resources import files
    # English beside the package's __init__, another language in its folder (starters/ru/...)
    name = f"{kind}.yaml" if lang == "en" else f"{lang}/{kind}.yaml"
    typer.echo(files("tmm_cli.starters").joinpath(name).read_text(encoding="utf-8"), nl=False)
