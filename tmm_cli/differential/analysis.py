"""Differential analysis (Popov & Timofeev, "Kursovoe proektirovanie po TMM", ch. on
planetary gears; Artobolevsky, "Teoriya mekhanizmov i mashin", §§ on differentials).

A planetary scheme A-D whose members "1", last ("3" in A, "4" in B-D) and "H" all turn.
With the carrier held the train is an ordinary one of ratio

    u = i_{1,last}^H = (w1 - wH) / (wlast - wH)       (Willis)
    A: u = -z3/z1    B: u = -z2 z4/(z1 z3)    C, D: u = +z2 z4/(z1 z3)

(u = 1 - i_1H of the same scheme with the last wheel fixed), so any two members' speeds give
the third. The satellite (the block 2-3) turns at w2 = wH + s (w1 - wH), s = -z1/z2 (A-C, an
external mesh 1-2) or +z1/z2 (D, ring 1).

Torques (external, on each member, ccw positive), steady motion: their sum is zero,

    T1 + Tlast + TH = 0,

and in the motion relative to the carrier the power goes from the member that drives it to
the other through the train of efficiency eta:

    Tlast (wlast - wH) = -eta^k T1 (w1 - wH),   k = +1 when member 1 drives (T1 (w1 - wH) > 0),
                                                k = -1 when the last wheel drives,

i.e. Tlast = -u eta^k T1. With eta = 1 the external powers sum to zero; with eta < 1 they sum to
the loss P_loss = T1 w1 + Tlast wlast + TH wH >= 0. Where the members do not move relative
to the carrier (w1 = wH) no power passes the meshes and eta does not act (k = 0).
Given the carrier's torque, T1 (1 - u eta^k) = -TH. Where neither k is consistent with it
(u > 0 near 1 and eta < 1) the train self-locks; where both are (u eta < 1 < u / eta, the other
sign of TH) the torque does not determine T1: which holds is the drive's choice. Either is a
StageError. With u eta^k = 1 (u = 1 and eta = 1, or u = 1 and w1 = wH) Tlast = -T1 for any T1:
a non-zero TH cannot be balanced, a zero one leaves T1 open (an invalid task, naming the torque);
a zero TH otherwise gives zero torques.

Velocity picture (Smirnov's method): on the radial line through the axis and a satellite's
centre, each member's tangential velocity is a straight line v(y): wheel 1, the last wheel and
the carrier through the axis (v = w y), the satellite through its centre's velocity wH a_w
with slope w2. Where two wheels mesh their lines cross on the pitch radius: a second method
for the satellite's speed, reported beside Willis'.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction

from ..errors import StageError, field_error
from ..messages import Message
from .spec import last_member, members

STAGE = "differential"
RPM = 30.0 / math.pi          # rad/s -> rpm


def willis_ratio(scheme: str, teeth: dict) -> Fraction:
    """u = (w1 - wH)/(wlast - wH), exact, from the scheme's ratio with the last wheel fixed."""
    from ..gears.planetary import ratio_exact
    return 1 - ratio_exact(scheme, teeth)


def third_speed(u: float, given: dict, last: str) -> dict:
    """The three members' speeds {"1", last, "H"} from two of them by Willis' formula."""
    w = dict(given)
    if "H" not in w:
        if u == 1:
            raise ValueError("u = 1")
        w["H"] = (w["1"] - u * w[last]) / (1 - u)
    elif "1" not in w:
        w["1"] = w["H"] + u * (w[last] - w["H"])
    elif last not in w:
        w[last] = w["H"] + (w["1"] - w["H"]) / u
    return {"1": w["1"], last: w[last], "H": w["H"]}


def torques(u: float, w: dict, last: str, given: dict, eta: float) -> tuple[dict, int]:
    """The external torques on the three members from one given, and k (the exponent of eta)."""
    rel1 = w["1"] - w["H"]
    (member, value), = given.items()

    def from_t1(t1: float, k: int) -> dict:
        tl = -u * eta ** k * t1
        return {"1": t1, last: tl, "H": -t1 - tl}

    def k_of(t1: float) -> int:
        p = t1 * rel1
        return 0 if p == 0 else (1 if p > 0 else -1)

    if member == "1":
        return from_t1(value, k_of(value)), k_of(value)
    if member == last:
        t1_sign = -value / u                       # sign of T1 whatever eta^k (> 0)
        k = k_of(t1_sign)
        return from_t1(-value / (u * eta ** k), k), k
    # the carrier's torque: T1 (1 - u eta^k) = -TH, k consistent with the T1 it gives
    if rel1 == 0 or eta == 1:
        # no loss in the relative motion (eta^k = 1): T1 (1 - u) = -TH; with u = 1 the wheel
        # `last` takes -T1 whatever T1 and the carrier nothing
        if u == 1:
            if value == 0:
                raise field_error(f"{STAGE}.torque.H", Message("differential.carrier_indeterminate", u=u, eta=eta,
                                                               last=last))
            raise field_error(f"{STAGE}.torque.H", Message("differential.carrier_unbalanced", value=value,
                                                           last=last))
        t1 = -value / (1 - u)
        k = k_of(t1) if eta == 1 else 0
        return from_t1(t1, k), k
    if value == 0:
        # no load: T1 (1 - u eta^k) = 0 gives T1 = 0 (no power passes the meshes), unless
        # u eta^k = 1 for a k, which balances any T1 of that k's sign
        if any(u * eta ** k == 1 for k in (1, -1)):
            raise field_error(f"{STAGE}.torque.H", Message("differential.carrier_indeterminate", u=u, eta=eta,
                                                           last=last))
        return from_t1(0.0, 0), 0
    found = []
    for k in (1, -1):
        den = 1 - u * eta ** k
        if den != 0:
            t1 = -value / den
            if k_of(t1) == k:
                found.append((k, t1))
    if not found:
        raise StageError(STAGE, Message("differential.fail.self_locking", u=u, eta=eta))
    if len(found) == 2:
        # both directions of the power flow balance the torque: which holds is the drive's
        # choice, not this torque's (a train self-braking in the relative motion)
        t1 = dict(found)
        raise StageError(STAGE, Message("differential.fail.indeterminate", u=u, eta=eta, value=value, last=last,
                                        t1_first=t1[1], t1_last=t1[-1]))
    k, t1 = found[0]
    return from_t1(t1, k), k


@dataclass
class DifferentialResult:
    scheme: str
    z: dict
    satellites: int
    u: float
    speeds: dict
    satellite_relative: float
    torques: dict | None
    powers: dict | None
    loss: float | None
    efficiency: float
    eta_exponent: int | None
    given_speeds: list
    given_torque: str | None
    m: float
    m_given: bool
    plan: dict
    checks: dict
    warnings: list = field(default_factory=list)

    def to_dict(self) -> dict:
        sp = dict(self.speeds)
        d = {"scheme": self.scheme, "last": last_member(self.scheme), "z": dict(self.z), "satellites": self.satellites,
             "u": self.u,
             "given": {"speeds": list(self.given_speeds), "torque": self.given_torque},
             "speeds": sp, "speeds_rpm": {k: v * RPM for k, v in sp.items()},
             "satellite_relative": self.satellite_relative, "efficiency": self.efficiency}
        if self.torques is not None:
            d.update(torques=dict(self.torques), powers=dict(self.powers), power_loss=self.loss,
                     relative_driver=None if not self.eta_exponent else ("1" if self.eta_exponent > 0 else
                                                                         "last"))
        d.update(m=self.m, m_given=self.m_given, checks=dict(self.checks), velocity_plan=self.plan,
                 warnings=list(self.warnings))
        return d



def _plan(scheme: str, teeth: dict, m: float, w: dict, last: str) -> dict:
    """Smirnov's velocity picture: the members' lines v(y) and the points where wheels mesh."""
    from ..gears.planetary import centre_distances
    r = {k: m * v / 2 for k, v in teeth.items()}
    aw = abs(centre_distances(scheme, teeth)[0]) * m
    w_sat = w["satellite"]

    def v_sat(y):
        return w["H"] * aw + w_sat * (y - aw)

    # meshes: (wheel on the axis, its pitch radius, the satellite's wheel)
    r1 = r["z1"]
    r_last = r["z3"] if scheme == "A" else r["z4"]
    points = [{"name": "O", "y": 0.0, "v": 0.0},
              {"name": "A", "y": r1, "v": w["1"] * r1},            # mesh 1-2
              {"name": "C", "y": aw, "v": w["H"] * aw},            # satellite's centre
              {"name": "B", "y": r_last, "v": w[last] * r_last}]   # mesh of the satellite with the last wheel
    lines = {"1": {"slope": w["1"], "y0": 0.0}, last: {"slope": w[last], "y0": 0.0},
             "H": {"slope": w["H"], "y0": 0.0},
             "satellite": {"slope": w_sat, "y0": aw - w["H"] * aw / w_sat if w_sat else None,
                           "v_centre": w["H"] * aw}}
    # the satellite's speed read from the picture: the line through the meshes' points A and B
    # of the satellite (rows 2 and 3 of a double satellite turn together): slope (vB - vA)/(yB - yA)
    # for A (one satellite spans both meshes); for B-D the line through C and A
    if scheme == "A":
        w_plan = (points[3]["v"] - points[1]["v"]) / (r_last - r1)
    else:
        w_plan = (points[1]["v"] - points[2]["v"]) / (r1 - aw) if r1 != aw else None
    return {"m": m, "aw": aw, "points": points, "lines": lines, "satellite_omega_plan": w_plan,
            # the satellite's line must pass both meshes' points: what it misses by (m/s)
            "mismatch": max(abs(points[1]["v"] - v_sat(r1)), abs(points[3]["v"] - v_sat(r_last)))}


def check_buildable(spec) -> float:
    """Coaxiality and adjacency: a train that cannot be built is an invalid task (exit 2, found
    when the task is validated too); the adjacency margin (modules). Tooth limits and the
    assembly of the given number of satellites are not checked here: the user's teeth are
    computed, with a warning (:func:`analyze`)."""
    from ..gears import planetary as pl
    scheme, teeth, k = spec.scheme, spec.teeth, spec.satellites
    a1, a2 = pl.centre_distances(scheme, teeth)
    if not (a1 == a2 and a1 > 0):
        raise field_error("differential.z", Message("differential.not_coaxial", a1=2 * a1, a2=2 * a2))
    margin = pl.adjacency_margin(scheme, teeth, k)
    if margin <= 0:
        raise field_error("differential.satellites", Message("differential.adjacency", k=k, margin=margin))
    return margin


def analyze(spec) -> DifferentialResult:
    """The differential of the task section (a DifferentialSection)."""
    from ..gears import planetary as pl
    from ..gears.train import satellite_speeds

    scheme, teeth, k = spec.scheme, spec.teeth, spec.satellites
    last = spec.last
    names = members(scheme)
    margin = check_buildable(spec)
    warnings: list = []
    bad = pl.undercut_ok(scheme, teeth, pl.Limits())
    if bad:
        warnings.append(Message("differential.tooth_limits", violations=bad))
    p = pl.assembly_p(scheme, teeth, k)
    if p is None:
        warnings.append(Message("differential.assembly", k=k, fits=pl.assembling_counts(scheme, teeth)))
    u_exact = willis_ratio(scheme, teeth)
    u = float(u_exact)
    if u_exact == 1 and set(spec.speeds) == {"1", last}:
        raise field_error("differential.speeds", Message("differential.rigid", last=last))
    w = third_speed(u, {kk: float(v) for kk, v in spec.speeds.items()}, last)
    zl = [teeth[n] for n in pl.SCHEMES[scheme]["wheels"]]
    w_sat, w_rel = satellite_speeds(scheme, zl, w["1"], w["H"])
    tq = pw = loss = expo = None
    if spec.torque:
        tq, expo = torques(u, w, last, {kk: float(v) for kk, v in spec.torque.items()}, float(spec.efficiency))
        pw = {n: tq[n] * w[n] for n in names}
        loss = sum(pw.values())
    m = float(spec.m) if spec.m is not None else 0.001
    speeds = {"1": w["1"], last: w[last], "H": w["H"], "satellite": w_sat}
    plan = _plan(scheme, teeth, m, speeds, last)
    checks = {"coaxial": True, "adjacency": True, "adjacency_margin": margin, "assembly": p is not None,
              "assembly_p": p, "tooth_limits": not bad}
    return DifferentialResult(scheme=scheme, z=teeth, satellites=k, u=u, speeds=speeds, satellite_relative=w_rel,
                              torques=tq, powers=pw, loss=loss, efficiency=float(spec.efficiency),
                              eta_exponent=expo, given_speeds=sorted(spec.speeds), given_torque=next(iter(spec.torque),
                                                                                                   None),
                              m=m, m_given=spec.m is not None, plan=plan, checks=checks, warnings=warnings)
