"""Instant centres of every pair of links at every reported position: the pairs joined
directly at their pins, Kennedy's theorem for the rest (three centres of three links on one
line), null at infinity (a relative translation), against a hand construction."""
import itertools
from pathlib import Path

import numpy as np
import pytest

from tmm_cli import load_task, run

ROOT = Path(__file__).resolve().parents[1]
LINKAGES = [p.stem for p in sorted((ROOT / "tasks").glob("*.yaml"))
            if "mechanism:" in p.read_text(encoding="utf-8") or "synthesis:" in p.read_text(encoding="utf-8")]


def _line_through(p, q):
    return np.array(p, float), np.array(q, float) - np.array(p, float)


def _cross(u, v):
    return u[0] * v[1] - u[1] * v[0]


@pytest.mark.parametrize("name", LINKAGES)
def test_kennedy_three_centres_on_a_line(name, shared_once):
    from pdf_extent import results
    _, res = results(shared_once, name)          # as tmm run computes them, once a session
    n = len(res["structure"]["links"])
    size = max(abs(c) for e in res["kinematics"] for p in e["points"].values() for c in (p["x"], p["y"]))
    checked, finite = 0, 0
    for e in res["kinematics"]:
        ic = e["instant_centres"]
        assert set(ic) == {f"{i}-{j}" for i, j in itertools.combinations(range(n + 1), 2)}
        for i, j, k in itertools.combinations(range(n + 1), 3):
            a, b, c = ic[f"{i}-{j}"], ic[f"{i}-{k}"], ic[f"{j}-{k}"]
            if None in (a, b, c):
                continue
            finite += 1
            a, b, c = map(np.array, (a, b, c))
            far = max(np.abs(a).max(), np.abs(b).max(), np.abs(c).max(), size)
            if far > 1e3 * size:
                continue                         # nearly parallel lines: the test's own round-off
            # twice the triangle's area over its longest side: its height, relative to the size
            side = max(np.linalg.norm(b - a), np.linalg.norm(c - a), np.linalg.norm(c - b), 1e-300)
            assert abs(_cross(b - a, c - a)) / side <= 1e-9 * far, (name, e["index"], i, j, k)
            checked += 1
    assert checked > 0 or finite == 0        # a Scotch yoke: every triple has a centre at infinity
    assert checked >= 0.9 * finite


def test_four_bar_centres_by_hand():
    """Crank 1 (O, A), coupler 2 (A, B), rocker 3 (O3, B): 0-1 = O, 1-2 = A, 2-3 = B, 0-3 = O3;
    0-2 = the lines OA and O3B crossed; 1-3 = the lines O O3 and AB crossed."""
    res = run(load_task(ROOT / "tasks" / "crank_rocker_fourbar.yaml"))
    for e in res["kinematics"]:
        P = {k: np.array([v["x"], v["y"]]) for k, v in e["points"].items()}
        ic = {k: np.array(v) for k, v in e["instant_centres"].items()}
        L = np.linalg.norm(P["A"] - P["O"])
        for key, want in (("0-1", P["O"]), ("1-2", P["A"]), ("2-3", P["B"]), ("0-3", P["O3"])):
            assert np.allclose(ic[key], want, atol=1e-12 * L), key

        def meet(p1, d1, p2, d2):
            t = _cross(p2 - p1, d2) / _cross(d1, d2)
            return p1 + t * d1
        assert np.allclose(ic["0-2"], meet(P["O"], P["A"] - P["O"], P["O3"], P["B"] - P["O3"]), atol=1e-9)
        assert np.allclose(ic["1-3"], meet(P["O"], P["O3"] - P["O"], P["A"], P["B"] - P["A"]), atol=1e-9)


def test_slider_on_a_fixed_guide_translates():
    """The piston translates along its fixed guide: its centre with the frame is at infinity (null);
    with the rod it is the pin B; the rod's with the frame lies on the perpendicular to the guide
    at B and on the crank's line OA."""
    res = run(load_task(ROOT / "tasks" / "engine_slider_crank.yaml"))
    names = [lk["name"] for lk in res["structure"]["links"]]
    k_piston, k_rod = names.index("piston") + 1, names.index("rod") + 1
    for e in res["kinematics"]:
        if e.get("singular") or e.get("near_singular"):
            continue
        ic = e["instant_centres"]
        assert ic[f"0-{k_piston}"] is None
        B = np.array([e["points"]["B"]["x"], e["points"]["B"]["y"]])
        assert np.allclose(ic[f"{k_rod}-{k_piston}"], B, atol=1e-12)
        c = ic[f"0-{k_rod}"]
        if c is not None:
            # the guide is vertical (angle 90) through O: the perpendicular at B is horizontal
            assert c[1] == pytest.approx(B[1], abs=1e-9 * max(1.0, abs(c[0])))


def test_links_at_rest_at_an_extreme_have_kennedys_centres():
    """The forging machine at its extreme positions: the rocker 3, link 4 and the slider 5 are
    at rest (their velocities vanish), so the velocities alone do not fix the centres 0-4 and
    3-5 -- which are not at infinity but the limits as the crank turns on, Kennedy's
    construction: 0-4 on the line O1 K (centres 0-3, 3-4) and on the perpendicular to the
    vertical guide at D (centres 0-5 at infinity, 4-5 = D); 3-5 on the horizontal through O1
    (0-3, 0-5) and on the line K D (3-4, 4-5).  Once null (the relative motion taken for a
    translation)."""
    res = run(load_task(ROOT / "tasks" / "forging_sixbar.yaml"))
    names = [lk["name"] for lk in res["structure"]["links"]]
    assert names == ["crank", "rod", "rocker", "link4", "slider"]

    def meet(p1, d1, p2, d2):
        t = _cross(p2 - p1, d2) / _cross(d1, d2)
        return p1 + t * d1
    ends = [e for e in res["kinematics"] if e["index"] in (0, 12)]
    assert len(ends) == 2
    horizontal = np.array([1.0, 0.0])
    for e in ends:
        P = {k: np.array([v["x"], v["y"]]) for k, v in e["points"].items()}
        assert abs(e["links"]["rocker"]["omega"]) < 1e-12 and abs(e["points"]["D"]["v"]) < 1e-12
        ic = e["instant_centres"]
        assert ic["0-5"] is None                           # the slide: at infinity
        want04 = meet(P["O1"], P["K"] - P["O1"], P["D"], horizontal)
        want35 = meet(P["O1"], horizontal, P["K"], P["D"] - P["K"])
        assert ic["0-4"] is not None and ic["3-5"] is not None, e["index"]
        assert np.allclose(ic["0-4"], want04, rtol=0, atol=1e-9), (e["index"], ic["0-4"], want04)
        assert np.allclose(ic["3-5"], want35, rtol=0, atol=1e-9), (e["index"], ic["3-5"], want35)
