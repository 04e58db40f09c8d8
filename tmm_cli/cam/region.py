"""The admissible region of cam centres and the point of it nearest to ``B0``.

The region is the intersection of the half-planes ``n(phi) . O <= c(phi)`` (one pair per
cam angle on the rise and on the return, see :mod:`.geometry`), a convex set.  The
smallest cam is its point nearest to the lowest roller-centre position ``B0``: a
least-distance problem with a continuum of linear constraints.  It is solved exactly by
an exchange method:

1. the constraints on a grid of 361 points per phase form a least-distance program, solved
   exactly by Lawson & Hanson's reduction to non-negative least squares (LDP via NNLS);
2. at that centre every local minimum of the continuous slack ``c(phi) - n(phi) . O`` is
   located to machine precision by a vectorised bracketing search, the violated
   tangent lines are added and step 1 is repeated, until no line is violated by more
   than 1e-13 of the stroke.

At the solution the active constraints are the tangent lines of the graphical method
(the lines through the points D of the ``s - ds/dphi`` diagram at the allowed pressure
angle); they are returned for the drawing.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .geometry import Geometry
from .motion import FAR_DWELL, NEAR_DWELL, Motion

GRID = 361
TOL = 1e-13
LDP_TOL = 1e-9     # accepted constraint violation of an LDP solution (scaled units)
MAX_ROUNDS = 40


@dataclass(frozen=True)
class Family:
    """A family of pressure-angle constraint lines: its phase, side and tan of the angle."""

    phase: int         # RISE, RETURN, NEAR_DWELL, FAR_DWELL
    side: int          # +1 / -1
    tan: float         # tan of the allowed pressure angle


@dataclass
class Tangent:
    """One active constraint line at the solution."""
    phase: int
    side: int
    x: float           # phase fraction
    n: np.ndarray      # unit normal of the line
    c: float
    D: np.ndarray      # the point of the s - ds/dphi diagram the line passes through


def rows(motion: Motion, geom: Geometry, k, side, tan, x):
    """The pressure-angle constraint lines n . O <= c at points of the motion.

    Parameters
    ----------
    motion : Motion
        The follower's motion.
    geom : Geometry
        The follower's geometry.
    k, side, tan, x : array_like
        Per line: the phase index, the side (+1/-1), tan of the allowed pressure angle and
        the fraction of the phase.

    Returns
    -------
    N : numpy.ndarray
        The unit normals (n, 2).
    c : numpy.ndarray
        The right-hand sides, m.
    D : numpy.ndarray
        The points of the ``s - ds/dphi`` diagram the lines pass through, m.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*; Popov & Timofeev, *Kursovoe
    proektirovanie po TMM*; Frolov (ed.), *Teoriya mekhanizmov i mashin*: the tangents to the
    s - ds/dphi diagram at the allowed pressure angle bounding the region of the cam
    centres; docs/methods.md §5.
    """
    s, s1, _, _ = motion.phase_mixed(k, x)
    return geom.lines(s, s1, tan, side)


def zoom(func, lo, hi, m: int = 65, rounds: int = 8):
    """Vectorised bracketing search for the minima of a function, one per row.

    Parameters
    ----------
    func : callable
        ``func(grid)`` takes an array (k, m) of abscissae and returns values of that shape.
    lo, hi : numpy.ndarray
        The brackets [lo_i, hi_i] (k,).
    m : int
        Points per bracket and round.
    rounds : int
        Rounds; each keeps the two grid cells around the row's minimum, shrinking the
        bracket by (m - 1)/2: 8 rounds of 65 points reach 1e-12 of the initial bracket
        (itself two grid cells of 1/360 of a phase).

    Returns
    -------
    x : numpy.ndarray
        The abscissae of the minima (k,).
    value : numpy.ndarray
        The values there (k,).
    """
    lo = np.asarray(lo, dtype=float).copy()
    hi = np.asarray(hi, dtype=float).copy()
    t = np.linspace(0.0, 1.0, m)
    rows_ = np.arange(lo.size)
    for _ in range(rounds):
        grid = lo[:, None] + (hi - lo)[:, None] * t
        vals = func(grid)
        j = np.argmin(vals, axis=1)
        lo = grid[rows_, np.maximum(j - 1, 0)]
        hi = grid[rows_, np.minimum(j + 1, m - 1)]
    grid = lo[:, None] + (hi - lo)[:, None] * t
    vals = func(grid)
    j = np.argmin(vals, axis=1)
    return grid[rows_, j], vals[rows_, j]


def local_minima(v: np.ndarray) -> np.ndarray:
    """Indices of the local minima of a sampled function.

    Parameters
    ----------
    v : numpy.ndarray
        The samples (n,).

    Returns
    -------
    numpy.ndarray
        The indices of the local minima, the ends included.
    """
    left = np.concatenate([[np.inf], v[:-1]])
    right = np.concatenate([v[1:], [np.inf]])
    return np.nonzero((v <= left) & (v < right))[0]


def ldp(N: np.ndarray, c: np.ndarray, P0: np.ndarray) -> np.ndarray | None:
    """The point nearest to P0 of the polygon N @ O <= c (least distance programming).

    Parameters
    ----------
    N : numpy.ndarray
        The constraints' normals (n, 2).
    c : numpy.ndarray
        The right-hand sides (n,).
    P0 : numpy.ndarray
        The point (2,).

    Returns
    -------
    numpy.ndarray or None
        The nearest admissible point; None when the region is empty.

    References
    ----------
    Lawson & Hanson, *Solving Least Squares Problems*, ch. 23: LDP by NNLS.
    """
    b = c - N @ P0
    E = np.vstack([-N.T, -b[None, :]])
    f = np.array([0.0, 0.0, 1.0])
    from scipy.optimize import nnls      # lazy: scipy costs more to import than validating a task
    try:
        u, _ = nnls(E, f, maxiter=50 * E.shape[1])
    except RuntimeError:          # NNLS did not converge: treat as no (reliable) solution
        return None
    r = E @ u - f
    if np.linalg.norm(r) < 1e-12 or abs(r[2]) < 1e-300:
        return None
    O = P0 - r[:2] / r[2]
    # Near-empty regions (the infimum escapes to infinity) give a tiny residual and a
    # far, inaccurate point that violates the constraints: accept only a feasible point.
    if not np.all(np.isfinite(O)):
        return None
    if float(np.max(N @ O - c)) > LDP_TOL * max(1.0, float(np.linalg.norm(O))):
        return None
    return O


class _Problem:
    def __init__(self, motion: Motion, geom: Geometry, families: list[Family], grid: int = GRID):
        self.motion, self.geom, self.families = motion, geom, families
        segs, ks, sds, tns, xs = [], [], [], [], []
        pos = 0
        for f in families:
            x = np.array([0.0]) if f.phase in (NEAR_DWELL, FAR_DWELL) else np.linspace(0, 1, grid)
            segs.append((pos, pos + x.size))
            pos += x.size
            ks.append(np.full(x.size, f.phase))
            sds.append(np.full(x.size, f.side))
            tns.append(np.full(x.size, f.tan))
            xs.append(x)
        self.segs = segs
        self.k, self.side, self.tan, self.x = (np.concatenate(a) for a in (ks, sds, tns, xs))
        self.N, self.c, self.D = rows(motion, geom, self.k, self.side, self.tan, self.x)

    def refine(self, value_fn, values: np.ndarray, threshold: float):
        """Continuous local minima of value_fn near the sampled local minima below threshold."""
        cand_f, cand_lo, cand_hi = [], [], []
        for fi, (a, b) in enumerate(self.segs):
            v = values[a:b]
            if b - a == 1:
                if v[0] < threshold:
                    cand_f.append(fi)
                    cand_lo.append(0.0)
                    cand_hi.append(0.0)
                continue
            x = self.x[a:b]
            for j in local_minima(v):
                if v[j] < threshold:
                    cand_f.append(fi)
                    cand_lo.append(x[max(j - 1, 0)])
                    cand_hi.append(x[min(j + 1, b - a - 1)])
        if not cand_f:
            return []
        fams = [self.families[i] for i in cand_f]
        k = np.array([f.phase for f in fams])[:, None]
        sd = np.array([f.side for f in fams], dtype=float)[:, None]
        tn = np.array([f.tan for f in fams])[:, None]

        def fn(grid):
            kk = np.broadcast_to(k, grid.shape)
            n, c, D = rows(self.motion, self.geom, kk.ravel(), np.broadcast_to(sd, grid.shape).ravel(),
                           np.broadcast_to(tn, grid.shape).ravel(), grid.ravel())
            return value_fn(n, c).reshape(grid.shape)

        xs, vals = zoom(fn, np.array(cand_lo), np.array(cand_hi))
        out = []
        n, c, D = rows(self.motion, self.geom, k.ravel(), sd.ravel(), tn.ravel(), xs)
        for i, f in enumerate(fams):
            out.append((f, float(xs[i]), float(vals[i]), n[i], float(c[i]), D[i]))
        return out


def nearest(motion: Motion, geom: Geometry, families: list[Family], P0=(0.0, 0.0),
            scale: float = 1.0) -> tuple[np.ndarray, list[Tangent]] | None:
    """The admissible cam centre nearest to a point, exact, with the active tangent lines.

    Parameters
    ----------
    motion : Motion
        The follower's motion.
    geom : Geometry
        The follower's geometry.
    families : list of Family
        The constraint families (phase, side, tan of the allowed angle).
    P0 : tuple of float
        The point, m (B0, the lowest follower position, is the origin).
    scale : float
        A length of the problem (stroke or rocker length), m, for the tolerances.

    Returns
    -------
    tuple of (numpy.ndarray, list of Tangent) or None
        The centre O (m) and the active constraints; None when the region is empty or no
        admissible point is found to the tolerance (the region recedes to infinity).

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*; Popov & Timofeev, *Kursovoe
    proektirovanie po TMM*; Frolov (ed.), *Teoriya mekhanizmov i mashin*: the smallest cam: the
    cam centre in the admissible region nearest to B0; docs/methods.md §5.
    """
    P0 = np.asarray(P0, dtype=float)
    prob = _Problem(motion, geom, families)
    N, c = prob.N, prob.c
    extra_N, extra_c = [], []
    O = None
    cand = []
    for _ in range(MAX_ROUNDS):
        NN = np.vstack([N] + extra_N) if extra_N else N
        cc = np.concatenate([c] + extra_c) if extra_c else c
        O = ldp(NN, cc / scale, P0 / scale)
        if O is None:
            return None
        O = O * scale
        slack = c - N @ O
        cand = prob.refine(lambda n, cc_: cc_ - n @ O, slack, threshold=1e-3 * scale)
        viol = [e for e in cand if e[2] < -TOL * scale]
        if not viol:
            break
        extra_N.append(np.array([e[3] for e in viol]))
        extra_c.append(np.array([e[4] for e in viol]))
    else:
        # no convergence within MAX_ROUNDS: accept a centre whose remaining violation is at
        # the level of the LDP's rounding (a stalled exchange); a larger one means the centre
        # keeps moving away (the region is empty, its infimum at infinity): never return a
        # point that violates the limits
        worst = min(e[2] for e in cand)
        if worst < -LDP_TOL * max(scale, float(np.linalg.norm(O))):
            return None
    tangents = [Tangent(f.phase, f.side, x, n, cval, D)
                for (f, x, v, n, cval, D) in cand if v < 1e-9 * scale]
    return O, tangents


def highest_on_vertical(motion: Motion, geom: Geometry, families: list[Family], x0: float,
                        scale: float = 1.0) -> tuple[np.ndarray, list[Tangent]]:
    """The admissible centre on the line x = x0 nearest to B0 (translating follower, given offset).

    Parameters
    ----------
    motion : Motion
        The follower's motion.
    geom : Geometry
        The translating follower's geometry.
    families : list of Family
        The constraint families.
    x0 : float
        The line of the cam centres, m (-sigma times the offset).
    scale : float
        A length of the problem (the stroke), m, for the tolerances.

    Returns
    -------
    tuple of (numpy.ndarray, list of Tangent)
        The centre O (m) and the active constraint.

    Notes
    -----
    Every normal has n_y = sin(theta_max) > 0, so the admissible part of the line is
    y <= min_phi (c - n_x x0) / n_y: a one-dimensional minimum over the continuous phi.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*; Popov & Timofeev, *Kursovoe
    proektirovanie po TMM*; Frolov (ed.), *Teoriya mekhanizmov i mashin*: the least base radius
    with a given offset; docs/methods.md §5.
    """
    prob = _Problem(motion, geom, families)

    def yb(n, c):
        return (c - n[:, 0] * x0) / n[:, 1]

    vals = yb(prob.N, prob.c)
    cand = prob.refine(yb, vals, threshold=float(np.min(vals)) + 1e-3 * scale)
    y = min(e[2] for e in cand)
    O = np.array([x0, y])
    tangents = [Tangent(f.phase, f.side, x, n, cval, D)
                for (f, x, v, n, cval, D) in cand if v < y + 1e-9 * scale]
    return O, tangents


def max_angle(motion: Motion, geom: Geometry, phase: int, O) -> tuple[float, float]:
    """The greatest pressure angle over a phase for a given cam centre.

    Parameters
    ----------
    motion : Motion
        The follower's motion.
    geom : Geometry
        The follower's geometry.
    phase : int
        RISE, RETURN, NEAR_DWELL or FAR_DWELL.
    O : array_like
        The cam centre in the design frame, m.

    Returns
    -------
    theta : float
        The greatest pressure angle, rad.
    x : float
        The fraction of the phase where it is.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*; Popov & Timofeev, *Kursovoe
    proektirovanie po TMM*; Frolov (ed.), *Teoriya mekhanizmov i mashin*: the pressure angle
    tan(theta) = |ds/dphi -+ e| / (s0 + s); docs/methods.md §5.
    """
    O = np.asarray(O, dtype=float)
    if phase in (NEAR_DWELL, FAR_DWELL):
        s, s1, _, _ = motion.phase(phase, np.array([0.0]))
        th, _ = geom.pressure_angle(s, s1, O)
        return float(th[0]), 0.0

    def neg(xg):
        s, s1, _, _ = motion.phase(phase, xg)
        th, _ = geom.pressure_angle(s, s1, O)
        return -th

    x, v = phase_min(neg)
    return float(-v), float(x)


def phase_min(func) -> tuple[float, float]:
    """Minimum of a function on the closed phase [0, 1].

    Parameters
    ----------
    func : callable
        Vectorised over rows of fractions of the phase.

    Returns
    -------
    x : float
        The fraction of the phase where the minimum is.
    value : float
        The minimum.

    Notes
    -----
    Sampled on the grid, every local minimum refined by :func:`zoom`.
    """
    x = np.linspace(0, 1, GRID)
    v = func(x[None, :])[0]
    idx = local_minima(v)
    xs, vals = zoom(func, x[np.maximum(idx - 1, 0)], x[np.minimum(idx + 1, x.size - 1)])
    j = int(np.argmin(vals))
    return float(xs[j]), float(vals[j])
