"""Warnings as data: a stable code, named parameters and one catalogue per language.

A stage reports a warning as ``Message("cam.soft_impact", phi=140.0, where="far_dwell/return")``.
The message *is* its English text (``Message`` is a ``str``, rendered from the English
catalogue when it is made), so the stages and their tests handle warnings as strings;
beside the text it carries ``code`` and ``params``.  The pipeline writes both forms to
results.json: ``warnings`` (the English texts) and ``messages``
(``{"code", "params", "text"}`` in the same order); a report renders ``messages``
through the catalogue of its language (:func:`render_list`).

The catalogues are the topic ``messages`` of every language's catalogue set
(``tmm_cli/locales/<lang>/messages.yaml``, read through :mod:`tmm_cli.locales`)::

    messages:                  # code -> template (str.format, parameters by name)
      cam.soft_impact: "soft impact (finite jump of acceleration) at phi = {phi:.4g} deg ({where})"
    terms:                     # word tables a template names as the format spec
      phase: {rise: rise, far_dwell: far dwell}    # in ru, uk: the course's words

A placeholder ``{where:phase}`` renders the parameter through the language's ``phase``
table (the whole value, else each ``/``-separated part, joined by `` / ``; a list joined by
``, ``); the spec ``or`` joins a list as alternatives (``'a', 'b' or 'c'``, the word from the
language's ``conj`` table); a list of messages is one a line, or with ``joined`` one line
joined by ``; ``; the spec ``angles`` shows crank-angle intervals ``[[a, b], ...]``
as ``φ = 37.5…52.1°`` (:data:`SPECS`); any other
spec is a Python format spec (a list parameter: each item formatted -- an interval ``[a, b]``
as ``a..b`` --, joined by ``, ``).
Parameters are plain JSON values (numbers in the unit the text shows).  Adding a
language is adding its folder of catalogues (tmm_cli/locales/<lang>/, this topic among
them); tests/test_messages.py checks that every code and placeholder of English exists in
every other catalogue.
"""
from __future__ import annotations

import functools
import string
from typing import Any

from .. import locales, numfmt

# the languages: one folder of catalogues each, English first
LANGS = locales.LANGS

# a warning given as a plain string (not a Message): shown as written in every language
PLAIN = "text"
# format specs the formatter knows beside Python's and the word tables: `or` (alternatives)
# `angles` (crank-angle intervals [[from, to], ...] in degrees: "φ = 37.5…52.1°") and
# `joined` (a list of messages in one line, joined by "; "; without it: one a line), `below1`
# (a number < 1 to three digits or as many more as keep it below 1: numfmt.below_one), `deg`
# (a crank angle, or a list of them, in [0, 360) to 0.001 deg: numfmt.crank_deg); a
# count's noun in its forms, `|form|form...` (numfmt.plural: "{n:|character|characters}"), and
# the noun alone in the form a list's length takes, `#form|form...` ("{angles:#angle|angles}")
SPECS = ("or", "angles", "joined", "below1", "deg")


def _angles(intervals: list, sep: str = ", ") -> str:
    """Crank-angle intervals as "φ = 37.5…52.1°, 250.0…265.5°": to 0.1°, or finer (to
    0.001°) where an interval would show the same number at both ends; ``sep`` between them
    ("; " where the decimal comma is written)."""
    out = []
    for a, b in intervals:
        d = 1
        while d < 3 and f"{a:.{d}f}" == f"{b:.{d}f}":
            d += 1
        out.append(f"{a:.{d}f}…{b:.{d}f}°")
    return "φ = " + sep.join(out)


@functools.cache
def catalogue(lang: str) -> dict:
    """The catalogue of ``lang``: ``{"messages": {code: template}, "terms": {name: {word: text}},
    "folded": {code: template}}`` (``folded``: the short forms of :func:`grouped`)."""
    data = locales.topic(lang, "messages")
    return {"messages": dict(data.get("messages") or {}), "terms": dict(data.get("terms") or {}),
            "folded": dict(data.get("folded") or {})}


def unit(text: str, lang: str | None = None) -> str:
    """A unit as a task writes it ('m/s', 'rad/s', 'N*m', 'mm') in the language's spelling
    (in ru and uk Cyrillic letters and the raised dot: the catalogue's ``unit`` table; unchanged
    where it has none);
    ``lang`` None: the language of the enclosing ``numfmt.language`` block."""
    return catalogue(lang if lang is not None else numfmt.current())["terms"].get("unit", {}).get(text, text)


class _Formatter(string.Formatter):
    """``str.format`` whose spec may name a word table of the catalogue; list values are
    formatted item by item and joined by ``", "``."""

    def __init__(self, terms: dict, lang: str = "en"):
        super().__init__()
        self.terms = terms
        self.lang = lang

    def format_field(self, value: Any, spec: str) -> str:
        if isinstance(value, dict) and "code" in value:      # a message inside a message
            return localize(value, self.lang)
        if isinstance(value, list) and value and all(isinstance(v, dict) and "code" in v for v in value):
            return ("; " if spec == "joined" else "\n").join(localize(v, self.lang) for v in value)
        if spec.startswith("|"):                            # a count and its noun: {n:|character|characters}
            return numfmt.plural(value, spec[1:].split("|"), self.lang)
        if spec.startswith("#"):                            # the noun alone, by a list's length: {a:#angle|angles}
            n = len(value) if isinstance(value, list) else value
            return numfmt.plural(n, spec[1:].split("|"), self.lang).split(" ", 1)[1]
        if spec == "raw":                                   # as written (a number not localized: '0.38')
            return str(value)
        if spec == "below1" and numfmt.is_number(value):    # a value < 1 never shown as 1 (K = 0.9996 < 1)
            return numfmt.localize(numfmt.below_one(float(value)), self.lang)
        if spec == "deg" and isinstance(value, list):       # crank angles: "0, 180" ("0; 180" in ru, uk)
            return numfmt.list_sep(self.lang).join(numfmt.localize(numfmt.crank_deg(v), self.lang) for v in value)
        if spec == "deg" and numfmt.is_number(value):       # a crank angle: 180.0000016 -> "180"
            return numfmt.localize(numfmt.crank_deg(value), self.lang)
        if spec == "angles" and isinstance(value, list):
            return numfmt.localize(_angles(value, numfmt.list_sep(self.lang)), self.lang)
        if spec == "or" and isinstance(value, list):        # alternatives: 'a', 'b' or 'c'
            word = self.terms.get("conj", {}).get("or", "or")
            items = [str(v) for v in value]
            return items[0] if len(items) == 1 else f"{', '.join(items[:-1])} {word} {items[-1]}"
        table = self.terms.get(spec) if spec else None
        if table is not None:
            if isinstance(value, list):
                return ", ".join(str(table.get(str(v), v)) for v in value)
            if str(value) in table:
                return str(table[str(value)])
            parts = str(value).split("/")
            return " / ".join(str(table.get(p, p)) for p in parts) if any(p in table for p in parts) else str(value)
        if isinstance(value, list):                          # an interval [a, b]: a..b
            # a list of numbers where the decimal comma is written (ru, uk): items separated by
            # "; ", an interval's ends by "…" ("0,5; 1,25", "45…105"), never a comma between numbers
            comma = numfmt.comma(self.lang)
            dots = "…" if comma else ".."
            numbers = comma and any(isinstance(v, list) or numfmt.is_number(v) for v in value)
            return (numfmt.list_sep(self.lang) if numbers else ", ").join(
                f"{numfmt.num(v[0], spec, self.lang)}{dots}{numfmt.num(v[1], spec, self.lang)}"
                if isinstance(v, list) and len(v) == 2 else numfmt.num(v, spec, self.lang) for v in value)
        return numfmt.localize(format(value, spec), self.lang) if numfmt.is_number(value) else format(value, spec)


def render(code: str, params: dict, lang: str = "en") -> str:
    """The text of message ``code`` with ``params`` in ``lang`` (English when the language
    or the code is unknown). Raises KeyError for a code no catalogue knows."""
    cat = catalogue(lang if lang in LANGS else "en")
    template = cat["messages"].get(code)
    if template is None:
        if lang == "en":
            raise KeyError(f"unknown message code {code!r}")
        return render(code, params, "en")
    return _Formatter(cat["terms"], lang if lang in LANGS else "en").format(template, **params)


def _plain(value: Any) -> Any:
    """A parameter as a plain JSON value (numpy scalars and arrays, tuples)."""
    if isinstance(value, Message):           # a message inside a message: kept as data
        return value.to_dict()
    if value is None or type(value) in (str, bool, int, float):
        return value
    if isinstance(value, bool):
        return bool(value)
    for kind in (str, int, float):          # subclasses (numpy.float64, ...) as the plain type
        if isinstance(value, kind):
            return kind(value)
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, dict):
        return {str(k): _plain(v) for k, v in value.items()}
    item = getattr(value, "tolist", None)
    if item is not None:
        return _plain(item())
    return str(value)


def _rebuild(code: str, params: dict) -> "Message":
    return Message(code, **params)


class Message(str):
    """A warning: its English text (the string itself), ``code`` and ``params``."""

    code: str
    params: dict

    def __new__(cls, code: str, /, **params: Any) -> "Message":
        params = {k: _plain(v) for k, v in params.items()}
        self = super().__new__(cls, render(code, params, "en"))
        self.code = code
        self.params = params
        return self

    def __reduce__(self):
        return _rebuild, (self.code, self.params)

    def to_dict(self) -> dict:
        return {"code": self.code, "params": dict(self.params), "text": str(self)}


def as_message(text: str) -> "Message":
    """``text`` as a Message: itself when it is one (coded), else the plain ``text`` code."""
    return text if isinstance(text, Message) else Message(PLAIN, text=str(text))


def as_dict(warning: str) -> dict:
    """The results.json ``messages`` entry of a warning (a plain string gets code ``text``)."""
    if isinstance(warning, Message):
        return warning.to_dict()
    return {"code": PLAIN, "params": {"text": str(warning)}, "text": str(warning)}


def localize(entry: dict, lang: str) -> str:
    """A results.json ``messages`` entry in ``lang``; its English ``text`` when the entry
    cannot be rendered (a code or parameter this version does not know)."""
    try:
        return render(entry["code"], entry.get("params") or {}, lang)
    except (KeyError, IndexError, TypeError, ValueError, AttributeError):
        return str(entry.get("text", ""))


def in_lang(note, lang: str) -> str:
    """A warning or note (a coded :class:`Message`, or plain text shown as written) in ``lang``:
    the terminal's lines under `--lang`."""
    if lang != "en" and isinstance(note, Message):
        return localize(note.to_dict(), lang)
    return str(note)


def render_list(section: dict, lang: str) -> list[str]:
    """The warnings of a results dict (or one section of it) in ``lang``: its ``messages``
    rendered through the catalogue, else (results written before messages existed) its
    English ``warnings`` as they are."""
    entries = section.get("messages")
    if entries is not None:
        return [localize(e, lang) for e in entries]
    return [str(w) for w in section.get("warnings") or []]


# a change point's warnings under one head: the warnings of the same crank angle (to the 0.001 deg a
# message shows) and group, each in its short form (the catalogue's ``folded`` table), and the
# group's list of singular angles where every angle of it is such a head
HEAD = "kinematics.change_point"
SUMMARY = "kinematics.singular_continuity"


# what an item's short form leaves out (said by its head or too technical there): merged over positions
_PER_POSITION = ("phi", "det", "ill", "position")


def _same_angle(a, b) -> bool:
    return numfmt.is_number(a) and numfmt.is_number(b) and numfmt.crank_deg(a) == numfmt.crank_deg(b)


def grouped(entries: list[dict]) -> list[tuple[dict, list[dict]]]:
    """results.json ``messages`` entries as the terminal and the report show them: ``[(entry,
    items)]`` in their order, where a change point's entry (:data:`HEAD`) takes as its items the
    later entries of its crank angle whose code has a short form (its group's, where the entry
    names a group: the continuity limits, the values without one, the dead point, the
    kinetostatics without a solution), and a group's summary of singular angles (:data:`SUMMARY`)
    is left out where each of its angles is a head of that group.  An item is ``{"code",
    "params"}`` with ``position`` the list of the positions it was given for (a grid position and
    the extreme one at the same angle make one item).  Every other entry stands alone with no
    items; results.json keeps every entry as it is."""
    short = catalogue("en")["folded"]
    heads = [e for e in entries if e.get("code") == HEAD]
    out: list[tuple[dict, list[dict]]] = []
    taken: set[int] = set()
    for n, e in enumerate(entries):
        if id(e) in taken:
            continue
        p = e.get("params") or {}
        if e.get("code") == SUMMARY and p.get("angles") and all(
                any(h["params"].get("group") == p.get("group") and _same_angle(h["params"].get("phi"), a)
                    for h in heads) for a in p["angles"]):
            continue
        items: dict = {}
        if e.get("code") == HEAD:
            for f in entries[n + 1:]:           # its later entries: one before it was shown alone
                q = f.get("params") or {}
                if (f.get("code") in short and id(f) not in taken and _same_angle(q.get("phi"), p.get("phi"))
                        and q.get("group", p.get("group")) == p.get("group")):
                    taken.add(id(f))
                    # two positions at the angle (a grid position and the extreme one): one item,
                    # the positions listed (the short form names neither the angle nor the determinant)
                    rest = {k: v for k, v in q.items() if k not in _PER_POSITION}
                    key = (f["code"], repr(sorted(rest.items())))
                    if key not in items:
                        items[key] = {"code": f["code"], "params": {**rest, "position": []}}
                    if "position" in q:
                        items[key]["params"]["position"].append(q["position"])
        out.append((e, list(items.values())))
    return out


def folded(entry: dict, lang: str) -> str:
    """An entry of a change point's items (:func:`grouped`) in its short form in ``lang``."""
    cat = catalogue(lang if lang in LANGS else "en")
    template = cat["folded"].get(entry["code"]) or catalogue("en")["folded"][entry["code"]]
    try:
        return _Formatter(cat["terms"], lang if lang in LANGS else "en").format(template, **(entry.get("params") or {}))
    except (KeyError, IndexError, TypeError, ValueError, AttributeError):
        return localize(entry, lang)


def render_grouped(section: dict, lang: str) -> list[tuple[str, list[str]]]:
    """The warnings of a results dict in ``lang`` as the terminal and the report list them: each
    ``(text, items)``, a change point's warnings one head with its items (:func:`grouped`);
    results written before messages existed: their English ``warnings``, no items."""
    entries = section.get("messages")
    if entries is None:
        return [(str(w), []) for w in section.get("warnings") or []]
    if not any(e.get("code") == HEAD for e in entries):      # nothing to group: no catalogue read for it
        return [(str(e.get("text", "")) if lang == "en" else localize(e, lang), []) for e in entries]
    return [(localize(e, lang), [folded(f, lang) for f in items]) for e, items in grouped(entries)]


__all__ = ["LANGS", "Message", "as_dict", "as_message", "catalogue", "in_lang", "localize", "render", "render_grouped", "render_list"]
