"""KinematicsResult: positions and exact derivatives of every point and link."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ...results import LazyEntries


def angle_deg(rad) -> np.ndarray:
    """An angle in degrees in [0, 360).

    Parameters
    ----------
    rad : float or array_like
        The angle, rad.

    Returns
    -------
    numpy.ndarray
        The angle, deg, in [0, 360).
    """
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
    pins: dict[str, str | None] = field(default_factory=dict)  # "i-j" joined directly: the pin (None: a slide)
    # (N,) the least normalised determinant of the groups' velocity equations (None: the fast
    # path answered, every one at least changepoints.ILL_DET) and (N,) the group that has it
    det_min: np.ndarray | None = field(default=None, repr=False)
    det_group: np.ndarray | None = field(default=None, repr=False)

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

    # ---------------------------------------------------------------
    def to_entries(self, index=None) -> LazyEntries:
        """results.json ``kinematics`` entries, one per position.

        ``index``: the position numbers (sequence of N ints; default 0..N-1).
        Per point: x, y, vx, vy, v, ax, ay, a and the analogues vqx, vqy, vq (= dr/dphi,
        m/rad), aqx, aqy, aq (= d2r/dphi2); per link: angle (deg, [0, 360)), omega,
        epsilon, i = dtheta/dphi (= omega_i/omega1), iq2 = d2theta/dphi2. A
        :class:`tmm_cli.results.LazyEntries` (made from this result's arrays when read)
        of clean values: a value that is not finite is 0.0, or None where it has no
        finite limit (``undefined``); see :mod:`tmm_cli.linkage.kinematics.entries`."""
        from .entries import lazy_entries
        N = len(self.phi)
        idx = list(range(N)) if index is None else [int(i) for i in index]
        if len(idx) != N:
            raise ValueError(f"to_entries: {len(idx)} indices for {N} positions")
        return lazy_entries(self, idx)
