"""Equations of motion and dynamic reactions of the rotary impact mechanism (docs/methods.md §7).

Derivation (re-derived after V.V. Voronkin, docs/methods.md §10;
Lagrange's equations of the second kind as in Artobolevsky's and Frolov's textbooks).
Generalised coordinates q = (phi, psi); theta = phi + psi is the absolute angle of
the striker (direction O1 -> M).  With e(a) = (cos a, sin a) and n(a) = (-sin a, cos a):

    O1 = l e(phi),   S1 = s1 e(phi),   C = l e(phi) + l_c e(theta),   M = l e(phi) + l_M e(theta)
    v_C = l phi' n(phi) + l_c theta' n(theta)
    |v_C|^2 = l^2 phi'^2 + l_c^2 theta'^2 + 2 l l_c phi' theta' cos psi

    T = 1/2 J_O phi'^2 + 1/2 m2 |v_C|^2 + 1/2 J_C theta'^2
      = 1/2 a phi'^2 + 1/2 d (phi' + psi')^2 + b cos(psi) phi' (phi' + psi')
    a = J_O + m2 l^2,  b = m2 l l_c,  d = J_C + m2 l_c^2      (J_O: the rotor about O)

(the paper's (6) has -m l l_c cos psi_i because its psi_i is measured from O1 -> O:
psi_paper = psi - pi).  The mass matrix and Lagrange's equations:

    M11 = a + d + 2 b cos psi,   M12 = d + b cos psi,   M22 = d
    M11 phi'' + M12 psi'' - b sin psi psi' (2 phi' + psi') = Q_phi
    M12 phi'' + M22 psi''  + b sin psi phi'^2              = Q_psi
    Q_phi = M_d - g [m1 s1 cos phi + m2 (l cos phi + l_c cos theta)],   Q_psi = -g m2 l_c cos theta

det M = a d - b^2 cos^2 psi > 0 unless the rotor has no inertia and the striker is a
point mass (then it vanishes at psi = 0, 180 deg: reported as an error).

Reactions (theorem on the motion of the centre of mass of each link; R_ij = force of
link i on link j, ground 0, rotor 1, striker 2; G = (0, -m g)):

    striker:  m2 a_C  = R12 + G2            ->  R12 = m2 a_C - G2
    rotor:    m1 a_S1 = R01 - R12 + G1      ->  R01 = m1 a_S1 + R12 - G1

Everything here is vectorised over numpy arrays of states.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..errors import StageError
from ..messages import Message

if TYPE_CHECKING:
    from .spec import Dof2Section

G_ACC = 9.81  # m/s^2, as in loads (docs/methods.md §3.1: g = 9.81 along -y)


@dataclass(frozen=True)
class Params:
    """The mechanism in SI units (all floats)."""

    l: float            # |OO1|
    m1: float           # rotor mass
    s1: float           # |OS1|
    J_O: float          # rotor about O
    l_M: float          # |O1M|
    l_c: float          # |O1C|
    m2: float           # striker mass
    J_C: float          # striker about C
    g: float = 0.0      # gravity acceleration (0: horizontal machine)

    @property
    def a(self) -> float:
        return self.J_O + self.m2 * self.l ** 2

    @property
    def b(self) -> float:
        return self.m2 * self.l * self.l_c

    @property
    def d(self) -> float:
        return self.J_C + self.m2 * self.l_c ** 2

    @classmethod
    def from_section(cls, sec: Dof2Section) -> "Params":
        r, s = sec.rotor, sec.striker
        return cls(l=float(r.length), m1=float(r.mass), s1=float(r.com), J_O=r.inertia_O,
                   l_M=float(s.length), l_c=s.l_c, m2=float(s.mass), J_C=float(s.J),
                   g=G_ACC if sec.gravity else 0.0)

    def check(self, speed_held: bool) -> None:
        """Raise StageError when the equations of motion are singular."""
        scale = self.a * self.d
        if self.d <= 0:
            raise StageError("dof2", Message("dof2.fail.no_striker_inertia"))
        if not speed_held and self.a * self.d - self.b ** 2 <= 1e-12 * max(scale, 1e-300):
            raise StageError("dof2", Message("dof2.fail.singular_mass"))


def mass_matrix(p: Params, psi):
    """The mass matrix of the kinetic energy.

    Parameters
    ----------
    p : Params
        The mechanism (SI units).
    psi : float or numpy.ndarray
        The striker's angle relative to the rotor, rad.

    Returns
    -------
    tuple
        (M11, M12, M22) = (a + d + 2 b cos psi, d + b cos psi, d), kg*m^2.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*; Frolov (ed.), *Teoriya mekhanizmov i
    mashin*: Lagrange's equations of the second kind for a machine with two degrees of freedom;
    V. V. Voronkin, the rotary impact mechanism (the derivation re-done in the module's
    docstring); docs/methods.md §7.
    """
    c = np.cos(psi)
    return p.a + p.d + 2 * p.b * c, p.d + p.b * c, p.d + 0 * c


def velocity_terms(p: Params, psi, w, pd):
    """The velocity-dependent terms of Lagrange's equations (their left-hand sides).

    Parameters
    ----------
    p : Params
        The mechanism (SI units).
    psi : float or numpy.ndarray
        The striker's angle relative to the rotor, rad.
    w, pd : float or numpy.ndarray
        Their rates phi' and psi', rad/s.

    Returns
    -------
    tuple
        (h1, h2) = (-b sin psi psi' (2 phi' + psi'), b sin psi phi'^2), N*m.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*; Frolov (ed.), *Teoriya mekhanizmov i
    mashin*: Lagrange's equations of the second kind for a machine with two degrees of freedom;
    V. V. Voronkin, the rotary impact mechanism (the derivation re-done in the module's
    docstring); docs/methods.md §7.
    """
    s = np.sin(psi)
    return -p.b * s * pd * (2 * w + pd), p.b * s * w ** 2


def gravity_forces(p: Params, phi, psi):
    """The generalised forces of gravity.

    Parameters
    ----------
    p : Params
        The mechanism (SI units; ``g`` = 0 for a horizontal machine).
    phi, psi : float or numpy.ndarray
        The rotor's angle and the striker's angle relative to it, rad.

    Returns
    -------
    tuple
        (Q_phi, Q_psi) = -dV/dq, N*m.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*; Frolov (ed.), *Teoriya mekhanizmov i
    mashin*: Lagrange's equations of the second kind for a machine with two degrees of freedom;
    V. V. Voronkin, the rotary impact mechanism (the derivation re-done in the module's
    docstring); docs/methods.md §7.
    """
    th = phi + psi
    q2 = -p.g * p.m2 * p.l_c * np.cos(th)
    q1 = -p.g * (p.m1 * p.s1 + p.m2 * p.l) * np.cos(phi) + q2
    return q1, q2


def accelerations(p: Params, phi, psi, w, pd, moment):
    """The angular accelerations under a given moment on the rotor.

    Parameters
    ----------
    p : Params
        The mechanism (SI units).
    phi, psi : float or numpy.ndarray
        The rotor's angle and the striker's angle relative to it, rad.
    w, pd : float or numpy.ndarray
        Their rates phi' and psi', rad/s.
    moment : float or numpy.ndarray
        The driving moment M_d on the rotor, N*m.

    Returns
    -------
    tuple
        (phi'', psi''), rad/s^2 (Cramer's rule on the 2x2 system).

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*; Frolov (ed.), *Teoriya mekhanizmov i
    mashin*: Lagrange's equations of the second kind for a machine with two degrees of freedom;
    V. V. Voronkin, the rotary impact mechanism (the derivation re-done in the module's
    docstring); docs/methods.md §7.
    """
    m11, m12, m22 = mass_matrix(p, psi)
    h1, h2 = velocity_terms(p, psi, w, pd)
    g1, g2 = gravity_forces(p, phi, psi)
    r1 = moment + g1 - h1
    r2 = g2 - h2
    det = m11 * m22 - m12 ** 2
    return (r1 * m22 - m12 * r2) / det, (m11 * r2 - m12 * r1) / det


def held_speed(p: Params, phi, psi, w, pd):
    """The striker's motion and the motor's moment with the rotor held at a constant speed.

    Parameters
    ----------
    p : Params
        The mechanism (SI units).
    phi, psi : float or numpy.ndarray
        The rotor's angle and the striker's angle relative to it, rad.
    w, pd : float or numpy.ndarray
        Their rates phi' and psi', rad/s.

    Returns
    -------
    tuple
        (psi'', rad/s^2; M_d, N*m): the striker's equation with phi'' = 0 and the moment the
        motor must apply (the first Lagrange equation).

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*; Frolov (ed.), *Teoriya mekhanizmov i
    mashin*: Lagrange's equations of the second kind for a machine with two degrees of freedom;
    V. V. Voronkin, the rotary impact mechanism (the derivation re-done in the module's
    docstring); docs/methods.md §7.
    """
    _, m12, m22 = mass_matrix(p, psi)
    h1, h2 = velocity_terms(p, psi, w, pd)
    g1, g2 = gravity_forces(p, phi, psi)
    psi_dd = (g2 - h2) / m22
    return psi_dd, m12 * psi_dd + h1 - g1


def energy(p: Params, phi, psi, w, pd):
    """Kinetic and potential energy of the mechanism.

    Parameters
    ----------
    p : Params
        The mechanism (SI units).
    phi, psi : float or numpy.ndarray
        The rotor's angle and the striker's angle relative to it, rad.
    w, pd : float or numpy.ndarray
        Their rates phi' and psi', rad/s.

    Returns
    -------
    tuple
        (T, V), J (V = 0 at y = 0).
    """
    m11, m12, m22 = mass_matrix(p, psi)
    T = 0.5 * (m11 * w ** 2 + 2 * m12 * w * pd + m22 * pd ** 2)
    V = p.g * ((p.m1 * p.s1 + p.m2 * p.l) * np.sin(phi) + p.m2 * p.l_c * np.sin(phi + psi))
    return T, V


def _e(a):
    return np.stack([np.cos(a), np.sin(a)], axis=-1)


def _n(a):
    return np.stack([-np.sin(a), np.cos(a)], axis=-1)


def point_kinematics(radius_rotor: float, radius_striker: float, phi, psi, w, pd, wd, pdd):
    """Position, velocity and acceleration of a point of the striker.

    Parameters
    ----------
    radius_rotor : float
        The point's distance along the rotor, m (``l`` for a point of the striker).
    radius_striker : float
        Its distance along the striker from O1, m.
    phi, psi : float or numpy.ndarray
        The angles, rad.
    w, pd : float or numpy.ndarray
        phi' and psi', rad/s.
    wd, pdd : float or numpy.ndarray
        phi'' and psi'', rad/s^2.

    Returns
    -------
    tuple of numpy.ndarray
        The position (m), velocity (m/s) and acceleration (m/s^2), each (..., 2), of the point
        radius_rotor e(phi) + radius_striker e(phi + psi).
    """
    phi, psi, w, pd, wd, pdd = (np.asarray(x, float) for x in (phi, psi, w, pd, wd, pdd))
    th, om2, ep2 = phi + psi, w + pd, wd + pdd
    r = radius_rotor * _e(phi) + radius_striker * _e(th)
    v = (radius_rotor * w[..., None] * _n(phi) + radius_striker * om2[..., None] * _n(th))
    acc = (radius_rotor * (wd[..., None] * _n(phi) - (w ** 2)[..., None] * _e(phi))
           + radius_striker * (ep2[..., None] * _n(th) - (om2 ** 2)[..., None] * _e(th)))
    return r, v, acc


def reactions(p: Params, phi, psi, w, pd, wd, pdd):
    """The dynamic reactions in the pairs O and O1.

    Parameters
    ----------
    p : Params
        The mechanism (SI units).
    phi, psi : float or numpy.ndarray
        The rotor's angle and the striker's angle relative to it, rad.
    w, pd : float or numpy.ndarray
        Their rates phi' and psi', rad/s.
    wd, pdd : float or numpy.ndarray
        phi'' and psi'', rad/s^2.

    Returns
    -------
    tuple of numpy.ndarray
        (R01, R12), each (..., 2), N: the force of the ground on the rotor at O and of the
        rotor on the striker at O1.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: the theorem on the motion of the centre
    of mass of each link; docs/methods.md §7.
    """
    phi, psi, w, pd, wd, pdd = (np.asarray(x, float) for x in (phi, psi, w, pd, wd, pdd))
    _, _, aC = point_kinematics(p.l, p.l_c, phi, psi, w, pd, wd, pdd)
    _, _, aS = point_kinematics(p.s1, 0.0, phi, psi, w, pd, wd, pdd)
    G2 = np.array([0.0, -p.m2 * p.g])
    G1 = np.array([0.0, -p.m1 * p.g])
    R12 = p.m2 * aC - G2
    R01 = p.m1 * aS + R12 - G1
    return R01, R12


def rhs_scalar(p: Params, speed_held: bool, moment: float):
    """The right-hand side f(t, y) for the integrator.

    Parameters
    ----------
    p : Params
        The mechanism (SI units).
    speed_held : bool
        True: the rotor is held at a constant speed (phi'' = 0).
    moment : float
        The constant driving moment, N*m (free motion: 0).

    Returns
    -------
    callable
        f(t, y) with y = (phi, psi, w, pd, W): the same equations as :func:`accelerations` /
        :func:`held_speed` written with ``math`` on floats (the integrator calls it ~10^3..10^6
        times; numpy on scalars is ~5x slower); W is the work of the driving moment, J.
    """
    a, b, d, g = p.a, p.b, p.d, p.g
    gm1 = g * (p.m1 * p.s1 + p.m2 * p.l)
    gm2 = g * p.m2 * p.l_c
    cos, sin = math.cos, math.sin

    def f(t, y):
        phi, psi, w, pd = y[0], y[1], y[2], y[3]
        c, s = cos(psi), sin(psi)
        q2 = -gm2 * cos(phi + psi)
        q1 = -gm1 * cos(phi) + q2
        h1 = -b * s * pd * (2 * w + pd)
        h2 = b * s * w * w
        m12 = d + b * c
        if speed_held:
            pdd = (q2 - h2) / d
            return [w, pd, 0.0, pdd, (m12 * pdd + h1 - q1) * w]
        m11 = a + d + 2 * b * c
        r1, r2 = moment + q1 - h1, q2 - h2
        det = m11 * d - m12 * m12
        return [w, pd, (r1 * d - m12 * r2) / det, (m11 * r2 - m12 * r1) / det, moment * w]
    return f
