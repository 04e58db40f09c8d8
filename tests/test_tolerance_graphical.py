"""`tolerance: graphical`: a hand solution is graded with the error of the hand method.

The expected tolerances are written out from their definitions: a plan segment of a careful
hand solution is off by up to 2.5 % of the crank pin's vector (measured on a course project's
plans: benchmarks/graphical_calibration.py), i.e. the relative error 0.025 v_A / v; the
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
    # a careful hand solution's plan: off by 2.5 % of the crank pin's vector (v_A) on any segment
    vA = max(e["points"]["A"]["v"] for e in r["kinematics"])
    vB = r["kinematics"][1]["points"]["B"]["v"]
    assert tolerance_for("kinematics[1].points.B.v", tol).rel == pytest.approx(0.025 * vA / vB, rel=1e-12)
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


def test_the_course_projects_hand_plans_pass_and_its_slips_do_not():
    """The hand-drawn velocity plans of the course project (benchmarks/reference): every value
    but the two slips (v_S4 = 0 where it is 13.9 m/s) passes `graphical`; both slips fail."""
    import sys
    sys.path.insert(0, str(ROOT / "benchmarks"))
    import graphical_calibration as cal
    from tmm_cli.check import Tol
    task = load_task(cal.TASK)
    r = run(task)
    task.tolerance["default"] = "graphical"
    tol = tolerances(task, results=r)
    paths = {"B.v": "points.B.v", "S2.v": "points.S2.v", "D.v": "points.D.v", "S4.v": "points.S4.v",
             "rod1.omega": "links.rod1.omega", "rod2.omega": "links.rod2.omega"}
    verdicts = {}
    for i, hand in cal.HAND.items():
        e = next(k for k in r["kinematics"] if k["index"] == i)
        for col, h in zip(cal.COLUMNS, hand):
            if col not in paths:
                continue
            p = f"kinematics[{i}].{paths[col]}"
            section, name, q = paths[col].split(".")
            x = e[section][name][q]
            t = tolerance_for(p, tol)
            t = t if isinstance(t, Tol) else Tol(rel=float(t))
            verdicts[(i, col)] = compare(h if x >= 0 else -h, x, t, False)[0]
            # independently: within 2.5 % of v_A (an omega: of v_A / l), or an exact zero answered 0
            bound = 0.025 * cal.V_A / (cal.L_ROD if q == "omega" else 1.0)
            if abs(x) > 0.02 * cal.V_A / (cal.L_ROD if q == "omega" else 1.0):
                assert (verdicts[(i, col)] == "ok") == (abs(abs(h) - abs(x)) <= bound * 1.001), (i, col, h, x)
    assert [k for k, v in verdicts.items() if v != "ok"] == [(3, "S4.v"), (9, "S4.v")]
