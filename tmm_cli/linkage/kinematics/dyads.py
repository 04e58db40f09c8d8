"""Closed-form positions of every class-II group (dyad), vectorised over positions.

A dyad has links A, B (in the reading order of :mod:`tmm_cli.linkage.structure`), an external
pair of A, the pair A-B and an external pair of B. An external pair leaves its link one
freedom:

* revolute at a known point P: the link turns about P (its angle is unknown);
* prismatic: the link's angle is known and its origin moves along a known line
  (o = base + s e).

The pair A-B closes the group:

=========  ===================================  ==============================
 type      equations                              solution (closures)
=========  ===================================  ==============================
 RRR       |C - P1| = l_A, |C - P3| = l_B          circle/circle (sigma = +-1)
 RRP, PRR  |C - P1| = l_A, C on a line             circle/line (sigma = +-1)
 PRP       C on two lines                         line/line (unique)
 RPR       the guide through one pivot keeps      psi = delta - asin(c/rho)
           distance c from the other pivot        (sigma = +-1)
 RPP, PPR  angles known, one translation          linear (unique)
=========  ===================================  ==============================

Closure sign conventions (the documented default is sigma = +1):

* RRR: sigma = +1 puts the middle joint C to the left of the directed line from the
  external joint of A to that of B (counter-clockwise triangle P1, P3, C);
* RRP / PRR: sigma = +1 takes the intersection farther along the guide direction
  (e.g. the slider of a slider-crank on a guide at 0 deg to the right of the crank);
* RPR: sigma = +1 is the closure in which the slider's pivot lies ahead of the guide
  link's pivot along the guide direction (the crank pin on the slotted link between
  its pivot and its free end, as drawn for a shaper).

``margin`` (length units) is >= 0 where the group assembles: RRR:
min(l_A + l_B - d, d - |l_A - l_B|); circle/line: l - (distance of the centre from
the line); RPR: rho - |c|; the linear cases: |sin| of the angle between the lines.
"""
from __future__ import annotations

import math

import numpy as np

try:                                    # np.clip's ufunc, without its Python wrappers
    from numpy._core.umath import clip as _clip
except ImportError:                     # numpy < 2
    from numpy.core.umath import clip as _clip

from .state import ONE, WORK_ROWS_FROM, ZERO, PCon, RCon, State, const, cross, dot, left, pairs, scale, unit

_TINY, _M1 = const(1e-300), const(-1.0)


def _atan2(v):
    return np.arctan2(v[..., 1], v[..., 0])


def _minus_const(x, k: float, kc=None):
    """x - k for a float k; x itself when k is +0.0 (x - (+0.0) is x bit for bit, -0.0 and
    NaN included); ``kc``: k as a 0-d array (see state.const), then in place in x."""
    if k == 0.0 and math.copysign(1.0, k) > 0:
        return x
    return x - k if kc is None else np.subtract(x, kc, x)


def _cs(th):
    return np.cos(th), np.sin(th)


def _rot(cs, u):
    """R(th) u (N, 2) from cs = (cos th, sin th)."""
    c, s = cs
    out = pairs(len(c))
    np.subtract(c * u[0], s * u[1], out=out[:, 0])
    np.add(s * u[0], c * u[1], out=out[:, 1])
    return out


class DyadPlan:
    """How to close one class-II group in closed form."""

    def __init__(self, A: int, B: int, e1, mid, e2):
        self.A, self.B = A, B
        self.e1, self.mid, self.e2 = e1, mid, e2
        self.kind = e1.kind + mid.kind + e2.kind
        self.two_closures = self.kind in ("RRR", "RRP", "PRR", "RPR")
        if self.kind == "PPP":
            raise ValueError("a PPP group (three prismatic pairs) has no definite position")
        if mid.kind == "R":
            for X in (A, B):
                ext = e1 if X == A else e2
                if ext.kind == "R":
                    v = np.asarray(mid.local(X)) - np.asarray(ext.local(X))
                    if np.hypot(*v) < 1e-12:
                        raise ValueError("the two pairs of a link of the group coincide")
        self.length = 1.0     # the group's length (Solver sets it): scales the determinant's angle row
        self.slide = None
        if self.kind in ("RRP", "PRR") and mid.kind == "R" and (e2 if self.kind == "RRP" else e1).g == 0:
            self.slide = _FixedSlide(self)
        self.rrr = None
        if self.kind == "RRR":
            ka, kb = (e.j if e.i == X else e.i for X, e in ((A, e1), (B, e2)))
            if (ka == 0) != (kb == 0):          # one pivot on the ground, the other moving
                self.rrr = _GroundRRR(self, kb == 0)

    # ------------------------------------------------------------------
    @staticmethod
    def _ext(X: int, con, st: State):
        """The one freedom an external pair leaves to link X."""
        if isinstance(con, RCon):
            K = con.j if con.i == X else con.i
            uK = con.local(K)
            P = st.point_d(K, uK)[0] if K in st.th1 else st.point(K, uK)    # (shared with the derivatives)
            return ("R", P, np.asarray(con.local(X)))
        # prismatic: ("P", angle th of X, base, direction e of the line, (cos th, sin th))
        if con.s == X:
            th, e = st.guide(con)
            if con.g == 0 and st.N >= WORK_ROWS_FROM:
                # a fixed guide: e is one row broadcast (State.guide), so is the base: its
                # values from that row, repeated (an operation on a broadcast (N, 2) array
                # would run numpy's inner loop two elements at a time)
                base = np.repeat(st.o[0][:1] + con.c0 * left(e[:1]), st.N, axis=0)
            else:
                base = st.o[con.g] + con.c0 * left(e)
            return ("P", th, base, e, (e[:, 0], e[:, 1]))
        th = st.th[con.s] - con.a
        e = unit(st.th[con.s])
        base = st.o[con.s] - con.c0 * left(e)
        return ("P", th, base, e, _cs(th))

    @staticmethod
    def _set_from_point(st, X, p, u, th):
        """Pose of X turned by th with its local point u at p."""
        cs = _cs(th)
        st.set_pose(X, p - _rot(cs, u), th, cs)

    def solve(self, st: State, sigma: float = 1.0) -> np.ndarray:
        """Set the poses of A and B in ``st``; return the assembly margin (N,)."""
        if self.slide is not None and FIXED_SLIDE:
            return self.slide.pose(st, sigma)
        if self.rrr is not None and GROUND_RRR:
            return self.rrr.pose(st, sigma)
        A, B = self.A, self.B
        ea = self._ext(A, self.e1, st)
        eb = self._ext(B, self.e2, st)
        mid = self.mid
        if isinstance(mid, RCon):
            uAC = np.asarray(mid.local(A))
            uBC = np.asarray(mid.local(B))
            if ea[0] == "R" and eb[0] == "R":
                return self._rrr(st, ea, eb, uAC, uBC, sigma)
            if ea[0] == "R" and eb[0] == "P":
                return self._rrp(st, A, B, ea, eb, uAC, uBC, sigma)
            if ea[0] == "P" and eb[0] == "R":
                return self._rrp(st, B, A, eb, ea, uBC, uAC, sigma)
            return self._prp(st, ea, eb, uAC, uBC)
        # internal prismatic pair
        if ea[0] == "R" and eb[0] == "R":
            return self._rpr(st, ea, eb, sigma)
        if ea[0] == "R":
            return self._rpp(st, A, B, ea, eb)
        return self._rpp(st, B, A, eb, ea)

    # ------------------------------------------------------------------
    def _rrr(self, st, ea, eb, uAC, uBC, sigma):
        A, B = self.A, self.B
        _, P1, uA1 = ea
        _, P3, uB3 = eb
        vA = uAC - uA1
        vB = uBC - uB3
        lA = float(np.hypot(*vA))
        lB = float(np.hypot(*vB))
        D = P3 - P1
        d = np.hypot(D[:, 0], D[:, 1])
        margin = np.minimum(lA + lB - d, d - abs(lA - lB))
        ds = np.where(d > 1e-300, d, 1e-300)
        cg = np.clip((lA ** 2 + d ** 2 - lB ** 2) / (2 * lA * ds), -1.0, 1.0)
        beta = _atan2(D)
        C = P1 + lA * unit(beta + sigma * np.arccos(cg))
        thA = _minus_const(_atan2(C - P1), np.arctan2(vA[1], vA[0]))
        thB = _minus_const(_atan2(C - P3), np.arctan2(vB[1], vB[0]))
        self._set_from_point(st, A, P1, uA1, thA)
        self._set_from_point(st, B, P3, uB3, thB)
        return margin

    def _rrp(self, st, X, Y, ex, ey, uXC, uYC, sigma):
        """X turns about P1, Y translates on a line: circle/line."""
        _, P1, uX1 = ex
        _, thY, bY, eY, csY = ey
        vX = uXC - uX1
        lX = float(np.hypot(*vX))
        if csY[0].strides[0] == 0 and len(bY) >= WORK_ROWS_FROM:
            # a fixed guide (_ext: its direction broadcast, its base one row repeated): the
            # same values from one row, repeated
            c0 = np.repeat(bY[:1] + _rot((csY[0][:1], csY[1][:1]), uYC), len(bY), axis=0)
        else:
            c0 = bY + _rot(csY, uYC)
        w = c0 - P1
        h = cross(w, eY)
        margin = lX - np.abs(h)
        root = np.sqrt(np.maximum(lX ** 2 - h ** 2, 0.0))
        if sigma == 1.0:                    # -a + 1.0 r is r - a, bit for bit
            s = np.subtract(root, dot(w, eY), out=root)
        else:
            s = -dot(w, eY) + sigma * root
        sE = scale(s, eY)
        C = c0 + sE
        thX = _minus_const(_atan2(C - P1), np.arctan2(vX[1], vX[0]))
        self._set_from_point(st, X, P1, uX1, thX)
        st.set_pose(Y, bY + sE, thY.copy(), csY)
        if csY[0].strides[0] == 0:          # a fixed guide: Y's angle is one value
            st.const_th[Y] = float(thY[0])
        return margin

    def _prp(self, st, ea, eb, uAC, uBC):
        A, B = self.A, self.B
        _, thA, bA, eA, csA = ea
        _, thB, bB, eB, csB = eb
        cA = bA + _rot(csA, uAC)
        cB = bB + _rot(csB, uBC)
        den = cross(eA, eB)
        margin = np.abs(den) - 1e-9
        dd = np.where(np.abs(den) > 1e-300, den, 1e-300)
        Dl = cB - cA
        sA = cross(Dl, eB) / dd
        sB = cross(Dl, eA) / dd
        st.set_pose(A, bA + scale(sA, eA), thA.copy(), csA)
        st.set_pose(B, bB + scale(sB, eB), thB.copy(), csB)
        return margin

    def _rpr(self, st, ea, eb, sigma):
        mid: PCon = self.mid
        A = self.A
        s_, g_ = mid.s, mid.g
        (_, PA, uA), (_, PB, uB) = ea, eb
        if s_ == A:
            Sp, us, G, ug = PA, uA, PB, uB
        else:
            Sp, us, G, ug = PB, uB, PA, uA
        c = mid.c0 + float(us[1]) - float(np.dot(mid.na, ug))
        D = Sp - G
        rho = np.hypot(D[:, 0], D[:, 1])
        margin = rho - abs(c)
        rs = np.where(rho > 1e-300, rho, 1e-300)
        asn = np.arcsin(np.clip(c / rs, -1.0, 1.0))
        delta = _atan2(D)
        psi = delta - asn if sigma > 0 else delta - np.pi + asn
        th_s = psi
        th_g = psi - mid.a
        self._set_from_point(st, s_, Sp, us, th_s)
        self._set_from_point(st, g_, G, ug, th_g)
        return margin

    def _rpp(self, st, X, Y, ex, ey):
        """X turns about a known point, Y translates with a known angle; the pair X-Y
        is prismatic, so X's angle follows from Y's and Y's shift is linear."""
        mid: PCon = self.mid
        _, pX, uX = ex
        _, thY, bY, eY, csY = ey
        thX = thY + mid.a if X == mid.s else thY - mid.a
        thX = thX.copy()
        csX = _cs(thX)
        oX = pX - _rot(csX, uX)
        th_g = thX if X == mid.g else thY
        n = left(unit(th_g + mid.a))
        den = dot(n, eY)
        margin = np.abs(den) - 1e-9
        dd = np.where(np.abs(den) > 1e-300, den, 1e-300)
        if Y == mid.s:
            t = (mid.c0 - dot(n, bY - oX)) / dd
        else:
            t = (dot(n, oX - bY) - mid.c0) / dd
        st.set_pose(X, oX, thX, csX)
        st.set_pose(Y, bY + scale(t, eY), thY.copy(), csY)
        return margin


class _MidApply:
    """block_X . (ox, oy, th) of the pair A-B, without materialising the blocks.

    ``t`` may be the float 1.0 (the angle's coefficient of a link turning about a known
    point: then t * r is r itself) or 0.0 (a link with a known angle)."""

    def __init__(self, con, st: State):
        self.con = con
        self.ru = None
        if isinstance(con, RCon):
            self.ru = {b: st.rot(b, con.local(b)) for b in con.bodies if b != 0}
        else:
            self.e = st.guide(con)[1]
            self.n = left(self.e)
            self.ed = dot(self.e, st.o[con.s] - st.o[con.g])

    def fixed(self, X, U):
        """The column of a link X sliding on a fixed guide (U = (e_x, e_y, 0.0), e its
        direction, broadcast columns) jointed by a revolute pair A-B: +-(e - 0 r) is +-e
        exactly (r and e finite, e has no -0: its angle is 0.0 + a), as one (1,)
        constant that broadcasts."""
        e0, e1 = U[0][:1], U[1][:1]
        return (e0, e1) if X == self.con.i else (-e0, -e1)

    def fixed_zero(self, X):
        """Its V and W terms, +-(0 - 0 r): a signed scalar zero (x + z is then x + that
        array, bit for bit)."""
        return (0.0, 0.0) if X == self.con.i else (-0.0, -0.0)

    def __call__(self, X, ox, oy, t):
        c = self.con
        one = isinstance(t, float) and t == 1.0
        if isinstance(c, RCon):
            ru = self.ru[X]
            r1, r0 = (ru[:, 1], ru[:, 0]) if one else (t * ru[:, 1], t * ru[:, 0])
            a, b = ox - r1, oy + r0
            if X != c.i:                    # in place: no second temporary
                np.negative(a, out=a)
                np.negative(b, out=b)
            return a, b
        nv = self.n[:, 0] * ox + self.n[:, 1] * oy
        if X == c.s:
            return t, nv
        np.negative(nv, out=nv)
        np.subtract(nv, self.ed if one else self.ed * t, out=nv)
        return -t, nv


def _length(cX) -> np.ndarray:
    """|cX|, the length of link X's column of the 2x2 system ((1,) for a link sliding on
    a fixed guide, see :meth:`_MidApply.fixed`: it broadcasts)."""
    return np.hypot(cX[0], cX[1])


def _clearly_regular(det, cA, cB) -> bool:
    """True when |det| >= 1e-10 |cA| |cB| (the singularity test of dyad_derivatives, with
    the lengths by np.hypot) holds at every position by a margin, seen from squares:
    det^2 > 1.001e-20 |cA|^2 |cB|^2 + 1e-290. The margin (1.001 against a few ulps of
    rounding in either test) makes the squared test imply the exact one; the 1e-290 covers
    a product of squares that underflows (then |det| > 1e-145 exceeds 1e-10 |cA| |cB|), and
    an overflow or a NaN fails it. Where it does not hold everywhere the caller takes the
    exact test."""
    a0, a1 = cA
    b0, b1 = cB
    with np.errstate(over="ignore", invalid="ignore"):
        q = (a0 * a0 + a1 * a1) * (b0 * b0 + b1 * b1)       # (a column of shape (1,) broadcasts)
        q *= 1.001e-20
        q += 1e-290
        return bool(np.all(det * det > q))


def _inverse(cA, cB, st: State, dets: bool, bound: float | None = None, kbound=None,
             length: float | None = None):
    """(1 / det, the singular mask) of a dyad's 2x2 system with the columns cA, cB: where
    |det| < 1e-10 |cA| |cB| the determinant is taken as +-1e-10 |cA| |cB| (its limit by
    continuity is taken afterwards); ``dets``: the normalised determinant in
    ``st.last_det`` too, dimensionless: the sine of the angle between the columns; with a
    prismatic pair A-B (``length``: the group's length) the determinant itself, divided by
    that length where both links turn about known points (RPR: the determinant is then the
    distance tau along the guide from the foot of the slider's pivot to the guide link's
    pivot, whatever the links' frames; RPP, PPR: the sine of the angle between the guides),
    not the columns' lengths (they mix an angle row and a length row: the sine would change
    with the linkage's size). ``bound``: a number that _clearly_regular's right-hand side
    (1.001e-20 |cA|^2 |cB|^2 + 1e-290, as it rounds) does not exceed at any position:
    det^2 > bound everywhere implies its test, without forming the squares (``kbound``:
    bound as a 0-d array, see state.const)."""
    N = st.N
    mul = np.multiply
    det = mul(cA[0], cB[1])
    np.subtract(det, mul(cA[1], cB[0]), det)
    # with a bound, at any N (three numpy calls against the exact test's eight); without,
    # the squares are worth their cost from WORK_ROWS_FROM positions on
    if not dets and ((bound is not None
                      and np.count_nonzero(np.greater(mul(det, det), bound if kbound is None else kbound)) == N)
                     or (N >= WORK_ROWS_FROM and _clearly_regular(det, cA, cB))):
        sing = np.zeros(N, bool)           # what the test below gives there, without its two hypot
    else:
        nn = _length(cA) * _length(cB)
        if dets:
            nd = nn if length is None else np.full(N, length)
            dn = det
            with np.errstate(divide="ignore", invalid="ignore"):
                st.last_det = np.where(nd > 0, dn / np.maximum(nd, 1e-300), 0.0)  # sine of the angle between the columns
        sing = ~(np.abs(det) >= 1e-10 * nn)
        if sing.any():
            det = np.where(sing, np.where(det >= 0, 1.0, -1.0) * np.maximum(nn, 1e-300) * 1e-10, det)
        del nn
    return np.divide(ONE, det, det), sing


def _cramer(r0, r1, cA, cB, inv):
    """Cramer's rule for the system with the columns cA, cB and the right-hand side
    (r0, r1), the products formed in place (the same operations)."""
    mul, sub = np.multiply, np.subtract
    x = mul(r0, cB[1])
    t = mul(r1, cB[0])
    sub(x, t, x)
    mul(x, inv, x)
    y = mul(cA[0], r1)
    mul(cA[1], r0, t)
    sub(y, t, y)
    mul(y, inv, y)
    return x, y


def dyad_derivatives(plan: DyadPlan, st: State, dets: bool = True) -> np.ndarray:
    """The exact phi-derivatives of a dyad's poses by a 2x2 linear solve.

    Parameters
    ----------
    plan : DyadPlan
        The dyad's plan (its links, pairs and the known points and lines).
    st : State
        The state with the dyad's poses set (its derivatives are written into it).
    dets : bool
        True: the normalised determinant in ``st.last_det`` too (the change points).

    Returns
    -------
    numpy.ndarray
        The mask of positions where the 2x2 system is singular.

    Notes
    -----
    Each link keeps one free scalar lambda after its external pair (its angle about a known
    point, or its shift s along a known line), so its pose derivatives are affine in lambda':
    (o', th') = U lambda' + V, (o'', th'') = U lambda'' + W; the pair A-B then gives two
    linear equations (Cramer's rule, vectorised).

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: the kinematic analysis of the dyads
    (Assur groups of class II); docs/methods.md §2.
    """
    if plan.slide is not None and FIXED_SLIDE:
        return plan.slide.derivatives(st, dets)
    if plan.rrr is not None and GROUND_RRR:
        return plan.rrr.derivatives(st, dets)
    A, B = plan.A, plan.B
    N = st.N
    info = {}
    for X, ext in ((A, plan.e1), (B, plan.e2)):
        if isinstance(ext, RCon):
            K = ext.j if ext.i == X else ext.i
            _, P1, P2 = st.point_d(K, ext.local(K))
            ru = st.rot(X, ext.local(X))
            U = (ru[:, 1], -ru[:, 0], 1.0)              # -J R u, 1
            V = (P1[:, 0], P1[:, 1], 0.0)
            info[X] = ("R", U, V, (P2, ru))
        else:
            K = ext.g if ext.s == X else ext.s
            sgn = 1.0 if ext.s == X else -1.0        # Q = o_K + sgn c0 n(psi)
            e = st.guide(ext)[1] if ext.s == X else unit(st.th[ext.s])
            if K == 0 and ext.s == X:
                # a fixed guide: Q', Q'', w1, w2 are zero, so V and W are (0, 0, 0) --
                # as the general terms below evaluate them (+0 in every place, the data
                # being finite), without the arithmetic
                info[X] = ("P", (e[:, 0], e[:, 1], 0.0), (0.0, 0.0, st.th1[0]), None)
                continue
            n = left(e)
            w1 = st.th1[K]
            w2 = st.th2[K]
            cc = sgn * ext.c0
            Q = st.o[K] + cc * n
            Q1 = st.o1[K] - scale(cc * w1, e)
            Q2 = st.o2[K] - cc * (scale(w2, e) + scale(st.th1_sq(K), n))
            s = dot(e, st.o[X] - Q)
            U = (e[:, 0], e[:, 1], 0.0)
            V = (Q1[:, 0] + s * w1 * n[:, 0], Q1[:, 1] + s * w1 * n[:, 1], w1)
            info[X] = ("P", U, V, (Q2, e, n, s, w1, w2))
    ap = _MidApply(plan.mid, st)
    # a link on a fixed guide jointed to the other by a revolute pair (one of the two):
    # its column is a constant and its V, W terms signed zeros (see _MidApply.fixed)
    fx = [X for X in (A, B) if info[X][3] is None] if isinstance(plan.mid, RCon) else []
    fx = fx[0] if len(fx) == 1 else None

    def apply(X, k):
        if X != fx:
            return ap(X, *info[X][k])
        return ap.fixed(X, info[X][1]) if k == 1 else ap.fixed_zero(X)

    cA = apply(A, 1)
    cB = apply(B, 1)
    norm = None                          # a revolute pair A-B: the sine between the columns
    if not isinstance(plan.mid, RCon):
        norm = plan.length if plan.kind == "RPR" else 1.0
    inv, sing = _inverse(cA, cB, st, dets, length=norm)

    def solve2(r0, r1):
        return _cramer(r0, r1, cA, cB, inv)

    def neg_sum(a, b, c=None):
        """-(a + b) or -(a + b + c), in place in the first sum."""
        r = a + b
        if c is not None:
            r = r + c if np.ndim(r) == 0 else np.add(r, c, out=r)
        return -r if np.ndim(r) == 0 else np.negative(r, out=r)

    def pose_d(X, lx, W):
        """(o, th) derivative U lx + W of link X."""
        U = info[X][1]
        o = pairs(N)
        np.add(U[0] * lx, W[0], out=o[:, 0])
        np.add(U[1] * lx, W[1], out=o[:, 1])
        th = lx + W[2] if info[X][0] == "R" else U[2] * lx + W[2]      # R: U[2] = 1
        return o, th

    vA = apply(A, 2)
    vB = apply(B, 2)
    l1 = dict(zip((A, B), solve2(neg_sum(vA[0], vB[0]), neg_sum(vA[1], vB[1]))))
    del vA, vB
    Wd = {}
    for X in (A, B):
        kind, U, V, extra = info[X]
        lx = l1[X]
        st.set_d1(X, *pose_d(X, lx, V))
        if kind == "R":
            P2, ru = extra
            l2 = st.th1_sq(X)              # (lx + 0.0)^2 is lx^2 to the bit
            Wd[X] = (P2[:, 0] + l2 * ru[:, 0], P2[:, 1] + l2 * ru[:, 1], 0.0)
        elif extra is None:                     # on a fixed guide
            Wd[X] = (0.0, 0.0, st.th2[0])
        else:
            Q2, e, n, s, w1, w2 = extra
            a = 2 * lx * w1 + s * w2
            b = s * w1 * w1
            Wd[X] = (Q2[:, 0] + a * n[:, 0] - b * e[:, 0], Q2[:, 1] + a * n[:, 1] - b * e[:, 1], w2)
    gam = plan.mid.gamma(st, ap.ru)
    wA = ap(A, *Wd[A]) if A != fx else ap.fixed_zero(A)
    wB = ap(B, *Wd[B]) if B != fx else ap.fixed_zero(B)
    l2 = dict(zip((A, B), solve2(neg_sum(wA[0], wB[0], gam[:, 0]), neg_sum(wA[1], wB[1], gam[:, 1]))))
    del wA, wB, gam, l1
    for X in (A, B):
        st.set_d2(X, *pose_d(X, l2[X], Wd[X]))
    return sing


FIXED_SLIDE = True      # the fused path of _FixedSlide (off: the generic one, for the tests)
GROUND_RRR = True       # the fused path of _GroundRRR (off: the generic one, for the tests)


def _column_bound(l: float, u1, uC) -> float:
    """A number not below |(-J R u1) - (-J R uC)| as a link's column of the 2x2 system
    rounds (_MidApply with t = 1.0; l = |uC - u1|): c^2 + s^2 = 1 to a few ulps, and its
    products and differences round within 1e-15 of l + |u1| + |uC|."""
    return l + 1e-12 * (l + float(np.hypot(*u1)) + float(np.hypot(*uC)))


def _zero_rot(u1, uC) -> bool:
    """u1 = (+0, +0) and uC = (l0 > 0, 0): then 0 (R uC) is R u1 bit for bit (0 c l0 has the
    sign of c, as c 0 has; cos never gives 0, c l0 does not underflow) -- the t = 0.0 terms
    of _MidApply are R u1's columns."""
    return (all(float(x) == 0.0 and math.copysign(1.0, float(x)) > 0 for x in u1)
            and float(uC[0]) > 0.0 and float(uC[1]) == 0.0)


class _FixedSlide:
    """An RRP / PRR dyad whose slider Y runs on a fixed guide, its other link X turning
    about a known point, the pair X-Y revolute (the slider-crank's piston and rod): its
    poses and derivatives by the same operations as :meth:`DyadPlan._rrp` and
    :func:`dyad_derivatives`, element by element, in the columns x, y, without their
    per-call bookkeeping; the guide's direction and the constant rows (the base of the
    line, the circle-line centre) are taken once per plan, by the same operations on one
    row as there (the values, bit for bit)."""

    def __init__(self, plan: DyadPlan):
        rrp = plan.kind == "RRP"
        X, Y = (plan.A, plan.B) if rrp else (plan.B, plan.A)
        ex, ey = (plan.e1, plan.e2) if rrp else (plan.e2, plan.e1)
        mid = plan.mid
        self.X, self.Y, self.ex, self.mid = X, Y, ex, mid
        self.K = ex.j if ex.i == X else ex.i                 # the body carrying X's pivot
        self.uK = ex.local(self.K)
        self.uX1 = np.asarray(ex.local(X))                   # X's pivot and its point of the pair X-Y
        self.uXC = np.asarray(mid.local(X))
        self.uYC = np.asarray(mid.local(Y))
        vX = self.uXC - self.uX1
        self.lX = float(np.hypot(*vX))
        self.lX2 = self.lX ** 2
        self.th0 = np.arctan2(vX[1], vX[0])
        # State.guide of a fixed guide and _ext / _rrp's rows, on one row
        psi = np.full(1, 0.0 + ey.a)
        e = unit(psi)
        base = np.zeros((1, 2)) + ey.c0 * left(e)
        c0 = base + _rot((e[:, 0], e[:, 1]), self.uYC)
        self.psi = float(psi[0])
        self.e0, self.e1 = float(e[0, 0]), float(e[0, 1])
        self.e_row = e[0]                                    # the broadcast cos, sin of Y's angle
        self.bx, self.by = float(base[0, 0]), float(base[0, 1])
        self.cx, self.cy = float(c0[0, 0]), float(c0[0, 1])
        self.xa = X == plan.A
        self.x_sign = X == mid.i                             # _MidApply: +- the terms of X, of Y
        y_first = Y == mid.i
        self.cY = (self.e0, self.e1) if y_first else (-self.e0, -self.e1)     # _MidApply.fixed
        self.zY = 0.0 if y_first else -0.0                   # _MidApply.fixed_zero: x + (-0.0) is x
        # _inverse's bound: |cA| = |R vX| (l, c^2 + s^2 = 1 to a few ulps; its products and
        # differences round within 1e-15 of l + |u1| + |uC|), |cB| = |e| (1 to a few ulps):
        # a relative 1e-12 over both covers the rounding of _clearly_regular's products
        big = _column_bound(self.lX, self.uX1, self.uXC)
        self.bound = 1.001e-20 * (big * big) * (1.0 + 1e-12) + 2e-290
        self.zero_rot = _zero_rot(self.uX1, self.uXC)
        self._bc = (0, None)
        # the same numbers as 0-d arrays (a ufunc takes them without a scalar's conversion)
        self.k = {n: const(getattr(self, n)) for n in ("lX", "lX2", "th0", "e0", "e1", "cx", "cy", "bx", "by",
                                                       "bound")}
        self.ku = (const(self.uX1[0]), const(self.uX1[1]))
        self.cY = tuple(const(v) for v in self.cY)

    def _cs_y(self, N: int):
        """Y's (cos, sin) as State.guide gives them: one row broadcast (kept per N)."""
        n, cs = self._bc
        if n != N:
            b = np.broadcast_to(self.e_row, (N, 2))
            cs = (b[:, 0], b[:, 1])
            self._bc = (N, cs)
        return cs

    def pose(self, st: State, sigma: float) -> np.ndarray:
        """DyadPlan._rrp of this dyad."""
        N = st.N
        X, Y, k = self.X, self.Y, self.k
        e0, e1 = k["e0"], k["e1"]
        add, sub, mul = np.add, np.subtract, np.multiply
        K = self.K                          # DyadPlan._ext: X's pivot
        P1 = st.point_d(K, self.uK)[0] if K in st.th1 else st.point(K, self.uK)
        px, py = P1[:, 0], P1[:, 1]
        w0 = sub(k["cx"], px)
        w1 = sub(k["cy"], py)
        h = mul(w0, e1)
        sub(h, mul(w1, e0), h)
        margin = sub(k["lX"], np.abs(h))
        root = np.sqrt(np.maximum(sub(k["lX2"], h ** 2), ZERO))
        d = mul(w0, e0, w0)
        add(d, mul(w1, e1, w1), d)
        if sigma == 1.0:                    # -a + 1.0 r is r - a, bit for bit
            s = sub(root, d, root)
        else:
            s = -d + sigma * root
        sx = mul(s, e0)
        sy = mul(s, e1, s)
        D = np.empty((N, 2))                # C - P1, strided as there (the arctangent's input)
        dx, dy = D[:, 0], D[:, 1]
        add(k["cx"], sx, dx)
        sub(dx, px, dx)
        add(k["cy"], sy, dy)
        sub(dy, py, dy)
        th = _minus_const(np.arctan2(dy, dx), self.th0, k["th0"])
        c, sn = np.cos(th), np.sin(th)
        u0, u1 = self.ku
        o = pairs(N)
        ru = pairs(N)               # (c u0, s u0): R u1 as State.rot takes it when u1 = (u0, 0)
        cu, su = ru[:, 0], ru[:, 1]
        mul(c, u0, cu)
        mul(sn, u0, su)
        sub(px, sub(cu, mul(sn, u1)), o[:, 0])
        sub(py, add(su, mul(c, u1)), o[:, 1])
        st.set_pose(X, o, th, (c, sn))
        if float(self.uX1[1]) == 0.0:       # shared with the derivatives (State.rot)
            st.share_rot(X, self.uX1, ru)
        oY = pairs(N)
        add(k["bx"], sx, oY[:, 0])
        add(k["by"], sy, oY[:, 1])
        thY = np.empty(N)
        thY.fill(self.psi)
        st.set_pose(Y, oY, thY, self._cs_y(N))
        st.const_th[Y] = self.psi
        return margin

    def derivatives(self, st: State, dets: bool) -> np.ndarray:
        """dyad_derivatives of this dyad."""
        N = st.N
        X, Y = self.X, self.Y
        _, P1, P2 = st.point_d(self.K, self.uK)
        ru = st.rot(X, self.uX1)
        rx, ry = ru[:, 0], ru[:, 1]
        ruM = st.rot(X, self.uXC)
        mx, my = ruM[:, 0], ruM[:, 1]
        # X's column: (-J R u1) - (-J R uC) of the pair, +- by the pair's order
        a = ry - my
        b = mx - rx                          # (-rx) + mx
        z1, z0 = (ry, rx) if self.zero_rot else (np.multiply(ZERO, my), np.multiply(ZERO, mx))
        if not self.x_sign:
            np.negative(a, a)
            np.negative(b, b)
        cX, cY = (a, b), self.cY
        cA, cB = (cX, cY) if self.xa else (cY, cX)
        inv, sing = _inverse(cA, cB, st, dets, self.bound, self.k["bound"])
        # first derivatives: -(V terms), V = (P1', 0) for X, (0, 0) for Y
        lX, lY = self._level(*self._rhs(P1[:, 0], P1[:, 1], z1, z0), cA, cB, inv)
        self._set(st.set_d1, N, lX, lY, P1[:, 0], P1[:, 1], rx, ry)
        l2 = st.th1_sq(X)
        W0 = P2[:, 0] + l2 * rx
        W1 = P2[:, 1] + l2 * ry
        gam = self.mid.gamma(st, {X: ruM, Y: st.rot(Y, self.uYC)})
        # second derivatives: -(W terms + gamma), W = (P1'' + th1^2 R u1, 0) for X, (0, 0) for Y
        lX, lY = self._level(*self._rhs(W0, W1, z1, z0, gam), cA, cB, inv)
        self._set(st.set_d2, N, lX, lY, W0, W1, rx, ry)
        return sing

    def _rhs(self, t0, t1, z1, z0, gam=None):
        """The right-hand side -(X's terms + Y's (signed zeros) [+ gamma]) of the 2x2
        system, as _MidApply and neg_sum form it; (t0, t1): X's pose terms (V or W)."""
        add, neg = np.add, np.negative
        v0 = np.subtract(t0, z1)
        v1 = add(t1, z0)
        if not self.x_sign:
            neg(v0, v0)
            neg(v1, v1)
        zY = self.zY
        if zY == 0.0 and math.copysign(1.0, zY) > 0:
            add(v0, ZERO, v0)
            add(v1, ZERO, v1)
        if gam is not None:
            add(v0, gam[:, 0], v0)
            add(v1, gam[:, 1], v1)
        return neg(v0, v0), neg(v1, v1)

    def _level(self, r0, r1, cA, cB, inv):
        """(lambda of X, lambda of Y) by Cramer's rule."""
        lA, lB = _cramer(r0, r1, cA, cB, inv)
        return (lA, lB) if self.xa else (lB, lA)

    def _set(self, set_d, N, lX, lY, W0, W1, rx, ry):
        """pose_d of X (U = (-J R u1, 1)) and of Y (U = (e, 0)), W = (W0, W1, 0) for X and
        (0, 0, 0) for Y; set by ``set_d`` (State.set_d1 or set_d2)."""
        add, mul = np.add, np.multiply
        o = pairs(N)
        add(mul(ry, lX), W0, o[:, 0])
        np.subtract(W1, mul(rx, lX), o[:, 1])          # (-rx) lX + W1
        set_d(self.X, o, add(lX, ZERO))
        o = pairs(N)
        k = self.k
        add(mul(k["e0"], lY), ZERO, o[:, 0])
        add(mul(k["e1"], lY), ZERO, o[:, 1])
        t = mul(ZERO, lY)
        set_d(self.Y, o, add(t, ZERO, t))


class _GroundRRR:
    """An RRR dyad whose external pairs are at known points, one of them a ground pivot
    (the four-bar's rod and rocker; the six-bars' first group): its poses and derivatives
    by the same operations as :meth:`DyadPlan._rrr` and :func:`dyad_derivatives`, element
    by element, in (2, N) blocks, without their per-call bookkeeping; the ground pivot's
    coordinates (State.point_d of the ground: u + 0.0), the links' lengths and the constants
    of the circle/circle closure taken once per plan. The positions are assumed finite (as
    every run has them): the ground pivot's terms of the derivatives are then signed
    zeros."""

    def __init__(self, plan: DyadPlan, ground_b: bool):
        A, B, mid = plan.A, plan.B, plan.mid
        self.A, self.B, self.mid = A, B, mid
        self.ground_b = ground_b                               # B's pivot on the ground (else A's)
        ex = plan.e1 if ground_b else plan.e2                  # the moving pivot's pair
        M = A if ground_b else B
        self.K = ex.j if ex.i == M else ex.i                   # the body carrying it
        self.uK = ex.local(self.K)
        eg = plan.e2 if ground_b else plan.e1
        ug = eg.local(0)
        self.G = np.array([[float(ug[0]) + 0.0], [float(ug[1]) + 0.0]])     # (2, 1): broadcasts
        self.uA1 = np.asarray(plan.e1.local(A))
        self.uB1 = np.asarray(plan.e2.local(B))
        self.uAC = np.asarray(mid.local(A))
        self.uBC = np.asarray(mid.local(B))
        vA, vB = self.uAC - self.uA1, self.uBC - self.uB1
        lA, lB = float(np.hypot(*vA)), float(np.hypot(*vB))      # as _rrr takes them
        self.lA = lA
        self.lsum, self.ldiff = lA + lB, abs(lA - lB)
        self.lA2, self.lB2, self.tlA = lA ** 2, lB ** 2, 2 * lA
        self.kA, self.kB = np.arctan2(vA[1], vA[0]), np.arctan2(vB[1], vB[0])
        # _MidApply: + the terms of the pair's first body, - those of the other
        self.a_first = A == mid.i
        # the ground link's _MidApply terms of V (and of W where u1 = (+0, +0)), t = 0.0, are
        # +-(0 - 0 R uC) = +-0: a signed zero (x + (+0.0) turns -0 to +0; x + (-0.0) is x)
        self.zG = 0.0 if (B if ground_b else A) == mid.i else -0.0
        self.zrA, self.zrB = _zero_rot(self.uA1, self.uAC), _zero_rot(self.uB1, self.uBC)
        bA, bB = _column_bound(lA, self.uA1, self.uAC), _column_bound(lB, self.uB1, self.uBC)
        self.bound = 1.001e-20 * (bA * bA) * (bB * bB) * (1.0 + 1e-12) + 2e-290
        # the same numbers as 0-d arrays (a ufunc takes them without a scalar's conversion)
        self.k = {n: const(getattr(self, n)) for n in ("lA", "lsum", "ldiff", "lA2", "lB2", "tlA", "kA", "kB",
                                                       "bound")}
        self.kuA = (const(self.uA1[0]), const(self.uA1[1]))
        self.kuB = (const(self.uB1[0]), const(self.uB1[1]))
        self._gn = (0, None)

    def _ground(self, N: int) -> np.ndarray:
        """The ground pivot's (2, 1) coordinates repeated over N positions (kept per N):
        the same values, an operation on two (2, N) blocks takes numpy's plain loop."""
        n, g = self._gn
        if n != N:
            g = np.repeat(self.G, N, axis=1)
            g.flags.writeable = False
            self._gn = (N, g)
        return g

    def pose(self, st: State, sigma: float) -> np.ndarray:
        """DyadPlan._rrr of this dyad, its (N, 2) pairs as (2, N) blocks (their transposes,
        see state.pairs: one numpy call for both coordinates)."""
        N = st.N
        K = self.K
        k = self.k
        add, sub, mul = np.add, np.subtract, np.multiply
        P = (st.point_d(K, self.uK)[0] if K in st.th1 else st.point(K, self.uK)).T
        G = self._ground(N) if N < WORK_ROWS_FROM else self.G      # (many positions: less memory)
        P1, P3 = (P, G) if self.ground_b else (G, P)
        D = P3 - P1
        Dx, Dy = D[0], D[1]
        d = np.hypot(Dx, Dy)
        margin = np.minimum(sub(k["lsum"], d), sub(d, k["ldiff"]))
        # np.where(d > 1e-300, d, 1e-300): the same where d is not NaN (a NaN d makes the
        # numerator below NaN, and a division returns its first operand's NaN)
        ds = np.maximum(d, _TINY)
        cg = mul(d, d)
        add(cg, k["lA2"], cg)
        sub(cg, k["lB2"], cg)
        mul(ds, k["tlA"], ds)
        np.divide(cg, ds, cg)
        _clip(cg, _M1, ONE, cg)
        ang = np.arctan2(Dy, Dx)
        ac = np.arccos(cg, cg)
        if sigma == 1.0:                     # beta + 1.0 a is beta + a, bit for bit
            add(ang, ac, ang)
        elif sigma == -1.0:                  # beta + (-1.0) a is beta - a
            sub(ang, ac, ang)
        else:
            ang += sigma * ac
        C = np.empty((2, N))                 # P1 + lA (cos, sin)
        np.cos(ang, C[0])
        np.sin(ang, C[1])
        mul(C, k["lA"], C)
        add(C, P1, C)
        sub(C, P1, D)
        thA = _minus_const(np.arctan2(Dy, Dx), self.kA, k["kA"])
        sub(C, P3, D)
        thB = _minus_const(np.arctan2(Dy, Dx), self.kB, k["kB"])
        self._set(st, self.A, P1, self.uA1, self.kuA, thA)
        self._set(st, self.B, P3, self.uB1, self.kuB, thB)
        return margin

    @staticmethod
    def _set(st: State, X: int, P, u, ku, th) -> None:
        """DyadPlan._set_from_point: X turned by th, its point u at P ((2, N) or (2, 1)); ``ku``: u's
        coordinates as 0-d arrays; R u of the derivatives shared where State.rot takes it
        as here (u = (u0, 0))."""
        N = st.N
        cs = np.empty((2, N))
        c, s = cs[0], cs[1]
        np.cos(th, c)
        np.sin(th, s)
        ru = np.multiply(cs, ku[0])          # (c u0, s u0)
        if N < WORK_ROWS_FROM:
            t = np.multiply(cs, ku[1])       # (c u1, s u1)
            o = np.empty((2, N))
            np.subtract(ru[0], t[1], o[0])   # c u0 - s u1
            np.add(ru[1], t[0], o[1])        # s u0 + c u1
        else:                                # many positions: in place, one block less
            o = np.multiply(cs[::-1], ku[1])     # (s u1, c u1)
            np.subtract(ru[0], o[0], o[0])
            np.add(ru[1], o[1], o[1])
        st.set_pose(X, np.subtract(P, o, o).T, th, (c, s))
        if float(u[1]) == 0.0:
            st.share_rot(X, u, ru.T)

    def derivatives(self, st: State, dets: bool) -> np.ndarray:
        """dyad_derivatives of this dyad."""
        N = st.N
        A, B, gb = self.A, self.B, self.ground_b
        neg, sub = np.negative, np.subtract
        _, P1, P2 = st.point_d(self.K, self.uK)               # the moving pivot's derivatives
        rA, rB = st.rot(A, self.uA1), st.rot(B, self.uB1)
        mA, mB = st.rot(A, self.uAC), st.rot(B, self.uBC)
        rAx, rAy, rBx, rBy = rA[:, 0], rA[:, 1], rB[:, 0], rB[:, 1]
        mAx, mAy, mBx, mBy = mA[:, 0], mA[:, 1], mB[:, 0], mB[:, 1]
        # the columns (_MidApply, t = 1.0): (ry - my, (-rx) + mx), +- by the pair's order
        cA = (sub(rAy, mAy), sub(mAx, rAx))
        cB = (sub(rBy, mBy), sub(mBx, rBx))
        for col in (cB if self.a_first else cA):
            neg(col, col)
        inv, sing = _inverse(cA, cB, st, dets, self.bound, self.k["bound"])
        # _MidApply's t = 0.0 terms (0 my, 0 mx): R u1's columns where they are the same bits
        zA = (rAy, rAx) if self.zrA else (np.multiply(ZERO, mAy), np.multiply(ZERO, mAx))
        zB = (rBy, rBx) if self.zrB else (np.multiply(ZERO, mBy), np.multiply(ZERO, mBx))
        (zM, fM), (zG, fG) = ((zA, self.a_first), (zB, not self.a_first)) if gb else \
            ((zB, not self.a_first), (zA, self.a_first))
        # the links' U = (-J R u1, 1): (ry, -rx) as (2, N) blocks
        UA, UB = _u_block(N, rAx, rAy), _u_block(N, rBx, rBy)
        # first derivatives: V = (P1', 0) for the moving pivot's link, (0, 0) for the ground's
        # (its _MidApply terms the signed zero zG)
        P1x, P1y = P1[:, 0], P1[:, 1]
        v0, v1 = _mid_terms(P1x, P1y, zM, fM)
        lA, lB = _cramer(_neg_sum(v0, self.zG), _neg_sum(v1, self.zG), cA, cB, inv)
        V = P1.T
        _pose_d(st.set_d1, A, lA, UA, V if gb else 0.0)
        _pose_d(st.set_d1, B, lB, UB, 0.0 if gb else V)
        # second derivatives: W = (P'' + th1^2 R u1, 0), P'' = +0 for the ground's link (then
        # +0.0 + th1^2 R u1; with u1 = (+0, +0): W = (+0, +0), its terms the signed zero zG)
        qA, qB = st.th1_sq(A), st.th1_sq(B)
        WA = np.add(P2.T, np.multiply(qA, rA.T)) if gb else _ground_w(qA, rA, self.zrA)
        WB = _ground_w(qB, rB, self.zrB) if gb else np.add(P2.T, np.multiply(qB, rB.T))
        WM, WG = (WA, WB) if gb else (WB, WA)
        wM = _mid_terms(WM[0], WM[1], zM, fM)
        wG = (self.zG, self.zG) if isinstance(WG, float) else _mid_terms(WG[0], WG[1], zG, fG)
        gam = self.mid.gamma(st, {A: mA, B: mB})
        lA, lB = _cramer(_neg_sum(wM[0], wG[0], gam[:, 0]), _neg_sum(wM[1], wG[1], gam[:, 1]), cA, cB, inv)
        _pose_d(st.set_d2, A, lA, UA, WA)
        _pose_d(st.set_d2, B, lB, UB, WB)
        return sing


def _mid_terms(t0, t1, z, first: bool):
    """_MidApply of a link turning about a known point with t = 0.0 (its V or W terms
    (t0, t1), z = (0 my, 0 mx)): (t0 - 0 my, t1 + 0 mx), negated for the pair's second body."""
    a = np.subtract(t0, z[0])
    b = np.add(t1, z[1])
    if not first:
        np.negative(a, a)
        np.negative(b, b)
    return a, b


def _neg_sum(a, b, c=None):
    """dyad_derivatives' neg_sum -(a + b [+ c]) in place in a (an array of its own); b may be
    a signed zero (an array of them broadcast: x + (-0.0) is x, x + (+0.0) turns -0 to +0)."""
    if isinstance(b, float) and b == 0.0:
        if math.copysign(1.0, b) > 0:
            np.add(a, ZERO, a)
    else:
        np.add(a, b, a)
    if c is not None:
        np.add(a, c, a)
    return np.negative(a, a)


def _ground_w(q, r, zero: bool):
    """A ground-pivoted link's W terms +0 + th1^2 R u1 as a (2, N) block (r = R u1, (N, 2));
    +0.0 where R u1 is signed zeros (``zero``: u1 = (+0, +0); th1^2 is finite)."""
    if zero:
        return 0.0
    w = np.multiply(q, r.T)
    return np.add(w, ZERO, w)


def _u_block(N: int, rx, ry) -> np.ndarray:
    """(ry, -rx): U's first two rows of a link turning about a known point (-J R u1)."""
    U = np.empty((2, N))
    U0, U1 = U[0], U[1]
    np.copyto(U0, ry)
    np.negative(rx, U1)
    return U


def _pose_d(set_d, X: int, lx, U, W) -> None:
    """dyad_derivatives' pose_d of a link turning about a known point: U lx + W, its
    terms W = (W0, W1, 0) a (2, N) block or +0.0, set by ``set_d`` (set_d1 or set_d2)."""
    o = np.multiply(U, lx)
    np.add(o, ZERO if isinstance(W, float) else W, o)
    set_d(X, o.T, np.add(lx, ZERO))
