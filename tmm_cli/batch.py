"""`tmm batch`: run and grade many variants; one variant never stops the rest.

The variants run on a pool of ``--jobs`` worker processes forked from the batch process
(started afresh, "spawn", where fork is not available: Windows, macOS; docs/platforms.md);
each worker runs variants one at a time (the batch sends it a variant's index over a
pipe, the worker leaves the outcome in a file and says so on a second pipe), with a time
limit (``--timeout``) and an address-space limit (``--memory``, RLIMIT_AS: the worker's
address space when the variant starts + the limit, so the limit is what one variant may
add; where RLIMIT_AS is not available the batch reads the workers' memory with psutil and
ends one past it). A worker that dies (a signal, the out-of-memory killer) is replaced by a fresh
fork, one that overruns its time is killed and replaced; its variant becomes one
``failed`` row with the reason, a variant past its memory too. A worker also ends, and a fresh fork takes its
place, after a variant that failed (out of memory, a stage's error), after
``MAX_VARIANTS`` variants, and once its address space has grown by ``RECYCLE_GROWTH``
over its start: what a variant leaves behind stays bounded and a failure's state never
reaches the next variant. The batch goes on and always writes summary.csv,
summary.html and check.csv. Every variant writes into its own sanitised, unique folder
inside ``--out``; a manifest (``.tmm-batch.json``) lists what the batch wrote, so the
next batch removes the files of variants that are gone and nothing else.
"""
from __future__ import annotations

import glob
import json
import os
import re
import signal
import stat
import sys
import time
from pathlib import Path, PurePath
from types import SimpleNamespace

from .check import STATUSES, AnswerSet, _same, set_code
from .messages import Message

SUMMARY_FIELDS = ["student", "group", "variant", "file", "status", "score", "answers", "ok", "outside", "sign",
                  "missing", "unknown_path", "not_computed", "message", "answers_file", "flags", "invalid"]
GRADEBOOK = "gradebook-moodle.csv"
RESERVED = {"summary.csv", "summary.html", "check.csv", "feedback", ".tmm-batch.json", GRADEBOOK}
# the columns of the gradebook file Moodle's grade import (CSV) maps: a user field to identify
# the student by (Email address -> useremail, ID number -> useridnumber), a grade, a feedback text
GRADEBOOK_FIELDS = ["Email address", "ID number", "Full name", "Group", "tmm grade", "Feedback"]
MANIFEST = ".tmm-batch.json"
DEFAULT_TIMEOUT = 120.0
DEFAULT_MEMORY_MB = 4096


# ------------------------------------------------------------------ inputs
def _not_regular(p: Path) -> Message | None:
    """Why a path named like a task file is not one (coded), or None."""
    try:
        st = os.stat(p)
    except FileNotFoundError:
        return Message("batch.dangling_link" if os.path.islink(p) else "batch.no_such_file")
    except OSError as exc:
        return Message("batch.unreadable", error=str(exc.strerror or exc))
    if stat.S_ISDIR(st.st_mode):
        return Message("batch.directory")
    if stat.S_ISFIFO(st.st_mode):
        return Message("batch.fifo")
    if not stat.S_ISREG(st.st_mode):
        return Message("batch.not_regular")
    return None


def _looks_like_answers(p: Path) -> bool:
    """An answers file in the group folder (no `schema:`, an `answers:` key) is not a variant."""
    try:
        with open(p, "rb") as fh:
            head = fh.read(65536).decode("utf-8", "replace")
    except OSError:
        return False
    return (re.search(r"^answers\s*:", head, re.M) is not None
            and re.search(r"^schema\s*:", head, re.M) is None)


def find_tasks(source: str) -> tuple[list[tuple[Path, str | None]], list[Path]]:
    """([(task file, reason it cannot be a task or None)], [answers files skipped])."""
    p = Path(source)
    if p.is_dir():
        cands = sorted(set(p.glob("*.yaml")) | set(p.glob("*.yml")))
    else:
        cands = sorted(Path(f) for f in glob.glob(source, recursive=True, include_hidden=True))
    out, skipped = [], []
    for f in cands:
        why = _not_regular(f)
        if why is None and _looks_like_answers(f):
            skipped.append(f)
            continue
        out.append((f, why))
    return out, skipped


def folder_names(files: list[Path]) -> list[str]:
    """A unique, safe folder name per task file: its stem as :func:`tmm_cli.safepath.safe_name`
    makes it (a name Windows and macOS take too), never a name of the batch's own files; a
    clash (v1.yaml and v1.yml, a/v2.yaml and b/v2.yaml, v3.yaml and V3.yaml: one folder
    on Windows and macOS) gets -2, -3..."""
    from .safepath import UniqueNames, safe_name
    used = UniqueNames()
    names = []
    for f in files:
        base = safe_name(f.stem, "task")
        if base.lower() in RESERVED or base.lower().startswith("summary."):
            base = "v_" + base
        names.append(used.take(base))
    return names


# ------------------------------------------------------------------ one variant (in the worker)
def work(path: Path, out: Path, folder: str, formats: set[str], lang: str, sets: list[AnswerSet] | None,
         tol_override: dict | None, quantities: str | None, options: dict | None = None) -> dict:
    """Run, write and grade one variant. Never raises: errors become the outcome.
    ``options``: ``feedback`` ('key' | 'no-key'); with answer sets the outcome carries the
    variant's ``key`` (path -> (reference, tolerance, angle)) for the paths any set answered."""
    from .check import check_csv, counts, grade, set_status, task_answer_set, tolerances
    from .io import atomic_write
    from .orchestrate import checked, classify, process

    vout = out / folder
    res: dict = {"task": None, "written": [], "sets": [], "code": 0, "status": "ok", "message": "", "notes": []}
    try:
        task, mechanism = checked(path, stage_errors=False)
        res["task"] = {"title": task.title, "variant": task.variant, "name": task.name,
                       "student": task.who[0], "group": task.who[1]}
        try:
            task, results, written = process(path, vout, formats, lang, task=task, mechanism=mechanism)
        except BaseException as exc:
            # a failed stage: results.json and the report were written with what was computed
            from .pipeline import PartialResults
            partial = exc.written if isinstance(exc, PartialResults) else None
            if partial:
                res["written"] = [_rel(p, out) for p in partial if _inside(p, out)]
            elif (vout / "results.json").exists():
                res["written"].append(f"{folder}/results.json")
            raise
        res["written"] = [_rel(p, out) for p in written if _inside(p, out)]
        style = (options or {}).get("csv", "plain")
        if style != "plain":          # every CSV of the run in the spreadsheet's style
            from .tables import csv_styled
            for p in written:
                if str(p).endswith(".csv"):
                    atomic_write(p, csv_styled(Path(p).read_text(encoding="utf-8"), style))
        if sets is None:
            own = task_answer_set(task)
            mine = [(-1, own)] if own else []
        else:
            mine = [(i, s) for i, s in enumerate(sets) if s.matches(task)]
        if mine or sets:        # graded: the entries as lists (looked up answer by answer)
            from .results import listed
            results = listed(results)
        tol = tolerances(task, tol_override, results=results) if (mine or sets) else {}
        if sets:
            res["key"] = variant_key(results, {p for a in sets for p in a.answers}, tol)
        all_rows = []
        for i, aset in mine:
            if aset.error:
                res["sets"].append({"index": i, "status": "invalid", "message": aset.error, "rows": [],
                                    "student": aset.student, "group": aset.group, "variant": aset.variant,
                                    "answers_file": aset.answers_file})
                continue
            required = None
            if quantities:
                from .forms import expand
                required = expand(quantities, results, strict=False)
            rows = grade(results, aset, tol, required)
            # the set answers this task: its variant as the task writes it ('07' matched 7; a file
            # matched by its name had none in check.csv)
            shown = task.variant if task.variant is not None else aset.variant
            for r in rows:
                r["variant"] = "" if shown is None else shown
            all_rows.extend(rows)
            sst = set_status(rows)
            res["sets"].append({"index": i, "status": sst, "rows": rows, "counts": counts(rows),
                                "student": aset.student, "group": aset.group, "answers_file": aset.answers_file,
                                "variant": shown,
                                "message": _set_message(rows, sst, aset)})
        if mine:
            from .tables import csv_styled
            atomic_write(vout / "check.csv", csv_styled(check_csv(all_rows), style))
            res["written"].append(f"{folder}/check.csv")
            from .feedback import write_feedback
            for s in res["sets"]:
                if s["rows"]:
                    p = write_feedback(task, s, vout, lang, pdf="pdf" in formats, notes=res["notes"],
                                       key=(options or {}).get("feedback", "key") != "no-key")
                    s["feedback"] = [_rel(x, out) for x in p]
                    res["written"].extend(s["feedback"])
        if mine or sets:                     # a misspelt tolerance key: said once for the batch
            from .check import unused_tolerance_keys
            res["notes"].extend(unused_tolerance_keys(set(task.tolerance or {}) | set(tol_override or {}), results))
            from .check import angle_tolerance_note
            if (wide := angle_tolerance_note([r for s in res["sets"] for r in s["rows"]], tol)) is not None:
                res["notes"].append(wide)          # after the feedback pages: the instructor's, not theirs
    except BaseException as exc:  # one broken variant must not stop the batch
        if isinstance(exc, KeyboardInterrupt):
            raise
        res["code"], res["status"], res["message"] = classify(exc)
        coded = stage_failure_message(exc)
        if coded is not None and str(coded) == res["message"]:
            res["message_coded"] = coded            # the same text, in the report language too
    return res


def variant_key(results: dict, paths: set[str], tol: dict) -> dict:
    """path -> (reference, Tol, angle: check.angle_kind) of the paths that hold a number in
    ``results``."""
    from .check import Tol, angle_kind, parse_tolerance, tolerance_for
    from .results import lookup
    key = {}
    for p in sorted(paths):
        try:
            v = lookup(results, p)
        except KeyError:
            continue
        if isinstance(v, (int, float)) and not isinstance(v, bool) and v == v:
            t = tolerance_for(p, tol, count=type(v) is int)
            key[p] = (float(v), t if isinstance(t, Tol) else parse_tolerance(t, p), angle_kind(p))
    return key


def stage_failure_message(exc: BaseException) -> Message | None:
    """A StageError whose message is coded, as one coded message ("stage 'cam' failed at
    ...: ..."), the text of ``str(exc)``; an invalid task (TaskError) as its coded lines
    (``TaskError.coded``); None for any other failure."""
    from .errors import StageError, TaskError
    if isinstance(exc, TaskError):
        return exc.coded()
    if not isinstance(exc, StageError) or not isinstance(exc.message, Message) or exc.message.code is None:
        return None
    pos = exc.position
    if pos is None:
        where = Message("text", text="")
    elif isinstance(pos, str):                 # (no stage gives a named position today)
        where = Message("text", text=f" at {pos}")
    else:
        where = Message("batch.at_angle", angle=float(pos))
    return Message("batch.stage_failed", stage=exc.stage, where=where, message=exc.message)


def _rel(p, out: PurePath) -> str:
    """``p`` relative to ``out`` with '/' between the parts on every system (Windows too):
    the manifest's entries and summary.html's links (a '\\' would be quoted into a link
    that leads nowhere)."""
    return type(out)(p).relative_to(out).as_posix()


def _inside(p, out: Path) -> bool:
    try:
        Path(p).relative_to(out)
        return True
    except ValueError:
        return False


def _set_message(rows, status, aset) -> str:
    if status == "no_answers":
        return Message("batch.set_no_answers", file=Path(aset.source).name)
    parts = []       # each status with its paths: "outside: a, b; invalid: c"
    for st in ("outside", "invalid", "sign", "missing", "unknown_path", "not_computed"):
        bad = [r["path"] for r in rows if r["status"] == st]
        if bad:
            parts.append(Message("batch.set_not_ok" if len(bad) <= 6 else "batch.set_not_ok_more", status=st,
                                 paths=bad[:6]))
    if len(parts) <= 1:
        return parts[0] if parts else ""
    return Message("batch.set_statuses", parts=parts)


def _variants_beside(source: str, files: list[Path]) -> set[str]:
    """The variants (file stems and `variant:` lines) of the task files beside those a
    pattern matched, in their folders, that the pattern left out: answers for them are
    not this run's. Empty when the source is a folder (every task in it runs)."""
    if Path(source).is_dir():
        return set()
    given = {Path(f).resolve() for f in files}
    out: set[str] = set()
    line = re.compile(r"""^variant\s*:\s*["']?([^"'#\n]*?)["']?\s*(?:#.*)?$""", re.M)
    for d in {Path(f).parent for f in files}:
        for f in set(d.glob("*.yaml")) | set(d.glob("*.yml")):
            if f.resolve() in given or _not_regular(f) is not None or _looks_like_answers(f):
                continue
            out.add(f.stem)
            try:
                with open(f, "rb") as fh:
                    m = line.search(fh.read(65536).decode("utf-8", "replace"))
            except OSError:
                m = None
            if m and m.group(1).strip():
                out.add(m.group(1).strip())
    return out


# the modules a variant's sections need (imported once in the batch, before the workers fork)
_SECTION_MODULES = {"mechanism": ("linkage.mechanism", "linkage.structure", "linkage.kinematics",
                                  "linkage.kinematics.changepoints", "linkage.loads", "linkage.kinetostatics",
                                  "linkage.dynamics", "linkage.drive_speed", "graphical", "plans"),
                    "synthesis": ("linkage.synthesis",), "cam": ("cam", "cam.laws", "cam.synthesis"),
                    # the packages load their stages on first use: the stage modules named
                    "gears": ("gears", "gears.involute", "gears.geometry", "gears.shifts", "gears.tooth",
                              "gears.analysis"),
                    "planetary": ("gears", "gears.involute", "gears.geometry", "gears.planetary"),
                    "drive_train": ("gears", "gears.involute", "gears.geometry", "gears.planetary", "gears.train"),
                    "dof2": ("dof2", "dof2.analysis")}
_SECTION_MODULES["synthesis"] += _SECTION_MODULES["mechanism"]
# modules outside tmm_cli the stages import on first use (numpy's `np.unique` imports
# numpy.ma; the plans' scales): ~30 ms a variant
_FIRST_USE = {"mechanism": ("numpy.ma", "tmm_cli.scales")}
_FIRST_USE["synthesis"] = _FIRST_USE["mechanism"]


def warm(files: list[Path], formats) -> None:
    """Do in the batch process, once, what every worker would otherwise repeat: import the
    modules of the sections the task files have (a top-level key ``cam:`` etc.) and of the
    outputs asked for, and build the task model's validator. The workers are forked from
    this process, so they start warm.
    Anything that fails here is left to the variant that needs it."""
    import gc
    import importlib
    sections: set[str] = set()
    pattern = re.compile(r"^(" + "|".join(_SECTION_MODULES) + r")\s*:", re.M)
    for f in files:
        try:
            with open(f, "rb") as fh:
                sections.update(pattern.findall(fh.read(65536).decode("utf-8", "replace")))
        except OSError:
            pass
    names = ["orchestrate", "pipeline", "validation", "yamlload", "input_notices", "results", "io", "check"]
    for sec in sorted(sections):
        names += _SECTION_MODULES[sec]
    if set(formats) & {"html", "pdf"}:
        names.append("report")
    full = [f"{__package__}.{name}" for name in names]
    for sec in sorted(sections):
        full += _FIRST_USE.get(sec, ())
    for name in dict.fromkeys(full):
        try:
            importlib.import_module(name)
        except Exception:   # noqa: BLE001  (the variant that needs it reports the failure)
            pass
    try:
        from .task import Task
        Task.model_rebuild()
    except Exception:   # noqa: BLE001
        pass
    if set(formats) & {"html", "pdf"}:
        try:
            from .report import warm_templates
            warm_templates()            # compiled once here, not once per variant
        except Exception:   # noqa: BLE001  (the variant that needs them reports the failure)
            pass
    gc.freeze()         # the workers' collections leave the inherited objects (and their pages) alone
    # (no gc.collect() first, as Python's gc.freeze documents the recipe: it is 7 % of the warm-up
    # here and a full pass over every object of a long-lived caller's heap, such as a test run's)


def _address_space() -> int:
    """Bytes of virtual memory this process has mapped now (0 where it cannot be read)."""
    try:
        with open("/proc/self/statm", "rb") as fh:
            return int(fh.read().split()[0]) * os.sysconf("SC_PAGE_SIZE")
    except (OSError, ValueError, IndexError, AttributeError):
        pass
    return _vms(os.getpid())        # no /proc (Windows, macOS): psutil's reading


def _vms(pid: int) -> int:
    """The virtual memory size of process ``pid`` (psutil's ``vms``: the address space on
    Linux and macOS, the committed private memory on Windows); 0 where it cannot be read."""
    try:
        import psutil
        return int(psutil.Process(pid).memory_info().vms)
    except Exception:  # noqa: BLE001 - psutil missing, the process gone: no reading
        return 0


def _rlimit_available() -> bool:
    """The worker can limit its own address space (RLIMIT_AS): Linux. macOS has the call
    but does not enforce it; Windows has no ``resource``: there the batch watches the
    workers' memory (:func:`_memory_watch`)."""
    if not sys.platform.startswith("linux"):
        return False
    try:
        import resource
    except ImportError:
        return False
    return hasattr(resource, "RLIMIT_AS")


def _memory_watch() -> bool:
    """The batch can read a worker's memory from outside (psutil)."""
    try:
        import psutil  # noqa: F401
    except ImportError:
        return False
    return True


# the worker pool: how long a worker lives
MAX_VARIANTS = 100                 # a worker runs at most this many variants, then a fresh one replaces it
RECYCLE_GROWTH = 256 * 1024 ** 2   # ... or fewer, once its address space grew this much over its start
STARTUP = 60.0                     # s: a worker's time to start (spawned: imports) before --timeout counts
WATCH_INTERVAL = 0.1               # s: how often the batch reads the workers' memory where they cannot limit it


def _failed(message) -> dict:
    return {"task": None, "written": [], "sets": [], "code": 3, "status": "failed", "message": message}


def _run_one(result_file: str, memory_mb, args, work_fn=None) -> bool:
    """In a worker: limit what this variant may add to the address space (``memory_mb``:
    None where the batch watches it from outside), run it, leave
    the outcome in ``result_file`` (a file, not a pipe: nothing can block between a
    dying worker and the batch). True when the worker should end: the variant ran out of
    memory or failed."""
    import pickle
    oom = False
    try:
        if memory_mb:
            import resource
            # the limit is what the variant may add: the worker's address space now (the
            # batch process's, inherited by the fork, and what earlier variants left) + --memory;
            # only the soft limit, so the next variant can have its own
            hard = resource.getrlimit(resource.RLIMIT_AS)[1]
            lim = int(memory_mb) * 1024 * 1024 + _address_space()
            if hard != resource.RLIM_INFINITY:
                lim = min(lim, hard)
            resource.setrlimit(resource.RLIMIT_AS, (lim, hard))
        res = (work_fn or work)(*args)
    except MemoryError:
        oom = True
        res = _failed(Message("batch.out_of_memory", limit=memory_mb))
    try:
        data = pickle.dumps(res)
    except Exception as exc:  # noqa: BLE001 - whatever fails to pickle, the worker still reports
        data = pickle.dumps(_failed(Message("batch.no_report", error=type(exc).__name__)))
    tmp = result_file + ".part"
    with open(tmp, "wb") as fh:
        fh.write(data)
    os.replace(tmp, result_file)
    return oom or res.get("status") == "failed"


def _worker(work_fn, jobs_args, tmpdir: str, memory_mb, task_r, done_w, close: list[int],
            policy: tuple[int, int], spawned: bool = False) -> None:
    """A worker of the pool: read a variant's index from ``task_r``, acknowledge it
    ("<index> a" to ``done_w``), run it (``work_fn``: :func:`work`, passed so that a
    spawned worker runs the same function as a forked one), write its outcome to
    ``tmpdir/<index>.pickle``, then "<index> <retire>" to ``done_w``; exit on
    end of input, after ``MAX_VARIANTS`` variants, once its address space has grown by
    ``RECYCLE_GROWTH`` (``policy``: the two, as the batch has them), or after a variant
    that failed (out of memory, a stage's error): the batch then starts a fresh worker.
    ``close``: the descriptors of the batch's ends of every worker's pipes, which a forked
    worker inherits (a spawned one inherits nothing: empty). A ``spawned`` worker first
    does what the batch does before it forks (:func:`warm`): its first variant then runs
    as fast as the next ones, and its growth is counted from there."""
    for fd in close:
        try:
            os.close(fd)
        except OSError:
            pass
    try:
        if spawned and jobs_args:
            warm([a[0] for a in jobs_args], jobs_args[0][3])
        from .io import deferred_sync
        with deferred_sync():   # the variants' files flushed to the disk at once by the batch (flush_all)
            _serve(work_fn, jobs_args, tmpdir, memory_mb, task_r, done_w, policy)
    except KeyboardInterrupt:          # Ctrl-C reaches the workers too: the batch reports it
        os._exit(130)
    os._exit(0)                    # no atexit handlers or inherited threads of the parent


def _serve(work_fn, jobs_args, tmpdir: str, memory_mb, task_r, done_w, policy: tuple[int, int]) -> None:
    max_variants, growth = policy
    start = _address_space()
    for n in range(1, max_variants + 1):
        try:
            i = int(task_r.recv_bytes())
        except (EOFError, OSError):
            return
        done_w.send_bytes(b"%d a %d" % (i, _address_space()))   # begun (a death from now on is this
        # variant's), with the memory it begins from (the batch's base where it watches memory)
        retire = _run_one(os.path.join(tmpdir, f"{i}.pickle"), memory_mb, jobs_args[i], work_fn)
        retire = retire or n == max_variants or _address_space() - start > growth
        done_w.send_bytes(b"%d %d" % (i, retire))       # a few bytes: never blocks
        if retire:
            break


def _death(exitcode: int | None, memory_mb) -> str:
    if exitcode is not None and exitcode < 0:
        sig = -exitcode
        try:
            name = signal.Signals(sig).name
        except ValueError:
            name = f"signal {sig}"
        if sig == getattr(signal, "SIGKILL", None):
            return Message("batch.worker_killed", signal=name)
        return Message("batch.worker_signal", signal=name)
    return Message("batch.worker_exit", code=exitcode, limit=memory_mb)


class _Slot:
    """The batch's side of one worker: its process, the pipe it reads variants from, the
    pipe it reports on (multiprocessing's connections: they pass to a forked and to a
    spawned worker alike), the variant it runs (index, start time) and the worker's memory
    when that variant began (where the batch watches it)."""

    def __init__(self, ctx, jobs_args, tmpdir, memory_mb, parent_fds: set[int], work_fn=None, watch=False):
        task_r, self.task_w = ctx.Pipe(duplex=False)
        self.done_r, done_w = ctx.Pipe(duplex=False)
        own = {self.task_w.fileno(), self.done_r.fileno()}
        parent_fds.update(own)
        close = sorted(parent_fds) if ctx.get_start_method() == "fork" else []
        self.proc = ctx.Process(target=_worker, args=(work_fn or work, jobs_args, tmpdir, memory_mb, task_r, done_w,
                                                      close, (MAX_VARIANTS, RECYCLE_GROWTH),
                                                      ctx.get_start_method() != "fork"), daemon=False)
        try:
            self.proc.start()
        finally:
            task_r.close()
            done_w.close()
        self.parent_fds, self.own = parent_fds, own
        self.watch = watch
        self.i: int | None = None
        self.t0 = 0.0
        self.base = 0
        self.buf: list[bytes] = []
        self.retire = False
        self.begun = False             # the worker acknowledged variant i (it began it)

    def send(self, i: int) -> bool:
        """Give the worker variant i; False when it is gone (then it gets a successor)."""
        if not self.proc.is_alive():
            return False
        self.base = 0                  # until the worker says it began (its memory then)
        try:
            self.task_w.send_bytes(b"%d" % i)
        except OSError:
            return False
        self.i, self.t0, self.begun = i, time.monotonic(), False
        return True

    def deadline(self, timeout: float) -> float:
        """When the variant overruns ``timeout``: counted from when the worker began it; a
        worker that has not begun it yet (a spawned one starting: a fresh interpreter
        importing the modules) has ``STARTUP`` more."""
        return self.t0 + timeout + (0.0 if self.begun else STARTUP)

    def over_memory(self, memory_mb) -> bool:
        """The watched worker's memory grew by more than ``memory_mb`` since it began its
        variant (not since it was started: a spawned worker's imports are not the variant's)."""
        return bool(self.watch and memory_mb and self.base
                    and _vms(self.proc.pid) - self.base > int(memory_mb) * 1024 * 1024)

    def reports(self) -> list[tuple[int, str]]:
        """The "<index> a <memory>" (begun) and "<index> <retire: 0|1>" (done) messages the
        worker has sent and not yet read, as (index, "a" | "0" | "1"); the memory of the
        current variant's start kept as ``base``."""
        out = []
        while True:
            try:
                if not self.done_r.poll(0):
                    break
                parts = self.done_r.recv_bytes().split()
            except (EOFError, OSError):
                break
            if len(parts) < 2:
                continue
            k, what = int(parts[0]), parts[1].decode()
            if what == "a" and k == self.i and len(parts) > 2:
                self.base = int(parts[2])
            out.append((k, what))
        return out

    def close(self, kill: bool) -> None:
        if kill:
            _kill(self.proc)
        for conn in (self.task_w, self.done_r):
            try:
                conn.close()
            except OSError:
                pass
        self.parent_fds.difference_update(self.own)
        self.proc.join(5)
        if self.proc.is_alive():
            _kill(self.proc)


def run_all(jobs_args: list[tuple], *, jobs: int, timeout: float, memory_mb: int | None, on_done,
            method: str | None = None) -> list[dict]:
    """Run the jobs on a pool of at most ``jobs`` workers (started by ``method``, fork or
    spawn: :func:`tmm_cli.portable.start_method` by default), each running variants
    one at a time; return the outcomes in order. ``on_done(i, outcome)`` is called as
    each finishes. A worker that dies or overruns ``timeout`` fails the variant it was
    running, is replaced by a fresh one, and the batch goes on. Where a worker cannot
    limit its own memory (:func:`_rlimit_available`), the batch reads it every
    ``WATCH_INTERVAL`` and ends one whose variant added more than ``memory_mb``. A worker
    that died before it acknowledged its variant (killed from outside while idle, just as
    the variant was sent) did not run it: the variant is given, once, to a fresh worker."""
    import multiprocessing as mp
    import pickle
    import shutil
    import tempfile
    from multiprocessing.connection import wait

    from .portable import start_method

    ctx = mp.get_context(method or start_method())
    watch = bool(memory_mb) and not _rlimit_available() and _memory_watch()
    limit_in_worker = memory_mb if memory_mb and _rlimit_available() else None
    work_fn = work                     # as this module has it now (a test may replace it)
    results: list[dict | None] = [None] * len(jobs_args)
    pending = list(range(len(jobs_args)))
    pending.reverse()                  # pop() from the end: the variants in order
    slots: list[_Slot] = []
    parent_fds: set[int] = set()
    resent: set[int] = set()           # the variants sent again after their worker died idle
    tmpdir = tempfile.mkdtemp(prefix="tmm-batch-")

    def load(i):
        rf = os.path.join(tmpdir, f"{i}.pickle")
        try:
            with open(rf, "rb") as fh:
                return pickle.load(fh)
        except (OSError, EOFError, pickle.UnpicklingError):
            return None
        finally:
            try:
                os.unlink(rf)
            except OSError:
                pass

    try:
        while pending or any(s.i is not None for s in slots):
            for s in slots:                                   # idle workers take the next variants
                if s.i is None and not s.retire and pending:
                    if s.send(pending[-1]):
                        pending.pop()
                    else:
                        s.retire = True
            for s in [s for s in slots if s.retire and s.i is None]:
                s.close(kill=False)
                slots.remove(s)
            while pending and len(slots) < max(1, jobs):      # fresh workers for the rest
                s = _Slot(ctx, jobs_args, tmpdir, limit_in_worker, parent_fds, work_fn, watch)
                slots.append(s)
                if s.send(pending[-1]):
                    pending.pop()
                else:
                    s.retire = True
                    break
            busy = [s for s in slots if s.i is not None]
            if not busy:
                continue
            now = time.monotonic()
            left = min(s.deadline(timeout) - now for s in busy) if timeout else None
            if watch:
                left = WATCH_INTERVAL if left is None else min(left, WATCH_INTERVAL)
            wait([s.proc.sentinel for s in busy] + [s.done_r for s in busy],
                 timeout=None if left is None else max(0.0, left))
            now = time.monotonic()
            for s in busy:
                res, i = None, s.i
                reports = [r for k, r in s.reports() if k == i]
                if "a" in reports and not s.begun:
                    s.begun, s.t0 = True, now      # the time limit counts from here
                done = [r == "1" for r in reports if r != "a"]
                if done:
                    res = load(i)
                    if res is None:
                        res = _failed(Message("batch.no_report", error="no result file"))
                    s.retire = s.retire or done[0]
                elif not s.proc.is_alive():
                    s.proc.join()
                    s.begun = s.begun or "a" in [r for k, r in s.reports() if k == i]   # its last words
                    s.retire = True
                    res = load(i)              # it may have died after writing its outcome
                    if res is None and not s.begun and i not in resent:
                        resent.add(i)          # it never began the variant: a fresh worker runs it
                        pending.append(i)
                        s.i = None
                        continue
                    if res is None:
                        res = _failed(_death(s.proc.exitcode, memory_mb))
                elif timeout and now > s.deadline(timeout):
                    _kill(s.proc)
                    res = _failed(Message("batch.timeout", timeout=timeout))
                    s.retire = True
                elif s.over_memory(memory_mb):
                    _kill(s.proc)
                    res = _failed(Message("batch.out_of_memory", limit=memory_mb))
                    s.retire = True
                if res is not None:
                    s.i = None
                    results[i] = res
                    on_done(i, res)
    finally:
        for s in slots:
            s.close(kill=s.i is not None)
        shutil.rmtree(tmpdir, ignore_errors=True)
    return results  # type: ignore[return-value]


def _kill(proc) -> None:
    """End a worker and the report helper it may have forked (its own process group is
    not used: the helper exits when its parent's pipe closes)."""
    if proc.is_alive():
        if hasattr(signal, "SIGKILL"):
            proc.kill()
        else:                       # Windows: terminate is TerminateProcess, as final as SIGKILL
            proc.terminate()
    proc.join(5)


def _remove_own_temps(out: Path, since: float) -> list[Path]:
    """The temporary files ``.NAME.<random>.tmp`` (atomic_write's) under ``out`` made
    since ``since``: left by workers ended while writing. Only regular files, no links
    followed."""
    from .io import _TMP
    removed = []
    for root, dirs, names in os.walk(out):
        for name in names:
            if not _TMP.match(name):
                continue
            p = os.path.join(root, name)
            try:
                st = os.lstat(p)
                if stat.S_ISREG(st.st_mode) and st.st_mtime >= since - 1.0:
                    os.unlink(p)
                    removed.append(Path(p))
            except OSError:
                continue
    return removed


# ------------------------------------------------------------------ manifest
def _read_manifest(out: Path) -> set[str]:
    try:
        data = json.loads((out / MANIFEST).read_text(encoding="utf-8"))
        files = data.get("files", []) if isinstance(data, dict) else []
        return {f for f in files if isinstance(f, str)}
    except (OSError, ValueError):
        return set()


def _remove_stale(out: Path, old: set[str], new: set[str]) -> list[str]:
    """Remove files a previous batch wrote that this one did not (variants that are gone),
    then their folders if empty. Only paths inside ``out``, only regular files."""
    removed = []
    root = out.resolve()
    for rel in sorted(old - new):
        p = out / rel
        try:
            if ".." in Path(rel).parts or Path(rel).is_absolute():
                continue
            if not p.resolve().is_relative_to(root) or p.is_symlink() or not p.is_file():
                continue
            p.unlink()
            removed.append(rel)
        except OSError:
            continue
        d = p.parent
        while d != out and d.is_relative_to(out):
            try:
                d.rmdir()
            except OSError:
                break
            d = d.parent
    return removed


# ------------------------------------------------------------------ the batch
def run_batch(source: str, out: Path, **kwargs) -> int:
    """:func:`_run_batch` with the output folder locked (tmm_cli.io.folder_lock): two
    batches (or a batch and a run) into one folder never interleave."""
    from .io import folder_lock
    with folder_lock(out):
        return _run_batch(source, out, **kwargs)


def _run_batch(source: str, out: Path, *, jobs: int = 1, formats: set[str] = frozenset({"json"}), lang: str = "en",
               answers: Path | None = None, tolerance: Path | None = None, quantities: str | None = None,
               timeout: float = DEFAULT_TIMEOUT, memory_mb: int | None = DEFAULT_MEMORY_MB,
               latest: bool = False, grades: list[tuple[int, float]] | None = None, gradebook: str | None = None,
               feedback: str = "key", csv_style: str = "plain") -> int:
    from rich.console import Console

    from .check import CHECK_FIELDS, load_sources, load_tolerance_file, repeats
    from .errors import TaskError
    from .io import atomic_write, deferred_sync, flush_all
    from .tables import csv_text

    con = Console(stderr=True, highlight=False)
    found, skipped = find_tasks(source)
    if not found:
        con.print(f"error: no task files match '{source}'", markup=False)
        return 2
    try:
        sets = load_sources(answers) if answers is not None else None
        tol_override = load_tolerance_file(tolerance) if tolerance is not None else None
    except TaskError as exc:
        # the file it is (`invalid answers file`, `invalid tolerance file`); a table's or a folder's
        # own error: `invalid answers`
        con.print(f"error: invalid {exc.kind if exc.kind != 'task' else 'answers'}\n{exc.render()}", markup=False)
        return 2
    set_notes = []
    if sets is not None:
        sets, set_notes = repeats(sets, latest)
    out.mkdir(parents=True, exist_ok=True)
    old_files = _read_manifest(out)
    files = [f for f, _ in found]
    folders = folder_names(files)
    runnable = [k for k, (f, why) in enumerate(found) if why is None]
    outcomes: dict[int, dict] = {}
    for k, (f, why) in enumerate(found):
        if why is not None:
            why = Message("batch.not_a_task", file=str(f), reason=why)
            outcomes[k] = {"task": None, "written": [], "sets": [], "code": 2, "status": "invalid",
                           "message": why, "message_coded": why}
    options = {"feedback": feedback, "csv": csv_style}
    args = [(found[k][0], out, folders[k], set(formats), lang, sets, tol_override, quantities, options)
            for k in runnable]
    from .portable import start_method
    if start_method() == "fork":       # the workers inherit what the batch imported
        warm([found[k][0] for k in runnable], formats)
    if memory_mb and not _rlimit_available() and not _memory_watch():
        from .messages import in_lang
        con.print(in_lang(Message("batch.memory_unlimited", limit=memory_mb), lang), markup=False)
    from .summary import batch_words
    words = batch_words(lang)
    with _progress(con, len(args), words["variants"], words["left"]) as advance:
        def done(i, res):
            advance()
        started = time.time()
        try:
            with deferred_sync():       # (and so in a forked worker from its start)
                res_list = run_all(args, jobs=jobs, timeout=timeout, memory_mb=memory_mb, on_done=done)
        except KeyboardInterrupt:
            # Ctrl-C: the workers are gone, some killed while writing; their temporary
            # files (never a file under its own name) go too, so nothing half-written stays
            _remove_own_temps(out, started)
            raise
        finally:
            import gc
            gc.unfreeze()
    for k, res in zip(runnable, res_list):
        outcomes[k] = res
    # the variants' files, put in place unflushed (io.deferred_sync), flushed to the disk at
    # once, before the summary and the manifest that list them
    flush_all(out)

    # no_answers fails (exit 1) only when answers were expected
    expected = sets is not None or any(o.get("sets") for o in outcomes.values())
    rows, check_rows, written = [], [], set()
    matched: set[int] = set()
    for k in range(len(found)):
        res, f, folder = outcomes[k], files[k], folders[k]
        written.update(res.get("written", []))
        t = res.get("task") or {}
        base = {"student": t.get("student", ""), "group": t.get("group", ""),
                "variant": "" if t.get("variant") is None else t.get("variant"), "file": str(f),
                "folder": folder}
        note = "" if folder == f.stem else Message("batch.results_in", folder=folder)
        if res["status"] != "ok":
            failure = {"status": res["status"], "message": res["message"] + note, "code": res["code"],
                       "message_parts": [res.get("message_coded", res["message"]), note]}
            # the students who answered this variant: each a row with why it was not graded (its
            # task failed or is invalid), not "no task of this variant"
            probe = SimpleNamespace(variant=t.get("variant"), name=t.get("name") or f.stem)
            theirs = [i for i, s in enumerate(sets or []) if i not in matched and not s.error and s.matches(probe)]
            for i in theirs:
                matched.add(i)
                s = sets[i]
                rows.append({**base, **failure, "student": s.student, "group": s.group,
                             "variant": base["variant"] if s.variant in (None, "") else s.variant,
                             "answers_file": s.answers_file, "flags": ";".join(s.flags)})
            if not theirs:
                rows.append({**base, **failure})
            continue
        if not res["sets"]:
            st = "no_answers" if expected else "ok"
            msg = Message("batch.nobody_answered" if expected else "batch.no_answers_to_check")
            rows.append({**base, "status": st, "code": 1 if expected else 0,
                         "message": msg + note, "message_parts": [msg, note]})
            continue
        for s in res["sets"]:
            matched.add(s["index"])
            c = s.get("counts") or {}
            n = sum(c.values()) - c.get("unknown_path", 0)       # a misspelt path answers no quantity
            own = s["index"] < 0            # the task's own `answers`: the task's student
            aset = None if own else sets[s["index"]]
            row = {**base, "student": s["student"] or (base["student"] if own else ""),
                   "group": s["group"] or (base["group"] if own else ""),
                   "answers_file": s.get("answers_file", ""), "flags": ";".join(aset.flags if aset else []),
                   "variant": "" if s["variant"] is None else s["variant"], "status": s["status"],
                   "code": set_code(s["status"]), "message": s["message"] + note, "answers": n,
                   "message_parts": [s["message"], note],
                   "score": round(c.get("ok", 0) / n, 4) if n else 0, "feedback": s.get("feedback", []),
                   "per_path": {r["path"]: r["status"] for r in s["rows"]}, "rows": s["rows"],
                   "_k": k, "_set": aset, **{k: c.get(k, 0) for k in STATUSES}}
            rows.append(row)
            check_rows.extend(s["rows"])
    outside = _variants_beside(source, files)
    skipped_sets = []
    for i, s in enumerate(sets or []):
        if i not in matched and not s.error and s.answers_file and any(
                _same(x, v) for v in outside for x in (s.variant, s.stem) if x not in (None, "")):
            skipped_sets.append(s)         # a variant of the folder that this run (a pattern) left out
            continue
        if i not in matched:
            why = s.error or (Message("batch.no_task_of_variant", variant=s.variant) if s.variant not in (None, "")
                              else Message("batch.no_task_of_name", file=Path(s.source).name))
            rows.append({"student": s.student, "group": s.group, "variant": "" if s.variant is None else s.variant,
                         "file": s.source, "folder": "", "status": "invalid", "code": 2, "message": why,
                         "answers_file": s.answers_file, "flags": ";".join(s.flags),
                         "message_parts": [why]})
    for r in rows:
        if "answers" not in r:
            r.update({"answers": 0, "score": 0, **{s: 0 for s in STATUSES}})
    if sets is not None:
        labels = []
        for k in range(len(found)):
            v = (outcomes[k].get("task") or {}).get("variant")
            labels.append(files[k].stem if v is None else str(v))
        _copies(rows, [outcomes[k].get("key") or {} for k in range(len(found))], labels)
    fields = SUMMARY_FIELDS + (["grade"] if grades else [])
    if grades:
        from .copies import grade_of
        for r in rows:
            r["grade"] = grade_of(float(r["score"]), grades) if r.get("rows") is not None and r["answers"] else ""
    paths = []
    for r in rows:
        for p in r.get("per_path", {}):
            if p not in paths:
                paths.append(p)
    for r in rows:
        for p in paths:
            r[p] = r.get("per_path", {}).get(p, "")
    from .tables import csv_styled
    atomic_write(out / "summary.csv", csv_styled(csv_text(fields + paths, rows), csv_style))
    if gradebook:
        atomic_write(out / GRADEBOOK, csv_styled(gradebook_csv(rows, bool(grades)), csv_style))
        # Moodle's import finds a student by the email or the ID number: a line with neither is told
        unmatched = [r["_set"].answers_file for r in rows if r.get("_set") is not None and r.get("answers")
                     and not (r["_set"].email or r["_set"].idnumber)]
        if unmatched:
            set_notes.append(Message("batch.gradebook_unmatched", file=GRADEBOOK, n=len(unmatched),
                                     files=unmatched[:5], more=", ..." if len(unmatched) > 5 else ""))
    atomic_write(out / "check.csv", csv_styled(csv_text(CHECK_FIELDS, check_rows), csv_style))
    from .summary import summary_html
    atomic_write(out / "summary.html", summary_html(rows, paths, source, lang,
                                                    {Path(w).as_posix() for w in written}))
    written.update({"summary.csv", "summary.html", "check.csv"} | ({GRADEBOOK} if gradebook else set()))
    removed = _remove_stale(out, old_files, written)
    atomic_write(out / MANIFEST, json.dumps({"files": sorted(written)}, indent=1) + "\n")
    from .check import variant_order
    from .summary import print_batch
    if skipped_sets:
        set_notes.append(Message("batch.answers_outside", count=len(skipped_sets),
                                 variants=variant_order({str(s.variant if s.variant not in (None, "") else s.stem)
                                                         for s in skipped_sets})))
    from .check import merged_angle_notes
    notes = dict.fromkeys(merged_angle_notes(                                        # each once, in order
        set_notes + [n for s in sets or [] for n in s.notes] + [n for o in outcomes.values() for n in o.get("notes", ())]))
    print_batch(rows, out, skipped, removed, notes=list(notes), lang=lang)
    return max((r["code"] for r in rows), default=0)


def _copies(rows: list[dict], keys: list[dict], variants: list[str]) -> None:
    """Add `same_as=<student>` and `key_of=<variant>` to the graded rows' `flags`."""
    from .copies import KeyTable, agreed, key_of, same_as
    graded = [r for r in rows if r.get("_set") is not None]
    nums = [{p: v for p, v in r["_set"].answers.items() if v is not None and p not in r["_set"].invalid}
            for r in graded]
    for i, (r, others) in enumerate(zip(graded, same_as(nums))):
        for j in others:
            o = graded[j]
            who = o['student'] or o['answers_file']
            r["flags"] = ";".join(filter(None, [r["flags"], f"same_as={who}"]))
            # the evidence summary.html gives beside the flag: how many answers agree, how many of
            # them are wrong (the same mistakes say more than the same right results)
            same = agreed(nums[i], nums[j])
            r.setdefault("_same", {})[who] = (len(same), sum(r.get("per_path", {}).get(p) != "ok" for p in same))
    table = KeyTable(keys)
    for r, a in zip(graded, nums):
        k = key_of(a, r["_k"], r.get("ok", 0), table)
        if k is not None:
            r["flags"] = ";".join(filter(None, [r["flags"], f"key_of={variants[k]}"]))


def gradebook_csv(rows: list[dict], with_grades: bool) -> str:
    """gradebook-moodle.csv: one line per graded answer set, the columns of GRADEBOOK_FIELDS;
    the grade is `grade` with --grades, else the score in percent."""
    from .tables import csv_text
    out = []
    for r in rows:
        a = r.get("_set")
        if a is None or not r.get("answers"):
            continue
        grade = r["grade"] if with_grades else round(100 * float(r["score"]), 1)
        fb = f"{r['ok']}/{r['answers']} ok ({r['status']})" + (f"; {r['flags']}" if r.get("flags") else "")
        out.append({"Email address": a.email, "ID number": a.idnumber, "Full name": r["student"],
                    "Group": r["group"], "tmm grade": grade, "Feedback": fb})
    return csv_text(GRADEBOOK_FIELDS, out)


class _progress:
    """A rich progress bar with the count and the time left (on stderr; nothing when
    stderr is not a terminal)."""

    def __init__(self, con, total: int, what: str, left: str = "left"):
        self.con, self.total, self.what, self.left = con, total, what, left

    def __enter__(self):
        from rich.progress import (BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn,
                                   TimeRemainingColumn)
        self.prog = Progress(TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(),
                             TimeElapsedColumn(), TextColumn(self.left), TimeRemainingColumn(),
                             console=self.con, transient=True)
        self.prog.__enter__()
        self.bar = self.prog.add_task(self.what, total=self.total)
        return lambda n=1: self.prog.advance(self.bar, n)

    def __exit__(self, *exc):
        return self.prog.__exit__(*exc)


progress = _progress
