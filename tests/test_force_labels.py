"""The force drawings -- each group with its loads, Zhukovsky's lever -- of the report and of
sheet 2, for every example task with a linkage, in en, ru and uk: which name belongs to which
arrow stays plain.

* no two arrows of a drawing cover each other (on one line, their shafts sharing more than
  half a millimetre): the shaper's ram load F1, its friction F_f05 and its inertia force Φ5
  act at one point along the guide and were drawn one over the other, their three names
  stacked around one point (sheet 2's lever: F, Φ4, Φ5, G4 at one point); in a force
  polygon, a link's weight and its inertia force one after the other the other way round
  were drawn one over the other (drawings.forces.apart_order, beside);
* the arms' names of a lever are apart: arms with one foot (the weights of links whose
  ends of the turned plan coincide, a load on the line of a plan's ray) had their names at
  one point (now one name, h with all their subscripts); arms whose feet are a millimetre
  apart, or a few degrees, are named along them apart;
* every force's or couple's name is within drawings.forces.LEADER mm of its arrow's tip (its
  couple's ring), or a leader line runs from there to the name;
* no text of any figure of the report or of any sheet overlaps another or leaves its figure
  (the checks of test_figure_labels and test_sheets), in every language.

Recorded as drawn: the canvas' arrows, lines and texts while the drawing functions of
tmm_cli/drawings/forces.py run for the report (the one `tmm run --format html,pdf` writes,
built once per test session: tests/pdf_extent.py) and for the sheets (tests/figure_record.py)."""
from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
LINKAGES = sorted(p.stem for p in (ROOT / "tasks").glob("*.yaml")          # given or synthesised
                  if re.search(r"^(mechanism|synthesis):", p.read_text(encoding="utf-8"), re.M))


def _box_dist(x, box) -> float:
    nx = min(max(float(x[0]), box[0]), box[2])
    ny = min(max(float(x[1]), box[1]), box[3])
    return math.hypot(nx - float(x[0]), ny - float(x[1]))


def _covering(arrows) -> list:
    """Pairs of arrows (p, q) on one line whose shafts share more than 0.5 mm."""
    out = []
    for i in range(len(arrows)):
        p1, q1 = (np.asarray(v, float) for v in arrows[i])
        d1 = q1 - p1
        L1 = float(np.hypot(*d1))
        if L1 < 1e-9:
            continue
        u = d1 / L1
        n = np.array([-u[1], u[0]])
        for j in range(i + 1, len(arrows)):
            p2, q2 = (np.asarray(v, float) for v in arrows[j])
            if abs(float((p2 - p1) @ n)) > 0.3 or abs(float((q2 - p1) @ n)) > 0.3:
                continue
            a, b = sorted((float((p2 - p1) @ u), float((q2 - p1) @ u)))
            if min(b, L1) - max(a, 0.0) > 0.5:
                out.append((tuple(np.round(p1, 2).tolist()), tuple(np.round(p2, 2).tolist())))
    return out


ARM_APART = 1.0        # mm: two arms' names of a lever closer than this are at one place


def problems(panels) -> list[str]:
    from tmm_cli.drawings.forces import LEADER
    bad = []
    for k, pan in enumerate(panels):
        where = f"{pan['kind']} {k}"
        for a, b in _covering(pan["arrows"]):
            bad.append(f"{where}: arrows from {a} and {b} cover each other")
        arms = [(anchor, name) for anchor, u, name, box, leader in pan["labels"] if name.startswith("h\u0000")]
        for i, (a1, n1) in enumerate(arms):
            for a2, n2 in arms[i + 1:]:
                if math.dist(a1, a2) < ARM_APART:
                    bad.append(f"{where}: the arms' names {n1!r} and {n2!r} at one place of the lever")
        for anchor, u, name, box, leader in pan["labels"]:
            if not leader:
                continue
            d = _box_dist(anchor, box)
            if d > LEADER + 1e-6:
                near = (min(max(float(anchor[0]), box[0]), box[2]), min(max(float(anchor[1]), box[1]), box[3]))
                if not any(math.dist(p, anchor) < 0.05 and math.dist(q, near) < 0.05 for p, q in pan["lines"]):
                    bad.append(f"{where}: {name!r} {d:.1f} mm from its arrow, no leader")
                continue
    return bad


def test_the_checks_see_covering_arrows_and_a_lost_name():
    panels = [{"kind": "group", "arrows": [((0, 0), (10, 0)), ((2, 0), (8, 0)), ((0, 0), (-5, 0)), ((0, 5), (0, 9))],
               "lines": [], "labels": [(np.array([0.0, 9.6]), (0.0, 1.0), "G4", (6.0, 12.0, 8.0, 14.0), True)]}]
    got = problems(panels)
    assert got[0].startswith("group 0: arrows from (0.0, 0.0) and (2.0, 0.0)") and len(got) == 2
    assert "'G4' 6.5 mm from its arrow, no leader" in got[1]      # hypot(6, 2.4)


def test_a_ram_load_its_friction_and_inertia_one_after_another():
    """drawings.forces.along_line: three forces at one point along one line are drawn one
    after another along it (each starting a millimetre past the tip before), an opposite one
    from the point itself."""
    from tmm_cli.drawings.forces import along_line
    drawn = []
    u = np.array([-1.0, 0.0])
    for L in (9.0, 7.0, 5.0):
        s = along_line((0.0, 0.0), u, L, drawn)
        drawn.append((s, s + u * L, u))
    assert [tuple(np.round(d[0], 9)) for d in drawn] == [(0.0, 0.0), (-10.0, 0.0), (-18.0, 0.0)]
    s = along_line((-4.0, 0.0), -u, 3.0, drawn)          # from inside the first, the other way
    assert tuple(s) == (0.0, 0.0)
    s = along_line((0.0, 0.0), np.array([0.0, -1.0]), 6.0, drawn)    # across: where it is
    assert tuple(s) == (0.0, 0.0)


def test_parallel_forces_of_a_polygon_one_after_another():
    """drawings.forces.apart_order: a weight G = (0, -100) N followed by an inertia force
    Φ = (0, 60) N (upwards) runs back along G; the first order that draws every side apart,
    the loads first, puts the horizontal load F = (50, 0) N between them:
    G (0,0)->(0,-100), F ->(50,-100), Φ ->(50,-40), R ->(0,0): no two sides on one line,
    and the polygon still closes (the sum is the same)."""
    from tmm_cli.drawings.forces import apart_order, covered
    vecs = [("G2", np.array([0.0, -100.0]), "gravity"), ("Fi2", np.array([0.0, 60.0]), "inertia"),
            ("F2", np.array([50.0, 0.0]), "load"), ("R12", np.array([-50.0, 40.0]), "reaction")]
    assert covered([F for _, F, _ in vecs], 1.0) == [False, True, False, False]
    got = apart_order(vecs)
    assert [n for n, _, _ in got] == ["G2", "F2", "Fi2", "R12"]
    assert not any(covered([F for _, F, _ in got], 1.0))
    assert np.allclose(sum(F for _, F, _ in got), 0.0)
    # already apart: the given order kept
    assert apart_order(got) == got


def test_collinear_sides_drawn_beside():
    """drawings.forces.beside: all forces along one line (a piston's weight down 30 mm, its
    gas force up 50 mm, the reaction down 20 mm) cannot be drawn apart in any order: the
    second side lies along the first (drawn 1 x SIDE_GAP beside), the third along both (2 x)."""
    from tmm_cli.drawings.forces import beside
    T = [(0.0, 0.0), (0.0, -30.0), (0.0, 20.0), (0.0, 0.0)]
    assert beside(T) == [0, 1, 2]
    assert beside([(0.0, 0.0), (0.0, -30.0), (40.0, -30.0), (0.0, 0.0)]) == [0, 0, 0]


def test_arms_with_one_foot_named_once():
    """drawings.forces.merge_arms: the arms of G3 and Φ3 end at one foot (0.1 mm apart): one
    arm h with the subscript 'G3, Φ3'; F1's, 5 mm away, keeps its own."""
    from tmm_cli.drawings.forces import merge_arms
    z = np.zeros(2)
    arms = [(z, (0, 1), "h\u0000G3", "#6b7b7c", np.array([10.0, 0.0])),
            (z, (0, 1), "h\u0000Φ3", "#1f5fbf", np.array([10.1, 0.0])),
            (z, (0, 1), "h\u0000F1", "#c0392b", np.array([15.0, 0.0]))]
    got = merge_arms(arms)
    assert [(n, c) for _, _, n, c, _ in got] == [("h\u0000G3, Φ3", "#444"), ("h\u0000F1", "#c0392b")]


@pytest.mark.parametrize("balance", [None, "slider"])
def test_the_levers_lines_as_the_course_writes_them(balance):
    """Under the lever: M_b (or P_b) with b as a subscript -- it was printed 'M_b by the lever'
    with its underscore -- and a force's unit after its value ('P_b (Zhukovsky) = 123.45 N',
    not 'P_b (Zhukovsky), N = 123.45'); the values those of the results."""
    import copy

    from test_kinetostatics_pipeline import SIX

    import tmm_cli
    from tmm_cli.drawings import forces as K
    from tmm_cli.drawings.words import Words
    from tmm_cli.report.svgdraw import Canvas
    case = copy.deepcopy(SIX)
    if balance:
        case["kinetostatics"] = {"balance": balance}
    r = tmm_cli.run(case, kinematics_curve=0)
    e = next(k for k in r["kinetostatics"] if k.get("zhukovsky_force" if balance else "zhukovsky_moment") is not None)
    ke = next(k for k in r["kinematics"] if k["index"] == e["index"])
    got = []
    text0 = Canvas.text

    class Rec(Canvas):
        def text(self, x, y, s, *a, sub=None, after=None, **kw):
            got.append((s, sub, after))
            return text0(self, x, y, s, *a, sub=sub, after=after, **kw)
    w = Words("en")
    K.lever_panel(w, Rec(170, 110), (0, 0, 170, 110), e, ke, None, (r.get("drive") or {}).get("omega"),
                  r["kinetostatics_info"]["balance_kind"])
    if balance:
        want = [("P", "b", f" (Zhukovsky) = {w.fmt(e['zhukovsky_force'], 5)} N"),
                ("P", "b", f" (groups) = {w.fmt(e['balancing_force'], 5)} N")]
    else:
        want = [("M", "b", f" by the lever = {w.fmt(e['zhukovsky_moment'], 5)} N·m"),
                ("M", "b", f" by the groups = {w.fmt(e['balancing_moment'], 5)} N·m")]
    assert all(x in got for x in want), [g for g in got if g[1] == "b"]
    assert not any("_" in (s + (after or "")) for s, sub, after in got)


@pytest.mark.parametrize("name", LINKAGES)
def test_force_names_beside_their_arrows(name, shared_once):
    from pdf_extent import recorded, results
    from test_figure_labels import problems as text_problems
    from test_sheets import example_drawn

    task, res = results(shared_once, name)
    if not res.get("kinetostatics"):
        pytest.skip("no kinetostatics")
    bad = []
    for lang in ("en", "ru", "uk"):
        # the report `tmm run` writes, its figures recorded as they were drawn (pdf_extent.report_out)
        drawn = recorded(shared_once, name, lang)
        bad += [f"{lang}: report: {b}" for b in text_problems(drawn["texts"])]
        assert drawn["panels"]
        bad += [f"{lang}: report: {b}" for b in problems(drawn["panels"])]
        # the sheets, their force drawings recorded as they were drawn (every text of every
        # sheet: tests/test_sheets.py, test_texts_of_every_examples_sheets)
        panels = example_drawn(name, shared_once)[lang][1]
        assert panels                                # sheet 2's groups, polygons and lever
        bad += [f"{lang}: {b}" for b in problems(panels)]
    assert not bad, f"{len(bad)} problems, e.g. {bad[:8]}"


def test_a_tall_lever_drawn_larger():
    """The report's lever figure: 110 mm high for a wide turned plan, higher (up to 200 mm)
    for a tall one, at the finest standard μv (1, 2, 2.5, 4, 5 x 10^k) at which the plan --
    its extent measured here from the turned velocities and the pole -- fits in the figure
    less its margins, title and the lines under it.  The shaper's plan is tall: it was drawn
    at a μv two steps coarser in 110 mm."""
    import tmm_cli
    from tmm_cli.drawings.forces import LEVER_TEXT_H, TITLE_H
    from tmm_cli.report.sections.kinetostatics import FIG_W, LEVER_H, LEVER_H_MAX, lever_box_height, lever_scale
    r = tmm_cli.run(tmm_cli.load_task(ROOT / "tasks" / "shaper_slotted_ram.yaml"))
    kin = {k["index"]: k for k in r["kinematics"]}
    grown = 0
    for e in r["kinetostatics"]:
        ke = kin[e["index"]]
        h = lever_box_height(e, ke)
        mu = lever_scale(e, ke)
        pts = [(0.0, 0.0)] + [(-float(d.get("vy") or 0), float(d.get("vx") or 0)) for d in ke["points"].values()]
        xs, ys = [p[0] for p in pts], [p[1] for p in pts]
        assert LEVER_H <= h <= LEVER_H_MAX
        assert (max(xs) - min(xs)) / mu <= FIG_W - 20 + 1e-6
        assert (max(ys) - min(ys)) / mu <= h - TITLE_H - LEVER_TEXT_H - 20 + 1e-6
        m = mu / 10 ** math.floor(math.log10(mu) + 1e-12)
        assert round(m, 9) in (1, 2, 2.5, 4, 5)
        if h > LEVER_H:
            grown += 1
            assert mu < lever_scale(e, ke, FIG_W, LEVER_H)          # finer than in 110 mm
    assert grown >= 6


def test_a_round_off_couple_is_not_drawn():
    """An inertia couple at a dead centre is a round-off zero (-1.06e-15 N*m for a central
    slider-crank's rod at position 0, where epsilon_2 = 0): the tables print 0 and the drawing
    has no arrow for it; a real couple is drawn."""
    from tmm_cli.drawings.forces import group_couples
    e = {"couples": [{"name": "Mi1", "link": "crank", "M": 0.0, "kind": "inertia"},
                     {"name": "Mi2", "link": "rod", "M": -1.06e-15, "kind": "inertia"},
                     {"name": "Mi3", "link": "rod", "M": 2.5, "kind": "inertia"},
                     {"name": "Mi4", "link": "other", "M": 3.0, "kind": "inertia"}]}
    assert group_couples(e, {"crank", "rod"}) == [("Mi3", "rod", 2.5, "inertia")]


@pytest.mark.parametrize("name", ["balancing_fourbar", "forging_sixbar", "engine_slider_crank"])
def test_every_lever_force_stands_on_a_drawn_ray_of_the_turned_plan(name):
    """On Zhukovsky's lever a force is moved to the end of its point's turned velocity. The
    crank's inertia force at its centre of mass beyond O (a counterweight) floated 124 mm from
    p with no ray to it: every force's point now ends a drawn line of the plan (ps1, lettered
    s1), at every position the task computes. (The point: rot90(v)/mu_v from the pole.)"""
    import numpy as np

    import tmm_cli
    from tmm_cli.drawings import forces as K
    from tmm_cli.drawings.words import Words
    from tmm_cli.report.svgdraw import Canvas
    from pathlib import Path
    tasks = Path(__file__).resolve().parents[1] / "tasks"
    r = tmm_cli.run(tmm_cli.load_task(tasks / f"{name}.yaml"), kinematics_curve=0)
    lines, letters = [], []
    line0, text0 = Canvas.line, Canvas.text

    class Rec(Canvas):
        def line(self, p, q, *a, **kw):
            lines.append((np.asarray(p, float), np.asarray(q, float)))
            return line0(self, p, q, *a, **kw)

        def text(self, x, y, s, *a, sub=None, **kw):
            letters.append(s + (sub or ""))
            return text0(self, x, y, s, *a, sub=sub, **kw)
    checked = 0
    for e in r["kinetostatics"]:
        if e.get("zhukovsky_moment") is None:
            continue
        ke = next(k for k in r["kinematics"] if k["index"] == e["index"])
        lines.clear()
        letters.clear()
        box = (0.0, 0.0, 170.0, 110.0)
        mu_v = K.lever_panel(Words("en"), Rec(170, 110), box, e, ke, None, (r.get("drive") or {}).get("omega"),
                             r["kinetostatics_info"]["balance_kind"])
        pole = lines[0][0]                      # the first ray starts at the pole
        for f in e["loads"]:
            if float(np.hypot(*f["F"])) == 0:
                continue
            q = pole + np.array([-f["v"][1], f["v"][0]]) / mu_v
            assert any(K._off(q, a, b) <= 0.3 for a, b in lines), (name, e["index"], f["name"])
            checked += 1
    assert checked > 0
