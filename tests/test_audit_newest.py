"""Independent checks added by the audit of the newest features (docs/audit-newest.md): the example tasks
synthesis_crank_rocker, press_drive_train, cam_flat and cam_chosen_size, every number below
recomputed here by a few lines of trigonometry or a hand calculation from the task's data
(nothing is read back from an earlier run)."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import tmm_cli

from test_acceptance_cam import Motion

TASKS = Path(__file__).resolve().parent.parent / "tasks"


def _run(name):
    return tmm_cli.run(tmm_cli.load_task(TASKS / f"{name}.yaml"))


# ------------------------------------------------------------------ crank-rocker synthesis
def _gamma(a, b, c, d, phi_deg):
    """Transmission angle of the four-bar O(0,0)-A-B-O1(d,0) with the crank at phi: the diagonal
    O1A by the cosine rule, the angle ABO1 between coupler and rocker, folded to <= 90 deg."""
    f2 = a * a + d * d - 2 * a * d * math.cos(math.radians(phi_deg))
    mu = math.degrees(math.acos((b * b + c * c - f2) / (2 * b * c)))
    return min(mu, 180.0 - mu)


def test_crank_rocker_example_by_hand():
    # task: psi = 40 deg, K = 1.2, rocker c = 0.3, frame d = 0.4
    s = _run("synthesis_crank_rocker")["synthesis"]
    theta = 180.0 * (1.2 - 1) / (1.2 + 1)                                   # 16.3636 deg
    assert s["theta"] == pytest.approx(theta, abs=1e-9) and s["K"] == pytest.approx(1.2, abs=1e-12)
    a, b, c, d = (s["lengths"][k] for k in ("crank", "coupler", "rocker", "frame"))
    assert (c, d) == (0.3, 0.4)
    # the synthesized mechanism re-analysed by hand: the rocker's extremes are where crank and
    # coupler are collinear (O1B at c, OB at b - a folded and b + a stretched)
    r1 = math.degrees(math.acos((d * d + c * c - (b - a) ** 2) / (2 * d * c)))
    r2 = math.degrees(math.acos((d * d + c * c - (b + a) ** 2) / (2 * d * c)))
    assert abs(r1 - r2) == pytest.approx(40.0, abs=1e-9)                    # psi
    # the crank angles at the extremes (angle at O of the triangles): theta between them
    p1 = math.degrees(math.acos((d * d + (b - a) ** 2 - c * c) / (2 * d * (b - a))))
    p2 = math.degrees(math.acos((d * d + (b + a) ** 2 - c * c) / (2 * d * (b + a))))
    assert abs(p1 - p2) == pytest.approx(theta, abs=1e-9)
    # extreme crank angles: stretched along OB2, folded opposite to OB1 (B above the frame line)
    assert sorted(s["extreme"]) == pytest.approx(sorted([p2, 180.0 + p1]), abs=1e-6)
    # least transmission angle: the crank along the frame line (phi = 0 or 180 deg)
    g0, g180 = _gamma(a, b, c, d, 0.0), _gamma(a, b, c, d, 180.0)
    assert s["gamma_min"] == pytest.approx(min(g0, g180), abs=1e-7)
    assert s["gamma_min_phi"] % 360.0 == pytest.approx(0.0 if g0 < g180 else 180.0, abs=1e-4)
    # every listed solution: its own least transmission angle by the same two triangles
    for sol in s["solutions"]:
        ga = [_gamma(sol["crank"], sol["coupler"], sol["rocker"], sol["frame"], p) for p in (0.0, 180.0)]
        assert sol["gamma_min"] == pytest.approx(min(ga), abs=1e-7)
    # gamma over the cycle, point by point
    for phi, g in zip(s["transmission"]["phi"], s["transmission"]["gamma"]):
        assert g == pytest.approx(_gamma(a, b, c, d, phi), abs=1e-9)
    # the construction: C1, C2 on the rocker's circle (radius c about O1), |OC1| = b - a,
    # |OC2| = b + a; the circle through O, C1, C2 has the chord C1C2 seen under theta from O:
    # R = |C1C2| / (2 sin theta), and its centre is at R from each of the three points
    con = s["construction"]
    O, O1, C1, C2 = (np.array(con[k]) for k in ("O", "O1", "C1", "C2"))
    assert np.linalg.norm(C1 - O1) == pytest.approx(c, rel=1e-9)
    assert np.linalg.norm(C2 - O1) == pytest.approx(c, rel=1e-9)
    assert sorted([np.linalg.norm(C1 - O), np.linalg.norm(C2 - O)]) == pytest.approx([b - a, b + a], rel=1e-9)
    R = np.linalg.norm(C1 - C2) / (2 * math.sin(math.radians(theta)))
    assert con["circle"]["radius"] == pytest.approx(R, rel=1e-9)
    ctr = np.array(con["circle"]["centre"])
    for P in (O, C1, C2):
        assert np.linalg.norm(P - ctr) == pytest.approx(R, rel=1e-9)


# ------------------------------------------------------------------ drive train (press)
def test_press_drive_train_by_hand():
    """Task: pair 18/36, pair 20/44, scheme A chosen; motor 1440 rpm, crank 100 rpm cw.
    u = (-36/18)(-44/20) u_A = 4.4 u_A = 14.4 -> u_A = 14.4/4.4 = 3.2727 = 1 + z3/z1."""
    r = _run("press_drive_train")
    d = r["drive_train"]
    st = d["stages"]
    assert [s["z"] for s in st[:2]] == [[18, 36], [20, 44]]
    z1, z2, z3 = st[2]["z"]
    u = (-36 / 18) * (-44 / 20) * (1 + z3 / z1)                              # by hand, from the teeth
    assert d["ratio"] == pytest.approx(u, rel=1e-12)
    assert [s["ratio"] for s in st] == pytest.approx([-2.0, -2.2, 1 + z3 / z1], rel=1e-12)
    assert d["required"] == pytest.approx(1440 / 100, rel=1e-12)
    assert d["ratio_error"] == pytest.approx((u - 14.4) / 14.4, abs=1e-12)
    assert d["split"][0]["ratio"] == pytest.approx(14.4 / 4.4, rel=1e-12)
    # scheme A conditions written out: coaxial, assembly with k = 3, adjacency, no undercut
    assert z3 == z1 + 2 * z2 and (z1 + z3) % 3 == 0
    assert (z1 + z2) * math.sin(math.pi / 3) > z2 + 2 and min(z1, z2) >= 17
    # shaft speeds: the motor cw (the crank cw, u > 0), each shaft the previous / stage ratio
    wm = -1440 * 2 * math.pi / 60
    w = [wm, wm / -2.0, wm / -2.0 / -2.2, wm / u]
    assert d["shafts"] == pytest.approx(w, rel=1e-12)
    for s, wi, wo in zip(st, w, w[1:]):
        assert s["omega_in"] == pytest.approx(wi, rel=1e-12) and s["omega_out"] == pytest.approx(wo, rel=1e-12)
    # the crank turns at 100 rpm: motor speed / ratio is the drive's speed
    assert w[-1] == pytest.approx(-100 * 2 * math.pi / 60, rel=1e-12)
    assert r["drive"]["omega"] == pytest.approx(w[-1], rel=1e-12)
    # satellite by Willis with the carrier held: omega_2 - omega_H = -(z1/z2)(omega_1 - omega_H)
    rel = -(z1 / z2) * (w[2] - w[3])
    assert st[2]["omega_carrier"] == pytest.approx(w[3], rel=1e-12)
    assert st[2]["omega_satellite_rel"] == pytest.approx(rel, rel=1e-12)
    assert st[2]["omega_satellite"] == pytest.approx(w[3] + rel, rel=1e-12)
    # the listed sets: teeth is the sum of the teeth, size the largest wheel, ratio from the teeth
    for cand in d["candidates"]:
        zz = cand["z"]
        assert cand["teeth"] == sum(sum(x) for x in zz) and cand["size"] == max(max(x) for x in zz)
        assert cand["ratio"] == pytest.approx((-zz[0][1] / zz[0][0]) * (-zz[1][1] / zz[1][0])
                                              * (1 + zz[2][2] / zz[2][0]), rel=1e-12)
    assert d["candidates"][0]["z"][2] == [z1, z2, z3]
    # the velocity plan reads the same speeds (motor, shafts, satellite, carrier)
    assert d["velocity_plan"]["omega_plan"] == pytest.approx(w[:3] + [w[3] + rel, w[3]], rel=1e-9)


# ------------------------------------------------------------------ flat-faced follower
def test_flat_follower_example_profile_and_curvature_by_hand():
    """Task cam_flat: h = 20 mm, cosine rise 120, far dwell 30, sine return 120, ccw.
    The face is at r0 + s from O, the contact point ds/dphi along it; the profile's radius
    of curvature is rho = r0 + s + s'' (checked also from the profile's own geometry)."""
    c = _run("cam_flat")["cam"]
    mo = Motion(0.02, {"rise": 120, "far_dwell": 30, "return": 120}, {"rise": "cosine", "return": "sine"})
    phi = np.radians(np.arange(360.0))
    s, s1, s2 = mo.at(phi)
    r0 = c["r0"]
    assert c["s"] == pytest.approx(list(s), abs=1e-15) and c["ds"] == pytest.approx(list(s1), abs=1e-15)
    # the contact point (ds, r0 + s) in the follower's frame, turned back by -phi (ccw cam)
    x, y = s1, r0 + s
    P = np.column_stack([x * np.cos(-phi) - y * np.sin(-phi), x * np.sin(-phi) + y * np.cos(-phi)])
    assert np.asarray(c["working_profile"]) == pytest.approx(P, abs=1e-12)
    # rho_min and where: min of r0 + s + s'' on a dense grid
    g = np.linspace(0, 2 * math.pi, 720001)
    sg, _, s2g = mo.at(g)
    rho = r0 + sg + s2g
    assert c["rho_min"] == pytest.approx(float(rho.min()), abs=1e-9)
    assert c["rho_min"] == pytest.approx(0.005, abs=1e-12)                  # r0 is the least one
    assert c["rho_min_phi"] == pytest.approx(math.degrees(g[np.argmin(rho)]), abs=0.01)
    # second method: the curvature of the profile polyline (circle through three neighbours)
    Q = np.asarray(c["working_profile"])
    A, B, C = np.roll(Q, 1, axis=0), Q, np.roll(Q, -1, axis=0)
    ab, bc, ca = (np.linalg.norm(A - B, axis=1), np.linalg.norm(B - C, axis=1), np.linalg.norm(C - A, axis=1))
    cross = np.abs((B - A)[:, 0] * (C - A)[:, 1] - (B - A)[:, 1] * (C - A)[:, 0])
    R3 = ab * bc * ca / (2 * cross)
    smooth = np.abs(np.diff(np.r_[s2[-1], s2])) < 1e-3                     # away from the s'' jumps
    smooth &= np.roll(smooth, -1)
    assert R3[smooth] == pytest.approx((r0 + s + s2)[smooth], rel=2e-3, abs=2e-5)
    # the face covers the contact points: ds/dphi from its least (sine return, -2h/P) to its
    # largest (cosine rise, h pi / (2P))
    Pp = math.radians(120)
    assert c["face_width"] == pytest.approx(0.02 * math.pi / (2 * Pp) + 2 * 0.02 / Pp, rel=1e-12)
    assert c["max_pressure_angle"] == 0 and max(c["pressure_angle"]) == 0 == min(c["pressure_angle"])
    # r0_design rounds r0 up to a whole millimetre
    assert c["r0_design"] == pytest.approx(math.ceil(r0 * 1000 - 1e-9) / 1000, abs=1e-15)


# ------------------------------------------------------------------ chosen-size cam
def test_chosen_size_example_by_hand():
    """Task cam_chosen_size: h = 30 mm, sine rise 120, far dwell 30, cosine return 120, e = 0,
    chosen r0 = 40 mm, allowed 30 deg: tan(alpha) = |s'| / (r0 + s); r0_min = max(|s'|/tan 30 - s)."""
    c = _run("cam_chosen_size")["cam"]
    mo = Motion(0.03, {"rise": 120, "far_dwell": 30, "return": 120}, {"rise": "sine", "return": "cosine"})
    r0 = 0.04
    assert c["r0"] == r0
    x = np.linspace(0, 1, 400001)
    amax = {}
    for which in ("rise", "return"):
        s, s1, _ = mo.phase(which, x)
        amax[which] = float(np.degrees(np.arctan(np.abs(s1) / (r0 + s))).max())
        if which == "rise":
            i = int(np.argmax(np.abs(s1) / (r0 + s)))
            assert c["max_pressure_angle_phi"] == pytest.approx(120 * x[i], abs=0.01)
    assert c["max_pressure_angle_rise"] == pytest.approx(amax["rise"], abs=1e-6)
    assert c["max_pressure_angle_return"] == pytest.approx(amax["return"], abs=1e-6)
    assert c["max_pressure_angle"] == pytest.approx(max(amax.values()), abs=1e-6)
    assert c["max_pressure_angle"] < 30
    # the least base radius for 30 deg, central follower, by hand on the grid
    t30 = math.tan(math.radians(30))
    need = max(float(np.max(np.abs(mo.phase(w, x)[1]) / t30 - mo.phase(w, x)[0])) for w in ("rise", "return"))
    assert c["r0_min"] == pytest.approx(need, rel=1e-6)
    assert c["r0_min"] == pytest.approx(0.03644, abs=1e-5)                # the task's comment: 36.44 mm
    # on this example the least radius of curvature is the base circle's (the dwell), so the
    # roller is min(0.7 r0, 0.4 r0) = 0.4 r0; the curvature along the rise is checked below
    assert c["rho_min"] == pytest.approx(r0, rel=1e-12) and c["rho_min_phi"] == 0.0
    assert c["roller"] == pytest.approx(0.4 * r0, rel=1e-12)


def _polar_rho(mo, r0):
    """Radius of curvature of the pitch curve r(phi) = r0 + s (central follower), by the polar
    formula rho = (r^2 + r'^2)^1.5 / (r^2 + 2 r'^2 - r r'') on a dense grid; concave parts skipped."""
    g = np.linspace(0, 2 * math.pi, 720001)
    s, s1, s2 = mo.at(g)
    r = r0 + s
    den = r * r + 2 * s1 * s1 - r * s2
    rho = np.where(den > 0, (r * r + s1 * s1) ** 1.5 / np.where(den > 0, den, 1.0), np.inf)
    return rho, np.degrees(g)


@pytest.mark.parametrize("r0", [0.04, 0.06])
def test_chosen_size_curvature_inside_the_rise_by_hand(r0):
    # a short rise (60 deg): the pitch curve is sharpest inside the rise, not on the base circle
    ph = {"rise": 60, "far_dwell": 30, "return": 90}
    c = tmm_cli.run(tmm_cli.load_task({"schema": "tmm/1", "cam": {
        "follower": "translating", "stroke": 0.03, "offset": 0, "r0": r0, "phases": ph,
        "laws": {"rise": "sine", "return": "cosine"}, "pressure_angle": 60, "roller": "auto"}}))["cam"]
    rho, deg = _polar_rho(Motion(0.03, ph, {"rise": "sine", "return": "cosine"}), r0)
    assert rho.min() < r0
    assert c["rho_min"] == pytest.approx(float(rho.min()), rel=1e-8)
    assert c["rho_min_phi"] == pytest.approx(float(deg[np.argmin(rho)]), abs=0.01)
    assert c["roller"] == pytest.approx(min(0.7 * c["rho_min"], 0.4 * r0), rel=1e-12)


# ------------------------------------------------------------------ slotted lever, shaper: construction
@pytest.mark.parametrize("name", ["synthesis_slotted_lever", "synthesis_shaper"])
def test_slotted_construction_by_hand(name):
    """At the extremes the slotted link O1B is tangent to the crank circle at the block A:
    OA is perpendicular to O1A (so A . O1 = r^2), and O1, A, B lie on one line; the crank
    angles there are the extreme positions found by the analysis; theta = 2 asin(r/f)."""
    r = _run(name)
    s = r["synthesis"]
    con, rr, f, L = s["construction"], s["lengths"]["crank"], s["lengths"]["frame"], s["lengths"]["rocker"]
    O1 = np.array(con["O1"])
    assert np.linalg.norm(O1) == pytest.approx(f, rel=1e-12)
    assert 2 * math.degrees(math.asin(rr / f)) == pytest.approx(s["theta"], abs=1e-9)
    ext = sorted(s["extreme"])
    pts = sorted([np.array(con["A1"]), np.array(con["A2"])], key=lambda p: math.degrees(math.atan2(p[1], p[0])) % 360)
    for A, B, e in zip(pts, sorted([np.array(con["B1"]), np.array(con["B2"])],
                                   key=lambda p: math.degrees(math.atan2(p[1] - O1[1], p[0] - O1[0])) % 360), ext):
        assert np.linalg.norm(A) == pytest.approx(rr, rel=1e-12)
        assert float(A @ O1) == pytest.approx(rr * rr, rel=1e-9)                 # tangency
        assert A == pytest.approx([rr * math.cos(math.radians(e)), rr * math.sin(math.radians(e))], abs=1e-12)
    for A, B in ((con["A1"], con["B1"]), (con["A2"], con["B2"])):
        u, v = np.array(A) - O1, np.array(B) - O1
        assert abs(u[0] * v[1] - u[1] * v[0]) == pytest.approx(0.0, abs=1e-12)  # O1, A, B collinear
        assert np.linalg.norm(v) == pytest.approx(L, rel=1e-12)
    if name == "synthesis_shaper":
        # the ram's extremes C1, C2 on the guide, H apart, on the link's line
        C1, C2 = np.array(con["C1"]), np.array(con["C2"])
        assert np.linalg.norm(C2 - C1) == pytest.approx(s["H"], rel=1e-12)
        assert C1[1] == C2[1] == pytest.approx(con["guide_y"], abs=1e-15)
        for B, C in ((con["B1"], C1), (con["B2"], C2)):
            u, v = np.array(B) - O1, C - O1
            assert abs(u[0] * v[1] - u[1] * v[0]) == pytest.approx(0.0, abs=1e-12)


# ------------------------------------------------------------------ slider-crank synthesis: the rest
@pytest.mark.parametrize("name", ["synthesis_offset_slider_crank", "synthesis_slider_crank"])
def test_slider_crank_construction_transmission_by_hand(name):
    """O at the origin, guide y = -e: B1 (folded) at sqrt((l - r)^2 - e^2), B2 (stretched) at
    sqrt((l + r)^2 - e^2), H = B2 - B1; the crank along OB2 and opposite to OB1 at the extremes;
    gamma(phi) = 90 - asin(|r sin(phi) + e| / l); the circle through O, B1, B2 has
    R = H / (2 sin theta) (none for theta = 0)."""
    s = _run(name)["synthesis"]
    r, l, e = s["lengths"]["crank"], s["lengths"]["rod"], s["lengths"]["offset"]
    x1, x2 = math.sqrt((l - r) ** 2 - e * e), math.sqrt((l + r) ** 2 - e * e)
    con = s["construction"]
    assert con["B1"] == pytest.approx([x1, -e], abs=1e-12) and con["B2"] == pytest.approx([x2, -e], abs=1e-12)
    assert x2 - x1 == pytest.approx(s["H"], rel=1e-9)
    e2 = math.degrees(math.atan2(-e, x2)) % 360
    e1 = math.degrees(math.atan2(e, -x1)) % 360
    assert sorted(s["extreme"]) == pytest.approx(sorted([e1, e2]), abs=1e-6)
    theta = (e2 - e1) % 360 - 180                                           # the idle less the working
    assert abs(theta) == pytest.approx(s["theta"], abs=1e-6)
    for phi, g in zip(s["transmission"]["phi"], s["transmission"]["gamma"]):
        assert g == pytest.approx(90 - math.degrees(math.asin(abs(r * math.sin(math.radians(phi)) + e) / l)), abs=1e-9)
    assert s["gamma_min"] == pytest.approx(90 - math.degrees(math.asin((r + e) / l)), abs=1e-9)
    assert s["gamma_min_phi"] == pytest.approx(90.0, abs=1e-4)
    if s["theta"] > 1e-9:
        assert con["circle"]["radius"] == pytest.approx(s["H"] / (2 * math.sin(math.radians(s["theta"]))), rel=1e-9)
    else:
        assert con["circle"] is None


def test_shaper_and_slotted_transmission_by_hand():
    # shaper: the ram's block presses along the guide on the slotted link O1A produced; the
    # transmission angle is 90 deg less the link's deviation from the normal to the guide
    s = _run("synthesis_shaper")["synthesis"]
    r, O1 = s["lengths"]["crank"], np.array(s["construction"]["O1"])
    for phi, g in zip(s["transmission"]["phi"], s["transmission"]["gamma"]):
        A = r * np.array([math.cos(math.radians(phi)), math.sin(math.radians(phi))])
        u = A - O1
        assert g == pytest.approx(90 - math.degrees(math.atan(abs(u[0] / u[1]))), abs=1e-9)
    assert s["gamma_min"] == pytest.approx(90 - s["theta"] / 2, abs=1e-9)
    # slotted lever: the block's force is normal to the slot, the slot moves normal to itself
    s = _run("synthesis_slotted_lever")["synthesis"]
    assert s["transmission"]["gamma"] == pytest.approx([90.0] * len(s["transmission"]["gamma"]), abs=1e-9)


def test_synthesis_examples_drive_speed_by_hand():
    # working stroke over pi + theta of the crank: omega = v_w (pi + theta) / (stroke)
    r = _run("synthesis_crank_rocker")
    th, psi = math.radians(r["synthesis"]["theta"]), math.radians(40.0)
    assert r["drive"]["omega"] == pytest.approx(1.2 * (math.pi + th) / psi, rel=1e-9)      # ccw
    assert r["drive"]["n"] == pytest.approx(r["drive"]["omega"] * 30 / math.pi, rel=1e-12)
    r = _run("synthesis_shaper")
    th = math.radians(r["synthesis"]["theta"])
    assert r["drive"]["omega"] == pytest.approx(-0.4 * (math.pi + th) / 0.4, rel=1e-9)      # cw, H = 0.4
    # mean output speed: the slider covers 2H a turn, omega = pi v / H
    r = _run("synthesis_offset_slider_crank")
    assert r["drive"]["omega"] == pytest.approx(math.pi * 0.5 / 0.2, rel=1e-9)


def test_chosen_size_construction_by_hand():
    """The diagram of the chosen cam (ccw, central follower): B = B0 + s up the follower's axis,
    D = B moved by ds/dphi across it (to the left on the rise, to the right on the return);
    the binding tangent at 30 deg to the axis touches D where |s'|/tan 30 - s is largest and
    crosses the axis r0_min below B0 (the least cam's centre)."""
    c = _run("cam_chosen_size")["cam"]
    con = c["construction"]
    mo = Motion(0.03, {"rise": 120, "far_dwell": 30, "return": 120}, {"rise": "sine", "return": "cosine"})
    r0 = 0.04
    assert con["O"] == [0.0, 0.0] and con["B0"] == pytest.approx([0.0, r0], abs=1e-15)
    for which in ("rise", "return"):
        phi = np.radians(np.asarray(con[f"phi_{which}"]))
        s, s1, _ = mo.at(phi)
        assert np.asarray(con[f"B_{which}"]) == pytest.approx(np.column_stack([0 * s, r0 + s]), abs=1e-12)
        assert np.asarray(con[f"D_{which}"]) == pytest.approx(np.column_stack([-s1, r0 + s]), abs=1e-12)
    (t,) = con["tangents"]
    x = np.linspace(0, 1, 400001)
    s, s1, _ = mo.phase("rise", x)
    k = int(np.argmax(np.abs(s1) / math.tan(math.radians(30)) - s))
    assert t["phi"] == pytest.approx(120 * x[k], abs=0.01)
    p, dvec = np.array(t["point"]), np.array(t["direction"])
    ps, ps1, _ = mo.at(np.radians([t["phi"]]))
    assert p == pytest.approx([-ps1[0], r0 + ps[0]], abs=1e-12)
    assert abs(dvec[1]) / np.linalg.norm(dvec) == pytest.approx(math.cos(math.radians(30)), rel=1e-12)
    y_axis = p[1] - p[0] * dvec[1] / dvec[0]                    # where the tangent crosses x = 0
    assert r0 - y_axis == pytest.approx(c["r0_min"], rel=1e-9)
    assert r0 - y_axis == pytest.approx(float(np.max(np.abs(s1) / math.tan(math.radians(30)) - s)), rel=1e-6)


def test_press_velocity_plan_points_by_hand():
    """Drawing module m = 1 mm, the motor's axis at y = 0: pitch point P1 at m z1/2 = 9 mm,
    shaft 2 at m (18 + 36)/2 = 27 mm, P2 10 mm above it, shaft 3 at 27 + m (20 + 44)/2 = 59 mm;
    scheme A [44, 28, 100] about shaft 3: A at +22 mm, the satellite's centre C at +36 mm, the
    fixed ring's mesh F at +50 mm. Speeds v = omega (y - y_axis) of the wheel that owns the point."""
    d = _run("press_drive_train")["drive_train"]
    p = d["velocity_plan"]
    w = d["shafts"]
    ref = {"P1": (0.009, w[0] * 0.009), "O2": (0.027, 0.0), "P2": (0.037, w[1] * 0.010),
           "O3": (0.059, 0.0), "A3": (0.081, w[2] * 0.022), "C3": (0.095, w[3] * 0.036), "F3": (0.109, 0.0)}
    got = {q["name"]: (q["y"], q["v"]) for q in p["points"]}
    assert set(got) == set(ref)
    for k, (y, v) in ref.items():
        assert got[k] == pytest.approx((y, v), rel=1e-12, abs=1e-15)
    # the satellite's velocities: zero at F (on the fixed ring), its centre's at C
    sat = d["stages"][2]["omega_satellite"]
    assert sat * (0.095 - 0.109) == pytest.approx(got["C3"][1], rel=1e-12)
    assert p["mu_omega"] == pytest.approx(p["mu_v"] / (p["H"] * p["mu_l"]), rel=1e-12)
