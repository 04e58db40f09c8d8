"""The `cam` section of the task file (README, *The task file*): the follower, the phases,
the motion laws and the allowed pressure angle, validated once by the task model
(tmm_cli/task.py composes it), with the rules of the followers and of a chosen size
(:func:`check_section`)."""
# annotations evaluated as written (no `from __future__ import annotations`): pydantic would
# compile and evaluate every field's annotation string when the models are made
from typing import Literal, Union

from pydantic import Field, field_validator, model_validator

from ..messages import Message
from ..modelbase import FieldValueError, _Model
from ..units import Angle, AngularSpeed, Length, Number


def check_section(sec, given: set) -> None:
    """Rules of the task's ``cam`` section for the followers and a chosen size (a ValueError
    naming the field, :class:`tmm_cli.modelbase.FieldValueError`)."""
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


# ---------------------------------------------------------------- cam
class PhasesSpec(_Model):
    rise: Angle = Field(..., gt=0)
    far_dwell: Angle = Field(0.0, ge=0)
    return_: Angle = Field(..., alias="return", gt=0)
    near_dwell: Angle | None = Field(None, ge=0)

    @model_validator(mode="after")
    def _sum(self):
        used = self.rise + self.far_dwell + self.return_
        if self.near_dwell is None:
            if used > 360 + 1e-6:           # as the sum of four is held: 360.0000001 is 360 written to 7 places
                raise ValueError(Message("input.phases_over", used=used))
            self.near_dwell = max(0.0, 360.0 - used)
        elif abs(used + self.near_dwell - 360) > 1e-6:
            raise ValueError(Message("input.phases_sum", total=used + self.near_dwell))
        return self


LawName = Literal["constant_velocity", "parabolic", "cosine", "sine", "poly345",
                  "linear_decreasing", "trapezoidal"]


class LawsSpec(_Model):
    rise: LawName = "cosine"
    return_: LawName = Field("cosine", alias="return")


def _default_laws() -> LawsSpec:
    """LawsSpec() (cosine rise and return) without building its validator."""
    return LawsSpec.model_construct()


class LimitsSpec(_Model):
    rise: Angle = Field(..., gt=0, lt=90)
    return_: Angle = Field(..., alias="return", gt=0, lt=90)


class CamSection(_Model):
    follower: Literal["translating", "rocker", "flat", "knife"] = "translating"
    stroke: Number = Field(..., gt=0, description="the follower's stroke h: m (translating follower) or its swing, deg (rocker)")
    rocker_length: Length | None = Field(None, gt=0)
    offset: Union[Literal["auto"], Length] = 0.0
    phases: PhasesSpec
    laws: LawsSpec = Field(default_factory=_default_laws)
    pressure_angle: Union[LimitsSpec, Angle, None] = None
    transmission_angle: Union[LimitsSpec, Angle, None] = None
    swing: Literal["with", "against", "auto"] = "auto"
    roller: Union[Literal["auto"], Length] = "auto"
    rotation: Literal["ccw", "cw"] = "ccw"
    speed: AngularSpeed | None = Field(None, gt=0)
    r0: Union[Literal["auto"], Length] = "auto"
    center_distance: Length | None = Field(None, gt=0)
    rho_min_allowed: Length = Field(0.0, ge=0)
    divisions: int = Field(8, ge=1, le=360)

    @staticmethod
    def plain_lengths(raw: dict) -> tuple[str, ...]:
        """The fields of ``raw`` (the section as written) that are lengths though their type is a
        plain number: the stroke, but for a rocker (its swing, deg). A plain number there is read
        in m and warned about where it is no length in metres (input_notices)."""
        return () if raw.get("follower") == "rocker" else ("stroke",)

    @field_validator("stroke", mode="before")
    @classmethod
    def _stroke(cls, v, info):
        """A stroke with its unit: an angle for a rocker (its swing), a length otherwise (the
        follower, declared before the stroke, is among the fields validated); an error is the
        stroke's, at its line."""
        if isinstance(v, str):
            from ..units import convert
            follower = info.data.get("follower")
            if follower is None:            # the follower invalid (its own error): either unit stands
                try:
                    return convert(v, "angle")
                except ValueError:
                    pass
            return convert(v, "angle" if follower == "rocker" else "length")
        return v

    @model_validator(mode="after")
    def _limits(self):
        if self.pressure_angle is not None and self.transmission_angle is not None:
            raise ValueError(Message("input.cam_angles_both"))
        lim = self.pressure_angle
        if lim is None and self.transmission_angle is not None:
            t = self.transmission_angle
            if isinstance(t, LimitsSpec):
                lim = LimitsSpec(rise=90 - t.rise, **{"return": 90 - t.return_})
            else:
                lim = 90 - t
        if lim is None:
            lim = 45.0 if self.follower == "rocker" else 30.0
        if not isinstance(lim, LimitsSpec):
            if not 0 < lim < 90:
                given = "pressure_angle" if self.pressure_angle is not None else "transmission_angle"
                raise FieldValueError((given,), Message("input.cam_pressure_range"))
            # checked just above as LimitsSpec would (an angle in (0, 90)): built without
            # validating again, which would build LimitsSpec's own validator (~10 ms)
            lim = LimitsSpec.model_construct(rise=lim, return_=lim)
        self.pressure_angle = lim
        if self.follower == "rocker":
            if self.rocker_length is None:
                raise ValueError(Message("input.cam_rocker_length"))
            if self.offset not in (0.0, "auto"):
                raise ValueError(Message("input.cam_offset_rocker"))
            if self.stroke >= 180:
                raise ValueError(Message("input.cam_swing"))
        check_section(self, self.model_fields_set)
        return self
