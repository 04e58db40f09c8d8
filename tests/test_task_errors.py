"""Bad input: every kind gets a clear message naming file, line and field, exit 2,
and no traceback (SPEC 2; issue 2: at least ten kinds)."""
from __future__ import annotations

import subprocess
import sys
import textwrap

import pytest
from typer.testing import CliRunner

from tmm_cli.cli import app

runner = CliRunner()

GOOD_MECH = """\
schema: tmm/1
title: slider-crank
mechanism:
  ground: {O: [0, 0]}
  links:
    crank: {points: [O, A], length: 0.1, mass: 1}
    rod: {points: [A, B], length: 0.4, mass: 2}
    slider: {slider: B, guide: {through: O, angle: 0}, mass: 3}
drive: {link: crank, speed: 100 rpm}
"""


def _validate(tmp_path, text, name="task.yaml", extra=()):
    f = tmp_path / name
    f.write_text(textwrap.dedent(text), encoding="utf-8")
    res = runner.invoke(app, ["validate", *extra, str(f)])
    return res, str(f)


# (description, task text, expected line, expected fragments of the message)
CASES = [
    ("missing required field", GOOD_MECH.replace("drive: {link: crank, speed: 100 rpm}", "drive: {link: crank}"),
     9, ["drive.speed", "required field is missing"]),
    ("wrong unit", GOOD_MECH.replace("length: 0.4,", "length: 5 kg,"),
     7, ["mechanism.links.rod.length", "is not a length"]),
    ("unknown key with suggestion", GOOD_MECH.replace("mass: 2}", "mas: 2}"),
     7, ["mechanism.links.rod.mas", "did you mean 'mass'"]),
    ("unknown section", GOOD_MECH + "flywhel: {delta: 1/18}\n",
     10, ["flywhel", "did you mean 'flywheel'"]),
    ("bad enum value", GOOD_MECH.replace("speed: 100 rpm}", "speed: 100 rpm, direction: left}"),
     9, ["drive.direction", "'ccw' or 'cw'"]),
    ("negative mass", GOOD_MECH.replace("mass: 3}", "mass: -3}"),
     8, ["mechanism.links.slider.mass", "greater than or equal to 0"]),
    ("unknown unit", GOOD_MECH.replace("length: 0.1,", "length: 10 furlongz,"),
     6, ["mechanism.links.crank.length", "unknown unit"]),
    ("bad schema version", GOOD_MECH.replace("schema: tmm/1", "schema: tmm/9"),
     1, ["schema", "unsupported schema"]),
    ("drive link unknown", GOOD_MECH.replace("link: crank,", "link: crnk,"),
     9, ["drive.link", "did you mean 'crank'"]),
    ("point used by no link", GOOD_MECH.replace("ground: {O: [0, 0]}", "ground: {O: [0, 0], O2: [1, 1]}"),
     4, ["mechanism.ground.O2", "used by no link"]),
    ("bar without length", GOOD_MECH.replace("{points: [A, B], length: 0.4, mass: 2}", "{points: [A, B], mass: 2}"),
     7, ["mechanism.links.rod", "needs `length`"]),
    ("flywheel without loads", GOOD_MECH + "flywheel: {delta: 1/18}\n",
     10, ["field 'flywheel'", "flywheel` needs `loads"]),
    ("delta as a bad fraction", GOOD_MECH + "loads: {gravity: true}\nflywheel: {delta: 1/0}\n",
     11, ["flywheel.delta", "division by zero"]),
    ("cam phases over 360", "schema: tmm/1\ncam:\n  stroke: 0.02\n  phases: {rise: 200, far_dwell: 50, return: 200}\n",
     4, ["cam.phases", "exceeds 360"]),
    ("diagram lengths differ", GOOD_MECH + "loads:\n  forces:\n    - on: slider\n      diagram: {s: [0, 1], value: [1, 2, 3]}\n",
     13, ["loads.forces[0].diagram", "differ in length"]),
    ("guide through a non-ground point", GOOD_MECH.replace("through: O,", "through: A,"),
     8, ["mechanism.links.slider.guide.through", "not a ground point"]),
    ("duplicate key", GOOD_MECH.replace("title: slider-crank", "title: a\ntitle: b"),
     3, ["duplicate key 'title'"]),
    ("YAML syntax error", GOOD_MECH.replace("{O: [0, 0]}", "{O: [0, 0]"),
     None, ["YAML syntax error"]),
    ("com names a foreign point", GOOD_MECH.replace("mass: 2}", "mass: 2, com: O}"),
     7, ["mechanism.links.rod.com", "not a point of link 'rod'"]),
    ("not a mapping", "- just\n- a list\n", 1, ["must be a mapping"]),
    # pint reads a bare unit as one of it: `length: mm` was a 1 mm crank, `speed: rpm` 1 rpm
    ("unit without a number", GOOD_MECH.replace("length: 0.1,", "length: mm,"),
     6, ["mechanism.links.crank.length", "'mm' is a unit without a number"]),
    ("speed without a number", GOOD_MECH.replace("speed: 100 rpm}", "speed: rpm}"),
     9, ["drive.speed", "'rpm' is a unit without a number"]),
    # numbers that are not numbers (one grammar, tmm_cli/numbers.py): never coerced, never evaluated
    ("approximate value", GOOD_MECH.replace("length: 0.1,", 'length: "≈0,1 m",'),
     6, ["mechanism.links.crank.length", "'≈0,1 m' is not a number: it begins with '≈'"]),
    ("a number with its error", GOOD_MECH.replace("length: 0.1,", 'length: "0,1 ± 0,01 m",'),
     6, ["mechanism.links.crank.length", "is not one number"]),
    ("two decimal marks", GOOD_MECH.replace("length: 0.4,", "length: 0.4.1,"),
     7, ["mechanism.links.rod.length", "more than one decimal mark"]),
    ("thousands not in threes", GOOD_MECH.replace("mass: 3}", 'mass: "1 23,4"}'),
     8, ["mechanism.links.slider.mass", "grouped by spaces in threes"]),
    ("an expression", GOOD_MECH.replace("speed: 100 rpm}", "speed: 9**9**9 rpm}"),
     9, ["drive.speed", "is not a number but an expression"]),
    ("a dash for a minus", GOOD_MECH.replace("mass: 3}", "mass: –3}"),
     8, ["mechanism.links.slider.mass", "a dash is not a minus sign"]),
    ("a frequency for a speed", GOOD_MECH.replace("speed: 100 rpm}", "speed: 100 kHz}"),
     9, ["drive.speed", "is a frequency, not an angular speed"]),
    ("a unit with a power of a power", GOOD_MECH.replace("mass: 3}", "mass: 3 kg^2^2}"),
     8, ["mechanism.links.slider.mass", "cannot read the unit 'kg^2^2'"]),
    # a decimal comma inside a flow mapping: YAML made keys '1' and '012 кг·м²' of the pieces;
    # the message names the real field and says how to write the value
    ("decimal comma in a flow mapping", GOOD_MECH.replace("rod: {points: [A, B], length: 0.4, mass: 2}",
                                                          "rod: {points: [A, B], length: 0.4, mass: 2,1, J: 0,012 кг·м²}"),
     7, ["field 'mechanism.links.rod.mass'", "'2,1' has a decimal comma", "write 2.1, or quote the value"]),
    ("positions as a number", GOOD_MECH + "kinetostatics:\n  positions: 2\n",
     11, ["kinetostatics.positions", "a list of positions, e.g. [2] (or all); got 2"]),
    ("file without schema", GOOD_MECH.replace("schema: tmm/1\n", ""),
     1, ["field 'schema'", "add `schema: tmm/1` as the first line"]),
    ("stray comma", GOOD_MECH.replace("drive: {link: crank, speed: 100 rpm}", "drive: {link: crank, speed: 100 rpm,, }"),
     9, ["YAML syntax error: a stray comma: delete it"]),
    ("stray comma after a section", GOOD_MECH.replace("drive: {link: crank, speed: 100 rpm}", "drive: {link: crank, speed: 100 rpm},"),
     9, ["a stray comma: delete it"]),
    ("Cyrillic word that is no unit", GOOD_MECH.replace("length: 0.1,", "length: 100 попугаев,"),
     6, ["mechanism.links.crank.length", "unknown unit"]),
]


@pytest.mark.parametrize("desc,text,line,frags", CASES, ids=[c[0] for c in CASES])
def test_bad_input(tmp_path, desc, text, line, frags):
    res, f = _validate(tmp_path, text, extra=("--no-assembly",))
    assert res.exit_code == 2, (desc, res.output)
    out = res.output
    assert "Traceback" not in out
    assert f in out, out
    if line is not None:
        assert f"{f}:{line}:" in out, out
    for fr in frags:
        assert fr in out, (fr, out)


def test_missing_file(tmp_path):
    res = runner.invoke(app, ["validate", str(tmp_path / "nope.yaml")])
    assert res.exit_code == 2
    assert "file not found" in res.output


def test_real_process_exit_code_and_no_traceback(tmp_path):
    f = tmp_path / "bad.yaml"
    f.write_text(GOOD_MECH.replace("mass: 2}", "mas: 2}"), encoding="utf-8")
    p = subprocess.run([sys.executable, "-m", "tmm_cli", "run", str(f), "--out", str(tmp_path / "o")],
                       capture_output=True, text=True)
    assert p.returncode == 2
    assert "Traceback" not in p.stderr + p.stdout
    assert f"{f}:7:" in p.stderr
    assert not (tmp_path / "o").exists()  # nothing written for an invalid task


def test_yaml_12_keys_stay_strings(tmp_path):
    """`on:` must stay the key 'on' (YAML 1.1 would make it True); `yes` stays a string."""
    from tmm_cli.yamlload import load_yaml
    data, marks = load_yaml("x.yaml", text="on: yes\noff: no\nt: true\nf: False\nn: 1:30\nx: 0o17\n")
    assert data == {"on": "yes", "off": "no", "t": True, "f": False, "n": "1:30", "x": 15}
    assert marks[("off",)] == (2, 1)


def test_force_on_key_parses(tmp_path):
    from tmm_cli import load_task
    t = load_task(tmp_path / "x.yaml" if False else {
        "schema": "tmm/1",
        "mechanism": {"ground": {"O": [0, 0]}, "links": {
            "crank": {"points": ["O", "A"], "length": 0.1},
            "rod": {"points": ["A", "B"], "length": 0.4},
            "slider": {"slider": "B", "guide": {"through": "O", "angle": 0}}}},
        "drive": {"link": "crank", "speed": "60 rpm"},
        "loads": {"forces": [{"on": "slider", "kind": "resistance", "magnitude": "3 kN"}]}})
    assert t.loads.forces[0].on == "slider"
    assert t.loads.forces[0].magnitude == 3000.0


FOURBAR = """\
schema: tmm/1
mechanism:
  ground: {O: [0, 0], C: [0.3, 0]}
  links:
    crank: {points: [O, A], length: 0.1}
    rod: {points: [A, B], length: 0.3}
    rocker: {points: [C, B], length: 0.2}
drive: {link: crank, speed: 10}
"""


@pytest.mark.parametrize("desc,text,line,frags", [
    # a brace A-C makes the four-bar rigid: n = 4, p5 = 6 -> W = 3*4 - 2*6 = 0
    ("W = 0", FOURBAR.replace("drive:", "    brace: {points: [A, C], length: 0.25}\ndrive:"), 2,
     ["field 'mechanism'", "W = 0", "3*4 - 2*6"]),
    # a five-bar O-A-B-D-C: n = 4, p5 = 5 -> W = 2
    ("W = 2", FOURBAR.replace("rocker: {points: [C, B], length: 0.2}",
                              "rod2: {points: [B, D], length: 0.3}\n    rocker: {points: [C, D], length: 0.2}")
     .replace("C: [0.3, 0]", "C: [0.5, 0]"), 2, ["W = 2", "needs 2 inputs"]),
    # |OC| = 1 m but rod + rocker = 0.4 m and crank 0.1 m: no crank angle assembles
    ("impossible dimensions", FOURBAR.replace("C: [0.3, 0]", "C: [1.0, 0]"), 6,
     ["mechanism.links.rod", "impossible dimensions", "cannot reach"]),
], ids=["W=0", "W=2", "never assembles"])
def test_infeasible_linkage_is_invalid(tmp_path, desc, text, line, frags):
    res, f = _validate(tmp_path, text)
    assert res.exit_code == 2, res.output
    assert f"{f}:{line}:" in res.output
    for fr in frags:
        assert fr in res.output, (fr, res.output)
    assert "Traceback" not in res.output


@pytest.mark.parametrize("line, field", [("  pressure_angle: 0", "cam.pressure_angle"),
                                         ("  transmission_angle: 90", "cam.transmission_angle")])
def test_cam_limit_out_of_range_names_its_line(tmp_path, line, field):
    """An allowed pressure angle outside (0, 90) deg (or a transmission angle of 90) points
    at its own line and field, not at the `cam` section."""
    text = ("schema: tmm/1\ncam:\n  follower: translating\n  stroke: 20 mm\n" + line + "\n"
            "  phases: {rise: 120, far_dwell: 60, return: 120, near_dwell: 60}\n"
            "  laws: {rise: cosine, return: cosine}\n")
    f = tmp_path / "cam.yaml"
    f.write_text(text, encoding="utf-8")
    res = runner.invoke(app, ["validate", str(f)])
    assert res.exit_code == 2
    assert f"{f}:5:3: field '{field}': the allowed pressure angle must lie in (0, 90) deg" in res.output


def test_impossible_dimensions_say_crank_angle_once(tmp_path):
    """The reason already names the crank angles (all of them, or 'any crank angle'): the
    message adds only what to check."""
    res, f = _validate(tmp_path, FOURBAR.replace("C: [0.3, 0]", "C: [1.0, 0]"))
    assert res.exit_code == 2, res.output
    assert res.output.count("crank angle") == 1, res.output
    assert "cannot reach); check the lengths of rod, rocker and the ground points" in res.output


def test_each_interval_where_a_group_does_not_assemble_says_why_at_its_own_angle(tmp_path):
    """The conveyor's four-bar with a 0.25 m crank (frame 0.30, coupler 0.30, rocker 0.22): the
    dyad cannot reach about phi = 180 deg (|AO3| = 0.30 + 0.25 = 0.55 > 0.30 + 0.22) and folds
    too near about phi = 0 (|AO3| = 0.30 - 0.25 = 0.05 < 0.30 - 0.22). Each interval is told with
    its own reason at its own middle (the message quoted 0.55 m for both, its header naming
    0 deg); one reason where they agree (test_run_outputs: a slider's rod too short)."""
    import json
    import math
    from pathlib import Path
    text = (Path(__file__).resolve().parents[1] / "tasks" / "crank_rocker_fourbar.yaml").read_text(encoding="utf-8")
    f = tmp_path / "long_crank.yaml"
    f.write_text(text.replace("points: [O, A], length: 0.08,", "points: [O, A], length: 0.25,"), encoding="utf-8")
    res = CliRunner().invoke(app, ["run", str(f), "--out", str(tmp_path / "o"), "--format", "json", "-q"])
    assert res.exit_code == 3, res.output
    err = json.loads((tmp_path / "o" / "results.json").read_text(encoding="utf-8"))["errors"][0]
    assert err["code"] == "kinematics.fail.intervals" and err["params"]["reason"]["code"] == "kinematics.reason.each"
    (a1, b1), (a2, b2) = err["params"]["intervals"]
    items = err["params"]["reason"]["params"]["items"]
    assert [i["params"]["reason"]["code"] for i in items] == ["kinematics.reason.rrr_far", "kinematics.reason.rrr_near"]
    for (a, b), item in zip(((a1, b1), (a2, b2)), items):
        phi = item["params"]["phi"]
        assert phi == pytest.approx((a + ((b - a) % 360) / 2) % 360, abs=1e-9)      # the interval's middle
        # |AO3| at that angle, by hand: A = 0.25 (cos phi, sin phi), O3 = (0.30, 0)
        d = math.hypot(0.25 * math.cos(math.radians(phi)) - 0.30, 0.25 * math.sin(math.radians(phi)))
        assert item["params"]["reason"]["params"]["d"] == pytest.approx(d, rel=1e-9)
    assert [round(i["params"]["phi"]) % 360 for i in items] == [180, 0]
    assert "at 180 deg, |AO3| = 0.55 m > |AB| + |BO3|" in res.output
    assert "at 0 deg, |AO3| = 0.05 m < ||AB| - |BO3||" in res.output


def test_a_name_typed_with_cyrillic_letters_is_told_so(tmp_path):
    """A point or link name typed on the other keyboard layout (the Cyrillic O, U+041E, for the
    Latin O) looks the same as the name it should be: the message says which holds the Cyrillic
    letter instead of 'did you mean O?' beside an identical-looking O."""
    from tmm_cli.limits import lookalike
    CYR_O, CYR_A, CYR_a = "\u041e", "\u0410", "\u0430"
    assert lookalike(CYR_O + "1", "O1") and not lookalike("O1", "O1") and not lookalike("O1", "Q1")

    def four_bar(ground_o="O", crank=("O", "A"), coupler=("A", "B"), drive="crank"):
        return {"schema": "tmm/1", "mechanism": {
            "ground": {ground_o: [0, 0], "O3": [0.3, 0]},
            "links": {"crank": {"points": list(crank), "length": 0.08}, "coupler": {"points": list(coupler), "length": 0.3},
                      "rocker": {"points": ["O3", "B"], "length": 0.22}}, "assembly": {"B": [0.33, 0.21]}},
            "drive": {"link": drive, "speed": "120 rpm"}}

    def error(task) -> str:
        import yaml
        f = tmp_path / "t.yaml"
        f.write_text(yaml.safe_dump(task, allow_unicode=True, sort_keys=False), encoding="utf-8")
        res = CliRunner().invoke(app, ["validate", str(f)])
        assert res.exit_code == 2, res.output
        return res.output

    msg = error(four_bar(ground_o=CYR_O))
    assert f"did you mean the ground point '{CYR_O}'? ('{CYR_O}' is typed with the Cyrillic {CYR_O}, 'O' with " \
           "Latin letters: type the names alike)" in msg, msg
    msg = error(four_bar(crank=("O", CYR_A)))
    assert f"did you mean A? ('{CYR_A}' is typed with the Cyrillic {CYR_A}, 'A' with Latin letters" in msg, msg
    msg = error(four_bar(drive="cr" + CYR_a + "nk"))
    assert f"did you mean 'crank'? ('cr{CYR_a}nk' is typed with the Cyrillic {CYR_a}, 'crank' with Latin" in msg, msg


def test_a_rockers_stroke_in_mm_is_the_strokes_error_at_its_line(tmp_path):
    """A rocker's stroke is its swing, an angle: '20 mm' is refused at cam.stroke's own line
    (it was the cam section's first line), the unit named as the language writes it."""
    from typer.testing import CliRunner

    from tmm_cli.cli import app
    f = tmp_path / "cam.yaml"
    f.write_text("schema: tmm/1\ncam:\n  follower: rocker\n  stroke: 20 mm\n  rocker_length: 100 mm\n"
                 "  phases: {rise: 100, far_dwell: 40, return: 100}\n", encoding="utf-8")
    en = CliRunner().invoke(app, ["validate", str(f)])
    assert en.exit_code == 2
    assert "cam.yaml:4:3: field 'cam.stroke': '20 mm' is not an angle (deg, rad)" in en.output
    ru = CliRunner().invoke(app, ["validate", str(f), "--lang", "ru"])
    assert "cam.yaml:4:3: поле «cam.stroke»: «20 mm» — не угол (deg, rad): единица не приводится к °" in ru.output
    f.write_text(f.read_text().replace("stroke: 20 mm", "stroke: 20 deg"), encoding="utf-8")
    import tmm_cli
    assert tmm_cli.load_task(f).cam.stroke == 20.0
    f.write_text(f.read_text().replace("follower: rocker", "follower: translating"), encoding="utf-8")
    assert "field 'cam.stroke': '20 deg' is not a length" in CliRunner().invoke(app, ["validate", str(f)]).output


@pytest.mark.parametrize("field, written, meant", [
    ("direction", "против часовой", "ccw"), ("direction", "По часовой стрелке", "cw"),
    ("direction", "проти годинникової стрілки", "ccw"), ("law", "синусоидальный", "sine"),
    ("law", "рівномірний", "constant_velocity"), ("follower", "коромысло", "rocker"),
])
def test_a_value_written_in_the_course_language_gets_its_code_as_the_hint(field, written, meant, tmp_path):
    """A student writes the value in words (direction: против часовой): the error lists the
    codes and says which one was meant."""
    import tmm_cli
    from tmm_cli.errors import TaskError
    task = {"schema": "tmm/1", "cam": {"follower": "translating", "stroke": "20 mm",
                                       "phases": {"rise": 120, "far_dwell": 30, "return": 120},
                                       "laws": {"rise": "cosine", "return": "cosine"}}}
    if field == "direction":
        task["cam"]["rotation"] = written
    elif field == "law":
        task["cam"]["laws"]["rise"] = written
    else:
        task["cam"]["follower"] = written
    with pytest.raises(TaskError) as exc:
        tmm_cli.load_task(task)
    assert f"got {written!r}; did you mean {meant!r}?" in str(exc.value)


def test_a_misspelt_follower_does_not_make_the_stroke_wrong(tmp_path):
    """A rocker's '20 deg' under a misspelt follower ('roker'): one error, the follower's (with
    its hint); the stroke, whose unit the follower decides, is not also refused as 'not a
    length' (the follower failed, so it is not among the fields validated: the stroke was
    judged a translating follower's)."""
    from typer.testing import CliRunner

    from tmm_cli.cli import app
    f = tmp_path / "cam.yaml"
    f.write_text("schema: tmm/1\ncam:\n  follower: roker\n  stroke: 20 deg\n  rocker_length: 100 mm\n"
                 "  phases: {rise: 100, far_dwell: 40, return: 100}\n", encoding="utf-8")
    res = CliRunner().invoke(app, ["validate", str(f)])
    assert res.exit_code == 2 and "field 'cam.follower'" in res.output and "did you mean 'rocker'" in res.output
    assert "cam.stroke" not in res.output, res.output
    f.write_text(f.read_text().replace("stroke: 20 deg", "stroke: 20 kg"), encoding="utf-8")
    assert "field 'cam.stroke'" in CliRunner().invoke(app, ["validate", str(f)]).output    # no unit at all: still said


def test_every_unknown_key_of_a_mapping_in_one_error(tmp_path):
    """A link written {points: [O, A], lenght: 0.15, masss: 1.5, foo: 1}: one error at the first
    unknown key's line naming all three, each with its likely meaning (the second typo was
    hidden until the first was mended)."""
    import tmm_cli
    from tmm_cli.errors import TaskError
    from pathlib import Path
    root = Path(__file__).resolve().parents[1]
    text = (root / "tasks" / "crank_rocker_fourbar.yaml").read_text(encoding="utf-8")
    old = "crank:   {points: [O, A], length: 0.08, mass: 1.0, J: 0.0015}"
    assert old in text
    f = tmp_path / "t.yaml"
    f.write_text(text.replace(old, "crank:   {points: [O, A], lenght: 0.08, masss: 1.0, J: 0.0015, foo: 1}"),
                 encoding="utf-8")
    with pytest.raises(TaskError) as exc:
        tmm_cli.load_task(f)
    (issue,) = exc.value.issues
    assert issue[0] == "mechanism.links.crank.lenght" and issue[1] == 13
    assert str(issue[3]) == ("unknown key 'lenght'; did you mean 'length'? Also unknown: 'masss' "
                             "(did you mean 'mass'?); 'foo' (no key of that name here)")
