"""A cam built on a chosen size (for example the student's rounded base radius).

* translating roller or knife-edge follower with offset e: the cam centre lies on the line
  of the offset, ``r0`` from the lowest follower position B0, so
  ``O = (-sigma e, -sqrt(r0^2 - e^2))`` in the design frame of :mod:`.geometry`, and the
  pressure angle is tan(theta) = |ds/dphi - e| / (sqrt(r0^2 - e^2) + s);
* rocker: O is the point, below B0, at ``r0`` from B0 and ``center_distance`` from the
  pivot A (the intersection of two circles).

The least base radius for the allowed pressure angle with the same offset is the
synthesis on that line (:func:`.region.highest_on_vertical`); with the same centre
distance it is found on the circle about A, along which r0 grows monotonically with the
angle from the direction A -> B0: the first admissible point is bracketed on a grid and
located by bisection.
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import StageError
from ..messages import Message
from .geometry import Geometry
from .motion import FAR_DWELL, NEAR_DWELL, RETURN, RISE, Motion
from .region import max_angle

STAGE = "cam"


def check_section(sec, given: set) -> None:
    """Rules of the task's ``cam`` section for the followers and a chosen size (a ValueError
    naming the field, :class:`tmm_cli.task.FieldValueError`)."""
    from ..task import FieldValueError

    def err(field, message):
        return FieldValueError((field,), message)

    f = sec.follower
    if f in ("flat", "knife") and "roller" in given:
        raise err("roller", Message("input.cam_roller_flat_knife", follower=f))
    if f == "flat" and sec.offset != 0.0:
        raise err("offset", Message("input.cam_offset_flat"))
    if f != "flat" and "rho_min_allowed" in given:
        raise err("rho_min_allowed", Message("input.cam_rho_min_flat"))
    chosen = sec.r0 != "auto"
    if chosen and not sec.r0 > 0:
        raise err("r0", Message("input.cam_r0_positive"))
    if sec.center_distance is not None and not (f == "rocker" and chosen):
        raise err("center_distance", Message("input.cam_center_distance_rocker"))
    if not chosen:
        return
    if f in ("translating", "knife"):
        if sec.offset == "auto":
            raise err("offset", Message("input.cam_offset_auto_chosen"))
        if sec.r0 < abs(sec.offset):
            raise err("r0", Message("input.cam_r0_below_offset", r0=sec.r0, offset=abs(sec.offset)))
    elif f == "rocker":
        a, l = sec.center_distance, sec.rocker_length
        if a is None:
            raise err("r0", Message("input.cam_rocker_needs_center_distance"))
        if not abs(a - l) <= sec.r0 <= a + l:
            raise err("r0", Message("input.cam_r0_rocker_range", r0=sec.r0, a=a, l=l, low=abs(a - l),
                                    high=a + l))


def centre(geom: Geometry, r0: float, offset: float | None, center_distance: float | None) -> np.ndarray:
    """Cam centre O (design frame, B0 at the origin) of the chosen size."""
    if geom.kind == "translating":
        e = float(offset)
        return np.array([-geom.sigma * e, -math.sqrt(max(r0 * r0 - e * e, 0.0))])
    l, a = geom.l, float(center_distance)
    x = (a * a - r0 * r0 - l * l) / (2.0 * geom.tau * l)
    return np.array([x, -math.sqrt(max(r0 * r0 - x * x, 0.0))])


def excess(motion: Motion, geom: Geometry, O, th_rise: float, th_ret: float) -> tuple[float, dict]:
    """Largest excess (deg) of the pressure angle over the allowed one and the per-phase maxima.

    Returns (excess, {phase: (max deg, fraction)}); dwells are checked against the larger limit."""
    got = {ph: max_angle(motion, geom, ph, O) for ph in (RISE, RETURN)}
    for ph, span in ((NEAR_DWELL, motion.near_dwell), (FAR_DWELL, motion.far_dwell)):
        if span > 1e-12:
            got[ph] = max_angle(motion, geom, ph, O)
    lim = {RISE: th_rise, RETURN: th_ret, NEAR_DWELL: max(th_rise, th_ret), FAR_DWELL: max(th_rise, th_ret)}
    worst = max(math.degrees(v[0]) - lim[ph] for ph, v in got.items())
    return worst, got


def r0_min_on_circle(motion: Motion, geom: Geometry, a: float, th_rise: float, th_ret: float,
                     scale: float) -> float | None:
    """Least r0 of an admissible cam centre at the distance ``a`` from the rocker pivot (below B0)."""
    A = geom.A
    base = math.atan2(-A[1], -A[0])                    # direction A -> B0
    sgn = -1.0 if math.cos(base) > 0 else 1.0          # the side below B0

    def O_of(d):
        b = base + sgn * d
        return A + a * np.array([math.cos(b), math.sin(b)])

    def ok(d):
        return excess(motion, geom, O_of(d), th_rise, th_ret)[0] <= 0.0

    grid = np.linspace(0.0, math.pi, 181)[1:]
    prev = 0.0
    for d in grid:
        if ok(d):
            lo, hi = prev, float(d)
            for _ in range(60):                      # 2^-60 of a degree-wide bracket
                mid = 0.5 * (lo + hi)
                if ok(mid):
                    hi = mid
                else:
                    lo = mid
            return float(np.hypot(*O_of(hi)))
        prev = float(d)
    return None


def violation(r0: float, worst: float, got: dict, motion: Motion, th_rise: float, th_ret: float,
              r0_min: float | None, what: str) -> StageError:
    """The exit-3 error of a chosen size whose pressure angle exceeds the allowed one."""
    lim = {RISE: th_rise, RETURN: th_ret, NEAR_DWELL: max(th_rise, th_ret), FAR_DWELL: max(th_rise, th_ret)}
    names = {RISE: "rise", RETURN: "return", NEAR_DWELL: "near dwell", FAR_DWELL: "far dwell"}
    ph = max(got, key=lambda p: math.degrees(got[p][0]) - lim[p])
    th, x = got[ph]
    start = motion.starts[{RISE: 0, FAR_DWELL: 1, RETURN: 2, NEAR_DWELL: 3}[ph]]
    span = {RISE: motion.rise, RETURN: motion.ret}.get(ph, 0.0)
    phi = math.degrees(start + x * span) % 360.0
    common = dict(r0=r0 * 1000, theta=math.degrees(th), phase=names[ph], worst=worst, limit=lim[ph], phi=phi,
                  what=what)
    if r0_min is not None:
        return StageError(STAGE, Message("cam.fail.chosen_pressure", r0_min=r0_min * 1000, **common))
    return StageError(STAGE, Message("cam.fail.chosen_pressure_none", **common))
