"""Issue 10, item 7: change points of any linkage are found, warned about with the crank
angle, and the positions next to them are flagged (values without a finite limit null).

Closed forms used: a four-bar with crank a, coupler b, rocker c, ground d is at a change
point when its four links are collinear. With a = 0.1, b = c = 0.2, d = 0.3 (s + l =
0.1 + 0.3 = p + q = 0.2 + 0.2: the Grashof limit) the crank pin at phi = 180 deg is
A = (-0.1, 0), |A O3| = 0.4 = b + c: coupler and rocker lie along the ground line, the
only crank angle where that happens (at phi = 0, |A O3| = 0.2 < b + c and > |b - c|).
A deltoid (kite) with a = d = 0.1 and b = c = 0.25 has its crank pin on the rocker pivot
at phi = 0 (A = O3): coupler and rocker coincide, a change point."""
from __future__ import annotations

import math

import numpy as np
import pytest

from tmm_cli.linkage.kinematics.changepoints import NEAR_DEG, circle_zeros

LIMIT = """\
schema: tmm/1
title: Four-bar on the Grashof limit
mechanism:
  ground:
    O: [0, 0]
    O3: [0.30, 0]
  links:
    crank:   {points: [O, A], length: 0.10, mass: 1.0, J: 0.001}
    coupler: {points: [A, B], length: 0.20, mass: 2.0, J: 0.02}
    rocker:  {points: [O3, B], length: 0.20, mass: 1.5, J: 0.01}
  assembly: {B: [0.2, 0.19]}
drive: {link: crank, speed: 120 rpm, direction: ccw}
positions:
  count: 12
  zero: extreme
  output: rocker
loads:
  gravity: true
  forces:
    - {on: rocker, kind: resistance, stroke: working, moment: 30}
kinetostatics:
  positions: all
  balance: crank
"""

DELTOID = """\
schema: tmm/1
title: Deltoid four-bar
mechanism:
  ground:
    O: [0, 0]
    O3: [0.10, 0]
  links:
    crank:   {points: [O, A], length: 0.10}
    coupler: {points: [A, B], length: 0.25}
    rocker:  {points: [O3, B], length: 0.25}
  assembly: {B: [0.1, 0.25]}
drive: {link: crank, speed: 120 rpm, direction: ccw}
positions: {count: 12, zero: 0, output: rocker}
"""


def _run(tmp_path, text):
    import tmm_cli
    f = tmp_path / "task.yaml"
    f.write_text(text, encoding="utf-8")
    task = tmm_cli.load_task(f)
    from tmm_cli.results import clean
    return clean(tmm_cli.run(task))   # as written to results.json (NaN -> null)


@pytest.fixture(scope="module")
def limit(tmp_path_factory):
    """(task, results as results.json has them) of LIMIT: run once for the tests that read them."""
    import tmm_cli
    d = tmp_path_factory.mktemp("limit")
    res = _run(d, LIMIT)
    return tmm_cli.load_task(d / "task.yaml"), res


@pytest.fixture(scope="module")
def limit_at_zero(tmp_path_factory):
    """LIMIT with position 6 on the change point (zero: 0), as results.json has it: run once for
    the tests of how its warnings are shown."""
    return _run(tmp_path_factory.mktemp("limit0"), LIMIT.replace("zero: extreme", "zero: 0"))


def _cp_warnings(res):
    return [w for w in res["warnings"] if w.startswith("change point at crank angle")]


def test_crank_angles_in_sentences_are_periodic_and_rounded():
    """A sentence names a crank angle in [0, 360) to 0.001 deg, trailing zeros dropped: a
    position found by a root search at a change point (180.0000016) or a probe just short of a
    turn (359.9999995) is not shown with the search's last digits; ru and uk with the decimal
    comma, a list of them separated by semicolons there."""
    from tmm_cli.messages import render
    from tmm_cli.numfmt import crank_deg
    cases = {180.00000160988924: "180", 359.9999995: "0", -1e-9: "0", 360.0: "0", 0.0: "0",
             38.94236: "38.942", 38.9425: "38.943", 12.5: "12.5", 725.25: "5.25", -90.0: "270",
             0.0004: "0", 0.0006: "0.001"}
    for x, want in cases.items():
        assert crank_deg(x) == want, x
    # whole degrees: the integer's own zeros stay (they had been stripped as decimals: '18', '1')
    assert (crank_deg(180.0, 0), crank_deg(100.4, 0), crank_deg(359.7, 0), crank_deg(30.0, 1)) == \
        ("180", "100", "0", "30")
    p = {"phi": 180.00000160988924, "group": "II(2,3)", "links": ["coupler", "rocker"], "near": 1.0,
         "blowup": 10.0}
    assert render("kinematics.change_point", p).startswith("change point at crank angle 180 deg:")
    assert "φ = 180°" in render("kinematics.change_point", p, "ru")
    p = {"group": "II(2,3)", "links": ["rod", "slider"], "angles": [12.5, 359.9999995], "delta": 1e-6}
    assert "crank angle(s) 12.5, 0 deg" in render("kinematics.singular_continuity", p)
    assert "кривошипа 12,5; 0°" in render("kinematics.singular_continuity", p, "ru")
    assert "кривошипа 12,5; 0°" in render("kinematics.singular_continuity", p, "uk")


def test_grashof_limit_change_point_at_the_extreme(limit):
    _, res = limit
    ws = _cp_warnings(res)
    assert len(ws) == 1 and ws[0].startswith("change point at crank angle 180 deg: group II(2,3)")
    # the rocker's extreme position at the change point is added as an extra position
    ext = [e for e in res["kinematics"] if abs(e["phi"] - 180.0) < 1e-3]
    assert ext, [e["phi"] for e in res["kinematics"]]
    for e in ext:
        assert e["near_singular"] is True
        # omega jumps there (0.683 on one side, -0.183 on the other: no limit), so does a_B;
        # epsilon of the rocker tends to 0 from both sides (its analogue is proportional to
        # the distance from 180 deg on either branch): the limit by continuity
        assert e["links"]["rocker"]["omega"] is None and e["points"]["B"]["a"] is None
        assert e["links"]["rocker"]["epsilon"] == pytest.approx(0.0, abs=1e-4)
    far = [e for e in res["kinematics"] if min(abs(e["phi"] - 180.0), 360 - abs(e["phi"] - 180.0)) > NEAR_DEG]
    assert len(far) == len(res["kinematics"]) - len(ext)
    for e in far:
        assert "near_singular" not in e
        assert all(isinstance(e["links"][lk]["epsilon"], float) for lk in e["links"])
    # kinetostatics: the change point is singular, the position next to it flagged
    assert any(abs(a - 180.0) < 1e-6 for a in res["singular"])
    ks = {e["index"]: e for e in res["kinetostatics"]}
    for e in ext:
        assert ks[e["index"]]["near_singular"] is True


def test_extreme_positions_at_change_points_are_the_change_points(tmp_path):
    """A parallelogram four-bar at the Grashof limit (crank = rocker 0.1, coupler = ground 0.3) run
    with the rocker as output: the rocker turns back at the change points 0 and 180 deg (the closure
    keeps its branch, the linkage folds flat there).  Its extreme positions are those change points
    exactly, so K = 1 and the working stroke is not called the quick one; the search's root was
    1.1e-7 deg off 180 (the analogue's sign is round-off there), K = 0.9999999987 and a warning
    that the working stroke is fast."""
    text = ("schema: tmm/1\nmechanism: {ground: {O: [0, 0], O1: [0.3, 0]}, links: {crank: {points: [O, A], "
            "length: 0.1}, rod: {points: [A, B], length: 0.3}, rocker: {points: [O1, B], length: 0.1}}, "
            "assembly: {B: [0.3, 0.1]}}\ndrive: {link: crank, speed: 60 rpm}\npositions: {output: rocker}\n")
    res = _run(tmp_path, text)
    changes = sorted(m["params"]["phi"] for m in res["messages"] if m["code"] == "kinematics.change_point")
    pos = res["positions"]
    assert changes == [0.0, 180.0] and sorted(pos["extreme"]) == changes
    assert pos["K"] == 1.0 and pos["theta"] == 0.0
    assert "positions.quick_working" not in [m["code"] for m in res["messages"]]
    (row,) = res["transmission"]
    assert row["gamma_min"] == 0.0 and row["phi"] in changes


def test_a_change_point_at_the_extreme_position_is_named_once(tmp_path):
    """Grashof limit a + b = c + d (0.1 + 0.3 = 0.25 + 0.15): coupler and rocker collinear at
    phi = 0, also the rocker's extreme position, so the course grid starts at phi0 ~ 5e-7 deg
    (a root found numerically) while the kinematics curve starts at 0. The singular angle is
    one warning "0 deg", not a second one "1e-06 deg" for the same position."""
    text = """\
schema: tmm/1
mechanism:
  ground: {O: [0, 0], O3: [0.15, 0]}
  links:
    crank: {points: [O, A], length: 0.1}
    coupler: {points: [A, B], length: 0.3}
    rocker: {points: [O3, B], length: 0.25}
  assembly: {B: [0.2, 0.25]}
drive: {link: crank, speed: 100 rpm}
"""
    res = _run(tmp_path, text)
    assert abs(res["positions"]["phi0"]) < 1e-5 or abs(res["positions"]["phi0"] - 360) < 1e-5
    sing = [w for w in res["warnings"] if "the velocity equations are singular at crank angle(s)" in w]
    assert len(sing) == 1 and "singular at crank angle(s) 0 deg" in sing[0], sing


def test_grashof_limit_values_kept_near_but_not_at_the_change_point(tmp_path):
    # 2 deg before the change point the values are finite and of the cycle's size
    import tmm_cli
    from tmm_cli.linkage.kinematics import solve
    from tmm_cli.linkage.mechanism import build_mechanism
    f = tmp_path / "task.yaml"
    f.write_text(LIMIT, encoding="utf-8")
    mech = build_mechanism(tmm_cli.load_task(f))
    k = solve(mech, [178.0, 179.5, 180.0 + 1.6e-6], 1.0)
    assert not k.near[0] and k.near[1] and k.near[2]
    # at the change point omega3 jumps (no limit: null); epsilon3 tends to 0 from both sides
    # (the limit by continuity, given)
    assert "omega:rocker" in k.undefined and k.undefined["omega:rocker"].tolist() == [False, False, True]
    assert "epsilon:rocker" not in k.undefined and float(k.a2["rocker"][2]) == pytest.approx(0.0, abs=1e-4)
    # the rocker's analogue i = omega3/omega1 at 178 deg against the closed form of the
    # four-bar: i = a sin(phi - theta2) / (c sin(theta3 - theta2))
    a, c = 0.1, 0.2
    th2, th3 = float(k.angle["coupler"][0]), float(k.angle["rocker"][0])   # rad
    phi = math.radians(178.0)
    assert float(k.a1["rocker"][0]) == pytest.approx(a * math.sin(phi - th2) / (c * math.sin(th3 - th2)), rel=1e-9)


def test_deltoid_change_point_and_branch_jump(tmp_path):
    res = _run(tmp_path, DELTOID)
    ws = _cp_warnings(res)
    assert len(ws) == 1 and ws[0].startswith("change point at crank angle 0 deg")
    e0 = res["kinematics"][0]
    assert e0["phi"] == 0.0 and e0["near_singular"] is True
    assert all("near_singular" not in e for e in res["kinematics"][1:])
    # the coupler and the rocker fold onto each other at 0 deg (A on O3): their sine touches 0
    # there without changing its sign, and the least is that exact point (was 1.7e-9 deg, the
    # line through a limit's -1e-10 and its neighbour)
    (row,) = res["transmission"]
    assert row["gamma_min"] == 0.0 and row["phi"] == 0.0
    # the rocker's curve jumps by 180 deg across the change point (the kite folds on one
    # side, A B and O3 B along the ground line; it opens on the other) - the warning says so
    import tmm_cli
    from tmm_cli.linkage.kinematics import solve
    from tmm_cli.linkage.mechanism import build_mechanism
    mech = build_mechanism(tmm_cli.load_task(tmp_path / "task.yaml"))
    k = solve(mech, [359.99, 0.01], 1.0)
    jump = math.degrees(float(k.angle["rocker"][0] - k.angle["rocker"][1])) % 360.0
    assert jump == pytest.approx(180.0, abs=0.02)
    assert k.near.tolist() == [True, True]


def test_regular_crank_rocker_has_no_change_point(tmp_path):
    text = LIMIT.replace("O3: [0.30, 0]", "O3: [0.29, 0]")   # s + l = 0.39 < p + q = 0.40
    res = _run(tmp_path, text)
    assert _cp_warnings(res) == []
    assert all("near_singular" not in e for e in res["kinematics"])


def test_circle_zeros_closed_forms():
    grid = np.linspace(0.0, 360.0, 721)

    def make(f):
        return f(grid) / np.max(np.abs(f(grid))), (lambda phi, start: float(f(np.array([phi]))[0]) /
                                                     float(np.max(np.abs(f(grid)))))
    # crossing zeros of sin(phi - 37.3): 37.3 and 217.3
    g, F = make(lambda p: np.sin(np.radians(p - 37.3)))
    assert circle_zeros(grid, g, F) == pytest.approx([37.3, 217.3], abs=1e-8)
    # a touching zero of 1 + cos(phi - 100.7) at 280.7 (a V-shaped |.| touching zero too)
    g, F = make(lambda p: 1.0 + np.cos(np.radians(p - 100.7)))
    assert circle_zeros(grid, g, F) == pytest.approx([280.7], abs=1e-4)
    g, F = make(lambda p: np.abs(np.sin(np.radians(p - 123.45) / 2.0)))
    assert circle_zeros(grid, g, F) == pytest.approx([123.45], abs=1e-7)
    # no zero: 2 + sin
    g, F = make(lambda p: 2.0 + np.sin(np.radians(p)))
    assert circle_zeros(grid, g, F) == []


def test_curve_of_the_output_leaves_out_values_without_a_limit(tmp_path):
    # ground 0.2, crank 0.1, coupler 0.3, rocker 0.2 (s + l = 0.4 = p + q): at phi = 0 the
    # pin A = (0.1, 0) is 0.1 = b - c from O3, coupler and rocker fold onto the ground line;
    # it is also the rocker's extreme position, so position 0 and the curve start there
    text = (LIMIT.replace("O3: [0.30, 0]", "O3: [0.20, 0]")
            .replace("coupler: {points: [A, B], length: 0.20", "coupler: {points: [A, B], length: 0.30")
            .replace("B: [0.2, 0.19]", "B: [0.25, 0.19]"))
    res = _run(tmp_path, text)
    ws = _cp_warnings(res)
    assert len(ws) == 1 and ws[0].startswith("change point at crank angle 0 deg")
    assert abs(res["positions"]["phi0"]) < 1e-5
    c = res["kinematics_curve"]
    # at the change point omega3 jumps (0.732 on one side, -2.732 on the other): no limit,
    # null; epsilon3 tends to 0 from both sides: the limit by continuity, given (to 1e-4 of
    # the cycle's ~400 rad/s^2)
    assert c["v"][0] is None and c["v"][-1] is None
    assert c["a"][0] == pytest.approx(0.0, abs=0.1) and c["a"][-1] == pytest.approx(0.0, abs=0.1)
    assert max(abs(x) for x in c["a"]) < 1e3   # |eps| of the rocker stays ~400 rad/s^2
    e0 = res["kinematics"][0]
    assert e0["near_singular"] is True and e0["links"]["rocker"]["omega"] is None
    assert e0["links"]["rocker"]["epsilon"] == pytest.approx(0.0, abs=0.1)


def test_one_continuity_warning_a_group_with_every_runs_angles():
    """A four-bar on the Grashof limit (0.1 + 0.3 = 0.1 + 0.3) is singular at crank angles 0 and
    180 deg; the course's positions, the diagrams' grid and the other runs of the solver each
    found some of them, and each said so in a warning of its own (three of one kind). Now one
    warning for the group names both angles."""
    from tmm_cli import load_task, run
    r = run(load_task({"schema": "tmm/1", "mechanism": {
        "ground": {"O": [0, 0], "O3": [0.3, 0]},
        "links": {"crank": {"points": ["O", "A"], "length": 0.1}, "coupler": {"points": ["A", "B"], "length": 0.3},
                  "rocker": {"points": ["B", "O3"], "length": 0.1}},
        "assembly": {"B": [0.3, 0.1]}}, "drive": {"link": "crank", "speed": "100 rpm"}}))
    found = [m for m in r["messages"] if m["code"] == "kinematics.singular_continuity"]
    assert len(found) == 1 and found[0]["params"]["group"] == "II(2,3)"
    assert found[0]["params"]["angles"] == [0.0, 180.0]
    assert "at crank angle(s) 0, 180 deg" in found[0]["text"]


def test_no_plan_drawn_from_values_that_have_no_limit(limit, tmp_path):
    """At the Grashof-limit four-bar's change point (phi = 180, the rocker's extreme position
    12*) v B, a B, omega of the coupler and rocker have no limit and are null: a plan built
    from them would draw each null as a zero (v B = 0, and aBA tau closing the plan at the
    length of a A, 39.5 mm, beside its computed 3.4e-8 m/s^2: a drawing whose scale is not its
    table's). So no plan is built there, saying which quantities it lacks; at every other
    position each segment is its value at the plan's scale (length x mu = value). The report
    gives the position its notes and no figure."""
    from tmm_cli.plans import build_plan, geometry
    task, res = limit
    geom = geometry(res)
    seen = 0
    for e in res["kinematics"]:
        for kind in ("v", "a"):
            plan = build_plan(kind, e, geom, 0.01)
            if abs(e["phi"] - 180.0) < 1e-3:
                want = {"v B", "v S2", "v S3", "ω coupler", "ω rocker"} | (
                    {"a B", "a S2", "a S3"} if kind == "a" else set())
                assert set(plan.undefined) == want and not plan.vecs, plan.undefined
                continue
            assert not plan.undefined
            for sym, seg, mm, value in plan.rows():
                assert mm * 0.01 == pytest.approx(value, rel=1e-9, abs=1e-12), (e["index"], kind, seg)
                seen += 1
    assert seen > 100
    from tmm_cli.report import render
    out = tmp_path / "r"
    render(res, task, out, {"html"}, "en")
    html = (out / "report.html").read_text(encoding="utf-8")
    i = html.index("Position 12*")
    block = html[i:html.index("Position", i + 10)]
    assert "<svg" not in block and "<figure" not in block
    assert block.count("not drawn at this position: v B, v S2, v S3") == 2
    assert "have no limit by continuity here" in block and "<table" not in block
    # the tables' values there: the continuity extrapolation's round-off of a zero (eps of the
    # coupler and rocker ~1e-7 rad/s^2, their largest ~40) shown as 0, without a sense arrow
    import re
    kin = html[html.index('id="kinematics"'):html.index("Position 12*")]
    rows = re.findall(r"<tr><td>12\*</td>(.*?)</tr>", kin)
    assert len(rows) >= 4 and not any("e-0" in r or "·10⁻" in r for r in rows), rows


def test_no_inertia_load_from_accelerations_that_have_no_limit(limit, tmp_path):
    """At the change point (position 12*, phi = 180) a S2, a S3 have no limit: the coupler's
    and the rocker's inertia forces have none either (null in results.json, '—' in the
    report's table of loads), where the singular solve's accelerations had given the coupler
    1.9e8 N. The crank's inertia (its centre at O: 0) and the weights stay; the velocities of
    the loads on the coupler and the rocker are null, the crank's are its own (0 at O). Every
    number written for that position is of the task's size (below 1e3 N)."""
    task, res = limit
    (e,) = [k for k in res["kinetostatics"] if abs(k["phi"] - 180.0) < 1e-3]
    assert e["inertia"]["crank"] == {"Fx": 0.0, "Fy": 0.0, "M": 0.0}
    for link in ("coupler", "rocker"):
        assert e["inertia"][link]["Fx"] is None and e["inertia"][link]["Fy"] is None
    loads = {ld["name"]: ld for ld in e["loads"]}
    assert loads["Fi2"]["F"] == [None, None] and loads["Fi3"]["F"] == [None, None]
    assert loads["G2"]["F"] == [0.0, -19.62] and loads["G2"]["v"] == [None, None]
    assert loads["G1"]["v"] == [0.0, 0.0]

    def numbers(x):
        if isinstance(x, dict):
            return [v for y in x.values() for v in numbers(y)]
        if isinstance(x, list):
            return [v for y in x for v in numbers(y)]
        return [x] if isinstance(x, float) else []
    assert max(abs(v) for v in numbers(e)) < 1e3
    others = [k for k in res["kinetostatics"] if k is not e]
    assert all(k["inertia"]["coupler"]["Fx"] is not None for k in others)
    from tmm_cli.report import render
    render(res, task, tmp_path / "r", {"html"}, "en")
    html = (tmp_path / "r" / "report.html").read_text(encoding="utf-8")
    i = html.index("<td>12*</td>", html.index("Loads of the positions"))
    row = html[i:html.index("</tr>", i)]
    assert "e+08" not in row and row.count("—") >= 2, row


def test_a_position_placed_at_the_change_point_is_said_to_be_one(tmp_path):
    """With zero: 0 and an extra position at 180 the change point is reached three ways (the
    grid's position 6, the extra one, the rocker's extreme): each is 'a singular or change point
    of the linkage', not 'singular for the balance link' (the balance solve failing first named
    the crank alone), and none carries an inertia force of the coupler."""
    import tmm_cli
    from tmm_cli.results import clean
    f = tmp_path / "task.yaml"
    text = LIMIT.replace("  zero: extreme\n", "  zero: 0\n").replace("  output: rocker\n",
                                                                     "  output: rocker\n  extra: [180]\n")
    assert text.count("extra: [180]") == 1 and "zero: 0" in text
    f.write_text(text, encoding="utf-8")
    res = clean(tmm_cli.run(tmm_cli.load_task(f)))
    at = [e for e in res["kinetostatics"] if abs(e["phi"] - 180.0) < 1e-3]
    assert len(at) >= 2
    codes = {m["params"]["position"]: m["code"] for m in res["messages"] if m["code"].startswith("kinetostatics.")}
    assert all(codes[e["index"]] == "kinetostatics.no_kinematics" for e in at), codes
    assert all(e["inertia"]["coupler"]["Fy"] is None for e in at)


def test_a_change_points_warnings_are_one_head_with_its_items(tmp_path, limit_at_zero):
    """The Grashof-limit four-bar with position 6 on the change point (phi = 180 deg), which is the
    rocker's extreme position too (one position: the extreme found at the change point is the
    change point, not a second position 1e-7 deg from it, as it was), gives seven warnings in
    results.json (kept there, each with its code); the terminal and the report show them as the
    change point's warning with four short items under it -- the continuity limits, the values
    without one, the dead point and the kinetostatics -- and leave out the group's list of
    singular angles (180 only: said by the head).  The kinetostatics of several positions at one
    change point are one item."""
    from tmm_cli.messages import Message, grouped, render_grouped
    res = limit_at_zero
    pos = res["positions"]
    assert pos["extreme"][1] == 180.0 and pos["extreme_index"] == 6 and pos["kinds"] == ["grid"] * 12
    codes = [m["code"] for m in res["messages"]]
    assert codes == ["positions.quick_working", "kinematics.singular_continuity", "kinematics.change_point",
                     "kinematics.by_continuity", "kinematics.no_limit", "kinematics.transmission_dead",
                     "kinetostatics.no_kinematics"]
    assert len(res["warnings"]) == len(codes)
    g = grouped(res["messages"])
    assert [(e["code"], [i["code"] for i in items]) for e, items in g] == [
        ("positions.quick_working", []),
        ("kinematics.change_point", ["kinematics.by_continuity", "kinematics.no_limit",
                                     "kinematics.transmission_dead", "kinetostatics.no_kinematics"])]
    kin = g[1][1][3]
    assert kin["params"]["position"] in (6, [6]) and kin["params"]["balancing"] == "moment"
    en = render_grouped(res, "en")
    assert en[1][0] == res["warnings"][2]                         # the head as results.json has it
    assert en[1][1] == [
        "ε coupler, ε rocker are the limit by continuity (extrapolated from the neighbouring positions "
        "of the same branch)",
        "v B, a B, v S2, a S2, v S3, a S3, ω coupler, ω rocker have no limit by continuity (the values "
        "from either side differ) and are null",
        "a dead point: the transmission angle is 0 (at joint B) and the forces in the group's joints "
        "have no bound; a lever mechanism is designed with a transmission angle of at least 40 deg",
        "kinetostatics, position 6: no balancing moment or reactions"]
    ru = render_grouped(res, "ru")[1][1]
    assert ru[3] == "кинетостатика, положение 6: конечного уравновешивающего момента нет, реакции не выводятся"
    assert render_grouped(res, "uk")[1][1][2].startswith("мертве положення: кут передачі дорівнює нулю (у шарнірі B)")
    one = _run(tmp_path, LIMIT)                       # the extreme position alone: its position, singular
    assert render_grouped(one, "en")[1][1][3] == "kinetostatics, position 12: no balancing moment or reactions"
    # two positions at the change point: their kinetostatics one item
    head = Message("kinematics.change_point", phi=180.0, group="II(2,3)", links=["coupler", "rocker"], near=1.0,
                   blowup=10.0).to_dict()
    kins = [Message("kinetostatics.no_kinematics", position=k, phi=180.0, link="crank", balancing="moment").to_dict()
            for k in (6, 12)]
    both = {"messages": [head] + kins, "warnings": [head["text"]] + [k["text"] for k in kins]}
    assert render_grouped(both, "en")[0][1] == ["kinetostatics, positions 6, 12: no balancing moment or reactions"]
    assert render_grouped(both, "ru")[0][1] == [
        "кинетостатика, положения 6; 12: конечного уравновешивающего момента нет, реакции не выводятся"]


def test_items_go_to_the_head_of_their_angle_and_group():
    """grouped() folds an entry under a change point only where its crank angle shows the same to
    0.001 deg and its group is the head's (an entry without a group: by the angle); two change
    points of one group each take their own; the group's list of singular angles stays where an
    angle of it is no change point (a toggle), and entries without a short form stay as they are."""
    from tmm_cli.messages import Message, grouped

    def m(code, **p):
        return Message(code, **p).to_dict()
    g23, g45 = {"group": "II(2,3)", "links": ["coupler", "rocker"]}, {"group": "II(4,5)", "links": ["rod", "ram"]}
    head = {"near": 1.0, "blowup": 10.0}
    dead = {"joint": "B", "recommended": 40.0}
    lim = {"det": 1e-8, "ill": 1e-3, "quantities": ["v B"]}
    entries = [m("kinematics.singular_continuity", angles=[0.0, 180.0], delta=1e-6, **g23),
               m("kinematics.singular_continuity", angles=[90.0, 180.0], delta=1e-6, **g45),
               m("kinematics.change_point", phi=0.0, **g23, **head),
               m("kinematics.change_point", phi=180.0, **g23, **head),
               m("kinematics.change_point", phi=180.0, **g45, **head),
               m("kinematics.transmission_dead", phi=359.9999999, **g23, **dead),      # at 0
               m("kinematics.transmission_dead", phi=180.0004, **g23, **dead),         # 180 to 0.001
               m("kinematics.transmission_dead", phi=180.002, **g23, **dead),          # not 180
               m("kinematics.no_limit", phi=180.0, **g45, **lim),
               m("kinetostatics.no_kinematics", position=6, phi=180.0, link="crank", balancing="moment"),
               m("kinematics.transmission_low", gamma=20.0, phi=180.0, joint="B", factor=2.9, recommended=40.0,
                 low=30.0, **g23)]
    g = grouped(entries)
    shown = [(e["code"], e["params"].get("phi"), e["params"].get("group"),
              [(i["code"], i["params"].get("group")) for i in items]) for e, items in g]
    assert shown == [
        ("kinematics.singular_continuity", None, "II(4,5)", []),                   # 90: a toggle, not a head
        ("kinematics.change_point", 0.0, "II(2,3)", [("kinematics.transmission_dead", "II(2,3)")]),
        ("kinematics.change_point", 180.0, "II(2,3)", [("kinematics.transmission_dead", "II(2,3)"),
                                                       ("kinetostatics.no_kinematics", None)]),
        ("kinematics.change_point", 180.0, "II(4,5)", [("kinematics.no_limit", "II(4,5)")]),
        ("kinematics.transmission_dead", 180.002, "II(2,3)", []),
        ("kinematics.transmission_low", 180.0, "II(2,3)", [])]
    assert grouped([]) == [] and grouped(entries[-1:]) == [(entries[-1], [])]


@pytest.mark.parametrize("lang", ["en", "ru", "uk"])
def test_the_terminal_prints_a_change_point_as_one_warning_with_its_items(limit_at_zero, lang, monkeypatch, capsys):
    """The run summary prints the change point's warning once, its items indented under it ("  – ",
    a wrapped item's lines under its first word), each line inside 80 columns; the text written
    without Rich is Rich's, character for character."""
    from pathlib import Path as P

    from tmm_cli import summary
    for k in ("COLUMNS", "LINES", "FORCE_COLOR", "TTY_COMPATIBLE"):
        monkeypatch.delenv(k, raising=False)
    res = limit_at_zero
    summary.print_summary(res, [P("out/results.json")], lang)
    plain = capsys.readouterr().out
    real = summary._plain_summary
    monkeypatch.setattr(summary, "_plain_summary", lambda *a: None)               # Rich itself
    summary.print_summary(res, [P("out/results.json")], lang)
    assert capsys.readouterr().out == plain
    monkeypatch.setattr(summary, "_plain_summary", real)
    word = summary.run_words(lang)["warning"]
    lines = plain.splitlines()
    assert sum(s.startswith(f"{word}:") for s in lines) == 2                     # K < 1 and the change point
    items = [k for k, s in enumerate(lines) if s.startswith("  – ")]
    assert len(items) == 4 and all(len(s.rstrip()) <= 80 for s in lines)
    first = items[0]
    assert lines[first + 1].startswith("    ") and not lines[first + 1].startswith("     ")


def test_an_entry_before_its_change_point_stays_alone_and_is_not_shown_twice():
    """grouped() folds the *later* entries of a change point's angle under it (as its docstring
    says): an entry of that angle and group written before the head is shown once, where it
    stands, not both alone and again as the head's item."""
    from tmm_cli.messages import Message, grouped

    def m(code, **p):
        return Message(code, **p).to_dict()
    g23 = {"group": "II(2,3)", "links": ["coupler", "rocker"]}
    dead = {"joint": "B", "recommended": 40.0}
    entries = [m("kinematics.transmission_dead", phi=180.0, **g23, **dead),
               m("kinematics.change_point", phi=180.0, **g23, near=1.0, blowup=10.0),
               m("kinematics.transmission_dead", phi=180.0, **g23, **{**dead, "joint": "C"})]
    g = grouped(entries)
    shown = [(e["code"], [i["params"].get("joint") for i in items]) for e, items in g]
    assert shown == [("kinematics.transmission_dead", []), ("kinematics.change_point", ["C"])]


def test_the_reports_warnings_list_a_change_points_items_under_it(tmp_path, limit_at_zero):
    """The report's list of warnings: the change point's warning with its four items in a list
    inside its own item (the PDF takes the nested list as Typst's), in the report's language."""
    import re as _re

    import tmm_cli
    from tmm_cli.report import render_html
    f = tmp_path / "task.yaml"
    f.write_text(LIMIT.replace("zero: extreme", "zero: 0"), encoding="utf-8")
    task = tmm_cli.load_task(f)
    html, _ = render_html(limit_at_zero, task, tmp_path / "o", "uk")
    sec = html[html.index('id="warnings"'):]
    items = _re.findall(r"<li>([^<]*)<ul>(.*?)</ul></li>", sec, _re.S)
    assert len(items) == 1 and items[0][0].startswith("\u043e\u0441\u043e\u0431\u043b\u0438\u0432\u0435")
    assert items[0][1].count("<li>") == 4 and "\u043f\u043e\u043b\u043e\u0436\u0435\u043d\u043d\u044f 6:" in items[0][1]


def test_warnings_without_a_change_point_are_shown_without_grouping(monkeypatch):
    """render_grouped reads no catalogue where nothing is to be grouped (a JSON run's summary
    starts fast): English shows each entry's text, another language renders it."""
    from tmm_cli import messages
    entries = [messages.Message("answers.note_missing").to_dict()]
    monkeypatch.setattr(messages, "grouped", lambda _e: (_ for _ in ()).throw(AssertionError("grouped")))
    assert messages.render_grouped({"messages": entries}, "en") == [("no value given", [])]
    assert messages.render_grouped({"messages": []}, "en") == []
    assert messages.render_grouped({"messages": entries}, "ru")[0][0] != "no value given"
