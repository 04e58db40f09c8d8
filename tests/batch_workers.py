"""Misbehaving variants for the tests of `tmm batch`'s worker pool.

``work`` replaces :func:`tmm_cli.batch.work` (``monkeypatch.setattr(batch, "work",
batch_workers.work)``): a function of a module, not a closure, so that a spawned worker
(Windows, macOS, TMM_START_METHOD=spawn) runs it as a forked one does (it is passed to the
worker by its name). What a variant does is told by the last part of its file's stem
("v2_killed", "slow"): killed / crash (the worker kills itself), slow (60 s), greedy (3 GB at
once), hog (3 GB, then held for 30 s), leaky (64 MB kept in the worker); anything else runs
the real work. With TMM_TEST_PID_LOG set, each variant first appends "<stem> <pid>" to that
file (the environment reaches a spawned worker; a test's variables do not); with TMM_TEST_SLEPT
set, a slow or hog variant that sleeps its whole time appends its stem to that file (a test
asserts that none did: the batch ended it, it did not wait for it -- bounded work, not a clock)."""
from __future__ import annotations

import os
import signal
import time
from pathlib import Path

import tmm_cli.batch as _batch

_REAL = _batch.work                # imported before a test replaces it (a spawned worker: unreplaced)
_KEPT: list = []


def pid_log(path: Path) -> dict[str, str]:
    """{stem: pid} of the variants logged in ``path``."""
    return dict(line.split() for line in path.read_text(encoding="utf-8").splitlines())


def _slept(stem: str) -> None:
    log = os.environ.get("TMM_TEST_SLEPT")
    if log:
        with open(log, "a", encoding="utf-8") as fh:
            fh.write(f"{stem}\n")


def work(path, *a):
    stem = Path(path).stem
    log = os.environ.get("TMM_TEST_PID_LOG")
    if log:
        with open(log, "a", encoding="utf-8") as fh:
            fh.write(f"{stem} {os.getpid()}\n")
    kind = stem.rsplit("_", 1)[-1]
    if kind in ("killed", "crash"):
        os.kill(os.getpid(), getattr(signal, "SIGKILL", signal.SIGTERM))
    if kind == "slow":
        time.sleep(60)
        _slept(stem)
    if kind == "greedy":
        x = bytearray(3 * 1024 ** 3)
        return {"never": len(x)}
    if kind == "hog":
        x = bytearray(3 * 1024 ** 3)
        time.sleep(30)
        _slept(stem)
        return {"never": len(x)}
    if kind == "leaky":
        _KEPT.append(bytearray(64 * 1024 ** 2))
    return _REAL(path, *a)


def quick(path, *a):
    """A variant done at once (no stage run): what is left of its time is the worker's start."""
    return {"task": None, "written": [], "sets": [], "code": 0, "status": "ok", "message": "", "notes": []}
