"""The task section ``dof2:`` -- a machine with two degrees of freedom (docs/methods.md §7):
the rotary impact mechanism (a rotor O-O1 turning about the fixed point O with a
striker hinged at O1), which is also a double pendulum.

Conventions (docs/methods.md §8: SI units, angles in degrees, ccw positive):

* ``phi`` -- the rotor angle: the direction O -> O1 from +x, ccw.
* ``psi`` -- the striker angle relative to the rotor: the direction O1 -> M
  minus the direction O -> O1 (so ``psi = 0`` is the striker stretched out along
  the rotor, the stable position of the centrifugal pendulum).  The paper
  (V.V. Voronkin, docs/methods.md §10) measures its psi_i
  from the direction O1 -> O: psi_paper = psi - 180 deg.
* Link numbers for the reactions (docs/methods.md §7): ground 0, rotor 1, striker 2.

Example::

    dof2:
      rotor:   {length: 60 mm, mass: 1.2, com: 0, J: 0.0012}
      striker: {length: 90 mm, com: 55 mm, mass: 0.35, J: 2.4e-4}
      drive:   {speed: 1500 rpm, direction: ccw}     # or {moment: 0.8} (N*m), or omit: free
      initial: {phi: 0, psi: 150, psi_dot: 0}
      t_end: 40 ms                                   # or turns: 2
      samples: 401
      impact:  {phi: 270}
"""
# annotations evaluated as written (no `from __future__ import annotations`): pydantic would
# compile and evaluate every field's annotation string when the models are made
import math
from typing import Annotated, Any, Literal

from pydantic import BeforeValidator, Field, WithJsonSchema, field_validator, model_validator

from ..messages import Message
from ..modelbase import _Model
from ..units import Angle, AngularSpeed, Inertia, Length, Mass, MomentQ, Ratio, quantity

__all__ = ["Dof2Section", "RotorSpec", "StrikerSpec", "DriveSpec", "InitialSpec", "ImpactSpec", "Time"]


def _time(value: Any) -> float:
    """A time: a number in seconds or a string with a unit ('40 ms', '0.5 s', '1 min')."""
    if isinstance(value, bool) or value is None:
        raise ValueError(Message("input.unit_expected", kind="time", got=repr(value)))
    if isinstance(value, (int, float)):
        v = float(value)
    elif isinstance(value, str):
        v = quantity(value, "time")[0]       # tmm_cli.numbers' grammar: s, ms, min (Latin or Cyrillic)
    else:
        raise ValueError(Message("input.unit_expected", kind="time", got=type(value).__name__))
    if not math.isfinite(v):
        raise ValueError(Message("input.not_finite"))
    if abs(v) > 1e12:
        raise ValueError(Message("input.time_range", value=v))
    return v


Time = Annotated[float, BeforeValidator(_time), WithJsonSchema({"anyOf": [
    {"type": "number", "description": "in s"},
    {"type": "string", "description": "a time (s, ms, min) with its unit, e.g. '40 ms'"}]})]


def _nonneg(v: float | None, what: str) -> float | None:
    if v is not None and v < 0:
        raise ValueError(Message("input.dof2_negative", what=what, value=v))
    return v


class RotorSpec(_Model):
    """Link 1, the rotor O-O1 turning about the fixed point O."""

    length: Length = Field(..., description="l = |OO1|, m (the striker's hinge O1 on the rotor)")
    mass: Mass = Field(0.0, description="m1, kg (default 0)")
    com: Length = Field(0.0, description="distance |OS1| of the rotor's centre of mass from O along OO1, m "
                                         "(default 0: a balanced rotor)")
    J: Inertia | None = Field(None, description="J_S1: moment of inertia about its centre of mass, kg*m^2")
    J_O: Inertia | None = Field(None, description="alternatively J_O: moment of inertia about O, kg*m^2 "
                                                  "(J_O = J_S1 + m1*com^2)")

    @field_validator("length")
    @classmethod
    def _len(cls, v):
        if v <= 0:
            raise ValueError(Message("input.rotor_length", value=v))
        return v

    @field_validator("mass", "J", "J_O")
    @classmethod
    def _nn(cls, v, info):
        return _nonneg(v, info.field_name)

    @model_validator(mode="after")
    def _inertia(self):
        if self.J is not None and self.J_O is not None:
            raise ValueError(Message("input.rotor_inertia_both"))
        if self.J_O is not None and self.J_O < self.mass * self.com ** 2 * (1 - 1e-12):
            raise ValueError(Message("input.rotor_J_O", J_O=self.J_O, m_com2=self.mass * self.com ** 2))
        return self

    @property
    def inertia_O(self) -> float:
        """J_O: the rotor's moment of inertia about the fixed axis O (Huygens-Steiner)."""
        if self.J_O is not None:
            return float(self.J_O)
        return float(self.J or 0.0) + self.mass * self.com ** 2


class StrikerSpec(_Model):
    """Link 2, the striker O1-M hinged to the rotor at O1; its centre of mass C lies on O1M."""

    length: Length = Field(..., description="l_M = |O1M|, m: the striking point M")
    com: Length | None = Field(None, description="l_c = |O1C|, m, along O1M (negative: behind the hinge); "
                                                 "default length/2")
    mass: Mass = Field(..., description="m2, kg")
    J: Inertia = Field(0.0, description="J_C: moment of inertia about its centre of mass C, kg*m^2")

    @field_validator("length")
    @classmethod
    def _len(cls, v):
        if v <= 0:
            raise ValueError(Message("input.striker_length", value=v))
        return v

    @field_validator("mass", "J")
    @classmethod
    def _nn(cls, v, info):
        return _nonneg(v, info.field_name)

    @model_validator(mode="after")
    def _check(self):
        if self.mass <= 0 and self.J <= 0:
            raise ValueError(Message("input.striker_mass"))
        return self

    @property
    def l_c(self) -> float:
        return float(self.length / 2 if self.com is None else self.com)


class DriveSpec(_Model):
    """What drives the rotor: a constant moment, or a motor that holds its speed."""

    moment: MomentQ | None = Field(None, description="a constant driving moment on the rotor, N*m, ccw positive")
    speed: AngularSpeed | None = Field(None, description="the motor holds the rotor speed omega1 = const "
                                                         "(rad/s or rpm, > 0): only psi is free")
    direction: Literal["ccw", "cw"] = Field("ccw", description="with `speed`: ccw | cw")

    @model_validator(mode="after")
    def _one(self):
        if (self.moment is None) == (self.speed is None):
            raise ValueError(Message("input.dof2_drive_one"))
        if self.speed is not None and self.speed <= 0:
            raise ValueError(Message("input.dof2_speed_positive", value=self.speed))
        if self.moment is not None and "direction" in self.model_fields_set:
            raise ValueError(Message("input.dof2_direction_moment"))
        return self

    @property
    def omega1(self) -> float | None:
        """Signed held rotor speed, rad/s (None for a moment drive)."""
        if self.speed is None:
            return None
        return float(self.speed) * (1.0 if self.direction == "ccw" else -1.0)


class InitialSpec(_Model):
    """The state at t = 0."""

    phi: Angle = Field(0.0, description="rotor angle phi0 (O -> O1 from +x, ccw), deg")
    psi: Angle = Field(0.0, description="striker angle psi0 relative to the rotor, deg (0: along O -> O1)")
    omega: AngularSpeed = Field(0.0, description="rotor speed omega0, rad/s, ccw positive "
                                                 "(with a `speed` drive it is the drive speed)")
    psi_dot: AngularSpeed = Field(0.0, description="relative striker speed dpsi/dt at t = 0, rad/s")


class ImpactSpec(_Model):
    """Where the striker meets the workpiece: the state there is reported."""

    phi: Angle = Field(..., description="the rotor angle at which the striker hits, deg (every crossing "
                                        "phi = this angle + k*360 is reported; the first one is `impact`)")
    stop: bool = Field(False, description="true: the motion ends at the first hit (the pre-impact period only)")


class Dof2Section(_Model):
    """A machine with two degrees of freedom: rotor + hinged striker (docs/methods.md §7)."""

    rotor: RotorSpec = Field(..., description="link 1: {length, mass, com, J or J_O}")
    striker: StrikerSpec = Field(..., description="link 2: {length (to M), com (l_c), mass, J (about C)}")
    gravity: bool = Field(False, description="true: g = 9.81 m/s^2 along -y (default false: a horizontal machine)")
    drive: DriveSpec | None = Field(None, description="{moment} constant moment on the rotor, or {speed, direction} "
                                                      "rotor held at omega1 = const; absent: free motion")
    initial: InitialSpec = Field(default_factory=InitialSpec, description="{phi, psi, omega, psi_dot} at t = 0")
    t_end: Time | None = Field(None, description="duration, s (or give `turns`)")
    turns: Ratio | None = Field(None, description="alternatively: run until the rotor has made this many turns")
    t_max: Time = Field(60.0, description="with `turns`: the longest time searched, s (default 60)")
    samples: int = Field(401, description="number of equally spaced output instants (default 401)")
    impact: ImpactSpec | None = Field(None, description="{phi, stop}: the rotor angle at which the striker hits")

    @model_validator(mode="after")
    def _duration(self):
        if (self.t_end is None) == (self.turns is None):
            raise ValueError(Message("input.dof2_duration"))
        if self.t_end is not None and self.t_end <= 0:
            raise ValueError(Message("input.dof2_positive", name="t_end", value=self.t_end))
        if self.turns is not None and self.turns <= 0:
            raise ValueError(Message("input.dof2_positive", name="turns", value=self.turns))
        if self.t_max <= 0:
            raise ValueError(Message("input.dof2_positive", name="t_max", value=self.t_max))
        if not 2 <= self.samples <= 100001:
            raise ValueError(Message("input.dof2_samples", value=self.samples))
        if (self.drive is not None and self.drive.speed is not None
                and "omega" in self.initial.model_fields_set
                and abs(self.initial.omega - self.drive.omega1) > 1e-9 * abs(self.drive.omega1)):
            raise ValueError(Message("input.dof2_omega", omega1=self.drive.omega1, omega=self.initial.omega))
        return self
