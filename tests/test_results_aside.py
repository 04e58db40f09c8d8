"""results.json written by a forked child while the report is made (tmm_cli.io.Aside,
tmm_cli.orchestrate.write_outputs): the same file, the same list of written files, the
same errors and exit codes as the one-process path; never a half-written results.json, a
temporary file left behind or a child left unwaited for."""
from __future__ import annotations

import errno
import os
import subprocess
import sys
from pathlib import Path

import pytest
from typer.testing import CliRunner

import tmm_cli.io as tio
import tmm_cli.orchestrate as orch
from tmm_cli.cli import app

ROOT = Path(__file__).resolve().parents[1]
FORGING = ROOT / "tasks" / "forging_sixbar.yaml"
runner = CliRunner()

pytestmark = pytest.mark.skipif(not hasattr(os, "fork") or os.environ.get("TMM_START_METHOD") == "spawn",
                                reason="no os.fork (or TMM_START_METHOD=spawn): always the one-process path")


def _temps(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.rglob("*") if p.name.endswith(".tmp"))


@pytest.fixture
def started(monkeypatch):
    """Every io.Aside started: (the Aside or None, its child's pid)."""
    seen = []
    real = tio.Aside.start.__func__

    def spy(cls, path, data, tail=None):
        a = real(cls, path, data, tail)
        seen.append((a, a._pid if a is not None else None))
        return a
    monkeypatch.setattr(tio.Aside, "start", classmethod(spy))
    return seen


def _gone(pid: int) -> bool:
    """The child was waited for (no zombie left): waitpid knows it no more."""
    try:
        os.waitpid(pid, os.WNOHANG)
    except ChildProcessError:
        return True
    return False


# ----------------------------------------------------------------- io.Aside itself
def test_aside_writes_in_a_child_and_puts_the_file_in_place(tmp_path):
    target = tmp_path / "sub" / "r.json"
    parent = os.getpid()
    a = tio.Aside.start(target, lambda write: write(b"%d" % os.getpid()))
    assert a is not None
    pid = a._pid
    assert not target.exists()                 # in place only once finished
    assert a.finish() == target
    assert int(target.read_text()) == pid != parent   # written by the child
    assert _gone(pid)
    assert _temps(tmp_path) == []
    assert oct(target.stat().st_mode & 0o777) == oct(tio.file_mode())


def test_a_failed_child_is_written_again_here(tmp_path, monkeypatch):
    """The child fails (here: only in the child) -> the file is written by this process."""
    parent = os.getpid()
    real_fsync = tio.os.fsync

    def fsync(fd):
        if os.getpid() != parent:
            raise OSError(errno.EIO, os.strerror(errno.EIO))
        real_fsync(fd)
    monkeypatch.setattr(tio.os, "fsync", fsync)
    a = tio.Aside.start(tmp_path / "r.json", lambda write: write(b"%d" % os.getpid()))
    assert a is not None
    a.finish()
    assert int((tmp_path / "r.json").read_text()) == parent
    assert _temps(tmp_path) == []


def test_a_failing_write_raises_what_atomic_write_raises(tmp_path, monkeypatch):
    def full(fd):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
    monkeypatch.setattr(tio.os, "fsync", full)
    target = tmp_path / "r.json"
    with pytest.raises(OSError) as serial:
        tio.atomic_write(target, lambda write: write(b"x"))
    a = tio.Aside.start(target, lambda write: write(b"x"))
    assert a is not None
    with pytest.raises(OSError) as aside:
        a.finish()
    assert (type(aside.value), aside.value.errno, aside.value.strerror, aside.value.filename) == \
        (type(serial.value), serial.value.errno, serial.value.strerror, serial.value.filename) == \
        (OSError, errno.ENOSPC, os.strerror(errno.ENOSPC), str(target))
    assert not target.exists() and _temps(tmp_path) == []


def test_abandoned_child_is_ended_and_waited_for(tmp_path):
    target = tmp_path / "r.json"
    target.write_text("old")
    a = tio.Aside.start(target, lambda write: __import__("time").sleep(60))
    assert a is not None
    pid = a._pid
    a.abandon()
    assert _gone(pid)
    assert target.read_text() == "old" and _temps(tmp_path) == []


def test_no_fork_no_aside(tmp_path, monkeypatch):
    def nofork():
        raise OSError(errno.EAGAIN, "no more processes")
    monkeypatch.setattr(tio.os, "fork", nofork)
    assert tio.Aside.start(tmp_path / "r.json", lambda write: write(b"x")) is None
    assert list(tmp_path.iterdir()) == []        # the temporary file opened for it is removed
    monkeypatch.delattr(tio.os, "fork")
    assert tio.Aside.start(tmp_path / "r.json", lambda write: write(b"x")) is None


def test_no_aside_while_another_thread_runs(tmp_path):
    """A forked child has only the forking thread: a lock another thread holds (a thread
    pool's, logging's) would stay held in it, so no child then."""
    import threading
    stop = threading.Event()
    t = threading.Thread(target=stop.wait)
    t.start()
    try:
        assert tio.Aside.start(tmp_path / "r.json", lambda write: write(b"x")) is None
    finally:
        stop.set()
        t.join()
    assert _temps(tmp_path) == []
    a = tio.Aside.start(tmp_path / "r.json", lambda write: write(b"x"))
    assert a is not None and a.finish().read_bytes() == b"x"


def test_a_folder_in_place_of_the_file_fails_at_once(tmp_path):
    (tmp_path / "r.json").mkdir()
    assert tio.Aside.start(tmp_path / "r.json", lambda write: write(b"x")) is None
    assert _temps(tmp_path) == []


def test_the_child_runs_no_atexit_callback_and_flushes_nothing_again(tmp_path):
    """os._exit in the child: the parent's atexit callbacks and unflushed output once."""
    code = ("import atexit, sys\n"
            "import tmm_cli.io as tio\n"
            "atexit.register(lambda: print('atexit'))\n"
            "sys.stdout.write('buffered ')\n"
            f"a = tio.Aside.start({str(tmp_path / 'r.json')!r}, lambda write: write(b'x'))\n"
            "assert a is not None\n"
            "a.finish()\n")
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120,
                       stdin=subprocess.DEVNULL)
    assert p.returncode == 0, p.stderr
    assert p.stdout == "buffered atexit\n"
    assert (tmp_path / "r.json").read_bytes() == b"x"


# ----------------------------------------------------------------- tmm run
def _run(out: Path, fmt: str = "html"):
    return runner.invoke(app, ["run", str(FORGING), "--out", str(out), "--format", fmt, "--quiet"])


def _files(folder: Path) -> dict[str, bytes]:
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in sorted(folder.rglob("*"))
            if p.is_file() and p.name not in (".tmm-manifest.json", "report.html")}


def test_run_writes_the_same_files_aside_and_in_one_process(tmp_path, monkeypatch, started):
    monkeypatch.setattr(orch, "ASIDE_ENTRIES", 0)        # the 12 positions written aside too
    res = _run(tmp_path / "aside")
    assert res.exit_code == 0, res.output
    assert len(started) == 1 and started[0][0] is not None and _gone(started[0][1])
    monkeypatch.setenv("TMM_REPORT_JOBS", "1")           # one process: written at once
    res = _run(tmp_path / "one")
    assert res.exit_code == 0, res.output
    assert len(started) == 1                             # not started
    a, b = _files(tmp_path / "aside"), _files(tmp_path / "one")
    assert a.keys() == b.keys() and "results.json" in a and "kinematics.csv" in a
    assert a == b
    import json
    man = [json.loads((tmp_path / d / ".tmm-manifest.json").read_text())["files"] for d in ("aside", "one")]
    assert list(man[0]) == list(man[1])                  # the same files listed
    assert _temps(tmp_path) == []


def test_small_results_are_written_at_once(tmp_path, started):
    res = _run(tmp_path / "o")
    assert res.exit_code == 0, res.output
    assert started == []                                 # 12 positions: below ASIDE_ENTRIES


@pytest.mark.parametrize("jobs", ["", "1"])
def test_run_failing_write_same_message_and_code(tmp_path, monkeypatch, started, jobs):
    """A disk that fills up: the message names results.json (written first in one process)
    and the exit code is 3, with or without the child; no temporary file is left."""
    monkeypatch.setattr(orch, "ASIDE_ENTRIES", 0)
    monkeypatch.setenv("TMM_REPORT_JOBS", jobs)

    def full(fd):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
    monkeypatch.setattr(tio.os, "fsync", full)
    out = tmp_path / "o"
    res = _run(out)
    assert res.exit_code == 3, res.output
    assert res.output.strip() == f"error: stage 'output' failed: cannot write {out / 'results.json'}: " \
                                 "No space left on device"
    assert not (out / "results.json").exists() and _temps(tmp_path) == []
    assert [a is not None for a, _ in started] == ([True] if jobs == "" else [])
    assert all(_gone(pid) for a, pid in started)


@pytest.mark.parametrize("jobs", ["", "1"])
def test_run_results_target_a_folder_same_message(tmp_path, monkeypatch, started, jobs):
    monkeypatch.setattr(orch, "ASIDE_ENTRIES", 0)
    monkeypatch.setenv("TMM_REPORT_JOBS", jobs)
    out = tmp_path / "o"
    (out / "results.json").mkdir(parents=True)
    res = _run(out)
    assert res.exit_code == 3, res.output
    assert f"stage 'output' failed: cannot write {out / 'results.json'}: Is a directory" in res.output
    assert not (out / "report.html").exists()            # as in one process: nothing after it
    assert _temps(tmp_path) == []


def _write(tmp_path, task, results, render):
    import tmm_cli.report as R
    R_render = R.render
    try:
        R.render = render
        return orch.write_outputs(task, results, tmp_path, {"html"}, "en")
    finally:
        R.render = R_render


@pytest.fixture(scope="module")
def forging():
    task = orch.prepare(FORGING)
    return task, orch.compute(task, lazy=True)


def test_a_failing_report_still_leaves_the_results_file(tmp_path, monkeypatch, forging, started):
    """The report fails after results.json was written (one process): the same here."""
    monkeypatch.setattr(orch, "ASIDE_ENTRIES", 0)
    task, results = forging

    def broken(*a, **k):
        raise ValueError("boom")
    with pytest.raises(ValueError, match="boom"):
        _write(tmp_path, task, results, broken)
    assert started and started[0][0] is not None and _gone(started[0][1])
    from tmm_cli.orchestrate import REPORT_ONLY
    from tmm_cli.results import dumps, listed
    assert (tmp_path / "results.json").read_text(encoding="utf-8") == \
        dumps({k: v for k, v in listed(results).items() if k not in REPORT_ONLY})
    assert _temps(tmp_path) == []


def test_interrupted_report_leaves_the_old_results_file(tmp_path, monkeypatch, forging, started):
    monkeypatch.setattr(orch, "ASIDE_ENTRIES", 0)
    task, results = forging
    (tmp_path / "results.json").write_text("old")

    def interrupted(*a, **k):
        raise KeyboardInterrupt
    with pytest.raises(KeyboardInterrupt):
        _write(tmp_path, task, results, interrupted)
    assert started and started[0][0] is not None and _gone(started[0][1])
    assert (tmp_path / "results.json").read_text() == "old" and _temps(tmp_path) == []


# ----------------------------------------------------------------- the file in two parts
def test_dump_parts_are_the_file_at_any_split(forging):
    """The head (the child's) then the tail (this process's) are dumps() to the byte,
    wherever the file is split (the task's sections: entries, nested dicts, lists)."""
    from tmm_cli.results import dump_parts, dumps, listed
    _, results = forging
    res = dict(listed(results))
    res["task"] = {**res["task"], "title": "Кривошипно-ползунный μ \"q\""}   # non-ASCII
    whole = dumps(res).encode("utf-8")
    for split in range(-1, len(res) + 2):
        head, tail = dump_parts(res, split)
        a: list[bytes] = []
        b: list[bytes] = []
        head(a.append)
        tail(b.append)
        assert b"".join(a + b) == whole, split
        assert (split <= 0) == (b"".join(a) == b"{")
    for tiny in ({}, {"a": [1.5, -0.0, float("nan")]}):
        for split in (0, 1):
            head, tail = dump_parts(tiny, split)
            out: list[bytes] = []
            head(out.append)
            tail(out.append)
            assert b"".join(out) == dumps(tiny).encode(), (tiny, split)


def test_aside_with_a_tail_made_here(tmp_path):
    parent = os.getpid()
    target = tmp_path / "r.json"
    a = tio.Aside.start(target, lambda write: write(b"%d," % os.getpid()),
                        lambda write: write(b"%d" % os.getpid()))
    assert a is not None
    pid = a._pid
    a.finish()
    assert target.read_text() == f"{pid},{parent}" and pid != parent
    assert _temps(tmp_path) == []


def test_the_file_split_after_its_last_entries(tmp_path, monkeypatch, forging, started):
    """write_outputs: the child writes up to the last section of per-position entries
    (kinetostatics), this process the graphical-error block after it."""
    monkeypatch.setattr(orch, "ASIDE_ENTRIES", 0)
    task, results = forging
    heads = []
    real = tio.Aside.start.__func__

    def spy(cls, path, data, tail=None):
        out: list[bytes] = []
        data(out.append)
        heads.append(b"".join(out))
        return real(cls, path, data, tail)
    monkeypatch.setattr(tio.Aside, "start", classmethod(spy))
    _write(tmp_path, task, results, lambda *a, **k: [])
    text = (tmp_path / "results.json").read_bytes()
    assert len(heads) == 1 and text.startswith(heads[0])
    assert b'"kinetostatics"' in heads[0] and b'"graphical_error"' not in heads[0]
    assert b'"graphical_error"' in text[len(heads[0]):]
    from tmm_cli.orchestrate import REPORT_ONLY
    from tmm_cli.results import dumps, listed
    assert text == dumps({k: v for k, v in listed(results).items() if k not in REPORT_ONLY}).encode()


def test_the_child_ends_with_its_parent_and_leaves_no_file(tmp_path):
    """The main process killed while the child writes: the child stops at its next piece
    and removes its temporary file (nothing to clean after it)."""
    out = tmp_path / "o"
    out.mkdir()
    code = ("import os, time\n"
            "import tmm_cli.io as tio\n"
            "def slow(write):\n"
            "    for _ in range(400):\n"
            "        time.sleep(0.025)\n"
            "        write(b'x')\n"
            f"a = tio.Aside.start({str(out / 'r.json')!r}, slow)\n"
            "time.sleep(0.3)\n"
            f"print(a._pid, len([n for n in os.listdir({str(out)!r}) if n.endswith('.tmp')]), flush=True)\n"
            "os._exit(9)\n")
    log = tmp_path / "log"
    with open(log, "w") as fh:        # not a pipe: the child holds it open, run() would wait for it
        p = subprocess.run([sys.executable, "-c", code], stdout=fh, stderr=subprocess.STDOUT, timeout=120,
                           stdin=subprocess.DEVNULL)
    assert p.returncode == 9, log.read_text()
    pid, temps = map(int, log.read_text().split())
    assert temps == 1                          # the child was writing (10 s of pieces) when it ended
    import time
    for _ in range(200):
        try:
            os.kill(pid, 0)
            with open(f"/proc/{pid}/stat") as st:    # a zombie (ended, its reaper slow) counts
                if st.read().rsplit(")", 1)[1].split()[0] == "Z":
                    break
        except (ProcessLookupError, FileNotFoundError):
            break
        except OSError:
            pass
        time.sleep(0.05)
    else:
        pytest.fail("the child outlived its parent")
    assert _temps(out) == [] and not (out / "r.json").exists()
