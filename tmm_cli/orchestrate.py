"""One path from a task file to its outputs, shared by `run`, `validate`, `check`,
`batch`, `variants`, `paths` and `form`:

    prepare (load + validate over the whole cycle) -> compute -> write (partial results
    on a failed stage) -> (check)

and one mapping from what went wrong to an exit code, a status and a message, so every
command gives the same answer for the same task.
"""
from __future__ import annotations

from pathlib import Path
from typing import Callable

from .errors import StageError, TaskError

EXIT_OK, EXIT_ANSWERS, EXIT_INVALID, EXIT_STAGE = 0, 1, 2, 3


def prepare(path: str | Path, *, assembly: bool = True, text: str | None = None, stage_errors: bool = True):
    """The task, loaded and validated as `tmm validate` does: the schema, the mechanism a
    `synthesis` generates (linkage.synthesis.generate), the references, the positions named
    by other sections, and (with ``assembly``) that the linkage assembles at every crank
    angle. Raises TaskError (exit 2) or StageError (exit 3)."""
    return checked(path, assembly=assembly, text=text, stage_errors=stage_errors)[0]


def checked(path: str | Path, *, assembly: bool = True, text: str | None = None, stage_errors: bool = True):
    """(task, mechanism): :func:`prepare`'s task and the linkage's mechanism that validation
    built from it and checked over the cycle (None: no linkage, no ``assembly``, or a failed
    check), which :func:`compute` takes to compute on instead of building and checking it again."""
    from .task import load_task
    task = load_task(Path(path), text=text)
    crank_range = None
    if task.synthesis is not None:
        from .linkage.synthesis import SynthesisImpossible, generate
        try:
            task, design = generate(task)
            crank_range = design.crank_range
        except SynthesisImpossible:
            if stage_errors:
                raise          # requirements a lever synthesis cannot meet (exit 3)
            return task, None  # compute() meets the same failure
    mechanism = None
    if task.mechanism is not None:
        from .validation import check_feasible
        try:
            mechanism = check_feasible(task, assembly=assembly, crank_range=crank_range)
        except StageError:
            if stage_errors:
                raise
            # a valid task that cannot be computed everywhere: compute() meets the same
            # failure and keeps the sections computed before it (partial results)
    from .validation import check_sections
    check_sections(task, mechanism)
    return task, mechanism


# drawing data made for the HTML report only: kept out of results.json (a JSON run
# neither computes nor writes it; results.json is the same whatever the formats)
REPORT_ONLY = ("kinematics_explore", "kinetostatics_explore")


def compute(task, progress: Callable[[str], None] | None = None, *, explore: bool = False,
            lazy: bool = False, mechanism=None) -> dict:
    """The results dict. Raises TaskError, StageError or PartialResults (a StageError
    with the sections computed before the failure). ``explore``: also the data of the
    HTML report's mechanism in motion (``kinematics_explore``). ``lazy``: the
    per-position entries as the stages give them (:class:`tmm_cli.results.LazyEntries`,
    made when read: results.json is written block by block), else as lists.
    ``mechanism``: the one :func:`checked` gave with ``task``."""
    from .pipeline import run, run_listed
    return (run if lazy else run_listed)(task, progress=progress, explore=explore, mechanism=mechanism)


def write_outputs(task, results: dict, out: Path, formats: set[str], lang: str, *,
                  notes: list[str] | None = None, study: tuple[dict, dict] | None = None) -> list[Path]:
    """results.json (always: the reports are made from it) and the reports, each written
    atomically; the run's manifest in ``out`` then lists them, and the files of the
    previous run into ``out`` that were not written again are removed
    (:class:`tmm_cli.io.Manifest`). ``notes`` receives one line per output skipped (the
    PDF where its engine cannot run). ``study``: (study, trapezoid) of
    ``tmm_cli.study.run_study``, shown in the reports and written as study.json and
    study.html (never in results.json)."""
    from .io import folder_lock
    with folder_lock(out):              # one run writes into a folder at a time
        return _write_outputs(task, results, Path(out), formats, lang, notes=notes, study=study)


def _write_outputs(task, results: dict, out: Path, formats: set[str], lang: str, *,
                   notes: list[str] | None, study: tuple[dict, dict] | None) -> list[Path]:
    """write_outputs, the output folder locked."""
    from .io import Manifest, atomic_write
    from .results import dump

    manifest = Manifest(out)
    rep = set(formats) & {"html", "pdf", "note"}
    if rep or "sheets" in formats:      # they read the entries as lists: made once, for the file too
        from .results import listed
        results = listed(results)
    kept = {k: v for k, v in results.items() if k not in REPORT_ONLY}
    # a large results file written by a second process while the report or the sheets
    # are made (io.Aside): the same file, the same errors, in the same order of the list
    aside = _aside(out / "results.json", kept) if rep or "sheets" in formats else None
    written = [aside.path if aside is not None else atomic_write(out / "results.json",
                                                                 lambda write: dump(kept, write))]
    try:
        if rep:
            from .report import render
            shown = results if study is None else {**results, "study": study[0], "study_trapezoid": study[1]}
            written.extend(render(shown, task, out, rep, lang, notes=notes))
        if study is not None:
            from .report.sections import study as study_page
            written.extend(study_page.write(study[0], out, study[1], lang))
        if "sheets" in formats:   # the A1 drawing sheets (README, Drawing sheets)
            from .sheets import build_sheets, write_sheets
            written.extend(write_sheets(build_sheets(results, task, lang), out / "sheets", {"pdf", "svg", "dxf"}))
    except Exception:
        if aside is not None:     # written before the report, as one process does: its error first
            aside.finish()
        raise
    except BaseException:         # interrupted: the results file left as it was
        if aside is not None:
            aside.abandon()
        raise
    if aside is not None:
        aside.finish()
    manifest.commit(written)
    return written + [manifest.path]     # the manifest too: a batch removes the whole folder


# results files of at least this many per-position entries are written aside (io.Aside)
# while a report is made: the 12 positions of a task (~25 entries, 0.03 s to write) gain
# nothing from a second process; 3600 (7200 entries, ~1.6 s) gain that time
ASIDE_ENTRIES = 1000


def _aside(path: Path, kept: dict):
    """An :class:`tmm_cli.io.Aside` writing ``path``, or None (write it at once): a small
    file, TMM_REPORT_JOBS=1 (one process), a single core, no fork. The child writes the
    sections up to the last one of per-position entries; this process, its report made,
    the ones after it (the graphical-error block: ~1/8 of the file at 3600 positions)."""
    from .results import Entries, LazyEntries
    sizes = [len(v) if type(v) is Entries or type(v) is LazyEntries else 0 for v in kept.values()]
    if sum(sizes) < ASIDE_ENTRIES:
        return None
    from .io import Aside, workers_wanted
    if not workers_wanted():
        return None
    from .results import dump_parts
    last = max((i for i, n in enumerate(sizes) if n), default=len(sizes) - 1)
    return Aside.start(path, *dump_parts(kept, last + 1))


def process(path: str | Path, out, formats: set[str], lang: str, *,
            progress: Callable[[str], None] | None = None, task=None, mechanism=None, study: bool = False,
            notes: list[str] | None = None):
    """prepare -> compute -> write. Returns (task, results, written paths). On a failed
    stage every independent section is still computed, and results.json and the reports
    are written with them and, in place of the failed part, what failed; then the
    PartialResults is re-raised (its ``written`` the paths). ``out`` None: nothing is
    written; a callable: out(task) gives the folder. ``study``: also the accuracy study
    (``tmm run --study``). The results returned keep their per-position entries lazy
    (:func:`compute` with ``lazy``): a reader that takes them many times lists them
    (:func:`tmm_cli.results.listed`); but where a report or the sheets were made, they
    are listed as those read them. ``task``, ``mechanism``: what :func:`checked` gave
    (the task is then not read again)."""
    from .pipeline import PartialResults
    if task is None:
        task, mechanism = checked(path, stage_errors=False)
    folder = out(task) if callable(out) else out
    failure = None
    try:
        results = compute(task, progress, explore="html" in formats, lazy=True, mechanism=mechanism)
    except PartialResults as exc:
        results, failure = exc.partial, exc
    st = None
    if study and failure is None:
        from . import study as study_mod
        st = study_mod.run_study(task, progress=progress, repeat=3)
        note = study_mod.nothing_to_sweep(task, *st)
        if note is not None:     # no empty study.html: said as a warning
            st = None
            if notes is not None:
                notes.append(note)
    if folder is not None and set(formats) & {"html", "pdf", "sheets", "note"}:
        from .results import listed
        results = listed(results)   # as write_outputs reads them; returned so (made once)
    written = (write_outputs(task, results, folder, formats, lang, notes=notes, study=st)
               if folder is not None else [])
    if failure is not None:
        failure.written = written
        raise failure
    return task, results, written


def classify(exc: BaseException) -> tuple[int, str, str]:
    """(exit code, batch status, one-line message) of what went wrong."""
    if isinstance(exc, TaskError):
        return EXIT_INVALID, "invalid", exc.render()
    if isinstance(exc, StageError):
        return EXIT_STAGE, "failed", str(exc)
    if isinstance(exc, OSError):
        return EXIT_STAGE, "failed", write_error_text(exc)
    if isinstance(exc, MemoryError):
        return EXIT_STAGE, "failed", "out of memory (the per-variant memory limit was reached)"
    if isinstance(exc, RecursionError):
        return EXIT_STAGE, "failed", "internal error: recursion too deep"
    return EXIT_STAGE, "failed", f"internal error: {type(exc).__name__}: {exc}"


def write_error_text(exc: OSError) -> str:
    """stage 'output' failed: cannot write FILE: reason."""
    where = exc.filename if exc.filename is not None else ""
    reason = exc.strerror or str(exc) or type(exc).__name__
    if isinstance(exc, (FileExistsError, NotADirectoryError)):
        reason += " (a file is in the way of the output folder)"
    return f"stage 'output' failed: cannot write {where}: {reason}"
