"""Shaking force and moment of a linkage, and its counterweights (Artobolevsky, "Teoriya
mekhanizmov i mashin", ch. "Uravnoveshivanie mekhanizmov"; Frolov; Berkof and Lowen, "A new
method for completely force balancing simple linkages", 1969; Norton, *Design of Machinery*,
ch. 12).

The shaking force is what the links' motion makes the frame feel: the resultant of the
frame's reactions less the loads, i.e. minus the inertia forces of all links,
F = sum m_i a_Si, and the shaking moment about the crank's fixed pivot O, minus the
moments of the inertia forces and couples, M = sum [(S_i - O) x m_i a_Si + J_Si eps_i]
(N, N*m; counter-clockwise positive; gravity and the loads are not part of it).

Counterweights (a point mass m at distance r from the link's fixed pivot, at the angle from
the link's axis, fixed pivot -> its other pair point, ccw positive), with the links' mass
moments written as complex numbers in their own frames (mu = m (S - P) e^{-i theta}):

* ``full`` (a four-bar O-A-B-O1): the total centre of mass stays still when the terms in
  e^{i theta1} and e^{i theta3} of M S_total vanish (Berkof-Lowen's linearly independent
  vectors): the crank's mass moment about O becomes -m2 l1 (1 - s2/l2) and the rocker's
  about O1 -m2 l3 s2/l2 (s2: the coupler's centre of mass from A in its frame A->B). The
  shaking force is then zero at every position; the shaking moment is not.
* ``crank`` (a slider-crank O-A-B): the counterweight cancels the rotating masses (the crank
  and the rod's share at A, m2 (1 - s2/l2), exactly) and ``reciprocating_share`` of the
  reciprocating mass m_rec = m_slider + m2 Re(s2/l2) at the crank radius. What remains is
  the rest of the primary force, about (1 - share) m_rec l1 omega^2, the secondary force,
  about m_rec l1 omega^2 lambda (lambda = l1/l2), the share's new force across the guide,
  and the shaking moment.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import field_error
from ..messages import Message

STAGE = "balancing"


def _c(a: np.ndarray) -> np.ndarray:
    """(N, 2) -> (N,) complex."""
    a = np.asarray(a, float)
    return a[..., 0] + 1j * a[..., 1]


@dataclass
class Counterweight:
    role: str               # 'crank' | 'rocker'
    link: str
    pivot: str
    other: str
    m: float
    r: float
    angle: float            # deg from the link's axis pivot -> other, ccw

    def to_dict(self) -> dict:
        # m r (kg*m): the product the balancing conditions fix (Norton and the course books
        # state a counterweight by it; m follows from the radius the task chose)
        return {"link": self.link, "m": self.m, "r": self.r, "mr": self.m * self.r, "angle": self.angle}



def _geometry(mech):
    """The roles of a four-bar or a slider-crank: crank (O, A), coupler or rod (A, B), and the
    rocker (O1, B) or the slider at B on a fixed guide; None where the linkage is neither."""
    if mech.n != 3:
        return None
    crank = mech.crank
    O, A = mech.crank_pivot, mech.crank_pin
    rest = [lk for lk in mech.links if lk.index != crank.index]
    coupler = next((lk for lk in rest if A in lk.local and lk.kind == "bar"), None)
    if coupler is None:
        return None
    third = next(lk for lk in rest if lk.index != coupler.index)
    B = next((p for p in coupler.local if p != A and third.index in mech.owner.get(p, [])), None)
    if B is None:
        return None
    if third.kind == "bar":
        O1 = next((p for p in third.local if 0 in mech.owner.get(p, [])), None)
        return None if O1 is None else ("fourbar", crank, coupler, third, O, A, B, O1)
    if third.kind == "slider" and third.guide is not None and third.guide.link is None:
        return ("slidercrank", crank, coupler, third, O, A, B, None)
    return None


def _mass_moment(kin, lk, pivot: str, other: str, k: int = 0) -> complex:
    """m (S - P) in the link's frame whose axis is pivot -> other (at position k)."""
    P, Q = _c(kin.pos[pivot][k]), _c(kin.pos[other][k])
    e = (Q - P) / abs(Q - P)
    return complex(lk.mass * (_c(kin.pos[f"S{lk.index}"][k]) - P) * np.conj(e))


def check_kind(mech, spec):
    """The linkage's roles (:func:`_geometry`) when it is the kind ``spec.method`` balances (full:
    a four-bar; crank: a slider-crank), else a TaskError naming the method (exit 2; found when
    the task is validated too)."""
    g = _geometry(mech)
    kind = "fourbar" if spec.method == "full" else "slidercrank"
    if g is None or g[0] != kind:
        raise field_error("balancing.counterweights.method",
                           Message("balancing.method_needs", method=spec.method,
                                   kind="four-bar linkage" if kind == "fourbar" else "slider-crank linkage"))
    return g


def counterweights(mech, kin, spec) -> tuple[list[Counterweight], dict]:
    """The counterweights of ``spec`` (a CounterweightSpec) and what remains (a dict)."""
    g = check_kind(mech, spec)
    kind = g[0]
    _, crank, coupler, third, O, A, B, O1 = g
    P, Q = _c(kin.pos[A][0]), _c(kin.pos[B][0])
    l1 = abs(_c(kin.pos[A][0]) - _c(kin.pos[O][0]))
    l2 = abs(Q - P)
    s2 = complex((_c(kin.pos[f"S{coupler.index}"][0]) - P) * np.conj((Q - P) / l2))
    m2 = coupler.mass
    mu1 = _mass_moment(kin, crank, O, A)
    out: list[Counterweight] = []
    remains: dict = {}

    def add(role, lk, piv, oth, need, have):
        c = need - have
        r = float(spec.radius[role])
        m = float(abs(c)) / r
        ang = float(np.degrees(np.angle(c)) % 360.0) if abs(c) > 0 else 0.0
        out.append(Counterweight(role, lk.name, piv, oth, m, r, ang))

    if kind == "fourbar":
        l3 = abs(_c(kin.pos[B][0]) - _c(kin.pos[O1][0]))
        add("crank", crank, O, A, -m2 * l1 * (1 - s2 / l2), mu1)
        add("rocker", third, O1, B, -m2 * l3 * s2 / l2, _mass_moment(kin, third, O1, B))
    else:
        share = float(spec.reciprocating_share)
        m_rec = third.mass + m2 * (s2 / l2).real
        add("crank", crank, O, A, -m2 * l1 * (1 - s2 / l2) - share * m_rec * l1, mu1)
        w = float(np.abs(np.asarray(kin.omega1, float)).max())
        remains = {"reciprocating_share": share, "reciprocating_mass": m_rec, "primary_amplitude": (1 - share) * m_rec * l1 * w ** 2,
                   "secondary_amplitude": m_rec * l1 * w ** 2 * (l1 / l2), "lambda": l1 / l2}
    return out, remains


def with_counterweights(mech, cws):
    """The mechanism with each counterweight (a point mass) added to its link: the link's mass
    M' = M + m, centre of mass S' = (M S + m X)/M' and moment of inertia about it
    J' = J + M |S - S'|^2 + m |X - S'|^2 (parallel axes), with X = P + r e^{i angle} (Q - P)/|Q - P|
    in the link's own frame (P the fixed pivot, Q the other pair point). The geometry is unchanged."""
    from dataclasses import replace

    links = []
    for lk in mech.links:
        M, S, J = float(lk.mass), complex(*lk.com), float(lk.J)
        for cw in (c for c in cws if c.link == lk.name):
            P, Q = complex(*lk.local[cw.pivot]), complex(*lk.local[cw.other])
            X = P + cw.r * np.exp(1j * np.radians(cw.angle)) * (Q - P) / abs(Q - P)
            M2 = M + cw.m
            S2 = (M * S + cw.m * X) / M2
            J = J + M * abs(S - S2) ** 2 + cw.m * abs(X - S2) ** 2
            M, S = M2, S2
        links.append(lk if (M, S, J) == (float(lk.mass), complex(*lk.com), float(lk.J))
                     else replace(lk, mass=M, com=(S.real, S.imag), J=J))
    return replace(mech, links=links)


def _applied(mech, cws) -> dict:
    """results.json ``balancing.applied``: each counterweighted link's mass (kg), centre of mass
    in its own frame (m) and moment of inertia about it (kg*m^2) as the kinetostatics and the
    flywheel take them."""
    out = {}
    for lk in with_counterweights(mech, cws).links:
        if any(c.link == lk.name for c in cws):
            out[lk.name] = {"mass": float(lk.mass), "com": [float(lk.com[0]), float(lk.com[1])], "J": float(lk.J)}
    return out


def _cw_motion(kin, cw: Counterweight):
    """Position and acceleration (complex, (N,)) of a counterweight on a link turning about its
    fixed pivot: X = P + c e^{i theta_axis}, a = (i eps - omega^2)(X - P)."""
    P, Q = _c(kin.pos[cw.pivot]), _c(kin.pos[cw.other])
    e = (Q - P) / np.abs(Q - P)
    X = P + cw.r * np.exp(1j * np.radians(cw.angle)) * e
    w, eps = kin.omega(cw.link), kin.epsilon(cw.link)
    return X, (1j * eps - w ** 2) * (X - P)


ROUNDOFF = 1e-12    # a sum within this share of the sum of its terms' sizes is round-off of 0


def _exact_zero(total: np.ndarray, size: np.ndarray) -> np.ndarray:
    """``total`` with the values at or below ROUNDOFF ``size`` (the sum of the absolute values
    of the terms that made it) set to 0: floating point leaves such a sum at a few eps times
    ``size`` where the exact sum is 0 (a fully force-balanced linkage: about 1e-16 of it), so
    1e-12 keeps every remainder a counterweight's mass carried to 12 digits could leave."""
    return np.where(np.abs(total) <= ROUNDOFF * size, 0.0, total) + 0.0


def shaking(mech, kin, about: str, extra=()) -> dict:
    """Fx, Fy, M (N, N*m; (N,) arrays) of the links (and the counterweights ``extra``); a
    component within round-off of 0 (see :func:`_exact_zero`) is written 0."""
    O = _c(kin.pos[about])
    F = np.zeros(len(kin.phi), complex)
    M = np.zeros(len(kin.phi))
    sx, sy, sm = np.zeros(len(kin.phi)), np.zeros(len(kin.phi)), np.zeros(len(kin.phi))
    for lk in mech.links:
        S = _c(kin.pos[f"S{lk.index}"])
        a = _c(kin.acc(f"S{lk.index}"))
        f, m = lk.mass * a, lk.mass * ((S - O).conj() * a).imag
        j = lk.J * kin.epsilon(lk.name)
        F, M = F + f, M + m + j
        sx, sy, sm = sx + np.abs(f.real), sy + np.abs(f.imag), sm + np.abs(m) + np.abs(j)
    for cw in extra:
        X, a = _cw_motion(kin, cw)
        f, m = cw.m * a, cw.m * ((X - O).conj() * a).imag
        F, M = F + f, M + m
        sx, sy, sm = sx + np.abs(f.real), sy + np.abs(f.imag), sm + np.abs(m)
    Fx, Fy = _exact_zero(F.real, sx), _exact_zero(F.imag, sy)
    return {"Fx": Fx, "Fy": Fy, "F": np.abs(Fx + 1j * Fy), "M": _exact_zero(M, sm)}


def _peak(mech, grid, about: str, sh: dict, key: str, cws=()) -> float:
    """The largest |F| (``key`` "F") or |M| ("M") over the turn: the grid's (``sh`` its values)
    largest local maxima, each refined by a bounded Brent search in the grid step either side
    (the shaking at one crank angle solved afresh, as the grid was), to 1e-9 deg -- the grid's own
    largest is low by O(step^2) (59.0557 N against 59.0582 N on a 1-degree grid)."""
    from ..lazy import minimize_scalar
    from ..linkage.kinematics import solve
    vals = np.abs(np.asarray(sh[key], float))
    top = float(vals.max()) if len(vals) else 0.0
    phi = np.asarray(grid.phi, float)
    if len(vals) < 3 or not np.isfinite(top) or top == 0.0 or np.ndim(grid.omega1) != 0:
        return top
    step = float(phi[1] - phi[0])
    peaks = [k for k in range(len(vals)) if vals[k] >= vals[k - 1] and vals[k] >= vals[(k + 1) % len(vals)]]
    best = top
    for k in sorted(peaks, key=lambda k: -vals[k])[:3]:
        def f(x):
            s = shaking(mech, solve(mech, np.array([x % 360.0]), grid.omega1), about, cws)
            return -abs(float(np.asarray(s[key], float)[0]))
        res = minimize_scalar(f, bounds=(phi[k] - step, phi[k] + step), method="bounded", options={"xatol": 1e-9})
        # between two grid angles the maximum exceeds the grid's by O(step^2) (4e-5 of it at 1 deg): a
        # value far above it is another assembly branch of the single-angle solve, not this motion's
        if -float(res.fun) <= vals[k] * (1 + 1e-3):
            best = max(best, -float(res.fun))
    return best


def _entries(phi, sh) -> list[dict]:
    keys = ("Fx", "Fy", "F", "M")
    cols = [np.asarray(phi, float).tolist()] + [np.asarray(sh[k], float).tolist() for k in keys]
    return [dict(zip(("phi", *keys), row)) for row in zip(*cols)]


@dataclass
class BalancingResult:
    about: str
    shaking: list
    shaking_balanced: list | None
    counterweights: dict | None
    remains: dict
    hodograph: dict
    maxima: dict
    rotor: dict | None = None
    warnings: list = field(default_factory=list)
    applied: dict | None = None              # balancing.apply: the links as the later stages take them
    weights: list = field(default_factory=list, repr=False)   # the Counterweight objects (not written)

    def to_dict(self) -> dict:
        d = {"about": self.about, "shaking": self.shaking}
        if self.shaking_balanced is not None:
            d["shaking_balanced"] = self.shaking_balanced
        if self.counterweights is not None:
            d["counterweights"] = self.counterweights
        if self.remains:
            d["remains"] = self.remains
        d.update(max=self.maxima, hodograph=self.hodograph)
        if self.rotor is not None:
            d["rotor"] = self.rotor
        if self.applied is not None:
            d["applied"] = self.applied
        return d


def analyze(mech, kin, spec, grid=None) -> BalancingResult:
    """The results.json ``balancing`` of a linkage: ``kin`` its kinematics at the reported
    positions, ``grid`` at a fine grid over the turn (the hodographs; default ``kin``),
    ``spec`` the BalancingSection."""
    about = mech.crank_pivot
    grid = kin if grid is None else grid
    cws, remains = ([], {}) if spec.counterweights is None else counterweights(mech, kin, spec.counterweights)
    sh, shg = shaking(mech, kin, about), shaking(mech, grid, about)
    hod = {"phi": np.asarray(grid.phi, float).tolist(), "Fx": shg["Fx"].tolist(), "Fy": shg["Fy"].tolist()}
    maxima = {"F": _peak(mech, grid, about, shg, "F"), "M": _peak(mech, grid, about, shg, "M")}
    balanced = None
    if cws:
        shb, shgb = shaking(mech, kin, about, cws), shaking(mech, grid, about, cws)
        balanced = _entries(kin.phi, shb)
        hod.update(Fx_balanced=shgb["Fx"].tolist(), Fy_balanced=shgb["Fy"].tolist())
        maxima.update(F_balanced=_peak(mech, grid, about, shgb, "F", cws),
                      M_balanced=_peak(mech, grid, about, shgb, "M", cws))
    rotor = None
    if spec.rotor is not None:
        from .rotor import balance_rotor
        rotor = balance_rotor(spec.rotor)
    return BalancingResult(about=about, shaking=_entries(kin.phi, sh), shaking_balanced=balanced,
                           counterweights={c.role: c.to_dict() for c in cws} if cws else None,
                           remains=remains, hodograph=hod, maxima=maxima, rotor=rotor,
                           applied=_applied(mech, cws) if spec.apply else None, weights=cws)
