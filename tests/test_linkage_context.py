"""The linkage context (tmm_cli/linkage/context.py): built once from the task, frozen, the
one carrier of the sense of rotation; every linkage stage takes it and its own section."""
from __future__ import annotations

import ast
import dataclasses
import inspect
import math
from pathlib import Path

import pytest

import tmm_cli
from tmm_cli.linkage import dynamics, kinematics, kinetostatics, loads, synthesis
from tmm_cli.linkage.context import build

ROOT = Path(__file__).resolve().parent.parent
TASKS = ROOT / "tasks"


def test_a_clockwise_drive_in_the_context():
    task = tmm_cli.load_task(TASKS / "press_offset_slider_crank.yaml")     # 90 rpm, cw
    lk = build(task)
    # 90 rpm = 90 * 2 pi / 60 = 9.42477796... rad/s, clockwise: negative
    assert lk.drive.sign == -1.0
    assert lk.drive.omega == pytest.approx(-9.42477796076938, rel=1e-15)
    assert lk.drive.speed == pytest.approx(3.0 * math.pi, rel=1e-15)
    assert (lk.drive.direction, lk.drive.cycle, lk.drive.source) == ("cw", 360.0, "speed")
    assert lk.positions.sign == lk.drive.sign and lk.positions.direction == "cw"
    # the grid runs in the drive's sense: position 1 is 360/count deg clockwise of position 0
    step = 360.0 / lk.positions.count
    assert (lk.positions.phi0 - lk.positions.phi[1]) % 360.0 == pytest.approx(step)
    with pytest.raises(dataclasses.FrozenInstanceError):
        lk.drive.omega = 1.0
    with pytest.raises(dataclasses.FrozenInstanceError):
        lk.positions = None


def test_the_pipeline_runs_on_the_same_context():
    task = tmm_cli.load_task(TASKS / "press_offset_slider_crank.yaml")
    res = tmm_cli.run(task)
    lk = build(task)
    assert res["drive"] == lk.drive.to_dict()
    assert res["positions"]["phi"] == [float(x) for x in lk.positions.phi]
    assert res["kinematics"] == kinematics.analyze(lk).to_entries(list(lk.positions.index))


@pytest.mark.parametrize("fn", [kinematics.analyze, kinematics.output_curve, loads.evaluate, dynamics.analyze,
                                kinetostatics.analyze, synthesis.analyse])
def test_every_stage_takes_the_linkage_and_no_task(fn):
    names = list(inspect.signature(fn).parameters)
    assert names[0] == "linkage"
    assert "task" not in names


STAGE_FILES = [p for p in (ROOT / "tmm_cli" / "linkage").rglob("*.py")
               if p.name != "solver.py"]   # the solver reads State fields by name (o1, th1, ...)


def test_no_getattr_default_stands_in_for_a_type():
    """getattr(x, name, default) / hasattr(x, name) on a stage's inputs would accept any
    stand-in; the stages read typed fields."""
    found = []
    for p in STAGE_FILES:
        for node in ast.walk(ast.parse(p.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Call) and isinstance(node.func, ast.Name):
                if (node.func.id == "getattr" and len(node.args) == 3) or node.func.id == "hasattr":
                    found.append(f"{p.relative_to(ROOT)}:{node.lineno}")
    assert found == []
