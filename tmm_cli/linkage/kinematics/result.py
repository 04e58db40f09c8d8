"""KinematicsResult: positions and exact derivatives of every point and link."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ...results import LazyEntries, bulk


def _rows(cols, n: int, flat: bool = False):
    """The columns (each (n,) or a scalar) as n rows (tuples, to be read once) of plain
    floats, a value that is not finite as 0.0 and -0.0 as 0.0 (``flat``: one column, the
    list of its n values)."""
    a = np.empty((len(cols), n))
    for j, c in enumerate(cols):
        a[j] = c
    a = np.where(np.isfinite(a), a, 0.0) + 0.0
    return a[0].tolist() if flat else zip(*a.tolist())


def angle_deg(rad) -> np.ndarray:
    """Angle in degrees in [0, 360)."""
    d = np.mod(np.degrees(np.asarray(rad, float)), 360.0)
    return np.where(d >= 360.0 - 1e-11, 0.0, d)


@dataclass
class KinematicsResult:
    """Kinematics of the linkage at N crank positions (see docs/ARCHITECTURE.md).

    ``d1``/``d2`` are the first and second derivatives with respect to the crank angle
    phi (rad, ccw): the analogues (transfer functions) of velocity and acceleration.
    Real velocities and accelerations: vel = d1 omega1, acc = d2 omega1^2 + d1 eps1.
    """
    phi: np.ndarray
    omega1: float | np.ndarray
    eps1: float | np.ndarray
    pos: dict[str, np.ndarray]
    d1: dict[str, np.ndarray]
    d2: dict[str, np.ndarray]
    angle: dict[str, np.ndarray]
    a1: dict[str, np.ndarray]
    a2: dict[str, np.ndarray]
    warnings: list[str] = field(default_factory=list)
    points: list[str] = field(default_factory=list)      # report order
    links: list[str] = field(default_factory=list)
    singular: np.ndarray | None = None                  # (N,) bool: velocity equations singular
    near: np.ndarray | None = None                      # (N,) bool: within 1 deg of a change point
    undefined: dict[str, np.ndarray] = field(default_factory=dict)  # 'v:P', 'a:P', 'omega:L', 'epsilon:L'

    # ---------------------------------------------------------------
    def _w(self):
        w = np.asarray(self.omega1, float)
        return w if w.ndim == 0 else w.reshape(-1)

    def _e(self):
        e = np.asarray(self.eps1, float)
        return e if e.ndim == 0 else e.reshape(-1)

    def vel(self, p: str) -> np.ndarray:
        w = self._w()
        return self.d1[p] * (w if w.ndim == 0 else w[:, None])

    def acc(self, p: str) -> np.ndarray:
        w, e = self._w(), self._e()
        w2 = w ** 2 if w.ndim == 0 else (w ** 2)[:, None]
        e2 = e if e.ndim == 0 else e[:, None]
        return self.d2[p] * w2 + self.d1[p] * e2

    def omega(self, link: str) -> np.ndarray:
        return self.a1[link] * self._w()

    def epsilon(self, link: str) -> np.ndarray:
        return self.a2[link] * self._w() ** 2 + self.a1[link] * self._e()

    _PKEYS = ("x", "y", "vx", "vy", "v", "ax", "ay", "a", "vqx", "vqy", "vq", "aqx", "aqy", "aq")
    _LKEYS = ("angle", "omega", "epsilon", "i", "iq2")
    _NULLED = {"v": ("vx", "vy", "v", "vqx", "vqy", "vq"), "a": ("ax", "ay", "a", "aqx", "aqy", "aq"),
               "omega": ("omega", "i"), "epsilon": ("epsilon", "iq2")}

    def _null(self, e: dict, k: int) -> None:
        """Null the values of entry ``e`` (position k) that have no finite limit there."""
        for key, mask in self.undefined.items():
            if not mask[k]:
                continue
            what, name = key.split(":", 1)
            target = e["points"].get(name) if what in ("v", "a") else e["links"].get(name)
            if target is not None:
                for f in self._NULLED[what]:
                    target[f] = None

    # ---------------------------------------------------------------
    def to_entries(self, index=None) -> LazyEntries:
        """results.json ``kinematics`` entries, one per position.

        ``index``: the position numbers (sequence of N ints; default 0..N-1).
        Per point: x, y, vx, vy, v, ax, ay, a and the analogues vqx, vqy, vq (= dr/dphi,
        m/rad), aqx, aqy, aq (= d2r/dphi2); per link: angle (deg, [0, 360)), omega,
        epsilon, i = dtheta/dphi (= omega_i/omega1), iq2 = d2theta/dphi2. A
        :class:`tmm_cli.results.LazyEntries` (made from this result's arrays when read)
        of clean values: a value that is not finite is 0.0, or None where it has no
        finite limit (``undefined``)."""
        N = len(self.phi)
        idx = list(range(N)) if index is None else [int(i) for i in index]
        if len(idx) != N:
            raise ValueError(f"to_entries: {len(idx)} indices for {N} positions")

        def build(i0: int, i1: int) -> list[dict]:
            with bulk():
                return self._entries(slice(i0, i1), idx[i0:i1])
        return LazyEntries(N, build)

    def _entries(self, sl: slice, idx: list[int]) -> list[dict]:
        """The entries of the rows ``sl`` (see :meth:`to_entries`); every value depends
        on its own row only, so the entries do not depend on the blocks they are built in."""
        N = len(idx)
        phi = angle_deg(np.radians(self.phi[sl]))
        w, e = self._w(), self._e()
        w = w if w.ndim == 0 or w.shape[0] == 1 else w[sl]
        e = e if e.ndim == 0 or e.shape[0] == 1 else e[sl]
        wc = w if w.ndim == 0 else w[:, None]
        w2 = w ** 2 if w.ndim == 0 else (w ** 2)[:, None]
        ec = e if e.ndim == 0 else e[:, None]
        pts = {}
        for p in self.points:                 # one (N, 14) block per point, rows as dicts
            q, r = self.d1[p][sl], self.d2[p][sl]
            v, a = q * wc, r * w2 + q * ec          # vel(p), acc(p) at the rows
            x = self.pos[p][sl]
            cols = (x[:, 0], x[:, 1], v[:, 0], v[:, 1], np.hypot(v[:, 0], v[:, 1]),
                    a[:, 0], a[:, 1], np.hypot(a[:, 0], a[:, 1]), q[:, 0], q[:, 1], np.hypot(q[:, 0], q[:, 1]),
                    r[:, 0], r[:, 1], np.hypot(r[:, 0], r[:, 1]))
            pts[p] = [dict(zip(self._PKEYS, row)) for row in _rows(cols, N)]
        lks = {}
        for lk in self.links:
            a1, a2 = self.a1[lk][sl], self.a2[lk][sl]
            cols = (angle_deg(self.angle[lk][sl]), a1 * w, a2 * w ** 2 + a1 * e, a1, a2)
            lks[lk] = [dict(zip(self._LKEYS, row)) for row in _rows(cols, N)]
        pnames, lnames = list(pts), list(lks)
        prow = zip(*pts.values()) if pnames else [()] * N
        lrow = zip(*lks.values()) if lnames else [()] * N
        out = [{"index": i, "phi": f, "points": dict(zip(pnames, pr)), "links": dict(zip(lnames, lr))}
               for i, f, pr, lr in zip(idx, _rows((phi,), N, flat=True), prow, lrow)]
        i0 = sl.start
        sing = [] if self.singular is None else np.flatnonzero(self.singular[sl]).tolist()
        for k in sing:
            out[k]["singular"] = True
        near = [] if self.near is None else np.flatnonzero(self.near[sl]).tolist()
        for k in near:
            out[k]["near_singular"] = True
            self._null(out[k], i0 + k)
        return out
