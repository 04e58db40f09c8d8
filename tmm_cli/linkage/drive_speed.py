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

from ..errors import field_error
from ..messages import Message
from .context import Drive

SOURCES = ("speed", "mean_output_speed", "working_stroke_speed")


def check_output_speed(value) -> tuple[float, str | None]:
    """(magnitude in m/s or rad/s, 'linear' | 'angular' | None for a plain number).
    Raises ValueError for a value that is neither a linear nor an angular speed, or
    not positive."""
    from ..units import check_magnitude, quantity

    if isinstance(value, bool):
        raise ValueError(Message("input.output_speed_bool"))
    if isinstance(value, (int, float)):
        v, kind = check_magnitude(float(value)), None
    else:
        try:
            v, _notes, read_as = quantity(str(value), "output_speed")
        except ValueError as exc:
            if isinstance(exc.args[0], Message) and exc.args[0].code == "input.unit_not_kind":
                raise ValueError(Message("input.output_speed_unit", value=str(value))) from None
            raise
        kind = {"linear_speed": "linear", "speed": "angular"}.get(read_as)
        v = check_magnitude(v)
    if not v > 0:
        raise ValueError(Message("input.output_speed_positive", value=repr(value)))
    return v, kind


def omega_from_mean(V: float, H: float) -> float:
    """|omega1| (rad/s) from the output's mean speed over the cycle V and stroke H."""
    return math.pi * V / H


def omega_from_working(V_w: float, H: float, K: float) -> float:
    """|omega1| (rad/s) from the output's mean speed over the working stroke."""
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
    source = "mean_output_speed" if section.mean_output_speed is not None else "working_stroke_speed"
    V, kind = check_output_speed(getattr(section, source))
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
