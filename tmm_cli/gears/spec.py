"""The `gears` and `planetary` sections of the task file (README, *The task file*),
validated once by the task model (tmm_cli/task.py composes them)."""
# annotations evaluated as written (no `from __future__ import annotations`): pydantic would
# compile and evaluate every field's annotation string when the models are made
from typing import Annotated, Literal, Union

from pydantic import Field, field_validator, model_validator

from ..messages import Message
from ..modelbase import PLANETARY_ALIASES, PLANETARY_SCHEMES, FieldValueError, _Model
from ..units import Angle, Length, Number, Ratio


# ---------------------------------------------------------------- gears
class GearsSection(_Model):
    m: Length = Field(..., gt=0, description="module (give '3 mm')")
    z: tuple[Annotated[int, Field(le=10**12)], Annotated[int, Field(le=10**12)]]  # the 1e12 limit on values
    x: Union[Literal["auto"], tuple[Number, Number]] = (0.0, 0.0)
    alpha: Angle = Field(20.0, gt=0, lt=45)
    ha: Number = Field(1.0, gt=0)
    c: Number = Field(0.25, ge=0)
    rule: Literal["no_undercut", "equal_sliding", "table"] = Field(
        "equal_sliding", description="how `x: auto` chooses the shifts: no_undercut (the least that avoid "
                                     "undercut) | equal_sliding (equal greatest specific sliding) | table "
                                     "(x1 = x2 = 0.5, a handbook choice)")
    sa_min: float = Field(0.25, gt=0, lt=1, description="least tip thickness as a fraction of m "
                                                         "(0.25 common, 0.4 hardened teeth)")
    rho_f: Number | None = Field(None, ge=0, description="rack fillet radius / m (default c/(1 - sin alpha))")

    @field_validator("z")
    @classmethod
    def _z(cls, v):
        if min(v) < 5:
            raise ValueError(Message("input.z_min"))
        return v




class PlanetarySection(_Model):
    scheme: str
    ratio: Number
    satellites: int = Field(3, ge=1, le=12)
    tolerance: Ratio = Field(0.05, gt=0)
    m: Length | None = Field(None, gt=0)
    z_min: int = Field(17, ge=5, le=300)
    # the candidate search grows as z_max^3 (schemes B, C: 0.5 s at 300, a minute at 1000)
    z_max: int = Field(150, ge=10, le=300)
    candidates: int = Field(10, ge=1, le=100, description="how many ranked candidate sets to list")
    rank: Literal["size", "ratio_error"] = "size"
    z_min_external: int | None = Field(None, ge=5)
    z_min_internal: int = Field(85, ge=5)
    z_min_satellite_in_internal: int | None = Field(None, ge=5)
    internal_minus_external_min: int = Field(8, ge=1)

    @field_validator("ratio")
    @classmethod
    def _ratio(cls, v):
        if v == 0:
            raise ValueError(Message("input.ratio_zero"))
        return v

    @field_validator("scheme")
    @classmethod
    def _scheme(cls, v):
        # an unknown scheme is an invalid task (exit 2), not a failed stage. The names are
        # those of tmm_cli.gears.planetary (SCHEMES, ALIASES; a test keeps the two equal),
        # copied so that validating a task does not import the gears package (~1 s)
        key = str(v).strip()
        if PLANETARY_ALIASES.get(key.lower(), key.upper()) not in PLANETARY_SCHEMES:
            raise ValueError(Message("input.planetary_scheme", scheme=repr(v), known=list(PLANETARY_SCHEMES)))
        return v

    @model_validator(mode="after")
    def _z_range(self):
        if self.z_min > self.z_max:
            raise FieldValueError(("z_min",), Message("input.z_range", z_min=self.z_min, z_max=self.z_max))
        return self
