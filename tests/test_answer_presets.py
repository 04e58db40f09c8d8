"""Answer-form presets of the balancing, differential and synthesis chapters (`tmm form -q
balancing|differential|synthesis_function|synthesis_positions|synthesis_path`): the form lists the preset's
quantities with their own symbol and unit in each language (a path's notation by its pattern:
differential.speeds.H is the carrier's speed, not the stroke H), and `tmm check` grades a key
made from the results as all-pass and answers 10 % off as outside."""
from __future__ import annotations

import math
import re
from pathlib import Path

import pytest
import yaml
from typer.testing import CliRunner

from tmm_cli.check import _path_unit, answer_value
from tmm_cli.cli import app
from tmm_cli.forms import notation

runner = CliRunner()
TASKS = Path(__file__).resolve().parent.parent / "tasks"

# example, preset, the paths the preset names there, (path, symbol, unit in en / ru / uk) samples
CASES = {
    "balancing": ("balancing_fourbar", [
        "balancing.max.F", "balancing.max.M", "balancing.max.F_balanced", "balancing.max.M_balanced",
        "balancing.counterweights.crank.m", "balancing.counterweights.rocker.m",
        "balancing.counterweights.crank.angle", "balancing.counterweights.rocker.angle",
        "balancing.rotor.corrections[0].m", "balancing.rotor.corrections[1].m",
        "balancing.rotor.corrections[0].angle", "balancing.rotor.corrections[1].angle"],
        [("balancing.max.F", "F_max", ("N", "Н", "Н")), ("balancing.max.M", "M_max", ("N*m", "Н·м", "Н·м")),
         ("balancing.counterweights.rocker.m", "m_cw", ("kg", "кг", "кг")),
         ("balancing.rotor.corrections[1].angle", "φ_corr", ("deg", "°", "°"))]),
    "differential": ("differential_A", [
        "differential.u", "differential.speeds.1", "differential.speeds.3", "differential.speeds.H",
        "differential.speeds.satellite", "differential.torques.1", "differential.torques.3",
        "differential.torques.H", "differential.power_loss"],
        [("differential.speeds.H", "ω_H", ("rad/s", "рад/с", "рад/с")),
         ("differential.speeds.satellite", "ω_satellite", ("rad/s", "рад/с", "рад/с")),
         ("differential.torques.H", "T_H", ("N*m", "Н·м", "Н·м")),
         ("differential.power_loss", "P_loss", ("W", "Вт", "Вт"))]),
    "synthesis_function": ("synthesis_function", [
        "synthesis.lengths.crank", "synthesis.lengths.coupler", "synthesis.lengths.rocker", "synthesis.lengths.frame",
        "synthesis.K[0]", "synthesis.K[1]", "synthesis.K[2]", "synthesis.structural_error.max",
        "synthesis.structural_error.at_x"],
        [("synthesis.lengths.rocker", "l_rocker", ("m", "м", "м")),
         ("synthesis.structural_error.max", "Δψ_max", ("deg", "°", "°"))]),
    "synthesis_positions": ("synthesis_positions", [
        "synthesis.lengths.crank", "synthesis.lengths.coupler", "synthesis.lengths.rocker", "synthesis.lengths.frame",
        "synthesis.fixed_pivots.O[0]", "synthesis.fixed_pivots.O[1]", "synthesis.fixed_pivots.O1[0]",
        "synthesis.fixed_pivots.O1[1]"],
        [("synthesis.lengths.coupler", "l_coupler", ("m", "м", "м")),
         ("synthesis.fixed_pivots.O1[1]", "y_O1", ("m", "м", "м"))]),
    "synthesis_path": ("synthesis_path", [
        "synthesis.lengths.crank", "synthesis.lengths.coupler", "synthesis.lengths.rocker", "synthesis.lengths.frame",
        "synthesis.fixed_pivots.O[0]", "synthesis.fixed_pivots.O[1]", "synthesis.fixed_pivots.O1[0]",
        "synthesis.fixed_pivots.O1[1]", "synthesis.max_deviation"],
        [("synthesis.fixed_pivots.O[0]", "x_O", ("m", "м", "м")),
         ("synthesis.max_deviation", "Δ_max", ("m", "м", "м"))]),
}


def _form(tmp_path, example, preset, lang):
    out = tmp_path / lang
    res = runner.invoke(app, ["form", str(TASKS / f"{example}.yaml"), "-q", preset, "-o", str(out), "--lang", lang])
    assert res.exit_code == 0, res.output
    return out / f"{example}.key.yaml"


@pytest.mark.parametrize("preset", list(CASES))
def test_preset_form_lists_its_quantities_with_symbol_and_unit(tmp_path, preset):
    example, paths, samples = CASES[preset]
    for i, lang in enumerate(("en", "ru", "uk")):
        key_file = _form(tmp_path, example, preset, lang)
        text = key_file.read_text(encoding="utf-8")
        assert list(yaml.safe_load(text)["answers"]) == paths
        lines = {re.match(r'\s*"([^"]+)"', ln).group(1): ln for ln in text.splitlines() if ln.startswith('  "')}
        for path, sym, units in samples:
            assert f"# {sym}, {units[i]} — " in lines[path], (lang, lines[path])
        if lang != "en":       # the comments in the language: no English unit word left
            comments = " ".join(ln.split("#", 1)[1] for ln in lines.values())
            assert not re.search(r", (m|N|kg|deg|W|N\*m|rad/s) —", comments), comments


@pytest.mark.parametrize("preset", list(CASES))
def test_preset_key_passes_and_ten_percent_off_fails(tmp_path, preset):
    example, paths, _ = CASES[preset]
    key_file = _form(tmp_path, example, preset, "en")
    task = str(TASKS / f"{example}.yaml")
    res = runner.invoke(app, ["check", task, "--answers", str(key_file), "-q", preset, "-o", str(tmp_path / "ok")])
    assert res.exit_code == 0, res.output
    key = yaml.safe_load(key_file.read_text(encoding="utf-8"))
    # a reference that is round-off (the balanced shaking force, 1e-14 N; the example four-bar's
    # O at the origin and O1 on the x axis) has no 10 % to miss
    off = {p: 1.1 * v for p, v in key["answers"].items() if abs(v) > 1e-9}
    assert len(off) >= len(paths) - (3 if preset == "synthesis_positions" else 1)
    bad = tmp_path / "off.yaml"
    bad.write_text(yaml.safe_dump({"variant": key["variant"], "answers": off}), encoding="utf-8")
    res = runner.invoke(app, ["check", task, "--answers", str(bad), "-o", str(tmp_path / "off")])
    assert res.exit_code == 1, res.output
    import csv
    rows = list(csv.DictReader((tmp_path / "off" / "check.csv").open(encoding="utf-8")))
    assert {r["path"] for r in rows} == set(off)
    # a wrong answer; an angle near 180 deg 10 % off (173.7 -> 191.0) is also near its
    # reference's opposite (-191.0 = 169.0 deg), which the grader names a wrong sign
    assert all(r["status"] == "outside" or (r["status"] == "sign" and r["path"].endswith(".angle"))
               for r in rows), [(r["path"], r["status"]) for r in rows]


def test_differential_key_against_willis(tmp_path):
    """The differential's preset values against Willis' formula by hand: scheme A, z1 = 27,
    z3 = 87, n1 = 1000 rpm, n3 = -200 rpm; u = -z3/z1, omega_H = (omega1 - u omega3)/(1 - u);
    the satellite (z2 = 30) from omega2 - omega_H = -(z1/z2)(omega1 - omega_H); T1 = 50 N*m and
    the torques balance, the power lost being the sum of the powers."""
    a = yaml.safe_load(_form(tmp_path, "differential_A", "differential", "en").read_text(encoding="utf-8"))["answers"]
    r = {"differential": {"u": a["differential.u"],
                          "speeds": {k: a[f"differential.speeds.{k}"] for k in ("1", "3", "H", "satellite")},
                          "torques": {k: a[f"differential.torques.{k}"] for k in ("1", "3", "H")},
                          "power_loss": a["differential.power_loss"]}}
    from tmm_cli.results import lookup
    u = -87 / 27
    w1, w3 = 1000 * math.pi / 30, -200 * math.pi / 30
    wh = (w1 - u * w3) / (1 - u)
    w2 = wh - 27 / 30 * (w1 - wh)
    assert lookup(r, "differential.u") == pytest.approx(u, rel=1e-12)
    assert lookup(r, "differential.speeds.H") == pytest.approx(wh, rel=1e-12)
    assert lookup(r, "differential.speeds.satellite") == pytest.approx(w2, rel=1e-12)
    t = [lookup(r, f"differential.torques.{k}") for k in ("1", "3", "H")]
    assert t[0] == 50 and sum(t) == pytest.approx(0, abs=1e-9)
    loss = sum(ti * wi for ti, wi in zip(t, (w1, w3, wh)))
    assert lookup(r, "differential.power_loss") == pytest.approx(loss, rel=1e-9)
    assert 0 < loss < 0.05 * t[0] * w1          # a few per cent of the input power: η = 0.97 per mesh


def test_carrier_speed_is_not_the_stroke():
    """differential.speeds.H ends in H, the stroke's key ('m or deg'): its notation and the
    grader's unit are the carrier's speed (rad/s), so '84.21 rpm' reads as 8.818 rad/s and
    a length is refused; positions.H keeps the stroke's."""
    assert _path_unit("differential.speeds.H") == "rad/s"
    assert notation("differential.speeds.H").startswith("ω_H, rad/s — ")
    assert notation("positions.H").startswith("H, m or deg — ")
    assert answer_value("84.2105263157895 rpm", "differential.speeds.H") == pytest.approx(
        84.2105263157895 * math.pi / 30, rel=1e-12)
    with pytest.raises(ValueError):
        answer_value("8.8 m", "differential.speeds.H")
    assert _path_unit("balancing.max.M") == "N*m" and _path_unit("differential.power_loss") == "W"
    assert answer_value("0.14385 кВт", "differential.power_loss") == pytest.approx(143.85)


def test_answers_for_a_chapter_the_task_lacks_are_not_computed(tmp_path):
    """An answer into `differential` or `balancing` for a task without that stage is
    not_computed (the task has no such stage), not a misspelt path."""
    ans = tmp_path / "a.yaml"
    ans.write_text("variant: 1\nanswers:\n  differential.speeds.H: 8.8\n  balancing.max.F: 59\n"
                   "  synthesis.lengths.crank: 0.08\n", encoding="utf-8")
    res = runner.invoke(app, ["check", str(TASKS / "synthesis_positions.yaml"), "--answers", str(ans),
                              "-o", str(tmp_path / "o")])
    import csv
    rows = {r["path"]: r["status"] for r in csv.DictReader((tmp_path / "o" / "check.csv").open(encoding="utf-8"))}
    assert rows == {"differential.speeds.H": "not_computed", "balancing.max.F": "not_computed",
                    "synthesis.lengths.crank": "ok"}, (rows, res.output)


def test_a_synthesis_length_named_for_what_it_is():
    """synthesis.lengths.* are link lengths l_<link>, but a slider-crank's `offset` keeps the
    eccentricity's symbol e and a shaper's `guide_height` is h, not a 'link length'."""
    assert notation("synthesis.lengths.rod") == "l_rod, m — link length"
    assert notation("synthesis.lengths.offset", "ru", local_units=True) == "e, м — эксцентриситет"
    assert notation("synthesis.lengths.guide_height").startswith("h, m — height of the ram guide")
    assert _path_unit("synthesis.lengths.offset") == "m"
    assert answer_value("12 mm", "synthesis.lengths.offset") == pytest.approx(0.012)


def test_zero_for_the_balanced_shaking_force_passes(tmp_path):
    """After full balancing the shaking force is zero but for round-off (about 1e-14 N in
    results.json): a student's 0 is right, and 5 N is not."""
    import csv
    ans = tmp_path / "a.yaml"
    ans.write_text("variant: 3\nanswers:\n  balancing.max.F_balanced: 0\n  balancing.shaking_balanced[0].F: 5 N\n",
                   encoding="utf-8")
    runner.invoke(app, ["check", str(TASKS / "balancing_fourbar.yaml"), "--answers", str(ans), "-o", str(tmp_path / "o")])
    rows = {r["path"]: r for r in csv.DictReader((tmp_path / "o" / "check.csv").open(encoding="utf-8"))}
    assert abs(float(rows["balancing.max.F_balanced"]["reference"])) < 1e-9
    assert rows["balancing.max.F_balanced"]["status"] == "ok"
    assert rows["balancing.shaking_balanced[0].F"]["status"] == "outside"


def test_a_name_means_its_quantity_only_in_its_own_section():
    """A key's notation by its last name holds in its own section only: a link's J is no
    flywheel's (it was labelled "J_fly -- flywheel moment of inertia"), gears.a is the centre
    distance (it was read as an acceleration: '120 mm' refused as a wrong unit),
    planetary.r.z1 a radius (it was "z1 -- teeth", a plain number), differential.powers.H a
    power, not the stroke H; graphical_error's relative errors carry none."""
    from tmm_cli.forms import key_notation, unit_of
    assert key_notation("flywheel.J")[0] == "J_fly" and unit_of("flywheel.J") == "kg*m^2"
    for path in ("synthesis.mechanism.links.coupler.J", "structure.links[2].J", "gears.a", "planetary.r.z1",
                 "differential.powers.H", "drive_train.velocity_plan.H", "dof2.parameters.a",
                 "graphical_error.plans.positions[1].points.A.v", "flywheel.J_n_methods.energy-mass",
                 "kinematics_curve.s[3]", "balancing.counterweights.crank.r"):
        assert key_notation(path) is None, path
    assert unit_of("positions.H") == "m or deg" and unit_of("gears.r[1]") == "m" and unit_of("cam.a[4]") is None
    assert key_notation("planetary.candidates[2].z.z1")[1] == "" and unit_of("kinematics[1].points.B.v") == "m/s"
    assert answer_value("120 \u043c\u043c", "gears.a") == pytest.approx(0.12)


def test_synthesis_and_drive_train_presets_ask_what_a_student_computes(tmp_path):
    """The synthesis and drive-train presets list the designed quantities with their notation,
    not the task's own data (the generated links' masses, the efficiency, the tolerance, the
    plan's scales: they were "every number under the section"); a misspelt preset is told."""
    res = runner.invoke(app, ["form", str(TASKS / "synthesis_crank_rocker.yaml"), "-q", "synthesis",
                              "--out", str(tmp_path)])
    assert res.exit_code == 0, res.output
    form = yaml.safe_load((tmp_path / "synthesis_crank_rocker.form.yaml").read_text(encoding="utf-8"))["answers"]
    assert list(form) == ["synthesis.lengths.crank", "synthesis.lengths.coupler", "synthesis.lengths.rocker",
                          "synthesis.lengths.frame", "synthesis.theta", "synthesis.gamma_min", "synthesis.gamma_min_phi"]
    text = (tmp_path / "synthesis_crank_rocker.form.yaml").read_text(encoding="utf-8")
    assert "# γ_min, deg — least transmission angle" in text
    res = runner.invoke(app, ["form", str(TASKS / "press_drive_train.yaml"), "-q", "drive_train", "--out", str(tmp_path)])
    form = yaml.safe_load((tmp_path / "press_drive_train.form.yaml").read_text(encoding="utf-8"))["answers"]
    assert not [p for p in form if re.search(r"efficiency|tolerance|velocity_plan|candidates|split", p)], list(form)
    assert {"drive_train.ratio", "drive_train.motor_power", "drive_train.stages[2].omega_carrier"} <= set(form)
    text = (tmp_path / "press_drive_train.form.yaml").read_text(encoding="utf-8")
    assert "Δi — ratio error (fraction); signed: (obtained - required) / required" in text
    res = runner.invoke(app, ["form", str(TASKS / "differential_A.yaml"), "-q", "differntial", "--out", str(tmp_path)])
    assert res.exit_code == 2 and "did you mean the preset 'differential'" in res.output


def test_presets_ask_nothing_that_is_zero_by_construction_or_given(tmp_path):
    """The kinematics preset leaves out a fixed pivot's velocity and acceleration (O: 0 in every
    variant) and a slider's omega and epsilon on a fixed guide (the piston: 0), keeps a slide block's
    on a moving guide (it turns with the slotted lever); the flywheel preset leaves out the given
    delta."""
    from tmm_cli import load_task, run
    from tmm_cli.forms import expand
    res = run(load_task(TASKS / "engine_slider_crank.yaml"))
    got = expand("kinematics,flywheel", res)
    assert not [p for p in got if ".points.O." in p or ".links.piston." in p or p == "flywheel.delta"], got
    assert "kinematics[1].points.B.v" in got and "kinematics[1].links.rod.epsilon" in got and "flywheel.J" in got
    got = expand("kinematics", run(load_task(TASKS / "shaper_slotted_lever.yaml")))
    assert "kinematics[1].links.block.omega" in got and not [p for p in got if ".links.ram." in p]
    # the Scotch yoke's block and yoke translate (omega 0 at every position); its crank turns at a
    # constant speed (epsilon 0): none asked
    got = expand("kinematics", run(load_task(TASKS / "scotch_yoke_pump.yaml")))
    assert [p for p in got if ".links." in p] == ["kinematics[1].links.crank.omega"]


def test_a_rocker_followers_curves_take_their_own_unit(tmp_path):
    """cam.v and cam.a of a rocker follower (rad/s, rad/s^2), and kinematics_curve.v and .a of a
    rocker output, are angular: an answer '3.21 rad/s' was refused as 'does not convert to m/s'
    once every path ending in v took m/s; they take the unit written, as before."""
    from tmm_cli.check import answer_value
    assert answer_value("3.21 rad/s", "cam.v[10]") == pytest.approx(3.21)
    assert answer_value("510 rad/s^2", "cam.a[10]") == pytest.approx(510.0)
    assert answer_value("2 rad/s", "kinematics_curve.v[100]") == pytest.approx(2.0)
    assert answer_value("1200 mm/s", "kinematics[1].points.B.v") == pytest.approx(1.2)


def test_a_position_preset_asks_at_a_position_the_task_computes(tmp_path):
    """The kinetostatics preset asked at position 1 only: with `kinetostatics: {positions: [3]}`
    (the tutorial's kind of task) it found nothing and wrote no form. Now the first position the
    task computes; 'kinetostatics[3]' (or 'kinematics[5]') asks at the position it names, and a
    position not computed is an error naming those that are."""
    from tmm_cli import load_task, run
    from tmm_cli.errors import TaskError
    from tmm_cli.forms import expand
    src = (TASKS / "engine_slider_crank.yaml").read_text(encoding="utf-8")
    assert "\nkinetostatics:\n  positions: all\n" in src
    task = tmp_path / "e.yaml"
    task.write_text(src.replace("\nkinetostatics:\n  positions: all\n", "\nkinetostatics:\n  positions: [3, 7]\n"),
                    encoding="utf-8")
    res = run(load_task(task))
    assert [e["index"] for e in res["kinetostatics"]] == [3, 7]
    got = expand("kinetostatics", res)
    assert got and all(p.startswith("kinetostatics[3].") for p in got), got
    assert "kinetostatics[3].balancing_moment" in got
    assert all(p.startswith("kinetostatics[7].") for p in expand("kinetostatics[7]", res))
    assert "kinematics[5].points.B.v" in expand("kinematics[5]", res)
    assert "kinematics[1].points.B.v" in expand("kinematics", res)          # kinematics: position 1 is there
    with pytest.raises(TaskError, match=r"no position 5 \(positions computed: 3, 7\)"):
        expand("kinetostatics[5]", res)


def test_a_form_tells_the_crank_angle_of_each_position_it_asks_at(tmp_path):
    """A form asking kinematics[3] and kinetostatics[7] did not say which crank angle position 3
    is: a comment now gives the crank's angle at each, as results.json holds it (every
    30 deg from position 0's phi0 for 12 positions, in the crank's sense)."""
    src = (TASKS / "engine_slider_crank.yaml").read_text(encoding="utf-8")
    task = tmp_path / "e.yaml"
    task.write_text(src, encoding="utf-8")
    res = runner.invoke(app, ["form", str(task), "-q", "kinematics[3].points.B.v,kinetostatics[7].balancing_moment",
                              "--out", str(tmp_path / "f")])
    assert res.exit_code == 0, res.output
    from tmm_cli import load_task, run
    r = run(load_task(task))
    phi0 = r["positions"]["phi0"]
    sense = 1.0 if r["positions"]["direction"] == "ccw" else -1.0
    want = [(k, (phi0 + sense * 30.0 * k) % 360.0) for k in (3, 7)]
    for name in ("e.form.yaml", "e.key.yaml"):
        text = (tmp_path / "f" / name).read_text(encoding="utf-8")
        line = next(ln for ln in text.splitlines() if "crank's angle" in ln)
        got = [(int(k), float(v)) for k, v in re.findall(r"(\d+): \u03c6 = ([\d.]+)\u00b0", line)]
        assert [k for k, _ in got] == [3, 7] and all(abs(g - w) < 0.051 for (_, g), (_, w) in zip(got, want)), line
    plain = runner.invoke(app, ["form", str(task), "-q", "flywheel", "--out", str(tmp_path / "g")])
    assert plain.exit_code == 0 and "crank's angle" not in (tmp_path / "g" / "e.form.yaml").read_text(encoding="utf-8")


def test_a_quantity_pattern_asks_every_path_it_matches():
    """`-q 'kinetostatics[3].reactions.*.R'` was 'no key *': a pattern, as the presets write
    theirs (`*` a name, `[*]` an index), asks each path of the results it matches, in their
    order, each once; a pattern matching none is an error saying so."""
    from tmm_cli import load_task, run
    from tmm_cli.errors import TaskError
    from tmm_cli.forms import expand
    res = run(load_task(TASKS / "engine_slider_crank.yaml"))
    want = [f"kinetostatics[3].reactions.{k}.R" for k in res["kinetostatics"][3]["reactions"]]
    assert res["kinetostatics"][3]["index"] == 3 and len(want) >= 4
    assert expand("kinetostatics[3].reactions.*.R", res) == want
    assert expand(f"{want[0]},kinetostatics[3].reactions.*.R", res) == want          # each once
    with pytest.raises(TaskError, match=r"pattern 'gears.r\[\*\]' matches no quantity"):
        expand("gears.r[*]", res)
    assert expand("gears.r[*]", res, strict=False) == []
