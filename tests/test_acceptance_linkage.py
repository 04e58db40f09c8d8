"""Acceptance tests of the linkage stages, written as an outsider would: from SPEC.md and
METHODS.md only, through the public API (`tmm_cli.load_task(dict)`, `tmm_cli.run`).

Every expected number comes from code in this file or in `acceptance_util.py`, which
shares nothing with tmm_cli:
* closed forms (slider-crank and four-bar dead centres by the cosine rule, the
  slotted-lever extremes sin(beta) = r/d, x_B of the central slider-crank, K);
* an independent numerical solver (Newton on the loop equations, 8th-order central
  differences in the crank angle for velocities and accelerations);
* an independent force solution: one global Newton-Euler system per position (all
  links at once, not group by group), cross-checked inside the reference against the
  principle of virtual power (virtual work);
* singular crank angles by root finding (brentq) on the virtual velocity of the
  balance link, or the cosine-rule toggle angles.

Conventions taken from SPEC: position 0 = extreme position starting the working stroke,
`count` positions every 360/count deg in the drive direction, then the user's `extra`
angles, then the positions the tool adds (the second extreme); angles in [0, 360);
omega, epsilon signed ccw; R<i><j> = force of link i on link j (i < j, ground 0);
balancing moment ccw positive on the balance link; a balancing force on a slider is
signed along its guide direction (as slider loads in SPEC `loads`).
"""
from __future__ import annotations

import copy
import json
import math

import numpy as np
import pytest

import tmm_cli
from acceptance_util import Linkage, angdiff, rate_roots, wrap360

RTOL = 1e-6
DEG_TOL = 1e-6


def run(task):
    return tmm_cli.run(tmm_cli.load_task(copy.deepcopy(task)))


_REFS = {}


def ref_linkage(task):
    """The independent reference for a task (cached by mechanism and drive)."""
    key = json.dumps([task["mechanism"], task["drive"]])  # link order matters
    if key not in _REFS:
        _REFS[key] = Linkage(copy.deepcopy(task))
    return _REFS[key]


def by_index(entries):
    return {e["index"]: e for e in entries}


def close(got, exp, scale, what=""):
    assert got is not None, f"{what}: got null, expected {exp}"
    assert abs(got - exp) <= RTOL * abs(exp) + 1e-9 * scale, f"{what}: got {got!r}, expected {exp!r}"


def close_deg(got, exp, what="", tol=DEG_TOL):
    assert got is not None, f"{what}: got null, expected {exp}"
    assert abs(angdiff(got, exp)) <= tol, f"{what}: got {got!r}, expected {exp!r}"


def expected_phis(phi0, count, sign, extra):
    return [wrap360(phi0 + sign * 360.0 / count * k) for k in range(count)] + [wrap360(e) for e in extra]


# ---------------------------------------------------------------------------------
# generic checks
# ---------------------------------------------------------------------------------
def check_positions(res, phi0, phi1, working, K=None):
    pos = res["positions"]
    close_deg(pos["phi0"], phi0, "phi0")
    assert len(pos["extreme"]) == 2
    close_deg(pos["extreme"][0], phi0, "extreme[0]")
    close_deg(pos["extreme"][1], phi1, "extreme[1]")
    assert abs(pos["working_stroke_angle"] - working) <= DEG_TOL, (pos["working_stroke_angle"], working)
    for a in (pos["phi0"], *pos["extreme"]):
        assert 0.0 <= a < 360.0
    if K is not None:
        assert abs(pos["K"] - K) <= 1e-9 * K, (pos["K"], K)


def check_kinematics(res, L, phi0, count, extra, phi1=None):
    """Every entry (grid + extra + the added second extreme) vs the reference."""
    ents = by_index(res["kinematics"])
    exp_phi = expected_phis(phi0, count, L.sign, extra)
    for i, ph in enumerate(exp_phi):
        assert i in ents, f"no kinematics entry with index {i}"
        close_deg(ents[i]["phi"], ph, f"kinematics[{i}].phi")
    if phi1 is not None:  # the second extreme is added after the user's extra angles
        added = [e for e in res["kinematics"] if e["index"] >= count + len(extra)]
        if any(abs(angdiff(p, phi1)) < DEG_TOL for p in exp_phi):
            added = res["kinematics"]  # already a grid position (central slider-crank)
        assert any(abs(angdiff(e["phi"], phi1)) < DEG_TOL for e in added), "second extreme not reported"
    # scales for the absolute floor of the tolerance
    refs = {e["index"]: L.kin(e["phi"]) for e in res["kinematics"]}
    sc = {k: 1e-3 for k in ("x", "v", "a", "w", "e")}
    for pts, lk in refs.values():
        for v in pts.values():
            sc["x"] = max(sc["x"], abs(v[0]), abs(v[1]))
            sc["v"] = max(sc["v"], math.hypot(v[2], v[3]))
            sc["a"] = max(sc["a"], math.hypot(v[4], v[5]))
        for v in lk.values():
            sc["w"] = max(sc["w"], abs(v[1]))
            sc["e"] = max(sc["e"], abs(v[2]))
    for idx, e in ents.items():
        assert 0.0 <= e["phi"] < 360.0
        pts, lk = refs[idx]
        assert set(pts) <= set(e["points"]), f"missing points {set(pts) - set(e['points'])}"
        for p, (x, y, vx, vy, ax, ay) in pts.items():
            g = e["points"][p]
            w = f"kinematics[{idx}].points.{p}"
            close(g["x"], x, sc["x"], w + ".x")
            close(g["y"], y, sc["x"], w + ".y")
            close(g["vx"], vx, sc["v"], w + ".vx")
            close(g["vy"], vy, sc["v"], w + ".vy")
            close(g["v"], math.hypot(vx, vy), sc["v"], w + ".v")
            close(g["ax"], ax, sc["a"], w + ".ax")
            close(g["ay"], ay, sc["a"], w + ".ay")
            close(g["a"], math.hypot(ax, ay), sc["a"], w + ".a")
        assert set(lk) == set(e["links"])
        for n, (ang, om, ep) in lk.items():
            g = e["links"][n]
            w = f"kinematics[{idx}].links.{n}"
            assert 0.0 <= g["angle"] < 360.0, (w, g["angle"])
            close_deg(g["angle"], ang, w + ".angle", tol=1e-7)
            close(g["omega"], om, sc["w"], w + ".omega")
            close(g["epsilon"], ep, sc["e"], w + ".epsilon")


def stroke_load(L, phi0, working, magnitude, slider, direction):
    """Constant resistance on the working stroke (SPEC loads): opposes the working motion,
    along the guide; position 0 (start of the working stroke) carries it, the second
    extreme (start of the idle stroke) does not."""

    def ext(phi, pts, lk):
        d = wrap360(L.sign * (phi - phi0))
        if d > 360.0 - 1e-7:
            d = 0.0
        if d < working - 1e-7:
            P = {p: np.array(v[:2]) for p, v in pts.items()}
            _, u = L.guide_line(P, slider)
            F = -magnitude * direction * u
            return [(slider, L.links[slider]["slider"], F, 0.0)]
        return []

    return ext


def check_kinetostatics(res, L, balance, singular, inertia=True, gravity=False, ext=None, near=1.0):
    assert "singular" in res
    got_s = sorted(res["singular"])
    assert len(got_s) == len(singular), (got_s, singular)
    for g, s in zip(got_s, sorted(singular)):
        close_deg(g, s, "singular")
    assert all(0.0 <= s < 360.0 for s in got_s)
    kin = by_index(res["kinematics"])
    ks = res["kinetostatics"]
    assert {e["index"] for e in ks} == set(kin), "kinetostatics: positions all"
    bl = L.links[balance]
    is_force = "points" not in bl
    ref = {}
    for e in ks:
        ph = e["phi"]
        close_deg(ph, kin[e["index"]]["phi"])
        dist = min((abs(angdiff(ph, s)) for s in singular), default=999.0)
        if dist < near:
            assert e.get("near_singular") is True, f"index {e['index']} phi {ph}: near_singular expected"
        else:
            assert not e.get("near_singular"), f"index {e['index']} phi {ph}: not near a singular angle"
        if dist < 1e-3:
            continue  # singular to working precision: the numbers may be null
        r = L.forces(ph, balance=balance, inertia=inertia, gravity=gravity, ext=ext)
        # the reference checks itself: Newton-Euler vs virtual power
        assert abs(r["bal"] - r["power_bal"]) <= 1e-8 * max(1.0, abs(r["bal"])), (r["bal"], r["power_bal"])
        ref[e["index"]] = (e, r)
    assert ref, "nothing to compare"
    scb = max(abs(r["bal"]) for _, r in ref.values())
    scr = max(max(math.hypot(*v) for v in r["reactions"].values()) for _, r in ref.values())
    for idx, (e, r) in ref.items():
        w = f"kinetostatics[{idx}] (phi {e['phi']:.4f})"
        if is_force:
            close(e["balancing_force"], r["bal"], scb, w + ".balancing_force")
        else:
            close(e["balancing_moment"], r["bal"], scb, w + ".balancing_moment")
            close(e["zhukovsky_moment"], r["bal"], scb, w + ".zhukovsky_moment")
            assert e["discrepancy"] is not None and e["discrepancy"] < 1e-6
        assert set(e["reactions"]) == set(r["reactions"]), (sorted(e["reactions"]), sorted(r["reactions"]))
        for k, (x, y) in r["reactions"].items():
            g = e["reactions"][k]
            close(g["x"], x, scr, f"{w}.{k}.x")
            close(g["y"], y, scr, f"{w}.{k}.y")
            close(g["R"], math.hypot(x, y), scr, f"{w}.{k}.R")
        if inertia:
            pts, lk = L.kin(e["phi"])
            for i, n in enumerate(L.names, 1):
                l = L.links[n]
                m, J = float(l.get("mass", 0.0)), float(l.get("J", 0.0))
                S = pts[f"S{i}"]
                gi = e["inertia"][n]
                sci = 1.0 + scr
                close(gi["Fx"], -m * S[4], sci, f"{w}.inertia.{n}.Fx")
                close(gi["Fy"], -m * S[5], sci, f"{w}.inertia.{n}.Fy")
                close(gi["M"], -J * lk[n][2], sci, f"{w}.inertia.{n}.M")
    return ref


# ---------------------------------------------------------------------------------
# slider-crank mechanisms
# ---------------------------------------------------------------------------------
def slider_crank(r, l, through, angle, hint, direction="ccw", working="forward", extra=(), masses=False):
    links = {
        "crank": {"points": ["O", "A"], "length": r},
        "rod": {"points": ["A", "B"], "length": l},
        "slider": {"slider": "B", "guide": {"through": list(through), "angle": angle}},
    }
    if masses:
        links["crank"].update(mass=2.0, J=0.01, com=[0.03, 0.0])
        links["rod"].update(mass=3.0, J=0.045, com=[0.14, 0.0])
        links["slider"].update(mass=5.0)
    return {
        "schema": "tmm/1",
        "mechanism": {"ground": {"O": [0, 0]}, "links": links, "assembly": {"B": list(hint)}},
        "drive": {"link": "crank", "speed": "120 rpm", "direction": direction},
        "positions": {"output": "slider", "working": working, "extra": list(extra)},
    }


def slider_crank_dead_centres(r, l, through, angle):
    """Closed form: (crank angle at the far dead centre, at the near one, s_far, s_near),
    s measured along the guide from `through`; B assumed on the +u side of the foot of O."""
    T = np.array(through, float)
    u = np.array([math.cos(math.radians(angle)), math.sin(math.radians(angle))])
    foot = T + ((np.zeros(2) - T) @ u) * u  # projection of O on the guide
    e = math.hypot(*foot)
    B_far = foot + math.sqrt((l + r) ** 2 - e * e) * u
    B_near = foot + math.sqrt((l - r) ** 2 - e * e) * u
    phi_far = math.degrees(math.atan2(B_far[1], B_far[0]))
    phi_near = math.degrees(math.atan2(-B_near[1], -B_near[0]))
    return wrap360(phi_far), wrap360(phi_near), float((B_far - T) @ u), float((B_near - T) @ u)


def sc_expected(task):
    """(phi0, phi1, working stroke angle) of a slider-crank task from the closed form."""
    g = task["mechanism"]["links"]
    r, l = g["crank"]["length"], g["rod"]["length"]
    gd = g["slider"]["guide"]
    phi_far, phi_near, s_far, s_near = slider_crank_dead_centres(r, l, gd["through"], gd["angle"])
    fwd = task["positions"].get("working", "forward") == "forward"
    # forward: the working stroke goes toward increasing s, so it starts at the minimum s
    phi0, phi1 = (phi_near, phi_far) if fwd == (s_near < s_far) else (phi_far, phi_near)
    sign = 1.0 if task["drive"].get("direction", "ccw") == "ccw" else -1.0
    return phi0, phi1, wrap360(sign * (phi1 - phi0))


R_SC, L_SC = 0.1, 0.4
CENTRAL = slider_crank(R_SC, L_SC, [0, 0], 0, [0.5, 0], extra=[37.5])
OFFSET = slider_crank(0.12, 0.42, [0, -0.04], 0, [0.5, -0.04], extra=[200.5])
OFFSET_CW = slider_crank(0.12, 0.42, [0, -0.04], 0, [0.5, -0.04], direction="cw", extra=[200.5])
INCLINED = slider_crank(0.1, 0.35, [0.02, 0.03], 150, [-0.3, 0.2], working="backward", extra=[10.0])


@pytest.fixture(scope="module")
def central():
    return run(CENTRAL), ref_linkage(CENTRAL)


def test_central_slider_crank_structure(central):
    st = central[0]["structure"]
    assert (st["n"], st["p5"], st["p4"], st["W"], st["class"]) == (3, 4, 0, 1, 2)
    assert len(st["groups"]) == 1 and st["groups"][0]["type"] == "RRP"
    assert sorted(st["groups"][0]["links"]) == ["rod", "slider"]


def test_central_slider_crank_positions(central):
    # central: dead centres at phi = 180 (near, start of the forward working stroke) and 0
    res, L = central
    check_positions(res, 180.0, 0.0, 180.0, K=1.0)


def test_central_slider_crank_kinematics(central):
    res, L = central
    check_kinematics(res, L, 180.0, 12, [37.5], phi1=0.0)
    # closed form of the central slider-crank: x_B = r cos(phi) + sqrt(l^2 - r^2 sin^2 phi)
    w = 4 * math.pi
    for e in res["kinematics"]:
        ph = math.radians(e["phi"])
        s, c = math.sin(ph), math.cos(ph)
        root = math.sqrt(L_SC**2 - R_SC**2 * s * s)
        x = R_SC * c + root
        dx = -R_SC * s - R_SC**2 * s * c / root
        close(e["points"]["B"]["x"], x, 1.0, "x_B closed form")
        close(e["points"]["B"]["vx"], w * dx, 1.0, "v_B closed form")
        close_deg(e["links"]["slider"]["angle"], 0.0, "slider angle = guide angle")
        assert e["links"]["slider"]["omega"] == pytest.approx(0.0, abs=1e-12)


@pytest.mark.parametrize("task", [OFFSET, OFFSET_CW, INCLINED], ids=["offset", "offset_cw", "inclined_backward"])
def test_slider_crank_positions_and_kinematics(task):
    res, L = run(task), ref_linkage(task)
    g = task["mechanism"]["links"]
    r, l = g["crank"]["length"], g["rod"]["length"]
    gd = g["slider"]["guide"]
    phi_far, phi_near, s_far, s_near = slider_crank_dead_centres(r, l, gd["through"], gd["angle"])
    # the reference solver agrees with the closed form (its own check)
    assert abs(L.coord_rate("slider", phi_far)) < 1e-9 and abs(L.coord_rate("slider", phi_near)) < 1e-9
    assert L.coord("slider", phi_far) == pytest.approx(s_far, abs=1e-12)
    phi0, phi1, working = sc_expected(task)
    K = working / (360.0 - working)  # (180 + theta)/(180 - theta), theta = working - 180
    check_positions(res, phi0, phi1, working, K=K)
    check_kinematics(res, L, phi0, 12, task["positions"]["extra"], phi1=phi1)


def test_offset_cw_is_mirror_of_ccw_stroke_angles():
    """With the direction reversed the same dead centres bound complementary strokes."""
    a, b = run(OFFSET)["positions"], run(OFFSET_CW)["positions"]
    close_deg(a["phi0"], b["phi0"])
    assert a["working_stroke_angle"] + b["working_stroke_angle"] == pytest.approx(360.0, abs=1e-9)


# ---------------------------------------------------------------------------------
# crank-rocker four-bar
# ---------------------------------------------------------------------------------
O1_4, R4, L4, C4 = (0.28, 0.1), 0.08, 0.3, 0.2


def fourbar(direction="ccw", balance=None, extra=(50.0,)):
    t = {
        "schema": "tmm/1",
        "mechanism": {
            "ground": {"O": [0, 0], "O1": list(O1_4)},
            "links": {
                "crank": {"points": ["O", "A"], "length": R4, "mass": 0.5, "J": 0.0004},
                "rod": {"points": ["A", "B"], "length": L4, "mass": 1.2, "J": 0.009},
                "rocker": {"points": ["O1", "B"], "length": C4, "mass": 0.8, "J": 0.0027,
                           "extra": {"E": [0.1, 0.05]}},
            },
            "assembly": {"B": [0.3, 0.28]},
        },
        "drive": {"link": "crank", "speed": "200 rpm", "direction": direction},
        "positions": {"output": "rocker", "working": "forward", "extra": list(extra)},
    }
    if balance:
        t["loads"] = {"gravity": True}
        t["kinetostatics"] = {"balance": balance, "inertia": True}
    return t


def fourbar_toggles():
    """Cosine rule: crank angles where crank and rod are collinear (extended, folded),
    B on the left of O->O1 (the assembly used)."""
    d = math.hypot(*O1_4)
    th = math.atan2(O1_4[1], O1_4[0])
    a_ext = math.acos((d * d + (L4 + R4) ** 2 - C4 * C4) / (2 * d * (L4 + R4)))
    a_fold = math.acos((d * d + (L4 - R4) ** 2 - C4 * C4) / (2 * d * (L4 - R4)))
    phi_ext = wrap360(math.degrees(th + a_ext))
    phi_fold = wrap360(math.degrees(th + a_fold) + 180.0)
    B_ext = (L4 + R4) * np.array([math.cos(th + a_ext), math.sin(th + a_ext)])
    B_fold = (L4 - R4) * np.array([math.cos(th + a_fold), math.sin(th + a_fold)])
    psi_ext = math.degrees(math.atan2(B_ext[1] - O1_4[1], B_ext[0] - O1_4[0]))
    psi_fold = math.degrees(math.atan2(B_fold[1] - O1_4[1], B_fold[0] - O1_4[0]))
    return phi_ext, phi_fold, psi_ext, psi_fold


@pytest.mark.parametrize("direction,working", [("ccw", "forward"), ("cw", "forward"), ("ccw", "backward")])
def test_fourbar_positions_and_kinematics(direction, working):
    task = fourbar(direction)
    task["positions"]["working"] = working
    res, L = run(task), ref_linkage(task)
    assert res["structure"]["groups"][0]["type"] == "RRR"
    phi_ext, phi_fold, psi_ext, psi_fold = fourbar_toggles()
    # own check: the reference solver is on that closure and agrees with the cosine rule
    assert sorted(rate_roots(L, "rocker")) == pytest.approx(sorted([phi_ext, phi_fold]), abs=1e-8)
    # forward = rocker turning ccw: the stroke starts at the clockwise-most rocker angle
    phi0, phi1 = (phi_fold, phi_ext) if angdiff(psi_ext, psi_fold) > 0 else (phi_ext, phi_fold)
    if working == "backward":
        phi0, phi1 = phi1, phi0
    working = wrap360(L.sign * (phi1 - phi0))
    check_positions(res, phi0, phi1, working, K=working / (360 - working))
    check_kinematics(res, L, phi0, 12, [50.0], phi1=phi1)


def test_fourbar_balance_on_rocker_singular_angles():
    """Balancing moment on the rocker: singular where omega_rocker/omega_crank = 0, i.e.
    the toggle positions (crank and rod collinear), closed form by the cosine rule.
    Extra angles 0.5 deg from them are flagged near_singular with finite numbers; 1.5 deg
    away they are not flagged."""
    phi_ext, phi_fold, _, _ = fourbar_toggles()
    extra = [phi_ext + 0.5, phi_fold - 0.6, phi_ext - 1.5, 50.0]
    task = fourbar(balance="rocker", extra=extra)
    res, L = run(task), ref_linkage(task)
    ref = check_kinetostatics(res, L, "rocker", [phi_ext, phi_fold], inertia=True, gravity=True)
    flagged = {e["index"] for e in res["kinetostatics"] if e.get("near_singular")}
    assert {12, 13} <= flagged and 14 not in flagged and {12, 13, 14} <= set(ref)
    check_exact_singular_not_huge(res, ref, [phi_ext, phi_fold])


def check_exact_singular_not_huge(res, ref, singular):
    """SPEC: positions at singular angles are never filled with huge numbers or NaN."""
    json.dumps(res, allow_nan=False)
    big = max(abs(r["bal"]) for _, r in ref.values())
    hit = 0
    for e in res["kinetostatics"]:
        if min(abs(angdiff(e["phi"], s)) for s in singular) < 1e-6:
            hit += 1
            for key in ("balancing_moment", "balancing_force"):
                v = e.get(key)
                assert v is None or abs(v) <= 10 * big, (e["index"], key, v)
    assert hit >= 1


# ---------------------------------------------------------------------------------
# SPEC's six-bar (section 1 mechanism, section 3 positions)
# ---------------------------------------------------------------------------------
def sixbar(balance=None, inertia=False, working="backward", hint_B=(0.9, 0.6), hint_D=(0.5, 1.4)):
    t = {
        "schema": "tmm/1",
        "mechanism": {
            "ground": {"O": [0, 0], "O1": [0.50, 0.37]},
            "links": {
                "crank": {"points": ["O", "A"], "length": 0.15, "mass": 1.5, "J": 0.02},
                "rod": {"points": ["A", "B"], "length": 0.97, "mass": 9.7, "J": 0.76, "com": [0.485, 0]},
                "rocker": {"points": ["O1", "B"], "length": 0.66, "extra": {"K": [0.25, 0]}},
                "link4": {"points": ["K", "D"], "length": 0.86},
                "slider": {"slider": "D", "guide": {"through": "O1", "angle": 90}, "mass": 20},
            },
            "assembly": {"B": list(hint_B), "D": list(hint_D)},
        },
        "drive": {"link": "crank", "speed": "50 rpm", "direction": "ccw"},
        "positions": {"output": "slider", "working": working, "extra": [120.686]},
    }
    if balance:
        t["loads"] = {"gravity": True}
        t["kinetostatics"] = {"balance": balance, "inertia": inertia}
    return t


def sixbar_rocker_toggles():
    """Cosine rule for the four-bar O-A-B-O1 of the six-bar: |OB| = 0.97 +- 0.15,
    B on the right of O->O1 (the closure of the hint B ~ (0.9, 0.6) at phi = 0)."""
    d = math.hypot(0.5, 0.37)
    th = math.atan2(0.37, 0.5)
    a_ext = math.acos((d * d + 1.12**2 - 0.66**2) / (2 * d * 1.12))
    a_fold = math.acos((d * d + 0.82**2 - 0.66**2) / (2 * d * 0.82))
    return wrap360(math.degrees(th - a_ext)), wrap360(math.degrees(th - a_fold) + 180.0)


@pytest.fixture(scope="module")
def six():
    return run(sixbar()), ref_linkage(sixbar())


def test_sixbar_structure(six):
    st = six[0]["structure"]
    assert (st["n"], st["p5"], st["p4"], st["W"], st["class"]) == (5, 7, 0, 1, 2)
    assert st["formula"] == "I(0,1) -> II(2,3) -> II(4,5)"
    assert [g["type"] for g in st["groups"]] == ["RRR", "RRP"]


def test_sixbar_positions_match_spec_section3(six):
    """SPEC 3 quotes phi0 6.42, extremes [6.42, 164.19], working stroke 157.8: obtained with
    SPEC's own assembly hint B ~ (0.9, 0.6) and `working: backward` (the slider's working
    stroke goes down, toward decreasing coordinate along the +y guide).  The slider's
    extremes coincide with the rocker's (the rocker never reaches 90 deg), i.e. with the
    crank-rod toggles given by the cosine rule."""
    res, L = six
    phi_ext, phi_fold = sixbar_rocker_toggles()
    assert rate_roots(L, "slider") == pytest.approx(sorted([phi_ext, phi_fold]), abs=1e-8)
    # the slider is highest at the extended toggle: backward working starts there
    assert L.coord("slider", phi_ext) > L.coord("slider", phi_fold)
    check_positions(res, phi_ext, phi_fold, phi_fold - phi_ext, K=(phi_fold - phi_ext) / (360 - phi_fold + phi_ext))
    pos = res["positions"]
    assert round(pos["phi0"], 2) == 6.42
    assert [round(a, 2) for a in pos["extreme"]] == [6.42, 164.19]
    assert round(pos["working_stroke_angle"], 1) == 157.8


def test_sixbar_forward_starts_at_the_other_extreme():
    """Defaults: output = the last link (the slider), working = forward."""
    task = sixbar(working="forward")
    del task["positions"]["output"], task["positions"]["working"]
    res = run(task)
    phi_ext, phi_fold = sixbar_rocker_toggles()
    check_positions(res, phi_fold, phi_ext, wrap360(phi_ext - phi_fold))


def test_sixbar_kinematics(six):
    res, L = six
    phi_ext, phi_fold = sixbar_rocker_toggles()
    check_kinematics(res, L, phi_ext, 12, [120.686], phi1=phi_fold)


def test_sixbar_other_closures():
    """The hint picks the closure of each group: D below K, and B on the other side (the
    rocker toggles mirrored about O-O1)."""
    task = sixbar(hint_D=(0.5, -0.4))
    res, L = run(task), ref_linkage(task)
    phi_ext, phi_fold = sixbar_rocker_toggles()
    assert L.state(0.0)[0]["D"][1] < 0
    check_positions(res, phi_ext, phi_fold, phi_fold - phi_ext)
    check_kinematics(res, L, phi_ext, 12, [120.686], phi1=phi_fold)
    task = sixbar(hint_B=(0.0, 0.8), working="forward")
    res, L = run(task), ref_linkage(task)
    th = math.degrees(math.atan2(0.37, 0.5))
    m_ext, m_fold = wrap360(2 * th - phi_ext), wrap360(2 * th - phi_fold)  # mirror images
    roots = rate_roots(L, "slider")
    assert roots == pytest.approx(sorted([m_ext, m_fold]), abs=1e-8)
    lo = m_ext if L.coord("slider", m_ext) < L.coord("slider", m_fold) else m_fold
    hi = m_fold if lo == m_ext else m_ext
    check_positions(res, lo, hi, wrap360(hi - lo))
    check_kinematics(res, L, lo, 12, [120.686], phi1=hi)


@pytest.mark.parametrize("balance,inertia", [
    ("crank", False), ("rocker", False), ("slider", False), ("rod", False), ("link4", False),
    ("crank", True), ("slider", True)])
def test_sixbar_gravity_balance(balance, inertia):
    """Six-bar under gravity only (inertia: false).  The balancing moment on the crank,
    then on the rocker, then a balancing force on the slider (and on the couplers rod,
    link4): each against the reference's Newton-Euler system (itself checked by virtual
    work), reactions too (determined uniquely).  Singular: none for the crank; the
    toggles for the rocker; zeros of v_D for the slider (the same toggles here); zeros
    of the coupler's omega for rod / link4 (root finding)."""
    task = sixbar(balance=balance, inertia=inertia)
    res, L = run(task), ref_linkage(task)
    if balance == "crank":
        sing = []
    else:
        sing = rate_roots(L, balance)
        if balance in ("rocker", "slider"):
            assert sing == pytest.approx(sorted(sixbar_rocker_toggles()), abs=1e-8)
    if balance == "rod":  # SPEC 3 quotes "singular": [120.686, 334.097] (and extra 120.686)
        assert [round(a, 3) for a in sorted(res["singular"])] == [120.686, 334.097]
    ref = check_kinetostatics(res, L, balance, sing, inertia=inertia, gravity=True)
    if balance in ("rocker", "slider"):  # positions 0 and 12 are exactly singular
        check_exact_singular_not_huge(res, ref, sing)
    if balance == "crank":
        # METHODS 3: P_b = M_b / l_OA at the crank pin
        for e, r in ref.values():
            assert abs(e["balancing_force"]) == pytest.approx(abs(r["bal"]) / 0.15, rel=1e-9)


# ---------------------------------------------------------------------------------
# slider-crank with inertia and a constant resistance on the working stroke
# ---------------------------------------------------------------------------------
@pytest.mark.parametrize("task", [
    slider_crank(0.1, 0.4, [0, 0], 0, [0.5, 0], masses=True, extra=[95.0]),
    slider_crank(0.12, 0.42, [0, -0.04], 0, [0.5, -0.04], direction="cw", masses=True, extra=[95.0]),
], ids=["central", "offset_cw"])
def test_slider_crank_inertia_and_resistance(task):
    task = copy.deepcopy(task)
    task["loads"] = {"forces": [{"on": "slider", "kind": "resistance", "stroke": "working", "magnitude": 2000}]}
    task["kinetostatics"] = {"inertia": True}
    res, L = run(task), ref_linkage(task)
    phi0, phi1, working = sc_expected(task)
    ext = stroke_load(L, phi0, working, 2000.0, "slider", +1)
    ref = check_kinetostatics(res, L, "crank", [], inertia=True, gravity=False, ext=ext)
    # the load really is there on the working stroke and absent on the idle stroke
    with_load = [e for e, r in ref.values() if ext(e["phi"], *L.kin(e["phi"]))]
    assert 0 < len(with_load) < len(ref)
    # position 0 carries the working-stroke load, the second extreme does not (SPEC loads)
    assert ext(phi0, *L.kin(phi0)) and not ext(phi1, *L.kin(phi1))
    assert any(abs(angdiff(e["phi"], phi1)) < DEG_TOL for e, r in ref.values())


def test_slider_crank_balance_on_coupler():
    """Balancing moment on the rod of a central slider-crank: omega_rod = 0 where the crank
    is perpendicular to the guide, phi = 90 and 270 (omega_2 = omega_1 r cos(phi) /
    (l cos(beta))): those are the singular angles; 90 and 270 are grid positions here."""
    task = slider_crank(0.1, 0.4, [0, 0], 0, [0.5, 0], masses=True, extra=[95.0, 268.0])
    task["loads"] = {"gravity": True,
                     "forces": [{"on": "slider", "kind": "resistance", "stroke": "working", "magnitude": 2000}]}
    task["kinetostatics"] = {"inertia": True, "balance": "rod"}
    res, L = run(task), ref_linkage(task)
    phi0, _, working = sc_expected(task)
    ext = stroke_load(L, phi0, working, 2000.0, "slider", +1)
    ref = check_kinetostatics(res, L, "rod", [90.0, 270.0], inertia=True, gravity=True, ext=ext)
    check_exact_singular_not_huge(res, ref, [90.0, 270.0])


def test_slider_crank_resistance_diagram_vs_relative_stroke():
    """`diagram: {s, value}` over the relative stroke s/H of the working stroke (SPEC loads),
    linear interpolation; resistance opposes the working motion."""
    task = slider_crank(0.12, 0.42, [0, -0.04], 0, [0.5, -0.04], masses=True, extra=[95.0])
    diag = {"s": [0, 0.3, 0.7, 1], "value": [0, 2500, 2500, 400]}
    task["loads"] = {"forces": [{"on": "slider", "kind": "resistance", "stroke": "working", "diagram": diag}]}
    task["kinetostatics"] = {"inertia": True}
    res, L = run(task), ref_linkage(task)
    phi0, phi1, work = sc_expected(task)
    s0 = L.coord("slider", phi0)
    Hs = abs(L.coord("slider", phi1) - s0)

    def ext(phi, pts, lk):
        d = wrap360(L.sign * (phi - phi0))
        if d > 360.0 - 1e-7:
            d = 0.0
        if d >= work - 1e-7:
            return []
        srel = abs(L.coord("slider", phi) - s0) / Hs
        return [("slider", "B", np.array([-np.interp(srel, diag["s"], diag["value"]), 0.0]), 0.0)]

    check_kinetostatics(res, L, "crank", [], inertia=True, ext=ext)


def test_force_on_a_bar_with_direction_and_point_and_a_couple():
    """A force on a bar link: constant phi-diagram, `direction` 100 deg, applied at local
    [u, v] = [0.1, 0.02] of the rod; a constant couple of 10 N*m (ccw) on the rod on both
    strokes.  Extra angles outside [0, 360) are reported wrapped (SPEC: all angles in
    results are in [0, 360))."""
    task = slider_crank(0.1, 0.4, [0, 0], 0, [0.5, 0], masses=True, extra=[-30.0, 370.0])
    task["loads"] = {"gravity": True, "forces": [
        {"on": "rod", "diagram": {"phi": [0, 360], "value": [150, 150]}, "direction": 100, "at": [0.1, 0.02]},
        {"on": "rod", "moment": 10, "stroke": "both"}]}
    task["kinetostatics"] = {"inertia": True}
    res, L = run(task), ref_linkage(task)
    assert [round(e["phi"], 9) for e in res["kinematics"] if e["index"] in (12, 13)] == [330.0, 10.0]
    F = 150.0 * np.array([math.cos(math.radians(100)), math.sin(math.radians(100))])

    def ext(phi, pts, lk):
        A, B = np.array(pts["A"][:2]), np.array(pts["B"][:2])
        u = (B - A) / np.hypot(*(B - A))
        p = A + 0.1 * u + 0.02 * np.array([-u[1], u[0]])
        w = lk["rod"][1]
        v = np.array(pts["A"][2:4]) + w * np.array([-(p - A)[1], (p - A)[0]])
        return [("rod", (p, v), F, 10.0)]

    check_kinetostatics(res, L, "crank", [], inertia=True, gravity=True, ext=ext)


def test_links_numbered_in_the_order_listed():
    """SPEC: links are numbered 1..n in the order listed, whatever the drive link; R<i><j>
    and S<i> follow that numbering (here slider = 1, rod = 2, crank = 3)."""
    base = slider_crank(0.12, 0.42, [0, -0.04], 0, [0.5, -0.04], masses=True, extra=[95.0])
    lk = base["mechanism"]["links"]
    base["mechanism"]["links"] = {"slider": lk["slider"], "rod": lk["rod"], "crank": lk["crank"]}
    base["loads"] = {"gravity": True, "forces": [
        {"on": "slider", "kind": "resistance", "stroke": "working", "magnitude": 900}]}
    base["kinetostatics"] = {"inertia": True}
    res, L = run(base), ref_linkage(base)
    assert L.names == ["slider", "rod", "crank"]
    phi0, phi1, working = sc_expected(base)
    check_positions(res, phi0, phi1, working)
    ext = stroke_load(L, phi0, working, 900.0, "slider", +1)
    ref = check_kinetostatics(res, L, "crank", [], inertia=True, gravity=True, ext=ext)
    assert set(next(iter(ref.values()))[1]["reactions"]) == {"R01", "R03", "R12", "R23"}
    check_kinematics(res, L, phi0, 12, [95.0], phi1=phi1)


# ---------------------------------------------------------------------------------
# crank-and-slotted-lever (shaper)
# ---------------------------------------------------------------------------------
D_SH, R_SH = 0.25, 0.1


def shaper(kinetostatics=False):
    t = {
        "schema": "tmm/1",
        "mechanism": {
            "ground": {"O2": [0, 0], "O1": [0, D_SH]},
            "links": {
                "crank": {"points": ["O1", "A"], "length": R_SH, "mass": 1.0},
                "block": {"slider": "A", "guide": {"link": "lever"}, "mass": 0.5, "J": 0.0002},
                "lever": {"points": ["O2", "C"], "length": 0.55, "mass": 4.0, "J": 0.1},
                "rod": {"points": ["C", "D"], "length": 0.15, "mass": 1.5, "J": 0.003},
                "ram": {"slider": "D", "guide": {"through": [0, 0.58], "angle": 0}, "mass": 12.0},
            },
            "assembly": {"C": [0.2, 0.51], "D": [0.34, 0.58]},
        },
        "drive": {"link": "crank", "speed": "60 rpm", "direction": "ccw"},
        "positions": {"output": "ram", "working": "backward", "extra": [100.0]},
    }
    if kinetostatics:
        t["loads"] = {"gravity": True, "forces": [
            {"on": "ram", "kind": "resistance", "stroke": "working", "magnitude": 1500}]}
        t["kinetostatics"] = {"inertia": True}
    return t


def test_shaper_positions_and_kinematics():
    """Slotted lever extremes: the lever is tangent to the crank circle, sin(beta) = r/d;
    ccw crank, the long (slow) stroke from phi = -beta to 180 + beta moves the ram to -x."""
    task = shaper()
    res, L = run(task), ref_linkage(task)
    types = [g["type"] for g in res["structure"]["groups"]]
    assert types == ["RPR", "RRP"]
    beta = math.degrees(math.asin(R_SH / D_SH))
    phi0, phi1 = 360.0 - beta, 180.0 + beta
    check_positions(res, phi0, phi1, 180 + 2 * beta, K=(180 + 2 * beta) / (180 - 2 * beta))
    check_kinematics(res, L, phi0, 12, [100.0], phi1=phi1)
    # SPEC: a slider on a moving guide reports the guide's angle and omega
    for e in res["kinematics"]:
        assert e["links"]["block"]["angle"] == pytest.approx(e["links"]["lever"]["angle"], abs=1e-9)
        assert e["links"]["block"]["omega"] == pytest.approx(e["links"]["lever"]["omega"], abs=1e-9)


@pytest.mark.parametrize("guide", [{"offset": 0.02}, {"offset": -0.015}, {"angle": 3.0}],
                         ids=["offset_left", "offset_right", "turned"])
def test_shaper_moving_guide_offset_and_angle(guide):
    """SPEC: moving guide with `offset` (perpendicular; positive to the left of P->Q like
    the local v axis) or `angle` (relative, deg; the line through P turned ccw)."""
    task = shaper(kinetostatics=True)
    task["mechanism"]["links"]["block"]["guide"].update(guide)
    res, L = run(task), ref_linkage(task)
    roots = rate_roots(L, "ram")
    assert len(roots) == 2
    s = [L.coord("ram", p) for p in roots]
    phi0, phi1 = (roots[0], roots[1]) if s[0] > s[1] else (roots[1], roots[0])  # backward
    working = wrap360(phi1 - phi0)
    check_positions(res, phi0, phi1, working, K=working / (360 - working))
    check_kinematics(res, L, phi0, 12, [100.0], phi1=phi1)
    ext = stroke_load(L, phi0, working, 1500.0, "ram", -1)
    check_kinetostatics(res, L, "crank", [], inertia=True, gravity=True, ext=ext)


def test_inverted_slider_crank_PRR():
    """Rotating guide on the crank itself (block slides along O->A), rod O3-B: a PRR dyad.
    Position 0 given as a crank angle (`zero: 15`), 8 positions, speed as a number (rad/s)."""
    task = {
        "schema": "tmm/1",
        "mechanism": {
            "ground": {"O": [0, 0], "O3": [0.1, 0.0]},
            "links": {
                "crank": {"points": ["O", "A"], "length": 0.12, "mass": 1.0, "J": 0.002},
                "block": {"slider": "B", "guide": {"link": "crank"}, "mass": 0.4, "J": 0.0001},
                "rod": {"points": ["O3", "B"], "length": 0.25, "mass": 1.1, "J": 0.006},
            },
            "assembly": {"B": [0.35, 0.0]},
        },
        "drive": {"link": "crank", "speed": 15.0, "direction": "ccw"},  # rad/s
        "positions": {"zero": 15, "count": 8, "extra": [77.0]},
        "loads": {"gravity": True},
        "kinetostatics": {"inertia": True},
    }
    res, L = run(task), ref_linkage(task)
    assert [g["type"] for g in res["structure"]["groups"]] == ["PRR"]
    close_deg(res["positions"]["phi0"], 15.0)
    check_kinematics(res, L, 15.0, 8, [77.0])
    check_kinetostatics(res, L, "crank", [], inertia=True, gravity=True)


def test_shaper_kinetostatics():
    task = shaper(kinetostatics=True)
    res, L = run(task), ref_linkage(task)
    beta = math.degrees(math.asin(R_SH / D_SH))
    ext = stroke_load(L, 360.0 - beta, 180.0 + 2 * beta, 1500.0, "ram", -1)
    check_kinetostatics(res, L, "crank", [], inertia=True, gravity=True, ext=ext)


# ---------------------------------------------------------------------------------
# class-III group (a triad: ternary base link + three binary links)
# ---------------------------------------------------------------------------------
def triad(kinetostatics=False):
    t = {
        "schema": "tmm/1",
        "mechanism": {
            "ground": {"O": [0, 0], "O2": [0.527, 0.543], "O3": [0.39, -0.284]},
            "links": {
                "crank": {"points": ["O", "A"], "length": 0.1, "mass": 0.6, "J": 0.001},
                "link2": {"points": ["A", "E"], "length": 0.3977, "mass": 1.0, "J": 0.013},
                "link3": {"points": ["O2", "C"], "length": 0.351, "mass": 0.9, "J": 0.009},
                "link4": {"points": ["O3", "D"], "length": 0.3016, "mass": 0.8, "J": 0.006},
                "base": {"points": ["E", "C"], "length": 0.2214, "extra": {"D": [-0.041, -0.048]},
                         "mass": 2.0, "J": 0.01, "com": [0.09, -0.02]},
            },
            "assembly": {"E": [0.493, 0.061], "C": [0.652, 0.215], "D": [0.473, 0.0]},
        },
        "drive": {"link": "crank", "speed": "90 rpm", "direction": "cw"},
        "positions": {"zero": 30, "extra": [200.0]},
    }
    if kinetostatics:
        t["loads"] = {"gravity": True}
        t["kinetostatics"] = {"inertia": True}
    return t


def test_class3_structure_and_kinematics():
    task = triad()
    res, L = run(task), ref_linkage(task)
    st = res["structure"]
    assert (st["n"], st["p5"], st["W"], st["class"]) == (5, 7, 1, 3)
    assert len(st["groups"]) == 1
    g = st["groups"][0]
    assert g["class"] == 3 and sorted(g["links"]) == ["base", "link2", "link3", "link4"]
    close_deg(res["positions"]["phi0"], 30.0)
    check_kinematics(res, L, 30.0, 12, [200.0])


def test_class3_kinetostatics():
    task = triad(kinetostatics=True)
    res, L = run(task), ref_linkage(task)
    check_kinetostatics(res, L, "crank", [], inertia=True, gravity=True)


def test_kinetostatics_positions_list():
    """`kinetostatics.positions` as a list of position numbers: only those entries."""
    task = triad(kinetostatics=True)
    task["kinetostatics"]["positions"] = [0, 3, 7, 12]
    res, L = run(task), ref_linkage(task)
    ks = res["kinetostatics"]
    assert [e["index"] for e in ks] == [0, 3, 7, 12]
    kin = by_index(res["kinematics"])
    for e in ks:
        close_deg(e["phi"], kin[e["index"]]["phi"])
        r = L.forces(e["phi"], inertia=True, gravity=True)
        close(e["balancing_moment"], r["bal"], 1.0, f"kinetostatics[{e['index']}].balancing_moment")
