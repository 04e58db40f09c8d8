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
