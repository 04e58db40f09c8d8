"""`tolerance: graphical`: a hand solution is graded with the error of reading the drawings.

The expected tolerances are written out from their definitions: a plan segment read to
0.5 mm at the plan's scale mu gives |dv| = 0.5 mu, i.e. the relative error 0.5 mu / v; the
flywheel's is the 12-position trapezoid's own error |J_hand - J| / J."""
from __future__ import annotations

from pathlib import Path

import pytest

from tmm_cli.check import compare, tolerance_for, tolerances
from tmm_cli.pipeline import run
from tmm_cli.task import load_task
from tmm_cli.yamlload import load_yaml

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def forging():
    data, _ = load_yaml(ROOT / "tasks" / "forging_sixbar.yaml")
    data["tolerance"] = {"default": "graphical", "flywheel.M_constant": 0.01, "positions": 0.02}
    task = load_task(data)
    return task, run(task)


def test_graphical_tolerances_from_their_definitions(forging):
    task, r = forging
    tol = tolerances(task, results=r)
    hand, fw = r["flywheel"]["hand"], r["flywheel"]
    assert tolerance_for("flywheel.J_n", tol).rel == pytest.approx(abs(hand["J_n"] - fw["J_n"]) / fw["J_n"],
                                                                    rel=1e-9)
    # the plan read to 0.5 mm: mu_v in (m/s)/mm of the report's velocity plans
    mu_v = r["graphical_error"]["plans"]["mu_v"]
    vB = r["kinematics"][1]["points"]["B"]["v"]
    assert tolerance_for("kinematics[1].points.B.v", tol).rel == pytest.approx(0.5 * mu_v / vB, rel=1e-12)
    # an explicit key wins over the graphical default; paths without a drawing keep 0.05
    assert tolerance_for("flywheel.M_constant", tol).rel == pytest.approx(0.01)
    assert tolerance_for("positions.phi0", tol).rel == pytest.approx(0.02)
    assert tolerance_for("structure.W", tol) == 0.05


def test_grading_with_the_graphical_tolerance(forging):
    task, r = forging
    tol = tolerances(task, results=r)
    ref = r["flywheel"]["J_n"]
    g = abs(r["flywheel"]["hand"]["J_n"] - ref) / ref
    t = tolerance_for("flywheel.J_n", tol)
    assert compare(ref * (1 + 0.9 * g), ref, t, False)[0] == "ok"
    assert compare(ref * (1 + 1.1 * g), ref, t, False)[0] == "outside"
    # the student's own 12-position hand value passes
    assert compare(r["flywheel"]["hand"]["J_n"], ref, t, False)[0] == "ok"


def test_graphical_is_a_valid_tolerance_value_and_nothing_else_is():
    from tmm_cli.errors import TaskError
    data, _ = load_yaml(ROOT / "tasks" / "forging_sixbar.yaml")
    data["tolerance"] = {"default": "graphic"}
    with pytest.raises(TaskError) as ei:
        load_task(data)
    assert "tolerance" in str(ei.value.render())
