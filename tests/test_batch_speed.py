"""The batch's speed paths keep their guarantees (issue 38): files put in place unflushed
inside io.deferred_sync (still whole: a temporary file and os.replace), the file system
flushed once by the batch before its summary and manifest; results.clean's list-of-floats
path gives what cleaning each value gives."""
from __future__ import annotations

import math
import os
import random
import struct
from pathlib import Path

import numpy as np
import pytest

import tmm_cli.io as tio
from tmm_cli.results import clean

ROOT = Path(__file__).resolve().parents[1]


def _clean_each(obj):
    """clean's rule written out value by value: a float finite -> itself (-0.0 as 0.0),
    else None; lists element by element; anything else as clean leaves it."""
    if type(obj) is float:
        if math.isnan(obj) or math.isinf(obj):
            return None
        return 0.0 if obj == 0.0 else obj
    if type(obj) is list:
        return [_clean_each(v) for v in obj]
    return clean(obj)


def test_clean_of_float_lists_as_value_by_value():
    rnd = random.Random(38)
    special = [0.0, -0.0, 1.5, -2.25, math.inf, -math.inf, math.nan, 5e-324, -5e-324, 1.7976931348623157e308,
               -1e-300, 3, -7, True, None, "x", np.float64(-0.0), np.float64(np.nan)]
    for _ in range(5000):
        pick = special if rnd.random() < 0.3 else special[:11]        # mostly all-float lists
        xs = [rnd.choice(pick + [struct.unpack("<d", rnd.getrandbits(64).to_bytes(8, "little"))[0]])
              for _ in range(rnd.randint(1, 7))]
        got, want = clean(xs), _clean_each(xs)
        assert repr(got) == repr(want), xs          # repr: -0.0 and 0.0, an int and a float told apart
        assert [type(v) for v in got] == [type(v) for v in want]
    assert clean([]) == [] and clean([[-0.0, math.inf], [1.0]]) == [[0.0, None], [1.0]]
    # an array's values: tolist, then the same path
    assert repr(clean(np.array([-0.0, np.inf, 2.5, np.nan]))) == repr([0.0, None, 2.5, None])


def _fsync_log(monkeypatch, log: Path):
    """os.fsync (in this process and in a forked one) records the file it flushes."""
    real = os.fsync

    def fsync(fd):
        try:
            name = os.readlink(f"/proc/self/fd/{fd}")
        except OSError:
            name = "?"
        with open(log, "a", encoding="utf-8") as fh:
            fh.write(name + "\n")
        real(fd)
    monkeypatch.setattr(tio.os, "fsync", fsync)


@pytest.mark.skipif(not os.path.isdir("/proc/self/fd"), reason="reads /proc/self/fd")
def test_deferred_sync_writes_whole_files_without_fsync(tmp_path, monkeypatch):
    log = tmp_path / "fsync.log"
    _fsync_log(monkeypatch, log)
    out = tmp_path / "out"
    tio.atomic_write(out / "a.txt", "first")
    assert log.read_text().count("\n") == 1                   # outside: each file flushed
    flushes = []
    monkeypatch.setattr(tio, "_FLUSH_FS", lambda fd: flushes.append(fd))
    with tio.deferred_sync():
        tio.atomic_write(out / "b.txt", "second")
        tio.atomic_write(out / "a.txt", lambda write: write(b"again"))
    assert log.read_text().count("\n") == 1                   # inside: none
    assert (out / "a.txt").read_text() == "again" and (out / "b.txt").read_text() == "second"
    assert sorted(p.name for p in out.iterdir()) == ["a.txt", "b.txt"]     # no temporary file left
    assert not flushes
    tio.flush_all(out)
    assert len(flushes) == 1                                  # the file system, once
    tio.atomic_write(out / "c.txt", "third")                  # the block left: flushed again
    assert log.read_text().count("\n") == 2


def test_deferred_sync_changes_nothing_without_a_whole_flush(tmp_path, monkeypatch):
    """Where the system has no call that flushes a file system (Windows), every file is
    flushed as it is written, inside the block too, and flush_all does nothing."""
    monkeypatch.setattr(tio, "_FLUSH_FS", None)
    calls = []
    real = os.fsync
    monkeypatch.setattr(tio.os, "fsync", lambda fd: (calls.append(fd), real(fd)))
    with tio.deferred_sync():
        tio.atomic_write(tmp_path / "x.txt", "x")
    assert len(calls) == 1
    tio.flush_all(tmp_path)


def test_flush_failure_names_the_folder(tmp_path, monkeypatch):
    import errno

    def failing(fd):
        raise OSError(errno.EIO, os.strerror(errno.EIO))
    monkeypatch.setattr(tio, "_FLUSH_FS", failing)
    with pytest.raises(OSError) as info:
        tio.flush_all(tmp_path)
    assert info.value.errno == errno.EIO and info.value.filename == str(tmp_path)


def test_the_real_flush_runs(tmp_path):
    """The system's own call (syncfs on Linux) flushes without an error."""
    tio._FLUSH_FS = tio._UNKNOWN          # found afresh
    try:
        tio.atomic_write(tmp_path / "x.txt", "x")
        tio.flush_all(tmp_path)
    finally:
        tio._FLUSH_FS = tio._UNKNOWN


@pytest.mark.skipif(not os.path.isdir("/proc/self/fd"), reason="reads /proc/self/fd")
def test_batch_flushes_once_before_its_summary(tmp_path, monkeypatch):
    """The variants' files are written unflushed (in the forked worker), the batch flushes
    the file system once, then writes summary.csv, check.csv, summary.html and its manifest,
    each flushed as it is written."""
    from tmm_cli import batch
    from tmm_cli.portable import start_method
    if start_method() != "fork":
        pytest.skip("the worker must inherit the test's fsync")
    log = tmp_path / "fsync.log"
    _fsync_log(monkeypatch, log)
    flushed = []
    real_flush = tio.flush_all

    def flush_all(folder):
        flushed.append((Path(folder), (Path(folder) / "summary.csv").exists()))
        real_flush(folder)
    monkeypatch.setattr(tio, "flush_all", flush_all)
    tasks = tmp_path / "tasks"
    tasks.mkdir()
    (tasks / "01.yaml").write_text((ROOT / "tasks" / "crank_rocker_fourbar.yaml").read_text(encoding="utf-8"),
                                   encoding="utf-8")
    out = tmp_path / "g"
    assert batch.run_batch(str(tasks), out, jobs=1) == 0
    assert (out / "01" / "results.json").is_file()
    assert flushed == [(out, False)]                        # once, before the summary was written
    synced = {Path(p).name for p in log.read_text().splitlines()}
    assert not any(n.startswith(".results.json.") for n in synced)           # the variant's: none
    for name in ("summary.csv", "check.csv", "summary.html", ".tmm-batch.json"):
        assert any(n.startswith(f".{name}.") and n.endswith(".tmp") for n in synced), name


def _relative_by_relpath(folder, p, written=False):
    """Manifest._relative as it was written before its prefix path: os.path.relpath."""
    root = os.path.abspath(folder)
    full = os.path.abspath(p if written or os.path.isabs(p) else os.path.join(root, p))
    rel = os.path.relpath(full, root)
    if rel.startswith("..") or os.path.isabs(rel) or rel == ".":
        return None
    return Path(rel).as_posix()


def test_manifest_relative_paths_as_relpath_gives_them():
    rnd = random.Random(41)
    parts = ["a", "b", "..", ".", "", "..x", "figures", "/", "//", "c.csv", "x//y", "o"]
    folders = ["/tmp/o", "/tmp/o/", "o", "./o", "/", "//", "//tmp", "o/a/..", "/tmp", "."]
    for _ in range(20000):
        folder = rnd.choice(folders)
        p = "/".join(rnd.choice(parts) for _ in range(rnd.randint(1, 4)))
        if rnd.random() < 0.5:
            p = os.path.join(rnd.choice(["/tmp/o", "o", "/tmp", "//tmp/o", os.path.join(os.getcwd(), "o")]), p)
        for written in (False, True):
            assert tio.Manifest(folder)._relative(p, written=written) == \
                _relative_by_relpath(folder, p, written), (folder, p, written)


@pytest.mark.parametrize("task, module", [("gears_zero", "tmm_cli.gears.analysis"),
                                          ("planetary_A", "tmm_cli.gears.planetary"),
                                          ("cam_knife", "tmm_cli.cam.synthesis"),
                                          ("impact_rotor", "tmm_cli.dof2.analysis")])
def test_warm_imports_the_stages_the_tasks_need(task, module):
    """The packages load their stages on first use: the batch's warm-up names the stage modules
    themselves, so a worker starts warm (a spawned one counts its growth from there: a first
    variant that imported its stage grew past a small RECYCLE_GROWTH and retired its worker)."""
    import subprocess
    import sys
    code = ("import sys; from pathlib import Path; from tmm_cli.batch import warm; "
            f"warm([Path({str(ROOT / 'tasks' / (task + '.yaml'))!r})], {{'json'}}); print({module!r} in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "True"
