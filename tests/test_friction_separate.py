"""Separate friction coefficients of revolute (f_pin) and prismatic (f_slide) pairs:
closed-form cases and the shorthand ``f`` unchanged."""
from __future__ import annotations

import math

import numpy as np
import pytest

from tmm_cli.errors import TaskError
from tmm_cli.linkage.spec import FrictionSpec
from tmm_cli.task import load_task

from test_kinetostatics import _run, sc_solver
from test_kinetostatics_closedform import SC, slider_crank_kin, slider_crank_task


def test_slider_only_sliding_friction_closed_form():
    """f_pin = 0 exactly (no pin friction at all), f_slide = 0.15: the rod is a two-force
    member, at phi = 90 deg T (ux - f r / l) = -P, N = T r / l, M_b = -r T ux (hand solution)."""
    r, l, f, P = SC["r"], SC["l"], 0.15, 1000.0
    kin = slider_crank_kin([90.0], e=0.0)
    task = slider_crank_task(e=0.0, m2=0, J2=0, m3=0)
    mech, res, d = _run(task, kin, {"forces": [{"on": "slider", "magnitude": P}]},
                        {"inertia": False, "friction": {"pin_radius": 0.02, "f_slide": f}}, sc_solver)
    ux = math.sqrt(l ** 2 - r ** 2) / l
    T = -P / (ux - f * r / l)
    ent = d["kinetostatics"][0]
    assert ent["balancing_moment"] == pytest.approx(-r * T * ux, rel=1e-12)
    assert ent["reactions"]["R03"]["R"] == pytest.approx(abs(T) * r / l, rel=1e-12)
    # the loss is all in the prismatic pair: f |N| |v_B|, v_B = r w1 at 90 deg (w1 = 10)
    assert ent["friction_pairs"]["R01"] == 0 and ent["friction_pairs"]["R12"] == 0
    assert ent["friction_power"] == pytest.approx(f * abs(T) * r / l * r * 10.0, rel=1e-9)


def test_pin_only_friction_closed_form():
    """f_slide missing (0), f_pin = 0.1 on a massless centric slider-crank at phi = 60 deg with
    P along +x on the slider.  The slider takes no friction force, so T_x = -P (T: the rod's
    force on the slider, |R12| = |R23| = |R01| = |T| for massless links).  Pin couples
    f_pin r |T| oppose the relative rotations: on the rod at A against w2 - w1 and at B
    against w2; on the crank at A the reaction of the first, at O against w1.
    Rod, moments about A: (B - A) x (-T) + C_A + C_B = 0 (solved for T_y by fixed point);
    crank, moments about O: A x (-T) - C_A - f_pin r |T| sgn(w1) + M_b = 0."""
    fp, rp, P = 0.1, 0.01, 1000.0
    w1 = 10.0
    kin = slider_crank_kin([60.0], e=0.0)
    task = slider_crank_task(e=0.0, m2=0, J2=0, m3=0)
    mech, res, d = _run(task, kin, {"forces": [{"on": "slider", "magnitude": P}]},
                        {"inertia": False, "friction": {"pin_radius": rp, "f_pin": fp}}, sc_solver)
    ent = d["kinetostatics"][0]
    A, B = kin.pos["A"][0], kin.pos["B"][0]
    w2 = kin.a1["rod"][0] * w1
    BA = B - A
    Tx, Ty = -P, 0.0
    for _ in range(200):
        Mf = fp * rp * math.hypot(Tx, Ty)
        CA = -Mf * math.copysign(1, w2 - w1)
        CB = -Mf * math.copysign(1, w2)
        # -(BAx Ty - BAy Tx) + CA + CB = 0
        Ty = (CA + CB + BA[1] * Tx) / BA[0]
    Mf = fp * rp * math.hypot(Tx, Ty)
    CA = -Mf * math.copysign(1, w2 - w1)
    Mb = (A[0] * (-Ty) - A[1] * (-Tx)) * -1 + CA + Mf * math.copysign(1, w1)
    assert ent["reactions"]["R23"]["x"] == pytest.approx(Tx, rel=1e-10)
    assert ent["reactions"]["R23"]["y"] == pytest.approx(Ty, rel=1e-10)
    assert ent["balancing_moment"] == pytest.approx(Mb, rel=1e-10)
    assert ent["friction_pairs"]["R03"] == 0
    # the losses: f_pin r |T| times the relative angular speeds of the three pins
    assert ent["friction_power"] == pytest.approx(Mf * (abs(w1) + abs(w2 - w1) + abs(w2)), rel=1e-9)


def test_f_is_the_shorthand_for_both():
    phi = np.arange(5.0, 360.0, 30.0)
    kin = slider_crank_kin(phi, omega1=10.0)
    task = slider_crank_task(m1=1.0, J1=0.01)
    loads = {"gravity": True, "forces": [{"on": "slider", "magnitude": -2000}]}
    _, _, a = _run(task, kin, loads, {"friction": {"pin_radius": 0.015, "f": 0.12}}, sc_solver)
    _, _, b = _run(task, kin, loads, {"friction": {"pin_radius": 0.015, "f_pin": 0.12, "f_slide": 0.12}},
                   sc_solver)
    assert a == b


def test_coefficient_rules():
    fr = FrictionSpec.model_validate({"pin_radius": 0.01, "f_pin": 0.1})
    assert (fr.f_pin, fr.f_slide) == (0.1, 0.0)
    fr = FrictionSpec.model_validate({"pin_radius": 0.01, "f": 0.2})
    assert (fr.f_pin, fr.f_slide) == (0.2, 0.2)


@pytest.mark.parametrize("fric", [{"pin_radius": 0.01, "f": 0.1, "f_pin": 0.1},
                                  {"pin_radius": 0.01, "f": 0.1, "f_slide": 0.2},
                                  {"pin_radius": 0.01}])
def test_bad_combinations_are_task_errors(fric, tmp_path):
    import yaml
    from pathlib import Path
    src = yaml.safe_load(Path("tasks").joinpath(_kst_task()).read_text())
    src["kinetostatics"]["friction"] = fric
    p = tmp_path / "t.yaml"
    p.write_text(yaml.safe_dump(src))
    with pytest.raises(TaskError) as e:
        load_task(p)
    assert "kinetostatics.friction" in str(e.value)


def _kst_task() -> str:
    from pathlib import Path
    for f in sorted(Path("tasks").glob("*.yaml")):
        if "kinetostatics:" in f.read_text() and "friction" in f.read_text():
            return f.name
    raise AssertionError("no task with friction in tasks/")


@pytest.mark.parametrize("dead", [0.0, 180.0])
def test_friction_at_a_reversal_is_the_mean_of_its_two_sides(dead):
    """At a dead centre the slider's velocity is zero (round-off: at 180 deg v_B is -9e-18):
    its sliding friction there is the mean of its two sides, 0 -- not f |N| with the sign
    of the round-off -- while a hundredth of a degree either side it is f |N| against the
    motion, with opposite signs; the moment at the dead centre lies between its sides'."""
    f, P = 0.15, 1000.0
    task = slider_crank_task(e=0.0, m2=0, J2=0, m3=0)
    out = {}
    for d in (-0.01, 0.0, 0.01):
        kin = slider_crank_kin([(dead + d) % 360.0], e=0.0)
        mech, res, ent = _run(task, kin, {"forces": [{"on": "slider", "magnitude": P}]},
                              {"inertia": False, "friction": {"pin_radius": 0.02, "f": f}}, sc_solver)
        e = ent["kinetostatics"][0]
        ff = [ld for ld in e["loads"] if ld["name"] == "Ff03"][0]
        vB = kin.d1["B"][0][0]
        out[d] = (ff["F"][0], vB, e["balancing_moment"], abs(e["reactions"]["R03"]["R"]))
    assert out[0.0][0] == 0.0
    for d in (-0.01, 0.01):
        F, vB, _, N = out[d]
        assert F == pytest.approx(-f * N * math.copysign(1.0, vB), rel=1e-9)   # against the motion
    assert out[-0.01][0] * out[0.01][0] < 0
    lo, hi = sorted((out[-0.01][2], out[0.01][2]))
    assert lo - 1e-6 <= out[0.0][2] <= hi + 1e-6
