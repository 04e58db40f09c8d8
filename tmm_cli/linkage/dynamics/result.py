"""The dynamics stage's result: the flywheel, the steady motion at any crank angle and
results.json ``flywheel``."""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from . import flywheel as fw
from .cycle import GAUSS_DEFAULT, CycleResult, Sampler


def _f(x):
    """Plain float, None for non-finite."""
    if x is None:
        return None
    x = float(x)
    return x + 0.0 if math.isfinite(x) else None     # + 0.0: no negative zero in the results


def _l(a):
    """Plain floats (None for non-finite, no negative zero), as `_f` gives them one by one."""
    a = np.asarray(a, float).ravel()
    if np.isfinite(a).all():
        return (a + 0.0).tolist()
    return [_f(v) for v in a]


@dataclass
class DynamicsResult:
    """The flywheel stage: the steady cycle, the flywheel's J and size, the hand method beside it."""

    cycle: CycleResult
    cycle_deg: float
    resolution: int
    phi0: float
    sign: float
    constant: str
    shape: dict
    size: fw.FlywheelSize
    accuracy: dict | None
    warnings: list[str]
    q_deg: np.ndarray
    side: np.ndarray
    sampler: Sampler | None = field(default=None, repr=False)
    map_cycle: float | None = None   # how motion_at reads crank angles (default: the cycle)
    hand: dict | None = None         # the 12-position hand method beside the accurate result
    quadrature_points: int = GAUSS_DEFAULT

    # ---- the numbers
    @property
    def J_fly(self) -> float:
        """The chosen flywheel's own moment of inertia (>= 0), kg*m^2."""
        return self.cycle.J

    @property
    def J(self) -> float:
        return self.cycle.J

    @property
    def crank_inertia(self) -> float:
        """The constant moment of inertia the steady motion adds on the crank: the chosen
        flywheel and ``flywheel.reduced_J``, kg*m^2."""
        return float(self.J_fly) + float(self.cycle.J_extra)

    @property
    def phi(self) -> np.ndarray:
        """Absolute crank angles of the nodes, deg in [0, 360)."""
        return np.mod(self.phi0 + self.sign * self.q_deg, 360.0)

    # ---- the steady motion at arbitrary crank angles
    def _q_of(self, phi) -> np.ndarray:
        c = self.map_cycle or self.cycle_deg
        return np.mod(self.sign * (np.asarray(phi, float) - self.phi0), c)

    def motion_at(self, phi) -> tuple[np.ndarray, np.ndarray]:
        """(omega1, epsilon1), signed (ccw positive), of the steady motion with the
        chosen flywheel at absolute crank angles phi (deg), read as the rotation
        sign*(phi - phi0) mod `map_cycle`: the cycle, or, from `analysis.analyze`, 360 (the
        reported positions are the first turn after position 0 of a 720-deg cycle, as the
        loads read them), so that the loads at these positions match.  With a sampler the
        reduced moment and inertia
        are evaluated exactly at phi (so eps satisfies the equation of motion exactly
        there and the balancing moment of kinetostatics equals the constant driving
        moment); only dT is interpolated (cubic Hermite with slope M_red)."""
        phi = np.atleast_1d(np.asarray(phi, float))
        c = self.cycle
        q = self._q_of(phi)
        qr = np.deg2rad(q)
        dT = fw.hermite_at(c.q, c.work.dT, c.work.M_red, qr)
        if self.sampler is not None:
            s = self.sampler(q, np.zeros_like(q))
            M = s.M_given + c.work.M_constant
            names = [k for k in s.J_links if k not in c.const_links]
            J_var = np.zeros_like(q)
            for k in names:
                J_var = J_var + s.J_links[k]
            ds = [(s.dJ_links or {}).get(k) for k in names]
            if all(d is not None for d in ds):
                dJ = np.zeros_like(q)
                for d in ds:
                    dJ = dJ + d
            else:   # no second-order analogues: the grid's finite differences
                dJ = np.interp(qr, c.q, c.dJ_var)
        else:
            M = np.interp(qr, c.q, c.work.M_red)
            J_var = np.interp(qr, c.q, c.J_var)
            dJ = np.interp(qr, c.q, c.dJ_var)
        J_tot = c.J_const + c.J + J_var
        pos = J_tot > 0
        Js = np.where(pos, J_tot, 1.0)
        # no inertia at all (massless links, no flywheel): steady_motion allows this only
        # when nothing changes over the cycle, and then the motion is uniform at omega_m
        w = np.where(pos, np.sqrt(np.maximum(2 * (c.motion.T0 + dT), 0.0) / Js), c.omega_m)
        eps = np.where(pos, (M - dJ * w**2 / 2) / Js, 0.0)
        return self.sign * w, self.sign * eps

    def omega_of(self, phi) -> np.ndarray:
        """Signed omega1(phi) of the steady motion (rad/s)."""
        return self.motion_at(phi)[0]

    def epsilon_of(self, phi) -> np.ndarray:
        """Signed epsilon1(phi) of the steady motion (rad/s^2), from the equation of
        motion eps = (M_red - J' omega^2/2)/J."""
        return self.motion_at(phi)[1]

    # ---- results.json
    def to_dict(self) -> dict:
        c = self.cycle
        w = c.work
        m = c.motion
        d = {
            "J": _f(c.J),
            "J_energy_mass": _f(c.J_fly["energy-mass"]),
            "J_merzalov": _f(c.J_fly["merzalov"]),
            "J_exact": _f(c.J_fly["exact"]),
            "J_n": _f(c.J_n[c.method]),
            "J_const": _f(c.J_const),
            "delta_achieved": _f(m.delta),
            "omega_max": _f(m.omega_max),
            "omega_min": _f(m.omega_min),
            "M_constant": _f(w.M_constant),
            "diameter": _f(self.size.diameter),
            "width": _f(self.size.width),
            "mass": _f(self.size.mass),
            # extensions
            "method": c.method,
            "constant": self.constant,
            "delta": _f(c.delta),
            "omega_m": _f(c.omega_m),
            "cycle": _f(self.cycle_deg),
            "resolution": int(self.resolution),
            "phi0": _f(self.phi0),
            "direction": "ccw" if self.sign > 0 else "cw",
            "J_wittenbauer": _f(c.J_fly["wittenbauer"]),
            "J_n_methods": {k: _f(v) for k, v in c.J_n.items()},
            "J_fly_primary": _f(c.J_fly[c.method]),
            "J_extra": _f(c.J_extra),
            "J_var_min": _f(c.J_var_min),
            "J_var_max": _f(c.J_var_max),
            "constant_links": list(c.const_links),
            "energy_mass": {"a": _f(c.a), "b": _f(c.b),
                            "omega_max": _f(c.omega_m * (1 + c.delta / 2)),
                            "omega_min": _f(c.omega_m * (1 - c.delta / 2)),
                            "a_wittenbauer": _f(c.a_w), "b_wittenbauer": _f(c.b_w)},
            "work_cycle": _f(w.A_given),
            "T0": _f(m.T0),
            "rim_speed": _f(self.size.rim_speed),
            "shape": dict(self.shape),
            "thickness": _f(self.size.thickness) if self.size.thickness is not None else None,
            "arrays": {
                "phi_cycle": _l(self.q_deg),
                "phi": _l(self.phi),
                "M_red": _l(w.M_red),
                "M_d": _l(w.M_d),
                "M_c": _l(w.M_c),
                "M_given": _l(w.M_given),
                "M_by_kind": {k: _l(v) for k, v in c.M_by_kind.items()},
                "A_d": _l(w.A_d),
                "A_c": _l(w.A_c),
                "dT": _l(w.dT),
                "J_red": _l(c.J_red),
                "J_var": _l(c.J_var),
                "J_links": {k: _l(v) for k, v in c.J_links.items()},
                "dT_I": _l(c.dT_I),
                "T_II": _l(c.T_II),
                "omega": _l(self.sign * m.omega),
                "epsilon": _l(self.sign * c.epsilon),
            },
            "quadrature": _quadrature_of(self),
            "hand": self.hand,
            "accuracy": self.accuracy,
            "warnings": list(self.warnings),
        }
        return d


def _quadrature_of(r: "DynamicsResult") -> str:
    n = r.quadrature_points
    return "trapezoid" if n == 0 else f"gauss-legendre {n} points per interval"
