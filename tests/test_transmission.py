"""The transmission angle of each dyad (results `transmission`, tmm_cli/linkage/transmission.py):
its least over the cycle against closed forms (the slider-crank's arccos((r + e)/l), the
four-bar's cosine rule with the crank along the frame line), against the independent
reference solver of the acceptance tests (the forging six-bar: an RRR dyad at a ternary
rocker and an RRP dyad), against the synthesis's own minimisation, a dead point, its
exact derivative against finite differences, and the warning below 20 deg."""
from __future__ import annotations

import copy
import math

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

import tmm_cli
from acceptance_util import Linkage
from test_acceptance_linkage import C4, L4, O1_4, R4, fourbar, sixbar, slider_crank


def run(task):
    return tmm_cli.run(tmm_cli.load_task(copy.deepcopy(task)))


def codes(res):
    return [m["code"] for m in res["messages"]]


@pytest.mark.parametrize("r,l,e", [(0.1, 0.4, 0.0), (0.1, 0.4, 0.05), (0.12, 0.42, -0.04), (0.1, 0.3, 0.15)])
def test_slider_crank_least_is_arccos_r_plus_e_over_l(r, l, e):
    """The rod is steepest to the guide with the crank square to it on the far side of the
    offset: sin(90 - gamma_min) = (r + |e|) / l, at crank angle 90 or 270 deg (guide along x
    through (0, e))."""
    res = run(slider_crank(r, l, [0, e], 0, [0.5, e]))
    (row,) = res["transmission"]
    assert row["type"] == "RRP" and row["links"] == ["rod", "slider"] and row["joint"] == "B"
    assert row["gamma_min"] == pytest.approx(math.degrees(math.acos((r + abs(e)) / l)), abs=1e-9)
    assert row["phi"] == pytest.approx(270.0 if e >= 0 else 90.0, abs=1e-6) or (e == 0 and row["phi"] == 90.0)
    assert ("kinematics.transmission_low" in codes(res)) == (row["gamma_min"] < 20.0)


def test_fourbar_least_by_the_cosine_rule():
    """A crank-rocker's coupler-rocker angle is least with the crank along the frame line
    (towards O1 or away from it): cos mu = (b^2 + c^2 - (d -+ a)^2) / (2bc), the acute
    angle of the two."""
    res = run(fourbar())
    (row,) = res["transmission"]
    d = math.hypot(*O1_4)
    th = math.degrees(math.atan2(O1_4[1], O1_4[0]))
    cands = []
    for q, at in ((d - R4, th), (d + R4, th + 180.0)):
        mu = math.degrees(math.acos((L4 * L4 + C4 * C4 - q * q) / (2 * L4 * C4)))
        cands.append((min(mu, 180.0 - mu), at % 360.0))
    g, at = min(cands)
    assert row["type"] == "RRR" and row["links"] == ["rod", "rocker"] and row["joint"] == "B"
    assert row["gamma_min"] == pytest.approx(g, abs=1e-9)
    assert row["phi"] == pytest.approx(at, abs=1e-6)


def _ref_gamma(L: Linkage, phi: float) -> tuple[float, float]:
    """(RRR at B: rod-rocker, RRP at D: link4-guide) transmission angles, deg, of the
    six-bar from the reference solver's points."""
    P, _ = L.state(phi)
    u, v = P["A"] - P["B"], P["O1"] - P["B"]
    rrr = math.degrees(math.asin(min(1.0, abs(u[0] * v[1] - u[1] * v[0]) / (np.hypot(*u) * np.hypot(*v)))))
    r = P["D"] - P["K"]
    rrp = 90.0 - math.degrees(math.asin(min(1.0, abs(r[0]) / np.hypot(*r))))     # the rod off the vertical guide
    return rrr, rrp


def test_forging_sixbar_against_the_reference_solver():
    """The forging six-bar (a ternary rocker O1-B-K, then link4 and the slider on a vertical
    guide): each dyad's least found by scanning the reference's points every 0.25 deg and
    a bounded Brent search on them."""
    task = sixbar()
    res = run(task)
    L = Linkage(copy.deepcopy(task))
    rows = {r["group"]: r for r in res["transmission"]}
    assert [r["type"] for r in res["transmission"]] == ["RRR", "RRP"]
    for k, name in enumerate(("II(2,3)", "II(4,5)")):
        grid = np.arange(0.0, 360.0, 0.25)
        vals = np.array([_ref_gamma(L, p)[k] for p in grid])
        i = int(np.argmin(vals))
        m = minimize_scalar(lambda p: _ref_gamma(L, p)[k], bounds=(grid[i] - 0.25, grid[i] + 0.25),
                            method="bounded", options={"xatol": 1e-9})
        assert rows[name]["gamma_min"] == pytest.approx(m.fun, abs=1e-8), name
        assert rows[name]["phi"] == pytest.approx(m.x % 360.0, abs=2e-3), name
        assert rows[name]["gamma_min"] <= m.fun + 1e-10             # the least, not a point near it


def _closed_form(sy: dict) -> float:
    """The least transmission angle of a generated mechanism from its lengths: the offset
    slider-crank's arccos((r + e) / l); a crank-rocker's cosine rule with the crank along the
    frame line (the acute angle of the two); the shaper's 90 - psi / 2 (sin(psi/2) = r / d)."""
    L = sy["lengths"]
    if "rod" in L:
        return math.degrees(math.acos((L["crank"] + abs(L.get("offset", 0.0))) / L["rod"]))
    if "guide_height" in L:
        return 90.0 - math.degrees(math.asin(L["crank"] / L["frame"]))
    a, b, c, d = L["crank"], L["coupler"], L["rocker"], L["frame"]
    mus = [math.degrees(math.acos((b * b + c * c - q * q) / (2 * b * c))) for q in (d - a, d + a)]
    return min(min(m, 180.0 - m) for m in mus)


@pytest.mark.parametrize("name", ["synthesis_offset_slider_crank", "synthesis_crank_rocker", "synthesis_path",
                                  "synthesis_shaper"])
def test_generated_mechanisms_least_is_the_closed_form(name, shared_once):
    """A generated slider-crank, crank-rocker or shaper (its ram's PRP dyad): the dyad's least
    and the synthesis's gamma_min (one computation) are the closed form of the generated
    lengths."""
    from pdf_extent import results
    _, res = results(shared_once, name)          # as tmm run computes them, once a session
    rows = [r for r in res["transmission"] if r["type"] != "RPR"]          # the shaper's slot: 90 (below)
    assert all(r["gamma_min"] == 90.0 for r in res["transmission"] if r["type"] == "RPR")
    (row,) = rows
    want = _closed_form(res["synthesis"])
    assert row["gamma_min"] == pytest.approx(want, abs=1e-8)
    assert res["synthesis"]["gamma_min"] == pytest.approx(want, abs=1e-8)
    assert (row["phi"] - res["synthesis"]["gamma_min_phi"] + 180.0) % 360.0 - 180.0 == pytest.approx(0.0, abs=1e-9)


def test_derivative_is_the_finite_difference_of_the_sine():
    """sine()'s d(sin gamma)/dphi from the velocity analogues against central differences."""
    from tmm_cli.linkage import transmission as T
    from tmm_cli.linkage.context import build
    from tmm_cli.linkage.kinematics import solve
    task = tmm_cli.load_task(copy.deepcopy(sixbar()))
    lk = build(task)
    ds = T.dyads(lk.mechanism, lk.structure.groups)
    phi = np.array([3.0, 47.5, 121.0, 200.0, 333.3])
    h = 1e-4
    kin, kp, km = (solve(lk.mechanism, phi + o) for o in (0.0, h, -h))
    for d in ds:
        s, dsd = T.sine(d, kin)
        fd = (T.sine(d, kp)[0] - T.sine(d, km)[0]) / math.radians(2 * h)
        assert np.allclose(dsd, fd, rtol=1e-6, atol=1e-8), d.kind


def test_dead_point_is_zero_at_the_change_point():
    """A four-bar on Grashof's limit (a = c = 0.1, b = d = 0.3) folds flat: coupler and rocker
    collinear at its change points, where the least is 0."""
    task = {"schema": "tmm/1",
            "mechanism": {"ground": {"O": [0, 0], "O1": [0.3, 0]},
                          "links": {"crank": {"points": ["O", "A"], "length": 0.1},
                                    "rod": {"points": ["A", "B"], "length": 0.3},
                                    "rocker": {"points": ["O1", "B"], "length": 0.1}},
                          "assembly": {"B": [0.3, 0.1]}},
            "drive": {"link": "crank", "speed": "60 rpm"},
            "positions": {"output": "rocker"}}
    res = run(task)
    (row,) = res["transmission"]
    assert row["gamma_min"] == pytest.approx(0.0, abs=1e-6)
    change = [m["params"]["phi"] for m in res["messages"] if m["code"] == "kinematics.change_point"]
    assert change and min(abs((row["phi"] - p + 180.0) % 360.0 - 180.0) for p in change) < 1e-4
    # said as a dead point, not as 1/sin 0 (was: 'to 99999999999999990380...0.0 times', 301 digits)
    (m,) = [m for m in res["messages"] if m["code"].startswith("kinematics.transmission_")]
    assert m["code"] == "kinematics.transmission_dead" and "dead point" in m["text"] and "times" not in m["text"]
    assert len(m["text"]) < 300 and m["params"]["phi"] == row["phi"]


def test_a_dead_point_where_the_sine_touches_zero_is_zero():
    """A slider-crank whose rod equals its crank: at 90 deg the rod folds onto the crank, square to
    the guide (gamma = 0 exactly), and sin gamma touches 0 there without changing sign -- the
    least was its round-off, 3.5e-15 deg, printed so in the run's summary; at or below DEAD a
    least is a dead point, and 0."""
    res = run(slider_crank(0.1, 0.1, [0, 0], 0, [0.2, 0]))
    (row,) = res["transmission"]
    assert row["gamma_min"] == 0.0 and row["phi"] in (90.0, 270.0)
    assert "kinematics.transmission_dead" in codes(res)


def test_warning_below_20_deg_names_the_group_and_angle():
    """A slider-crank with l = 1.05 r: gamma_min = arccos(1/1.05) = 17.75 deg, warned with the
    group, the angle and 1/sin gamma; none at 21 deg."""
    res = run(slider_crank(0.1, 0.105, [0, 0], 0, [0.2, 0]))
    (m,) = [m for m in res["messages"] if m["code"] == "kinematics.transmission_low"]
    g = math.degrees(math.acos(1 / 1.05))
    assert m["params"]["group"] == "II(2,3)" and m["params"]["gamma"] == pytest.approx(g, abs=1e-9)
    assert m["params"]["factor"] == pytest.approx(1 / math.sin(math.radians(g)), rel=1e-12)
    assert "17.8 deg" in m["text"] and "3.3 times" in m["text"]
    l21 = 0.1 / math.cos(math.radians(21.0))
    res = run(slider_crank(0.1, l21, [0, 0], 0, [0.2, 0]))
    assert res["transmission"][0]["gamma_min"] == pytest.approx(21.0, abs=1e-9)
    assert "kinematics.transmission_low" not in codes(res)


def test_no_row_for_a_triad_and_90_for_a_slotted_lever():
    """A class III triad: no row. The slotted lever's RPR dyad, its slot through the lever's
    pivot: 90 deg exactly (the block presses normal to the slot, the lever's point under it moves
    normal to the slot too), the synthesis's own figure."""
    from pathlib import Path
    root = Path(__file__).resolve().parents[1] / "tasks"
    res = tmm_cli.run(tmm_cli.load_task(root / "triad_class3.yaml"))
    assert "transmission" not in res
    res = tmm_cli.run(tmm_cli.load_task(root / "synthesis_slotted_lever.yaml"))
    (row,) = res["transmission"]
    assert row["type"] == "RPR" and row["links"] == ["block", "rocker"] and row["joint"] == "A"
    assert row["gamma_min"] == 90.0 and res["synthesis"]["gamma_min"] == 90.0


@pytest.mark.parametrize("slot, want", [(90.0, 90.0), (60.0, 60.0), (120.0, 60.0), (15.0, 15.0)])
def test_scotch_yoke_is_the_angle_between_its_slot_and_its_guide(slot, want):
    """The Scotch yoke's RPP dyad (tasks/scotch_yoke_pump: the slot on the yoke at 90 deg to the
    yoke's horizontal guide): the block presses normal to the slot, the yoke moves along its
    guide, so the pressure angle is the angle between the slot's normal and the guide and the
    transmission angle 90 deg minus it: the acute angle between the slot and the guide, the same
    at every position (the yoke does not turn). Slot at 60 deg: the force along 150 deg, the
    motion along 0: pressure angle 30, gamma 60; at 120 deg the same 60; at 15 deg, 15 (below
    20: the low warning). Written as the PPR order too (the same group, its pairs reversed)."""
    from pathlib import Path

    import yaml
    root = Path(__file__).resolve().parents[1] / "tasks"
    task = yaml.safe_load((root / "scotch_yoke_pump.yaml").read_text(encoding="utf-8"))
    task["mechanism"]["links"]["block"]["guide"]["angle"] = slot
    for k in ("loads", "kinetostatics"):
        task.pop(k, None)
    res = tmm_cli.run(tmm_cli.load_task(task))
    (row,) = res["transmission"]
    assert row["type"] == "RPP" and row["links"] == ["block", "yoke"] and row["joint"] == "A"
    assert row["gamma_min"] == pytest.approx(want, abs=1e-9)
    low = [m for m in res["messages"] if m["code"] == "kinematics.transmission_low"]
    assert bool(low) == (want < 20.0)
    import dataclasses

    from tmm_cli.linkage import transmission
    from tmm_cli.linkage.context import build
    from tmm_cli.linkage.kinematics import solve
    L = build(tmm_cli.load_task(task))
    (g,) = L.structure.groups
    kin = solve(L.mechanism, np.linspace(0.0, 350.0, 36))
    rev = dataclasses.replace(g, joints=list(g.joints)[::-1], links=list(g.links)[::-1])
    assert "".join(j.kind for j in rev.joints) == "PPR"
    for group in (g, rev):
        (d,) = transmission.dyads(L.mechanism, [group])
        assert d.middle == "A" and np.allclose(transmission.gamma(d, kin), want, atol=1e-9)


def test_slotted_lever_with_an_offset_slot():
    """The shaper's slotted lever (O1 0.30 m below O, crank 0.11 m) with its slot offset by e from
    the lever's axis: gamma = 90 - asin(e / |O1A|) at every position, least where the block is
    nearest the pivot, |O1A| = 0.30 - 0.11 with the crank pointing at O1 (270 deg)."""
    from pathlib import Path
    root = Path(__file__).resolve().parents[1] / "tasks"
    import yaml
    for e in (0.02, -0.05):
        task = yaml.safe_load((root / "shaper_slotted_lever.yaml").read_text(encoding="utf-8"))
        task["mechanism"]["links"]["block"]["guide"]["offset"] = e
        for k in ("loads", "kinetostatics", "flywheel", "dynamics"):
            task.pop(k, None)
        res = tmm_cli.run(tmm_cli.load_task(task))
        row = next(r for r in res["transmission"] if r["type"] == "RPR")
        assert row["gamma_min"] == pytest.approx(90.0 - math.degrees(math.asin(abs(e) / 0.19)), abs=1e-7), e
        assert row["phi"] == pytest.approx(270.0, abs=1e-5)
        # at every crank angle of a grid: the closed form with |O1A| from the crank's own circle
        from tmm_cli.linkage import transmission
        from tmm_cli.linkage.kinematics import solve
        from tmm_cli.linkage.mechanism import build_mechanism
        from tmm_cli.linkage.structure import analyze
        mech = build_mechanism(tmm_cli.load_task(task))
        (d,) = [x for x in transmission.dyads(mech, analyze(mech).groups) if x.kind == "RPR"]
        phi = np.arange(0.0, 360.0, 7.5)
        oa = np.hypot(0.11 * np.cos(np.radians(phi)), 0.11 * np.sin(np.radians(phi)) + 0.30)
        want = 90.0 - np.degrees(np.arcsin(abs(e) / oa))
        assert np.max(np.abs(transmission.gamma(d, solve(mech, phi)) - want)) < 1e-9



def test_derivative_on_a_moving_guide():
    """An RRP dyad whose guide is on a turning link: sine()'s derivative (the rod's and the
    guide's rates) against central differences of the same motion written out: K = (cos p,
    sin 2p / 2), D = (2 + 0.3 sin p, 1 + cos 3p), the guide link at 0.7 sin p (+ 30 deg)."""
    from types import SimpleNamespace

    from tmm_cli.linkage import transmission as T

    def kin(p):
        p = np.asarray(p, float)
        return SimpleNamespace(
            pos={"K": np.column_stack([np.cos(p), 0.5 * np.sin(2 * p)]),
                 "D": np.column_stack([2 + 0.3 * np.sin(p), 1 + np.cos(3 * p)])},
            d1={"K": np.column_stack([-np.sin(p), np.cos(2 * p)]),
                "D": np.column_stack([0.3 * np.cos(p), -3 * np.sin(3 * p)])},
            angle={"guide": 0.7 * np.sin(p)}, a1={"guide": 0.7 * np.cos(p)})
    d = T.DyadAngle(group=None, kind="RRP", middle="D", ends=("K", "D"), guide_angle=30.0, guide_link="guide")
    p = np.linspace(0.1, 6.0, 13)
    h = 1e-6
    s, ds = T.sine(d, kin(p))
    fd = (T.sine(d, kin(p + h))[0] - T.sine(d, kin(p - h))[0]) / (2 * h)
    assert np.allclose(ds, fd, rtol=1e-6, atol=1e-8)
    r = kin(p).pos["D"] - kin(p).pos["K"]
    th = np.radians(30.0) + 0.7 * np.sin(p)
    assert np.allclose(s, (r[:, 0] * np.cos(th) + r[:, 1] * np.sin(th)) / np.hypot(r[:, 0], r[:, 1]), rtol=1e-14)


def test_a_generator_whose_input_range_runs_backwards(tmp_path):
    """A function generator with a negative input range (the crank turning cw through it, 45 ..
    -15 deg): the least over that range (an empty grid crashed the stage), as a scan of the
    generated linkage's points every 0.01 deg over the range finds it."""
    from pathlib import Path

    from tmm_cli.linkage.mechanism import build_mechanism
    from tmm_cli.linkage.kinematics import solve
    from tmm_cli.linkage.synthesis import generate
    src = (Path(__file__).resolve().parents[1] / "tasks" / "synthesis_function_log10.yaml").read_text(encoding="utf-8")
    src = src.replace("input: {start: 45, range: 60}", "input: {start: 45, range: -60}")
    src = src.replace("output: {start: 300, range: 90}", "output: {start: 300, range: -90}")
    assert "range: -60" in src and "range: -90" in src
    f = tmp_path / "neg.yaml"
    f.write_text(src, encoding="utf-8")
    task = tmm_cli.load_task(f)
    res = tmm_cli.run(task)
    (row,) = res["transmission"]
    gen, _ = generate(task)
    kin = solve(build_mechanism(gen), np.linspace(45.0, -15.0, 6001))
    u, v = kin.pos["A"] - kin.pos["B"], kin.pos["O1"] - kin.pos["B"]
    g = np.degrees(np.arcsin(np.minimum(1.0, np.abs(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0])
                                        / (np.hypot(*u.T) * np.hypot(*v.T)))))
    assert row["gamma_min"] == pytest.approx(g.min(), abs=1e-6)
    assert -15.0 - 1e-9 <= (row["phi"] + 180.0) % 360.0 - 180.0 <= 45.0 + 1e-9


def test_function_generator_over_a_cw_input_range():
    """A function generator's input range may run cw (``input.range`` < 0): the mirror image
    of tasks/synthesis_function_log10.yaml (input 315 deg back 60, output 60 deg back 90) has
    the same least transmission angle, at the mirror of its crank angle (was: an empty grid,
    the kinematics stage failed)."""
    from pathlib import Path

    import yaml
    src = yaml.safe_load((Path(__file__).resolve().parents[1] / "tasks" / "synthesis_function_log10.yaml").read_text())
    mirror = copy.deepcopy(src)
    mirror["synthesis"]["input"] = {"start": 315, "range": -60}
    mirror["synthesis"]["output"] = {"start": 60, "range": -90}
    (a,) = run(src)["transmission"]
    res = run(mirror)
    (b,) = res["transmission"]
    assert b["gamma_min"] == pytest.approx(a["gamma_min"], abs=1e-9)
    assert b["phi"] == pytest.approx((360.0 - a["phi"]) % 360.0, abs=1e-6)
    assert "kinematics.transmission_low" in codes(res)


def test_sharp_least_near_a_dead_point_off_the_grid():
    """A crank-rocker 1e-9 m short of folding flat (b + c = a + d + 1e-9), its frame line at
    33.3 deg: the least, with the crank pointing away from O1 (213.3 deg, between grid
    points), is sharp (sin gamma ~ sqrt(eps + k dphi^2), turning within ~1e-3 deg), and by
    the cosine rule sin(gamma/2) = sqrt((b + c - q)(b + c + q) / 4bc), q = |O O1| + a (was:
    one grid of 129 points and a line, 3e-5 deg off and gamma 7e-6 too large)."""
    a, b, c, th = 0.1, 0.3, 0.2, math.radians(33.3)
    d = b + c - a - 1e-9
    o1 = [d * math.cos(th), d * math.sin(th)]
    task = {"schema": "tmm/1",
            "mechanism": {"ground": {"O": [0, 0], "O1": o1},
                          "links": {"crank": {"points": ["O", "A"], "length": a},
                                    "rod": {"points": ["A", "B"], "length": b},
                                    "rocker": {"points": ["O1", "B"], "length": c}},
                          "assembly": {"B": [0.6 * o1[0] - 0.2 * math.sin(th), 0.6 * o1[1] + 0.2 * math.cos(th)]}},
            "drive": {"link": "crank", "speed": "60 rpm"},
            "positions": {"output": "rocker"}}
    (row,) = run(task)["transmission"]
    q = math.hypot(*o1) + a
    g = math.degrees(2 * math.asin(math.sqrt((b + c - q) * (b + c + q) / (4 * b * c))))
    assert row["gamma_min"] == pytest.approx(g, rel=1e-6)
    assert row["phi"] == pytest.approx(213.3, abs=1e-6)


def test_a_least_within_round_off_of_zero_is_a_dead_point():
    """A least of 3e-6 deg (the round-off of an angle found at an exact Grashof limit) is told
    as a dead point, not as 'falls to 0.0 deg ... 19098593.2 times'; 0.01 deg is still a low
    angle with its factor."""
    from tmm_cli.linkage import transmission as T
    row = {"group": "II(2,3)", "links": ["rod", "rocker"], "type": "RRR", "joint": "B", "phi": 12.0}
    (dead,) = T.warnings([{**row, "gamma_min": 3e-6}])
    (low,) = T.warnings([{**row, "gamma_min": 0.01}])
    assert dead.code == "kinematics.transmission_dead" and "factor" not in dead.params
    assert low.code == "kinematics.transmission_low"
    assert low.params["factor"] == pytest.approx(1 / math.sin(math.radians(0.01)), rel=1e-12)


def test_a_steep_dead_point_away_from_the_grids_least(monkeypatch):
    """sin gamma with a shallow least of 0.04 at 100 deg and a steep zero at 250.1 deg (through
    it within a tenth of a degree: the grid's points either side read 0.07 and more): the least
    is 0 at 250.1 (it was the shallow 2.3 deg, the grid's least being the only place looked at);
    without the zero, the shallow least refined to its closed form."""
    from types import SimpleNamespace

    import tmm_cli.linkage.kinematics as K
    from tmm_cli.linkage import transmission as T
    t1, t2, k = math.radians(100.0), math.radians(250.1), 40.0

    def fake_sine(d, kin):
        p = np.radians(kin.phi)
        f1, df1 = 0.04 + 0.5 * (1 - np.cos(p - t1)), 0.5 * np.sin(p - t1)
        if d.kind == "RRR":                        # the shallow least alone
            return f1, df1
        th = np.tanh(k * (p - t2))
        return f1 * th, df1 * th + f1 * k * (1 - th ** 2)
    monkeypatch.setattr(K, "solve", lambda mech, xs: SimpleNamespace(phi=np.asarray(xs, float)))
    monkeypatch.setattr(K, "solve_raw", lambda mech, xs: SimpleNamespace(phi=np.asarray(xs, float)))
    monkeypatch.setattr(T, "sine", fake_sine)
    steep = T.DyadAngle(group=None, kind="RRP", middle="B", ends=("A", "B"))
    shallow = T.DyadAngle(group=None, kind="RRR", middle="B", ends=("A", "C"))
    (g0, x0), (g1, x1) = T.least(None, [steep, shallow])
    assert g0 == 0.0 and x0 == pytest.approx(250.1, abs=1e-7)
    assert g1 == pytest.approx(math.degrees(math.asin(0.04)), abs=1e-9) and x1 == pytest.approx(100.0, abs=1e-6)


def test_shaper_ram_through_a_block_in_the_slot():
    """tasks/shaper_slotted_ram.yaml: the ram's PRP dyad (a block in the rocker's slot pinned to
    the ram on a horizontal guide): the slot is steepest to the guide at the slotted lever's
    extreme positions, where sin(psi/2) = r / |OO1| = 0.12 / 0.32: gamma_min = 90 - psi/2, at
    the crank angle square to the rocker (180 + psi/2 for this cw drive)."""
    from pathlib import Path
    res = tmm_cli.run(tmm_cli.load_task(Path(__file__).resolve().parents[1] / "tasks" / "shaper_slotted_ram.yaml"))
    slot, row = res["transmission"]
    assert slot["type"] == "RPR" and slot["gamma_min"] == 90.0            # the crank's block: slot through O1
    half = math.degrees(math.asin(0.12 / 0.32))
    assert row["type"] == "PRP" and row["links"] == ["blockC", "ram"] and row["joint"] == "C"
    assert row["gamma_min"] == pytest.approx(90.0 - half, abs=1e-9)
    assert row["phi"] == pytest.approx(180.0 + half, abs=1e-6)
    assert min(abs(row["phi"] - x) for x in res["positions"]["extreme"]) < 1e-6


def test_prp_derivative_with_both_guides_turning():
    """A PRP dyad whose slot and guide both turn (0.7 sin p and 0.2 cos 2p, at 10 and 80 deg to
    their links): sine() is sin of the angle between them, its derivative the central
    difference's."""
    from types import SimpleNamespace

    from tmm_cli.linkage import transmission as T

    def kin(p):
        p = np.asarray(p, float)
        return SimpleNamespace(phi=np.degrees(p), angle={"g1": 0.7 * np.sin(p), "g2": 0.2 * np.cos(2 * p)},
                               a1={"g1": 0.7 * np.cos(p), "g2": -0.4 * np.sin(2 * p)})
    d = T.DyadAngle(group=None, kind="PRP", middle="C", ends=("C", "C"), guide_angle=10.0, guide_link="g1",
                    guide2_angle=80.0, guide2_link="g2")
    p = np.linspace(0.1, 6.0, 13)
    s, ds = T.sine(d, kin(p))
    h = 1e-6
    fd = (T.sine(d, kin(p + h))[0] - T.sine(d, kin(p - h))[0]) / (2 * h)
    assert np.allclose(ds, fd, rtol=1e-6, atol=1e-8)
    assert np.allclose(s, np.sin(np.radians(70.0) + 0.2 * np.cos(2 * p) - 0.7 * np.sin(p)), rtol=1e-14)


def test_each_dyad_reads_its_own_guides():
    """dyads() on every linkage example: a PRP dyad's two guides are the two sliders' own (the
    first the slot's, the second the other slider's, fixed or on a link), an RPR's slot the block's,
    and only an RPR may be through its pivot (a field out of place read a guide's link as that)."""
    from pathlib import Path

    from tmm_cli.linkage import transmission
    from tmm_cli.linkage.mechanism import build_mechanism
    from tmm_cli.linkage.structure import analyze
    from tmm_cli.orchestrate import prepare
    kinds = set()
    for path in sorted((Path(__file__).resolve().parents[1] / "tasks").glob("*.yaml")):
        task = prepare(path, assembly=False)
        if getattr(task, "mechanism", None) is None:
            continue
        mech = build_mechanism(task)
        for d in transmission.dyads(mech, analyze(mech).groups):
            kinds.add(d.kind)
            assert type(d.through_pivot) is bool and (d.kind == "RPR" or not d.through_pivot), (path.name, d)
            joints = list(d.group.joints)
            if d.kind == "PRP":
                g1, g2 = mech.link(joints[0].slider).guide, mech.link(joints[2].slider).guide
                assert (d.guide_link, d.guide2_link) == (g1.link, g2.link), path.name
                assert (d.guide_angle, d.guide2_angle) == (float(g1.angle), float(g2.angle)), path.name
            if d.kind == "RPR":
                assert d.guide_link == mech.link(joints[1].slider).guide.link, path.name
    assert {"RRR", "RRP", "RPR", "PRP"} <= kinds


def test_a_least_found_a_hair_below_zero_is_at_zero():
    """The crank angle of a least is in [0, 360): a root a hair below 0 is 0, not
    359.99999999999994 (a table's five digits showed 360)."""
    from tmm_cli.linkage.transmission import _turn
    assert _turn(-6e-14) == 0.0 and _turn(360.0) == 0.0 and _turn(-90.0) == 270.0
    assert _turn(359.5) == 359.5 and _turn(725.0) == 5.0
