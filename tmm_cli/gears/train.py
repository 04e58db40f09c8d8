"""Compound gear drive (``drive_train``): ordinary pairs and planetary stages in series.

Stage ratio u = omega_in / omega_out (input wheel first; Artobolevsky, Popov & Timofeev):
external pair u = -z2/z1, internal pair u = +z2/z1, planetary stages (input central wheel 1,
output carrier H, the last wheel fixed) by Willis' formula (:mod:`.planetary`).  The overall
ratio is the product; shaft i+1 turns at omega_i / u_i.  Satellite (Willis, carrier held):
omega_2 - omega_H = -(z1/z2)(omega_1 - omega_H) for schemes A, B, C, + for D (ring 1).

Synthesis of stages without ``z``: the stages with a ``ratio`` of their own keep it; the others
share u_free = ratio / (product of the given ratios) equally in magnitude, the sign going to the
first free stage able to take it (an external pair is negative, an internal pair and the
schemes A, B positive, C and D either).  A free pair takes z1 = least teeth and the nearest z2;
a free planetary stage is searched over every tooth set meeting the conditions of
:mod:`.planetary`.  Whole trains are ranked by ``ratio_error`` (|error|, size) or ``size``
(largest stage size, sum of teeth, |error|).
"""
from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field
from fractions import Fraction
from typing import TYPE_CHECKING

from ..errors import StageError, field_error
from ..messages import Message
from . import planetary as pl

if TYPE_CHECKING:
    from ..trainspec import DriveTrainSection

STAGE = "drive_train"
CONDITION = {"coaxial": "coaxiality", "assembly": "assembly", "adjacency": "adjacency",
             "undercut": "tooth-limit (undercut)"}
KEEP = 400        # per free planetary stage: candidates carried into the whole-train ranking


def stage_ratio(kind: str, z: list[int], internal: bool = False) -> float:
    """The ratio of one stage of a drive train.

    Parameters
    ----------
    kind : str
        ``pair`` or a planetary scheme's letter A-D.
    z : list of int
        The stage's tooth numbers (input wheel first).
    internal : bool
        A pair: True when z2 is a ring.

    Returns
    -------
    float
        u = omega_in/omega_out: -z2/z1 (external pair), +z2/z1 (internal pair), Willis' i_1H
        (planetary).

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*; Popov & Timofeev, *Kursovoe
    proektirovanie po TMM*: the ratio of a gear pair and Willis' formula; docs/methods.md §6.
    """
    return float(_exact(kind, z, internal))


def _exact(kind: str, z, internal: bool = False) -> Fraction:
    if kind == "pair":
        return (1 if internal else -1) * Fraction(int(z[1]), int(z[0]))
    return pl.ratio_exact(kind, _zdict(kind, z))


def _zdict(kind: str, z) -> dict:
    return {n: int(v) for n, v in zip(pl.SCHEMES[kind]["wheels"], z)}


def satellite_speeds(kind: str, z, omega_in: float, omega_h: float) -> tuple[float, float]:
    """The angular speed of a planetary stage's satellite.

    Parameters
    ----------
    kind : str
        The scheme's letter A-D.
    z : list of int
        The stage's tooth numbers.
    omega_in : float
        The speed of wheel 1, rad/s.
    omega_h : float
        The carrier's speed, rad/s.

    Returns
    -------
    tuple of float
        (absolute, relative to the carrier) speed of the satellite block 2-3, rad/s: by
        Willis, omega_2 - omega_H = -+(z1/z2)(omega_1 - omega_H) (+ for scheme D).
    """
    rel = (1.0 if kind == "D" else -1.0) * z[0] / z[1] * (omega_in - omega_h)
    return omega_h + rel, rel


def stage_size(kind: str, z) -> int:
    """The size of a stage, in teeth, for the ranking.

    Parameters
    ----------
    kind : str
        ``pair`` or a scheme's letter.
    z : list of int
        The stage's tooth numbers.

    Returns
    -------
    int
        The largest wheel of a pair; :func:`.planetary.size_key` of a planetary stage.
    """
    return max(z) if kind == "pair" else int(pl.size_key(kind, _zdict(kind, z)))


def planetary_checks(kind: str, z, k: int, limits: pl.Limits, z_max: int) -> dict:
    """The conditions of a planetary stage with given teeth, the ratio aside.

    Parameters
    ----------
    kind : str
        The scheme's letter A-D.
    z : list of int
        The stage's tooth numbers.
    k : int
        The number of satellites.
    limits : Limits
        The tooth limits.
    z_max : int
        The largest tooth number allowed.

    Returns
    -------
    dict
        ``coaxial``, ``assembly``, ``adjacency``, ``undercut`` -> (holds, the detail in words).

    References
    ----------
    Popov & Timofeev, *Kursovoe proektirovanie po TMM*: the conditions of coaxiality,
    assembly and adjacency; docs/methods.md §6.
    """
    zd = _zdict(kind, z)
    a1, a2 = pl.centre_distances(kind, zd)
    p = pl.assembly_p(kind, zd, k)
    margin = pl.adjacency_margin(kind, zd, k)
    bad = pl.undercut_ok(kind, zd, limits) + [f"{n} = {v} > z_max = {z_max}" for n, v in zd.items() if v > z_max]
    return {"coaxial": (a1 == a2 and a1 > 0, f"centre distances {2 * a1:g} and {2 * a2:g} teeth differ"),
            "assembly": (p is not None, f"{k} equally spaced satellites cannot be assembled "
                                        f"(u z1 (1 + k p)/k is never whole)"),
            "adjacency": (margin > 0, f"neighbouring satellites overlap: 2 a_w/m sin(pi/k) - (z_s + 2) = "
                                      f"{margin:.4g} <= 0"),
            "undercut": (not bad, "tooth limits: " + "; ".join(bad))}


@dataclass
class TrainResult:
    """The compound drive: its stages and shafts, the ratio and the candidates."""

    ratio: float
    required: float | None
    shafts: list
    stages: list
    candidates: list
    best_ratio_error: float | None
    motor_direction: str
    input_source: str
    tolerance: float
    efficiency: float
    rank: str
    split: list
    plan: dict
    synthesised: bool
    motor_power: float | None = None
    warnings: list = field(default_factory=list)

    def to_dict(self) -> dict:
        d = {"ratio": self.ratio}
        if self.required is not None:
            d.update(required=self.required, ratio_error=(self.ratio - self.required) / self.required,
                     best_ratio_error=self.best_ratio_error)
        d.update(shafts=list(self.shafts), stages=[dict(s) for s in self.stages],
                 candidates=[dict(c) for c in self.candidates],
                 # 0 where no power is computed (no flywheel, or a resistance constant), as
                 # the results format fixes; motor_power_computed tells the two apart
                 motor_power=0.0 if self.motor_power is None else self.motor_power,
                 motor_power_computed=self.motor_power is not None,
                 motor_direction=self.motor_direction, input=self.input_source, tolerance=self.tolerance,
                 efficiency=self.efficiency, rank=self.rank, split=list(self.split),
                 synthesised=self.synthesised, velocity_plan=self.plan, warnings=list(self.warnings))
        return d



def _can_take(kind: str, sign: int) -> bool:
    if kind == "pair":
        return True          # the pair kind (internal or not) is fixed below
    return sign > 0 or kind in ("C", "D")


def _free_signs(specs, free, sign_needed):
    """Signs of the free stages: fixed by their kind, the remaining sign to the first C/D stage."""
    signs = {}
    for i in free:
        st = specs[i]
        signs[i] = (1 if st.internal else -1) if st.kind == "pair" else 1
    prod = math.prod(signs.values()) if signs else 1
    if prod != sign_needed:
        for i in free:
            if specs[i].kind in ("C", "D"):
                signs[i] = -signs[i]
                return signs
        return None
    return signs


def required_ratio(spec: DriveTrainSection, drive) -> tuple[float | None, str]:
    """The required overall ratio and how it was found.

    Parameters
    ----------
    spec : DriveTrainSection
        The task's ``drive_train`` section (``ratio``, dimensionless; ``motor_speed``, rad/s).
    drive : Drive or DriveSection or None
        The crank's drive (``speed``, rad/s), or None.

    Returns
    -------
    tuple of (float or None, str)
        The ratio u = omega_motor/omega_crank (None: not given) and its source: ``given``,
        ``motor`` (motor_speed/drive.speed, unsigned yet) or ``none``.
    """
    if spec.ratio is not None:
        return float(spec.ratio), "given"
    if spec.motor_speed is not None and drive is not None:
        return float(spec.motor_speed) / float(drive.speed), "motor"
    return None, "none"


def analyze(spec: DriveTrainSection, drive=None) -> TrainResult:
    """The drive train of a ``drive_train`` section: the stages' tooth numbers, ratios and speeds.

    Parameters
    ----------
    spec : DriveTrainSection
        The task's ``drive_train`` section: the stages (pairs and planetary schemes A-D, with
        or without tooth numbers), the required ratio or the motor's speed (rad/s), the
        tolerance (relative), the tooth limits, ``z_max``, the efficiency and the ranking.
    drive : Drive or DriveSection or None
        The crank's drive (the linkage's Drive or the task's `drive` section: ``speed``,
        rad/s, ``sign``, ``direction``), or None.

    Returns
    -------
    TrainResult
        The overall ratio, the stages with their tooth numbers, ratios and angular speeds
        (rad/s), the shafts' speeds (rad/s), the ranked candidate trains and the velocity
        plans; ``to_dict()`` is the results.json ``drive_train`` section.

    Raises
    ------
    StageError
        No train meets the required ratio within the tolerance, or a free stage cannot take
        its share of the ratio.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*; Popov & Timofeev, *Kursovoe
    proektirovanie po TMM*: the ratio of a compound train as the product of the stages'
    ratios, Willis' formula for the planetary stages, the velocity plans; docs/methods.md §6.
    """
    lim = pl.tooth_limits(spec.z_min_external, spec.z_min_internal, spec.z_min_satellite_in_internal,
                          spec.internal_minus_external_min)
    k, tol, zmax = int(spec.satellites), float(spec.tolerance), int(spec.z_max)
    specs = list(spec.stages)
    req, req_src = required_ratio(spec, drive)
    warnings = []
    given_u = _given_stages(specs, k, lim, zmax, warnings)
    free = [i for i, st in enumerate(specs) if st.z is None]
    if free and req is None and any(specs[i].ratio is None for i in free):
        raise field_error("drive_train.ratio", "stages without z need the required `ratio` "
                                        "(or `motor_speed` with a `drive` section)")
    if req_src == "motor":
        req *= _motor_sign(spec, drive, specs, given_u, free)
    targets = _targets(specs, free, req, given_u)
    split = [{"stage": i, "ratio": targets[i]} for i in sorted(targets)]
    options = [[list(st.z)] if st.z is not None else _stage_options(spec, i, st, targets[i], k, tol, lim, zmax)
               for i, st in enumerate(specs)]
    # ---- whole trains
    kinds = [(st.kind, st.internal) for st in specs]
    rows = _ranked_trains(kinds, options, req, spec.rank)
    chosen = rows[0]
    best = min(abs(r[2]) for r in rows) if req is not None else None
    cands = [{"z": [list(z) for z in r[0]], "ratio": r[1], "ratio_error": r[2] if req is not None else None,
              "size": r[3], "teeth": r[4]} for r in rows[: int(spec.candidates)]]
    if req is not None and abs(chosen[2]) > tol * (1 + 1e-12):
        if free:
            raise StageError(STAGE, Message("drive_train.fail.missed", u=chosen[1], err=chosen[2], req=req, tol=tol))
        warnings.append(Message("drive_train.ratio_missed", ratio=chosen[1], required=req, error=chosen[2],
                                tolerance=tol))
    u_total = chosen[1]
    w0, src, mdir = _input_speed(spec, drive, u_total, warnings)
    shafts, stages = _stage_speeds(kinds, chosen[0], specs, w0, k, lim, zmax)
    from .trainplan import velocity_plans
    plan = velocity_plans(stages, shafts)
    return TrainResult(ratio=u_total, required=req, shafts=shafts, stages=stages, candidates=cands,
                       best_ratio_error=best, motor_direction=mdir, input_source=src, tolerance=tol,
                       efficiency=float(spec.efficiency), rank=spec.rank, split=split, plan=plan,
                       synthesised=bool(free), warnings=warnings)


def check_given(spec) -> None:
    """The given teeth's checks of :func:`analyze` that make the train impossible to build (an
    internal pair without a larger ring, coaxiality, adjacency): a TaskError naming the stage's
    `z` (exit 2), found when the task is validated (``tmm validate``), not only by a run."""
    lim = pl.tooth_limits(spec.z_min_external, spec.z_min_internal, spec.z_min_satellite_in_internal,
                          spec.internal_minus_external_min)
    _given_stages(list(spec.stages), int(spec.satellites), lim, int(spec.z_max), [])


def _given_stages(specs, k: int, lim: pl.Limits, zmax: int, warnings: list) -> dict:
    """The ratios of the stages with given teeth (stage index -> u), with their checks: a tooth
    limit or the assembly of k satellites that fails is warned about; a train that cannot be
    built (an internal pair without a larger ring, coaxiality, adjacency) is an invalid task."""
    given_u = {}
    for i, st in enumerate(specs):
        path = f"drive_train.stages[{i}].z"
        if st.z is None:
            continue
        if st.kind == "pair":
            if not st.internal and min(st.z) < lim.external:
                warnings.append(Message("drive_train.undercut", stage=i, z=min(st.z), limit=lim.external))
            if st.internal and st.z[1] <= st.z[0]:
                raise field_error(path, f"stage {i}: an internal pair needs the ring z2 > z1 (got {st.z})")
        else:
            # given teeth are the user's: a tooth limit or the assembly of k satellites that fails is
            # computed with a warning; a train that cannot be built (coaxiality, adjacency) is an error
            for name, (ok, why) in planetary_checks(st.kind, st.z, k, lim, zmax).items():
                if ok:
                    continue
                if name == "undercut":
                    warnings.append(Message("drive_train.given_tooth_limits", stage=i, scheme=st.kind,
                                            z=list(st.z), violations=why.split(": ", 1)[1].split("; ")))
                elif name == "assembly":
                    warnings.append(Message("drive_train.given_assembly", stage=i, scheme=st.kind, z=list(st.z),
                                            k=k, fits=pl.assembling_counts(st.kind, _zdict(st.kind, st.z))))
                else:
                    raise field_error(path, f"stage {i} (planetary {st.kind}, z = {list(st.z)}): "
                                     f"{CONDITION[name]} condition violated: {why}")
        given_u[i] = stage_ratio(st.kind, st.z, st.internal)
    return given_u


def _motor_sign(spec, drive, specs, given_u: dict, free: list) -> int:
    """The sign of a ratio found from the speeds: the motor's and the crank's senses when both
    are known, else the sign the stages give naturally."""
    if spec.motor_direction is not None and drive is not None:
        return 1 if spec.motor_direction == drive.direction else -1
    natural = math.prod(1 if u > 0 else -1 for u in given_u.values()) if given_u else 1
    for i in free:
        st = specs[i]
        natural *= (1 if st.internal else -1) if st.kind == "pair" else (
            1 if st.ratio is None else int(math.copysign(1, st.ratio)))
    return natural


def _targets(specs, free: list, req: float | None, given_u: dict) -> dict:
    """The ratio each free stage aims at (stage index -> u): its own, or an equal share in
    magnitude of what the given stages leave of ``req``, the sign going to a stage able to take it."""
    targets = {i: float(specs[i].ratio) for i in free if specs[i].ratio is not None}
    shared = [i for i in free if i not in targets]
    if shared:
        u_free = req / math.prod(list(given_u.values()) + list(targets.values()))
        mag = abs(u_free) ** (1.0 / len(shared))
        signs = _free_signs(specs, shared, 1 if u_free > 0 else -1)
        if signs is None:
            raise StageError(STAGE, Message("drive_train.fail.sign", stages=str(shared), u=u_free))
        targets.update({i: signs[i] * mag for i in shared})
    return targets


def _stage_options(spec, i: int, st, u: float, k: int, tol: float, lim: pl.Limits, zmax: int) -> list:
    """The tooth sets a free stage ``i`` may take for the ratio ``u``: one for a pair (least
    teeth on the pinion), the ranked feasible sets of a planetary stage."""
    if st.kind == "pair":
        z1 = lim.satellite_in_internal if st.internal else lim.external
        z2 = int(round(abs(u) * z1))
        if st.internal:
            z2 = max(z2, z1 + lim.difference, lim.internal)
        if (u > 0) != bool(st.internal):
            raise StageError(STAGE, Message("drive_train.fail.pair_sign", i=i, u=u,
                                            kind="internal" if st.internal else "external"))
        if not st.internal and z2 < lim.external:
            raise StageError(STAGE, Message("drive_train.fail.pair_zmin", i=i, u=u, z2=z2, zmin=lim.external))
        if z2 > zmax or z2 < 5:
            raise StageError(STAGE, Message("drive_train.fail.pair_zmax", i=i, u=u, z2=z2, zmax=zmax))
        return [[z1, z2]]
    if st.kind in ("A", "B") and u <= 1:
        raise StageError(STAGE, Message("drive_train.fail.below_one", i=i, kind=st.kind, u=u))
    found, _ = pl.search(st.kind, u, tol, k, lim, zmax, "ratio_error" if spec.rank == "ratio_error"
                         else "size", KEEP, STAGE)
    if spec.rank == "size" and len(found) == KEEP:          # add the most accurate ones too
        more, _ = pl.search(st.kind, u, tol, k, lim, zmax, "ratio_error", KEEP // 4, STAGE)
        seen = {tuple(c["z"].values()) for c in found}
        found += [c for c in more if tuple(c["z"].values()) not in seen]
    if not found:
        near = pl.nearest_ratio(st.kind, u, k, lim, zmax)
        near_txt = (Message("drive_train.hint.nearest", near=near, rel=(near - u) / u) if near is not None
                    else Message("drive_train.hint.none"))
        raise StageError(STAGE, Message("drive_train.fail.none_found", i=i, kind=st.kind, u=u, tol=tol, k=k,
                                        near=near_txt, ext=lim.external, int=lim.internal,
                                        sat=lim.satellite_in_internal))
    return [list(c["z"].values()) for c in found]


def _ranked_trains(kinds: list, options: list, req: float | None, rank: str) -> list:
    """Every combination of the stages' options as (tooth sets, ratio, relative error, size,
    teeth), best first by ``rank``."""
    rows = []
    for combo in itertools.product(*options):
        u = float(math.prod(_exact(kd, z, it) for (kd, it), z in zip(kinds, combo)))
        size = max(stage_size(kd, z) for (kd, _), z in zip(kinds, combo))
        teeth = sum(sum(z) for z in combo)
        err = (u - req) / req if req is not None else 0.0
        rows.append((combo, u, err, size, teeth))
    if rank == "ratio_error":
        rows.sort(key=lambda r: (round(abs(r[2]), 12), r[3], r[4]))
    else:
        rows.sort(key=lambda r: (r[3], r[4], abs(r[2])))
    return rows


def _input_speed(spec, drive, u_total: float, warnings: list) -> tuple[float, str, str]:
    """The input shaft's signed speed (rad/s; 1 when nothing gives it), its source (``motor``,
    ``drive``, ``unit``) and the motor's sense."""
    if spec.motor_speed is not None:
        if spec.motor_direction is not None:
            mdir = spec.motor_direction
        elif drive is not None:
            mdir = drive.direction if u_total > 0 else ("cw" if drive.direction == "ccw" else "ccw")
        else:
            mdir = "ccw"
        w0 = (1.0 if mdir == "ccw" else -1.0) * float(spec.motor_speed)
        if drive is not None:
            out_dir = "ccw" if w0 / u_total > 0 else "cw"
            if out_dir != drive.direction:
                warnings.append(Message("drive_train.output_sense", output=out_dir, drive=drive.direction))
        return w0, "motor", mdir
    if drive is not None:
        w0 = u_total * (drive.sign * drive.speed)
        return w0, "drive", "ccw" if w0 > 0 else "cw"
    return 1.0, "unit", "ccw"


def _stage_speeds(kinds: list, combo, specs, w0: float, k: int, lim: pl.Limits, zmax: int) -> tuple[list, list]:
    """The shafts' speeds from the input's ``w0`` (rad/s) and the rows of the chosen stages."""
    shafts = [w0]
    stages = []
    for i, ((kd, it), z) in enumerate(zip(kinds, combo)):
        u = stage_ratio(kd, z, it)
        w_in, w_out = shafts[-1], shafts[-1] / u
        shafts.append(w_out)
        if kd == "pair":
            stages.append({"type": "pair", "z": list(z), "internal": bool(it), "ratio": u,
                           "omega_in": w_in, "omega_out": w_out, "given": specs[i].z is not None})
        else:
            sat, rel = satellite_speeds(kd, z, w_in, w_out)
            chk = planetary_checks(kd, z, k, lim, zmax)
            stages.append({"type": "planetary", "scheme": kd, "z": list(z), "ratio": u, "omega_in": w_in,
                           "omega_out": w_out, "omega_carrier": w_out, "omega_satellite": sat,
                           "omega_satellite_rel": rel, "checks": {n: bool(v[0]) for n, v in chk.items()},
                           "given": specs[i].z is not None,
                           "assembly_p": pl.assembly_p(kd, _zdict(kd, z), k)})
    return shafts, stages


def motor_shaft(train: dict, flywheel: dict, constant: str) -> dict:
    """The flywheel moved to the motor shaft, and the motor's power.

    Parameters
    ----------
    train : dict
        The results.json ``drive_train`` section (``ratio``, ``efficiency``).
    flywheel : dict
        The results.json ``flywheel`` section (``J``, ``J_n`` in kg*m^2, ``M_constant`` in N*m,
        ``omega_m`` in rad/s).
    constant : str
        The flywheel's constant moment: ``driving`` or ``resistance``.

    Returns
    -------
    dict
        ``flywheel``: J/u^2, J_n/u^2 (kg*m^2) and GD^2 = 4 g J (N*m^2) on the motor shaft;
        ``motor_power``: |M_constant omega_m| / efficiency (W) for a driving constant moment,
        else None.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: reduction of moments of inertia by the
    square of the ratio; docs/methods.md §4.
    """
    u2 = train["ratio"] ** 2
    out = {"J_motor_shaft": flywheel["J"] / u2, "J_n_motor_shaft": flywheel["J_n"] / u2}
    out["GD2_motor_shaft"] = 4 * 9.80665 * out["J_motor_shaft"]
    power = abs(flywheel["M_constant"] * flywheel["omega_m"]) / train["efficiency"] if constant == "driving" else None
    return {"flywheel": out, "motor_power": power}


__all__ = ["analyze", "TrainResult", "stage_ratio", "satellite_speeds", "motor_shaft", "planetary_checks"]
