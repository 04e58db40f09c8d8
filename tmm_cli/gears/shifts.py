"""Choice of the shift coefficients (``x: auto``) and the blocking contour.

Blocking contour (Bolotovsky's "blokiruyushchii kontur"): the region of the (x1, x2) plane
where every quality check holds.  It is computed on a grid with the closed forms of
:mod:`geometry` and its boundary lines are the zero levels of

  undercut_i      x_i - x_min_i                                  (straight lines)
  sharpening_i    sa_i / m - k                                   (k = 0.25 default)
  contact_ratio   eps_alpha - 1.2
  interference_i  (rho_p_i - max(rho_l_i, 0)) / m

(positive = the check holds), traced by marching squares (contourpy).

Rules for ``x: auto`` (``rule`` in the task; the task model's default is equal_sliding):
  no_undercut    the smallest non-negative shifts without undercut: x_i = max(0, x_min_i)
                 (so the smallest sum x1 + x2 for which neither wheel is undercut and no wheel
                 is weakened by a negative shift).
  equal_sliding  the same sum x_sum = max(0, x_min1) + max(0, x_min2) distributed so that the
                 maximum specific slidings are equal, lambda1(B1) = lambda2(B2) (Popov &
                 Timofeev; for z1, z2 >= 17 this gives the height-corrected pair x2 = -x1).
  table          the handbook recommendation x1 = x2 = 0.5 (general-purpose spur pairs,
                 z1, z2 >= 10; below 10 teeth: x_i = max(0.5, x_min_i)).
The point of any rule is then checked against the contour; if it falls outside, the nearest
admissible grid point is taken instead and a warning says so.
"""
from __future__ import annotations

import numpy as np
from ..lazy import brentq
from ..messages import Message

from .geometry import COURSE_EPS, pair, sliding

RULES = ("no_undercut", "equal_sliding", "table")


def _margins(geo, m, sa_min, x1, x2):
    return {
        "undercut_1": x1 - geo["x_min1"],
        "undercut_2": x2 - geo["x_min2"],
        "sharpening_1": geo["sa1"] / m - sa_min,
        "sharpening_2": geo["sa2"] / m - sa_min,
        "contact_ratio": geo["eps"] - COURSE_EPS,
        "interference_1": (geo["rho_p1"] - np.maximum(geo["rho_l1"], 0.0)) / m,
        "interference_2": (geo["rho_p2"] - np.maximum(geo["rho_l2"], 0.0)) / m,
    }


def max_sliding(geo, z1, z2):
    """The extreme specific slidings of the two wheels.

    Parameters
    ----------
    geo : dict
        The pair's quantities (:func:`.geometry.pair`).
    z1, z2 : int
        Tooth numbers.

    Returns
    -------
    tuple of float
        (lambda1 at B1, lambda2 at B2).

    References
    ----------
    Popov & Timofeev, *Kursovoe proektirovanie po TMM*: the specific sliding at the ends of
    the active line of action; docs/methods.md §6.
    """
    l1, _ = sliding(geo["N1B1"], geo["N1N2"], z1, z2)
    _, l2 = sliding(geo["N1B2"], geo["N1N2"], z1, z2)
    return l1, l2


def blocking_contour(m, z1, z2, alpha=20.0, ha=1.0, c=0.25, sa_min=0.25, rho_f=None,
                     x1_range=None, x2_range=None, n=161):
    """The blocking contour of a pair: the admissible region of the shifts (x1, x2).

    Parameters
    ----------
    m : float
        Module, m.
    z1, z2 : int
        Tooth numbers.
    alpha : float
        The rack's profile angle, deg.
    ha, c : float
        The addendum and clearance coefficients.
    sa_min : float
        The least tip thickness, a fraction of m.
    rho_f : float or None
        The rack's tip fillet coefficient (None: the full fillet).
    x1_range, x2_range : tuple of float or None
        The ranges of the grid (None: from max(min(x_min, 0), -1) - 0.3, x_min the least shift
        without undercut, to 1.5).
    n : int
        Grid points per axis.

    Returns
    -------
    dict
        ``x1``, ``x2`` (the grid), ``ok`` (the admissible mask), ``lines`` (the boundary
        lines of each check: undercut, sharpening, interference, the contact ratio) and
        ``geo`` (the pair's quantities over the grid).

    References
    ----------
    Bolotovsky, the blocking contours of involute gears; Popov & Timofeev, *Kursovoe
    proektirovanie po TMM*: the choice of the shifts; docs/methods.md §6.
    """
    geo0 = pair(m, z1, z2, 0.0, 0.0, alpha, ha, c, rho_f)
    lo1 = max(min(float(geo0["x_min1"]), 0.0), -1.0) - 0.3
    lo2 = max(min(float(geo0["x_min2"]), 0.0), -1.0) - 0.3
    x1_range = x1_range or (lo1, 1.5)
    x2_range = x2_range or (lo2, 1.5)
    g1 = np.linspace(*x1_range, n)
    g2 = np.linspace(*x2_range, n)
    X1, X2 = np.meshgrid(g1, g2)                       # rows: x2, columns: x1
    with np.errstate(invalid="ignore", divide="ignore"):
        geo = pair(m, z1, z2, X1, X2, alpha, ha, c, rho_f)
        marg = _margins(geo, m, sa_min, X1, X2)
    valid = geo["valid"] & np.isfinite(geo["eps"])
    ok = valid.copy()
    for v in marg.values():
        ok &= np.nan_to_num(v, nan=-1.0) >= 0
    lines = {}
    import contourpy  # lazy (marching squares; a dependency of its own)

    for name, v in marg.items():
        vv = np.where(valid, v, np.nan)
        if not np.isfinite(vv).any():
            lines[name] = []
            continue
        gen = contourpy.contour_generator(g1, g2, np.ma.masked_invalid(vv))
        segs = gen.lines(0.0)
        lines[name] = [[[float(a), float(b)] for a, b in seg] for seg in segs if len(seg) > 1]
    return {"x1": g1, "x2": g2, "ok": ok, "lines": lines, "geo": geo}


def _equal_sliding_split(m, z1, z2, xs, alpha, ha, c, rho_f, lo, hi):
    def f(x1):
        g = pair(m, z1, z2, x1, xs - x1, alpha, ha, c, rho_f)
        l1, l2 = max_sliding(g, z1, z2)
        return float(l1 - l2)
    grid = np.linspace(lo, hi, 81)
    vals = []
    for x in grid:
        try:
            v = f(x)
        except ValueError:
            v = float("nan")
        vals.append(v)
    vals = np.array(vals)
    for i in range(len(grid) - 1):
        a, b = vals[i], vals[i + 1]
        if np.isfinite(a) and np.isfinite(b) and a * b <= 0:
            return brentq(f, grid[i], grid[i + 1], xtol=1e-12)
    fin = np.isfinite(vals)
    if not fin.any():
        return None
    return float(grid[fin][np.argmin(np.abs(vals[fin]))])


def rule_point(rule, m, z1, z2, alpha=20.0, ha=1.0, c=0.25, rho_f=None):
    """The shifts a rule gives before the contour's check.

    Parameters
    ----------
    rule : str
        ``no_undercut``, ``equal_sliding`` or ``table``.
    m : float
        Module, m.
    z1, z2 : int
        Tooth numbers.
    alpha : float
        The rack's profile angle, deg.
    ha, c : float
        The addendum and clearance coefficients.
    rho_f : float or None
        The rack's tip fillet coefficient.

    Returns
    -------
    tuple of float
        (x1, x2).

    References
    ----------
    Popov & Timofeev, *Kursovoe proektirovanie po TMM*: the rules of choosing the shifts (no
    undercut; equal specific slidings lambda1(B1) = lambda2(B2); the table);
    docs/methods.md §6.
    """
    geo0 = pair(m, z1, z2, 0.0, 0.0, alpha, ha, c, rho_f)
    xm1, xm2 = float(geo0["x_min1"]), float(geo0["x_min2"])
    if rule == "no_undercut":
        return max(0.0, xm1), max(0.0, xm2)
    if rule == "table":
        return max(0.5, xm1), max(0.5, xm2)
    if rule == "equal_sliding":
        xs = max(0.0, xm1) + max(0.0, xm2)
        lo = max(xm1, xs - 1.5, -1.0)
        hi = min(xs - xm2, 1.5)
        if hi <= lo:
            return max(0.0, xm1), max(0.0, xm2)
        x1 = _equal_sliding_split(m, z1, z2, xs, alpha, ha, c, rho_f, lo, hi)
        if x1 is None:
            return max(0.0, xm1), max(0.0, xm2)
        return float(x1), float(xs - x1)
    raise ValueError(f"unknown shift rule {rule!r}; use one of {', '.join(RULES)}")


def choose(rule, m, z1, z2, alpha=20.0, ha=1.0, c=0.25, sa_min=0.25, rho_f=None, contour=None):
    """The shifts for ``x: auto``.

    Parameters
    ----------
    rule : str
        ``no_undercut``, ``equal_sliding`` or ``table``.
    m : float
        Module, m.
    z1, z2 : int
        Tooth numbers.
    alpha : float
        The rack's profile angle, deg.
    ha, c : float
        The addendum and clearance coefficients.
    sa_min : float
        The least tip thickness, a fraction of m.
    rho_f : float or None
        The rack's tip fillet coefficient (None: the full fillet).
    contour : dict or None
        The blocking contour already computed (None: computed here).

    Returns
    -------
    x1, x2 : float
        The shifts: the rule's point, moved into the admissible region when it is outside.
    notes : list
        Warnings (coded messages) about the choice.
    """
    x1, x2 = rule_point(rule, m, z1, z2, alpha, ha, c, rho_f)
    notes = []
    g = pair(m, z1, z2, x1, x2, alpha, ha, c, rho_f)
    marg = _margins(g, m, sa_min, x1, x2) if bool(g["valid"]) else None
    if marg is not None and all(float(v) >= -1e-12 for v in marg.values()):
        return x1, x2, notes
    bc = contour or blocking_contour(m, z1, z2, alpha, ha, c, sa_min, rho_f)
    ok = bc["ok"]
    if not ok.any():
        notes.append(Message("gears.no_admissible_shifts", rule=rule, x1=x1, x2=x2))
        return x1, x2, notes
    X1, X2 = np.meshgrid(bc["x1"], bc["x2"])
    d = np.where(ok, (X1 - x1) ** 2 + (X2 - x2) ** 2, np.inf)
    k = np.unravel_index(np.argmin(d), d.shape)
    nx1, nx2 = float(X1[k]), float(X2[k])
    notes.append(Message("gears.shifts_outside_contour", rule=rule, x1=x1, x2=x2, nx1=nx1, nx2=nx2))
    return nx1, nx2, notes


def _bisect(f, lo, hi, flo, steps):
    """Vectorised bisection of f on [lo, hi] (f(lo) = flo, a sign change in each row)."""
    for _ in range(steps):
        mid = 0.5 * (lo + hi)
        fm = f(mid)
        left = np.sign(fm) == np.sign(flo)
        lo, flo, hi = np.where(left, mid, lo), np.where(left, fm, flo), np.where(left, hi, mid)
    return 0.5 * (lo + hi)


def contour_deviation(bc, m, z1, z2, alpha=20.0, ha=1.0, c=0.25, sa_min=0.25, rho_f=None,
                      tol=1e-13, where: bool = False, boundary: bool = True) -> dict:
    """How far the traced blocking contour lies from the exact zero levels of its checks.

    Parameters
    ----------
    bc : dict
        The contour (:func:`blocking_contour`).
    m : float
        Module, m.
    z1, z2 : int
        Tooth numbers.
    alpha : float
        The rack's profile angle, deg.
    ha, c : float
        The addendum and clearance coefficients.
    sa_min : float
        The least tip thickness, a fraction of m.
    rho_f : float or None
        The rack's tip fillet coefficient (None: the full fillet).
    tol : float
        The bisection's tolerance, in units of x.
    where : bool
        True: give the place of each largest distance too.
    boundary : bool
        True: count the points of the blocking contour itself (where every other check
        holds); False: the whole lines.

    Returns
    -------
    dict
        check -> the largest distance, in units of the shift coefficient x (with ``where``:
        check -> (distance, x1, x2)).

    Notes
    -----
    Marching squares puts each point P of a line on a grid edge, linearly interpolated
    between the edge's two nodes (error O(h^2) where the margin is smooth).  Here the check's
    zero level is located exactly (bisection to ``tol``) on the line through P along its edge
    (A, a distance d1 from P) and on the line through P across it (B, within a cell, d2;
    none: d2 = inf); P's distance to the exact curve is that to the chord AB,
    d1 d2 / sqrt(d1^2 + d2^2) (to O(h^4)).  Counted: points not at a node, with a sign change
    along the edge (not next to an invalid region).
    """
    g1, g2 = bc["x1"], bc["x2"]
    h1, h2 = g1[1] - g1[0], g2[1] - g2[0]
    names = list(bc["lines"])
    P, along, which = [], [], []
    for k, name in enumerate(names):
        pts = np.array([p for seg in bc["lines"][name] for p in seg], dtype=float).reshape(-1, 2)
        # which coordinate lies on the grid: the other one was interpolated
        on_row = np.abs(g2[0] + np.rint((pts[:, 1] - g2[0]) / h2) * h2 - pts[:, 1]) <= 1e-9 * h2
        on_col = np.abs(g1[0] + np.rint((pts[:, 0] - g1[0]) / h1) * h1 - pts[:, 0]) <= 1e-9 * h1
        for ax, sel in ((0, on_row & ~on_col), (1, on_col & ~on_row)):
            P.append(pts[sel])
            along.append(np.full(int(sel.sum()), ax))
            which.append(np.full(int(sel.sum()), k))
    P, along, which = np.concatenate(P), np.concatenate(along), np.concatenate(which)
    out = {name: (0.0, None, None) for name in names}
    if P.size:
        rows = np.arange(len(P))

        def f(x, ax):
            """The point's own margin on the line through it along axis ax (per row)."""
            x1_ = np.where(ax == 0, x, P[:, 0])
            x2_ = np.where(ax == 0, P[:, 1], x)
            with np.errstate(invalid="ignore", divide="ignore"):
                geo = pair(m, z1, z2, x1_, x2_, alpha, ha, c, rho_f)
                marg = _margins(geo, m, sa_min, x1_, x2_)
            v = np.choose(which, [np.broadcast_to(marg[nm], x.shape) for nm in names])
            return np.where(geo["valid"], v, np.nan), marg

        steps = int(np.ceil(np.log2(max(h1, h2) / tol))) + 1
        # along the edge: the edge's nodes bracket the root
        h = np.where(along == 0, h1, h2)
        g0 = np.where(along == 0, g1[0], g2[0])
        nmax = np.where(along == 0, g1.size, g2.size) - 2
        pa = P[rows, along]
        i = np.clip(np.floor((pa - g0) / h), 0, nmax)
        lo, hi = g0 + i * h, g0 + (i + 1) * h
        flo, fhi = f(lo, along)[0], f(hi, along)[0]
        ok = np.isfinite(flo) & np.isfinite(fhi) & (flo * fhi <= 0)
        d1 = np.abs(pa - _bisect(lambda x: f(x, along)[0], lo, hi, flo, steps))
        # across the edge: within a cell on either side of P
        across = 1 - along
        hc = np.where(across == 0, h1, h2)
        pc = P[rows, across]
        f0, marg = f(pc, across)
        fm, fp = f(pc - hc, across)[0], f(pc + hc, across)[0]
        use_m = np.isfinite(fm) & (fm * f0 <= 0)
        use_p = ~use_m & np.isfinite(fp) & (fp * f0 <= 0)
        lo_c = np.where(use_m, pc - hc, pc)
        hi_c = np.where(use_m, pc, pc + hc)
        flo_c = np.where(use_m, fm, f0)
        rc = _bisect(lambda x: f(x, across)[0], lo_c, hi_c, flo_c, steps)
        d2 = np.where(use_m | use_p, np.abs(pc - rc), np.inf)
        with np.errstate(invalid="ignore", divide="ignore"):
            dist = np.where(np.isinf(d2), d1, d1 * d2 / np.sqrt(d1 * d1 + d2 * d2))
        dist = np.where(d1 == 0, 0.0, dist)
        if boundary:        # only the parts of the lines where every other check holds
            for k, nm in enumerate(names):
                ok &= (which == k) | (np.nan_to_num(marg[nm], nan=-1.0) >= 0)
        d = np.where(ok, dist, -1.0)
        for k, name in enumerate(names):
            sel = np.flatnonzero(which == k)
            if sel.size and d[sel].max() >= 0:
                j = sel[np.argmax(d[sel])]
                out[name] = (float(d[j]), float(P[j, 0]), float(P[j, 1]))
    return out if where else {k: v[0] for k, v in out.items()}


__all__ = ["RULES", "blocking_contour", "choose", "rule_point", "max_sliding", "contour_deviation"]
