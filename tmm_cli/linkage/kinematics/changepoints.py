"""Change points of a linkage: crank angles where a group's velocity equations are singular.

A group's velocity (and acceleration) equations J(phi) q' = b(phi) are singular where the
determinant of J vanishes: the group's links are collinear. Where this happens inside the
cycle of a linkage that turns all the way round, the mechanism is at a change point
(Artobolevsky, ch. on four-bar linkages: a four-bar on the Grashof limit s + l = p + q -
a parallelogram, an antiparallelogram, a deltoid - and its relatives): its links can
leave the point along either branch, and a velocity or acceleration may jump or grow
without bound there. They are found on every group, not only on known linkages:

* the normalised determinant of each group (the sine of the angle between the columns
  of a dyad's 2x2 system; the determinant of the row/column-equilibrated matrix of a
  larger group) is sampled over one turn (``N_GRID`` points);
* a sign change is refined by Brent's method, a touching zero (a double root: a local
  minimum of |det| that does not change sign, as at the extended position of a
  crank-rocker on the Grashof limit) by a bounded minimisation, accepted below
  DOUBLE_ROOT and placed at the vertex of det^2 (docs/methods.md §2.1).

Positions within ``NEAR_DEG`` of a change point are marked ``near_singular`` in the
results; there a velocity or acceleration whose magnitude exceeds ``BLOWUP`` times its
largest value elsewhere in the cycle (farther than ``NEAR_DEG`` from every change point)
has no finite limit and is reported as null.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...messages import Message

N_GRID = 720        # samples of each group's determinant over one turn
NEAR_DEG = 1.0      # positions this close to a change point are flagged (as in kinetostatics)
BLOWUP = 10.0       # a value this many times its largest value elsewhere in the cycle: null
TOUCH_GRID = 1e-3   # |det| / max|det| below this at a local minimum: look for a touching zero
TOUCH_ZERO = 1e-9   # ... and accept it when the refined minimum is below this


ZERO_TOL = 1e-13    # |g| at or below this on the grid is a root (round-off of an exact zero)

# A group's normalised determinant s (dimensionless: the sine of the angle between the
# columns of a dyad's system scaled by the group's length, the determinant of a larger
# group's equilibrated matrix) against round-off. At a change point s has a double root
# (it touches zero without changing sign, |s| V-shaped or parabolic); computed in double
# precision from lengths that are not binary fractions (0.1 + 0.35 = 0.25 + 0.2) its
# minimum only reaches the round-off of an arccos next to +-1, about sqrt(eps) = 1.5e-8
# times a factor of the geometry. Hence:
DOUBLE_ROOT = 1e-6       # a local minimum of |s| refined below this is a change point (a double root)
GROUP_TOUCH_GRID = 0.05  # ... looked for at grid minima of |s| below this (a V of slope ~10 sampled 0.25 deg off)
# A position where |s| < ILL_DET is ill-conditioned: the velocities carry errors of about
# eps / s^2 and the accelerations eps / s^3 of the cycle's values (1e-6 at s = 1e-3, 0.01 at
# s = 1e-4, the size of the value at s = 1e-5). It is flagged near_singular and its
# velocities and accelerations are taken by continuity (limits.py), or null; where
# |s| < SING_DET it is at a singular (change) point to working precision: flagged singular.
ILL_DET = 1e-3
SING_DET = DOUBLE_ROOT


def circle_zeros(grid: np.ndarray, g: np.ndarray, F, *, zero_tol: float = ZERO_TOL, touch_grid: float = TOUCH_GRID,
                 touch_zero: float = TOUCH_ZERO, vertex: bool = False) -> list[float]:
    """Zeros in [0, 360) of a function of the crank angle periodic over the turn.

    Parameters
    ----------
    grid : numpy.ndarray
        n + 1 angles from 0 to 360, deg.
    g : numpy.ndarray
        The values there, normalised so that max |g| = 1 (NaN where the function is
        undefined, e.g. a group that does not assemble).
    F : callable
        F(phi, start): the value at ``phi`` evaluated continuously from ``start`` (a grid
        point next to ``phi``).
    zero_tol : float
        A grid value within it of zero is a root (at 0/360 the two round-off values may
        differ in sign, as +1e-17 and -1e-17).
    touch_grid, touch_zero : float
        A local minimum of |g| on the grid below ``touch_grid`` whose refined value is below
        ``touch_zero`` is a touching (double) zero.
    vertex : bool
        True: that minimum placed by :func:`_vertex` (the minimiser alone stops anywhere in
        the round-off floor).

    Returns
    -------
    list of float
        The zeros, deg: sign changes refined by Brent's method to 1e-10 deg (the interval
        ending at 360 bracketed with g(0)); touching zeros, local minima of |g| without a
        sign change (around 0 deg as well), by a bounded minimisation (docs/methods.md §3.2).
    """
    from ...lazy import brentq, minimize_scalar

    grid = np.asarray(grid, float)
    n = grid.size - 1
    step = grid[1] - grid[0]
    gp = np.asarray(g, float)[:n]           # one period: the value at 360 is the one at 0
    with np.errstate(invalid="ignore"):
        zero = np.abs(gp) <= zero_tol      # (False where NaN)
    roots: list[float] = [float(grid[i]) for i in np.flatnonzero(zero)]
    for i in range(n):
        j = (i + 1) % n
        if not zero[i] and not zero[j] and gp[i] * gp[j] < 0:   # False where either is NaN
            a0, a1 = grid[i], grid[i + 1]
            try:
                roots.append(brentq(F, a0, a1, args=(a0,), xtol=1e-10, rtol=4 * np.finfo(float).eps))
            except ValueError:  # F does not change sign as sampled: no root to refine
                pass
    ag = np.abs(gp)
    for i in range(n):
        im, ip = (i - 1) % n, (i + 1) % n
        if zero[i] or not (ag[i] < ag[im] and ag[i] <= ag[ip] and ag[i] < touch_grid):
            continue
        if gp[im] * gp[ip] > 0 and gp[im] * gp[i] > 0:
            lo = grid[i] - step
            res = minimize_scalar(lambda t: abs(F(t, lo)), bounds=(lo, grid[i] + step),
                                  method="bounded", options={"xatol": 1e-10})
            if res.fun < touch_zero:
                roots.append(_vertex(F, float(res.x), lo) if vertex else float(res.x))
    out: list[float] = []
    for r in sorted(float(r) % 360.0 for r in roots):
        if r >= 360.0 - 1e-12:
            r = 0.0
        if not out or abs(r - out[-1]) > 1e-7:
            out.append(r)
    if len(out) > 1 and abs(out[0] + 360.0 - out[-1]) <= 1e-7:
        out.pop()
    return out


VERTEX_STEP = 1e-3     # deg: the samples of s^2 either side of a touching zero (s ~ 1e-5, clear of round-off)


def _vertex(F, x0: float, start: float) -> float:
    """A touching (double) zero of g = F refined: g^2 is smooth there, a parabola
    k^2 (phi - phi_c)^2 whether |g| is V-shaped (g = k |phi - phi_c|, a change point) or
    parabolic; its vertex from g^2 at x0 + VERTEX_STEP (-2, -1, 1, 2) by least squares (one
    Newton step on the derivative of g^2), taken when within VERTEX_STEP of x0 (else x0).
    The minimiser alone stops anywhere where |g| is below its round-off floor, sqrt(eps)
    for lengths that are not binary fractions: a few 1e-6 deg off."""
    t = np.array([-2.0, -1.0, 1.0, 2.0]) * VERTEX_STEP
    y = np.array([F(x0 + dt, start) ** 2 for dt in t])
    c2, c1, _ = np.polyfit(t, y, 2)
    if not (c2 > 0 and np.all(np.isfinite(y))):
        return x0
    dx = -c1 / (2.0 * c2)
    return x0 + dx if abs(dx) <= VERTEX_STEP else x0


@dataclass(frozen=True)
class ChangePoint:
    """A crank angle where a group's closure changes (the solver's branch switches)."""

    phi: float          # crank angle, deg in [0, 360)
    group: int          # index of the group in the solver's order
    describe: str       # "group II(2,3) (links coupler, rocker)"


def change_points(solver) -> list[ChangePoint]:
    """Every change point of a linkage over one turn.

    Parameters
    ----------
    solver : Solver
        The linkage's kinematic model.

    Returns
    -------
    list of ChangePoint
        The crank angles (deg) where a group's determinant vanishes, with the group and the
        kind (cached on the solver).

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: the change (singular) positions of a
    linkage, where an Assur group's closure is degenerate; docs/methods.md §2.
    """
    cached = solver.__dict__.get("_change_points")
    if cached is not None:
        return cached
    grid = np.linspace(0.0, 360.0, N_GRID + 1)
    st = solver.run(np.radians(grid), strict=False, fallback=False, dets=True)
    found: list[ChangePoint] = []
    for gi, det in st.gdet.items():
        d = np.where(st.margins[gi] >= -solver.tol, np.asarray(det, float), np.nan)
        fmax = float(np.nanmax(np.abs(d))) if np.isfinite(d).any() else 0.0
        if not np.isfinite(fmax) or fmax == 0.0:
            continue

        def F(phi, start, gi=gi, fmax=fmax):
            s = solver.run(np.radians(np.array([start, phi])), upto=gi + 1, strict=False, fallback=False,
                           dets=True)
            return float(s.gdet[gi][-1]) / fmax

        for phi in circle_zeros(grid, d / fmax, F, touch_grid=GROUP_TOUCH_GRID / fmax,
                                touch_zero=DOUBLE_ROOT / fmax, vertex=True):
            found.append(ChangePoint(phi, gi, solver.groups[gi].describe()))
    found.sort(key=lambda c: c.phi)
    solver.__dict__["_change_points"] = found
    return found


def distance_deg(phi_deg, angles) -> np.ndarray:
    """The distance on the circle to the nearest of given angles.

    Parameters
    ----------
    phi_deg : array_like
        Crank angles, deg.
    angles : sequence of float
        The angles, deg.

    Returns
    -------
    numpy.ndarray
        The distance of each of ``phi_deg`` to the nearest of ``angles``, deg, on the circle.
    """
    phi = np.atleast_1d(np.asarray(phi_deg, float)) % 360.0
    a = np.asarray(list(angles), float)
    if a.size == 0:
        return np.full(phi.shape, np.inf)
    d = np.abs(phi[:, None] - a[None, :]) % 360.0
    return np.min(np.minimum(d, 360.0 - d), axis=1)


def warning(cp: ChangePoint, group) -> Message:
    """The warning of a change point.

    Parameters
    ----------
    cp : ChangePoint
        The change point.
    group : Group
        Its Assur group (:class:`..structure.Group`).

    Returns
    -------
    Message
        The coded warning naming the group and the crank angle (deg).
    """
    return Message("kinematics.change_point", phi=cp.phi, **group.message_params(), near=NEAR_DEG,
                   blowup=BLOWUP)
