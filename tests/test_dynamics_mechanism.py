"""Dynamics stage on real linkages (kinematics + loads of the other stages).

Independent references:
* central slider-crank, r = 0.1, l = 0.4, written out here: J_red(phi) and the reduced
  moment of a constant piston force F dx_B/dphi in closed form;
* work of a constant force over a stroke = F * H exactly (H = 2 r), so
  M_constant = F H / (2 pi) (or / 4 pi for a 720-deg cycle);
* the kinetostatics stage (group by group): with the steady motion omega(phi),
  epsilon(phi) and the flywheel couple, the balancing moment equals the constant
  driving moment at every position (energy balance of the machine).
"""
from __future__ import annotations

import json

import numpy as np
import pytest

import tmm_cli
from tmm_cli.linkage import dynamics, kinematics
from tmm_cli.linkage.mechanism import build_mechanism

R, L = 0.1, 0.4


def slider_crank(loads, flywheel=None, direction="ccw", speed="120 rpm", cycle=360, rod_J=0.05,
                 working="forward"):
    d = {
        "schema": "tmm/1",
        "mechanism": {
            "ground": {"O": [0, 0]},
            "links": {
                "crank": {"points": ["O", "A"], "length": R, "mass": 3.0, "J": 0.01},
                "rod": {"points": ["A", "B"], "length": L, "mass": 4.0, "J": rod_J},
                "slider": {"slider": "B", "guide": {"through": "O", "angle": 0}, "mass": 10.0},
            },
            "assembly": {"B": [0.5, 0.0]},
        },
        "drive": {"link": "crank", "speed": speed, "direction": direction, "cycle": cycle},
        "positions": {"count": 12, "output": "slider", "working": working},
        "loads": loads,
        "flywheel": flywheel or {"delta": "1/20"},
    }
    task = tmm_cli.load_task(d)
    mech = build_mechanism(task)
    pos = kinematics.find_positions(mech, task.positions, task.drive.sign)
    return task, mech, pos


def linkage_of(task, mech, pos):
    """The linkage context of the stages (tmm_cli.linkage.context)."""
    from tmm_cli.linkage import structure
    from tmm_cli.linkage.context import Linkage
    from tmm_cli.linkage.drive_speed import resolve
    return Linkage(mechanism=mech, structure=structure.analyze(mech, task=task),
                   drive=resolve(task.drive, pos), positions=pos, loads=task.loads)


def closed_form(phi):
    """Central slider-crank on the x-axis: analogues written out."""
    sth = -R * np.sin(phi) / L
    cth = np.sqrt(1 - sth**2)
    a1 = -R * np.cos(phi) / (L * cth)
    dA = np.stack([-R * np.sin(phi), R * np.cos(phi)], -1)
    dxB = -R * np.sin(phi) - L * sth * a1
    dB = np.stack([dxB, np.zeros_like(phi)], -1)
    dS2 = 0.5 * (dA + dB)
    J = 0.01 + 3.0 * (R / 2) ** 2 * 0 + 4.0 * np.sum(dS2**2, -1) + 0.05 * a1**2 + 10.0 * dxB**2
    return J, dxB


def test_reduced_inertia_and_moment_closed_form():
    task, mech, pos = slider_crank({"forces": [{"on": "slider", "magnitude": -500.0}]})
    r = dynamics.analyze(linkage_of(task, mech, pos), task.flywheel, accuracy=False)
    # nodes at jumps are evaluated EPS_DEG before/after the node (one-sided limits)
    phi = np.deg2rad(r.phi0 + r.q_deg + r.side * dynamics.EPS_DEG)
    J_cf, dxB = closed_form(phi)
    # crank com at its pivot (default): crank J 0.01 is the constant part
    J_crank = 3.0 * 0 + 0.01
    assert r.cycle.const_links == ["crank"]
    assert r.cycle.J_const == pytest.approx(J_crank)
    assert r.cycle.J_red == pytest.approx(J_cf, rel=1e-9)
    # a signed force -500 N along the guide (+x): M_red = -500 dx_B/dphi (ccw drive)
    assert r.cycle.work.M_given == pytest.approx(-500.0 * dxB, abs=1e-9)
    # over a turn a constant force does no net work: M_constant = 0
    assert abs(r.cycle.work.M_constant) < 1e-9


@pytest.mark.parametrize("direction", ["ccw", "cw"])
def test_constant_force_over_working_stroke(direction):
    """Resistance 2000 N over the working stroke: work 2000 H per cycle, H = 2r."""
    task, mech, pos = slider_crank({"forces": [{"on": "slider", "kind": "resistance",
                                                "magnitude": 2000.0}]}, direction=direction)
    assert pos.H == pytest.approx(2 * R, rel=1e-9)
    r = dynamics.analyze(linkage_of(task, mech, pos), task.flywheel)
    d = r.to_dict()
    # trapezoid on 1-deg steps of a smooth F dx/dphi: relative error ~ h^2/12 ~ 3e-5
    assert d["M_constant"] == pytest.approx(2000 * 2 * R / (2 * np.pi), rel=1e-4)
    assert d["direction"] == direction
    # resistance is against the motion: M_c >= 0 everywhere, A_c(end) = 2000 H
    # (one-sided nodes 1e-7 deg from an extreme may carry an O(1e-7) N*m residue)
    assert np.min(r.cycle.work.M_c) >= -1e-6
    assert r.cycle.work.A_c[-1] == pytest.approx(400.0, rel=1e-4)
    assert d["J_exact"] == pytest.approx(d["J_energy_mass"], rel=1e-9)
    assert d["J_var_min"] <= d["J_merzalov"] - d["J_energy_mass"] <= d["J_var_max"]
    for key in ("J", "diameter", "width", "mass", "omega_max", "omega_min"):
        assert d[key] > 0
    w = 120 * np.pi / 30
    assert d["omega_max"] == pytest.approx(w * (1 + 1 / 40), rel=1e-9)
    assert d["omega_min"] == pytest.approx(w * (1 - 1 / 40), rel=1e-9)
    # signed omega/epsilon arrays: cw drive -> negative omega
    sgn = 1 if direction == "ccw" else -1
    assert np.all(np.sign(d["arrays"]["omega"]) == sgn)
    json.dumps(d, allow_nan=False)


def test_jump_inside_stroke_on_the_grid():
    """s-diagram 0 then 3000 N from mid-stroke: work 3000 H/2 per cycle.  The jump angle
    (from loads.switch_angles) is a double node of the grid; the trapezoid error of the
    smooth rest falls as h^2."""
    from tmm_cli.linkage import loads as loads_mod
    loads = {"forces": [{"on": "slider", "kind": "resistance",
                         "diagram": {"s": [0, 0.5, 0.5, 1], "value": [0, 0, 3000, 3000]}}]}
    exact = 3000 * R / (2 * np.pi)
    errs = []
    for res in (90, 360, 1440):
        task, mech, pos = slider_crank(loads, flywheel={"delta": "1/20", "resolution": res})
        r = dynamics.analyze(linkage_of(task, mech, pos), task.flywheel, accuracy=False)
        sw = loads_mod.switch_angles(mech, task.loads, pos, sign=task.drive.sign, cycle=task.drive.cycle)
        assert len(sw) == 1
        qs = (sw[0] - pos.phi0) % 360.0
        assert np.sum(np.abs(r.q_deg - qs) < 1e-9) == 2
        errs.append(abs(r.cycle.work.M_constant / exact - 1))
    assert errs[2] < 1e-5
    assert errs[0] / errs[1] > 10 and errs[1] / errs[2] > 10      # ~16 for h^2


def test_engine_720_cycle_phi_diagram():
    """Four-stroke engine: gas force 1000 N pushing the piston over the power stroke
    (crank 0..180 deg of the 720-deg cycle from TDC), nothing otherwise.  Work per
    cycle = 1000 H; constant resistance moment = 1000 H/(4 pi)."""
    loads = {"forces": [{"on": "slider", "diagram": {"phi": [0, 180, 180, 720],
                                                     "value": [-1000, -1000, 0, 0]}}]}
    task, mech, pos = slider_crank(loads, flywheel={"delta": "1/80", "constant": "resistance",
                                                    "resolution": 720},
                                   cycle=720, working="backward")
    assert pos.phi0 == pytest.approx(0.0, abs=1e-9) or pos.phi0 == pytest.approx(360.0)
    r = dynamics.analyze(linkage_of(task, mech, pos), task.flywheel)
    d = r.to_dict()
    assert d["cycle"] == 720.0
    assert d["arrays"]["phi_cycle"][-1] == 720.0
    # working: backward -> position 0 is B farthest from O (phi = 0, "TDC"); over the first
    # half turn the piston moves along -x, the force -1000 N along the guide drives: +1000 H
    assert -d["M_constant"] == pytest.approx(1000 * 2 * R / (4 * np.pi), rel=1e-4)
    assert not any("net" in w for w in d["warnings"])
    assert d["J"] > 0


@pytest.mark.parametrize("direction", ["ccw", "cw"])
def test_balancing_moment_equals_constant_driving_moment(direction):
    """Kinetostatics with the steady motion: M_b = M_constant (signed) at every position."""
    from tmm_cli.linkage import kinetostatics, loads as loads_mod, structure
    task, mech, pos = slider_crank({"gravity": True, "forces": [
        {"on": "slider", "kind": "resistance",
         "diagram": {"s": [0, 0.3, 1], "value": [500, 2500, 2500]}}]}, direction=direction)
    r = dynamics.analyze(linkage_of(task, mech, pos), task.flywheel, accuracy=False)
    phi = np.asarray(pos.phi, float)
    w, e = r.motion_at(phi)
    kin = kinematics.solve(mech, phi, w, e)
    lds = loads_mod.evaluate(linkage_of(task, mech, pos), kin, inertia=True)
    st = structure.analyze(mech, task=task)
    ks = tmm_cli.linkage.spec.KinetostaticsSection()
    res = kinetostatics.equilibrium(mech, st, kin, lds, ks, crank_inertia=r.J_fly + task.flywheel.reduced_J)
    entries = res.to_dict()["kinetostatics"]
    Mb = np.array([x["balancing_moment"] for x in entries])
    sgn = 1.0 if direction == "ccw" else -1.0
    assert Mb == pytest.approx(np.full(Mb.size, sgn * r.cycle.work.M_constant), rel=1e-6, abs=1e-6)


def test_balancing_moment_720_cycle_positions_off_zero():
    """720-deg cycle, position 0 at phi0 = 180 deg: the reported angles 0..150 deg are read
    as the loads module reads them (first turn), so M_b = M_constant there too."""
    from tmm_cli.linkage import kinetostatics, loads as loads_mod, structure
    loads = {"forces": [{"on": "slider", "diagram": {"phi": [0, 100, 180, 400, 720],
                                                     "value": [2000, 800, 0, -300, 0]}}]}
    task, mech, pos = slider_crank(loads, flywheel={"delta": "1/50", "constant": "resistance"},
                                   cycle=720)
    assert pos.phi0 == pytest.approx(180.0)
    r = dynamics.analyze(linkage_of(task, mech, pos), task.flywheel, accuracy=False)
    phi = np.asarray(pos.phi, float)
    w, e = r.motion_at(phi)
    kin = kinematics.solve(mech, phi, w, e)
    lds = loads_mod.evaluate(linkage_of(task, mech, pos), kin, inertia=True)
    st = structure.analyze(mech, task=task)
    res = kinetostatics.equilibrium(mech, st, kin, lds, tmm_cli.linkage.spec.KinetostaticsSection(),
                                crank_inertia=r.J_fly)
    Mb = np.array([x["balancing_moment"] for x in res.to_dict()["kinetostatics"]])
    assert Mb == pytest.approx(np.full(Mb.size, r.cycle.work.M_constant), rel=1e-6, abs=1e-6)
