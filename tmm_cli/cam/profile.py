"""Cam profile by inverted motion (docs/methods.md §5).

The whole mechanism is given the rotation -omega of the cam: the cam stands still and
the frame with the follower turns about O by -phi (phi in the direction of rotation).
With ``q(phi) = B(phi) - O`` in the fixed frame the pitch (centre) profile in the cam's
frame (which coincides with the fixed frame at phi = 0, O at the origin) is

    Q = R(-sigma*phi) q,
    Q'  = R(-sigma*phi) (q' - sigma J q),
    Q'' = R(-sigma*phi) (q'' - 2 sigma J q' - q),

(J: turn by +90 deg), all analytic.  The curve runs clockwise for a counter-clockwise
cam (orientation ``-sigma``); its signed curvature is ``k = (Q' x Q'') / |Q'|^3`` and a
part is convex where ``-sigma*k > 0``.  The working (actual) profile is the inner
equidistant at the roller radius: ``Q - r_r nu`` with ``nu`` the outward unit normal.
"""
from __future__ import annotations

import math

import numpy as np

from .geometry import Geometry, J
from .motion import FAR_DWELL, NEAR_DWELL, RETURN, RISE, Motion
from .region import GRID, phase_min


def rot(v: np.ndarray, ang: np.ndarray) -> np.ndarray:
    """Turn plane vectors by angles.

    Parameters
    ----------
    v : numpy.ndarray
        Vectors (..., 2).
    ang : numpy.ndarray
        Angles, rad (ccw positive), broadcast against ``v[..., 0]``.

    Returns
    -------
    numpy.ndarray
        The turned vectors (..., 2).
    """
    c, s = np.cos(ang), np.sin(ang)
    return np.stack([c * v[..., 0] - s * v[..., 1], s * v[..., 0] + c * v[..., 1]], axis=-1)


def _cross(a, b):
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


class Profile:
    """Pitch and working profiles of a synthesised cam (lengths in metres, O at origin)."""

    def __init__(self, motion: Motion, geom: Geometry, O: np.ndarray):
        self.motion, self.geom = motion, geom
        self.O = np.asarray(O, dtype=float)
        self.sigma = geom.sigma
        self.orient = -geom.sigma

    # derivatives in the fixed frame ------------------------------------------------
    def _fixed(self, s, s1, s2):
        B, B1, B2, _ = self.geom.kinematics(s, s1, s2)
        return B - self.O, B1, B2

    def _cam_derivs(self, q, q1, q2):
        sg = self.sigma
        d1 = q1 - sg * J(q)
        d2 = q2 - 2 * sg * J(q1) - q
        return d1, d2

    def pitch(self, phi_rad):
        """Pitch profile points Q and dQ/dphi, d2Q/dphi2 (cam frame) at cycle angles (rad)."""
        phi = np.asarray(phi_rad, dtype=float)
        s, s1, s2, _ = self.motion.evaluate(phi)
        q, q1, q2 = self._fixed(s, s1, s2)
        d1, d2 = self._cam_derivs(q, q1, q2)
        ang = -self.sigma * phi
        return rot(q, ang), rot(d1, ang), rot(d2, ang)

    def curvature_phase(self, phase: int, x):
        """Signed convexity ``-sigma * k`` (1/m) of the pitch profile on a phase at fractions x."""
        s, s1, s2, _ = self.motion.phase(phase, x)
        q, q1, q2 = self._fixed(s, s1, s2)
        d1, d2 = self._cam_derivs(q, q1, q2)
        speed = np.hypot(d1[..., 0], d1[..., 1])
        return self.orient * _cross(d1, d2) / speed ** 3, speed

    def min_speed(self) -> float:
        """Smallest |dQ/dphi| over the cycle (zero would be a cusp of the pitch profile)."""
        best = math.inf
        for ph in (RISE, RETURN, NEAR_DWELL, FAR_DWELL):
            _, sp = self.curvature_phase(ph, np.linspace(0, 1, GRID))
            best = min(best, float(np.min(sp)))
        return best

    def rho_min(self) -> tuple[float, float]:
        """Minimum radius of curvature on the convex parts and the cam angle (deg) there.

        The maximum of the convexity ``-sigma*k`` is located on each phase (closed
        interval, with the law's one-sided values) by sampling and a bracketing search.
        """
        best, where = -math.inf, 0.0
        starts = self.motion.starts
        spans = {RISE: (starts[0], self.motion.rise), FAR_DWELL: (starts[1], self.motion.far_dwell),
                 RETURN: (starts[2], self.motion.ret), NEAR_DWELL: (starts[3], self.motion.near_dwell)}
        for ph in (RISE, RETURN, NEAR_DWELL, FAR_DWELL):
            start, span = spans[ph]
            if span <= 0:
                continue

            def neg(xg, ph=ph):
                return -self.curvature_phase(ph, xg)[0]

            xj, vj = phase_min(neg)
            if -vj > best:
                best, where = -vj, math.degrees(start + xj * span)
        if best <= 0:
            return math.inf, where
        return 1.0 / best, where % 360.0

    def working(self, phi_rad, roller: float):
        """Working profile: the pitch profile offset inwards by the roller radius."""
        Q, Q1, _ = self.pitch(phi_rad)
        t = Q1 / np.hypot(Q1[..., 0], Q1[..., 1])[..., None]
        nu = self.orient * np.stack([t[..., 1], -t[..., 0]], axis=-1)
        return Q - roller * nu

    def follower_at(self, phi_rad):
        """Fixed-frame roller centre B (O at origin) and, for a rocker, the pivot A."""
        phi = np.asarray(phi_rad, dtype=float)
        s, s1, s2, _ = self.motion.evaluate(phi)
        q, _, _ = self._fixed(s, s1, s2)
        return q
