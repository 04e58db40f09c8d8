"""Kinetostatics against a hand free-body solution, a closed-form friction case,
closed-form singular positions, and the agreement of the four methods."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from tmm_cli.linkage import structure
from tmm_cli.linkage.kinetostatics import equilibrium, find_singular
from tmm_cli.linkage.loads import evaluate_on
from tmm_cli.results import listed
from tmm_cli.linkage.spec import KinetostaticsSection, LoadsSection

from test_kinetostatics_closedform import (FB, SC, four_bar_kin, four_bar_task, mech_of, slider_crank_kin,
                                           slider_crank_task)

g = 9.81


def sc_solver(m, phi, w, e=0.0):
    return slider_crank_kin(phi, omega1=w)


def fb_solver(m, phi, w, e=0.0):
    return four_bar_kin(phi, omega1=w)


def _run(task, kin, loads, ks, solver, **kw):
    mech = mech_of(task)
    st_ = structure.analyze(mech)
    sec = LoadsSection.model_validate(loads) if loads is not None else None
    lds = evaluate_on(mech, sec, kin, None, sign=1.0, cycle=360.0, inertia=ks.get("inertia", True))
    res = equilibrium(mech, st_, kin, lds, KinetostaticsSection.model_validate(ks), solver=solver, **kw)
    return mech, res, res.to_dict()


# ------------------------------------------------------------------ hand free-body solution
@pytest.mark.parametrize("phi", [0.0, 37.0, 90.0, 151.0, 200.0, 333.0])
def test_slider_crank_free_body_by_hand(phi):
    r = SC["r"]
    m1, J1, m2, J2, m3 = 1.2, 0.015, SC["m2"], SC["J2"], SC["m3"]
    w, eps = 12.0, 4.0
    P = 1500.0                                    # N along +x on the slider (no kind: signed)
    task = slider_crank_task(m1=m1, J1=J1)
    kin = slider_crank_kin([phi], omega1=w, eps1=eps)
    mech, res, d = _run(task, kin, {"gravity": True, "forces": [{"on": "slider", "magnitude": P}]}, {},
                        sc_solver)
    ent = d["kinetostatics"][0]
    # --- the hand solution (Artobolevsky's order: group 2-3 first, then the crank) ---
    A, B, S2 = kin.pos["A"][0], kin.pos["B"][0], kin.pos["S2"][0]
    aB = kin.d2["B"][0] * w ** 2 + kin.d1["B"][0] * eps
    aS2 = kin.d2["S2"][0] * w ** 2 + kin.d1["S2"][0] * eps
    eps2 = kin.a2["rod"][0] * w ** 2 + kin.a1["rod"][0] * eps
    Fi3 = -m3 * aB
    Fi2 = -m2 * aS2
    Mi2 = -J2 * eps2
    Mi1 = -J1 * eps
    G2 = np.array([0, -m2 * g])
    # slider, x: R23x + P + Fi3x = 0
    R23x = -(P + Fi3[0])
    # rod, moments about A: (B - A) x (-R23) + (S2 - A) x (G2 + Fi2) + Mi2 = 0
    F2 = G2 + Fi2
    cS = (S2 - A)[0] * F2[1] - (S2 - A)[1] * F2[0]
    R23y = ((B - A)[1] * R23x + cS + Mi2) / (B - A)[0]
    # slider, y: R23y + N - m3 g = 0
    N = m3 * g - R23y
    # rod, forces: R12 - R23 + G2 + Fi2 = 0
    R12 = np.array([R23x, R23y]) - F2
    # crank (centre of mass on O): R01 - R12 + G1 = 0; moments about O: A x (-R12) + Mi1 + Mb = 0
    R01 = R12 - np.array([0, -m1 * g])
    Mb = A[0] * R12[1] - A[1] * R12[0] - Mi1
    rx = ent["reactions"]
    assert ent["balancing_moment"] == pytest.approx(Mb, rel=1e-10, abs=1e-9)
    assert ent["balancing_force"] == pytest.approx(Mb / r, rel=1e-10, abs=1e-9)
    assert [rx["R23"]["x"], rx["R23"]["y"]] == pytest.approx([R23x, R23y], rel=1e-10, abs=1e-9)
    assert [rx["R12"]["x"], rx["R12"]["y"]] == pytest.approx(list(R12), rel=1e-10, abs=1e-9)
    assert [rx["R01"]["x"], rx["R01"]["y"]] == pytest.approx(list(R01), rel=1e-10, abs=1e-9)
    assert rx["R03"]["N"] == pytest.approx(N, rel=1e-10, abs=1e-9)      # n = +y for a guide along +x
    assert rx["R03"]["R"] == pytest.approx(abs(N), rel=1e-10)
    assert rx["R03"]["M"] == pytest.approx(0.0, abs=1e-9)              # all forces on 3 pass its pin
    assert rx["R01"]["R"] == pytest.approx(math.hypot(*R01), rel=1e-10)
    assert ent["inertia"]["rod"] == pytest.approx({"Fx": Fi2[0], "Fy": Fi2[1], "M": Mi2}, rel=1e-12)
    assert ent["inertia"]["slider"]["Fx"] == pytest.approx(Fi3[0], rel=1e-12)
    assert ent["inertia"]["crank"] == pytest.approx({"Fx": 0, "Fy": 0, "M": Mi1}, abs=1e-12)
    for key in ("zhukovsky_moment", "virtual_power_moment", "matrix_moment"):
        assert ent[key] == pytest.approx(Mb, rel=1e-9)
    assert ent["discrepancy"] < 1e-9
    assert ent["near_singular"] is False and ent["efficiency"] is None


def test_prismatic_point_of_action_by_hand():
    """A couple on the slider moves the guide's normal force off the pin: x = M03 / N."""
    kin = slider_crank_kin([60.0])
    mech, res, d = _run(slider_crank_task(m2=0, J2=0, m3=0), kin,
                        {"forces": [{"on": "slider", "moment": 30.0}, {"on": "slider", "magnitude": 800}]},
                        {"inertia": False}, sc_solver)
    r03 = d["kinetostatics"][0]["reactions"]["R03"]
    # slider: couple 30 + M03 = 0 (all forces through the pin) -> M03 = -30
    assert r03["M"] == pytest.approx(-30.0, rel=1e-12)
    assert r03["offset"] == pytest.approx(-30.0 / r03["N"], rel=1e-12)
    assert r03["point"][0] == pytest.approx(kin.pos["B"][0, 0] + r03["offset"], rel=1e-12)


# ------------------------------------------------------------------ friction, closed form
def test_slider_friction_closed_form_at_90_deg():
    """Centric, massless slider-crank at phi = 90 deg, force P along +x on the slider which
    moves toward -x; the rod is a two-force member (pin friction made negligible):
    T (ux - f r / l) = -P, N = T r / l, M_b = -r T ux; eta = P r / M_b = (ux - f r/l) / ux."""
    r, l, f, P = SC["r"], SC["l"], 0.15, 1000.0
    kin = slider_crank_kin([90.0], e=0.0)
    task = slider_crank_task(e=0.0, m2=0, J2=0, m3=0)
    mech, res, d = _run(task, kin, {"forces": [{"on": "slider", "magnitude": P}]},
                        {"inertia": False, "friction": {"pin_radius": 1e-12, "f": f}}, sc_solver)
    ux = math.sqrt(l ** 2 - r ** 2) / l
    T = -P / (ux - f * r / l)
    ent = d["kinetostatics"][0]
    assert ent["balancing_moment"] == pytest.approx(-r * T * ux, rel=1e-9)
    assert ent["reactions"]["R03"]["R"] == pytest.approx(abs(T) * r / l, rel=1e-9)
    assert ent["efficiency"] == pytest.approx((ux - f * r / l) / ux, rel=1e-9)
    assert ent["zhukovsky_moment"] == pytest.approx(ent["balancing_moment"], rel=1e-9)


def test_friction_losses_equal_the_extra_driving_power():
    """With friction: M_b w1 + sum of the powers of the task/inertia loads = sum of the pair
    losses f r |R| |w_rel| + f |N| |v_rel|, recomputed here from the reported reactions."""
    phi = np.arange(5.0, 360.0, 30.0)
    w = 10.0
    kin = slider_crank_kin(phi, omega1=w)
    f, rp = 0.12, 0.015
    task = slider_crank_task(m1=1.0, J1=0.01)
    loads = {"gravity": True, "forces": [{"on": "slider", "magnitude": -2000}]}
    mech, res, d = _run(task, kin, loads, {"friction": {"pin_radius": rp, "f": f}}, sc_solver)
    mech0, res0, d0 = _run(task, kin, loads, {}, sc_solver)
    om = {"crank": np.full(len(phi), w), "rod": kin.a1["rod"] * w, "slider": 0 * phi}
    for i, (e, e0) in enumerate(zip(d["kinetostatics"], d0["kinetostatics"])):
        rx = e["reactions"]
        loss = (f * rp * rx["R01"]["R"] * abs(om["crank"][i]) + f * rp * rx["R12"]["R"] * abs(om["rod"][i] - w)
                + f * rp * rx["R23"]["R"] * abs(om["rod"][i]) + f * rx["R03"]["R"] * abs(kin.d1["B"][i, 0] * w))
        # without friction M_b0 w = -P_loads; with friction M_b w = -P_loads + loss
        assert e["balancing_moment"] * w == pytest.approx(e0["balancing_moment"] * w + loss, rel=1e-9, abs=1e-7)
        assert e["friction_power"] == pytest.approx(loss, rel=1e-9)
        assert e["zhukovsky_moment"] == pytest.approx(e["balancing_moment"], rel=1e-9, abs=1e-9)
        if e["efficiency"] is not None:
            assert e["efficiency"] == pytest.approx(1 - loss / e["driving_power"], rel=1e-12)


# ------------------------------------------------------------------ flywheel couple, variable speed
def test_crank_inertia_adds_J_eps1_and_variable_speed_keeps_methods_equal():
    phi = np.arange(0.0, 360.0, 30.0)
    w = 10 + 0.5 * np.sin(np.radians(phi))
    eps = 0.5 * np.cos(np.radians(phi)) * w          # d(w)/dt = dw/dphi * w
    kin = slider_crank_kin(phi, omega1=w, eps1=eps)
    task = slider_crank_task(m1=1.0, J1=0.01)
    loads = {"forces": [{"on": "slider", "magnitude": -700}]}
    _, r0, d0 = _run(task, kin, loads, {}, sc_solver)
    _, r1, d1 = _run(task, kin, loads, {}, sc_solver, crank_inertia=2.5)
    for i, (a, b) in enumerate(zip(d0["kinetostatics"], d1["kinetostatics"])):
        assert b["balancing_moment"] - a["balancing_moment"] == pytest.approx(2.5 * eps[i], rel=1e-9, abs=1e-9)
        for e in (a, b):
            assert e["zhukovsky_moment"] == pytest.approx(e["balancing_moment"], rel=1e-9, abs=1e-9)
            assert e["virtual_power_moment"] == pytest.approx(e["balancing_moment"], rel=1e-9, abs=1e-9)


# ------------------------------------------------------------------ all methods agree, equilibrium
FB_LOADS = {"gravity": True, "forces": [{"on": "rocker", "moment": -40.0},
                                        {"on": "coupler", "magnitude": 300, "direction": 250, "at": [0.2, 0.05]}]}


@pytest.mark.parametrize("balance", [None, "crank", "coupler", "rocker"])
def test_four_bar_methods_agree(balance):
    phi = np.arange(0.0, 360.0, 30.0) + 7.0
    kin = four_bar_kin(phi, omega1=15.0, eps1=3.0)
    ks = {} if balance is None else {"balance": balance}
    mech, res, d = _run(four_bar_task(), kin, FB_LOADS, ks, fb_solver)
    for e in d["kinetostatics"]:
        if e["near_singular"]:
            continue
        m = e["balancing_moment"]
        for key in ("zhukovsky_moment", "virtual_power_moment", "matrix_moment"):
            assert e[key] == pytest.approx(m, rel=1e-9, abs=1e-9 * 100)
        assert e["matrix_discrepancy"] < 1e-9
    json.dumps(listed(d), allow_nan=False)


def test_slider_balance_methods_agree():
    phi = np.arange(0.0, 360.0, 30.0) + 11.0
    kin = slider_crank_kin(phi, omega1=8.0)
    mech, res, d = _run(slider_crank_task(m1=1.0, J1=0.01), kin, {"gravity": True, "forces": [
        {"on": "crank", "moment": 25.0}]}, {"balance": "slider"}, sc_solver)
    for e in d["kinetostatics"]:
        assert e["balancing_moment"] is None
        for key in ("zhukovsky_force", "virtual_power_force", "matrix_force"):
            assert e[key] == pytest.approx(e["balancing_force"], rel=1e-9)


@settings(max_examples=40, deadline=None)
@given(st.floats(0, 359.9), st.floats(-500, 500), st.floats(0, 360), st.floats(-50, 50),
       st.sampled_from(["crank", "coupler", "rocker"]), st.floats(-20, 20))
def test_whole_mechanism_is_in_equilibrium(phi, P, dirn, M, balance, eps):
    """Sum of all external loads, inertia loads, ground reactions (and the balancing
    couple) is zero: force and moment about the origin."""
    kin = four_bar_kin([phi], omega1=9.0, eps1=eps)
    loads = {"gravity": True, "forces": [{"on": "coupler", "magnitude": P, "direction": dirn, "at": [0.1, -0.02]},
                                         {"on": "rocker", "moment": M}]}
    mech, res, d = _run(four_bar_task(), kin, loads, {"balance": balance}, fb_solver, singular=[])
    e = d["kinetostatics"][0]
    if not res.ok[0] or abs(res.cond[0]) > 1e6:
        return
    Fs, Ms = np.zeros(2), 0.0
    for f in e["loads"]:
        Fs += f["F"]
        Ms += f["point"][0] * f["F"][1] - f["point"][1] * f["F"][0]
    for c in e["couples"]:
        Ms += c["M"]
    for key, rr in e["reactions"].items():
        if key.startswith("R0"):                 # force of the ground on a link
            Fs += [rr["x"], rr["y"]]
            Ms += rr["point"][0] * rr["y"] - rr["point"][1] * rr["x"]
    Ms += e["balancing_moment"]
    scale = sum(abs(np.hypot(*f["F"])) for f in e["loads"]) + abs(M) + abs(e["balancing_moment"]) + 1.0
    assert np.allclose(Fs, 0, atol=1e-9 * scale)
    assert abs(Ms) < 1e-9 * scale


# ------------------------------------------------------------------ singular positions
def _fb_dead_points():
    """Crank angles where crank and coupler are collinear (cosine rule in O-C-B, B above OC):
    extended |OB| = b + a at the angle of B; folded |OB| = b - a, A opposite to B."""
    a, b, c, d = FB["a"], FB["b"], FB["c"], FB["d"]
    ext = math.degrees(math.acos(((a + b) ** 2 + d ** 2 - c ** 2) / (2 * (a + b) * d)))
    fold = math.degrees(math.acos(((b - a) ** 2 + d ** 2 - c ** 2) / (2 * (b - a) * d))) + 180.0
    return sorted([ext, fold])


def test_singular_positions_of_a_rocker_balance_by_the_cosine_rule():
    mech = mech_of(four_bar_task())
    got = find_singular(mech, structure.analyze(mech), "rocker", solver=fb_solver)
    exp = _fb_dead_points()
    assert len(got) == 2
    assert got == pytest.approx(exp, abs=1e-6)
    # the crank as balance link: never singular for a crank-rocker
    assert find_singular(mech, None, "crank", solver=fb_solver) == []


def test_singular_positions_of_a_coupler_balance_crank_parallel_to_rocker():
    """omega_coupler = 0 when the crank is parallel to the rocker: sin(phi - theta3) = 0."""
    mech = mech_of(four_bar_task())
    got = find_singular(mech, None, "coupler", solver=fb_solver)
    assert len(got) == 2
    for phi in got:
        t3 = four_bar_kin([phi]).angle["rocker"][0]
        assert abs(math.sin(math.radians(phi) - t3)) < 1e-8


def test_slider_balance_singular_where_crank_and_rod_are_collinear():
    mech = mech_of(slider_crank_task())
    got = find_singular(mech, None, "slider", solver=sc_solver)
    r, l, e = SC["r"], SC["l"], SC["e"]
    exp = [math.degrees(math.asin(e / (r + l))), 180 + math.degrees(math.asin(e / (l - r)))]
    assert got == pytest.approx(exp, abs=1e-6)


def test_at_and_near_a_singular_position_numbers_are_null_or_finite_and_flagged():
    sing = _fb_dead_points()
    phi = np.array([sing[0], sing[0] + 0.5, sing[0] + 3.0, sing[1] - 1e-9])
    kin = four_bar_kin(phi)
    mech, res, d = _run(four_bar_task(), kin, FB_LOADS, {"balance": "rocker"}, fb_solver)
    text = json.dumps(listed(d), allow_nan=False)        # never NaN / inf
    e0, e1, e2, e3 = d["kinetostatics"]
    assert e0["near_singular"] and e0["balancing_moment"] is None and e0["reactions"]["R12"]["x"] is None
    assert e3["near_singular"] and e3["balancing_moment"] is None
    assert e1["near_singular"] and e1["balancing_moment"] is not None
    assert e1["zhukovsky_moment"] == pytest.approx(e1["balancing_moment"], rel=1e-6)
    assert not e2["near_singular"]
    assert d["singular"] == pytest.approx(sing, abs=1e-6)
    assert "Infinity" not in text


def test_conditioning_certificate_never_clears_an_ill_conditioned_matrix():
    """The Cholesky certificate that spares the SVD: True only when cond_2 < 1.5e6
    (checked by the SVD on matrices of prescribed singular values), and it clears the
    well-conditioned ones; matrix by matrix: an ill-conditioned or not finite one among
    them is left undecided, the others cleared."""
    from tmm_cli.linkage.kinetostatics.solve import _certified
    rng = np.random.default_rng(7)
    m = 15
    for c in [1.0, 10.0, 1e3, 1e5, 1e6, 2e6, 1e8, 1e12, 1e17]:
        As = []
        for _ in range(20):
            U, _r = np.linalg.qr(rng.normal(size=(m, m)))
            V, _r = np.linalg.qr(rng.normal(size=(m, m)))
            s = np.geomspace(1.0, 1.0 / c, m) * 10.0 ** rng.uniform(-3, 3)
            As.append((U * s) @ V.T)
        As = np.array(As)
        cond = np.linalg.cond(As)
        got = _certified(As)
        assert got.dtype == bool and got.shape == (20,)
        assert np.all(cond[got] < 1.5e6)
        assert np.all(got[cond < 1e5])
        assert np.array_equal(got, [bool(_certified(A[None])[0]) for A in As])   # each on its own
    good = np.tile(np.eye(m), (4, 1, 1))
    assert _certified(good).all()
    good[2, :, 3] = 0.0                              # a singular matrix among them
    assert _certified(good).tolist() == [True, True, False, True]
    good[1, 3, 3] = np.nan
    assert _certified(good).tolist() == [True, False, False, True]
    assert not _certified(np.tile(np.eye(31), (2, 1, 1))).any()     # beyond the proof's m <= 30


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 2 ** 32 - 1), st.floats(0.0, 9.0), st.floats(0.05, 0.9))
def test_conditioning_certificate_on_sparse_matrices(seed, log_cond, density):
    """Matrices with zeros where the equilibrium systems have them (a random pattern, a
    few columns and rows of one nonzero): the certificate only clears cond_2 < 1.5e6, and
    clears every matrix of cond_2 < 1e5 the dense LAPACK Cholesky of the same Gram matrix
    clears too (the sparse factorisation is the dense one with its exact zeros skipped)."""
    from tmm_cli.linkage.kinetostatics.solve import _certified
    rng = np.random.default_rng(seed)
    m = int(rng.integers(3, 16))
    mask = rng.random((m, m)) < density
    mask[np.arange(m), rng.permutation(m)] = True             # structurally nonsingular
    As = rng.normal(size=(30, m, m)) * 10.0 ** rng.uniform(-log_cond, 0, size=(30, 1, m)) * mask
    As[::7, :, 0] *= 1e-9                                     # some badly scaled ones
    got = _certified(As)
    cond = np.linalg.cond(As)
    assert np.all(cond[got] < 1.5e6)
    for A, g, c in zip(As, got, cond):
        G = A.T @ A
        G[np.arange(m), np.arange(m)] -= 1e-12 * np.trace(G)
        try:
            dense = bool(np.all(np.isfinite(np.linalg.cholesky(G))))
        except np.linalg.LinAlgError:
            dense = False
        if c < 1e5:
            assert g and dense


@pytest.mark.parametrize("balance", ["rocker", "coupler", "crank"])
def test_matrix_method_flags_the_positions_the_svd_condition_number_flags(balance):
    """The stage's conditioning decision equals cond_2 (SVD) < COND_MAX position by position,
    on a fine grid with the singular angles and angles 1e-9 deg, 1e-7 deg off them."""
    from tmm_cli.linkage.kinetostatics.equations import geometry
    from tmm_cli.linkage.kinetostatics.solve import COND_MAX, condition_numbers, matrix_method
    mech = mech_of(four_bar_task())
    b = mech.link(balance).index
    sing = np.array(find_singular(mech, None, balance, solver=fb_solver))
    phi = np.concatenate([np.linspace(0.0, 360.0, 5000, endpoint=False), sing, sing + 1e-9, sing - 1e-7])
    geo = geometry(mech, four_bar_kin(phi))
    q = np.random.default_rng(1).normal(size=(len(phi), mech.n + 1, 3))
    _, _, well, _ = matrix_method(mech, geo, q, b, with_det=False)
    cond = condition_numbers(mech, geo, b)
    assert np.array_equal(well, cond < COND_MAX)
    assert (balance == "crank") == bool(np.all(well))
