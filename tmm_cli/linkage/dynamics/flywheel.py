"""The flywheel on arrays: works, speed fluctuation and the three methods (docs/methods.md §4).

Everything here works on one steady cycle sampled at nodes ``q`` (rad), the crank
rotation from position 0 in the direction of motion, ``q[0] = 0``, ``q[-1]`` = the
cycle (2 pi or 4 pi).  A node may appear twice with the same ``q`` (left and right
limits of a load that jumps there): the trapezoid over that zero-width interval adds
nothing, so the works are exact for loads that are piecewise linear between nodes.

Reduced moments are signed *along the motion* (positive = driving).  Reduced inertia
is split (docs/methods.md §4) into the constant part ``J_const`` (crank, rotor, gears, any link
whose reduced inertia is constant) and the variable part ``J_var(q)`` of the other
links, so ``J_red = J_const + J_var``.  ``J_n`` is the constant reduced inertia needed
(the constant part that, added to ``J_var``, gives the required delta), and the
flywheel is ``J_fly = J_n - J_const``.

Kinetic energy at q: ``T(q) = T0 + dT(q)`` with ``dT = A_d - A_c``, the exact first
integral of the equation of motion ``J omega domega/dq + J' omega^2/2 = M_red``;
``omega = sqrt(2 T / (J_n + J_var))``.

Methods (docs/methods.md §4; where it is silent: Artobolevsky, "Teoriya mekhanizmov i
mashin", ch. on the motion of a machine; Popov & Timofeev; Frolov):

* energy-mass, exact analytic form: ``omega_max,min = omega_m (1 +/- delta/2)``,
  ``a = max(dT - J_var omega_max^2/2)``, ``b = min(dT - J_var omega_min^2/2)``,
  ``J_n = (a - b)/(omega_m^2 delta)``.  On the same nodes this *is* the exact steady
  motion with mean (omega_max + omega_min)/2 = omega_m: if T0 = J_n omega_max^2/2 - a
  then max omega = omega_max and min omega = omega_min exactly.
* Wittenbauer's graphical tangents (tan psi = (mu_J/mu_T) omega_m^2 (1 +/- delta)/2)
  drop the delta^2/4 term: ``|J_n,W - J_n| <= (max J_var - min J_var) delta/8``.
* Merzalov: ``T_II = J_var omega_m^2/2``, ``dT_I = dT - T_II``,
  ``J_n = (max dT_I - min dT_I)/(omega_m^2 delta)``; it neglects the smoothing done
  by the links of variable inertia: ``min J_var <= J_n,M - J_n <= max J_var``.
* exact: the steady motion is integrated (energy form) for a trial J_n, T0 is found so
  that (omega_max + omega_min)/2 = omega_m, and J_n is found by root finding so that the
  achieved (omega_max - omega_min)/omega_m equals delta.  This is an independent
  numerical route to the energy-mass result (they agree to the root tolerance).
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
from ...lazy import brentq, leggauss

from ...errors import StageError
from ...messages import Message

STAGE = "dynamics"
_TINY = 1e-300


def gauss_legendre(n: int) -> tuple[np.ndarray, np.ndarray]:
    """The n-point Gauss-Legendre rule on [0, 1].

    Parameters
    ----------
    n : int
        The number of points.

    Returns
    -------
    nodes : numpy.ndarray
        The nodes on [0, 1].
    weights : numpy.ndarray
        The weights, summing to 1: exact for polynomials of degree 2n - 1, the error
        O(h^(2n)) on smooth integrands.
    """
    x, w = _leggauss(int(n))
    return x.copy(), w.copy()


@functools.lru_cache(maxsize=8)
def _leggauss(n: int) -> tuple[np.ndarray, np.ndarray]:
    x, w = leggauss(n)             # numpy.polynomial.legendre.leggauss's, without importing numpy.polynomial
    return (x + 1.0) / 2.0, w / 2.0


def gauss_points(q: np.ndarray, n: int) -> np.ndarray:
    """The Gauss-Legendre points of every interval of the nodes.

    Parameters
    ----------
    q : numpy.ndarray
        Non-decreasing nodes.
    n : int
        Points per interval.

    Returns
    -------
    numpy.ndarray
        The points inside every interval of positive width, interval by interval
        (intervals, n).
    """
    q = np.asarray(q, float)
    a, h = q[:-1], np.diff(q)
    x, _ = gauss_legendre(n)
    pos = h > 0
    return a[pos, None] + h[pos, None] * x[None, :]


def gauss_increments(q: np.ndarray, y_gauss: np.ndarray, n: int) -> np.ndarray:
    """The integral of a function over every interval of the nodes.

    Parameters
    ----------
    q : numpy.ndarray
        Non-decreasing nodes, rad.
    y_gauss : numpy.ndarray
        The function at :func:`gauss_points` (q, n).
    n : int
        Points per interval.

    Returns
    -------
    numpy.ndarray
        The integrals (zero-width intervals: 0); for a reduced moment in N*m, the works in J.
    """
    q = np.asarray(q, float)
    h = np.diff(q)
    _, w = gauss_legendre(n)
    out = np.zeros(h.size)
    pos = h > 0
    out[pos] = h[pos] * (np.asarray(y_gauss, float).reshape(-1, int(n)) @ w)
    return out


def hermite_critical(q: np.ndarray, y: np.ndarray, dy: np.ndarray) -> np.ndarray:
    """The interior critical points of a piecewise cubic Hermite interpolant.

    Parameters
    ----------
    q : numpy.ndarray
        Non-decreasing nodes.
    y, dy : numpy.ndarray
        The function's values and slopes at the nodes.

    Returns
    -------
    numpy.ndarray
        In every interval of positive width where dy changes sign, the root of the cubic's
        derivative (a quadratic) inside it.  At a maximum or minimum of a smooth y the cubic's
        extremum is within O(h^4) of the true one.
    """
    q = np.asarray(q, float)
    y = np.asarray(y, float)
    dy = np.asarray(dy, float)
    h = np.diff(q)
    s0, s1 = dy[:-1], dy[1:]
    idx = np.nonzero((h > 0) & (s0 * s1 < 0))[0]
    if idx.size == 0:
        return np.zeros(0)
    hh = h[idx]
    p0, p1 = y[idx], y[idx + 1]
    m0, m1 = s0[idx] * hh, s1[idx] * hh
    # p(t) = h00 p0 + h10 m0 + h01 p1 + h11 m1; p'(t) = A t^2 + B t + C
    A = 6 * p0 + 3 * m0 - 6 * p1 + 3 * m1
    B = -6 * p0 - 4 * m0 + 6 * p1 - 2 * m1
    C = m0
    t = np.full(idx.size, 0.5)
    lin = np.abs(A) <= 1e-14 * (np.abs(B) + np.abs(C))
    t[lin] = -C[lin] / np.where(B[lin] != 0, B[lin], 1.0)
    qa = ~lin
    if np.any(qa):
        disc = np.sqrt(np.maximum(B[qa] ** 2 - 4 * A[qa] * C[qa], 0.0))
        qq = -0.5 * (B[qa] + np.copysign(disc, B[qa]))     # stable quadratic formula
        r1 = qq / np.where(A[qa] != 0, A[qa], 1.0)
        r2 = C[qa] / np.where(qq != 0, qq, 1.0)
        # p'(0) and p'(1) differ in sign: exactly one root lies in [0, 1]
        t[qa] = np.where(np.abs(r1 - 0.5) <= np.abs(r2 - 0.5), r1, r2)
    t = np.clip(t, 0.0, 1.0)
    return q[idx] + t * hh


def hermite_at(q: np.ndarray, y: np.ndarray, dy: np.ndarray, x: np.ndarray) -> np.ndarray:
    """The cubic Hermite interpolant at given points.

    Parameters
    ----------
    q : numpy.ndarray
        Non-decreasing nodes (duplicates: one-sided limits).
    y, dy : numpy.ndarray
        The values and slopes at the nodes.
    x : numpy.ndarray
        The points.

    Returns
    -------
    numpy.ndarray
        The interpolant's values at ``x``.
    """
    q = np.asarray(q, float)
    x = np.asarray(x, float)
    i = np.clip(np.searchsorted(q, x, side="right") - 1, 0, q.size - 2)
    h = q[i + 1] - q[i]
    hs = np.where(h > 0, h, 1.0)
    t = np.where(h > 0, (x - q[i]) / hs, 0.0)
    h00 = 2 * t**3 - 3 * t**2 + 1
    h10 = t**3 - 2 * t**2 + t
    h01 = -2 * t**3 + 3 * t**2
    h11 = t**3 - t**2
    return h00 * y[i] + h10 * h * dy[i] + h01 * y[i + 1] + h11 * h * dy[i + 1]


def cumtrapz(q: np.ndarray, y: np.ndarray) -> np.ndarray:
    """The cumulative trapezoid.

    Parameters
    ----------
    q : numpy.ndarray
        Non-decreasing nodes.
    y : numpy.ndarray
        The values there.

    Returns
    -------
    numpy.ndarray
        The integral from q[0] to each node (0 at q[0]; zero-width intervals add nothing).
    """
    q = np.asarray(q, float)
    y = np.asarray(y, float)
    out = np.zeros_like(y)
    if y.size > 1:
        out[1:] = np.cumsum(0.5 * (y[1:] + y[:-1]) * np.diff(q))
    return out


# ------------------------------------------------------------------ works
@dataclass
class CycleWork:
    """Works over the cycle.  M_d is the reduced moment of the driving side (along the
    motion), M_c of the resistance side (positive when it resists); dT = A_d - A_c."""
    q: np.ndarray
    M_given: np.ndarray       # reduced moment of the task's loads (+ gravity), along the motion
    M_constant: float         # the constant reduced moment (signed along the motion)
    M_red: np.ndarray         # M_given + M_constant
    M_d: np.ndarray
    M_c: np.ndarray
    A_d: np.ndarray
    A_c: np.ndarray
    dT: np.ndarray
    A_given: float            # work of the given loads over the cycle
    constant: str             # 'driving' | 'resistance'


def cycle_work(q: np.ndarray, M_given: np.ndarray, constant: str = "driving",
               increments: np.ndarray | None = None) -> CycleWork:
    """The constant reduced moment and the works over the steady cycle.

    Parameters
    ----------
    q : numpy.ndarray
        The nodes along the motion, rad.
    M_given : numpy.ndarray
        The reduced moment of the given loads, N*m.
    constant : str
        ``driving`` (a motor-driven machine: the given loads are the resistance, M_d =
        M_constant) or ``resistance`` (an engine: the given loads drive, M_c = -M_constant).
    increments : numpy.ndarray or None
        The integrals of M_given over every interval, J (e.g. :func:`gauss_increments`;
        None: the trapezoid on the nodes).

    Returns
    -------
    CycleWork
        M_constant (N*m) from zero net work over the cycle, the moments M_d, M_c (N*m) and the
        works A_d, A_c and dT = A_d - A_c (J) along q.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: the works of the driving and
    resisting moments over the steady cycle; docs/methods.md §4.
    """
    q = np.asarray(q, float)
    M_given = np.asarray(M_given, float)
    if q.ndim != 1 or q.size < 2 or q.shape != M_given.shape:
        raise StageError(STAGE, Message("flywheel.fail.nodes"))
    if not np.all(np.isfinite(M_given)):
        raise StageError(STAGE, Message("flywheel.fail.M_not_finite"))
    if np.any(np.diff(q) < 0) or q[-1] <= q[0]:
        raise StageError(STAGE, Message("flywheel.fail.nodes_order"))
    if increments is None:
        A_g = cumtrapz(q, M_given)
    else:
        inc = np.asarray(increments, float)
        if inc.shape != (q.size - 1,) or not np.all(np.isfinite(inc)):
            raise StageError(STAGE, Message("flywheel.fail.works_not_finite"))
        A_g = np.concatenate([[0.0], np.cumsum(inc)])
    span = q[-1] - q[0]
    Mc = -A_g[-1] / span
    M_red = M_given + Mc
    dT = A_g + Mc * (q - q[0])
    # exact zero at the end (removes the rounding of the cumulative sum)
    dT[-1] = 0.0 if abs(dT[-1]) <= 1e-12 * max(np.max(np.abs(A_g)), _TINY) else dT[-1]
    ones = np.ones_like(q)
    if constant == "driving":
        M_d, M_c = Mc * ones, -M_given
        A_d, A_c = Mc * (q - q[0]), -A_g
    elif constant == "resistance":
        M_d, M_c = M_given, -Mc * ones
        A_d, A_c = A_g, -Mc * (q - q[0])
    else:
        raise StageError(STAGE, Message("flywheel.fail.constant", kind=str(constant)))
    return CycleWork(q=q, M_given=M_given, M_constant=float(Mc), M_red=M_red, M_d=M_d, M_c=M_c,
                     A_d=A_d, A_c=A_c, dT=dT, A_given=float(A_g[-1]), constant=constant)


# ------------------------------------------------------------------ methods
def _check(dT, J_var, omega_m, delta):
    dT = np.asarray(dT, float)
    J_var = np.broadcast_to(np.asarray(J_var, float), dT.shape)
    if not (omega_m > 0 and math.isfinite(omega_m)):
        raise StageError(STAGE, Message("flywheel.fail.mean_speed", value=omega_m))
    if not (0 < delta < 1):
        raise StageError(STAGE, Message("flywheel.fail.delta", value=delta))
    if not (np.all(np.isfinite(dT)) and np.all(np.isfinite(J_var))):
        raise StageError(STAGE, Message("flywheel.fail.energy_not_finite"))
    return dT, J_var


def energy_mass(dT, J_var, omega_m: float, delta: float) -> tuple[float, float, float]:
    """The flywheel by the energy-mass (Wittenbauer) method, exactly.

    Parameters
    ----------
    dT : numpy.ndarray
        The increase of the kinetic energy along the cycle, dT = A_d - A_c, J.
    J_var : numpy.ndarray
        The variable part of the reduced moment of inertia, kg*m^2.
    omega_m : float
        The mean speed, rad/s.
    delta : float
        The allowed coefficient of speed fluctuation.

    Returns
    -------
    tuple of float
        (J_n = (a - b)/(omega_m^2 delta), kg*m^2; a = max(dT - J_var omega_max^2/2),
        b = min(dT - J_var omega_min^2/2), J, with omega_max,min = omega_m (1 +- delta/2)).

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: the energy-mass diagram
    (Wittenbauer's method); docs/methods.md §4.
    """
    dT, J_var = _check(dT, J_var, omega_m, delta)
    wmax = omega_m * (1 + delta / 2)
    wmin = omega_m * (1 - delta / 2)
    a = float(np.max(dT - J_var * wmax**2 / 2))
    b = float(np.min(dT - J_var * wmin**2 / 2))
    return (a - b) / (omega_m**2 * delta), a, b


def wittenbauer(dT, J_var, omega_m: float, delta: float) -> tuple[float, float, float]:
    """The flywheel by the graphical Wittenbauer construction.

    Parameters
    ----------
    dT : numpy.ndarray
        The increase of the kinetic energy along the cycle, dT = A_d - A_c, J.
    J_var : numpy.ndarray
        The variable part of the reduced moment of inertia, kg*m^2.
    omega_m : float
        The mean speed, rad/s.
    delta : float
        The allowed coefficient of speed fluctuation.

    Returns
    -------
    tuple of float
        (J_n, kg*m^2; a, b, J): the tangents of slope omega_m^2 (1 +- delta)/2 to the
        energy-mass diagram drawn as the construction draws them.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: Wittenbauer's construction;
    docs/methods.md §4.
    """
    dT, J_var = _check(dT, J_var, omega_m, delta)
    a = float(np.max(dT - J_var * omega_m**2 * (1 + delta) / 2))
    b = float(np.min(dT - J_var * omega_m**2 * (1 - delta) / 2))
    return (a - b) / (omega_m**2 * delta), a, b


def merzalov(dT, J_var, omega_m: float, delta: float) -> tuple[float, np.ndarray, np.ndarray]:
    """The flywheel by Merzalov's method.

    Parameters
    ----------
    dT : numpy.ndarray
        The increase of the kinetic energy along the cycle, dT = A_d - A_c, J.
    J_var : numpy.ndarray
        The variable part of the reduced moment of inertia, kg*m^2.
    omega_m : float
        The mean speed, rad/s.
    delta : float
        The allowed coefficient of speed fluctuation.

    Returns
    -------
    tuple
        (J_n, kg*m^2; dT_I = dT - T_II, J; T_II = J_var omega_m^2/2, J).

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: Merzalov's method of the flywheel;
    docs/methods.md §4.
    """
    dT, J_var = _check(dT, J_var, omega_m, delta)
    T_II = J_var * omega_m**2 / 2
    dT_I = dT - T_II
    return float(np.max(dT_I) - np.min(dT_I)) / (omega_m**2 * delta), dT_I, T_II


# ------------------------------------------------------------------ steady motion
def _omega(T0, dT, J):
    return np.sqrt(np.maximum(2.0 * (T0 + dT), 0.0) / J)


def _omega_extremes(dT2: np.ndarray, J_tot: np.ndarray, buf: np.ndarray):
    """T0 -> (max, min) of `_omega`(T0, dT, J_tot) given dT2 = 2 dT: the same numbers
    (2 (T0 + dT) = 2 T0 + 2 dT exactly, and the square root, correctly rounded, keeps the
    order, so the largest root is the root of the largest value), one pass fewer and no
    array of speeds."""
    def ext(T0):
        np.add(dT2, 2.0 * T0, out=buf)
        np.maximum(buf, 0.0, out=buf)
        np.divide(buf, J_tot, out=buf)
        return math.sqrt(buf.max()), math.sqrt(buf.min())
    return ext


def steady_T0(dT, J_tot, omega_m: float) -> float | None:
    """The initial kinetic energy of the steady motion of a given mean speed.

    Parameters
    ----------
    dT : numpy.ndarray
        The increase of the kinetic energy along the cycle, J.
    J_tot : numpy.ndarray
        The total reduced inertia, kg*m^2.
    omega_m : float
        The mean speed, rad/s.

    Returns
    -------
    float or None
        T0 (J) such that (max omega + min omega)/2 = omega_m for
        omega = sqrt(2 (T0 + dT)/J_tot); None when there is none (the speed would reach zero:
        delta >= 2).
    """
    dT = np.asarray(dT, float)
    J_tot = np.broadcast_to(np.asarray(J_tot, float), dT.shape)
    jmax = float(np.max(J_tot))
    u_lo = -float(np.min(dT))
    u_hi = omega_m**2 * jmax / 2 + u_lo
    ext = _omega_extremes(2.0 * dT, J_tot, np.empty(dT.shape))

    def g(u):
        wmax, wmin = ext(u)
        return 0.5 * (wmax + wmin) - omega_m

    g_lo = g(u_lo)
    if g_lo > 0:
        return None
    if g_lo == 0:
        return u_lo
    span = max(u_hi - u_lo, abs(u_lo), 1e-300)
    for _ in range(60):   # u_hi makes min omega >= omega_m; only rounding can spoil it
        if g(u_hi) >= 0:
            break
        u_hi = u_hi + span
        span *= 2
    else:
        return None
    scale = max(abs(u_hi), abs(u_lo), _TINY)
    return float(brentq(g, u_lo, u_hi, xtol=1e-15 * scale, rtol=8.9e-16, maxiter=400))


@dataclass
class Motion:
    """Steady motion with constant reduced inertia J_n + J_var (along the motion)."""
    T0: float
    omega: np.ndarray         # |omega1|(q), rad/s
    omega_max: float
    omega_min: float
    delta: float              # (omega_max - omega_min)/omega_m, omega_m = their mean


def steady_motion(dT, J_var, J_n: float, omega_m: float) -> Motion:
    """The periodic steady motion with a flywheel.

    Parameters
    ----------
    dT : numpy.ndarray
        The increase of the kinetic energy along the cycle, dT = A_d - A_c, J.
    J_var : numpy.ndarray
        The variable part of the reduced moment of inertia, kg*m^2.
    omega_m : float
        The mean speed, rad/s.
    J_n : float
        The flywheel's constant reduced inertia, kg*m^2.

    Returns
    -------
    Motion
        T0 (J), omega(q) (rad/s), omega_max, omega_min and the achieved delta, the mean
        (omega_max + omega_min)/2 equal to omega_m.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: the motion of the machine from the
    equation of kinetic energy; docs/methods.md §4.
    """
    dT = np.asarray(dT, float)
    J_tot = J_n + np.broadcast_to(np.asarray(J_var, float), dT.shape)
    rng = float(np.max(dT) - np.min(dT))
    if float(np.min(J_tot)) <= 0:
        if float(np.max(np.abs(J_tot))) == 0 and rng == 0:
            w = np.full_like(dT, omega_m)   # nothing moves, nothing changes: uniform
            return Motion(T0=0.0, omega=w, omega_max=omega_m, omega_min=omega_m, delta=0.0)
        raise StageError(STAGE, Message("flywheel.fail.J_not_positive"))
    T0 = steady_T0(dT, J_tot, omega_m)
    if T0 is None:
        raise StageError(STAGE, Message("flywheel.fail.stops"))
    w = _omega(T0, dT, J_tot)
    wmax, wmin = float(np.max(w)), float(np.min(w))
    wm = 0.5 * (wmax + wmin)
    return Motion(T0=T0, omega=w, omega_max=wmax, omega_min=wmin, delta=(wmax - wmin) / wm)


def achieved_delta(dT, J_var, J_n: float, omega_m: float) -> float:
    """The speed fluctuation of the steady motion with a flywheel.

    Parameters
    ----------
    dT : numpy.ndarray
        The increase of the kinetic energy along the cycle, dT = A_d - A_c, J.
    J_var : numpy.ndarray
        The variable part of the reduced moment of inertia, kg*m^2.
    omega_m : float
        The mean speed, rad/s.
    J_n : float
        The flywheel's constant reduced inertia, kg*m^2.

    Returns
    -------
    float
        delta = (omega_max - omega_min)/omega_m (2.0 when the machine would stop).
    """
    dT = np.asarray(dT, float)
    J_tot = J_n + np.broadcast_to(np.asarray(J_var, float), dT.shape)
    if float(np.min(J_tot)) <= 0:
        return 2.0
    T0 = steady_T0(dT, J_tot, omega_m)
    if T0 is None:
        return 2.0
    wmax, wmin = _omega_extremes(2.0 * dT, J_tot, np.empty(dT.shape))(T0)
    return (wmax - wmin) / (0.5 * (wmax + wmin))


def exact_flywheel(dT, J_var, omega_m: float, delta: float, guess: float | None = None) -> float:
    """The flywheel giving exactly the required fluctuation of the integrated motion.

    Parameters
    ----------
    dT : numpy.ndarray
        The increase of the kinetic energy along the cycle, dT = A_d - A_c, J.
    J_var : numpy.ndarray
        The variable part of the reduced moment of inertia, kg*m^2.
    omega_m : float
        The mean speed, rad/s.
    delta : float
        The required coefficient of speed fluctuation.
    guess : float or None
        A starting J_n, kg*m^2.

    Returns
    -------
    float
        J_n, kg*m^2: the root of achieved_delta(J_n) = delta (T0 from the mean-speed
        condition at every trial); when even the lightest feasible inertia (J_n -> -min J_var)
        keeps the fluctuation below delta, that lower limit (no flywheel is needed).

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: the equation of motion in the energy
    form; docs/methods.md §4.
    """
    dT, J_var = _check(dT, J_var, omega_m, delta)
    jv_min = float(np.min(J_var))
    rng = float(np.max(dT) - np.min(dT))
    scale = max(abs(guess or 0.0), float(np.max(np.abs(J_var))),
                rng / (omega_m**2 * delta), _TINY)
    lower = -jv_min            # J_n must exceed this (positive total inertia)
    if rng == 0 and float(np.ptp(J_var)) == 0:
        return lower           # nothing fluctuates: any inertia keeps omega constant

    def h(J):
        return achieved_delta(dT, J_var, J, omega_m) - delta

    lo_lim = lower + 1e-12 * scale
    if h(lo_lim) <= 0:
        return lower
    x0 = guess if (guess is not None and math.isfinite(guess) and guess > lo_lim) else lower + scale
    step = 1e-7 * scale
    lo, hi = max(x0 - step, lo_lim), x0 + step
    h_lo, h_hi = h(lo), h(hi)
    for _ in range(200):
        if h_lo > 0 and h_hi <= 0:
            break
        if h_lo <= 0:      # lo too heavy already: move down
            hi, h_hi = lo, h_lo
            step *= 4
            lo = max(lo - step, lo_lim)
            h_lo = h(lo)
        else:              # hi too light: move up
            lo, h_lo = hi, h_hi
            step *= 4
            hi = hi + step
            h_hi = h(hi)
    else:
        raise StageError(STAGE, Message("flywheel.fail.bracket"))
    if h_hi == 0:
        return hi
    return float(brentq(h, lo, hi, xtol=1e-14 * scale, rtol=1e-13, maxiter=400))


# ------------------------------------------------------------------ size
# Rim (peripheral) speed limits commonly quoted in TMM / machine-design textbooks
# (e.g. Artobolevsky, TMM, on flywheel design; Frolov et al.): cast iron about 30 m/s,
# steel about 70 m/s.  The material is guessed from the density.
RIM_SPEED_CAST_IRON = 30.0
RIM_SPEED_STEEL = 70.0


@dataclass
class FlywheelSize:
    """The flywheel's dimensions for its moment of inertia (a disk or a rim), m and kg."""

    diameter: float
    width: float
    mass: float
    rim_speed: float
    thickness: float | None
    warnings: list[str]


def size(J: float, shape: str, density: float, width_ratio: float, omega_max: float,
         lang_warn: bool = True) -> FlywheelSize:
    """The flywheel's dimensions for a moment of inertia.

    Parameters
    ----------
    J : float
        The flywheel's moment of inertia, kg*m^2.
    shape : str
        ``disk`` or ``rim``.
    density : float
        The material's density, kg/m^3.
    width_ratio : float
        psi_b = b/D.
    omega_max : float
        The greatest speed, rad/s (for the rim speed).
    lang_warn : bool
        True: warn about an excessive rim speed.

    Returns
    -------
    FlywheelSize
        The diameter D, width b and (rim) thickness (m), the mass (kg), the rim speed (m/s)
        and the warnings.

    Notes
    -----
    disk: a solid disk, J = m D^2/8, b = psi_b D, m = rho pi D^2/4 b, so
    D = (32 J/(pi rho psi_b))^(1/5); the rim speed omega_max D/2.
    rim: a thin rim of mean diameter D, J ~ m D^2/4, a square section b = h = psi_b D (the
    course gives only psi_b; the square section is the usual textbook choice),
    m = rho pi D b h, so D = (4 J/(pi rho psi_b^2))^(1/5); the rim speed at the outer radius
    omega_max (D + h)/2.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: the dimensions of a flywheel;
    docs/methods.md §4.
    """
    warns: list[str] = []
    if not (J > 0 and math.isfinite(J)):
        return FlywheelSize(0.0, 0.0, 0.0, 0.0, 0.0 if shape == "rim" else None, warns)
    psi = float(width_ratio)
    rho = float(density)
    if shape == "disk":
        D = (32.0 * J / (math.pi * rho * psi)) ** 0.2
        b = psi * D
        m = rho * math.pi * D**2 / 4 * b
        h = None
        v = abs(omega_max) * D / 2
    elif shape == "rim":
        D = (4.0 * J / (math.pi * rho * psi**2)) ** 0.2
        b = h = psi * D
        m = rho * math.pi * D * b * h
        v = abs(omega_max) * (D + h) / 2
    else:
        raise StageError(STAGE, Message("flywheel.fail.shape", shape=str(shape)))
    if v > RIM_SPEED_STEEL:
        warns.append(Message("flywheel.rim_speed_steel", v=v, limit=RIM_SPEED_STEEL))
    elif v > RIM_SPEED_CAST_IRON and rho < 7500:
        warns.append(Message("flywheel.rim_speed_cast_iron", v=v, limit=RIM_SPEED_CAST_IRON))
    return FlywheelSize(D, b, m, v, h, warns)
