"""Motion laws of the cam follower: shape, continuity, integration, published coefficients."""
import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st
from scipy.integrate import cumulative_trapezoid

from tmm_cli.cam.laws import LAW_NAMES, LAWS
from tmm_cli.cam.motion import Motion
from cam_spec import fields, section  # noqa: E402  (the task model builds the section)

# Peak velocity / acceleration coefficients (factors of h/Phi and h/Phi^2) as tabulated in
# the textbooks (Popov & Timofeev, Frolov; Norton "Cam design and manufacturing handbook",
# table 3-2 for the cycloidal, harmonic, 3-4-5 and constant-acceleration laws):
PUBLISHED = {
    "sine": (2.0, 2 * math.pi),                 # cycloidal: 2, 6.2832
    "cosine": (math.pi / 2, math.pi ** 2 / 2),  # harmonic: 1.5708, 4.9348
    "parabolic": (2.0, 4.0),
    "poly345": (1.875, 5.7735),
    # linearly decreasing acceleration a = a0 (1 - 2x): s = 3x^2 - 2x^3 by hand,
    # v = 6x(1 - x) peaks at x = 1/2 with 1.5, a0 = 6
    "linear_decreasing": (1.5, 6.0),
    # trapezoidal acceleration, ramps of 1/8: the half-pulse area A*(1/8/2 + 1/4 + 1/8/2)
    # = 3A/8 is the peak velocity; the pulse is symmetric about x = 1/4, so the
    # displacement at mid-rise is (3A/8)(1/2 - 1/4) = 3A/32 = 1/2  ->  A = 16/3, v = 2
    "trapezoidal": (2.0, 16.0 / 3.0),
    "constant_velocity": (1.0, None),
}
IMPACT = {  # textbook classification at the ends of the phase next to a dwell
    "constant_velocity": "rigid", "parabolic": "soft", "cosine": "soft",
    "linear_decreasing": "soft", "sine": "none", "poly345": "none", "trapezoidal": "none",
}


@pytest.mark.parametrize("name", LAW_NAMES)
def test_end_values_and_monotone(name):
    x = np.linspace(0, 1, 20001)
    f, f1, f2, f3 = LAWS[name](x)
    assert f[0] == pytest.approx(0, abs=1e-15)
    assert f[-1] == pytest.approx(1, abs=1e-14)
    assert np.all(np.diff(f) >= -1e-15)
    assert np.all(f1 >= -1e-15)


@pytest.mark.parametrize("name", LAW_NAMES)
def test_norton_popov_frolov_law_coefficients(name):
    cv, ca = PUBLISHED[name]
    law = LAWS[name]
    x = np.linspace(0, 1, 200001)
    _, f1, f2, _ = law(x)
    assert law.cv == pytest.approx(cv, rel=1e-4)
    assert np.max(np.abs(f1)) == pytest.approx(cv, rel=1e-6)
    if ca is None:
        assert law.ca is None
    else:
        assert law.ca == pytest.approx(ca, rel=1e-4)
        assert np.max(np.abs(f2)) == pytest.approx(ca, rel=1e-4)
    assert law.impact == IMPACT[name]


@pytest.mark.parametrize("name", LAW_NAMES)
def test_integration_of_derivatives(name):
    """Integrating f''' gives f'', f'' gives f', f' gives f (trapezoid rule on a fine grid).

    The integration restarts at the interior breakpoints where a derivative jumps
    (parabolic: f'' at 1/2; trapezoidal: f''' at the ends of the ramps), from the
    one-sided values just after the breakpoint.
    """
    law = LAWS[name]
    knots = [0.0, *law.breaks, 1.0]
    for a, b in zip(knots[:-1], knots[1:]):
        x = np.linspace(a + 1e-13, b - 1e-13, 100001)
        f, f1, f2, f3 = law(x)
        assert np.max(np.abs(cumulative_trapezoid(f1, x, initial=0) + f[0] - f)) < 1e-9
        assert np.max(np.abs(cumulative_trapezoid(f2, x, initial=0) + f1[0] - f1)) < 1e-8
        assert np.max(np.abs(cumulative_trapezoid(f3, x, initial=0) + f2[0] - f2)) < 1e-6


def _motion(rise_law, ret_law, h=0.04, phases=(100, 40, 120)):
    cam = section("cam", {"stroke": h, "phases": fields(rise=phases[0], far_dwell=phases[1], return_=phases[2]),
                          "laws": fields(rise=rise_law, return_=ret_law)})
    return Motion.from_spec(h, cam.phases, cam.laws)


@pytest.mark.parametrize("name", LAW_NAMES)
def test_cycle_continuity_at_boundaries(name):
    m = _motion(name, name)
    for b in np.radians([0.0, 100.0, 140.0, 260.0]):
        lft = m.evaluate(np.array([b - 1e-9]))
        rgt = m.evaluate(np.array([b + 1e-9]))
        assert rgt[0][0] == pytest.approx(lft[0][0], abs=1e-9)           # s continuous
        jump = abs(rgt[1][0] - lft[1][0])
        if name == "constant_velocity":
            # rigid impact: the velocity jumps by h/Phi at every end of a phase
            P = math.radians(100.0 if b < math.radians(120) else 120.0)
            assert jump == pytest.approx(0.04 / P, rel=1e-6)
        else:
            assert jump < 1e-6


def test_cycle_values_and_return_symmetry():
    m = _motion("cosine", "sine", h=0.05, phases=(90, 30, 120))
    phi = np.radians(np.array([45.0, 100.0, 180.0, 300.0]))
    s, s1, s2, _ = m.evaluate(phi)
    # cosine at mid-rise: h/2, ds/dphi = h*pi/(2*Phi)
    assert s[0] == pytest.approx(0.025)
    assert s1[0] == pytest.approx(0.05 * math.pi / 2 / (math.pi / 2))
    assert s[1] == pytest.approx(0.05) and s1[1] == 0.0                     # far dwell
    # sine return at its middle (x = 1/2): s = h/2, ds = -2h/Phi_r, d2s = 0
    assert s[2] == pytest.approx(0.025)
    assert s1[2] == pytest.approx(-2 * 0.05 / math.radians(120))
    assert s2[2] == pytest.approx(0.0, abs=1e-12)
    assert s[3] == 0.0                                                      # near dwell


def test_impacts_on_the_cycle():
    m = _motion("cosine", "sine", phases=(90, 30, 120))
    kinds = {e["where"]: e["kind"] for e in m.boundaries()}
    # cosine rise: acceleration pi^2/2*h/Phi^2 appears from zero at its start and at its end
    assert kinds["near_dwell/rise"] == "soft"
    assert kinds["rise/far_dwell"] == "soft"
    assert kinds["far_dwell/return"] == "none"
    assert kinds["return/near_dwell"] == "none"
    m = _motion("constant_velocity", "parabolic", phases=(90, 30, 120))
    ev = m.boundaries()
    assert [e["kind"] for e in ev if e["where"] == "near_dwell/rise"] == ["rigid"]
    # parabolic: the jump of acceleration in the middle of the return (8 h / Phi^2)
    mid = [e for e in ev if e["where"] == "return"]
    assert len(mid) == 1 and mid[0]["phi"] == pytest.approx(180.0)
    assert abs(mid[0]["d2s_jump"]) == pytest.approx(8 * 0.04 / math.radians(120) ** 2)


@settings(max_examples=40, deadline=None)
@given(st.sampled_from(LAW_NAMES), st.floats(0.001, 0.999))
def test_law_symmetry(name, x):
    """Every law is point-symmetric: f(x) + f(1 - x) = 1, f'(x) = f'(1 - x)."""
    law = LAWS[name]
    f, f1, _, _ = law(np.array([x, 1 - x]))
    assert f[0] + f[1] == pytest.approx(1.0, abs=1e-12)
    assert f1[0] == pytest.approx(f1[1], abs=1e-12)
