"""Scalar root finding and bounded minimisation without importing scipy.

``scipy.optimize`` costs 0.3-0.6 s to import, more than a whole JSON run computes;
the stages only need two scalar routines from it, so they are written out here,
step for step as scipy does them (Brent 1973, "Algorithms for Minimization without
Derivatives", ch. 4 and 5): the same iterates, hence the same results.

* ``brentq(f, a, b, args=(), xtol=2e-12, rtol=4*eps, maxiter=100)`` - the zero of
  ``f`` in ``[a, b]`` (``f(a)``, ``f(b)`` of opposite signs); a transcription of
  scipy's C ``brentq`` (Brent's method with inverse quadratic extrapolation).
* ``minimize_scalar(f, bounds=(a, b), method="bounded", options={"xatol": ...})`` -
  Brent's bounded minimiser (scipy's ``_minimize_scalar_bounded``), returning an
  object with ``x``, ``fun``, ``success``, ``nfev``.
* ``unique(a)`` - ``np.unique(a)`` (the sorted distinct values, NaNs counted once): numpy's
  own function imports numpy.ma (~10 ms) to ask whether ``a`` is masked.
* ``leggauss(n)`` - ``numpy.polynomial.legendre.leggauss(n)`` (the n-point Gauss-Legendre
  nodes and weights on [-1, 1]), step for step: importing numpy.polynomial (its six
  polynomial kinds) costs ~5 ms, a fifth of a flywheel's computing.
"""
from __future__ import annotations

import math
from types import SimpleNamespace

_EPS = 2.220446049250313e-16


def brentq(f, a, b, args=(), xtol=2e-12, rtol=4 * _EPS, maxiter=100, full_output=False, disp=True):
    """The zero of f in [a, b] by Brent's method (scipy.optimize.brentq's algorithm)."""
    if xtol <= 0:
        raise ValueError(f"xtol too small ({xtol:g} <= 0)")
    if rtol < 4 * _EPS:
        raise ValueError(f"rtol too small ({rtol:g} < {4 * _EPS:g})")
    xpre, xcur = float(a), float(b)
    xblk = fblk = spre = scur = 0.0
    fpre = float(f(xpre, *args))
    fcur = float(f(xcur, *args))
    if fpre == 0:
        return xpre
    if fcur == 0:
        return xcur
    if math.copysign(1.0, fpre) == math.copysign(1.0, fcur):
        raise ValueError("f(a) and f(b) must have different signs")
    for _ in range(int(maxiter)):
        if fpre != 0 and fcur != 0 and math.copysign(1.0, fpre) != math.copysign(1.0, fcur):
            xblk, fblk = xpre, fpre
            spre = scur = xcur - xpre
        if abs(fblk) < abs(fcur):
            xpre, xcur, xblk = xcur, xblk, xcur
            fpre, fcur, fblk = fcur, fblk, fcur
        delta = (xtol + rtol * abs(xcur)) / 2
        sbis = (xblk - xcur) / 2
        if fcur == 0 or abs(sbis) < delta:
            return xcur
        if abs(spre) > delta and abs(fcur) < abs(fpre):
            if xpre == xblk:                      # interpolate
                stry = -fcur * (xcur - xpre) / (fcur - fpre)
            else:                                 # extrapolate
                dpre = (fpre - fcur) / (xpre - xcur)
                dblk = (fblk - fcur) / (xblk - xcur)
                stry = -fcur * (fblk * dblk - fpre * dpre) / (dblk * dpre * (fblk - fpre))
            if 2 * abs(stry) < min(abs(spre), 3 * abs(sbis) - delta):
                spre, scur = scur, stry           # good short step
            else:
                spre = scur = sbis                # bisect
        else:
            spre = scur = sbis                    # bisect
        xpre, fpre = xcur, fcur
        if abs(scur) > delta:
            xcur += scur
        else:
            xcur += delta if sbis > 0 else -delta
        fcur = float(f(xcur, *args))
    if disp:
        raise RuntimeError(f"brentq: failed to converge after {maxiter} iterations, value is {xcur}")
    return xcur


def minimize_scalar(func, bounds, args=(), method="bounded", options=None):
    """Brent's bounded minimiser of a scalar function (scipy's ``method="bounded"``)."""
    if method != "bounded":
        raise ValueError("only method='bounded' is provided")
    opts = dict(options or {})
    xatol = float(opts.get("xatol", 1e-5))
    maxfun = int(opts.get("maxiter", 500))
    x1, x2 = (float(v) for v in bounds)
    if not (math.isfinite(x1) and math.isfinite(x2)):
        raise ValueError("Optimization bounds must be finite scalars.")
    if x1 > x2:
        raise ValueError("The lower bound exceeds the upper bound.")
    flag = 0
    sqrt_eps = math.sqrt(2.2e-16)
    golden_mean = 0.5 * (3.0 - math.sqrt(5.0))
    a, b = x1, x2
    fulc = a + golden_mean * (b - a)
    nfc, xf = fulc, fulc
    rat = e = 0.0
    x = xf
    fx = func(x, *args)
    num = 1
    fu = math.inf
    ffulc = fnfc = fx
    xm = 0.5 * (a + b)
    tol1 = sqrt_eps * abs(xf) + xatol / 3.0
    tol2 = 2.0 * tol1
    while abs(xf - xm) > (tol2 - 0.5 * (b - a)):
        golden = 1
        if abs(e) > tol1:                          # parabolic fit
            golden = 0
            r = (xf - nfc) * (fx - ffulc)
            q = (xf - fulc) * (fx - fnfc)
            p = (xf - fulc) * q - (xf - nfc) * r
            q = 2.0 * (q - r)
            if q > 0.0:
                p = -p
            q = abs(q)
            r = e
            e = rat
            if abs(p) < abs(0.5 * q * r) and p > q * (a - xf) and p < q * (b - xf):
                rat = (p + 0.0) / q
                x = xf + rat
                if (x - a) < tol2 or (b - x) < tol2:
                    si = _sign(xm - xf) + ((xm - xf) == 0)
                    rat = tol1 * si
            else:
                golden = 1
        if golden:                                 # golden-section step
            e = (a - xf) if xf >= xm else (b - xf)
            rat = golden_mean * e
        si = _sign(rat) + (rat == 0)
        x = xf + si * max(abs(rat), tol1)
        fu = func(x, *args)
        num += 1
        if fu <= fx:
            if x >= xf:
                a = xf
            else:
                b = xf
            fulc, ffulc = nfc, fnfc
            nfc, fnfc = xf, fx
            xf, fx = x, fu
        else:
            if x < xf:
                a = x
            else:
                b = x
            if fu <= fnfc or nfc == xf:
                fulc, ffulc = nfc, fnfc
                nfc, fnfc = x, fu
            elif fu <= ffulc or fulc == xf or fulc == nfc:
                fulc, ffulc = x, fu
        xm = 0.5 * (a + b)
        tol1 = sqrt_eps * abs(xf) + xatol / 3.0
        tol2 = 2.0 * tol1
        if num >= maxfun:
            flag = 1
            break
    if math.isnan(xf) or math.isnan(fx) or math.isnan(fu):
        flag = 2
    return SimpleNamespace(x=xf, fun=fx, status=flag, success=flag == 0, nfev=num, nit=num)


def unique(a):
    """``np.unique(a)`` without importing numpy.ma: numpy's ``_unique1d`` step for step
    (sort a flattened copy, keep each value that differs from the one before; of the
    NaNs sorted last, only the first)."""
    import numpy as np

    aux = np.array(a).ravel()           # a copy, as np.unique's flatten()
    aux.sort()
    mask = np.empty(aux.shape, dtype=bool)
    mask[:1] = True
    if aux.shape[0] > 0 and aux.dtype.kind in "cfmM" and np.isnan(aux[-1]):
        if aux.dtype.kind == "c":
            first_nan = np.searchsorted(np.isnan(aux), True, side="left")
        else:
            first_nan = np.searchsorted(aux, aux[-1], side="left")
        if first_nan > 0:
            mask[1:first_nan] = aux[1:first_nan] != aux[:first_nan - 1]
        mask[first_nan] = True
        mask[first_nan + 1:] = False
    else:
        mask[1:] = aux[1:] != aux[:-1]
    return aux[mask]


def _sign(v: float) -> float:
    return 0.0 if v == 0 else math.copysign(1.0, v)


def leggauss(n: int):
    """``numpy.polynomial.legendre.leggauss(n)``: numpy's steps in numpy's order (the
    eigenvalues of the scaled companion matrix of L_n, one Newton step, the weights from
    L_n' and L_(n-1), symmetrised and scaled to sum to 2), hence the same values."""
    import numpy as np

    n = int(n)
    if n <= 0:
        raise ValueError("deg must be a positive integer")
    c = np.array([0] * n + [1], dtype=np.double)
    if n == 1:                                      # legcompanion of a degree-1 series
        m = np.array([[-c[0] / c[1]]])
    else:                                           # legcompanion: symmetric, c = e_n
        m = np.zeros((n, n))
        scl = 1. / np.sqrt(2 * np.arange(n) + 1)
        top = m.reshape(-1)[1::n + 1]
        bot = m.reshape(-1)[n::n + 1]
        top[...] = np.arange(1, n) * scl[:n - 1] * scl[1:n]
        bot[...] = top
        m[:, -1] -= (c[:-1] / c[-1]) * (scl / scl[-1]) * (n / (2 * n - 1))
    x = np.linalg.eigvalsh(m)
    dy = _legval(x, c)                              # one Newton step
    df = _legval(x, _legder(c))
    x -= dy / df
    fm = _legval(x, c[1:])                          # the weights, scaled against overflow
    fm /= np.abs(fm).max()
    df /= np.abs(df).max()
    w = 1 / (fm * df)
    w = (w + w[::-1]) / 2                           # symmetrise
    x = (x - x[::-1]) / 2
    w *= 2. / w.sum()
    return x, w


def _legval(x, c):
    """numpy's legval(x, c) of a 1-D float series at an array x (Clenshaw recursion)."""
    c = c.reshape(c.shape + (1,) * x.ndim)
    if len(c) == 1:
        c0, c1 = c[0], 0
    elif len(c) == 2:
        c0, c1 = c[0], c[1]
    else:
        nd = len(c)
        c0, c1 = c[-2], c[-1]
        for i in range(3, len(c) + 1):
            tmp = c0
            nd = nd - 1
            c0 = c[-i] - c1 * ((nd - 1) / nd)
            c1 = tmp + c1 * x * ((2 * nd - 1) / nd)
    return c0 + c1 * x


def _legder(c):
    """numpy's legder(c) (the first derivative) of a 1-D float series."""
    import numpy as np

    c = c.copy()
    n = len(c)
    if n <= 1:
        return c[:1] * 0
    n = n - 1
    der = np.empty((n,), dtype=c.dtype)
    for j in range(n, 2, -1):
        der[j - 1] = (2 * j - 1) * c[j]
        c[j - 2] += c[j]
    if n > 1:
        der[1] = 3 * c[2]
    der[0] = c[1]
    return der
