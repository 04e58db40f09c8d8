"""The task section ``differential:`` -- a planetary scheme A-D with no member fixed.

Members: the first central wheel ``"1"``, the last central wheel (``"3"`` for scheme A,
``"4"`` for B-D) and the carrier ``"H"``. Two members' speeds are given (signed,
counter-clockwise positive); the third follows from Willis' formula. One member's torque
may be given (the external torque on that member, N*m, counter-clockwise positive); the
others follow from the balance of the torques and the power balance with ``efficiency``,
the efficiency of the train with the carrier held.

Example::

    differential:
      scheme: A
      z: [20, 25, 70]
      satellites: 3
      speeds: {"1": 1000 rpm, "3": -200 rpm}
      torque: {"1": 50 N*m}
      efficiency: 1
"""
# annotations evaluated as written (no `from __future__ import annotations`): pydantic would
# compile and evaluate every field's annotation string when the models are made
from typing import Any

from pydantic import Field, field_validator, model_validator

from ..messages import Message
from ..modelbase import PLANETARY_ALIASES, PLANETARY_SCHEMES, FieldValueError, _Model
from ..units import AngularSpeed, Length, MomentQ, Ratio

__all__ = ["DifferentialSection", "Z_COUNT", "last_member", "members"]

Z_COUNT = {"A": 3, "B": 4, "C": 4, "D": 4}


def last_member(scheme: str) -> str:
    """The last central wheel's name: "3" in scheme A, "4" in B-D."""
    return "3" if scheme == "A" else "4"


def members(scheme: str) -> tuple[str, str, str]:
    """The three members whose speeds Willis' formula ties: "1", the last wheel, "H"."""
    return "1", last_member(scheme), "H"


def _member_keys(value: Any) -> Any:
    """YAML reads ``{1: ...}`` with an integer key and ``{h: ...}`` in lower case: members by name."""
    if isinstance(value, dict):
        out: dict = {}
        spelt: dict = {}
        for k, v in value.items():
            name = "H" if str(k).strip().upper() == "H" else str(k).strip()
            if name in out:             # `h` and `H` (or `1` and "1"): one member given twice
                raise ValueError(Message("input.diff_member_twice", member=name, keys=[spelt[name], str(k)]))
            out[name], spelt[name] = v, str(k)
        return out
    return value


class DifferentialSection(_Model):
    scheme: str = Field(..., description="planetary scheme A, B, C or D (as `planetary`)")
    z: list[int] = Field(..., description="tooth numbers z1, z2, z3 (A) or z1..z4 (B-D)")
    satellites: int = Field(3, ge=1, le=12, description="number of satellites, equally spaced")
    m: Length | None = Field(None, gt=0, description="module (m); with it the velocity picture is to scale")
    speeds: dict[str, AngularSpeed] = Field(..., description="two members' speeds: any two of \"1\", the last "
                                                             "wheel (\"3\" for A, \"4\" for B-D) and \"H\"; "
                                                             "signed, ccw positive")
    torque: dict[str, MomentQ] = Field(default_factory=dict,
                                       description="optional: one member's external torque (N*m, ccw positive)")
    efficiency: Ratio = Field(1.0, gt=0, le=1, description="efficiency of the train with the carrier held")

    @field_validator("speeds", "torque", mode="before")
    @classmethod
    def _keys(cls, v):
        return _member_keys(v)

    @field_validator("scheme")
    @classmethod
    def _scheme(cls, v):
        key = PLANETARY_ALIASES.get(str(v).strip().lower(), str(v).strip().upper())
        if key not in PLANETARY_SCHEMES:
            raise ValueError(Message("input.planetary_scheme", scheme=repr(v), known=list(PLANETARY_SCHEMES)))
        return key

    @model_validator(mode="after")
    def _shape(self):
        n = Z_COUNT[self.scheme]
        if len(self.z) != n:
            raise FieldValueError(("z",), Message("input.train_z_count_scheme", scheme=self.scheme, n=n,
                                                  got=len(self.z)))
        if min(self.z) < 5:
            raise FieldValueError(("z",), Message("input.z_min"))
        names = members(self.scheme)
        for key in (*self.speeds, *self.torque):
            if key not in names:
                where = "speeds" if key in self.speeds else "torque"
                raise FieldValueError((where, key), Message("input.diff_member", key=key, scheme=self.scheme,
                                                            members=list(names)))
        if len(self.speeds) != 2:
            raise FieldValueError(("speeds",), Message("input.diff_two_speeds", got=len(self.speeds),
                                                       members=list(names)))
        if len(self.torque) > 1:
            raise FieldValueError(("torque",), Message("input.diff_one_torque", got=len(self.torque)))
        return self

    @property
    def teeth(self) -> dict[str, int]:
        """{"z1": .., "z2": .., ...} as the planetary functions take them."""
        return {f"z{i + 1}": int(v) for i, v in enumerate(self.z)}

    @property
    def last(self) -> str:
        return last_member(self.scheme)
