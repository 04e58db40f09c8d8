"""Follower geometry and the pressure-angle condition as half-planes of cam centres.

Design frame: the roller centre's lowest position ``B0`` is the origin and the roller
centre moves in +y at the start of the rise.

* translating follower: ``B = (0, s)``, the follower axis is x = 0;
* rocker of length ``l``: pivot ``A = (-tau*l, 0)``, ``B = A + l (cos psi, sin psi)``,
  ``psi = psi0 + tau*s`` (``psi0`` = 0 or pi), ``tau`` = +1 when the rocker turns
  counter-clockwise on the rise.

Cam rotation: ``sigma`` = +1 counter-clockwise, -1 clockwise; ``phi`` grows in the
direction of rotation.  The relative instant centre of cam and follower gives the
classical construction of the ``s - ds/dphi`` diagram: the normal to the pitch profile at
``B`` is parallel to ``D - O`` where

* translating: ``D = B + sigma * s' * J u`` (``u`` = follower direction, ``J`` = turn by
  +90 deg): the segment ds/dphi laid off from B perpendicular to the follower, turned
  from the velocity by 90 deg in the direction of the cam's rotation;
* rocker: ``D = B + i (A - B)``, ``i = omega2/omega1 = sigma*tau*s'``: the velocity
  analogue ``l*|psi'|`` laid off along the rocker line.

The pressure angle is the angle between the line ``OD`` and the velocity ``w`` of B, so
``|theta| <= theta_max`` and ``(D - O).w > 0`` (the cam lies on the side opposite to the
follower's rise velocity) are the two half-planes

    n(+-) . O <= n(+-) . D,   n(+-) = w sin(theta_max) +- J w cos(theta_max)

bounded by the lines through D at theta_max to the follower velocity: the tangent lines of
the graphical method.  This is the textbook construction (Artobolevsky; Popov & Timofeev;
Frolov) written analytically.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


def J(v: np.ndarray) -> np.ndarray:
    """Turn plane vectors by +90 degrees.

    Parameters
    ----------
    v : numpy.ndarray
        Vectors (..., 2).

    Returns
    -------
    numpy.ndarray
        (-v_y, v_x) of each vector.
    """
    return np.stack([-v[..., 1], v[..., 0]], axis=-1)


@dataclass(frozen=True)
class Geometry:
    """The follower's geometry: translating or rocker, the cam's sense of rotation, the rocker's."""

    kind: str                 # 'translating' | 'rocker'
    sigma: int                # cam rotation: +1 ccw, -1 cw
    tau: int = 1              # rocker turn on the rise in the fixed frame: +1 ccw, -1 cw
    l: float | None = None    # rocker length

    @property
    def A(self) -> np.ndarray | None:
        if self.kind != "rocker":
            return None
        return np.array([-self.tau * self.l, 0.0])

    @property
    def psi0(self) -> float:
        return 0.0 if self.tau > 0 else math.pi

    def kinematics(self, s, s1, s2):
        """Roller centre B and its derivatives dB/dphi, d2B/dphi2, unit rise direction w."""
        s = np.asarray(s, dtype=float)
        s1 = np.asarray(s1, dtype=float)
        s2 = np.asarray(s2, dtype=float)
        if self.kind == "translating":
            zero = np.zeros_like(s)
            B = np.stack([zero, s], axis=-1)
            B1 = np.stack([zero, s1], axis=-1)
            B2 = np.stack([zero, s2], axis=-1)
            w = np.stack([zero, np.ones_like(s)], axis=-1)
            return B, B1, B2, w
        psi = self.psi0 + self.tau * s
        r = self.l * np.stack([np.cos(psi), np.sin(psi)], axis=-1)     # B - A
        B = self.A + r
        Jr = J(r)
        B1 = self.tau * s1[..., None] * Jr
        B2 = self.tau * s2[..., None] * Jr - (s1 ** 2)[..., None] * r
        w = self.tau * Jr / self.l
        return B, B1, B2, w

    def pole_point(self, s, s1):
        """B, the point D of the s - ds/dphi construction, and w (see the module doc)."""
        B, _, _, w = self.kinematics(s, s1, np.zeros_like(np.asarray(s, dtype=float)))
        s1 = np.asarray(s1, dtype=float)
        if self.kind == "translating":
            D = B + self.sigma * s1[..., None] * J(w)
        else:
            i = self.sigma * self.tau * s1
            D = B + i[..., None] * (self.A - B)
        return B, D, w

    def lines(self, s, s1, tan_max, side):
        """Half-planes n . O <= c of admissible cam centres.

        ``side`` = +1 or -1 selects n = w sin + side * Jw cos.  Returns (n, c, D).
        """
        _, D, w = self.pole_point(s, s1)
        th = np.arctan(np.asarray(tan_max, dtype=float))
        side = np.asarray(side, dtype=float)
        n = w * np.sin(th)[..., None] + (side * np.cos(th))[..., None] * J(w)
        c = np.einsum("...i,...i->...", n, D)
        return n, c, D

    def pressure_angle(self, s, s1, O):
        """Pressure angle (rad, magnitude) for the cam centre O; nan where O is on the wrong side."""
        _, D, w = self.pole_point(s, s1)
        q = D - np.asarray(O, dtype=float)
        along = np.einsum("...i,...i->...", q, w)
        across = np.einsum("...i,...i->...", q, J(w))
        th = np.arctan2(np.abs(across), along)
        return th, along
