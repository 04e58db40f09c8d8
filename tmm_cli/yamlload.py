"""YAML reading with YAML 1.2 booleans and a map of field paths to line numbers.

PyYAML's default resolver follows YAML 1.1, where ``on``, ``off``, ``yes``, ``no``
become booleans (so the key ``on:`` of a force would turn into ``True``). The task
file uses YAML 1.2 booleans: only ``true``/``false`` (any case form the 1.2 core
schema allows). Sexagesimal numbers (``1:30``) and other 1.1-only forms stay strings.
Duplicate keys are errors.
"""
from __future__ import annotations

import re
from pathlib import Path
from typing import Any

import yaml

from .errors import TaskError


class _Loader12(yaml.SafeLoader):
    """SafeLoader with the YAML 1.2 core-schema resolvers for bool, int and float."""


# drop every implicit resolver for bool/int/float and install the 1.2 core ones
_Loader12.yaml_implicit_resolvers = {
    k: [(tag, rx) for tag, rx in v
        if tag not in ("tag:yaml.org,2002:bool", "tag:yaml.org,2002:int", "tag:yaml.org,2002:float")]
    for k, v in yaml.SafeLoader.yaml_implicit_resolvers.items()
}
_Loader12.add_implicit_resolver(
    "tag:yaml.org,2002:bool", re.compile(r"^(?:true|True|TRUE|false|False|FALSE)$"), list("tTfF"))
_Loader12.add_implicit_resolver(
    "tag:yaml.org,2002:int", re.compile(r"^(?:[-+]?[0-9]+|0o[0-7]+|0x[0-9a-fA-F]+)$"),
    list("-+0123456789"))
_Loader12.add_implicit_resolver(
    "tag:yaml.org,2002:float",
    re.compile(r"^(?:[-+]?(?:\.[0-9]+|[0-9]+(?:\.[0-9]*)?)(?:[eE][-+]?[0-9]+)?"
               r"|[-+]?\.(?:inf|Inf|INF)|\.(?:nan|NaN|NAN))$"),
    list("-+.0123456789"))


def _construct_int(loader, node):
    text = loader.construct_scalar(node)
    if text.startswith("0o"):
        return int(text[2:], 8)
    if text.startswith("0x"):
        return int(text[2:], 16)
    return int(text)


_Loader12.add_constructor("tag:yaml.org,2002:int", _construct_int)

Path_ = tuple  # a field path: tuple of str keys / int indices


def _walk(node: yaml.Node, path: tuple, marks: dict, file: str | None) -> None:
    marks[path] = (node.start_mark.line + 1, node.start_mark.column + 1)
    if isinstance(node, yaml.MappingNode):
        seen: dict[Any, int] = {}
        for knode, vnode in node.value:
            key = knode.value if isinstance(knode, yaml.ScalarNode) else str(knode.value)
            if key in seen:
                raise TaskError("duplicate key", file=file, issues=[(
                    ".".join(map(str, path + (key,))), knode.start_mark.line + 1,
                    knode.start_mark.column + 1,
                    f"duplicate key '{key}' (first given on line {seen[key]})")])
            seen[key] = knode.start_mark.line + 1
            marks[path + (key,)] = (knode.start_mark.line + 1, knode.start_mark.column + 1)
            _walk(vnode, path + (key,), marks, file)
            # the key's line is more useful than the value's for messages
            marks[path + (key,)] = (knode.start_mark.line + 1, knode.start_mark.column + 1)
    elif isinstance(node, yaml.SequenceNode):
        for i, item in enumerate(node.value):
            _walk(item, path + (i,), marks, file)


def _tab_indented_line(text: str) -> int | None:
    """The first line (1-based) whose indentation holds a tab, or None."""
    for i, line in enumerate(text.splitlines(), 1):
        indent = line[:len(line) - len(line.lstrip(" \t"))]
        if "\t" in indent and line.strip():
            return i
    return None


_DECIMAL_COMMA = re.compile(r"(?<![\w.,])(-?\d+),(\d+)(?![\d.])")


def decimal_comma_hint(line: str) -> str | None:
    """'use a decimal point: 0.38' when a line (outside its comment) holds a number
    written with a decimal comma such as ``0,38``, else None."""
    code = line.split("#", 1)[0]
    m = _DECIMAL_COMMA.search(code)
    if m is None:
        return None
    if ("[" in code or "{" in code) and not re.search(r",\s", code):
        return None     # a compact list such as [12,42,7]: commas without spaces throughout
    return (f"use a decimal point: {m.group(1)}.{m.group(2)} (YAML reads '{m.group(0)}' as two "
            f"numbers or as text)")


def load_yaml(source: str | Path, *, text: str | None = None) -> tuple[Any, dict]:
    """Read a YAML file. Returns ``(data, marks)`` where ``marks`` maps a field path
    (tuple of keys and indices) to ``(line, column)``, 1-based."""
    file = str(source)
    if text is None:
        try:
            text = Path(source).read_text(encoding="utf-8")
        except FileNotFoundError:
            raise TaskError("file not found", file=file) from None
        except UnicodeDecodeError as exc:
            raise TaskError(f"not a UTF-8 text file ({exc.reason})", file=file) from None
        except OSError as exc:
            raise TaskError(f"cannot read: {exc.strerror}", file=file) from None
    try:
        loader = _Loader12(text)
        try:
            node = loader.get_single_node()
            marks: dict = {}
            if node is not None:
                _walk(node, (), marks, file)
            data = loader.construct_document(node) if node is not None else None
        finally:
            loader.dispose()
    except yaml.MarkedYAMLError as exc:
        tab = _tab_indented_line(text)
        if tab is not None:
            raise TaskError("YAML syntax error", file=file, issues=[(
                "", tab, 1, "use spaces for indentation: this line is indented with a tab, "
                            "which YAML does not allow")]) from None
        mark = exc.problem_mark or exc.context_mark
        line = mark.line + 1 if mark else None
        col = mark.column + 1 if mark else None
        raise TaskError("YAML syntax error", file=file,
                        issues=[("", line, col, f"YAML syntax error: {exc.problem or exc.context}")]) from None
    except yaml.reader.ReaderError as exc:
        # a character YAML does not allow (a NUL, a control character): the reader gives
        # its offset in the text, not a mark, so count the lines up to it
        pos = max(0, min(int(exc.position), len(text)))
        line = text.count("\n", 0, pos) + 1
        col = pos - (text.rfind("\n", 0, pos) + 1) + 1
        ch = exc.character
        code = ord(ch) if isinstance(ch, str) else int(ch)
        what = f"#x{code:04x}"
        raise TaskError("YAML error", file=file, issues=[(
            "", line, col, f"YAML error: character {what} is not allowed in a YAML file ({exc.reason})")]) from None
    except yaml.YAMLError as exc:
        raise TaskError("YAML error", file=file, issues=[("", 1, 1, f"YAML error: {exc}")]) from None
    return data, marks
