"""One grammar for every number a user writes (tmm_cli/numbers.py): task files, variants
tables and students' answers read numbers and units alike; what is not a number is
refused with its reason, never coerced and never evaluated."""
from __future__ import annotations

import csv
import math
import subprocess
import sys
from decimal import Decimal
from pathlib import Path

import pytest
import yaml
from hypothesis import given, settings
from hypothesis import strategies as st
from typer.testing import CliRunner

import tmm_cli
from tmm_cli.check import answer_value
from tmm_cli.cli import app
from tmm_cli.numbers import read
from tmm_cli.tables import cell_value, read_table
from tmm_cli.units import convert, quantity

runner = CliRunner()
RPM = 2 * math.pi / 60
OMEGA = "kinematics[1].links.crank.omega"

# ------------------------------------------------------------------ the grammar, table-driven
# text -> (value as written, unit expression)
VALID = [
    ("0.59", 0.59, ""), ("0,59", 0.59, ""), ("-0,59", -0.59, ""), ("\u22120,59", -0.59, ""),
    ("+5", 5.0, ""), (".5", 0.5, ""), (",5", 0.5, ""), ("5.", 5.0, ""),
    ("1 234,5", 1234.5, ""), ("12 435", 12435.0, ""), ("\u2212508,7", -508.7, ""),
    ("1\u00a0234\u00a0567,25", 1234567.25, ""), ("1\u202f234.5", 1234.5, ""), ("100 000", 100000.0, ""),
    ("1e-3", 1e-3, ""), ("1,2E3", 1200.0, ""), ("1,2\u00b710\u207b\u00b3", 1.2e-3, ""),
    ("8,9\u00b710\u207b\u00b9\u2076", 8.9e-16, ""), ("1,2 \u00d7 10^-3", 1.2e-3, ""), ("1.2*10**3", 1200.0, ""),
    ("2,5\u00b710^(\u22122)", 0.025, ""), ("1/18", 1 / 18, ""),
    ("300 mm", 300.0, "mm"), ("300mm", 300.0, "mm"), ("300 \u043c\u043c", 300.0, "mm"),
    ("5 \u0441\u043c", 5.0, "cm"), ("2 \u043c", 2.0, "m"), ("1,5 \u043a\u0433", 1.5, "kg"),
    ("40 \u0433", 40.0, "g"), ("12 \u041d", 12.0, "N"), ("3 \u043a\u041d", 3.0, "kN"),
    ("5 \u041d\u00b7\u043c", 5.0, "N*m"), ("5 \u041d*\u043c", 5.0, "N*m"), ("5 \u041d\u043c", 5.0, "N*m"),
    ("5 Nm", 5.0, "N*m"), ("2 \u043a\u041d\u00b7\u043c", 2.0, "kN*m"),
    ("0,15 \u043a\u0433\u00b7\u043c\u00b2", 0.15, "kg*m**2"), ("0,15 \u043a\u0433*\u043c^2", 0.15, "kg*m**2"),
    ("0.15 kg*m^2", 0.15, "kg*m**2"), ("0.15 kg m**2", 0.15, "kg*m**2"),
    ("120 \u043e\u0431/\u043c\u0438\u043d", 120.0, "rpm"), ("120 \u043e\u0431/\u0445\u0432", 120.0, "rpm"), ("3 \u0440\u0430\u0434/\u0441", 3.0, "rad/s"),
    ("2 \u043c/\u0441", 2.0, "m/s"), ("9,81 \u043c/\u0441\u00b2", 9.81, "m/s**2"),
    ("4 \u0440\u0430\u0434/\u0441\u00b2", 4.0, "rad/s**2"), ("12,57 \u0441\u207b\u00b9", 12.57, "1/s"),
    ("120 \u043c\u0438\u043d\u207b\u00b9", 120.0, "1/min"), ("120 min^-1", 120.0, "1/min"),
    ("120 1/min", 120.0, "1/min"), ("2 Hz", 2.0, "Hz"), ("30 \u0433\u0440\u0430\u0434", 30.0, "degree"),
    ("30 grad", 30.0, "degree"), ("30\u00b0", 30.0, "degree"), ("30 \u00b0", 30.0, "degree"),
    ("2 %", 2.0, "percent"), ("\u22125,6 rpm", -5.6, "rpm"), ("1 234,5 mm", 1234.5, "mm"),
]

# text -> the reason's code
INVALID = [
    ("\u22480,59", "input.number_prefix"), ("~0.6", "input.number_prefix"),
    ("\u043e\u043a\u043e\u043b\u043e 0,6", "input.number_prefix"), ("about 5 mm", "input.number_prefix"),
    ("0,59 \u00b1 0,02", "input.number_plus_minus"), ("0,59\u00b10,02", "input.number_plus_minus"),
    ("0.59 +/- 0.02", "input.number_plus_minus"),
    ("1,2,3", "input.number_marks"), ("0.5.9", "input.number_marks"), ("1.000.000", "input.number_marks"),
    ("1 23,4", "input.number_groups"), ("12 43", "input.number_groups"), ("1234 567", "input.number_groups"),
    ("9**9**9", "input.number_expression"), ("9**9**9 rpm", "input.number_expression"),
    ("2*3", "input.number_expression"), ("1+2", "input.number_expression"), ("2^10", "input.number_expression"),
    ("3 (m)", "input.number_expression"), ("1.2*10^(3", "input.number_expression"),
    ("216 kg m23", "input.number_unit_syntax"), ("3 m^2^3", "input.number_unit_syntax"),
    ("3 m**2**2", "input.number_unit_syntax"), ("3 m^99", "input.number_unit_syntax"),
    ("3 m/s/s", "input.number_unit_syntax"), ("5 \u043f\u043e\u043f\u0443\u0433\u0430\u0435\u0432", "input.number_unit_unknown"),
    ("abc", "input.number_not_number"), ("mm", "input.number_not_number"), ("5,", "input.number_not_number"),
    ("1_000", "input.number_not_number"), ("-", "input.number_not_number"), ("", "input.number_not_number"),
    ("1" * 200, "input.number_not_number"), ("\u20135", "input.number_dash"), ("nan", "input.not_finite"),
    # Word's ordinal indicator, a ring above, a superscript o: not the degree sign, and told so
    ("182,14\u00ba", "input.number_not_degree"), ("90\u02da", "input.number_not_degree"),
    ("90 \u1d52", "input.number_not_degree"),
]


@pytest.mark.parametrize("text,value,unit", VALID)
def test_valid_numbers_read_exactly(text, value, unit):
    r = read(text, answer=True)
    assert r.value == value and r.expression == unit, (text, r)


@pytest.mark.parametrize("text,code", INVALID)
def test_what_is_not_a_number_is_refused_with_its_reason(text, code):
    with pytest.raises(ValueError) as err:
        read(text)
    assert err.value.args[0].code == code, (text, str(err.value.args[0]))


def test_a_dash_is_a_minus_in_answers_only():
    assert read("\u20130,59", answer=True).value == -0.59
    with pytest.raises(ValueError):
        read("\u20130,59")


# ------------------------------------------------------------------ round trip
def _fixed(x: float) -> str:
    """x's shortest digits written without an exponent."""
    return format(Decimal(repr(x)), "f")


def _grouped(digits: str, sep: str) -> str:
    out = ""
    while len(digits) > 3:
        digits, out = digits[:-3], sep + digits[-3:] + out
    return digits + out


def _spellings(x: float) -> list[str]:
    """x written in every way the grammar reads, each exactly x."""
    sign, mag = ("-" if math.copysign(1, x) < 0 else ""), abs(x)
    text = _fixed(mag)
    whole, _, frac = text.partition(".")
    exp = int(f"{mag:e}".partition("e")[2])
    mant = format(Decimal(repr(mag)).scaleb(-exp), "f")
    sup = str(exp).translate(str.maketrans("-0123456789", "\u207b\u2070\u00b9\u00b2\u00b3\u2074\u2075\u2076\u2077"
                                                         "\u2078\u2079"))
    out = [repr(x), sign + text, sign + text.replace(".", ","), "\u2212" + text.replace(".", ",") if sign else text,
           f"{sign}{mant}e{exp}", f"{sign}{mant.replace('.', ',')}\u00b710{sup}", f"{sign}{mant}*10^{exp}"]
    for sep in (" ", "\u00a0", "\u202f"):
        out.append(sign + _grouped(whole, sep) + ("," + frac if frac else ""))
    return out


@settings(max_examples=300, deadline=None)
@given(st.floats(min_value=-1e12, max_value=1e12, allow_nan=False).filter(lambda v: v == 0 or abs(v) > 1e-30))
def test_round_trip_in_every_spelling(x):
    for text in _spellings(x):
        got = read(text).value
        assert got == x, (x, text, got)
        assert read(text + " mm").value == x
        assert convert(text + " \u043c\u043c", "length") == x * 0.001


# ------------------------------------------------------------------ bounded work
def test_an_exponent_of_an_exponent_never_reaches_pint(monkeypatch):
    """'9**9**9 rpm' hung validate, run, check and batch (pint computed the power as an
    integer): it is refused by the grammar, before any unit is looked at."""
    import tmm_cli.numbers as numbers

    def boom(*a, **k):
        raise AssertionError("pint reached")
    monkeypatch.setattr(numbers, "ureg", boom)
    monkeypatch.setattr(numbers, "_pint_factor", boom)
    monkeypatch.setattr(numbers, "_pint_base", boom)
    for text in ("9**9**9 rpm", "9**9**9", "9^9^9 rpm", "2 rpm**9**9", "2 m^9^9", "10**10**10 mm"):
        with pytest.raises(ValueError) as err:
            convert(text, "speed")
        assert err.value.args[0].code.startswith("input.number_"), text
        with pytest.raises(ValueError):
            answer_value(text, OMEGA)


def test_an_exponent_of_an_exponent_in_a_task_is_exit_2(tmp_path):
    f = tmp_path / "t.yaml"
    f.write_text("schema: tmm/1\nmechanism:\n  ground: {O: [0, 0]}\n  links:\n"
                 "    crank: {points: [O, A], length: 0.1}\n    rod: {points: [A, B], length: 0.4}\n"
                 "    slider: {slider: B, guide: {through: O, angle: 0}}\n"
                 "drive: {link: crank, speed: '9**9**9 rpm'}\n", encoding="utf-8")
    res = subprocess.run([sys.executable, "-m", "tmm_cli", "validate", str(f)], capture_output=True, text=True,
                         timeout=60)
    assert res.returncode == 2, res.stdout + res.stderr
    assert f"{f}:8:" in res.stderr and "drive.speed" in res.stderr and "expression" in res.stderr
    assert "Traceback" not in res.stderr


def test_plain_and_course_units_validate_without_pint():
    code = ("import sys, tmm_cli\n"
            "t = tmm_cli.load_task({'schema': 'tmm/1', 'mechanism': {'ground': {'O': [0, 0]}, 'links': {"
            "'crank': {'points': ['O', 'A'], 'length': '100 \u043c\u043c', 'mass': '1,5 \u043a\u0433'},"
            "'rod': {'points': ['A', 'B'], 'length': '1 234,5 mm'},"
            "'slider': {'slider': 'B', 'guide': {'through': 'O', 'angle': '\u22125'}}}},"
            "'drive': {'link': 'crank', 'speed': '120 \u043e\u0431/\u043c\u0438\u043d'}})\n"
            "assert 'pint' not in sys.modules, 'pint imported'\n"
            "print(t.mechanism.links['rod'].length)\n")
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert res.returncode == 0, res.stderr
    assert res.stdout.strip() == "1.2345"


# ------------------------------------------------------------------ task files
def _task(speed="100 rpm", **extra):
    t = {"schema": "tmm/1", "mechanism": {"ground": {"O": [0, 0]}, "links": {
        "crank": {"points": ["O", "A"], "length": 0.1},
        "rod": {"points": ["A", "B"], "length": 0.4},
        "slider": {"slider": "B", "guide": {"through": "O", "angle": 0}}}},
        "drive": {"link": "crank", "speed": speed}}
    t.update(extra)
    return t


@pytest.mark.parametrize("speed, omega, code", [
    ("120 min^-1", 4 * math.pi, "input.reading_per_min"), ("120 1/min", 4 * math.pi, "input.reading_per_min"),
    ("120 \u043c\u0438\u043d\u207b\u00b9", 4 * math.pi, "input.reading_per_min"),
    ("2 Hz", 4 * math.pi, "input.reading_hz"), ("12,57 s^-1", 12.57, "input.reading_per_s"),
    ("12,57 1/s", 12.57, "input.reading_per_s"), ("12,57 \u0441\u207b\u00b9", 12.57, "input.reading_per_s"),
])
def test_frequency_units_of_a_speed_read_as_the_course_does(speed, omega, code):
    """n = 120 min^-1 is 120 rpm (pint's 1/min has no 2 pi: every velocity was off by
    2 pi); Hz is rev/s; s^-1 of an angular velocity is rad/s. Each stated as a warning."""
    t = tmm_cli.load_task(_task(speed))
    assert t.drive.speed == pytest.approx(omega, rel=1e-15)
    assert [m.code for m in t.input_warnings] == [code]
    assert "drive.speed" in t.input_warnings[0]
    assert tmm_cli.load_task(_task("120 min^-1")).drive.speed == tmm_cli.load_task(_task("120 rpm")).drive.speed


def test_a_reading_is_stated_once_naming_every_field():
    task = _task("120 rpm", positions={"extra": ["30 grad", "45 grad"]})
    task["mechanism"]["links"]["slider"]["guide"]["angle"] = "10 grad"
    t = tmm_cli.load_task(task)
    grads = [m for m in t.input_warnings if m.code == "input.reading_grad"]
    assert len(grads) == 1, t.input_warnings
    assert "mechanism.links.slider.guide.angle" in grads[0] and "positions.extra[1]" in grads[0]
    assert "gon" in grads[0]
    # the Cyrillic word: degrees as every course book writes it, nothing to say
    cyr = _task("120 rpm", positions={"extra": ["30 \u0433\u0440\u0430\u0434"]})
    cyr["mechanism"]["links"]["slider"]["guide"]["angle"] = "10 \u0433\u0440\u0430\u0434."
    t = tmm_cli.load_task(cyr)
    assert t.positions.extra[0] == 30.0 and not [m for m in t.input_warnings if m.code == "input.reading_grad"]


def test_grad_is_degrees_and_gon_gradians():
    assert convert("90 grad", "angle") == 90.0
    assert convert("90 \u0433\u0440\u0430\u0434", "angle") == 90.0
    assert convert("100 gon", "angle") == pytest.approx(90.0, rel=1e-15)


def test_cyrillic_task_equals_the_latin_one():
    cyr = _task("120 \u043e\u0431/\u043c\u0438\u043d")
    cyr["mechanism"]["links"]["crank"].update(length="100 \u043c\u043c", mass="1,5 \u043a\u0433",
                                               J="0,02 \u043a\u0433\u00b7\u043c\u00b2")
    lat = _task("120 rpm")
    lat["mechanism"]["links"]["crank"].update(length="100 mm", mass="1.5 kg", J="0.02 kg*m^2")
    assert tmm_cli.load_task(cyr).model_dump() == tmm_cli.load_task(lat).model_dump()
    assert tmm_cli.load_task(cyr).input_warnings == []


@pytest.mark.parametrize("value, frag", [
    ("\u22480,1 m", "begins with '\u2248'"), ("0,1 \u00b1 0,01 m", "not one number"),
    ("1,2,3", "more than one decimal mark"), ("1 23,4 mm", "grouped by spaces in threes"),
    ("\u20130,1", "a dash is not a minus sign"), ("0,1 kg m23", "cannot read the unit"),
])
def test_not_a_number_in_a_task_file_is_exit_2_naming_line_and_field(tmp_path, value, frag):
    f = tmp_path / "t.yaml"
    f.write_text(yaml.safe_dump(_task(), sort_keys=False).replace("length: 0.1", f"length: '{value}'"),
                 encoding="utf-8")
    line = next(i for i, s in enumerate(f.read_text(encoding="utf-8").splitlines(), 1) if value in s)
    res = runner.invoke(app, ["validate", str(f)])
    assert res.exit_code == 2, res.output
    assert f"{f}:{line}:" in res.output and "mechanism.links.crank.length" in res.output and frag in res.output
    assert "Traceback" not in res.output


def test_a_frequency_for_a_speed_is_refused():
    for text in ("120 kHz", "3 1/h"):
        with pytest.raises(ValueError) as err:
            convert(text, "speed")
        assert err.value.args[0].code == "input.number_frequency"


def test_grouped_thousands_and_unicode_minus_in_task_fields():
    assert convert("1 234,5 mm", "length") == 1.2345
    assert convert("\u2212508,7", "force") == -508.7
    assert convert("12 435 N", "force") == 12435.0
    assert quantity("0,5 MPa", "force_or_pressure") == (500000.0, [], "pressure")


# ------------------------------------------------------------------ answers
@pytest.mark.parametrize("text, path, value", [
    ("1 234,5", "flywheel.J", 1234.5), ("12 435", "flywheel.J", 12435.0),
    ("\u2212508,7", "kinetostatics[1].balancing_moment", -508.7), ("\u22120,59", "kinematics[1].points.B.v", -0.59),
    ("\u20130,59", "kinematics[1].points.B.v", -0.59), ("\u22125,6 rpm", OMEGA, -5.6 * RPM),
    ("3,04 \u0440\u0430\u0434/\u0441", OMEGA, 3.04), ("12,57 \u0441\u207b\u00b9", OMEGA, 12.57),
    ("120 \u043c\u0438\u043d\u207b\u00b9", OMEGA, 120 * RPM), ("120 min^-1", OMEGA, 120 * RPM),
    ("2 Hz", OMEGA, 4 * math.pi), ("0,67 \u043c/\u0441", "kinematics[1].points.B.v", 0.67),
    ("3 \u043c/\u0441\u00b2", "kinematics[1].points.B.a", 3.0),
    ("5 \u0440\u0430\u0434/\u0441\u00b2", "kinematics[1].links.rod.epsilon", 5.0),
    ("216 \u043a\u0433\u00b7\u043c\u00b2", "flywheel.J", 216.0), ("216 \u043a\u0433*\u043c^2", "flywheel.J", 216.0),
    ("1,5 \u043a\u041d\u00b7\u043c", "kinetostatics[1].balancing_moment", 1500.0),
    ("336 \u041d", "kinetostatics[1].reactions.R12.R", 336.0), ("84,83 \u043c\u043c", "gears.aw", 0.08483),
    ("12 \u0433\u0440\u0430\u0434", "positions.phi0", 12.0), ("12\u00b0", "positions.phi0", 12.0),
    ("1,2\u00b710\u207b\u00b3", "flywheel.delta", 1.2e-3),
    # the second shortened as texts still write it: рад/сек, м/сек
    ("1,335 \u0440\u0430\u0434/\u0441\u0435\u043a", OMEGA, 1.335),
    ("0,304 \u043c/\u0441\u0435\u043a", "kinematics[1].points.B.v", 0.304),
])
def test_answers_read_as_students_write_them(text, path, value):
    assert answer_value(text, path) == pytest.approx(value, rel=1e-15)


@pytest.mark.parametrize("text, code", [
    ("\u22480,59", "input.number_prefix"), ("0,59 \u00b1 0,02", "input.number_plus_minus"),
    ("\u043e\u043a\u043e\u043b\u043e 0,6", "input.number_prefix"), ("1,2,3", "input.number_marks"),
    ("0.5.9", "input.number_marks"), ("1 23,4", "input.number_groups"), ("9**9**9", "input.number_expression"),
    ("216 kg m23", "input.number_unit_syntax"), ("0,67 \u043a\u0433", "answers.wrong_unit"),
])
def test_answers_that_are_not_numbers_give_the_reason(text, code):
    path = "flywheel.J" if "kg" in text else "kinematics[1].points.B.v"
    with pytest.raises(ValueError) as err:
        answer_value(text, path)
    assert err.value.args[0].code == code


# ------------------------------------------------------------------ tables
def test_cells_read_by_the_grammar():
    assert cell_value("1 234,5") == 1234.5 and cell_value("12 435") == 12435 and cell_value("\u22121,5") == -1.5
    assert cell_value("07") == 7 and cell_value("0,12") == 0.12 and cell_value("1e3") == 1000.0
    for text in ("1,2,3", "0.5.9", "1 23,4", "\u22480,59", "\u0418\u0432\u0430\u043d\u043e\u0432", "1/18", "12 mm"):
        assert cell_value(text) == text


def _write_csv(path: Path, header: list[str], rows: list[list], sep=";"):
    with open(path, "w", encoding="utf-8-sig", newline="") as fh:
        w = csv.writer(fh, delimiter=sep)
        w.writerow(header)
        w.writerows(rows)
    return path


TEMPLATE = """schema: tmm/1
title: "Variant {variant}"
mechanism:
  ground: {O: [0, 0]}
  links:
    crank: {points: [O, A], length: "{l_OA}", mass: "{m}"}
    rod: {points: [A, B], length: "{l_AB}"}
    slider: {slider: B, guide: {through: [0, 0], angle: 0}}
  assembly: {B: [0.3, 0]}
drive: {link: crank, speed: "{n}", direction: ccw}
loads:
  forces:
    - {on: slider, kind: resistance, magnitude: "{F}"}
"""


# Variant; l_OA, mm; l_AB, mm; m, kg; n, rpm; F, kN -- in Russian
VARIANT_HEADER = ["\u0412\u0430\u0440\u0438\u0430\u043d\u0442", "l_OA, \u043c\u043c", "l_AB, \u043c\u043c",
                  "m, \u043a\u0433", "n, \u043e\u0431/\u043c\u0438\u043d", "F, \u043a\u041d"]


def test_variants_table_with_cyrillic_headers_and_units(tmp_path):
    tpl = tmp_path / "tpl.yaml"
    tpl.write_text(TEMPLATE, encoding="utf-8")
    tab = _write_csv(tmp_path / "t.csv", VARIANT_HEADER, [["1", "100", "400", "1,5", "120", "1 234,5"],
                                                  ["2", "110", "420", "2", "1 440", "2,5"]])
    res = runner.invoke(app, ["variants", str(tpl), str(tab), "--out", str(tmp_path / "o")])
    assert res.exit_code == 0, res.output
    t1 = tmm_cli.load_task(tmp_path / "o" / "1.yaml")
    assert t1.variant == 1 and t1.mechanism.links["crank"].length == 0.1
    assert t1.mechanism.links["crank"].mass == 1.5 and t1.drive.speed == 120 * RPM
    assert t1.loads.forces[0].magnitude == 1234500.0
    t2 = tmm_cli.load_task(tmp_path / "o" / "2.yaml")
    assert t2.drive.speed == 1440 * RPM


def test_headers_in_russian_and_ukrainian_are_aliases():
    for word, name in (("\u0412\u0430\u0440\u0438\u0430\u043d\u0442", "variant"),
                       ("\u0412\u0430\u0440\u0456\u0430\u043d\u0442", "variant"),
                       ("\u0421\u0442\u0443\u0434\u0435\u043d\u0442", "student"),
                       ("\u0413\u0440\u0443\u043f\u043f\u0430", "group"), ("\u0413\u0440\u0443\u043f\u0430", "group")):
        from tmm_cli.numbers import header_name
        assert header_name(f" {word} ") == name and header_name(word.upper()) == name


def test_answers_table_with_cyrillic_headers_and_numbers(tmp_path):
    from tmm_cli.check import load_answers_csv
    header = ["\u0421\u0442\u0443\u0434\u0435\u043d\u0442", "\u0413\u0440\u0443\u043f\u043f\u0430",
              "\u0412\u0430\u0440\u0438\u0430\u043d\u0442", "flywheel.J", OMEGA]
    tab = _write_csv(tmp_path / "a.csv", header, [["Ivanov", "MT-31", "7", "1 234,5", "3,04 \u0440\u0430\u0434/\u0441"],
                                                  ["Petrov", "MT-31", "8", "\u2212508,7", "120 \u043c\u0438\u043d\u207b\u00b9"]])
    assert read_table(tab)[0][:3] == ["student", "group", "variant"]
    sets = load_answers_csv(tab)
    assert [(s.student, s.group, s.variant) for s in sets] == [("Ivanov", "MT-31", 7), ("Petrov", "MT-31", 8)]
    assert sets[0].answers == {"flywheel.J": 1234.5, OMEGA: 3.04}
    assert sets[1].answers["flywheel.J"] == -508.7 and sets[1].answers[OMEGA] == pytest.approx(4 * math.pi)
    assert all(s.error is None for s in sets)


def test_plain_number_fields_read_by_the_grammar():
    """A field without a unit (gears.x) reads a string as the grammar does; a unit there, or
    what is not a number, is the field's error with the reason."""
    t = tmm_cli.load_task({"schema": "tmm/1", "gears": {"m": "4 \u043c\u043c", "z": [14, 30],
                                                        "x": ["0,3", "\u22120,1"]}})
    assert t.gears.x == (0.3, -0.1) and t.gears.m == 0.004
    with pytest.raises(tmm_cli.TaskError) as err:
        tmm_cli.load_task({"schema": "tmm/1", "gears": {"m": 0.004, "z": [14, 30], "x": ["0,3 mm", "1,2,3"]}})
    text = str(err.value.render())
    assert "gears.x[0]" in text and "gears.x[1]" in text and "more than one decimal mark" in text


def test_check_refuses_an_exponent_of_an_exponent_at_once(tmp_path):
    """As a student's answer '9**9**9' hung `check` (pint computed the power): now it is that
    answer's status `invalid` with the reason (the other answers graded as usual), and `check`
    ends at once (exit 1: not every answer within tolerance)."""
    t = tmp_path / "g.yaml"
    t.write_text("schema: tmm/1\nvariant: 7\ngears: {m: 4 mm, z: [14, 30], x: [0.3, 0.1]}\n", encoding="utf-8")
    ans = tmp_path / "a.yaml"
    ans.write_text("variant: 7\nanswers:\n  gears.aw: '9**9**9 mm'\n", encoding="utf-8")
    res = subprocess.run([sys.executable, "-m", "tmm_cli", "check", str(t), "--answers", str(ans),
                          "--out", str(tmp_path / "c")], capture_output=True, text=True, timeout=120)
    out = res.stdout + res.stderr
    assert res.returncode == 1, out
    assert "gears.aw" in out and "invalid" in out and "expression" in out and "Traceback" not in out


def test_variants_cell_that_is_not_a_number_gives_the_reason(tmp_path):
    tpl = tmp_path / "tpl.yaml"
    tpl.write_text(TEMPLATE, encoding="utf-8")
    tab = _write_csv(tmp_path / "t.csv", VARIANT_HEADER, [["1", "1,2,3", "400", "1,5", "120", "1"],
                                                  ["2", "110", "420", "\u22482", "120", "1"],
                                                  ["3", "110", "420", "2", "120", "1"]])
    res = runner.invoke(app, ["variants", str(tpl), str(tab), "--out", str(tmp_path / "o")])
    assert res.exit_code == 2
    assert f"{tab}:2: variant 1: column l_OA, \u043c\u043c: '1,2,3' is not a number: it has more than one " \
           "decimal mark" in res.output, res.output
    assert f"{tab}:3: variant 2: column m, \u043a\u0433: '\u22482' is not a number: it begins with" in res.output
    assert (tmp_path / "o" / "3.yaml").is_file() and not (tmp_path / "o" / "1.yaml").exists()


@settings(max_examples=1500, deadline=None)
@given(st.text(alphabet="0123456789 .,-+eE*/^()\u00b1\u2248~\u2212\u2013\u00b7\u00d7\u00b2\u207b\u00b9\u00b0%"
                        "mskgNhinrpdaz\u043c\u0441\u043a\u0433\u041d\u0438\u043d\u00a0\u202f", max_size=30))
def test_any_text_is_a_number_or_a_reason(text):
    """Whatever the text, the grammar gives a reading or a ValueError carrying a catalogue
    Message -- no other exception, no evaluation; a reading holds a finite number or one
    beyond the float range written as digits, and its unit only checked names (one-digit
    powers, added up where a name repeats)."""
    from tmm_cli.messages import Message
    try:
        r = read(text, answer=True)
    except ValueError as exc:
        assert isinstance(exc.args[0], Message), (text, exc)
        return
    assert isinstance(r.value, float)
    assert all(isinstance(n, str) and 0 < abs(p) <= 9 * 25 and p != 0 for n, p in r.unit), (text, r)


def test_variants_column_unit_that_is_no_unit_stops_before_anything_is_written(tmp_path):
    """A header unit tmm cannot read ('l_OA, parrots') made every row fail with the same
    message; it is one error naming the column, exit 2, nothing written."""
    tpl = tmp_path / "tpl.yaml"
    tpl.write_text(TEMPLATE, encoding="utf-8")
    header = list(VARIANT_HEADER)
    header[1] = "l_OA, \u043f\u043e\u043f\u0443\u0433\u0430\u0438"
    tab = _write_csv(tmp_path / "t.csv", header, [["1", "100", "400", "1,5", "120", "1"],
                                                  ["2", "110", "420", "2", "120", "1"]])
    res = runner.invoke(app, ["variants", str(tpl), str(tab), "--out", str(tmp_path / "o")])
    assert res.exit_code == 2, res.output
    assert f"{tab}:1:2:" in res.output and "\u043f\u043e\u043f\u0443\u0433\u0430\u0438" in res.output
    assert res.output.count("not a unit tmm knows") == 1, res.output
    assert not (tmp_path / "o" / "1.yaml").exists()


def test_a_unit_typed_in_latin_letters_drawn_as_cyrillic_ones_is_told_so():
    """'13,1 H': the Latin H is the henry, not the newton's Cyrillic Н; the answer is invalid
    (never coerced) and the reason says which letters to type; a unit that is simply another
    quantity's is told as before, its target unit in the page's language (Н, not N)."""
    from tmm_cli.check import answer_value
    from tmm_cli.messages import localize
    path = "kinetostatics[1].reactions.R03.R"
    with pytest.raises(ValueError) as info:
        answer_value("13,1 H", path)
    m = info.value.args[0]
    assert m.code == "answers.wrong_unit_latin" and m.params["cyr"] == "\u041d"
    assert answer_value("13,1 \u041d", path) == pytest.approx(13.1)          # as the hint says
    with pytest.raises(ValueError) as info:
        answer_value("13,1 kg", path)
    m = info.value.args[0]
    assert m.code == "answers.wrong_unit"
    assert localize(m.to_dict(), "ru").endswith("\u043d\u0435 \u043f\u0440\u0438\u0432\u043e\u0434\u0438\u0442\u0441\u044f \u043a \u041d")


def test_an_answer_to_a_path_of_unknown_unit_is_read_in_a_course_quantitys_unit():
    """A path the answers reader knows no unit of (positions.H) takes an answer in SI base units
    -- of a course quantity's unit only: '5 MM' (pint's megamolar) was read as 5e9 and graded;
    now it is invalid, with the reason. '160 mm', '3 W' read as before."""
    from tmm_cli.check import answer_value
    assert answer_value("160 mm", "positions.H") == pytest.approx(0.16)
    assert answer_value("3 kW", "drive_train.motor_power") == pytest.approx(3000.0)
    with pytest.raises(ValueError) as info:
        answer_value("5 MM", "positions.H")
    assert info.value.args[0].code == "answers.unit_not_course"


@pytest.mark.parametrize("text, value, expression", [
    ("0,08 \u043a\u0433\u00b7\u043c2", 0.08, "kg*m**2"), ("9,81 \u043c/\u04412", 9.81, "m/s**2"),
    ("78,5 \u043c\u043c2", 78.5, "mm**2"), ("7800 \u043a\u0433/\u043c3", 7800.0, "kg/m**3"),
    ("216 kg m2", 216.0, "kg*m**2")])
def test_a_power_typed_as_a_plain_digit_after_the_unit(text, value, expression):
    """'kg*m2', 'm/s2', 'mm2', 'kg/m3' as students type them (no caret, no superscript): a 2 or 3
    right after a unit's name is its power (no unit's name ends in a digit); 'm23' is no unit."""
    from tmm_cli.numbers import read
    r = read(text)
    assert (r.value, r.expression) == (value, expression)


@pytest.mark.parametrize("text", ["30\u00b02", "40 \u0433\u0440\u0430\u04342", "5 %2", "5 rpm2", "5 Hz2"])
def test_a_bare_power_follows_a_length_or_the_second_only(text):
    """'30°2' (a minute mark left off) was read as a squared degree, 0.52 deg, silently (a 3 m
    cam): a bare 2 or 3 is a power after a length or the second only; elsewhere the unit is
    refused as before."""
    from tmm_cli.numbers import read
    with pytest.raises(ValueError):
        read(text)


def test_a_yes_no_answer_is_no_number(tmp_path):
    """YAML's true and false are not read as 1 and 0: the answer is invalid, its reason says why
    (never coerced)."""
    for v in (True, False):
        with pytest.raises(ValueError) as err:
            answer_value(v, "positions.H")
        assert err.value.args[0].code == "answers.not_number_bool"
        assert str(err.value.args[0]).startswith(f"{str(v).lower()} is a yes/no value")


def test_a_rockers_swing_answered_in_degrees_is_read_in_degrees():
    """positions.H is the output's stroke: metres for a slider, degrees for a rocker's swing
    (results.json holds every angle in degrees). An answer with an angle unit is read in degrees:
    '45,6\u00b0' was read as 0.796 (radians, SI's base) and graded outside against 45.59; one with a
    length unit in metres; a frequency stays what it was (no angle)."""
    from tmm_cli.check import AnswerSet, grade
    assert answer_value("45,6\u00b0", "positions.H") == pytest.approx(45.6)
    assert answer_value("45,6 \u0433\u0440\u0430\u0434", "positions.H") == pytest.approx(45.6)
    assert answer_value("0,8 rad", "positions.H") == pytest.approx(0.8 * 180 / math.pi)
    assert answer_value("90 \u043c\u043c", "positions.H") == pytest.approx(0.09)
    assert answer_value("5 rpm", "positions.H") == pytest.approx(5 * math.pi / 30)
    aset = AnswerSet(source="a.yaml", answers={"positions.H": answer_value("45,6\u00b0", "positions.H")})
    rows = grade({"positions": {"H": 45.59113734524769, "output_kind": "rocker"}}, aset, {})
    assert rows[0]["status"] == "ok"
