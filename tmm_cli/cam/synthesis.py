"""Cam mechanism synthesis: smallest cam from the allowed pressure angles, profile.

Entry point :func:`synthesize` takes the task's validated ``cam`` section
(:class:`~tmm_cli.task.CamSection`: SI floats, angles in degrees) and returns a
:class:`CamResult` whose ``to_dict()`` is the results.json ``cam`` section.

Method (docs/methods.md §5; Artobolevsky, Popov & Timofeev, Frolov):

* the motion laws give s, ds/dphi, d2s/dphi2 over the cycle (:mod:`.laws`, :mod:`.motion`);
* the pressure-angle limits on the rise and on the return define half-planes of
  admissible cam centres bounded by the tangent lines of the ``s - ds/dphi`` diagram
  (:mod:`.geometry`); the smallest cam is the point of their intersection nearest to the
  lowest roller-centre position ``B0``, found exactly (:mod:`.region`).  A translating
  follower with a given offset keeps the cam centre on that line; ``offset: auto``
  frees it (best offset); a rocker's pivot is fixed relative to B0 and the cam centre
  gives the centre distance, for ``swing: auto`` both senses are solved and the smaller
  cam kept;
* the profile follows by inverted motion (:mod:`.profile`).

Conventions of the results: lengths in metres, angles in degrees.  Frame of the points:
cam centre O at the origin, the cam's frame coinciding with the fixed frame at phi = 0;
the roller centre starts the rise moving in +y (translating follower: its axis is
vertical, x = offset * (+1 for a ccw cam, -1 for cw)).  ``offset`` is positive on the side
that lowers the rise pressure angle (docs/methods.md §5).  For a rocker, ``s`` is the rocker's turn from
its initial position in degrees, ``ds`` = dpsi/dphi (rad/rad), ``d2s`` in 1/rad, and with
a speed ``v``, ``a``, ``jerk`` are the rocker's angular velocity (rad/s), acceleration and
jerk.

Design choices (documented in the report):

* ``r0_design``: r0 rounded up to a whole millimetre;
* roller ``auto``: r_r = min(0.7 rho_min, 0.4 r0), the lower (safer) ends of the course
  rules r_r <= (0.7..0.8) rho_min and r_r <= (0.4..0.5) r0, not rounded;
* the dwells must satisfy the larger of the two allowed pressure angles (on the dwells
  the follower does not move; for laws that start and end with zero velocity these
  constraints coincide with those at the ends of the rise and return);
* the geometry reported (max pressure angle, rho_min, profile) is that of the exact
  minimum cam (r0, offset, centre distance as reported), so the maximum pressure angle
  equals the allowed one where that limit is active.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ..errors import StageError
from ..messages import Message
from . import chosen, flat
from .division import division_table
from .geometry import Geometry, J
from .laws import LAW_NAMES
from .motion import FAR_DWELL, NEAR_DWELL, RETURN, RISE, Motion
from .profile import Profile
from .region import Family, Tangent, highest_on_vertical, max_angle, nearest, rows

if TYPE_CHECKING:
    from .spec import CamSection

STAGE = "cam"
_PHASE_NAMES = {RISE: "rise", RETURN: "return", NEAR_DWELL: "near_dwell", FAR_DWELL: "far_dwell"}
ROLLER_RULE = "min(0.7*rho_min, 0.4*r0)"
R0_DESIGN_RULE = "r0 rounded up to a whole millimetre"

# accepted excess of the computed maximum pressure angle over the allowed one, deg (the
# region is solved to 1e-13 of the stroke; a larger excess means no valid centre was found)
PA_TOL_DEG = 1e-6

def _f(v):
    """Plain float or None (no NaN/inf in results)."""
    if v is None:
        return None
    v = float(v)
    return v if math.isfinite(v) else None


def _pts(a: np.ndarray) -> list[list[float]]:
    return [[float(p[0]), float(p[1])] for p in np.asarray(a)]


@dataclass
class CamResult:
    """The cam stage: the base radius, offset, roller and the profile with its checks."""

    follower: str
    rotation: str
    swing: str | None
    stroke: float                      # m | deg
    rocker_length: float | None
    phases: dict
    allowed: dict                      # allowed pressure angles, deg
    r0: float
    offset: float | None
    center_distance: float | None
    psi0: float | None                 # rocker: angle O-A-B0, deg
    roller: float
    roller_given: bool
    max_pressure_angle: float          # deg
    max_pressure_angle_rise: float
    max_pressure_angle_return: float
    max_pressure_angle_phi: float
    rho_min: float
    rho_min_phi: float
    laws: dict
    impacts: list
    phi: np.ndarray                    # deg grid
    s: np.ndarray
    ds: np.ndarray
    d2s: np.ndarray
    d3s: np.ndarray
    speed: float | None
    pressure_angle: np.ndarray         # deg, magnitude
    pitch: np.ndarray                  # (N, 2)
    working: np.ndarray                # (N, 2)
    construction: dict
    alternatives: dict
    warnings: list = field(default_factory=list)
    extra: dict = field(default_factory=dict)     # follower- and size-specific keys (flat, chosen r0)
    # internals for export / tests (not serialised)
    motion: Motion | None = None
    geometry: Geometry | None = None
    O_design: np.ndarray | None = None

    @property
    def r0_design(self) -> float:
        return math.ceil(self.r0 * 1000.0 - 1e-9) / 1000.0

    @property
    def profile(self) -> Profile:
        return Profile(self.motion, self.geometry, self.O_design)

    def to_dict(self) -> dict:
        rocker = self.follower == "rocker"
        conv = math.degrees if rocker else (lambda v: v)
        w = self.speed
        d = {
            "r0": _f(self.r0),
            "offset": _f(self.offset) if self.offset is not None else None,
            "center_distance": _f(self.center_distance) if self.center_distance is not None else None,
            "roller": _f(self.roller),
            "max_pressure_angle": _f(self.max_pressure_angle),
            "rho_min": _f(self.rho_min),
            "r0_design": _f(self.r0_design),
            "r0_design_rule": R0_DESIGN_RULE,
            "roller_rule": "given" if self.roller_given else ROLLER_RULE,
            "follower": self.follower,
            "rotation": self.rotation,
            "swing": self.swing,
            "stroke": _f(self.stroke),
            "rocker_length": _f(self.rocker_length),
            "psi0": _f(self.psi0),
            "phases": dict(self.phases),
            "pressure_angle_allowed": dict(self.allowed),
            "max_pressure_angle_rise": _f(self.max_pressure_angle_rise),
            "max_pressure_angle_return": _f(self.max_pressure_angle_return),
            "max_pressure_angle_phi": _f(self.max_pressure_angle_phi),
            "rho_min_phi": _f(self.rho_min_phi),
            "laws": self.laws,
            "impacts": self.impacts,
            "phi": [float(v) for v in self.phi],
            "s": [float(conv(v)) for v in self.s],
            "ds": [float(v) for v in self.ds],
            "d2s": [float(v) for v in self.d2s],
            "speed": _f(w),
            "v": [float(v * w) for v in self.ds] if w else None,
            "a": [float(v * w * w) for v in self.d2s] if w else None,
            "jerk": [float(v * w ** 3) for v in self.d3s] if w else None,
            "pressure_angle": [float(v) for v in self.pressure_angle],
            "pitch_profile": _pts(self.pitch),
            "working_profile": _pts(self.working),
            "construction": self.construction,
            "alternatives": self.alternatives,
            "warnings": list(self.warnings),
        }
        d.update(self.extra)
        return d


# ---------------------------------------------------------------------- helpers
# an allowed pressure angle above this is told (the course's are 30 deg for a translating follower,
# 45 for a rocker): past it the cam pushes with over twice the force the follower's motion takes
# (1/cos 60 = 2), the follower can jam in its guide, and the cam that comes out is a sliver
PRESSURE_HIGH = 60.0


GRID_DEG = 1.0          # the step of the result's arrays (the tables, the diagrams, the profile's exports)
FEW_STEPS = 10          # a rise or return of fewer steps is shown coarsely: said


def _coarse_phases(spec: CamSection, warnings: list) -> None:
    """``cam.phase_coarse`` for a rise or return shorter than FEW_STEPS steps of the result's
    grid: the arrays (tables, diagrams, cam_profile.csv and .dxf) show it coarsely, or miss it
    below one step; r0, rho_min and the pressure angles are found on the laws themselves."""
    for name, angle in (("rise", spec.phases.rise), ("return", spec.phases.return_)):
        if angle < FEW_STEPS * GRID_DEG:
            warnings.append(Message("cam.phase_coarse", phase=name, angle=float(angle), step=GRID_DEG,
                                    steps=FEW_STEPS))


def _limits(spec: CamSection) -> tuple[float, float]:
    """The allowed pressure angles on the rise and on the return, deg (the task model turns a
    single angle, a transmission angle or none into the pair)."""
    pa = spec.pressure_angle
    rise, ret = float(pa.rise), float(pa.return_)
    for name, v in (("rise", rise), ("return", ret)):
        if not 0.0 < v < 90.0:
            raise StageError(STAGE, Message("cam.fail.pressure_range", phase=name, value=v))
    return rise, ret


def _rocker_hint(swing: float, th_rise: float, th_ret: float) -> str:
    """With dwells at both ends the rocker's velocity turns through the swing while the cam
    centre is seen from B0 and from the far position in nearly one direction when far away:
    the best maximum pressure angle then tends to half the swing (found by brute force over
    cam centres as well), so smaller limits leave the region empty."""
    if min(th_rise, th_ret) <= swing / 2:
        return Message("cam.fail.rocker_hint", swing=swing, half=swing / 2)
    return Message("text", text="")


def _families(motion: Motion, th_rise: float, th_ret: float) -> list[Family]:
    tr, td = math.tan(math.radians(th_rise)), math.tan(math.radians(th_ret))
    fams = [Family(RISE, +1, tr), Family(RISE, -1, tr), Family(RETURN, +1, td), Family(RETURN, -1, td)]
    tdw = math.tan(math.radians(max(th_rise, th_ret)))
    if motion.near_dwell > 1e-12:
        fams += [Family(NEAR_DWELL, +1, tdw), Family(NEAR_DWELL, -1, tdw)]
    if motion.far_dwell > 1e-12:
        fams += [Family(FAR_DWELL, +1, tdw), Family(FAR_DWELL, -1, tdw)]
    return fams


def _law_info(motion: Motion, which: int, speed: float | None, rocker: bool) -> dict:
    law = motion.law_rise if which == RISE else motion.law_return
    P = motion.rise if which == RISE else motion.ret
    ds_max = motion.h * law.cv / P
    d2s_max = motion.h * law.ca / P ** 2 if law.ca is not None else None
    info = {
        "name": law.name, "title": law.title_en,
        "cv": law.cv, "ca": law.ca, "impact": law.impact,
        "ds_max": ds_max, "d2s_max": d2s_max,
        "v_max": ds_max * speed if speed else None,
        "a_max": d2s_max * speed ** 2 if (speed and d2s_max is not None) else None,
    }
    return info


def _solve(motion, geom, fams, offset, scale):
    if geom.kind == "translating" and offset != "auto":
        x0 = -geom.sigma * float(offset)
        return highest_on_vertical(motion, geom, fams, x0, scale)
    sol = nearest(motion, geom, fams, (0.0, 0.0), scale)
    if sol is None:
        raise StageError(STAGE, Message("cam.fail.no_region"))
    return sol


def _region_polygon(motion, geom, fams, O, box):
    """Admissible region clipped to ``box`` = (xmin, ymin, xmax, ymax), as a polygon."""
    from scipy.spatial import HalfspaceIntersection

    ks, sds, tns, xs = [], [], [], []
    for f in fams:
        x = np.linspace(0, 1, 181) if f.phase in (RISE, RETURN) else np.array([0.0])
        ks.append(np.full(x.size, f.phase))
        sds.append(np.full(x.size, f.side))
        tns.append(np.full(x.size, f.tan))
        xs.append(x)
    N, c, _ = rows(motion, geom, np.concatenate(ks), np.concatenate(sds), np.concatenate(tns),
                   np.concatenate(xs))
    xmin, ymin, xmax, ymax = box
    N = np.vstack([N, [[-1, 0], [1, 0], [0, -1], [0, 1]]])
    c = np.concatenate([c, [-xmin, xmax, -ymin, ymax]])
    # an interior point: step from the optimum O against the active normals (cheap);
    # otherwise the Chebyshev centre (largest inscribed circle) by a small LP
    interior = None
    slack0 = c - N @ O
    active = N[np.argsort(slack0)[:4]]
    if len(active):
        d = active.sum(axis=0)
        if np.hypot(*d) > 1e-9:
            for step in (0.05, 0.01, 0.002):
                cand = O - step * (xmax - xmin) * d / np.hypot(*d)
                if np.all(c - N @ cand > 1e-12 * (xmax - xmin)):
                    interior = cand
                    break
    if interior is None:
        from scipy.optimize import linprog

        norms = np.hypot(N[:, 0], N[:, 1])
        res = linprog([0, 0, -1], A_ub=np.column_stack([N, norms]), b_ub=c,
                      bounds=[(None, None), (None, None), (0, None)], method="highs")
        if not res.success or res.x[2] <= 0:
            return []
        interior = res.x[:2]
    hs = HalfspaceIntersection(np.column_stack([N, -c]), interior)
    P = hs.intersections
    ctr = P.mean(axis=0)
    order = np.argsort(np.arctan2(P[:, 1] - ctr[1], P[:, 0] - ctr[0]))
    P = P[order]
    keep = [0] + [i for i in range(1, len(P)) if np.hypot(*(P[i] - P[i - 1])) > 1e-12 * (xmax - xmin)]
    return P[keep]


def _construction(motion, geom, fams, O, tangents: list[Tangent], scale):
    """Data of the graphical construction in the output frame (O at the origin)."""
    out = {"B0": _pts((np.zeros(2) - O)[None])[0], "O": [0.0, 0.0],
           "A": _pts((geom.A - O)[None])[0] if geom.A is not None else None}
    pts = []
    for ph, name in ((RISE, "rise"), (RETURN, "return")):
        P = motion.rise if ph == RISE else motion.ret
        x = np.linspace(0, 1, max(2, int(round(math.degrees(P))) + 1))
        s, s1, _, _ = motion.phase(ph, x)
        B, D, w = geom.pole_point(s, s1)
        out[f"B_{name}"] = _pts(B - O)
        out[f"D_{name}"] = _pts(D - O)
        # the points' crank angles, deg: the phase's start and its n-th parts in degrees (through
        # radians a label read 149.99999999999997)
        k = 0 if ph == RISE else 2
        out[f"phi_{name}"] = [float(v) for v in motion.starts_deg[k]
                              + motion.phases_deg[k] * np.arange(len(x)) / (len(x) - 1)]
        pts.append(B - O)
        pts.append(D - O)
    lines = []
    for t in tangents:
        direction = J(t.n[None])[0]
        start = motion.starts[{RISE: 0, FAR_DWELL: 1, RETURN: 2, NEAR_DWELL: 3}[t.phase]]
        span = {RISE: motion.rise, RETURN: motion.ret}.get(t.phase, 0.0)
        lines.append({"phase": _PHASE_NAMES[t.phase], "side": t.side,
                      "phi": float(math.degrees(start + t.x * span) % 360.0),
                      "point": _pts((t.D - O)[None])[0], "normal": _pts(t.n[None])[0],
                      "direction": _pts(direction[None])[0]})
    out["tangents"] = lines
    allp = np.vstack(pts + [np.zeros((1, 2)), -O[None]])
    lo, hi = allp.min(axis=0), allp.max(axis=0)
    pad = 0.3 * max(hi - lo)
    lo, hi = lo - pad, hi + pad
    lo[1] = min(lo[1], -pad)
    poly = _region_polygon(motion, geom, fams, O, (lo[0] + O[0], lo[1] + O[1], hi[0] + O[0], hi[1] + O[1]))
    out["region"] = _pts(np.asarray(poly) - O) if len(poly) else []
    out["box"] = [float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1])]
    return out


# ---------------------------------------------------------------------- main
def synthesize(spec: CamSection) -> CamResult:
    """Synthesise the smallest cam for the allowed pressure angles, and its profile.

    Parameters
    ----------
    spec : CamSection
        The task's ``cam`` section, validated by the task model: the follower kind, the
        stroke (m; deg for a rocker), the phase angles (deg), the motion laws, the allowed
        pressure angles (deg), the offset or rocker length (m), the roller (m or ``auto``),
        the sense of rotation, the cam speed (rad/s, optional) and an optional chosen base
        radius ``r0`` (m).

    Returns
    -------
    CamResult
        The base radius r0 (m), offset or centre distance (m), roller radius (m), the
        greatest pressure angle (deg), the least radius of curvature (m), the motion
        diagrams over the cycle and the pitch and working profiles (m); ``to_dict()`` is
        the results.json ``cam`` section.

    Raises
    ------
    StageError
        No admissible cam centre, a cusp on the profile, a roller that undercuts it, or a
        chosen r0 below the least one.

    Notes
    -----
    The admissible cam centres are bounded by the tangents to the ``s - ds/dphi`` diagram
    drawn at the allowed pressure angles; the smallest cam is the nearest admissible point
    to the lowest follower position (see the module's docstring).

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*; Popov & Timofeev, *Kursovoe
    proektirovanie po TMM*; Frolov (ed.), *Teoriya mekhanizmov i mashin*: the least size of a
    cam from the allowed pressure angle, the profile by inverted motion; docs/methods.md §5.
    """
    follower, rotation = spec.follower, spec.rotation
    stroke, rocker_length = _check_follower(spec)
    rocker = follower == "rocker"
    sigma = 1 if rotation == "ccw" else -1
    h, scale = (math.radians(stroke), rocker_length) if rocker else (stroke, stroke)
    motion = _motion(spec, h)
    th_rise, th_ret = _limits(spec)
    r0_chosen = None if spec.r0 == "auto" else float(spec.r0)
    divisions = int(spec.divisions)
    if follower == "flat":
        return _flat(spec, motion, stroke, r0_chosen, divisions)
    fams = _families(motion, th_rise, th_ret)
    warnings: list[Message] = []
    _coarse_phases(spec, warnings)
    if max(th_rise, th_ret) > PRESSURE_HIGH:     # the cam is sized for it, and said to be no cam to build
        warnings.append(Message("cam.pressure_high", angle=max(th_rise, th_ret), usual=45.0 if rocker else 30.0,
                                high=PRESSURE_HIGH, force=1 / math.cos(math.radians(max(th_rise, th_ret)))))

    # ---- smallest cam
    if rocker:
        size = _rocker_size(spec, motion, fams, sigma, rocker_length, th_rise, th_ret, r0_chosen, warnings)
    else:
        size = _translating_size(spec, motion, fams, sigma, scale, r0_chosen)
    geom, O, r0 = size.geom, size.O, size.r0
    _check_size(size, motion, scale, th_rise, th_ret, r0_chosen)

    # ---- pressure angles
    th_max, th_max_rise, th_max_ret, th_max_phi = _pressure_angles(motion, geom, O, th_rise, th_ret)

    # ---- profile
    prof = Profile(motion, geom, O)
    if prof.min_speed() <= 1e-9 * scale:
        raise StageError(STAGE, Message("cam.fail.cusp"))
    rho_min, rho_phi = prof.rho_min()
    roller, roller_given = _roller(spec, r0, rho_min, rho_phi, warnings)

    # ---- grid values
    phi = np.arange(0.0, 360.0, GRID_DEG)
    phr = np.radians(phi)
    s, s1, s2, s3 = motion.evaluate(phr)
    pa, _ = geom.pressure_angle(s, s1, O)
    pitch, _, _ = prof.pitch(phr)
    working = prof.working(phr, roller)

    # ---- laws and impacts
    speed, laws_info, impacts, phases = _laws_impacts(spec, motion, rocker, warnings)
    corners = [e for e in impacts if e["kind"] == "rigid"]
    if corners:
        warnings.append(Message("cam.profile_corners_knife" if follower == "knife" else "cam.profile_corners",
                                phis=[e["phi"] for e in corners]))

    construction = _construction(motion, geom, fams, O, size.tangents, scale)
    extra = {"r0_min": _f(size.r0_min), "r0_given": r0_chosen is not None,
             "division_table": division_table(motion, divisions, rocker,
                                              lambda s, s1: geom.pressure_angle(s, s1, O)[0])}
    return CamResult(
        follower=follower, rotation=rotation, swing=size.swing, stroke=stroke, rocker_length=rocker_length,
        phases=phases, allowed={"rise": th_rise, "return": th_ret},
        r0=r0, offset=size.offset, center_distance=size.center_distance, psi0=size.psi0,
        roller=roller, roller_given=roller_given,
        max_pressure_angle=th_max, max_pressure_angle_rise=th_max_rise,
        max_pressure_angle_return=th_max_ret, max_pressure_angle_phi=th_max_phi,
        rho_min=rho_min, rho_min_phi=rho_phi, laws=laws_info, impacts=impacts,
        phi=phi, s=s, ds=s1, d2s=s2, d3s=s3, speed=speed,
        pressure_angle=np.degrees(pa), pitch=pitch, working=working,
        construction=construction, alternatives=size.alternatives, warnings=warnings, extra=extra,
        motion=motion, geometry=geom, O_design=O,
    )


def _check_follower(spec: CamSection) -> tuple[float, float | None]:
    """The stroke (m, or deg for a rocker) and the rocker's length (m; None for a translating
    follower), with the checks of the follower, the stroke and the laws."""
    if spec.follower not in ("translating", "rocker", "knife", "flat"):
        raise StageError(STAGE, Message("cam.fail.unknown_follower", follower=str(spec.follower)))
    stroke = float(spec.stroke)
    if not stroke > 0:
        raise StageError(STAGE, Message("cam.fail.stroke"))
    for nm in (spec.laws.rise, spec.laws.return_):
        if nm not in LAW_NAMES:
            raise StageError(STAGE, Message("cam.fail.unknown_law", law=str(nm)))
    if spec.follower != "rocker":
        return stroke, None
    l = spec.rocker_length
    if l is None or not l > 0:
        raise StageError(STAGE, Message("cam.fail.rocker_length"))
    return stroke, float(l)


def _motion(spec: CamSection, h: float) -> Motion:
    """The follower's motion over the cycle (stroke ``h``: m, or rad for a rocker)."""
    motion = Motion.from_spec(h, spec.phases, spec.laws)
    if motion.rise <= 0 or motion.ret <= 0:
        raise StageError(STAGE, Message("cam.fail.phases_positive"))
    total = math.degrees(motion.rise + motion.far_dwell + motion.ret + motion.near_dwell)
    if abs(total - 360.0) > 1e-6:
        raise StageError(STAGE, Message("cam.fail.phases_sum", total=total))
    return motion


@dataclass
class _Size:
    """The cam centre found: its geometry, the centre O in the design frame (m), the base
    radius and the least one (m), the active tangents and the follower's placement."""

    geom: Geometry
    O: np.ndarray
    tangents: list
    r0: float
    r0_min: float | None = None
    swing: str | None = None
    offset: float | None = None
    center_distance: float | None = None
    psi0: float | None = None
    alternatives: dict = field(default_factory=dict)


def _rocker_size(spec: CamSection, motion: Motion, fams: list[Family], sigma: int, l: float,
                 th_rise: float, th_ret: float, r0_chosen: float | None, warnings: list) -> _Size:
    """The rocker's cam centre: the smaller cam of the swing senses allowed (``swing: auto``:
    both), or the centre on a chosen r0 and centre distance."""
    stroke = float(spec.stroke)
    scale = l
    swing_in = spec.swing
    options = ("with", "against") if swing_in == "auto" else (swing_in,)
    alternatives: dict = {}
    best = None
    for sw in options:
        tau = sigma if sw == "with" else -sigma
        geom = Geometry("rocker", sigma, tau, l)
        try:
            O, tang = _solve(motion, geom, fams, "auto", scale)
        except StageError as err:
            if len(options) == 1:
                raise StageError(STAGE, Message("cam.fail.with_hint", first=err.message,
                                                hint=_rocker_hint(stroke, th_rise, th_ret))) from None
            alternatives[sw] = None
            continue
        r0 = float(np.hypot(*O))
        alternatives[sw] = {"r0": r0, "center_distance": float(np.hypot(*(O - geom.A)))}
        if best is None or r0 < best[0] * (1 - 1e-12):
            best = (r0, sw, geom, O, tang)
    if best is None:
        raise StageError(STAGE, Message("cam.fail.no_region_either", hint=_rocker_hint(stroke, th_rise, th_ret)))
    r0, swing, geom, O, tang = best
    if r0_chosen is not None:
        swing, geom, O, tang = _chosen_rocker(spec, motion, best, options, sigma, l, fams, scale,
                                              th_rise, th_ret, r0_chosen)
        r0 = r0_chosen
        alternatives = {}
    if r0_chosen is None and swing_in == "auto" and len([a for a in alternatives.values() if a]) == 2:
        other = "against" if swing == "with" else "with"
        warnings.append(Message("cam.swing_auto", swing=swing, r0=r0 * 1000, other=other,
                                r0_other=alternatives[other]["r0"] * 1000))
    v1, v2 = O - geom.A, -geom.A        # A->O and A->B0
    psi0 = math.degrees(math.acos(np.clip(np.dot(v1, v2) / (np.linalg.norm(v1) * l), -1, 1)))
    return _Size(geom=geom, O=O, tangents=tang, r0=r0, swing=swing,
                 center_distance=float(np.hypot(*(O - geom.A))), psi0=psi0, alternatives=alternatives)


def _translating_size(spec: CamSection, motion: Motion, fams: list[Family], sigma: int, scale: float,
                      r0_chosen: float | None) -> _Size:
    """The translating follower's cam centre: on the line of the given offset, or the nearest
    admissible point (``offset: auto``), or at a chosen r0 on the offset's line."""
    offset_in = spec.offset
    geom = Geometry("translating", sigma)
    O, tang = _solve(motion, geom, fams, offset_in, scale)
    r0 = float(np.hypot(*O))
    r0_min = None
    if r0_chosen is not None:
        r0_min = r0
        r0 = r0_chosen
        O = chosen.centre(geom, r0, offset_in, None)
    offset = -sigma * float(O[0])
    if offset_in != "auto":
        offset = float(offset_in)
    return _Size(geom=geom, O=O, tangents=tang, r0=r0, r0_min=r0_min, offset=offset)


def _check_size(size: _Size, motion: Motion, scale: float, th_rise: float, th_ret: float,
                r0_chosen: float | None) -> None:
    """A cam of non-zero size; the least r0 (``size.r0_min``) and, on a chosen r0, the check of
    its pressure angles."""
    rocker = size.geom.kind == "rocker"
    if not size.r0 > 1e-12 * scale:
        raise StageError(STAGE, Message("cam.fail.zero_r0"))
    if r0_chosen is None:
        size.r0_min = size.r0
    elif rocker:
        size.r0_min = chosen.r0_min_on_circle(motion, size.geom, size.center_distance, th_rise, th_ret, scale)
    if r0_chosen is not None:
        worst, got = chosen.excess(motion, size.geom, size.O, th_rise, th_ret)
        if worst > PA_TOL_DEG:
            raise chosen.violation(size.r0, worst, got, motion, th_rise, th_ret, size.r0_min,
                                   "centre distance" if rocker else "offset")


def _pressure_angles(motion: Motion, geom: Geometry, O: np.ndarray, th_rise: float,
                     th_ret: float) -> tuple[float, float, float, float]:
    """The greatest pressure angle over the cycle, on the rise and on the return, and the cam
    angle where the greatest of the rise and the return occurs, all in deg; a centre that
    exceeds an allowed angle (a numerically lost region) is an error."""
    th = {}
    for ph in (RISE, RETURN):
        th[ph] = max_angle(motion, geom, ph, O)
    dwell_max = 0.0
    for ph, span in ((NEAR_DWELL, motion.near_dwell), (FAR_DWELL, motion.far_dwell)):
        if span > 1e-12:
            dwell_max = max(dwell_max, max_angle(motion, geom, ph, O)[0])
    th_max_rise = math.degrees(th[RISE][0])
    th_max_ret = math.degrees(th[RETURN][0])
    if th_max_rise >= th_max_ret:
        th_max_phi = math.degrees(th[RISE][1] * motion.rise)
    else:
        th_max_phi = math.degrees(motion.starts[2] + th[RETURN][1] * motion.ret)
    th_max = max(th_max_rise, th_max_ret, math.degrees(dwell_max))
    # never report a centre that violates the limits (a numerically lost region)
    for name, got, lim in (("rise", th_max_rise, th_rise), ("return", th_max_ret, th_ret),
                           ("dwells", math.degrees(dwell_max), max(th_rise, th_ret))):
        if not got <= lim + PA_TOL_DEG:
            raise StageError(STAGE, Message("cam.fail.pressure_exceeded", phase=name, limit=lim, got=got))
    return th_max, th_max_rise, th_max_ret, th_max_phi


def _roller(spec: CamSection, r0: float, rho_min: float, rho_phi: float, warnings: list) -> tuple[float, bool]:
    """The roller radius (m) and whether it was given: none for a knife edge, the rule
    min(0.7 rho_min, 0.4 r0) for ``auto``, else the given one checked against the profile's
    least radius of curvature ``rho_min`` (m, at the cam angle ``rho_phi``, deg) and r0 (m)."""
    roller_in = spec.roller
    if spec.follower == "knife":
        return 0.0, False
    if roller_in == "auto":
        return min(0.7 * rho_min, 0.4 * r0), False
    roller = float(roller_in)
    if not roller > 0:
        raise StageError(STAGE, Message("cam.fail.roller_positive"))
    if roller >= rho_min:
        raise StageError(STAGE, Message("cam.fail.roller_undercut", roller=roller * 1000, rho=rho_min * 1000,
                                        phi=rho_phi))
    if roller >= r0:
        raise StageError(STAGE, Message("cam.fail.roller_r0", roller=roller * 1000, r0=r0 * 1000))
    if roller > 0.8 * rho_min:
        warnings.append(Message("cam.roller_rho", roller=roller * 1000, limit=0.8 * rho_min * 1000))
    if roller > 0.5 * r0:
        warnings.append(Message("cam.roller_r0", roller=roller * 1000, limit=0.5 * r0 * 1000))
    return roller, True


def _laws_impacts(spec: CamSection, motion: Motion, rocker: bool, warnings: list):
    """Speed, the laws' coefficients, the impacts (with their warnings) and the phase angles."""
    speed = float(spec.speed) if spec.speed else None
    laws_info = {"rise": _law_info(motion, RISE, speed, rocker),
                 "return": _law_info(motion, RETURN, speed, rocker)}
    impacts = motion.boundaries()
    for e in impacts:
        if e["kind"] != "none":
            warnings.append(Message("cam.rigid_impact" if e["kind"] == "rigid" else "cam.soft_impact", phi=e["phi"], where=e["where"]))
    phases = {"rise": math.degrees(motion.rise), "far_dwell": math.degrees(motion.far_dwell),
              "return": math.degrees(motion.ret), "near_dwell": math.degrees(motion.near_dwell)}
    return speed, laws_info, impacts, phases


def _chosen_rocker(spec: CamSection, motion: Motion, best, options, sigma, l, fams, scale, th_rise, th_ret, r0):
    """Rocker on a chosen r0 and centre distance: the swing sense (for auto: the one with the
    smaller pressure-angle excess) and its cam centre."""
    a = float(spec.center_distance)
    cands = []
    for sw in options:
        tau = sigma if sw == "with" else -sigma
        geom = Geometry("rocker", sigma, tau, l)
        O = chosen.centre(geom, r0, None, a)
        cands.append((chosen.excess(motion, geom, O, th_rise, th_ret)[0], sw, geom, O))
    worst, sw, geom, O = min(cands, key=lambda c: c[0])
    tang = best[4] if best[1] == sw else _solve(motion, geom, fams, "auto", scale)[1]
    return sw, geom, O, tang


def _flat(spec: CamSection, motion: Motion, stroke: float, r0_chosen: float | None, divisions: int) -> CamResult:
    """Flat-faced translating follower (see :mod:`.flat`)."""
    rotation = spec.rotation
    sigma = 1 if rotation == "ccw" else -1
    rigid = [e for e in motion.boundaries() if e["kind"] == "rigid"]
    if rigid:
        raise StageError(STAGE, Message("cam.fail.flat_corner", phis=[e["phi"] for e in rigid]))
    rho_allowed = float(spec.rho_min_allowed)
    margin, margin_phi = flat.convexity_margin(motion)
    r0_min = rho_allowed + margin
    if r0_chosen is None:
        r0 = r0_min
    else:
        r0 = r0_chosen
        if r0 - margin < rho_allowed - 1e-12 * stroke:
            raise StageError(STAGE, Message("cam.fail.flat_r0", r0=r0 * 1000, rho=(r0 - margin) * 1000, phi=margin_phi,
                                            allowed=rho_allowed * 1000, r0_min=r0_min * 1000))
    if not r0 > 1e-12 * stroke:
        raise StageError(STAGE, Message("cam.fail.zero_r0_flat"))
    warnings: list[str] = []
    _coarse_phases(spec, warnings)
    speed, laws_info, impacts, phases = _laws_impacts(spec, motion, False, warnings)
    w_span, w_sym = flat.face_widths(motion)
    phi = np.arange(0.0, 360.0, GRID_DEG)
    phr = np.radians(phi)
    s, s1, s2, s3 = motion.evaluate(phr)
    prof = flat.profile(motion, r0, sigma, phr)
    extra = {"r0_min": _f(r0_min), "r0_given": r0_chosen is not None, "rho_min_allowed": rho_allowed,
             "face_width": _f(w_span), "face_width_symmetric": _f(w_sym),
             "division_table": division_table(motion, divisions, False, None)}
    return CamResult(
        follower="flat", rotation=rotation, swing=None, stroke=stroke, rocker_length=None,
        phases=phases, allowed=dict(zip(("rise", "return"), _limits(spec))), r0=r0, offset=0.0, center_distance=None,
        psi0=None, roller=0.0, roller_given=False, max_pressure_angle=0.0, max_pressure_angle_rise=0.0,
        max_pressure_angle_return=0.0, max_pressure_angle_phi=0.0,
        rho_min=r0 - margin, rho_min_phi=margin_phi, laws=laws_info, impacts=impacts,
        phi=phi, s=s, ds=s1, d2s=s2, d3s=s3, speed=speed, pressure_angle=np.zeros_like(phi),
        pitch=prof, working=prof, construction=None, alternatives={}, warnings=warnings, extra=extra,
        motion=motion, geometry=None, O_design=np.array([0.0, -r0]),
    )
