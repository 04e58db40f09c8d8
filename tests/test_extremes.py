"""Numerical soundness at the extremes: flywheel, cam and gear stages.

Every case runs through the public API (``tmm_cli.run(tmm_cli.load_task(dict))``) and must
give finite, correct results or a clear StageError naming the stage and the reason -- never
NaN/inf, never another exception, never a silent wrong answer.

Independent references written out here:

* flywheel -- a central slider-crank whose only inertia is the crank's (J_red constant):
  dT(q) = M_c q - W(q) with W the work against the resistance, W = F s(q) over the working
  (down) stroke, s(q) = r + L - r cos q - sqrt(L^2 - r^2 sin^2 q) from the loop closure,
  M_c = A_cycle / (2 pi); the extremes of dT at the roots of dT' (brentq) and the ends;
  METHODS 4 with J_var = 0: J_n = (max dT - min dT) / (omega_m^2 delta).  Scaling laws
  (J proportional to every mass when the loads are gravity only, J_n delta constant when
  J_red is constant) and the mirror symmetry of the central slider-crank (a cw drive is the
  mirror image of a ccw one);
* cam -- a central translating follower: the pressure angle is atan(|s'|/(r0 + s)) (offset
  e: atan(|s' - e|/(sqrt(r0^2 - e^2) + s)), Artobolevsky), so the least base radius is
  r0 = max over the rise and the return of (|s'|/tan theta_allowed - s), maximised here on a
  dense grid refined by a bounded scalar search; the pitch radius is r0 + s (inverted motion);
* gears -- GOST 16532 formulas written out below with an inverse involute by bisection,
  the course's undercut limit x_min = ha (z_min - z)/z_min, z_min = round(2 ha / sin^2 alpha);
* planetary -- Willis' ratio, coaxiality, the assembly condition and adjacency checked with
  exact fractions here.
"""
from __future__ import annotations

import copy
import math
from fractions import Fraction

import numpy as np
import pytest
from scipy.optimize import brentq, minimize_scalar

import tmm_cli
from tmm_cli.errors import StageError


# ----------------------------------------------------------------------------- helpers
def run(task: dict) -> dict:
    return tmm_cli.run(tmm_cli.load_task(copy.deepcopy(task)))


def nonfinite(obj, path="") -> list[str]:
    """Paths of NaN/inf floats anywhere in the results."""
    bad = []
    if isinstance(obj, dict):
        for k, v in obj.items():
            bad += nonfinite(v, f"{path}.{k}")
    elif isinstance(obj, (list, tuple)):
        for i, v in enumerate(obj):
            bad += nonfinite(v, f"{path}[{i}]")
    elif isinstance(obj, float) and not math.isfinite(obj):
        bad.append(path)
    return bad


def run_ok(task: dict) -> dict:
    res = run(task)
    assert nonfinite(res) == []
    return res


def stage_error(task: dict, stage: str) -> StageError:
    with pytest.raises(StageError) as ei:
        run(task)
    err = ei.value
    assert err.stage == stage
    assert err.message and "Error:" not in err.message      # not a wrapped Python exception
    return err


# ============================================================================ flywheel
R, L = 0.1, 0.4            # crank and rod of a central slider-crank, guide = y axis
N_RPM = 100.0
OMEGA = N_RPM * math.pi / 30
F = 1000.0                 # resistance on the working (down) stroke, N
J_CRANK = 0.01             # crank J about its pivot (its centre of mass is the pivot)


def engine(*, delta=0.1, res=360, loads=None, gravity=False, mass=1.0, inertia=True,
           direction="ccw", cycle=None, extra=None) -> dict:
    """Central slider-crank; position 0 = top dead centre (crank at 90 deg), the working
    stroke is the down stroke (the first half-turn either way round)."""
    rod = {"points": ["A", "B"], "length": L}
    ram = {"slider": "B", "guide": {"through": "O", "angle": 90}}
    if inertia:
        rod.update(mass=3 * mass, J=0.05 * mass)
        ram.update(mass=10 * mass)
    t = {"schema": "tmm/1",
         "mechanism": {"ground": {"O": [0, 0]},
                       "links": {"crank": {"points": ["O", "A"], "length": R, "mass": 2 * mass,
                                           "J": J_CRANK * mass},
                                 "rod": rod, "ram": ram},
                       "assembly": {"B": [0, 0.45]}},
         "drive": {"link": "crank", "speed": f"{N_RPM} rpm", "direction": direction},
         "positions": {"output": "ram", "working": "backward"},
         "loads": {"gravity": gravity,
                   "forces": loads if loads is not None else
                   [{"on": "ram", "kind": "resistance", "stroke": "working", "magnitude": F}]},
         "flywheel": {"delta": delta, "resolution": res}}
    if cycle:
        t["drive"]["cycle"] = cycle
    if extra:
        t.update(extra)
    return t


def s_down(q):
    """Ram displacement from the top dead centre, crank turned by q from it."""
    return R + L - R * np.cos(q) - np.sqrt(L * L - (R * np.sin(q)) ** 2)


def ds_down(q):
    return R * np.sin(q) + R * R * np.sin(q) * np.cos(q) / np.sqrt(L * L - (R * np.sin(q)) ** 2)


def dT_extremes(work, dwork, A_cycle):
    """(max, min) of dT(q) = M_c q - work(q) over [0, 2 pi], work piecewise smooth on the
    working half-turn and constant after it; M_c = A_cycle / (2 pi)."""
    Mc = A_cycle / (2 * math.pi)
    dT = lambda q: Mc * q - work(q)                                     # noqa: E731
    g = lambda q: Mc - dwork(q)                                         # noqa: E731
    cands = [0.0, math.pi, 2 * math.pi]
    qs = np.linspace(1e-9, math.pi - 1e-9, 4001)
    gv = g(qs)
    for a, b, ga, gb in zip(qs[:-1], qs[1:], gv[:-1], gv[1:]):
        if ga * gb < 0:
            cands.append(brentq(g, a, b, xtol=1e-15))
    vals = [dT(q) if q <= math.pi else Mc * q - A_cycle for q in cands]
    return max(vals), min(vals)


def J_closed_constant_resistance(delta):
    H = 2 * R
    mx, mn = dT_extremes(lambda q: F * s_down(q), lambda q: F * ds_down(q), F * H)
    return (mx - mn) / (OMEGA**2 * delta) - J_CRANK


@pytest.mark.parametrize("delta", [1 / 5, 1 / 1000, 1e-4])
def test_flywheel_constant_inertia_matches_closed_form_at_small_and_large_delta(delta):
    res = run_ok(engine(delta=delta, res=3600, inertia=False))
    fw = res["flywheel"]
    ref = J_closed_constant_resistance(delta)
    assert fw["J"] == pytest.approx(ref, rel=2e-6)
    # J_var = 0: the three methods coincide
    for k in ("J_energy_mass", "J_merzalov", "J_exact"):
        assert fw[k] == pytest.approx(fw["J"], rel=1e-9)
    assert fw["J_const"] == pytest.approx(J_CRANK, rel=1e-12)
    # the work by the trapezoid on 3600 steps: ~h^2 relative
    assert fw["M_constant"] == pytest.approx(F * 2 * R / (2 * math.pi), rel=1e-6)
    assert fw["omega_max"] == pytest.approx(OMEGA * (1 + delta / 2), rel=1e-10)
    assert fw["omega_min"] == pytest.approx(OMEGA * (1 - delta / 2), rel=1e-10)
    assert abs(fw["delta_achieved"] - delta) <= 1e-7 * delta
    assert fw["J"] >= 0 and fw["diameter"] > 0


def test_flywheel_Jn_times_delta_is_constant_for_constant_inertia():
    # J_var = 0: J_n = range(dT)/(omega_m^2 delta), the same grid for every delta
    prods = [(run_ok(engine(delta=d, inertia=False))["flywheel"]["J_n"]) * d
             for d in (1 / 5, 1 / 18, 1 / 1000, 1e-4)]
    assert max(prods) == pytest.approx(min(prods), rel=1e-9)


def test_flywheel_resolution_12_and_20000():
    ref = J_closed_constant_resistance(0.1)
    coarse = run_ok(engine(res=12, inertia=False))
    fine = run_ok(engine(res=20000, inertia=False))
    assert fine["flywheel"]["J"] == pytest.approx(ref, rel=1e-7)
    assert coarse["flywheel"]["J"] == pytest.approx(ref, rel=0.1)
    assert any("resolution" in w for w in coarse["warnings"])
    # the coarse grid is still a steady motion with exactly the requested fluctuation
    fc = coarse["flywheel"]
    assert fc["omega_max"] == pytest.approx(OMEGA * 1.05, rel=1e-10)
    assert fc["omega_min"] == pytest.approx(OMEGA * 0.95, rel=1e-10)


def test_flywheel_resistance_switched_on_mid_stroke():
    H = 2 * R
    loads = [{"on": "ram", "kind": "resistance", "stroke": "working",
              "diagram": {"s": [0, 0.5, 0.5, 1], "value": [0, 0, F, F]}}]
    fw = run_ok(engine(loads=loads, res=3600, inertia=False))["flywheel"]
    mx, mn = dT_extremes(lambda q: F * np.maximum(s_down(q) - H / 2, 0.0),
                         lambda q: F * ds_down(q) * (s_down(q) > H / 2), F * H / 2)
    assert fw["M_constant"] == pytest.approx(F * H / 2 / (2 * math.pi), rel=1e-6)
    assert fw["J"] == pytest.approx((mx - mn) / (OMEGA**2 * 0.1) - J_CRANK, rel=2e-6)


def test_flywheel_load_jump_at_the_extreme_positions_and_at_position_0():
    const = run_ok(engine())["flywheel"]["J"]
    # a jump exactly where the working stroke starts (s = 0), or ends (s = 1): the same load
    # as a constant magnitude everywhere else
    start = [{"on": "ram", "kind": "resistance", "stroke": "working",
              "diagram": {"s": [0, 0, 1], "value": [0, F, F]}}]
    end = [{"on": "ram", "kind": "resistance", "stroke": "working",
            "diagram": {"s": [0, 1, 1], "value": [F, F, 0]}}]
    # a crank-angle diagram jumping at position 0 and at the second extreme (180 deg): +F
    # along the guide (up) while the ram moves down resists, exactly the working-stroke load
    phi = [{"on": "ram", "diagram": {"phi": [0, 0, 180, 180, 360], "value": [0, F, F, 0, 0]}}]
    for loads in (start, end, phi):
        fw = run_ok(engine(loads=loads))["flywheel"]
        assert fw["J"] == pytest.approx(const, rel=1e-8)
        assert fw["M_constant"] > 0


def test_flywheel_masses_scale_J_linearly_with_gravity_only():
    base = run_ok(engine(loads=[], gravity=True))["flywheel"]
    assert base["J"] > 0
    # gravity does no net work over the cycle
    assert abs(base["M_constant"]) <= 1e-9 * 15 * 9.81 * R
    for k in (1e-6, 1e6):
        fw = run_ok(engine(loads=[], gravity=True, mass=k))["flywheel"]
        assert fw["J"] == pytest.approx(k * base["J"], rel=1e-9)
        assert fw["J_const"] == pytest.approx(k * base["J_const"], rel=1e-12)
        assert fw["omega_max"] == pytest.approx(base["omega_max"], rel=1e-12)
        assert fw["delta_achieved"] == pytest.approx(0.1, rel=1e-7)


def test_flywheel_light_and_heavy_machine_with_a_working_load():
    for k in (1e-6, 1e6):
        fw = run_ok(engine(mass=k, gravity=True))["flywheel"]
        assert fw["J"] >= 0
        assert fw["omega_max"] == pytest.approx(OMEGA * 1.05, rel=1e-9)
        assert fw["omega_min"] == pytest.approx(OMEGA * 0.95, rel=1e-9)
    # the very light machine is the constant-inertia one plus nothing
    light = run_ok(engine(mass=1e-6))["flywheel"]["J"]
    assert light == pytest.approx(J_closed_constant_resistance(0.1), rel=1e-3)


def test_flywheel_no_work_no_fluctuation_gives_zero_with_a_warning():
    # massless links, gravity only: nothing does work and J_red = 0 -> no flywheel
    res = run_ok(engine(loads=[], gravity=True, inertia=False, mass=0.0))
    fw = res["flywheel"]
    assert fw["J"] == 0.0 and fw["J_n"] == 0.0 and fw["delta_achieved"] == 0.0
    assert fw["omega_max"] == fw["omega_min"] == pytest.approx(OMEGA, rel=1e-12)
    assert any("no flywheel is needed" in w for w in res["warnings"])
    # crank inertia only, gravity at the pivot does no work: the crank's own J suffices
    res = run_ok(engine(loads=[], gravity=True, inertia=False))
    assert res["flywheel"]["J"] == 0.0
    assert any("no flywheel is needed" in w for w in res["warnings"])
    assert "-0.0" not in repr(res["flywheel"]["M_constant"])


def test_regression_massless_machine_motion_true_is_uniform_not_nan():
    # Before: DynamicsResult.motion_at divided 0/0 (no inertia at all) -> omega = NaN, and
    # kinetostatics flagged every position as singular.  Massless, unloaded: omega = omega_m,
    # every balancing moment is zero.
    t = engine(loads=[], inertia=False, mass=0.0, extra={"kinetostatics": {"motion": True}})
    res = run_ok(t)
    assert not any("singular" in w for w in res["warnings"])
    for e in res["kinetostatics"]:
        assert e["balancing_moment"] == pytest.approx(0.0, abs=1e-12)
        assert not e.get("near_singular")
    assert res["flywheel"]["arrays"]["omega"] == pytest.approx([OMEGA] * len(res["flywheel"]["arrays"]["omega"]))


def test_flywheel_cw_720_cycle_is_the_mirror_of_ccw_360():
    # the central slider-crank is symmetric about the guide: a cw drive is the mirror image,
    # and with stroke loads the 720-deg cycle repeats the 360-deg one
    ccw = run_ok(engine(gravity=True, res=360))["flywheel"]
    cw = run_ok(engine(gravity=True, res=720, direction="cw", cycle=720))["flywheel"]
    assert cw["J"] == pytest.approx(ccw["J"], rel=1e-9)
    assert cw["M_constant"] == pytest.approx(ccw["M_constant"], rel=1e-9)
    assert cw["cycle"] == 720 and cw["direction"] == "cw"
    assert cw["omega_max"] == pytest.approx(OMEGA * 1.05, rel=1e-10)
    assert all(w <= 0 for w in cw["arrays"]["omega"])       # signed: cw is negative


def test_flywheel_all_methods_and_variable_inertia_invariants():
    for method in ("energy-mass", "merzalov", "exact"):
        t = engine(gravity=True, delta=1 / 1000)
        t["flywheel"]["method"] = method
        fw = run_ok(t)["flywheel"]
        assert fw["J"] >= 0 and fw["J_n"] > 0
        # METHODS 4: Merzalov exceeds the exact J_n by between min and max of J_var
        assert fw["J_var_min"] - 1e-9 <= fw["J_merzalov"] - fw["J_energy_mass"] <= fw["J_var_max"] + 1e-9
        assert fw["J_exact"] == pytest.approx(fw["J_energy_mass"], rel=1e-9)
        if method != "merzalov":
            assert abs(fw["delta_achieved"] - 1e-3) <= 1e-9
        else:
            assert fw["delta_achieved"] < 1e-3


# ================================================================================= cam
LAW_F = {   # f(x), f'(x) of the laws used here (x: phase fraction)
    "cosine": (lambda x: (1 - np.cos(np.pi * x)) / 2, lambda x: np.pi / 2 * np.sin(np.pi * x)),
    "sine": (lambda x: x - np.sin(2 * np.pi * x) / (2 * np.pi), lambda x: 1 - np.cos(2 * np.pi * x)),
}


def cam_task(**kw) -> dict:
    c = {"follower": "translating", "stroke": 0.03, "phases": {"rise": 120, "far_dwell": 30, "return": 120},
         "laws": {"rise": "sine", "return": "cosine"}, "pressure_angle": 30, "offset": 0}
    c.update(kw)
    return {"schema": "tmm/1", "cam": c}


def central_r0(h, rise, ret, law_rise, law_ret, th_rise, th_ret):
    """Least base radius of a central translating follower: max(|s'|/tan theta - s)."""
    best = -math.inf
    for P, law, th, up in ((math.radians(rise), law_rise, th_rise, True),
                           (math.radians(ret), law_ret, th_ret, False)):
        f, f1 = LAW_F[law]
        t = math.tan(math.radians(th))

        def g(x):
            s = h * f(x) if up else h * (1 - f(x))
            return -(h * f1(x) / P / t - s)
        xs = np.linspace(0, 1, 20001)
        k = int(np.argmin(g(xs)))
        lo, hi = xs[max(k - 1, 0)], xs[min(k + 1, xs.size - 1)]
        r = minimize_scalar(g, bounds=(lo, hi), method="bounded", options={"xatol": 1e-14})
        best = max(best, -float(r.fun), -float(g(xs[k])))
    return best


def s_of_phi(cam, phi_deg):
    """s and ds/dphi of the task's motion at cycle angles (right-continuous)."""
    h = cam["stroke"]
    ph = cam["phases"]
    rise, far, ret = ph["rise"], ph.get("far_dwell", 0.0), ph["return"]
    phi = np.asarray(phi_deg, float)
    s, s1 = np.zeros_like(phi), np.zeros_like(phi)
    m = phi < rise
    f, f1 = LAW_F[cam["laws"]["rise"]]
    s[m] = h * f(phi[m] / rise)
    s1[m] = h * f1(phi[m] / rise) / math.radians(rise)
    m = (phi >= rise) & (phi < rise + far)
    s[m] = h
    m = (phi >= rise + far) & (phi < rise + far + ret)
    f, f1 = LAW_F[cam["laws"]["return"]]
    x = (phi[m] - rise - far) / ret
    s[m] = h * (1 - f(x))
    s1[m] = -h * f1(x) / math.radians(ret)
    return s, s1


def check_cam_invariants(c: dict):
    lim = c["pressure_angle_allowed"]
    assert c["r0"] > 0 and c["roller"] > 0 and c["rho_min"] > 0
    assert c["max_pressure_angle_rise"] <= lim["rise"] + 1e-6
    assert c["max_pressure_angle_return"] <= lim["return"] + 1e-6
    assert max(c["pressure_angle"]) <= max(lim.values()) + 1e-6
    # the smallest cam: at least one limit is binding
    assert max(c["max_pressure_angle_rise"] - lim["rise"],
               c["max_pressure_angle_return"] - lim["return"]) == pytest.approx(0.0, abs=1e-6)
    # the pitch profile is a closed curve around O that winds once
    P = np.asarray(c["pitch_profile"])
    ang = np.unwrap(np.arctan2(P[:, 1], P[:, 0]))
    close = math.atan2(P[-1, 0] * P[0, 1] - P[-1, 1] * P[0, 0], float(np.dot(P[-1], P[0])))
    turn = ang[-1] - ang[0] + close
    assert abs(abs(turn) - 2 * math.pi) < 1e-9
    assert c["roller"] < c["rho_min"] and c["roller"] < c["r0"]


@pytest.mark.parametrize("phases,laws,pa", [
    ({"rise": 1, "far_dwell": 30, "return": 120}, ("cosine", "cosine"), 30),      # tiny rise
    ({"rise": 1, "far_dwell": 10, "return": 1}, ("sine", "cosine"), 30),          # tiny both
    ({"rise": 180, "return": 180}, ("cosine", "sine"), 30),                       # no dwells
    ({"rise": 300, "return": 60}, ("sine", "cosine"), 30),                        # no dwells
    ({"rise": 120, "far_dwell": 30, "return": 120}, ("sine", "cosine"), 89),      # nearly 90
    ({"rise": 120, "far_dwell": 30, "return": 120}, ("sine", "cosine"), 1),       # tiny angle
])
def test_cam_central_follower_extremes_match_closed_form(phases, laws, pa):
    t = cam_task(phases=phases, laws={"rise": laws[0], "return": laws[1]}, pressure_angle=pa)
    c = run_ok(t)["cam"]
    ref = central_r0(0.03, phases["rise"], phases["return"], laws[0], laws[1], pa, pa)
    assert c["r0"] == pytest.approx(ref, rel=1e-8)
    check_cam_invariants(c)
    # inverted motion: the pitch radius is r0 + s; pressure angle atan(|s'|/(r0 + s))
    phi = np.asarray(c["phi"])
    s, s1 = s_of_phi(t["cam"], phi)
    P = np.asarray(c["pitch_profile"])
    assert np.hypot(P[:, 0], P[:, 1]) == pytest.approx(c["r0"] + s, rel=1e-9, abs=1e-12)
    th = np.degrees(np.arctan2(np.abs(s1), c["r0"] + s))
    assert np.asarray(c["pressure_angle"]) == pytest.approx(th, abs=1e-7)


def test_cam_auto_offset_with_asymmetric_limits():
    for lim, sign in (({"rise": 10, "return": 80}, 1), ({"rise": 80, "return": 10}, -1)):
        t = cam_task(offset="auto", pressure_angle=lim)
        c = run_ok(t)["cam"]
        check_cam_invariants(c)
        e, r0 = c["offset"], c["r0"]
        assert sign * e > 0          # the offset helps the stricter phase
        # own pressure angle with this offset: tan theta = |s' - e| / (sqrt(r0^2 - e^2) + s)
        phi = np.linspace(0, 360, 36001)[:-1]
        s, s1 = s_of_phi(t["cam"], phi)
        th = np.degrees(np.arctan2(np.abs(s1 - e), math.sqrt(r0 * r0 - e * e) + s))
        rise = phi < 120
        ret = (phi >= 150) & (phi < 270)
        assert th[rise].max() <= lim["rise"] + 1e-6
        assert th[ret].max() <= lim["return"] + 1e-6
        assert th.max() == pytest.approx(max(c["max_pressure_angle_rise"], c["max_pressure_angle_return"]),
                                         abs=1e-3)
        # optimal: no smaller than r0 with the offset fixed at 0 or at other values
        for e_fixed in (0.0, e / 2, 2 * e):
            other = run_ok(cam_task(offset=e_fixed, pressure_angle=lim))["cam"]["r0"]
            assert r0 <= other * (1 + 1e-9)


@pytest.mark.parametrize("swing", [1, 170])
def test_cam_rocker_swing_1_and_170_deg(swing):
    # 170 deg needs an allowed angle above half the swing (see the regression test below)
    pa = 45 if swing == 1 else 89
    c = run_ok(cam_task(follower="rocker", stroke=swing, rocker_length=0.1, pressure_angle=pa,
                        offset=0))["cam"]
    check_cam_invariants(c)
    assert c["center_distance"] > 0
    assert c["swing"] in ("with", "against")
    # the rocker pivot, the cam centre and B0: |O B0| = r0 and |A B0| = l
    con = c["construction"]
    A, B0 = np.asarray(con["A"]), np.asarray(con["B0"])
    assert math.hypot(*B0) == pytest.approx(c["r0"], rel=1e-9)
    assert math.hypot(*(A - B0)) == pytest.approx(0.1, rel=1e-9)
    assert math.hypot(*A) == pytest.approx(c["center_distance"], rel=1e-9)


@pytest.mark.parametrize("swing,pa,sw", [(90, 45, "with"), (90, 45, "auto"), (170, 85, "auto"),
                                         (120, 60, "against")])
def test_regression_rocker_limit_below_half_swing_is_a_clear_error(swing, pa, sw):
    # Before: the exchange method diverged (the region's infimum lies at infinity) and the
    # last, infeasible centre was returned: r0 of hundreds of metres with the maximum pressure
    # angle above the allowed one (45.005 > 45 deg for 90/45/with).  With dwells at both ends
    # the best pressure angle tends to half the swing only as the cam centre goes to infinity.
    err = stage_error(cam_task(follower="rocker", stroke=swing, rocker_length=0.1,
                               pressure_angle=pa, swing=sw, offset=0), "cam")
    assert "admissible region is empty" in err.message
    assert "half the swing" in err.message


def test_regression_rocker_never_reports_a_centre_on_the_wrong_side():
    # Before: maximum pressure angle 180 deg (the cam centre on the wrong side) was returned
    # with r0 = 32 m for a 10 mm rocker.
    t = cam_task(follower="rocker", stroke=10, rocker_length=0.01, pressure_angle=5, offset=0,
                 phases={"rise": 90, "far_dwell": 180, "return": 90},
                 laws={"rise": "sine", "return": "cosine"})
    err = stage_error(t, "cam")
    assert "increase the allowed pressure angle" in err.message


def test_cam_roller_larger_than_rho_min_is_undercut():
    c = run_ok(cam_task())["cam"]
    err = stage_error(cam_task(roller=1.01 * c["rho_min"]), "cam")
    assert "undercut" in err.message
    # between 0.8 and 1 rho_min (and below 0.4 r0): allowed with the course-rule warning
    if 0.9 * c["rho_min"] < 0.5 * c["r0"]:
        res = run_ok(cam_task(roller=0.9 * c["rho_min"]))
        assert any("0.8 rho_min" in w for w in res["warnings"])


def test_cam_constant_velocity_corners():
    t = cam_task(laws={"rise": "constant_velocity", "return": "constant_velocity"},
                 phases={"rise": 90, "far_dwell": 45, "return": 135})
    res = run_ok(t)
    c = res["cam"]
    check_cam_invariants(c)
    corner = [w for w in res["warnings"] if "corners" in w]
    assert len(corner) == 1
    for a in ("0", "90", "135", "270"):
        assert a in corner[0]
    # central follower, constant velocity: r0 = max(h/(P tan theta) - s) is at the start
    # of each phase with s'= h/P: rise at s = 0, return at s = h
    h, t30 = 0.03, math.tan(math.radians(30))
    ref = max(h / (math.radians(90) * t30), h / (math.radians(135) * t30) - h)
    assert c["r0"] == pytest.approx(ref, rel=1e-9)
    # near dwell: a circle of radius r0 on the pitch profile, so rho_min <= r0
    assert c["rho_min"] <= c["r0"] * (1 + 1e-9)


def test_cam_huge_stroke_tiny_pressure_angle_is_finite():
    c = run_ok(cam_task(stroke=10.0, pressure_angle=1, offset=0))["cam"]
    assert c["r0"] == pytest.approx(central_r0(10.0, 120, 120, "sine", "cosine", 1, 1), rel=1e-8)
    check_cam_invariants(c)


# =============================================================================== gears
def inv(a):
    return math.tan(a) - a


def inv_bisect(v):
    lo, hi = 0.0, math.pi / 2 - 1e-12
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if inv(mid) < v:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def gost(m, z1, z2, x1, x2, alpha=20.0, ha=1.0, c=0.25):
    """GOST 16532-70 pair (Popov & Timofeev), written out independently."""
    al = math.radians(alpha)
    inv_w = inv(al) + 2 * (x1 + x2) * math.tan(al) / (z1 + z2)
    if inv_w <= 0:
        return None
    aw_ang = inv_bisect(inv_w)
    a = m * (z1 + z2) / 2
    aw = a * math.cos(al) / math.cos(aw_ang)
    y = (aw - a) / m
    dy = x1 + x2 - y
    out = {"alpha_w": math.degrees(aw_ang), "aw": aw, "ra": [], "sa": [], "x_min": [], "rb": []}
    zmin = round(2 * ha / math.sin(al) ** 2)
    eps = 0.0
    for z, x in ((z1, x1), (z2, x2)):
        r = m * z / 2
        rb = r * math.cos(al)
        ra = r + (ha + x - dy) * m
        s = m * (math.pi / 2 + 2 * x * math.tan(al))
        aa = math.acos(min(rb / ra, 1.0))
        out["ra"].append(ra)
        out["rb"].append(rb)
        out["sa"].append(2 * ra * (s / (2 * r) + inv(al) - inv(aa)))
        out["x_min"].append(ha * (zmin - z) / zmin)
        eps += z * (math.tan(aa) - math.tan(aw_ang))
    out["eps"] = eps / (2 * math.pi)
    return out


def check_gear_verdicts(g: dict, x, m, sa_min=0.25):
    ch = g["checks"]
    for i in (0, 1):
        assert ch["undercut"][i] == (x[i] < g["x_min"][i] - 1e-12)
        assert ch["sharpening"][i] == (g["sa"][i] < sa_min * m * (1 - 1e-12))
    assert ch["contact_ratio_low"] == (g["eps_alpha"] < 1.2 - 1e-12)
    # every defect is also a warning
    words = " ".join(g.get("_warnings", []))
    if any(ch["undercut"]):
        assert "undercut" in words
    if any(ch["sharpening"]):
        assert "too thin" in words
    if ch["contact_ratio_low"]:
        assert "contact ratio" in words
    if ch["interference"]:
        assert "interference" in words or "no involute flank" in words


def gears_run(m, z, x, **kw):
    res = run_ok({"schema": "tmm/1", "gears": {"m": m, "z": list(z), "x": x, **kw}})
    g = res["gears"]
    g["_warnings"] = res["warnings"]
    return g


@pytest.mark.parametrize("z", [(5, 300), (300, 300), (5, 5), (17, 17), (12, 300)])
def test_gears_tooth_numbers_5_to_300_zero_shift(z):
    m = 0.002
    g = gears_run(m, z, [0, 0])
    ref = gost(m, *z, 0, 0)
    assert g["aw"] == pytest.approx(m * (z[0] + z[1]) / 2, rel=1e-14)
    assert g["alpha_w"] == pytest.approx(20.0, abs=1e-12)
    assert g["sa"] == pytest.approx(ref["sa"], rel=1e-12)
    assert g["eps_alpha"] == pytest.approx(ref["eps"], rel=1e-12)
    assert g["checks"]["undercut"] == [z[0] < 17, z[1] < 17]
    check_gear_verdicts(g, (0, 0), m)


@pytest.mark.parametrize("alpha,ha", [(20, 1.0), (14.5, 1.0), (25, 1.0), (20, 0.8)])
def test_gears_shift_grid_minus_1_to_plus_2(alpha, ha):
    m = 0.001
    for z in ((12, 30), (17, 40), (40, 100)):
        for x1 in (-1.0, -0.5, 0.0, 0.5, 1.0, 2.0):
            for x2 in (-1.0, 0.0, 1.0, 2.0):
                ref = gost(m, *z, x1, x2, alpha, ha)
                task = {"schema": "tmm/1", "gears": {"m": m, "z": list(z), "x": [x1, x2],
                                                     "alpha": alpha, "ha": ha}}
                if ref is None:      # inv alpha_w <= 0: no working pressure angle exists
                    err = stage_error(task, "gears")
                    assert "no mesh angle" in err.message
                    continue
                try:
                    g = gears_run(m, z, [x1, x2], alpha=alpha, ha=ha)
                except StageError as err:       # only a missing tooth is acceptable here
                    assert err.stage == "gears" and "root" in err.message
                    continue
                assert g["alpha_w"] == pytest.approx(ref["alpha_w"], abs=1e-9)
                assert g["aw"] == pytest.approx(ref["aw"], rel=1e-12)
                assert g["ra"] == pytest.approx(ref["ra"], rel=1e-12)
                assert g["sa"] == pytest.approx(ref["sa"], rel=1e-9, abs=1e-15)
                assert g["x_min"] == pytest.approx(ref["x_min"], rel=1e-12)
                assert g["eps_alpha"] == pytest.approx(ref["eps"], rel=1e-9)
                check_gear_verdicts(g, (x1, x2), m)


def test_gears_pair_where_everything_fails_has_clear_verdicts():
    m = 0.001
    g = gears_run(m, (10, 6), [0, 0.3])
    ch = g["checks"]
    assert ch["undercut"] == [True, True]
    assert ch["sharpening"] == [False, True]
    assert ch["contact_ratio_low"] and ch["interference"]
    check_gear_verdicts(g, (0, 0.3), m)
    assert g["blocking_contour"]["chosen_admissible"] is False


@pytest.mark.parametrize("z,x,alpha", [((5, 12), (2, -1), 14.5), ((5, 5), (-1, 2), 14.5),
                                       ((8, 12), (2, -1), 14.5), ((100, 5), (2, 2), 14.5)])
def test_regression_tooth_without_involute_gives_verdicts_not_a_crash(z, x, alpha):
    # Before: Wheel.flank called brentq on an interval without a sign change (the tooth is
    # pointed below the start of its involute, or its tip lies inside the base circle) and
    # the stage failed with "ValueError: f(a) and f(b) must have different signs".
    m = 0.001
    g = gears_run(m, z, list(x), alpha=alpha)
    assert any("no involute flank" in w for w in g["_warnings"])
    assert g["checks"]["interference"] is True
    assert g["blocking_contour"]["chosen_admissible"] is False
    check_gear_verdicts(g, x, m)


@pytest.mark.parametrize("z1", [6, 7, 8, 9, 10])
def test_gears_auto_shift_for_small_pinions(z1):
    m = 0.002
    for z2 in (12, 40):
        g = gears_run(m, (z1, z2), "auto")
        x = g["x"]
        check_gear_verdicts(g, x, m)
        defects = (any(g["checks"]["undercut"]) or any(g["checks"]["sharpening"])
                   or g["checks"]["contact_ratio_low"] or g["checks"]["interference"])
        moved = any("blocking contour" in w or "no shifts satisfy" in w for w in g["_warnings"])
        # either the rule's point is admissible, or the tool says it had to move / give up
        assert (not defects) or moved
        assert g["blocking_contour"]["chosen_admissible"] == (not defects)


def test_inverse_involute_near_zero_and_above_60_deg():
    from tmm_cli.gears import ainv, inv as tinv
    # near 0: a = u - 2 u^3/15 + O(u^5), u = (3 v)^(1/3)
    for v in (1e-30, 1e-18, 1e-12, 1e-9):
        u = (3 * v) ** (1 / 3)
        assert ainv(v) == pytest.approx(u - 2 * u**3 / 15, rel=1e-12)
    assert ainv(0.0) == 0.0
    # exact values: inv 60 deg = sqrt(3) - pi/3, inv 45 deg = 1 - pi/4
    assert ainv(math.sqrt(3) - math.pi / 3) == pytest.approx(math.pi / 3, rel=1e-14)
    assert ainv(1 - math.pi / 4) == pytest.approx(math.pi / 4, rel=1e-14)
    for deg in (60.0, 70.0, 80.0, 85.0, 89.0, 89.9):
        a = math.radians(deg)
        assert ainv(math.tan(a) - a) == pytest.approx(a, rel=1e-13)
        assert tinv(a) == pytest.approx(math.tan(a) - a, rel=1e-14)
    for deg in (1e-6, 1e-3, 0.5, 2.0, 20.0):
        a = math.radians(deg)
        assert ainv(tinv(a)) == pytest.approx(a, rel=1e-12)


# =========================================================================== planetary
def planet_ok(scheme, z, k, req, tol):
    """Own check of one set (Popov & Timofeev conditions, exact fractions)."""
    if scheme == "A":
        i = 1 + Fraction(z["z3"], z["z1"])
        coax = z["z1"] + 2 * z["z2"] == z["z3"]
        aw, sats = Fraction(z["z1"] + z["z2"], 2), [z["z2"]]
        limits = z["z1"] >= 17 and z["z2"] >= 20 and z["z3"] >= 85 and z["z3"] - z["z2"] >= 8
    elif scheme == "B":
        i = 1 + Fraction(z["z2"] * z["z4"], z["z1"] * z["z3"])
        coax = z["z1"] + z["z2"] == z["z4"] - z["z3"]
        aw, sats = Fraction(z["z1"] + z["z2"], 2), [z["z2"], z["z3"]]
        limits = (min(z["z1"], z["z2"]) >= 17 and z["z3"] >= 20 and z["z4"] >= 85
                  and z["z4"] - z["z3"] >= 8)
    else:
        raise AssertionError(scheme)
    ratio = abs(float(i) - req) <= tol * abs(req) * (1 + 1e-12)
    q = i * z["z1"] / k
    assembly = any((q * (1 + k * p)).denominator == 1 for p in range(0, k * q.denominator + 1))
    adjacency = k == 1 or 2 * float(aw) * math.sin(math.pi / k) > max(sats) + 2
    return ratio and coax and assembly and adjacency and limits, float(i)


@pytest.mark.parametrize("scheme,ratio,k,tol", [
    ("A", 3.24, 3, 1e-6), ("A", 4.0, 1, 0.05), ("A", 2.5, 8, 0.05), ("A", 9.0, 3, 0.05),
    ("B", 10.0, 1, 0.05), ("B", 25.0, 3, 0.05), ("B", 3.24, 3, 1e-6), ("B", 20.0, 2, 0.05),
])
def test_planetary_every_returned_set_satisfies_its_conditions(scheme, ratio, k, tol):
    p = run_ok({"schema": "tmm/1", "planetary": {"scheme": scheme, "ratio": ratio, "satellites": k,
                                                 "tolerance": tol}})["planetary"]
    ok, i = planet_ok(scheme, p["z"], k, ratio, tol)
    assert ok
    assert p["ratio"] == pytest.approx(i, rel=1e-15)
    assert p["ratio_error"] == pytest.approx((i - ratio) / ratio, rel=1e-12, abs=1e-15)
    for cand in p["candidates"]:
        assert planet_ok(scheme, cand["z"], k, ratio, tol)[0]


@pytest.mark.parametrize("spec,words", [
    ({"scheme": "A", "ratio": 100}, "scheme A gives 1 + z3/z1 only between"),
    ({"scheme": "A", "ratio": 1e6}, "scheme A gives 1 + z3/z1 only between"),
    ({"scheme": "A", "ratio": 0.5}, "i_1H > 1 only"),
    ({"scheme": "B", "ratio": -3}, "i_1H > 1 only"),
    ({"scheme": "B", "ratio": 1e6}, "no tooth numbers"),
    ({"scheme": "C", "ratio": 3.24, "tolerance": 1e-9}, "no tooth numbers"),
    ({"scheme": "A", "ratio": 3.24, "z_max": 60}, "needs z >= 85"),
    ({"scheme": "A", "ratio": 4, "satellites": 8}, "fewer satellites"),
])
def test_planetary_impossible_requests_are_clear_stage_errors(spec, words):
    err = stage_error({"schema": "tmm/1", "planetary": spec}, "planetary")
    assert words in err.message


def test_planetary_scheme_A_eight_satellites_at_ratio_4_is_truly_impossible():
    # i = 4 in scheme A means z3 = 3 z1 and z2 = z1: adjacency needs
    # (z1 + z2) sin(pi/8) > z2 + 2, i.e. 0.765 z1 > z1 + 2 -- never.
    assert all(2 * z1 * math.sin(math.pi / 8) <= z1 + 2 for z1 in range(17, 151))
