"""Singular positions are roots of a function periodic over the crank turn: a root at the
start of the cycle is found whatever the round-off signs of the values at 0 and 360 deg."""
from __future__ import annotations

import math

import numpy as np
import pytest

import tmm_cli
from tmm_cli.linkage.kinematics.changepoints import circle_zeros

GRID = np.linspace(0.0, 360.0, 721)


def _sampled(fun, at0=None, at360=None):
    """Values of ``fun`` on GRID, with the round-off values at 0 and 360 deg replaced."""
    g = np.array([fun(p) for p in GRID])
    if at0 is not None:
        g[0] = at0
    if at360 is not None:
        g[-1] = at360
    return g


def _F(fun, at0=None, at360=None):
    def F(phi, start):
        if phi == 0.0 and at0 is not None:
            return at0
        if phi == 360.0 and at360 is not None:
            return at360
        return fun(phi)
    return F


def _sin2(p):           # simple roots at 0 and 180 deg: sin(phi)... as a determinant would be
    return math.sin(math.radians(p))


@pytest.mark.parametrize("at0, at360", [(+1e-17, -1e-17), (-1e-17, +1e-17), (0.0, -1e-17),
                                        (+1e-17, 0.0), (0.0, 0.0), (+3e-17, +3e-17)])
def test_simple_root_at_the_start_of_the_cycle(at0, at360):
    roots = circle_zeros(GRID, _sampled(_sin2, at0, at360), _F(_sin2, at0, at360))
    assert roots == pytest.approx([0.0, 180.0], abs=1e-9)


def test_root_just_before_360_is_bracketed_across_the_period_end():
    # sin(phi - 359.9): roots at 179.9 and 359.9 (the second in the interval ending at 360)
    fun = lambda p: math.sin(math.radians(p - 359.9))  # noqa: E731
    roots = circle_zeros(GRID, _sampled(fun), _F(fun))
    assert roots == pytest.approx([179.9, 359.9], abs=1e-8)


def test_root_just_after_0():
    fun = lambda p: math.sin(math.radians(p - 0.1))  # noqa: E731
    roots = circle_zeros(GRID, _sampled(fun), _F(fun))
    assert roots == pytest.approx([0.1, 180.1], abs=1e-8)


@pytest.mark.parametrize("centre", [0.0, 0.2, 359.8, 90.0])
def test_touching_root_at_or_around_the_cycle_start(centre):
    # 1 - cos(phi - centre): a double root at `centre` (no sign change), none elsewhere
    fun = lambda p: (1.0 - math.cos(math.radians(p - centre))) / 2.0 + 0.0  # noqa: E731
    roots = circle_zeros(GRID, _sampled(fun), _F(fun))
    assert len(roots) == 1
    d = (roots[0] - centre + 180.0) % 360.0 - 180.0
    assert abs(d) < 1e-4


def test_no_roots_no_false_alarm():
    fun = lambda p: 2.0 + math.sin(math.radians(p))  # noqa: E731
    assert circle_zeros(GRID, _sampled(fun), _F(fun)) == []


def _opposed_twin(balance: str) -> dict:
    """Opposed two-cylinder machine: one crank, two rods on the same pin A, pistons on the
    x axis either side of O. With the balancing force on a piston the equations are
    singular where that piston cannot take a force along its guide from the crank: at its
    dead centres, crank along the guide: phi = 0 and 180 deg (the rod and the crank in one
    line, v_piston = 0)."""
    return {"schema": "tmm/1",
            "mechanism": {"ground": {"O": [0, 0]}, "links": {
                "crank": {"points": ["O", "A"], "length": 0.05, "mass": 2, "J": 0.01},
                "rod1": {"points": ["A", "B"], "length": 0.2, "mass": 1, "J": 0.004},
                "piston1": {"slider": "B", "guide": {"through": "O", "angle": 0}, "mass": 0.8},
                "rod2": {"points": ["A", "C"], "length": 0.2, "mass": 1, "J": 0.004},
                "piston2": {"slider": "C", "guide": {"through": "O", "angle": 180}, "mass": 0.8}},
                "assembly": {"B": [0.25, 0], "C": [-0.15, 0]}},
            "drive": {"link": "crank", "speed": "1500 rpm", "direction": "ccw"},
            "positions": {"output": "piston1"},
            "kinetostatics": {"balance": balance}}


@pytest.mark.parametrize("balance", ["piston1", "piston2"])
def test_two_cylinder_engine_balancing_force_on_a_piston(balance):
    # piston2's scaled determinant is +3e-17 at 0 deg and -3e-17 at 360 deg
    r = tmm_cli.run(tmm_cli.load_task(_opposed_twin(balance)))
    assert r["singular"] == pytest.approx([0.0, 180.0], abs=1e-6)
    flagged = {round(e["phi"]) % 360 for e in r["kinetostatics"] if e.get("near_singular")}
    assert {0, 180} <= flagged
