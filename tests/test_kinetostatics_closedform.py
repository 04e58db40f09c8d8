"""Closed-form kinematics of a slider-crank and a four-bar, written independently of
tmm_cli.linkage.kinematics, shaped like a KinematicsResult; used by the loads and
kinetostatics tests. The tests in this file check the closed forms themselves
against central finite differences (so a typo in a derivative cannot pass)."""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pytest

from tmm_cli.linkage.mechanism import build_mechanism
from tmm_cli.task import load_task


@dataclass
class Kin:
    phi: np.ndarray
    omega1: float | np.ndarray
    eps1: float | np.ndarray
    pos: dict = field(default_factory=dict)
    d1: dict = field(default_factory=dict)
    d2: dict = field(default_factory=dict)
    angle: dict = field(default_factory=dict)
    a1: dict = field(default_factory=dict)
    a2: dict = field(default_factory=dict)
    singular: np.ndarray | None = None          # the fields of KinematicsResult the force analysis reads
    near: np.ndarray | None = None
    undefined: dict = field(default_factory=dict)

    def vel(self, p):
        return self.d1[p] * np.asarray(self.omega1)[..., None]

    def acc(self, p):
        w = np.asarray(self.omega1)[..., None]
        e = np.asarray(self.eps1)[..., None]
        return self.d2[p] * w ** 2 + self.d1[p] * e

    def omega(self, l):
        return self.a1[l] * self.omega1

    def epsilon(self, l):
        return self.a2[l] * np.asarray(self.omega1) ** 2 + self.a1[l] * self.eps1


def _v(x, y):
    return np.stack([np.broadcast_to(x, np.shape(x) if np.ndim(x) else np.shape(y)),
                     np.broadcast_to(y, np.shape(y) if np.ndim(y) else np.shape(x))], axis=-1).astype(float)


# ------------------------------------------------------------------ slider-crank
SC = dict(r=0.1, l=0.4, e=0.02, m2=5.0, J2=0.08, m3=8.0, m1=0.0, J1=0.0)


def slider_crank_task(r=SC["r"], l=SC["l"], e=SC["e"], m1=SC["m1"], J1=SC["J1"], m2=SC["m2"], J2=SC["J2"],
                      m3=SC["m3"], s2=None, speed=10.0, extra=None):
    links = {
        "crank": {"points": ["O", "A"], "length": r, "mass": m1, "J": J1},
        "rod": {"points": ["A", "B"], "length": l, "mass": m2, "J": J2},
        "slider": {"slider": "B", "guide": {"through": [0.0, e], "angle": 0}, "mass": m3},
    }
    if s2 is not None:
        links["rod"]["com"] = list(s2)
    d = {"schema": "tmm/1", "mechanism": {"ground": {"O": [0, 0]}, "links": links},
         "drive": {"link": "crank", "speed": speed, "direction": "ccw"}}
    if extra:
        d.update(extra)
    return d


def slider_crank_kin(phi_deg, omega1=10.0, eps1=0.0, r=SC["r"], l=SC["l"], e=SC["e"], s2=(None, 0.0)):
    """Closed form: A = r(cos p, sin p); l sin t2 = e - r sin p; x_B = r cos p + l cos t2."""
    phi_deg = np.atleast_1d(np.asarray(phi_deg, float))
    p = np.radians(phi_deg)
    c, s = np.cos(p), np.sin(p)
    st2 = (e - r * s) / l
    t2 = np.arcsin(st2)                         # the rod points to the right (|t2| < 90)
    ct2 = np.cos(t2)
    t2p = -r * c / (l * ct2)
    t2pp = (r * s + l * st2 * t2p ** 2) / (l * ct2)
    xb = r * c + l * ct2
    xbp = -r * s - l * st2 * t2p
    xbpp = -r * c - l * ct2 * t2p ** 2 - l * st2 * t2pp
    z = np.zeros_like(p)
    k = Kin(phi_deg, omega1, eps1)
    k.pos["O"], k.d1["O"], k.d2["O"] = _v(z, z), _v(z, z), _v(z, z)
    k.pos["A"], k.d1["A"], k.d2["A"] = _v(r * c, r * s), _v(-r * s, r * c), _v(-r * c, -r * s)
    k.pos["B"], k.d1["B"], k.d2["B"] = _v(xb, e + z), _v(xbp, z), _v(xbpp, z)
    u2 = l / 2 if s2[0] is None else s2[0]
    v2 = s2[1]
    # S2 = A + R(t2) (u2, v2)
    rx, ry = u2 * ct2 - v2 * st2, u2 * st2 + v2 * ct2
    jx, jy = -ry, rx
    k.pos["S2"] = k.pos["A"] + _v(rx, ry)
    k.d1["S2"] = k.d1["A"] + _v(jx * t2p, jy * t2p)
    k.d2["S2"] = k.d2["A"] + _v(jx * t2pp - rx * t2p ** 2, jy * t2pp - ry * t2p ** 2)
    k.pos["S1"], k.d1["S1"], k.d2["S1"] = k.pos["O"], k.d1["O"], k.d2["O"]
    k.pos["S3"], k.d1["S3"], k.d2["S3"] = k.pos["B"], k.d1["B"], k.d2["B"]
    k.angle.update(crank=p, rod=t2, slider=z)
    k.a1.update(crank=z + 1.0, rod=t2p, slider=z)
    k.a2.update(crank=z, rod=t2pp, slider=z)
    return k


# ------------------------------------------------------------------ four-bar
FB = dict(a=0.08, b=0.30, c=0.25, d=0.28)   # crank OA, coupler AB, rocker CB, frame OC


def four_bar_task(a=FB["a"], b=FB["b"], c=FB["c"], d=FB["d"], masses=(0.5, 2.0, 1.5), J=(0.001, 0.02, 0.01),
                  speed=10.0):
    return {"schema": "tmm/1",
            "mechanism": {"ground": {"O": [0, 0], "C": [d, 0]},
                          "links": {"crank": {"points": ["O", "A"], "length": a, "mass": masses[0], "J": J[0],
                                              "com": [a / 2, 0]},
                                    "coupler": {"points": ["A", "B"], "length": b, "mass": masses[1], "J": J[1]},
                                    "rocker": {"points": ["C", "B"], "length": c, "mass": masses[2], "J": J[2]}},
                          "assembly": {"B": [d, c]}},
            "drive": {"link": "crank", "speed": speed, "direction": "ccw"}}


def four_bar_kin(phi_deg, omega1=10.0, eps1=0.0, a=FB["a"], b=FB["b"], c=FB["c"], d=FB["d"], upper=True):
    """B = intersection of circles (A, b) and (C, c), on the upper side of AC;
    angle analogues from the differentiated loop a e1 + b e2 - c e3 - d i = 0."""
    phi_deg = np.atleast_1d(np.asarray(phi_deg, float))
    p = np.radians(phi_deg)
    A = _v(a * np.cos(p), a * np.sin(p))
    C = np.array([d, 0.0])
    AC = C - A
    L = np.linalg.norm(AC, axis=1)
    # angle at A between AC and AB by the cosine rule
    cosA = np.clip((b ** 2 + L ** 2 - c ** 2) / (2 * b * L), -1, 1)
    base = np.arctan2(AC[:, 1], AC[:, 0])
    t2 = base + (1 if upper else -1) * np.arccos(cosA)
    B = A + b * _v(np.cos(t2), np.sin(t2))
    t3 = np.arctan2(B[:, 1] - C[1], B[:, 0] - C[0])
    N = len(p)
    t2p, t3p, t2pp, t3pp = (np.zeros(N) for _ in range(4))
    for i in range(N):
        e2 = np.array([-np.sin(t2[i]), np.cos(t2[i])])
        e3 = np.array([-np.sin(t3[i]), np.cos(t3[i])])
        M = np.column_stack([b * e2, -c * e3])
        rhs = -a * np.array([-np.sin(p[i]), np.cos(p[i])])
        t2p[i], t3p[i] = np.linalg.solve(M, rhs)
        u1 = np.array([np.cos(p[i]), np.sin(p[i])])
        u2 = np.array([np.cos(t2[i]), np.sin(t2[i])])
        u3 = np.array([np.cos(t3[i]), np.sin(t3[i])])
        rhs2 = a * u1 + b * t2p[i] ** 2 * u2 - c * t3p[i] ** 2 * u3
        t2pp[i], t3pp[i] = np.linalg.solve(M, rhs2)
    z = np.zeros(N)
    k = Kin(phi_deg, omega1, eps1)
    k.pos["O"], k.d1["O"], k.d2["O"] = _v(z, z), _v(z, z), _v(z, z)
    k.pos["C"], k.d1["C"], k.d2["C"] = _v(z + d, z), _v(z, z), _v(z, z)
    k.pos["A"], k.d1["A"], k.d2["A"] = A, _v(-a * np.sin(p), a * np.cos(p)), -A
    u2 = _v(np.cos(t2), np.sin(t2))
    j2 = _v(-np.sin(t2), np.cos(t2))
    u3 = _v(np.cos(t3), np.sin(t3))
    j3 = _v(-np.sin(t3), np.cos(t3))
    k.pos["B"] = B
    k.d1["B"] = k.d1["A"] + b * j2 * t2p[:, None]
    k.d2["B"] = k.d2["A"] + b * (j2 * t2pp[:, None] - u2 * (t2p ** 2)[:, None])
    k.pos["S1"], k.d1["S1"], k.d2["S1"] = A / 2, k.d1["A"] / 2, k.d2["A"] / 2
    k.pos["S2"] = A + b / 2 * u2
    k.d1["S2"] = k.d1["A"] + b / 2 * j2 * t2p[:, None]
    k.d2["S2"] = k.d2["A"] + b / 2 * (j2 * t2pp[:, None] - u2 * (t2p ** 2)[:, None])
    k.pos["S3"] = C + c / 2 * u3
    k.d1["S3"] = c / 2 * j3 * t3p[:, None]
    k.d2["S3"] = c / 2 * (j3 * t3pp[:, None] - u3 * (t3p ** 2)[:, None])
    k.angle.update(crank=p, coupler=t2, rocker=t3)
    k.a1.update(crank=z + 1, coupler=t2p, rocker=t3p)
    k.a2.update(crank=z, coupler=t2pp, rocker=t3pp)
    return k


def mech_of(d):
    return build_mechanism(load_task(d))


# ------------------------------------------------------------------ self-checks
@pytest.mark.parametrize("make", [slider_crank_kin, four_bar_kin])
def test_closed_forms_match_finite_differences(make):
    phi = np.linspace(3.0, 357.0, 37)
    h = 1e-4                     # deg
    k0, kp, km = make(phi), make(phi + h), make(phi - h)
    hr = math.radians(h)
    for name in k0.pos:
        fd1 = (kp.pos[name] - km.pos[name]) / (2 * hr)
        fd2 = (kp.pos[name] - 2 * k0.pos[name] + km.pos[name]) / hr ** 2
        assert np.allclose(k0.d1[name], fd1, atol=1e-7), name
        assert np.allclose(k0.d2[name], fd2, atol=2e-4), name
        assert np.allclose(k0.d2[name], (kp.d1[name] - km.d1[name]) / (2 * hr), atol=1e-7), name
    for name in k0.angle:
        fd1 = (kp.angle[name] - km.angle[name]) / (2 * hr)
        assert np.allclose(k0.a1[name], fd1, atol=1e-7), name
        assert np.allclose(k0.a2[name], (kp.a1[name] - km.a1[name]) / (2 * hr), atol=1e-7), name


def test_closed_forms_close_their_loops():
    k = four_bar_kin(np.linspace(0, 359, 50))
    assert np.allclose(np.linalg.norm(k.pos["B"] - k.pos["A"], axis=1), FB["b"])
    assert np.allclose(np.linalg.norm(k.pos["B"] - k.pos["C"], axis=1), FB["c"])
    k = slider_crank_kin(np.linspace(0, 359, 50))
    assert np.allclose(np.linalg.norm(k.pos["B"] - k.pos["A"], axis=1), SC["l"])
    assert np.allclose(k.pos["B"][:, 1], SC["e"])
