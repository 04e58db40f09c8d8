"""Numbers as the reader's language writes them: the one place that knows it.

English keeps the decimal point and Python's exponent (``8.9e-16``); Russian and Ukrainian
typeset the decimal comma and powers of ten (``0,25``, ``8,9·10⁻¹⁶``).  Every formatter of a
text a person reads (the report, its figures and PDF, the sheets, forms, feedback pages,
messages) passes its formatted number through :func:`localize`; machine files (results.json,
CSV, DXF coordinates) never do.

The language is either given (``localize(s, lang)``) or the one of the enclosing
``with language(lang):`` block -- a context variable, so the report's sections, figures and
charts, which format numbers deep below the code that knows the language, need no parameter
for it.  Outside any block the numbers stay as Python writes them.
"""
from __future__ import annotations

import contextlib
import contextvars
import functools
import re
import string
from typing import Any


@functools.cache
def comma_langs() -> tuple[str, ...]:
    """The languages whose typeset numbers use the decimal comma (the catalogues' numbers
    `format.decimal`: ru and uk)."""
    from . import locales
    return tuple(lang for lang in locales.LANGS if locales.of("numbers", "format", lang).get("decimal") == ",")


_LANG: contextvars.ContextVar[str] = contextvars.ContextVar("tmm_number_language", default="en")

_SUP = str.maketrans("0123456789-+", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻⁺")
# a formatted number: sign, digits, decimals, exponent (what format() gives for a float)
# (not a part of a designation or a date: 'KP.07.00.00', '06.12.2026', 'v1.2' stay as they are)
_NUMBER = re.compile(r"(?<!\w)(?<!\w\.)([-+\u2212]?)(\d+)(?:\.(\d*))?(?:[eE]([-+\u2212]?)(\d+))?(?!\w)(?!\.\d)")


def current() -> str:
    """The language of the enclosing ``with language(...)`` block ('en' outside any)."""
    return _LANG.get()


@contextlib.contextmanager
def language(lang: str | None):
    """Numbers formatted inside the block are written the way ``lang`` writes them."""
    token = _LANG.set(lang if lang in comma_langs() else "en")
    try:
        yield
    finally:
        _LANG.reset(token)


def comma(lang: str | None = None) -> bool:
    """True when numbers in ``lang`` (default: the current one) take the decimal comma."""
    return (lang if lang is not None else _LANG.get()) in comma_langs()


def list_sep(lang: str | None = None) -> str:
    """What separates the numbers of a list in ``lang``: ", " (0.5, 1.25), or "; " where the
    decimal comma is written (0,5; 1,25: "0, 180" would read as a decimal "0,180")."""
    return "; " if comma(lang) else ", "


def superscript(s: str) -> str:
    """Digits and signs raised: '-5' -> '⁻⁵' (a power of ten as typeset text writes it)."""
    return s.translate(_SUP)


def _typeset(m: re.Match) -> str:
    sign, whole, dec, esign, exp = m.groups()
    s = ("\u2212" if sign in ("-", "\u2212") else sign) + whole + ("," + dec if dec else "")
    if exp is not None:
        e = int(exp)
        if e == 0:
            return s
        return s + "·10" + (("-" if esign in ("-", "\u2212") else "") + str(e)).translate(_SUP)
    return s


def localize(s: str, lang: str | None = None) -> str:
    """A formatted number (or a short text of formatted numbers: '0.5..1.25', '8.9e-16 m')
    in ``lang``'s writing: unchanged in English, '0,5', '8,9·10⁻¹⁶', '−1,19' (the minus sign,
    U+2212, as typeset text writes it) in ru/uk."""
    if not comma(lang) or not s or ("." not in s and "e" not in s and "E" not in s and "-" not in s):
        return s
    return _typeset_all(s)


@functools.lru_cache(maxsize=8192)
def _typeset_all(s: str) -> str:
    """Every number of ``s`` typeset (remembered: a drawing's labels repeat)."""
    return _NUMBER.sub(_typeset, s)


def num(x: Any, spec: str = "", lang: str | None = None) -> str:
    """``format(x, spec)`` written in the language (a non-number: ``str(x)``)."""
    if isinstance(x, bool) or not isinstance(x, (int, float)) and not hasattr(x, "__float__"):
        return format(x, spec) if spec else str(x)
    return localize(format(x, spec), lang)


@functools.cache
def _plural_rule(lang: str) -> str:
    """How ``lang`` chooses the noun after a count (its numbers catalogue's `format.plural`)."""
    from . import locales
    return locales.of("numbers", "format", lang).get("plural", "one_other")


def plural(value: Any, forms: list[str], lang: str | None = None) -> str:
    """The count ``value`` (written in ``lang``) and the noun's form that follows it:
    ``forms`` as the catalogue gives them, (one, other) in English, (one, few, many) in
    Russian and Ukrainian (transliterated: 1 polozhenie, 24 polozheniya, 12 polozheniy,
    21 polozhenie); a fraction takes the few form, the other in English. A catalogue writes
    ``{n:|position|positions}`` (three forms in ru and uk)."""
    lang = lang if lang is not None else current()
    try:
        x = abs(float(value))
    except (TypeError, ValueError):
        return f"{value} {forms[-1]}"
    if _plural_rule(lang) == "one_few_many":
        if not x.is_integer():
            k = 1
        else:
            n = int(x)
            k = 0 if n % 10 == 1 and n % 100 != 11 else (1 if 2 <= n % 10 <= 4 and not 12 <= n % 100 <= 14 else 2)
    else:
        k = 0 if x == 1 else 1
    return f"{localize(str(value), lang)} {forms[min(k, len(forms) - 1)]}"


_WRITTEN = re.compile(r"[-+\u2212]?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?")


def is_number(value: Any) -> bool:
    """A number, or a text that is one number as Python writes it ('0.02', '8.9e-16': a
    parameter formatted beforehand)."""
    if isinstance(value, str):
        return bool(_WRITTEN.fullmatch(value))
    return not isinstance(value, bool) and (isinstance(value, (int, float))
                                            or type(value).__module__ == "numpy" and hasattr(value, "__float__"))


class Formatter(string.Formatter):
    """``str.format`` whose numeric fields are written in ``lang`` (the current language when
    None): the message catalogues' and the report tables' templates ("{phi:.4g}°")."""

    def __init__(self, lang: str | None = None):
        super().__init__()
        self.lang = lang

    def format_field(self, value: Any, spec: str) -> str:
        if spec.startswith("|"):                    # a count and its noun: {n:|position|positions}
            return plural(value, spec[1:].split("|"), self.lang)
        text = super().format_field(value, spec)
        return localize(text, self.lang) if is_number(value) else text


def below_one(x: float) -> str:
    """``x`` (< 1) to three significant digits, or as many more as keep it below 1: a sentence
    that says "K < 1" never shows "K = 1" (0.99962 -> '0.9996'); Python's writing (localize it
    for a language)."""
    for digits in range(3, 18):
        shown = f"{x:.{digits}g}"
        if float(shown) < 1.0:
            return shown
    return repr(float(x))


def crank_deg(x: float, places: int = 3) -> str:
    """A crank angle in degrees as a sentence names it: in [0, 360) (a crank angle is periodic:
    -1e-9 and 359.9999999 are 0), to ``places`` decimals with the trailing zeros dropped
    (180.0000016 -> '180', 38.94236 -> '38.942'): a position found by a root search at a
    change point is not shown with the search's last digits. Python's writing (localize it
    for a language)."""
    v = round(float(x) % 360.0, places)
    if v >= 360.0:
        v -= 360.0
    text = f"{v:.{places}f}"
    if "." in text:                     # the decimals' trailing zeros only (places = 0: '180', not '18')
        text = text.rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def format_text(template: str, lang: str | None = None, /, **kw) -> str:
    """``template.format(**kw)`` with the numeric fields written in ``lang``."""
    return Formatter(lang).format(template, **kw)
