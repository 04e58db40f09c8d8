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
    """Exact maximum over the cycle of a function of the follower's motion.

    Parameters
    ----------
    motion : Motion
        The follower's motion.
    fn : callable
        ``fn(s, s1, s2)`` of the displacement (m) and its first and second derivatives with
        respect to the cam angle (per rad), vectorised.

    Returns
    -------
    value : float
        The maximum of ``fn`` over the cycle.
    phi : float
        The cam angle where it is, deg.

    Notes
    -----
    Each phase is a closed interval with its law's one-sided end values: sampled on a grid,
    every local maximum refined by a bracketing search; the dwells are constant.
    """
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
    """What a flat-faced follower's cam needs beyond its least radius of curvature.

    Parameters
    ----------
    motion : Motion
        The follower's motion (s in m).

    Returns
    -------
    margin : float
        max(-s - d2s/dphi2) over the cycle, m: r0_min = rho_min_allowed + margin, and a cam
        of base radius r0 has rho_min = r0 - margin.
    phi : float
        The cam angle where the maximum is, deg.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*; Popov & Timofeev, *Kursovoe
    proektirovanie po TMM*; Frolov (ed.), *Teoriya mekhanizmov i mashin*: the convexity
    condition r0 + s + d2s/dphi2 >= rho_min of a cam with a flat-faced follower;
    docs/methods.md §5.
    """
    return cycle_max(motion, lambda s, s1, s2: -s - s2)


def face_widths(motion: Motion) -> tuple[float, float]:
    """The width of a flat face that keeps the contact on it.

    Parameters
    ----------
    motion : Motion
        The follower's motion (s in m).

    Returns
    -------
    span : float
        max ds/dphi - min ds/dphi over the cycle, m (the contact's travel along the face).
    symmetric : float
        2 max |ds/dphi|, m (a face symmetric about the follower's axis).

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*; Popov & Timofeev, *Kursovoe
    proektirovanie po TMM*; Frolov (ed.), *Teoriya mekhanizmov i mashin*: the contact point's
    distance ds/dphi from the follower's axis; docs/methods.md §5.
    """
    hi, _ = cycle_max(motion, lambda s, s1, s2: s1)
    lo, _ = cycle_max(motion, lambda s, s1, s2: -s1)
    lo = -lo
    return hi - lo, 2.0 * max(abs(hi), abs(lo))


def profile(motion: Motion, r0: float, sigma: int, phi_rad) -> np.ndarray:
    """Profile of the cam of a flat-faced translating follower.

    Parameters
    ----------
    motion : Motion
        The follower's motion (s in m).
    r0 : float
        The base radius, m.
    sigma : int
        +1 for a ccw cam, -1 for cw.
    phi_rad : array_like
        Cam angles, rad.

    Returns
    -------
    numpy.ndarray
        The points (N, 2) of the envelope of the face in the cam's frame (O at the origin), m.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*; Popov & Timofeev, *Kursovoe
    proektirovanie po TMM*; Frolov (ed.), *Teoriya mekhanizmov i mashin*: the profile of a
    flat-faced follower's cam as the envelope of the face's positions in inverted motion;
    docs/methods.md §5.
    """
    phi = np.asarray(phi_rad, dtype=float)
    s, s1, _, _ = motion.evaluate(phi)
    X = np.stack([sigma * s1, r0 + s], axis=-1)
    return rot(X, -sigma * phi)
