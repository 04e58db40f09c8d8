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


def centre(geom: Geometry, r0: float, offset: float | None, center_distance: float | None) -> np.ndarray:
    """Cam centre O of a cam of the chosen size.

    Parameters
    ----------
    geom : Geometry
        The follower's geometry (translating or rocker; the rocker's length ``l`` in m).
    r0 : float
        The chosen base radius, m.
    offset : float or None
        Translating follower: the offset e, m (None for a rocker).
    center_distance : float or None
        Rocker: the distance a from the cam centre to the rocker's pivot, m.

    Returns
    -------
    numpy.ndarray
        O = (x, y) in the design frame (B0 at the origin), m: ``(-sigma e, -sqrt(r0^2 - e^2))``
        for a translating follower, the intersection below B0 of the circles of radii r0
        about B0 and a about the pivot for a rocker.
    """
    if geom.kind == "translating":
        e = float(offset)
        return np.array([-geom.sigma * e, -math.sqrt(max(r0 * r0 - e * e, 0.0))])
    l, a = geom.l, float(center_distance)
    x = (a * a - r0 * r0 - l * l) / (2.0 * geom.tau * l)
    return np.array([x, -math.sqrt(max(r0 * r0 - x * x, 0.0))])


def excess(motion: Motion, geom: Geometry, O, th_rise: float, th_ret: float) -> tuple[float, dict]:
    """Largest excess of the pressure angle over the allowed one for a given cam centre.

    Parameters
    ----------
    motion : Motion
        The follower's motion.
    geom : Geometry
        The follower's geometry.
    O : array_like
        The cam centre (x, y) in the design frame, m.
    th_rise, th_ret : float
        The allowed pressure angles on the rise and on the return, deg (the dwells are
        checked against the larger).

    Returns
    -------
    excess : float
        max over the phases of (greatest pressure angle - allowed one), deg; <= 0 when the
        centre is admissible.
    got : dict
        phase index -> (greatest pressure angle, rad; the fraction of the phase where it is).
    """
    got = {ph: max_angle(motion, geom, ph, O) for ph in (RISE, RETURN)}
    for ph, span in ((NEAR_DWELL, motion.near_dwell), (FAR_DWELL, motion.far_dwell)):
        if span > 1e-12:
            got[ph] = max_angle(motion, geom, ph, O)
    lim = {RISE: th_rise, RETURN: th_ret, NEAR_DWELL: max(th_rise, th_ret), FAR_DWELL: max(th_rise, th_ret)}
    worst = max(math.degrees(v[0]) - lim[ph] for ph, v in got.items())
    return worst, got


def r0_min_on_circle(motion: Motion, geom: Geometry, a: float, th_rise: float, th_ret: float,
                     scale: float) -> float | None:
    """Least base radius of an admissible cam centre on the circle about the rocker's pivot.

    Parameters
    ----------
    motion : Motion
        The follower's motion (a rocker's stroke in rad).
    geom : Geometry
        The rocker's geometry (pivot ``A`` in the design frame, m).
    a : float
        The centre distance (cam centre to the pivot), m.
    th_rise, th_ret : float
        The allowed pressure angles on the rise and on the return, deg.
    scale : float
        A length of the problem (the rocker's length), m (kept for the callers' symmetry).

    Returns
    -------
    float or None
        The least r0 = |O B0| of an admissible centre O at the distance ``a`` from A below
        B0, m (bracketed on a 1-degree grid of the angle at A and bisected); None when no
        point of the circle is admissible.
    """
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
    """The exit-3 error of a chosen size whose pressure angle exceeds the allowed one.

    Parameters
    ----------
    r0 : float
        The chosen base radius, m.
    worst : float
        The largest excess of the pressure angle over the allowed one, deg.
    got : dict
        phase index -> (greatest pressure angle, rad; fraction of the phase), as
        :func:`excess` gives it.
    motion : Motion
        The follower's motion (for the cam angle of the worst point).
    th_rise, th_ret : float
        The allowed pressure angles, deg.
    r0_min : float or None
        The least admissible r0 with the same offset or centre distance, m (None: none).
    what : str
        What is kept fixed: ``"offset"`` or ``"centre distance"``.

    Returns
    -------
    StageError
        The coded error ``cam.fail.chosen_pressure`` (or ``..._none``) naming the phase, the
        cam angle (deg) and the least r0 (mm).
    """
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
