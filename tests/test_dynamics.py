"""Dynamics and the flywheel (METHODS 4) on closed-form fixtures.

Independent references used here:
* a hand-worked 5-node example (trapezoid works, a, b, Merzalov) written out below;
* machines with constant reduced inertia: J_n = (max dT - min dT)/(omega_m^2 delta),
  dT integrated by hand for piecewise-constant loads;
* a machine without loads: energy conservation J omega^2 = const gives
  omega_max/omega_min = sqrt(J_max/J_min), so J_n = (Jv_max - r^2 Jv_min)/(r^2 - 1),
  r = (1 + delta/2)/(1 - delta/2); J_var of a central slider-crank written out here;
* scipy's ODE solver on the differential equation of motion
  J omega domega/dq + J' omega^2/2 = M (a different route from the energy form);
* the bounds min J_var <= J_n(Merzalov) - J_n(exact) <= max J_var and
  |J_n(Wittenbauer tangents) - J_n(exact)| <= (max J_var - min J_var) delta/8
  derived in tmm_cli/linkage/dynamics/flywheel.py's docstring (checked on random fields).
"""
from __future__ import annotations

import json

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from tmm_cli.linkage.dynamics import EPS_DEG, Sample, analyze_sampler, grid, solve_cycle
from tmm_cli.linkage.dynamics import flywheel as fw
from tmm_cli.errors import StageError
from task_sections import flywheel  # noqa: E402  (the section through the task model)

SPEC_KEYS = {"J", "J_energy_mass", "J_merzalov", "J_exact", "J_n", "J_const", "delta_achieved",
             "omega_max", "omega_min", "M_constant", "diameter", "width", "mass"}


def section(delta=0.1, method="energy-mass", constant="driving", resolution=360, shape="disk",
            density=7800.0, width_ratio=0.1, reduced_J=0.0, quadrature=2):
    return flywheel(delta=delta, constant=constant, method=method, resolution=resolution,
                    quadrature=quadrature,
                    shape=dict(type=shape, density=density, width_ratio=width_ratio), reduced_J=reduced_J)


def step_sampler(levels, edges, J0=2.0, Jvar=None):
    """Piecewise-constant reduced moment: levels[k] on [edges[k], edges[k+1]) (deg of the
    cycle, edges[0] = 0); constant reduced inertia J0 (+ optional J_var(q_rad))."""
    edges = np.asarray(edges, float)
    levels = np.asarray(levels, float)

    def sampler(q, side):
        qe = np.mod(q + side * EPS_DEG, 360.0)
        k = np.searchsorted(edges, qe, side="right") - 1
        M = levels[k]
        links = {"crank": np.full(q.shape, J0)}
        dlinks = {"crank": np.zeros(q.shape)}
        if Jvar is not None:
            qr = np.deg2rad(q)
            links["rod"], dlinks["rod"] = Jvar(qr)
        return Sample(M_by_kind={"resistance": M}, M_given=M, J_links=links, dJ_links=dlinks)
    return sampler


# ---------------------------------------------------------------- hand-worked example
def test_hand_worked_five_nodes():
    """Nodes every 90 deg; M_given = -40, -80, -40, 0, -40 N*m; J_var = .2, .6, .2, .6, .2;
    J_const = 1; omega_m = 10 rad/s; delta = 0.2.

    Trapezoid, h = pi/2: A_given = -30pi, -60pi, -70pi, -80pi -> M_constant = 80pi/2pi = 40.
    dT = A_given + 40 q = 0, -10pi, -20pi, -10pi, 0.
    omega_max^2/2 = 11^2/2 = 60.5, omega_min^2/2 = 9^2/2 = 40.5:
      a = max(dT - 60.5 J_var) = -12.1 (q = 0)
      b = min(dT - 40.5 J_var) = -20pi - 8.1 (q = pi)
      J_n = (a - b)/(100 * 0.2) = (20pi - 4)/20 = pi - 0.2, J_fly = pi - 1.2.
    Merzalov: T_II = 50 J_var = 10, 30, 10, 30, 10; dT_I = -10, -10pi-30, -20pi-10, ...
      J_n = (-10 - (-20pi - 10))/20 = pi, J_fly = pi - 1.
    """
    q = np.arange(5) * np.pi / 2
    M = np.array([-40.0, -80, -40, 0, -40])
    Jv = np.array([0.2, 0.6, 0.2, 0.6, 0.2])
    c = solve_cycle(q, M, {"crank": np.ones(5), "rod": Jv}, omega_m=10.0, delta=0.2,
                    dJ_links={"rod": np.zeros(5)})
    assert c.const_links == ["crank"] and c.J_const == pytest.approx(1.0)
    assert c.work.M_constant == pytest.approx(40.0, rel=1e-14)
    assert c.work.dT == pytest.approx(np.array([0, -10, -20, -10, 0]) * np.pi, abs=1e-12)
    assert c.work.A_d == pytest.approx(40 * q)
    assert c.work.A_c == pytest.approx(np.array([0, 30, 60, 70, 80]) * np.pi)
    assert c.a == pytest.approx(-12.1) and c.b == pytest.approx(-20 * np.pi - 8.1)
    assert c.J_fly["energy-mass"] == pytest.approx(np.pi - 1.2, rel=1e-13)
    assert c.J_fly["exact"] == pytest.approx(np.pi - 1.2, rel=1e-10)
    assert c.J_fly["merzalov"] == pytest.approx(np.pi - 1.0, rel=1e-13)
    assert c.J == pytest.approx(np.pi - 1.2, rel=1e-13)
    # the steady motion with this flywheel: omega 11 at q = 0, 9 at q = pi
    assert c.motion.omega_max == pytest.approx(11.0, rel=1e-12)
    assert c.motion.omega_min == pytest.approx(9.0, rel=1e-12)
    assert c.motion.omega[0] == pytest.approx(11.0) and c.motion.omega[2] == pytest.approx(9.0)


# ---------------------------------------------------------------- constant J_red
@pytest.mark.parametrize("method", ["energy-mass", "merzalov", "exact"])
@pytest.mark.parametrize("resolution", [12, 13, 360, 1001])
def test_constant_inertia_closed_form(method, resolution):
    """Resistance 100 N*m over the first half turn, nothing over the second: the driving
    moment is 50 N*m; dT falls by 50*pi over [0, pi] and recovers: range 50 pi J.
    J_n = 50 pi/(omega_m^2 delta); J_fly = J_n - J_crank.  Exact for any resolution
    because the jumps at 0 and 180 deg are grid nodes (inserted twice)."""
    sec = section(delta=0.05, method=method, resolution=resolution)
    r = analyze_sampler(step_sampler([-100.0, 0.0], [0, 180], J0=2.0), sec, 12.0,
                        switch_q=(0.0, 180.0), accuracy=False)
    Jn = 50 * np.pi / (144 * 0.05)
    d = r.to_dict()
    assert d["M_constant"] == pytest.approx(50.0, rel=1e-12)
    for key in ("J_energy_mass", "J_merzalov", "J_exact", "J"):
        assert d[key] == pytest.approx(Jn - 2.0, rel=1e-9), key
    assert d["J_n"] == pytest.approx(Jn, rel=1e-9)
    assert d["J_const"] == 2.0
    assert d["omega_max"] == pytest.approx(12 * 1.025, rel=1e-9)
    assert d["omega_min"] == pytest.approx(12 * 0.975, rel=1e-9)
    assert d["delta_achieved"] == pytest.approx(0.05, rel=1e-9)


@settings(max_examples=40, deadline=None)
@given(st.lists(st.floats(1.0, 359.0), min_size=1, max_size=5, unique=True),
       st.lists(st.floats(-500.0, 500.0), min_size=6, max_size=6),
       st.floats(0.001, 0.2), st.floats(0.5, 200.0), st.integers(12, 400))
def test_piecewise_constant_loads_any_grid(cuts, levels, delta, omega, resolution):
    """Random piecewise-constant moments with jumps at random angles: the works are
    integrated by hand here (sum of level * width), J_n = range(dT)/(omega^2 delta)."""
    edges = np.array([0.0] + sorted(cuts))
    if np.min(np.diff(edges)) < 1e-3:
        return
    lv = np.array(levels[: len(edges)])
    widths = np.diff(np.append(edges, 360.0)) * np.pi / 180
    Mc = -np.sum(lv * widths) / (2 * np.pi)
    ends = np.concatenate([[0.0], np.cumsum((lv + Mc) * widths)])   # dT at the edges
    rng = float(np.max(ends) - np.min(ends))
    sec = section(delta=delta, resolution=resolution, method="exact")
    r = analyze_sampler(step_sampler(lv, edges, J0=0.0), sec, omega, switch_q=list(edges),
                        accuracy=False)
    c = r.cycle
    assert c.work.M_constant == pytest.approx(Mc, rel=1e-9, abs=1e-9)
    Jn = rng / (omega**2 * delta)
    tol = 1e-9 * (np.max(np.abs(lv)) * 2 * np.pi / (omega**2 * delta) + 1e-12)
    for m in ("energy-mass", "merzalov", "exact"):
        assert abs(c.J_n[m] - Jn) <= tol, m
    json.dumps(r.to_dict(), allow_nan=False)


# ---------------------------------------------------------------- energy conservation
def slider_crank_Jvar(r=0.1, l=0.4, m2=4.0, J2=0.06, m3=10.0):
    """Reduced inertia of rod (com mid-length) and slider of a central slider-crank,
    written out: A = r(cos q, sin q), sin th = -r sin q / l, a1 = dth/dq = -r cos q/(l cos th),
    x_B = r cos q + l cos th, dx_B/dq = -r sin q - l sin th a1."""
    def f_only(q):
        sth = -r * np.sin(q) / l
        cth = np.sqrt(1 - sth**2)
        a1 = -r * np.cos(q) / (l * cth)
        dA = np.stack([-r * np.sin(q), r * np.cos(q)], -1)
        dB = np.stack([-r * np.sin(q) - l * sth * a1, np.zeros_like(q)], -1)
        dS = 0.5 * (dA + dB)
        return m2 * np.sum(dS**2, -1) + J2 * a1**2 + m3 * dB[:, 0] ** 2

    def f(q):
        h = 1e-6
        return f_only(q), (f_only(q + h) - f_only(q - h)) / (2 * h)
    return f, f_only


def _true_extremes(f_only):
    """max and min of f_only(q) over a turn: a fine scan, then scipy's bounded search."""
    from scipy.optimize import minimize_scalar
    qs = np.linspace(0, 2 * np.pi, 3601)
    ys = f_only(qs)
    out = []
    for sgn in (1.0, -1.0):
        i = int(np.argmax(sgn * ys))
        lo, hi = qs[max(i - 1, 0)], qs[min(i + 1, qs.size - 1)]
        res = minimize_scalar(lambda x: -sgn * f_only(np.array([x]))[0], bounds=(lo, hi),
                              method="bounded", options={"xatol": 1e-12})
        out.append(max(sgn * ys[i], -res.fun) * sgn)
    return out[0], out[1]


@pytest.mark.parametrize("delta", [0.2, 1 / 18, 1 / 1000])
def test_no_loads_energy_conservation(delta):
    """No loads: T = const, omega ~ 1/sqrt(J): J_n = (Jv_max - r^2 Jv_min)/(r^2 - 1)."""
    f, f_only = slider_crank_Jvar()
    sampler = step_sampler([0.0], [0.0], J0=0.05, Jvar=f)
    r = analyze_sampler(sampler, section(delta=delta, resolution=720), 30.0, accuracy=False)
    Jv = r.cycle.J_var
    rr = ((1 + delta / 2) / (1 - delta / 2)) ** 2
    # the true extremes of J_var (between the grid's nodes), by a bounded scalar search
    Jv_max, Jv_min = _true_extremes(f_only)
    assert Jv_max >= Jv.max() and Jv_min <= Jv.min()
    Jn = (Jv_max - rr * Jv_min) / (rr - 1)
    assert r.cycle.work.M_constant == 0.0
    assert r.cycle.J_n["energy-mass"] == pytest.approx(Jn, rel=1e-10)
    assert r.cycle.J_n["exact"] == pytest.approx(Jn, rel=1e-9)
    # the grid's J_var is the closed form (slider-crank written out above)
    assert Jv == pytest.approx(f_only(np.deg2rad(r.q_deg)), rel=1e-12)
    # omega * sqrt(J) is constant along the motion
    wsj = r.cycle.motion.omega * np.sqrt(r.cycle.J_total)
    assert np.ptp(wsj) <= 1e-12 * wsj.mean()


# ---------------------------------------------------------------- methods compared
def smooth_sampler(M0=120.0, Jc=0.3, J1=0.4, phase=0.7):
    """M_given = -M0 (1 + sin q + 0.4 sin(2q + phase)) and J_var = J1 (1 + cos 2q)/2 + J1 sin^2 q/3."""
    def sampler(q, side):
        x = np.deg2rad(q + side * EPS_DEG)
        M = -M0 * (1 + np.sin(x) + 0.4 * np.sin(2 * x + phase))
        Jv = J1 * (1 + np.cos(2 * x)) / 2 + J1 * np.sin(x) ** 2 / 3
        dJ = -J1 * np.sin(2 * x) + J1 * np.sin(2 * x) / 3
        return Sample(M_by_kind={"resistance": M}, M_given=M,
                      J_links={"crank": np.full(q.shape, Jc), "rod": Jv},
                      dJ_links={"crank": np.zeros(q.shape), "rod": dJ})
    return sampler


@settings(max_examples=60, deadline=None)
@given(st.floats(0.001, 0.2), st.floats(0.0, 3.0), st.floats(0.01, 2.0), st.floats(0.0, 6.0),
       st.integers(12, 400))
def test_method_bounds(delta, M0, J1, phase, resolution):
    """exact == energy-mass (same nodes) to the root tolerance;
    min J_var <= J_n,Merzalov - J_n,exact <= max J_var;
    |J_n,Wittenbauer - J_n,exact| <= ptp(J_var) delta/8."""
    sampler = smooth_sampler(M0=M0 * 100, J1=J1, phase=phase)
    r = analyze_sampler(sampler, section(delta=delta, resolution=resolution), 10.0, accuracy=False)
    c = r.cycle
    Jn = c.J_n
    # the extremes of J_var over the cycle: the nodes' and those located between them
    assert c.J_var_min <= c.J_var.min() and c.J_var_max >= c.J_var.max()
    x = np.linspace(0, 360, 20001)
    Jv_fine = sampler(x, np.zeros_like(x)).J_links["rod"]
    assert c.J_var_max <= Jv_fine.max() * (1 + 1e-12) + 1e-15
    assert c.J_var_min >= Jv_fine.min() * (1 - 1e-12) - 1e-15
    scale = max(abs(Jn["energy-mass"]), c.J_var_max, 1e-12)
    assert abs(Jn["exact"] - Jn["energy-mass"]) <= 1e-9 * scale
    diff = Jn["merzalov"] - Jn["exact"]
    assert c.J_var_min - 1e-9 * scale <= diff <= c.J_var_max + 1e-9 * scale
    assert abs(Jn["wittenbauer"] - Jn["exact"]) <= (c.J_var_max - c.J_var_min) * delta / 8 + 1e-9 * scale
    assert c.motion.delta <= delta * (1 + 1e-9)


def test_exact_against_ode_solver():
    """The flywheel found on a fine grid, put into scipy's solver of the differential
    equation of motion (d omega/dq = (M - J' omega^2/2)/(J omega)) with the initial speed
    tuned so that (max + min)/2 = omega_m, gives the required delta."""
    from scipy.integrate import solve_ivp
    from scipy.optimize import brentq

    delta, wm = 1 / 25, 15.0
    sampler = smooth_sampler()
    r = analyze_sampler(sampler, section(delta=delta, resolution=3600), wm, accuracy=False)
    c = r.cycle
    Jconst = c.J_const + c.J
    M0, J1, ph = 120.0, 0.4, 0.7
    # the constant driving moment over the cycle, by hand: mean of M0 (1 + sin + 0.4 sin(2q+ph)) = M0
    assert c.work.M_constant == pytest.approx(M0, rel=1e-6)

    def rhs(q, y):
        M = -M0 * (1 + np.sin(q) + 0.4 * np.sin(2 * q + ph)) + M0
        J = Jconst + J1 * (1 + np.cos(2 * q)) / 2 + J1 * np.sin(q) ** 2 / 3
        dJ = -J1 * np.sin(2 * q) + J1 * np.sin(2 * q) / 3
        return [(M - dJ * y[0] ** 2 / 2) / (J * y[0])]

    qq = np.linspace(0, 2 * np.pi, 20001)

    def run(w0):
        s = solve_ivp(rhs, (0, 2 * np.pi), [w0], t_eval=qq, rtol=1e-11, atol=1e-12, method="DOP853")
        return s.y[0]

    w0 = brentq(lambda w0: 0.5 * (run(w0).max() + run(w0).min()) - wm, 0.8 * wm, 1.2 * wm, xtol=1e-12)
    w = run(w0)
    assert w[-1] == pytest.approx(w[0], rel=1e-9)               # periodic: zero net work
    d_ode = (w.max() - w.min()) / wm
    assert d_ode == pytest.approx(delta, rel=2e-5)              # grid 0.1 deg: O(h^2)
    assert c.motion.omega_max == pytest.approx(w.max(), rel=1e-6)
    assert c.motion.omega_min == pytest.approx(w.min(), rel=1e-6)
    # omega(q) of the stage against the ODE along the cycle
    wq = np.interp(np.deg2rad(r.q_deg), qq, w)
    assert np.max(np.abs(c.motion.omega - wq)) <= 1e-6 * wm


# ---------------------------------------------------------------- motion at any angle
def test_omega_epsilon_of_satisfy_equation_of_motion():
    """eps = omega domega/dq (finite differences of omega_of) and signs for a cw drive."""
    sampler = smooth_sampler()
    for sign in (1.0, -1.0):
        r = analyze_sampler(sampler, section(delta=0.05, resolution=720), 10.0, sign=sign, phi0=33.0,
                            accuracy=False)
        phi = 33.0 + sign * np.array([10.0, 77.0, 141.5, 250.25, 330.0])
        w, e = r.motion_at(phi)
        assert np.all(np.sign(w) == sign) and np.all(np.abs(w) > 9)
        h = 1e-3
        wp = np.abs(r.omega_of(phi + sign * h))
        wmn = np.abs(r.omega_of(phi - sign * h))
        fd = np.abs(w) * (wp - wmn) / (2 * np.deg2rad(h))        # omega domega/dq = d|omega|/dt
        assert sign * e == pytest.approx(fd, rel=2e-3, abs=1e-3 * np.max(np.abs(e)))
        # at the nodes the arrays and the functions agree
        w_nodes = r.omega_of(r.phi)
        assert np.allclose(np.abs(w_nodes), r.cycle.motion.omega, rtol=1e-12)


def test_motion_at_jump_takes_the_stroke_that_begins():
    """At a jump the right limit applies (SPEC: the load of the stroke that begins)."""
    r = analyze_sampler(step_sampler([-100.0, 0.0], [0, 180], J0=2.0), section(delta=0.1), 10.0,
                        switch_q=(0.0, 180.0), accuracy=False)
    Jt = r.cycle.J_const + r.cycle.J
    w, e = r.motion_at(np.array([0.0, 90.0, 180.0, 270.0]))
    assert e == pytest.approx(np.array([-50, -50, 50, 50]) / Jt, rel=1e-9)
    assert w[0] == pytest.approx(10.5) and w[2] == pytest.approx(9.5)


# ---------------------------------------------------------------- convergence
def _fit_slope(res, err):
    x, y = np.log(np.asarray(res, float)), np.log(np.asarray(err, float))
    return -np.polyfit(x, y, 1)[0]


def test_convergence_order_of_the_rules_with_jumps_inserted():
    """Smooth loads + a jump at 100 deg (inserted): J converges as h^2 with the trapezoid
    (quadrature 0: extrema on the grid) and as h^(2n) with n-point Gauss-Legendre per
    interval and the extrema located between the nodes (the theoretical orders of the
    rules); hand-style (the node at a jump carries one value) only as h."""
    base = smooth_sampler()

    def jumpy(q, side):
        s = base(q, side)
        qe = np.mod(q + side * EPS_DEG, 360.0)
        extra = np.where((qe >= 100.0) & (qe < 250.0), -150.0, 0.0)
        return Sample(M_by_kind={"resistance": s.M_given + extra}, M_given=s.M_given + extra,
                      J_links=s.J_links, dJ_links=s.dJ_links)

    sec = section(delta=0.05, resolution=360)
    ref = analyze_sampler(jumpy, section(delta=0.05, resolution=4000, quadrature=3), 10.0,
                          switch_q=(100.0, 250.0), accuracy=False).cycle.J_n["exact"]
    from tmm_cli.linkage.dynamics.cycle import run_grid
    for n_g, res, band in ((0, [36, 72, 144, 288, 576], (1.6, 2.6)),
                           (1, [36, 72, 144, 288, 576], (1.6, 2.6)),
                           (2, [36, 72, 144, 288, 576], (3.5, 4.5)),
                           (3, [30, 40, 54, 72, 96], (5.0, 7.2))):
        err_in = []
        for n in res:
            ci = analyze_sampler(jumpy, section(delta=0.05, resolution=n + 1, quadrature=n_g), 10.0,
                                 switch_q=(100.0, 250.0), accuracy=False).cycle
            err_in.append(abs(ci.J_n["exact"] / ref - 1))
        p_in = _fit_slope(res, err_in)
        print("quadrature", n_g, "slope", p_in, err_in)
        assert band[0] <= p_in <= band[1], (n_g, p_in, err_in)
    res = [36, 72, 144, 288, 576]
    err_out = []
    for n in res:
        co = run_grid(jumpy, sec, 10.0, 360.0, n, (), insert=False)[0]
        err_out.append(abs(co.J_n["exact"] / ref - 1))
    p_out = _fit_slope(res, err_out)
    assert 0.6 <= p_out <= 1.4, (p_out, err_out)
    assert sec.resolution == 360


def test_accuracy_table_and_hand_row():
    r = analyze_sampler(step_sampler([-100.0, 0.0], [0, 200], J0=2.0), section(delta=0.1), 10.0,
                        switch_q=(0.0, 200.0))
    acc = r.to_dict()["accuracy"]
    rows = acc["rows"]
    assert [x["resolution"] for x in rows] == [12, 24, 36, 72, 180, 360, 3600]
    assert rows[-1]["reference"] and rows[-1]["err_J"] == 0.0
    # piecewise-constant loads with inserted jumps: every resolution exact (closed form:
    # M_c = 100*200/360, dT falls by (100 - M_c)*200 deg, J_n = that/(omega^2 delta))
    Mc = 100 * 200 / 360
    Jn = (100 - Mc) * np.deg2rad(200) / (100 * 0.1)
    for x in rows:
        assert x["J"] == pytest.approx(Jn - 2, rel=1e-9)
        assert x["time_ms"] is None or x["time_ms"] >= 0
    # the 12-position hand calculation (every 30 deg, trapezoid, no inserted jump at 200 deg):
    # M at 0..330 step 30: -100 for q < 200 -> nodes 0..6 (0..180) -100, nodes 7..11 zero,
    # node 12 (= node 0) -100.  Works: 6 full intervals * -100 * pi/6 = -100 pi, interval
    # 180-210 trapezoid -50 pi/6, interval 330-360 -50 pi/6: A = -100pi - 100pi/6 = -700pi/6.
    hand = acc["hand"]
    assert hand["positions"] == 12
    Mc_h = 700 * np.pi / 6 / (2 * np.pi)
    assert hand["M_constant"] == pytest.approx(Mc_h, rel=1e-12)
    # dT at the nodes: -100+Mc_h per interval up to 180, then ...; computed directly:
    qn = np.arange(13) * np.pi / 6
    Mn = np.where(np.arange(13) * 30 < 200, -100.0, 0.0)
    Mn[12] = -100.0
    dT = np.concatenate([[0], np.cumsum((Mn[1:] + Mn[:-1]) / 2 * np.diff(qn))]) + Mc_h * qn
    assert hand["J"] == pytest.approx(np.ptp(dT) / (100 * 0.1) - 2, rel=1e-12)


# ---------------------------------------------------------------- extremes
@settings(max_examples=30, deadline=None)
@given(st.floats(1 / 1000, 1 / 5), st.sampled_from([1e-9, 1e-3, 1.0, 1e4, 1e9]),
       st.sampled_from(["energy-mass", "merzalov", "exact"]))
def test_scale_invariance_and_no_nan(delta, k, method):
    """Loads and inertia scaled by k: J scales by k, speeds do not; never NaN."""
    def scaled(q, side):
        s = smooth_sampler()(q, side)
        return Sample(M_by_kind={x: k * v for x, v in s.M_by_kind.items()}, M_given=k * s.M_given,
                      J_links={x: k * v for x, v in s.J_links.items()},
                      dJ_links={x: k * v for x, v in s.dJ_links.items()})
    sec = section(delta=delta, method=method, resolution=90)
    r1 = analyze_sampler(smooth_sampler(), sec, 10.0, accuracy=False)
    rk = analyze_sampler(scaled, sec, 10.0, accuracy=False)
    assert rk.J == pytest.approx(k * r1.J, rel=1e-8)
    assert rk.cycle.motion.omega_max == pytest.approx(r1.cycle.motion.omega_max, rel=1e-10)
    d = rk.to_dict()
    json.dumps(d, allow_nan=False)
    assert SPEC_KEYS <= set(d)
    assert all(d[key] is not None for key in SPEC_KEYS)


def test_no_flywheel_needed_is_a_warning():
    sampler = step_sampler([-1.0, 0.0], [0, 180], J0=1000.0)
    r = analyze_sampler(sampler, section(delta=0.1), 10.0, switch_q=(0.0, 180.0), accuracy=False)
    d = r.to_dict()
    assert d["J"] == 0.0 and d["J_energy_mass"] < 0 and d["mass"] == 0.0 and d["diameter"] == 0.0
    assert any("no flywheel is needed" in w for w in d["warnings"])
    # delta with the machine's own 1000 kg*m^2: range 0.5 pi J -> ~ dT/(J omega^2)
    assert 0 < d["delta_achieved"] < 0.1
    assert d["delta_achieved"] == pytest.approx(0.5 * np.pi / (1000 * 100), rel=1e-3)


def test_constant_kind_warnings_and_engine():
    """constant: resistance (engine): the given loads are the driving side."""
    r = analyze_sampler(step_sampler([300.0, -60.0], [0, 90], J0=0.5),
                        section(constant="resistance", delta=0.02), 20.0, switch_q=(0.0, 90.0),
                        accuracy=False)
    c = r.cycle
    # work of the given loads: 300 pi/2 - 60 * 3pi/2 = 60 pi, resistance constant 60pi/2pi = 30
    assert -c.work.M_constant == pytest.approx(30.0, rel=1e-12)
    assert c.work.M_c == pytest.approx(np.full(c.q.size, 30.0))
    assert c.work.A_d[-1] == pytest.approx(60 * np.pi) and c.work.A_c[-1] == pytest.approx(60 * np.pi)
    assert not r.warnings
    # the same loads with `constant: driving` would need a negative driving moment
    r2 = analyze_sampler(step_sampler([300.0, -60.0], [0, 90], J0=0.5), section(delta=0.02), 20.0,
                         switch_q=(0.0, 90.0), accuracy=False)
    assert any("net positive work" in w for w in r2.warnings)


def test_stage_errors():
    with pytest.raises(StageError):
        solve_cycle(np.linspace(0, 2 * np.pi, 5), np.array([0, np.nan, 0, 0, 0]), np.ones(5),
                    omega_m=10.0, delta=0.1)
    with pytest.raises(StageError):
        fw.energy_mass(np.zeros(3), np.zeros(3), 10.0, 1.5)
    # no inertia at all and a fluctuating load: a flywheel is needed (finite, positive)
    c = solve_cycle(np.linspace(0, 2 * np.pi, 9), -np.abs(np.sin(np.linspace(0, 2 * np.pi, 9))),
                    np.zeros(9), omega_m=10.0, delta=0.1)
    assert c.J > 0 and c.J_const == 0.0
    # nothing at all: no flywheel, uniform motion
    c = solve_cycle(np.linspace(0, 2 * np.pi, 9), np.zeros(9), np.zeros(9), omega_m=10.0, delta=0.1)
    assert c.J == 0.0 and c.motion.delta == 0.0 and np.all(c.motion.omega == 10.0)


def test_varying_inertia_needs_its_exact_derivative():
    """A link whose reduced inertia varies needs dJ/dq given (from the second transmission
    functions): solve_cycle never takes it by finite differences; a constant one needs none."""
    q = np.linspace(0, 2 * np.pi, 9)
    M = -np.abs(np.sin(q))
    with pytest.raises(ValueError, match="'rod' varies"):
        solve_cycle(q, M, {"crank": np.ones(9), "rod": 1 + 0.5 * np.sin(q)}, omega_m=10.0, delta=0.1)
    with pytest.raises(ValueError, match="'mechanism' varies"):
        solve_cycle(q, M, 1 + 0.5 * np.sin(q), omega_m=10.0, delta=0.1)
    c = solve_cycle(q, M, {"crank": np.ones(9), "rod": 1 + 0.5 * np.sin(q)}, omega_m=10.0, delta=0.1,
                    dJ_links={"rod": 0.5 * np.cos(q)})
    assert c.const_links == ["crank"] and c.J > 0


# ---------------------------------------------------------------- grid and size
def test_grid_inserts_jumps_twice():
    q, side = grid(12, 360.0, [45.0, 90.0, 0.0, 360.0 + 45.0])
    assert list(q[:4]) == [0.0, 30.0, 45.0, 45.0] and list(side[:4]) == [1, 0, -1, 1]
    assert list(q[4:7]) == [60.0, 90.0, 90.0] and list(side[5:7]) == [-1, 1]
    assert q[-1] == 360.0 and side[-1] == -1
    assert q.size == 13 - 1 + 4
    q2, s2 = grid(24, 720.0, [], insert=False)
    assert q2.size == 25 and np.all(s2 == 0)


@pytest.mark.parametrize("shape", ["disk", "rim"])
def test_flywheel_size(shape):
    J, rho, psi = 12.5, 7200.0, 0.2
    s = fw.size(J, shape, rho, psi, 10.0)
    D, b = s.diameter, s.width
    assert b == pytest.approx(psi * D)
    if shape == "disk":
        m = rho * np.pi * D**2 / 4 * b
        assert J == pytest.approx(m * D**2 / 8)
        assert s.rim_speed == pytest.approx(10 * D / 2)
    else:
        m = rho * np.pi * D * b * b
        assert J == pytest.approx(m * D**2 / 4)
    assert s.mass == pytest.approx(m)
    fast = fw.size(J, shape, rho, psi, 200.0)
    assert any("cast iron" in w for w in fast.warnings)
    faster = fw.size(J, shape, 7800.0, psi, 2000.0)
    assert any("steel" in w for w in faster.warnings)
    assert fw.size(J, shape, 7800.0, psi, 1.0).warnings == []


def test_accuracy_table_includes_the_chosen_resolution():
    """A resolution finer than 3600 becomes the reference row; a coarse one gets a warning."""
    r = analyze_sampler(smooth_sampler(), section(delta=0.05, resolution=5000), 10.0)
    acc = r.accuracy
    assert acc["reference_resolution"] == 5000 and acc["rows"][-1]["resolution"] == 5000
    assert acc["err_J"] == 0.0
    # the trapezoid (quadrature 0) at 13 positions is > 1 % off: warned
    r = analyze_sampler(smooth_sampler(), section(delta=0.05, resolution=13, quadrature=0), 10.0)
    assert any(x["resolution"] == 13 for x in r.accuracy["rows"])
    assert r.accuracy["err_J"] > 0.01 and any("resolution" in w for w in r.warnings)


@pytest.mark.parametrize("delta, told", [(1 / 1000, True), (1 / 4, True), (1 / 300, False), (1 / 5, False),
                                         (1 / 20, False)])
def test_a_coefficient_of_fluctuation_outside_the_machines_range_is_told(delta, told):
    """delta = 1/1000 sized a 2.4-tonne disk for a 150 rpm compressor without a word: a delta outside
    the 1/5...1/300 that machines are given (pumps 1/5 to generators 1/300) is warned of; the
    flywheel is sized all the same (J_n = (max dT - min dT)/(omega_m^2 delta) for a constant J:
    dT = 1 - cos q, its range 2)."""
    q = np.linspace(0, 2 * np.pi, 721)
    c = solve_cycle(q, np.sin(q), np.ones(721), omega_m=10.0, delta=delta)
    assert any("coefficient of speed fluctuation" in str(w) for w in c.warnings) == told
    assert c.J_n["energy-mass"] == pytest.approx(2.0 / (100.0 * delta), rel=1e-4)


def test_delta_written_as_its_inverse_is_told_so(tmp_path):
    """`delta: 18` (meant 1/18) was "Input should be less than 1": now exit 2 naming the line and
    the field, with the fraction meant; the schema still says below 1."""
    import re
    from pathlib import Path

    from typer.testing import CliRunner

    from tmm_cli.cli import app
    src = (Path(__file__).resolve().parents[1] / "tasks" / "forging_sixbar.yaml").read_text(encoding="utf-8")
    bad = tmp_path / "t.yaml"
    bad.write_text(src.replace("  delta: 1/18", "  delta: 18"), encoding="utf-8")
    res = CliRunner().invoke(app, ["validate", str(bad)])
    assert res.exit_code == 2 and "did you mean 1/18?" in res.output and "Traceback" not in res.output
    assert re.search(r"t\.yaml:\d+:\d+: field 'flywheel\.delta'", res.output)
    res = CliRunner().invoke(app, ["schema"])
    assert '"exclusiveMaximum": 1' in res.output


def test_delta_of_one_is_below_one_without_a_hint(tmp_path):
    """`delta: 1` has no inverse to suggest ('did you mean 1/1?' was as invalid)."""
    from pathlib import Path

    from typer.testing import CliRunner

    from tmm_cli.cli import app
    src = (Path(__file__).resolve().parents[1] / "tasks" / "forging_sixbar.yaml").read_text(encoding="utf-8")
    bad = tmp_path / "t.yaml"
    bad.write_text(src.replace("  delta: 1/18", "  delta: 1"), encoding="utf-8")
    res = CliRunner().invoke(app, ["validate", str(bad)])
    assert res.exit_code == 2 and "less than 1" in res.output and "did you mean" not in res.output
