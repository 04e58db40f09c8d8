"""Structural analysis: Chebyshev's formula and Assur groups, checked by hand counts."""
from pathlib import Path

import pytest

from tmm_cli.errors import StageError, TaskError
from tmm_cli.linkage.mechanism import build_mechanism
from tmm_cli.linkage.structure import analyze
from tmm_cli.task import load_task

TASKS = Path(__file__).resolve().parent.parent / "tasks"


def mech_of(links, ground, drive="crank"):
    t = load_task({"schema": "tmm/1", "mechanism": {"ground": ground, "links": links},
                   "drive": {"link": drive, "speed": 10}})
    return t, build_mechanism(t)


SIXBAR = {"crank": {"points": ["O", "A"], "length": 0.15},
          "rod": {"points": ["A", "B"], "length": 0.97},
          "rocker": {"points": ["O1", "B"], "length": 0.66, "extra": {"K": [0.25, 0]}},
          "link4": {"points": ["K", "D"], "length": 0.86},
          "slider": {"slider": "D", "guide": {"through": "O1", "angle": 90}}}


def test_spec_sixbar():
    _, m = mech_of(SIXBAR, {"O": [0, 0], "O1": [0.5, 0.37]})
    r = analyze(m)
    # by hand: 5 moving links; pairs O, A, B, O1, K, D (revolute) + slider guide (prismatic) = 7
    assert (r.n, r.p5, r.p4) == (5, 7, 0)
    assert r.W == 3 * 5 - 2 * 7 == 1
    assert r.formula == "I(0,1) -> II(2,3) -> II(4,5)"
    d = r.to_dict()
    assert d["class"] == 2
    assert [g["links"] for g in d["groups"]] == [["rod", "rocker"], ["link4", "slider"]]
    assert [g["type"] for g in d["groups"]] == ["RRR", "RRP"]
    assert [g["order"] for g in d["groups"]] == [2, 2]


# file -> (n, p5, formula, group types), counted by hand from each scheme
EXPECTED = {
    "engine_slider_crank.yaml": (3, 4, "I(0,1) -> II(2,3)", ["RRP"]),
    "press_offset_slider_crank.yaml": (3, 4, "I(0,1) -> II(2,3)", ["RRP"]),
    "crank_rocker_fourbar.yaml": (3, 4, "I(0,1) -> II(2,3)", ["RRR"]),
    "shaper_slotted_lever.yaml": (5, 7, "I(0,1) -> II(2,3) -> II(4,5)", ["RPR", "RRP"]),
    "shaper_slotted_ram.yaml": (5, 7, "I(0,1) -> II(2,3) -> II(4,5)", ["RPR", "PRP"]),
    "forging_sixbar.yaml": (5, 7, "I(0,1) -> II(2,3) -> II(4,5)", ["RRR", "RRP"]),
    "scotch_yoke_pump.yaml": (3, 4, "I(0,1) -> II(2,3)", ["RPP"]),
    "triad_class3.yaml": (5, 7, "I(0,1) -> III(2,3,4,5)", ["RR-RR-PR"]),
}


@pytest.mark.parametrize("name", sorted(EXPECTED))
def test_examples(name):
    t = load_task(TASKS / name)
    r = analyze(build_mechanism(t))
    n, p5, formula, types = EXPECTED[name]
    assert (r.n, r.p5, r.W) == (n, p5, 3 * n - 2 * p5)
    assert r.W == 1
    assert r.formula == formula
    assert [g.type for g in r.groups] == types


def test_every_dyad_type_among_examples():
    types = set()
    for name in EXPECTED:
        types |= {g.type for g in analyze(build_mechanism(load_task(TASKS / name))).groups}
    assert {"RRR", "RRP", "RPR", "PRP", "RPP"} <= types


def test_triad_class_order():
    r = analyze(build_mechanism(load_task(TASKS / "triad_class3.yaml")))
    g = r.groups[0]
    assert (g.klass, g.order, r.class_) == (3, 3, 3)
    assert g.names[-1] == "base"            # the ternary base link is listed last
    assert len(g.joints) == 6


def test_reading_order_prr_and_ppr():
    # block sliding on the crank, hinged to a rocker: read from the crank side -> PRR
    _, m = mech_of({"crank": {"points": ["O", "A"], "length": 0.1},
                    "block": {"slider": "B", "guide": {"link": "crank"}},
                    "rocker": {"points": ["O3", "B"], "length": 0.5}},
                   {"O": [0, 0], "O3": [0.3, 0]})
    assert [g.type for g in analyze(m).groups] == ["PRR"]
    _, m = mech_of({"crank": {"points": ["O", "A"], "length": 0.1},
                    "block1": {"slider": "B", "guide": {"link": "crank"}},
                    "block2": {"slider": "O3", "guide": {"link": "block1", "angle": 90}}},
                   {"O": [0, 0], "O3": [0.3, 0]})
    assert [g.type for g in analyze(m).groups] == ["PPR"]


def test_rigid_truss_is_rejected():
    # a four-bar with an extra bar A-O1 braces it: n = 4
    links = {"crank": {"points": ["O", "A"], "length": 0.1},
             "r1": {"points": ["A", "B"], "length": 0.3},
             "r2": {"points": ["O1", "B"], "length": 0.3},
             "r3": {"points": ["A", "O1"], "length": 0.35}}
    t, m = mech_of(links, {"O": [0, 0], "O1": [0.4, 0]})
    # pairs: O(0-1), A(1-2), A(1-4), B(2-3), O1(0-3), O1(0-4): p5 = 6, W = 12 - 12 = 0
    with pytest.raises(StageError, match=r"W = 0"):
        analyze(m)
    with pytest.raises(TaskError, match=r"W = 0"):
        analyze(m, task=t)


def test_five_bar_needs_two_inputs():
    links = {"crank": {"points": ["O", "A"], "length": 0.1},
             "r1": {"points": ["A", "B"], "length": 0.3},
             "r2": {"points": ["B", "C"], "length": 0.3},
             "r3": {"points": ["O1", "C"], "length": 0.2}}
    _, m = mech_of(links, {"O": [0, 0], "O1": [0.4, 0]})
    # n = 4, pairs O, A, B, C, O1 -> p5 = 5, W = 12 - 10 = 2
    with pytest.raises(StageError, match=r"W = 2"):
        analyze(m)


def test_idle_link_flagged():
    links = {"crank": {"points": ["O", "A"], "length": 0.1},
             "rod": {"points": ["A", "B"], "length": 0.4},
             "slider": {"slider": "B", "guide": {"through": "O", "angle": 0}},
             "flag": {"points": ["B", "F"], "length": 0.05}}
    _, m = mech_of(links, {"O": [0, 0]})
    # n = 4, pairs O, A, B(rod-slider), B(rod-flag), P -> p5 = 5, W = 2: the flag turns freely
    with pytest.raises(StageError, match=r"idle"):
        analyze(m)
