"""The kinematics stage of a linkage: the reported positions, and the output's curves.

``analyze(linkage)`` solves the linkage at its reported positions at the drive's mean
speed; ``output_curve(linkage, n)`` gives the output link's s, v, a over one turn for
the kinematic diagrams (results.json ``kinematics_curve``).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from .result import KinematicsResult
from .solver import solve

if TYPE_CHECKING:       # the type only: the context builds its positions with the kinematics
    from ..context import Linkage


def analyze(linkage: Linkage) -> KinematicsResult:
    """Positions, velocities and accelerations of every point and link at the reported
    positions, at the drive's mean speed (epsilon1 = 0).

    Parameters
    ----------
    linkage : Linkage
        The mechanism, its reported crank angles ``positions.phi`` (deg) and the drive
        (``drive.omega``, rad/s, signed).

    Returns
    -------
    KinematicsResult
        Per point: position (m), analogues dr/dphi (m/rad), d2r/dphi2; per link: angle
        (rad) and its analogues; velocities (m/s, rad/s) and accelerations (m/s^2,
        rad/s^2) by ``vel``, ``acc``, ``omega``, ``epsilon``; ``warnings`` at change points.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*, the method of closed vector
    contours group by group (Assur groups); docs/methods.md §2.
    """
    phi = np.asarray(linkage.positions.phi, dtype=float)
    return solve(linkage.mechanism, phi, linkage.drive.omega)


@dataclass(frozen=True)
class OutputCurve:
    """The output link's motion over one turn of the crank from position 0.

    ``turn``: crank rotation from position 0 along the motion, deg; ``phi``: the absolute
    crank angle, deg; ``s``: a slider's displacement along its guide from position 0 (m)
    or a rocker's angle from position 0 (deg, in (-180, 180]); ``v``, ``a``: velocity and
    acceleration along the guide (m/s, m/s^2) or omega, epsilon (rad/s, rad/s^2), NaN
    next to a change point where they have no finite limit; ``quantity``: 'slider' | 'rocker'.
    """
    turn: np.ndarray
    phi: np.ndarray
    s: np.ndarray
    v: np.ndarray
    a: np.ndarray
    quantity: str

    def to_dict(self) -> dict:
        """results.json ``kinematics_curve`` (NaN as null)."""
        return {"turn": self.turn.tolist(), "phi": self.phi.tolist(), "s": self.s.tolist(),
                "v": self.v.tolist(), "a": self.a.tolist(), "quantity": self.quantity}


def output_curve(linkage: Linkage, n: int = 361, turn=None) -> OutputCurve:
    """s, v, a of the output link at ``n`` equal steps over one turn from position 0
    (over a crank range, ``positions.over`` 'input_range': from its start to its end), or
    at the angles ``turn`` when given.

    Parameters
    ----------
    linkage : Linkage
        The mechanism, position 0 and the output link (``positions``), the drive's
        omega (rad/s, signed) and sense of rotation.
    n : int
        Number of points over the turn, both ends included.
    turn : array_like of float, optional
        The angles (deg from position 0, in the sense of rotation) to evaluate at
        instead of the ``n`` equal steps.

    Returns
    -------
    OutputCurve
        The kinematic diagrams of the output: s (m or deg), v, a (see the class).

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: kinematic diagrams of the output
    link (displacement, velocity and acceleration against the crank angle).
    """
    mech, positions, drive = linkage.mechanism, linkage.positions, linkage.drive
    if positions.span is not None:      # over a crank range (positions.over 'input_range'): from its start to its end
        turn = np.linspace(0.0, abs(positions.span), n) if turn is None else np.asarray(turn, float)
        phi = np.mod(positions.phi0 + math.copysign(1.0, positions.span) * turn, 360.0)
    else:
        turn = np.linspace(0.0, 360.0, n) if turn is None else np.asarray(turn, float)
        phi = np.mod(positions.phi0 + drive.sign * turn, 360.0)
    kin = solve(mech, phi, drive.omega)
    out = mech.link(positions.output)
    s, _ = positions.output_value(phi)
    s0, _ = positions.output_value([positions.phi0])
    s = np.asarray(s, float) - float(s0[0])
    if positions.output_kind == "slider":
        ang = np.asarray(kin.angle[out.name])
        u = np.stack([np.cos(ang), np.sin(ang)], axis=1)
        v = np.einsum("ij,ij->i", kin.vel(out.origin), u)
        a = np.einsum("ij,ij->i", kin.acc(out.origin), u)
    else:
        s = np.mod(s + 180.0, 360.0) - 180.0
        v = np.asarray(kin.omega(out.name)) * np.ones_like(phi)
        a = np.asarray(kin.epsilon(out.name)) * np.ones_like(phi)
    # next to a change point a value without a finite limit is left out (null), not drawn
    vk, ak = ((f"v:{out.origin}", f"a:{out.origin}") if positions.output_kind == "slider"
              else (f"omega:{out.name}", f"epsilon:{out.name}"))
    v = np.where(kin.undefined.get(vk, False), np.nan, v)
    a = np.where(kin.undefined.get(ak, False), np.nan, a)
    return OutputCurve(turn=turn, phi=phi, s=s, v=v, a=a, quantity=positions.output_kind)


def positions_at(linkage: Linkage, phi_deg) -> list[dict]:
    """The mechanism's configuration at the crank angles ``phi_deg`` (deg): results.json
    ``singular_positions`` (the report draws the mechanism at each singular angle of the
    kinetostatics).

    Parameters
    ----------
    linkage : Linkage
        The mechanism and its drive.
    phi_deg : array_like of float
        Crank angles, deg.

    Returns
    -------
    list of dict
        Per angle: ``phi`` (deg), ``points`` (x, y in m of every point) and ``links``
        (``angle``, deg in [0, 360), of every link), as the kinematics entries hold them
        (null where not finite).
    """
    from .entries import angle_deg
    phi = np.asarray(phi_deg, float).reshape(-1)
    if not len(phi):
        return []
    kin = solve(linkage.mechanism, phi, linkage.drive.omega)
    pos = {p: np.asarray(kin.pos[p], float) for p in kin.points}
    ang = {n: angle_deg(kin.angle[n]) for n in kin.links}

    def fin(x):                          # (null where the position has no finite value)
        return float(x) if np.isfinite(x) else None
    return [{"phi": float(f),
             "points": {p: {"x": fin(xy[i, 0]), "y": fin(xy[i, 1])} for p, xy in pos.items()},
             "links": {n: {"angle": fin(a[i])} for n, a in ang.items()}}
            for i, f in enumerate(phi)]
