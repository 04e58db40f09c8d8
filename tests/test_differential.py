"""Differentials (a planetary scheme with no member fixed) against closed forms written out
by hand, the velocity picture as a second method, and the task-file errors."""
import json
import math

import pytest
from typer.testing import CliRunner

from tmm_cli import load_task
from tmm_cli.cli import app
from tmm_cli.differential import analyze

RPM = math.pi / 30
runner = CliRunner()


def _spec(**kw):
    d = {"schema": "tmm/1", "differential": {"scheme": "A", "z": [27, 30, 87], "satellites": 3,
                                             "speeds": {"1": "1000 rpm", "3": "-200 rpm"}, **kw}}
    return load_task(d).differential


def test_scheme_a_speeds_by_hand():
    # u = -z3/z1 = -87/27; wH = (w1 - u w3)/(1 - u) = (1000 - (87/27)(200)) / (1 + 87/27) rpm
    r = analyze(_spec()).to_dict()
    u = -87 / 27
    wh = (1000 - 87 / 27 * 200) / (1 + 87 / 27)
    assert r["u"] == pytest.approx(u, rel=1e-15)
    assert r["speeds_rpm"]["H"] == pytest.approx(wh, rel=1e-13)
    assert r["speeds"]["H"] == pytest.approx(wh * RPM, rel=1e-13)
    # satellite: relative to the carrier -z1/z2 of wheel 1's, and +z3/z2 of the ring's (the second mesh)
    w1, w3, wH = 1000 * RPM, -200 * RPM, wh * RPM
    ws = wH - 27 / 30 * (w1 - wH)
    assert r["speeds"]["satellite"] == pytest.approx(ws, rel=1e-13)
    assert r["speeds"]["satellite"] == pytest.approx(wH + 87 / 30 * (w3 - wH), rel=1e-12)


@pytest.mark.parametrize("given", [{"1": "1000 rpm", "H": "50 rpm"}, {"3": "-200 rpm", "H": "50 rpm"}])
def test_any_two_members_give_the_third(given):
    r = analyze(_spec(speeds=given)).to_dict()
    w = r["speeds"]
    assert (w["1"] - w["H"]) / (w["3"] - w["H"]) == pytest.approx(-87 / 27, rel=1e-12)
    for k, v in given.items():
        assert r["speeds_rpm"][k] == pytest.approx(float(v.split()[0]), rel=1e-14)


@pytest.mark.parametrize("scheme, z, u", [
    ("B", [20, 40, 20, 80], -(40 * 80) / (20 * 20)),       # -z2 z4/(z1 z3); coaxial 20 + 40 = 80 - 20
    ("C", [40, 20, 30, 30], (20 * 30) / (40 * 30)),        # +z2 z4/(z1 z3); coaxial 40 + 20 = 30 + 30
    ("D", [100, 20, 22, 102], (20 * 102) / (100 * 22)),    # +z2 z4/(z1 z3); coaxial 100 - 20 = 102 - 22
])
def test_two_row_schemes_willis(scheme, z, u):
    spec = load_task({"schema": "tmm/1", "differential": {"scheme": scheme, "z": z, "satellites": 2,
                                                          "speeds": {"1": 300, "4": -100}}}).differential
    r = analyze(spec).to_dict()
    assert r["u"] == pytest.approx(u, rel=1e-15)
    w = r["speeds"]
    assert w["H"] == pytest.approx((300 - u * -100) / (1 - u), rel=1e-13)
    # satellite from the picture (its line through the meshes' points) = the relative-speed formula
    sign = 1 if scheme == "D" else -1
    ws = w["H"] + sign * z[0] / z[1] * (w["1"] - w["H"])
    assert w["satellite"] == pytest.approx(ws, rel=1e-12)
    assert r["velocity_plan"]["satellite_omega_plan"] == pytest.approx(ws, rel=1e-9)
    assert r["velocity_plan"]["mismatch"] < 1e-12 * abs(300 * z[0])


def test_torques_efficiency_one_power_balance():
    r = analyze(_spec(torque={"1": "50 N*m"})).to_dict()
    T, w = r["torques"], r["speeds"]
    # T3 = -u T1 = (87/27) 50; TH = -(T1 + T3)
    assert T["3"] == pytest.approx(87 / 27 * 50, rel=1e-14)
    assert T["1"] + T["3"] + T["H"] == pytest.approx(0, abs=1e-12)
    assert T["1"] * (w["1"] - w["H"]) + T["3"] * (w["3"] - w["H"]) == pytest.approx(0, abs=1e-9)
    assert r["power_loss"] == pytest.approx(0, abs=1e-9)


def test_torques_with_efficiency_hand_values():
    # wheel 1 drives the relative motion (T1 (w1 - wH) > 0): T3 = -u eta T1 = (87/27)(0.95)(50)
    r = analyze(_spec(torque={"1": 50}, efficiency=0.95)).to_dict()
    T, w = r["torques"], r["speeds"]
    assert T["3"] == pytest.approx(87 / 27 * 0.95 * 50, rel=1e-14)
    assert T["H"] == pytest.approx(-50 - 87 / 27 * 0.95 * 50, rel=1e-14)
    loss = 50 * (w["1"] - w["H"]) * (1 - 0.95)          # the relative power in, times (1 - eta)
    assert r["power_loss"] == pytest.approx(loss, rel=1e-12)
    assert r["relative_driver"] == "1"


def test_ring_torque_given_ring_drives():
    # T1 sign: -T3/u; here T3 = 100, u < 0 -> T1 > 0 ... relative power of 1: T1 (w1 - wH) > 0 -> 1 drives
    # choose T3 = -100: T1 < 0, wheel 3 drives the relative motion: T1 = -T3/(u / eta) = -(-100) eta/u
    eta = 0.9
    r = analyze(_spec(torque={"3": -100}, efficiency=eta)).to_dict()
    u = -87 / 27
    assert r["torques"]["1"] == pytest.approx(100 * eta / u, rel=1e-13)
    assert r["relative_driver"] == "last"
    w, T = r["speeds"], r["torques"]
    p1, p3 = T["1"] * (w["1"] - w["H"]), T["3"] * (w["3"] - w["H"])
    assert p1 == pytest.approx(-eta * p3, rel=1e-12)


def test_carrier_torque_given():
    eta = 0.9
    r = analyze(_spec(torque={"H": -300}, efficiency=eta)).to_dict()
    T, w = r["torques"], r["speeds"]
    assert T["H"] == -300
    assert T["1"] + T["3"] + T["H"] == pytest.approx(0, abs=1e-12)
    p1, p3 = T["1"] * (w["1"] - w["H"]), T["3"] * (w["3"] - w["H"])
    # whichever drives, the other receives eta of its relative power
    assert (p3 == pytest.approx(-eta * p1, rel=1e-12)) if p1 > 0 else (p1 == pytest.approx(-eta * p3, rel=1e-12))


def test_given_teeth_breaking_limits_are_computed_with_a_warning():
    # the book's ring 72, sun 32 (satellite 20): z3 = 72 < 85 and assembly with 3 satellites fails
    # ((32 + 72)/3 not whole): computed, each condition named, and which numbers of satellites assemble
    r = analyze(_spec(z=[32, 20, 72])).to_dict()
    assert r["checks"]["tooth_limits"] is False and r["checks"]["assembly"] is False
    text = " ".join(map(str, r["warnings"]))
    assert "z3 = 72 < 85" in text and "cannot be assembled" in text
    assert "fit: 1, 2, 4" in text      # (32 + 72)/k whole for k = 1, 2, 4, 8, 13; 8 satellites overlap (adjacency)
    assert r["speeds"]["H"] == pytest.approx((1000 * RPM + 72 / 32 * -200 * RPM) / (1 + 72 / 32), rel=1e-13)


def _run(tmp_path, text):
    f = tmp_path / "d.yaml"
    f.write_text("schema: tmm/1\ndifferential:\n" + text, encoding="utf-8")
    res = runner.invoke(app, ["run", str(f), "--format", "json", "--out", str(tmp_path / "o")])
    return res.exit_code, res.output, f


@pytest.mark.parametrize("text, field, words", [
    ("  scheme: A\n  z: [20, 25, 71]\n  speeds: {\"1\": 100, \"3\": 10}\n", "differential.z", "not coaxial"),
    ("  scheme: A\n  z: [20, 25, 70]\n  satellites: 9\n  speeds: {\"1\": 100, \"3\": 10}\n",
     "differential.satellites", "do not fit"),
    ("  scheme: A\n  z: [20, 25, 70]\n  speeds: {\"1\": 100}\n", "differential.speeds", "exactly two"),
    ("  scheme: A\n  z: [20, 25, 70]\n  speeds: {\"1\": 100, \"4\": 10}\n", "differential.speeds.4",
     "not a member"),
    ("  scheme: B\n  z: [20, 25, 70]\n  speeds: {\"1\": 100, \"4\": 10}\n", "differential.z", "4 tooth numbers"),
    ("  scheme: C\n  z: [30, 20, 20, 30]\n  speeds: {\"1\": 100, \"4\": 10}\n", "differential.speeds",
     "turn together"),
])
def test_invalid_differentials_exit_2_naming_the_field(tmp_path, text, field, words):
    code, out, f = _run(tmp_path, text)
    assert code == 2, out
    assert field in out and words in out and "Traceback" not in out
    assert f"{f}:" in out or str(f) in out


def test_example_task_runs_and_its_numbers_hold(tmp_path):
    from pathlib import Path
    task = Path(__file__).resolve().parent.parent / "tasks" / "differential_A.yaml"
    res = runner.invoke(app, ["run", str(task), "--format", "json,html", "--out", str(tmp_path / "o")])
    assert res.exit_code == 0, res.output
    d = json.loads((tmp_path / "o" / "results.json").read_text())["differential"]
    u = -87 / 27
    assert d["speeds_rpm"]["H"] == pytest.approx((1000 - u * -200) / (1 - u), rel=1e-13)
    assert d["torques"]["3"] == pytest.approx(-u * 0.97 * 50, rel=1e-13)
    html = (tmp_path / "o" / "report.html").read_text(encoding="utf-8")
    assert 'id="differential"' in html and html.count("<svg") >= 1
    assert (tmp_path / "o" / "figures" / "differential-velocity.svg").is_file()


# --- the carrier's torque given: Willis' formula with eta^k, T1 (1 - u eta^k) = -TH ---------------------------

def _c_u1(speeds, **kw):
    """Scheme C with z2 z4 = z1 z3 (40 * 20 = 20 * 40): u = +z2 z4/(z1 z3) = 1."""
    return load_task({"schema": "tmm/1", "differential": {"scheme": "C", "z": [20, 40, 40, 20], "satellites": 3,
                                                          "speeds": speeds, **kw}}).differential


@pytest.mark.parametrize("speeds, eta", [
    ({"1": 10, "H": 12}, 1.0),      # eta = 1: T4 = -u T1 = -T1
    ({"1": 10, "H": 10}, 1.0),      # w1 = wH: no relative motion, eta^0 = 1
    ({"1": 10, "H": 10}, 0.9),      # the same with a lossy train
])
def test_u1_carrier_torque_cannot_be_balanced(tmp_path, speeds, eta):
    # u = 1 and eta^k = 1: T4 = -u eta^k T1 = -T1, so TH = -(T1 + T4) = 0 whatever T1; TH = 5 has no balance
    from tmm_cli.errors import TaskError
    with pytest.raises(TaskError) as e:
        analyze(_c_u1(speeds, torque={"H": 5}, efficiency=eta))
    assert "differential.torque.H" in str(e.value) and "cannot be balanced" in str(e.value)
    # TH = 0 leaves T1 open
    with pytest.raises(TaskError) as e:
        analyze(_c_u1(speeds, torque={"H": 0}, efficiency=eta))
    assert "undetermined" in str(e.value)
    # the command: an invalid task naming the field (exit 2), no ZeroDivisionError
    sp = ", ".join(f'"{k}": {v}' for k, v in speeds.items())
    code, out, _ = _run(tmp_path, f"  scheme: C\n  z: [20, 40, 40, 20]\n  speeds: {{{sp}}}\n  torque: {{H: 5}}\n"
                                  f"  efficiency: {eta}\n")
    assert code == 2, out
    assert "differential.torque.H" in out and "ZeroDivision" not in out


def test_u1_lossy_train_torque_of_wheel_1_by_willis():
    # u = 1, eta = 0.9, w1 - wH = 10 - 12 = -2; T1 = -20: T1 (w1 - wH) = 40 > 0, wheel 1 drives (k = +1):
    # T4 = -u eta T1 = 0.9 * 20 = 18, TH = -(T1 + T4) = 2
    r = analyze(_c_u1({"1": 10, "H": 12}, torque={"1": -20}, efficiency=0.9)).to_dict()
    assert r["u"] == 1
    assert r["torques"]["4"] == pytest.approx(18, rel=1e-14)
    assert r["torques"]["H"] == pytest.approx(2, rel=1e-13)
    assert r["relative_driver"] == "1"


def test_both_power_flows_balancing_the_carrier_torque_is_named_as_such():
    # scheme D, z = [90, 30, 26, 86]: u = z2 z4/(z1 z3) = 30 * 86/(90 * 26) = 43/39; w1 = -50, w4 = 20 rad/s:
    # wH = (w1 - u w4)/(1 - u) = (-50 - 860/39)/(-4/39) = 702.5, w1 - wH = -752.5.
    # TH = 40: k = +1: T1 = -TH/(1 - u eta) = -40/(1 - 38.7/39) = -5200, T1 (w1 - wH) > 0: consistent;
    #          k = -1: T1 = -TH/(1 - u/eta) = -40/(1 - 430/351) = 40 * 351/79, T1 (w1 - wH) < 0: consistent too
    from tmm_cli.errors import StageError
    spec = load_task({"schema": "tmm/1", "differential": {
        "scheme": "D", "z": [90, 30, 26, 86], "satellites": 3, "speeds": {"1": -50, "4": 20},
        "torque": {"H": 40}, "efficiency": 0.9}}).differential
    with pytest.raises(StageError) as e:
        analyze(spec)
    msg = e.value.message
    assert msg.code == "differential.fail.indeterminate"
    assert msg.params["t1_first"] == pytest.approx(-5200, rel=1e-12)
    assert msg.params["t1_last"] == pytest.approx(40 * 351 / 79, rel=1e-12)
    assert "self-locks" not in str(msg)
    # TH = -40: k = +1 gives T1 = +5200 (T1 (w1 - wH) < 0), k = -1 gives T1 = -40 * 351/79 (> 0): none is
    # consistent, the train self-locks
    spec = load_task({"schema": "tmm/1", "differential": {
        "scheme": "D", "z": [90, 30, 26, 86], "satellites": 3, "speeds": {"1": -50, "4": 20},
        "torque": {"H": -40}, "efficiency": 0.9}}).differential
    with pytest.raises(StageError) as e:
        analyze(spec)
    assert e.value.message.code == "differential.fail.self_locking"


def test_u1_lossy_carrier_torque_has_two_balances():
    # u = 1, eta = 0.9 (d14): k = +1: T1 = -5/(1 - 0.9) = -50, T1 (w1 - wH) = -50 * -2 > 0;
    # k = -1: T1 = -5/(1 - 1/0.9) = 45, T1 (w1 - wH) < 0: both consistent
    from tmm_cli.errors import StageError
    with pytest.raises(StageError) as e:
        analyze(_c_u1({"1": 10, "H": 12}, torque={"H": 5}, efficiency=0.9))
    p = e.value.message.params
    assert (p["t1_first"], p["t1_last"]) == (pytest.approx(-50, rel=1e-12), pytest.approx(45, rel=1e-12))


def test_zero_carrier_torque_with_a_lossy_train_is_no_load():
    # T1 (1 - u eta^k) = 0 with 1 - u eta^k != 0 for both k: T1 = 0, so T3 = TH = 0
    r = analyze(_spec(torque={"H": 0}, efficiency=0.9)).to_dict()
    assert r["torques"] == {"1": 0, "3": 0, "H": 0}
    assert r["relative_driver"] is None
