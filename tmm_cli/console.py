"""What the commands share (the Typer app of :mod:`tmm_cli.commands` and the fast path of
:mod:`tmm_cli.cli`): the exit codes, formats and languages, how a failure is told, and the
two commands a user repeats most, `tmm run` (:func:`run_task`) and `tmm validate`
(:func:`validate_tasks`)."""
from __future__ import annotations

import re
import sys
import time
from pathlib import Path
from typing import Callable, Optional

from .errors import StageError, TaskError
from .messages import in_lang

EXIT_OK, EXIT_ANSWERS, EXIT_INVALID, EXIT_STAGE = 0, 1, 2, 3
FORMATS = {"json", "html", "pdf", "sheets", "note"}
LANGS = ("en", "ru", "uk")

_ANSI = re.compile(r"\033\[[;?0-9]*[a-zA-Z]")     # click's: stripped when not a terminal


def echo(message: str, err: bool = False) -> None:
    """click.echo of a text line on a well-configured stream (what the fast path runs
    with): the line and a newline, ANSI codes stripped unless a terminal, flushed."""
    file = sys.stderr if err else sys.stdout
    if file is None:
        return
    out = message + "\n"
    try:
        tty = file.isatty()
    except Exception:  # noqa: BLE001 - click.isatty's: a stream without isatty is no terminal
        tty = False
    if not tty:
        out = _ANSI.sub("", out)
    file.write(out)
    file.flush()


Echo = Callable[..., None]


# the invalid file's kind (TaskError.kind) -> the head of its errors in another language
_INVALID = {"task": "invalid_task", "answers file": "invalid_answers", "tolerance file": "invalid_tolerance",
            "no answers": "no_answers_head",       # a valid task, `tmm check` given nothing to check
            "quantities": "invalid_quantities"}    # `--quantities` asks what the task's results lack


def fail_task(exc: TaskError, echo: Echo = echo, lang: str = "en") -> int:
    """An invalid task file (or answers or tolerance file): its errors (file, line, field, what is
    wrong), exit 2; in ru and uk (`--lang`) in that language where every part of them is coded."""
    head = _INVALID.get(exc.kind)
    coded = exc.coded() if lang != "en" and head is not None else None
    if coded is None:
        echo(f"error: {_word(head, 'en') if head else 'invalid ' + exc.kind}\n{exc.render()}", err=True)
    else:
        from .messages import localize
        echo(f"{_word(head, lang)}:\n{localize(coded.to_dict(), lang)}", err=True)
    return EXIT_INVALID


def fail_stage(exc: StageError, file: str | None = None, echo: Echo = echo, lang: str = "en") -> int:
    where = f"{file}: " if file else ""
    echo(f"{_word('error', lang)}: {where}{stage_text(exc.to_dict(), lang)}", err=True)
    return EXIT_STAGE


def _word(key: str, lang: str) -> str:
    """A word of the terminal (the catalogue's summary ``run`` table) in ``lang``."""
    return run_words(lang)[key]


def run_words(lang: str) -> dict[str, str]:
    """The terminal's words in ``lang`` (:func:`tmm_cli.summary.run_words`)."""
    from .summary import run_words as words
    return words(lang)


def stage_text(err: dict, lang: str = "en") -> str:
    """A failed stage (results.json's ``errors`` entry) as the terminal says it in ``lang``:
    English as :class:`StageError` words it; in ru and uk the report's sentence
    (:func:`tmm_cli.report.failure.what`: the same words as the report's failure box)."""
    if lang == "en":
        return str(StageError(err.get("stage"), err.get("message") or "", err.get("position")))
    from .report.failure import what
    return what(err, lang)


def stage_progress(stage: str, lang: str = "en") -> str:
    """A progress line's stage (``positions``, ``study: curves``) in ``lang``: the catalogue's
    stage names (English: as the pipeline names it)."""
    if lang == "en":
        return stage
    from .messages import catalogue
    names = catalogue(lang)["terms"].get("stage") or {}
    T = run_words(lang)
    if stage.startswith("study: "):
        part = stage[len("study: "):]
        return f"{T['study']}: {T['curves'] if part == 'curves' else names.get(part, part)}"
    return str(names.get(stage, stage))


def fail_write(exc: OSError, echo: Echo = echo) -> int:
    """The output folder or a file in it cannot be written (--out names a file, no
    permission, disk full): the writing stage failed, exit 3, no traceback."""
    from .orchestrate import write_error_text
    echo(f"error: {write_error_text(exc)}", err=True)
    return EXIT_STAGE


def parse_formats(text: str) -> set[str] | None:
    """The set of --format, or None when it names no format or an unknown one."""
    fm = {f.strip().lower() for f in text.split(",") if f.strip()}
    return fm if fm and not fm - FORMATS else None


def run_task(task_file: Path, out: Optional[Path], formats: set[str], lang: str, quiet: bool, study: bool,
             echo: Echo = echo, held: list | None = None) -> int:
    """`tmm run` with its options checked: compute, write, report; the exit code.
    ``held``: receives the results (the caller keeps them to its end)."""
    from .orchestrate import process
    from .pipeline import PartialResults
    progress = None
    if not quiet:
        def progress(stage: str) -> None:
            echo(f"  {stage_progress(stage, lang)}...", err=True)
    failure = None
    notes: list[str] = []
    started = time.time()

    def folder(name: str) -> Path:             # the task's output folder (a task's name: its file's stem)
        return out or Path("out") / name
    try:
        task, results, paths = process(task_file, lambda t: folder(t.name), formats, lang,
                                       progress=progress, study=study, notes=notes)
    except PartialResults as exc:
        # results.json and the report were written with every computed section and, in
        # place of a failed one, what failed; then exit 3
        failure, results = exc, exc.partial
    except TaskError as exc:
        code = fail_task(exc, echo, lang)
        earlier_run(folder(task_file.stem), started, echo, lang)
        return code
    except StageError as exc:
        code = fail_stage(exc, str(task_file), echo, lang)
        earlier_run(folder(task_file.stem), started, echo, lang)
        return code
    except OSError as exc:
        return fail_write(exc, echo)
    if held is not None:
        held.append(results)
    for note in notes:
        echo(f"{_word('warning', lang)}: {in_lang(note, lang)}", err=True)
    if failure is not None:
        for e in results.get("errors", [])[1:]:
            echo(f"{_word('error', lang)}: {task_file}: {stage_text(e, lang)}", err=True)
        code = fail_stage(failure, str(task_file), echo, lang)
        if not quiet:           # what was written all the same: the computed sections, the failure in place
            for p in failure.written or []:
                echo(f"{_word('wrote', lang)} {p}")
        return code
    if not quiet:
        from .summary import print_summary
        print_summary(results, paths, lang)
    return EXIT_OK


def earlier_run(folder: Path, started: float, echo: Echo = echo, lang: str = "en") -> None:
    """After a run that wrote nothing (its task invalid, a stage failed before the outputs): say
    that ``folder`` still holds an earlier run's outputs (its manifest older than this run), so
    that nobody reads them as this task file's."""
    from .io import MANIFEST
    from .messages import Message
    try:
        when = (folder / MANIFEST).stat().st_mtime
    except OSError:
        return                                   # no earlier run there (or not readable): nothing to say
    if when < started:
        echo(in_lang(Message("output.earlier_run", folder=f"{folder}/",
                         when=time.strftime("%Y-%m-%d %H:%M", time.localtime(when))), lang), err=True)


def validate_tasks(task_files: list[Path], no_assembly: bool, echo: Echo = echo, lang: str = "en") -> int:
    """`tmm validate`: each file checked, `FILE: ok` or its errors; the exit code. A folder
    stands for its task files (*.yaml, *.yml; answers files skipped) and a quoted pattern
    (`'group21/*.yaml'`) for the files it matches, as for `tmm batch`. ``lang``: the errors and
    warnings in that language (`--lang`)."""
    code = EXIT_OK
    files = []
    for a in task_files:
        try:
            files += _task_files([a])
        except TaskError as exc:
            fail_task(exc, echo, lang)
            code = EXIT_INVALID
    for f in files:
        try:
            from .orchestrate import prepare
            task = prepare(f, assembly=not no_assembly)
            echo(f"{f}: ok")
            for note in task.input_warnings:        # e.g. a plain number read as metres
                echo(f"{_word('warning', lang)}: {f}: {in_lang(note, lang)}", err=True)
        except TaskError as exc:
            fail_task(exc, echo, lang)
            code = max(code, EXIT_INVALID) if code != EXIT_STAGE else code
        except StageError as exc:
            text = str(exc) if lang == "en" else stage_text(exc.to_dict(), lang)
            echo(f"{_word('error', lang)}: {f}: {text}", err=True)
            code = EXIT_STAGE if code == EXIT_OK else max(code, EXIT_STAGE)
    return code


def _task_files(args: list[Path]) -> list[Path]:
    """The arguments of `tmm validate` with folders and unexpanded patterns expanded (a
    folder or pattern with no task file stays as given: its check names why)."""
    out: list[Path] = []
    for a in args:
        if a.is_dir() or (not a.exists() and any(c in str(a) for c in "*?[")):
            from .batch import find_tasks
            found = [f for f, _ in find_tasks(str(a))[0]]
            if not found and a.is_dir():
                raise TaskError("no task files (*.yaml, *.yml) in this folder", file=str(a))
            out += found or [a]
        else:
            out.append(a)
    return out
