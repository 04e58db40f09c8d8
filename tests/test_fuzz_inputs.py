"""No input produces a traceback, a NaN or a wrong exit code (SPEC 2, SPEC 3, SPEC 4).

The contract: bad input gets a TaskError naming the field (and, for a file, the line),
exit 2; a valid task that cannot be computed gets a StageError naming the stage, exit 3;
results never hold NaN/inf. Three layers:

1. property tests (hypothesis, bounded and derandomised so CI sees the same examples):
   the example tasks of ``tasks/`` mutated structurally (a key deleted or renamed, a value
   replaced by a wrong type, a wrong unit, a negative, zero, huge or empty value, a link
   duplicated, a reference pointed at a missing name, two points swapped), through
   ``tmm_cli.load_task`` + ``tmm_cli.run``, as a dict and as a file; and YAML garbage;
2. command-line checks (exit codes 2 / 3, no "Traceback");
3. regression examples for every defect the fuzzing found, each failing before its fix.

``TMM_FUZZ_SCALE=10 python -m pytest tests/test_fuzz_inputs.py`` runs ten times the
examples (random, not derandomised) for a deeper local search.
"""
from __future__ import annotations

import copy
import json
import math
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest
import yaml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from typer.testing import CliRunner

import tmm_cli
from tmm_cli.cli import app
from tmm_cli.errors import StageError, TaskError
from tmm_cli.results import parse_path
from tmm_cli.yamlload import load_yaml

ROOT = Path(__file__).resolve().parents[1]
runner = CliRunner()

SCALE = int(os.environ.get("TMM_FUZZ_SCALE", "1"))


def fuzz(n: int) -> settings:
    """Bounded hypothesis settings: ``n`` examples (times TMM_FUZZ_SCALE), no deadline."""
    return settings(max_examples=n * SCALE, deadline=None, database=None, derandomize=SCALE == 1,
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])


def _examples() -> dict[str, dict]:
    """The example tasks of tasks/ that load (a task of a section still being written by
    someone else is left out: test_examples covers the examples themselves)."""
    out = {}
    for f in sorted((ROOT / "tasks").glob("*.yaml")):
        try:
            tmm_cli.load_task(f)
        except TaskError:
            continue
        out[f.name] = load_yaml(f)[0]
    return out


TASKS = _examples()
NAMES = sorted(TASKS)

# stages whose failures must read as a course statement, not a wrapped Python exception
LINKAGE_STAGES = {"structure", "positions", "kinematics", "kinetostatics", "loads"}
_WRAPPED = re.compile(r"^(\w+Error|\w+Exception): ")


# ---------------------------------------------------------------- mutations
def _paths(obj, p=()):
    yield p
    if isinstance(obj, dict):
        for k, v in obj.items():
            yield from _paths(v, p + (k,))
    elif isinstance(obj, list):
        for i, v in enumerate(obj):
            yield from _paths(v, p + (i,))


def _get(obj, path):
    for k in path:
        obj = obj[k]
    return obj


def _names(d) -> list[str]:
    """Every key and string value of the task: the names a reference may point at."""
    out = set()
    for p in _paths(d):
        if p and isinstance(p[-1], str):
            out.add(p[-1])
        v = _get(d, p)
        if isinstance(v, str):
            out.add(v)
    return sorted(out)


BAD_VALUES = [
    None, [], {}, "", "abc", True, [1], [1, 2, 3], ["x", "y"], {"a": 1},        # wrong types
    "5 kg", "3 rpm", "10 MPa", "20 deg", "0.15 kg*m^2", "12 furlongz",          # wrong / unknown units
    -1, -0.5, 0, 0.0, "0 mm", "-3 mm",                                         # negative, zero
    1e300, -1e300, 1e20, 10 ** 30, "1e400", "1e400 mm", 1e-300,                 # huge, tiny
    "nan", ".nan", "inf", "-inf", "nan mm",                                     # not finite
    "1/0", "0/0", "1/18", 360, 720, 3600, 1.5, 2,                               # fractions, round numbers
    [0, 0], "O", "A", "crank", "slider",                                       # names out of place
]
OPS = ["delete", "rename", "value", "value", "value", "scale", "negate", "duplicate", "reference",
       "swap", "empty"]


@st.composite
def mutated_task(draw, names=None):
    """(example name, a task dict with 1-2 structural mutations); the name one of ``names``
    (all the examples unless given)."""
    name = draw(st.sampled_from(names or NAMES))
    d = copy.deepcopy(TASKS[name])
    for _ in range(draw(st.integers(1, 2))):
        paths = [p for p in _paths(d) if p]
        if not paths:
            break
        path = draw(st.sampled_from(paths))
        parent, key = _get(d, path[:-1]), path[-1]
        op = draw(st.sampled_from(OPS))
        v = parent[key]
        if op == "delete":
            del parent[key]
        elif op == "rename" and isinstance(parent, dict):
            parent[str(key) + draw(st.sampled_from(["x", "_", "s"]))] = parent.pop(key)
        elif op == "value":
            parent[key] = copy.deepcopy(draw(st.sampled_from(BAD_VALUES)))
        elif op == "scale" and isinstance(v, (int, float)) and not isinstance(v, bool):
            parent[key] = v * draw(st.sampled_from([0, 1e-9, 1e-3, 10, 1e3, 1e9, 1e200]))
        elif op == "negate" and isinstance(v, (int, float)) and not isinstance(v, bool):
            parent[key] = -v
        elif op == "negate" and isinstance(v, str):
            parent[key] = "-" + v
        elif op == "duplicate" and isinstance(parent, dict):      # e.g. a second copy of a link
            parent[str(key) + "_2"] = copy.deepcopy(v)
        elif op == "duplicate" and isinstance(parent, list):
            parent.append(copy.deepcopy(v))
        elif op == "reference" and isinstance(v, str):            # a name pointed elsewhere or nowhere
            parent[key] = draw(st.sampled_from(_names(d) + ["missing", "Z9"]))
        elif op == "swap" and isinstance(v, list) and len(v) >= 2:  # points [P, Q] -> [Q, P]...
            v[0], v[1] = v[1], v[0]
        elif op == "empty" and isinstance(v, (list, dict)):
            parent[key] = type(v)()
    return name, d


# ---------------------------------------------------------------- the contract
def _nonfinite(obj, path="") -> list[str]:
    if isinstance(obj, float):
        return [] if math.isfinite(obj) else [path]
    if isinstance(obj, dict):
        return [p for k, v in obj.items() for p in _nonfinite(v, f"{path}.{k}")]
    if isinstance(obj, (list, tuple)):
        return [p for i, v in enumerate(obj) for p in _nonfinite(v, f"{path}[{i}]")]
    return []


def check_results(results: dict) -> None:
    """Results are plain JSON: no NaN / inf anywhere (SPEC 3), the API dict included (SPEC 4)."""
    bad = _nonfinite(results)
    assert not bad, f"non-finite numbers at {bad[:5]}"
    json.dumps(results, allow_nan=False)


def check_task_error(err: TaskError, from_file: bool) -> None:
    assert err.issues, f"a TaskError without a field: {err}"
    for field, line, col, msg in err.issues:
        assert msg
        if not field:  # only whole-file problems have no field: YAML syntax, not a mapping
            assert "YAML" in msg or "mapping" in msg, f"a TaskError without a field: {err}"
        if from_file:
            assert line is not None, f"a TaskError without a line: {err}"
    text = str(err)
    assert "Traceback" not in text
    if from_file:
        assert err.file and err.file in text


def check_stage_error(err: StageError) -> None:
    assert err.stage and err.message
    assert "Traceback" not in str(err)
    if err.stage in LINKAGE_STAGES:
        assert not _WRAPPED.match(err.message), f"an internal error wrapped as a stage failure: {err}"


def outcome(source, *, text: str | None = None) -> str:
    """Load and run; the only acceptable outcomes are success (clean results), a TaskError
    naming a field (and a line for files) or a StageError. Anything else propagates."""
    from_file = not isinstance(source, dict)
    try:
        task = tmm_cli.load_task(source, text=text) if from_file else tmm_cli.load_task(source)
        results = tmm_cli.run(task, kinematics_curve=37)
    except TaskError as err:
        check_task_error(err, from_file)
        return "task"
    except StageError as err:
        check_stage_error(err)
        return "stage"
    check_results(results)
    return "ok"


# ---------------------------------------------------------------- 1. property tests
# 200 examples in four tests of 50, each mutating a quarter of the example tasks (the
# suite's workers share them out; each example runs the whole pipeline)
_SHARES = 4


@pytest.mark.parametrize("share", range(_SHARES))
@fuzz(200 // _SHARES)
@given(data=st.data())
def test_mutated_task_dict(share, data):
    name, d = data.draw(mutated_task(NAMES[share::_SHARES]))
    outcome(d)


@pytest.fixture(scope="module")
def fuzz_dir(tmp_path_factory) -> Path:
    """One folder for the files the property tests write (module scope: hypothesis reruns
    the body many times within one test call)."""
    return tmp_path_factory.mktemp("fuzz")


@fuzz(80)
@given(mutated_task())
def test_mutated_task_file(fuzz_dir, case):
    """The same mutations written as a YAML file: every TaskError names its line."""
    name, d = case
    f = fuzz_dir / name
    f.write_text(yaml.safe_dump(d, sort_keys=False, allow_unicode=True), encoding="utf-8")
    outcome(f)


YAML_CHARS = list(":-[]{}#&*!|>'\"%@`,?\t\n ") + ["\x00", "\x07", "\ufeff", "é", "0", ".", "e", "~"]


@st.composite
def garbled_text(draw):
    """An example task's text with a few characters deleted, inserted or doubled."""
    name = draw(st.sampled_from(NAMES))
    chars = list((ROOT / "tasks" / name).read_text(encoding="utf-8"))
    for _ in range(draw(st.integers(1, 4))):
        j = draw(st.integers(0, len(chars) - 1))
        op = draw(st.sampled_from(["delete", "insert", "double"]))
        if op == "delete":
            del chars[j]
        elif op == "insert":
            chars.insert(j, draw(st.sampled_from(YAML_CHARS)))
        else:
            chars.insert(j, chars[j])
    return "".join(chars)


@fuzz(60)
@given(garbled_text())
def test_garbled_task_text(fuzz_dir, text):
    f = fuzz_dir / "garbled.yaml"
    f.write_text(text, encoding="utf-8")
    outcome(f)


@fuzz(80)
@given(st.one_of(st.text(alphabet=st.sampled_from(YAML_CHARS + list("abcxyz019 ")), max_size=60),
                 st.text(max_size=40)))
def test_yaml_garbage(fuzz_dir, text):
    """Random text: never anything but a TaskError with a line (or, rarely, a valid task)."""
    f = fuzz_dir / "garbage.yaml"
    f.write_bytes(text.encode("utf-8", errors="replace"))   # lone surrogates -> '?'
    try:
        tmm_cli.load_task(f)
    except TaskError as err:
        check_task_error(err, from_file=True)


def test_examples_results_are_plain_json():
    """Every example task runs to plain JSON (allow_nan=False), through the API."""
    for name in NAMES:
        check_results(tmm_cli.run(tmm_cli.load_task(ROOT / "tasks" / name), kinematics_curve=37))


# ---------------------------------------------------------------- 2. command line
SLIDER_CRANK = """\
schema: tmm/1
mechanism:
  ground: {O: [0, 0]}
  links:
    crank: {points: [O, A], length: 0.1, mass: 1}
    rod: {points: [A, B], length: 0.4, mass: 2}
    slider: {slider: B, guide: {through: O, angle: 0}, mass: 3}
drive: {link: crank, speed: 10}
"""
LOADS = """\
loads:
  forces:
    - {on: slider, kind: resistance, magnitude: 100}
kinetostatics: {positions: all}
"""


def _cli(tmp_path, text, *args, name="t.yaml"):
    f = tmp_path / name
    f.write_text(text, encoding="utf-8")
    res = runner.invoke(app, [a.replace("{f}", str(f)) for a in args])
    assert "Traceback" not in res.output
    assert "internal error" not in res.output, res.output
    return res, str(f)


CLI_CASES = [
    ("valid", SLIDER_CRANK, 0, []),
    ("wrong unit", SLIDER_CRANK.replace("length: 0.4", "length: 4 kg"), 2,
     [":6:", "mechanism.links.rod.length", "is not a length"]),
    ("NUL character", SLIDER_CRANK.replace("mass: 2", "mass: 2\x00"), 2, [":6:", "#x0000"]),
    ("load on a missing link", SLIDER_CRANK + LOADS.replace("on: slider", "on: slidr"), 2,
     [":11:", "loads.forces[0].on", "did you mean 'slider'"]),
    ("balance on a missing link", SLIDER_CRANK + LOADS.replace("{positions: all}", "{balance: rodd}"), 2,
     [":12:", "kinetostatics.balance", "did you mean 'rod'"]),
    ("huge length", SLIDER_CRANK.replace("length: 0.1", "length: 1e300"), 2,
     [":5:", "mechanism.links.crank.length", "out of range"]),
    # the rod (0.05) is shorter than the crank (0.1): the dyad assembles only near phi = 0, 180
    ("does not assemble", SLIDER_CRANK.replace("length: 0.4", "length: 0.05"), 3,
     ["stage 'kinematics' failed", "crank angle"]),
]


@pytest.mark.parametrize("args", [["run", "{f}", "--format", "json", "-q", "--out", "{out}"],
                                  ["validate", "{f}"]], ids=["run", "validate"])
@pytest.mark.parametrize("desc,text,code,frags", CLI_CASES, ids=[c[0] for c in CLI_CASES])
def test_cli_exit_codes(tmp_path, args, desc, text, code, frags):
    args = [a.replace("{out}", str(tmp_path / "out")) for a in args]
    res, f = _cli(tmp_path, text, *args)
    assert res.exit_code == code, res.output
    for fr in frags:
        assert (f + fr if fr.startswith(":") else fr) in res.output, (fr, res.output)
    if code == 2 and args[0] == "run":
        assert not (tmp_path / "out").exists()        # nothing written for an invalid task


def test_cli_out_is_a_file(tmp_path):
    """--out naming a file: the output stage fails (exit 3) with the reason, not an
    'internal error' (regression: FileExistsError reached the catch-all handler)."""
    (tmp_path / "afile").write_text("x")
    res, f = _cli(tmp_path, SLIDER_CRANK, "run", "{f}", "--format", "json", "-q", "--out",
                  str(tmp_path / "afile"))
    assert res.exit_code == 3, res.output
    assert "stage 'output' failed: cannot write" in res.output and "afile" in res.output
    res, f = _cli(tmp_path, SLIDER_CRANK, "schema", "--out", str(tmp_path / "afile" / "s.json"))
    assert res.exit_code == 3 and "cannot write" in res.output


def test_real_process_garbage_and_stage_failure(tmp_path):
    """A real process: garbage -> 2, a stage failure -> 3, never a traceback on stderr."""
    bad = tmp_path / "bad.yaml"
    bad.write_bytes(b"schema: tmm/1\ngears: {m: 3 mm, z: [12, 42], x: [0, .inf]}\n")
    fail = tmp_path / "fail.yaml"
    fail.write_text(SLIDER_CRANK.replace("length: 0.4", "length: 0.05"), encoding="utf-8")
    for f, code, frag in ((bad, 2, f"{bad}:2:"), (fail, 3, "stage 'kinematics' failed")):
        p = subprocess.run([sys.executable, "-m", "tmm_cli", "run", str(f), "--format", "json",
                            "--out", str(tmp_path / "o")], capture_output=True, text=True)
        assert p.returncode == code, p.stderr
        assert "Traceback" not in p.stdout + p.stderr
        assert frag in p.stderr


# ---------------------------------------------------------------- 3. regressions
def _err(source, text=None) -> TaskError:
    with pytest.raises(TaskError) as ei:
        tmm_cli.load_task(source, text=text) if text is not None else tmm_cli.load_task(source)
    return ei.value


def _linkage(extra: dict | None = None) -> dict:
    d = yaml.safe_load(SLIDER_CRANK)
    for k, v in (extra or {}).items():
        d[k] = v
    return d


@pytest.mark.parametrize("text,field,line", [
    # section-level checks used to give no field (loc = ()) and line 1
    ("schema: tmm/1\ntitle: x\nloads: {gravity: true}\n", "loads", 3),
    (SLIDER_CRANK.replace("drive: {link: crank, speed: 10}\n", ""), "mechanism", 2),
    (SLIDER_CRANK + "flywheel: {delta: 1/18}\n", "flywheel", 9),
], ids=["loads without mechanism", "mechanism without drive", "flywheel without loads"])
def test_section_errors_name_field_and_line(text, field, line):
    err = _err("t.yaml", text)
    assert [(i[0], i[1]) for i in err.issues] == [(field, line)], str(err)


def test_disallowed_character_has_line_and_column():
    # yaml.reader.ReaderError has no mark: it used to give a TaskError without a line
    err = _err("t.yaml", "schema: tmm/1\ntitle: ab\x00c\n")
    assert [(i[1], i[2]) for i in err.issues] == [(2, 10)]   # line 2, the 10th character
    assert "#x0000" in str(err)


@pytest.mark.parametrize("x", ["inf", ".inf", "1e400", float("nan"), 1e300])
def test_non_finite_or_huge_plain_numbers_are_invalid(x):
    # plain float fields took 'inf' / 1e400 / nan; gears then failed with an OverflowError
    text = f"schema: tmm/1\ngears:\n  m: 3 mm\n  z: [12, 42]\n  x: [0, {x}]\n"
    err = _err("t.yaml", text)
    assert any(i[0] == "gears.x[1]" and i[1] == 5 for i in err.issues), str(err)


@pytest.mark.parametrize("section,field,value", [
    ("gears", "m", 1e300), ("gears", "m", "1e13 km"), ("gears", "ha", "inf"),
    ("cam", "stroke", 1e300), ("planetary", "ratio", 1e20),
])
def test_huge_quantities_are_invalid(section, field, value):
    base = {"gears": {"m": "3 mm", "z": [12, 42]},
            "cam": {"stroke": 0.02, "phases": {"rise": 90, "return": 90}},
            "planetary": {"scheme": "A", "ratio": 3.24}}[section]
    err = _err({"schema": "tmm/1", section: dict(base, **{field: value})})
    assert [i[0] for i in err.issues] == [f"{section}.{field}"], str(err)


def test_limit_is_far_above_real_values():
    """1e12 in base units: 10 MPa, 20 kN, 3000 rpm, a 1 km length are all far below it."""
    from tmm_cli.units import LIMIT, convert
    for v, kind in (("10 MPa", "pressure"), ("20 kN", "force"), ("3000 rpm", "speed"), ("1 km", "length")):
        assert abs(convert(v, kind)) < LIMIT * 1e-3
    with pytest.raises(ValueError, match="out of range"):
        convert("2e12", "force")


def test_unknown_planetary_scheme_is_an_invalid_task():
    # it used to pass validation and fail in the planetary stage (exit 3)
    err = _err("t.yaml", "schema: tmm/1\nplanetary:\n  scheme: Q\n  ratio: 3\n")
    assert [(i[0], i[1]) for i in err.issues] == [("planetary.scheme", 3)]
    assert "known: A, B, C, D" in str(err)
    for ok in ("A", "b", " c ", "D", "single", "james"):
        tmm_cli.load_task({"schema": "tmm/1", "planetary": {"scheme": ok, "ratio": 3.24}})


def test_planetary_scheme_names_match_the_planetary_module():
    from tmm_cli.gears import planetary
    from tmm_cli.modelbase import PLANETARY_ALIASES, PLANETARY_SCHEMES
    assert tuple(planetary.SCHEMES) == PLANETARY_SCHEMES
    assert planetary.ALIASES == PLANETARY_ALIASES


def test_planetary_search_range_is_bounded():
    # z_max: 100000 made the candidate search run for hours (schemes B, C grow as z_max^3)
    assert _err({"schema": "tmm/1", "planetary": {"scheme": "B", "ratio": 7, "z_max": 100000}}).issues[0][0] \
        == "planetary.z_max"
    assert _err({"schema": "tmm/1", "planetary": {"scheme": "B", "ratio": 7, "z_min": 60, "z_max": 40}}
                ).issues[0][0] == "planetary.z_min"


def test_negative_tolerance_is_invalid():
    assert _err({"schema": "tmm/1", "tolerance": {"default": -1}}).issues[0][0] == "tolerance.default"


@pytest.mark.parametrize("patch,field", [
    ({"loads": {"forces": [{"on": "slidr", "magnitude": 5}]}}, "loads.forces[0].on"),
    ({"loads": {"forces": [{"on": "slider", "magnitude": 5, "at": "ZZ"}]}}, "loads.forces[0].at"),
    ({"loads": {"forces": [{"on": "rod", "magnitude": 5}]}}, "loads.forces[0]"),     # a bar needs direction
    ({"loads": {}, "kinetostatics": {"balance": "rodd"}}, "kinetostatics.balance"),
    ({"loads": {}, "kinetostatics": {"motion": True}}, "kinetostatics.motion"),
    ({"positions": {"output": "nope"}}, "positions.output"),
])
def test_references_of_other_sections_are_checked_with_the_mechanism(tmp_path, patch, field):
    """Unknown names in loads / kinetostatics / positions: a TaskError naming the field and its
    line, found by `tmm validate` too. Before, run raised a TaskError without file or line
    (loads, balance), or a StageError, exit 3 (positions.output), and validate said ok."""
    f = tmp_path / "t.yaml"
    f.write_text(yaml.safe_dump(_linkage(patch), sort_keys=False), encoding="utf-8")
    task = tmm_cli.load_task(f)
    with pytest.raises(TaskError) as ei:
        tmm_cli.run(task)
    err = ei.value
    assert err.file == str(f)
    assert [i[0] for i in err.issues] == [field], str(err)
    assert err.issues[0][1] == task.line_of(tuple(parse_path(field)))[0] > 1
    res = runner.invoke(app, ["validate", str(f)])
    assert res.exit_code == 2, res.output
    assert f"field '{field}'" in res.output


def test_stage_task_error_is_located():
    """A TaskError raised inside a stage (it knows the field, not the file) gets the file and
    the line from the task (Task.locate)."""
    task = tmm_cli.load_task("t.yaml", text=SLIDER_CRANK + LOADS)
    err = task.locate(TaskError("m", issues=[("loads.forces[0].kind", None, None, "m")]))
    assert err.file == "t.yaml" and err.issues == [("loads.forces[0].kind", 11, 20, "m")]


PRESS = ROOT / "tasks" / "press_offset_slider_crank.yaml"


def test_self_locking_friction_is_flagged_not_huge():
    """Pins of radius 10 m with f = 1 on an 80 mm crank: the friction circles are far larger
    than the links, so at some positions the friction moments grow faster than the loads
    that cause them (self-locking) and the fixed-point iteration diverges. Before, those
    positions reported balancing moments of 1e305 N*m and couples of inf."""
    d = load_yaml(PRESS)[0]
    d["kinetostatics"]["friction"] = {"pin_radius": 10, "f": 1}
    r = tmm_cli.run(tmm_cli.load_task(d))
    check_results(r)
    locked = [e for e in r["kinetostatics"] if e["balancing_moment"] is None]
    assert locked, "expected self-locking positions"
    for e in locked:
        assert e["near_singular"] is True and e["efficiency"] is None
        assert all(v["R"] is None for v in e["reactions"].values())
        assert any(f"position {e['index']} " in w and "self-locking" in w for w in r["warnings"])
    # the other positions: the balancing moment of the converged iteration, a few hundred kN*m
    # at most for these loads (20 kN at the ram, friction arms of 10 m: < 20e3 * 10 * 3)
    for e in r["kinetostatics"]:
        if e["balancing_moment"] is not None:
            assert abs(e["balancing_moment"]) < 20e3 * 10 * 3


def test_self_locking_check_leaves_ordinary_friction_alone():
    """Ordinary friction (the example: r = 20 mm, f = 0.08) converges everywhere: no position
    is flagged, and 0 < eta < 1 wherever it is defined."""
    r = tmm_cli.run(tmm_cli.load_task(PRESS))
    assert not any("self-locking" in w for w in r["warnings"])
    etas = [e["efficiency"] for e in r["kinetostatics"] if e["efficiency"] is not None]
    assert etas and all(0 < x < 1 for x in etas)


@pytest.mark.parametrize("task,balance", [("shaper_slotted_lever.yaml", "rocker"),
                                          ("scotch_yoke_pump.yaml", "yoke"),
                                          ("scotch_yoke_pump.yaml", "block")])
def test_friction_at_singular_positions_is_not_infinite(task, balance):
    """With friction and a balance link whose equations are singular at some positions, the
    infinite reactions there became friction couples of +-inf (np.nan_to_num(inf) = 1.8e308)
    in the results; now those positions carry null and the rest is finite."""
    d = load_yaml(ROOT / "tasks" / task)[0]
    d["kinetostatics"]["balance"] = balance
    d["kinetostatics"]["friction"] = {"pin_radius": 0.01, "f": 0.1}
    r = tmm_cli.run(tmm_cli.load_task(d))
    check_results(r)
    assert any(e["near_singular"] for e in r["kinetostatics"])
