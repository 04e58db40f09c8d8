"""Kinematics of a crank-driven planar linkage, group by group (docs/methods.md §2).

Positions: every class-II group in closed form (:mod:`.dyads`), any other group
(class III and higher) by Newton's method on its loop-closure equations
(:mod:`.newton`), marched continuously over the cycle. Velocities and accelerations:
exact derivatives -- a linear solve per group and position (vectorised), never finite
differences.

Assembly (which closure of each group): ``mech.assembly`` gives rough coordinates of
moving points at crank angle 0 deg; each group takes the closure whose hinted points
are nearest to them and keeps it (a dyad keeps its closure sign, a Newton group is
followed continuously). Without hints a dyad takes its documented default closure
(sigma = +1, see :mod:`.dyads`); a group of class III or higher takes, among the
solutions found from a fixed set of starting guesses, the one whose points have the
largest mean y (the "upper" closure), with a warning suggesting hints. If a group does
not assemble at 0 deg the closure is chosen at the first crank angle where it does.

Singular positions: where a group's velocity equations are singular (its links
collinear: a toggle of the group, or a change point) the run's values are the mean of
those at crank angles +-1e-6 deg, with a warning; :func:`solve` then takes the values at
every ill-conditioned position (a normalised determinant below changepoints.ILL_DET) by
continuity from either side, or null (:mod:`.limits`, docs/methods.md §2.1).
"""
from __future__ import annotations

import math

import numpy as np
from ...lazy import brentq

from ...errors import StageError
from ...messages import Message
from ..mechanism import Mechanism
from ..structure import Group, analyze
from . import newton as nw
from .dyads import DyadPlan, dyad_derivatives
from .result import KinematicsResult
from .state import WORK_ROWS_FROM, PCon, RCon, State, const, zero_pairs

MARCH_STEP = 1.0          # deg, the Newton groups' path over the cycle
CONT_DELTA = 1e-6         # deg, singular positions: mean of +-CONT_DELTA
DYAD_TYPES = ("RRR", "RRP", "PRR", "RPR", "PRP", "RPP", "PPR")


class _NewtonPlan:
    def __init__(self, cons):
        self.cons = cons


class Solver:
    """The kinematic model of one mechanism: groups, closures, paths (cached)."""

    def __init__(self, mech: Mechanism):
        self.mech = mech
        self.struct = analyze(mech)
        if self.struct.idle:
            raise StageError("kinematics", Message("kinematics.fail.idle", links=list(self.struct.idle)))
        self.groups: list[Group] = self.struct.groups
        crank = mech.crank
        self.piv = mech.crank_pivot
        self.pin = mech.crank_pin
        self.cp = np.array(crank.local[self.piv], float)
        cq = np.array(crank.local[self.pin], float)
        self.alpha0 = math.atan2(cq[1] - self.cp[1], cq[0] - self.cp[0])
        self.pivot = np.array(mech.ground[self.piv], float)
        self.pivot2 = self.pivot.reshape(2, 1)             # (2, 1): broadcasts over a (2, N) block
        # 0-d arrays of the crank's constants (a ufunc takes them without a scalar's conversion)
        self.k_alpha0 = const(self.alpha0)
        self.k_cp = (const(self.cp[0]), const(self.cp[1]))
        sizes = [lk.length or 0.0 for lk in mech.links]
        for lk in mech.links:
            sizes += [math.hypot(*u) for u in lk.local.values()]
        g = np.array(list(mech.ground.values()), float)
        if len(g) > 1:
            sizes.append(float(np.ptp(g, axis=0).max()))
        self.L = max(max(sizes), 1e-6)
        self.tol = 1e-9 * self.L
        self.k_mtol = const(-self.tol)
        self.plans = []
        for grp in self.groups:
            cons = [self._con(j) for j in grp.joints]
            if grp.klass == 2 and len(grp.links) == 2 and grp.type in DYAD_TYPES:
                try:
                    self.plans.append(DyadPlan(grp.links[0], grp.links[1], *cons))
                except ValueError as exc:
                    raise StageError("kinematics", f"{grp.describe()}: {exc}") from None
                self.plans[-1].length = self._group_length(grp)
            else:
                if grp.type == "PPP":
                    raise StageError("kinematics", Message("kinematics.fail.ppp", **grp.message_params()))
                self.plans.append(_NewtonPlan(cons))
            self.plans[-1].cons = cons
        self._sigma: dict[int, float] = {}
        self._path: dict[int, tuple] = {}
        self.warnings: list[str] = []

    # ------------------------------------------------------------------ model
    def _group_length(self, grp: Group) -> float:
        """The group's length: the largest distance between two points of one of its links
        (the linkage's size where its links have one point each); the scale of its
        normalised determinant (see dyads._inverse)."""
        best = 0.0
        for b in grp.links:
            pts = np.array(list(self.mech.link(b).local.values()), float).reshape(-1, 2)
            if len(pts) > 1:
                best = max(best, float(np.max(np.hypot(*(pts[:, None, :] - pts[None, :, :]).T))))
        return best if best > 0.0 else self.L

    def outputs(self) -> tuple:
        """What the result holds (:func:`_outputs`: the ground points, the moving ones, ...)."""
        return _outputs(self)

    def local(self, b: int, p: str):
        if b == 0:
            return self.mech.ground[p]
        return self.mech.link(b).local[p]

    def _con(self, j):
        if j.kind == "R":
            return RCon(j.a, j.b, self.local(j.a, j.point), self.local(j.b, j.point), j.point, j)
        s = j.slider
        g = j.a if j.b == s else j.b
        gd = self.mech.link(s).guide
        a = math.radians(gd.angle)
        if g == 0:
            c0 = -math.sin(a) * gd.point[0] + math.cos(a) * gd.point[1]
        else:
            c0 = gd.offset
        return PCon(s, g, a, c0, j)

    def _crank(self, st: State, phi: np.ndarray) -> None:
        """The crank's pose and derivatives: th = phi - alpha0, o = pivot - R u (u its
        pivot's local coordinates), o' = -J R u, o'' = R u; the pairs as (2, N) blocks
        (their transposes, see state.pairs)."""
        N = len(phi)
        th = np.subtract(phi, self.k_alpha0)
        CS = np.empty((2, N))
        c, s = CS[0], CS[1]
        np.cos(th, c)
        np.sin(th, s)
        u0, u1 = self.k_cp
        R = np.multiply(CS, u0)                 # (c u0, s u0)
        T = np.multiply(CS, u1)                 # (c u1, s u1)
        np.subtract(R[0], T[1], R[0])           # c u0 - s u1
        np.add(R[1], T[0], R[1])                # s u0 + c u1
        O1 = T                                  # -J R u: (R u_y, -R u_x)
        np.copyto(O1[0], R[1])
        np.negative(R[0], O1[1])
        d = self.mech.drive
        st.set_pose(d, np.subtract(self.pivot2, R).T, th, (c, s))
        one = np.empty(N)
        one.fill(1.0)
        st.set_d1(d, O1.T, one)
        st.set_d2(d, R.T, np.zeros(N))

    # ------------------------------------------------------------------ run
    def run(self, phi: np.ndarray, upto: int | None = None, derivs: bool = True, strict: bool = True,
            fallback: bool = True, dets: bool = False) -> State:
        """Poses (and derivatives) of every body at crank angles ``phi`` (rad); ``dets``:
        each group's normalised determinant in ``st.gdet`` too (the change points)."""
        phi = np.asarray(phi, float).reshape(-1)
        N = len(phi)
        st = State(N)
        st.margins = {}
        st.sing = {}
        st.gdet = {}     # group -> normalised signed determinant of its velocity equations
        self._crank(st, phi)
        upto = len(self.groups) if upto is None else upto
        for gi in range(upto):
            plan = self.plans[gi]
            if isinstance(plan, DyadPlan):
                sigma = self.sigma(gi) if plan.two_closures else 1.0
                m = plan.solve(st, sigma)
            else:
                m = self._newton_vector(gi, st, phi)
            st.margins[gi] = m
            if strict and np.count_nonzero(np.greater_equal(m, self.k_mtol)) != m.size:
                raise self._assembly_error(gi, np.degrees(phi[~(m >= -self.tol)]))
            if derivs:
                if isinstance(plan, DyadPlan):
                    st.sing[gi] = dyad_derivatives(plan, st, dets)
                else:
                    st.sing[gi] = nw.derivatives(plan.cons, self.groups[gi].links, st)
                if dets:
                    st.gdet[gi] = st.last_det
        if derivs and fallback and st.sing:
            self._continuity(st, phi, upto)
        return st

    def _continuity(self, st: State, phi: np.ndarray, upto: int) -> None:
        sing = None
        for gi, s in st.sing.items():
            if np.count_nonzero(s):
                sing = s.copy() if sing is None else np.logical_or(sing, s, out=sing)
                # to 1e-4 deg (the message shows 6 digits), 360 as 0: a course grid starting
                # at an extreme position 5e-7 deg off 0 names the same angle as a grid from 0
                ang = np.round(np.degrees(phi[s]) % 360, 4) % 360 + 0.0
                params = self.groups[gi].message_params()
                # one warning a group: the angles of every run of this solver (the course's
                # positions, the diagrams' grid, the extra positions) joined, not one per run
                old = next((k for k, w in enumerate(self.warnings) if isinstance(w, Message) and w.code ==
                            "kinematics.singular_continuity" and w.params.get("group") == params.get("group")), None)
                if old is not None:
                    ang = np.concatenate([ang, self.warnings[old].params["angles"]])
                msg = Message("kinematics.singular_continuity", **params, angles=np.unique(ang)[:8], delta=CONT_DELTA)
                if old is None:
                    self.warnings.append(msg)
                else:
                    self.warnings[old] = msg
        if sing is None:
            return
        idx = np.nonzero(sing)[0]
        h = math.radians(CONT_DELTA)
        sp = self.run(phi[idx] + h, upto=upto, strict=False, fallback=False)
        sm = self.run(phi[idx] - h, upto=upto, strict=False, fallback=False)
        for b in list(st.o1):
            if b == 0:
                continue
            for cur, plus, minus in ((st.o1, sp.o1, sm.o1), (st.th1, sp.th1, sm.th1),
                                     (st.o2, sp.o2, sm.o2), (st.th2, sp.th2, sm.th2)):
                arr = cur[b].copy()
                arr[idx] = 0.5 * (plus[b] + minus[b])
                cur[b] = arr
        st.derivatives_changed()         # the points' derivatives change with the bodies'
        st.singular = sing

    # ------------------------------------------------------------------ closures
    def _hints(self, gi: int) -> list[tuple[int, str, np.ndarray]]:
        out = []
        for b in self.groups[gi].links:
            for p, u in self.mech.link(b).local.items():
                if p in self.mech.assembly:
                    out.append((b, p, np.array(self.mech.assembly[p], float)))
        return out

    def _ref_angle(self, gi: int) -> float:
        """Crank angle (rad) where the closure of group gi is chosen: 0, or the first
        angle on a 0.25-deg scan where the group assembles."""
        st = self.run(np.array([0.0]), upto=gi + 1, derivs=False, strict=False)
        if all(st.margins[k][0] >= -self.tol for k in range(gi + 1)):
            return 0.0
        grid = np.radians(np.arange(0.0, 360.0, 0.25))
        st = self.run(grid, upto=gi + 1, derivs=False, strict=False)
        ok = np.ones(len(grid), bool)
        for k in range(gi + 1):
            ok &= st.margins[k] >= -self.tol
        if not ok.any():
            raise self._assembly_error(gi, np.array([0.0]), whole=True)
        ang = float(grid[np.argmax(ok)])
        self.warnings.append(Message("kinematics.closure_not_at_zero", **self.groups[gi].message_params(),
                                     phi=math.degrees(ang)))
        return ang

    def sigma(self, gi: int) -> float:
        if gi in self._sigma:
            return self._sigma[gi]
        self._sigma[gi] = 1.0          # provisional (used by the scans below)
        hints = self._hints(gi)
        if not hints:
            return 1.0
        ang = self._ref_angle(gi)
        plan = self.plans[gi]
        best, best_d = 1.0, None
        scores = {}
        for sg in (1.0, -1.0):
            st = self.run(np.array([ang]), upto=gi, derivs=False, strict=False)
            plan.solve(st, sg)
            d = sum(float(np.sum((st.point(b, self.mech.link(b).local[p])[0] - h) ** 2)) for b, p, h in hints)
            scores[sg] = d
            # a tie (the hints as near to both closures) keeps +1; the margin scales with the
            # linkage (squared lengths): an absolute 1e-15 m^2 ignored every hint of a linkage
            # smaller than about 0.1 um and always took +1
            if best_d is None or d < best_d - 1e-15 * self.L * self.L:
                best, best_d = sg, d
        self._sigma[gi] = best
        return best

    # ------------------------------------------------------------------ Newton groups
    def _newton_start(self, gi: int, st1: State) -> np.ndarray:
        """Poses of group gi at one position (st1, N = 1): from the hints, else the
        'upper' solution among those found from fixed starting guesses."""
        grp = self.groups[gi]
        cons = self.plans[gi].cons
        links = grp.links
        hints = self._hints(gi)
        known_pts: dict[str, np.ndarray] = {}
        for c in cons:
            if isinstance(c, RCon):
                for b in (c.i, c.j):
                    if b not in links:
                        known_pts[c.point] = st1.point(b, c.local(b))[0]
        est = dict(known_pts)
        for b, p, h in hints:
            est.setdefault(p, h)
        centre = np.mean(list(est.values()), axis=0) if est else self.pivot
        q0 = []
        for b in links:
            loc = self.mech.link(b).local
            pts = [(p, loc[p]) for p in loc if p in est]
            if len(pts) >= 2:
                (p1, u1), (p2, u2) = pts[0], pts[1]
                v = est[p2] - est[p1]
                th = math.atan2(v[1], v[0]) - math.atan2(u2[1] - u1[1], u2[0] - u1[0])
            else:
                th = 0.0
            if pts:
                p1, u1 = pts[0]
                c, s = math.cos(th), math.sin(th)
                o = est[p1] - np.array([c * u1[0] - s * u1[1], s * u1[0] + c * u1[1]])
            else:
                o = centre
            q0 += [o[0], o[1], th]
        q0 = np.array([q0])
        if hints:
            q, conv = nw.newton(cons, links, st1.take(np.array([0])), q0, self.L)
            if conv[0]:
                return q[0]
        # multi-start
        rng = np.random.default_rng(12345)
        S = 400
        stm = st1.take(np.zeros(S, int))
        Q = np.repeat(q0, S, axis=0)
        Q[:, 2::3] = rng.uniform(-np.pi, np.pi, (S, len(links)))
        Q[:, 0::3] += rng.normal(0, 0.5 * self.L, (S, len(links)))
        Q[:, 1::3] += rng.normal(0, 0.5 * self.L, (S, len(links)))
        q, conv = nw.newton(cons, links, stm, Q, self.L, maxit=60)
        if not conv.any():
            raise StageError("kinematics", Message("kinematics.fail.not_assembled", **grp.message_params(),
                                                   phi=math.degrees(float(self._phi_of(st1)))),
                             position=float(math.degrees(self._phi_of(st1))))
        sols = q[conv]
        nw.set_q(stm, links, q)
        pts = []
        for b in links:
            for p, u in self.mech.link(b).local.items():
                pts.append((b, p, np.asarray(u)))
        P = np.stack([stm.point(b, u)[conv] for b, p, u in pts], axis=1)   # (S', npts, 2)
        if hints:
            H = {p: h for b, p, h in hints}
            score = np.zeros(len(sols))
            for k, (b, p, u) in enumerate(pts):
                if p in H:
                    score += np.sum((P[:, k] - H[p]) ** 2, axis=1)
            k = int(np.argmin(score))
        else:
            my = P[:, :, 1].mean(axis=1)
            mx = P[:, :, 0].mean(axis=1)
            key = np.round(my / self.L, 9) * 1e3 + mx / self.L * 1e-6
            k = int(np.argmax(key))
            self.warnings.append(Message("kinematics.no_assembly_hints", **grp.message_params()))
        return sols[k]

    def _phi_of(self, st: State) -> float:
        d = self.mech.drive
        return float(st.th[d][0] + self.alpha0)

    def path(self, gi: int):
        """Group gi's poses and their derivatives on a 1-deg grid over one turn,
        marched continuously from crank angle 0 (Newton with a second-order predictor
        and step halving)."""
        if gi in self._path:
            return self._path[gi]
        grp = self.groups[gi]
        cons = self.plans[gi].cons
        links = grp.links
        h = math.radians(MARCH_STEP)
        K = int(round(360.0 / MARCH_STEP))
        grid = np.arange(K + 1) * h
        st = self.run(grid, upto=gi, derivs=True, strict=True)
        q = self._newton_start(gi, st.take(np.array([0])))

        def at(phi_val, q_guess):
            s1 = self.run(np.array([phi_val]), upto=gi, derivs=True, strict=True)
            qq, conv = nw.newton(cons, links, s1, q_guess[None, :], self.L, maxit=12)
            if not conv[0]:
                return None, None, None
            nw.derivatives(cons, links, s1)
            return qq[0], self._qd(s1, links, 1)[0], self._qd(s1, links, 2)[0]

        def march(q_start, sign):
            qs, q1s = [q_start], []
            s0 = self.run(np.array([0.0]), upto=gi, derivs=True, strict=True)
            nw.set_q(s0, links, q_start[None, :])
            nw.derivatives(cons, links, s0)
            qc, q1, q2 = q_start, self._qd(s0, links, 1)[0], self._qd(s0, links, 2)[0]
            q1s.append(q1)
            phi_c = 0.0
            for k in range(1, K + 1):
                target = sign * k * h
                while True:
                    step = target - phi_c
                    ok = False
                    while abs(step) > 1e-9:
                        guess = qc + q1 * step + 0.5 * q2 * step ** 2
                        qn, q1n, q2n = at(phi_c + step, guess)
                        if qn is not None and np.max(np.abs(qn[2::3] - guess[2::3])) < 0.3:
                            ok = True
                            break
                        step *= 0.5
                    if not ok:
                        return qs, q1s, phi_c
                    qc, q1, q2, phi_c = qn, q1n, q2n, phi_c + step
                    if abs(phi_c - target) < 1e-12:
                        break
                qs.append(qc)
                q1s.append(q1)
            return qs, q1s, None

        qs, q1s, fail = march(q, +1.0)
        if fail is not None:
            qb, _, fail_b = march(q, -1.0)
            a = math.degrees(fail) % 360
            b = (math.degrees(fail_b) % 360) if fail_b is not None else a
            raise StageError("kinematics", Message("kinematics.fail.limit_position", **grp.message_params(), a=a, b=b),
                             position=a)
        self._path[gi] = (grid, np.array(qs), np.array(q1s))
        return self._path[gi]

    @staticmethod
    def _qd(st: State, links, order: int) -> np.ndarray:
        oo = st.o1 if order == 1 else st.o2
        tt = st.th1 if order == 1 else st.th2
        return np.concatenate([np.concatenate([oo[b], tt[b][:, None]], axis=1) for b in links], axis=1)

    def _newton_vector(self, gi: int, st: State, phi: np.ndarray) -> np.ndarray:
        grid, Q, Q1 = self.path(gi)
        h = grid[1] - grid[0]
        ph = np.mod(phi, 2 * np.pi)
        k = np.minimum((ph / h).astype(int), len(grid) - 2)
        t = ((ph - grid[k]) / h)[:, None]
        h00 = 2 * t ** 3 - 3 * t ** 2 + 1
        h10 = t ** 3 - 2 * t ** 2 + t
        h01 = -2 * t ** 3 + 3 * t ** 2
        h11 = t ** 3 - t ** 2
        q0 = h00 * Q[k] + h10 * h * Q1[k] + h01 * Q[k + 1] + h11 * h * Q1[k + 1]
        links = self.groups[gi].links
        q, conv = nw.newton(self.plans[gi].cons, links, st, q0, self.L, maxit=20)
        drift = np.max(np.abs(q[:, 2::3] - q0[:, 2::3]), axis=1)
        conv &= drift < 0.3
        return np.where(conv, self.L, -self.L)

    # ------------------------------------------------------------------ errors
    def _margin_at(self, gi: int, phi_deg: float) -> float:
        st = self.run(np.radians([phi_deg]), upto=gi + 1, derivs=False, strict=False)
        return float(st.margins[gi][0]) + self.tol

    def bad_intervals(self, gi: int, step: float = 0.25) -> list[tuple[float, float]]:
        """Crank-angle intervals (deg) where dyad gi does not assemble, edges to 1e-10 deg."""
        grid = np.arange(0.0, 360.0, step)
        st = self.run(np.radians(grid), upto=gi + 1, derivs=False, strict=False)
        m = st.margins[gi]
        ok_prev = np.ones(len(grid), bool)
        for k in range(gi):
            ok_prev &= st.margins[k] >= -self.tol
        bad = (m < -self.tol) & ok_prev
        if not bad.any():
            return []
        if bad.all():
            return [(0.0, 360.0)]
        # rotate so that the scan starts at a good point
        start = int(np.argmin(bad))
        order = (np.arange(len(grid)) + start) % len(grid)
        ang = grid[order] + np.where(order < start, 360.0, 0.0)
        b = bad[order]
        out = []
        k = 0
        n = len(grid)
        while k < n:
            if b[k]:
                j = k
                while j + 1 < n and b[j + 1]:
                    j += 1
                lo_a, lo_b = ang[k - 1], ang[k]
                hi_a = ang[j]
                hi_b = ang[j + 1] if j + 1 < n else ang[0] + 360.0
                f = lambda x: self._margin_at(gi, x % 360.0)
                try:
                    e1 = brentq(f, lo_a, lo_b, xtol=1e-11)
                except ValueError:
                    e1 = lo_b
                try:
                    e2 = brentq(f, hi_a, hi_b, xtol=1e-11)
                except ValueError:
                    e2 = hi_a
                out.append((e1 % 360.0, e2 % 360.0))
                k = j + 1
            else:
                k += 1
        return out

    def _reason(self, gi: int, phi_deg: float) -> Message:
        plan = self.plans[gi]
        if not isinstance(plan, DyadPlan):
            return Message("kinematics.reason.no_solution")
        st = self.run(np.radians([phi_deg]), upto=gi, derivs=False, strict=False)
        kind = plan.kind
        e1, mid, e2 = plan.e1, plan.mid, plan.e2
        nm = lambda b: self.mech.link(b).name
        A, B = plan.A, plan.B
        if kind == "RRR":
            P1 = st.point(e1.j if e1.i == A else e1.i, e1.local(e1.j if e1.i == A else e1.i))[0]
            P3 = st.point(e2.j if e2.i == B else e2.i, e2.local(e2.j if e2.i == B else e2.i))[0]
            d = float(np.hypot(*(P3 - P1)))
            lA = float(np.hypot(*(np.asarray(mid.local(A)) - e1.local(A))))
            lB = float(np.hypot(*(np.asarray(mid.local(B)) - e2.local(B))))
            pa, pb, pc = e1.point, e2.point, mid.point
            if d > lA + lB:
                return Message("kinematics.reason.rrr_far", pa=pa, pb=pb, pc=pc, d=d, la=lA, lb=lB,
                               link_a=nm(A), link_b=nm(B))
            return Message("kinematics.reason.rrr_near", pa=pa, pb=pb, pc=pc, d=d, la=lA, lb=lB)
        if kind in ("RRP", "PRR"):
            X = A if kind == "RRP" else B
            ext = e1 if X == A else e2
            lX = float(np.hypot(*(np.asarray(mid.local(X)) - ext.local(X))))
            return Message("kinematics.reason.rrp_short", p=ext.point, q=mid.point, l=lX, link=nm(X))
        if kind == "RPR":
            return Message("kinematics.reason.rpr_offset", s=nm(mid.s), g=nm(mid.g),
                           pivot=e1.point if mid.s == A else e2.point, other=e2.point if mid.s == A else e1.point)
        return Message("kinematics.reason.parallel_guides")

    def _assembly_error(self, gi: int, bad_deg: np.ndarray, whole: bool = False) -> StageError:
        grp = self.groups[gi]
        pos = float(np.mod(bad_deg[0], 360.0))
        if whole:
            return StageError("kinematics", Message("kinematics.fail.never", **grp.message_params()), position=pos,
                              never_assembles=[self.mech.link(i).name for i in grp.links_sorted])
        try:
            iv = self.bad_intervals(gi)
        except StageError:
            iv = []
        if not iv:
            lo, hi = float(np.min(np.mod(bad_deg, 360))), float(np.max(np.mod(bad_deg, 360)))
            iv = [(lo, hi)]
        # why, in the middle of each interval: the reasons differ from one to another (a
        # four-bar's group reaches too far about one dead centre, folds too near about the other)
        mids = [(a + ((b - a) % 360.0) / 2) % 360.0 for a, b in iv]
        reasons = [self._reason(gi, m) for m in mids]
        if len({str(r) for r in reasons}) == 1:          # one reason for all (a slider's rod too short)
            reason = reasons[0]
        else:                                            # each interval's, at the angle it names
            reason = Message("kinematics.reason.each", items=[Message("kinematics.reason.at", phi=m, reason=r)
                                                              for m, r in zip(mids, reasons)])
        ivs = [[float(a), float(b)] for a, b in iv]      # degrees; each language formats them
        never = None
        if sum((b - a) % 360.0 or (360.0 if b > a else 0.0) for a, b in iv) >= 360.0 - 1e-6:
            # no crank angle at all: the dimensions are impossible, an invalid task
            never = [self.mech.link(i).name for i in grp.links_sorted]
        return StageError("kinematics", Message("kinematics.fail.intervals", **grp.message_params(), intervals=ivs,
                                                reason=reason), position=pos, never_assembles=never)


# ---------------------------------------------------------------------- cache
def get_solver(mech: Mechanism) -> Solver:
    """The cached kinematic model of a mechanism.

    Parameters
    ----------
    mech : Mechanism
        The mechanism (not to be changed after the first solve).

    Returns
    -------
    Solver
        Its closures and paths, computed once per Mechanism object (kept in its instance
        ``__dict__``).
    """
    s = mech.__dict__.get("_kinematics_solver")
    if s is None:
        s = Solver(mech)
        mech.__dict__["_kinematics_solver"] = s
    return s


def _unwrap(p: np.ndarray, inplace: bool = False) -> np.ndarray:
    """np.unwrap(p) of a 1-D array (period 2 pi), the same operations without its
    generic-axis overhead (most of the fixed cost of a small solve); ``inplace``: into
    p itself (p[0] stays, every other value is replaced)."""
    up = p if inplace else p.copy()
    if len(p) < 2:
        return up
    dd = p[1:] - p[:-1]
    big = np.abs(dd) >= math.pi
    if not big.any():                      # no jump: the correction is zero everywhere
        np.add(p[1:], 0.0, out=up[1:])
        return up
    ddmod = np.mod(dd + math.pi, 2.0 * math.pi) - math.pi
    ddmod[(ddmod == -math.pi) & (dd > 0)] = math.pi
    corr = ddmod - dd
    corr[~big] = 0.0
    np.add(p[1:], np.cumsum(corr), out=up[1:])
    return up


_PI = const(math.pi)


def _unwrapped(ths: list, consts: list, N: int, order: np.ndarray | None, seen: set) -> list:
    """The links' angles (as their poses gave them, in link order) unwrapped along increasing
    crank angle (``order``: argsort, None if sorted). Few positions in order: as the rows of
    one block, their differences taken along the block in one call (those across two rows
    not counted), a row unwrapped only if it jumps. Else each in place where it is the
    pose's own array; ``consts``: a link's one angle (a slider on a fixed guide), which
    does not jump, or None."""
    if order is None and 2 <= N < WORK_ROWS_FROM:
        TH = np.array(ths, float)
        flat = TH.reshape(-1)
        dd = np.subtract(flat[1:], flat[:-1])
        dd[N - 1::N] = 0.0
        if np.count_nonzero(np.greater_equal(np.abs(dd, dd), _PI)):
            for row in TH:
                _unwrap(row, inplace=True)
        return list(TH)
    out = []
    for t, v in zip(ths, consts):
        own = _fresh(t, N, seen)            # the pose's own array: unwrapped in place
        if own and v is not None and math.isfinite(v) and math.copysign(1.0, v) > 0:
            out.append(t)                   # one finite value, not -0.0: already unwrapped
        else:
            out.append(_unwrap_sorted(t if own else np.asarray(t, float), order, inplace=own))
    return out


def _unwrap_sorted(th: np.ndarray, order: np.ndarray | None, inplace: bool = False) -> np.ndarray:
    """th unwrapped along increasing crank angle (order: argsort, None if sorted)."""
    if order is None:
        return _unwrap(th, inplace)
    out = th if inplace else th.copy()
    out[order] = _unwrap(th[order])
    return out


def _fresh(v, N: int, seen: set) -> bool:
    """v is an (N,) float array of its own (not a view, not given to another output):
    it may be handed out (or changed in place) as it is."""
    if (type(v) is np.ndarray and v.base is None and id(v) not in seen and v.shape == (N,)
            and v.dtype.char == "d" and v.flags.writeable):
        seen.add(id(v))
        return True
    return False


def _vector(v, N: int, seen: set) -> np.ndarray:
    """A float array of shape (N,) of its own holding v (an array of that shape or a
    scalar): v itself when it is such an array not handed out yet, else a copy."""
    if _fresh(v, N, seen):
        return v
    out = np.empty(N)
    out[:] = v
    return out


def _outputs(solver: Solver) -> tuple:
    """What the result holds, taken once per mechanism: the ground points (name,
    x, y), the points fixed on links (name, link index, local coordinates), the order in
    which to take those body by body ((index into the points, whether it is its body's
    last)), the report order of the points and the links (name, index)."""
    hit = solver.__dict__.get("_outputs")
    if hit is not None:
        return hit
    mech = solver.mech
    ground = [(p, float(xy[0]), float(xy[1])) for p, xy in mech.ground.items()]
    seen = set(mech.ground)
    moving = []
    for lk in mech.links:
        for p, u in lk.local.items():
            if p not in seen:
                seen.add(p)
                moving.append((p, lk.index, u))
    for i, s in mech.com_names.items():
        if s in seen and s not in mech.link(i).local:
            continue
        if s not in seen:
            seen.add(s)
            moving.append((s, i, mech.link(i).com))
        else:                      # a centre of mass named as a point of its own link
            moving = [(q, b, u) if q != s else (s, i, mech.link(i).com) for q, b, u in moving]
    names = mech.all_points()
    links = [(lk.name, lk.index) for lk in mech.links]
    # many positions: the points taken body by body, each body's origin released after
    # its last point (the result's order stays that of ``moving``)
    by_body = sorted(range(len(moving)), key=lambda k: moving[k][1])
    done = [k == len(by_body) - 1 or moving[by_body[k + 1]][1] != moving[j][1] for k, j in enumerate(by_body)]
    hit = solver.__dict__["_outputs"] = (ground, moving, list(zip(by_body, done)), names, links)
    return hit


def solve(mech: Mechanism, phi_deg, omega1=1.0, eps1=0.0) -> KinematicsResult:
    """The kinematics at crank angles.

    Parameters
    ----------
    mech : Mechanism
        The mechanism (lengths in m).
    phi_deg : array_like
        Crank angles, deg: the direction of the vector from the crank's ground pivot to its
        pin, from +x ccw.
    omega1 : float or array_like
        The crank's angular velocity, rad/s (ccw positive; scalar or (N,)).
    eps1 : float or array_like
        Its angular acceleration, rad/s^2.

    Returns
    -------
    KinematicsResult
        The positions (m), velocities (m/s), accelerations (m/s^2) of the points, the
        links' angles (rad), angular velocities and accelerations, and the analogues d1, d2
        (m/rad, m/rad^2) and a1, a2; positions next to a change point of the linkage are
        marked (:mod:`.changepoints`).

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: the method of closed vector contours
    group by group (Assur groups); docs/methods.md §2.
    """
    cpm = _changepoints()
    res = _solve(mech, phi_deg, omega1, eps1)
    solver = get_solver(mech)
    cps = cpm.change_points(solver)
    if cps:
        for cp in cps:
            msg = cpm.warning(cp, solver.groups[cp.group])
            if msg not in solver.warnings:
                solver.warnings.append(msg)
        res.warnings = list(dict.fromkeys(solver.warnings))
        near = cpm.distance_deg(res.phi, [c.phi for c in cps]) <= cpm.NEAR_DEG
        if near.any():
            res.near = near
            res.undefined = _blown_up(mech, solver, res, near)
    if res.det_min is not None:
        # ill-conditioned positions (the fast path answers none): by continuity, or null
        from .limits import by_continuity
        by_continuity(mech, solver, res, res.det_min, res.det_group, _solve)
    return res


def solve_raw(mech: Mechanism, phi_deg, omega1=1.0, eps1=0.0) -> KinematicsResult:
    """:func:`solve` without its marks.

    Parameters
    ----------
    mech : Mechanism
        The mechanism.
    phi_deg : array_like
        Crank angles, deg.
    omega1 : float or array_like
        rad/s.
    eps1 : float or array_like
        rad/s^2.

    Returns
    -------
    KinematicsResult
        The exact derivatives as the groups give them at every position, ill-conditioned or
        not (no change points, no limits by continuity, no nulls): for a search along the
        curves (the extreme positions: roots of an analogue) that must see the solver's own
        smooth values on either side of a singular point.
    """
    return _solve(mech, phi_deg, omega1, eps1)


_CPM = None


def _changepoints():
    """The module :mod:`.changepoints`, imported on the first solve (not at every call)."""
    global _CPM
    if _CPM is None:
        from . import changepoints
        _CPM = changepoints
    return _CPM


def _blown_up(mech: Mechanism, solver: Solver, res: KinematicsResult, near: np.ndarray) -> dict[str, np.ndarray]:
    """Masks of the values without a finite limit at positions next to a change point:
    keys 'v:P', 'a:P' (point P), 'omega:L', 'epsilon:L' (link L). A value is so when its
    analogue (d/dphi, d2/dphi2) exceeds BLOWUP times its largest magnitude over the rest
    of the cycle (sampled away from every change point)."""
    cpm = _changepoints()
    ref = solver.__dict__.get("_cp_reference")
    if ref is None:
        grid = np.arange(0.0, 360.0, 0.5)
        grid = grid[cpm.distance_deg(grid, [c.phi for c in cpm.change_points(solver)]) > cpm.NEAR_DEG]
        k = _solve(mech, grid, 1.0, 0.0)
        ref = ({p: (float(np.max(np.hypot(*k.d1[p].T))), float(np.max(np.hypot(*k.d2[p].T)))) for p in k.points},
               {lk: (float(np.max(np.abs(k.a1[lk]))), float(np.max(np.abs(k.a2[lk])))) for lk in k.links})
        solver.__dict__["_cp_reference"] = ref
    pts, lks = ref
    floor_p = 1e-6 * max([max(v) for v in pts.values()] + [1e-300])
    floor_l = 1e-6 * max([max(v) for v in lks.values()] + [1e-300])
    out: dict[str, np.ndarray] = {}
    for p in res.points:
        if p not in pts:
            continue
        m1, m2 = pts[p]
        v_bad = near & ~(np.hypot(*res.d1[p].T) <= cpm.BLOWUP * m1 + floor_p)
        a_bad = near & (v_bad | ~(np.hypot(*res.d2[p].T) <= cpm.BLOWUP * m2 + floor_p))
        out[f"v:{p}"], out[f"a:{p}"] = v_bad, a_bad
    for lk in res.links:
        m1, m2 = lks[lk]
        w_bad = near & ~(np.abs(res.a1[lk]) <= cpm.BLOWUP * m1 + floor_l)
        e_bad = near & (w_bad | ~(np.abs(res.a2[lk]) <= cpm.BLOWUP * m2 + floor_l))
        out[f"omega:{lk}"], out[f"epsilon:{lk}"] = w_bad, e_bad
    return {k: v for k, v in out.items() if v.any()}


_NO_STEPS = object()


def _fast_steps(solver: Solver):
    """The fast path's steps for the solver's groups (made once), None if it does not cover them."""
    steps = solver.__dict__.get("_fast_steps", _NO_STEPS)
    if steps is _NO_STEPS:
        from . import fast
        steps = solver.__dict__["_fast_steps"] = fast.compile_steps(solver)
    return steps


FAST = True       # the complex-number fast path of a regular call (off: the general solver only, for the tests)


def _solve(mech: Mechanism, phi_deg, omega1=1.0, eps1=0.0) -> KinematicsResult:
    solver = get_solver(mech)
    phi_deg = np.asarray(phi_deg, float).reshape(-1)     # (a scalar: shape (1,))
    N = len(phi_deg)
    order = None if N < 2 or np.count_nonzero(np.greater_equal(phi_deg[1:], phi_deg[:-1])) == N - 1 \
        else np.argsort(phi_deg, kind="stable")
    steps = _fast_steps(solver) if N else None
    if steps is not None and FAST:
        from . import fast
        S = fast.run(solver, steps, np.radians(phi_deg), 0 if order is None else int(order[0]))
        if S is not None:
            return _fast_result(mech, solver, S, phi_deg, order, omega1, eps1)
    ground, moving, done, names, links = _outputs(solver)
    st = solver.run(np.radians(phi_deg), dets=True)
    from .limits import dets_of
    s_min, s_group = dets_of(solver, st)
    st.margins = st.sing = st.gdet = None     # (held memory only)
    seen: set = set()
    bs = range(1, mech.n + 1)
    for b, t in zip(bs, _unwrapped([st.th[b] for b in bs], [st.const_th.get(b) for b in bs], N, order, seen)):
        if t is not st.th[b]:
            st.unwrap(b, t)
    pos, d1, d2 = {}, {}, {}
    _ground_points(ground, N, pos, d1, d2)
    if N < WORK_ROWS_FROM:
        for p, b, u in moving:
            pos[p], d1[p], d2[p] = st.point_d(b, u)
    else:                                  # many positions: hold less memory
        got = [None] * len(moving)
        for k, last in done:
            p, b, u = moving[k]
            got[k] = st.point_d(b, u)
            if last:                       # no point of body b is left: its origin goes
                st.release(b)
        for (p, _, _), g in zip(moving, got):
            pos[p], d1[p], d2[p] = g
    angle, a1, a2 = {}, {}, {}
    for name, b in links:
        angle[name] = st.th[b]
        a1[name] = _vector(st.th1[b], N, seen)
        a2[name] = _vector(st.th2[b], N, seen)
    res = _result(solver, phi_deg, omega1, eps1, pos, d1, d2, angle, a1, a2, names, links, st.singular)
    res.det_min, res.det_group = s_min, s_group
    return res


def _ground_points(ground, N: int, pos: dict, d1: dict, d2: dict) -> None:
    for p, x, y in ground:
        g = np.empty((2, N))
        g[0].fill(x)
        g[1].fill(y)
        pos[p] = g.T
        d1[p] = zero_pairs(N)
        d2[p] = zero_pairs(N)


def _fast_result(mech: Mechanism, solver: Solver, S, phi_deg: np.ndarray, order, omega1, eps1) -> KinematicsResult:
    """The result of a call the fast path answered (``S``: its bodies' poses)."""
    from .fast import as_pairs
    ground, moving, done, names, links = _outputs(solver)
    N = len(phi_deg)
    bodies = S.bodies
    seen: set = set()
    bs = range(1, mech.n + 1)
    th = dict(zip(bs, _unwrapped([bodies[b].th for b in bs],
                                 [float(bodies[b].th[0]) if bodies[b].const else None for b in bs], N, order, seen)))
    pos, d1, d2 = {}, {}, {}
    _ground_points(ground, N, pos, d1, d2)
    for p, b, u in _moving_complex(solver, moving):
        P, P1, P2 = S.pt(b, u)
        pos[p], d1[p], d2[p] = as_pairs(P, N, seen), as_pairs(P1, N, seen), as_pairs(P2, N, seen)
    angle, a1, a2 = {}, {}, {}
    for name, b in links:
        angle[name] = th[b]
        a1[name] = _vector(bodies[b].w, N, seen)
        a2[name] = _vector(bodies[b].e, N, seen)
    return _result(solver, phi_deg, omega1, eps1, pos, d1, d2, angle, a1, a2, names, links, None)


def _moving_complex(solver: Solver, moving) -> list:
    """The moving points (name, body, local coordinates as a complex number), made once."""
    hit = solver.__dict__.get("_moving_complex")
    if hit is None:
        hit = solver.__dict__["_moving_complex"] = [(p, b, complex(float(u[0]), float(u[1]))) for p, b, u in moving]
    return hit


def _result(solver, phi_deg, omega1, eps1, pos, d1, d2, angle, a1, a2, names, links, singular) -> KinematicsResult:
    N = len(phi_deg)
    w = np.asarray(omega1, float)
    e = np.asarray(eps1, float)
    for nm_, v in (("omega1", w), ("eps1", e)):
        if v.ndim and v.shape != (N,):
            raise ValueError(f"{nm_} must be a scalar or an array of shape ({N},), got {v.shape}")
    warnings = list(dict.fromkeys(solver.warnings))
    return KinematicsResult(phi=phi_deg, omega1=omega1 if w.ndim == 0 else w, eps1=eps1 if e.ndim == 0 else e,
                            pos=pos, d1=d1, d2=d2, angle=angle, a1=a1, a2=a2, warnings=warnings,
                            points=[p for p in names if p in pos], links=[nm for nm, _ in links],
                            singular=singular, pins=pins_of(solver.mech))


def pins_of(mech: Mechanism) -> dict[str, str | None]:
    """The pairs of links joined directly.

    Parameters
    ----------
    mech : Mechanism
        The mechanism.

    Returns
    -------
    dict
        "i-j" (i < j, 0 the frame) -> a revolute's point (their permanent instant centre), or
        None for a prismatic pair (a relative translation).
    """
    out: dict[str, str | None] = {}
    for j in mech.joints:
        out.setdefault(f"{j.a}-{j.b}", j.point if j.kind == "R" else None)
    return out


def check_assembly(mech: Mechanism, n: int = 720) -> list[str]:
    """Whether the linkage assembles through the whole cycle (``tmm validate``).

    Parameters
    ----------
    mech : Mechanism
        The mechanism.
    n : int
        Crank angles checked over a turn.

    Returns
    -------
    list
        The warnings (singular positions, closures).

    Raises
    ------
    StageError
        ('kinematics') naming the group and the crank-angle interval where it does not
        assemble.
    """
    solver = get_solver(mech)
    phi = np.arange(n) * (360.0 / n)
    solver.run(np.radians(phi))
    for gi, plan in enumerate(solver.plans):
        if isinstance(plan, DyadPlan):
            iv = solver.bad_intervals(gi)
            if iv:
                raise solver._assembly_error(gi, np.array([iv[0][0]]))
    return list(dict.fromkeys(solver.warnings))
