"""Load diagrams: piecewise-linear interpolation with jumps, the crank angle of the
cycle from position 0, a load's diagram as given."""
from __future__ import annotations

import numpy as np

_SNAP = 1e-9          # s/H or deg: abscissae this close to a jump are put on it


def interp_right(x: np.ndarray, xp, fp) -> np.ndarray:
    """Right-continuous piecewise-linear interpolation.

    Parameters
    ----------
    x : numpy.ndarray
        The abscissae asked for.
    xp, fp : array_like
        The diagram's points (a repeated abscissa: a jump).

    Returns
    -------
    numpy.ndarray
        The values: constant beyond the ends, the value after the jump at a repeated
        abscissa; x within 1e-9 of an abscissa is snapped onto it.
    """
    xp = np.asarray(xp, float)
    fp = np.asarray(fp, float)
    x = np.array(x, dtype=float, copy=True)
    j = np.clip(np.searchsorted(xp, x), 0, len(xp) - 1)
    for jj in (j, np.clip(j - 1, 0, len(xp) - 1)):
        near = np.abs(x - xp[jj]) <= _SNAP * max(1.0, float(np.max(np.abs(xp))))
        x[near] = xp[jj][near]
    i = np.searchsorted(xp, x, side="right") - 1
    out = np.empty_like(x)
    lo = i < 0
    hi = i >= len(xp) - 1
    mid = ~(lo | hi)
    out[lo] = fp[0]
    out[hi] = fp[-1]
    im = i[mid]
    x0, x1 = xp[im], xp[im + 1]
    t = (x[mid] - x0) / (x1 - x0)
    out[mid] = fp[im] + t * (fp[im + 1] - fp[im])
    return out


def cycle_angle(phi, phi0: float, sign: float, cycle: float) -> np.ndarray:
    """The crank's rotation from position 0 along the motion.

    Parameters
    ----------
    phi : array_like
        Crank angles, deg.
    phi0 : float
        The angle of position 0, deg.
    sign : float
        +1 for a ccw crank, -1 for cw.
    cycle : float
        The cycle, deg.

    Returns
    -------
    numpy.ndarray
        q in [0, cycle), deg: angles at or after phi0 (unwrapped: phi0 + sign q) give
        q mod cycle; angles numerically before phi0 (the reported positions are in [0, 360))
        are read in the first turn: q mod 360.
    """
    q = (np.asarray(phi, float) - phi0) * sign
    q = np.where(q < 0, np.mod(q, 360.0), np.mod(q, cycle))
    return np.where(q > cycle - _SNAP, 0.0, q)


def diagram_curve(sp, scale: float) -> dict:
    """A load's diagram as the task gives it.

    Parameters
    ----------
    sp : ForceSpec
        The load (its ``diagram``).
    scale : float
        The factor of its values (a pressure's area, m^2; 1 for a force).

    Returns
    -------
    dict
        The abscissa (s/H or phi from position 0, deg) and the values, N.
    """
    if sp.diagram is not None:
        xs = sp.diagram.phi if sp.diagram.phi is not None else sp.diagram.s
        return {"x": [float(v) for v in xs], "value": [float(v) * scale for v in sp.diagram.value]}
    return {"x": [0.0, 1.0], "value": [float(sp.magnitude) * scale] * 2}
