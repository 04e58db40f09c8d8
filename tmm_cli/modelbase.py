"""The base of the task model's sections (tmm_cli/task.py, tmm_cli/trainspec.py,
tmm_cli/dof2/spec.py): unknown keys are errors with a "did you mean", and a model-level
error can name its field.  Kept apart from task.py so that the section modules and the
task model import it without importing each other."""
from __future__ import annotations

from typing import Any

from pydantic import BaseModel, ConfigDict, model_validator

from .messages import Message

PLANETARY_SCHEMES = ("A", "B", "C", "D")
PLANETARY_ALIASES = {"a": "A", "b": "B", "c": "C", "d": "D", "single": "A", "james": "A"}


class FieldValueError(ValueError):
    """A model-level validation error that belongs to a field (a section missing or
    inconsistent with another): ``field`` is the path, relative to the model, that the
    message should point at (so the message names a field and its line)."""

    def __init__(self, field: tuple, message: str):
        super().__init__(message)
        self.field = tuple(field)


class _Model(BaseModel):
    """Base: unknown keys are errors with a suggestion."""

    # allow_inf_nan=False: a plain float field rejects .inf, .nan, 'inf' and '1e400'
    model_config = ConfigDict(extra="forbid", populate_by_name=True, frozen=False, allow_inf_nan=False,
                              defer_build=True)

    @model_validator(mode="before")
    @classmethod
    def _unknown_keys(cls, data: Any) -> Any:
        if isinstance(data, dict):
            allowed: list[str] = []
            for name, f in cls.model_fields.items():
                allowed.append(f.alias or name)
            unknown: list[str] = []
            for key in data:
                if not isinstance(key, str):
                    raise ValueError(Message("input.key_not_name", key=str(key), allowed=allowed))
                if key not in allowed:
                    unknown.append(key)
            if unknown:
                # every unknown key of the mapping in one error, at the first one's line: a
                # student's 'lenght' no longer hides the 'masss' beside it
                import difflib

                def near(key: str) -> str | None:
                    close = difflib.get_close_matches(key, allowed, n=1, cutoff=0.6)
                    return close[0] if close else None
                hint = near(unknown[0])
                first = Message("input.unknown_key", key=unknown[0], hint=hint) if hint \
                    else Message("input.unknown_key_allowed", key=unknown[0], allowed=allowed)
                if len(unknown) == 1:
                    raise ValueError(first)
                rest = [Message("input.unknown_also", key=k, hint=h) if (h := near(k))
                        else Message("input.unknown_also_plain", key=k) for k in unknown[1:]]
                raise ValueError(Message("input.unknown_keys", first=first, rest=rest))
        return data
