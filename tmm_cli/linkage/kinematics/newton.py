"""Group-level linear algebra: Jacobians, batched solves, Newton's method.

Used for the velocities and accelerations of every group (exact derivatives of the
loop-closure equations: Phi_q q' = -sum(known blocks . k'), Phi_q q'' = -(... + gamma))
and for the positions of groups without a closed form (class III and higher).
"""
from __future__ import annotations

import numpy as np

from .state import State

CHUNK = 16384
SINGULAR = 1e-10      # |det| of the row/column-equilibrated matrix below this: singular


def group_q(st: State, links) -> np.ndarray:
    """The group's poses as one vector per position.

    Parameters
    ----------
    st : State
        The state of the N positions.
    links : sequence
        The group's bodies.

    Returns
    -------
    numpy.ndarray
        (N, 3k): per body its origin x, y (m) and angle (rad).
    """
    return np.concatenate([np.concatenate([st.o[b], st.th[b][:, None]], axis=1) for b in links], axis=1)


def set_q(st: State, links, q: np.ndarray) -> None:
    """Set the group's poses from one vector per position.

    Parameters
    ----------
    st : State
        The state, changed in place.
    links : sequence
        The group's bodies.
    q : numpy.ndarray
        (N, 3k) as :func:`group_q` gives it.
    """
    for k, b in enumerate(links):
        st.set_pose(b, q[:, 3 * k:3 * k + 2].copy(), q[:, 3 * k + 2].copy())


def residual(cons, st: State) -> np.ndarray:
    """The residuals of the group's closure equations.

    Parameters
    ----------
    cons : list
        The group's constraints (revolute and prismatic pairs).
    st : State
        The state of the N positions.

    Returns
    -------
    numpy.ndarray
        (N, m): each constraint's residual (m for a pair's point, dimensionless for a
        direction).
    """
    return np.concatenate([c.value(st) for c in cons], axis=1)


def blocks(cons, st: State):
    """The constraints' Jacobian blocks.

    Parameters
    ----------
    cons : list
        The group's constraints (revolute and prismatic pairs).
    st : State
        The state of the N positions.

    Returns
    -------
    list of dict
        Per constraint: body -> (N, m_c, 3), the derivatives of its equations with respect to
        the body's x, y and angle.
    """
    return [c.blocks(st) for c in cons]


def jacobian(cons, blks, links, N) -> np.ndarray:
    """The group's Jacobian in its own bodies' poses.

    Parameters
    ----------
    cons : list
        The constraints.
    blks : list of dict
        :func:`blocks`.
    links : sequence
        The group's bodies.
    N : int
        The number of positions.

    Returns
    -------
    numpy.ndarray
        (N, sum of m_c, 3k).
    """
    col = {b: 3 * k for k, b in enumerate(links)}
    M = 3 * len(links)
    A = np.zeros((N, sum(c.m for c in cons), M))
    r = 0
    for c, bl in zip(cons, blks):
        for b, blk in bl.items():
            if b in col:
                A[:, r:r + c.m, col[b]:col[b] + 3] = blk
        r += c.m
    return A


def known_rhs(cons, blks, links, st: State, order: int) -> np.ndarray:
    """The known part of the velocity or acceleration equations.

    Parameters
    ----------
    cons : list
        The constraints.
    blks : list of dict
        :func:`blocks`.
    links : sequence
        The group's bodies.
    st : State
        The state (the bodies outside the group known).
    order : int
        1: velocities (analogues d1), 2: accelerations (d2).

    Returns
    -------
    numpy.ndarray
        The sum over bodies outside the group of block_b . (o_b^(order), th_b^(order)).
    """
    N = st.N
    out = np.zeros((N, sum(c.m for c in cons)))
    r = 0
    lk = set(links)
    oo = st.o1 if order == 1 else st.o2
    tt = st.th1 if order == 1 else st.th2
    for c, bl in zip(cons, blks):
        for b, blk in bl.items():
            if b in lk:
                continue
            v = np.concatenate([oo[b], tt[b][:, None]], axis=1)
            out[:, r:r + c.m] += np.einsum("nij,nj->ni", blk, v)
        r += c.m
    return out


class BatchedInverse:
    """Row/column-equilibrated inverse of a batch of square matrices.

    ``sing`` flags the matrices whose equilibrated determinant is below SINGULAR;
    for those the Moore-Penrose pseudo-inverse is used (the caller replaces the
    result by continuity)."""

    def __init__(self, A: np.ndarray):
        N, M, _ = A.shape
        self.rs = np.empty((N, M))
        self.cs = np.empty((N, M))
        self.inv = np.empty_like(A)
        self.sing = np.zeros(N, bool)
        self.det = np.zeros(N)   # signed determinant of the equilibrated matrix
        for s in range(0, N, CHUNK):
            a = A[s:s + CHUNK]
            rn = np.sqrt(np.einsum("nij,nij->ni", a, a))
            rn[rn == 0] = 1.0
            a = a / rn[:, :, None]
            cn = np.sqrt(np.einsum("nij,nij->nj", a, a))
            cn[cn == 0] = 1.0
            a = a / cn[:, None, :]
            sdet = np.linalg.det(a)
            self.det[s:s + CHUNK] = sdet
            det = np.abs(sdet)
            sg = ~(det >= SINGULAR)
            if sg.any():
                inv = np.empty_like(a)
                ok = ~sg
                if ok.any():
                    inv[ok] = np.linalg.inv(a[ok])
                inv[sg] = np.linalg.pinv(a[sg], rcond=1e-9)
            else:
                inv = np.linalg.inv(a)
            self.rs[s:s + CHUNK] = rn
            self.cs[s:s + CHUNK] = cn
            self.inv[s:s + CHUNK] = inv
            self.sing[s:s + CHUNK] = sg

    def apply(self, b: np.ndarray) -> np.ndarray:
        """x with A x = b, b (N, M)."""
        y = np.einsum("nij,nj->ni", self.inv, b / self.rs)
        return y / self.cs


def derivatives(cons, links, st: State) -> np.ndarray:
    """The exact first and second phi-derivatives of a group's poses.

    Parameters
    ----------
    cons : list
        The group's constraints (revolute and prismatic pairs).
    links : sequence
        The group's bodies.
    st : State
        The state of the N positions, the group's poses set; their derivatives are
        written into it.

    Returns
    -------
    numpy.ndarray
        The mask of positions where the velocity equations are singular.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: the analogues of velocities and
    accelerations by differentiating the closure equations; docs/methods.md §2.
    """
    blks = blocks(cons, st)
    A = jacobian(cons, blks, links, st.N)
    inv = BatchedInverse(A)
    del A
    b1 = known_rhs(cons, blks, links, st, 1)
    q1 = -inv.apply(b1)
    for k, b in enumerate(links):
        st.set_d1(b, q1[:, 3 * k:3 * k + 2].copy(), q1[:, 3 * k + 2].copy())
    b2 = known_rhs(cons, blks, links, st, 2)
    b2 += np.concatenate([c.gamma(st) for c in cons], axis=1)
    q2 = -inv.apply(b2)
    for k, b in enumerate(links):
        st.set_d2(b, q2[:, 3 * k:3 * k + 2].copy(), q2[:, 3 * k + 2].copy())
    st.last_det = inv.det
    return inv.sing


def newton(cons, links, st: State, q0: np.ndarray, L: float, maxit: int = 40,
           tol: float = 1e-11) -> tuple[np.ndarray, np.ndarray]:
    """Vectorised Newton iterations on a group's closure equations.

    Parameters
    ----------
    cons : list
        The constraints.
    links : sequence
        The group's bodies.
    st : State
        The state; it holds the last iterate.
    q0 : numpy.ndarray
        The starting poses (N, 3k).
    L : float
        The group's length scale, m (for the tolerance).
    maxit : int
        Iterations at most.
    tol : float
        The relative tolerance.

    Returns
    -------
    tuple of numpy.ndarray
        (q (N, 3k), the converged mask (N,)).
    """
    q = q0.copy()
    N = st.N
    conv = np.zeros(N, bool)
    angle_rows = None
    for it in range(maxit):
        set_q(st, links, q)
        r = residual(cons, st)
        if angle_rows is None:
            angle_rows = np.concatenate([[c.kind == "P", False] for c in cons])
        rs = r.copy()
        rs[:, angle_rows] *= L
        err = np.max(np.abs(rs), axis=1)
        conv = err <= tol * L
        if conv.all() and it > 0:
            break
        A = jacobian(cons, blocks(cons, st), links, N)
        inv = BatchedInverse(A)
        dq = -inv.apply(r)
        dth = np.abs(dq[:, 2::3]).max(axis=1)
        f = np.minimum(1.0, 0.5 / np.maximum(dth, 1e-300))
        dq *= f[:, None]
        q = q + dq
        bad = ~np.isfinite(q).all(axis=1)
        if bad.any():
            q[bad] = q0[bad]
    set_q(st, links, q)
    r = residual(cons, st)
    rs = r.copy()
    rs[:, angle_rows] *= L
    conv = np.max(np.abs(rs), axis=1) <= tol * L
    return q, conv
