"""The tutorials' task (docs/tutorial.md and its Russian twin): the engine they write is a valid
task whose position 0 is the top dead centre its comment names. Worked by hand: a central
slider-crank with its guide vertical through O has its piston highest with the crank
straight up, phi = 90 deg; the power stroke moves the piston down (against the guide's +y),
so with `working: backward` position 0, the start of the working stroke, is there. Their
shell commands are the ones the CLI takes (each parses as a command line)."""
from __future__ import annotations

import re
import shlex
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
TUTORIALS = ["docs/tutorial.md", "docs/tutorial.ru.md"]


@pytest.mark.parametrize("doc", TUTORIALS)
def test_the_tutorial_engine_starts_at_top_dead_centre(doc, tmp_path):
    import tmm_cli
    text = (ROOT / doc).read_text(encoding="utf-8")
    engine = re.findall(r"```yaml\n(.*?)```", text, re.S)[0]
    f = tmp_path / "my_engine.yaml"
    f.write_text(engine, encoding="utf-8")
    res = tmm_cli.run(tmm_cli.load_task(f))
    assert res["positions"]["phi0"] == pytest.approx(90.0, abs=1e-9)
    assert not [m for m in res["messages"] if m["code"] == "positions.quick_working"]
    gear = re.findall(r"```yaml\n(.*?)```", text, re.S)[2]
    g = tmp_path / "gear.yaml"
    g.write_text(re.sub(r"(?m)^  ", "", gear), encoding="utf-8")
    assert tmm_cli.load_task(g).gears is not None


@pytest.mark.parametrize("doc", TUTORIALS)
def test_the_tutorial_commands_are_the_clis(doc):
    """Each `.venv/bin/tmm ...` line of the tutorial's shell blocks parses as the command line it
    shows (a renamed option or command fails here, not in a student's terminal)."""
    from typer.main import get_command

    from tmm_cli.cli import app
    cli = get_command(app)
    text = (ROOT / doc).read_text(encoding="utf-8")
    lines = [ln.split(">")[0] for b in re.findall(r"```sh\n(.*?)```", text, re.S) for ln in b.splitlines()
             if ln.startswith(".venv/bin/tmm ")]
    assert len(lines) >= 4
    for ln in lines:
        args = shlex.split(ln)[1:]
        if args == ["--help"]:
            continue
        sub = cli.commands[args[0]]
        sub.make_context(args[0], args[1:], resilient_parsing=False)    # raises on a wrong option
    with pytest.raises(Exception, match="No such option"):      # the check can fail: a renamed option
        cli.commands["run"].make_context("run", ["tasks/x.yaml", "--language", "ru"], resilient_parsing=False)
