"""The instructor's loop: variant tables, answer forms, grading, feedback, and the
robustness of `tmm batch` (isolated workers, folders, manifest, CSV injection)."""
from __future__ import annotations

import csv
import json
import math
import os
import re
from pathlib import Path

import pytest
import yaml
from typer.testing import CliRunner

from tmm_cli.check import AnswerSet, Tol, answer_value, compare, grade, parse_tolerance, set_status
from tmm_cli.cli import app
from tmm_cli.tables import cell_value, csv_text, read_table, safe_cell

runner = CliRunner()
ROOT = Path(__file__).resolve().parent.parent
EX = ROOT / "examples" / "instructor"

GEARS = """schema: tmm/1
title: gears
variant: {v}
gears: {{m: 4 mm, z: [14, 30], x: [0.3, 0.1]}}
"""


def _write(d: Path, name: str, text: str) -> Path:
    p = d / name
    p.parent.mkdir(parents=True, exist_ok=True)
    p.write_text(text, encoding="utf-8")
    return p


def _csv(path: Path) -> list[dict]:
    with open(path, encoding="utf-8", newline="") as fh:
        return list(csv.DictReader(fh))


# ------------------------------------------------------------------ tables and CSV
def test_cells_decimal_comma_and_text():
    assert cell_value("0,12") == 0.12 and cell_value("-1,5") == -1.5 and cell_value(" 07 ") == 7
    assert cell_value("1e3") == 1000.0 and cell_value("abc") == "abc" and cell_value("") == ""


def test_read_table_semicolons_bom_and_line_numbers(tmp_path):
    p = tmp_path / "t.csv"
    p.write_bytes("variant;l, mm\r\n1;0,5\r\n\r\n\"2\";\"3,25\"\r\n3;1;9\r\n".encode("utf-8-sig"))
    header, rows = read_table(p)
    assert header == ["variant", "l, mm"]
    assert [(ln, r["l, mm"], bad) for ln, r, bad in rows][:2] == [(2, "0,5", None), (4, "3,25", None)]
    assert rows[2][0] == 5 and "malformed row" in rows[2][2]


@pytest.mark.parametrize("text,out", [("=HYPERLINK(\"x\")", "'=HYPERLINK(\"x\")"), ("@SUM(A1)", "'@SUM(A1)"),
                                      ("+1+2 x", "'+1+2 x"), ("-cmd", "'-cmd"), ("\tx", "'\tx"),
                                      ("\rx", "'\rx"), ("-1.5", "-1.5"), ("plain", "plain")])
def test_formula_cells_neutralised(text, out):
    assert safe_cell(text) == out
    assert safe_cell(-2.5) == "-2.5" and safe_cell(-3) == -3 and safe_cell(None) == ""


def test_csv_text_header_and_rows_neutralised():
    text = csv_text(["=a", "b"], [["@x", -1.0], {"=a": 1, "b": "+y"}])
    rows = list(csv.reader(text.splitlines()))
    assert rows == [["'=a", "b"], ["'@x", "-1.0"], ["1", "'+y"]]


def test_csv_text_floats_written_as_safe_cell_writes_them():
    """Finite floats skip safe_cell (the fast path of long tables): the same text."""
    vals = [1.0, -0.1, 1e-20, -2.5e300, 1e308, 0.30000000000000004, float("nan"), float("inf"),
            -float("inf"), None, True, 3, "-x", "a,b"]
    rows = list(csv.reader(csv_text(["h"] * len(vals), [vals]).splitlines()))
    assert rows[1] == ["1.0", "-0.1", "1e-20", "-2.5e+300", "1e+308", "0.30000000000000004", "", "", "",
                       "", "true", "3", "'-x", "a,b"]


# ------------------------------------------------------------------ grading (hand values)
def test_compare_relative_absolute_angles_and_sign():
    # |9.1 - 10| / 10 = 0.09 within 0.1
    assert compare(9.1, 10.0, Tol(rel=0.1), False)[:2] == ("ok", pytest.approx(0.09))
    # sign: -10.2 is 2 % from -10... the student wrote +10.2 for a reference of -10
    assert compare(10.2, -10.0, Tol(rel=0.05), False)[0] == "sign"
    assert compare(11.0, 10.0, Tol(rel=0.05), False)[0] == "outside"
    # zero reference with a plain number: absolute 0.001 <= 0.05
    assert compare(0.001, 0.0, Tol(rel=0.05), False) == ("ok", 0.001, "abs")
    # {rel, abs}: bound = max(0.5, 0.02 * 246) = 4.92 deg
    t = parse_tolerance({"rel": 0.02, "abs": 0.5}, "x")
    assert compare(250.0, 246.0, t, True)[0] == "ok" and compare(251.0, 246.0, t, True)[0] == "outside"
    # angles modulo 360: 359 vs 1 differ by 2 deg, not 358
    st, err, kind = compare(359.0, 1.0, Tol(rel=0.0, abs=2.5, plain=False), True)
    assert st == "ok" and err == pytest.approx(2.0) and kind == "abs"
    assert compare(3.0, 1.0, Tol(rel=0.0, abs=1.5, plain=False), True)[0] == "outside"
    # 359 deg is -1 deg: for a reference of 1 deg that is the sign error
    assert compare(359.0, 1.0, Tol(rel=0.0, abs=1.5, plain=False), True)[0] == "sign"
    # the issue's case: phi0 = 246 deg, 12 deg off, abs 0.5 -> outside
    assert compare(258.0, 246.0, parse_tolerance({"abs": 0.5}, "x"), True)[0] == "outside"


def test_a_round_off_zero_reference_is_graded_as_zero():
    """B's speed at a dead centre is zero; the kinematics gives its round-off (1.3e-16 m/s in
    press_offset_slider_crank's position 0). Graded against 0 (the zero reference's absolute
    tolerance), as the report's tables print it: a student's 1 mm/s read off the plan passes --
    against 1.3e-16 the relative 5 % failed it by 10^14 %. A small reference above the round-off
    stays relative; the key and `tmm paths` give the reference as graded."""
    import tmm_cli
    from tmm_cli.forms import form_text
    from tmm_cli.report.context import fmt
    from tmm_cli.results import ROUND_OFF_ZERO, lookup, reference
    task = tmm_cli.load_task(ROOT / "tasks" / "press_offset_slider_crank.yaml")
    res = tmm_cli.run(task)
    p = "kinematics[0].points.B.v"
    raw = lookup(res, p)
    assert 0 < abs(raw) < 1e-14                          # the round-off the grading meets
    rows = grade(res, AnswerSet(source="", answers={p: 0.001, "kinematics[0].points.A.v": 0.001}), {})
    assert rows[0]["reference"] == 0.0 and rows[0]["status"] == "ok" and rows[0]["error"] == 0.001
    assert rows[1]["status"] == "outside"                # A moves: 0.001 m/s is 100 % off
    assert grade(res, AnswerSet(source="", answers={p: 0.06}), {})[0]["status"] == "outside"   # abs 0.05
    # the boundary is the report's: what its tables print 0 is graded against 0
    for v in (0.99e-10, -0.99e-10, 1.01e-10, -1.01e-10, 5e-324, -0.0):
        assert (reference(v) == 0.0) == (fmt(v) == "0") == (abs(v) < ROUND_OFF_ZERO)
    small = 3e-9                                         # above the round-off: relative 5 %
    assert compare(3.1e-9, reference(small), Tol(rel=0.05), False)[0] == "ok"
    assert compare(3.3e-9, reference(small), Tol(rel=0.05), False)[0] == "outside"
    key = form_text(task, [p], res, "en")
    assert f"{p}: 0.0" in key or f'"{p}": 0.0' in key, key
    out = CliRunner().invoke(app, ["paths", str(ROOT / "tasks" / "press_offset_slider_crank.yaml"),
                                   "--prefix", "kinematics[0].points.B"])
    assert out.exit_code == 0 and f"{p}\t0.0\n" in out.output, out.output


def test_answer_values_with_units():
    assert answer_value("283 kg*m^2", "flywheel.J") == pytest.approx(283.0)
    assert answer_value("12 deg", "positions.phi0") == pytest.approx(12.0)
    assert answer_value("0.5 rad", "positions.phi0") == pytest.approx(0.5 * 180 / math.pi)
    assert answer_value("50 rpm", "kinematics[1].links.crank.omega") == pytest.approx(50 * 2 * math.pi / 60)
    assert answer_value("120 mm", "gears.aw") == pytest.approx(0.12)
    assert answer_value("3,5", "gears.aw") == 3.5 and answer_value("", "x") is None and answer_value(None, "x") is None
    for bad in ("abc", "12 apples", float("nan"), "mm", "m/s"):     # a bare unit is not 1 of it
        with pytest.raises(ValueError):
            answer_value(bad, "gears.aw")


def test_answer_with_a_decimal_comma_and_a_unit():
    """'0,67 m/s' is 0.67 m/s as '0,67' alone is 0.67: pint alone read it as 0 m/s (graded
    outside with no reason given) and '3,5 mm' as 35 mm."""
    assert answer_value("0,67 m/s", "kinematics[1].points.B.v") == pytest.approx(0.67)
    assert answer_value("3,5 mm", "gears.aw") == pytest.approx(0.0035)
    assert answer_value("-1,5 kN*m", "kinetostatics[1].balancing_moment") == pytest.approx(-1500.0)


def test_answer_in_cyrillic_units_is_read():
    """'3,04 рад/с' as a Russian student writes it is 3.04 rad/s; a Cyrillic word that is
    no unit is that answer's reason."""
    assert answer_value("3,04 рад/с", "kinematics[1].links.rocker.omega") == pytest.approx(3.04)
    with pytest.raises(ValueError) as err:
        answer_value("5 попугаев", "kinematics[1].links.rocker.omega")
    assert err.value.args[0].code == "input.number_unit_unknown"


def test_answer_in_another_quantitys_unit_is_not_graded():
    """A unit of another quantity is an error naming the path's unit, not a number taken in
    SI base units and graded: "0.67 kg" for a velocity was 0.67 and graded ok against
    0.6685 m/s. Units of the right quantity convert: 1005 mm/s = 1.005 m/s, 3 kN*m =
    3000 N*m, 2 % of a ratio error = 0.02; an angle in metres is no angle. A path outside
    the presets keeps SI base units (a last name like `y` means different things)."""
    from tmm_cli.messages import render
    assert answer_value("1005 mm/s", "kinematics[1].points.B.v") == pytest.approx(1.005)
    assert answer_value("3 kN*m", "kinetostatics[1].balancing_moment") == pytest.approx(3000.0)
    assert answer_value("2 %", "planetary.ratio_error") == pytest.approx(0.02)
    assert answer_value("12 mm", "kinematics[1].points.B.y") == pytest.approx(0.012)
    for bad, path, unit in (("0.67 kg", "kinematics[1].points.B.v", "m/s"),
                            ("5 m/s", "kinematics[1].points.B.a", "m/s^2"),
                            ("12 m", "positions.phi0", "degree"),
                            ("3 kg", "flywheel.delta", "dimensionless"),
                            ("0.5 kg", "kinematics[7].points.O.v", "m/s"),        # outside the presets too
                            ("2 N", "kinematics[3].links.rod.epsilon", "rad/s^2"),
                            ("336 N*m", "kinetostatics[1].reactions.R12.R", "N")):
        with pytest.raises(ValueError) as err:
            answer_value(bad, path)
        msg = err.value.args[0]
        assert msg.code == "answers.wrong_unit" and f"does not convert to {unit}" in str(msg), (bad, str(msg))
        # the target unit in the page's language
        ru = {"m/s": "м/с", "m/s^2": "м/с²", "degree": "°", "dimensionless": "безразмерной величине", "N": "Н",
              "rad/s^2": "рад/с²"}[unit]
        assert render(msg.code, msg.params, "ru").endswith("единица не приводится к " + ru)


def test_grade_statuses():
    res = {"structure": {"W": 1}, "flywheel": {"J": 10.0, "delta": None}, "positions": {"phi0": 246.0}}
    aset = AnswerSet(source="a", answers={"structure.W": 1, "flywheel.J": -10.1, "flywheel.JJ": 3,
                                          "flywheel.delta": 0.1, "gears.aw": 0.1, "positions.phi0": None})
    rows = {r["path"]: r for r in grade(res, aset, {}, required=["structure.W", "positions.H"])}
    assert rows["structure.W"]["status"] == "ok"
    assert rows["flywheel.J"]["status"] == "sign"
    assert rows["flywheel.JJ"]["status"] == "unknown_path" and "did you mean 'flywheel.J'" in rows["flywheel.JJ"]["note"]
    assert rows["flywheel.delta"]["status"] == "not_computed"
    assert rows["gears.aw"]["status"] == "not_computed"
    assert rows["positions.phi0"]["status"] == "missing"
    assert rows["positions.H"]["status"] == "unknown_path"
    assert set_status(list(rows.values())) == "sign"
    assert set_status(grade(res, AnswerSet(source="b", answers={"flywheel.J": None}), {})) == "no_answers"


# ------------------------------------------------------------------ variants
def test_shipped_example_writes_30_valid_tasks(tmp_path):
    res = runner.invoke(app, ["variants", str(EX / "press_template.yaml"), str(EX / "press_variants.csv"),
                              "--out", str(tmp_path / "v")])
    assert res.exit_code == 0, res.output
    rows = _csv(tmp_path / "v" / "variants.csv")
    assert len(rows) == 30 and {r["status"] for r in rows} == {"written"}
    import yaml
    t7 = yaml.safe_load((tmp_path / "v" / "07.yaml").read_text())
    table = {r["variant"]: r for _, r, _ in read_table(EX / "press_variants.csv")[1]}
    assert t7["variant"] == 7 and t7["title"] == "Crank press, variant 7"
    assert t7["mechanism"]["links"]["rod"]["length"] == f"{table['07']['l_AB, mm']} mm"
    assert t7["drive"]["speed"] == f"{table['07']['n [rpm]']} rpm"
    assert t7["flywheel"]["delta"] == cell_value(table["07"]["delta"])


TEMPLATE = """schema: tmm/1
title: "Variant {variant} {{literal}}"
mechanism:
  ground: {O: [0, 0]}
  links:
    crank: {points: [O, A], length: "{a}"}
    rod: {points: [A, B], length: "{b}"}
    slider: {slider: B, guide: {through: [0, 0], angle: 0}}
  assembly: {B: [0.3, 0]}
drive: {link: crank, speed: "{n}", direction: ccw}
"""


def test_variants_bad_rows_are_reported_and_others_written(tmp_path):
    tpl = _write(tmp_path, "tpl.yaml", TEMPLATE)
    tab = _write(tmp_path, "tab.csv", "variant;a, mm;b [mm];n\n1;100;300;10\n2;100;50;10\n3;100;300;10;7\n"
                                      "4;100;300;ten rpm\n5;80;250;12,5\n")
    res = runner.invoke(app, ["variants", str(tpl), str(tab), "--out", str(tmp_path / "o")])
    assert res.exit_code == 2
    err = res.output
    assert f"{tab}:3: variant 2: stage 'kinematics' failed" in err          # rod shorter than the crank
    assert f"{tab}:4: variant 3: malformed row" in err
    assert f"{tab}:5: variant 4: " in err and "drive.speed" in err
    assert sorted(p.name for p in (tmp_path / "o").glob("*.yaml")) == ["1.yaml", "5.yaml"]
    rep = {r["variant"]: r for r in _csv(tmp_path / "o" / "variants.csv")}
    assert rep["1"]["status"] == "written" and rep["2"]["status"] == "invalid" and rep["3"]["line"] == "4"
    import yaml
    t = yaml.safe_load((tmp_path / "o" / "5.yaml").read_text())
    assert t["title"] == "Variant 5 {literal}" and t["variant"] == 5
    assert t["mechanism"]["links"]["crank"]["length"] == "80 mm" and t["drive"]["speed"] == 12.5


def test_variants_empty_cell_and_unused_column(tmp_path):
    """An empty cell a placeholder takes is the row's error naming the column: with a unit
    in the header it became ' mm', read as 1 mm, and the row was written as a valid task
    with a 1 mm crank; without one '' reached the field. A column no placeholder takes is
    warned about (the instructor meant to vary it); the rows are still written."""
    tpl = _write(tmp_path, "tpl.yaml", TEMPLATE)
    tab = _write(tmp_path, "tab.csv", "variant;a, mm;b [mm];n;m2\n1;;300;10;2\n2;100;300;;2\n3;100;300;10;2\n")
    res = runner.invoke(app, ["variants", str(tpl), str(tab), "--out", str(tmp_path / "o")])
    assert res.exit_code == 2, res.output
    assert f"{tab}:2: variant 1: empty cell in column a" in res.output
    assert f"{tab}:3: variant 2: empty cell in column n" in res.output
    assert f"{tab}: warning: column m2 used by no placeholder of tpl.yaml" in res.output
    assert sorted(p.name for p in (tmp_path / "o").glob("*.yaml")) == ["3.yaml"]
    # in Ukrainian (--lang): the lines and the count, the noun as its number takes it
    res = runner.invoke(app, ["variants", str(tpl), str(tab), "--out", str(tmp_path / "u"), "--lang", "uk"])
    assert res.exit_code == 2, res.output
    assert (f"{tab}:2: \u0432\u0430\u0440\u0456\u0430\u043d\u0442 1: \u043f\u043e\u0440\u043e\u0436\u043d\u044f "
            f"\u043a\u043b\u0456\u0442\u0438\u043d\u043a\u0430 \u0432 \u0441\u0442\u043e\u0432\u043f\u0446\u0456 a") in res.output
    assert "\u0437\u0430\u043f\u0438\u0441\u0430\u043d\u043e 1 \u0437 3" in res.output and "wrote" not in res.output


def test_a_tables_students_reach_their_tasks_and_forms(tmp_path):
    """A variants table's student and group columns (recognised, then warned as used by no
    placeholder) were dropped: the tasks had no `student`, the forms and form.csv an empty
    name. Now a template without its own `student` gets the row's, and `tmm form` writes it
    into the form, form.csv and key.csv; a template with its own keeps it (no warning either way
    for the columns it uses)."""
    tpl = _write(tmp_path, "tpl.yaml", TEMPLATE)
    tab = _write(tmp_path, "tab.csv", "variant;a, mm;b, mm;n;student;group\n"
                                      "1;100;300;10;Ann Lee;MT-21\n2;100;320;10;Bob Ray;\n3;100;340;10;;\n"
                                      "4;100;360;10;007;0301\n")
    res = runner.invoke(app, ["variants", str(tpl), str(tab), "--out", str(tmp_path / "v")])
    assert res.exit_code == 0 and "no placeholder" not in res.output, res.output
    tasks = {p.stem: yaml.safe_load(p.read_text(encoding="utf-8")) for p in (tmp_path / "v").glob("*.yaml")}
    assert tasks["1"]["student"] == {"name": "Ann Lee", "group": "MT-21"}
    assert tasks["2"]["student"] == {"name": "Bob Ray"} and "student" not in tasks["3"]
    assert tasks["4"]["student"] == {"name": "007", "group": "0301"}        # as written, not read as numbers
    assert list(tasks["1"])[:4] == ["schema", "title", "variant", "student"]
    res = runner.invoke(app, ["form", str(tmp_path / "v"), "-q", "positions", "--out", str(tmp_path / "f")])
    assert res.exit_code == 0, res.output
    assert 'student: {name: "Ann Lee", group: "MT-21"}' in (tmp_path / "f" / "1.form.yaml").read_text(encoding="utf-8")
    assert 'student: {name: "", group: ""}' in (tmp_path / "f" / "3.form.yaml").read_text(encoding="utf-8")
    for table in ("form.csv", "key.csv"):
        rows = _csv(tmp_path / "f" / table)
        assert [(r["student"], r["group"], r["variant"]) for r in rows] == [
            ("Ann Lee", "MT-21", "1"), ("Bob Ray", "", "2"), ("", "", "3"), ("007", "0301", "4")], table
    own = _write(tmp_path, "own.yaml", TEMPLATE + "student: {name: '{student}'}\n")
    res = runner.invoke(app, ["variants", str(own), str(tab), "--out", str(tmp_path / "w")])
    assert yaml.safe_load((tmp_path / "w" / "1.yaml").read_text(encoding="utf-8"))["student"] == {"name": "Ann Lee"}
    assert "column group used by no placeholder" in res.output, res.output


@pytest.mark.parametrize("table,what", [("variant,a\n1,2\n", "placeholder {b} names no column"),
                                        ("a,b,n\n1,2,3\n", "needs a `variant` column"),
                                        ("variant,a,b,n\n1,1,2,3\n01,1,2,3\n", "duplicate variant"),
                                        ("variant,a,b,n\n\n", "a header line but no rows")])
def test_variants_errors_before_anything_is_written(tmp_path, table, what):
    tpl = _write(tmp_path, "tpl.yaml", TEMPLATE)
    tab = _write(tmp_path, "tab.csv", table)
    res = runner.invoke(app, ["variants", str(tpl), str(tab), "--out", str(tmp_path / "o")])
    assert res.exit_code == 2 and what in res.output, res.output
    assert not (tmp_path / "o").exists()
    if "placeholder" in what:
        assert f"{tpl}:" in res.output and "mechanism.links.rod.length" in res.output


# ------------------------------------------------------------------ paths, form, check
def test_paths_lists_every_leaf(tmp_path):
    t = _write(tmp_path, "g.yaml", GEARS.format(v=3))
    res = runner.invoke(app, ["paths", str(t), "--format", "json"])
    assert res.exit_code == 0, res.output
    d = json.loads(res.output)
    rj = tmp_path / "r"
    assert runner.invoke(app, ["run", str(t), "--out", str(rj), "--format", "json", "-q"]).exit_code == 0
    results = json.loads((rj / "results.json").read_text())
    assert d["gears.aw"] == results["gears"]["aw"] and d["gears.r[1]"] == results["gears"]["r"][1]
    res = runner.invoke(app, ["paths", str(t), "--prefix", "gears.r["])
    lines = res.output.strip().splitlines()
    assert lines == [f"gears.r[0]\t{results['gears']['r'][0]!r}", f"gears.r[1]\t{results['gears']['r'][1]!r}"]
    # a prefix no path has (a typo) is an error with a suggestion, not an empty list and exit 0
    res = runner.invoke(app, ["paths", str(t), "--prefix", "gearz.a"])
    assert res.exit_code == 2 and "no result path of this task starts with 'gearz.a'" in res.output, res.output
    assert "did you mean 'gears.a'?" in res.output
    # a section the results do not have ('mechanism': its data are under 'structure'): the
    # sections they have, to choose from
    res = runner.invoke(app, ["paths", str(t), "--prefix", "mechanism"])
    secs = list(dict.fromkeys(k.split(".")[0].split("[")[0] for k in d))
    assert res.exit_code == 2 and "gears" in secs, res.output
    assert "did you mean one of: " + ", ".join(secs) + "?" in " ".join(res.output.split()), res.output


def test_form_and_key(tmp_path):
    t = _write(tmp_path, "g7.yaml", GEARS.format(v=7))
    res = runner.invoke(app, ["form", str(t), "--quantities", "gears.aw,planetary", "--out", str(tmp_path / "f")])
    assert res.exit_code == 2 and "preset 'planetary'" in res.output
    res = runner.invoke(app, ["form", str(t), "--quantities", "gears.ww", "--out", str(tmp_path / "f")])
    assert res.exit_code == 2 and "did you mean 'gears.aw'" in res.output
    res = runner.invoke(app, ["form", str(t), "--quantities", "gears,gears.aw", "--out", str(tmp_path / "f"),
                              "--lang", "ru"])
    assert res.exit_code == 0, res.output
    import yaml
    form = yaml.safe_load((tmp_path / "f" / "g7.form.yaml").read_text())
    key = yaml.safe_load((tmp_path / "f" / "g7.key.yaml").read_text())
    assert form["variant"] == 7 and form["student"] == {"name": "", "group": ""}
    assert set(form["answers"]) == set(key["answers"]) and all(v is None for v in form["answers"].values())
    assert "межосевое расстояние" in (tmp_path / "f" / "g7.form.yaml").read_text()
    kc = _csv(tmp_path / "f" / "key.csv")
    assert list(kc[0])[:3] == ["student", "group", "variant"] and float(kc[0]["gears.aw"]) == key["answers"]["gears.aw"]
    # the key graded against the task is all ok
    res = runner.invoke(app, ["check", str(t), "--answers", str(tmp_path / "f" / "g7.key.yaml")])
    assert res.exit_code == 0, res.output


def test_check_warns_of_an_answers_file_of_another_variant(tmp_path):
    """`tmm check TASK --answers FILE` grades one FILE as given, but a form of another variant
    (the student took the wrong task) is warned about: every answer would be outside without
    a reason shown. Variant 7's own file draws no warning."""
    t = _write(tmp_path, "g7.yaml", GEARS.format(v=7))
    for v, warned in ((8, True), (7, False)):
        ans = _write(tmp_path, f"a{v}.yaml", f"variant: {v}\nanswers:\n  gears.aw: 0.1\n")
        res = runner.invoke(app, ["check", str(t), "--answers", str(ans)])
        assert res.exit_code == 1, res.output
        assert (f"warning: {ans} holds answers for variant 8; the task is variant 7" in res.output) == warned, \
            res.output


def test_form_that_fails_keeps_the_earlier_set_files(tmp_path):
    """A rerun of `tmm form` whose quantities fit no task (exit 2) writes no form, so it
    leaves form.csv and key.csv of the earlier run as they were (the key is not emptied),
    and names the task file once, not a '<task>' placeholder."""
    t = _write(tmp_path, "g7.yaml", GEARS.format(v=7))
    out = tmp_path / "f"
    assert runner.invoke(app, ["form", str(t), "-q", "gears.aw", "-o", str(out)]).exit_code == 0
    before = {n: (out / n).read_text() for n in ("form.csv", "key.csv")}
    assert "gears.aw" in before["key.csv"]
    res = runner.invoke(app, ["form", str(t), "-q", "planetary", "-o", str(out)])
    assert res.exit_code == 2, res.output
    assert f"error: {t}: preset 'planetary'" in res.output and "<task>" not in res.output, res.output
    assert {n: (out / n).read_text() for n in before} == before


def test_form_in_ukrainian(tmp_path):
    """`tmm form --lang uk`: the comments in Ukrainian course terms, no Russian or English left."""
    import re
    t = _write(tmp_path, "g8.yaml", GEARS.format(v=8))
    res = runner.invoke(app, ["form", str(t), "--quantities", "gears", "--out", str(tmp_path / "f"), "--lang", "uk"])
    assert res.exit_code == 0, res.output
    text = (tmp_path / "f" / "g8.key.yaml").read_text()
    assert text.startswith("# Ключ відповідей") and "значення в одиницях СІ" in text
    assert "міжосьова відстань" in text and "радіус кола западин" in text and "кут зачеплення" in text
    # the units as the course writes them (issue 39): metres and degrees in the language's spelling
    assert "# a_w, м — міжосьова відстань" in text and "# α_w, ° — кут зачеплення" in text
    assert not re.search(r", (m|deg|m/s|N\*m|kg\*m\^2) —", text), text
    comments = " ".join(line.split("#", 1)[1] for line in text.splitlines() if "#" in line)
    assert not re.search(r"[ыэъё]", comments), comments        # letters Russian has and Ukrainian lacks
    assert not re.search(r"\b(radius|distance|angle|coefficient)\b", comments), comments
    res = runner.invoke(app, ["form", str(t), "--quantities", "gears", "--out", str(tmp_path / "f"), "--lang", "de"])
    assert res.exit_code == 2 and "en, ru or uk" in res.output


def test_check_answer_sources_and_messages(tmp_path):
    t = _write(tmp_path, "g.yaml", GEARS.format(v=4))
    d = tmp_path / "ans"
    key = tmp_path / "k"
    assert runner.invoke(app, ["form", str(t), "-q", "gears.aw,gears.alpha_w", "--out", str(key)]).exit_code == 0
    import yaml
    ref = yaml.safe_load((key / "g.key.yaml").read_text())["answers"]
    _write(d, "ivanov.yaml", f"variant: 4\nstudent: {{name: Ivanov, group: MM-1}}\nanswers:\n"
                             f"  gears.aw: \"{ref['gears.aw'] * 1000} mm\"\n  gears.alpha_w: {-ref['gears.alpha_w']}\n")
    _write(d, "other.yaml", "variant: 5\nanswers: {gears.aw: 1}\n")
    res = runner.invoke(app, ["check", str(t), "--answers", str(d), "--out", str(tmp_path / "c")])
    assert res.exit_code == 1, res.output
    rows = _csv(tmp_path / "c" / "check.csv")
    assert list(rows[0]) == ["student", "group", "variant", "path", "answer", "reference", "error", "tolerance",
                             "status", "note", "answers_file"]
    assert [(r["student"], r["path"], r["status"]) for r in rows] == [("Ivanov", "gears.aw", "ok"),
                                                                     ("Ivanov", "gears.alpha_w", "sign")]
    # CSV: one row per student, decimal commas; another variant's row is not this task's
    tab = _write(tmp_path, "a.csv", f"student;group;variant;gears.aw\nPetrov;MM-2;4;{str(ref['gears.aw']).replace('.', ',')}\n"
                                    "Sidorov;MM-2;9;1\n")
    res = runner.invoke(app, ["check", str(t), "--answers", str(tab)])
    assert res.exit_code == 0 and "Petrov" in res.output and "Sidorov" not in res.output, res.output
    # ... and said to be left for its own task, not silently
    assert "note: 1 answer set(s) of other variants (9) left for their own tasks" in res.output
    # a non-YAML file: an invalid answers file, where YAML stops reading it (as for a task file),
    # its content never echoed
    junk = _write(tmp_path, "junk.txt", "SECRET-FIRST-LINE: [unclosed\n\x07binary")
    res = runner.invoke(app, ["check", str(t), "--answers", str(junk)])
    assert res.exit_code == 2 and "SECRET" not in res.output, res.output
    assert res.output.startswith("error: invalid answers file\n") and "junk.txt:2:1: YAML error" in res.output
    # a YAML file without answers: not an answers file
    other = _write(tmp_path, "other.txt", "SECRET: 1\n")
    res = runner.invoke(app, ["check", str(t), "--answers", str(other)])
    assert res.exit_code == 2 and "not an answers file" in res.output and "SECRET" not in res.output
    # a non-numeric answer: that answer's `invalid` with the reason, the set graded (exit 1, not 2)
    bad = _write(tmp_path, "bad.yaml", "answers:\n  gears.aw: twelve\n")
    res = runner.invoke(app, ["check", str(t), "--answers", str(bad)])
    assert res.exit_code == 1 and "invalid answer: 'twelve' is not a number" in res.output, res.output
    # an unknown path: exit 1 with "did you mean"
    up = _write(tmp_path, "up.yaml", "answers:\n  gears.a_w: 1\n")
    res = runner.invoke(app, ["check", str(t), "--answers", str(up), "--out", str(tmp_path / "u")])
    assert res.exit_code == 1
    r = _csv(tmp_path / "u" / "check.csv")[0]
    assert r["status"] == "unknown_path" and "did you mean 'gears.aw'" in r["note"]
    # --tolerance FILE with an absolute tolerance on the angle
    tol = _write(tmp_path, "tol.yaml", "gears.alpha_w: {abs: 0.01}\n")
    near = _write(tmp_path, "near.yaml", f"answers:\n  gears.alpha_w: {ref['gears.alpha_w'] + 0.05}\n")
    assert runner.invoke(app, ["check", str(t), "--answers", str(near)]).exit_code == 0
    assert runner.invoke(app, ["check", str(t), "--answers", str(near), "--tolerance", str(tol)]).exit_code == 1


def test_positions_out_of_range_is_invalid_in_every_command(tmp_path):
    text = (ROOT / "tasks" / "press_offset_slider_crank.yaml").read_text().replace("positions: all",
                                                                                   "positions: [0, 99]")
    t = _write(tmp_path / "g", "p.yaml", text + "answers: {structure.W: 1}\n")
    for cmd in (["validate", str(t)], ["run", str(t), "--format", "json", "--out", str(tmp_path / "r")],
                ["check", str(t)]):
        res = runner.invoke(app, cmd)
        assert res.exit_code == 2, (cmd, res.output)
        assert "kinetostatics.positions" in res.output and "position 99 does not exist" in res.output
    res = runner.invoke(app, ["batch", str(tmp_path / "g"), "--out", str(tmp_path / "b")])
    assert res.exit_code == 2
    assert _csv(tmp_path / "b" / "summary.csv")[0]["status"] == "invalid"


# ------------------------------------------------------------------ batch robustness
def test_batch_folders_are_unique_and_inside_out(tmp_path):
    src = tmp_path / "src"
    for name in ("...yaml", "v1.yaml", "v1.yml", "a/v2.yaml", "b/v2.yaml", "summary.csv.yaml"):
        _write(src, name, GEARS.format(v=1))
    out = tmp_path / "out"
    res = runner.invoke(app, ["batch", str(src) + "/**/*.y*ml", "--out", str(out)])
    assert res.exit_code == 0, res.output
    rows = _csv(out / "summary.csv")
    assert len(rows) == 6 and all(r["status"] == "ok" for r in rows)
    results = sorted(p.parent.name for p in out.rglob("results.json"))
    assert len(results) == 6 and len(set(results)) == 6
    assert all(p.resolve().is_relative_to(out.resolve()) for p in out.rglob("*"))
    assert not (tmp_path / "results.json").exists() and (out / "summary.csv").is_file()
    assert "summary.csv" not in results


def test_batch_rows_for_what_is_not_a_task_file(tmp_path):
    src = tmp_path / "src"
    _write(src, "ok.yaml", GEARS.format(v=1))
    (src / "dir.yaml").mkdir()
    os.mkfifo(src / "fifo.yaml")
    os.symlink(src / "nowhere", src / "dangling.yaml")
    res = runner.invoke(app, ["batch", str(src), "--out", str(tmp_path / "o")])
    rows = {Path(r["file"]).name: r for r in _csv(tmp_path / "o" / "summary.csv")}
    assert rows["ok.yaml"]["status"] == "ok"
    assert "directory" in rows["dir.yaml"]["message"] and "FIFO" in rows["fifo.yaml"]["message"]
    assert "dangling" in rows["dangling.yaml"]["message"]
    assert {rows[k]["status"] for k in ("dir.yaml", "fifo.yaml", "dangling.yaml")} == {"invalid"}
    assert rows["dir.yaml"]["message"] == f"{src / 'dir.yaml'}: a directory, not a task file"
    assert res.exit_code == 2
    # summary.html in Russian: the reasons translated too
    res = runner.invoke(app, ["batch", str(src), "--out", str(tmp_path / "r"), "--lang", "ru"])
    html = (tmp_path / "r" / "summary.html").read_text(encoding="utf-8")
    for ru in ("это папка, а не файл задания", "это именованный канал, а не файл задания",
               "символическая ссылка ведёт в никуда"):
        assert ru in html
    assert "not a task file" not in html and "symbolic link" not in html


def test_batch_removes_only_its_own_stale_folders(tmp_path):
    src = tmp_path / "src"
    for v in (1, 2):
        _write(src, f"v{v}.yaml", GEARS.format(v=v))
    out = tmp_path / "o"
    assert runner.invoke(app, ["batch", str(src), "--out", str(out)]).exit_code == 0
    (out / "mine").mkdir()
    (out / "mine" / "notes.txt").write_text("keep")
    (out / "v1" / "notes.txt").write_text("keep too")
    (src / "v2.yaml").unlink()
    (src / "v1.yaml").unlink()
    _write(src, "v3.yaml", GEARS.format(v=3))
    assert runner.invoke(app, ["batch", str(src), "--out", str(out)]).exit_code == 0
    assert not (out / "v2").exists()                                   # gone with its variant
    assert (out / "v1" / "notes.txt").read_text() == "keep too"        # not written by tmm: kept
    assert not (out / "v1" / "results.json").exists()
    assert (out / "mine" / "notes.txt").exists() and (out / "v3" / "results.json").exists()


@pytest.fixture(params=["fork", "spawn"])
def start_method(request, monkeypatch):
    """The batch's workers forked (Linux) and spawned (Windows, macOS; TMM_START_METHOD=spawn)."""
    if os.environ.get("TMM_SPAWN_SUITE"):
        pytest.skip("run with both start methods in the suite itself (tests/test_spawn_suite.py)")
    monkeypatch.setenv("TMM_START_METHOD", request.param)
    return request.param


def test_batch_survives_dead_slow_and_greedy_workers(tmp_path, monkeypatch, start_method):
    import batch_workers
    import tmm_cli.batch as b
    monkeypatch.setattr(b, "work", batch_workers.work)           # the workers run it, forked or spawned
    src = tmp_path / "src"
    for name in ("killed", "slow", "greedy", "good1", "good2"):
        _write(src, f"{name}.yaml", GEARS.format(v=1))
    vm = int(open("/proc/self/status").read().split("VmSize:")[1].split()[0]) // 1024
    monkeypatch.setenv("TMM_TEST_SLEPT", str(tmp_path / "slept.log"))
    res = runner.invoke(app, ["batch", str(src), "--out", str(tmp_path / "o"), "--jobs", "2", "--timeout", "1.5",
                              "--memory", str(vm + 1500)])
    assert not (tmp_path / "slept.log").exists()        # the slow variant ended, not waited for (its 60 s)
    rows = {Path(r["file"]).stem: r for r in _csv(tmp_path / "o" / "summary.csv")}
    assert rows["good1"]["status"] == rows["good2"]["status"] == "ok"
    assert rows["killed"]["status"] == "failed" and "SIGKILL" in rows["killed"]["message"]
    assert rows["slow"]["status"] == "failed" and "time limit" in rows["slow"]["message"]
    assert rows["greedy"]["status"] == "failed" and "memory" in rows["greedy"]["message"]
    assert res.exit_code == 3 and (tmp_path / "o" / "summary.html").exists()
    assert "BrokenProcessPool" not in res.output


HOSTILE = "<script>alert(1)</script><img src=x onerror=alert(2)>"


def test_summary_html_escapes_every_user_string_and_csv_neutralised(tmp_path):
    src = tmp_path / "src"
    _write(src, "h.yaml", f"schema: tmm/1\ntitle: '=HYPERLINK(\"http://x\")'\nvariant: '{HOSTILE}'\n"
                          f"student: {{name: '@SUM(A1) {HOSTILE}', group: '{HOSTILE}'}}\n"
                          "gears: {m: 4 mm, z: [14, 30]}\nanswers: {gears.aw: 1, 'gears.r[0]': 0.028}\n")
    res = runner.invoke(app, ["batch", str(src), "--out", str(tmp_path / "o"), "--lang", "ru"])
    assert res.exit_code == 1, res.output
    html = (tmp_path / "o" / "summary.html").read_text()
    assert "<script" not in html and "<img" not in html and "&lt;script&gt;" in html
    assert "вне допуска" in html                                        # in the report language
    for f in [tmp_path / "o" / "summary.csv", tmp_path / "o" / "check.csv"] + list((tmp_path / "o").glob("*/*.html")):
        text = f.read_text()
        assert "<script" not in text or f.suffix == ".csv"
    rows = _csv(tmp_path / "o" / "summary.csv")
    assert rows[0]["student"].startswith("'@SUM") and rows[0]["score"] == "0.5"
    for r in _csv(tmp_path / "o" / "check.csv"):
        assert r["student"].startswith("'@")


# ------------------------------------------------------------------ the whole loop (README)
def test_instructor_loop_end_to_end(tmp_path):
    """template + table -> tasks -> forms -> filled answers -> graded summary and feedback,
    with the bad inputs: a malformed row, an answers file for an unknown variant, a
    non-numeric answer."""
    tab = tmp_path / "table.csv"
    lines = (EX / "press_variants.csv").read_text(encoding="utf-8-sig").splitlines()
    tab.write_text("\n".join(lines[:4] + ["04;90;300;20;3;5;22;60;12;0,05;extra"]) + "\n", encoding="utf-8")
    res = runner.invoke(app, ["variants", str(EX / "press_template.yaml"), str(tab), "--out", str(tmp_path / "tasks")])
    assert res.exit_code == 2 and f"{tab}:5: variant 04: malformed row" in res.output
    res = runner.invoke(app, ["form", str(tmp_path / "tasks"), "-q", "positions,flywheel.J,kinetostatics",
                              "--out", str(tmp_path / "forms")])
    assert res.exit_code == 0, res.output
    import yaml
    ans = tmp_path / "answers"
    ans.mkdir()
    for v in ("01", "02", "03"):
        key = yaml.safe_load((tmp_path / "forms" / f"{v}.key.yaml").read_text())
        key["student"] = {"name": f"Student {v}", "group": "MM-21"}
        if v == "02":
            key["answers"]["flywheel.J"] *= 1.3                   # a wrong flywheel
        if v == "03":
            key["answers"]["positions.K"] = "a lot"               # non-numeric
        (ans / f"s{v}.yaml").write_text(yaml.safe_dump(key))
    (ans / "ghost.yaml").write_text("variant: 77\nanswers: {flywheel.J: 1}\n")
    res = runner.invoke(app, ["batch", str(tmp_path / "tasks"), "--out", str(tmp_path / "graded"),
                              "--answers", str(ans), "--format", "json,html", "--lang", "ru"])
    assert res.exit_code == 2, res.output
    rows = _csv(tmp_path / "graded" / "summary.csv")
    by = {r["student"] or r["file"]: r for r in rows}
    assert by["Student 01"]["status"] == "ok" and by["Student 01"]["score"] == "1.0"
    assert by["Student 02"]["status"] == "outside" and by["Student 02"]["flywheel.J"] == "outside"
    # a non-numeric answer: that answer's `invalid`, the student's other answers graded
    assert by["Student 03"]["status"] == "outside" and by["Student 03"]["positions.K"] == "invalid"
    assert "positions.K" in by["Student 03"]["message"] and by["Student 03"]["flywheel.J"] == "ok"
    ghost = [r for r in rows if r["variant"] == "77"][0]
    assert ghost["status"] == "invalid" and "no task of this variant" in ghost["message"]
    html = (tmp_path / "graded" / "summary.html").read_text(encoding="utf-8")
    assert "ответы на вариант 77: задания этого варианта нет" in html        # the row texts in Russian
    assert "вне допуска: flywheel.J" in html and "no task of this variant" not in html
    assert "outside: flywheel.J" in by["Student 02"]["message"]             # summary.csv stays English
    fb = list((tmp_path / "graded" / "02").glob("feedback-*.html"))
    assert fb and "маховик" in fb[0].read_text()                  # the step a wrong J depends on
    assert (tmp_path / "graded" / "01" / "report.html").exists()


def test_write_failure_of_a_variant_is_named_not_an_internal_error():
    from tmm_cli.errors import StageError, TaskError
    from tmm_cli.orchestrate import classify
    code, status, msg = classify(PermissionError(13, "Permission denied", "/o/v1/results.json"))
    assert (code, status) == (3, "failed") and msg == ("stage 'output' failed: cannot write /o/v1/results.json: "
                                                       "Permission denied")
    assert "internal error" not in msg
    assert classify(TaskError("bad", file="t.yaml"))[:2] == (2, "invalid")
    assert classify(StageError("kinematics", "x"))[:2] == (3, "failed")


def test_memory_limit_counts_what_a_variant_adds(tmp_path):
    """A forked worker starts with the parent's address space: a parent that has mapped more
    than --memory (a long test run, a notebook) must not fail every variant."""
    import mmap
    big = mmap.mmap(-1, 5 * 1024 ** 3)          # 5 GB mapped (not touched) in the parent
    try:
        src = tmp_path / "tasks"
        src.mkdir()
        (src / "v1.yaml").write_text((ROOT / "tasks" / "gears_zero.yaml").read_text(encoding="utf-8"),
                                     encoding="utf-8")
        res = runner.invoke(app, ["batch", str(src), "--out", str(tmp_path / "o"), "--format", "json",
                                  "--memory", "1024"])
        assert res.exit_code == 0, res.output
        assert ",ok," in (tmp_path / "o" / "summary.csv").read_text(encoding="utf-8")
    finally:
        big.close()


def _pid_logging_work(monkeypatch, log: Path):
    """Replace the batch's `work` by tests/batch_workers.py's (the workers run it, forked or
    spawned), which logs "<stem> <pid>" to ``log`` and misbehaves as the stem says."""
    import batch_workers
    import tmm_cli.batch as b
    monkeypatch.setattr(b, "work", batch_workers.work)
    monkeypatch.setenv("TMM_TEST_PID_LOG", str(log))
    return lambda: batch_workers.pid_log(log)


def test_a_worker_reused_across_variants_writes_what_a_fresh_one_writes(tmp_path, monkeypatch):
    """One worker runs every variant in turn (--jobs 1): each results.json is byte-identical
    to the one the variant writes alone in a batch of its own (a fresh worker)."""
    names = ["forging_sixbar", "gears_zero", "cam_knife", "planetary_A", "engine_slider_crank",
             "synthesis_slider_crank"]
    src = tmp_path / "src"
    for k, name in enumerate(names):
        _write(src, f"{k}_{name}.yaml", (ROOT / "tasks" / f"{name}.yaml").read_text(encoding="utf-8"))
    _write(src, "9_gears_again.yaml", GEARS.format(v=3))
    pids = _pid_logging_work(monkeypatch, tmp_path / "pids.log")
    res = runner.invoke(app, ["batch", str(src), "--out", str(tmp_path / "o"), "--jobs", "1", "--format", "json"])
    assert res.exit_code == 0, res.output
    assert len(set(pids().values())) == 1                     # all in one worker
    for f in sorted(src.glob("*.yaml")):                       # the same file alone in a batch
        alone = tmp_path / "alone" / f.stem
        r = runner.invoke(app, ["batch", str(f), "--out", str(alone), "--format", "json"])
        assert r.exit_code == 0, r.output
        assert (tmp_path / "o" / f.stem / "results.json").read_bytes() == \
            (alone / f.stem / "results.json").read_bytes(), f.stem
    assert [r["status"] for r in _csv(tmp_path / "o" / "summary.csv")] == ["ok"] * (len(names) + 1)


def test_a_dying_slow_or_greedy_variant_in_a_long_run_fails_alone(tmp_path, monkeypatch, start_method):
    """In a long run on one worker, a variant that kills its worker, overruns --timeout or
    --memory is that variant's failed row; the next variant runs in a fresh worker, and
    the variants before and after write what they write without it."""
    order = ["good", "good", "killed", "good", "slow", "good", "greedy", "good", "good"]
    src = tmp_path / "src"
    for k, kind in enumerate(order):
        _write(src, f"v{k}_{kind}.yaml", GEARS.format(v=k + 1))
    pids = _pid_logging_work(monkeypatch, tmp_path / "pids.log")
    monkeypatch.setenv("TMM_TEST_SLEPT", str(tmp_path / "slept.log"))
    res = runner.invoke(app, ["batch", str(src), "--out", str(tmp_path / "o"), "--jobs", "1", "--timeout", "1.5",
                              "--memory", "1024", "--format", "json"])
    assert not (tmp_path / "slept.log").exists()        # the slow variant ended, not waited for (its 60 s)
    assert res.exit_code == 3, res.output
    rows = {Path(r["file"]).stem: r for r in _csv(tmp_path / "o" / "summary.csv")}
    assert [Path(r["file"]).stem for r in _csv(tmp_path / "o" / "summary.csv")] == sorted(rows)
    assert rows["v2_killed"]["status"] == "failed" and "SIGKILL" in rows["v2_killed"]["message"]
    assert rows["v4_slow"]["status"] == "failed" and "time limit" in rows["v4_slow"]["message"]
    assert rows["v6_greedy"]["status"] == "failed" and "memory" in rows["v6_greedy"]["message"]
    good = [s for s in rows if s.endswith("good")]
    assert all(rows[s]["status"] == "ok" for s in good)
    p = pids()
    assert p["v0_good"] == p["v1_good"] == p["v2_killed"]           # one worker until it died
    assert p["v3_good"] not in (p["v2_killed"], p["v0_good"]) and p["v3_good"] == p["v4_slow"]
    assert p["v5_good"] != p["v4_slow"] and p["v5_good"] == p["v6_greedy"]
    assert p["v7_good"] != p["v6_greedy"] and p["v7_good"] == p["v8_good"]
    monkeypatch.undo()
    for s in good:                                                   # nothing of one variant in another
        alone = tmp_path / "alone" / s
        assert runner.invoke(app, ["batch", str(src / f"{s}.yaml"), "--out", str(alone), "--format", "json"]).exit_code == 0
        assert (tmp_path / "o" / s / "results.json").read_bytes() == (alone / s / "results.json").read_bytes()
    for f in ("summary.html", "check.csv", ".tmm-batch.json"):
        assert (tmp_path / "o" / f).exists()


def test_a_spawned_workers_start_is_not_the_variants_time(tmp_path, monkeypatch):
    """A spawned worker (Windows, macOS) first starts an interpreter and imports the modules
    (a second or more): --timeout counts from when it begins the variant, not from when
    the batch handed it over."""
    import batch_workers
    import tmm_cli.batch as b
    monkeypatch.setenv("TMM_START_METHOD", "spawn")
    monkeypatch.setattr(b, "work", batch_workers.quick)             # the variant itself: no time at all
    src = tmp_path / "src"
    _write(src, "v1.yaml", (ROOT / "tasks" / "engine_slider_crank.yaml").read_text(encoding="utf-8"))
    res = runner.invoke(app, ["batch", str(src), "--out", str(tmp_path / "o"), "--format", "html",
                              "--timeout", "0.5"])
    assert res.exit_code == 0, res.output
    assert _csv(tmp_path / "o" / "summary.csv")[0]["status"] == "ok"


def test_memory_watched_from_outside_where_a_worker_cannot_limit_itself(tmp_path, monkeypatch, start_method):
    """Where RLIMIT_AS is not available (Windows; macOS does not enforce it) the batch reads
    each worker's memory (psutil) and ends one whose variant added more than --memory: that
    variant's failed row, the others computed."""
    import batch_workers
    import tmm_cli.batch as b
    monkeypatch.setattr(b, "_rlimit_available", lambda: False)
    monkeypatch.setattr(b, "work", batch_workers.work)
    src = tmp_path / "src"
    for name in ("a_good", "b_hog", "c_good"):
        _write(src, f"{name}.yaml", GEARS.format(v=1))
    monkeypatch.setenv("TMM_TEST_SLEPT", str(tmp_path / "slept.log"))
    res = runner.invoke(app, ["batch", str(src), "--out", str(tmp_path / "o"), "--jobs", "1", "--format", "json",
                              "--memory", "1024"])
    assert not (tmp_path / "slept.log").exists()        # the hog ended, not waited for (its 30 s)
    rows = {Path(r["file"]).stem: r for r in _csv(tmp_path / "o" / "summary.csv")}
    assert rows["b_hog"]["status"] == "failed" and "--memory limit of 1024 MB" in rows["b_hog"]["message"]
    assert rows["a_good"]["status"] == rows["c_good"]["status"] == "ok"
    assert res.exit_code == 3


def test_watched_memory_counts_from_the_variants_start_not_the_workers(tmp_path, monkeypatch):
    """A spawned worker imports numpy, scipy, pydantic... (~150 MB of address space) before
    its first variant: a watched --memory counts what the variant adds from when it begins
    it, so a small limit does not fail every variant of a fresh worker."""
    import tmm_cli.batch as b
    monkeypatch.setenv("TMM_START_METHOD", "spawn")
    monkeypatch.setattr(b, "_rlimit_available", lambda: False)
    src = tmp_path / "src"
    for v in (1, 2, 3):
        _write(src, f"v{v}.yaml", (ROOT / "tasks" / "engine_slider_crank.yaml").read_text(encoding="utf-8"))
    res = runner.invoke(app, ["batch", str(src), "--out", str(tmp_path / "o"), "--jobs", "2", "--format", "json",
                              "--memory", "100"])
    assert res.exit_code == 0, res.output
    assert [r["status"] for r in _csv(tmp_path / "o" / "summary.csv")] == ["ok"] * 3


def test_memory_limit_not_available_is_said_not_an_error(tmp_path, monkeypatch):
    """No RLIMIT_AS and no psutil: the batch says --memory is not enforced and runs."""
    import tmm_cli.batch as b
    monkeypatch.setattr(b, "_rlimit_available", lambda: False)
    monkeypatch.setattr(b, "_memory_watch", lambda: False)
    src = tmp_path / "src"
    _write(src, "v1.yaml", GEARS.format(v=1))
    res = runner.invoke(app, ["batch", str(src), "--out", str(tmp_path / "o"), "--format", "json",
                              "--memory", "512"])
    assert res.exit_code == 0, res.output
    assert "--memory 512 is not enforced here" in res.output
    assert _csv(tmp_path / "o" / "summary.csv")[0]["status"] == "ok"


def test_a_worker_is_replaced_after_max_variants_and_after_growing(tmp_path, monkeypatch):
    """The pool's policy: a worker runs at most MAX_VARIANTS variants, and one whose address
    space has grown by RECYCLE_GROWTH (here a variant that leaks 64 MB) is replaced."""
    import tmm_cli.batch as b
    monkeypatch.setattr(b, "MAX_VARIANTS", 3)
    monkeypatch.setattr(b, "RECYCLE_GROWTH", 32 * 1024 ** 2)
    order = ["good", "good", "good", "good", "leaky", "good", "good"]
    src = tmp_path / "src"
    for k, kind in enumerate(order):
        _write(src, f"v{k}_{kind}.yaml", GEARS.format(v=k + 1))
    pids = _pid_logging_work(monkeypatch, tmp_path / "pids.log")
    res = runner.invoke(app, ["batch", str(src), "--out", str(tmp_path / "o"), "--jobs", "1", "--format", "json"])
    assert res.exit_code == 0, res.output
    assert [r["status"] for r in _csv(tmp_path / "o" / "summary.csv")] == ["ok"] * len(order)
    p = [pids()[f"v{k}_{kind}"] for k, kind in enumerate(order)]
    assert p[0] == p[1] == p[2] != p[3]                              # 3 variants, then a fresh worker
    assert p[3] == p[4] != p[5]                                      # the leak ends its worker
    assert p[5] == p[6]


def test_batch_stage_failure_in_the_summary_language(tmp_path):
    """A variant whose stage fails: summary.csv keeps the English text of stderr, summary.html
    shows the same failure in the batch's language."""
    src = tmp_path / "src"
    _write(src, "p.yaml", "schema: tmm/1\ntitle: p\nplanetary: {scheme: A, ratio: 1.2, satellites: 3, m: 2 mm}\n")
    res = runner.invoke(app, ["batch", str(src), "--out", str(tmp_path / "o"), "--lang", "uk", "--format", "json"])
    assert res.exit_code == 3, res.output
    row = _csv(tmp_path / "o" / "summary.csv")[0]
    assert row["status"] == "failed"
    assert row["message"].startswith("stage 'planetary' failed: no tooth numbers for scheme A give i_1H = 1.2")
    html = (tmp_path / "o" / "summary.html").read_text(encoding="utf-8")
    assert "етап «синтез планетарного механізму» не виконано: жоден набір чисел зубів схеми A не дає i_1H = 1,2" in html
    assert "no tooth numbers" not in html


SLIDER = """schema: tmm/1
mechanism:
  ground: {O: [0, 0]}
  links:
    crank: {points: [O, A], length: 0.08}
    rod:   {points: [A, B], length: 0.35}
    ram:   {slider: B, guide: {through: [0.025, 0], angle: 90}}
  assembly: {B: [0.025, 0.34]}
drive: {link: crank, speed: 90 rpm, direction: cw}
positions: {count: 12, zero: extreme, output: ram}
loads:
  forces:
    - {on: ram, kind: resistance, stroke: working, magnitude: 1 kN}
"""
# a student's mistakes: (file, what is changed, the Russian and the Ukrainian words shown)
BROKEN = [
    ("misspelt", ("length: 0.08", "lenght: 0.08"), "неизвестный ключ «lenght»; возможно, имелось в виду «length»?",
     "невідомий ключ «lenght»; можливо, малося на увазі «length»?"),
    ("word", ("length: 0.35", "length: long"), "ожидается длина (m, mm, cm...), задано: 'long'",
     "очікується довжина (m, mm, cm...), задано: 'long'"),
    ("negative", ("length: 0.08", "length: -0.08"), "длина звена `length` должна быть положительной",
     "довжина ланки `length` має бути додатною"),
    ("unit", ("90 rpm", "90 rmp"), "неизвестная единица измерения «rmp» в «90 rmp»; ожидается угловая скорость",
     "невідома одиниця вимірювання «rmp» у «90 rmp»; очікується кутова швидкість"),
    ("syntax", ("{O: [0, 0]}", "{O: [0, 0}"), "синтаксическая ошибка YAML", "синтаксична помилка YAML"),
    ("indent", ("  links:", "   links:"), "проверьте отступы в строках", "перевірте відступи в рядках"),
    ("assembly", ("assembly: {B:", "assembly: {Q:"), "указание сборки для неизвестной точки «Q»",
     "вказівка складання для невідомої точки «Q»"),
    ("loads", ("on: ram", "on: rem"), "звена с именем «rem» нет; возможно, имелось в виду «ram»?",
     "ланки з ім'ям «rem» немає; можливо, малося на увазі «ram»?"),
    ("literal", ("direction: cw", "direction: clockwise"), "допустимые значения: 'ccw' или 'cw'; задано 'clockwise'",
     "допустимі значення: 'ccw' або 'cw'; задано 'clockwise'"),
    ("count", ("count: 12", "count: 1"), "значение должно быть не меньше 2", "значення має бути не меншим за 2"),
    ("missing", ("{link: crank, ", "{"), "обязательное поле не задано", "обов'язкове поле не задане"),
]


@pytest.mark.parametrize("lang", ["ru", "uk"])
def test_batch_invalid_variants_in_the_summary_language(tmp_path, lang):
    """Broken variants: summary.csv (and stderr) keep the English lines of `tmm run`;
    summary.html shows each with its file, line and field, in the batch's language."""
    from html import unescape

    from tmm_cli.errors import TaskError
    from tmm_cli.orchestrate import prepare
    src = tmp_path / "src"
    english = {}
    for name, (a, b), _, _ in BROKEN:
        assert a in SLIDER
        f = _write(src, f"{name}.yaml", SLIDER.replace(a, b, 1))
        with pytest.raises(TaskError) as info:
            prepare(f)
        english[name] = info.value.render()
    res = runner.invoke(app, ["batch", str(src), "--out", str(tmp_path / "o"), "--lang", lang])
    assert res.exit_code == 2, res.output
    rows = {Path(r["file"]).stem: r for r in _csv(tmp_path / "o" / "summary.csv")}
    html = unescape((tmp_path / "o" / "summary.html").read_text(encoding="utf-8"))
    for name, _, ru, uk in BROKEN:
        assert rows[name]["status"] == "invalid" and rows[name]["message"] == english[name]
        first = english[name].splitlines()[0]
        where = re.match(r"^(.*?\.yaml:\d+(?::\d+)?): ", first).group(1)
        assert where in html, name                                   # file:line:col as in English
        if ": field '" in first:
            field = first.split(": field '")[1].split("'")[0]
            assert f"{where}: поле «{field}»: " in html, name
        assert (ru if lang == "ru" else uk) in html, (name, lang)
        assert first not in html, name                               # no English line left


def test_batch_resends_a_variant_whose_idle_worker_was_killed(tmp_path, monkeypatch):
    """A worker killed from outside while idle, just as a variant is sent to it, never began
    that variant: a fresh worker runs it (once). A variant that kills its own worker is not
    run again: its row says the worker died."""
    import signal

    import tmm_cli.batch as b
    real_send = b._Slot.send
    _pid_logging_work(monkeypatch, tmp_path / "runs.txt")
    sent = []

    def send(self, i):
        sent.append(i)
        if len(sent) == 2:                      # the second variant: its worker waits idle for it
            os.kill(self.proc.pid, signal.SIGSTOP)   # stopped: alive, but it will never read the index
            ok = real_send(self, i)
            os.kill(self.proc.pid, signal.SIGKILL)
            return ok
        return real_send(self, i)

    monkeypatch.setattr(b._Slot, "send", send)
    src = tmp_path / "src"
    for name in ("a1", "a2", "crash", "a4"):
        _write(src, f"{name}.yaml", GEARS.format(v=1))
    res = runner.invoke(app, ["batch", str(src), "--out", str(tmp_path / "o"), "--jobs", "1"])
    rows = {Path(r["file"]).stem: r for r in _csv(tmp_path / "o" / "summary.csv")}
    assert rows["a1"]["status"] == rows["a2"]["status"] == rows["a4"]["status"] == "ok", rows
    assert rows["crash"]["status"] == "failed" and "SIGKILL" in rows["crash"]["message"]
    assert sorted(ln.split()[0] for ln in (tmp_path / "runs.txt").read_text().splitlines()) == \
        ["a1", "a2", "a4", "crash"]             # each run once
    assert sent == [0, 1, 1, 2, 3]              # a2 sent twice: to the killed worker, then a fresh one
    assert res.exit_code == 3


def test_batch_invalid_answers_in_the_summary_language(tmp_path):
    """An answers file that is not one, and an answer that is not a number: summary.csv
    keeps the English; summary.html (ru) shows both in Russian, with the file and field."""
    from html import unescape
    src, ans = tmp_path / "src", tmp_path / "ans"
    _write(src, "v1.yaml", GEARS.format(v=1))
    _write(ans, "s1.yaml", "student: {name: Ivanov}\nvariant: 1\nanswers: {gears.aw: twelve}\n")
    _write(ans, "s2.yaml", "student: {name: Petrov}\nvariant: 1\nanswer: {gears.aw: 0.09}\n")
    res = runner.invoke(app, ["batch", str(src), "--out", str(tmp_path / "o"), "--answers", str(ans), "--lang", "ru"])
    assert res.exit_code == 2, res.output
    rows = {r["student"] or Path(r["file"]).name: r for r in _csv(tmp_path / "o" / "summary.csv")}
    # the answer that is not a number is that answer's `invalid`; the set is graded, not invalid
    assert rows["Ivanov"]["status"] == "outside" and rows["Ivanov"]["gears.aw"] == "invalid"
    assert rows["Ivanov"]["invalid"] == "1" and rows["Ivanov"]["answers"] == "1"
    note = [r for r in _csv(tmp_path / "o" / "check.csv") if r["student"] == "Ivanov"][0]
    assert note["answer"] == "twelve" and note["note"] == "invalid answer: 'twelve' is not a number"
    assert rows["s2.yaml"]["message"].endswith("s2.yaml: not an answers file (a YAML file with an `answers:` "
                                               "mapping of result paths to values)")
    html = unescape((tmp_path / "o" / "summary.html").read_text(encoding="utf-8"))
    assert f"{ans / 's2.yaml'}: это не файл ответов" in html
    assert "not an answers file" not in html
    fb = unescape(next((tmp_path / "o" / "v1").glob("feedback-Ivanov*.html")).read_text(encoding="utf-8"))
    assert "неверный ответ: «twelve» — не число" in fb


def test_feedback_page_names_a_misspelt_path_in_its_language(tmp_path):
    """A student's misspelt result path: check.csv's note keeps the English "did you mean";
    the Russian feedback page gives the hint in Russian."""
    from types import SimpleNamespace

    from tmm_cli.check import grade
    from tmm_cli.feedback import feedback_html
    res = {"flywheel": {"J": 1.0, "delta": 0.1}}
    rows = grade(res, AnswerSet(source="s.yaml", answers={"flywheel.JJ": 1.0, "flywheel.J": 1.0}), {})
    assert str(rows[0]["note"]).endswith("; did you mean 'flywheel.J'?")
    html = feedback_html(SimpleNamespace(title="t", name="t"), {"rows": rows, "student": "S"}, "ru")
    assert "возможно, имелось в виду «flywheel.J»?" in html.replace("&laquo;", "«").replace("&raquo;", "»")
    assert "did you mean" not in html


def test_unknown_path_note_quotes_the_path_and_the_key_whole(tmp_path):
    """check.csv's note on a misspelt path: the path bare, the key in whole quotes, the
    hint after; the same reason in Russian and Ukrainian (no English inside)."""
    from tmm_cli.check import load_answers_csv, load_answers_file
    from tmm_cli.errors import TaskError
    from tmm_cli.messages import localize
    res = {"flywheel": {"J": 1.0, "delta": 0.1}, "kinematics": [{"index": 0, "phi": 0.0}]}
    rows = grade(res, AnswerSet(source="s.yaml", answers={"flywheel.JJ": 1.0, "kinematics[5].phi": 0.0,
                                                           "flywheel.J[1]": 1.0}), {})
    notes = [r["note"] for r in rows]
    assert notes[0] == "flywheel.JJ: no key 'JJ'; did you mean 'flywheel.J'?"
    assert notes[1].startswith("kinematics[5].phi: no entry with index 5; ")
    assert notes[2].startswith("flywheel.J[1]: [1] applied to a non-list; ")
    assert localize(notes[0].to_dict(), "ru") == \
        "путь не найден (flywheel.JJ: нет ключа «JJ»); возможно, имелось в виду «flywheel.J»?"
    assert localize(notes[0].to_dict(), "uk").startswith("шлях не знайдено (flywheel.JJ: немає ключа «JJ»); ")
    # a malformed path in an answers file and in an answers table: the reason whole
    f = tmp_path / "a.yaml"
    f.write_text('answers:\n  "a..b": 1\n')
    with pytest.raises(TaskError) as exc:
        load_answers_file(f)
    assert exc.value.render().endswith("'answers.a..b': bad path 'a..b' near '..'")
    t = tmp_path / "a.csv"
    t.write_text("variant,a..b\n1,2\n")
    with pytest.raises(TaskError) as exc:
        load_answers_csv(t)
    assert exc.value.render().endswith("column 'a..b': bad path 'a..b' near '..'")
    assert "«a..b»" in localize(exc.value.coded().to_dict(), "ru")


def test_summary_html_links_only_files_that_exist(tmp_path):
    """A batch with a graded, a failing and an invalid variant (and answers for a variant
    with no task): every link of summary.html points at a file the batch wrote; the graded
    variant keeps its report, check and feedback links, the failing one its report."""
    from html import unescape
    from urllib.parse import unquote
    src, ans = tmp_path / "src", tmp_path / "ans"
    _write(src, "good.yaml", SLIDER.replace("schema: tmm/1\n", "schema: tmm/1\nvariant: 1\n"))
    _write(src, "fails.yaml", "schema: tmm/1\ntitle: p\nplanetary: {scheme: A, ratio: 1.2, satellites: 3, m: 2 mm}\n")
    _write(src, "bad.yaml", SLIDER.replace("length: 0.08", "lenght: 0.08"))
    _write(ans, "ivan.yaml", "student: {name: Ivan}\nvariant: 1\nanswers:\n  structure.W: 1\n  flywheel.JJ: 1\n")
    _write(ans, "olga.yaml", "student: {name: Olga}\nvariant: 7\nanswers:\n  structure.W: 1\n")
    out = tmp_path / "o"
    res = runner.invoke(app, ["batch", str(src), "--answers", str(ans), "--out", str(out), "--format", "json,html"])
    assert res.exit_code in (2, 3), res.output
    html = (out / "summary.html").read_text(encoding="utf-8")
    links = [unquote(unescape(h)) for h in re.findall(r'href="([^"]*)"', html)]
    assert {"good/report.html", "good/check.csv", "fails/report.html"} <= set(links), links
    assert any(h.startswith("good/feedback") for h in links), links
    for h in links:
        assert (out / h).is_file(), (h, links)


def test_summary_html_status_of_an_invalid_answers_file_does_not_blame_the_task(tmp_path):
    """`invalid` is a row's status both for a task that is not valid and for an answers file
    that is not (broken YAML, a variant no task has): its word in the ru/uk summary says the
    data are wrong ("ошибка в данных"), not "ошибка в задании", which blamed the instructor's
    task for a student's file; the message says which."""
    src, ans = tmp_path / "src", tmp_path / "ans"
    _write(src, "good.yaml", SLIDER.replace("schema: tmm/1\n", "schema: tmm/1\nvariant: 1\n"))
    _write(ans, "broken.yaml", "answers: [1, 2\n")
    _write(ans, "olga.yaml", "student: {name: Olga}\nvariant: 7\nanswers:\n  structure.W: 1\n")
    for lang, word, wrong in (("ru", "ошибка в данных", "ошибка в задании"),
                              ("uk", "помилка в даних", "помилка в завданні")):
        out = tmp_path / lang
        res = runner.invoke(app, ["batch", str(src), "--answers", str(ans), "--out", str(out),
                                  "--format", "json", "--lang", lang])
        assert res.exit_code == 2, res.output
        html = (out / "summary.html").read_text(encoding="utf-8")
        assert html.count(f'<span class="st">{word}</span>') == 2 and wrong not in html, html


@pytest.mark.parametrize("kind, name, text, ru", [
    ("tol", "neg.yaml", "flywheel.J: -1\n", "ожидается неотрицательное число (относительный допуск), задано −1"),
    ("tol", "abs.yaml", "flywheel.J: {abs: x}\n", "ожидается неотрицательное число (абсолютный допуск), задано 'x'"),
    ("tol", "key.yaml", "flywheel.J: {rell: 1}\n", "неизвестный ключ «rell»; в допуске бывают `rel`"),
    ("tol", "list.yaml", "- 1\n- 2\n", "это не файл допусков"),
    ("tol", "dir", None, "это не обычный файл (файл допусков"),
    ("answers", "empty.csv", "", "пустая таблица (нет строки заголовка)"),
    ("answers", "late.csv", "\n\nvariant,flywheel.J\n1,2\n", "заголовок таблицы должен быть в первой строке"),
    ("answers", "novar.csv", "student,flywheel.J\nA,2\n", "в таблице ответов нужен столбец `variant`"),
    ("answers", "bin.csv", b"\xff\xfe\x00\x81\x98", "это не текстовая таблица в кодировке UTF-8"),
    ("answers", "list.yaml", "answers: [1, 2]\n", "ожидается таблица YAML (ключ: значение), задано: список"),
    ("answers", "dir", None, "это не обычный файл (файл ответов"),
    ("answers", "none.yaml", False, "такого файла или папки нет"),
])
def test_tolerance_and_answers_file_errors_in_russian(tmp_path, kind, name, text, ru):
    """A broken tolerance file, answers table or answers file: the English text as on
    stderr, and the whole line in Russian (no English reason left)."""
    from tmm_cli.check import load_answers_file, load_sources, load_tolerance_file
    from tmm_cli.errors import TaskError
    from tmm_cli.messages import localize
    f = tmp_path / name
    if text is None:
        f.mkdir()
    elif isinstance(text, bytes):
        f.write_bytes(text)
    elif text is not False:
        f.write_text(text, encoding="utf-8")
    load = load_tolerance_file if kind == "tol" else (load_answers_file if name == "dir" else load_sources)
    with pytest.raises(TaskError) as info:
        load(f)
    coded = info.value.coded()
    assert coded is not None and str(coded) == info.value.render()
    out = localize(coded.to_dict(), "ru")
    assert ru in out, out
    assert not re.search(r"\b(expected|table|file|header|unknown|regular)\b", out), out


def test_tolerances_are_read_by_the_number_grammar(tmp_path):
    """A tolerance is a number a user writes: read as every other (the decimal comma, a
    fraction), in the task file and in --tolerance FILE; a wrong one is told in its own form's
    terms (not as the three forms' errors, one naming a class of the code); a decimal comma
    inside {...} says so, as for any other field; the head names the file that is wrong."""
    from tmm_cli.check import Tol, load_tolerance_file
    from tmm_cli.errors import TaskError
    from tmm_cli.task import load_task
    head = "schema: tmm/1\ngears: {m: 4 mm, z: [20, 40]}\ntolerance:\n"
    t = _write(tmp_path, "ok.yaml", head + "  default: 0,02\n  gears.a_w:\n    abs: 0,5\n  gears.d: '1/20'\n")
    tol = load_task(t).tolerance
    assert tol["default"] == 0.02 and tol["gears.a_w"].abs == 0.5 and tol["gears.d"] == 0.05
    bad = _write(tmp_path, "bad.yaml", head + "  gears.b: {rel: 0,1}\n  gears.z: fast\n  gears.c: {abs: x}\n")
    with pytest.raises(TaskError) as info:
        load_task(bad)
    issues = [(f, line, str(m)) for f, line, _, m in info.value.issues]
    assert issues == [("tolerance.gears.b.rel", 4, "'0,1' has a decimal comma, and YAML splits a number at the "
                                                   "comma inside [...] or {...}: write 0.1, or quote the value"),
                      ("tolerance.gears.z", 5, "expected a non-negative number (relative tolerance), got 'fast'"),
                      ("tolerance.gears.c.abs", 6, "expected a non-negative number (absolute), got 'x'")]
    # --tolerance FILE
    f = _write(tmp_path, "tol.yaml", "flywheel.J: 0,1\npositions.phi0: {abs: '0,5'}\n")
    got = load_tolerance_file(f)
    assert got["flywheel.J"] == Tol(rel=0.1) and got["positions.phi0"].abs == 0.5
    f2 = _write(tmp_path, "tol2.yaml", "positions.phi0: {abs: 0,5}\n")
    with pytest.raises(TaskError) as info:
        load_tolerance_file(f2)
    assert info.value.kind == "tolerance file" and "write 0.5, or quote the value" in info.value.render()
    runner = CliRunner()
    task = ROOT / "tasks" / "gears_zero.yaml"
    ans = _write(tmp_path, "a.yaml", "answers:\n  gears.aw: 1\n")
    res = runner.invoke(app, ["check", str(task), "--answers", str(ans), "--tolerance", str(f2)])
    assert res.exit_code == 2 and res.output.startswith("error: invalid tolerance file\n"), res.output
    tab = _write(tmp_path, "tab.yaml", "variant: 5\nanswers:\n\tgears.aw: 12\n")
    res = runner.invoke(app, ["check", str(task), "--answers", str(tab)])
    assert res.exit_code == 2 and res.output.startswith("error: invalid answers file\n"), res.output
    assert "tab.yaml:3:1: use spaces for indentation" in res.output


def test_malformed_answers_row_in_the_summary_language(tmp_path):
    """An answers table's malformed row: summary.csv keeps the English reason, summary.html
    shows it in Russian."""
    src = tmp_path / "src"
    _write(src, "v1.yaml", GEARS.format(v=1))
    t = _write(tmp_path, "a.csv", "student,variant,gears.a_w\nIvan,1,2,3,4\n")
    res = runner.invoke(app, ["batch", str(src), "--answers", str(t), "--out", str(tmp_path / "o"), "--lang", "ru"])
    assert res.exit_code == 2, res.output
    rows = [r for r in _csv(tmp_path / "o" / "summary.csv") if r["student"] == "Ivan"]
    assert rows and rows[0]["message"] == f"{t}:2: malformed row: 5 cells but the header has 3 columns"
    html = (tmp_path / "o" / "summary.html").read_text(encoding="utf-8")
    assert f"{t}:2: неверная строка: ячеек 5, а столбцов в заголовке 3" in html
    assert "malformed row" not in html


def test_form_names_a_misspelt_quantity_without_stray_quotes(tmp_path):
    """`tmm form -q` with a misspelt path: the reason reads as check.csv's note does."""
    task = _write(tmp_path, "g.yaml", GEARS.format(v=1))
    res = runner.invoke(app, ["form", str(task), "-q", "gears.a_ww", "-o", str(tmp_path / "f")])
    assert "quantity 'gears.a_ww' is not in the results: gears.a_ww: no key 'a_ww'; did you mean 'gears.aw'?" \
        in res.output, res.output


def test_summary_shows_a_variant_without_answers_as_computed_not_correct(tmp_path):
    """A batch with no answers anywhere grades nothing: summary.csv keeps its `ok` (the run
    succeeded, exit 0), but the page says "computed", not "correct"."""
    src = tmp_path / "src"
    _write(src, "g.yaml", "schema: tmm/1\nvariant: '7'\ngears: {m: 4 mm, z: [14, 30]}\n")
    for lang, word, verdict in (("en", ">computed<", ">ok<"), ("ru", ">рассчитано<", ">верно<"),
                                ("uk", ">розраховано<", ">правильно<")):
        out = tmp_path / f"o_{lang}"
        res = runner.invoke(app, ["batch", str(src), "--out", str(out), "--lang", lang, "--format", "json"])
        assert res.exit_code == 0, res.output
        assert _csv(out / "summary.csv")[0]["status"] == "ok"
        row = next(r for r in (out / "summary.html").read_text().split("<tr>") if "<td>7</td>" in r)
        assert word in row and verdict not in row


def test_readme_loop_grades_what_the_form_asked(tmp_path):
    """The README's instructor loop hands out forms for some quantities; its `batch` and
    `check` lines must ask for the same ones, else a student who leaves answers out of the
    form is graded only on what they gave (3 of 7 given, all right -> 100 %, `ok`)."""
    readme = (Path(__file__).resolve().parents[1] / "README.md").read_text(encoding="utf-8")
    block = readme.split("## The instructor's loop", 1)[1].split("```sh", 1)[1].split("```", 1)[0]
    cmds = {m.group(1): m.group(0) for m in re.finditer(r"^tmm (form|batch|check) .*$", block, re.M)}
    assert set(cmds) == {"form", "batch", "check"}
    q = {k: re.search(r"--quantities (\S+)", v) for k, v in cmds.items()}
    assert q["form"] and q["batch"] and q["check"], cmds
    assert q["batch"].group(1) == q["form"].group(1) == q["check"].group(1)
    # and with them, a half-filled form is `missing`, scored 3 / 7
    tab = tmp_path / "table.csv"
    lines = (EX / "press_variants.csv").read_text(encoding="utf-8-sig").splitlines()
    tab.write_text("\n".join(lines[:2]) + "\n", encoding="utf-8")
    res = runner.invoke(app, ["variants", str(EX / "press_template.yaml"), str(tab), "--out", str(tmp_path / "t")])
    assert res.exit_code == 0, res.output
    quant = "positions,flywheel.J"
    res = runner.invoke(app, ["form", str(tmp_path / "t"), "--quantities", quant, "--out", str(tmp_path / "f")])
    assert res.exit_code == 0, res.output
    import yaml
    key = yaml.safe_load((tmp_path / "f" / "01.key.yaml").read_text(encoding="utf-8"))
    assert len(key["answers"]) == 7          # flywheel.J + six position quantities
    key["answers"] = dict(list(key["answers"].items())[:3])
    (tmp_path / "a").mkdir()
    (tmp_path / "a" / "s.yaml").write_text(yaml.safe_dump(key, allow_unicode=True), encoding="utf-8")
    res = runner.invoke(app, ["batch", str(tmp_path / "t"), "--out", str(tmp_path / "g"), "--answers",
                              str(tmp_path / "a"), "--quantities", quant, "--jobs", "1", "--format", "json"])
    assert res.exit_code == 1, res.output
    rows = list(csv.DictReader((tmp_path / "g" / "summary.csv").open(encoding="utf-8-sig")))
    assert len(rows) == 1 and rows[0]["status"] == "missing", rows
    assert rows[0]["missing"] == "4" and abs(float(rows[0]["score"]) - 3 / 7) < 1e-3


def test_interrupted_batch_leaves_no_temporary_files(tmp_path, monkeypatch):
    """Ctrl-C during `tmm batch`: workers ended while writing leave `.NAME.<random>.tmp`
    files in the variant folders; the batch removes those this run made (an older one, a
    file of the user's, stays) and the interrupt goes on (exit 130)."""
    import time
    from tmm_cli import batch
    tasks = tmp_path / "t"
    tasks.mkdir()
    (tasks / "01.yaml").write_text((ROOT / "tasks" / "crank_rocker_fourbar.yaml").read_text(encoding="utf-8"),
                                   encoding="utf-8")
    out = tmp_path / "g"
    old = out / "00" / ".old.html.abcdefgh.tmp"
    old.parent.mkdir(parents=True)
    old.write_text("x")
    os.utime(old, (time.time() - 3600, time.time() - 3600))
    mine = out / "00" / "notes.tmp"
    mine.write_text("the user's")

    def interrupted(args, **kw):
        (out / "01").mkdir(parents=True, exist_ok=True)
        (out / "01" / ".report.html.k3j9x0a_.tmp").write_text("<html><body>half")
        raise KeyboardInterrupt
    monkeypatch.setattr(batch, "run_all", interrupted)
    with pytest.raises(KeyboardInterrupt):
        batch.run_batch(str(tasks), out, jobs=1)
    assert not (out / "01" / ".report.html.k3j9x0a_.tmp").exists()
    assert old.exists() and mine.read_text() == "the user's"


def test_variants_non_numeric_cell_of_a_unit_column_named(tmp_path):
    """A cell `abc` in the column `l_OA, mm` is reported as that column's bad number,
    not as "unknown unit in 'abc mm'" about a field; the other rows are written."""
    tab = tmp_path / "table.csv"
    lines = (EX / "press_variants.csv").read_text(encoding="utf-8-sig").splitlines()
    bad = lines[1].split(";")
    bad[1] = "abc"
    tab.write_text("\n".join([lines[0], ";".join(bad), lines[2]]) + "\n", encoding="utf-8")
    res = runner.invoke(app, ["variants", str(EX / "press_template.yaml"), str(tab), "--out", str(tmp_path / "t")])
    assert res.exit_code == 2
    assert f"{tab}:2: variant 01: column l_OA, mm: 'abc' is not a number" in res.output, res.output
    assert "unknown unit" not in res.output
    assert not (tmp_path / "t" / "01.yaml").exists() and (tmp_path / "t" / "02.yaml").exists()


def test_leaf_paths_give_python_numbers():
    """A numpy scalar among the results is listed as the number it is (printed by `tmm paths` and
    written to forms as 1.5, never as 'np.float64(1.5)'), a numpy integer or bool not dropped."""
    import numpy as np

    from tmm_cli.results import leaf_paths
    got = dict(leaf_paths({"a": np.float64(1.5), "b": {"c": np.int64(3), "d": np.bool_(True)}, "e": [np.float32(0.25)]}))
    assert got == {"a": 1.5, "b.c": 3, "b.d": True, "e[0]": 0.25}
    assert all(type(v) in (float, int, bool) for v in got.values())
    assert repr(got["a"]) == "1.5"
