"""`tmm study` on the command line as a student meets it: a synthesis no mechanism can meet
fails as `tmm run` fails (exit 3, the stage named, no "internal error"), and a task with
nothing to sweep says so and writes no empty page."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _tmm(*args, cwd=ROOT):
    return subprocess.run([sys.executable, "-m", "tmm_cli", *map(str, args)], cwd=cwd,
                          capture_output=True, text=True)


def test_impossible_synthesis_fails_as_run_does(tmp_path):
    """psi 170 deg at K = 3 with a 50 mm frame: no crank-rocker. `tmm study` said "internal error
    (SynthesisImpossible: ...); please report it"; `tmm run` says the stage failed, exit 3."""
    text = (ROOT / "tasks" / "synthesis_crank_rocker.yaml").read_text(encoding="utf-8")
    text = text.replace("psi: 40", "psi: 170").replace("K: 1.2", "K: 3").replace("frame: 0.4", "frame: 50 mm")
    task = tmp_path / "impossible.yaml"
    task.write_text(text, encoding="utf-8")
    run = _tmm("run", task, "--out", tmp_path / "run", "--format", "json", "--quiet")
    assert run.returncode == 3
    said = [x for x in run.stderr.splitlines() if x.startswith("error:")]
    assert said and "stage 'synthesis' failed" in said[0]
    for cmd in (["study", task, "--out", tmp_path / "study", "--repeat", "1"],
                ["sheets", task, "--out", tmp_path / "sheets"]):
        res = _tmm(*cmd)
        assert res.returncode == 3, (cmd[0], res.stderr)
        assert "internal error" not in res.stderr and "Traceback" not in res.stderr
        assert [x for x in res.stderr.splitlines() if x.startswith("error:")] == said[:1], cmd[0]
    assert not (tmp_path / "study").exists()
