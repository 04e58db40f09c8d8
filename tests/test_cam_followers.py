"""Flat-faced and knife-edge followers, a cam built on a chosen size, the division table.

Independent references (the laws and the motion from tests/test_acceptance_cam.py, which
imports nothing from tmm_cli):

* flat follower on an eccentric disc of radius R, eccentricity e: the face is at the distance
  p = R + e sin(...) from O, so s = e (1 - cos phi) (cosine rise and return over 180 deg each,
  h = 2 e), r0 = R - e, the profile is the disc itself (radius of curvature R everywhere) and
  the contact point runs +-e along the face (ds/dphi = e sin phi);
* chosen size: tan(theta) = |ds/dphi - e| / (sqrt(r0^2 - e^2) + s) on a brute-force sweep of
  400001 points a cycle;
* r0_min: the synthesis of the smallest cam with the same offset (translating) or the cam
  with the same centre distance (rocker);
* the division table against the law formulas written out by hand.
"""
from __future__ import annotations

import copy
import math

import numpy as np
import pytest

import tmm_cli
from tmm_cli.errors import StageError, TaskError

from test_acceptance_cam import Motion, law

TRANS = {"schema": "tmm/1", "cam": {
    "follower": "translating", "stroke": 0.03, "offset": 0.0,
    "phases": {"rise": 120, "far_dwell": 30, "return": 120},
    "laws": {"rise": "sine", "return": "cosine"}, "pressure_angle": 30, "rotation": "ccw"}}


def run(task, **kw):
    d = copy.deepcopy(task)
    d["cam"].update(kw)
    for k in [k for k, v in kw.items() if v is None]:
        del d["cam"][k]
    return tmm_cli.run(tmm_cli.load_task(d))["cam"]


# ------------------------------------------------------------------ flat follower
@pytest.mark.parametrize("rotation", ["ccw", "cw"])
def test_flat_follower_on_an_eccentric_disc(rotation):
    R, e = 0.04, 0.01
    c = run({"schema": "tmm/1", "cam": {
        "follower": "flat", "stroke": 2 * e, "phases": {"rise": 180, "far_dwell": 0, "return": 180},
        "laws": {"rise": "cosine", "return": "cosine"}, "rho_min_allowed": R, "rotation": rotation}})
    assert c["r0"] == pytest.approx(R - e, rel=1e-12)
    assert c["r0_min"] == pytest.approx(R - e, rel=1e-12)
    assert c["rho_min"] == pytest.approx(R, rel=1e-12)
    assert c["face_width"] == pytest.approx(2 * e, rel=1e-9)
    assert c["face_width_symmetric"] == pytest.approx(2 * e, rel=1e-9)
    assert c["max_pressure_angle"] == 0 and max(c["pressure_angle"]) == 0
    P = np.asarray(c["working_profile"])
    # the disc: centre at distance e from O opposite to the follower at phi = 0 (lowest position)
    assert np.hypot(P[:, 0], P[:, 1] + e) == pytest.approx(np.full(len(P), R), rel=1e-12)
    # the contact point at phi = 90 deg lies e sin 90 = e along the face from the follower's axis
    # (sigma e), the face at r0 + s = R - e + e = R from O; turned back by -sigma 90 deg
    sg = 1 if rotation == "ccw" else -1
    x, y = sg * e, R
    a = -sg * math.pi / 2
    assert P[90] == pytest.approx([x * math.cos(a) - y * math.sin(a), x * math.sin(a) + y * math.cos(a)],
                                  abs=1e-15)


def test_flat_follower_size_by_hand():
    """Cosine rise over 120 deg (h = 20 mm), sine return over 120 deg: -s - s'' is largest at the
    end of the rise, -h + h pi^2/(2 P^2) = -h + 9/8 h, or on the return (sine: -h(1-f) + h 2pi/P^2
    sin 2pi x), found here on a dense grid; the face spans ds/dphi from -2h/P (sine) to
    h pi/(2P) (cosine)."""
    h, rho = 0.02, 0.005
    c = run({"schema": "tmm/1", "cam": {
        "follower": "flat", "stroke": h, "phases": {"rise": 120, "far_dwell": 30, "return": 120},
        "laws": {"rise": "cosine", "return": "sine"}, "rho_min_allowed": rho}})
    mo = Motion(h, {"rise": 120, "far_dwell": 30, "return": 120}, {"rise": "cosine", "return": "sine"})
    best = -math.inf
    for which in ("rise", "return"):
        x = np.linspace(0, 1, 400001)
        s, s1, s2 = mo.phase(which, x)
        best = max(best, float(np.max(-s - s2)))
    best = max(best, 0.0, -h)                       # the dwells: -s
    assert c["r0"] == pytest.approx(rho + best, rel=1e-9)
    assert c["rho_min"] == pytest.approx(rho, abs=1e-15)
    P = math.radians(120)
    assert c["face_width"] == pytest.approx(h * math.pi / (2 * P) + 2 * h / P, rel=1e-12)
    assert c["face_width_symmetric"] == pytest.approx(2 * 2 * h / P, rel=1e-12)


def test_flat_chosen_size_and_errors():
    task = {"schema": "tmm/1", "cam": {"follower": "flat", "stroke": 0.02,
                                       "phases": {"rise": 120, "far_dwell": 30, "return": 120},
                                       "laws": {"rise": "cosine", "return": "sine"}, "rho_min_allowed": 0.005}}
    auto = run(task)
    c = run(task, r0=0.03)
    assert c["r0"] == 0.03 and c["r0_min"] == pytest.approx(auto["r0"], rel=1e-15)
    assert c["rho_min"] == pytest.approx(0.03 - auto["r0"] + 0.005, rel=1e-12)
    with pytest.raises(StageError, match="least radius of curvature"):
        run(task, r0=0.01)
    with pytest.raises(StageError, match="velocity jumps"):
        run(task, laws={"rise": "constant_velocity", "return": "sine"})
    with pytest.raises(TaskError, match="roller"):
        run(task, roller=0.005)
    with pytest.raises(TaskError, match="rho_min_allowed"):
        run(TRANS, rho_min_allowed=0.005)


# ------------------------------------------------------------------ knife edge
def test_knife_edge_is_the_roller_pitch_profile():
    roller = run(TRANS, offset=0.004)
    knife = run(TRANS, offset=0.004, follower="knife")
    assert knife["roller"] == 0
    assert knife["working_profile"] == knife["pitch_profile"] == roller["pitch_profile"]
    assert knife["r0"] == roller["r0"] and knife["max_pressure_angle"] == roller["max_pressure_angle"]
    with pytest.raises(TaskError, match="roller"):
        run(TRANS, follower="knife", roller=0.004)


# ------------------------------------------------------------------ chosen size
def _sweep(mo, r0, e):
    phi = np.linspace(0, 2 * math.pi, 400001)
    s, s1, _ = mo.at(phi)
    th = np.degrees(np.arctan(np.abs(s1 - e) / (math.sqrt(r0 ** 2 - e ** 2) + s)))
    return th, np.degrees(phi)


@pytest.mark.parametrize("follower,e,r0,rotation", [("translating", 0.006, 0.05, "ccw"),
                                                    ("knife", -0.004, 0.045, "cw"),
                                                    ("translating", 0.0, 0.06, "ccw")])
def test_chosen_size_against_a_brute_force_sweep(follower, e, r0, rotation):
    c = run(TRANS, follower=follower, offset=e, r0=r0, rotation=rotation)
    mo = Motion(0.03, TRANS["cam"]["phases"], {"rise": "sine", "return": "cosine"})
    th, phi = _sweep(mo, r0, e)
    assert c["r0"] == r0
    assert c["max_pressure_angle"] == pytest.approx(float(th.max()), abs=1e-4)
    assert c["max_pressure_angle_phi"] == pytest.approx(float(phi[np.argmax(th)]), abs=0.01)
    # the 1-deg table: the formula at each degree
    s, s1, _ = mo.at(np.radians(np.arange(360.0)))
    ref = np.degrees(np.arctan(np.abs(s1 - e) / (math.sqrt(r0 ** 2 - e ** 2) + s)))
    assert c["pressure_angle"] == pytest.approx(list(ref), abs=1e-9)
    # r0_min: the smallest cam with the same offset
    assert c["r0_min"] == pytest.approx(run(TRANS, follower=follower, offset=e, rotation=rotation)["r0"],
                                        rel=1e-13)


def test_chosen_size_violating_the_allowed_angle_names_excess_and_where():
    e, r0 = 0.005, 0.03
    mo = Motion(0.03, TRANS["cam"]["phases"], {"rise": "sine", "return": "cosine"})
    th, phi = _sweep(mo, r0, e)
    with pytest.raises(StageError) as err:
        run(TRANS, offset=e, r0=r0)
    msg = err.value.message
    assert f"{th.max() - 30:.2f} deg over the allowed 30 deg" in msg
    assert f"phi = {phi[np.argmax(th)]:.2f} deg" in msg
    assert f"{run(TRANS, offset=e)['r0'] * 1000:.3f} mm" in msg


@pytest.mark.parametrize("kw,field", [(dict(offset=0.05, r0=0.03), "cam.r0"), (dict(offset="auto", r0=0.05), "cam.offset"),
                                      (dict(r0=-0.01), "cam.r0"), (dict(center_distance=0.1, r0=0.05), "cam.center_distance"),
                                      (dict(follower="knife", roller=0.004), "cam.roller")])
def test_chosen_size_bad_input_is_a_task_error(kw, field):
    with pytest.raises(TaskError) as e:
        run(TRANS, **kw)
    assert f"'{field}'" in str(e.value)


ROCKER = {"schema": "tmm/1", "cam": {
    "follower": "rocker", "stroke": 20, "rocker_length": 0.1,
    "phases": {"rise": 100, "far_dwell": 40, "return": 100},
    "laws": {"rise": "poly345", "return": "cosine"}, "pressure_angle": 35}}


def test_rocker_chosen_size_reproduces_the_synthesis_and_its_r0_min():
    auto = run(ROCKER)
    same = run(ROCKER, r0=auto["r0"], center_distance=auto["center_distance"])
    np.testing.assert_allclose(same["pitch_profile"], auto["pitch_profile"], rtol=0, atol=1e-13)
    assert same["max_pressure_angle"] == pytest.approx(auto["max_pressure_angle"], abs=1e-9)
    big = run(ROCKER, r0=auto["r0"] * 1.2, center_distance=auto["center_distance"])
    # the least r0 on the circle of this centre distance is the smallest cam itself
    assert big["r0_min"] == pytest.approx(auto["r0"], rel=1e-9)
    assert big["center_distance"] == pytest.approx(auto["center_distance"], rel=1e-12)
    assert big["max_pressure_angle"] < 35
    with pytest.raises(StageError, match="over the allowed"):
        run(ROCKER, r0=auto["r0"] * 0.9, center_distance=auto["center_distance"])
    with pytest.raises(TaskError, match="center_distance"):
        run(ROCKER, r0=auto["r0"])


# ------------------------------------------------------------------ division table
def test_division_table_by_hand():
    h, n = 0.03, 6
    c = run(TRANS, laws={"rise": "parabolic", "return": "cosine"}, divisions=n)
    tab = c["division_table"]
    assert len(tab) == 2 * (n + 1)
    Pr = Pt = math.radians(120)
    for k in range(n + 1):
        x = k / n
        r = tab[k]
        assert (r["phase"], r["k"]) == ("rise", k)
        assert r["phi"] == pytest.approx(120 * x, abs=1e-9)
        # parabolic: 2x^2 (x <= 1/2), 1 - 2(1-x)^2; f'' = +4 then -4 (one-sided at the ends)
        f = 2 * x * x if x <= 0.5 else 1 - 2 * (1 - x) ** 2
        f1 = 4 * x if x <= 0.5 else 4 * (1 - x)
        assert r["s"] == pytest.approx(h * f, abs=1e-15)
        assert r["ds"] == pytest.approx(h * f1 / Pr, abs=1e-15)
        assert r["d2s"] == pytest.approx((4 if x < 0.5 else -4) * h / Pr ** 2, rel=1e-12)
        q = tab[n + 1 + k]
        assert (q["phase"], q["k"]) == ("return", k)
        assert q["phi"] == pytest.approx(150 + 120 * x, abs=1e-9)
        assert q["s"] == pytest.approx(h * (1 + math.cos(math.pi * x)) / 2, abs=1e-15)
        assert q["ds"] == pytest.approx(-h * math.pi / (2 * Pt) * math.sin(math.pi * x), abs=1e-15)
        assert q["d2s"] == pytest.approx(-h * math.pi ** 2 / (2 * Pt ** 2) * math.cos(math.pi * x), abs=1e-15)
        # central follower: tan theta = |ds| / (r0 + s)
        for row in (r, q):
            assert row["pressure_angle"] == pytest.approx(
                math.degrees(math.atan(abs(row["ds"]) / (c["r0"] + row["s"]))), abs=1e-12)
    # parabolic rise ends with d2s = -4h/P^2 (one-sided), the cosine return starts with -h pi^2/(2P^2)
    assert tab[n]["d2s"] < 0 and tab[0]["d2s"] > 0


def test_division_table_rocker_in_degrees():
    c = run(ROCKER, divisions=4)
    tab = c["division_table"]
    Pr = math.radians(100)
    f, f1, f2 = law("poly345", np.array([0.25]))
    assert tab[1]["s"] == pytest.approx(20 * f[0], rel=1e-12)
    assert tab[1]["ds"] == pytest.approx(math.radians(20) * f1[0] / Pr, rel=1e-12)
    assert tab[1]["d2s"] == pytest.approx(math.radians(20) * f2[0] / Pr ** 2, rel=1e-12)
    assert c["division_table"][4]["s"] == pytest.approx(20, rel=1e-12)
