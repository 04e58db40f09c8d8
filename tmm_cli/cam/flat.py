"""Flat-faced translating follower (tarel'chatyi tolkatel'): size, face width, profile.

The face is perpendicular to the follower's motion, so the pressure angle is zero and the
cam's size is limited by the convexity of the profile alone (Artobolevsky; Popov &
Timofeev; Frolov).  With the cam centre O at the origin, the face at the distance
``p = r0 + s`` from O and the cam turning by ``phi`` (``sigma`` = +1 counter-clockwise),
the inverted motion gives the face the unit normal ``u = R(-sigma phi) e_y``; the profile
is the envelope of the lines ``X . u = p``:

    X = R(-sigma phi) (sigma ds/dphi, r0 + s)

(in the fixed frame the contact point lies ``sigma ds/dphi`` from the follower's axis
along the face) and its radius of curvature is ``rho = r0 + s + d2s/dphi2``.  Hence

* the least base radius with a convex profile of radius of curvature at least
  ``rho_min_allowed``: r0 = max(rho_min_allowed - s - d2s/dphi2) over the cycle;
* the face width: max(ds/dphi) - min(ds/dphi) (the span of the contact points along the
  face), or 2 max|ds/dphi| for a face symmetric about the axis.
"""
from __future__ import annotations

import math

import numpy as np

from .motion import FAR_DWELL, NEAR_DWELL, RETURN, RISE, Motion
from .profile import rot
from .region import phase_min


def cycle_max(motion: Motion, fn) -> tuple[float, float]:
    """Exact maximum over the cycle of ``fn(s, s1, s2)`` and the cam angle (deg) where it is.

    Each phase is a closed interval with its law's one-sided end values: sampled on a grid,
    every local maximum refined by a bracketing search; dwells are constant."""
    starts = motion.starts
    spans = {RISE: (starts[0], motion.rise), FAR_DWELL: (starts[1], motion.far_dwell),
             RETURN: (starts[2], motion.ret), NEAR_DWELL: (starts[3], motion.near_dwell)}
    best, where = -math.inf, 0.0
    for ph, (start, span) in spans.items():
        if span <= 1e-12:
            continue
        if ph in (NEAR_DWELL, FAR_DWELL):
            s, s1, s2, _ = motion.phase(ph, np.array([0.0]))
            v = float(fn(s, s1, s2)[0])
            if v > best:
                best, where = v, math.degrees(start)
            continue

        def neg(xg, ph=ph):
            s, s1, s2, _ = motion.phase(ph, xg)
            return -fn(s, s1, s2)

        xj, vj = phase_min(neg)
        if -vj > best:
            best, where = -vj, math.degrees(start + xj * span)
    return best, where % 360.0


def convexity_margin(motion: Motion) -> tuple[float, float]:
    """max(-s - d2s/dphi2) over the cycle and where: r0_min = rho_min_allowed + this,
    and a cam of base radius r0 has rho_min = r0 - this."""
    return cycle_max(motion, lambda s, s1, s2: -s - s2)


def face_widths(motion: Motion) -> tuple[float, float]:
    """(max ds/dphi - min ds/dphi, 2 max|ds/dphi|) over the cycle, m."""
    hi, _ = cycle_max(motion, lambda s, s1, s2: s1)
    lo, _ = cycle_max(motion, lambda s, s1, s2: -s1)
    lo = -lo
    return hi - lo, 2.0 * max(abs(hi), abs(lo))


def profile(motion: Motion, r0: float, sigma: int, phi_rad) -> np.ndarray:
    """Profile points (cam frame, O at the origin) at cycle angles (rad): the envelope of the face."""
    phi = np.asarray(phi_rad, dtype=float)
    s, s1, _, _ = motion.evaluate(phi)
    X = np.stack([sigma * s1, r0 + s], axis=-1)
    return rot(X, -sigma * phi)
