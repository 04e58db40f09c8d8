"""File output: atomic writes with ordinary permissions, and the manifest by which a
run owns the files it wrote in its output folder.

- ``atomic_write`` writes through a temporary file ``.NAME.<random>.tmp`` in the same
  folder and ``os.replace``s it into place, so readers see the old or the new file,
  never half of one.  The file gets the mode an ordinary new file gets (0666 less the
  umask: 0644 under umask 022), not the 0600 of a bare temporary file.
- ``Manifest`` lists in ``.tmm-manifest.json`` the files a run wrote.  The next run
  into the same folder removes the files of the previous run that it does not write
  again (a drawing of a section since removed, a figure whose number is gone) and
  never touches a file it did not write: a listed file is removed only while its size
  and modification time are still those recorded (a file the user replaced or edited
  stays).  Temporary files of our naming left by a killed run are removed too.
- Durability: ``atomic_write`` flushes each file to the disk (``fsync``) before it puts it
  in place, so after a system crash a file under its own name is whole. A batch writes
  ~56 files a variant, and a flush each waited ~10 ms for a busy disk (the write itself
  ~1 ms; ~0.5 s a variant, measured 6 Dec 2026 on the shared 2-core machine): inside
  :func:`deferred_sync` (the batch's workers) the files are put in place unflushed -- still
  through a temporary file and ``os.replace``, so no reader and no killed process ever
  sees half a file -- and :func:`flush_all` then flushes the whole file system at once
  (Linux ``syncfs``: one wait for the disk instead of one a file), before the batch
  writes its summary and its manifest, flushed as ever. A system crash during the batch
  may leave files of its variants empty under their own names (the summary of the batch
  before still in place): the batch is run again, as after any interruption. Where no
  such call exists (macOS, Windows) every file is flushed as it is written, as before.
"""
from __future__ import annotations

import json
import os
import re
import sys
import time
from contextlib import contextmanager
from pathlib import Path
from typing import Callable

MANIFEST = ".tmm-manifest.json"
# the lock of an output folder (folder_lock): one run (or batch) writes into a folder at a time
LOCK = ".tmm-lock"
LOCK_WAIT = 300.0           # seconds a run waits for another to finish writing (TMM_LOCK_WAIT)
# _mkstemp(path): ".NAME." eight random characters ".tmp" (the names tempfile.mkstemp gives)
_TMP = re.compile(r"^\.(?P<name>.+)\.[a-z0-9_]{8}\.tmp$")
_TMP_CHARS = "abcdefghijklmnopqrstuvwxyz0123456789_"


def file_mode() -> int:
    """The mode of an ordinary new file under the current umask (0o666 & ~umask)."""
    try:
        with open("/proc/self/status", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("Umask:"):
                    return 0o666 & ~int(line.split()[1], 8)
    except (OSError, ValueError, IndexError):
        pass
    mask = os.umask(0o022)          # no /proc: read it by setting it (and put it back)
    os.umask(mask)
    return 0o666 & ~mask


def atomic_write(path: str | os.PathLike, data: bytes | str | Callable[[Callable[[bytes], object]], None],
                 encoding: str = "utf-8", tries: int | None = None) -> Path:
    """Write ``data`` to ``path`` through a temporary file in the same folder and
    ``os.replace`` it into place, so readers see either the old or the new file.
    ``data`` may be a function given the temporary file's ``write`` (bytes), to write a
    large file piece by piece. ``tries``: how many times the replace is tried while another
    program holds ``path`` (:func:`replace`; default :data:`REPLACE_TRIES`)."""
    path = Path(path)
    raw = data.encode(encoding) if isinstance(data, str) else data
    fd, tmp = _open_temp(path)
    with _removed_on_error(tmp, path):
        _fill(fd, raw)
        replace(tmp, path, tries)
    return path


# os.replace over a file another program holds open (Windows: a PDF viewer showing
# report.pdf, an antivirus or an indexer reading a file just written) fails with
# PermissionError; it is tried this many times, waiting 0.2, 0.4, 0.8... s in between
REPLACE_TRIES = 5
REPLACE_WAIT = 0.2


def replace(tmp: str | os.PathLike, path: str | os.PathLike, tries: int | None = None) -> None:
    """``os.replace(tmp, path)``, tried again (``tries`` times in all, :data:`REPLACE_TRIES`
    by default) while ``path`` is held by another program (PermissionError: the temporary file
    lies in the same folder, so the folder itself is writable); then a PermissionError naming
    ``path`` and saying why, for the user."""
    delay = REPLACE_WAIT
    tries = REPLACE_TRIES if tries is None else max(1, tries)
    for attempt in range(tries):
        try:
            os.replace(tmp, path)
            return
        except PermissionError as exc:
            if os.path.isdir(path):
                raise
            if attempt == tries - 1:
                import errno

                from .messages import Message
                raise PermissionError(exc.errno or errno.EACCES, Message("output.file_in_use"), str(path)) from exc
            time.sleep(delay)
            delay *= 2


def _open_temp(path: Path) -> tuple[int, str]:
    """The folder made and the temporary file of ``path`` opened (``_mkstemp``); an
    error names ``path``, not the temporary file."""
    path.parent.mkdir(parents=True, exist_ok=True)
    try:
        return _mkstemp(path)
    except OSError as exc:
        from .safepath import target_error
        raise target_error(exc, path) from exc


def _fill(fd: int, raw) -> None:
    """The temporary file ``fd`` given an ordinary file's mode, written (``raw``: bytes, or
    a function given its ``write``), flushed to the disk and closed."""
    if hasattr(os, "fchmod"):
        os.fchmod(fd, file_mode())
    with os.fdopen(fd, "wb") as fh:
        if callable(raw):
            raw(fh.write)
        else:
            fh.write(raw)
        fh.flush()
        if _SYNC_EACH:
            os.fsync(fh.fileno())


# False inside deferred_sync(): atomic_write leaves the flush to the disk to flush_all()
_SYNC_EACH = True


def _flush_fs():
    """:func:`_find_flush_fs`'s call, found once."""
    global _FLUSH_FS
    if _FLUSH_FS is _UNKNOWN:
        _FLUSH_FS = _find_flush_fs()
    return _FLUSH_FS


_UNKNOWN = object()
_FLUSH_FS = _UNKNOWN


def _find_flush_fs():
    """The call that flushes a whole file system to the disk and waits for it, given a
    descriptor of any file or folder on it: Linux's ``syncfs`` (returns 0, or -1 and
    errno); None elsewhere (macOS's and the BSDs' ``sync`` only schedules the writes,
    Windows has none): there each file is flushed as it is written."""
    if sys.platform.startswith("linux"):
        try:
            import ctypes
            libc = ctypes.CDLL(None, use_errno=True)
            call = libc.syncfs
        except (OSError, AttributeError):
            call = None
        if call is not None:
            call.argtypes = [ctypes.c_int]

            def syncfs(fd: int) -> None:
                if call(fd) != 0:
                    err = ctypes.get_errno()
                    raise OSError(err, os.strerror(err))
            return syncfs
    return None


@contextmanager
def deferred_sync():
    """Inside the block :func:`atomic_write` puts files in place without flushing each to
    the disk (a batch's worker: ~56 files a variant); the caller then calls
    :func:`flush_all` once. Where no whole-file-system flush exists, nothing changes."""
    global _SYNC_EACH
    was = _SYNC_EACH
    if _flush_fs() is not None:
        _SYNC_EACH = False
    try:
        yield
    finally:
        _SYNC_EACH = was


def flush_all(folder: str | os.PathLike) -> None:
    """Flush the file system of ``folder`` to the disk: every file written there unflushed
    (:func:`deferred_sync`, in this process or another) and every ``os.replace`` that put
    one in place. Raises the OSError of the flush (an I/O error, a full disk found only on
    writing back) naming ``folder``."""
    flush = _flush_fs()
    if flush is None:
        return
    fd = os.open(folder, os.O_RDONLY | getattr(os, "O_DIRECTORY", 0) | getattr(os, "O_CLOEXEC", 0))
    try:
        flush(fd)
    except OSError as exc:
        raise OSError(exc.errno, exc.strerror, str(folder)) from None
    finally:
        os.close(fd)


def _discard(tmp: str) -> None:
    try:
        os.unlink(tmp)
    except OSError:
        pass


@contextmanager
def _removed_on_error(tmp: str, path: Path):
    """On any error the temporary file ``tmp`` is removed; an OSError is raised as one
    naming ``path``, the file asked for."""
    try:
        yield
    except OSError as exc:
        _discard(tmp)
        from .safepath import target_error
        raise target_error(exc, path) from exc
    except BaseException:
        _discard(tmp)
        raise


def workers_wanted() -> bool:
    """A second process (fork) may work alongside this one (the report's helper, a results
    file written aside): unless TMM_REPORT_JOBS=1, fork is unavailable (or TMM_START_METHOD=spawn)
    or there is one core."""
    if os.environ.get("TMM_REPORT_JOBS", "").strip() == "1":
        return False
    from .portable import can_fork
    if not can_fork():              # no fork here, or TMM_START_METHOD=spawn
        return False
    return (os.cpu_count() or 1) >= 2


class Aside:
    """:func:`atomic_write` of a large file done by a forked child process while this one
    goes on (the results file written while the report is made: two cores busy instead of
    one). The temporary file is opened here before the fork, so a folder that cannot be
    written fails at once, as :func:`atomic_write` fails; the child writes it, flushes it to
    the disk and ends (``os._exit``: no atexit callback, no buffer of this process
    flushed again); :meth:`finish` waits for it and puts the file in place
    (``os.replace``, here). A child that failed or died is not trusted to tell why: the
    temporary file is removed and the file is written again here, by
    :func:`atomic_write`, which then gives the very error (or writes the file). A
    ``tail``: the file's end, made by this process when it has done its own work
    (:meth:`finish`, while the child still writes the rest) and appended. Start it
    with :meth:`start` (None where no child can be made: write it at once instead);
    :meth:`finish` or :meth:`abandon` it, always (no child left unwaited for)."""

    __slots__ = ("path", "_data", "_tail", "_pid", "_tmp")

    def __init__(self, path: Path, data, tail, pid: int, tmp: str):
        self.path, self._data, self._tail, self._pid, self._tmp = path, data, tail, pid, tmp

    @classmethod
    def start(cls, path: str | os.PathLike, data: Callable[[Callable[[bytes], object]], None],
              tail: Callable[[Callable[[bytes], object]], None] | None = None) -> "Aside | None":
        """The child started writing ``path`` (``data`` as :func:`atomic_write` takes
        it; then ``tail``, taken the same way, in this process), or None: no ``os.fork``
        here, or another thread runs in this process (a forked child has only the forking
        thread: a lock another one holds stays held). Raises what :func:`atomic_write`
        raises for a temporary file that cannot be made."""
        import sys
        threading = sys.modules.get("threading")
        path = Path(path)
        from .portable import can_fork
        if not can_fork() or (threading is not None and threading.active_count() > 1) \
                or os.path.isdir(path):    # that replace fails: at once, as atomic_write fails
            return None
        fd, tmp = _open_temp(path)
        import signal
        # Ctrl-C held back over the fork: the child ignores it (this process, interrupted,
        # ends the child: abandon), so it never runs this process's code on
        block = getattr(signal, "pthread_sigmask", None)
        held = block(signal.SIG_BLOCK, {signal.SIGINT}) if block is not None else None
        pid = None
        parent = os.getpid()
        try:
            pid = os.fork()
        except OSError:
            pid = None
        finally:
            if held is not None and pid != 0:
                block(signal.SIG_SETMASK, held)
        if pid == 0:                                    # the child
            code = 1
            try:
                signal.signal(signal.SIGINT, signal.SIG_IGN)
                if held is not None:
                    block(signal.SIG_SETMASK, held)
                import gc
                gc.disable()       # no collection walking (and copying) the parent's objects
                _fill(fd, _orphan_stops(data, parent))
                code = 0
            except BaseException:  # noqa: BLE001 - the parent writes it again and says why
                _discard(tmp)
            finally:
                os._exit(code)
        if pid is None:
            os.close(fd)
            _discard(tmp)
            return None
        os.close(fd)
        return cls(path, data, tail, pid, tmp)

    def finish(self) -> Path:
        """Wait for the child; the file in place (``path``), or the error
        :func:`atomic_write` gives."""
        try:
            end: list[bytes] = []
            if self._tail is not None:
                self._tail(end.append)
            _, status = os.waitpid(self._pid, 0)
        except BaseException:
            self.abandon()
            raise
        self._pid = None
        if os.waitstatus_to_exitcode(status) == 0:
            with _removed_on_error(self._tmp, self.path):
                if end:
                    with open(self._tmp, "ab") as fh:
                        fh.writelines(end)
                        fh.flush()
                        if _SYNC_EACH:
                            os.fsync(fh.fileno())
                replace(self._tmp, self.path)
            return self.path
        _discard(self._tmp)
        data, tail = self._data, self._tail
        return atomic_write(self.path, data if tail is None else lambda write: (data(write), tail(write)))

    def abandon(self) -> None:
        """End the child (if still running), wait for it, remove the temporary file: the
        file is left as it was."""
        if self._pid is not None:
            import signal
            try:
                os.kill(self._pid, getattr(signal, "SIGKILL", signal.SIGTERM))
            except OSError:
                pass
            try:
                os.waitpid(self._pid, 0)
            except ChildProcessError:
                pass
            self._pid = None
        _discard(self._tmp)


def _orphan_stops(data: Callable, parent: int) -> Callable:
    """``data`` given a ``write`` that raises once the process ``parent`` is gone (killed:
    nobody will put the file in place), so the child ends and removes its temporary file."""
    def go(write) -> None:
        def checked(b):
            if os.getppid() != parent:
                raise ChildProcessError("the writing process's parent is gone")
            return write(b)
        data(checked)
    return go


def _mkstemp(path: Path) -> tuple[int, str]:
    """``tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)``: a new
    file of mode 0600 (O_EXCL, no symlink followed) named ``.NAME.<8 random characters>.tmp``
    next to ``path``, opened for writing; without importing tempfile (and shutil, bz2,
    lzma: ~2.5 ms of a JSON run)."""
    flags = os.O_RDWR | os.O_CREAT | os.O_EXCL | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_CLOEXEC", 0) \
        | getattr(os, "O_BINARY", 0)
    for _ in range(10000):                      # tempfile.TMP_MAX tries
        tag = "".join(_TMP_CHARS[b % len(_TMP_CHARS)] for b in os.urandom(8))
        name = os.path.abspath(os.path.join(path.parent, f".{path.name}.{tag}.tmp"))
        try:
            return os.open(name, flags, 0o600), name
        except FileExistsError:
            continue
    raise FileExistsError(f"no unused temporary name for {path}")


def lock_wait() -> float:
    """Seconds to wait for an output folder another run writes into: TMM_LOCK_WAIT, else
    LOCK_WAIT."""
    try:
        v = float(os.environ.get("TMM_LOCK_WAIT", ""))
    except ValueError:
        return LOCK_WAIT
    return v if v >= 0 else LOCK_WAIT


@contextmanager
def folder_lock(folder: str | os.PathLike):
    """Hold the lock of the output ``folder`` (the file ``.tmm-lock`` in it while held;
    filelock: an advisory lock of the system, released when the process ends, however it
    ends) while
    the block writes into it, so that two runs into one folder never leave one's
    results.json beside the other's report: the second waits for the first to finish
    writing, up to :func:`lock_wait` seconds, then fails with an OSError (EBUSY) naming
    the folder (exit 3, as a folder that cannot be written). A folder where the lock file
    cannot be made is left to the writes themselves to report (they fail as before)."""
    import errno

    from filelock import FileLock, Timeout
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    if os.path.islink(folder / LOCK):    # never opened through a link planted in its place
        raise OSError(errno.ELOOP, "the output folder's lock file is a symbolic link", str(folder / LOCK))
    wait = lock_wait()
    lock = FileLock(str(folder / LOCK), timeout=wait)
    try:
        lock.acquire()
    except Timeout:
        raise OSError(errno.EBUSY, f"another tmm run or batch is writing into this folder (waited {wait:g} s; "
                                   f"TMM_LOCK_WAIT sets the wait)", str(folder)) from None
    except OSError:
        lock = None                     # cannot even make the lock file: the writes say why
    try:
        yield
    finally:
        if lock is not None:
            if os.name == "posix":      # no lock file left in the folder: unlinked while held, so
                _discard(lock.lock_file)  # a waiter that opened it retries on a new one (filelock >= 4.3)
            lock.release()


def _stamp(path: Path) -> list[int] | None:
    try:
        st = path.stat()
    except OSError:
        return None
    return [st.st_size, st.st_mtime_ns]


class Manifest:
    """What one run writes into ``folder``.  Create it when the run starts, then
    ``commit(paths)`` with every file the run wrote: files the previous run listed
    and this run did not write are removed (if unchanged since), stale temporary
    files of our naming are removed, and the new list is written atomically.

        man = Manifest(out)
        written = [...]                 # the run's atomic_write(...) paths
        removed = man.commit(written)
    """

    def __init__(self, folder: str | os.PathLike):
        self.folder = Path(folder)
        self.started = time.time()

    @property
    def path(self) -> Path:
        return self.folder / MANIFEST

    def previous(self) -> dict[str, list[int] | None]:
        """{relative path: [size, mtime_ns]} of the last run's files ({} if none or unreadable)."""
        try:
            data = json.loads(self.path.read_text(encoding="utf-8"))
            files = data["files"]
        except (OSError, ValueError, KeyError, TypeError):
            return {}
        if not isinstance(files, dict):
            return {}
        return {k: v for k, v in files.items() if isinstance(k, str)}

    def _relative(self, p: str | os.PathLike, *, written: bool = False) -> str | None:
        """The path inside the folder, as 'a/b.csv', or None if it lies outside. ``p`` is
        relative to the folder (a manifest's entry) or, ``written``, as the run wrote it:
        absolute or relative to the working directory (``--out out/task``)."""
        root = os.path.abspath(self.folder)
        full = os.path.abspath(p if written or os.path.isabs(p) else os.path.join(root, p))
        prefix = root if root.endswith(os.sep) else root + os.sep
        # both normalised: inside the folder, what relpath gives (without its splitting)
        rel = full[len(prefix):] if full.startswith(prefix) else ""
        if not rel or os.path.isabs(rel):
            rel = os.path.relpath(full, root)
        if rel.startswith("..") or os.path.isabs(rel) or rel == ".":
            return None
        return rel if os.sep == "/" else Path(rel).as_posix()

    def commit(self, written) -> list[Path]:
        """Record ``written``; remove what the previous run wrote and this one did not.
        Returns the removed paths."""
        now: dict[str, list[int] | None] = {}
        for p in written:
            rel = self._relative(p, written=True)
            if rel is not None and rel != MANIFEST:
                now[rel] = _stamp(self.folder / rel)
        removed: list[Path] = []
        previous = self.previous()              # (read once: this run writes the manifest last)
        for rel, stamp in previous.items():
            if rel in now or self._relative(rel) != rel:
                continue                      # written again, or not a plain path inside
            f = self.folder / rel
            if f.is_symlink() or not f.is_file() or stamp is None or _stamp(f) != list(stamp):
                continue                      # gone, replaced or changed since: not ours now
            try:
                f.unlink()
                removed.append(f)
            except OSError:
                continue
            self._prune(f.parent)
        dirs = {self.folder} | {(self.folder / r).parent for r in list(now) + list(previous)
                                if self._relative(r) == r} | set(self._subfolders())
        temps = self.remove_stale_temps(dirs)
        for t in temps:
            self._prune(t.parent)
        removed += temps
        atomic_write(self.path, json.dumps({"schema": "tmm-manifest/1", "files": now}, indent=1,
                                           sort_keys=True) + "\n")
        return removed

    def _subfolders(self):
        """The folder's own sub-folders (figures/, sheets/; not a link): a run killed before
        its first manifest leaves its temporary files there too."""
        try:
            entries = list(os.scandir(self.folder))
        except OSError:
            return
        for e in entries:
            try:
                if e.is_dir(follow_symlinks=False):
                    yield Path(e.path)
            except OSError:
                continue

    def _prune(self, d: Path) -> None:
        """Remove folders (inside ours) emptied by the removal."""
        root = self.folder.resolve()
        while d.resolve() != root and root in d.resolve().parents:
            try:
                d.rmdir()
            except OSError:
                return
            d = d.parent

    def remove_stale_temps(self, dirs) -> list[Path]:
        """Temporary files ``.NAME.<random>.tmp`` (atomic_write's) in ``dirs`` older
        than this run: left by a run that was killed while writing."""
        out = []
        for d in dirs:
            try:
                entries = list(os.scandir(d))
            except OSError:
                continue
            for e in entries:
                if not _TMP.match(e.name) or not e.is_file(follow_symlinks=False):
                    continue
                try:
                    if e.stat(follow_symlinks=False).st_mtime < self.started - 1.0:
                        os.unlink(e.path)
                        out.append(Path(e.path))
                except OSError:
                    continue
        return out
