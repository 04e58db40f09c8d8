"""find_positions: extremes against closed forms (crank and rod collinear)."""
import math
from pathlib import Path

import numpy as np
import pytest

from tmm_cli.errors import StageError
from tmm_cli.linkage.kinematics import find_positions
from tmm_cli.linkage.mechanism import build_mechanism
from tmm_cli.task import load_task

TASKS = Path(__file__).resolve().parent.parent / "tasks"


def task(links, ground, positions=None, direction="ccw"):
    t = load_task({"schema": "tmm/1", "mechanism": {"ground": ground, "links": links},
                   "drive": {"link": "crank", "speed": 10, "direction": direction},
                   "positions": positions or {}})
    return t, build_mechanism(t)


R, L, E = 0.1, 0.4, 0.03
SC = {"crank": {"points": ["O", "A"], "length": R}, "rod": {"points": ["A", "B"], "length": L},
      "slider": {"slider": "B", "guide": {"through": [0, E], "angle": 0}}}
# outer dead centre: crank and rod stretched, sin(phi) = e/(l + r);
# inner dead centre: folded, phi = 180 + asin(e/(l - r))
PHI_OUT = math.degrees(math.asin(E / (L + R)))
PHI_IN = 180.0 + math.degrees(math.asin(E / (L - R)))
H = math.sqrt((L + R) ** 2 - E ** 2) - math.sqrt((L - R) ** 2 - E ** 2)


def test_offset_slider_crank_extremes_ccw():
    t, m = task(SC, {"O": [0, 0]}, {"extra": [33.0, 400.0]})
    p = find_positions(m, t.positions, t.drive.sign)
    # forward working stroke starts at the minimum x (inner dead centre)
    assert p.extreme[0] == pytest.approx(PHI_IN, abs=1e-9)
    assert p.extreme[1] == pytest.approx(PHI_OUT, abs=1e-9)
    assert p.phi0 == p.extreme[0]
    w = (PHI_OUT - PHI_IN) % 360.0
    assert p.working_stroke_angle == pytest.approx(w, abs=1e-9)
    assert p.idle_stroke_angle == pytest.approx(360.0 - w, abs=1e-9)
    assert p.K == pytest.approx(w / (360.0 - w))
    theta = w - 180.0
    assert p.K == pytest.approx((180 + theta) / (180 - theta))
    assert p.H == pytest.approx(H, abs=1e-12)
    # grid every 30 deg ccw, then extras, then the second extreme
    assert np.allclose(p.phi[:12], (PHI_IN + 30.0 * np.arange(12)) % 360.0)
    assert p.phi[12] == 33.0 and p.phi[13] == pytest.approx(40.0)
    assert p.phi[14] == pytest.approx(PHI_OUT) and p.kinds[14] == "extreme" and p.extreme_index == 14
    assert list(p.index) == list(range(15))
    assert ((p.phi >= 0) & (p.phi < 360)).all()
    d = p.to_dict()
    assert d["extreme"] == [pytest.approx(PHI_IN), pytest.approx(PHI_OUT)]
    assert d["working_stroke_angle"] == pytest.approx(w)


def test_cw_backward():
    t, m = task(SC, {"O": [0, 0]}, {"working": "backward", "count": 8}, direction="cw")
    p = find_positions(m, t.positions, t.drive.sign, extra_added=[12.5, PHI_IN])
    assert p.extreme == [pytest.approx(PHI_OUT, abs=1e-9), pytest.approx(PHI_IN, abs=1e-9)]
    w = (PHI_OUT - PHI_IN) % 360.0                     # cw from the outer to the inner dead centre
    assert p.working_stroke_angle == pytest.approx(w, abs=1e-9)
    assert np.allclose(p.phi[:8], (PHI_OUT - 45.0 * np.arange(8)) % 360.0)
    # the second extreme is added, PHI_IN; the pipeline's 12.5 follows; PHI_IN is not repeated
    assert p.phi[8] == pytest.approx(PHI_IN) and p.phi[9] == 12.5 and len(p.phi) == 10


def test_stroke_state():
    t, m = task(SC, {"O": [0, 0]})
    p = find_positions(m, t.positions, t.drive.sign)
    phi = np.array([PHI_IN, PHI_OUT, 90.0, 300.0])
    state, s = p.stroke_state(phi)
    assert list(state) == ["working", "idle", "idle", "working"]
    f = np.radians(phi)
    x = R * np.cos(f) + np.sqrt(L ** 2 - (R * np.sin(f) - E) ** 2)
    xmin, xmax = x[0], x[1]
    assert s[0] == pytest.approx(0.0, abs=1e-12) and s[1] == pytest.approx(0.0, abs=1e-12)
    assert s[2] == pytest.approx((xmax - x[2]) / H, abs=1e-12)      # idle: back from x_max
    assert s[3] == pytest.approx((x[3] - xmin) / H, abs=1e-12)      # working: from x_min


def test_fourbar_rocker_extremes():
    a, b, c, d = 0.08, 0.30, 0.22, 0.30
    t = load_task(TASKS / "crank_rocker_fourbar.yaml")
    p = find_positions(build_mechanism(t), t.positions, t.drive.sign)

    def crank_angle(s, flip):
        # B on the circle (O, s) and the circle (O3, c), upper closure; A along OB (+-)
        x = (s * s - c * c + d * d) / (2 * d)
        y = math.sqrt(s * s - x * x)
        ang = math.degrees(math.atan2(y, x))
        return (ang + (180.0 if flip else 0.0)) % 360.0
    outer = crank_angle(b + a, False)    # stretched: rocker at its one extreme
    inner = crank_angle(b - a, True)     # folded
    assert sorted(p.extreme) == pytest.approx(sorted([outer, inner]), abs=1e-8)
    # rocker swing (deg) by the cosine rule at the two positions
    def rocker_deg(s):
        x = (s * s - c * c + d * d) / (2 * d)
        y = math.sqrt(s * s - x * x)
        return math.degrees(math.atan2(y, x - d))
    assert p.H == pytest.approx(abs(rocker_deg(b + a) - rocker_deg(b - a)), abs=1e-8)
    assert p.output_kind == "rocker"


def test_spec_forging_positions():
    # SPEC section 3 example: phi0 = 6.42, extreme [6.42, 164.19], working stroke 157.8
    t = load_task(TASKS / "forging_sixbar.yaml")
    p = find_positions(build_mechanism(t), t.positions, t.drive.sign)
    assert p.phi0 == pytest.approx(6.42, abs=0.005)
    assert p.extreme[1] == pytest.approx(164.19, abs=0.005)
    assert p.working_stroke_angle == pytest.approx(157.8, abs=0.05)


def test_explicit_zero_and_rotating_output():
    t, m = task(SC, {"O": [0, 0]}, {"zero": 10, "count": 4, "output": "crank"})
    p = find_positions(m, t.positions, t.drive.sign)
    assert p.extreme is None and p.K is None
    assert np.allclose(p.phi, [10, 100, 190, 280])
    t, m = task(SC, {"O": [0, 0]}, {"output": "crank"})
    with pytest.raises(StageError, match="zero"):
        find_positions(m, t.positions, t.drive.sign)


def test_shaper_quick_return():
    # oscillating slotted link: extremes where OA is perpendicular to O1A;
    # theta = 2 asin(r/|OO1|) and the working stroke turns the crank 180 + theta
    t = load_task(TASKS / "shaper_slotted_lever.yaml")
    p = find_positions(build_mechanism(t), t.positions, t.drive.sign)
    th = 2 * math.degrees(math.asin(0.11 / 0.30))
    assert p.working_stroke_angle == pytest.approx(180 + th, abs=1e-8)
    assert p.K == pytest.approx((180 + th) / (180 - th))
