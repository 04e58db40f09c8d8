"""The crank speed from the output's speed: the course's formulas by hand, and the
resolved omega1 checked against the mean |v| of the output over the cycle (and over the
working stroke) computed from the kinematics at that omega1."""
import math
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from tmm_cli.cli import app
from tmm_cli.linkage.drive_speed import omega_from_mean, omega_from_working
from tmm_cli.errors import TaskError
from tmm_cli.linkage.kinematics import solve
from tmm_cli.linkage.mechanism import build_mechanism
from tmm_cli.linkage.synthesis import generate
from tmm_cli.pipeline import run
from tmm_cli.task import load_task

TASKS = Path(__file__).resolve().parent.parent / "tasks"
SC = {"ground": {"O": [0, 0]},
      "links": {"crank": {"points": ["O", "A"], "length": 0.1}, "rod": {"points": ["A", "B"], "length": 0.4},
                "slider": {"slider": "B", "guide": {"through": [0, -0.05], "angle": 0}}}}


def test_formulas_by_hand():
    # V = 0.5 m/s, H = 0.2 m: omega1 = pi * 0.5/0.2 = 7.853982 rad/s (n = 75 rpm)
    assert omega_from_mean(0.5, 0.2) == pytest.approx(7.853982, abs=1e-6)
    # V_w = 0.6 m/s, H = 0.2, K = 1.2: omega1 = 2 pi 0.6/(0.2 (1 + 1/1.2)) = 3.769911/0.366667 = 10.281576
    assert omega_from_working(0.6, 0.2, 1.2) == pytest.approx(10.281576, abs=1e-6)
    # n1 = 60 V_w/(H (1 + 1/K)) rpm
    assert omega_from_working(0.6, 0.2, 1.2) * 30 / math.pi == pytest.approx(60 * 0.6 / (0.2 * (1 + 1 / 1.2)))
    # K = 1: both give pi V/H
    assert omega_from_working(0.5, 0.2, 1.0) == pytest.approx(omega_from_mean(0.5, 0.2), rel=1e-15)


def _task(drive, mech=SC, **extra):
    return load_task({"schema": "tmm/1", "mechanism": mech, "drive": {"link": "crank", **drive},
                      "positions": {"count": 12, "output": "slider"}, **extra})


def _mean_abs_v(t, r, working_only=False):
    """Mean |v| of the output over the cycle (or the working stroke) at the resolved
    omega1: crank angles uniform in time (omega1 constant), 72000 samples."""
    mech = build_mechanism(t)
    w = r["drive"]["omega"]
    pos = r["positions"]
    sign = 1.0 if w > 0 else -1.0
    span = pos["working_stroke_angle"] if working_only else 360.0
    n = 72000
    u = (np.arange(n) + 0.5) / n * span
    phi = np.mod(pos["phi0"] + sign * u, 360.0)
    k = solve(mech, phi, w)
    out = r["positions"]["output"]
    if pos["output_kind"] == "slider":
        v = np.abs(k.vel(mech.link(out).origin)[:, 0])
    else:
        v = np.abs(k.omega(out))
    return float(v.mean())


def test_mean_output_speed_gives_the_mean_of_abs_v():
    t = _task({"mean_output_speed": "0.5 m/s", "direction": "cw"})
    r = run(t, kinematics_curve=0)
    H = r["positions"]["H"]
    assert r["drive"]["source"] == "mean_output_speed"
    assert r["drive"]["omega"] == pytest.approx(-math.pi * 0.5 / H, rel=1e-12)
    assert r["drive"]["n"] == pytest.approx(30 * 0.5 / H, rel=1e-12)
    assert _mean_abs_v(t, r) == pytest.approx(0.5, rel=1e-6)


def test_working_stroke_speed_gives_the_mean_over_the_working_stroke():
    t = _task({"working_stroke_speed": "600 mm/s"})
    r = run(t, kinematics_curve=0)
    K, H = r["positions"]["K"], r["positions"]["H"]
    assert r["drive"]["omega"] == pytest.approx(2 * math.pi * 0.6 / (H * (1 + 1 / K)), rel=1e-12)
    assert _mean_abs_v(t, r, working_only=True) == pytest.approx(0.6, rel=1e-6)


def test_rocker_output_angular_speed():
    syn = {"type": "crank_rocker", "psi": 40, "K": 1.2, "rocker": 0.3, "frame": 0.4}
    t, _ = generate(load_task({"schema": "tmm/1", "synthesis": syn,
                               "drive": {"link": "crank", "mean_output_speed": "30 deg/s"}}))
    r = run(t, kinematics_curve=0)
    # omega1 = pi V/psi with V and psi in radians: pi (30 deg/s)/(40 deg) = 0.75 pi rad/s
    assert r["drive"]["omega"] == pytest.approx(0.75 * math.pi, rel=1e-9)
    assert _mean_abs_v(t, r) == pytest.approx(math.radians(30), rel=1e-6)


def test_speed_results_unchanged_and_reported():
    t = load_task(TASKS / "engine_slider_crank.yaml")
    r = run(t, kinematics_curve=0)
    assert r["drive"] == {"omega": pytest.approx(t.drive.sign * t.drive.speed, rel=1e-15),
                          "n": pytest.approx(t.drive.speed * 30 / math.pi, rel=1e-15), "source": "speed"}


def test_same_kinematics_as_the_equivalent_speed():
    # the output speed resolved to omega1 gives the same results as `speed: omega1`
    t1 = _task({"mean_output_speed": 0.5})
    r1 = run(t1, kinematics_curve=0)
    t2 = _task({"speed": abs(r1["drive"]["omega"])})
    r2 = run(t2, kinematics_curve=0)
    assert r1["kinematics"] == r2["kinematics"]


@pytest.mark.parametrize("drive,field", [
    ({}, "drive.speed"),
    ({"speed": 10, "mean_output_speed": 0.5}, "drive.mean_output_speed"),
    ({"mean_output_speed": "3 kg"}, "drive.mean_output_speed"),
    ({"working_stroke_speed": -1}, "drive.working_stroke_speed"),
])
def test_bad_drive_speed_exit_2(drive, field):
    with pytest.raises(TaskError) as ei:
        _task(drive)
    assert any(f == field for f, *_ in ei.value.issues), ei.value.render()


def test_linear_speed_for_a_rocker_is_exit_2(tmp_path):
    f = tmp_path / "t.yaml"
    f.write_text("schema: tmm/1\nsynthesis: {type: slotted_lever, K: 1.5, frame: 0.3}\n"
                 "drive: {link: crank, mean_output_speed: 0.5 m/s}\n")
    res = CliRunner().invoke(app, ["run", str(f), "--out", str(tmp_path / "o"), "-f", "json", "-q"])
    assert res.exit_code == 2, res.output
    assert "drive.mean_output_speed" in res.output and ":3" in res.output
