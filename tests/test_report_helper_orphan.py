"""Issue 10, item 5: the forked report helper never outlives the main process. When the
main process alone is killed (a scheduler, subprocess.run(timeout=...), the OOM killer),
the helper exits within seconds instead of waiting forever on its pipe."""
from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _children(pid: int) -> list[int]:
    out = []
    for task in Path(f"/proc/{pid}/task").glob("*"):
        try:
            out += [int(x) for x in (task / "children").read_text().split()]
        except OSError:
            pass
    return out


def _running(pid: int) -> bool:
    """True while ``pid`` exists and is not a zombie (an orphan's zombie may wait for a
    reaper that a container lacks; it holds no memory and runs no code)."""
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return False
    return stat.rsplit(")", 1)[1].split()[0] != "Z"


@pytest.mark.skipif(not sys.platform.startswith("linux") or (os.cpu_count() or 1) < 2,
                    reason="the helper is forked on Linux with two or more cores")
@pytest.mark.parametrize("kill_when", ["helper started", "helper waiting"])
def test_helper_exits_when_main_process_is_killed(tmp_path, kill_when):
    env = dict(os.environ)
    env.pop("TMM_REPORT_JOBS", None)
    main = subprocess.Popen([sys.executable, "-m", "tmm_cli", "run", str(ROOT / "tasks" / "forging_sixbar.yaml"),
                             "--out", str(tmp_path / "out"), "--format", "pdf", "--quiet"],
                            env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        helper = None
        deadline = time.monotonic() + 120
        while helper is None and time.monotonic() < deadline and main.poll() is None:
            kids = _children(main.pid)
            helper = kids[0] if kids else None
            time.sleep(0.02)
        assert helper is not None, "the report helper was never started"
        if kill_when == "helper waiting":
            # the helper has sent its sections and waits for the HTML: the main process is
            # writing the figures by then
            while main.poll() is None and not (tmp_path / "out" / "figures").exists():
                time.sleep(0.02)
        os.kill(main.pid, signal.SIGKILL)
        main.wait(timeout=10)
        # it exits when its pipe closes (no clock of its own to wait for): a generous bound,
        # not a wall time a busy machine could miss -- a helper waiting forever stays past it
        t0 = time.monotonic()
        while _running(helper) and time.monotonic() - t0 < 60:
            time.sleep(0.05)
        alive = _running(helper)
        if alive:
            os.kill(helper, signal.SIGKILL)
        assert not alive, "the report helper outlived the main process"
    finally:
        if main.poll() is None:
            main.kill()
            main.wait()
