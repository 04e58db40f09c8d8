"""The kinematics of a regular call in complex numbers: the fast path of :func:`.solver.solve`.

A point is a complex number x + iy, an (N,) complex array over the positions (its
(N, 2) float view is the result's array, without a copy). A body's pose is a reference
point R of it (with R' and R'', derivatives in the crank angle phi), the local coordinates
u_R of that point and its rotation E = e^{i theta}; a point of local coordinates u is

    P = R + E (u - u_R),   P' = R' + i omega E (u - u_R),
    P'' = R'' + (i epsilon - omega^2) E (u - u_R),

omega = theta', epsilon = theta''. Each class-II group is closed as in :mod:`.dyads` (the
same closures and the same sign conventions), written with complex products:

* RRR: C = P1 + (P3 - P1)(k + i sigma h), k = 1/2 + (l_A^2 - l_B^2) / (2 d^2),
  h^2 = l_A^2 / d^2 - k^2; velocities from C' = P1' + i omega_A (C - P1) = P3' + i omega_B (C - P3);
* RRP / PRR: the slider's pin on its guide C = C0 + s e, |C - P1| = l;
* RPR: the slider's pivot seen from the guide link's pivot, D = Sp - G, gives
  E_slider = D (tau - i c) / |D|^2, tau = sigma sqrt(|D|^2 - c^2);
* PRP: two lines; RPP / PPR on a fixed guide: one shift, linear.

The velocity and acceleration equations of a group are two real equations
x p + y q = r in complex form (Cramer's rule by cross products, Im(conj(a) b));
a slide on a moving guide adds the Coriolis term 2 i omega s' e.

This path answers only a regular call: every group assembles with a clear margin and
its velocity equations are well conditioned (the normalised determinant -- the sine of the
angle between the columns; for RPR the distance tau below over the group's length -- at
least ``changepoints.ILL_DET``, below which the general solver flags a position and takes
its values by continuity) at every position. Anything
else -- a group it does not cover (a Newton group, a dyad whose link carries the guide of
a known slider, RPP on a moving guide), a position near a limit or a singular position,
an angle whose branch is in doubt, no positions -- returns None, and the general solver
(:class:`.solver.Solver`, the real-valued group by group method that also finds the
limits by continuity and names where a group does not assemble) answers the whole call.
The two agree to the rounding of double precision (tests: every dyad kind, random
linkages, against the general solver and against finite differences).
"""
from __future__ import annotations

import cmath
import math

import numpy as np

from .changepoints import ILL_DET
from .dyads import DyadPlan
from .state import PCon

REGULAR = ILL_DET        # the least normalised determinant (and margin) the fast path takes
_TWO_PI = 2.0 * math.pi


def _c(u) -> complex:
    return complex(float(u[0]), float(u[1]))


def _solve2(p, q, r):
    """Real x, y with x p + y q = r (complex): Cramer's rule by cross products."""
    pc = np.conjugate(p)
    det = np.multiply(pc, q).imag
    inv = 1.0 / det
    x = np.multiply(np.conjugate(r), q).imag
    x *= inv
    y = np.multiply(pc, r).imag
    y *= inv
    return x, y, det


def _coriolis(e, s1, w):
    """2 i omega s' e: the Coriolis term of a slide s' along e on a guide turning at omega."""
    c = np.multiply(e, np.multiply(s1, w))
    c *= 2j
    return c


def _regular(det, scale, N) -> bool:
    """|det| >= REGULAR * scale at every position (a NaN fails)."""
    return np.count_nonzero(np.abs(det) >= REGULAR * scale) == N


class _Body:
    """A body's pose: reference point R (R', R''), its local u_R, E = e^{i th}, th, omega, eps.
    R, R', R'' and E are complex arrays or complex numbers (constant); omega and eps real
    arrays or floats; ``rot``: the body turns (E an array)."""
    __slots__ = ("R", "R1", "R2", "uR", "E", "th", "w", "e", "w2", "rot", "const")

    def __init__(self, R, R1, R2, uR, E, th, w, e, rot, const=False):
        self.R, self.R1, self.R2, self.uR, self.E = R, R1, R2, uR, E
        self.th, self.w, self.e, self.rot, self.const = th, w, e, rot, const
        self.w2 = None

    def wsq(self):
        if self.w2 is None:
            self.w2 = self.w * self.w
        return self.w2


_GROUND = _Body(0j, 0j, 0j, 0j, 1 + 0j, 0.0, 0.0, 0.0, False)


class _Run:
    """One call: the bodies' poses and the points taken from them."""

    def __init__(self, N: int):
        self.N = N
        self.bodies: dict[int, _Body] = {0: _GROUND}
        self._pts: dict = {}

    def pt(self, b: int, u: complex):
        """(P, P', P'') of the point of body b with local coordinates u."""
        key = (b, u)
        hit = self._pts.get(key)
        if hit is not None:
            return hit
        B = self.bodies[b]
        k = u - B.uR
        if k == 0:
            out = (B.R, B.R1, B.R2)
        elif not B.rot:                         # a translating body (or the ground)
            out = (B.R + B.E * k, B.R1, B.R2)
        else:
            t = np.multiply(B.E, k)
            P = B.R + t
            it = np.multiply(t, 1j)
            w, e = B.w, B.e
            if type(w) is float and w == 1.0 and type(e) is float and e == 0.0:   # the crank
                P1 = it if type(B.R1) is complex and B.R1 == 0 else B.R1 + it
                P2 = np.negative(t) if type(B.R2) is complex and B.R2 == 0 else B.R2 - t
            else:
                P1 = np.multiply(it, w)
                P1 += B.R1
                P2 = np.multiply(it, e)
                P2 += B.R2
                P2 -= np.multiply(t, B.wsq())
            out = (P, P1, P2)
        self._pts[key] = out
        return out

    def vel_at(self, b: int, X):
        """The velocity (d/dphi) of body b's material point at position X."""
        B = self.bodies[b]
        if not B.rot:
            return B.R1
        v = np.multiply(X - B.R, 1j)
        v *= B.w
        v += B.R1
        return v

    def acc_at(self, b: int, X):
        B = self.bodies[b]
        if not B.rot:
            return B.R2
        k = np.multiply(B.e, 1j)
        k -= B.wsq()
        k *= X - B.R
        k += B.R2
        return k


def _branch_ok(v, i0: int, l: float) -> bool:
    """The angle of v at the reference position is clearly off the cut at +-pi (where the
    general solver's arctan2 of the same vector, rounded differently, could take the other
    branch)."""
    z = complex(v[i0]) if np.ndim(v) else complex(v)
    return not (z.real < 0 and abs(z.imag) <= 1e-9 * l)


def _gap(S: _Run, K1: int, u1: complex, K2: int, u2: complex):
    """Two known points (each with its two derivatives), D = the second minus the first and
    |D|^2; None when both are fixed (no group to close over the positions)."""
    P = S.pt(K1, u1)
    Q = S.pt(K2, u2)
    D = np.subtract(Q[0], P[0])
    if np.ndim(D) == 0:
        return None
    Dr, Di = D.real, D.imag
    d2 = np.multiply(Dr, Dr)
    d2 += np.multiply(Di, Di)
    return P, Q, D, d2


class _Step:
    """One class-II group of the fast path."""

    def __init__(self, plan, gi):
        self.plan, self.gi = plan, gi


class _RRR(_Step):
    def __init__(self, plan, gi):
        super().__init__(plan, gi)
        A, B, e1, mid, e2 = plan.A, plan.B, plan.e1, plan.mid, plan.e2
        self.KA = e1.j if e1.i == A else e1.i
        self.KB = e2.j if e2.i == B else e2.i
        self.uKA, self.uKB = _c(e1.local(self.KA)), _c(e2.local(self.KB))
        self.uA1, self.uB3 = _c(e1.local(A)), _c(e2.local(B))
        vA = _c(mid.local(A)) - self.uA1
        vB = _c(mid.local(B)) - self.uB3
        self.lA, self.lB = abs(vA), abs(vB)
        self.lA2, self.lB2 = self.lA * self.lA, self.lB * self.lB
        self.kk = 0.5 * (self.lA2 - self.lB2)
        self.cA = vA.conjugate() / self.lA2           # E_A = (C - P1) cA
        self.cB = vB.conjugate() / self.lB2
        self.argA = math.atan2(vA.imag, vA.real)
        self.argB = math.atan2(vB.imag, vB.real)

    def run(self, S: _Run, sigma: float, i0: int) -> bool:
        N = S.N
        gap = _gap(S, self.KA, self.uKA, self.KB, self.uKB)
        if gap is None:
            return False
        (P1, P1d, P1dd), (P3, P3d, P3dd), D, q = gap
        np.divide(1.0, q, q)                          # 1 / d^2
        k = np.multiply(q, self.kk)
        k += 0.5
        h2 = np.multiply(q, self.lA2)
        h2 -= np.multiply(k, k)
        if np.count_nonzero(h2 > 0.0) != N:
            return False
        z = np.empty(N, complex)
        zf = z.view(np.float64).reshape(N, 2)
        zf[:, 0] = k
        np.sqrt(h2, zf[:, 1])
        if sigma < 0:
            np.negative(zf[:, 1], zf[:, 1])
        a = np.multiply(D, z)                         # C - P1
        C = np.add(P1, a)
        b = np.subtract(C, P3)                        # C - P3
        ac, bc = np.conjugate(a), np.conjugate(b)
        det = np.multiply(ac, b).imag
        if not _regular(det, self.lA * self.lB, N):
            return False
        if not (_branch_ok(a, i0, self.lA) and _branch_ok(b, i0, self.lB)):
            return False
        inv = np.divide(1.0, det)
        # i wA a - i wB b = r  ->  wA = Re(conj(b) r) / det, wB = Re(conj(a) r) / det
        r = np.subtract(P3d, P1d)
        wA = np.multiply(bc, r).real * inv
        wB = np.multiply(ac, r).real * inv
        wA2, wB2 = wA * wA, wB * wB
        r = np.subtract(P3dd, P1dd)
        r += np.multiply(a, wA2)
        r -= np.multiply(b, wB2)
        eA = np.multiply(bc, r).real * inv
        eB = np.multiply(ac, r).real * inv
        thA = np.angle(a)
        thA -= self.argA
        thB = np.angle(b)
        thB -= self.argB
        plan = self.plan
        S.bodies[plan.A] = bA = _Body(P1, P1d, P1dd, self.uA1, np.multiply(a, self.cA), thA, wA, eA, True)
        S.bodies[plan.B] = bB = _Body(P3, P3d, P3dd, self.uB3, np.multiply(b, self.cB), thB, wB, eB, True)
        bA.w2, bB.w2 = wA2, wB2
        return True


def _guide(con: PCon, S: _Run, u: complex):
    """A slider's guide (con.s the slider, on body con.g): (E of the slider, the material
    point of the guide's body where the slider's point of local u is at slide 0)."""
    ea = cmath.exp(1j * con.a)
    K = S.bodies[con.g]
    E = K.E * ea
    return E, S.pt(con.g, ea * (1j * con.c0 + u))


def _guide_th(con: PCon, S: _Run, N: int):
    """The slider's angle th_g + a, as the general solver forms it."""
    if con.g == 0:
        return np.full(N, 0.0 + con.a)
    return S.bodies[con.g].th + con.a


class _RRP(_Step):
    """X turns about a known point, Y slides on the guide of a known body; pin C."""

    def __init__(self, plan, gi, X, Y, ex, ey):
        super().__init__(plan, gi)
        self.X, self.Y, self.ey = X, Y, ey
        self.K = ex.j if ex.i == X else ex.i
        self.uK = _c(ex.local(self.K))
        self.uX1 = _c(ex.local(X))
        mid = plan.mid
        vX = _c(mid.local(X)) - self.uX1
        self.uYC = _c(mid.local(Y))
        self.lX = abs(vX)
        self.lX2 = self.lX * self.lX
        self.cX = vX.conjugate() / self.lX2
        self.argX = math.atan2(vX.imag, vX.real)

    def run(self, S: _Run, sigma: float, i0: int) -> bool:
        N = S.N
        ey = self.ey
        G = ey.g
        P1, P1d, P1dd = S.pt(self.K, self.uK)
        EY, (C0, _, _) = _guide(ey, S, self.uYC)
        w = np.subtract(C0, P1)
        if np.ndim(w) == 0:
            return False
        we = np.multiply(w, np.conjugate(EY))         # dot(w, e) + i cross(e, w)
        hh = we.imag
        root = np.multiply(hh, hh)
        np.subtract(self.lX2, root, root)
        if np.count_nonzero(root > (REGULAR * self.lX) ** 2) != N:
            return False
        np.sqrt(root, root)
        if sigma == 1.0:
            s = np.subtract(root, we.real, root)
        else:
            s = np.negative(root, root)
            s -= we.real
        sE = np.multiply(EY, s)
        C = np.add(C0, sE)
        a = np.subtract(C, P1)
        if not _branch_ok(a, i0, self.lX):
            return False
        # i wX a - s' e = V_K(C) - P1'
        p = np.multiply(a, 1j)
        q = np.negative(EY)
        VK = S.vel_at(G, C)
        wX, s1, det = _solve2(p, q, np.subtract(VK, P1d))
        if not _regular(det, self.lX, N):
            return False
        wX2 = wX * wX
        K = S.bodies[G]
        s1E = np.multiply(EY, s1)
        AK = S.acc_at(G, C)
        r = np.subtract(AK, P1dd)
        r += np.multiply(a, wX2)
        if K.rot:
            cor = _coriolis(EY, s1, K.w)
            r += cor
        eX, s2, _ = _solve2(p, q, r)
        # C' and C'' as Y's point: the guide's point there, the slide along it, Coriolis
        C1 = np.add(VK, s1E)
        C2 = np.multiply(EY, s2)
        C2 += AK
        if K.rot:
            C2 += cor
        thX = np.angle(a)
        thX -= self.argX
        bX = _Body(P1, P1d, P1dd, self.uX1, np.multiply(a, self.cX), thX, wX, eX, True)
        bX.w2 = wX2
        S.bodies[self.X] = bX
        if K.rot:
            S.bodies[self.Y] = _Body(C, C1, C2, self.uYC, EY, _guide_th(ey, S, N), K.w, K.e, True)
        else:
            S.bodies[self.Y] = _Body(C, C1, C2, self.uYC, EY, _guide_th(ey, S, N), 0.0, 0.0, False,
                                     const=G == 0)
        return True


class _RPR(_Step):
    """Both links turn about known points; the slider's guide is the other link."""

    def __init__(self, plan, gi):
        super().__init__(plan, gi)
        mid: PCon = plan.mid
        A = plan.A
        self.s, self.g = mid.s, mid.g
        es, eg = (plan.e1, plan.e2) if mid.s == A else (plan.e2, plan.e1)
        self.Ks = es.j if es.i == self.s else es.i
        self.Kg = eg.j if eg.i == self.g else eg.i
        self.uKs, self.uKg = _c(es.local(self.Ks)), _c(eg.local(self.Kg))
        self.us, self.ug = _c(es.local(self.s)), _c(eg.local(self.g))
        us, ug = es.local(self.s), eg.local(self.g)
        self.cc = mid.c0 + float(us[1]) - float(np.dot(mid.na, ug))    # as the general solver
        self.a = mid.a
        self.ema = cmath.exp(-1j * mid.a)
        self.tau_min2 = (REGULAR * plan.length) ** 2

    def run(self, S: _Run, sigma: float, i0: int) -> bool:
        N = S.N
        gap = _gap(S, self.Kg, self.uKg, self.Ks, self.uKs)
        if gap is None:
            return False
        (G, Gd, Gdd), (Sp, Spd, Spdd), D, rho2 = gap            # D = Sp - G
        c = self.cc
        tau2 = np.subtract(rho2, c * c)
        # assembles (tau^2 > 0) and regular (|tau| >= REGULAR rho) at once, and the
        # velocity equations (their determinant tau) well conditioned: tau >= REGULAR l_g
        if np.count_nonzero(tau2 > np.maximum(np.multiply(rho2, REGULAR * REGULAR), self.tau_min2)) != N:
            return False
        z = np.empty(N, complex)
        zf = z.view(np.float64).reshape(N, 2)
        np.sqrt(tau2, zf[:, 0])
        if sigma <= 0:
            np.negative(zf[:, 0], zf[:, 0])
        zf[:, 1] = -c
        np.divide(1.0, rho2, rho2)
        Es = np.multiply(D, z)
        Es *= rho2                                    # E_s = D (tau - i c) / rho^2
        # the angle on the general solver's branch: delta - asin(c / rho) (sigma > 0),
        # delta - pi + asin(c / rho)
        d0 = complex(D[i0])
        if not _branch_ok(d0, 0, abs(d0)):
            return False
        r0 = abs(d0)
        asn = math.asin(max(-1.0, min(1.0, c / r0)))
        delta = math.atan2(d0.imag, d0.real)
        psi0 = delta - asn if sigma > 0 else delta - math.pi + asn
        th_s = np.angle(Es)
        k = round((psi0 - float(th_s[i0])) / _TWO_PI)
        if abs(psi0 - float(th_s[i0]) - k * _TWO_PI) > 1e-6:
            return False
        if k:
            th_s += k * _TWO_PI
        th_g = th_s - self.a
        # i w D + t' E_s = Sp' - G';  i eps D + t'' E_s = Sp'' - G'' + w^2 D - 2 i w t' E_s
        p = np.multiply(D, 1j)
        w, t1, _ = _solve2(p, Es, np.subtract(Spd, Gd))
        w2 = w * w
        r = np.subtract(Spdd, Gdd)
        r += np.multiply(D, w2)
        r -= _coriolis(Es, t1, w)
        e, _, _ = _solve2(p, Es, r)
        bs = _Body(Sp, Spd, Spdd, self.us, Es, th_s, w, e, True)
        bg = _Body(G, Gd, Gdd, self.ug, np.multiply(Es, self.ema), th_g, w, e, True)
        bs.w2 = bg.w2 = w2
        S.bodies[self.s], S.bodies[self.g] = bs, bg
        return True


class _PRP(_Step):
    """Both links slide on guides of known bodies; pin C."""

    def __init__(self, plan, gi):
        super().__init__(plan, gi)
        self.uAC, self.uBC = _c(plan.mid.local(plan.A)), _c(plan.mid.local(plan.B))

    def run(self, S: _Run, sigma: float, i0: int) -> bool:
        N = S.N
        plan = self.plan
        eA, eB = plan.e1, plan.e2
        EA, (CA, _, _) = _guide(eA, S, self.uAC)           # (the guides' points' motion: vel_at, acc_at)
        EB, (CB, _, _) = _guide(eB, S, self.uBC)
        den = np.multiply(np.conjugate(EA), EB).imag
        if np.ndim(den) == 0:
            den = np.full(N, den)
        if not _regular(den, 1.0, N):
            return False
        Dl = np.subtract(CB, CA)
        sA = np.multiply(np.conjugate(Dl), EB).imag
        sA /= den
        C = np.add(CA, np.multiply(EA, sA))
        if np.ndim(C) == 0:
            return False
        KA, KB = S.bodies[eA.g], S.bodies[eB.g]
        VA, VB = S.vel_at(eA.g, C), S.vel_at(eB.g, C)
        qB = np.negative(EB)
        sA1, sB1, _ = _solve2(EA, qB, np.subtract(VB, VA))
        AA, AB = S.acc_at(eA.g, C), S.acc_at(eB.g, C)
        r = np.subtract(AB, AA)
        corA = 0.0
        if KB.rot:
            r += _coriolis(EB, sB1, KB.w)
        if KA.rot:
            corA = _coriolis(EA, sA1, KA.w)
            r -= corA
        sA2, _, _ = _solve2(EA, qB, r)
        C1 = np.add(VA, np.multiply(EA, sA1))
        C2 = np.add(AA, np.multiply(EA, sA2))
        C2 += corA
        for X, con, K, E, u in ((plan.A, eA, KA, EA, self.uAC), (plan.B, eB, KB, EB, self.uBC)):
            S.bodies[X] = _Body(C, C1, C2, u, E, _guide_th(con, S, N), K.w if K.rot else 0.0,
                                K.e if K.rot else 0.0, K.rot)
        return True


class _RPP(_Step):
    """X turns about a known point and slides in the guide carried by Y; Y slides on a
    fixed guide (the Scotch yoke)."""

    def __init__(self, plan, gi, X, Y, ex, ey):
        super().__init__(plan, gi)
        mid: PCon = plan.mid
        self.X, self.Y, self.ey = X, Y, ey
        self.K = ex.j if ex.i == X else ex.i
        self.uK, self.uX1 = _c(ex.local(self.K)), _c(ex.local(X))
        self.thY = 0.0 + ey.a
        self.thX = self.thY + mid.a                   # X == mid.s
        self.EY = cmath.exp(1j * self.thY)
        self.EX = complex(math.cos(self.thX), math.sin(self.thX))
        self.Q0 = 1j * ey.c0 * self.EY                # Y's origin at slide 0
        self.den = (self.EX.conjugate() * self.EY).imag
        self.c0m = mid.c0

    def run(self, S: _Run, sigma: float, i0: int) -> bool:
        N = S.N
        if abs(self.den) < REGULAR:
            return False
        P, Pd, Pdd = S.pt(self.K, self.uK)
        if np.ndim(P) == 0:
            return False
        Ec = self.EX.conjugate()
        oX = np.subtract(P, self.EX * self.uX1)
        t = np.multiply(np.subtract(oX, self.Q0), Ec).imag
        t -= self.c0m
        t /= self.den
        t1 = np.multiply(Pd, Ec).imag
        t1 /= self.den
        t2 = np.multiply(Pdd, Ec).imag
        t2 /= self.den
        EY = self.EY
        S.bodies[self.X] = _Body(P, Pd, Pdd, self.uX1, self.EX, np.full(N, self.thX), 0.0, 0.0, False)
        S.bodies[self.Y] = _Body(np.add(self.Q0, np.multiply(t, EY)), np.multiply(t1, EY), np.multiply(t2, EY),
                                 0j, EY, np.full(N, self.thY), 0.0, 0.0, False)
        return True


def compile_steps(solver) -> list | None:
    """The fast path's steps for a solver's groups.

    Parameters
    ----------
    solver : Solver
        The linkage's kinematic model.

    Returns
    -------
    list or None
        The steps (closed-form dyad solutions on complex numbers), or None when a group is
        not covered.
    """
    steps = []
    for gi, plan in enumerate(solver.plans):
        if not isinstance(plan, DyadPlan):            # a Newton group
            return None
        kind = plan.kind
        A, B, e1, mid, e2 = plan.A, plan.B, plan.e1, plan.mid, plan.e2
        if kind == "RRR":
            steps.append(_RRR(plan, gi))
        elif kind in ("RRP", "PRR"):
            X, Y, ex, ey = (A, B, e1, e2) if kind == "RRP" else (B, A, e2, e1)
            if ey.s != Y:                             # Y carries the guide of a known slider
                return None
            steps.append(_RRP(plan, gi, X, Y, ex, ey))
        elif kind == "RPR":
            steps.append(_RPR(plan, gi))
        elif kind == "PRP":
            if e1.s != A or e2.s != B:
                return None
            steps.append(_PRP(plan, gi))
        elif kind in ("RPP", "PPR"):
            X, Y, ex, ey = (A, B, e1, e2) if kind == "RPP" else (B, A, e2, e1)
            if ey.s != Y or ey.g != 0 or mid.s != X:
                return None
            steps.append(_RPP(plan, gi, X, Y, ex, ey))
        else:
            return None
    return steps


def run(solver, steps, phi: np.ndarray, i0: int):
    """The bodies' poses by the fast path.

    Parameters
    ----------
    solver : Solver
        The linkage's kinematic model.
    steps : list
        :func:`compile_steps`.
    phi : numpy.ndarray
        Crank angles, rad.
    i0 : int
        The index of the least angle (the assembly branch is fixed there).

    Returns
    -------
    _Run or None
        The bodies' poses (points in m as complex numbers, angles in rad), or None when a
        step does not answer (the general solver then does).
    """
    N = len(phi)
    S = _Run(N)
    th = np.subtract(phi, solver.k_alpha0)
    E = np.empty(N, complex)
    Ef = E.view(np.float64).reshape(N, 2)
    np.cos(th, Ef[:, 0])
    np.sin(th, Ef[:, 1])
    pv = solver.pivot
    S.bodies[solver.mech.drive] = _Body(complex(pv[0], pv[1]), 0j, 0j, _c(solver.cp), E, th, 1.0, 0.0, True)
    # (a position where the fast path divides by zero or gets no number fails its tests
    # below and goes to the general solver, which reports it)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        for step in steps:
            plan = step.plan
            sigma = solver.sigma(step.gi) if plan.two_closures else 1.0
            if not step.run(S, sigma, i0):
                return None
    return S


_PAIR = np.dtype((np.float64, (2,)))      # a complex number seen as its x, y


def as_pairs(z, N: int, seen: set) -> np.ndarray:
    """A complex array as an (N, 2) float array.

    Parameters
    ----------
    z : numpy.ndarray or complex
        Points as complex numbers.
    N : int
        The number of positions.
    seen : set
        The ids of the arrays already handed out.

    Returns
    -------
    numpy.ndarray
        (N, 2) of x, y: a view of ``z`` when it is an array not handed out yet, else a copy.
    """
    if type(z) is np.ndarray and z.shape == (N,) and id(z) not in seen:
        seen.add(id(z))
        return z.view(_PAIR)
    out = np.empty(N, complex)
    out[...] = z
    seen.add(id(out))
    return out.view(_PAIR)
