"""The crank speed from the output's speed (`drive.mean_output_speed` |
`drive.working_stroke_speed`), the course's formulas (Popov & Timofeev; Frolov).

Over one turn of the crank the output travels its stroke H forward and back, so its
mean speed over the cycle is V = 2 H n1/60 = H omega1/pi:  omega1 = pi V / H.
The working stroke takes the crank angle phi_w = 2 pi K/(K + 1) = 2 pi/(1 + 1/K), so
V_w = H omega1/phi_w and
omega1 = V_w phi_w / H = 2 pi V_w / (H (1 + 1/K)).  At K = 1 both give pi V/H.
A rocker output: H is its swing psi (rad) and V an angular speed (rad/s; '12 deg/s').

The positions stage gives H and K; :func:`resolve` returns the :class:`Drive` every later
stage reads (kinematics, dynamics, kinetostatics run at its omega).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import field_error
from ..messages import Message
from .spec import check_output_speed

SOURCES = ("speed", "mean_output_speed", "working_stroke_speed")


@dataclass(frozen=True)
class Drive:
    """The input link's motion at the mean speed.

    Attributes
    ----------
    link : str
        Name of the input link (the crank).
    omega : float
        Mean angular speed, rad/s, signed: positive counter-clockwise.
    sign : float
        Sense of rotation: +1.0 counter-clockwise, -1.0 clockwise (``omega`` has it).
    cycle : float
        Crank rotation of one machine cycle, deg: 360, or 720 (a four-stroke engine).
    source : str
        Where ``omega`` comes from: ``'speed'`` (given), ``'mean_output_speed'`` or
        ``'working_stroke_speed'`` (from the output's speed, stroke and K).
    """
    link: str
    omega: float
    sign: float
    cycle: float
    source: str = "speed"

    @property
    def speed(self) -> float:
        """|omega|, rad/s."""
        return abs(self.omega)

    @property
    def direction(self) -> str:
        """'ccw' | 'cw'."""
        return "ccw" if self.sign > 0 else "cw"

    def to_dict(self) -> dict:
        """results.json ``drive``: omega (rad/s, signed), n (rpm), source."""
        return {"omega": float(self.omega), "n": abs(float(self.omega)) * 30.0 / math.pi,
                "source": self.source}


def omega_from_mean(V: float, H: float) -> float:
    """The crank's speed from the output's mean speed over the cycle.

    Parameters
    ----------
    V : float
        The output's mean speed over the cycle, m/s (rad/s for a rocker).
    H : float
        The output's stroke, m (rad for a rocker).

    Returns
    -------
    float
        |omega1| = pi V / H, rad/s (the output travels 2 H per turn).

    References
    ----------
    Popov & Timofeev; Frolov, *Theory of Machines and Mechanisms*: the mean speed of the
    output V = H omega1/pi.
    """
    return math.pi * V / H


def omega_from_working(V_w: float, H: float, K: float) -> float:
    """The crank's speed from the output's mean speed over the working stroke.

    Parameters
    ----------
    V_w : float
        The output's mean speed over the working stroke, m/s (rad/s for a rocker).
    H : float
        The output's stroke, m (rad for a rocker).
    K : float
        The coefficient of the mean speed (the time ratio of the strokes).

    Returns
    -------
    float
        |omega1| = V_w phi_w / H with phi_w = 2 pi K/(K + 1), rad/s.

    References
    ----------
    Popov & Timofeev; Frolov, *Theory of Machines and Mechanisms*: the mean speed of the
    output over the working stroke V_w = H omega1/phi_w.
    """
    return 2.0 * math.pi * V_w / (H * (1.0 + 1.0 / K))


def resolve(section, positions) -> Drive:
    """The crank's mean motion: its speed given, or found from the output's speed.

    Parameters
    ----------
    section : DriveSection
        The task's ``drive``: ``link``, ``direction`` (its ``sign``), ``cycle`` and one of
        ``speed`` (rad/s), ``mean_output_speed`` or ``working_stroke_speed`` (m/s for a
        slider output; rad/s for a rocker).
    positions : PositionsResult
        The output's stroke ``H`` (m, or deg for a rocker) and the coefficient ``K``.

    Returns
    -------
    Drive
        ``omega`` (rad/s, signed: ccw positive), ``sign``, ``cycle`` (deg), ``source``.

    References
    ----------
    Popov & Timofeev; Frolov, *Theory of Machines and Mechanisms*: the mean speed of the
    output over the cycle V = H omega1/pi and over the working stroke
    V_w = H omega1/phi_w with phi_w = 2 pi K/(K + 1) (module docstring).
    """
    def drive(omega: float, source: str) -> Drive:
        return Drive(link=section.link, omega=section.sign * omega, sign=section.sign,
                     cycle=float(section.cycle), source=source)

    if section.speed is not None:
        return drive(float(section.speed), "speed")
    if section.mean_output_speed is not None:
        source, given = "mean_output_speed", section.mean_output_speed
    else:
        source, given = "working_stroke_speed", section.working_stroke_speed
    V, kind = check_output_speed(given)
    field = f"drive.{source}"
    if positions.H is None or not positions.H > 0:
        raise field_error(field, Message("input.output_no_stroke", output=positions.output))
    rocker = positions.output_kind == "rocker"
    if kind == ("linear" if rocker else "angular"):
        raise field_error(field, Message("input.output_rocker_speed" if rocker else "input.output_slider_speed",
                                         output=positions.output))
    H = math.radians(positions.H) if rocker else float(positions.H)
    if source == "mean_output_speed":
        w = omega_from_mean(V, H)
    else:
        if positions.K is None:
            raise field_error(field, Message("input.output_no_working_stroke"))
        w = omega_from_working(V, H, float(positions.K))
    return drive(w, source)
