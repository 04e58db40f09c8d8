"""One grammar for every number a user writes: task files, variants tables, answers.

A number, as students and course books write it:

* an optional sign: ``-``, ``+`` or the minus sign U+2212 ``−`` (in answers also the dash
  U+2013 ``–`` that word processors put);
* digits with an optional decimal point or decimal comma (``0.59``, ``0,59``, ``.5``); the
  integer part may be grouped in threes by a space, a no-break space (U+00A0) or a narrow
  no-break space (U+202F): ``1 234,5``, ``12 435``;
* an optional power of ten: ``1.2e-3``, ``1,2·10⁻³``, ``1,2×10^-3``, ``1.2*10**-3``;
* or a fraction of two such numbers without a unit: ``1/18``;
* then, optionally, a unit in Latin or Cyrillic letters: names joined by ``*``, ``·`` or
  a space, at most one ``/``, each name with an optional power of one digit (``m^2``,
  ``m**2``, ``m²``, ``s⁻¹``), or ``1/`` and names (``1/min``); ``°`` and ``%`` are units.

Nothing else is a number, and nothing is coerced or evaluated: ``≈0,59``, ``0,59 ± 0,02``,
a word before the number, ``1,2,3``, ``0.5.9``, ``1 23,4``, ``9**9**9`` are refused with the reason
(a ValueError carrying a catalogue Message).  The unit, once split off and checked, is
converted by a table of the course's units, else by pint on the checked unit expression
only (names, ``*``, ``/`` and one-digit powers: bounded work whatever the text).

Readings the course needs (:func:`quantity` returns them as notes for a warning):
an angular speed written in a frequency unit is revolutions -- ``min^-1``, ``1/min``,
``min⁻¹`` (Latin or Cyrillic) are rev/min (n = 120 min^-1 is 120 rpm) and ``Hz`` is rev/s --, while ``s^-1``,
``1/s``, ``s⁻¹`` are rad/s (ω = 12,57 s^-1); ``grad`` (and its Cyrillic spelling) is degrees (gradians are
``gon``).
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

from .messages import Message

GROUP = " \u00a0\u202f"          # what may group the digits in threes
MINUS = "-\u2212"                # minus signs of a task file; answers add the dash U+2013
DASH = "\u2013"
MAX_CHARS = 100                  # a number with its unit is short; longer text is no number
_SUP = str.maketrans("\u2070\u00b9\u00b2\u00b3\u2074\u2075\u2076\u2077\u2078\u2079\u207b\u207a", "0123456789-+")

_MANTISSA = re.compile(
    r"(?P<sign>[-+\u2212\u2013])?"
    r"(?P<int>[0-9]{1,3}(?:[ \u00a0\u202f][0-9]{3})+(?![0-9])|[0-9]+)?"
    r"(?:(?P<mark>[.,])(?P<frac>[0-9]+)?)?")
_EXPONENT = re.compile(
    r"[eE](?P<es>[-+\u2212]?)(?P<ed>[0-9]{1,3})(?![0-9])"
    r"|[ \u00a0\u202f]?[\u00b7\u22c5\u00d7*][ \u00a0\u202f]?10"
    r"(?:(?:\^|\*\*)(?P<pb>\(?)(?P<ps>[-+\u2212]?)(?P<pd>[0-9]{1,3})(?P<pe>\)?)"
    r"|(?P<sup>[\u207b\u207a]?[\u2070\u00b9\u00b2\u00b3\u2074-\u2079]{1,3}))"
    r"(?![0-9\u2070\u00b9\u00b2\u00b3\u2074-\u2079^*])")
# a unit: names of letters (Latin, Cyrillic, micro), or the signs ° and %
_NAME = re.compile(r"[A-Za-z\u00b5\u03bc\u0400-\u04ff]{1,16}\.?|\u00b0|%")
# a power: ^2, **2, ^(-1), superscripts; and a bare 2 or 3 right after the name as students type
# it ('\u043a\u0433\u00b7\u043c2', 'm/s2')
_POWER = re.compile(r"(?:\^|\*\*)(?P<b>\(?)(?P<s>[-\u2212]?)(?P<d>[1-9])(?P<e>\)?)"
                    r"|(?P<sup>\u207b?[\u00b9\u00b2\u00b3\u2074-\u2079])|(?P<bare>[23])(?![0-9])"
                    r"|(?P<per>[-\u2212]1)(?![0-9])")
# the units a bare -1 may follow: a speed in revolutions per minute as texts print it with its
# superscript lost ('n = 1450 \u043c\u0438\u043d-1', 'min-1'), and per second
_PER_BARE = frozenset({"min", "s"})
# the units a bare 2 or 3 may follow (an area, a volume, an acceleration's s^2): lengths and the second
_BARE_POWER = frozenset({"m", "mm", "cm", "dm", "km", "um", "s"})
_TIMES = re.compile(r"\s*[*\u00b7\u22c5]\s*|\s+(?=[^\s/])")
_OVER = re.compile(r"\s*/\s*")
_PER = re.compile(r"1\s*/\s*")
_CYRILLIC = re.compile(r"[\u0400-\u04ff]")
_OPERATOR = re.compile(r"\s*(?:\*\*|[*/^+\-\u2212\u00d7\u00b7\u22c5])\s*[0-9(.,]")
_PLUS_MINUS = re.compile(r"\s*(?:\u00b1|\+\s*/\s*-|\+-)")
_NONFINITE = {"nan", "+nan", "-nan", "inf", "+inf", "-inf", "infinity", "+infinity", "-infinity"}

# angle units: an angular speed whose unit names none is written in a frequency unit
ANGLE_NAMES = {"rad", "radian", "radians", "deg", "degree", "degrees", "degree_angle", "revolution", "rev",
               "revolutions", "turn", "turns", "cycle", "rpm", "rps", "gon", "gradian", "arcmin", "arcsec",
               "arcminute", "arcsecond"}
# the frequency spellings of an angular speed the course uses: (name, power) -> (rad/s per 1, note code)
_FREQUENCY = {(("min", -1),): (2 * math.pi / 60, "input.reading_per_min"),
              (("minute", -1),): (2 * math.pi / 60, "input.reading_per_min"),
              (("Hz", 1),): (2 * math.pi, "input.reading_hz"),
              (("s", -1),): (1.0, "input.reading_per_s"),
              (("second", -1),): (1.0, "input.reading_per_s")}
_GRAD = ("grad", "degree")        # the course's Cyrillic "grad" (and its transliteration): degrees
_SIGNS = {"\u00b0": "degree", "%": "percent"}
# units spelt out that the unit table knows by their short name (revolutions per minute: rpm;
# 'rev/min', and ISO 80000's and GOST 8.417's Latin 'r/min', 'r/s', as texts abbreviate them)
_SAME = {(("revolution", 1), ("min", -1)): (("rpm", 1),), (("rev", 1), ("min", -1)): (("rpm", 1),),
         (("r", 1), ("min", -1)): (("rpm", 1),), (("rev", 1), ("s", -1)): (("rps", 1),),
         (("r", 1), ("s", -1)): (("rps", 1),)}


@dataclass(frozen=True)
class Reading:
    """A number as written: its value, whether it was written as a whole number (digits
    only), its unit as (Latin name, power) factors and the unit's own text."""
    value: float
    integral: bool
    unit: tuple = ()
    unit_text: str = ""
    text: str = ""
    notes: tuple = ()             # ('input.reading_grad', ...) met while reading the unit

    @property
    def expression(self) -> str:
        """The unit as pint reads it ('kg*m**2', 'm/s**2', '1/min'); '' for none."""
        return unit_expression(self.unit)


def unit_expression(factors) -> str:
    up = [n if p == 1 else f"{n}**{p}" for n, p in factors if p > 0]
    down = [n if p == -1 else f"{n}**{-p}" for n, p in factors if p < 0]
    text = "*".join(up) or ("1" if down else "")
    return text + "".join("/" + d for d in down)


@lru_cache(maxsize=1)
def spellings() -> dict:
    """The Cyrillic spellings of units and column headers (spellings.yaml)."""
    import yaml

    text = (Path(__file__).resolve().parent / "spellings.yaml").read_text(encoding="utf-8")
    data = yaml.load(text, Loader=getattr(yaml, "CSafeLoader", yaml.SafeLoader))
    return {"units": dict(data.get("units") or {}), "headers": dict(data.get("headers") or {})}


def header_name(text: str) -> str:
    """A column header as tmm reads it: the Russian and Ukrainian words for variant,
    student and group (spellings.yaml `headers`) are `variant`, `student`, `group`; any
    other header as it is."""
    s = text.strip()
    if _CYRILLIC.search(s):
        return spellings()["headers"].get(s.lower(), s)
    return s


def read(text: str, *, answer: bool = False) -> Reading:
    """The number (and unit) ``text`` holds; ValueError(Message) with the reason when it
    holds anything else. ``answer``: a student's answer, where a dash U+2013 is a minus."""
    s = text.strip()
    if len(s) > MAX_CHARS or not s:
        raise ValueError(Message("input.number_not_number", text=s[:40] + ("…" if len(s) > 40 else "")))
    if s.lower() in _NONFINITE:
        raise ValueError(Message("input.not_finite"))
    m = _MANTISSA.match(s)
    if m.group("int") is None and m.group("frac") is None:
        _refuse_start(s)
    sign, mark = m.group("sign") or "", m.group("mark")
    if sign == DASH and not answer:
        raise ValueError(Message("input.number_dash", text=s))
    if mark == "," and m.group("frac") is None:
        raise ValueError(Message("input.number_not_number", text=s))
    digits = (m.group("int") or "0").translate({ord(c): None for c in GROUP})
    number = f"{'-' if sign and sign != '+' else ''}{digits}.{m.group('frac') or '0'}"
    pos, exponent = m.end(), None
    e = _EXPONENT.match(s, pos)
    if e is not None:
        if e.group("ed") is not None:
            exponent = e.group("es").replace("\u2212", "-") + e.group("ed")
        elif e.group("pd") is not None:
            if bool(e.group("pb")) != bool(e.group("pe")):
                raise ValueError(Message("input.number_expression", text=s))
            exponent = e.group("ps").replace("\u2212", "-") + e.group("pd")
        else:
            exponent = e.group("sup").translate(_SUP)
        number += "e" + exponent
        pos = e.end()
    value = float(number)
    integral = mark is None and exponent is None
    rest = s[pos:]
    if not rest:
        return Reading(value, integral, text=s)
    frac = _fraction(rest)
    if frac is not None:
        if frac == 0:
            raise ValueError(Message("input.fraction_zero"))
        return Reading(value / frac, False, text=s)
    dms = _DMS.fullmatch(rest) if integral else None
    if dms is not None:                  # 36°8′, 36°08'30": degrees, minutes (and seconds)
        minutes, seconds = (float((g or "0").replace(",", ".")) for g in dms.group("m", "s"))
        if minutes >= 60 or seconds >= 60:
            raise ValueError(Message("input.number_dms", text=s))
        whole = abs(value) + minutes / 60 + seconds / 3600
        factors, notes = parse_unit("\u00b0", s)
        return Reading(-whole if number.startswith("-") else whole, False, factors, "\u00b0", s, notes)
    _refuse_rest(s, rest)
    factors, notes = parse_unit(rest.strip(), s)
    return Reading(value, integral, factors, rest.strip(), s, notes)


# degrees and minutes (and seconds) after a whole number of degrees: 36°8′, 36° 08' 30"
_DMS = re.compile("\\s*\u00b0\\s*(?P<m>[0-9]+(?:[.,][0-9]+)?)\\s*['\u2032]"
                  "(?:\\s*(?P<s>[0-9]+(?:[.,][0-9]+)?)\\s*[\"\u2033])?\\s*")


def _fraction(rest: str) -> float | None:
    """The denominator of '<number>/<number>' (rest = '/18'), else None."""
    m = re.fullmatch(r"\s*/\s*([0-9]+(?:\.[0-9]+)?)\s*", rest)
    return None if m is None else float(m.group(1))


def _refuse_start(s: str):
    """The reason a text that does not begin with a number is none."""
    first = next((i for i, ch in enumerate(s) if "0" <= ch <= "9"), None)
    if first is None:
        raise ValueError(Message("input.number_not_number", text=s))
    prefix = s[:first].strip()
    if prefix and prefix not in ("-", "+", "\u2212", "\u2013", ".", ","):
        raise ValueError(Message("input.number_prefix", text=s,
                                 prefix=prefix.rstrip("-+\u2212\u2013.,").strip() or prefix))
    raise ValueError(Message("input.number_not_number", text=s))


def _refuse_rest(s: str, rest: str):
    """The reason when what follows the number is not a unit."""
    if re.match(r"[.,][0-9]", rest):
        raise ValueError(Message("input.number_marks", text=s))
    if _PLUS_MINUS.match(rest):
        raise ValueError(Message("input.number_plus_minus", text=s))
    if re.match(r"[ \u00a0\u202f]+[0-9]", rest) and not _PER.match(rest.lstrip()):
        raise ValueError(Message("input.number_groups", text=s))
    if _OPERATOR.match(rest) or rest.lstrip().startswith(("(", ")")):
        raise ValueError(Message("input.number_expression", text=s))
    if rest.strip()[:1] in _NOT_DEGREE:   # 182,14º: Word's ordinal indicator (or a ring) for the degree sign
        raise ValueError(Message("input.number_not_degree", text=s, sign=rest.strip()[0],
                                 code=f"U+{ord(rest.strip()[0]):04X}"))
    if not (rest[0].isspace() or _NAME.match(rest) or _PER.match(rest)):
        raise ValueError(Message("input.number_not_number", text=s))


# signs that look like the degree sign ° (U+00B0) and are not: the masculine ordinal indicator º
# (Word's autocorrect of "o" after a number), the ring above ˚, the superscript o
_NOT_DEGREE = "\u00ba\u02da\u1d52"


def parse_unit(u: str, s: str = "") -> tuple[tuple, tuple]:
    """((Latin name, power), ...) of a unit's text, and the notes of its reading
    ('input.reading_grad'); ValueError(Message) when it is not written as a unit."""
    s = s or u
    factors: list[tuple[str, int]] = []
    notes: list[str] = []
    pos, below = 0, False
    per = _PER.match(u)
    if per:
        pos, below = per.end(), True
    while True:
        m = _NAME.match(u, pos)
        if m is None:
            raise ValueError(Message("input.number_unit_syntax", text=s, unit=u))
        name, pos = m.group(0), m.end()
        power, bare = 1, False
        p = _POWER.match(u, pos)
        if p is not None:
            if p.group("d") is not None:
                if bool(p.group("b")) != bool(p.group("e")):
                    raise ValueError(Message("input.number_unit_syntax", text=s, unit=u))
                power = int(p.group("d")) * (-1 if p.group("s") else 1)
            elif p.group("bare") is not None:
                power = int(p.group("bare"))
                bare = True
            elif p.group("per") is not None:
                power, bare = -1, True
            else:
                power = int(p.group("sup").translate(_SUP))
            pos = p.end()
        for latin, k in _latin(name, s):
            if bare and latin not in (_PER_BARE if power == -1 else _BARE_POWER):   # '30°2' is no squared
                raise ValueError(Message("input.number_unit_syntax", text=s, unit=u))   # degree: refused
            if latin == _GRAD[0]:
                latin = _GRAD[1]
                # said for the Latin 'grad' only (pint's gradian): the Cyrillic word is degrees in
                # every course book, and a student who writes it means nothing else
                if "input.reading_grad" not in notes and not _CYRILLIC.search(name):
                    notes.append("input.reading_grad")
            factors.append((latin, k * power * (-1 if below else 1)))
        if pos == len(u):
            break
        over = _OVER.match(u, pos)
        if over is not None and over.end() > pos:
            if below:
                raise ValueError(Message("input.number_unit_syntax", text=s, unit=u))
            below, pos = True, over.end()
            continue
        times = _TIMES.match(u, pos)
        if times is None or times.end() == pos:
            raise ValueError(Message("input.number_unit_syntax", text=s, unit=u))
        pos = times.end()
    merged = _merged(factors)
    return _SAME.get(merged, merged), tuple(notes)


def _latin(name: str, s: str) -> list[tuple[str, int]]:
    """A unit name's Latin factors: Cyrillic 'mm' -> [('mm', 1)], 'Nm' -> [('N', 1), ('m', 1)]."""
    if name in _SIGNS:
        return [(_SIGNS[name], 1)]
    if _CYRILLIC.search(name):
        table = spellings()["units"]
        latin = table.get(name, table.get(name.rstrip(".")))
        if latin is None:
            raise ValueError(Message("input.number_unit_unknown", text=s, unit=name))
        return [(n, 1) for n in latin.split("*")]
    name = name.rstrip(".")
    if name in ("Nm", "kNm"):
        return [(name[:-1], 1), ("m", 1)]
    return [(name, 1)]


def _merged(factors: list) -> tuple:
    """Equal names' powers added ('m*m' is m**2), in the order first met; none of power 0."""
    out: dict[str, int] = {}
    for n, p in factors:
        out[n] = out.get(n, 0) + p
    return tuple((n, p) for n, p in out.items() if p != 0)


# ------------------------------------------------------------------ conversion
def in_unit(r: Reading, target: str, *, angular: bool = False, fast: dict | None = None) -> tuple[float, list]:
    """The reading in pint's unit ``target`` ('m', 'rad/s', 'degree'), with the notes of
    its reading. ``angular``: the quantity is an angular speed (frequency units read as
    the course does). ``fast``: {unit expression: factor to target} tried before pint.
    Raises ValueError(None) when the unit does not convert to ``target`` (the caller
    names the quantity), ValueError(Message) for a unit pint does not know."""
    notes = list(r.notes)
    if angular and r.unit in _FREQUENCY:
        factor, note = _FREQUENCY[r.unit]
        notes.append(note)
        return r.value * factor * (1.0 if target == "rad/s" else _pint_factor("rad/s", target)), notes
    if fast is not None and r.expression in fast:
        return r.value * fast[r.expression], notes
    if angular and not any(n in ANGLE_NAMES for n, _ in r.unit):
        # pint would read '120 kHz' or '3 1/h' as radians per second: a frequency, refused
        try:
            _pint_factor(r.expression, target)       # unknown or not of the dimension: its own error
        except ValueError as exc:
            msg = exc.args[0] if exc.args else None
            if isinstance(msg, Message) and msg.code == "input.number_unit_unknown":
                raise ValueError(Message("input.number_unit_unknown", text=r.text, unit=msg.params["unit"])) from None
            raise
        raise ValueError(Message("input.number_frequency", text=r.text))
    try:
        return r.value * _pint_factor(r.expression, target), notes
    except ValueError as exc:
        msg = exc.args[0] if exc.args else None
        if isinstance(msg, Message) and msg.code == "input.number_unit_unknown":      # the whole text named
            raise ValueError(Message("input.number_unit_unknown", text=r.text, unit=msg.params["unit"])) from None
        raise


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


@lru_cache(maxsize=256)
def _pint_factor(expression: str, target: str) -> float:
    """pint's factor from a checked unit expression to ``target``."""
    import pint

    reg = ureg()
    try:
        q = reg.Quantity(1.0, expression)
    except pint.errors.UndefinedUnitError as exc:
        names = getattr(exc, "unit_names", None) or (expression,)
        raise ValueError(Message("input.number_unit_unknown", text=expression, unit=str(names[0]))) from None
    except Exception:  # noqa: BLE001 - pint's parser errors of any kind on a checked expression
        raise ValueError(Message("input.number_unit_syntax", text=expression, unit=expression)) from None
    if target == "dimensionless":
        if not q.dimensionless:
            raise ValueError(None)
        return float(q.to("dimensionless").magnitude)
    try:
        return float(q.to(target).magnitude)
    except Exception:  # noqa: BLE001 - pint: another dimension (or an offset unit)
        raise ValueError(None) from None


def is_dimensionless(expression: str) -> bool:
    """Whether a checked unit expression is dimensionless (rad, deg, %) for pint."""
    try:
        _pint_factor(expression, "dimensionless")
    except ValueError as exc:
        if exc.args and exc.args[0] is not None:
            raise
        return False
    return True


@lru_cache(maxsize=256)
def _pint_base(expression: str) -> float:
    """pint's factor from a checked unit expression to SI base units."""
    try:
        return float(ureg().Quantity(1.0, expression).to_base_units().magnitude)
    except Exception:  # noqa: BLE001 - pint's parser errors of any kind on a checked expression
        raise ValueError(Message("input.number_unit_unknown", text=expression, unit=expression)) from None


# the dimensions of the course's quantities (a result path whose unit the answers reader does not
# know is read in SI base units, of one of these): lengths, masses, times, speeds and
# accelerations (linear and angular), forces, moments and works, inertias, pressures, areas,
# densities, powers, stiffnesses, and plain numbers (angles in radians)
_COURSE_UNITS = ("m", "kg", "s", "m/s", "m/s**2", "1/s", "1/s**2", "N", "N*m", "kg*m**2", "Pa", "m**2",
                 "kg/m**3", "W", "N/m", "dimensionless")


@lru_cache(maxsize=None)
def _course_dimensions() -> frozenset:
    u = ureg()
    return frozenset(u.Quantity(1.0, e).dimensionality for e in _COURSE_UNITS)


def _course_dimension(expression: str) -> bool:
    """The unit ``expression`` measures one of the course's quantities (:data:`_COURSE_UNITS`)."""
    try:
        return ureg().Quantity(1.0, expression).dimensionality in _course_dimensions()
    except Exception:  # noqa: BLE001 - pint's parser errors: _pint_base names the unit
        return True


def answer(text: str, unit: str | None, *, angle: bool = False, angular: bool = False) -> float:
    """A student's answer in ``unit`` (pint's words: 'm/s**2', 'degree', 'dimensionless';
    None: SI base units). ``angle``: an angle (any angle unit to degrees, a plain number
    in degrees); ``angular``: an angular speed (min^-1 and Hz are revolutions, s^-1 rad/s).
    ValueError(Message) with the reason for anything that is not a number of that unit."""
    r = read(text, answer=True)
    if not r.unit:
        return r.value
    target = "degree" if angle else unit
    if angular and target is None:
        target = "rad/s"
    try:
        if target is None:
            if not _course_dimension(r.expression):      # 'MM' is pint's megamolar: 5 MM was 5e9
                raise ValueError(Message("answers.unit_not_course", value=repr(r.text), unit=r.unit_text))
            if len(r.unit) == 1 and r.unit[0][0] in ANGLE_NAMES and r.unit[0][1] == 1:
                # an angle where the path's unit is open (a stroke H: m, or a rocker's swing): in
                # degrees, as results.json holds every angle (SI's radian read 45,6 deg as 0.796)
                try:
                    return in_unit(r, "degree")[0]
                except ValueError:          # rpm, rps: no angle (read in SI base units below)
                    pass
            return r.value * _pint_base(r.expression)
        return in_unit(r, target, angular=angular)[0]
    except ValueError as exc:
        if exc.args and exc.args[0] is not None:
            raise
        from .limits import in_cyrillic
        cyr = in_cyrillic(r.unit_text)
        if cyr is not None and _converts(cyr, target, angular):
            raise ValueError(Message("answers.wrong_unit_latin", value=repr(r.text), written=r.unit_text,
                                     cyr=cyr)) from None
        raise ValueError(Message("answers.wrong_unit", value=repr(r.text), unit=target.replace("**", "^"))) from None


def _converts(unit_text: str, target: str, angular: bool) -> bool:
    """One ``unit_text`` reads and converts to ``target``."""
    try:
        in_unit(read(f"1 {unit_text}", answer=True), target, angular=angular)
    except ValueError:
        return False
    return True
