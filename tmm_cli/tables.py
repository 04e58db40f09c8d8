"""CSV in and out, one way for the whole tool.

* :func:`csv_text` writes every CSV tmm produces (summary, check, forms, report tables):
  a text cell that a spreadsheet would take for a formula (it begins with ``=``, ``+``,
  ``-``, ``@``, a tab or a carriage return) gets a leading ``'``; numbers stay numbers,
  every float exact (its shortest repr, or the same digits spelt as results.json spells
  them in the report's tables).
* :func:`round_sig` rounds numbers to significant digits for compact embedded data
  (the report's mechanism in motion).
* :func:`read_table` reads a table an instructor typed or exported: ``,`` or ``;``
  separators (detected from the header line), optional quotes, UTF-8 with or without a
  BOM; the Russian and Ukrainian words for variant, student and group (spellings.yaml)
  head the columns ``variant``, ``student``, ``group``; :func:`cell_value` reads a cell as tmm_cli.numbers reads a
  number (``0,12``, ``-1,5``, ``1 234,5``, ``−1,5``).
"""
from __future__ import annotations

import csv
import io
import math
import os
import re
from pathlib import Path

from .messages import Message

FORMULA_START = ("=", "+", "-", "@", "\t", "\r")
_NUMBER = re.compile(r"^[-+]?(\d+([.,]\d*)?|[.,]\d+)([eE][-+]?\d+)?$")


def safe_cell(v):
    """A CSV cell that no spreadsheet evaluates: numbers (and number-like text) as they
    are, None empty, other text beginning with a formula character prefixed with ';
    a control character of a text replaced (tmm_cli.limits.printable)."""
    if v is None:
        return ""
    if isinstance(v, bool):
        return str(v).lower()
    if isinstance(v, int):
        return v
    if isinstance(v, float):
        # float's own repr: a numpy float64 (a float) would give np.float64(...) in numpy 2
        return float.__repr__(v) if math.isfinite(v) else ""
    s = str(v)
    if not s.isprintable():             # no NUL or control character written raw
        from .limits import printable
        s = printable(s)
    if s.startswith(FORMULA_START) and not _NUMBER.match(s.strip()):
        return "'" + s
    return s


# the text of a finite float in a CSV: its shortest repr (``0.1``, ``30.0``, ``1e-05``), or
# the same shortest digits as results.json spells them (orjson: ``0.00001``, ``2.5e-7``,
# ``1e+16``), whole tables of numbers at once: ~4x as fast to make, for the long
# per-position tables beside the report. Either reads back as the very same float (the
# sign of -0.0 and subnormals included); NaN and inf are written as an empty cell either way
SHORTEST, AS_JSON = "%r", "json"


def csv_text(header: list[str], rows, floats: str = SHORTEST) -> str:
    """A CSV (comma, UTF-8, full float precision) of ``rows`` (lists, or dicts keyed by
    the header); every cell through :func:`safe_cell`, the header too, but a finite float
    written as ``floats`` gives it (:data:`SHORTEST` or :data:`AS_JSON`)."""
    if floats not in (SHORTEST, AS_JSON):
        raise ValueError(f"floats: {floats!r}")
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow([safe_cell(h) for h in header])
    if floats == AS_JSON:
        _json_rows(w, buf, [tuple(r.get(h) for h in header) if isinstance(r, dict) else r for r in rows])
        return buf.getvalue()
    lines: list[str] = []
    formats: dict[tuple, bool] = {}
    for r in rows:
        vals = [r.get(h) for h in header] if isinstance(r, dict) else r
        if type(vals) is not tuple:
            vals = tuple(vals)
        # the long per-position tables are all numbers: a row of floats, ints and None
        # (empty cells) is its cells' reprs joined, None's cut out after (what the writer
        # gives: str of an int, nothing to quote), where the pattern of cell types allows
        # it (decided once per pattern); a non-finite float there writes nan or inf, the
        # only letter such a line can hold: the writer then
        kinds = tuple(map(type, vals))
        fast = formats.get(kinds)
        if fast is None:
            fast = formats[kinds] = _numbers_only(kinds)
        if fast:
            line = ",".join(map(repr, vals)).replace("None", "")
            if "n" not in line:
                lines.append(line)
                continue
        if lines:
            buf.write("\n".join(lines) + "\n")
            lines.clear()
        w.writerow([repr(float(v)) if isinstance(v, float) and v - v == 0 else safe_cell(v) for v in vals])
    if lines:
        buf.write("\n".join(lines) + "\n")
    return buf.getvalue()


CSV_STYLES = ("plain", "excel-ru")
_DOT_NUMBER = re.compile(r"^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$")


def csv_styled(text: str, style: str = "plain") -> str:
    """A CSV as ``style`` wants it: ``plain`` as written (`,`, decimal points, no BOM);
    ``excel-ru`` as a Russian or Ukrainian Excel opens it into columns: `;`, decimal commas
    in the number cells, a UTF-8 BOM."""
    if style == "plain":
        return text
    buf = io.StringIO()
    w = csv.writer(buf, delimiter=";", lineterminator="\n")
    for cells in csv.reader(io.StringIO(text, newline="")):
        w.writerow([c.replace(".", ",") if _DOT_NUMBER.match(c) else c for c in cells])
    return "\ufeff" + buf.getvalue()


_NONE = type(None)


def _numbers_only(kinds: tuple) -> bool:
    """Whether a row whose cells are of the types ``kinds`` is written as its cells'
    reprs joined: floats, ints and None only, but not a row of one empty cell (the writer
    quotes it: ``""``)."""
    return kinds != (_NONE,) and all(k is float or k is int or k is _NONE for k in kinds)


def _json_rows(w, buf, rows: list) -> None:
    """The rows in :data:`AS_JSON`'s spelling, into ``buf`` (the header written): a table
    of plain numbers, None and bools is one orjson text of the rows, its brackets turned
    into line breaks and ``null`` cut to an empty cell (JSON's ``true``/``false`` are
    safe_cell's text); a table holding anything else (text, numpy scalars, ints beyond 64
    bits, an empty row or a row of one empty cell, which the writer writes as ``""``)
    goes row by row, such rows through the writer."""
    import orjson
    if rows:
        try:
            text = orjson.dumps(rows)
        except orjson.JSONEncodeError:
            text = None
        if text is not None and _plain(text, len(rows)):
            buf.write(text[2:-2].replace(b"],[", b"\n").replace(b"null", b"").decode() + "\n")
            return
    for r in rows:
        try:
            text = orjson.dumps([r])
        except orjson.JSONEncodeError:
            text = None
        if text is not None and _plain(text, 1):
            buf.write(text[2:-2].replace(b"null", b"").decode() + "\n")
        else:
            w.writerow([orjson.dumps(float(v)).decode() if isinstance(v, float) and v - v == 0 else safe_cell(v)
                        for v in r])


def _plain(text: bytes, n: int) -> bool:
    """Whether ``text``, orjson's text of ``n`` rows, holds plain cells only: no string,
    no nested list or mapping, no empty row and no row of one empty cell."""
    return (b'"' not in text and b"{" not in text and b"[]" not in text and b"[null]" not in text
            and text.count(b"[") == n + 1)


def cell_value(text: str):
    """A table cell: an int or float when it is a number as tmm_cli.numbers reads one
    (decimal comma, thousands grouped by spaces, Unicode minus: ``0,12``, ``1 234,5``,
    ``−1,5``), else the stripped text ('' for an empty cell; a fraction or a number with a
    unit stays text, read by the field it goes to)."""
    s = text.strip()
    if not s or "/" in s or not (s[0] in "+-.,\u2212" or "0" <= s[0] <= "9"):
        return s
    from .numbers import GROUP, read
    try:
        r = read(s)
    except ValueError:
        return s
    if r.unit or not math.isfinite(r.value):
        return s
    if r.integral:
        return int(s.translate({ord(c): None for c in GROUP}).replace("\u2212", "-"))
    return r.value


class TableError(ValueError):
    """A table that cannot be read at all (line number and reason)."""

    def __init__(self, file: str, line: int | None, message: str):
        self.file, self.line, self.message = file, line, message
        super().__init__(f"{file}:{line}: {message}" if line else f"{file}: {message}")


def read_table(path: str | Path) -> tuple[list[str], list[tuple[int, dict[str, str], str | None]]]:
    """(header, rows): each row its line number in the file (header = line 1), a
    mapping column -> raw text, and the reason it is malformed (more cells than the
    header has columns) or None. Blank lines are skipped."""
    from .limits import MAX_TABLE_BYTES, MAX_TABLE_ROWS
    from .numbers import header_name
    path = Path(path)
    try:
        with open(path, "rb") as fh:
            raw = fh.read(MAX_TABLE_BYTES + 1)
            size = len(raw) if len(raw) <= MAX_TABLE_BYTES else max(len(raw), os.fstat(fh.fileno()).st_size)
    except OSError as exc:
        raise TableError(str(path), None, Message("input.table_unreadable", error=str(exc.strerror or exc))) from None
    if size > MAX_TABLE_BYTES:
        raise TableError(str(path), None, Message("input.table_large", size=size, limit=MAX_TABLE_BYTES))
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError:
        try:
            text = raw.decode("cp1251")       # a Russian Excel "CSV (comma delimited)"
        except UnicodeDecodeError:
            raise TableError(str(path), None, Message("input.table_not_text")) from None
    first = text.split("\n", 1)[0]
    # a ";" outside quotes in the header line means ";" (headers like "l, mm" hold commas)
    sep = ";" if ";" in re.sub(r'"[^"]*"', "", first) else ","
    reader = csv.reader(io.StringIO(text, newline=""), delimiter=sep)
    header: list[str] | None = None
    rows: list[tuple[int, dict[str, str], str | None]] = []
    prev = 0
    while True:
        try:
            cells = next(reader)
        except StopIteration:
            break
        except csv.Error as exc:        # a cell over the csv module's field limit (128 KiB)
            raise TableError(str(path), prev + 1,
                             Message("input.table_cell_long", limit=csv.field_size_limit())
                             if "field limit" in str(exc) else Message("input.table_unreadable", error=str(exc))) \
                from None
        start, prev = prev + 1, reader.line_num
        if not any(c.strip() for c in cells):
            continue
        if header is None:
            header = [header_name(c) for c in cells]     # the Russian 'variant' is `variant`
            if start != 1:
                raise TableError(str(path), start, Message("input.table_header_first"))
            continue
        if len(rows) == MAX_TABLE_ROWS:
            raise TableError(str(path), start, Message("input.table_rows_many", limit=MAX_TABLE_ROWS))
        bad = None
        if len(cells) > len(header):
            bad = Message("input.table_malformed_row", cells=len(cells), columns=len(header))
        rows.append((start, {h: (cells[i] if i < len(cells) else "") for i, h in enumerate(header)}, bad))
    if header is None:
        raise TableError(str(path), None, Message("input.table_empty"))
    return header, rows


def round_sig(values, digits: int = 7) -> list:
    """Each value rounded to ``digits`` significant digits (a plain float; 0 as 0);
    NaN, inf and None -> None: the floats that "%.6e" (digits - 1) and float() give.  A
    long list or array (>= 48 values) by numpy's arithmetic (_round_sig_vector), else the
    values written "%.6e" all at once (one formatting and one split, not one call per
    value), the exceptions put right after."""
    spec = f"%.{digits - 1}e"
    if isinstance(values, (list, tuple)):
        vals = values
        many = len(vals) >= _VECTOR_MIN
    else:                           # an array: numbers of a real dtype go to numpy as they are
        kind = getattr(getattr(values, "dtype", None), "kind", "")
        many = kind in ("f", "i", "u") and values.size >= _VECTOR_MIN
        vals = values.ravel() if many else _flat(values)
    if many and 1 <= digits <= _VECTOR_DIGITS:
        out = _round_sig_vector(vals, digits, spec)
        if out is not None:
            return out
        vals = _flat(vals)
    try:
        text = ((spec + " ") * len(vals)) % tuple(vals)
    except TypeError:               # a None (or a value "%e" does not take): one by one
        return _round_sig_each(vals, spec)
    out = list(map(float, text.split()))
    # nan or inf, or a zero, or a value rounded up beyond the largest float (inf too)
    if "n" in text or f"{0.0:{spec[1:]}} " in text or "e+308" in text:
        fin = math.isfinite
        for i, w in enumerate(out):
            if w == 0.0:
                out[i] = 0
            elif not fin(w):
                out[i] = None
    return out


# round_sig of a long list by numpy: the same floats as "%e" and float() give them, ~1/8
# of the time of the formatting (the explorable report's grid: ~0.1 s a report)
_VECTOR_MIN, _VECTOR_DIGITS = 48, 12


def _round_sig_vector(vals, digits: int, spec: str) -> list | None:
    """round_sig by arithmetic: each finite nonzero v scaled by an exact power of ten
    10**k (k = digits - 1 - its decimal exponent: one rounding, relative error <= 2**-53),
    rounded to the integer m (half to even, as "%e" rounds a tie), and m / 10**k (or
    m * 10**-k): IEEE division and multiplication round correctly, and m and 10**|k|
    (|k| <= 22) are exact, so that is the float nearest to m * 10**-k, the value of the
    "%e" text, which float() reads correctly rounded too.  Where the scaled value lies
    within 4 ulp of a half-integer (m may be off) or within 1 of the ends of the digits'
    range (the decimal exponent may be off), and for 0, NaN, inf and |k| > 22, each
    value is formatted as before (_round_sig_each).  None: not numbers numpy takes (the
    caller formats them as before)."""
    import numpy as np
    try:
        a = np.array(vals, dtype=float)
    except (TypeError, ValueError, OverflowError):
        return None
    if a.ndim != 1:
        return None
    lo, hi = 10.0 ** (digits - 1), 10.0 ** digits
    with np.errstate(all="ignore"):
        mag = np.abs(a)
        k = (digits - 1) - np.floor(np.log10(mag))       # -inf/nan for 0, inf, nan
        ok = np.abs(k) <= 22
        k = np.where(ok, k, 0.0).astype(np.int64)
        p = np.array(_POW10)[np.abs(k)]
        up = k >= 0
        y = np.where(up, a * p, a / p)
        m = np.rint(y)
        ay = np.abs(y)
        ok &= (ay >= lo + 1) & (ay < hi - 1) & (0.5 - np.abs(y - m) > hi * 2.0 ** -50)
        r = np.where(up, m / p, m * p)
    out = r.tolist()
    if not ok.all():
        for i in np.flatnonzero(~ok & (a != 0) & np.isfinite(a)).tolist():
            out[i] = _round_sig_each((a[i],), spec)[0]       # as "%e" and float() give it
        for i in np.flatnonzero(a == 0).tolist():
            out[i] = 0
        for i in np.flatnonzero(~np.isfinite(a)).tolist():
            out[i] = None
    return out


_POW10 = [float(10 ** i) for i in range(23)]     # exact doubles (5**22 < 2**53)


def _round_sig_each(vals, spec: str) -> list:
    fin = math.isfinite
    return [None if v is None or not fin(w := float(spec % float(v))) else (0 if w == 0.0 else w)
            for v in vals]


def _flat(values):
    """The values of an array (any shape) in order, without importing numpy here."""
    return values.ravel().tolist() if hasattr(values, "ravel") else list(values)
