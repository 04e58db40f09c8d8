"""Kinematics against closed forms written out here, finite differences and fsolve."""
import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st
from scipy.optimize import fsolve

from tmm_cli.errors import StageError
from tmm_cli.linkage.kinematics import check_assembly, solve
from tmm_cli.linkage.kinematics import newton as nw
from tmm_cli.linkage.kinematics.solver import get_solver
from tmm_cli.linkage.mechanism import build_mechanism
from tmm_cli.task import load_task

TASKS = Path(__file__).resolve().parent.parent / "tasks"
PHI = np.arange(0.0, 360.0, 7.5)


def mech(links, ground, assembly=None):
    t = load_task({"schema": "tmm/1",
                   "mechanism": {"ground": ground, "links": links, "assembly": assembly or {}},
                   "drive": {"link": "crank", "speed": 10}})
    return build_mechanism(t)


def fd_check(m, phi, h=1e-5, tol1=1e-7, tol2=1e-6):
    """d1, d2, a1, a2 against central differences of the positions / d1."""
    r0 = solve(m, phi)
    rp = solve(m, phi + math.degrees(h))
    rm = solve(m, phi - math.degrees(h))
    for p in r0.pos:
        L = 1 + np.abs(r0.d1[p]).max()
        assert np.abs((rp.pos[p] - rm.pos[p]) / (2 * h) - r0.d1[p]).max() < tol1 * L, p
        L = 1 + np.abs(r0.d2[p]).max()
        assert np.abs((rp.d1[p] - rm.d1[p]) / (2 * h) - r0.d2[p]).max() < tol2 * L, p
    for k in r0.angle:
        assert np.abs((rp.angle[k] - rm.angle[k]) / (2 * h) - r0.a1[k]).max() < tol1 * (1 + np.abs(r0.a1[k]).max())
        assert np.abs((rp.a1[k] - rm.a1[k]) / (2 * h) - r0.a2[k]).max() < tol2 * (1 + np.abs(r0.a2[k]).max())
    return r0


# ------------------------------------------------------------------ RRP
def test_offset_slider_crank_closed_form():
    r, l, e = 0.1, 0.4, 0.03
    m = mech({"crank": {"points": ["O", "A"], "length": r}, "rod": {"points": ["A", "B"], "length": l},
              "slider": {"slider": "B", "guide": {"through": [0, e], "angle": 0}}}, {"O": [0, 0]})
    k = solve(m, PHI, omega1=10.0)
    f = np.radians(PHI)
    root = np.sqrt(l ** 2 - (r * np.sin(f) - e) ** 2)
    x = r * np.cos(f) + root
    dx = -r * np.sin(f) - (r * np.sin(f) - e) * r * np.cos(f) / root
    assert np.allclose(k.pos["B"][:, 0], x, atol=1e-14)
    assert np.allclose(k.pos["B"][:, 1], e, atol=1e-14)
    assert np.allclose(k.vel("B")[:, 0], 10.0 * dx, atol=1e-12)
    # d2x/dphi2 from the closed form differentiated once more
    u = r * np.sin(f) - e
    du = r * np.cos(f)
    d2x = -r * np.cos(f) - ((du * du - u * r * np.sin(f)) * root + u * du * (u * du) / root) / root ** 2
    assert np.allclose(k.d2["B"][:, 0], d2x, atol=1e-12)
    # the rod angle: sin(theta2) = (e - r sin phi)/l
    assert np.allclose(np.sin(k.angle["rod"]), (e - r * np.sin(f)) / l, atol=1e-14)
    fd_check(m, PHI)


# ------------------------------------------------------------------ RRR
def test_fourbar_freudenstein():
    a, b, c, d = 0.08, 0.30, 0.22, 0.30
    m = mech({"crank": {"points": ["O", "A"], "length": a}, "coupler": {"points": ["A", "B"], "length": b},
              "rocker": {"points": ["O3", "B"], "length": c}}, {"O": [0, 0], "O3": [d, 0]})
    k = solve(m, PHI, omega1=3.0)
    t2 = np.radians(PHI)
    t3 = k.angle["coupler"]
    t4 = k.angle["rocker"]
    K1, K2, K3 = d / a, d / c, (a * a - b * b + c * c + d * d) / (2 * a * c)
    assert np.abs(K1 * np.cos(t4) - K2 * np.cos(t2) + K3 - np.cos(t2 - t4)).max() < 1e-12
    # default closure: B left of A -> O3, i.e. above for O3 to the right
    assert (k.pos["B"][:, 1] > 0).all()
    w4 = a * np.sin(t3 - t2) / (c * np.sin(t3 - t4))
    w3 = a * np.sin(t4 - t2) / (b * np.sin(t3 - t4))
    assert np.allclose(k.omega("rocker"), 3.0 * w4, atol=1e-12)
    assert np.allclose(k.omega("coupler"), 3.0 * w3, atol=1e-12)
    fd_check(m, PHI)


def test_fourbar_assembly_hint_picks_other_closure():
    links = {"crank": {"points": ["O", "A"], "length": 0.08}, "coupler": {"points": ["A", "B"], "length": 0.30},
             "rocker": {"points": ["O3", "B"], "length": 0.22}}
    k = solve(mech(links, {"O": [0, 0], "O3": [0.3, 0]}, {"B": [0.3, -0.2]}), PHI)
    assert (k.pos["B"][:, 1] < 0).all()


# ------------------------------------------------------------------ RPR (shaper)
def test_slotted_lever_rpr():
    r, dd = 0.11, 0.30
    m = build_mechanism(load_task(TASKS / "shaper_slotted_lever.yaml"))
    k = solve(m, PHI, omega1=2.0, eps1=0.5)
    f = np.radians(PHI)
    psi = np.arctan2(dd + r * np.sin(f), r * np.cos(f))
    rho2 = r * r + dd * dd + 2 * r * dd * np.sin(f)
    i31 = r * (r + dd * np.sin(f)) / rho2
    di31 = r * dd * np.cos(f) / rho2 - r * (r + dd * np.sin(f)) * 2 * r * dd * np.cos(f) / rho2 ** 2
    assert np.allclose(np.cos(k.angle["rocker"]), np.cos(psi), atol=1e-13)
    assert np.allclose(np.sin(k.angle["rocker"]), np.sin(psi), atol=1e-13)
    assert np.allclose(k.a1["rocker"], i31, atol=1e-13)
    assert np.allclose(k.a2["rocker"], di31, atol=1e-12)
    assert np.allclose(k.epsilon("rocker"), 4.0 * di31 + 0.5 * i31, atol=1e-12)
    # the block's angle is the slotted link's (its guide), so its omega is the rocker's
    assert np.allclose(k.a1["block"], i31, atol=1e-13)
    # B at the end of the rocker
    assert np.allclose(k.pos["B"], np.array([0, -dd]) + 0.55 * np.stack([np.cos(psi), np.sin(psi)], 1), atol=1e-13)
    fd_check(m, PHI)


def test_slotted_lever_coriolis():
    """Relative acceleration of the block along the slot: A's absolute acceleration
    (the crank's r omega^2 inward) = a of the coincident rocker point + a_rel + 2 w x v_rel."""
    m = build_mechanism(load_task(TASKS / "shaper_slotted_lever.yaml"))
    f = np.radians(PHI)
    k = solve(m, PHI, omega1=1.0)
    r, dd = 0.11, 0.30
    rho = np.sqrt(r * r + dd * dd + 2 * r * dd * np.sin(f))
    drho = r * dd * np.cos(f) / rho                 # d|O1A|/dphi: relative sliding velocity
    d2rho = (-r * dd * np.sin(f) - drho ** 2) / rho
    w = k.a1["rocker"]
    eps = k.a2["rocker"]
    e = np.stack([np.cos(k.angle["rocker"]), np.sin(k.angle["rocker"])], 1)
    n = np.stack([-e[:, 1], e[:, 0]], 1)
    a_coinc = (eps * rho)[:, None] * n - (w ** 2 * rho)[:, None] * e
    a_rel = d2rho[:, None] * e
    a_cor = (2 * w * drho)[:, None] * n
    aA = -r * np.stack([np.cos(f), np.sin(f)], 1)
    assert np.allclose(a_coinc + a_rel + a_cor, aA, atol=1e-13)
    assert np.allclose(k.d2["A"], aA, atol=1e-14)


def test_oscillating_cylinder_rpr():
    # crank OA, rod AB sliding through a block pivoted at the ground point O2
    r = 0.1
    m = mech({"crank": {"points": ["O", "A"], "length": r}, "rod": {"points": ["A", "B"], "length": 0.6},
              "block": {"slider": "O2", "guide": {"link": "rod"}}}, {"O": [0, 0], "O2": [0.35, 0.05]})
    k = solve(m, PHI)
    f = np.radians(PHI)
    A = r * np.stack([np.cos(f), np.sin(f)], 1)
    v = np.array([0.35, 0.05]) - A
    th = np.arctan2(v[:, 1], v[:, 0])
    assert np.allclose(np.cos(k.angle["rod"]), np.cos(th), atol=1e-13)
    assert np.allclose(np.sin(k.angle["rod"]), np.sin(th), atol=1e-13)
    fd_check(m, PHI)


# ------------------------------------------------------------------ RPP, PRP, PRR, PPR
def test_scotch_yoke_rpp():
    m = build_mechanism(load_task(TASKS / "scotch_yoke_pump.yaml"))
    k = solve(m, PHI, omega1=5.0, eps1=2.0)
    f = np.radians(PHI)
    r = 0.06
    assert np.allclose(k.pos["Y"][:, 0], r * np.cos(f), atol=1e-14)
    assert np.allclose(k.pos["P"][:, 0], r * np.cos(f) + 0.25, atol=1e-14)
    assert np.allclose(k.vel("P")[:, 0], -5.0 * r * np.sin(f), atol=1e-13)
    assert np.allclose(k.acc("P")[:, 0], -25.0 * r * np.cos(f) - 2.0 * r * np.sin(f), atol=1e-12)
    assert np.allclose(k.acc("P")[:, 1], 0.0, atol=1e-14)
    fd_check(m, PHI)


def test_slotted_ram_prp():
    m = build_mechanism(load_task(TASKS / "shaper_slotted_ram.yaml"))
    k = solve(m, PHI)
    f = np.radians(PHI)
    r, dd, h = 0.12, 0.32, 0.40
    psi = np.arctan2(dd + r * np.sin(f), r * np.cos(f))
    x = (h + dd) / np.tan(psi)
    dpsi = r * (r + dd * np.sin(f)) / (r * r + dd * dd + 2 * r * dd * np.sin(f))
    assert np.allclose(k.pos["C"][:, 0], x, atol=1e-13)
    assert np.allclose(k.d1["C"][:, 0], -(h + dd) / np.sin(psi) ** 2 * dpsi, atol=1e-12)
    fd_check(m, PHI)


def test_block_on_crank_prr():
    d, c = 0.2, 0.45
    m = mech({"crank": {"points": ["O", "A"], "length": 0.1},
              "block": {"slider": "B", "guide": {"link": "crank"}},
              "rocker": {"points": ["O3", "B"], "length": c}}, {"O": [0, 0], "O3": [d, 0]})
    k = solve(m, PHI)
    f = np.radians(PHI)
    s = d * np.cos(f) + np.sqrt(c * c - d * d * np.sin(f) ** 2)
    assert np.allclose(k.pos["B"], s[:, None] * np.stack([np.cos(f), np.sin(f)], 1), atol=1e-14)
    fd_check(m, PHI)


def test_ppr_projection():
    d = 0.3
    m = mech({"crank": {"points": ["O", "A"], "length": 0.1},
              "block1": {"slider": "B", "guide": {"link": "crank"}},
              "block2": {"slider": "O3", "guide": {"link": "block1", "angle": 90}}},
             {"O": [0, 0], "O3": [d, 0]})
    k = solve(m, PHI)
    f = np.radians(PHI)
    # block1 sits at the foot of the perpendicular from O3 to the crank line
    assert np.allclose(k.pos["B"], (d * np.cos(f))[:, None] * np.stack([np.cos(f), np.sin(f)], 1), atol=1e-14)
    fd_check(m, PHI)


def test_moving_guide_offset():
    # slider on the coupler of a four-bar, guide shifted by 0.02 to the left and turned 30 deg
    m = mech({"crank": {"points": ["O", "A"], "length": 0.08}, "coupler": {"points": ["A", "B"], "length": 0.3},
              "rocker": {"points": ["O3", "B"], "length": 0.22},
              "arm": {"points": ["O5", "E"], "length": 0.25},
              "blk": {"slider": "E", "guide": {"link": "coupler", "angle": 30, "offset": 0.02}}},
             {"O": [0, 0], "O3": [0.3, 0], "O5": [0.1, 0.35]})
    k = solve(m, PHI)
    th = k.angle["coupler"] + math.radians(30)
    e = np.stack([np.cos(th), np.sin(th)], 1)
    n = np.stack([-e[:, 1], e[:, 0]], 1)
    # E lies on the guide line: n . (E - A) = offset, and |O5 E| = 0.25
    assert np.allclose(np.sum(n * (k.pos["E"] - k.pos["A"]), 1), 0.02, atol=1e-13)
    assert np.allclose(np.hypot(*(k.pos["E"] - [0.1, 0.35]).T), 0.25, atol=1e-13)
    assert np.allclose(np.mod(k.angle["blk"] - th + 1, 2 * np.pi) - 1, 0, atol=1e-13)
    fd_check(m, PHI)


# ------------------------------------------------------------------ class III vs fsolve
def test_triad_against_fsolve():
    m = build_mechanism(load_task(TASKS / "triad_class3.yaml"))
    k = solve(m, PHI)
    O2 = np.array([0.17, 0.17])
    uD = np.array([0.0, -0.137])

    def eqs(z, f):
        t1, tb, t3, xd = z
        A = 0.05 * np.array([math.cos(f), math.sin(f)])
        B = A + 0.187 * np.array([math.cos(t1), math.sin(t1)])
        C = B + 0.087 * np.array([math.cos(tb), math.sin(tb)])
        D = B + np.array([math.cos(tb) * uD[0] - math.sin(tb) * uD[1], math.sin(tb) * uD[0] + math.cos(tb) * uD[1]])
        C2 = O2 + 0.178 * np.array([math.cos(t3), math.sin(t3)])
        return [C[0] - C2[0], C[1] - C2[1], D[0] - xd, D[1] + 0.10]

    # march from the assembly hint (B, C, D at phi = 0) in small steps, independently
    B0, C0 = np.array([0.235, 0.024]), np.array([0.313, 0.063])
    z = np.array([math.atan2(*(B0 - [0.05, 0])[::-1]), math.atan2(*(C0 - B0)[::-1]),
                  math.atan2(*(C0 - O2)[::-1]), 0.296])
    res = {}
    for deg in np.arange(0.0, 360.0, 0.5):
        z = fsolve(eqs, z, args=(math.radians(deg),), xtol=1e-13)
        res[round(deg, 3)] = z.copy()
    for j, deg in enumerate(PHI):
        t1, tb, t3, xd = res[round(deg, 3)]
        assert abs(k.pos["D"][j, 0] - xd) < 1e-10
        assert abs(math.remainder(k.angle["leg"][j] - t1, 2 * math.pi)) < 1e-9
        assert abs(math.remainder(k.angle["base"][j] - tb, 2 * math.pi)) < 1e-9
        assert abs(math.remainder(k.angle["rocker"][j] - t3, 2 * math.pi)) < 1e-9
    fd_check(m, PHI)


# ------------------------------------------------------------------ every example
@pytest.mark.parametrize("name", ["engine_slider_crank.yaml", "press_offset_slider_crank.yaml",
                                  "crank_rocker_fourbar.yaml", "shaper_slotted_lever.yaml",
                                  "shaper_slotted_ram.yaml", "forging_sixbar.yaml",
                                  "scotch_yoke_pump.yaml", "triad_class3.yaml"])
def test_examples_assemble_and_close(name):
    m = build_mechanism(load_task(TASKS / name))
    check_assembly(m, 360)
    s = get_solver(m)
    st_ = s.run(np.radians(np.arange(0, 360, 0.5)))
    for plan in s.plans:
        assert np.abs(nw.residual(plan.cons, st_)).max() < 1e-12
    fd_check(m, np.arange(0.0, 360.0, 5.0))


def test_spec_sixbar_points_and_entries():
    m = build_mechanism(load_task(TASKS / "forging_sixbar.yaml"))
    k = solve(m, [0.0, 90.0, 400.0], omega1=np.array([5.0, 5.0, 5.0]), eps1=np.array([0.0, 1.0, 0.0]))
    # all points incl. ground pivots and centres of mass; K on the rocker at 0.25 from O1
    for p in ("O", "O1", "A", "B", "K", "D", "S1", "S2", "S3", "S4", "S5"):
        assert p in k.pos and k.pos[p].shape == (3, 2)
    assert np.allclose(np.hypot(*(k.pos["K"] - [0.5, 0.37]).T), 0.25)
    assert np.allclose(k.pos["S1"], 0.0)          # crank's default com: its pivot
    assert np.allclose(k.pos["S2"], 0.5 * (k.pos["A"] + k.pos["B"]))
    ent = k.to_entries([0, 1, 2])
    assert ent[2]["phi"] == pytest.approx(40.0)
    e = ent[1]
    assert set(e["points"]["B"]) >= {"x", "y", "vx", "vy", "v", "ax", "ay", "a", "vqx", "vqy", "aqx", "aqy"}
    assert e["points"]["B"]["vx"] == pytest.approx(5.0 * e["points"]["B"]["vqx"])
    assert e["points"]["B"]["ax"] == pytest.approx(25.0 * e["points"]["B"]["aqx"] + 1.0 * e["points"]["B"]["vqx"])
    assert e["links"]["crank"]["angle"] == pytest.approx(90.0)
    assert e["links"]["slider"] == {"angle": pytest.approx(90.0), "omega": 0.0, "epsilon": 0.0,
                                    "i": 0.0, "iq2": 0.0}
    for en in ent:
        for lk in en["links"].values():
            assert 0.0 <= lk["angle"] < 360.0
    # the same position one turn later has the same state
    assert np.allclose(k.pos["D"][2], solve(m, [40.0]).pos["D"][0], atol=1e-13)


# ------------------------------------------------------------------ errors and singular positions
def test_non_assembling_fourbar_interval():
    a, b, c, d = 0.2, 0.3, 0.25, 0.5     # |AO3| > b + c around phi = 180: the crank cannot turn
    m = mech({"crank": {"points": ["O", "A"], "length": a}, "coupler": {"points": ["A", "B"], "length": b},
              "rocker": {"points": ["O3", "B"], "length": c}}, {"O": [0, 0], "O3": [d, 0]})
    # edges: |AO3|^2 = a^2 + d^2 - 2 a d cos(phi) = (b + c)^2  (|AO3| >= d - a > |b - c| always)
    edge = math.degrees(math.acos((a * a + d * d - (b + c) ** 2) / (2 * a * d)))
    with pytest.raises(StageError) as ei:
        solve(m, [0.0, 180.0])
    msg = str(ei.value)
    assert ei.value.stage == "kinematics"
    assert ei.value.position == pytest.approx(180.0)
    assert "group II(2,3) (links coupler, rocker) does not assemble" in msg
    lo, hi = (float(x) for x in msg.split("crank angles ")[1].split(" deg")[0].split(".."))
    assert lo == pytest.approx(edge, abs=1e-6)
    assert hi == pytest.approx(360.0 - edge, abs=1e-6)
    assert "|AO3| = 0.7 m > |AB| + |BO3|" in msg          # at the middle of the interval, phi = 180
    solve(m, [0.0, 30.0])                                  # outside the interval it solves
    with pytest.raises(StageError):
        check_assembly(m)


def test_parallelogram_change_point_is_finite():
    m = mech({"crank": {"points": ["O", "A"], "length": 0.1}, "coupler": {"points": ["A", "B"], "length": 0.3},
              "rocker": {"points": ["O3", "B"], "length": 0.1}}, {"O": [0, 0], "O3": [0.3, 0]})
    k = solve(m, [0.0, 10.0, 180.0])
    for arr in list(k.d1.values()) + list(k.d2.values()) + list(k.a1.values()):
        assert np.isfinite(arr).all()
    assert any("singular" in w for w in k.warnings)


# ------------------------------------------------------------------ property tests
@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
@given(a=st.floats(0.02, 0.1), b=st.floats(0.25, 0.6), c=st.floats(0.2, 0.5), d=st.floats(0.2, 0.5),
       up=st.booleans())
def test_random_fourbars(a, b, c, d, up):
    lens = sorted([a, b, c, d])
    assume(a == lens[0] and lens[0] + lens[3] < lens[1] + lens[2] - 1e-3)   # Grashof, crank shortest
    m = mech({"crank": {"points": ["O", "A"], "length": a}, "coupler": {"points": ["A", "B"], "length": b},
              "rocker": {"points": ["O3", "B"], "length": c}}, {"O": [0, 0], "O3": [d, 0]},
             {"B": [d, c if up else -c]})
    k = fd_check(m, np.arange(0.0, 360.0, 15.0), tol1=1e-6, tol2=1e-5)
    assert np.abs(np.hypot(*(k.pos["B"] - k.pos["A"]).T) - b).max() < 1e-9
    assert np.abs(np.hypot(*(k.pos["B"] - [d, 0]).T) - c).max() < 1e-9


@settings(max_examples=25, deadline=None)
@given(r=st.floats(0.02, 0.1), l=st.floats(0.25, 0.6), e=st.floats(-0.1, 0.1), ang=st.floats(-60, 60))
def test_random_slider_cranks(r, l, e, ang):
    assume(abs(e) + r < 0.95 * l)
    a = math.radians(ang)
    pt = [-e * math.sin(a), e * math.cos(a)]      # guide at distance e from O
    m = mech({"crank": {"points": ["O", "A"], "length": r}, "rod": {"points": ["A", "B"], "length": l},
              "slider": {"slider": "B", "guide": {"through": pt, "angle": ang}}}, {"O": [0, 0]})
    k = fd_check(m, np.arange(0.0, 360.0, 15.0), tol1=1e-6, tol2=1e-5)
    assert np.abs(np.hypot(*(k.pos["B"] - k.pos["A"]).T) - l).max() < 1e-9
    n = np.array([-math.sin(a), math.cos(a)])
    assert np.abs(k.pos["B"] @ n - e).max() < 1e-12


@settings(max_examples=15, deadline=None)
@given(dx=st.floats(-0.05, 0.05), dy=st.floats(-0.05, 0.05), kk=st.floats(0.15, 0.4), l4=st.floats(0.7, 1.0))
def test_random_sixbars(dx, dy, kk, l4):
    m = mech({"crank": {"points": ["O", "A"], "length": 0.15}, "rod": {"points": ["A", "B"], "length": 0.97},
              "rocker": {"points": ["O1", "B"], "length": 0.66, "extra": {"K": [kk, 0]}},
              "link4": {"points": ["K", "D"], "length": l4},
              "slider": {"slider": "D", "guide": {"through": "O1", "angle": 90}}},
             {"O": [0, 0], "O1": [0.5 + dx, 0.37 + dy]})
    k = fd_check(m, np.arange(0.0, 360.0, 15.0), tol1=1e-6, tol2=1e-5)
    assert np.abs(np.hypot(*(k.pos["D"] - k.pos["K"]).T) - l4).max() < 1e-9
    assert np.abs(k.pos["D"][:, 0] - (0.5 + dx)).max() < 1e-12
