"""Kinetostatics through the whole pipeline (tmm_cli.run) on every group type:
RRR + RRP six-bar, RPR + RRP shaper with a cutting force switched on mid-stroke and
friction, RPP Scotch yoke, a class-III triad, and every task in tasks/ with a
`kinetostatics` section. Independent checks: the slider-crank against the analysis
on closed-form kinematics; for all, group-by-group = Zhukovsky = virtual power =
matrix method (1e-9 relative) and the equilibrium of the whole mechanism."""
from __future__ import annotations

import copy
import json
import math
from pathlib import Path

import numpy as np
import pytest

import tmm_cli
from tmm_cli.linkage import structure
from tmm_cli.linkage.kinetostatics import equilibrium
from tmm_cli.linkage.loads import evaluate_on
from tmm_cli.linkage.spec import KinetostaticsSection, LoadsSection

from test_kinetostatics_closedform import mech_of, slider_crank_kin, slider_crank_task

SIX = {"schema": "tmm/1", "mechanism": {
    "ground": {"O": [0, 0], "C": [0.28, 0]},
    "links": {"crank": {"points": ["O", "A"], "length": 0.08, "mass": 1, "J": 0.002},
              "coupler": {"points": ["A", "B"], "length": 0.30, "mass": 3, "J": 0.03},
              "rocker": {"points": ["C", "B"], "length": 0.25, "mass": 2.5, "J": 0.02, "extra": {"K": [0.32, 0.0]}},
              "link4": {"points": ["K", "D"], "length": 0.30, "mass": 2, "J": 0.015},
              "slider": {"slider": "D", "guide": {"through": [0, 0.42], "angle": 0}, "mass": 6}},
    "assembly": {"B": [0.28, 0.25], "D": [0.1, 0.42]}},
    "drive": {"link": "crank", "speed": "120 rpm"},
    "loads": {"gravity": True, "forces": [{"on": "slider", "kind": "resistance", "magnitude": 1500},
                                          {"on": "coupler", "magnitude": 200, "direction": 30, "at": [0.1, 0.02]}]},
    "kinetostatics": {}}
SHAPER = {"schema": "tmm/1", "mechanism": {
    "ground": {"O": [0, 0.22], "O2": [0, 0]},
    "links": {"crank": {"points": ["O", "A"], "length": 0.1, "mass": 1},
              "block": {"slider": "A", "guide": {"link": "rocker"}, "mass": 0.5},
              "rocker": {"points": ["O2", "B"], "length": 0.55, "mass": 4, "J": 0.1},
              "rod": {"points": ["B", "D"], "length": 0.18, "mass": 1.5, "J": 0.005},
              "ram": {"slider": "D", "guide": {"through": [0, 0.56], "angle": 0}, "mass": 12}},
    "assembly": {"B": [0.0, 0.55], "D": [0.15, 0.56]}},
    "drive": {"link": "crank", "speed": "60 rpm", "direction": "cw"},
    "loads": {"gravity": True, "forces": [{"on": "ram", "kind": "resistance", "diagram": {
        "s": [0, 0.1, 0.1, 0.9, 0.9, 1], "value": [0, 0, 3000, 3000, 0, 0]}}]},
    "kinetostatics": {"friction": {"pin_radius": 0.01, "f": 0.1}}}
YOKE = {"schema": "tmm/1", "mechanism": {
    "ground": {"O": [0, 0]},
    "links": {"crank": {"points": ["O", "A"], "length": 0.1, "mass": 1},
              "block": {"slider": "A", "guide": {"link": "yoke", "angle": 90}, "mass": 0.5},
              "yoke": {"slider": "Y", "guide": {"through": [0, 0], "angle": 0}, "mass": 5}}},
    "drive": {"link": "crank", "speed": "100 rpm"},
    "loads": {"forces": [{"on": "yoke", "kind": "resistance", "magnitude": 500}]},
    "kinetostatics": {"balance": "yoke"}}
TRIAD = {"schema": "tmm/1", "mechanism": {
    "ground": {"O": [0, 0], "O3": [0.55, -0.15], "O4": [0.2, 0.4]},
    "links": {"crank": {"points": ["O", "A"], "length": 0.05, "mass": 0.5},
              "leg2": {"points": ["A", "B"], "length": 0.26926, "mass": 1, "J": 0.01},
              "leg3": {"points": ["O3", "C"], "length": 0.25495, "mass": 1, "J": 0.01},
              "leg4": {"points": ["O4", "D"], "length": 0.25, "mass": 1, "J": 0.01},
              "base": {"points": ["B", "C"], "length": 0.2, "extra": {"D": [0.1, 0.15]}, "mass": 3, "J": 0.05}},
    "assembly": {"B": [0.3, 0.1], "C": [0.5, 0.1], "D": [0.4, 0.25]}},
    "drive": {"link": "crank", "speed": "100 rpm"},
    "positions": {"output": "leg3"},
    "loads": {"gravity": True, "forces": [{"on": "leg4", "moment": 20}]},
    "kinetostatics": {}}

ROOT = Path(__file__).resolve().parents[1]


def _task_files():
    out = []
    for p in sorted((ROOT / "tasks").glob("*.yaml")):
        try:
            t = tmm_cli.load_task(p)
        except tmm_cli.TaskError:
            continue
        if t.kinetostatics is not None:
            out.append(p)
    return out


CASES = {"six-bar": SIX, "shaper": SHAPER, "yoke": YOKE, "triad": TRIAD,
         "six-bar, balance on the slider": {**SIX, "kinetostatics": {"balance": "slider"}},
         "triad, balance on a leg": {**TRIAD, "kinetostatics": {"balance": "leg4"}}}


def _results(case):
    if isinstance(case, Path):
        return tmm_cli.run(tmm_cli.load_task(case), kinematics_curve=0)
    return tmm_cli.run(copy.deepcopy(case), kinematics_curve=0)


def _check_methods_and_equilibrium(r):
    info = r["kinetostatics_info"]
    force = info["balance_kind"] == "force"
    for e in r["kinetostatics"]:
        if e["balancing_force" if force else "balancing_moment"] is None:
            assert e["near_singular"]
            continue
        if force:
            m = e["balancing_force"]
            others = [e["zhukovsky_force"], e["virtual_power_force"], e["matrix_force"]]
        else:
            m = e["balancing_moment"]
            others = [e["zhukovsky_moment"], e["virtual_power_moment"], e["matrix_moment"]]
        # a moment scale of the position: sum |F| * L + sum |M|
        L = max(abs(x) for f in e["loads"] for x in f["point"]) if e["loads"] else 1.0
        scale = sum(math.hypot(*f["F"]) * L for f in e["loads"]) + sum(abs(c["M"]) for c in e["couples"]) + 1e-9
        tol = 1e-9 * max(abs(m), 1e-3 * scale)
        for o in others:
            assert abs(o - m) <= tol, (e["index"], m, others)
        assert e["matrix_discrepancy"] < 1e-9
        # whole mechanism: loads + ground reactions + balancing couple / force = 0
        Fs, Ms = np.zeros(2), 0.0
        for f in e["loads"]:
            Fs += f["F"]
            Ms += f["point"][0] * f["F"][1] - f["point"][1] * f["F"][0]
        Ms += sum(c["M"] for c in e["couples"])
        for key, rr in e["reactions"].items():
            if key.startswith("R0"):
                Fs += [rr["x"], rr["y"]]
                if "N" in rr:          # prismatic: force at the pin + its couple
                    Ms += rr["pin"][0] * rr["y"] - rr["pin"][1] * rr["x"] + rr["M"]
                else:
                    Ms += rr["point"][0] * rr["y"] - rr["point"][1] * rr["x"]
        if force:
            j = next(j for j in info["joints"] if j["kind"] == "P" and j["slider"] is not None
                     and r["structure"]["links"][j["slider"] - 1]["name"] == info["balance"])
            pin = e["reactions"][j["key"]]["pin"]
            ang = math.radians(next(k for k in r["kinematics"] if k["index"] == e["index"])
                               ["links"][info["balance"]]["angle"])
            Fb = m * np.array([math.cos(ang), math.sin(ang)])
            Fs += Fb
            Ms += pin[0] * Fb[1] - pin[1] * Fb[0]
        else:
            Ms += m
        fscale = sum(math.hypot(*f["F"]) for f in e["loads"]) + abs(m) / max(L, 1e-9) + 1.0
        assert np.allclose(Fs, 0, atol=1e-9 * fscale), (e["index"], Fs)
        assert abs(Ms) <= 1e-9 * (scale + abs(m) + 1), (e["index"], Ms)


@pytest.mark.parametrize("name", list(CASES))
def test_every_group_type_methods_agree_and_equilibrium(name):
    r = _results(CASES[name])
    assert len(r["kinetostatics"]) == len(r["kinematics"])
    json.dumps(r, allow_nan=False)
    _check_methods_and_equilibrium(r)


@pytest.mark.parametrize("path", _task_files(), ids=lambda p: p.name)
def test_task_examples(path):
    from tmm_cli.errors import StageError
    try:
        r = _results(path)
    except StageError as exc:
        if exc.stage != "kinetostatics":        # an earlier stage's problem is tested there
            pytest.skip(f"stage {exc.stage} failed: {exc.message}")
        raise
    json.dumps(r, allow_nan=False)
    _check_methods_and_equilibrium(r)


def test_shaper_cutting_force_switch_positions_and_efficiency():
    r = _results(SHAPER)
    kinds = r["positions"]["kinds"]
    added = [i for i, k in enumerate(kinds) if k == "added"]
    assert len(added) == 2                                  # s = 0.1 and s = 0.9 of the working stroke
    ents = {e["index"]: e for e in r["kinetostatics"]}
    for i in added:
        d = ents[i]["diagram"]["F1"]
        assert d["x"] == pytest.approx(0.1, abs=1e-9) or d["x"] == pytest.approx(0.9, abs=1e-9)
        # at s = 0.1 the force has just switched on; at s = 0.9 just off
        assert abs(d["value"]) == pytest.approx(3000.0 if d["x"] < 0.5 else 0.0)
    for e in r["kinetostatics"]:
        if e["efficiency"] is not None:
            # 0 <= eta <= 1; eta = 0 (to round-off) where no useful load acts: at the idle
            # stroke's end all the driving power goes to friction (position 12 here)
            assert -1e-12 <= e["efficiency"] <= 1.0
            assert e["efficiency"] == pytest.approx(1 - e["friction_power"] / e["driving_power"], rel=1e-12,
                                                    abs=1e-12)


def test_pipeline_slider_crank_matches_closed_form_kinematics():
    """The same analysis on the tool's kinematics and on the closed form of the test."""
    d = slider_crank_task(m1=1.0, J1=0.01, extra={
        "loads": {"gravity": True, "forces": [{"on": "slider", "kind": "resistance", "stroke": "both",
                                               "magnitude": 900}]},
        "kinetostatics": {}})
    r = tmm_cli.run(d, kinematics_curve=0)
    phi = np.array([e["phi"] for e in r["kinetostatics"]])
    mech = mech_of(d)
    kin = slider_crank_kin(phi, omega1=10.0)

    class Pos:                   # the tool's positions only decide the stroke (here: both)
        phi0, sign, extreme, working_stroke_angle = r["positions"]["phi0"], 1.0, r["positions"]["extreme"], \
            r["positions"]["working_stroke_angle"]

        def stroke_for(self, name, working=None):     # a slider's own stroke: here the same
            return self

        def stroke_state(self, p):
            return np.full(np.shape(p), "working"), np.zeros(np.shape(p))

    lds = evaluate_on(mech, LoadsSection.model_validate(d["loads"]), kin, Pos(), sign=1.0, cycle=360.0)
    ref = equilibrium(mech, structure.analyze(mech), kin, lds, KinetostaticsSection(),
                  solver=lambda m, p, w: slider_crank_kin(p, omega1=w)).to_dict()["kinetostatics"]
    for a, b in zip(r["kinetostatics"], ref):
        assert a["balancing_moment"] == pytest.approx(b["balancing_moment"], rel=1e-7, abs=1e-7)
        for k in ("R01", "R12", "R23", "R03"):
            assert a["reactions"][k]["R"] == pytest.approx(b["reactions"][k]["R"], rel=1e-7, abs=1e-7)


def test_true_motion_with_the_flywheel_gives_the_constant_driving_moment():
    """With omega(phi), eps(phi) of the steady motion and the flywheel's couple -J eps1 on
    the crank, the balancing moment of a motor-driven machine must equal the constant
    driving moment found by the dynamics stage (equation of motion <=> d'Alembert)."""
    d = copy.deepcopy(SIX)
    d["flywheel"] = {"delta": 0.05, "constant": "driving"}
    d["kinetostatics"] = {"motion": True}
    r = tmm_cli.run(d, kinematics_curve=0)
    Mc = r["flywheel"]["M_constant"]
    for e in r["kinetostatics"]:
        assert e["balancing_moment"] == pytest.approx(Mc, rel=1e-5)
