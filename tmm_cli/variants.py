"""`tmm variants TEMPLATE.yaml TABLE.csv --out DIR`: one validated task per table row.

Placeholders: a string value of the template may hold ``{column}``. A value that is
exactly one placeholder becomes the cell (a number when the cell is numeric, else its
text; with a unit in the column header ``name, unit`` or ``name [unit]`` the string
"cell unit"); a placeholder inside text is replaced by the cell's text; ``{{`` and
``}}`` are literal braces.
"""
from __future__ import annotations

import re
from pathlib import Path
from typing import Any

from .errors import TaskError, dotted
from .messages import Message

_PLACE = re.compile(r"\{\{|\}\}|\{([^{}]*)\}")
_HEADER_UNIT = re.compile(r"^\s*(?P<name>[^,\[\]]+?)\s*(?:,\s*(?P<u1>.+?)|\[(?P<u2>[^\]]+)\])\s*$")


def parse_header(header: list[str]) -> dict[str, tuple[str, str]]:
    """column name -> (raw header, unit or '')."""
    cols = {}
    for h in header:
        m = _HEADER_UNIT.match(h)
        if m:
            cols[m.group("name").strip()] = (h, (m.group("u1") or m.group("u2") or "").strip())
        else:
            cols[h.strip()] = (h, "")
    return cols


def placeholders(data, path=()) -> list[tuple[tuple, str]]:
    """(field path, column name) of every placeholder in the template's string values."""
    out = []
    if isinstance(data, dict):
        for k, v in data.items():
            out += placeholders(v, path + (k,))
    elif isinstance(data, list):
        for i, v in enumerate(data):
            out += placeholders(v, path + (i,))
    elif isinstance(data, str):
        for m in _PLACE.finditer(data):
            if m.group(1) is not None:
                out.append((path, m.group(1).strip()))
    return out


def substitute(data, cells: dict[str, Any], units: dict[str, str]):
    """The template with the row's cells in place of its placeholders."""
    if isinstance(data, dict):
        return {k: substitute(v, cells, units) for k, v in data.items()}
    if isinstance(data, list):
        return [substitute(v, cells, units) for v in data]
    if not isinstance(data, str):
        return data
    m = _PLACE.fullmatch(data.strip())
    if m and m.group(1) is not None:
        name = m.group(1).strip()
        v = cells[name]
        if units.get(name):
            return f"{_text(v)} {units[name]}"
        return v
    return _PLACE.sub(lambda mm: "{" if mm.group(0) == "{{" else "}" if mm.group(0) == "}}"
                      else _text(cells[mm.group(1).strip()]), data)


def _text(v) -> str:
    if isinstance(v, float):
        return repr(v)
    return str(v)


def file_stem(raw: str) -> str:
    """The task file's name (without .yaml) for a variant: a name every system takes
    (:func:`tmm_cli.safepath.safe_name`: variant "CON" -> "_CON", "7." -> "7")."""
    from .safepath import safe_name
    return safe_name(raw, "variant")


def make_variants(template: Path, table: Path, out: Path) -> tuple[int, list[dict], list[str]]:
    """Write the tasks. Returns (exit code, variants.csv rows, stderr messages). Raises
    TaskError for what stops everything (a placeholder with no column, no `variant`
    column, a duplicate variant, a column's unit that is no unit, an unreadable template
    or table)."""
    import yaml

    from .io import atomic_write
    from .orchestrate import classify, prepare
    from .tables import TableError, cell_value, csv_text, read_table
    from .yamlload import load_yaml

    data, marks = load_yaml(template)
    if not isinstance(data, dict):
        raise TaskError("a template is a task file (a YAML mapping)", file=str(template))
    try:
        header, rows = read_table(table)
    except TableError as exc:
        raise TaskError(exc.message, file=str(table),
                        issues=[("", exc.line, None, exc.message)] if exc.line else None) from None
    cols = parse_header(header)
    if not rows:        # wrote 0 of 0 variants, exit 0: the instructor's table lost its rows
        raise TaskError("the table has a header line but no rows of variants", file=str(table))
    if "variant" not in cols:
        raise TaskError(f"the table needs a `variant` column (columns: {', '.join(cols)})", file=str(table))
    issues = []
    for path, name in placeholders(data):
        if name not in cols:
            line, col = marks.get(path, (None, None))
            issues.append((dotted(path), line, col, f"placeholder {{{name}}} names no column of {table} "
                                                    f"(columns: {', '.join(cols)})"))
    if issues:
        raise TaskError("placeholder with no column", file=str(template), issues=issues)
    bad_units = [(h, 1, header.index(h) + 1, reason) for n, (h, u) in cols.items()
                 if u and n in {name for _, name in placeholders(data)} and (reason := _unit_problem(u))]
    if bad_units:       # else every row fails alike, one message a row
        raise TaskError("a column's unit is not a unit", file=str(table), issues=bad_units)
    seen: dict[str, int] = {}
    for line, row, _bad in rows:
        raw = row.get(cols["variant"][0], "").strip()
        key = str(cell_value(raw))
        if key in seen:
            raise TaskError("duplicate variant", file=str(table),
                            issues=[("variant", line, None, f"duplicate variant {raw}: already on line {seen[key]}")])
        seen[key] = line
    units = {n: u for n, (_, u) in cols.items()}
    used = [n for n in dict.fromkeys(name for _, name in placeholders(data))]
    report, messages, code = [], [], 0
    # the student and group a row gives, written as the task's `student` where the template has
    # none of its own (its name and group in the title block, the report, the forms)
    who = [n for n in ("student", "group") if n in cols and n not in used] if "student" not in data else []
    unused = [n for n in cols if n != "variant" and n not in used and n not in who]
    if unused:      # a column the instructor meant to vary but no placeholder takes
        messages.append(Message("variants.unused_columns", table=str(table), columns=unused,
                                template=Path(template).name))
    from .safepath import UniqueNames
    names_used = UniqueNames()       # "a" and "A": one file on Windows and macOS
    from rich.console import Console

    from .batch import progress as progress_bar
    with progress_bar(Console(stderr=True), len(rows), "variants") as advance:
        for line, row, bad in rows:
            raw_v = row.get(cols["variant"][0], "").strip()
            name = names_used.take(file_stem(raw_v), sep="", suffix="_")
            target = Path(out) / f"{name}.yaml"
            status, msg = "written", ""
            try:
                if bad or raw_v == "":
                    raise _RowError(bad or Message("variants.empty_variant"))
                cells = {n: cell_value(row.get(h, "")) for n, (h, _) in cols.items()}
                empty = [n for n in used if cells[n] == ""]
                if empty:       # else '' or ' mm' reaches the field, a message about the field
                    raise _RowError(Message("variants.empty_cells", columns=empty))
                wordy = [n for n in used if units.get(n) and not isinstance(cells[n], (int, float))]
                if wordy:       # else 'abc mm' reaches the field: "'abc' is not a unit"
                    raise _RowError(Message("variants.not_numbers", cells=[
                        Message("variants.column_reason", column=cols[n][0], reason=_not_a_number(cells[n]))
                        for n in wordy]))
                task = substitute(data, cells, units)
                if "variant" not in data:       # after schema and title, as in a hand-written task
                    items = list(task.items())
                    at = sum(1 for k, _ in items[:2] if k in ("schema", "title"))
                    task = dict(items[:at] + [("variant", cells["variant"])] + items[at:])
                # as written: a group '0301' or a name '007' is no number ('cells' reads them so)
                named = {("name" if n == "student" else n): row.get(cols[n][0], "").strip() for n in who
                         if row.get(cols[n][0], "").strip()}
                if named:                       # after the variant
                    items = list(task.items())
                    at = [k for k, _ in items].index("variant") + 1 if "variant" in task else 0
                    task = dict(items[:at] + [("student", named)] + items[at:])
                text = (f"# generated by tmm variants from {Path(template).name} and {Path(table).name}, line {line}\n"
                        + yaml.safe_dump(task, sort_keys=False, allow_unicode=True, width=100))
                prepare(target, text=text)
                atomic_write(target, text)
            except BaseException as exc:
                if isinstance(exc, KeyboardInterrupt):
                    raise
                if isinstance(exc, _RowError):      # the row's own reason, coded (said in --lang)
                    why = exc.args[0] if isinstance(exc.args[0], Message) else Message("text", text=str(exc.args[0]))
                else:                               # a stage's, coded; the task's as written, its file stripped
                    from .batch import stage_failure_message
                    m, coded = classify(exc)[2], stage_failure_message(exc)
                    why = coded if coded is not None and str(coded) == m else Message("text", text=_strip_file(m, target))
                status, msg, code = "invalid", str(why), max(code, 2)
                _remove_generated(target)
                messages.append(Message("variants.row", where=f"{table}:{line}", variant=raw_v or "?", reason=why))
            report.append({"line": line, "variant": raw_v, "file": target.name if status == "written" else "",
                           "status": status, "message": msg})
            advance()
    atomic_write(Path(out) / "variants.csv", csv_text(["line", "variant", "file", "status", "message"], report))
    return code, report, messages


def _unit_problem(unit: str):
    """Why a column header's unit is none (its text is not written as units are, or names
    a unit tmm does not know), else None."""
    from .numbers import is_dimensionless, parse_unit, unit_expression
    try:
        is_dimensionless(unit_expression(parse_unit(unit)[0]))
    except ValueError as exc:
        return exc.args[0]
    return None


def _not_a_number(cell: str) -> Message:
    """Why a cell of a column with a unit is no number: the grammar's reason ('1,2,3': more
    than one decimal mark), else (a unit of its own, a fraction) that it is not a number."""
    from .numbers import read
    try:
        read(cell)
    except ValueError as exc:
        return exc.args[0] if isinstance(exc.args[0], Message) else Message("text", text=str(exc.args[0]))
    return Message("input.number_not_number", text=cell)


class _RowError(ValueError):
    """A table row that cannot make a task (malformed, no variant)."""


def _strip_file(msg: str, target: Path) -> str:
    """A message without the not-yet-written file's name in front of it."""
    return re.sub(r"(^|; )" + re.escape(str(target)) + r"(:\d+(:\d+)?)?: ", r"\1", msg.replace("\n", "; "))


def _remove_generated(target: Path) -> None:
    """A task this command wrote earlier for a row that is now invalid is removed (a file
    it did not write is left alone)."""
    try:
        with open(target, encoding="utf-8") as fh:
            first = fh.readline()
        if first.startswith("# generated by tmm variants") and target.is_file() and not target.is_symlink():
            target.unlink()
    except OSError:
        pass
