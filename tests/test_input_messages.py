"""Messages that send the user the right way: typos in point names, decimal commas, tabs,
plain numbers probably meant in rpm or mm, a negative size of a resistance, and the
command line's --version, bare `tmm` and `tmm fields`."""
from __future__ import annotations

import re
import textwrap

import pytest
from typer.testing import CliRunner

import tmm_cli
from tmm_cli.cli import app

runner = CliRunner()

SIXBAR = """\
schema: tmm/1
mechanism:
  ground:
    O: [0, 0]
    O1: [0.50, 0.37]
  links:
    crank:  {points: [O, A],  length: 0.15}
    rod:    {points: [A, B],  length: 0.97}
    rocker: {points: [O1, B], length: 0.66, extra: {C: [0.25, 0]}}
    link4:  {points: [C, D],  length: 0.86}
    slider: {slider: D, guide: {through: O1, angle: 90}}
  assembly: {B: [0.9, 0.6]}
drive: {link: crank, speed: 5, direction: ccw}
"""


def _validate(tmp_path, text):
    f = tmp_path / "task.yaml"
    f.write_text(textwrap.dedent(text), encoding="utf-8")
    res = runner.invoke(app, ["validate", str(f)])
    return res, str(f)


def test_the_sixbar_itself_is_valid(tmp_path):
    res, _ = _validate(tmp_path, SIXBAR)
    assert res.exit_code == 0, res.output


def test_point_used_by_one_link_is_named_before_the_dof_count(tmp_path):
    res, f = _validate(tmp_path, SIXBAR.replace("points: [C, D]", "points: [E, D]"))
    assert res.exit_code == 2
    out = res.output
    assert f"{f}:10:" in out and "mechanism.links.link4" in out
    expected = "point E is used by link4 only: a pair needs two links — did you mean C?"
    assert expected in out
    assert out.index(expected) < out.index("W = 3")
    assert "Traceback" not in out


@pytest.mark.parametrize("line, bad, said, lineno", [
    ("    O1: [0.50, 0.37]", "    O1: [0,50, 0,37]", "use a decimal point: 0.50", 5),   # four numbers, not two
    # 'length: 0' and a key '15': the field is the length, the value may be quoted
    ("    crank:  {points: [O, A],  length: 0.15}", "    crank:  {points: [O, A],  length: 0,15}",
     "field 'mechanism.links.crank.length': '0,15' has a decimal comma", 7),
])
def test_decimal_comma(tmp_path, line, bad, said, lineno):
    res, f = _validate(tmp_path, SIXBAR.replace(line, bad))
    assert res.exit_code == 2, res.output
    assert f"{f}:{lineno}:" in res.output
    assert said in res.output
    assert "Tuple should have" not in res.output and "unknown key" not in res.output


def test_compact_list_is_not_taken_for_decimal_commas(tmp_path):
    res, _ = _validate(tmp_path, "schema: tmm/1\ngears:\n  m: 3 mm\n  z: [12,42,7]\n")
    assert res.exit_code == 2
    assert "decimal point" not in res.output and "at most 2 items" in res.output


def test_decimal_comma_in_a_block_scalar_is_read(tmp_path):
    """A block scalar is read whole by the number grammar: '3,5 mm' is 3.5 mm (pint alone
    read it as 35 mm), '5,5 rad/s' 5.5 rad/s -- no hint, no error."""
    import yaml
    task = tmm_cli.load_task(yaml.safe_load("schema: tmm/1\ngears:\n  m: 3,5 mm\n  z: [12, 42]\n"))
    assert task.gears.m == pytest.approx(0.0035)
    res, _ = _validate(tmp_path, SIXBAR.replace("drive: {link: crank, speed: 5, direction: ccw}",
                                                "drive:\n  link: crank\n  speed: 5,5 rad/s\n  direction: ccw"))
    assert res.exit_code == 0, res.output


@pytest.mark.parametrize("text, line", [
    ("schema: tmm/1\ngears:\n\tm: 3 mm\n\tz: [12, 42]\n", 3),
    ("schema: tmm/1\ngears:\n  m: 3 mm\n \t z: [12, 42]\n", 4),
])
def test_tab_in_indentation(tmp_path, text, line):
    res, f = _validate(tmp_path, text)
    assert res.exit_code == 2
    assert f"{f}:{line}:" in res.output
    assert "use spaces for indentation" in res.output
    assert "cannot start any token" not in res.output


def _warnings(text: str) -> list[str]:
    import yaml
    return tmm_cli.load_task(yaml.safe_load(text)).input_warnings


def test_plain_speed_probably_meant_in_rpm_is_warned_about():
    w = _warnings(SIXBAR.replace("speed: 5,", "speed: 60,"))
    assert len(w) == 1
    assert "drive.speed" in w[0] and "60 rad/s" in w[0] and "573 rpm" in w[0] and "'60 rpm'" in w[0]
    # 60 rad/s * 30/pi = 572.96 rpm
    assert _warnings(SIXBAR.replace("speed: 5,", "speed: 50,")) == []
    assert _warnings(SIXBAR.replace("speed: 5,", "speed: 600 rpm,")) == []


def test_plain_length_above_10_m_is_warned_about():
    w = _warnings(SIXBAR.replace("length: 0.97}", "length: 970}").replace("O1: [0.50, 0.37]", "O1: [500, 370]"))
    assert any("mechanism.links.rod.length" in x and "970 m" in x and "'970 mm'" in x for x in w)
    assert any("mechanism.ground.O1[0]" in x and "'500 mm'" in x for x in w)
    assert _warnings(SIXBAR.replace("length: 0.97}", "length: 970 mm}")) == []
    assert _warnings(SIXBAR) == []


def test_plain_gear_module_in_metres_is_warned_about():
    w = _warnings("schema: tmm/1\ngears: {m: 3, z: [12, 42]}\n")
    assert len(w) == 1 and "gears.m" in w[0] and "'3 mm'" in w[0]
    assert _warnings("schema: tmm/1\ngears: {m: 3 mm, z: [12, 42]}\n") == []
    assert _warnings("schema: tmm/1\ngears: {m: 0.003, z: [12, 42]}\n") == []


def test_a_cams_plain_stroke_in_metres_is_warned_about_but_a_rockers_swing_is_not():
    """cam.stroke is a length (m) for a translating, knife or flat follower and a swing (deg) for a
    rocker: a plain 30 of the first is 30 m (r0 36.4 m), warned as any length over 10 m."""
    cam = "schema: tmm/1\ncam:\n  follower: {f}\n  stroke: {h}\n{more}  phases: {{rise: 120, far_dwell: 30, return: 120}}\n"
    for f in ("translating", "knife", "flat"):
        w = _warnings(cam.format(f=f, h=30, more=""))
        assert len(w) == 1 and "cam.stroke" in w[0] and "30 m" in w[0] and "'30 mm'" in w[0], (f, w)
        assert _warnings(cam.format(f=f, h="30 mm", more="")) == []
        assert _warnings(cam.format(f=f, h=0.03, more="")) == []
    assert _warnings(cam.format(f="rocker", h=30, more="  rocker_length: 0.1\n")) == []


def test_plain_number_warnings_reach_results():
    import yaml
    task = yaml.safe_load(SIXBAR.replace("speed: 5,", "speed: 100,"))
    r = tmm_cli.run(tmm_cli.load_task(task), kinematics_curve=0)
    assert any("drive.speed" in w and "'100 rpm'" in w for w in r["warnings"])


def test_length_meant_in_millimetres_is_named(tmp_path):
    res, f = _validate(tmp_path, SIXBAR.replace("length: 0.97}", "length: 100}"))
    assert res.exit_code == 2
    assert f"{f}:8:" in res.output and "mechanism.links.rod.length" in res.output
    # 100 / median(0.15, 0.66, 0.86, |OO1| = 0.6220) = 100 / 0.641 = 156
    assert "is 156 times the other lengths" in res.output
    assert "probably meant in millimetres" in res.output and "'100 mm'" in res.output


@pytest.mark.parametrize("field, value", [("magnitude", "-3000"), ("moment", "-20")])
def test_negative_size_of_a_resistance_is_invalid(tmp_path, field, value):
    text = SIXBAR + f"loads:\n  forces:\n    - on: slider\n      kind: resistance\n      {field}: {value}\n"
    if field == "moment":
        text = text.replace("on: slider", "on: rocker")
    res, f = _validate(tmp_path, text)
    assert res.exit_code == 2, res.output
    assert f"{f}:18:" in res.output and f"loads.forces[0].{field}" in res.output
    assert "must not be negative" in res.output
    ok, _ = _validate(tmp_path, text.replace(f"{field}: -", f"{field}: "))
    assert ok.exit_code == 0, ok.output


def test_negative_signed_force_without_kind_stays_valid(tmp_path):
    text = SIXBAR + "loads:\n  forces:\n    - on: slider\n      magnitude: -3000\n"
    res, _ = _validate(tmp_path, text)
    assert res.exit_code == 0, res.output


def test_version():
    res = runner.invoke(app, ["--version"])
    assert res.exit_code == 0
    assert res.output.strip() == f"tmm {tmm_cli.__version__}"


def test_bare_tmm_prints_help_and_succeeds():
    res = runner.invoke(app, [])
    assert res.exit_code == 0
    assert "Usage" in res.output and "run" in res.output and "validate" in res.output


def test_fields_keep_square_brackets():
    res = runner.invoke(app, ["fields", "mechanism"], env={"COLUMNS": "250"})
    assert res.exit_code == 0
    assert "name -> [x, y], m" in res.output
    assert "[u, v]" in res.output


def test_validate_shows_the_plain_number_warnings(tmp_path):
    """`tmm validate` says ok for a gear module given as a plain 3 (read as 3 m), and warns
    about it on stderr, as `tmm run` does."""
    f = tmp_path / "g.yaml"
    f.write_text("schema: tmm/1\ngears: {m: 3, z: [12, 42]}\n", encoding="utf-8")
    res = runner.invoke(app, ["validate", str(f)])
    assert res.exit_code == 0 and f"{f}: ok" in res.output
    assert f"warning: {f}: gears.m" in res.output and "'3 mm'" in res.output
    f.write_text("schema: tmm/1\ngears: {m: 3 mm, z: [12, 42]}\n", encoding="utf-8")
    assert "warning" not in runner.invoke(app, ["validate", str(f)]).output


_TASKS = __import__("pathlib").Path(__file__).resolve().parent.parent / "tasks"
# (task file, text replaced, replacement): one check of the dof2, drive_train and synthesis sections each
SECTION_CHECKS = [
    ("impact_rotor", "length: 60 mm", "length: -60 mm"),
    ("impact_rotor", "J: 0.0012 ", "J: 0.0012\n    J_O: 0.002 "),
    ("impact_rotor", "com: 0\n    J: 0.0012 ", "com: 0.1\n    J_O: 0.0012 "),
    ("impact_rotor", "length: 90 mm", "length: 0"),
    ("impact_rotor", "mass: 0.35\n    J: 2.4e-4", "mass: 0\n    J: 0"),
    ("impact_rotor", "mass: 1.2 ", "mass: -1.2 "),
    ("impact_rotor", "drive: {speed: 1500 rpm, direction: ccw}", "drive: {speed: 1500 rpm, moment: 5}"),
    ("impact_rotor", "drive: {speed: 1500 rpm, direction: ccw}", "drive: {speed: -1500 rpm}"),
    ("impact_rotor", "drive: {speed: 1500 rpm, direction: ccw}", "drive: {moment: 5, direction: cw}"),
    ("impact_rotor", "t_end: 40 ms ", "turns: 2\n  t_end: 40 ms "),
    ("impact_rotor", "t_end: 40 ms ", "t_end: -40 ms "),
    ("impact_rotor", "t_end: 40 ms ", "turns: 1\n  t_max: 0 "),
    ("impact_rotor", "samples: 401", "samples: 1"),
    ("impact_rotor", "    psi_dot: 0", "    psi_dot: 0\n    omega: 3"),
    ("impact_rotor", "t_end: 40 ms ", "t_end: abc "),
    ("impact_rotor", "t_end: 40 ms ", "t_end: 40 kg "),
    ("impact_rotor", "t_end: 40 ms ", "t_end: true "),
    ("impact_rotor", "t_end: 40 ms ", "t_end: 1e13 "),
    ("press_drive_train", "{type: planetary, scheme: A}", "{type: planetary}"),
    ("press_drive_train", "{type: pair, z: [18, 36]}", "{type: pair, z: [18, 36], scheme: A}"),
    ("press_drive_train", "{type: planetary, scheme: A}", "{type: planetary, scheme: A, internal: true}"),
    ("press_drive_train", "{type: pair, z: [18, 36]}", "{type: pair, z: [18, 36, 40]}"),
    ("press_drive_train", "{type: planetary, scheme: A}", "{type: planetary, scheme: A, z: [20, 30]}"),
    ("press_drive_train", "{type: pair, z: [18, 36]}", "{type: pair, z: [4, 36]}"),
    ("press_drive_train", "{type: pair, z: [18, 36]}", "{type: pair, z: [18, 36], ratio: -2}"),
    ("press_drive_train", "{type: pair, z: [18, 36]}", "{type: pair, ratio: 0}"),
    ("press_drive_train", "{type: planetary, scheme: A}", "{type: planetary, scheme: Q}"),
    ("press_drive_train", "  satellites: 3\n", "  satellites: 3\n  z_max: 20\n"),
    ("press_drive_train", "{type: pair, z: [18, 36]}", "{type: pair, z: [18, 360]}"),
    ("synthesis_slider_crank", "  H: 0.16\n", ""),
    ("synthesis_crank_rocker", "  frame: 0.4\n", "  frame: 0.4\n  H: 0.1\n"),
    ("synthesis_slider_crank", "  H: 0.16\n", "  H: 0.16\n  e: 0.01\n"),
    ("synthesis_crank_rocker", "  K: 1.2\n", ""),
    ("synthesis_offset_slider_crank", "  e: 50 mm\n", "  e: 50 mm\n  gamma_min: 60\n"),
    ("synthesis_slider_crank", "  H: 0.16\n", "  H: 0.16\n  K: 1.2\n"),
    ("synthesis_slider_crank", "rod: {mass: 5", "rood: {mass: 5"),
    ("synthesis_slider_crank", "rod: {mass: 5", "zzzzz: {mass: 5"),
]


@pytest.mark.parametrize("name, old, new", SECTION_CHECKS)
def test_dof2_drive_train_and_synthesis_checks_are_coded(tmp_path, name, old, new):
    """A broken dof2, drive_train or synthesis section: the English line as on stderr, and in Russian
    and Ukrainian the whole line translated (file, line and field kept, no English reason)."""
    from tmm_cli.errors import TaskError
    from tmm_cli.messages import localize
    text = (_TASKS / f"{name}.yaml").read_text(encoding="utf-8")
    assert old in text
    f = tmp_path / f"{name}.yaml"
    f.write_text(text.replace(old, new, 1), encoding="utf-8")
    with pytest.raises(TaskError) as info:
        tmm_cli.load_task(f)
    english = info.value.render()
    coded = info.value.coded()
    assert coded is not None and str(coded) == english
    where, _, reason = english.partition(": field '")
    reason = reason.split("': ", 1)[1]
    for lang in ("ru", "uk"):
        out = localize(coded.to_dict(), lang)
        assert out.startswith(where + ": ") and reason not in out, (lang, out)
        assert re.search("[а-яіїє]", out.split("»: ", 1)[1]), (lang, out)


@pytest.mark.parametrize("code", ["input.decimal_comma", "input.decimal_comma_value"])
@pytest.mark.parametrize("lang", ["ru", "uk"])
def test_the_decimal_point_asked_for_is_a_point(code, lang):
    """'use a decimal point: 0.35' in ru/uk: the number asked for is not given the decimal comma
    of the language (it read 'use a point: 0,35', the very mistake)."""
    from tmm_cli.messages import render
    text = render(code, {"fixed": "0.35", "given": "0,35"}, lang)
    assert "0.35" in text and "0,35" in text


def test_a_slider_cranks_crank_meant_in_millimetres_is_named(tmp_path):
    """A slider-crank has two lengths: `length: 80` for the crank (meant 80 mm) against a 0.32 m
    rod blamed the rod ('link rod is too short'); one other length is enough to tell the 80
    (250 times it) from the rod, and the message names the crank."""
    text = ("schema: tmm/1\ntitle: t\nmechanism:\n  ground: {O: [0, 0]}\n  links:\n"
            "    crank: {points: [O, A], length: 80}\n    rod: {points: [A, B], length: 0.32}\n"
            "    slider: {slider: B, guide: {through: O, angle: 0}}\ndrive: {link: crank, speed: 150 rpm}\n")
    res, f = _validate(tmp_path, text)
    assert res.exit_code == 2, res.output
    assert "mechanism.links.crank.length" in res.output and "is 250 times the other length (0.32 m)" in res.output
    assert "'80 mm'" in res.output and "Traceback" not in res.output


@pytest.mark.parametrize("law, meant", [("linear", "constant_velocity"), ("cosin", "cosine"), ("Sine", "sine"),
                                        ("harmonic", "cosine")])
def test_a_choice_misspelt_or_by_the_courses_other_name_is_suggested(tmp_path, law, meant):
    """'linear' (the course's name of the constant-velocity law) and 'cosin' listed the seven laws
    with no hint: the choice meant is suggested; nothing is suggested for a word near none."""
    from pathlib import Path
    src = Path(__file__).resolve().parents[1] / "tasks" / "cam_knife.yaml"
    text = src.read_text(encoding="utf-8").replace("return: sine", f"return: {law}")
    res, f = _validate(tmp_path, text)
    assert res.exit_code == 2 and f"did you mean '{meant}'?" in res.output, res.output
    res, f = _validate(tmp_path, text.replace(f"return: {law}", "return: zigzag"))
    assert res.exit_code == 2 and "did you mean" not in res.output


def test_an_unclosed_bracket_names_the_line_it_was_opened_on(tmp_path):
    """YAML notices a '{' left open only on a later line: the error says where it was opened
    (line 2, column 10: `answers: {gears.aw: 1`), not only where it was noticed."""
    from tmm_cli.errors import TaskError
    from tmm_cli.yamlload import load_yaml
    f = tmp_path / "a.yaml"
    f.write_text("variant: 7\nanswers: {gears.aw: 1\nstudent: {name: A}\n", encoding="utf-8")
    with pytest.raises(TaskError) as err:
        load_yaml(f)
    text = err.value.render()
    assert ":3:" in text and "the bracket opened at line 2, column 10 is not closed" in text, text
    f.write_text("variant: 7\nanswers: {gears.aw: 1 2: 3}\n", encoding="utf-8")     # noticed on its own line
    with pytest.raises(TaskError) as err:
        load_yaml(f)
    assert "bracket opened" not in err.value.render()
