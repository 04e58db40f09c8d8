"""The task section ``balancing:`` -- counterweights of a linkage and a rigid rotor's balancing.

Example::

    balancing:
      counterweights:
        method: full              # full: the total centre of mass stays still (four-bar:
                                  #   counterweights on the crank and the rocker, Berkof-Lowen);
                                  # crank: the crank's counterweight takes the rotating masses and
                                  #   `reciprocating_share` of the reciprocating ones (slider-crank)
        radius: {crank: 0.10 m, rocker: 0.12 m}   # from the link's fixed pivot
        reciprocating_share: 0.5
      apply: true                 # the kinetostatics and the flywheel with the counterweights on
                                  #   the links (default false: they show the unbalanced linkage)
      rotor:                      # static (one plane) or dynamic (two planes) balancing
        masses: [{m: 0.2 kg, r: 0.10 m, angle: 30, z: 0.05 m}, ...]
        planes: [0, 0.30 m]
        radius: 0.12 m

With a ``mechanism`` the section adds the shaking force and moment at every reported
position (always) and, with ``counterweights``, the same with the counterweights.
"""
# annotations evaluated as written (no `from __future__ import annotations`): pydantic would
# compile and evaluate every field's annotation string when the models are made
from typing import Literal

from pydantic import Field, model_validator

from ..messages import Message
from ..modelbase import FieldValueError, _Model
from ..units import Angle, Length, Mass, Ratio

__all__ = ["BalancingSection", "CounterweightSpec", "RotorSpec", "RotorMass"]


class CounterweightSpec(_Model):
    method: Literal["full", "crank"] = Field(..., description="full: four-bar, the total centre of mass stays "
                                                              "still; crank: slider-crank, the crank's counterweight")
    radius: dict[Literal["crank", "rocker"], Length] = Field(
        ..., description="the counterweights' distance from the link's fixed pivot (m): crank, rocker (full)")
    reciprocating_share: Ratio = Field(0.0, ge=0, le=1, description="crank method: the share of the "
                                                                    "reciprocating masses' primary force taken")

    @model_validator(mode="after")
    def _radii(self):
        if self.method == "full" and "reciprocating_share" in self.model_fields_set:
            raise FieldValueError(("reciprocating_share",), Message("input.balancing_share_full"))
        if self.method == "crank" and "rocker" in self.radius:
            # a rocker's radius with the slider-crank's method: most likely a four-bar given `crank`
            raise FieldValueError(("method",), Message("input.balancing_rocker_crank"))
        need = ("crank", "rocker") if self.method == "full" else ("crank",)
        for k in need:
            if k not in self.radius:
                raise FieldValueError(("radius",), Message("input.balancing_radius", method=self.method, key=k))
            if self.radius[k] <= 0:
                raise FieldValueError(("radius", k), Message("input.balancing_radius_positive", key=k))
        return self


class RotorMass(_Model):
    m: Mass = Field(..., gt=0, description="mass, kg")
    r: Length = Field(..., ge=0, description="distance from the axis, m")
    angle: Angle = Field(0.0, description="angular position, deg (ccw)")
    z: Length = Field(0.0, description="axial position, m")


class RotorSpec(_Model):
    masses: list[RotorMass] = Field(..., min_length=1, max_length=100,
                                    description="the rotor's masses: {m, r, angle, z}")
    planes: list[Length] = Field(..., min_length=1, max_length=2,
                                 description="axial positions of the correction planes: one (static balancing) "
                                             "or two (dynamic)")
    radius: Length = Field(..., gt=0, description="radius of the correction masses, m")

    @model_validator(mode="after")
    def _planes(self):
        if len(self.planes) == 2 and self.planes[0] == self.planes[1]:
            raise FieldValueError(("planes",), Message("input.rotor_planes_equal"))
        return self


class BalancingSection(_Model):
    counterweights: CounterweightSpec | None = Field(None, description="counterweights of the linkage: method, "
                                                                       "radius, reciprocating_share")
    rotor: RotorSpec | None = Field(None, description="a rigid rotor's masses and correction planes: static (one "
                                                      "plane) or dynamic (two planes) balancing")
    apply: bool = Field(False, description="true: the kinetostatics and the flywheel are computed with the "
                                           "counterweights on the links (their masses, centres of mass and "
                                           "moments of inertia as changed); needs counterweights")

    @model_validator(mode="after")
    def _apply_needs_counterweights(self):
        if self.apply and self.counterweights is None:
            raise FieldValueError(("apply",), Message("input.balancing_apply_needs"))
        return self
