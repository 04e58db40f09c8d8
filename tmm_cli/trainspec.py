"""The task section ``drive_train:`` -- a compound gear drive from the motor to the output
shaft: ordinary pairs (external or internal) and planetary stages of the schemes A-D, with
given tooth numbers or chosen by the program (see :mod:`tmm_cli.gears.train`).

Example::

    drive_train:
      motor_speed: 1440 rpm
      ratio: -28.8
      stages:
        - {type: pair, z: [20, 96]}
        - {type: planetary, scheme: A}          # no z: chosen

Kept apart from :mod:`tmm_cli.gears` so that validating a task does not import the gears
package.
"""
# annotations evaluated as written (no `from __future__ import annotations`): pydantic would
# compile and evaluate every field's annotation string when the models are made
from typing import Literal

from pydantic import Field, field_validator, model_validator

from .messages import Message
from .modelbase import PLANETARY_ALIASES, PLANETARY_SCHEMES, FieldValueError, _Model
from .units import AngularSpeed, Number, Ratio

# tooth numbers of each stage kind, in the order of the `z` list
Z_COUNT = {"pair": 2, "A": 3, "B": 4, "C": 4, "D": 4}



def _nonzero_ratio(v):
    """A required ratio (of a stage or the train) may have either sign but not be zero."""
    if v is not None and v == 0:
        raise ValueError(Message("input.ratio_zero"))
    return v

class TrainStageSpec(_Model):
    type: Literal["pair", "planetary"]
    z: list[int] | None = None
    internal: bool = False
    scheme: str | None = None
    ratio: Number | None = None

    @field_validator("scheme")
    @classmethod
    def _scheme(cls, v):
        if v is None:
            return v
        key = PLANETARY_ALIASES.get(str(v).strip().lower(), str(v).strip().upper())
        if key not in PLANETARY_SCHEMES:
            raise ValueError(Message("input.planetary_scheme", scheme=repr(v), known=list(PLANETARY_SCHEMES)))
        return key

    @field_validator("ratio")
    @classmethod
    def _ratio(cls, v):
        return _nonzero_ratio(v)

    @model_validator(mode="after")
    def _shape(self):
        if self.type == "planetary" and self.scheme is None:
            raise FieldValueError(("scheme",), Message("input.train_needs_scheme"))
        if self.type == "pair" and self.scheme is not None:
            raise FieldValueError(("scheme",), Message("input.train_scheme_pair"))
        if self.type == "planetary" and self.internal:
            raise FieldValueError(("internal",), Message("input.train_internal"))
        if self.z is not None:
            n = Z_COUNT["pair" if self.type == "pair" else self.scheme]
            if len(self.z) != n:
                raise FieldValueError(("z",), Message("input.train_z_count_pair", n=n, got=len(self.z))
                                      if self.type == "pair" else
                                      Message("input.train_z_count_scheme", scheme=self.scheme, n=n, got=len(self.z)))
            if min(self.z) < 5:
                raise FieldValueError(("z",), Message("input.z_min"))
            if self.ratio is not None:
                raise FieldValueError(("ratio",), Message("input.train_z_and_ratio"))
        return self

    @property
    def kind(self) -> str:
        """'pair' or the planetary scheme letter."""
        return "pair" if self.type == "pair" else str(self.scheme)


class DriveTrainSection(_Model):
    motor_speed: AngularSpeed | None = Field(None, gt=0)
    motor_direction: Literal["ccw", "cw"] | None = None
    ratio: Number | None = None
    tolerance: Ratio = Field(0.05, gt=0, lt=1)
    efficiency: Ratio = Field(1.0, gt=0, le=1)
    satellites: int = Field(3, ge=1, le=12)
    z_min_external: int = Field(17, ge=5)
    z_min_internal: int = Field(85, ge=5)
    z_min_satellite_in_internal: int = Field(20, ge=5)
    internal_minus_external_min: int = Field(8, ge=1)
    # the planetary search: under 0.1 s at z_max 300 for every scheme (benchmarks/bench_planetary.py)
    z_max: int = Field(150, ge=10, le=300)
    rank: Literal["size", "ratio_error"] = "size"
    candidates: int = Field(10, ge=1, le=100)
    stages: list[TrainStageSpec] = Field(..., min_length=1)

    @field_validator("ratio")
    @classmethod
    def _ratio(cls, v):
        return _nonzero_ratio(v)

    @model_validator(mode="after")
    def _limits(self):
        for name, value in (("z_min_external", self.z_min_external), ("z_min_internal", self.z_min_internal),
                            ("z_min_satellite_in_internal", self.z_min_satellite_in_internal)):
            if value > self.z_max:
                raise FieldValueError((name,), Message("input.train_z_above_max", name=name, value=value,
                                                       z_max=self.z_max))
        for i, st in enumerate(self.stages):
            if st.z is not None and max(st.z) > 300:
                raise FieldValueError(("stages", i, "z"), Message("input.train_z_300"))
        return self


DOCS = {
    DriveTrainSection: {
        "motor_speed": "input (motor) shaft speed, a magnitude ('1440 rpm')",
        "motor_direction": "ccw | cw; default: the sense that turns the output as `drive.direction`, else ccw",
        "ratio": "required overall ratio u = omega_in/omega_out, signed (default with a motor and a "
                 "`drive`: +-motor_speed/drive.speed)",
        "tolerance": "allowed |ratio error| (fraction) of the chosen stages and of the train",
        "efficiency": "overall efficiency of the train (motor power)",
        "satellites": "planetary stages: number of satellites k",
        "z_min_external": "least teeth of an external wheel in an external mesh",
        "z_min_internal": "least teeth of an internal (ring) wheel",
        "z_min_satellite_in_internal": "least teeth of an external wheel meshing a ring",
        "internal_minus_external_min": "least z_ring - z_pinion in an internal mesh",
        "z_max": "largest tooth number tried (<= 300)",
        "rank": "size | ratio_error: the ranking key of the candidate trains",
        "candidates": "how many ranked candidate trains to report",
        "stages": "ordered from the motor (input) to the output",
    },
    TrainStageSpec: {
        "type": "pair | planetary",
        "z": "tooth numbers, a list: pair z1, z2; A z1, z2, z3; B, C, D z1, z2, z3, z4; omit to choose them",
        "internal": "pair: true when z2 is a ring (u = +z2/z1)",
        "scheme": "planetary: A | B | C | D (input wheel 1, output carrier H, last wheel fixed)",
        "ratio": "this stage's own ratio when z is chosen (default: an equal share)",
    },
}
