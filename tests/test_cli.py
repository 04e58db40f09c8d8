"""The command line end to end: run, check, batch, schema, new; exit codes; atomic
and partial output. Reference values here are closed forms written out below."""
from __future__ import annotations

import csv
import json
import math
import os
from pathlib import Path

import pytest
from typer.testing import CliRunner

import tmm_cli
from tmm_cli.cli import app

runner = CliRunner()
ROOT = Path(__file__).resolve().parents[1]

GEARS = """\
schema: tmm/1
title: zero-shift pair
student: {name: A. Student, group: MM-1}
gears: {m: 4 mm, z: [14, 30], x: [0, 0]}
"""
# zero-shift pair: a_w = m (z1 + z2) / 2 = 4 * 44 / 2 = 88 mm; r1 = m z1 / 2 = 28 mm
AW = 0.088
R1 = 0.028

SLIDER_CRANK = """\
schema: tmm/1
title: slider-crank
mechanism:
  ground: {O: [0, 0]}
  links:
    crank: {points: [O, A], length: 0.1}
    rod: {points: [A, B], length: 0.4}
    slider: {slider: B, guide: {through: O, angle: 0}}
drive: {link: crank, speed: 10 rad/s}
"""


def _write(tmp_path, name, text):
    p = tmp_path / name
    p.write_text(text, encoding="utf-8")
    return p


def test_run_json_only(tmp_path):
    f = _write(tmp_path, "g.yaml", GEARS)
    res = runner.invoke(app, ["run", str(f), "--format", "json", "--out", str(tmp_path / "o"), "--quiet"])
    assert res.exit_code == 0, res.output
    data = json.loads((tmp_path / "o" / "results.json").read_text())
    assert data["schema"] == "tmm-results/1"
    assert data["gears"]["aw"] == pytest.approx(AW, rel=1e-12)
    assert data["gears"]["r"][0] == pytest.approx(R1, rel=1e-12)
    assert "mechanism" not in data and "kinematics" not in data   # only what the task asks for
    assert not (tmm_cli.run(tmm_cli.load_task(f)) != data)          # CLI == Python API
    assert not any(p.name.endswith(".tmp") for p in (tmp_path / "o").iterdir())


def test_default_out_dir(tmp_path, monkeypatch):
    f = _write(tmp_path, "variant7.yaml", GEARS)
    monkeypatch.chdir(tmp_path)
    res = runner.invoke(app, ["run", str(f), "--format", "json", "--quiet"])
    assert res.exit_code == 0, res.output
    assert (tmp_path / "out" / "variant7" / "results.json").exists()


def test_check_exit_codes(tmp_path):
    good = _write(tmp_path, "good.yaml", GEARS + f"answers: {{gears.aw: {AW * 1.01}, 'gears.r[0]': {R1}}}\n")
    res = runner.invoke(app, ["check", str(good)])
    assert res.exit_code == 0, res.output
    assert "2 of 2 answers within tolerance" in res.output
    bad = _write(tmp_path, "bad.yaml", GEARS + f"answers: {{gears.aw: {AW * 1.2}}}\n"
                 "tolerance: {default: 0.05}\n")
    res = runner.invoke(app, ["check", str(bad)])
    assert res.exit_code == 1, res.output
    assert "outside" in res.output
    # answers from a separate file override the task's
    ans = _write(tmp_path, "ans.yaml", f"answers:\n  gears.aw: {AW}\n")
    res = runner.invoke(app, ["check", str(bad), "--answers", str(ans), "--out", str(tmp_path / "c")])
    assert res.exit_code == 0, res.output
    rows = list(csv.DictReader((tmp_path / "c" / "check.csv").open()))
    assert rows[0]["path"] == "gears.aw" and rows[0]["status"] == "ok"


def test_check_without_answers_is_invalid(tmp_path):
    f = _write(tmp_path, "g.yaml", GEARS)
    res = runner.invoke(app, ["check", str(f)])
    assert res.exit_code == 2
    assert "no answers" in res.output


def test_batch(tmp_path):
    d = tmp_path / "group"
    d.mkdir()
    _write(d, "v1.yaml", GEARS + f"answers: {{gears.aw: {AW}}}\n")
    _write(d, "v2.yaml", GEARS + f"answers: {{gears.aw: {AW * 1.5}}}\n")
    _write(d, "v3.yaml", GEARS.replace("m: 4 mm", "m: 4 kg"))
    _write(d, "v4.yaml", SLIDER_CRANK.replace("length: 0.4", "length: 0.05"))   # does not assemble
    res = runner.invoke(app, ["batch", str(d), "--out", str(tmp_path / "b")])
    rows = {Path(r["file"]).stem: r for r in csv.DictReader((tmp_path / "b" / "summary.csv").open())}
    assert rows["v1"]["status"] == "ok"
    assert rows["v2"]["status"] == "outside" and "gears.aw" in rows["v2"]["message"]
    assert rows["v2"]["gears.aw"] == "outside" and rows["v1"]["gears.aw"] == "ok"
    assert rows["v3"]["status"] == "invalid" and "v3.yaml:4" in rows["v3"]["message"]
    assert rows["v4"]["status"] == "failed" and "kinematics" in rows["v4"]["message"]
    assert rows["v1"]["student"] == "A. Student" and rows["v1"]["group"] == "MM-1"
    assert res.exit_code == 3           # the worst variant: a stage failed
    html = (tmp_path / "b" / "summary.html").read_text()
    assert html.count("<tr") == 5
    assert (tmp_path / "b" / "v1" / "check.csv").exists() and (tmp_path / "b" / "check.csv").exists()
    assert (tmp_path / "b" / "v1" / "results.json").exists()


def test_batch_parallel_matches_serial(tmp_path):
    d = tmp_path / "g"
    d.mkdir()
    for i, z in enumerate((12, 17, 25)):
        _write(d, f"v{i}.yaml", GEARS.replace("z: [14, 30]", f"z: [{z}, 40]"))
    r1 = runner.invoke(app, ["batch", str(d / "*.yaml"), "--out", str(tmp_path / "s")])
    r2 = runner.invoke(app, ["batch", str(d), "--out", str(tmp_path / "p"), "--jobs", "2"])
    assert r1.exit_code == r2.exit_code == 0, r1.output + r2.output
    for i in range(3):
        a = json.loads((tmp_path / "s" / f"v{i}" / "results.json").read_text())
        b = json.loads((tmp_path / "p" / f"v{i}" / "results.json").read_text())
        assert a == b


def test_stage_failure_keeps_partial_results(tmp_path):
    # crank 0.1 and rod 0.05: |AB| can never reach the guide at most angles -> kinematics fails
    f = _write(tmp_path, "sc.yaml", SLIDER_CRANK.replace("length: 0.4", "length: 0.05"))
    res = runner.invoke(app, ["run", str(f), "--out", str(tmp_path / "o"), "--format", "json"])
    assert res.exit_code == 3
    assert "stage 'kinematics' failed" in res.output and "crank angle" in res.output
    assert "Traceback" not in res.output
    data = json.loads((tmp_path / "o" / "results.json").read_text())
    assert data["structure"]["W"] == 1          # computed before the failure, kept
    assert data["error"]["stage"] == "kinematics"
    res = runner.invoke(app, ["validate", str(f)])
    assert res.exit_code == 3


def test_schema_and_new(tmp_path):
    res = runner.invoke(app, ["schema"])
    assert res.exit_code == 0
    s = json.loads(res.output)
    for sec in ("mechanism", "drive", "positions", "loads", "kinetostatics", "flywheel", "cam", "gears",
                "planetary", "answers", "tolerance"):
        assert sec in s["properties"], sec
    assert s["additionalProperties"] is False
    for kind in ("linkage", "cam", "gears", "full", "synthesis"):
        res = runner.invoke(app, ["new", kind])
        assert res.exit_code == 0
        f = _write(tmp_path, f"{kind}.yaml", res.output)
        assert runner.invoke(app, ["validate", str(f)]).exit_code == 0
    assert runner.invoke(app, ["new", "spaceship"]).exit_code == 2


def test_help_mentions_every_command():
    res = runner.invoke(app, ["--help"])
    for cmd in ("run", "validate", "check", "batch", "schema", "new"):
        assert cmd in res.output
    res = runner.invoke(app, ["run", "--help"])
    for opt in ("--out", "--format", "--lang"):
        assert opt in res.output


def test_atomic_write_keeps_old_file_on_failure(tmp_path, monkeypatch):
    from tmm_cli.io import atomic_write
    p = tmp_path / "results.json"
    atomic_write(p, "old")

    def boom(*a, **k):
        raise OSError("disk full")
    monkeypatch.setattr(os, "replace", boom)
    with pytest.raises(OSError):
        atomic_write(p, "new")
    assert p.read_text() == "old"
    assert [x.name for x in tmp_path.iterdir()] == ["results.json"]


def test_slider_crank_numbers_against_closed_form():
    """One position of a central slider-crank checked by hand: phi = 90 deg,
    r = 0.1, l = 0.4, omega = 10 rad/s: x_B = sqrt(l^2 - r^2); v_B = -r omega (1 + 0)
    since at 90 deg the rod's angular velocity is zero... written out below."""
    t = tmm_cli.load_task({**__import__("yaml").safe_load(SLIDER_CRANK),
                           "positions": {"zero": 0.0, "count": 4}})
    res = tmm_cli.run(t)
    e = [k for k in res["kinematics"] if k["index"] == 1][0]      # phi = 90 deg
    assert e["phi"] == pytest.approx(90.0)
    r, l, w = 0.1, 0.4, 10.0
    xb = math.sqrt(l * l - r * r)
    # loop: r cos(phi) + l cos(beta) = x, r sin(phi) + l sin(beta) = 0 (central)
    # at phi = 90: sin(beta) = -r/l; d/dt: -r w + l cos(beta) beta' ... (y-eq): r w cos(phi) + l cos(beta) w2 = 0 -> w2 = 0
    # x-eq: v = -r w sin(phi) - l sin(beta) w2 = -r w
    # accel (y-eq): -r w^2 sin(phi) + l cos(beta) e2 - l sin(beta) w2^2 = 0 -> e2 = r w^2 / (l cos beta)
    cb = math.sqrt(1 - (r / l) ** 2)
    e2 = r * w * w / (l * cb)
    # x-eq: a = -r w^2 cos(phi) - l cos(beta) w2^2 - l sin(beta) e2 = -l*(-r/l)*e2 = r e2
    assert e["points"]["B"]["x"] == pytest.approx(xb, rel=1e-12)
    assert e["points"]["B"]["vx"] == pytest.approx(-r * w, rel=1e-12)
    assert e["links"]["rod"]["omega"] == pytest.approx(0.0, abs=1e-12)
    assert e["links"]["rod"]["epsilon"] == pytest.approx(e2, rel=1e-12)
    assert e["points"]["B"]["ax"] == pytest.approx(r * e2, rel=1e-12)


def test_every_task_field_is_documented():
    from tmm_cli.task import field_docs
    docs = field_docs()
    missing = [p for p, _, text in docs if not text]
    assert not missing, missing
    paths = {p for p, _, _ in docs}
    for p in ("flywheel.delta", "mechanism.links.<name>.guide.offset", "loads.forces[i].diagram.s",
              "cam.phases.return", "planetary.tolerance", "kinetostatics.friction.pin_radius"):
        assert p in paths, p


def test_fields_command():
    res = runner.invoke(app, ["fields", "flywheel"], env={"COLUMNS": "200"})
    assert res.exit_code == 0
    assert "flywheel.delta" in res.output and "coefficient of speed fluctuation" in res.output
    assert "cam.stroke" not in res.output
    assert runner.invoke(app, ["fields", "nonsense"]).exit_code == 2


@pytest.mark.parametrize("text,field", [
    ("answers: [1, 2]\n", "answers"),
    ("answers: {'gears..aw': 1}\n", "answers.gears..aw"),
])
def test_bad_answers_file(tmp_path, text, field):
    task = _write(tmp_path, "g.yaml", GEARS)
    ans = _write(tmp_path, "a.yaml", text)
    res = runner.invoke(app, ["check", str(task), "--answers", str(ans)])
    assert res.exit_code == 2, res.output
    assert f"{ans}:" in res.output and f"field '{field}'" in res.output
    assert "Traceback" not in res.output


@pytest.mark.parametrize("text", ["answers: {gears.aw: 1}\ntolerance: {default: abc}\n",
                                  "answers: {gears.aw: 1}\ntolerance: {default: -1}\n"])
def test_a_students_tolerance_even_a_broken_one_is_ignored(tmp_path, text):
    """The student's `tolerance` is never read: a warning, the answer graded (exit 1)."""
    task = _write(tmp_path, "g.yaml", GEARS)
    ans = _write(tmp_path, "a.yaml", text)
    res = runner.invoke(app, ["check", str(task), "--answers", str(ans)])
    assert res.exit_code == 1, res.output
    assert "`tolerance` is ignored" in " ".join(res.output.split()) and "outside" in res.output


@pytest.mark.parametrize("lang, head", [("en", "error: nothing to check"), ("ru", "\u041d\u0435\u0447\u0435\u0433\u043e"),
                                        ("uk", "\u041d\u0456\u0447\u043e\u0433\u043e")])
def test_check_with_nothing_to_check_is_no_invalid_task(tmp_path, lang, head):
    """`tmm check` of a valid task without answers and without --answers was headed "error:
    invalid task": the task is valid; nothing was given to check (exit 2, the remedy said)."""
    task = _write(tmp_path, "g.yaml", GEARS)
    res = runner.invoke(app, ["check", str(task), "--lang", lang])
    assert res.exit_code == 2, res.output
    assert res.output.startswith(head) and "invalid" not in res.output and "--answers" in res.output, res.output


def test_a_tolerance_files_plain_tolerance_line_is_told_not_ignored(tmp_path):
    """`tolerance: 0.02` in a --tolerance file (a task's section copied as a number) was taken
    for a path named 'tolerance' matching no quantity: the answers were graded at the default
    5 % with only a warning. Now the file is invalid at that line, the way to write it said;
    `tolerance: {default: 0.02}` is read (0.0968 against 0.088 is outside either way, 0.0891 is
    inside 5 % and outside 1 %)."""
    task = _write(tmp_path, "g.yaml", GEARS + "answers: {gears.aw: 0.0891}\n")
    bad = _write(tmp_path, "t.yaml", "tolerance: 0.01\n")
    res = runner.invoke(app, ["check", str(task), "--tolerance", str(bad)])
    assert res.exit_code == 2 and f"{bad}:1:1: field 'tolerance'" in res.output, res.output
    assert "write `tolerance: {default: 0.05}`" in res.output and "Traceback" not in res.output
    good = _write(tmp_path, "t2.yaml", "tolerance: {default: 0.01}\n")
    res = runner.invoke(app, ["check", str(task), "--tolerance", str(good)], env={"COLUMNS": "120"})
    assert res.exit_code == 1 and "outside" in res.output, res.output


def test_an_infinite_answer_is_that_answers_invalid(tmp_path):
    task = _write(tmp_path, "g.yaml", GEARS)
    ans = _write(tmp_path, "a.yaml", "answers: {gears.aw: .inf}\n")
    res = runner.invoke(app, ["check", str(task), "--answers", str(ans)])
    assert res.exit_code == 1 and "invalid answer: not a finite number" in res.output, res.output
    assert "Traceback" not in res.output


def test_check_table_tolerance_in_the_errors_terms(tmp_path):
    """The terminal table of `tmm check` at 80 columns: a relative tolerance in percent like
    the error beside it (0.05 -> '5 %'), tolerance {rel: 0.02, abs: 0.001} as '2 % abs 0.001',
    the notes (did you mean, wrong sign) below the table so that no status is broken across
    lines. gears.aw = 88 mm (m (z1 + z2) / 2 = 4 * 44 / 2): 0.0968 is 10 % off."""
    f = _write(tmp_path, "g.yaml", GEARS + f"answers: {{gears.aw: 0.0968, 'gears.r[0]': {-R1}, gears.aww: 1}}\n"
               "tolerance: {default: 0.05, 'gears.r': {rel: 0.02, abs: 0.001}}\n")
    res = runner.invoke(app, ["check", str(f)], env={"COLUMNS": "80"})
    assert res.exit_code == 1, res.output
    lines = res.output.splitlines()
    aw = next(ln for ln in lines if "gears.aw " in ln)
    assert "10.00 %" in aw and "5 %" in aw and "0.05 " not in aw and "outside" in aw, aw
    r0 = next(ln for ln in lines if "gears.r[0]" in ln and "│" in ln)
    assert "2 % abs 0.001" in r0 and r0.rstrip("│ ").endswith("sign"), r0
    assert any(ln.rstrip("│ ").endswith("unknown_path") for ln in lines), res.output
    table_end = next(i for i, ln in enumerate(lines) if ln.startswith("└"))
    below = "\n".join(lines[table_end + 1:])
    assert "gears.r[0]: right magnitude, wrong sign" in below
    assert "did you mean 'gears.aw'" in below.replace("\n", "")
    assert max(len(ln) for ln in lines) <= 80


def test_check_table_breaks_a_long_path_after_its_dots(tmp_path):
    """At 80 columns the quantity column is narrower than 'flywheel.moment_of_inertia': it
    was folded mid-word ('moment_of_ine' / 'rtia'); now broken after the dot, each line of
    the column a whole name. At 120 columns the path stays on one line."""
    from tmm_cli.summary import _path_lines
    assert _path_lines("kst[5].balancing_moment", 12) == "kst[5].\nbalancing_moment"
    assert _path_lines("kin[3].B.vx", 20) == "kin[3].B.vx"
    assert _path_lines("gears.r[0]", 6) == "gears.\nr[0]"
    assert _path_lines("kin[1.B.v", 40) == "kin[1.B.v"                  # a student's unclosed bracket kept
    assert _path_lines("kin[1.B.v", 4).replace("\n", "") == "kin[1.B.v"
    f = _write(tmp_path, "s.yaml", SLIDER_CRANK +
               "answers: {flywheel.moment_of_inertia: 1, 'kinetostatics[2].balancing_moment': 1}\n")
    res = runner.invoke(app, ["check", str(f)], env={"COLUMNS": "80"})
    lines = [ln for ln in res.output.splitlines() if ln.startswith("│")]
    cells = [ln.split("│")[1].strip() for ln in lines]
    assert "flywheel." in cells and "moment_of_inertia" in cells, res.output
    assert "kst[2].balancing_moment" in cells, res.output
    assert max(len(ln) for ln in res.output.splitlines()) <= 80
    wide = runner.invoke(app, ["check", str(f)], env={"COLUMNS": "120"})
    assert any("│ flywheel.moment_of_inertia " in ln for ln in wide.output.splitlines()), wide.output


def test_a_point_named_like_a_word_is_that_point():
    """'E' and 'W' are points of a linkage before they are a student's ε and ω: a path naming
    point E is told point E's path (it was read as epsilon, and nothing suggested)."""
    from tmm_cli.results import did_you_mean
    results = {"kinematics": [{"index": 1, "points": {"E": {"v": 1.0, "a": 2.0}, "W": {"v": 3.0}},
                               "links": {"rod": {"omega": 4.0, "epsilon": 5.0}}}]}
    assert str(did_you_mean("kinematics[1].velocities.E", results)) == "did you mean 'kinematics[1].points.E.v'?"
    assert str(did_you_mean("kinematics[1].v_W", results)) == "did you mean 'kinematics[1].points.W.v'?"
    assert str(did_you_mean("kinematics[1].e_rod", results)) == "did you mean 'kinematics[1].links.rod.epsilon'?"


@pytest.mark.parametrize("path, meant", [("kinematics[2].velocities.B", "kinematics[2].points.B.v"),
                                         ("kinematics[2].v_B", "kinematics[2].points.B.v"),
                                         ("kinematics[2].B.acceleration", "kinematics[2].points.B.a"),
                                         ("kinematics[2].omega_rod", "kinematics[2].links.rod.omega"),
                                         ("kinematics[2].points.B.velocity", "kinematics[2].points.B.v")])
def test_a_path_in_a_students_words_is_told_the_results_path(tmp_path, path, meant):
    """A path written in words ('velocities.B', 'v_B') was told the nearest spelling
    ('kinematics[3].points.B.y', 'kinematics[3].phi'): the path holding every name of it, a
    word read as the key it means (velocity v, acceleration a, omega), comes first."""
    f = _write(tmp_path, "s.yaml", SLIDER_CRANK + f"answers: {{'{path}': 1}}\n")
    res = runner.invoke(app, ["check", str(f)], env={"COLUMNS": "200"})
    assert res.exit_code == 1 and f"did you mean '{meant}'" in res.output, res.output


def test_validate_a_folder_and_a_quoted_pattern(tmp_path):
    """`tmm validate DIR` checks its task files (answers files skipped) and a quoted pattern
    the files it matches, as `tmm batch` takes them; a folder with no task file is exit 2
    saying so (it was "not a regular file (a folder)" for every folder)."""
    d = tmp_path / "group"
    d.mkdir()
    _write(d, "a.yaml", GEARS)
    _write(d, "b.yml", GEARS.replace("x: [0, 0]", "x: [0.5, 0]"))
    _write(d, "bad.yaml", GEARS.replace("m: 4 mm", "m: 4 parsecs"))
    _write(d, "ans.yaml", "answers: {gears.aw: 0.088}\n")
    res = runner.invoke(app, ["validate", str(d)])
    assert res.exit_code == 2, res.output
    assert f"{d / 'a.yaml'}: ok" in res.output and f"{d / 'b.yml'}: ok" in res.output
    assert f"{d / 'bad.yaml'}:" in res.output and "gears.m" in res.output and "ans.yaml" not in res.output
    res = runner.invoke(app, ["validate", str(d / "[ab].y*ml")])
    assert res.exit_code == 0 and res.output.count(": ok") == 2, res.output
    (tmp_path / "empty").mkdir()
    res = runner.invoke(app, ["validate", str(tmp_path / "empty")])
    assert res.exit_code == 2 and "no task files (*.yaml, *.yml) in this folder" in res.output, res.output


def test_a_students_small_slips_on_the_command_line(tmp_path):
    """--lang in capitals is the language (RU is ru), on the fast path and in the Typer app; an
    unknown format lists every format (note too); a misspelt section of `tmm fields` is
    suggested; a language that is none is still a usage error (exit 2)."""
    import subprocess
    import sys
    task = ROOT / "tasks" / "cam_knife.yaml"
    p = subprocess.run([sys.executable, "-m", "tmm_cli", "run", str(task), "--lang", "RU", "-f", "html",
                        "-o", str(tmp_path / "fast"), "-q"], capture_output=True, text=True, cwd=ROOT)
    assert p.returncode == 0, p.stderr
    assert '<html lang="ru"' in (tmp_path / "fast" / "report.html").read_text(encoding="utf-8")
    res = runner.invoke(app, ["sheets", str(task), "--lang", "Uk", "-o", str(tmp_path / "sh"), "-f", "svg"])
    assert res.exit_code == 0, res.output
    res = runner.invoke(app, ["run", str(task), "--lang", "de", "-o", str(tmp_path / "de")])
    assert res.exit_code == 2 and "--lang must be en, ru or uk" in res.output
    res = runner.invoke(app, ["run", str(task), "--format", "pdff"])
    assert res.exit_code == 2 and "choose from json, html, pdf, sheets, note" in res.output
    res = runner.invoke(app, ["fields", "flywhel"])
    assert res.exit_code == 2 and "no section or field 'flywhel'; did you mean 'flywheel'?" in res.output
