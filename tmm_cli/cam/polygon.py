"""The cam profile as a polygon at a given angular step, and its error (the accuracy study).

tmm writes the profile as points every 1 deg of cam angle (``CamResult.pitch`` /
``working``); between two points a machine or a drawing goes along the chord.  Here the
profile at any step: the vertices are the multiples of the step plus the phase boundaries
(where the profile may have a corner or a jump of curvature), so that every chord spans a
smooth arc; and two measures of the polygon against the exact (analytic) profile:

* ``polygon_deviation``: the largest distance of the exact working profile from the chord
  of its arc (the sagitta, ~ k L^2 / 8: order 2 in the step), sampled at ``sub`` points per
  arc, the largest of them refined by a parabola through its neighbours;
* ``polygon_rho_min``: the least radius of the circle through three successive vertices of
  one phase on the convex side of the pitch profile (the profile itself for a flat face):
  the hand-drawn estimate of rho_min.  The circle through three points a step apart
  has the curvature of the middle one to O(h^2); rho_min on the grid is therefore within
  O(h^2) of the located value where that lies inside a phase and O(h) where it lies at a
  phase boundary (the middle vertex is at least a step away).
"""
from __future__ import annotations

import math

import numpy as np

from ..lazy import unique
from . import flat as _flat


def _exact(result, which: str):
    """phi_rad -> points (N, 2) of the exact pitch or working profile (cam frame, O at origin)."""
    if result.follower == "flat":
        r0, sigma = result.r0, (1 if result.rotation == "ccw" else -1)
        return lambda phi: _flat.profile(result.motion, r0, sigma, phi)
    prof = result.profile
    if which == "pitch":
        return lambda phi: prof.pitch(phi)[0]
    return lambda phi: prof.working(phi, result.roller)


def vertices(result, step_deg: float) -> tuple[np.ndarray, np.ndarray]:
    """The cam angles of the vertices of the profile's polygon.

    Parameters
    ----------
    result : CamResult
        The cam stage's result.
    step_deg : float
        The step of the cam angle, deg.

    Returns
    -------
    phi : numpy.ndarray
        The multiples of the step over a turn and the phase boundaries, sorted, deg; the last
        is 360 (= 0, the polygon closes).
    phase : numpy.ndarray
        The phase index of each chord's arc.
    """
    step = float(step_deg)
    if not step > 0:
        raise ValueError("the step must be positive")
    n = int(math.ceil(360.0 / step - 1e-9))
    grid = np.minimum(np.arange(n + 1) * step, 360.0)
    bounds = np.degrees(np.asarray(result.motion.starts, float))
    phi = unique(np.concatenate([grid, bounds, [360.0]]))
    phi = phi[np.concatenate([[True], np.diff(phi) > 1e-9])]
    ph = np.searchsorted(bounds, 0.5 * (phi[:-1] + phi[1:]), side="right") - 1
    return phi, ph


def polygon(result, step_deg: float, which: str = "working") -> np.ndarray:
    """The profile's polygon at a step of the cam angle.

    Parameters
    ----------
    result : CamResult
        The cam stage's result.
    step_deg : float
        The step of the cam angle, deg.
    which : str
        ``"working"`` or ``"pitch"``.

    Returns
    -------
    numpy.ndarray
        The vertices (N, 2) at the angles of :func:`vertices`, m.
    """
    phi, _ = vertices(result, step_deg)
    return _exact(result, which)(np.radians(phi))


def polygon_deviation(result, step_deg: float, sub: int = 16) -> float:
    """Largest distance of the exact working profile from the polygon's chords.

    Parameters
    ----------
    result : CamResult
        The cam stage's result.
    step_deg : float
        The step of the cam angle, deg.
    sub : int
        Points of the exact profile per chord.

    Returns
    -------
    float
        The deviation, m.
    """
    phi, _ = vertices(result, step_deg)
    f = _exact(result, "working")
    P = f(np.radians(phi))
    a, b = P[:-1], P[1:]
    t = np.linspace(0.0, 1.0, sub + 1)[1:-1]
    x = phi[:-1, None] + (phi[1:] - phi[:-1])[:, None] * t            # (chords, sub-1)
    Q = f(np.radians(x).ravel()).reshape(x.shape + (2,))
    d = b - a
    L = np.hypot(d[:, 0], d[:, 1])[:, None]
    dist = np.abs(d[:, None, 0] * (Q[..., 1] - a[:, None, 1]) - d[:, None, 1] * (Q[..., 0] - a[:, None, 0])) / L
    # the largest sampled distance of each chord refined by the parabola through its neighbours
    j = np.clip(np.argmax(dist, axis=1), 1, dist.shape[1] - 2) if dist.shape[1] >= 3 else None
    if j is None:
        return float(dist.max())
    r = np.arange(dist.shape[0])
    y0, y1, y2 = dist[r, j - 1], dist[r, j], dist[r, j + 1]
    den = y0 - 2 * y1 + y2
    with np.errstate(divide="ignore", invalid="ignore"):
        top = np.where(den < 0, y1 - (y0 - y2) ** 2 / (8 * den), y1)
    return float(np.max(np.maximum(top, dist.max(axis=1))))


def polygon_rho_min(result, step_deg: float) -> float:
    """Least radius of curvature of the profile's polygon.

    Parameters
    ----------
    result : CamResult
        The cam stage's result.
    step_deg : float
        The step of the cam angle, deg.

    Returns
    -------
    float
        The least radius of the circle through three successive vertices of one phase on the
        convex side of the pitch profile (the flat face's profile itself), m; inf if none.
    """
    phi, ph = vertices(result, step_deg)
    P = _exact(result, "pitch")(np.radians(phi))
    a, b, c = P[:-2], P[1:-1], P[2:]
    same = ph[:-1] == ph[1:]                      # both chords of the middle vertex in one phase
    ab, bc, ac = b - a, c - b, c - a
    cross = ab[:, 0] * bc[:, 1] - ab[:, 1] * bc[:, 0]
    # the profile's orientation: the sign of its area (it runs once round O)
    area = 0.5 * float(np.sum(P[:-1, 0] * P[1:, 1] - P[1:, 0] * P[:-1, 1]))
    k = 2.0 * np.sign(area) * cross / (np.hypot(*ab.T) * np.hypot(*bc.T) * np.hypot(*ac.T))
    k = k[same & (k > 0)]
    return math.inf if k.size == 0 else float(1.0 / k.max())


__all__ = ["vertices", "polygon", "polygon_deviation", "polygon_rho_min"]
