"""Loads (tmm_cli/linkage/loads.py) against hand values on a centric slider-crank whose
extreme positions are known exactly (crank angles 0 and 180 deg)."""
from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from tmm_cli.linkage.loads import G, evaluate_on, interp_right, switch_angles
from tmm_cli.linkage.spec import LoadsSection

from test_kinetostatics_closedform import mech_of, slider_crank_kin, slider_crank_task

R, L = 0.1, 0.4


class CentricPositions:
    """Centric slider-crank, ccw, working stroke forward (+x): it starts at the inner
    dead point (phi = 180) and ends at the outer one (phi = 0 = 360)."""
    phi0 = 180.0
    extreme = [180.0, 0.0]
    working_stroke_angle = 180.0
    sign = 1.0

    def stroke_for(self, name, working=None):     # a slider's own stroke: here the same
        return self

    def stroke_state(self, phi):
        phi = np.mod(np.asarray(phi, float), 360.0)
        x = R * np.cos(np.radians(phi)) + np.sqrt(L ** 2 - (R * np.sin(np.radians(phi))) ** 2)
        working = phi >= 180.0
        s = np.where(working, (x - (L - R)) / (2 * R), ((L + R) - x) / (2 * R))
        return np.where(working, "working", "idle"), np.clip(s, 0, 1)


def _setup(loads: dict, phi, eps1=0.0, **kw):
    mech = mech_of(slider_crank_task(e=0.0, **kw))
    kin = slider_crank_kin(phi, omega1=10.0, eps1=eps1, e=0.0)
    sec = LoadsSection.model_validate(loads)
    return mech, kin, sec


def _force(lds, name):
    return next(f for f in lds.forces if f.name == name)


def test_gravity_and_inertia_hand_values():
    phi = np.array([30.0, 200.0])
    mech, kin, sec = _setup({"gravity": True}, phi, eps1=3.0)
    lds = evaluate_on(mech, sec, kin, CentricPositions(), sign=1.0, cycle=360.0, inertia=True)
    # gravity: m g down at S2 (rod midpoint) and at B
    g2 = _force(lds, "G2")
    assert np.allclose(g2.F, [[0, -5.0 * G]] * 2)
    assert np.allclose(g2.point, (kin.pos["A"] + kin.pos["B"]) / 2)
    assert np.allclose(_force(lds, "G3").F[:, 1], -8.0 * 9.81)
    # inertia of the slider by hand: a_B = x'' w^2 + x' eps, x from the closed form
    p = np.radians(phi)
    t2 = np.arcsin(-R * np.sin(p) / L)
    t2p = -R * np.cos(p) / (L * np.cos(t2))
    t2pp = (R * np.sin(p) + L * np.sin(t2) * t2p ** 2) / (L * np.cos(t2))
    xp = -R * np.sin(p) - L * np.sin(t2) * t2p
    xpp = -R * np.cos(p) - L * np.cos(t2) * t2p ** 2 - L * np.sin(t2) * t2pp
    aB = xpp * 100.0 + xp * 3.0
    assert np.allclose(_force(lds, "Fi3").F[:, 0], -8.0 * aB)
    assert np.allclose(_force(lds, "Fi3").F[:, 1], 0.0)
    # inertia couple of the rod: -J (t2'' w^2 + t2' eps)
    mi2 = next(c for c in lds.couples if c.name == "Mi2")
    assert np.allclose(mi2.M, -0.08 * (t2pp * 100 + t2p * 3.0))
    assert len(lds.external().forces) == 2 and not lds.external().couples


def test_inertia_of_a_local_com_uses_rigid_body_formulas():
    """S2 at local [0.1, 0.03] of the rod, not a named point: a_S by finite differences."""
    phi = np.array([40.0, 123.0, 301.0])
    mech = mech_of(slider_crank_task(e=0.0, s2=(0.1, 0.03)))
    w = 10.0

    def kin_at(ph):
        k = slider_crank_kin(ph, omega1=w, e=0.0, s2=(0.1, 0.03))
        for d in (k.pos, k.d1, k.d2):
            d.pop("S2")          # force the rigid-body path in loads.point_motion
        return k

    lds = evaluate_on(mech, None, kin_at(phi), None, sign=1.0, cycle=360.0, inertia=True)
    h = 1e-3
    ref = slider_crank_kin(phi, e=0.0, s2=(0.1, 0.03))
    kp, km = slider_crank_kin(phi + h, e=0.0, s2=(0.1, 0.03)), slider_crank_kin(phi - h, e=0.0, s2=(0.1, 0.03))
    a_fd = (kp.pos["S2"] - 2 * ref.pos["S2"] + km.pos["S2"]) / math.radians(h) ** 2 * w ** 2
    f = _force(lds, "Fi2")
    assert np.allclose(f.point, ref.pos["S2"], atol=1e-12)
    assert np.allclose(f.F, -5.0 * a_fd, rtol=1e-5, atol=1e-6)


def test_resistance_on_working_stroke_and_extreme_positions():
    # 180: start of the working stroke (v = 0): the working load applies, against +x
    # 270: working stroke, moving +x; 0: start of the idle stroke: no load; 90: idle
    phi = np.array([180.0, 270.0, 0.0, 90.0])
    mech, kin, sec = _setup({"forces": [{"on": "slider", "kind": "resistance", "magnitude": 2000}]}, phi)
    F = _force(evaluate_on(mech, sec, kin, CentricPositions(), sign=1.0, cycle=360.0, inertia=False), "F1")
    assert np.allclose(F.F, [[-2000, 0], [-2000, 0], [0, 0], [0, 0]])
    assert np.allclose(F.point, kin.pos["B"])


def test_driving_both_strokes_follows_the_motion():
    phi = np.array([0.0, 90.0, 180.0, 270.0])
    mech, kin, sec = _setup({"forces": [{"on": "slider", "kind": "driving", "stroke": "both",
                                         "magnitude": 500}]}, phi)
    F = _force(evaluate_on(mech, sec, kin, CentricPositions(), sign=1.0, cycle=360.0, inertia=False), "F1")
    # 0: idle begins, moving -x; 90: moving -x; 180: working begins (+x); 270: +x
    assert np.allclose(F.F[:, 0], [-500, -500, 500, 500])


def test_s_diagram_with_pressure_and_area():
    # force = p(s) * area, p from 0 to 1 MPa linearly over the working stroke
    phi = np.array([240.0, 300.0, 60.0])
    mech, kin, sec = _setup({"forces": [{"on": "slider", "kind": "resistance",
                                         "diagram": {"s": [0, 1], "value": ["0 MPa", "1 MPa"]},
                                         "area": 0.001}]}, phi)
    lds = evaluate_on(mech, sec, kin, CentricPositions(), sign=1.0, cycle=360.0, inertia=False)
    F = _force(lds, "F1")
    x = kin.pos["B"][:, 0]
    s = (x - (L - R)) / (2 * R)
    assert np.allclose(F.F[:2, 0], -1e6 * 0.001 * s[:2])
    assert F.F[2, 0] == 0.0                   # idle stroke: no working load
    info = lds.info[0]
    assert np.allclose(info["x"][:2], s[:2])


def test_switch_angle_of_a_cutting_force_switched_on_mid_stroke():
    """Jump at s = 1/2 of the working stroke: x_B = L, i.e. r cos p + sqrt(l^2 - r^2 sin^2 p) = l,
    whose root is cos p = r / (2 l) (squared by hand); on the working stroke p in (180, 360)."""
    sec = LoadsSection.model_validate({"forces": [{"on": "slider", "kind": "resistance",
                                                   "diagram": {"s": [0, 0.5, 0.5, 1], "value": [0, 0, 900, 900]}}]})
    mech = mech_of(slider_crank_task(e=0.0))
    ang = switch_angles(mech, sec, CentricPositions(), sign=1.0, cycle=360.0)
    expect = 360.0 - math.degrees(math.acos(R / (2 * L)))
    assert len(ang) == 1 and abs(ang[0] - expect) < 1e-8
    # at the switch angle the value after the jump applies; just before it nothing
    kin = slider_crank_kin(np.array([ang[0], ang[0] - 0.01]), e=0.0)
    F = _force(evaluate_on(mech, sec, kin, CentricPositions(), sign=1.0, cycle=360.0, inertia=False), "F1")
    assert F.F[0, 0] == pytest.approx(-900.0) and F.F[1, 0] == 0.0


def test_phi_diagram_is_measured_from_position_0_signed_along_the_guide():
    phi = np.array([180.0, 210.0, 225.0, 0.0])     # phi0 = 180: relative 0, 30, 45, 180
    mech, kin, sec = _setup({"forces": [{"on": "slider", "diagram": {"phi": [0, 30, 60, 360],
                                                                     "value": [0, -600, -900, 0]}}]}, phi)
    F = _force(evaluate_on(mech, sec, kin, CentricPositions(), sign=1.0, cycle=360.0, inertia=False), "F1")
    assert np.allclose(F.F[:, 0], [0, -600, -750, -900 * (1 - 120 / 300)])


def test_force_with_direction_at_a_point_and_couples():
    phi = np.array([90.0, 270.0])
    mech, kin, sec = _setup({"forces": [{"on": "rod", "magnitude": 100, "direction": 90, "at": "B"},
                                        {"on": "rod", "moment": 7},
                                        {"on": "crank", "kind": "resistance", "moment": 4}]}, phi)
    lds = evaluate_on(mech, sec, kin, CentricPositions(), sign=1.0, cycle=360.0, inertia=False)
    F = _force(lds, "F1")
    assert np.allclose(F.F, [[0, 100], [0, 100]]) and np.allclose(F.point, kin.pos["B"])
    m2 = next(c for c in lds.couples if c.name == "M2")
    assert np.allclose(m2.M, 7.0)
    m3 = next(c for c in lds.couples if c.name == "M3")   # resistance on a ccw crank: cw couple,
    assert np.allclose(m3.M, [0.0, -4.0])                 # on the working stroke only: phi = 90 is
                                                          # idle, phi = 270 working


@settings(max_examples=60, deadline=None)
@given(st.lists(st.floats(0, 1), min_size=2, max_size=6).map(sorted),
       st.lists(st.floats(-1e4, 1e4), min_size=6, max_size=6), st.floats(0, 1))
def test_interp_matches_numpy_without_jumps(xp, fp, x):
    xp = list(dict.fromkeys(xp))
    if len(xp) < 2 or min(np.diff(xp)) < 1e-6:      # closer abscissae are snapped (1e-9) by design
        return
    fp = fp[:len(xp)]
    # x within 1e-9 of a knot is snapped onto it: the error is at most slope * 1e-9
    slope = max(abs(b - a) / (x1 - x0) for a, b, x0, x1 in zip(fp, fp[1:], xp, xp[1:]))
    assert interp_right(np.array([x]), xp, fp)[0] == pytest.approx(np.interp(x, xp, fp),
                                                                    abs=1e-9 + 1.01e-9 * slope)


def test_interp_takes_the_value_after_a_jump():
    assert interp_right(np.array([0.5, 0.5 - 1e-12, 0.4999]), [0, 0.5, 0.5, 1], [0, 0, 9, 9]).tolist() == [9, 9, 0]


def test_720_degree_indicator_diagram_turns():
    """Cycle 720: reported angles (in [0, 360)) are the first turn after position 0,
    unwrapped angles phi0 + q with q in [360, 720) the second."""
    from tmm_cli.linkage.loads import cycle_angle
    assert cycle_angle([180.0, 90.0, 180.0 + 500.0, 179.0], 180.0, 1.0, 720.0).tolist() == \
        pytest.approx([0.0, 270.0, 500.0, 359.0])
    assert cycle_angle([170.0, 180.0 - 400.0], 180.0, -1.0, 720.0).tolist() == pytest.approx([10.0, 400.0])
    phi = np.array([180.0, 180.0 + 450.0])
    mech, kin, sec = _setup({"forces": [{"on": "slider", "diagram": {"phi": [0, 360, 720],
                                                                     "value": [100, 100, 820]}}]}, phi)
    F = _force(evaluate_on(mech, sec, kin, CentricPositions(), sign=1.0, cycle=720.0, inertia=False), "F1")
    assert F.F[:, 0].tolist() == pytest.approx([100.0, 100 + 720 * 90 / 360])
