"""The stage dof2 (METHODS 7): rotary impact mechanism = rotor O-O1 + striker hinged at O1.

Every check is against an independent value:
* energy conservation (no moment, no gravity) with T computed here from the physical
  formula 1/2 J_O w^2 + 1/2 m2 v_C^2 + 1/2 J_C w2^2 with v_C differentiated here;
* the centrifugal pendulum: rotor held at Omega, small oscillations of the striker at
  omega_n = Omega sqrt(m l l_c / (J2 + m l_c^2)) (derivation in the test);
* the equations of motion against a Newton-Euler formulation written here (both links
  free bodies, the reactions unknowns, a 6x6 linear system) at random states;
* the published equations (9) of V.V. Voronkin (reference/rotary-impact-mechanism-ocr.txt)
  in the paper's own angle convention;
* the reactions: R + G - m a_S = 0 for each link with a_S by finite differences of the
  centre-of-mass positions computed here from phi(t), psi(t);
* the double pendulum limit against the textbook equations (Landau & Lifshitz,
  Mechanics, par. 5 problem 1) integrated here.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from tmm_cli.dof2 import Dof2Section, analyze, model
from tmm_cli.dof2.model import Params
from tmm_cli.errors import StageError

G = 9.81


def run(sec: dict) -> dict:
    return analyze(Dof2Section.model_validate(sec)).to_dict()


def arr(x):
    return np.asarray(x, dtype=float)


BASE = {"rotor": {"length": 0.08, "mass": 1.5, "com": 0.02, "J": 0.004},
        "striker": {"length": 0.12, "com": 0.07, "mass": 0.4, "J": 3e-4}}


def sec_with(**kw):
    d = {k: dict(v) if isinstance(v, dict) else v for k, v in BASE.items()}
    d.update(kw)
    return d


# ------------------------------------------------------------------ energy
def kinetic_energy_here(d: dict, r: dict) -> np.ndarray:
    """T = 1/2 J_O w^2 + 1/2 m2 |v_C|^2 + 1/2 J_C w2^2, v_C from C = O1 + l_c e(phi+psi)."""
    ro, sk = d["rotor"], d["striker"]
    J_O = ro["J"] + ro["mass"] * ro["com"] ** 2
    phi, psi = np.radians(arr(r["phi"])), np.radians(arr(r["psi"]))
    w, pd = arr(r["omega"]), arr(r["psi_dot"])
    th, w2 = phi + psi, w + pd
    l, lc = ro["length"], sk["com"]
    vx = -l * np.sin(phi) * w - lc * np.sin(th) * w2
    vy = l * np.cos(phi) * w + lc * np.cos(th) * w2
    return 0.5 * J_O * w ** 2 + 0.5 * sk["mass"] * (vx ** 2 + vy ** 2) + 0.5 * sk["J"] * w2 ** 2


def potential_here(d: dict, r: dict) -> np.ndarray:
    ro, sk = d["rotor"], d["striker"]
    phi, psi = np.radians(arr(r["phi"])), np.radians(arr(r["psi"]))
    yS1 = ro["com"] * np.sin(phi)
    yC = ro["length"] * np.sin(phi) + sk["com"] * np.sin(phi + psi)
    return G * (ro["mass"] * yS1 + sk["mass"] * yC)


def test_energy_conserved_without_moment_and_gravity():
    d = sec_with(initial={"phi": 10, "psi": 40, "omega": 30, "psi_dot": -50}, t_end=0.5, samples=801)
    r = run(d)
    T = kinetic_energy_here(d, r)
    assert np.ptp(T) / T[0] < 1e-8
    assert r["energy"]["relative_error"] < 1e-8
    # the motion is not trivial: the striker really swings relative to the rotor
    assert np.ptp(r["psi"]) > 30
    # and the reported T is the physical one
    assert np.allclose(r["energy"]["T"], T, rtol=1e-12)


def test_energy_with_gravity_and_constant_moment():
    """T + V - M (phi - phi0) = const: the work of a constant moment is M * angle."""
    M = 0.7
    d = sec_with(gravity=True, drive={"moment": M}, initial={"phi": -30, "psi": 90, "omega": 2},
                 t_end=1.0, samples=1001)
    r = run(d)
    T, V = kinetic_energy_here(d, r), potential_here(d, r)
    W = M * np.radians(arr(r["phi"]) - r["phi"][0])
    E = T + V - W
    assert np.max(np.abs(E - E[0])) / np.max(np.abs(W)) < 1e-8
    assert np.allclose(r["energy"]["W"], W, rtol=1e-8, atol=1e-10 * np.max(np.abs(W)))


def test_energy_with_speed_drive_work_of_the_motor():
    """Rotor held at Omega: the motor's work int M_d Omega dt (trapezoid here) = dT + dV."""
    Om = 40.0
    d = sec_with(gravity=True, drive={"speed": Om, "direction": "cw"}, initial={"psi": 120},
                 t_end=0.4, samples=20001)
    r = run(d)
    assert np.allclose(r["omega"], -Om)
    t, Md = arr(r["t"]), arr(r["driving_moment"])
    P = Md * arr(r["omega"])
    W = np.concatenate([[0.0], np.cumsum(0.5 * (P[1:] + P[:-1]) * np.diff(t))])
    dE = kinetic_energy_here(d, r) + potential_here(d, r)
    dE -= dE[0]
    assert np.max(np.abs(W - dE)) < 1e-6 * np.max(np.abs(dE))
    assert np.max(np.abs(dE)) > 0.1        # energy really flows in and out


# ------------------------------------------------------------------ centrifugal pendulum
def test_centrifugal_pendulum_small_oscillations():
    """Rotor at Omega = const, no gravity.  Lagrange's second equation with phi' = Omega:
        d/dt[(J2 + m lc^2)(Omega + psi') + m l lc Omega cos psi] + m l lc Omega (Omega + psi') sin psi = 0
        (J2 + m lc^2) psi'' - m l lc Omega psi' sin psi + m l lc Omega^2 sin psi + m l lc Omega psi' sin psi = 0
        (J2 + m lc^2) psi'' + m l lc Omega^2 sin psi = 0
    so small oscillations about psi = 0 have omega_n = Omega sqrt(m l lc / (J2 + m lc^2))."""
    Om = 100.0
    m, l, lc, J2 = 0.4, 0.08, 0.07, 3e-4
    wn = Om * math.sqrt(m * l * lc / (J2 + m * lc ** 2))
    period = 2 * math.pi / wn
    d = sec_with(drive={"speed": Om}, initial={"psi": 0.1}, t_end=5.2 * period, samples=20001)
    r = run(d)
    t, psi = arr(r["t"]), arr(r["psi"])
    i = np.nonzero(np.sign(psi[1:]) != np.sign(psi[:-1]))[0]
    tz = t[i] - psi[i] * (t[i + 1] - t[i]) / (psi[i + 1] - psi[i])   # zero crossings
    assert len(tz) >= 10
    measured = 2 * math.pi / np.mean(np.diff(tz[::2]))
    assert measured == pytest.approx(wn, rel=1e-6)
    assert abs(np.max(np.abs(psi)) - 0.1) < 1e-6           # amplitude kept (conservative)
    c = r["centrifugal"]
    assert c["omega_n"] == pytest.approx(wn, rel=1e-12)
    assert c["period"] == pytest.approx(period, rel=1e-12)


# ------------------------------------------------------------------ Newton-Euler
def cross(r, f):
    return r[0] * f[1] - r[1] * f[0]


def newton_euler(p: Params, J_S1: float, phi, psi, w, pd, M=None, held=False):
    """Both links as free bodies.  Unknowns: [phi'', theta'', R01x, R01y, R12x, R12y]
    (free rotor, moment M given) or [M, theta'', R01x, R01y, R12x, R12y] (phi'' = 0, held).
      rotor:   m1 a_S1 = R01 - R12 + G1;   J_S1 phi'' = M + (O - S1) x R01 + (O1 - S1) x (-R12)
      striker: m2 a_C = R12 + G2;          J_C theta'' = (O1 - C) x R12
    """
    th = phi + psi
    e1, n1 = np.array([math.cos(phi), math.sin(phi)]), np.array([-math.sin(phi), math.cos(phi)])
    e2, n2 = np.array([math.cos(th), math.sin(th)]), np.array([-math.sin(th), math.cos(th)])
    w2 = w + pd
    S1, O1 = p.s1 * e1, p.l * e1
    C = O1 + p.l_c * e2
    G1, G2 = np.array([0, -p.m1 * p.g]), np.array([0, -p.m2 * p.g])
    A = np.zeros((6, 6))
    b = np.zeros(6)
    # rotor translation: m1 s1 n1 phi'' - R01 + R12 = m1 s1 w^2 (-e1)... moved: = -m1 s1 w^2 e1 * (-1)
    for k in range(2):
        if not held:
            A[k, 0] = p.m1 * p.s1 * n1[k]
        A[k, 2 + k] = -1.0
        A[k, 4 + k] = 1.0
        b[k] = p.m1 * p.s1 * w ** 2 * e1[k] + G1[k]
    # rotor rotation about S1: J_S1 phi'' - (O-S1) x R01 + (O1-S1) x R12 [- M] = 0 (+M on the right)
    rO, rO1 = -S1, O1 - S1
    if held:
        A[2, 0] = -1.0
        b[2] = 0.0
    else:
        A[2, 0] = J_S1
        b[2] = M
    A[2, 2], A[2, 3] = rO[1], -rO[0]                  # -(rO x R01) = -(rOx R01y - rOy R01x)
    A[2, 4], A[2, 5] = -rO1[1], rO1[0]                # +(rO1 x R12)
    # striker translation: m2 (l n1 phi'' + lc n2 theta'') - R12 = m2 (l w^2 e1 + lc w2^2 e2) + G2
    for k in range(2):
        if not held:
            A[3 + k, 0] = p.m2 * p.l * n1[k]
        A[3 + k, 1] = p.m2 * p.l_c * n2[k]
        A[3 + k, 4 + k] = -1.0
        b[3 + k] = p.m2 * (p.l * w ** 2 * e1[k] + p.l_c * w2 ** 2 * e2[k]) + G2[k]
    # striker rotation about C: J_C theta'' - (O1 - C) x R12 = 0
    rC = O1 - C
    A[5, 1] = p.J_C
    A[5, 4], A[5, 5] = rC[1], -rC[0]
    x = np.linalg.solve(A, b)
    return x


pos = st.floats(0.02, 0.3)
ang = st.floats(-math.pi, math.pi)
rate = st.floats(-60, 60)


@settings(max_examples=60, deadline=None)
@given(l=pos, s1=st.floats(-0.1, 0.1), m1=st.floats(0.1, 5), JS=st.floats(1e-4, 1e-2), lc=st.floats(-0.1, 0.3),
       m2=st.floats(0.05, 3), JC=st.floats(1e-5, 1e-2), phi=ang, psi=ang, w=rate, pd=rate,
       M=st.floats(-20, 20), grav=st.booleans())
def test_equations_against_newton_euler(l, s1, m1, JS, lc, m2, JC, phi, psi, w, pd, M, grav):
    p = Params(l=l, m1=m1, s1=s1, J_O=JS + m1 * s1 ** 2, l_M=0.1, l_c=lc, m2=m2, J_C=JC, g=G if grav else 0.0)
    phi_dd, th_dd, R01x, R01y, R12x, R12y = newton_euler(p, JS, phi, psi, w, pd, M=M)
    a1, a2 = model.accelerations(p, phi, psi, w, pd, M)
    scale = 1 + abs(phi_dd) + abs(th_dd)
    assert a1 == pytest.approx(phi_dd, abs=1e-9 * scale)
    assert a2 == pytest.approx(th_dd - phi_dd, abs=1e-9 * scale)
    R01, R12 = model.reactions(p, phi, psi, w, pd, a1, a2)
    Rs = 1 + math.hypot(R01x, R01y) + math.hypot(R12x, R12y)
    assert np.allclose(R01, [R01x, R01y], atol=1e-9 * Rs)
    assert np.allclose(R12, [R12x, R12y], atol=1e-9 * Rs)

    # rotor held at phi' = w: the motor's moment and the striker's motion
    Mh, thh, *R = newton_euler(p, JS, phi, psi, w, pd, held=True)
    psi_dd, Md = model.held_speed(p, phi, psi, w, pd)
    assert psi_dd == pytest.approx(thh, abs=1e-9 * (1 + abs(thh)))
    assert Md == pytest.approx(Mh, abs=1e-9 * (1 + abs(Mh)))


@settings(max_examples=40, deadline=None)
@given(l=pos, lc=st.floats(0.01, 0.3), m=st.floats(0.05, 3), J1=st.floats(1e-4, 1e-2), J2=st.floats(1e-5, 1e-2),
       phi=ang, psi=ang, w=rate, pd=rate)
def test_voronkin_equations_9(l, lc, m, J1, J2, phi, psi, w, pd):
    """Voronkin's (9), horizontal, no moment, his psi_p = psi - 180 deg (from O1 -> O):
        A phi'' + C psi'' + B psi' (2 phi' + psi') = 0,   C phi'' + D psi'' - B phi'^2 = 0
        A = J1 + m l^2 + J2 + m lc^2 - 2 m l lc cos psi_p,  B = m l lc sin psi_p,
        C = J2 + m lc^2 - m l lc cos psi_p,  D = J2 + m lc^2."""
    pp = psi - math.pi
    A = J1 + m * l ** 2 + J2 + m * lc ** 2 - 2 * m * l * lc * math.cos(pp)
    B = m * l * lc * math.sin(pp)
    Cc = J2 + m * lc ** 2 - m * l * lc * math.cos(pp)
    D = J2 + m * lc ** 2
    p = Params(l=l, m1=0.0, s1=0.0, J_O=J1, l_M=l, l_c=lc, m2=m, J_C=J2)
    f, g = model.accelerations(p, phi, psi, w, pd, 0.0)
    # residuals of the paper's equations (robust where the mass matrix is ill-conditioned)
    scale = (abs(A) + abs(Cc)) * (abs(f) + abs(g)) + m * l * lc * (w ** 2 + abs(pd * (2 * w + pd))) + 1e-300
    assert abs(A * f + Cc * g + B * pd * (2 * w + pd)) <= 1e-12 * scale
    assert abs(Cc * f + D * g - B * w ** 2) <= 1e-12 * scale


# ------------------------------------------------------------------ reactions vs centre-of-mass motion
def test_reactions_theorem_on_the_motion_of_the_centre_of_mass():
    """R12 + G2 - m2 a_C = 0 and R01 - R12 + G1 - m1 a_S1 = 0, a_S by central differences
    of the centres of mass computed here from phi(t), psi(t)."""
    d = sec_with(gravity=True, drive={"moment": 1.5}, initial={"phi": 20, "psi": -60, "omega": 5, "psi_dot": 10},
                 t_end=0.6, samples=30001)
    r = run(d)
    ro, sk = d["rotor"], d["striker"]
    t = arr(r["t"])
    h = t[1] - t[0]
    phi, psi = np.radians(arr(r["phi"])), np.radians(arr(r["psi"]))
    S1 = ro["com"] * np.stack([np.cos(phi), np.sin(phi)], 1)
    C = ro["length"] * np.stack([np.cos(phi), np.sin(phi)], 1) + sk["com"] * np.stack(
        [np.cos(phi + psi), np.sin(phi + psi)], 1)
    R01 = np.stack([arr(r["reactions"]["R01"]["x"]), arr(r["reactions"]["R01"]["y"])], 1)
    R12 = np.stack([arr(r["reactions"]["R12"]["x"]), arr(r["reactions"]["R12"]["y"])], 1)
    rng = np.random.default_rng(7)
    idx = rng.integers(1, len(t) - 1, 25)
    aC = (C[idx + 1] - 2 * C[idx] + C[idx - 1]) / h ** 2
    aS = (S1[idx + 1] - 2 * S1[idx] + S1[idx - 1]) / h ** 2
    G1 = np.array([0, -ro["mass"] * G])
    G2 = np.array([0, -sk["mass"] * G])
    scale = np.max(np.hypot(*R01.T)) + np.max(np.hypot(*R12.T))
    assert np.max(np.abs(R12[idx] + G2 - sk["mass"] * aC)) < 1e-5 * scale
    assert np.max(np.abs(R01[idx] - R12[idx] + G1 - ro["mass"] * aS)) < 1e-5 * scale
    # the magnitudes reported are those of the components
    assert np.allclose(r["reactions"]["R01"]["R"], np.hypot(*R01.T))
    # maxima are over the samples
    assert r["max"]["R12"]["value"] == pytest.approx(np.max(np.hypot(*R12.T)))


# ------------------------------------------------------------------ double pendulum
def test_landau_lifshitz_double_pendulum_limit():
    """Point masses m1 at l1 (rotor: com = length, J = 0), m2 at l2 (striker: com = length,
    J = 0), gravity on, no moment.  Textbook (Landau & Lifshitz par. 5, angles from the
    downward vertical, theta1 = phi + 90 deg, theta2 = phi + psi + 90 deg):
      (m1+m2) l1 th1'' + m2 l2 th2'' cos(th1-th2) + m2 l2 th2'^2 sin(th1-th2) + (m1+m2) g sin th1 = 0
      l2 th2'' + l1 th1'' cos(th1-th2) - l1 th1'^2 sin(th1-th2) + g sin th2 = 0"""
    from scipy.integrate import solve_ivp
    m1, m2, l1, l2 = 1.3, 0.7, 0.5, 0.35

    def rhs(t, y):
        t1, t2, w1, w2 = y
        c, s = math.cos(t1 - t2), math.sin(t1 - t2)
        A = np.array([[(m1 + m2) * l1, m2 * l2 * c], [l1 * c, l2]])
        b = np.array([-m2 * l2 * w2 ** 2 * s - (m1 + m2) * G * math.sin(t1), l1 * w1 ** 2 * s - G * math.sin(t2)])
        return [w1, w2, *np.linalg.solve(A, b)]
    th1, th2, w1, w2 = 1.2, -0.4, 0.5, -1.0
    t_end = 1.5
    ref = solve_ivp(rhs, (0, t_end), [th1, th2, w1, w2], method="DOP853", rtol=1e-12, atol=1e-13,
                    t_eval=np.linspace(0, t_end, 31))
    d = {"rotor": {"length": l1, "mass": m1, "com": l1, "J": 0.0},
         "striker": {"length": l2, "mass": m2, "com": l2, "J": 0.0},
         "gravity": True,
         "initial": {"phi": math.degrees(th1) - 90, "psi": math.degrees(th2 - th1),
                     "omega": w1, "psi_dot": w2 - w1},
         "t_end": t_end, "samples": 31}
    r = run(d)
    assert np.allclose(np.radians(r["phi"]) + math.pi / 2, ref.y[0], atol=1e-7)
    assert np.allclose(np.radians(arr(r["phi"]) + arr(r["psi"])) + math.pi / 2, ref.y[1], atol=1e-7)
    assert np.allclose(r["omega"], ref.y[2], atol=1e-6)
    assert np.allclose(r["omega2"], ref.y[3], atol=1e-6)
    # the point M is the lower bob: x = l1 sin th1 + l2 sin th2, y = -l1 cos th1 - l2 cos th2
    xM = l1 * np.sin(ref.y[0]) + l2 * np.sin(ref.y[1])
    yM = -l1 * np.cos(ref.y[0]) - l2 * np.cos(ref.y[1])
    assert np.allclose(r["points"]["M"]["x"], xM, atol=1e-7)
    assert np.allclose(r["points"]["M"]["y"], yM, atol=1e-7)
    # the tension of the upper rod at the start (bobs at rest would give (m1+m2) g ...):
    # here R01 = (m1 + m2) * a_cm-weighted + weight: check the vertical balance of the whole system
    # at t = 0: R01 + (m1+m2) g_vec = m1 a1 + m2 a2 (accelerations from the textbook rhs)
    acc = rhs(0, [th1, th2, w1, w2])
    e1 = lambda th: np.array([math.sin(th), -math.cos(th)])        # noqa: E731 bob direction
    t1d = lambda th: np.array([math.cos(th), math.sin(th)])        # noqa: E731 d e1/d th
    a1 = l1 * (acc[2] * t1d(th1) - w1 ** 2 * e1(th1))
    a2 = a1 + l2 * (acc[3] * t1d(th2) - w2 ** 2 * e1(th2))
    R01_ref = m1 * a1 + m2 * a2 - np.array([0, -(m1 + m2) * G])
    assert np.allclose([r["reactions"]["R01"]["x"][0], r["reactions"]["R01"]["y"][0]], R01_ref, rtol=1e-9)


# ------------------------------------------------------------------ closed forms of the drive
def test_impact_time_with_held_speed():
    """omega1 = const: the rotor reaches phi = 270 deg from 0 at t = (3 pi / 2) / omega1."""
    Om = 1500 * math.pi / 30
    d = sec_with(drive={"speed": "1500 rpm"}, initial={"psi": 150}, t_end="40 ms", samples=101,
                 impact={"phi": 270})
    r = run(d)
    assert r["impact"]["t"] == pytest.approx(1.5 * math.pi / Om, rel=1e-9)
    assert r["impact"]["phi"] == pytest.approx(270, abs=1e-7)
    assert len(r["impacts"]) == 1
    # the speed of M at the hit: |v_M| from phi', psi' at the hit (computed here)
    imp = r["impact"]
    phi, th = math.radians(imp["phi"]), math.radians(imp["phi"] + imp["psi"])
    l, lM = 0.08, 0.12
    vx = -l * math.sin(phi) * Om - lM * math.sin(th) * (Om + imp["psi_dot"])
    vy = l * math.cos(phi) * Om + lM * math.cos(th) * (Om + imp["psi_dot"])
    assert imp["M"]["v"] == pytest.approx(math.hypot(vx, vy), rel=1e-12)
    # stop at the hit: the motion ends there
    d["impact"] = {"phi": 270, "stop": True}
    r2 = run(d)
    assert r2["t_end"] == pytest.approx(1.5 * math.pi / Om, rel=1e-9)
    assert r2["psi"][-1] == pytest.approx(imp["psi"], abs=1e-7)


def test_turns_with_held_speed_and_with_a_moment():
    """Held speed: t = 2 pi n / omega1.  A moment M from rest with the striker's centre
    of mass at the hinge (l_c = 0, b = 0): the equations decouple, (J_O + m2 l^2) phi'' = M,
    so n turns take t = sqrt(2 * 2 pi n (J_O + m2 l^2) / M) and theta'' = 0."""
    Om = 50.0
    r = run(sec_with(drive={"speed": Om}, turns=2, samples=11))
    assert r["t_end"] == pytest.approx(4 * math.pi / Om, rel=1e-12)
    d = sec_with(drive={"moment": 2.0}, turns=1.5, samples=51)
    d["striker"]["com"] = 0.0
    r = run(d)
    J_O = 0.004 + 1.5 * 0.02 ** 2
    a = J_O + 0.4 * 0.08 ** 2
    assert r["t_end"] == pytest.approx(math.sqrt(2 * 2 * math.pi * 1.5 * a / 2.0), rel=1e-8)
    assert np.allclose(r["omega2"], 0, atol=1e-9)
    assert np.allclose(r["epsilon"], 2.0 / a, rtol=1e-9)


def test_errors_on_uncomputable_input():
    d = {"rotor": {"length": 0.1}, "striker": {"length": 0.1, "mass": 1.0, "com": 0.1}, "t_end": 1}
    with pytest.raises(StageError, match="singular"):
        run(d)
    d = sec_with(turns=1, t_max=0.5)            # free, at rest: never turns
    with pytest.raises(StageError, match="turns"):
        run(d)
    r = run(sec_with(drive={"speed": 10}, t_end=0.1, impact={"phi": 270}))
    assert r["impact"] is None and any("impact angle" in w for w in r["warnings"])


def test_results_are_json_plain():
    import json
    r = run(sec_with(gravity=True, drive={"moment": 0.5}, t_end=0.2, samples=21, impact={"phi": 5}))
    text = json.dumps(r, allow_nan=False)
    assert '"dof2"' not in text and len(r["t"]) == 21
    for k in ("t", "phi", "psi", "omega", "psi_dot", "epsilon", "psi_ddot", "driving_moment"):
        assert len(r[k]) == 21
