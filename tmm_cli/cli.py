"""The `tmm` command line (README, *Commands*): the entry point.

Exit codes: 0 success; 1 answers outside tolerance; 2 invalid task (file, line and
field named, no traceback); 3 a stage failed on valid input (stage and position named).

The commands, their options and --help are the Typer app of :mod:`tmm_cli.commands`
(``tmm_cli.cli.app`` is that app). Building it costs more than validating a task, so
:func:`main` runs the two commands a user repeats most, ``tmm run`` and ``tmm validate``,
without it when their command line is a plain one (options given as ``--opt VALUE``,
values that are valid): the same code (:func:`run_task`, :func:`validate_tasks`), the
same output and exit code. Anything else (--help, an unknown or misspelt option, a
bad value, a missing argument) goes to the Typer app, which says what is wrong.
"""
from __future__ import annotations

import sys
from pathlib import Path
from typing import Callable

from .console import EXIT_STAGE, LANGS, echo, parse_formats, run_task, validate_tasks


# ----------------------------------------------------------------- the fast path
_RUN_VALUES = {"--out": "out", "-o": "out", "--format": "format", "-f": "format", "--lang": "lang", "-l": "lang"}
_RUN_FLAGS = {"--quiet": "quiet", "-q": "quiet", "--study": "study"}


def _plain_path(arg: str) -> bool:
    """An argument Typer turns into Path(arg) without a word: not empty, no NUL, valid
    UTF-8, and not an existing path it cannot read (Typer refuses that one)."""
    import os
    if not arg or "\x00" in arg:
        return False
    try:
        arg.encode("utf-8")
        return not os.path.exists(arg) or os.access(arg, os.R_OK)
    except (UnicodeError, OSError, ValueError):
        return False


def _streams_plain() -> bool:
    """stdout and stderr are text streams that click.echo writes to as they are (not
    missing, not ASCII: click would re-wrap those)."""
    import codecs
    for s in (sys.stdout, sys.stderr):
        enc = getattr(s, "encoding", None)
        if s is None or not enc:
            return False
        try:
            if codecs.lookup(enc).name == "ascii":
                return False
        except LookupError:
            pass
    return True


def _fast(argv: list[str]) -> Callable[[], int] | None:
    """The command of a plain `tmm run` / `tmm validate` command line, or None (the
    Typer app then parses it)."""
    if not argv or argv[0] not in ("run", "validate"):
        return None
    import os
    if any(k.startswith("_") and k.endswith("_COMPLETE") for k in os.environ):   # shell completion
        return None
    if not _streams_plain():
        return None
    cmd, rest = argv[0], argv[1:]
    opts: dict[str, object] = {}
    args: list[str] = []
    i = 0
    while i < len(rest):
        a = rest[i]
        if a.startswith("-"):
            if cmd == "run" and a in _RUN_FLAGS:
                opts[_RUN_FLAGS[a]] = True
            elif cmd == "run" and a in _RUN_VALUES and i + 1 < len(rest) and rest[i + 1] \
                    and not rest[i + 1].startswith("-"):
                opts[_RUN_VALUES[a]] = rest[i + 1]          # the last one counts, as in click
                i += 1
            elif cmd == "validate" and a == "--no-assembly":
                opts["no_assembly"] = True
            elif cmd == "validate" and a in ("--lang", "-l") and i + 1 < len(rest) and rest[i + 1] \
                    and not rest[i + 1].startswith("-"):
                opts["lang"] = rest[i + 1]
                i += 1
            else:
                return None                                 # --help, -x, --opt=value, '-', '--', ...
        else:
            args.append(a)
        i += 1
    paths = args + ([str(opts["out"])] if "out" in opts else [])
    if not args or not all(_plain_path(a) for a in paths):
        return None
    if cmd == "validate":
        files = [Path(a) for a in args]
        vlang = str(opts.get("lang", "en")).strip().lower()
        if vlang not in LANGS:
            return None                                     # the Typer app says what --lang takes
        return _collector_off(lambda: validate_tasks(files, bool(opts.get("no_assembly")), lang=vlang))
    if len(args) != 1:
        return None
    formats = parse_formats(str(opts.get("format", "json,html,pdf")))
    lang = str(opts.get("lang", "en")).strip().lower()         # RU is ru, as the Typer app reads it
    if formats is None or lang not in LANGS:
        return None
    out = Path(str(opts["out"])) if "out" in opts else None
    task_file = Path(args[0])
    # the results held by the command to the program's end (_exit_now): the ~10^6 objects
    # of a fine grid's entries are not freed one by one (~0.1 s at 3600 positions) by a
    # process about to end
    held: list = []
    command = lambda: run_task(task_file, out, formats, lang, bool(opts.get("quiet")), bool(opts.get("study")),
                               held=held)
    return _collector_off(command) if formats == {"json"} else command


def _collector_off(command: Callable[[], int]) -> Callable[[], int]:
    """``command`` with Python's cycle collector off, for the short commands that draw
    nothing (`tmm validate`, `tmm run --format json`): they build ~10^5 objects that live
    to the end (modules, the task model, the results) and next to no garbage cycles, and
    the collector's passes over them were ~5% of their work. (A report's figures make
    cycles: those runs keep the collector.)"""
    def run() -> int:
        import gc
        gc.disable()
        return command()
    return run


def _run_fast(command: Callable[[], int], exit_now: bool = False) -> None:
    """The command as the Typer app's standalone mode runs it: its exit code; Ctrl-C
    exit 130; end of input 'Aborted!' exit 1; a closed pipe exit 1. ``exit_now``: the
    command is the program (:func:`entry`): it ends by :func:`_exit_now`."""
    import errno
    try:
        code = command()
    except EOFError:
        echo("", err=True)
        echo("Aborted!", err=True)
        sys.exit(1)
    except KeyboardInterrupt:
        sys.exit(130)
    except OSError as e:
        if e.errno != errno.EPIPE:
            raise
        from typer._click.utils import PacifyFlushWrapper
        sys.stdout = PacifyFlushWrapper(sys.stdout)
        sys.stderr = PacifyFlushWrapper(sys.stderr)
        sys.exit(1)
    if exit_now:
        _exit_now(code)
    sys.exit(code)


def _exit_now(code: int) -> None:
    """End the program with ``code`` once its output is flushed, without the interpreter's
    shutdown: that frees every module and object one by one and runs the cycle collector
    over them all (5-10 % of a JSON run, more after a report's PDF engine)
    in a process that is ending anyway. The atexit callbacks run first, as the shutdown
    runs them (a report's: multiprocessing's join of its helper, tempfile's cleanup). When
    it would have more to do (another thread, python -i, output that cannot be flushed),
    the ordinary ``sys.exit``."""
    import atexit
    import os
    threading = sys.modules.get("threading")
    run_callbacks = getattr(atexit, "_run_exitfuncs", None)
    if ((getattr(atexit, "_ncallbacks", lambda: 1)() == 0 or run_callbacks is not None)
            and not sys.flags.inspect and (threading is None or threading.active_count() == 1)):
        if run_callbacks is not None:
            run_callbacks()           # as the shutdown would first (a report's: multiprocessing's, tempfile's)
        try:
            for stream in (sys.stdout, sys.stderr):
                if stream is not None:
                    stream.flush()
        except Exception:  # noqa: BLE001 - the ordinary exit reports it as before
            pass
        else:
            os._exit(code)
    sys.exit(code)


def _say(message: str) -> None:
    """A message of :func:`main` on stderr: typer.echo once the Typer app is in use."""
    typer = sys.modules.get("typer")
    (typer.echo if typer is not None else echo)(message, err=True)


def main(exit_now: bool = False) -> None:
    """``tmm`` with the arguments of the command line. ``exit_now``: this is the program
    (``tmm``, ``python -m tmm_cli``): a plain run / validate ends the process at once
    when done (:func:`_exit_now`); a caller that goes on after ``main`` leaves it off."""
    from .portable import utf8_console
    utf8_console()          # Cyrillic on a Windows console or a redirected stream in a legacy code page
    try:
        command = _fast(sys.argv[1:])
        if command is not None:
            _run_fast(command, exit_now)
        from .commands import app
        app(standalone_mode=True)
    except KeyboardInterrupt:
        _say("interrupted")
        sys.exit(130)
    except SystemExit:
        raise
    except Exception as exc:  # a defect of ours: say so plainly, still no traceback
        _say(f"error: internal error ({type(exc).__name__}: {exc}); please report it with the task file. "
             f"Run `python -m tmm_cli ...` with TMM_DEBUG=1 for the traceback.")
        if __import__("os").environ.get("TMM_DEBUG"):
            raise
        sys.exit(EXIT_STAGE)


# BLAS libraries start a pool of threads on their first call (OpenBLAS: one per core), which
# costs a short run more CPU than its small matrices gain; tmm's arrays are vectorised over
# positions, not large linear algebra.  One thread, unless the user's environment says otherwise.
BLAS_THREADS = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")


def single_blas_thread(environ=None) -> None:
    """Set each of :data:`BLAS_THREADS` to 1 where unset (before numpy is imported)."""
    import os

    env = os.environ if environ is None else environ
    for name in BLAS_THREADS:
        env.setdefault(name, "1")


def entry() -> None:
    """The ``tmm`` program (pyproject's console script; ``python -m tmm_cli``)."""
    single_blas_thread()
    main(exit_now=True)


def __getattr__(name: str):
    """The Typer app and its commands (``from tmm_cli.cli import app``), built on first use."""
    if name.startswith("__"):            # the import system's probes (__path__, ...)
        raise AttributeError(name)
    from . import commands
    try:
        return getattr(commands, name)
    except AttributeError:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}") from None


if __name__ == "__main__":
    main()
