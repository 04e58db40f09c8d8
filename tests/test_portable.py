"""Windows and macOS: what differs from Linux (docs/platforms.md), tested on Linux by
taking Linux's extras away."""
from __future__ import annotations


def test_spawn_forced_means_no_fork_anywhere(monkeypatch):
    """TMM_START_METHOD=spawn: the batch spawns its workers, and neither the report's
    helper nor a results file written aside forks (as where fork does not exist)."""
    from tmm_cli import io, portable
    monkeypatch.setenv("TMM_START_METHOD", "spawn")
    monkeypatch.delenv("TMM_REPORT_JOBS", raising=False)
    assert portable.start_method() == "spawn" and not portable.can_fork()
    assert not io.workers_wanted()
    assert io.Aside.start("/nonexistent-dir/x.json", lambda w: w(b"x")) is None
    monkeypatch.setenv("TMM_START_METHOD", "fork")
    assert portable.start_method() == "fork" and portable.can_fork()


def test_fork_unavailable_falls_back_to_spawn(monkeypatch):
    import multiprocessing

    from tmm_cli import portable
    monkeypatch.delenv("TMM_START_METHOD", raising=False)
    monkeypatch.setattr(multiprocessing, "get_all_start_methods", lambda: ["spawn"])
    assert portable.start_method() == "spawn"
    monkeypatch.setenv("TMM_START_METHOD", "fork")                 # asked for, but not there
    assert portable.start_method() == "spawn"


def _held(monkeypatch, times: int):
    """os.replace fails with PermissionError ``times`` times (Windows: the file is open in
    a viewer), then works; the waits between tries skipped. Returns the calls made."""
    import os

    from tmm_cli import io
    real, calls = os.replace, []

    def replace(src, dst):
        calls.append(dst)
        if len(calls) <= times:
            raise PermissionError(13, "Access is denied", str(dst))
        return real(src, dst)
    monkeypatch.setattr(os, "replace", replace)
    monkeypatch.setattr(io.time, "sleep", lambda s: None)
    return calls


def test_replace_over_a_held_file_is_tried_again(tmp_path, monkeypatch):
    from tmm_cli.io import REPLACE_TRIES, atomic_write
    (tmp_path / "report.pdf").write_bytes(b"old")
    calls = _held(monkeypatch, REPLACE_TRIES - 1)
    atomic_write(tmp_path / "report.pdf", b"new")
    assert (tmp_path / "report.pdf").read_bytes() == b"new" and len(calls) == REPLACE_TRIES
    assert [p.name for p in tmp_path.iterdir()] == ["report.pdf"]


def test_a_file_held_for_good_is_named_no_traceback_no_temporary_left(tmp_path, monkeypatch):
    """`tmm run` whose results.json stays held: exit 3, the file named and why, the old
    file as it was, no temporary file left in the folder."""
    from typer.testing import CliRunner

    from tmm_cli.cli import app
    from tmm_cli.io import REPLACE_TRIES
    out = tmp_path / "out"
    out.mkdir()
    (out / "results.json").write_text("old")
    calls = _held(monkeypatch, 10 ** 6)
    task = __import__("pathlib").Path(__file__).resolve().parent.parent / "tasks" / "gears_zero.yaml"
    res = CliRunner().invoke(app, ["run", str(task), "--out", str(out), "--format", "json"])
    assert res.exit_code == 3, res.output
    assert f"cannot write {out / 'results.json'}: the file is open in another program" in res.output
    assert "Traceback" not in res.output and len(calls) == REPLACE_TRIES
    assert sorted(p.name for p in out.iterdir()) == ["results.json"]
    assert (out / "results.json").read_text() == "old"
