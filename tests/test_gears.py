"""Gears stage: formulas against hand calculations (GOST 16532-70 as in Popov & Timofeev,
"Курсовое проектирование по ТММ", 2002, and Frolov (ed.), "Теория механизмов и машин"),
the published worked example of the course material and property checks.

The hand calculations below are written out step by step with the textbook formulas and
do not call the package (the mesh angle is found by bisection on the involute, not by
the package's Newton solver).
"""
import json
import math

import numpy as np
import pytest
from pydantic import ValidationError
from hypothesis import given, settings
from hypothesis import strategies as st

from tmm_cli.errors import StageError
from tmm_cli.gears import ainv, analyze, inv
from tmm_cli.gears.geometry import pair, x_min_course, z_min_course
from task_sections import gears  # noqa: E402  (sections through the task model)

RAD = math.pi / 180


def inv_hand(a):
    return math.tan(a) - a


def ainv_bisect(v):
    lo, hi = 0.0, math.pi / 2 - 1e-9
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if inv_hand(mid) < v:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def rel(a, b):
    return abs(a - b) / max(abs(b), 1e-300)


# ---------------------------------------------------------------- inverse involute
def test_inverse_involute_grid_1_to_60_deg():
    a = np.linspace(1, 60, 5901) * RAD
    back = ainv(inv(a))
    assert np.max(np.abs(back - a)) < 1e-12


@given(st.floats(min_value=1.0, max_value=60.0))
@settings(max_examples=300, deadline=None)
def test_inverse_involute_property(a_deg):
    a = a_deg * RAD
    v = math.tan(a) - a
    assert abs(ainv(v) - a) < 1e-12
    assert abs(inv(ainv(v)) - v) <= 1e-13 * max(v, 1e-3)


def test_involute_table_values():
    # textbook tables (Popov & Timofeev, appendix): inv 20 = 0.014904, inv 25 = 0.029975
    assert inv(20 * RAD) == pytest.approx(0.014904, abs=5e-7)
    assert inv(25 * RAD) == pytest.approx(0.029975, abs=5e-7)
    assert ainv(0.0) == 0.0
    assert ainv(0.014904) / RAD == pytest.approx(20.0, abs=1e-3)
    with pytest.raises(ValueError):
        ainv(-1e-3)


def test_involute_small_angle_series_continuity():
    a = np.array([0.049999999, 0.05, 0.050000001])
    direct = np.tan(a) - a
    assert np.allclose(inv(a), direct, rtol=1e-9)


# ------------------------------------------------- zero-shift pair, published example
def test_course_project_engine_gears_z20_z15_m9_zero_shift():
    """reference/course-project-engine-cam-gears.txt, section 5: z1 = 20, z2 = 15, m = 9 mm,
    x = 0: rw = r, aw = a = 90 + 67.5 = 157.5 mm, h = 2.25 m = 20.25 mm, eps_alpha = 1.52."""
    r = analyze(gears(m=0.009, z=(20, 15), x=(0.0, 0.0), alpha=20, ha=1, c=0.25)).to_dict()
    assert r["aw"] == pytest.approx(0.1575, rel=1e-12)
    assert r["alpha_w"] == pytest.approx(20.0, rel=1e-12)
    assert r["rw"] == pytest.approx([0.090, 0.0675], rel=1e-12)
    assert r["r"] == pytest.approx([0.090, 0.0675], rel=1e-12)
    assert r["h"] == pytest.approx(0.02025, rel=1e-12)
    assert r["y"] == pytest.approx(0.0, abs=1e-12) and r["dy"] == pytest.approx(0.0, abs=1e-12)
    assert round(r["eps_alpha"], 2) == 1.52
    # hand formulas
    m, a = 9e-3, 20 * RAD
    assert r["rb"] == pytest.approx([0.090 * math.cos(a), 0.0675 * math.cos(a)], rel=1e-12)
    assert r["ra"] == pytest.approx([0.090 + m, 0.0675 + m], rel=1e-12)
    assert r["rf"] == pytest.approx([0.090 - 1.25 * m, 0.0675 - 1.25 * m], rel=1e-12)
    assert r["s"] == pytest.approx([math.pi * m / 2] * 2, rel=1e-12)
    assert r["p"] == pytest.approx(math.pi * m, rel=1e-12)
    # tip thickness of wheel 1: sa = da (s/d + inv a - inv aa), cos aa1 = rb1/ra1
    aa1 = math.acos(0.090 * math.cos(a) / 0.099)
    sa1 = 2 * 0.099 * (math.pi * m / 2 / 0.180 + inv_hand(a) - inv_hand(aa1))
    assert r["sa"][0] == pytest.approx(sa1, rel=1e-12)
    # z2 = 15 < 17: undercut of wheel 2, x_min2 = (17 - 15)/17
    assert r["checks"]["undercut"] == [False, True]
    assert r["x_min"] == pytest.approx([(17 - 20) / 17, (17 - 15) / 17], rel=1e-12)


def test_zero_shift_small_pinion_verdicts():
    """z1 = 12 with x = 0 (ha* = 1, 20 deg): undercut (x_min = 5/17) and the tip of the
    wheel 2 reaches beyond the tangency point N1 (N2B1 > N1N2): interference."""
    m, a = 0.003, 20 * RAD
    r = analyze(gears(m=m, z=(12, 30), x=(0.0, 0.0), alpha=20, ha=1, c=0.25)).to_dict()
    aw = m * 42 / 2
    g = aw * math.sin(a)                                   # N1N2
    rb2, ra2 = m * 15 * math.cos(a), m * 15 + m
    n2b1 = math.sqrt(ra2 ** 2 - rb2 ** 2)
    assert n2b1 > g                                          # B1 beyond N1 (hand check)
    assert r["line_of_action"]["N1N2"] == pytest.approx(g, rel=1e-12)
    assert r["line_of_action"]["N1B1"] == pytest.approx(g - n2b1, rel=1e-12)
    assert r["checks"]["undercut"] == [True, False]
    assert r["checks"]["interference"] is True
    assert r["checks"]["sharpening"] == [False, False]
    assert r["checks"]["contact_ratio_low"] is False
    assert r["x_min"][0] == pytest.approx(5 / 17, rel=1e-12)
    assert any("undercut" in w for w in r["warnings"])
    assert any("interference" in w for w in r["warnings"])
    assert len(r["warnings"]) == 3 and any("by the formula is formal" in w for w in r["warnings"])
    assert r["eps_alpha_formal"] is True      # interference: part of B1B2 is off the involutes


# ------------------------------------------------------ shifted pair (SPEC example)
def hand_shifted(m, z1, z2, x1, x2, alpha=20.0, ha=1.0, c=0.25):
    """GOST 16532-70, written out."""
    a = alpha * RAD
    inv_aw = inv_hand(a) + 2 * (x1 + x2) * math.tan(a) / (z1 + z2)
    aw_ang = ainv_bisect(inv_aw)
    a0 = m * (z1 + z2) / 2
    aw = a0 * math.cos(a) / math.cos(aw_ang)
    y = (aw - a0) / m
    dy = x1 + x2 - y
    out = dict(inv_aw=inv_aw, alpha_w=aw_ang / RAD, aw=aw, y=y, dy=dy, r=[], rb=[], rw=[], ra=[], rf=[],
               s=[], e=[], sa=[], sb=[], aa=[])
    for z, x in ((z1, x1), (z2, x2)):
        r = m * z / 2
        rb = r * math.cos(a)
        ra = r + (ha + x - dy) * m
        s = m * (math.pi / 2 + 2 * x * math.tan(a))
        aa = math.acos(rb / ra)
        out["r"].append(r)
        out["rb"].append(rb)
        out["rw"].append(rb / math.cos(aw_ang))
        out["ra"].append(ra)
        out["rf"].append(r - (ha + c - x) * m)
        out["s"].append(s)
        out["e"].append(math.pi * m - s)
        out["sa"].append(2 * ra * (s / (2 * r) + inv_hand(a) - inv_hand(aa)))
        out["sb"].append(2 * rb * (s / (2 * r) + inv_hand(a)))
        out["aa"].append(aa)
    out["eps"] = (z1 * (math.tan(out["aa"][0]) - math.tan(aw_ang))
                  + z2 * (math.tan(out["aa"][1]) - math.tan(aw_ang))) / (2 * math.pi)
    out["h"] = (2 * ha + c - dy) * m
    return out


def test_shifted_pair_spec_example_hand_calculation():
    """SPEC example: m = 3 mm, z = [12, 42], x = [0.63, 0.67] (high shifts).

    By hand with tables: inv aw = 0.014904 + 2 * 1.3 * 0.36397 / 54 = 0.032429,
    aw = 25.63 deg, a = 81 mm, aw = 81 cos 20 / cos 25.63 = 84.42 mm, y = 1.140,
    dy = 0.160, ra1 = 18 + 3 (1 + 0.63 - 0.160) = 22.41 mm, rf1 = 18 - 3 (1.25 - 0.63)
    = 16.14 mm, s1 = 3 (pi/2 + 2 * 0.63 * 0.36397) = 6.088 mm."""
    spec = gears(m=0.003, z=(12, 42), x=(0.63, 0.67), alpha=20, ha=1, c=0.25)
    r = analyze(spec).to_dict()
    h = hand_shifted(0.003, 12, 42, 0.63, 0.67)
    # rounded table values, by hand
    assert r["inv_alpha_w"] == pytest.approx(0.032429, abs=2e-6)
    assert r["alpha_w"] == pytest.approx(25.63, abs=0.01)
    assert r["aw"] * 1e3 == pytest.approx(84.42, abs=0.01)
    assert r["y"] == pytest.approx(1.140, abs=1e-3)
    assert r["dy"] == pytest.approx(0.160, abs=1e-3)
    assert r["ra"][0] * 1e3 == pytest.approx(22.41, abs=0.01)
    assert r["rf"][0] * 1e3 == pytest.approx(16.14, abs=1e-9)
    assert r["s"][0] * 1e3 == pytest.approx(6.088, abs=1e-3)
    # full precision against the written-out formulas
    tol = 1e-9
    for key, hk in (("aw", "aw"), ("alpha_w", "alpha_w"), ("y", "y"), ("dy", "dy"),
                    ("inv_alpha_w", "inv_aw"), ("eps_alpha", "eps"), ("h", "h")):
        assert rel(r[key], h[hk]) < tol, key
    for key in ("r", "rb", "rw", "ra", "rf", "s", "e", "sa", "sb"):
        for i in range(2):
            assert rel(r[key][i], h[key][i]) < tol, (key, i)
    # x_min = (17 - z)/17 (METHODS 6)
    assert r["x_min"] == pytest.approx([5 / 17, -25 / 17], rel=1e-12)
    assert r["checks"] == {"undercut": [False, False], "sharpening": [False, False],
                           "contact_ratio_low": False, "interference": False}
    assert r["warnings"] == []
    # pitch circles roll: rw1 + rw2 = aw, rw2/rw1 = z2/z1
    assert r["rw"][0] + r["rw"][1] == pytest.approx(r["aw"], rel=1e-13)
    assert r["rw"][1] / r["rw"][0] == pytest.approx(42 / 12, rel=1e-13)
    # zero backlash on the pitch circles: sw1 + sw2 = pw
    pw = 2 * math.pi * r["rw"][0] / 12
    assert r["sw"][0] + r["sw"][1] == pytest.approx(pw, rel=1e-12)
    # radial clearance at aw is c* m - dy... GOST: aw - ra1 - rf2 = c m
    assert r["aw"] - r["ra"][0] - r["rf"][1] == pytest.approx(0.25 * 0.003, rel=1e-9)


def test_line_of_action_and_contact_ratio_agree():
    r = analyze(gears(m=0.003, z=(12, 42), x=(0.63, 0.67))).to_dict()
    la = r["line_of_action"]
    aw, awa = r["aw"], r["alpha_w"] * RAD
    assert la["N1N2"] == pytest.approx(aw * math.sin(awa), rel=1e-12)
    # B1B2 from the tip circles: sqrt(ra^2 - rb^2) on each side
    n1b2 = math.sqrt(r["ra"][0] ** 2 - r["rb"][0] ** 2)
    n2b1 = math.sqrt(r["ra"][1] ** 2 - r["rb"][1] ** 2)
    ga = n1b2 + n2b1 - la["N1N2"]
    assert la["B1B2"] == pytest.approx(ga, rel=1e-12)
    assert r["eps_alpha"] == pytest.approx(ga / (math.pi * 0.003 * math.cos(20 * RAD)), rel=1e-12)
    assert la["N1P"] == pytest.approx(r["rb"][0] * math.tan(awa), rel=1e-12)
    # lowest active points: radius from the curvature radius
    rp1 = math.hypot(r["rb"][0], la["N1N2"] - n2b1)
    assert r["lowest_active"]["r_p"][0] == pytest.approx(rp1, rel=1e-12)


def test_specific_sliding_identities():
    z1, z2 = 12, 42
    r = analyze(gears(m=0.003, z=(z1, z2), x=(0.63, 0.67))).to_dict()
    sl = r["sliding"]
    g = r["line_of_action"]["N1N2"]
    X = np.array(sl["X"])
    for Xi, l1, l2 in zip(X, sl["lambda1"], sl["lambda2"]):
        if Xi == 0:
            assert l1 is None                             # infinite at N1
            continue
        if Xi == g:
            assert l2 is None
            assert l1 == pytest.approx(1.0)
            continue
        # by hand: rho1 = X, rho2 = g - X, u21 = z1/z2
        assert l1 == pytest.approx(1 - (g - Xi) * z1 / (Xi * z2), rel=1e-12, abs=1e-12)
        assert l2 == pytest.approx(1 - Xi * z2 / ((g - Xi) * z1), rel=1e-12, abs=1e-12)
        assert (1 - l1) * (1 - l2) == pytest.approx(1.0, rel=1e-9)
    # zero sliding at the pole
    iP = list(X).index(sl["marks"]["P"])
    assert sl["lambda1"][iP] == pytest.approx(0.0, abs=1e-12)
    assert sl["lambda2"][iP] == pytest.approx(0.0, abs=1e-12)


def test_checks_sharpening_and_contact_ratio():
    # z1 = 10, x1 = 1.0: pointed tip by hand (sa1 < 0.25 m)
    m = 0.003
    h = hand_shifted(m, 10, 40, 1.0, 0.0)
    r = analyze(gears(m=m, z=(10, 40), x=(1.0, 0.0))).to_dict()
    assert (h["sa"][0] < 0.25 * m) is True
    assert r["checks"]["sharpening"] == [True, False]
    assert any("tip is too thin" in w for w in r["warnings"])
    # large shifts on both wheels: eps below 1.2 by hand
    h = hand_shifted(m, 20, 20, 1.0, 1.0)
    r = analyze(gears(m=m, z=(20, 20), x=(1.0, 1.0))).to_dict()
    assert h["eps"] < 1.2
    assert r["checks"]["contact_ratio_low"] is True
    assert r["eps_alpha"] == pytest.approx(h["eps"], rel=1e-10)
    assert any("contact ratio" in w for w in r["warnings"])


def test_sharpening_limit_option():
    r = analyze(gears(m=0.003, z=(12, 42), x=(0.63, 0.67), sa_min=0.5)).to_dict()
    # sa1 = 0.454 m by hand (see the SPEC example): defect for a 0.5 m limit only
    assert 0.25 < r["sa"][0] / 0.003 < 0.5
    assert r["checks"]["sharpening"] == [True, False]


def test_z_min_and_x_min_generalised():
    assert z_min_course(20 * RAD, 1.0) == 17
    assert z_min_course(20 * RAD, 0.8) == 14                       # short teeth (textbook)
    assert z_min_course(15 * RAD, 1.0) == 30
    assert x_min_course(12, 20 * RAD, 1.0) == pytest.approx(5 / 17)
    # the exact limit: straight edge of the rack ends at ha m above the datum
    g = pair(0.003, 17, 40, 0.0, 0.0)
    assert g["x_min_exact1"] == pytest.approx(1 - 17 * math.sin(20 * RAD) ** 2 / 2, rel=1e-12)
    # a property of the wheel's number of teeth, not of the shift it is given (it read x_min - x:
    # z = 12 with x = 0.5 gave -0.20187 for 1 - 12 sin^2 20 / 2 = 0.29813; z = 200, x = 2 gave
    # -12.698 for -10.698)
    for z, x in ((12, 0.5), (12, -0.3), (200, 2.0), (40, 0.1)):
        g = pair(0.002, z, 40, x, 0.0)
        assert g["x_min_exact1"] == pytest.approx(1 - z * math.sin(20 * RAD) ** 2 / 2, rel=1e-12), (z, x)
    assert round(pair(0.002, 12, 40, 0.5, 0.0)["x_min_exact1"], 5) == 0.29813
    # with a fillet radius of its own (0.2 module) the straight edge ends at (ha + c) - rho_f (1 - sin a)
    g = pair(0.002, 12, 40, 0.5, 0.0, rho_f=0.2)
    h_l0 = (1.0 + 0.25) - 0.2 * (1 - math.sin(20 * RAD))            # modules above the datum
    assert g["x_min_exact1"] == pytest.approx(h_l0 - 12 * math.sin(20 * RAD) ** 2 / 2, rel=1e-12)


def test_results_are_json_and_have_spec_keys():
    d = analyze(gears(m=0.003, z=(12, 42), x=(0.63, 0.67))).to_dict()
    json.dumps(d, allow_nan=False)
    for k in ("aw", "alpha_w", "y", "dy", "r", "rb", "rw", "ra", "rf", "s", "sa", "eps_alpha",
              "x_min", "checks"):
        assert k in d
    assert set(d["checks"]) == {"undercut", "sharpening", "contact_ratio_low", "interference"}


def test_invalid_inputs_raise_stage_error():
    with pytest.raises(StageError):
        analyze(gears(m=0.003, z=(12, 14), x=(-3.0, -3.0)))           # inv aw < 0
    with pytest.raises(ValidationError):                  # x neither two numbers nor auto: the task model's
        gears(m=0.003, z=(12, 42), x="sometimes")


# ------------------------------------------------------------------ x: auto rules
def _lambda_max(d):
    z1, z2 = d["z"]
    g = d["line_of_action"]["N1N2"]
    X1, X2 = d["line_of_action"]["N1B1"], d["line_of_action"]["N1B2"]
    return 1 - (g - X1) * z1 / (X1 * z2), 1 - X2 * z2 / ((g - X2) * z1)


@pytest.mark.parametrize("z", [(12, 42), (14, 28), (20, 40), (25, 60)])
def test_auto_equal_sliding(z):
    d = analyze(gears(m=0.002, z=z, x="auto", rule="equal_sliding")).to_dict()
    l1, l2 = _lambda_max(d)
    assert l1 == pytest.approx(l2, rel=1e-7)
    xs = max(0, (17 - z[0]) / 17) + max(0, (17 - z[1]) / 17)
    assert sum(d["x"]) == pytest.approx(xs, abs=1e-9)
    assert not any(d["checks"]["undercut"]) and not any(d["checks"]["sharpening"])
    assert not d["checks"]["contact_ratio_low"] and not d["checks"]["interference"]
    assert d["blocking_contour"]["chosen_admissible"] is True


def test_auto_no_undercut():
    d = analyze(gears(m=0.002, z=(12, 42), x="auto", rule="no_undercut")).to_dict()
    assert d["x"] == pytest.approx([5 / 17, 0.0], abs=1e-12)
    assert d["checks"]["undercut"] == [False, False]


def test_auto_moves_into_contour_when_rule_fails():
    m = 0.002
    # table rule for z = (8, 60): x = (max(0.5, 9/17), 0.5); by hand sa1 < 0.25 m there
    h = hand_shifted(m, 8, 60, 9 / 17, 0.5)
    assert h["sa"][0] < 0.25 * m
    d = analyze(gears(m=m, z=(8, 60), x="auto", rule="table")).to_dict()
    assert "outside the blocking contour" in d["warnings"][0]
    x1, x2 = d["x"]
    h = hand_shifted(m, 8, 60, x1, x2)                       # the new point, checked by hand
    assert h["sa"][0] >= 0.25 * m and h["sa"][1] >= 0.25 * m and h["eps"] >= 1.2
    assert x1 >= (17 - 8) / 17 and x2 >= (17 - 60) / 17
    assert math.hypot(x1 - 9 / 17, x2 - 0.5) < 0.15
    assert d["blocking_contour"]["chosen_admissible"] is True
    # z = (10, 12): no admissible shifts at all (undercut limits force eps < 1.2)
    d = analyze(gears(m=m, z=(10, 12), x="auto", rule="table")).to_dict()
    assert "no shifts satisfy every check" in d["warnings"][0]
    assert d["checks"]["contact_ratio_low"] is True


def test_blocking_contour_lines_lie_on_their_limits():
    m, z1, z2 = 0.003, 12, 42
    d = analyze(gears(m=m, z=(z1, z2), x=(0.63, 0.67))).to_dict()
    lines = d["blocking_contour"]["lines"]
    for seg in lines["undercut_1"]:
        for x1, _ in seg:
            assert x1 == pytest.approx(5 / 17, abs=1e-9)             # straight line x1 = x_min1
    n = 0
    for seg in lines["contact_ratio"]:
        for x1, x2 in seg[:: max(1, len(seg) // 10)]:
            h = hand_shifted(m, z1, z2, x1, x2)
            assert h["eps"] == pytest.approx(1.2, abs=2e-3)             # grid interpolation
            n += 1
    for seg in lines["sharpening_1"]:
        for x1, x2 in seg[:: max(1, len(seg) // 10)]:
            h = hand_shifted(m, z1, z2, x1, x2)
            assert h["sa"][0] / m == pytest.approx(0.25, abs=2e-3)
            n += 1
    assert n > 5
    # the chosen SPEC point is admissible and close to the eps = 1.2 line
    assert d["blocking_contour"]["chosen_admissible"] is True


def test_a_pair_that_cannot_mesh_shows_its_contact_ratio_as_formal():
    """m = 9 mm, z = 20 and 15, x = +3 and -3: neither wheel has an involute flank (the second's
    tip circle inside its base circle), so the GOST contact ratio is a formal number; the run's
    summary says so beside it (it printed 1.4879 as if the pair meshed). A pair that meshes
    shows its contact ratio alone."""
    import tmm_cli
    from tmm_cli.summary import _summary_rows
    r = tmm_cli.run(tmm_cli.load_task({"schema": "tmm/1", "gears": {"m": "9 mm", "z": [20, 15], "x": [3, -3]}}))
    row = dict(_summary_rows(r))["contact ratio"]
    assert row.endswith(" (formal: the pair cannot mesh, see the warnings)"), row
    assert float(row.split()[0]) == pytest.approx(r["gears"]["eps_alpha"], rel=1e-4)
    ok = tmm_cli.run(tmm_cli.load_task({"schema": "tmm/1", "gears": {"m": "4 mm", "z": [20, 40]}}))
    assert dict(_summary_rows(ok))["contact ratio"] == f"{ok['gears']['eps_alpha']:.5g}"



def test_a_contact_ratio_with_interference_is_formal():
    """z = 5/8, x = 0 (m = 4 mm): the active line B1B2 = 14.67 mm by the formula is longer than
    the whole line of action N1N2 = 8.89 mm (N1B1 < 0): no real contact is that long, so the
    eps_alpha = 1.24 of the formula is formal (it was printed "eps < 1.2: no" with no word); a
    pair without interference keeps it plain."""
    from tmm_cli import load_task, run
    res = run(load_task({"schema": "tmm/1", "gears": {"m": 0.004, "z": [5, 8], "x": [0, 0]}}))
    r, la = res["gears"], res["gears"]["line_of_action"]
    assert la["B1B2"] > la["N1N2"] and la["N1B1"] < 0
    assert r["eps_alpha_formal"] is True and r["checks"]["interference"] is True
    assert any("by the formula is formal" in str(w) for w in res["warnings"])
    res = run(load_task({"schema": "tmm/1", "gears": {"m": 0.004, "z": [20, 40], "x": [0, 0]}}))
    assert res["gears"]["eps_alpha_formal"] is False and not any("formal" in str(w) for w in res.get("warnings", []))


def test_a_tooth_pointed_below_its_tip_makes_the_contact_ratio_formal():
    """z = [200, 5], x = [-1, 1], m = 3 mm: wheel 2's tooth is pointed (s_a < 0) below its tip
    circle. Its flanks meet where the half angle psi0 - inv(alpha_y) is 0, psi0 = s/(2r) + inv 20:
    the involute function inverted by bisection here; cut there, the tip meshes only up to it and the
    contact ratio is the formula's with that radius for r_a2 (0.854 where the formula gives 1.01)."""
    m, a = 0.003, 20 * RAD
    g = pair(m, 200, 5, -1.0, 1.0)
    assert g["sa2"] < 0
    r2 = m * 5 / 2
    rb2 = r2 * math.cos(a)
    s2 = m * (math.pi / 2 + 2 * 1.0 * math.tan(a))
    psi0 = s2 / (2 * r2) + math.tan(a) - a
    lo, hi = 0.0, math.pi / 2 - 1e-9
    for _ in range(200):                                  # inv(ap) = tan ap - ap = psi0
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if math.tan(mid) - mid < psi0 else (lo, mid)
    ap = (lo + hi) / 2
    r_point = rb2 / math.cos(ap)
    from tmm_cli.gears.geometry import pointed_tips
    cut = pointed_tips(g, 200, 5)
    assert cut["r_point2"] == pytest.approx(r_point, rel=1e-12) and round(r_point * 1e3, 2) == 12.34
    aw = g["alpha_w"]
    aa1 = math.acos(g["rb1"] / g["ra1"])
    aa2 = math.acos(rb2 / r_point)
    eps = (200 * (math.tan(aa1) - math.tan(aw)) + 5 * (math.tan(aa2) - math.tan(aw))) / (2 * math.pi)
    assert cut["eps_cut"] == pytest.approx(eps, rel=1e-12) and round(eps, 3) == 0.854
    d = analyze(gears(m=0.003, z=(200, 5), x=(-1.0, 1.0))).to_dict()
    assert d["eps_alpha_formal"] is True and d["checks"]["interference"] is False
    assert any(w.startswith("eps_alpha = 1.01 by the formula is formal: the tooth of wheel 2 comes to a point at "
                            "r = 12.34 mm") for w in d["warnings"])
    # a tooth that is not pointed: eps as the formula gives it, nothing formal
    g = pair(m, 20, 40, 0.0, 0.0)
    assert pointed_tips(g, 20, 40)["eps_cut"] == pytest.approx(g["eps"], rel=1e-12)
    assert analyze(gears(m=0.003, z=(20, 40), x=(0.0, 0.0))).to_dict()["eps_alpha_formal"] is False
