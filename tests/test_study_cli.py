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


def test_nothing_to_sweep_is_said_and_no_empty_page(tmp_path):
    """A differential has no setting that trades time for accuracy: `tmm study` wrote an empty
    study.html and study.json `{}`, printed nothing and exited 0. Now it says, in the language asked
    for, that there is nothing to sweep and what the study sweeps, and writes nothing; exit 0, as
    `tmm sheets` with no sheet to draw. `tmm run --study` says it as a warning and writes no page."""
    from tmm_cli import load_task
    from tmm_cli.messages import Message, render
    task = ROOT / "tasks" / "differential_A.yaml"
    want = Message("study.nothing_to_sweep", sections=["differential"])
    for lang in ("en", "ru", "uk"):
        out = tmp_path / lang
        res = _tmm("study", task, "--out", out, "--repeat", "1", "--lang", lang)
        assert res.returncode == 0, res.stderr
        text = render(want.code, want.params, lang)
        assert text[0].upper() + text[1:] + "." in res.stderr.splitlines(), (lang, res.stderr)
        assert "`cam`" in text and "`dof2`" in text
        assert not out.exists()                 # no empty page, no `{}`
    from tmm_cli import study
    assert study.nothing_to_sweep(load_task(task), {}, {}) == want
    res = _tmm("run", task, "--out", tmp_path / "run", "--study", "--format", "json,html", "--quiet")
    assert res.returncode == 0 and f"warning: {want}" in res.stderr.splitlines(), res.stderr
    assert not (tmp_path / "run" / "study.html").exists() and not (tmp_path / "run" / "study.json").exists()
    assert (tmp_path / "run" / "report.html").exists()
