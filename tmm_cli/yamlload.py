"""YAML reading with YAML 1.2 booleans and a map of field paths to line numbers.

PyYAML's default resolver follows YAML 1.1, where ``on``, ``off``, ``yes``, ``no``
become booleans (so the key ``on:`` of a force would turn into ``True``). The task
file uses YAML 1.2 booleans: only ``true``/``false`` (any case form the 1.2 core
schema allows). Sexagesimal numbers (``1:30``) and other 1.1-only forms stay strings.
Duplicate keys are errors.

Limits on input (a task is a small hand-written file; anything far beyond is hostile or
broken and is refused as an invalid task, exit 2, with the line): the file must be a
regular file of at most :data:`MAX_BYTES`; mappings and lists nest at most
:data:`MAX_DEPTH` deep; the document holds at most :data:`MAX_NODES` nodes with
every alias (``*name``) counted as the nodes it brings in, and an alias may not refer to
the node that contains it; an integer must fit a float. The text may be UTF-8 (with or without a BOM)
or UTF-16/UTF-32 with a BOM.
"""
from __future__ import annotations

import codecs
import os
import re
import stat
from pathlib import Path
from typing import Any

import yaml

from .errors import TaskError, dotted
from .messages import Message


MAX_BYTES = 256 << 10        # 256 KiB: the largest course task is a few kB
MAX_DEPTH = 64               # nesting of mappings and lists (a task needs about 6)
MAX_NODES = 20_000           # values, keys, lists and mappings in all, aliases counted with their
                             # contents (a task has a few hundred; 3600 positions listed fit)


class _Refused(Exception):
    """A limit of the reader was passed at ``mark``: becomes a TaskError with the line."""

    def __init__(self, mark, message: str, field: tuple = ()):
        super().__init__(message)
        self.mark = mark
        self.message = message
        self.field = field


class _Loader12(yaml.SafeLoader):
    """SafeLoader with the YAML 1.2 core-schema resolvers for bool, int and float, and
    the limits above enforced while the node graph is composed (before anything is
    expanded, so an alias bomb costs nothing)."""

    def __init__(self, stream):
        super().__init__(stream)
        self._sizes: dict[int, int] = {}   # id(node) -> nodes it stands for, aliases expanded
        self._nodes = 0      # nodes of the document as aliases would expand it
        self._depth = 0
        self._path: list = []  # the field path of the node being composed (for messages)

    def _field(self, index) -> tuple:
        here = tuple(p for p in self._path if p is not None)
        if isinstance(index, yaml.ScalarNode):
            return here + (index.value,)
        return here + (index,) if isinstance(index, int) else here

    def compose_node(self, parent, index):
        if self.check_event(yaml.AliasEvent):
            event = self.peek_event()
            target = self.anchors.get(event.anchor)
            if target is not None:
                size = self._sizes.get(id(target))
                if size is None:  # anchored node still being composed: it contains itself
                    raise _Refused(event.start_mark,
                                   f"alias '*{event.anchor}' refers to the node that contains it "
                                   f"(a recursive alias)", self._field(index))
                self._nodes += size
                if self._nodes > MAX_NODES:
                    raise _Refused(event.start_mark,
                                   f"aliases bring the file to more than {MAX_NODES} values "
                                   f"(alias '*{event.anchor}' alone stands for {size}); "
                                   f"write the values out or use fewer aliases", self._field(index))
            return super().compose_node(parent, index)
        self._nodes += 1
        if self._nodes > MAX_NODES:
            raise _Refused(self.peek_event().start_mark,
                           f"more than {MAX_NODES} values (keys, numbers, lists...): a task has a few hundred",
                           self._field(index)[:6])
        self._depth += 1
        if self._depth > MAX_DEPTH:
            raise _Refused(self.peek_event().start_mark,
                           f"mappings and lists nest more than {MAX_DEPTH} deep", self._field(index)[:6])
        self._path.append(None if parent is None else
                          index.value if isinstance(index, yaml.ScalarNode) else
                          index if isinstance(index, int) else None)
        try:
            node = super().compose_node(parent, index)
        finally:
            self._depth -= 1
            self._path.pop()
        size = 1
        if isinstance(node, yaml.MappingNode):
            for k, v in node.value:
                size += self._sizes.get(id(k), 1) + self._sizes.get(id(v), 1)
        elif isinstance(node, yaml.SequenceNode):
            for v in node.value:
                size += self._sizes.get(id(v), 1)
        self._sizes[id(node)] = size
        return node


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
    digits = len(text.lstrip("+-"))
    try:
        if digits > 400:  # past any float (and past Python's 4300-digit conversion limit)
            raise OverflowError
        if text.startswith("0o"):
            value = int(text[2:], 8)
        elif text.startswith("0x"):
            value = int(text[2:], 16)
        else:
            value = int(text)
        float(value)
    except OverflowError:
        raise _Refused(node.start_mark, f"integer of {digits} digits is out of range "
                                        f"(a number must fit a float, |x| < 1.8e308)") from None
    return value


_Loader12.add_constructor("tag:yaml.org,2002:int", _construct_int)

Path_ = tuple  # a field path: tuple of str keys / int indices


def _key(loader: _Loader12, knode: yaml.Node) -> Any:
    """A mapping key as the task sees it: a scalar as constructed (``~`` is None, so it is
    found again when a message names the key ``None``), anything else as text."""
    if isinstance(knode, yaml.ScalarNode):
        k = loader.construct_object(knode)
        return k if isinstance(k, str) else str(k)
    return str(knode.value)


def _walk(node: yaml.Node, path: tuple, marks: dict, file: str | None, loader: _Loader12) -> None:
    marks[path] = (node.start_mark.line + 1, node.start_mark.column + 1)
    if isinstance(node, yaml.ScalarNode) and node.tag == "tag:yaml.org,2002:int":
        try:
            loader.construct_object(node)  # an integer out of range is named with its field
        except _Refused as exc:
            exc.field = path
            raise
    if isinstance(node, yaml.MappingNode):
        seen: dict[Any, int] = {}
        for knode, vnode in node.value:
            key = _key(loader, knode)
            if key in seen:
                raise TaskError("duplicate key", file=file, issues=[(
                    ".".join(map(str, path + (key,))), knode.start_mark.line + 1,
                    knode.start_mark.column + 1,
                    Message("input.duplicate_key", key=str(key), first=seen[key]))])
            seen[key] = knode.start_mark.line + 1
            marks[path + (key,)] = (knode.start_mark.line + 1, knode.start_mark.column + 1)
            _walk(vnode, path + (key,), marks, file, loader)
            # the key's line is more useful than the value's for messages
            marks[path + (key,)] = (knode.start_mark.line + 1, knode.start_mark.column + 1)
    elif isinstance(node, yaml.SequenceNode):
        for i, item in enumerate(node.value):
            _walk(item, path + (i,), marks, file, loader)


def _tab_indented_line(text: str) -> int | None:
    """The first line (1-based) whose indentation holds a tab, or None."""
    for i, line in enumerate(text.splitlines(), 1):
        indent = line[:len(line) - len(line.lstrip(" \t"))]
        if "\t" in indent and line.strip():
            return i
    return None


_DECIMAL_COMMA = re.compile(r"(?<![\w.,])(-?\d+),(\d+)(?![\d.])")


def _indent_hint(text: str, line: int | None) -> Message | str:
    """A hint when a syntax error's line is indented unlike the content line before it,
    which does not open a block (``positions:`` / `` count: 12`` / ``  zero: extreme``:
    YAML reports the third line, the second is misindented); else ''."""
    lines = text.splitlines()
    if not line or line > len(lines):
        return ""

    def content(i: int) -> bool:
        t = lines[i - 1].strip()
        return bool(t) and not t.startswith("#")

    def indent(i: int) -> int:
        return len(lines[i - 1]) - len(lines[i - 1].lstrip(" "))

    prev = line - 1
    while prev >= 1 and not content(prev):
        prev -= 1
    if prev < 1 or not content(line) or indent(line) == indent(prev):
        return ""
    if indent(line) > indent(prev) and lines[prev - 1].split("#")[0].rstrip().endswith((":", "-")):
        return ""
    return Message("input.indent_hint", prev=prev, line=line, col_prev=indent(prev) + 1, col_line=indent(line) + 1)


def _open_bracket_hint(exc, line: int | None) -> Message | str:
    """Where an unclosed '{' or '[' was opened, when YAML noticed it on a later line
    (``answers: {gears.aw: 1`` then a line: the error is reported on the next line); else ''."""
    ctx = exc.context_mark
    if ctx is None or line is None or ctx.line + 1 >= line or "flow" not in str(exc.context or ""):
        return ""
    return Message("input.flow_open_hint", line=ctx.line + 1, col=ctx.column + 1)


_PROBLEMS = (re.compile(r"^expected <block end>, but found '(.*)'$"),
             re.compile(r"^expected ',' or '(.)', but got '(.*)'$"),
             re.compile(r"^found character '(.)' that cannot start any token$"))


def _problem(text: str) -> Message | str:
    """The problem pyyaml names, coded where it is one a student meets (an indentation
    that ends a block, an unclosed bracket, a colon inside a value...); else as written."""
    coded = {"mapping values are not allowed here": Message("input.yaml_colon"),
             "found unexpected end of stream": Message("input.yaml_end"),
             "could not find expected ':'": Message("input.yaml_no_colon"),
             "did not find expected key": Message("input.yaml_no_key")}.get(text)
    block, flow, char = (rx.match(text) for rx in _PROBLEMS)
    if block:
        coded = Message("input.yaml_block_end", found=block.group(1))
    elif flow:
        coded = Message("input.yaml_flow", close=flow.group(1), got=flow.group(2))
    elif char:
        coded = Message("input.yaml_char", char=char.group(1))
    return coded if coded is not None and coded == text else text


def decimal_comma_hint(line: str) -> Message | None:
    """'use a decimal point: 0.38' when a line (outside its comment) holds a number
    written with a decimal comma such as ``0,38`` inside a flow collection (``[0,38, 0,12]``,
    ``{length: 0,15}``: YAML splits it at the comma), else None. A block scalar
    (``speed: 5,5 rad/s``) is read whole, decimal comma and all (tmm_cli.numbers)."""
    code = re.sub(r'"[^"]*"|\'[^\']*\'', "''", line.split("#", 1)[0])    # a quoted scalar is read whole
    m = _DECIMAL_COMMA.search(code)
    if m is None or ("[" not in code and "{" not in code):
        return None
    if not re.search(r",\s", code) and not re.search(r"[^\s{}\[\],:]+\s*:\s*$", code[:m.start()]):
        return None     # a compact list such as [12,42,7]: commas without spaces throughout (a
        # mapping's value, {rel: 0,1}, is split all the same: YAML reads it as rel: 0 and a key 1)
    return Message("input.decimal_comma", fixed=f"{m.group(1)}.{m.group(2)}", given=m.group(0))


def decimal_comma_key(line: str) -> str | None:
    """The key whose value is the number with a decimal comma on a line ``{mass: 2,1, J: 0,012}``
    (``mass``: YAML read the mapping as ``mass: 2``, ``1``, ...), None when that number is not
    a mapping's value (a list ``[0,38, 0,12]``) or the line has none."""
    hint = decimal_comma_hint(line)
    if hint is None:
        return None
    code = re.sub(r'"[^"]*"|\'[^\']*\'', "''", line.split("#", 1)[0])
    m = _DECIMAL_COMMA.search(code)
    key = re.search(r"([^\s{}\[\],:]+)\s*:\s*$", code[:m.start()])
    return key.group(1) if key else None


try:                                   # libyaml's parser, when PyYAML was built with it
    from yaml._yaml import CParser as _CParser
except ImportError:                    # pragma: no cover - PyYAML's wheels carry it
    _CParser = None

# the largest text libyaml reads here: its composer recurses once per level of nesting in C
# (a few hundred thousand levels overflow the stack), and a text of n characters nests at
# most n deep; anything longer, or anything the fast reading refuses, is read by _Loader12
FAST_MAX_CHARS = 8192
# where libyaml and PyYAML's Python reader part (found by comparing the two on mutated task
# files): a tab (libyaml takes it as a separator in more places), '?' (PyYAML refuses it
# inside a plain scalar in a flow collection), '!' (a bare '!' tag: '' against None), a
# byte-order mark inside the text, and a block scalar's header ('|' or '>' after a space or
# at a line's start: '>#' is a header and a comment to libyaml, an error to PyYAML)
_NOT_FAST = "\t?!\ufeff"
_BLOCK_SCALAR = re.compile(r"(?:^|\s)[|>]", re.M)

if _CParser is not None:
    class _CLoader12(_CParser, yaml.constructor.SafeConstructor, yaml.resolver.Resolver):
        """_Loader12's resolvers and constructors on libyaml's parser and composer (~15
        times faster than PyYAML's Python ones), without _Loader12's limits: see
        :func:`_load_fast`."""

        yaml_implicit_resolvers = _Loader12.yaml_implicit_resolvers
        yaml_constructors = _Loader12.yaml_constructors

        def __init__(self, stream):
            _CParser.__init__(self, stream)
            yaml.constructor.SafeConstructor.__init__(self)
            yaml.resolver.Resolver.__init__(self)


def _within_limits(root: yaml.Node) -> bool:
    """The node graph is a tree (no alias: no node reached twice) of at most MAX_NODES
    nodes nesting at most MAX_DEPTH deep: what _Loader12 accepts without a word."""
    seen: set[int] = set()
    stack = [(root, 1)]
    while stack:
        node, depth = stack.pop()
        if id(node) in seen or len(seen) >= MAX_NODES:
            return False
        seen.add(id(node))
        if isinstance(node, yaml.MappingNode):
            if depth >= MAX_DEPTH and node.value:
                return False
            for k, v in node.value:
                stack.append((k, depth + 1))
                stack.append((v, depth + 1))
        elif isinstance(node, yaml.SequenceNode):
            if depth >= MAX_DEPTH and node.value:
                return False
            stack.extend((v, depth + 1) for v in node.value)
    return True


def _load_fast(text: str, file: str) -> tuple[Any, dict] | None:
    """``(data, marks)`` read by libyaml, or None: no libyaml, a long text, an alias, a limit
    passed, or any error at all (then _Loader12 reads the text again and names the problem
    in its own words). What libyaml reads in full is the same node tree, with the same
    marks, that PyYAML's Python reader composes (tests/test_hostile_yaml.py compares them)."""
    if _CParser is None or len(text) > FAST_MAX_CHARS or any(c in text for c in _NOT_FAST) \
            or _BLOCK_SCALAR.search(text):
        return None
    try:
        loader = _CLoader12(text)
        try:
            node = loader.get_single_node()
            if node is None or not _within_limits(node):
                return None
            marks: dict = {}
            _walk(node, (), marks, file, loader)
            data = loader.construct_document(node)
        finally:
            loader.dispose()
    except Exception:  # noqa: BLE001 - whatever libyaml refuses, _Loader12 reads again and names
        return None
    return data, marks


def load_yaml(source: str | Path, *, text: str | None = None) -> tuple[Any, dict]:
    """Read a YAML file. Returns ``(data, marks)`` where ``marks`` maps a field path
    (tuple of keys and indices) to ``(line, column)``, 1-based."""
    file = str(source)
    if text is None:
        text = read_text(source)
    fast = _load_fast(text, file)
    if fast is not None:
        return fast
    try:
        loader = _Loader12(text)
        try:
            node = loader.get_single_node()
            marks: dict = {}
            if node is not None:
                _walk(node, (), marks, file, loader)
            data = loader.construct_document(node) if node is not None else None
        finally:
            loader.dispose()
    except _Refused as exc:
        raise TaskError("refused", file=file, issues=[(
            dotted(exc.field), exc.mark.line + 1, exc.mark.column + 1, exc.message)]) from None
    except yaml.MarkedYAMLError as exc:
        tab = _tab_indented_line(text)
        if tab is not None:
            raise TaskError("YAML syntax error", file=file, issues=[(
                "", tab, 1, Message("input.tab"))]) from None
        mark = exc.problem_mark or exc.context_mark
        line = mark.line + 1 if mark else None
        col = mark.column + 1 if mark else None
        if str(exc.problem or "").endswith("but found ','") and exc.problem_mark is not None:
            # a stray comma ('speed: 1450 rpm,' then a line; '{a: 1,, b: 2}'): the mark is on it
            raise TaskError("YAML syntax error", file=file, issues=[("", line, col, Message(
                "input.yaml_syntax", problem=Message("input.yaml_comma"), hint=Message("text", text="")))]) from None
        hint = _indent_hint(text, line) or _open_bracket_hint(exc, line) or Message("text", text="")
        raise TaskError("YAML syntax error", file=file,
                        issues=[("", line, col, Message("input.yaml_syntax", problem=_problem(str(exc.problem or exc.context)),
                                                        hint=hint))
                                ]) from None
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


_BOMS = ((codecs.BOM_UTF32_LE, "utf-32"), (codecs.BOM_UTF32_BE, "utf-32"),
         (codecs.BOM_UTF8, "utf-8-sig"), (codecs.BOM_UTF16_LE, "utf-16"), (codecs.BOM_UTF16_BE, "utf-16"))


def read_text(source: str | Path) -> str:
    """The text of a YAML file: a regular file (not a folder, FIFO or device, checked before
    it is opened) of at most MAX_BYTES, decoded from UTF-8 or, by its BOM, UTF-16/32."""
    file = str(source)
    try:
        st = os.stat(source)
    except FileNotFoundError:
        raise TaskError(Message("input.file_not_found"), file=file) from None
    except OSError as exc:
        raise TaskError(Message("input.cannot_read", reason=exc.strerror), file=file) from None
    if not stat.S_ISREG(st.st_mode):
        kind = ("folder" if stat.S_ISDIR(st.st_mode) else "fifo" if stat.S_ISFIFO(st.st_mode)
                else "device" if stat.S_ISCHR(st.st_mode) or stat.S_ISBLK(st.st_mode)
                else "socket" if stat.S_ISSOCK(st.st_mode) else "other")
        raise TaskError(Message("input.not_regular", kind=kind), file=file)
    try:
        # O_NONBLOCK: should the path be swapped for a FIFO after the check, open does not hang
        fd = os.open(source, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
        with os.fdopen(fd, "rb") as fh:
            if not stat.S_ISREG(os.fstat(fh.fileno()).st_mode):
                raise TaskError(Message("input.not_regular_now"), file=file)    # swapped after the check
            raw = fh.read(MAX_BYTES + 1)
    except OSError as exc:
        raise TaskError(Message("input.cannot_read", reason=exc.strerror), file=file) from None
    if len(raw) > MAX_BYTES:
        raise TaskError(Message("input.too_large", kib=MAX_BYTES // 1024), file=file)
    encoding = "utf-8"
    for bom, enc in _BOMS:
        if raw.startswith(bom):
            encoding = enc
            break
    try:
        text = raw.decode(encoding)
    except UnicodeDecodeError as exc:
        line = raw.count(b"\n", 0, exc.start) + 1
        name = "UTF-8" if encoding == "utf-8" else encoding.upper().replace("-SIG", "")
        raise TaskError(Message("input.not_text_head"), file=file, issues=[(
            "", line, None, Message("input.not_text", encoding=name, reason=exc.reason, byte=exc.start))]) from None
    return text.lstrip("\ufeff")
