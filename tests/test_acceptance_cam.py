"""Acceptance tests of the `cam` stage, written as an outsider would: from SPEC.md, METHODS.md
(section 5) and the README's law definitions only, through the public API.

Independent reference (nothing imported from tmm_cli):

* Laws as dimensionless f(x), x in [0, 1] of the phase: cosine (1 - cos pi x)/2, sine
  (cycloidal) x - sin(2 pi x)/(2 pi), poly345 10x^3 - 15x^4 + 6x^5; the return is h (1 - f).
* Translating follower, offset e positive on the side that lowers the rise pressure angle
  (SPEC): from the velocity of the roller centre and the velocity of the coincident cam point,
  tan(theta) = |ds/dphi - e| / (s0 + s), s0 = sqrt(r0^2 - e^2). For a given e the least s0 is
  max over the rise and the return of |s' - e|/tan(theta_allowed) - s (dense grid + bounded
  refinement of every local maximum); `offset: auto` minimises r0(e) = sqrt(e^2 + s0(e)^2)
  (a convex function) by a bounded scalar search. Central cosine law: closed form
  r0 = sqrt(A^2 + B^2) - B, A = pi h/(2 Phi tan theta), B = h/2 (the maximum of
  A sin u - B (1 - cos u)).
* Rocker: pivot O2 at the origin, roller centre B = l (cos psi, sin psi), psi = sigma beta(phi)
  (sigma = +-1: the rocker turns with/against the cam, whose rotation sign is s1). With the
  relative velocity of B on the cam, tan(theta) = |sigma beta' l^2 - s1 l^2 + s1 O.B| / |O x B|,
  linear in the cam centre O; the rise moves B away from O (sigma (O x B) > 0). r0 is the
  distance from B0 to the admissible region of O: own brute force over ray directions from
  B0 (each ray gives an interval of admissible distances) refined by a scalar search;
  centre distance |O O2|. `swing: auto` = the smaller r0 of with/against.
* The pressure-angle formulas are themselves checked against a finite-difference tangent of
  the inverted-motion pitch profile. rho_min: curvature of the pitch profile (exact
  derivatives of the inverted-motion curve), min over the convex profile.

Tolerances: the reference is exact to ~1e-9 (dense grids of 4000 points a phase, refined);
closed forms 1e-6 relative, optimised quantities 1e-5 (the acceptance requirement is 1e-4).
"""
from __future__ import annotations

import copy
import math

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

import tmm_cli


def run(task):
    return tmm_cli.run(tmm_cli.load_task(copy.deepcopy(task)))


# --------------------------------------------------------------------------------------
# laws
# --------------------------------------------------------------------------------------
def law(name, x):
    """f, f', f'' (with respect to the phase fraction x)."""
    x = np.asarray(x, float)
    if name == "cosine":
        return (1 - np.cos(np.pi * x)) / 2, np.pi / 2 * np.sin(np.pi * x), np.pi**2 / 2 * np.cos(np.pi * x)
    if name == "sine":
        return (x - np.sin(2 * np.pi * x) / (2 * np.pi), 1 - np.cos(2 * np.pi * x),
                2 * np.pi * np.sin(2 * np.pi * x))
    if name == "poly345":
        return (10 * x**3 - 15 * x**4 + 6 * x**5, 30 * x**2 - 60 * x**3 + 30 * x**4,
                60 * x - 180 * x**2 + 120 * x**3)
    raise KeyError(name)


class Motion:
    """s(phi), s'(phi), s''(phi) over the cycle (phi in rad of cam rotation), phases in deg."""

    def __init__(self, h, phases, laws):
        self.h = h
        self.Pr = math.radians(phases["rise"])
        self.Pf = math.radians(phases["far_dwell"])
        self.Pt = math.radians(phases["return"])
        self.laws = laws

    def phase(self, which, x):
        f, f1, f2 = law(self.laws[which], x)
        h = self.h
        if which == "rise":
            P = self.Pr
            return h * f, h * f1 / P, h * f2 / P**2
        P = self.Pt
        return h * (1 - f), -h * f1 / P, -h * f2 / P**2

    def at(self, phi):
        phi = np.mod(np.asarray(phi, float), 2 * np.pi)
        s = np.zeros_like(phi)
        s1 = np.zeros_like(phi)
        s2 = np.zeros_like(phi)
        r = phi < self.Pr
        a, b, c = self.phase("rise", phi[r] / self.Pr)
        s[r], s1[r], s2[r] = a, b, c
        fd = (phi >= self.Pr) & (phi < self.Pr + self.Pf)
        s[fd] = self.h
        t0 = self.Pr + self.Pf
        t = (phi >= t0) & (phi < t0 + self.Pt)
        a, b, c = self.phase("return", (phi[t] - t0) / self.Pt)
        s[t], s1[t], s2[t] = a, b, c
        return s, s1, s2


def tans(pa):
    if isinstance(pa, dict):
        return math.tan(math.radians(pa["rise"])), math.tan(math.radians(pa["return"]))
    t = math.tan(math.radians(pa))
    return t, t


def refine_max(fun, x, n_keep=6):
    """Max of a smooth scalar function of x in [0, 1] given on a grid: refine the best
    few local maxima of the grid by a bounded search between the neighbours."""
    v = fun(x)
    idx = np.argsort(v)[::-1][: n_keep * 4]
    best = float(np.max(v))
    for i in idx[:n_keep]:
        lo, hi = x[max(i - 1, 0)], x[min(i + 1, len(x) - 1)]
        r = minimize_scalar(lambda t: -float(fun(np.array([t]))[0]), bounds=(lo, hi), method="bounded",
                            options={"xatol": 1e-14})
        best = max(best, -r.fun)
    return best


XG = np.linspace(0.0, 1.0, 4001)


# --------------------------------------------------------------------------------------
# translating follower
# --------------------------------------------------------------------------------------
def s0_needed(mo, pa, e):
    Tr, Tt = tans(pa)
    out = -np.inf
    for which, T in (("rise", Tr), ("return", Tt)):
        def g(x, which=which, T=T):
            s, s1, _ = mo.phase(which, x)
            return np.abs(s1 - e) / T - s
        out = max(out, refine_max(g, XG))
    return out


def translating_r0(mo, pa, e):
    s0 = s0_needed(mo, pa, e)
    assert s0 > 0
    return math.hypot(e, s0), s0


def translating_auto(mo, pa):
    h = mo.h
    r = minimize_scalar(lambda e: translating_r0(mo, pa, e)[0], bounds=(-2 * h, 2 * h), method="bounded",
                        options={"xatol": 1e-13})
    e = r.x
    r0, s0 = translating_r0(mo, pa, e)
    return r0, e, s0


def translating_profile(mo, e, s0, n=72001):
    """Pressure angle (deg) over the cycle and min radius of curvature of the pitch profile
    (ccw cam; the mirror image for cw has the same numbers)."""
    phi = np.linspace(0, 2 * np.pi, n)
    s, s1, s2 = mo.at(phi)
    theta = np.degrees(np.arctan(np.abs(s1 - e) / (s0 + s)))
    # roller centre in the fixed frame B = (e, s0 + s) (follower along +y, ccw cam);
    # the pitch profile is C = R(-phi) B: C' = R(B' - J B), C'' = R(B'' - 2 J B' - B)
    B = np.stack([np.full_like(s, e), s0 + s])
    B1 = np.stack([np.zeros_like(s), s1])
    B2 = np.stack([np.zeros_like(s), s2])
    return theta, rho_convex(B, B1, B2, +1.0)


def J(v):
    return np.stack([-v[1], v[0]])


def rho_convex(Bc, B1, B2, s1):
    """Signed radius of curvature of the inverted-motion curve of the point Bc (relative to
    the cam centre) for cam rotation sign s1: positive where the profile is convex."""
    d1 = B1 - s1 * J(Bc)
    d2 = B2 - 2 * s1 * J(B1) - Bc
    cross = d1[0] * d2[1] - d1[1] * d2[0]
    speed = np.hypot(d1[0], d1[1])
    return -s1 * speed**3 / cross


def rho_min_convex(rho):
    """Least radius of curvature over the convex stretches of the pitch profile (where the
    roller radius limit of METHODS 5 applies); concave stretches are never undercut."""
    return float(rho[rho > 0].min())


def central_cosine_r0(h, Phi_deg, T):
    A = math.pi * h / (2 * math.radians(Phi_deg) * T)
    B = h / 2
    return math.hypot(A, B) - B


# --------------------------------------------------------------------------------------
# rocker follower
# --------------------------------------------------------------------------------------
def rocker_constraints(mo_rad, l, pa, sigma, s1, n=4001):
    """Rows (c, d) of the constraints c + d.O >= 0 on the cam centre O (O2 at the origin)."""
    Tr, Tt = tans(pa)
    rows_c, rows_d = [], []
    for which, T in (("rise", Tr), ("return", Tt)):
        b, b1, _ = mo_rad.phase(which, np.linspace(0, 1, n))
        psi = sigma * b
        Bx, By = l * np.cos(psi), l * np.sin(psi)
        # X = sigma b' l^2 - s1 l^2 + s1 (ox Bx + oy By);  Y = ox By - oy Bx
        Xc = sigma * b1 * l**2 - s1 * l**2
        Xd = np.stack([s1 * Bx, s1 * By], 1)
        Yd = np.stack([By, -Bx], 1)
        for sg in (+1, -1):   # T sigma Y -+ X >= 0
            rows_c.append(-sg * Xc)
            rows_d.append(T * sigma * Yd - sg * Xd)
    return np.concatenate(rows_c), np.concatenate(rows_d)


def rocker_synthesis(mo_rad, l, pa, sigma, s1):
    c, d = rocker_constraints(mo_rad, l, pa, sigma, s1)
    B0 = np.array([l, 0.0])
    a0 = c + d @ B0

    def rho_at(alpha):
        u = np.array([math.cos(alpha), math.sin(alpha)])
        b = d @ u
        with np.errstate(divide="ignore", invalid="ignore"):
            q = -a0 / b
        pos, neg = b > 1e-15, b < -1e-15
        zero = ~(pos | neg)
        if np.any(a0[zero] < 0):
            return np.inf
        lo = max(0.0, q[pos].max()) if pos.any() else 0.0
        hi = q[neg].min() if neg.any() else np.inf
        return lo if lo <= hi else np.inf

    al = np.linspace(-np.pi, np.pi, 3601)
    vals = np.array([rho_at(a) for a in al])
    i = int(np.argmin(vals))
    assert np.isfinite(vals[i])
    r = minimize_scalar(rho_at, bounds=(al[i - 1], al[i + 1]), method="bounded", options={"xatol": 1e-13})
    alpha = r.x
    r0 = rho_at(alpha)
    O = B0 + r0 * np.array([math.cos(alpha), math.sin(alpha)])
    return r0, O


def rocker_profile(mo_rad, l, O, sigma, s1, n=72001):
    phi = np.linspace(0, 2 * np.pi, n)
    b, b1, b2 = mo_rad.at(phi)
    psi = sigma * b
    B = np.stack([l * np.cos(psi), l * np.sin(psi)])
    eB = np.stack([np.cos(psi), np.sin(psi)])
    X = sigma * b1 * l**2 - s1 * l**2 + s1 * (O[0] * B[0] + O[1] * B[1])
    Y = O[0] * B[1] - O[1] * B[0]
    theta = np.degrees(np.arctan(np.abs(X) / np.abs(Y)))
    B1 = sigma * b1 * J(B)
    B2 = sigma * b2 * J(B) - b1**2 * l * eB
    Bc = B - O[:, None]
    return theta, rho_convex(Bc, B1, B2, s1)


# --------------------------------------------------------------------------------------
# self-checks of the reference
# --------------------------------------------------------------------------------------
def _fd_pressure_angle(Bfun, Ofun_cam, s1, phi, h=1e-6):
    """Pressure angle from a finite-difference tangent of the inverted-motion profile
    and the finite-difference absolute velocity of the roller centre."""
    def C(p):
        B = Bfun(p)
        a = -s1 * p
        R = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
        return R @ (B - Ofun_cam)
    t = (C(phi + h) - C(phi - h)) / (2 * h)
    v = (Bfun(phi + h) - Bfun(phi - h)) / (2 * h)
    a = -s1 * phi
    R = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
    t = R.T @ t        # the tangent back in the fixed frame
    n = np.array([-t[1], t[0]])
    return math.degrees(math.acos(abs(n @ v) / np.linalg.norm(n) / np.linalg.norm(v)))


def test_reference_pressure_angle_formulas_by_finite_differences():
    mo = Motion(0.03, {"rise": 100, "far_dwell": 30, "return": 120}, {"rise": "poly345", "return": "sine"})
    e, s0 = 0.006, 0.04
    for phi in (0.3, 1.1, 2.7, 3.4):
        s, s1_, _ = mo.at(np.array([phi]))
        exp = math.degrees(math.atan(abs(s1_[0] - e) / (s0 + s[0])))
        Bf = lambda p: np.array([e, s0 + mo.at(np.array([p]))[0][0]])
        assert _fd_pressure_angle(Bf, np.zeros(2), +1, phi) == pytest.approx(exp, abs=1e-6)
    mr = Motion(math.radians(25), {"rise": 100, "far_dwell": 30, "return": 120}, {"rise": "cosine", "return": "sine"})
    l, O = 0.1, np.array([0.08, -0.07])
    for sigma, s1 in ((1, 1), (-1, 1), (1, -1), (-1, -1)):
        theta, _ = rocker_profile(mr, l, O, sigma, s1, n=361)
        for k in (20, 90, 150, 240):
            phi = 2 * np.pi * k / 360
            Bf = lambda p: l * np.array([math.cos(sigma * mr.at(np.array([p]))[0][0]),
                                         math.sin(sigma * mr.at(np.array([p]))[0][0])])
            assert _fd_pressure_angle(Bf, O, s1, phi) == pytest.approx(theta[k], abs=1e-5)


def test_reference_curvature_of_a_circle_and_closed_form():
    mo = Motion(0.0, {"rise": 90, "far_dwell": 90, "return": 90}, {"rise": "cosine", "return": "cosine"})
    _, rho = translating_profile(mo, 0.01, 0.05, n=101)
    assert np.allclose(rho, math.hypot(0.01, 0.05), rtol=1e-12)
    mo = Motion(0.09, {"rise": 90, "far_dwell": 90, "return": 90}, {"rise": "cosine", "return": "cosine"})
    T = math.tan(math.radians(30))
    r0, s0 = translating_r0(mo, 30, 0.0)
    assert r0 == pytest.approx(central_cosine_r0(0.09, 90, T), rel=1e-10)


# --------------------------------------------------------------------------------------
# translating follower
# --------------------------------------------------------------------------------------
def cam_task(**cam):
    return {"schema": "tmm/1", "cam": cam}


@pytest.mark.parametrize("rotation", ["ccw", "cw"])
def test_central_cosine_spec_example(rotation):
    """SPEC's cam: h = 90 mm, 90/90/90 deg, cosine both ways, 30 deg, central follower."""
    res = run(cam_task(follower="translating", stroke=0.09, offset=0,
                       phases={"rise": 90, "far_dwell": 90, "return": 90},
                       laws={"rise": "cosine", "return": "cosine"}, pressure_angle=30,
                       roller="auto", rotation=rotation, speed="50 rpm"))
    c = res["cam"]
    exp = central_cosine_r0(0.09, 90, math.tan(math.radians(30)))
    assert c["r0"] == pytest.approx(exp, rel=1e-6)
    assert c["offset"] == pytest.approx(0.0, abs=1e-12)
    assert c["max_pressure_angle"] == pytest.approx(30.0, abs=1e-6)
    mo = Motion(0.09, {"rise": 90, "far_dwell": 90, "return": 90}, {"rise": "cosine", "return": "cosine"})
    theta, rho = translating_profile(mo, 0.0, exp)
    assert theta.max() == pytest.approx(30.0, abs=1e-6)
    # concave just after the start of the rise (the cosine law's acceleration jump,
    # rho = -0.219 m there): rho_min is the convex minimum, at the end of the rise
    assert rho.min() < 0
    assert c["rho_min"] == pytest.approx(rho_min_convex(rho), rel=1e-5)
    # METHODS 5 roller limits
    assert 0 < c["roller"] <= 0.8 * c["rho_min"] + 1e-12 and c["roller"] <= 0.5 * c["r0"] + 1e-12


def test_central_cosine_unequal_phases_and_angles():
    """Rise 60 deg at 30 deg allowed, return 120 deg at 45: closed form of each phase."""
    h = 0.04
    res = run(cam_task(follower="translating", stroke="40 mm", offset=0,
                       phases={"rise": 60, "far_dwell": 30, "return": 120},
                       laws={"rise": "cosine", "return": "cosine"},
                       pressure_angle={"rise": 30, "return": 45}, roller=0.005))
    c = res["cam"]
    exp = max(central_cosine_r0(h, 60, math.tan(math.radians(30))),
              central_cosine_r0(h, 120, math.tan(math.radians(45))))
    assert c["r0"] == pytest.approx(exp, rel=1e-6)
    assert c["roller"] == pytest.approx(0.005, rel=1e-12)


def test_transmission_angle_is_the_complement():
    base = dict(follower="translating", stroke=0.05, offset=0,
                phases={"rise": 120, "far_dwell": 20, "return": 100},
                laws={"rise": "cosine", "return": "cosine"})
    r1 = run(cam_task(**base, pressure_angle=28))["cam"]["r0"]
    r2 = run(cam_task(**base, transmission_angle=62))["cam"]["r0"]
    exp = max(central_cosine_r0(0.05, 120, math.tan(math.radians(28))),
              central_cosine_r0(0.05, 100, math.tan(math.radians(28))))
    assert r1 == pytest.approx(exp, rel=1e-6)
    assert r2 == pytest.approx(exp, rel=1e-6)


OFFSET_CASE = dict(h=0.03, phases={"rise": 100, "far_dwell": 40, "return": 110},
                   laws={"rise": "poly345", "return": "sine"}, pa={"rise": 30, "return": 45})


@pytest.mark.parametrize("rotation", ["ccw", "cw"])
def test_offset_auto(rotation):
    k = OFFSET_CASE
    mo = Motion(k["h"], k["phases"], k["laws"])
    r0, e, s0 = translating_auto(mo, k["pa"])
    assert e > 0   # a larger allowed angle on the return: the offset favours the rise
    res = run(cam_task(follower="translating", stroke=k["h"], offset="auto", phases=k["phases"],
                       laws=k["laws"], pressure_angle=k["pa"], rotation=rotation, roller="auto"))
    c = res["cam"]
    assert c["r0"] == pytest.approx(r0, rel=1e-5)
    assert c["offset"] == pytest.approx(e, rel=1e-4)
    theta, rho = translating_profile(mo, e, s0)
    assert c["max_pressure_angle"] == pytest.approx(theta.max(), abs=1e-4)
    # this profile has nearly straight concave stretches (|rho| > 7 m): rho_min is the
    # convex minimum, the one the roller radius is limited by (METHODS 5)
    assert c["rho_min"] == pytest.approx(rho_min_convex(rho), rel=1e-4)


@pytest.mark.parametrize("e", [0.008, -0.004])
def test_given_offset(e):
    """A given offset: r0 = sqrt(e^2 + s0^2), s0 the least admissible for that e."""
    k = OFFSET_CASE
    mo = Motion(k["h"], k["phases"], k["laws"])
    r0, s0 = translating_r0(mo, k["pa"], e)
    res = run(cam_task(follower="translating", stroke=k["h"], offset=e, phases=k["phases"],
                       laws=k["laws"], pressure_angle=k["pa"], roller="auto"))
    c = res["cam"]
    assert c["offset"] == pytest.approx(e, rel=1e-12)
    assert c["r0"] == pytest.approx(r0, rel=1e-5)
    theta, rho = translating_profile(mo, e, s0)
    assert c["max_pressure_angle"] == pytest.approx(theta.max(), abs=1e-4)
    assert c["rho_min"] == pytest.approx(rho_min_convex(rho), rel=1e-4)


# --------------------------------------------------------------------------------------
# rocker follower
# --------------------------------------------------------------------------------------
ROCKER = dict(l=0.12, stroke=20.0, phases={"rise": 110, "far_dwell": 30, "return": 100},
              laws={"rise": "cosine", "return": "sine"}, pa={"rise": 30, "return": 40})


def rocker_reference(swing, rotation, k=ROCKER):
    s1 = 1.0 if rotation == "ccw" else -1.0
    mr = Motion(math.radians(k["stroke"]), k["phases"], k["laws"])
    out = {}
    for name, sigma in (("with", s1), ("against", -s1)):
        r0, O = rocker_synthesis(mr, k["l"], k["pa"], sigma, s1)
        out[name] = (r0, O, sigma)
    if swing == "auto":
        swing = min(out, key=lambda n: out[n][0])
    r0, O, sigma = out[swing]
    theta, rho = rocker_profile(mr, k["l"], O, sigma, s1)
    return dict(r0=r0, a=float(np.hypot(*O)), theta=theta.max(), rho=rho, swing=swing,
                other=out["against" if swing == "with" else "with"][0])


@pytest.mark.parametrize("swing,rotation", [("with", "ccw"), ("against", "ccw"), ("auto", "ccw"),
                                            ("auto", "cw")])
def test_rocker(swing, rotation):
    k = ROCKER
    ref = rocker_reference(swing, rotation)
    assert ref["theta"] <= max(k["pa"].values()) + 1e-5       # the reference is admissible
    res = run(cam_task(follower="rocker", stroke=k["stroke"], rocker_length=k["l"], phases=k["phases"],
                       laws=k["laws"], pressure_angle=k["pa"], swing=swing, rotation=rotation,
                       roller="auto"))
    c = res["cam"]
    assert c["r0"] == pytest.approx(ref["r0"], rel=1e-5)
    assert c["center_distance"] == pytest.approx(ref["a"], rel=1e-5)
    assert c["max_pressure_angle"] == pytest.approx(ref["theta"], abs=1e-4)
    assert c["rho_min"] == pytest.approx(rho_min_convex(ref["rho"]), rel=1e-4)
    if swing == "auto":
        assert ref["r0"] < ref["other"]


def test_rocker_single_allowed_angle_sign_of_swing():
    """Equal allowed angles, symmetric laws: `with` and `against` differ, `auto` is the smaller."""
    k = dict(l=0.1, stroke=18.0, phases={"rise": 90, "far_dwell": 20, "return": 90},
             laws={"rise": "poly345", "return": "poly345"}, pa=35)
    for swing in ("with", "against"):
        ref = rocker_reference(swing, "ccw", k)
        res = run(cam_task(follower="rocker", stroke=k["stroke"], rocker_length=k["l"], phases=k["phases"],
                           laws=k["laws"], pressure_angle=k["pa"], swing=swing, rotation="ccw"))
        assert res["cam"]["r0"] == pytest.approx(ref["r0"], rel=1e-5), swing
        assert res["cam"]["center_distance"] == pytest.approx(ref["a"], rel=1e-5), swing
