"""Poses of links over a batch of crank positions, and the lower-pair constraints.

Every body b (0 = ground) has a pose: the global position ``o[b]`` (N, 2) of its local
origin and the angle ``th[b]`` (N,) of its local u-axis, plus the first and second
derivatives of both with respect to the crank angle phi (rad): ``o1, th1, o2, th2``.
A point with local coordinates u is at ``o + R(th) u``.

Constraints (two equations each) of a pair between bodies i and j:

* revolute at a point with local coordinates u_i, u_j:
  ``o_i + R_i u_i - o_j - R_j u_j = 0``;
* prismatic between a slider s and the body g carrying its guide (g = 0: a fixed
  guide): ``th_s - th_g - a = 0`` and ``n(psi) . (o_s - o_g) - c0 = 0`` with
  psi = th_g + a the guide direction, n its left normal, c0 = n(a) . w where w is a
  point of the guide line in g's frame (a fixed guide: its global point; a moving
  guide: c0 = offset).

Each constraint gives its value, its Jacobian blocks d/d(o_x, o_y, th) per body, and
``gamma``: the part of its second derivative quadratic in the first derivatives, so
that, with q the poses, d2 Phi/dphi2 = sum_b block_b q_b'' + gamma. For the guide this
term holds -psi'^2 n.d - 2 psi' e.d' (e the guide direction, d = o_s - o_g): the
Coriolis term of a slider on a moving guide.
"""
from __future__ import annotations

import math

import numpy as np


WORK_ROWS_FROM = 1024    # positions: from this many on, fewer temporaries (memory) rather than fewer calls


def const(x) -> np.ndarray:
    """A float as a read-only 0-d float64 array.

    Parameters
    ----------
    x : float
        The number.

    Returns
    -------
    numpy.ndarray
        A 0-d array: a ufunc takes it without a Python scalar's conversion (a fraction of the
        call's cost at few positions), the same float64 arithmetic bit for bit.
    """
    a = np.array(float(x))
    a.flags.writeable = False
    return a


ZERO = const(0.0)
ONE = const(1.0)


def pairs(N: int) -> np.ndarray:
    """An (N, 2) array of x, y pairs held column by column.

    Parameters
    ----------
    N : int
        The number of positions.

    Returns
    -------
    numpy.ndarray
        Uninitialised, the transpose of a (2, N) array: an operation on its x or y column
        runs on contiguous memory.
    """
    return np.empty((2, N)).T


def zero_pairs(N: int) -> np.ndarray:
    """:func:`pairs` of zeros.

    Parameters
    ----------
    N : int
        The number of positions.

    Returns
    -------
    numpy.ndarray
        (N, 2) zeros held column by column.
    """
    return np.zeros((2, N)).T


class State:
    """Poses and their phi-derivatives of all bodies at N positions."""

    def __init__(self, N: int):
        self.N = N
        z2 = zero_pairs(N)
        z1 = np.zeros(N)
        self.o = {0: z2}
        self.th = {0: z1}
        self.o1 = {0: z2}
        self.th1 = {0: z1}
        self.o2 = {0: z2}
        self.th2 = {0: z1}
        self._cs: dict[int, tuple[np.ndarray, np.ndarray]] = {}
        self._csk: dict[int, tuple[np.ndarray, np.ndarray]] = {}   # given to set_pose
        self._gd: dict[int, tuple] = {}       # id(PCon) -> (g, (psi, e)): guide directions
        self._pd: dict[int, dict] = {}        # b -> {u: point_d(b, u)}
        self._sq: dict[int, np.ndarray] = {}  # b -> th1_b ** 2 (shared, read-only)
        self._dcols: dict[int, tuple] = {}    # b -> _cols(b)
        # b -> the one value of th_b where it is a constant (a slider on a fixed guide)
        self.const_th: dict[int, float] = {}
        self._rotated: dict[int, dict] = {}   # b -> {u: rot(b, u)} (few positions, or share_rot)
        # boolean mask of the positions where a group's velocity equations are singular
        # (their derivatives the mean of the two sides), None where there are none
        self.singular: np.ndarray | None = None

    def set_pose(self, b: int, o: np.ndarray, th: np.ndarray, cs=None) -> None:
        """Body b's pose; ``cs``: (cos th, sin th) when the caller has them already."""
        self.o[b] = o
        self.th[b] = th
        self._cs.pop(b, None)
        self.const_th.pop(b, None)
        self._rotated.pop(b, None)
        if cs is None:
            self._csk.pop(b, None)
        else:
            self._csk[b] = cs
        self._pd.pop(b, None)
        if self._gd:
            for k in [k for k, (g, _) in self._gd.items() if g == b]:
                del self._gd[k]

    def set_d1(self, b, o1, th1):
        self.o1[b] = o1
        self.th1[b] = th1
        self._sq.pop(b, None)
        self._dcols.pop(b, None)
        self._pd.pop(b, None)

    def set_d2(self, b, o2, th2):
        self.o2[b] = o2
        self.th2[b] = th2
        self._dcols.pop(b, None)
        self._pd.pop(b, None)

    def th1_sq(self, b: int) -> np.ndarray:
        """th1_b ** 2 (= th1_b * th1_b), computed once per first derivatives of b (shared,
        read-only)."""
        hit = self._sq.get(b)
        if hit is None:
            t1 = self.th1[b]
            hit = self._sq[b] = t1 * t1
        return hit

    def derivatives_changed(self) -> None:
        """Forget what was derived from the bodies' derivatives (after they were replaced
        in place of set_d1 / set_d2)."""
        self._pd.clear()
        self._sq.clear()
        self._dcols.clear()

    def release(self, b: int) -> None:
        """Forget body b's origin and its derivatives and the cosine and sine of its
        angle (kept: the angle and its derivatives); for a State whose points are all
        taken, to hold less memory while the results are being built."""
        for d in (self.o, self.o1, self.o2, self._cs, self._csk, self._sq, self._dcols, self._rotated, self._pd):
            d.pop(b, None)

    def guide(self, con) -> tuple[np.ndarray, np.ndarray]:
        """(psi, e) of prismatic pair ``con``: its guide's direction psi = th_g + a (N,)
        and e = (cos psi, sin psi) (N, 2), computed once per pose of the carrier g. A
        fixed guide (g = 0) has one direction: its cosine and sine are taken once and
        broadcast (read-only)."""
        hit = self._gd.get(id(con))
        if hit is not None:
            return hit[1]
        if con.g == 0:
            psi = np.full(self.N, 0.0 + con.a)            # = th_0 + a, th_0 = 0 everywhere
            out = (psi, np.broadcast_to(unit(psi[:1]), (self.N, 2)))
        else:
            psi = self.th[con.g] + con.a
            out = (psi, unit(psi))
        self._gd[id(con)] = (con.g, out)
        return out

    def cs(self, b: int):
        """(cos th_b, sin th_b), taken when first asked for after the pose was set (and
        kept when th_b is then unwrapped, see :meth:`unwrap`)."""
        if b not in self._cs:
            hit = self._csk.pop(b, None)
            if hit is None:
                t = self.th[b]
                hit = (np.cos(t), np.sin(t))
            self._cs[b] = hit
        return self._cs[b]

    def unwrap(self, b: int, th: np.ndarray) -> None:
        """Replace th_b by an unwrapped copy (the same angles, +- 2 pi k); the cosine and
        sine already taken stay."""
        self.th[b] = th
        self._csk.pop(b, None)

    def rot(self, b: int, u) -> np.ndarray:
        """R(th_b) u -> (N, 2) (read-only use: with few positions it is computed once per
        pose of b and shared; with many, once unless given by share_rot)."""
        u0, u1 = float(u[0]), float(u[1])
        got = self._rotated.get(b)
        hit = None if got is None else got.get((u0, u1))
        if hit is None:
            hit = self._rot(b, u0, u1)
            if self.N < WORK_ROWS_FROM:
                self._rotated.setdefault(b, {})[(u0, u1)] = hit
        return hit

    def share_rot(self, b: int, u, ru: np.ndarray) -> None:
        """rot(b, u) is ``ru`` (computed by the caller from the pose just set, by the same
        operations)."""
        self._rotated.setdefault(b, {})[(float(u[0]), float(u[1]))] = ru

    def _rot(self, b: int, u0: float, u1: float) -> np.ndarray:
        c, s = self.cs(b)
        out = pairs(self.N)
        if u1 == 0.0:
            k0 = np.array(u0)               # (a 0-d array: no scalar conversion per call)
            np.multiply(c, k0, out[:, 0])
            np.multiply(s, k0, out[:, 1])
        else:
            out[:, 0] = c * u0 - s * u1
            out[:, 1] = s * u0 + c * u1
        return out

    def point(self, b: int, u) -> np.ndarray:
        return self.o[b] + self.rot(b, u)

    def point_d(self, b: int, u):
        """Position, first and second phi-derivatives of a point fixed on body b
        (computed once per pose and derivatives of b: the arrays are shared, read-only)."""
        key = (float(u[0]), float(u[1]))
        got = self._pd.get(b)
        if got is None:
            got = self._pd[b] = {}
        hit = got.get(key)
        if hit is None:
            hit = got[key] = self._point_d(b, u)
        return hit

    def _cols(self, b: int) -> tuple:
        """Body b's derivative columns (o1x, o1y, o2x, o2y), taken once per derivatives."""
        hit = self._dcols.get(b)
        if hit is None:
            o1, o2 = self.o1[b], self.o2[b]
            hit = self._dcols[b] = (o1[:, 0], o1[:, 1], o2[:, 0], o2[:, 1])
        return hit

    def _point_d(self, b: int, u):
        N = self.N
        u0, u1 = float(u[0]), float(u[1])
        if b == 0:
            # the ground: o = 0, th = 0 (cos 1, sin 0 exactly) and zero derivatives, so
            # the general terms below are u + 0 and +0 -- the same values without them
            p = pairs(N)
            p[:, 0] = u0 + 0.0
            p[:, 1] = u1 + 0.0
            return p, zero_pairs(N), zero_pairs(N)
        t1 = self.th1[b]
        t2 = self.th2[b]
        o, o1, o2 = self.o[b], self.o1[b], self.o2[b]
        if N < WORK_ROWS_FROM:
            # few positions: the fewest numpy calls, the temporaries in the outputs' rows,
            # the body's derivative columns taken once per derivatives
            ru = self.rot(b, u)
            rx, ry = ru[:, 0], ru[:, 1]
            o1x, o1y, o2x, o2y = self._cols(b)
            p = o + ru
            mul, add, sub = np.multiply, np.add, np.subtract
            D1 = np.empty((2, N))
            x, y = D1[0], D1[1]
            sub(o1x, mul(t1, ry, x), x)                 # o1x - t1 ry
            add(o1y, mul(t1, rx, y), y)                 # o1y + t1 rx
            D2 = np.empty((2, N))
            x, y = D2[0], D2[1]
            t11 = self.th1_sq(b)
            tmp = mul(t11, rx)
            sub(o2x, add(mul(t2, ry, x), tmp, x), x)    # o2x - (t2 ry + t11 rx)
            mul(t11, ry, tmp)
            add(o2y, sub(mul(t2, rx, y), tmp, y), y)    # o2y + (t2 rx - t11 ry)
            return p, D1.T, D2.T
        # many positions: the same operations, the temporaries in four scratch rows
        rx, ry, tmp = np.empty((3, N))
        c, s = self.cs(b)
        if u1 == 0.0:                   # as rot()
            np.multiply(c, u0, out=rx)
            np.multiply(s, u0, out=ry)
        else:
            np.multiply(c, u0, out=rx)
            np.multiply(s, u1, out=tmp)
            np.subtract(rx, tmp, out=rx)
            np.multiply(s, u0, out=ry)
            np.multiply(c, u1, out=tmp)
            np.add(ry, tmp, out=ry)
        t11 = self.th1_sq(b)
        p, d1, d2 = pairs(N), pairs(N), pairs(N)
        np.add(o[:, 0], rx, out=p[:, 0])
        np.add(o[:, 1], ry, out=p[:, 1])
        np.multiply(t1, ry, out=tmp)
        np.subtract(o1[:, 0], tmp, out=d1[:, 0])
        np.multiply(t1, rx, out=tmp)
        np.add(o1[:, 1], tmp, out=d1[:, 1])
        x, y = d2[:, 0], d2[:, 1]           # (their own place, before their values)
        np.multiply(t2, ry, out=tmp)
        np.multiply(t11, rx, out=x)
        np.add(tmp, x, out=tmp)
        np.subtract(o2[:, 0], tmp, out=x)
        np.multiply(t2, rx, out=tmp)
        np.multiply(t11, ry, out=y)
        np.subtract(tmp, y, out=tmp)
        np.add(o2[:, 1], tmp, out=y)
        return p, d1, d2

    def take(self, idx) -> "State":
        """A State restricted to positions ``idx`` (index array or slice)."""
        sub = State.__new__(State)
        for name in ("o", "th", "o1", "th1", "o2", "th2"):
            setattr(sub, name, {b: v[idx] for b, v in getattr(self, name).items()})
        sub.N = len(sub.th[0])
        sub._cs = {}
        sub._csk = {}
        sub._gd = {}
        sub._pd = {}
        sub._sq = {}
        sub._dcols = {}
        sub.const_th = {}
        sub._rotated = {}
        return sub


def scale(x, v):
    """Scale plane vectors, column by column.

    Parameters
    ----------
    x : numpy.ndarray
        The factors (N,).
    v : numpy.ndarray
        The vectors (N, 2).

    Returns
    -------
    numpy.ndarray
        x[:, None] * v (a broadcast over the last axis of length 2 runs numpy's inner loop two
        elements at a time).
    """
    out = np.empty((2, len(x)))
    np.multiply(x, v[:, 0], out[0])
    np.multiply(x, v[:, 1], out[1])
    return out.T


def unit(ang):
    """Unit vectors of angles.

    Parameters
    ----------
    ang : array_like
        Angles, rad.

    Returns
    -------
    numpy.ndarray
        (..., 2): (cos, sin).
    """
    ang = np.asarray(ang, float)
    out = np.empty(ang.shape + (2,))
    np.cos(ang, out=out[..., 0])
    np.sin(ang, out=out[..., 1])
    return out


def left(v):
    """Plane vectors turned by +90 degrees.

    Parameters
    ----------
    v : numpy.ndarray
        Vectors (..., 2).

    Returns
    -------
    numpy.ndarray
        (-v_y, v_x).
    """
    out = np.empty(v.shape)
    np.negative(v[..., 1], out=out[..., 0])
    out[..., 1] = v[..., 0]
    return out


def cross(a, b):
    """The z component of plane cross products.

    Parameters
    ----------
    a, b : numpy.ndarray
        Vectors (..., 2).

    Returns
    -------
    numpy.ndarray
        a_x b_y - a_y b_x.
    """
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def dot(a, b):
    """Plane dot products.

    Parameters
    ----------
    a, b : numpy.ndarray
        Vectors (..., 2).

    Returns
    -------
    numpy.ndarray
        a_x b_x + a_y b_y.
    """
    return a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1]


def wrap(a):
    """Angles wrapped to [-pi, pi).

    Parameters
    ----------
    a : array_like
        Angles, rad.

    Returns
    -------
    numpy.ndarray
        (a + pi) mod 2 pi - pi.
    """
    return (a + np.pi) % (2 * np.pi) - np.pi


class RCon:
    """Revolute pair between bodies i and j at a point (local u_i, u_j)."""
    kind = "R"
    m = 2

    def __init__(self, i, j, ui, uj, point, joint=None):
        self.i, self.j = i, j
        self.ui = np.asarray(ui, float)
        self.uj = np.asarray(uj, float)
        self.point = point
        self.joint = joint
        self.bodies = (i, j)

    def local(self, b):
        return self.ui if b == self.i else self.uj

    def value(self, st: State) -> np.ndarray:
        return st.point(self.i, self.ui) - st.point(self.j, self.uj)

    def blocks(self, st: State) -> dict:
        out = {}
        for b, u, sg in ((self.i, self.ui, 1.0), (self.j, self.uj, -1.0)):
            if b == 0:
                continue
            ru = st.rot(b, u)
            blk = np.zeros((st.N, 2, 3))
            blk[:, 0, 0] = sg
            blk[:, 1, 1] = sg
            blk[:, 0, 2] = -sg * ru[:, 1]
            blk[:, 1, 2] = sg * ru[:, 0]
            out[b] = blk
        return out

    def gamma(self, st: State, ru: dict | None = None) -> np.ndarray:
        """``ru``: R(th_b) u_b of the two bodies when the caller has them already."""
        g = zero_pairs(st.N)
        for b, u, sub in ((self.i, self.ui, True), (self.j, self.uj, False)):
            if b == 0:
                continue
            # g -= (sg th1^2) R u with sg = +-1: g - (-y) is g + y to the bit
            t = scale(st.th1_sq(b), st.rot(b, u) if ru is None else ru[b])
            (np.subtract if sub else np.add)(g, t, g)
        return g


class PCon:
    """Prismatic pair: slider s on the guide carried by body g (0 = fixed guide)."""
    kind = "P"
    m = 2

    def __init__(self, s, g, a, c0, joint=None):
        self.s, self.g = s, g
        self.a = float(a)          # rad: guide direction relative to g (absolute if g = 0)
        self.c0 = float(c0)        # n(a) . w, w a point of the guide in g's frame
        self.joint = joint
        self.bodies = (s, g)
        self.na = np.array([-math.sin(self.a), math.cos(self.a)])

    def psi(self, st):
        return st.th[self.g] + self.a

    def value(self, st: State) -> np.ndarray:
        psi = self.psi(st)
        n = left(unit(psi))
        d = st.o[self.s] - st.o[self.g]
        return np.stack([wrap(st.th[self.s] - psi), dot(n, d) - self.c0], axis=-1)

    def blocks(self, st: State) -> dict:
        psi = self.psi(st)
        e = unit(psi)
        n = left(e)
        d = st.o[self.s] - st.o[self.g]
        out = {}
        bs = np.zeros((st.N, 2, 3))
        bs[:, 0, 2] = 1.0
        bs[:, 1, 0] = n[:, 0]
        bs[:, 1, 1] = n[:, 1]
        out[self.s] = bs
        if self.g != 0:
            bg = np.zeros((st.N, 2, 3))
            bg[:, 0, 2] = -1.0
            bg[:, 1, 0] = -n[:, 0]
            bg[:, 1, 1] = -n[:, 1]
            bg[:, 1, 2] = -dot(e, d)
            out[self.g] = bg
        return out

    def gamma(self, st: State, ru: dict | None = None) -> np.ndarray:
        e = st.guide(self)[1]
        n = left(e)
        d = st.o[self.s] - st.o[self.g]
        d1 = st.o1[self.s] - st.o1[self.g]
        w = st.th1[self.g]
        g = zero_pairs(st.N)
        g[:, 1] = -w ** 2 * dot(n, d) - 2.0 * w * dot(e, d1)
        return g
