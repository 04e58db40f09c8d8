"""Choice of the shift coefficients (``x: auto``) and the blocking contour.

Blocking contour (Bolotovsky's «блокирующий контур»): the region of the (x1, x2) plane
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
    """(lambda1 at B1, lambda2 at B2): the extreme specific slidings of the two wheels."""
    l1, _ = sliding(geo["N1B1"], geo["N1N2"], z1, z2)
    _, l2 = sliding(geo["N1B2"], geo["N1N2"], z1, z2)
    return l1, l2


def blocking_contour(m, z1, z2, alpha=20.0, ha=1.0, c=0.25, sa_min=0.25, rho_f=None,
                     x1_range=None, x2_range=None, n=161):
    """Grid, admissible mask and boundary lines of the blocking contour."""
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
    import contourpy  # lazy (a matplotlib dependency)

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
    """The (x1, x2) the rule gives before the contour check."""
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
    """Shifts for ``x: auto``: (x1, x2, notes) with notes a list of warning strings."""
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


__all__ = ["RULES", "blocking_contour", "choose", "rule_point", "max_sliding"]
