"""`tolerance: graphical`: a hand solution is graded with the error of the hand method.

The expected tolerances are written out from their definitions: a plan segment of a careful
hand solution is off by up to 2.5 % of the crank pin's vector (measured on a course project's
plans: benchmarks/graphical_calibration.py), i.e. the relative error 0.025 v_A / v; the
flywheel's is the band from the 12-position trapezoid's value to the accurate one, widened by
2.5 % of the larger (the hand method's error is one-sided)."""
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
    lo, hi = sorted((hand["J_n"], fw["J_n"]))
    m = 0.025 * max(abs(hand["J_n"]), abs(fw["J_n"]))
    assert tolerance_for("flywheel.J_n", tol).band == pytest.approx((lo - m, hi + m), rel=1e-12)
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
    ref, hand = r["flywheel"]["J_n"], r["flywheel"]["hand"]["J_n"]
    t = tolerance_for("flywheel.J_n", tol)
    m = 0.025 * max(ref, hand)
    lo, hi = min(ref, hand) - m, max(ref, hand) + m
    # the student's own 12-position hand value, rounded to 3 digits, and the accurate value pass
    assert compare(float(f"{hand:.3g}"), ref, t, False)[0] == "ok"
    assert compare(ref, ref, t, False)[0] == "ok"
    assert compare(lo * 1.001, ref, t, False)[0] == "ok" and compare(hi * 0.999, ref, t, False)[0] == "ok"
    assert compare(lo * 0.999, ref, t, False)[0] == "outside" and compare(hi * 1.001, ref, t, False)[0] == "outside"
    # beyond the accurate value by the hand method's error (the symmetric band passed it): outside
    # (J_n = 179.85, the hand 164.77: 194.9 lies past 179.85 + 4.50)
    assert abs(ref - hand) > 3 * m
    assert compare(ref + abs(ref - hand), ref, t, False)[0] == "outside"
    assert compare(-ref, ref, t, False)[0] == "sign"
    assert t.text == f"band {lo:.10g}..{hi:.10g}"
    # sign: any keeps the band (the magnitude graded against it)
    import dataclasses
    both = dataclasses.replace(t, any_sign=True)
    assert compare(-ref, ref, both, False)[0] == "ok" and compare(-3 * ref, ref, both, False)[0] == "outside"


def test_the_graphical_flywheel_band_on_a_worked_case():
    """The press of a newcomer's trial: J = 158.14 kg*m^2 accurate, 81.876 by the 12-position
    trapezoid; the band 81.876 - 0.025*158.14 = 77.92 .. 158.14 + 3.95 = 162.09 passes the hand
    value written as 81.8 (the symmetric band of the old rule, 158.14 +- 76.26, failed it at its
    edge) and fails 234 (which the old rule passed)."""
    from tmm_cli.check import Tol
    acc, hand = 158.13998288643785, 81.87648398923855
    results = {"flywheel": {"J": acc, "hand": {"positions": 12, "step": 30.0, "J": hand,
                                              "err_J": abs(hand - acc) / acc}}}
    from tmm_cli.graphical import graphical_tolerance
    lo, hi = graphical_tolerance(results)["flywheel.J"]
    assert (lo, hi) == pytest.approx((hand - 0.025 * acc, acc + 0.025 * acc), rel=1e-15)
    assert (round(lo, 2), round(hi, 2)) == (77.92, 162.09)
    t = Tol(rel=0.0, plain=False, band=(lo, hi))
    assert [compare(x, acc, t, False)[0] for x in (81.8, 158.1, 234.0, 77.0, -100.0)] == \
        ["ok", "ok", "outside", "outside", "sign"]


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


def test_key_of_reads_a_band_as_the_interval_it_is():
    """copies.KeyTable counts a key's band (the graphical flywheel) as the interval [lo, hi]:
    an answer inside another variant's band and outside its own counts for that variant."""
    from tmm_cli.check import Tol
    from tmm_cli.copies import KeyTable, key_of
    own = {"flywheel.J": (158.14, Tol(rel=0.0, plain=False, band=(77.92, 162.09)), False)}
    other = {"flywheel.J": (300.0, Tol(rel=0.0, plain=False, band=(200.0, 310.0)), False)}
    table = KeyTable([own, other])
    assert list(table.counts({"flywheel.J": 81.8})) == [1, 0]
    assert list(table.counts({"flywheel.J": 205.0})) == [0, 1]
    assert list(table.counts({"flywheel.J": 170.0})) == [0, 0]
    assert key_of({"flywheel.J": 205.0}, 0, 0, table) == 1


def test_angles_graded_with_a_relative_tolerance_are_told_to_the_instructor():
    """The default 5 % passes phi0 = 92.15 deg 4.6 deg off and a working-stroke angle of 181.43
    answered 175 (the strokes swapped): grading says so once, naming those paths; theta = 1.43 deg
    (5 % of it is 0.07 deg) and an angle held in degrees are not named; no note without one."""
    from tmm_cli.check import AnswerSet, angle_tolerance_note, grade, parse_tolerance
    results = {"positions": {"phi0": 92.15, "theta": 1.43, "working_stroke_angle": 181.43, "K": 1.016}}
    aset = AnswerSet(source="a.yaml", answers={"positions.phi0": 87.85, "positions.theta": 1.43,
                                               "positions.working_stroke_angle": 175.0, "positions.K": 1.0})
    rows = grade(results, aset, {})
    assert {r["path"]: r["status"] for r in rows}["positions.working_stroke_angle"] == "ok"   # 3.6 % < 5 %
    note = angle_tolerance_note(rows, {})
    assert note.code == "answers.angle_relative"
    assert note.params["paths"] == ["positions.phi0", "positions.working_stroke_angle"]
    assert note.params["rel"] == 0.05 and note.params["at90"] == pytest.approx(4.5)
    tol = {"positions.phi0": parse_tolerance({"abs": 0.5}, "t"), "positions.working_stroke_angle": 0.004}
    rows = grade(results, aset, tol)
    assert angle_tolerance_note(rows, tol) is None          # 0.4 % of 181.43 = 0.73 deg: within 1 deg
    assert angle_tolerance_note([], {}) is None


def test_a_misspelt_tolerance_key_is_told_even_as_a_section_name():
    """A tolerance key that names no quantity is a typo whose paths keep the default: in a section
    the task has (`positions.ph0`), and as a section no task has (`kinematcs`: it was silently
    ignored); a section of other tasks (`gears` for a linkage: a group's tolerance file) is not."""
    from tmm_cli.check import unused_tolerance_keys
    results = {"positions": {"phi0": 92.15, "K": 1.016}, "kinematics": [{"index": 0, "points": {"B": {"v": 1.0}}}]}
    said = {m.params["key"]: m.params["hint"]["text"] for m in unused_tolerance_keys(
        ["default", "positions.ph0", "kinematcs", "gears", "positions.K", "kinematics", "zzz"], results)}
    assert said == {"positions.ph0": "did you mean 'positions.phi0'?", "kinematcs": "did you mean 'kinematics'?",
                    "zzz": "no such path in the results"}


def test_a_batchs_angle_notes_are_one():
    """Each variant of a batch gives its own note on angles graded with a share; the batch prints
    one: the largest share and the paths of all (sorted), where the first note was."""
    from tmm_cli.check import merged_angle_notes
    from tmm_cli.messages import Message

    def note(rel, paths):
        return Message("answers.angle_relative", rel=rel, at90=90 * rel, paths=paths, more="", path=paths[0])
    other = Message("answers.note_missing")
    out = merged_angle_notes([other, note(0.05, ["positions.phi0"]), note(0.1, ["positions.theta", "positions.phi0"])])
    assert [getattr(n, "code", None) for n in out] == ["answers.note_missing", "answers.angle_relative"]
    assert out[1].params["rel"] == 0.1 and out[1].params["paths"] == ["positions.phi0", "positions.theta"]
    assert merged_angle_notes([other]) == [other]
