"""Follower motion over the whole cam cycle: rise, far dwell, return, near dwell.

``s`` is the follower displacement from its lowest position: metres for a translating
follower, radians for a rocker (the rocker's turn from its initial position).
Derivatives are taken with respect to the cam angle ``phi`` in radians, measured in the
cam's direction of rotation from the start of the rise.

On the whole-cycle grid the values are right-continuous: a point exactly on a phase
boundary belongs to the phase that starts there (so the constant-velocity law shows its
jump of velocity after the boundary).  Inside the synthesis every phase is a closed
interval with the law's own one-sided limits, so the limits on both sides of a jump are
taken into account.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from .laws import Law, get_law

if TYPE_CHECKING:
    from .spec import LawsSpec, PhasesSpec

RISE, RETURN, NEAR_DWELL, FAR_DWELL = 0, 1, 2, 3


@dataclass(frozen=True)
class Motion:
    """The follower's motion over a turn: the stroke, the phase angles and the laws."""

    h: float                      # stroke: m, or rad for a rocker
    rise: float                   # phase angles, rad
    far_dwell: float
    ret: float
    near_dwell: float
    law_rise: Law
    law_return: Law
    # the phase angles as the task gives them, deg (rise, far dwell, return, near dwell): the
    # crank angles told in degrees are sums of these, not degrees of the radians (150, not
    # 149.99999999999997)
    phases_deg: tuple[float, float, float, float]

    @classmethod
    def from_spec(cls, h: float, phases: PhasesSpec, laws: LawsSpec) -> "Motion":
        """The motion of a cam section.

        Parameters
        ----------
        h : float
            The stroke: m, or rad for a rocker.
        phases : PhasesSpec
            The phase angles, deg (the task model completes the near dwell to 360 deg).
        laws : LawsSpec
            The names of the laws of the rise and of the return.

        Returns
        -------
        Motion
            The phase angles in rad and the two laws.
        """
        rise = math.radians(float(phases.rise))
        far = math.radians(float(phases.far_dwell))
        ret = math.radians(float(phases.return_))
        near = math.radians(float(phases.near_dwell))
        deg = (float(phases.rise), float(phases.far_dwell), float(phases.return_), max(float(phases.near_dwell), 0.0))
        return cls(float(h), rise, far, ret, max(near, 0.0), get_law(laws.rise), get_law(laws.return_), deg)

    # ------------------------------------------------------------------ bounds
    @property
    def starts_deg(self) -> tuple[float, float, float, float]:
        """Start angles (deg) of rise, far dwell, return, near dwell: sums of the phases' degrees."""
        r, f, t, _ = self.phases_deg
        return 0.0, r, r + f, r + f + t

    @property
    def starts(self) -> tuple[float, float, float, float]:
        """Start angles (rad) of rise, far dwell, return, near dwell."""
        a = 0.0
        b = a + self.rise
        c = b + self.far_dwell
        d = c + self.ret
        return a, b, c, d

    def phase(self, k: int, x) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """s, s', s'', s''' on phase ``k`` (RISE/RETURN/NEAR_DWELL/FAR_DWELL) at fractions ``x``."""
        x = np.asarray(x, dtype=float)
        if k == RISE:
            f, f1, f2, f3 = self.law_rise(x)
            P = self.rise
            return self.h * f, self.h * f1 / P, self.h * f2 / P ** 2, self.h * f3 / P ** 3
        if k == RETURN:
            f, f1, f2, f3 = self.law_return(x)
            P = self.ret
            return self.h * (1 - f), -self.h * f1 / P, -self.h * f2 / P ** 2, -self.h * f3 / P ** 3
        zero = np.zeros_like(x)
        s = zero + (self.h if k == FAR_DWELL else 0.0)
        return s, zero.copy(), zero.copy(), zero.copy()

    def phase_mixed(self, k, x):
        """Like :meth:`phase` with an array of phase indices ``k`` matching ``x``."""
        k = np.asarray(k)
        x = np.asarray(x, dtype=float)
        out = [np.zeros_like(x) for _ in range(4)]
        for kk in (RISE, RETURN, NEAR_DWELL, FAR_DWELL):
            m = k == kk
            if np.any(m):
                vals = self.phase(kk, x[m])
                for o, v in zip(out, vals):
                    o[m] = v
        return tuple(out)

    def locate(self, phi_rad) -> tuple[np.ndarray, np.ndarray]:
        """Phase index and fraction for cycle angles (rad), right-continuous at boundaries."""
        phi = np.mod(np.asarray(phi_rad, dtype=float), 2 * math.pi)
        a, b, c, d = self.starts
        k = np.full(phi.shape, NEAR_DWELL, dtype=int)
        x = np.zeros_like(phi)
        eps = 1e-12
        rise = phi < b - eps
        far = (~rise) & (phi < c - eps)
        ret = (~rise) & (~far) & (phi < d - eps)
        k[rise] = RISE
        x[rise] = phi[rise] / self.rise
        k[far] = FAR_DWELL
        k[ret] = RETURN
        x[ret] = (phi[ret] - c) / self.ret
        return k, np.clip(x, 0.0, 1.0)

    def evaluate(self, phi_rad):
        """s, s', s'', s''' over the cycle at angles ``phi_rad`` (right-continuous)."""
        k, x = self.locate(phi_rad)
        return self.phase_mixed(k, x)

    def boundaries(self) -> list[dict]:
        """Jumps of s' and s'' at the phase boundaries (and inside a law).

        Each entry: ``phi`` (deg), ``ds_jump``, ``d2s_jump`` (right minus left limits),
        ``kind`` ('rigid' | 'soft' | 'none') and ``where``.
        """
        seq = [(RISE, self.rise, "rise"), (FAR_DWELL, self.far_dwell, "far_dwell"),
               (RETURN, self.ret, "return"), (NEAR_DWELL, self.near_dwell, "near_dwell")]
        seq = [p for p in seq if p[1] > 1e-12]
        out = []
        start = 0.0
        ends = []
        for k, length, name in seq:
            ends.append((start + length, k, name))
            start += length
        n = len(seq)
        scale_v = self.h / min(self.rise, self.ret)
        scale_a = scale_v / min(self.rise, self.ret)
        for i in range(n):
            end, k_left, name_left = ends[i]
            k_right, _, name_right = seq[(i + 1) % n]
            _, v_l, a_l, _ = self.phase(k_left, np.array([1.0]))
            _, v_r, a_r, _ = self.phase(k_right, np.array([0.0]))
            dv = float(v_r[0] - v_l[0])
            da = float(a_r[0] - a_l[0])
            kind = "rigid" if abs(dv) > 1e-9 * scale_v else ("soft" if abs(da) > 1e-9 * scale_a else "none")
            out.append({"phi": math.degrees(end) % 360.0, "where": f"{name_left}/{name_right}",
                        "ds_jump": dv, "d2s_jump": da, "kind": kind})
        # jumps of acceleration inside a law (parabolic: at mid-phase)
        for k, law, P, off in ((RISE, self.law_rise, self.rise, 0.0),
                               (RETURN, self.law_return, self.ret, self.starts[2])):
            for xi in law.soft_inside:
                a_l = self.phase(k, np.array([xi - 1e-12]))[2][0]
                a_r = self.phase(k, np.array([xi + 1e-12]))[2][0]
                out.append({"phi": math.degrees(off + xi * P), "where": "rise" if k == RISE else "return",
                            "ds_jump": 0.0, "d2s_jump": float(a_r - a_l), "kind": "soft"})
        out.sort(key=lambda e: e["phi"])
        return out
