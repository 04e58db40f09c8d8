"""Issue 37, items 1-2: singular and change points of linkages written in decimal lengths
(not binary fractions) are found by a scale-aware criterion, and no value there is printed
without its flag.

Closed forms: a four-bar with crank a, coupler b, rocker c and ground d (pivots O = (0, 0),
O3 = (d, 0)) is at a change point where its four links are collinear: with a + d = b + c
(0.1 + 0.35 = 0.25 + 0.2) the crank pin at phi = 180 deg is A = (-a, 0), |A O3| = a + d =
b + c (coupler and rocker stretched along the ground line); with crank 0.1, coupler 0.35,
rocker 0.25 and ground 0.2 the pin at phi = 0 is A = (a, 0), |A O3| = d - a = 0.1 = b - c
(coupler and rocker folded). In decimal lengths the determinant there only reaches ~1e-8
by round-off (sqrt(eps)), not the 1e-9 of a binary-exact linkage."""
from __future__ import annotations

import math

import numpy as np
import pytest

import tmm_cli
from tmm_cli.linkage.kinematics import changepoints, fast, solve
from tmm_cli.linkage.kinematics import solver as ksolver
from tmm_cli.linkage.mechanism import build_mechanism


def fourbar(a, b, c, d, *, zero=0, count=12, extra=None, scale=1.0, loads=True):
    """A four-bar task (text) with the rocker's pin B assembled above the ground line."""
    a, b, c, d = (x * scale for x in (a, b, c, d))
    # B: the upper intersection of the circles about A(phi = 90) and O3
    A = np.array([0.0, a])
    O3 = np.array([d, 0.0])
    D = O3 - A
    dist = float(np.hypot(*D))
    k = (b * b - c * c + dist * dist) / (2 * dist)
    h = math.sqrt(max(b * b - k * k, 0.0))
    e = D / dist
    B = A + k * e + h * np.array([-e[1], e[0]])
    if B[1] < 0:
        B = A + k * e - h * np.array([-e[1], e[0]])
    pos = f"positions: {{count: {count}, zero: {zero}, output: rocker"
    pos += f", extra: {list(extra)}}}" if extra else "}"
    text = f"""\
schema: tmm/1
title: four-bar
mechanism:
  ground:
    O: [0, 0]
    O3: [{d!r}, 0]
  links:
    crank:   {{points: [O, A], length: {a!r}, mass: 1.0, J: 0.001}}
    coupler: {{points: [A, B], length: {b!r}, mass: 2.0, J: 0.02}}
    rocker:  {{points: [O3, B], length: {c!r}, mass: 1.5, J: 0.01}}
  assembly: {{B: [{float(B[0])!r}, {float(B[1])!r}]}}
drive: {{link: crank, speed: 120 rpm, direction: ccw}}
{pos}
"""
    if loads:
        text += """\
loads:
  gravity: true
  forces:
    - {on: rocker, kind: resistance, stroke: working, moment: 30}
kinetostatics:
  positions: all
  balance: crank
"""
    return text


def _task(tmp_path, text, name="task.yaml"):
    f = tmp_path / name
    f.write_text(text, encoding="utf-8")
    return tmm_cli.load_task(f)


def _mech(tmp_path, text):
    return build_mechanism(_task(tmp_path, text))


def _cps(tmp_path, text):
    return [c.phi for c in changepoints.change_points(ksolver.get_solver(_mech(tmp_path, text)))]


@pytest.mark.parametrize("lengths, at", [((0.1, 0.25, 0.2, 0.35), 180.0), ((0.1, 0.35, 0.25, 0.2), 0.0)])
@pytest.mark.parametrize("scale", [1.0, 1e-3, 1e3])
def test_decimal_grashof_limit_change_point_is_found(tmp_path, lengths, at, scale):
    cps = _cps(tmp_path, fourbar(*lengths, scale=scale))
    assert len(cps) == 1 and changepoints.distance_deg([at], cps)[0] < 1e-6, cps


def test_regular_decimal_crank_rocker_has_no_change_point(tmp_path):
    assert _cps(tmp_path, fourbar(0.1, 0.25, 0.2, 0.34)) == []
