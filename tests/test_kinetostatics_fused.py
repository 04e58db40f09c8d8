"""The kinetostatics' fused paths against the generic ones they replace, bit for bit, on
hypothesis-made geometries (any numbers: signed zeros, tiny and huge values, NaN, inf):
the scaled matrix of all equations, the groups' matrices, the Zhukovsky lever's couples
with shared arms and the powers with shared point velocities."""
from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from tmm_cli import load_task
from tmm_cli.linkage import structure
from tmm_cli.linkage.kinetostatics import equations as E, solve as S
from tmm_cli.linkage.loads import AppliedCouple, AppliedForce, Loads
from tmm_cli.linkage.mechanism import build_mechanism

from test_kinetostatics_pipeline import SIX          # the RRR + RRP six-bar

MECH = build_mechanism(load_task(SIX))
STRUCT = structure.analyze(MECH)
N = 5

special = st.sampled_from([0.0, -0.0, 1.0, -1.0, 1e-300, -1e-300, 1e300, np.nan, np.inf, -np.inf])
num = st.one_of(st.floats(-10.0, 10.0), st.floats(allow_nan=True, allow_infinity=True), special)
vec = st.lists(num, min_size=N, max_size=N).map(lambda v: np.array(v, float))
pts = st.lists(num, min_size=2 * N, max_size=2 * N).map(lambda v: np.array(v, float).reshape(N, 2))


@st.composite
def geometries(draw):
    """A Geometry of the six-bar with any numbers."""
    links = [lk.index for lk in MECH.links]
    jdir = [None if j.kind == "R" else draw(pts) for j in MECH.joints]
    return E.Geometry(N, {i: draw(pts) for i in links}, {i: draw(pts) for i in links},
                      {i: draw(vec) for i in links}, {i: draw(vec) for i in links}, [draw(pts) for _ in MECH.joints],
                      jdir, draw(vec), draw(vec), draw(st.sampled_from([1e-3, 0.3, 0.42, 7.0])))


def same(a: np.ndarray, b: np.ndarray) -> bool:
    """Bit for bit (every NaN alike)."""
    a, b = np.asarray(a), np.asarray(b)
    return a.shape == b.shape and (np.isnan(a) == np.isnan(b)).all() and \
        (np.where(np.isnan(a), 0.0, a).tobytes() == np.where(np.isnan(b), 0.0, b).tobytes())


@settings(max_examples=60, deadline=None)
@given(geometries(), st.sampled_from([lk.name for lk in MECH.links]))
@pytest.mark.filterwarnings("ignore::RuntimeWarning")
def test_scaled_matrix_is_the_full_matrix_scaled_bit_for_bit(geo, balance):
    b = MECH.link(balance).index
    rs, cs = E.scaling(MECH, geo.Lc, b)
    want = E.full_matrix(MECH, geo, b) * rs[None, :, None] * cs[None, None, :]
    assert same(E.scaled_matrix(MECH, geo, b, rs, cs), want)
    # not finite scales: the generic product itself
    rs2 = rs.copy()
    rs2[2] = np.inf
    assert same(E.scaled_matrix(MECH, geo, b, rs2, cs), E.full_matrix(MECH, geo, b) * rs2[None, :, None]
                * cs[None, None, :])


@settings(max_examples=40, deadline=None)
@given(geometries())
@pytest.mark.filterwarnings("ignore::RuntimeWarning")
def test_group_matrices_are_the_coefficient_blocks_bit_for_bit(geo):
    """The groups' matrices filled from the coefficients that are not zero by kind hold
    the (N, 3, 2) blocks of joint_coeffs exactly (checked through the inverses' input:
    the plan's inverse of each group equals the inverse of the matrix built from the blocks)."""
    plan = S._group_plan(MECH, STRUCT, geo)
    coeffs = [E.joint_coeffs(geo, j, k) for k, j in enumerate(MECH.joints)]
    solved: set[int] = set()
    for links, rows, unknown, known, inv, is_crank in plan:
        ncol = 2 * len(unknown) + (1 if is_crank else 0)
        A = np.zeros((N, 3 * len(links), ncol))
        for c, k in enumerate(unknown):
            for l, cf in coeffs[k].items():
                if l in rows:
                    A[:, 3 * rows[l]:3 * rows[l] + 3, 2 * c:2 * c + 2] = cf
        if is_crank:
            A[:, 3 * rows[MECH.drive] + 2, -1] = 1.0
        assert same(inv, S._safe_inverse(A))
        for k, i, cf in known:
            l = next(l for l, r in rows.items() if r == i)
            assert same(cf, coeffs[k][l])
        solved.update(links)


def _pair_generic(geo, link, M):
    """A couple on the lever as the pair of forces of its definition, its points' velocities
    made for it alone."""
    if link == 0:
        return np.zeros(geo.n_pos)
    l = geo.Lc
    u = np.tile([1.0, 0.0], (geo.n_pos, 1))
    pA = geo.origin[link]
    pB = pA + l * u
    F = (M / l)[:, None] * E.rot90(u)
    return E.cross(E.rot90(geo.point_vel(link, pB)), F) + E.cross(E.rot90(geo.point_vel(link, pA)), -F)


def _lever_generic(geo, loads):
    """The lever and the powers as made before the arms and velocities were shared: each
    couple's two points and each force's velocity made on their own."""
    tot = np.zeros(geo.n_pos)
    for f in loads.forces:
        if f.link:
            tot += E.cross(E.rot90(geo.point_vel(f.link, f.point)), f.F)
    for c in loads.couples:
        tot += _pair_generic(geo, c.link, c.M)
    each = [np.einsum("ij,ij->i", f.F, geo.point_vel(f.link, f.point)) if f.link else np.zeros(geo.n_pos)
            for f in loads.forces] + [c.M * geo.omega(c.link) for c in loads.couples]
    return tot, each


@settings(max_examples=60, deadline=None)
@given(geometries(), st.lists(st.tuples(st.integers(0, 5), pts, pts), max_size=4),
       st.lists(st.tuples(st.integers(0, 5), vec), max_size=6))
@pytest.mark.filterwarnings("ignore::RuntimeWarning")
def test_lever_and_powers_with_shared_arms_are_the_generic_ones_bit_for_bit(geo, forces, couples):
    loads = Loads(np.zeros(N), [AppliedForce(l, f"F{i}", p, F, "external") for i, (l, p, F) in enumerate(forces)],
                  [AppliedCouple(l, f"M{i}", M, "external") for i, (l, M) in enumerate(couples)])
    want, each = _lever_generic(geo, loads)
    vel, arms = S.point_velocities(geo, loads), {}
    assert same(S.lever_moments(MECH, geo, loads, vel, arms), want)
    assert same(S.lever_moments(MECH, geo, loads), want)
    got_tot, got_each = S.powers(MECH, geo, loads, vel)
    assert len(got_each) == len(each) and all(same(a, b) for a, b in zip(got_each, each))
    assert same(got_tot, np.sum(each, axis=0) if each else np.zeros(N))
    for lk in MECH.links:                   # the unit balancing couple, arms shared or not
        if lk.kind != "slider":
            want = _pair_generic(geo, lk.index, np.ones(N))
            assert same(S.balance_lever(MECH, geo, lk.index, arms), want)
            assert same(S.balance_lever(MECH, geo, lk.index), want)


def _load_vector_generic(geo, loads):
    """The load vector as one array added to load by load."""
    q = np.zeros((geo.n_pos, MECH.n + 1, 3))
    for f in loads.forces:
        if f.link:
            q[:, f.link, 0] += f.F[:, 0]
            q[:, f.link, 1] += f.F[:, 1]
            q[:, f.link, 2] += E.cross(f.point - geo.origin[f.link], f.F)
    for c in loads.couples:
        if c.link:
            q[:, c.link, 2] += c.M
    return q


@pytest.mark.filterwarnings("ignore::RuntimeWarning")
@settings(max_examples=60, deadline=None)
@given(geometries(), st.lists(st.tuples(st.integers(0, 5), pts, pts), max_size=5),
       st.lists(st.tuples(st.integers(0, 5), vec), max_size=7))
def test_load_vector_is_the_generic_one_bit_for_bit(geo, forces, couples):
    loads = Loads(np.zeros(N), [AppliedForce(l, f"F{i}", p, F, "external") for i, (l, p, F) in enumerate(forces)],
                  [AppliedCouple(l, f"M{i}", M, "external") for i, (l, M) in enumerate(couples)])
    assert same(E.load_vector(MECH, geo, loads), _load_vector_generic(geo, loads))


@pytest.mark.filterwarnings("ignore::RuntimeWarning")
@settings(max_examples=40, deadline=None)
@given(geometries(), st.lists(num, min_size=2 * N * len(MECH.joints), max_size=2 * N * len(MECH.joints)))
def test_friction_loads_with_the_motion_signs_made_once(geo, xs):
    """The friction loads with the relative motion's signs made once per geometry, with and
    without the losses, are those of np.sign / np.abs of relative_motion made at the call."""
    x = np.array(xs, float).reshape(N, -1)
    f, r, fs = 0.1, 0.01, 0.15
    ff, fc, loss = S.friction_loads(MECH, geo, x, f, r, fs)
    ff2, fc2, none = S.friction_loads(MECH, geo, x, f, r, fs, losses=False)
    assert none is None
    assert all(same(a.F, b.F) and a.link == b.link for a, b in zip(ff, ff2)) and len(ff) == len(ff2)
    assert all(same(a.M, b.M) and a.link == b.link for a, b in zip(fc, fc2)) and len(fc) == len(fc2)
    rel = S.relative_motion(MECH, geo)
    xf = np.where(np.isfinite(x), x, 0.0)
    c = iter(fc)
    fo = iter(ff)
    for k, j in enumerate(MECH.joints):
        # a relative motion within 1e-9 of the drive's (rad/rad; m/rad over the size) is none
        tol = 1e-9 * np.abs(geo.omega1) * (1.0 if j.kind == "R" else geo.Lc)
        sgn = np.where(np.abs(rel[:, k]) <= tol, 0.0, np.sign(rel[:, k]))
        if j.kind == "R":
            Mf = f * r * np.hypot(xf[:, 2 * k], xf[:, 2 * k + 1])
            assert same(next(c).M, -Mf * sgn)
            if j.a:
                assert same(next(c).M, Mf * sgn)
            assert same(loss[:, k], Mf * np.abs(rel[:, k]))
        else:
            Ff = fs * np.abs(xf[:, 2 * k])
            assert same(next(fo).F, -(Ff * sgn)[:, None] * geo.jdir[k])
            assert same(loss[:, k], Ff * np.abs(rel[:, k]))
