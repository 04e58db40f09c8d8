"""Equilibrium equations of the links (d'Alembert), vectorised over positions.

Three equations per moving link i (rows ``3(i-1) .. 3(i-1)+2``):
sum Fx = 0, sum Fy = 0, sum of moments about the link's origin O_i = 0 (ccw positive).

Unknowns (columns): two per pair in the order of ``mech.joints``:

* revolute pair (a, b), a < b: R_ab = (x, y), the force of link a on link b, acting
  at the pair's point (so link a feels -R_ab there);
* prismatic pair (a, b): N_ab, the normal force of a on b along n = e rotated +90 deg
  (e: unit vector of the guide direction, the slider's u-axis), acting at the
  slider's pin, and M_ab, the couple of a on b about the pin; the force N n then acts
  on the guide line at the distance ``M / N`` from the pin along e (its point of
  action);

and optionally one balancing unknown: a couple on a bar link, or a force along the
guide acting at the pin of a slider.

The equations read ``A x + q = 0`` where ``q`` holds the applied loads
(sum F, sum of moments about O_i).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..loads import Loads
from ..loads.model import all_rows


def cross(r: np.ndarray, f: np.ndarray) -> np.ndarray:
    """The z component of plane cross products.

    Parameters
    ----------
    r, f : numpy.ndarray
        Vectors (..., 2) (e.g. an arm in m and a force in N).

    Returns
    -------
    numpy.ndarray
        r_x f_y - r_y f_x (e.g. the moment, N*m).
    """
    return r[..., 0] * f[..., 1] - r[..., 1] * f[..., 0]


def rot90(r: np.ndarray) -> np.ndarray:
    """Turn plane vectors by +90 degrees.

    Parameters
    ----------
    r : numpy.ndarray
        Vectors (..., 2).

    Returns
    -------
    numpy.ndarray
        (-r_y, r_x).
    """
    return np.stack([-r[..., 1], r[..., 0]], axis=-1)


@dataclass
class Geometry:
    """Positions and velocity analogues needed by the equations, at N positions."""
    n_pos: int
    origin: dict[int, np.ndarray]          # link -> (N,2) position of its origin O_i
    d1o: dict[int, np.ndarray]             # link -> (N,2) dO_i/dphi
    a1: dict[int, np.ndarray]              # link -> (N,) dtheta_i/dphi
    a2: dict[int, np.ndarray]
    jpoint: list[np.ndarray]               # joint -> (N,2): pair point (R) or slider pin (P)
    jdir: list[np.ndarray | None]          # joint -> (N,2) unit guide direction e (P) or None
    omega1: np.ndarray                     # (N,)
    eps1: np.ndarray                       # (N,)
    Lc: float                              # length scale of the mechanism

    def point_d1(self, link: int, p: np.ndarray) -> np.ndarray:
        """dr/dphi of the material point of ``link`` now at ``p`` (N,2); ground: 0."""
        if link == 0:
            return np.zeros_like(p)
        return self.d1o[link] + self.a1[link][:, None] * rot90(p - self.origin[link])

    def point_vel(self, link: int, p: np.ndarray) -> np.ndarray:
        return self.point_d1(link, p) * self.omega1[:, None]

    def omega(self, link: int) -> np.ndarray:
        if link == 0:
            return np.zeros(self.n_pos)
        return self.a1[link] * self.omega1

    def take(self, sl: slice) -> "Geometry":
        """The positions ``sl`` (a slice: views, no copies)."""
        return Geometry(len(range(*sl.indices(self.n_pos))), {k: v[sl] for k, v in self.origin.items()},
                        {k: v[sl] for k, v in self.d1o.items()}, {k: v[sl] for k, v in self.a1.items()},
                        {k: v[sl] for k, v in self.a2.items()}, [v[sl] for v in self.jpoint],
                        [None if v is None else v[sl] for v in self.jdir], self.omega1[sl], self.eps1[sl], self.Lc)


def length_scale(mech) -> float:
    """A characteristic length of a mechanism.

    Parameters
    ----------
    mech : Mechanism
        The mechanism.

    Returns
    -------
    float
        The largest link length or spread of the ground points, m (at least 1 mm).
    """
    L = [abs(lk.length) for lk in mech.links if lk.length]
    g = np.array(list(mech.ground.values()), float) if mech.ground else np.zeros((1, 2))
    spread = float(np.max(np.ptp(g, axis=0))) if len(g) > 1 else 0.0
    return max(L + [spread, 1e-3])


def geometry(mech, kin, rows=None) -> Geometry:
    """The positions and velocity analogues the equilibrium equations need.

    Parameters
    ----------
    mech : Mechanism
        The mechanism.
    kin : KinematicsResult
        Its kinematics.
    rows : array_like or None
        The rows of ``kin`` (None: all).

    Returns
    -------
    Geometry
        Per link its origin (m), d(origin)/dphi (m/rad), dtheta/dphi and d2theta/dphi2; per
        pair its point (m) and a slider's guide direction; omega1 (rad/s) and eps1 (rad/s^2).
    """
    phi = np.atleast_1d(np.asarray(kin.phi, float))
    rows = np.arange(len(phi)) if rows is None else np.asarray(rows, int)
    N = len(rows)
    every = all_rows(rows, len(phi))

    def sel(a):
        """The rows of ``a`` (every row: ``a`` itself, no copy; nothing here changes it)."""
        a = np.asarray(a, float)
        return a if every else a[rows]

    origin, d1o, a1, a2 = {}, {}, {}, {}
    for lk in mech.links:
        o = lk.origin
        origin[lk.index] = sel(kin.pos[o])
        d1o[lk.index] = sel(kin.d1[o])
        a1[lk.index] = sel(kin.a1[lk.name])
        a2[lk.index] = sel(kin.a2[lk.name])
    jpoint, jdir = [], []
    for j in mech.joints:
        if j.kind == "R":
            jpoint.append(sel(kin.pos[j.point]))
            jdir.append(None)
        else:
            s = mech.link(j.slider)
            jpoint.append(sel(kin.pos[s.origin]))
            th = sel(kin.angle[s.name])
            jdir.append(np.stack([np.cos(th), np.sin(th)], axis=-1))
    w = np.broadcast_to(np.asarray(kin.omega1, float), phi.shape)[rows].astype(float)
    e = np.broadcast_to(np.asarray(kin.eps1, float), phi.shape)[rows].astype(float)
    return Geometry(N, origin, d1o, a1, a2, jpoint, jdir, w, e, length_scale(mech))


def joint_terms(geo: Geometry, joint, jidx: int) -> dict[int, list[tuple[int, int, np.ndarray | float]]]:
    """The coefficients of a pair's two unknowns in its links' equations.

    Parameters
    ----------
    geo : Geometry
        The positions.
    joint : Joint
        The pair.
    jidx : int
        Its index.

    Returns
    -------
    dict
        link -> [(equation 0..2, unknown 0..1, value: (N,) or a number)], the terms not zero
        by the pair's kind (a pin: the reaction's x, y; a slider: the normal force and its
        moment).

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: the equilibrium equations of a link:
    sum of forces and of moments; docs/methods.md §3.
    """
    p = geo.jpoint[jidx]
    out = {}
    for link, sg in ((joint.b, 1.0), (joint.a, -1.0)):
        if link == 0:
            continue
        r = p - geo.origin[link]
        if joint.kind == "R":
            out[link] = [(0, 0, sg), (1, 1, sg), (2, 0, -sg * r[:, 1]), (2, 1, sg * r[:, 0])]
        else:
            nv = rot90(geo.jdir[jidx])
            out[link] = [(0, 0, sg * nv[:, 0]), (1, 0, sg * nv[:, 1]), (2, 0, sg * cross(r, nv)), (2, 1, sg)]
    return out


def coeff_array(n_pos: int, terms: list[tuple[int, int, np.ndarray | float]]) -> np.ndarray:
    """A link's pair terms as a block of its equations' coefficients.

    Parameters
    ----------
    n_pos : int
        The number of positions N.
    terms : list
        (equation, unknown, value) of :func:`joint_terms`.

    Returns
    -------
    numpy.ndarray
        (N, 3, 2).
    """
    c = np.zeros((n_pos, 3, 2))
    for i, k, v in terms:
        c[:, i, k] = v
    return c


def joint_coeffs(geo: Geometry, joint, jidx: int) -> dict[int, np.ndarray]:
    """The contribution of a pair's two unknowns to its links' equations.

    Parameters
    ----------
    geo : Geometry
        The positions.
    joint : Joint
        The pair.
    jidx : int
        Its index.

    Returns
    -------
    dict
        link -> (N, 3, 2).
    """
    return {link: coeff_array(geo.n_pos, t) for link, t in joint_terms(geo, joint, jidx).items()}


def balance_terms(mech, geo: Geometry, link: int) -> list[tuple[int, np.ndarray | float]]:
    """The coefficients of the balancing unknown in a link's equations.

    Parameters
    ----------
    mech : Mechanism
        The mechanism.
    geo : Geometry
        Its positions and velocity analogues at N positions (m, m/rad).
    link : int
        The balance link.

    Returns
    -------
    list
        (equation 0..2, value: (N,) or a number) of a unit couple on a bar, or a unit force
        along the guide at the pin of a slider, the terms not zero by the link's kind.
    """
    lk = mech.link(link)
    if lk.kind == "slider":
        j = next(k for k, jj in enumerate(mech.joints) if jj.kind == "P" and jj.slider == link)
        e = geo.jdir[j]
        return [(0, e[:, 0]), (1, e[:, 1]), (2, cross(geo.jpoint[j] - geo.origin[link], e))]
    return [(2, 1.0)]


def balance_coeffs(mech, geo: Geometry, link: int) -> np.ndarray:
    """The balancing unknown's column in a link's equations.

    Parameters
    ----------
    mech : Mechanism
        The mechanism.
    geo : Geometry
        Its positions and velocity analogues at N positions (m, m/rad).
    link : int
        The balance link.

    Returns
    -------
    numpy.ndarray
        (N, 3): a unit balancing couple on a bar, or a unit force along the guide at the pin
        of a slider.
    """
    c = np.zeros((geo.n_pos, 3))
    for i, v in balance_terms(mech, geo, link):
        c[:, i] = v
    return c


def load_vector(mech, geo: Geometry, loads: Loads) -> np.ndarray:
    """The applied loads' sums per link.

    Parameters
    ----------
    mech : Mechanism
        The mechanism.
    geo : Geometry
        Its positions and velocity analogues at N positions (m, m/rad).
    loads : Loads
        The loads (N, N*m).

    Returns
    -------
    numpy.ndarray
        (N, n+1, 3): the sum of the applied forces (N) and of their moments about O_i (N*m)
        per link (row 0, the ground, left zero).  Each sum is made on its own (N,) vector, its
        terms added in the loads' order to 0.0 (forces, then couples).
    """
    sums: dict[tuple[int, int], np.ndarray] = {}

    def add(link: int, comp: int, v: np.ndarray) -> None:
        s = sums.get((link, comp))
        if s is None:
            sums[(link, comp)] = s = np.empty(geo.n_pos)
            np.add(0.0, v, out=s)
        else:
            s += v
    for f in loads.forces:
        if f.link == 0:
            continue
        add(f.link, 0, f.F[:, 0])
        add(f.link, 1, f.F[:, 1])
        add(f.link, 2, cross(f.point - geo.origin[f.link], f.F))
    for c in loads.couples:
        if c.link == 0:
            continue
        add(c.link, 2, c.M)
    q = np.zeros((geo.n_pos, mech.n + 1, 3))
    for (link, comp), s in sums.items():
        q[:, link, comp] = s
    return q


def full_matrix(mech, geo: Geometry, balance: int) -> np.ndarray:
    """All equilibrium equations of all links.

    Parameters
    ----------
    mech : Mechanism
        The mechanism.
    geo : Geometry
        Its positions and velocity analogues at N positions (m, m/rad).
    balance : int
        The balance link.

    Returns
    -------
    numpy.ndarray
        A (N, 3n, 2p+1): the equations in all pair unknowns and the balancing unknown (last
        column).

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: the kinetostatics of the whole
    mechanism as one linear system; docs/methods.md §3.
    """
    n, p = mech.n, len(mech.joints)
    A = np.zeros((geo.n_pos, 3 * n, 2 * p + 1))
    for k, j in enumerate(mech.joints):
        for link, c in joint_coeffs(geo, j, k).items():
            A[:, 3 * (link - 1):3 * link, 2 * k:2 * k + 2] += c
    A[:, 3 * (balance - 1):3 * balance, 2 * p] += balance_coeffs(mech, geo, balance)
    return A


def scaled_matrix(mech, geo: Geometry, balance: int, rs: np.ndarray, cs: np.ndarray) -> np.ndarray:
    """The scaled equilibrium system, bit for bit, made from its non-zero coefficients.

    Parameters
    ----------
    mech : Mechanism
        The mechanism.
    geo : Geometry
        Its positions and velocity analogues at N positions (m, m/rad).
    balance : int
        The balance link.
    rs, cs : numpy.ndarray
        The row and column scales (:func:`scaling`).

    Returns
    -------
    numpy.ndarray
        ``full_matrix(mech, geo, balance) * rs[None, :, None] * cs[None, None, :]`` bit for bit:
        each coefficient not zero by the pairs' kinds is ``((0.0 + v) * rs[i]) * cs[j]``
        (0.0 + v: -0.0 made 0.0, as the sum makes it), the rest 0.0; no (N, 3, 2) blocks, no
        scaled copies of the whole matrix.
    """
    if not (np.all(np.isfinite(rs)) and np.all(np.isfinite(cs))):
        return full_matrix(mech, geo, balance) * rs[None, :, None] * cs[None, None, :]
    n, p = mech.n, len(mech.joints)
    A = np.zeros((geo.n_pos, 3 * n, 2 * p + 1))

    def put(row: int, col: int, v) -> None:
        A[:, row, col] = ((0.0 + v) * rs[row]) * cs[col]
    for k, j in enumerate(mech.joints):
        for link, terms in joint_terms(geo, j, k).items():
            for i, c, v in terms:
                put(3 * (link - 1) + i, 2 * k + c, v)
    for i, v in balance_terms(mech, geo, balance):
        put(3 * (balance - 1) + i, 2 * p, v)
    return A


def scaling(mech, Lc: float, balance: int) -> tuple[np.ndarray, np.ndarray]:
    """Row and column scales making the equilibrium system dimensionless.

    Parameters
    ----------
    mech : Mechanism
        The mechanism.
    Lc : float
        Its length scale, m.
    balance : int
        The balance link.

    Returns
    -------
    tuple of numpy.ndarray
        (row scales, column scales): moment rows / Lc, moment unknowns * Lc, so the entries
        of A are O(1).
    """
    n, p = mech.n, len(mech.joints)
    rs = np.ones(3 * n)
    rs[2::3] = 1.0 / Lc
    cs = np.ones(2 * p + 1)
    for k, j in enumerate(mech.joints):
        if j.kind == "P":
            cs[2 * k + 1] = Lc
    if mech.link(balance).kind != "slider":
        cs[2 * p] = Lc
    return rs, cs


def scaled_det(mech, geo: Geometry, balance: int) -> np.ndarray:
    """The determinant of the scaled equilibrium system.

    Parameters
    ----------
    mech : Mechanism
        The mechanism.
    geo : Geometry
        Its positions and velocity analogues at N positions (m, m/rad).
    balance : int
        The balance link.

    Returns
    -------
    numpy.ndarray
        det (N,), dimensionless; its roots are the singular positions.
    """
    n, p = mech.n, len(mech.joints)
    if 3 * n != 2 * p + 1:
        raise ValueError(f"the equilibrium system is not square ({3 * n} equations, "
                         f"{2 * p + 1} unknowns)")
    rs, cs = scaling(mech, geo.Lc, balance)
    return np.linalg.det(scaled_matrix(mech, geo, balance, rs, cs))
