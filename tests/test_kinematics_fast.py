"""The complex-number fast path of the kinematics (tmm_cli.linkage.kinematics.fast).

It answers a regular call of ``solve`` (every group assembles and is regular at every
position); the general solver answers every other call. Checked here against two
independent values: the general solver (a different method: real-valued poses of link
origins, Cramer's rule on the pair's columns) and central finite differences of the
positions (the derivatives), on every dyad kind the fast path covers, the tasks, and
random linkages; and that it hands every other call to the general solver unchanged.
"""
from __future__ import annotations

import glob
import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as hst

from tmm_cli.linkage.kinematics import fast
from tmm_cli.linkage.kinematics import solver as sv
from tmm_cli.linkage.mechanism import build_mechanism
from tmm_cli.orchestrate import prepare
from tmm_cli.task import load_task


def _mech(mechanism, speed="60 rpm"):
    return build_mechanism(load_task({"schema": "tmm/1", "mechanism": mechanism,
                                      "drive": {"link": "crank", "speed": speed}}))


FOUR_BAR = {"ground": {"O": [0, 0], "O3": [0.30, 0]},
            "links": {"crank": {"points": ["O", "A"], "length": 0.08},
                      "coupler": {"points": ["A", "B"], "length": 0.30, "extra": {"E": [0.12, 0.09]}},
                      "rocker": {"points": ["O3", "B"], "length": 0.22, "extra": {"G": [0.11, -0.05]}}},
            "assembly": {"B": [0.33, 0.21]}}

# every dyad kind the fast path covers, and the four-bar's other closure
CASES = {
    "RRR ground pivot": FOUR_BAR,
    "RRR other closure": {**FOUR_BAR, "assembly": {"B": [0.2, -0.2]}},
    "RRR both pivots moving": {
        "ground": FOUR_BAR["ground"],
        "links": {**FOUR_BAR["links"],
                  "link4": {"points": ["E", "F"], "length": 0.25},
                  "link5": {"points": ["F", "G"], "length": 0.2}},
        "assembly": {"B": [0.33, 0.21], "F": [0.3, 0.45]}},
    "RRP fixed guide": {
        "ground": {"O": [0, 0]},
        "links": {"crank": {"points": ["O", "A"], "length": 0.05},
                  "rod": {"points": ["A", "B"], "length": 0.2, "extra": {"K": [0.05, 0.02]}},
                  "slider": {"slider": "B", "guide": {"through": [0, 0.015], "angle": 20}}},
        "assembly": {"B": [0.2, 0.08]}},
    "PRR fixed guide, the other closure": {
        "ground": {"O": [0, 0]},
        "links": {"crank": {"points": ["O", "A"], "length": 0.05},
                  "slider": {"slider": "B", "guide": {"through": [0, -0.01], "angle": 90}},
                  "rod": {"points": ["A", "B"], "length": 0.2}},
        "assembly": {"B": [0, -0.2]}},
    "RRP on a moving guide (the rocker)": {
        "ground": FOUR_BAR["ground"],
        "links": {**FOUR_BAR["links"],
                  "rod": {"points": ["E", "D"], "length": 0.3},
                  "block": {"slider": "D", "guide": {"link": "rocker"}}},
        "assembly": {"B": [0.33, 0.21], "D": [0.36, 0.3]}},
    "RPR (slotted lever)": {
        "ground": {"O": [0, 0], "O1": [0, -0.3]},
        "links": {"crank": {"points": ["O", "A"], "length": 0.11},
                  "block": {"slider": "A", "guide": {"link": "rocker"}},
                  "rocker": {"points": ["O1", "B"], "length": 0.55},
                  "rod": {"points": ["B", "C"], "length": 0.16},
                  "ram": {"slider": "C", "guide": {"through": [0, 0.26], "angle": 0}}},
        "assembly": {"A": [0.11, 0], "B": [0.15, 0.23], "C": [0.31, 0.26]}},
    "PRP on a moving guide (slotted ram)": {
        "ground": {"O": [0, 0], "O1": [0, -0.32]},
        "links": {"crank": {"points": ["O", "A"], "length": 0.12},
                  "block": {"slider": "A", "guide": {"link": "rocker"}},
                  "rocker": {"points": ["O1", "B"], "length": 0.8},
                  "blockC": {"slider": "C", "guide": {"link": "rocker"}},
                  "ram": {"slider": "C", "guide": {"through": [0, 0.4], "angle": 0}}},
        "assembly": {"A": [0.12, 0], "C": [0.24, 0.4]}},
    "RRP on a translating guide (the Scotch yoke's)": {
        "ground": {"O": [0, 0]},
        "links": {"crank": {"points": ["O", "A"], "length": 0.06, "extra": {"E": [0.02, 0.03]}},
                  "block": {"slider": "A", "guide": {"link": "yoke", "angle": 90}},
                  "yoke": {"slider": "Y", "extra": {"P": [0.25, 0.1]}, "guide": {"through": "O", "angle": 0}},
                  "rod": {"points": ["E", "D"], "length": 0.2},
                  "block2": {"slider": "D", "guide": {"link": "yoke", "angle": 0, "offset": 0.1}}},
        "assembly": {"D": [0.2, 0.1]}},
    "PRP on a translating guide (the Scotch yoke's) and a fixed one": {
        "ground": {"O": [0, 0]},
        "links": {"crank": {"points": ["O", "A"], "length": 0.06},
                  "block": {"slider": "A", "guide": {"link": "yoke", "angle": 90}},
                  "yoke": {"slider": "Y", "extra": {"P": [0.25, 0.1]}, "guide": {"through": "O", "angle": 0}},
                  "block2": {"slider": "D", "guide": {"link": "yoke", "angle": 45, "offset": 0.05}},
                  "block3": {"slider": "D", "guide": {"through": [0.3, 0], "angle": 90}}}},
    "RPP (Scotch yoke)": {
        "ground": {"O": [0, 0]},
        "links": {"crank": {"points": ["O", "A"], "length": 0.06},
                  "block": {"slider": "A", "guide": {"link": "yoke", "angle": 90}},
                  "yoke": {"slider": "Y", "extra": {"P": [0.25, 0]}, "guide": {"through": "O", "angle": 0},
                           "com": [0.1, 0]}}},
}


def _both(mech, phi_deg, monkeypatch=None):
    """(the fast path's result, the general solver's result) of one call."""
    fst = sv._solve(mech, phi_deg, 1.0, 0.0)
    sv.FAST = False
    try:
        gen = sv._solve(mech, phi_deg, 1.0, 0.0)
    finally:
        sv.FAST = True
    return fst, gen


def _answers(mech, phi_deg) -> bool:
    solver = sv.get_solver(mech)
    steps = sv._fast_steps(solver)
    return steps is not None and fast.run(solver, steps, np.radians(phi_deg), 0) is not None


def _conditioning_tol(mech, phi_deg, tol=1e-12):
    """tol / s^2 at each position, s the least |normalised determinant| of the groups'
    velocity equations there (the general solver's): near a limit position both methods
    lose digits as 1/s (positions) to 1/s^2 (accelerations), whichever is right."""
    st = sv.get_solver(mech).run(np.radians(phi_deg), dets=True, strict=False, fallback=False)
    s = np.min(np.abs(np.array([st.gdet[g] for g in st.gdet])), axis=0)
    return tol / np.minimum(1.0, s) ** 2


def _assert_close(a, b, L, tol=1e-12):
    """a and b the same to tol (relative to the scale L and the values' magnitude); tol a
    number or one per position."""
    tol = np.asarray(tol, float)
    t2 = tol if tol.ndim == 0 else tol[:, None]
    assert sorted(a.pos) == sorted(b.pos) and sorted(a.angle) == sorted(b.angle)
    assert a.points == b.points and a.links == b.links
    for what in ("pos", "d1", "d2"):
        for p in b.pos:
            x, y = getattr(a, what)[p], getattr(b, what)[p]
            assert x.shape == y.shape == (len(a.phi), 2)
            scale = L * (1 + np.max(np.abs(y)) / L)
            assert (np.abs(x - y) <= t2 * scale).all(), (what, p, np.max(np.abs(x - y)))
    for what in ("angle", "a1", "a2"):
        for lk in b.angle:
            x, y = getattr(a, what)[lk], getattr(b, what)[lk]
            scale = 1 + np.max(np.abs(y))
            # the angles on the same branch (not only equal mod 2 pi)
            assert (np.abs(x - y) <= tol * scale).all(), (what, lk, np.max(np.abs(x - y)))
    assert (a.singular is None) == (b.singular is None)
    assert a.warnings == b.warnings


@pytest.mark.parametrize("name", sorted(CASES))
def test_every_dyad_kind_agrees_with_the_general_solver(name):
    mech = _mech(CASES[name])
    for phi in (np.arange(360) * 1.0, np.array([17.0]), np.random.default_rng(5).uniform(0, 360, 2000),
                np.arange(0.0, 360.0, 0.1)):
        assert _answers(mech, phi), name
        f, g = _both(mech, phi)
        _assert_close(f, g, sv.get_solver(mech).L)


@pytest.mark.parametrize("name", sorted(CASES))
def test_derivatives_are_those_of_the_positions(name):
    """d1, d2 (points) and a1, a2 (links) against central differences of the fast path's
    own positions and angles (h = 1e-4 rad: truncation ~1e-9 of the scale)."""
    mech = _mech(CASES[name])
    phi = np.arange(0.0, 360.0, 7.5) + 0.3
    h = math.degrees(1e-4)
    k, kp, km = (sv._solve(mech, phi + d, 1.0, 0.0) for d in (0.0, h, -h))
    L = sv.get_solver(mech).L
    for p in k.pos:
        d1 = (kp.pos[p] - km.pos[p]) / 2e-4
        d2 = (kp.pos[p] - 2 * k.pos[p] + km.pos[p]) / 1e-8
        s1 = 1 + np.max(np.abs(k.d1[p])) / L
        s2 = 1 + np.max(np.abs(k.d2[p])) / L
        assert np.max(np.abs(d1 - k.d1[p])) <= 1e-7 * L * s1, p
        assert np.max(np.abs(d2 - k.d2[p])) <= 1e-4 * L * s2, p
    for lk in k.angle:
        d1 = (kp.angle[lk] - km.angle[lk]) / 2e-4
        d2 = (kp.angle[lk] - 2 * k.angle[lk] + km.angle[lk]) / 1e-8
        assert np.max(np.abs(d1 - k.a1[lk])) <= 1e-7 * (1 + np.max(np.abs(k.a1[lk]))), lk
        assert np.max(np.abs(d2 - k.a2[lk])) <= 1e-4 * (1 + np.max(np.abs(k.a2[lk]))), lk


def _task_mechs():
    out = []
    for f in sorted(glob.glob("tasks/*.yaml")):
        t = prepare(f, assembly=False)      # a synthesis's mechanism generated
        if getattr(t, "mechanism", None) is not None:
            syn = getattr(t, "synthesis", None)
            # a function generator works over its input range (a double-rocker does not close
            # over the whole turn): its crank angles from the range's start to its end
            span = (float(syn.input.start), float(syn.input.start + syn.input.range)) \
                if getattr(syn, "type", None) == "function" else None
            out.append((f, build_mechanism(t), span))
    return out


def test_the_tasks_take_the_fast_path_and_agree():
    """Every linkage task but the class-III one is answered by the fast path, at the
    course positions and a fine grid, as the general solver answers it."""
    mechs = _task_mechs()
    assert len(mechs) >= 10
    for f, mech, span in mechs:
        covered = sv._fast_steps(sv.get_solver(mech)) is not None
        assert covered == ("triad" not in f), f
        grids = (np.arange(12) * 30.0, np.arange(3600) * 0.1) if span is None else \
            (np.mod(np.linspace(*span, 12), 360.0), np.mod(np.linspace(*span, 3600), 360.0))
        for phi in grids:
            if covered:
                assert _answers(mech, phi), f
            a, b = _both(mech, phi)
            _assert_close(a, b, sv.get_solver(mech).L)


def test_outputs_are_arrays_of_their_own():
    """No two outputs share memory (a consumer may change one in place)."""
    mech = _mech(CASES["RPR (slotted lever)"])
    k = sv._solve(mech, np.arange(24) * 15.0, 1.0, 0.0)
    arrays = [v for d in (k.pos, k.d1, k.d2, k.angle, k.a1, k.a2) for v in d.values()]
    for i, x in enumerate(arrays):
        for y in arrays[i + 1:]:
            assert not np.shares_memory(x, y)
    for d in (k.pos, k.d1, k.d2):
        for v in d.values():
            assert v.dtype == np.float64 and v.shape == (24, 2)
            v += 1.0                                       # writeable


def test_a_singular_position_goes_to_the_general_solver():
    """A parallelogram four-bar has change points (its links in line): the fast path does
    not answer there; the general solver gives the limits by continuity and the warning,
    bit for bit as without the fast path."""
    mech = _mech({"ground": {"O": [0, 0], "O3": [0.3, 0]},
                  "links": {"crank": {"points": ["O", "A"], "length": 0.1},
                            "coupler": {"points": ["A", "B"], "length": 0.3},
                            "rocker": {"points": ["O3", "B"], "length": 0.1}},
                  "assembly": {"B": [0.4, 0.0]}})
    phi = np.arange(12) * 30.0
    assert not _answers(mech, phi)
    f, g = _both(mech, phi)
    assert f.singular is not None and f.warnings
    for what in ("pos", "d1", "d2", "angle", "a1", "a2"):
        for key, v in getattr(g, what).items():
            assert getattr(f, what)[key].tobytes() == v.tobytes()
    # away from the change points the fast path answers
    assert _answers(mech, np.array([45.0, 100.0, 250.0]))


def test_an_angle_on_the_cut_goes_to_the_general_solver():
    """A link pointing along -x at the first position (its angle +-pi, where the two
    methods' arctan2 may round to either branch): the general solver answers, so the
    link's angle keeps the branch it always had."""
    # a slider-crank on a guide along -x: at phi = 180 deg the rod points along -x
    mech = _mech({"ground": {"O": [0, 0]},
                  "links": {"crank": {"points": ["O", "A"], "length": 0.05},
                            "rod": {"points": ["A", "B"], "length": 0.2},
                            "piston": {"slider": "B", "guide": {"through": "O", "angle": 180}}},
                  "assembly": {"B": [-0.25, 0]}})
    phi = np.array([180.0, 190.0, 200.0])
    assert not _answers(mech, phi)
    f, g = _both(mech, phi)
    for what in ("pos", "d1", "d2", "angle", "a1", "a2"):
        for key, v in getattr(g, what).items():
            assert getattr(f, what)[key].tobytes() == v.tobytes()
    assert _answers(mech, phi + 0.5)


def test_a_linkage_that_does_not_assemble_still_names_where():
    mech = _mech({"ground": {"O": [0, 0], "O3": [0.30, 0]},
                  "links": {"crank": {"points": ["O", "A"], "length": 0.2},
                            "coupler": {"points": ["A", "B"], "length": 0.15},
                            "rocker": {"points": ["O3", "B"], "length": 0.1}},
                  "assembly": {"B": [0.3, 0.1]}})
    from tmm_cli.errors import StageError
    with pytest.raises(StageError) as a:
        sv.solve(mech, np.arange(12) * 30.0)
    assert "does not assemble" in str(a.value) or "assemble" in str(a.value)


@settings(max_examples=60, deadline=None)
@given(a=hst.floats(0.02, 0.2), b=hst.floats(0.1, 0.6), c=hst.floats(0.1, 0.6), d=hst.floats(0.1, 0.6),
       up=hst.booleans(), n=hst.integers(1, 400), start=hst.floats(0, 360))
def test_random_four_bars_agree_with_the_general_solver(a, b, c, d, up, n, start):
    mech = _mech({"ground": {"O": [0, 0], "O3": [d, 0]},
                  "links": {"crank": {"points": ["O", "A"], "length": a},
                            "coupler": {"points": ["A", "B"], "length": b, "extra": {"E": [0.3 * b, 0.2 * b]}},
                            "rocker": {"points": ["O3", "B"], "length": c}},
                  "assembly": {"B": [d, c if up else -c]}})
    phi = (start + np.arange(n) * (360.0 / n)) % 360.0
    from tmm_cli.errors import StageError
    try:
        sv.FAST = False
        g = sv._solve(mech, phi, 1.0, 0.0)
    except StageError:
        return
    finally:
        sv.FAST = True
    f = sv._solve(mech, phi, 1.0, 0.0)
    _assert_close(f, g, sv.get_solver(mech).L, tol=_conditioning_tol(mech, phi))


@settings(max_examples=60, deadline=None)
@given(r=hst.floats(0.01, 0.1), lam=hst.floats(1.5, 6.0), off=hst.floats(-0.4, 0.4), ang=hst.floats(-180, 180),
       ahead=hst.booleans(), n=hst.integers(1, 400))
def test_random_slider_cranks_agree_with_the_general_solver(r, lam, off, ang, ahead, n):
    l = lam * r
    e = off * (l - r)
    t = math.radians(ang)
    gp = [-e * math.sin(t), e * math.cos(t)]
    sgn = 1 if ahead else -1
    mech = _mech({"ground": {"O": [0, 0]},
                  "links": {"crank": {"points": ["O", "A"], "length": r},
                            "rod": {"points": ["A", "B"], "length": l},
                            "piston": {"slider": "B", "guide": {"through": gp, "angle": ang}}},
                  "assembly": {"B": [gp[0] + sgn * l * math.cos(t), gp[1] + sgn * l * math.sin(t)]}})
    phi = np.arange(n) * (360.0 / n)
    sv.FAST = False
    try:
        g = sv._solve(mech, phi, 1.0, 0.0)
    finally:
        sv.FAST = True
    f = sv._solve(mech, phi, 1.0, 0.0)
    _assert_close(f, g, sv.get_solver(mech).L, tol=_conditioning_tol(mech, phi))


def _scaled(d, k):
    """A mechanism's data with every length times k (angles kept)."""
    if isinstance(d, dict):
        return {key: (v if key == "angle" else _scaled(v, k)) for key, v in d.items()}
    if isinstance(d, list):
        return [_scaled(v, k) for v in d]
    if isinstance(d, (int, float)) and not isinstance(d, bool):
        return d * k
    return d


@pytest.mark.parametrize("k", [1e-3, 1e3])
@pytest.mark.parametrize("name", sorted(CASES))
def test_every_kind_at_extreme_sizes_and_odd_angles(name, k):
    """Linkages a thousand times smaller and larger (a watch, a crane), crank angles
    unsorted, repeated, negative and beyond 360: the fast path answers (its tests are
    relative to the linkage's size) and agrees with the general solver."""
    mech = _mech(_scaled(CASES[name], k))
    rng = np.random.default_rng(11)
    assert _answers(mech, np.arange(0.0, 360.0, 7.0) + 0.3)
    for phi in (rng.uniform(-720, 720, 40), np.array([5.0, 5.0, 5.0]), np.array([359.999, 0.0, 0.001]),
                np.arange(0.0, 360.0, 0.5)[::-1]):
        f, g = _both(mech, phi)
        _assert_close(f, g, sv.get_solver(mech).L, tol=_conditioning_tol(mech, phi))
