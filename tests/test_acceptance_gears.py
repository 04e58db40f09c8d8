"""Acceptance tests of the `gears` and `planetary` stages, written as an outsider would:
from SPEC.md, METHODS.md (section 6) and the README's documented choices only, through the
public API (`tmm_cli.load_task(dict)`, `tmm_cli.run`).

Expected values come from the GOST 16532-70 formulas written out below (own Newton solver
for the inverse involute, started from the Cheng approximation), nothing is imported from
tmm_cli:

    inv a_w = inv a + 2 (x1 + x2) tan a / (z1 + z2)
    a_w = m (z1 + z2)/2 * cos a / cos a_w,   y = (a_w - a)/m,   dy = x1 + x2 - y
    r = m z/2, r_b = r cos a, r_w = r cos a / cos a_w
    r_a = r + m (ha + x - dy),   r_f = r - m (ha + c - x)
    s = m (pi/2 + 2 x tan a),    s_a = 2 r_a (s/(2 r) + inv a - inv a_a),  cos a_a = r_b/r_a
    eps = (sqrt(ra1^2 - rb1^2) + sqrt(ra2^2 - rb2^2) - a_w sin a_w) / (pi m cos a)
    x_min = ha (17 - z)/17  (z_min = 17 rounded, METHODS 6 / README)

Verdicts (true = defect present, SPEC 3): undercut x < x_min; sharpening s_a < 0.25 m;
contact_ratio_low eps < 1.2; interference: the lowest point of the active profile of a wheel
(where the mating tip circle meets the line of action) lies below the start of its true
involute, rho_p = a_w sin a_w - sqrt(ra_o^2 - rb_o^2) < rho_l = r sin a - (ha - x) m / sin a
(GOST 16532 d_p >= d_l; the rack's straight flank ends at ha*m with the default fillet), and
always when rho_p < 0 (active point below the base circle).

Planetary: tooth numbers returned by the tool are checked with own code against Willis'
formula of each scheme of the README list, coaxiality, the README assembly condition
(i z1/k)(1 + k p) whole (exact fractions), adjacency (centre distance * 2 sin(pi/k) >
largest satellite tip diameter, ha = 1) and the README undercut limits; ratio_error is
(ratio - required)/required (SPEC 3).
"""
from __future__ import annotations

import copy
import itertools
import math
from fractions import Fraction

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import tmm_cli

RTOL = 1e-6


def run(task):
    return tmm_cli.run(tmm_cli.load_task(copy.deepcopy(task)))


# --------------------------------------------------------------------------------------
# independent GOST 16532 calculation
# --------------------------------------------------------------------------------------
def inv(a):
    return math.tan(a) - a


def inv_inverse(v):
    """Newton on tan(a) - a = v, started from Cheng's approximation."""
    a = (3.0 * v) ** (1 / 3) if v > 0 else 0.0
    a = min(a, 1.5)
    for _ in range(100):
        f = math.tan(a) - a - v
        d = math.tan(a) ** 2
        if d == 0.0:
            break
        step = f / d
        a -= step
        if abs(step) < 1e-16:
            break
    assert abs(inv(a) - v) < 1e-15
    return a


def gost(m, z, x, alpha_deg=20.0, ha=1.0, c=0.25):
    al = math.radians(alpha_deg)
    z1, z2 = z
    x1, x2 = x
    inv_w = inv(al) + 2 * (x1 + x2) * math.tan(al) / (z1 + z2)
    aw_ = inv_inverse(inv_w)
    a = m * (z1 + z2) / 2
    aw = a * math.cos(al) / math.cos(aw_)
    y = (aw - a) / m
    dy = x1 + x2 - y
    r = [m * zi / 2 for zi in z]
    rb = [ri * math.cos(al) for ri in r]
    rw = [ri * math.cos(al) / math.cos(aw_) for ri in r]
    ra = [ri + m * (ha + xi - dy) for ri, xi in zip(r, x)]
    rf = [ri - m * (ha + c - xi) for ri, xi in zip(r, x)]
    s = [m * (math.pi / 2 + 2 * xi * math.tan(al)) for xi in x]
    aa = [math.acos(rbi / rai) for rbi, rai in zip(rb, ra)]
    sa = [2 * rai * (si / (2 * ri) + inv(al) - inv(aai)) for rai, si, ri, aai in zip(ra, s, r, aa)]
    ga = [math.sqrt(rai**2 - rbi**2) for rai, rbi in zip(ra, rb)]
    eps = (ga[0] + ga[1] - aw * math.sin(aw_)) / (math.pi * m * math.cos(al))
    zmin = round(2 * ha / math.sin(al) ** 2)
    x_min = [ha * (zmin - zi) / zmin for zi in z]
    # lowest active point of each profile vs the start of its involute (both measured
    # along the line of action from the tangency point N_i with the base circle)
    rho_p = [aw * math.sin(aw_) - ga[1], aw * math.sin(aw_) - ga[0]]
    rho_l = [ri * math.sin(al) - (ha - xi) * m / math.sin(al) for ri, xi in zip(r, x)]
    return dict(
        aw=aw, alpha_w=math.degrees(aw_), y=y, dy=dy, r=r, rb=rb, rw=rw, ra=ra, rf=rf, s=s,
        sa=sa, eps_alpha=eps, x_min=x_min, rho_p=rho_p, rho_l=rho_l,
        undercut=[xi < xm for xi, xm in zip(x, x_min)],
        sharpening=[sai < 0.25 * m for sai in sa],
        contact_ratio_low=eps < 1.2,
    )


GEOM_KEYS = ["aw", "alpha_w", "y", "dy", "eps_alpha"]
PAIR_KEYS = ["r", "rb", "rw", "ra", "rf", "s", "sa", "x_min"]


def close(got, exp, what, scale=1.0):
    assert got is not None, f"{what}: null, expected {exp}"
    # absolute floor for quantities that are zero for a zero-shift pair (y, dy)
    assert abs(got - exp) <= RTOL * abs(exp) + 1e-12 * scale, f"{what}: got {got!r}, expected {exp!r}"


def check_geometry(g, e, m):
    for k in GEOM_KEYS:
        close(g[k], e[k], k, scale=1.0)
    for k in PAIR_KEYS:
        assert len(g[k]) == 2, k
        for i in range(2):
            close(g[k][i], e[k][i], f"{k}[{i}]", scale=m)


def gear_task(m, z, x, **extra):
    return {"schema": "tmm/1", "gears": {"m": m, "z": list(z), "x": list(x), **extra}}


# --------------------------------------------------------------------------------------
# the self-check of the reference (the formulas above against hand arithmetic)
# --------------------------------------------------------------------------------------
def test_reference_zero_shift_hand_numbers():
    """z = 12/30, m = 5 mm, x = 0: a_w = a = 105 mm, r_a = 35/80 mm, r_f = 23.75/68.75 mm,
    s = pi m/2; the tip of wheel 2 reaches beyond N1 (rho_p1 < 0)."""
    e = gost(0.005, [12, 30], [0.0, 0.0])
    assert e["alpha_w"] == pytest.approx(20.0, abs=1e-12)
    assert e["aw"] == pytest.approx(0.105, rel=1e-14)
    assert e["ra"] == pytest.approx([0.035, 0.080], rel=1e-14)
    assert e["rf"] == pytest.approx([0.02375, 0.06875], rel=1e-14)
    assert e["s"][0] == pytest.approx(math.pi * 0.005 / 2, rel=1e-14)
    # eps by hand: (sqrt(35^2-(30cos20)^2) + sqrt(80^2-(75cos20)^2) - 105 sin20)/(5 pi cos20)
    c20, s20 = math.cos(math.radians(20)), math.sin(math.radians(20))
    eps = (math.sqrt(35**2 - (30 * c20) ** 2) + math.sqrt(80**2 - (75 * c20) ** 2) - 105 * s20) / (5 * math.pi * c20)
    assert e["eps_alpha"] == pytest.approx(eps, rel=1e-13)
    assert e["rho_p"][0] < 0


# --------------------------------------------------------------------------------------
# the pairs
# --------------------------------------------------------------------------------------
def test_zero_shift_small_pinion():
    m = 0.005
    res = run(gear_task("5 mm", [12, 30], [0, 0]))
    g = res["gears"]
    e = gost(m, [12, 30], [0.0, 0.0])
    check_geometry(g, e, m)
    ch = g["checks"]
    assert ch["undercut"] == [True, False]          # 12 < 17 teeth without shift
    assert ch["sharpening"] == [False, False]
    assert ch["contact_ratio_low"] is False         # eps = 1.54
    assert e["rho_p"][0] < 0 and ch["interference"] is True   # tip of 2 beyond N1
    # each defect is also a warnings entry (SPEC 3)
    assert len(res["warnings"]) >= 2


def test_shifted_pair_spec_example():
    """SPEC's m = 3 mm, z = 12/42, x = 0.63/0.67: no defect (eps = 1.206 > 1.2)."""
    m = 0.003
    res = run(gear_task("3 mm", [12, 42], [0.63, 0.67], alpha=20))
    g = res["gears"]
    e = gost(m, [12, 42], [0.63, 0.67])
    check_geometry(g, e, m)
    assert e["eps_alpha"] > 1.2 + 1e-3 and min(e["sa"]) > 0.25 * m
    assert all(p > l + 1e-4 for p, l in zip(e["rho_p"], e["rho_l"]))
    assert g["checks"] == {"undercut": [False, False], "sharpening": [False, False],
                           "contact_ratio_low": False, "interference": False}


def test_shifted_pair_sharpened_and_low_contact_ratio():
    """Large shifts on a small pinion: tip sharpened (s_a1 < 0.25 m) and eps < 1.2."""
    m = 0.004
    x = [0.9, 0.0]
    res = run(gear_task("4 mm", [12, 25], x))
    g = res["gears"]
    e = gost(m, [12, 25], x)
    check_geometry(g, e, m)
    assert e["sa"][0] < 0.25 * m - 1e-5 and e["eps_alpha"] < 1.2 - 1e-3   # the reference's verdicts
    ch = g["checks"]
    assert ch["sharpening"][0] is True
    assert ch["sharpening"][1] is (e["sa"][1] < 0.25 * m)
    assert ch["contact_ratio_low"] is True
    assert ch["undercut"] == [False, False]
    assert min(p - l for p, l in zip(e["rho_p"], e["rho_l"])) > 1e-4
    assert ch["interference"] is False
    assert len(res["warnings"]) >= 2


def test_negative_shift_undercut_wheel():
    """x2 < x_min of wheel 2 (z2 = 14, x2 = -0.3): undercut of wheel 2 only."""
    m = 0.002
    x = [0.5, -0.3]
    res = run(gear_task("2 mm", [20, 14], x))
    g = res["gears"]
    e = gost(m, [20, 14], x)
    check_geometry(g, e, m)
    assert e["undercut"] == [False, True]
    assert g["checks"]["undercut"] == [False, True]
    assert g["checks"]["sharpening"] == e["sharpening"]
    assert g["checks"]["contact_ratio_low"] is e["contact_ratio_low"]


@settings(max_examples=40, deadline=None)
@given(
    z1=st.integers(12, 40),
    z2=st.integers(12, 120),
    x1=st.floats(-0.3, 0.8),
    x2=st.floats(-0.3, 0.8),
    m=st.sampled_from([0.001, 0.0025, 0.004, 0.01]),
)
def test_property_random_pairs(z1, z2, x1, x2, m):
    al = math.radians(20.0)
    # a mesh exists only while inv alpha_w = inv alpha + 2 tan alpha (x1 + x2)/(z1 + z2) > 0
    assume(inv(al) + 2 * math.tan(al) * (x1 + x2) / (z1 + z2) > 1e-6)
    e = gost(m, [z1, z2], [x1, x2])
    assume(min(e["sa"]) > 0.05 * m and e["eps_alpha"] > 1.0)
    res = run(gear_task(m, [z1, z2], [x1, x2]))
    g = res["gears"]
    check_geometry(g, e, m)
    ch = g["checks"]
    for i, xi in enumerate((x1, x2)):
        if abs(xi - e["x_min"][i]) > 1e-9:
            assert ch["undercut"][i] is e["undercut"][i], ("undercut", i)
        if abs(e["sa"][i] - 0.25 * m) > 1e-9 * m:
            assert ch["sharpening"][i] is e["sharpening"][i], ("sharpening", i)
    if abs(e["eps_alpha"] - 1.2) > 1e-9:
        assert ch["contact_ratio_low"] is e["contact_ratio_low"]
    # interference verdict where the reference is unambiguous: no undercut on either wheel
    # (the involute start formula holds) and a margin, or an active point below a base circle
    if min(e["rho_p"]) < -1e-6 * m:
        assert ch["interference"] is True
    elif not any(e["undercut"]) and min(e["rho_l"]) > 0:
        margin = min(p - l for p, l in zip(e["rho_p"], e["rho_l"]))
        if abs(margin) > 1e-6 * m:
            assert ch["interference"] is (margin < 0)


def test_no_mesh_angle_is_a_clear_stage_error():
    """z = 12/12 with x1 + x2 = -0.5: inv alpha_w = inv 20 deg + 2 tan 20 deg (-0.5)/24
    = 0.014904 - 0.015165 < 0, no working pressure angle exists."""
    al = math.radians(20.0)
    assert inv(al) + 2 * math.tan(al) * (-0.5) / 24 < 0
    with pytest.raises(tmm_cli.StageError) as e:
        run(gear_task(0.001, [12, 12], [-0.25, -0.25]))
    assert e.value.stage == "gears" and "inv alpha_w" in e.value.message


# --------------------------------------------------------------------------------------
# planetary
# --------------------------------------------------------------------------------------
def willis(scheme, z):
    if scheme == "A":
        return Fraction(1) + Fraction(z["z3"], z["z1"])
    if scheme == "B":
        return Fraction(1) + Fraction(z["z2"] * z["z4"], z["z1"] * z["z3"])
    return Fraction(1) - Fraction(z["z2"] * z["z4"], z["z1"] * z["z3"])   # C, D


def coaxial(scheme, z):
    if scheme == "A":
        return z["z3"] == z["z1"] + 2 * z["z2"]
    if scheme == "B":
        return z["z1"] + z["z2"] == z["z4"] - z["z3"]
    if scheme == "C":
        return z["z1"] + z["z2"] == z["z3"] + z["z4"]
    return z["z1"] - z["z2"] == z["z4"] - z["z3"]                      # D


def assembles(i_frac, z1, k):
    """README: (i_1H z1 / k)(1 + k p) is a whole number for some integer p."""
    q = i_frac * z1 / k
    return any(((q * (1 + k * p)).denominator == 1) for p in range(0, q.denominator * k + 1))


def adjacency(scheme, z, k):
    """2 a_w sin(pi/k) > largest satellite tip diameter m (z + 2 ha), per module m."""
    if scheme == "A":
        aw2, sats = z["z1"] + z["z2"], [z["z2"]]
    elif scheme in ("B", "C"):
        aw2, sats = z["z1"] + z["z2"], [z["z2"], z["z3"]]
    else:
        aw2, sats = z["z1"] - z["z2"], [z["z2"], z["z3"]]
    return aw2 * math.sin(math.pi / k) > max(sats) + 2


def undercut_free(scheme, z):
    """README limits: external z >= 17; external wheel of an internal mesh >= 20; internal
    z >= 85; internal - external >= 8."""
    if scheme == "A":
        ext, ext_int, internal = [z["z1"]], [z["z2"]], [(z["z3"], z["z2"])]
    elif scheme == "B":
        ext, ext_int, internal = [z["z1"], z["z2"]], [z["z3"]], [(z["z4"], z["z3"])]
    elif scheme == "C":
        ext, ext_int, internal = [z["z1"], z["z2"], z["z3"], z["z4"]], [], []
    else:
        ext, ext_int, internal = [], [z["z2"], z["z3"]], [(z["z1"], z["z2"]), (z["z4"], z["z3"])]
    return (all(v >= 17 for v in ext) and all(v >= 20 for v in ext_int)
            and all(zi >= 85 and zi - ze >= 8 for zi, ze in internal))


PLANETARY = [
    ("A", 3.24, 3, 0.05),
    ("A", 5.6, 4, 0.02),
    ("A", 7.0, 3, 0.01),
    ("B", 8.0, 3, 0.05),
    ("B", 14.0, 3, 0.03),
    ("C", -0.25, 3, 0.05),
    ("D", 0.08, 3, 0.05),
]


@pytest.mark.parametrize("scheme,ratio,k,tol", PLANETARY)
def test_planetary_conditions(scheme, ratio, k, tol):
    res = run({"schema": "tmm/1",
               "planetary": {"scheme": scheme, "ratio": ratio, "satellites": k, "tolerance": tol}})
    p = res["planetary"]
    z = {key: int(v) for key, v in p["z"].items()}
    n = 3 if scheme == "A" else 4
    assert sorted(z) == [f"z{i}" for i in range(1, n + 1)], z
    i_exact = willis(scheme, z)
    assert p["ratio"] == pytest.approx(float(i_exact), rel=1e-12, abs=1e-12)
    err = (float(i_exact) - ratio) / ratio
    assert p["ratio_error"] == pytest.approx(err, rel=1e-9, abs=1e-12)
    assert abs(err) <= tol + 1e-12, (z, float(i_exact))
    assert coaxial(scheme, z), z
    assert assembles(i_exact, z["z1"], k), z
    assert adjacency(scheme, z, k), z
    assert undercut_free(scheme, z), z


def test_planetary_A_smallest_ring():
    """README ranking for scheme A: the smallest ring (then the least sum of teeth, then
    the ratio error). Own exhaustive search over z1 (sun) and z2 (satellite)."""
    ratio, k, tol = 4.2, 3, 0.03
    res = run({"schema": "tmm/1",
               "planetary": {"scheme": "A", "ratio": ratio, "satellites": k, "tolerance": tol}})
    got = {key: int(v) for key, v in res["planetary"]["z"].items()}
    best = None
    for z1, z2 in itertools.product(range(17, 151), range(20, 151)):
        z = {"z1": z1, "z2": z2, "z3": z1 + 2 * z2}
        if z["z3"] > 150:
            continue
        i = willis("A", z)
        err = abs(float(i) - ratio) / ratio
        if err > tol or not assembles(i, z1, k) or not adjacency("A", z, k) or not undercut_free("A", z):
            continue
        key = (z["z3"], z1 + z2 + z["z3"], err)
        if best is None or key < best[0]:
            best = (key, z)
    assert best is not None
    assert got["z3"] == best[1]["z3"], (got, best)
