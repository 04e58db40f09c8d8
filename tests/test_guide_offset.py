"""`offset` on a fixed guide: the guide line through `through` at `angle`, shifted by `offset`
along its left normal (docs/task-file.md). A newcomer's `guide: {through: O, angle: 0,
offset: 20 mm}` was validated and then ignored (a central slider-crank, K = 1).

Checked against the closed form of the offset slider-crank (crank r, rod l, offset e):
H = sqrt((l+r)^2 - e^2) - sqrt((l-r)^2 - e^2), theta = asin(e/(l-r)) - asin(e/(l+r)),
the dead centres at the crank angles asin(e/(l+r)) (outer) and 180 deg + asin(e/(l-r))
(inner) for a guide above the crank axis."""
from __future__ import annotations

import math

import pytest

import tmm_cli

R, L, E = 0.05, 0.2, 0.02


def _task(guide: dict) -> dict:
    return {"schema": "tmm/1", "mechanism": {
        "ground": {"O": [0, 0]},
        "links": {"crank": {"points": ["O", "A"], "length": R},
                  "rod": {"points": ["A", "B"], "length": L},
                  "slider": {"slider": "B", "guide": guide}}},
        "drive": {"link": "crank", "speed": "100 rpm", "direction": "ccw"},
        "positions": {"count": 12, "zero": "extreme", "output": "slider"}}


def _positions(guide: dict) -> dict:
    return tmm_cli.run(tmm_cli.load_task(_task(guide)), kinematics_curve=0)["positions"]


def test_offset_of_a_fixed_guide_against_the_closed_form():
    p = _positions({"through": "O", "angle": 0, "offset": "20 mm"})
    H = math.sqrt((L + R) ** 2 - E ** 2) - math.sqrt((L - R) ** 2 - E ** 2)
    theta = math.degrees(math.asin(E / (L - R)) - math.asin(E / (L + R)))
    assert p["H"] == pytest.approx(H, rel=1e-9)
    assert abs(p["theta"]) == pytest.approx(theta, rel=1e-7)
    K = (180 + theta) / (180 - theta)
    assert p["K"] == pytest.approx(K, rel=1e-7) or p["K"] == pytest.approx(1 / K, rel=1e-7)
    assert p["K"] != pytest.approx(1.0, abs=1e-3)
    outer = math.degrees(math.asin(E / (L + R)))
    inner = 180 + math.degrees(math.asin(E / (L - R)))
    assert sorted(p["extreme"]) == pytest.approx(sorted([outer, inner]), abs=1e-6)


@pytest.mark.parametrize("angle,shifted", [(0, [0, 0.02]), (90, [-0.02, 0]), (180, [0, -0.02])])
def test_offset_is_the_same_line_as_a_shifted_through(angle, shifted):
    """`offset: e` to the left of the direction `angle` is the line through the point shifted so."""
    a = _positions({"through": "O", "angle": angle, "offset": "20 mm"})
    b = _positions({"through": shifted, "angle": angle})
    for k in ("H", "K", "theta", "extreme"):
        assert a[k] == pytest.approx(b[k], abs=1e-9), k
