"""Quantities with units for the task model.

A number is taken in the field's base unit (SI, angles in degrees). A string is read by
the grammar of tmm_cli.numbers (decimal comma, grouped thousands, Unicode minus, a unit in
Latin or Cyrillic letters: ``"300 mm"``, ``"50 rpm"``, ``"120 min⁻¹"``, ``"0,15 kg·m²"``)
and its unit converted by a table of the course's units, else by pint. A fraction
(``1/18``) is a plain number. pint is imported only when a unit outside the table is met,
so plain-number tasks validate fast.
"""
from __future__ import annotations

import math
from fractions import Fraction
from functools import lru_cache, partial
from typing import Annotated, Any

from pydantic import AfterValidator, BeforeValidator, WithJsonSchema

from .messages import Message

# field kind -> (pint unit the value is converted to, words for messages)
KINDS: dict[str, tuple[str, str]] = {
    "length": ("m", "a length (m, mm, cm...)"),
    "mass": ("kg", "a mass (kg, g, t)"),
    "inertia": ("kg*m**2", "a moment of inertia (kg*m^2)"),
    "angle": ("degree", "an angle (deg, rad)"),
    "speed": ("rad/s", "an angular speed (rad/s, rpm)"),
    "force": ("N", "a force (N, kN)"),
    "moment": ("N*m", "a moment of force (N*m)"),
    "pressure": ("Pa", "a pressure (Pa, kPa, MPa, bar)"),
    "area": ("m**2", "an area (m^2, mm^2, cm^2)"),
    "density": ("kg/m**3", "a density (kg/m^3)"),
    "force_or_pressure": ("", "a force (N) or, with `area`, a pressure (Pa)"),
    "dimensionless": ("", "a plain number or a fraction such as 1/18"),
    # read by their own fields (dof2's times, drive.mean_output_speed), here for the fast table
    "time": ("s", "a time (s, ms, min)"),
    "linear_speed": ("m/s", "a linear speed (m/s)"),
    "output_speed": ("", "a speed (m/s, rad/s, deg/s)"),   # drive.mean_output_speed (linkage/drive_speed.py)
}

# No quantity of a course task comes near 1e12 in its base unit (m, kg, N, Pa, rad/s, deg...);
# a larger value is a typo or an overflow waiting to happen (its square or cube in a stage
# would leave the float range), so it is rejected at the field that holds it.
LIMIT = 1e12

def _as_float(x: Any) -> float:
    if isinstance(x, bool):
        raise ValueError(Message("input.number_bool"))
    v = float(x)
    if not math.isfinite(v):
        raise ValueError(Message("input.not_finite"))
    return check_magnitude(v)


def check_magnitude(v: float) -> float:
    """``v`` if it is finite and |v| <= LIMIT, else a ValueError naming the limit."""
    if not math.isfinite(v):
        raise ValueError(Message("input.not_finite"))
    if abs(v) > LIMIT:
        raise ValueError(Message("input.out_of_range", value=v, limit=LIMIT))
    return v


def convert(value: Any, kind: str) -> float:
    """Convert a task value of the given field kind to a float in the base unit."""
    if isinstance(value, bool) or value is None:
        raise ValueError(Message("input.unit_expected", kind=kind, got=repr(value)))
    if isinstance(value, (int, float)):
        return _as_float(value)
    if not isinstance(value, str):
        raise ValueError(Message("input.unit_expected", kind=kind, got=type(value).__name__))
    return _as_float(quantity(value, kind)[0])


# The units course tasks write, with pint's factor to the base unit (a test checks each
# against pint): "<number> <unit>" is converted as number * factor -- pint's own product --
# without building pint's registry (~0.3 s).  Anything else goes to pint, after
# tmm_cli.numbers has checked the unit's text.
_FAST_UNITS: dict[str, dict[str, float]] = {
    "length": {"m": 1.0, "mm": 0.001, "cm": 0.01, "dm": 0.1, "km": 1000.0},
    "mass": {"kg": 1.0, "g": 0.001, "t": 1000.0},
    "angle": {"deg": 1.0, "degree": 1.0, "degrees": 1.0, "°": 1.0, "rad": 57.29577951308232},
    "speed": {"rpm": 0.10471975511965977, "rad/s": 1.0, "deg/s": 0.017453292519943295},
    "linear_speed": {"m/s": 1.0, "mm/s": 0.001, "cm/s": 0.01},
    "time": {"s": 1.0, "ms": 0.001, "min": 60.0},
    "force": {"N": 1.0, "kN": 1000.0, "MN": 1000000.0},
    "moment": {"N*m": 1.0, "kN*m": 1000.0},
    "pressure": {"Pa": 1.0, "kPa": 1000.0, "MPa": 1000000.0, "GPa": 1000000000.0, "bar": 100000.0},
    "area": {"m^2": 1.0, "mm^2": 1e-06, "cm^2": 0.0001},
    "density": {"kg/m^3": 1.0},
    "inertia": {"kg*m^2": 1.0},
}
_FAST_UNITS["force_or_pressure"] = {**_FAST_UNITS["force"], **_FAST_UNITS["pressure"]}
# a kind -> the (base unit, table of _FAST_UNITS) its value may convert to, in that order
_TARGETS = {"force_or_pressure": (("N", "force"), ("Pa", "pressure")),
            "output_speed": (("m/s", "linear_speed"), ("rad/s", "speed"))}


@lru_cache(maxsize=None)
def _fast_table(table: str) -> dict[str, float]:
    """_FAST_UNITS[table] keyed by the unit's expression as tmm_cli.numbers spells it."""
    from .numbers import parse_unit, unit_expression
    return {unit_expression(parse_unit(k)[0]): v for k, v in _FAST_UNITS.get(table, {}).items()}


def quantity(text: str, kind: str) -> tuple[float, list, str]:
    """(value in the base unit of ``kind``, the notes of its reading, the kind it was read
    as: ``kind``, or for force_or_pressure and output_speed the one that converted) of a
    number written with an optional unit (tmm_cli.numbers' grammar; a plain number is in
    the base unit). Raises ValueError(Message) naming the reason."""
    from .numbers import in_unit, read
    text = text.strip()
    try:
        r = read(text)
    except ValueError as exc:
        raise ValueError(_for_kind(exc.args[0], text, kind)) from None
    if not r.unit:
        return r.value, [], kind
    if kind == "dimensionless":
        if r.expression == "percent":       # '97 %': a share
            return r.value / 100, [], kind
        raise ValueError(Message("input.unit_expected", kind=kind, got=f"'{text}'"))
    targets = _TARGETS.get(kind, ((KINDS[kind][0], kind),))
    for target, table in targets:           # a unit of the table first: no pint for '2 MPa' or '1.2 m/s'
        if r.expression in _fast_table(table):
            return (*in_unit(r, target, angular=table == "speed", fast=_fast_table(table)),
                    table if kind in _TARGETS else kind)
    for target, table in targets:
        try:
            value, notes = in_unit(r, target, angular=table == "speed", fast=_fast_table(table))
        except ValueError as exc:
            if exc.args and exc.args[0] is not None:
                raise ValueError(_for_kind(exc.args[0], text, kind)) from None
            continue
        return value, notes, table if kind in _TARGETS else kind
    if kind in _TARGETS:
        raise ValueError(Message("input.unit_not_kind", text=text, kind=kind))
    raise ValueError(Message("input.unit_not_convert", text=text, kind=kind,
                             unit=KINDS[kind][0].replace("**", "^")))


def _for_kind(msg, text: str, kind: str):
    """A reason of tmm_cli.numbers in the words of a field of ``kind``: an unknown unit
    names the quantity expected, a unit alone says the number is missing."""
    code = msg.code if isinstance(msg, Message) else None
    if code == "input.number_unit_unknown":
        return Message("input.unit_unknown", text=text, unit=msg.params["unit"], kind=kind)
    if code == "input.number_not_number" and not any("0" <= ch <= "9" for ch in text) and kind != "dimensionless":
        from .numbers import is_dimensionless, parse_unit, unit_expression
        try:                                # a unit pint knows, alone: 'mm', 'rpm'
            is_dimensionless(unit_expression(parse_unit(text)[0]))
        except ValueError:
            return Message("input.unit_expected", kind=kind, got=f"'{text}'")
        return Message("input.unit_no_number", text=text, kind=kind)
    if code == "input.number_not_number" and kind == "dimensionless":
        return Message("input.unit_expected", kind=kind, got=f"'{text}'")
    return msg


def fraction_text(x: float) -> str:
    """1/18 for 0.0555..., used in reports."""
    f = Fraction(x).limit_denominator(1000)
    if f.numerator == 1 and abs(float(f) - x) < 1e-12:
        return f"1/{f.denominator}"
    return f"{x:g}"


def _q(kind: str):
    # a partial, not a closure: the task's validator can then be cached (tmm_cli.task)
    return BeforeValidator(partial(convert, kind=kind))


def _schema(kind: str) -> WithJsonSchema:
    unit, words = KINDS[kind]
    base = unit.replace("**", "^") or "1"
    return WithJsonSchema({"anyOf": [
        {"type": "number", "description": f"in {base}" if unit != "degree" else "in degrees"},
        {"type": "string", "description": f"{words} with its unit, e.g. '{_EXAMPLES.get(kind, '')}'"
         if kind != "dimensionless" else "a fraction such as '1/18'"}]})


_EXAMPLES = {"length": "300 mm", "mass": "2.5 kg", "inertia": "0.15 kg*m^2", "angle": "20 deg",
             "speed": "50 rpm", "force": "3 kN", "moment": "10 N*m", "pressure": "10 MPa",
             "area": "78.5 cm^2", "density": "7800 kg/m^3", "force_or_pressure": "3 kN"}


Length = Annotated[float, _q("length"), _schema("length")]
Mass = Annotated[float, _q("mass"), _schema("mass")]
Inertia = Annotated[float, _q("inertia"), _schema("inertia")]
Angle = Annotated[float, _q("angle"), _schema("angle")]
AngularSpeed = Annotated[float, _q("speed"), _schema("speed")]
Force = Annotated[float, _q("force"), _schema("force")]
MomentQ = Annotated[float, _q("moment"), _schema("moment")]
Pressure = Annotated[float, _q("pressure"), _schema("pressure")]
Area = Annotated[float, _q("area"), _schema("area")]
Density = Annotated[float, _q("density"), _schema("density")]
Ratio = Annotated[float, _q("dimensionless"), _schema("dimensionless")]
ForceOrPressure = Annotated[float, _q("force_or_pressure"), _schema("force_or_pressure")]
def plain_number(value: Any) -> Any:
    """A string read as a number without a unit (tmm_cli.numbers: '1 234,5', '−0,5',
    '1/18'); anything else as it is, for the field's own type check."""
    if not isinstance(value, str):
        return value
    from .numbers import read
    r = read(value)
    if r.unit:
        raise ValueError(Message("input.unit_expected", kind="dimensionless", got=f"'{value.strip()}'"))
    return r.value


def tolerance_number(value: Any, what: str = "plain") -> float:
    """A tolerance's number -- a share (``what`` "rel", or "plain": a plain tolerance) or an
    absolute amount ("abs") -- non-negative and finite, given as a number or as a string of the
    number grammar ('0,02', '1/20'); a share may be written in percent ('5 %', '2,5%'); else
    ValueError(Message ``input.tol_not_number``). A share of 1 or more (every answer within 100 %
    and more passes: `default: 5` meant for 5 %) is ValueError(Message ``input.tol_share_large``).
    One reader for the task file's ``tolerance`` and ``--tolerance FILE``."""
    x = value
    if isinstance(x, str):
        try:                                # a share read as a Ratio field reads it ('5 %' is 0.05)
            x = quantity(x, "dimensionless")[0] if what != "abs" else plain_number(x)
        except ValueError:
            x = None
    if not (isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(float(x)) and x >= 0):
        raise ValueError(Message("input.tol_not_number", what=what, got=repr(value)))
    x = float(x)
    if what != "abs" and x >= 1:
        raise ValueError(Message("input.tol_share_large", what=what, got=repr(value), pct=100 * x,
                                 share=x / 100))
    return x


# a plain number (no unit), finite and within LIMIT
Number = Annotated[float, BeforeValidator(plain_number), AfterValidator(check_magnitude)]
