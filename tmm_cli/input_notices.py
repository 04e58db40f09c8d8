"""Warnings about values that are valid but probably not what the user meant.

A plain number is in the base unit of its field (m, rad/s). For a field whose everyday
unit differs from the base unit, a plain number far above what a course task holds is
most likely in the everyday unit: ``speed: 60`` meant as 60 rpm is read as 60 rad/s
(573 rpm), ``length: 100`` meant as 100 mm is read as 100 m. Such values are computed
as written, with a warning that suggests the unit string.

A unit the course reads otherwise than pint would (tmm_cli.numbers) is stated once a
task, naming every field that holds it: ``120 min^-1`` is 120 rpm, ``2 Hz`` 2 rev/s,
``12,57 s^-1`` of an angular speed 12.57 rad/s, ``90 grad`` 90 degrees.
"""
from __future__ import annotations

import math
import typing
from typing import Any

from pydantic import BaseModel

from .messages import Message
from .errors import dotted

# plain numbers above these (in the base unit) get a warning
SPEED_PLAIN_MAX = 50.0      # rad/s (~480 rpm)
LENGTH_PLAIN_MAX = 10.0     # m
MODULE_PLAIN_MAX = 0.1      # m: a gear module (field `m`) is a few millimetres

_KIND_BY_DESCRIPTION = {"in m": "length", "in rad/s": "speed"}
# the kinds whose strings may hold a unit read as the course reads it (a note of tmm_cli.numbers)
_READ_KINDS = {"in degrees": "angle", "in rad/s": "speed"}


def _kind(metadata) -> str | None:
    """'length' or 'speed' for an annotation made by tmm_cli.units (its JSON Schema
    says the base unit of a plain number), else None."""
    for m in metadata:
        schema = getattr(m, "json_schema", None)
        if isinstance(schema, dict):
            for alt in schema.get("anyOf", []):
                kind = _KIND_BY_DESCRIPTION.get(alt.get("description", "")) or \
                    _READ_KINDS.get(alt.get("description", ""))
                if kind:
                    return kind
    return None


def _message(kind: str, value: float, path: tuple) -> str | None:
    field = dotted(path)
    if kind == "speed" and abs(value) > SPEED_PLAIN_MAX:
        rpm = abs(value) * 30.0 / math.pi
        return Message("input.speed_plain", field=field, value=value, rpm=rpm)
    limit = MODULE_PLAIN_MAX if path and path[-1] == "m" else LENGTH_PLAIN_MAX
    if kind == "length" and abs(value) > limit:
        return Message("input.length_plain", field=field, value=value)
    return None


def _walk(ann, raw: Any, path: tuple, out: list[str]) -> None:
    origin = typing.get_origin(ann)
    if origin is typing.Annotated:
        base, *meta = typing.get_args(ann)
        kind = _kind(meta)
        if kind is not None:
            if isinstance(raw, (int, float)) and not isinstance(raw, bool) and math.isfinite(raw):
                msg = _message(kind, float(raw), path)
                if msg:
                    out.append(msg)
            elif isinstance(raw, str) and kind in _READ_KINDS.values() and any("0" <= c <= "9" for c in raw):
                out.append(_Reading(path, raw, kind))
            return
        _walk(base, raw, path, out)
    elif isinstance(ann, type) and issubclass(ann, BaseModel):
        if not isinstance(raw, dict):
            return
        # fields whose unit another field sets (a cam's stroke: a length but for a rocker's swing):
        # the section names those that are lengths in this raw mapping
        named = ann.__dict__.get("plain_lengths")        # a staticmethod of the section's own class
        for key in (named.__func__(raw) if isinstance(named, staticmethod) else ()):
            v = raw.get(key)
            if isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v):
                msg = _message("length", float(v), path + (key,))
                if msg:
                    out.append(msg)
        for name, f in ann.model_fields.items():
            key = f.alias or name
            if key in raw:
                sub = typing.Annotated[(f.annotation, *f.metadata)] if f.metadata else f.annotation
                _walk(sub, raw[key], path + (key,), out)
    elif origin in (typing.Union, getattr(__import__("types"), "UnionType", None)):
        for arg in typing.get_args(ann):
            before = len(out)
            _walk(arg, raw, path, out)
            if len(out) > before:
                return
    elif origin in (list, tuple) and isinstance(raw, (list, tuple)):
        args = typing.get_args(ann)
        for i, item in enumerate(raw):
            arg = args[0] if (origin is list or (len(args) == 2 and args[1] is Ellipsis)) else \
                (args[i] if i < len(args) else None)
            if arg is not None:
                _walk(arg, item, path + (i,), out)
    elif origin is dict and isinstance(raw, dict):
        args = typing.get_args(ann)
        if len(args) == 2:
            for k, v in raw.items():
                _walk(args[1], v, path + (k,), out)


def plain_number_warnings(model_type: type[BaseModel], data: dict) -> list[str]:
    """Warnings for plain numbers in ``data`` (the task as read) whose field's everyday
    unit differs from its base unit and whose value is implausible in the base unit."""
    out: list = []
    _walk(model_type, data, (), out)
    return [m for m in out if not isinstance(m, _Reading)] + _reading_warnings(
        [m for m in out if isinstance(m, _Reading)])


class _Reading(typing.NamedTuple):
    path: tuple
    text: str
    kind: str


def _reading_warnings(readings: list[_Reading]) -> list[str]:
    """One warning per unit read as the course reads it, naming every field that holds it."""
    from .numbers import read
    from .units import quantity
    found: dict[tuple, tuple[dict, list]] = {}
    for path, text, kind in readings:
        try:
            value, notes, _ = quantity(text, kind)
            written = read(text).value
        except ValueError:
            continue
        for code in notes:
            found.setdefault((code, read(text).unit), ((text.strip(), written, value), []))[1].append(dotted(path))
    out = []
    for (code, _unit), ((text, written, value), fields) in found.items():
        field = fields if len(fields) > 1 else fields[0]
        if code == "input.reading_per_min":
            out.append(Message("input.reading_per_min", field=field, text=text, rpm=written, omega=value))
        elif code == "input.reading_hz":
            out.append(Message("input.reading_hz", field=field, text=text, rps=written, omega=value))
        elif code == "input.reading_per_s":
            out.append(Message("input.reading_per_s", field=field, text=text, omega=value))
        else:
            out.append(Message("input.reading_grad", field=field, text=text, deg=written))
    return out
