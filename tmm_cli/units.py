"""Quantities with units for the task model.

A number is taken in the field's base unit (SI, angles in degrees). A string carries
its own unit and is converted with pint (``"300 mm"``, ``"50 rpm"``, ``"20 deg"``).
Dimensionless fields also accept fractions (``1/18``). pint is imported only when a
string with a unit is met, so plain-number tasks validate fast.
"""
from __future__ import annotations

import math
import re
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

_FRACTION = re.compile(r"^\s*([-+]?\d+(?:\.\d*)?)\s*/\s*(\d+(?:\.\d*)?)\s*$")


@lru_cache(maxsize=1)
def ureg():
    import pint  # lazy: ~0.3 s import

    return pint.UnitRegistry(cache_folder=_pint_cache_folder(pint))


def _pint_cache_folder(pint):
    """pint's disk cache of parsed definitions, one folder per pint installation: pint's own
    shared folder (``:auto:``) serves the parse of one installation's definition files to
    another whose files have the same content, with the first one's paths inside, so a
    removed virtual environment broke the registry of every other one (FileNotFoundError
    on its `@import`s). None (no disk cache, ~0.1 s more to parse) where no folder can be made."""
    import hashlib
    import os

    import platformdirs

    where = os.path.dirname(os.path.abspath(pint.__file__))
    key = hashlib.sha1(f"{where}|{pint.__version__}".encode()).hexdigest()[:16]
    folder = platformdirs.user_cache_path(appname="pint", appauthor=False) / f"tmm-{key}"
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError:
        return None
    return folder


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


_DECIMAL_COMMA = re.compile(r"([-+]?\d+),(\d+)(?![\d,])")


def convert(value: Any, kind: str) -> float:
    """Convert a task value of the given field kind to a float in the base unit."""
    unit = KINDS[kind][0]
    if isinstance(value, bool) or value is None:
        raise ValueError(Message("input.unit_expected", kind=kind, got=repr(value)))
    if isinstance(value, (int, float)):
        return _as_float(value)
    if not isinstance(value, str):
        raise ValueError(Message("input.unit_expected", kind=kind, got=type(value).__name__))
    text = value.strip()
    comma = _DECIMAL_COMMA.match(text)
    if comma:   # pint would read '3,5 mm' as 35 mm
        raise ValueError(Message("input.unit_decimal_comma", fixed=f"{comma.group(1)}.{comma.group(2)}",
                                 given=comma.group(0)))
    m = _FRACTION.match(text)
    if m:
        den = float(m.group(2))
        if den == 0:
            raise ValueError(Message("input.fraction_zero"))
        return _as_float(float(m.group(1)) / den)
    try:
        plain = float(text)
    except ValueError:
        plain = None
    if plain is not None:
        return _as_float(plain)
    fast = _fast(text, kind)
    if fast is not None:
        return _as_float(fast)
    if kind in ("dimensionless", "force_or_pressure"):
        if kind == "force_or_pressure":
            # a force or a pressure: accept either dimension, converted to SI
            q = _parse(text, kind)
            for target in ("N", "Pa"):
                try:
                    return _as_float(q.to(target).magnitude)
                except Exception:  # noqa: BLE001 - pint: not this dimension, try the next
                    continue
            raise ValueError(Message("input.unit_not_kind", text=text, kind=kind))
        raise ValueError(Message("input.unit_expected", kind=kind, got=f"'{text}'"))
    q = _parse(text, kind)
    try:
        return _as_float(q.to(unit).magnitude)
    except Exception:  # noqa: BLE001 - pint's conversion errors of any kind; the message names the unit
        raise ValueError(Message("input.unit_not_convert", text=text, kind=kind,
                                 unit=unit.replace('**', '^'))) from None


# The units course tasks write, with pint's factor to the base unit (a test checks each
# against pint): "<number> <unit>" is converted as number * factor -- pint's own product --
# without building pint's registry (~0.3 s).  Anything else goes to pint.
_FAST_UNITS: dict[str, dict[str, float]] = {
    "length": {"m": 1.0, "mm": 0.001, "cm": 0.01, "dm": 0.1, "km": 1000.0},
    "mass": {"kg": 1.0, "g": 0.001, "t": 1000.0},
    "angle": {"deg": 1.0, "degree": 1.0, "degrees": 1.0, "°": 1.0, "rad": 57.29577951308232},
    "speed": {"rpm": 0.10471975511965977, "rad/s": 1.0, "1/s": 1.0, "deg/s": 0.017453292519943295},
    "linear_speed": {"m/s": 1.0, "mm/s": 0.001, "cm/s": 0.01},
    "time": {"s": 1.0, "ms": 0.001, "min": 60.0},
    "force": {"N": 1.0, "kN": 1000.0, "MN": 1000000.0},
    "moment": {"N*m": 1.0, "N m": 1.0, "N·m": 1.0, "kN*m": 1000.0, "kN m": 1000.0, "kN·m": 1000.0},
    "pressure": {"Pa": 1.0, "kPa": 1000.0, "MPa": 1000000.0, "GPa": 1000000000.0, "bar": 100000.0},
    "area": {"m^2": 1.0, "m**2": 1.0, "mm^2": 1e-06, "mm**2": 1e-06, "cm^2": 0.0001, "cm**2": 0.0001},
    "density": {"kg/m^3": 1.0, "kg/m**3": 1.0},
    "inertia": {"kg*m^2": 1.0, "kg*m**2": 1.0, "kg m^2": 1.0, "kg·m^2": 1.0},
}
_FAST_UNITS["force_or_pressure"] = {**_FAST_UNITS["force"], **_FAST_UNITS["pressure"]}
_NUM_UNIT = re.compile(r"^([-+]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][-+]?\d+)?)\s*(\S.*?)\s*$")


def _fast(text: str, kind: str) -> float | None:
    """number * factor for a unit of _FAST_UNITS[kind], else None (pint decides)."""
    table = _FAST_UNITS.get(kind)
    m = _NUM_UNIT.match(text) if table else None
    if m is None:
        return None
    factor = table.get(m.group(2))
    return None if factor is None else float(m.group(1)) * factor


# Units as a Russian or Ukrainian text writes them, and their Latin names: tmm reads units in
# Latin letters only, and names the Latin spelling when a Cyrillic one is met.
_CYRILLIC_UNITS = {"мм": "mm", "см": "cm", "дм": "dm", "м": "m", "км": "km", "кг": "kg", "г": "g", "т": "t",
                   "Н": "N", "кН": "kN", "МН": "MN", "Па": "Pa", "кПа": "kPa", "МПа": "MPa", "ГПа": "GPa",
                   "бар": "bar", "рад": "rad", "град": "deg", "с": "s", "мс": "ms", "мин": "min", "хв": "min"}
_CYRILLIC_WORD = re.compile(r"[А-Яа-яЁёІіЇїЄєҐґ]+")


def latin_units(text: str) -> str | None:
    """'120 об/мин' -> '120 rpm', '80 мм' -> '80 mm', '5 Н·м' -> '5 N*m': the Latin spelling of
    a quantity written with Cyrillic units; None when it holds none or a word not known here."""
    if not _CYRILLIC_WORD.search(text):
        return None
    t = re.sub(r"об\.?\s*/\s*(мин|хв)\.?", "rpm", text)
    t = t.replace("·", "*").replace("²", "^2").replace("³", "^3")
    t = _CYRILLIC_WORD.sub(lambda m: _CYRILLIC_UNITS.get(m.group(0), m.group(0)), t)
    return None if _CYRILLIC_WORD.search(t) else t


def _parse(text: str, kind: str):
    import pint

    reg = ureg()
    try:
        q = reg.Quantity(text)
    except (pint.errors.UndefinedUnitError, pint.errors.DefinitionSyntaxError) as exc:
        latin = latin_units(text)
        if latin is not None and kind in KINDS:
            try:
                convert(latin, kind)
            except ValueError:
                latin = None
            if latin is not None:
                raise ValueError(Message("input.unit_cyrillic", text=text, latin=latin)) from None
        english = f"unknown unit in '{text}' ({exc}); expected {KINDS[kind][1]}"   # pint's words inside
        names = getattr(exc, "unit_names", None) or ()
        coded = Message("input.unit_unknown", text=text, unit=names[0], kind=kind) if len(names) == 1 else None
        raise ValueError(coded if coded == english else english) from None
    except Exception:  # noqa: BLE001 - the rest of pint's parser errors (tokenize, syntax, types)
        raise ValueError(Message("input.unit_unreadable", text=text, kind=kind)) from None
    if not any(ch.isdigit() for ch in text):     # pint reads a bare 'mm' as 1 mm
        raise ValueError(Message("input.unit_no_number", text=text, kind=kind))
    if not isinstance(q, reg.Quantity):
        q = reg.Quantity(q)
    return q


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
# a plain number (no unit), finite and within LIMIT
Number = Annotated[float, AfterValidator(check_magnitude)]
