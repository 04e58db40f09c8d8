"""The limits of what tmm reads, in one place (docs/limits.md lists them for users).

Each is checked when the input is read or validated, so an input past one is an invalid
input (exit 2, the file, line and field named) within a second, never minutes of work, a
MemoryError or a crash of the report's engine. The reader's own limits (the task file's
size, nesting and node count) are in :mod:`tmm_cli.yamlload`.
"""
from __future__ import annotations

import unicodedata

# -- a task
MAX_POSITIONS = 3600          # positions.count + len(positions.extra): every position is computed and drawn
MAX_EXTRA_POSITIONS = 100     # positions.extra: each extra position is drawn on its own (its plans)
MAX_EXTRA_POINTS = 100        # the links' own extra points, all links together (a coupler curve needs a few)
MAX_FORCES = 200              # loads.forces
MAX_TEXT = 1000               # characters of any text of a task: title, names, student, a value
MAX_COMBINING = 30            # combining marks in a row (Unicode's stream-safe limit, UAX #15)

# -- tables (answers CSV, variants table)
MAX_TABLE_BYTES = 16 << 20    # 16 MiB
MAX_TABLE_ROWS = 10_000       # rows of a table: a course's students or variants, many times over

def bad_character(text: str, free: bool = False) -> str | None:
    """The first character a text field may not hold, as U+XXXX, or None: control
    characters (U+0000-U+001F, but tab and newline in free text; U+007F-U+009F), the
    noncharacters U+FFFE and U+FFFF, and lone surrogates (a text that is not Unicode)."""
    if text.isprintable():                      # the common case: no character of those
        return None
    for ch in text:
        o = ord(ch)
        if _forbidden(o, free):
            return f"U+{o:04X}"
    return None


def _forbidden(o: int, free: bool) -> bool:
    return (o < 0x20 and not (free and o in (9, 10))) or 0x7F <= o <= 0x9F or o in (0xFFFE, 0xFFFF) \
        or 0xD800 <= o <= 0xDFFF


def printable(text: str) -> str:
    """``text`` with each character :func:`bad_character` refuses (tab, newline and
    carriage return kept: a CSV quotes them) replaced by U+FFFD: a student's name from a
    table, written into a CSV or a page, never carries a NUL or a control character raw."""
    if text.isprintable():
        return text
    return "".join("\ufffd" if c != "\r" and _forbidden(ord(c), True) else c for c in text)


def combining_run(text: str) -> int:
    """The longest run of combining marks (Unicode combining class > 0) in ``text``."""
    if text.isascii():
        return 0
    best = run = 0
    comb = unicodedata.combining
    for ch in text:
        if comb(ch):
            run += 1
            if run > best:
                best = run
        else:
            run = 0
    return best


def text_problem(text: str, free: bool = False):
    """A coded Message saying what in ``text`` breaks the rule for every text field (a
    forbidden character, more than MAX_TEXT characters, more than MAX_COMBINING combining
    marks in a row), or None."""
    from .messages import Message
    bad = bad_character(text, free)
    if bad is not None:
        return Message("input.text_control", char=bad)
    if len(text) > MAX_TEXT:
        return Message("input.text_long", n=len(text), limit=MAX_TEXT)
    if combining_run(text) > MAX_COMBINING:
        return Message("input.text_combining", limit=MAX_COMBINING)
    return None


# free-text fields: the first key of the path (and under `student`, every field)
_FREE = ("title", "student")


def shown(text: str, width: int = 60) -> str:
    """``text`` safe to print in a message: a character that is not printable as its
    escape (\\u0001), a long text cut at ``width`` characters (with an ellipsis)."""
    if len(text) > width:
        text = text[:width] + "\u2026"
    if text.isprintable():
        return text
    return "".join(c if c.isprintable() else f"\\u{ord(c):04x}" for c in text)


def text_issues(data, marks: dict) -> list[tuple]:
    """(field, line, column, message) of every key and text value of the task ``data``
    (as read from YAML) that breaks :func:`text_problem`'s rule: one walk, linear in the
    size of the data."""
    from .errors import dotted
    out: list[tuple] = []

    def where(path):
        p = path
        while p:
            if p in marks:
                return marks[p]
            p = p[:-1]
        return marks.get((), (None, None))

    stack = [((), data)]
    while stack:
        path, v = stack.pop()
        if isinstance(v, str):
            msg = text_problem(v, free=bool(path) and path[0] in _FREE)
            if msg is not None:
                out.append((dotted(tuple(shown(p) if isinstance(p, str) else p for p in path)), *where(path), msg))
        elif isinstance(v, dict):
            for k, sub in v.items():
                if isinstance(k, str):
                    msg = text_problem(k)
                    if msg is not None:
                        out.append((dotted(path + (shown(k),)), *where(path + (k,)), msg))
                stack.append((path + (k,), sub))
        elif isinstance(v, list):
            stack.extend((path + (i,), sub) for i, sub in enumerate(v))
    out.sort(key=lambda t: (t[1] or 0, t[2] or 0))
    return out


# Cyrillic letters drawn as Latin ones: a name typed on the other keyboard layout (the Cyrillic
# O, U+041E, for the Latin O) looks the same and is another name
_LOOKALIKE = {0x0410: "A", 0x0412: "B", 0x0415: "E", 0x041A: "K", 0x041C: "M", 0x041D: "H", 0x041E: "O",
              0x0420: "P", 0x0421: "C", 0x0422: "T", 0x0425: "X", 0x0430: "a", 0x0435: "e", 0x043E: "o",
              0x0440: "p", 0x0441: "c", 0x0443: "y", 0x0445: "x", 0x0406: "I", 0x0456: "i"}
_TO_CYRILLIC = {ord(v): chr(k) for k, v in _LOOKALIKE.items()}


def lookalike(a: str, b: str) -> bool:
    """Two different names that read the same: one typed with Cyrillic letters drawn as Latin
    ones where the other has the Latin letters (O1 with the Cyrillic O, U+041E, and O1)."""
    return a != b and a.translate(_LOOKALIKE) == b.translate(_LOOKALIKE)


def in_cyrillic(text: str) -> str | None:
    """``text`` with its Latin letters drawn as Cyrillic ones written in Cyrillic (a unit typed on
    the other layout: the Latin H for the newton's Cyrillic EN, U+041D); None where it has none."""
    cyr = text.translate(_TO_CYRILLIC)
    return cyr if cyr != text else None


def script_note(a: str, b: str):
    """The note on two :func:`lookalike` names: which one holds the Cyrillic letters, and which."""
    from .messages import Message
    cyr, lat = (a, b) if any(ord(ch) in _LOOKALIKE for ch in a) else (b, a)
    letters = "".join(dict.fromkeys(ch for ch in cyr if ord(ch) in _LOOKALIKE))
    return Message("input.script_note", cyr=cyr, lat=lat, letters=letters)
