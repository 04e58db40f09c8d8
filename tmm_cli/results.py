"""The results file (README, *results.json*; docs/methods.md §8): JSON with plain numbers, NaN/inf never written."""
from __future__ import annotations

import gc
import json
import math
import re
from collections.abc import Sequence
from contextlib import contextmanager
from typing import Any, Callable

import orjson

from .messages import Message


class Entries(list):
    """A results section's entries (one per position) built already clean: plain
    Python values, every float finite (else None) and never -0.0, string keys.
    :func:`clean` takes them as they are and :func:`dumps` writes them without
    checking them again. The builders (``KinematicsResult.to_entries``,
    ``KinetostaticsResult.to_dict``, ``graphical_error``) make them so; anything else
    stays a plain list and is cleaned."""
    __slots__ = ()


class LazyEntries(Sequence):
    """A results section's entries (one per position, clean as :class:`Entries`) made
    from the stage result's arrays when they are read, a block of positions at a time:
    nothing holds every entry at once (36,000 kinetostatics entries as dicts hold
    ~230 MB; :func:`dump` writes them block by block).

    A read-only sequence of dicts: ``len(e)``; ``e[i]`` (a new dict at each access: a
    change to it is not kept) and ``e[a:b]`` (an :class:`Entries`); iteration (block by
    block); ``==`` with a list or another LazyEntries compares the entries in order;
    ``list(e)`` or ``e.tolist()`` gives them all (``tolist``: as an :class:`Entries`);
    copied or pickled as that list. :func:`dumps` and :func:`dump` write it as the
    list of its entries; ``json.dumps`` does not take it (it is no list).

    ``build(i0, i1)``: the clean entries of the rows i0..i1-1, as a list."""
    __slots__ = ("_n", "_build", "_block")

    BLOCK = 512          # entries built at a time by iteration

    def __init__(self, n: int, build: Callable[[int, int], list], block: int = BLOCK):
        self._n, self._build, self._block = int(n), build, max(1, int(block))

    def __len__(self) -> int:
        return self._n

    def __getitem__(self, i):
        if isinstance(i, slice):
            start, stop, step = i.indices(self._n)
            if step == 1:
                return Entries(self._build(start, stop) if start < stop else ())
            return Entries(self._build(k, k + 1)[0] for k in range(start, stop, step))
        k = i.__index__()
        if k < 0:
            k += self._n
        if not 0 <= k < self._n:
            raise IndexError("entry index out of range")
        return self._build(k, k + 1)[0]

    def __iter__(self):
        n, b, build = self._n, self._block, self._build
        for i0 in range(0, n, b):
            yield from build(i0, min(i0 + b, n))

    def tolist(self) -> Entries:
        return Entries(self)

    def __eq__(self, other):
        if isinstance(other, (list, LazyEntries)):
            return len(self) == len(other) and all(a == b for a, b in zip(self, other))
        return NotImplemented

    __hash__ = None

    def __reduce__(self):
        return Entries, (self.tolist(),)

    def __repr__(self) -> str:
        return f"<LazyEntries: {self._n} entries>"


def listed(results: Any) -> Any:
    """The results with every :class:`LazyEntries` in them (in dicts at any depth) made
    into its :class:`Entries` list: for readers that take the entries many times, keep
    them, or tell them apart by identity (the public ``tmm_cli.run``, the report, the
    sheets, grading). A dict holding one is copied, any other value is the same object."""
    t = type(results)
    if t is LazyEntries:
        return results.tolist()
    if t is dict:
        new = {k: listed(v) for k, v in results.items()}
        return new if any(new[k] is not v for k, v in results.items()) else results
    return results


@contextmanager
def bulk():
    """Python's cycle collector paused while a builder makes the many small containers
    of a section's entries (a dict per position, per point, per pair: ~10^6 at 36,000
    positions). They hold no cycles, so nothing is lost; with the collector running, it
    would scan them again and again as they pile up (half the building time). Made,
    they go straight to the oldest generation (``gc.freeze`` then ``gc.unfreeze``: no scan
    now; the next full collection sees them, and any garbage younger than them, as
    usual) instead of being scanned at once as young objects and again as middle-aged ones."""
    was = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if was:
            gc.freeze()
            gc.unfreeze()
            gc.enable()


_FLOATS = {float}


def clean(obj: Any) -> Any:
    """Plain JSON types: numpy scalars/arrays to Python, NaN and inf to None."""
    t = type(obj)
    if t is Entries or t is LazyEntries:
        return obj
    if t is float:                                            # the common cases first
        return obj + 0.0 if math.isfinite(obj) else None      # + 0.0: no "-0.0" in the file
    if t is dict:
        return {k if type(k) is str else str(k): clean(v) for k, v in obj.items()}
    if t is list:
        if obj and set(map(type, obj)) == _FLOATS:
            # a list of floats (a curve, an array's tolist()): cleaned in one pass, no call
            # per value (finite: v - v is 0.0; inf and NaN give NaN, which is no 0.0)
            return [v + 0.0 if v - v == 0.0 else None for v in obj]
        return [clean(v) for v in obj]
    if t is str or t is int or obj is None or t is bool:
        return obj
    if isinstance(obj, dict):
        return {str(k): clean(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [clean(v) for v in obj]
    if isinstance(obj, bool) or isinstance(obj, str):
        return obj
    if isinstance(obj, int):
        return obj
    if isinstance(obj, float):
        return obj + 0.0 if math.isfinite(obj) else None
    tolist = getattr(obj, "tolist", None)
    if tolist is not None:
        return clean(tolist())
    if hasattr(obj, "to_dict"):
        return clean(obj.to_dict())
    return str(obj)


_ENC = json.JSONEncoder(ensure_ascii=False, allow_nan=False)
_ORJSON = orjson.dumps
_ORJSON_ERROR = orjson.JSONEncodeError


def one_line(v) -> str:
    """A clean value (see :func:`clean`) as JSON on one line, by orjson: compact (no
    space after "," and ":"), UTF-8 text as it is, every float in the shortest form
    that reads back to the same float (ryu: ``0.00001``, ``2.5e-7``, ``1e+16``), ~20x
    faster than json's encoder, whose time at a fine grid is float.__repr__'s. The
    rare value orjson does not take (an int beyond 64 bits) goes to json's encoder."""
    try:
        return _ORJSON(v).decode()
    except _ORJSON_ERROR:
        return _ENC.encode(v)


def dumps(results: dict) -> str:
    """The results file's text, deterministic: the sections and their entries (one
    position, one joint...) one key a line, indented by one space a level; anything
    deeper, and any array of plain values, on one line (:func:`one_line`)."""
    out: list[str] = []
    _emit(clean(results), 0, out)
    out.append("\n")
    return "".join(out)


class _Spill(list):
    """The text pieces of :func:`_emit`, handed to ``write`` (UTF-8) every
    ``ENTRIES_PER_SPILL`` entries of a section and at the end: the file's text is
    never whole in memory."""
    __slots__ = ("write",)

    def __init__(self, write):
        super().__init__()
        self.write = write

    def spill(self) -> None:
        if self:
            self.write("".join(self).encode("utf-8"))
            self.clear()


ENTRIES_PER_SPILL = 256


def dump(results: dict, write) -> None:
    """The bytes of ``dumps(results)`` (UTF-8) given to ``write`` (a binary file's
    ``write``) piece by piece."""
    out = _Spill(write)
    _emit(clean(results), 0, out)
    out.append("\n")
    out.spill()


def dump_parts(results: dict, split: int) -> tuple[Callable, Callable]:
    """(head, tail): ``dump`` in two parts, each a function given ``write`` as ``dump``
    is; head's bytes then tail's are ``dump(results)``'s. The head writes the sections
    before the ``split``-th (0: none), the tail the others (the results cleaned once,
    here)."""
    items = list(clean(results).items())
    split = max(0, min(split, len(items)))

    def part(lo: int, hi: int, first: bool):
        def go(write) -> None:
            out = _Spill(write)
            if first:
                out.append("{" if items else "{}")
            _emit_items(items, lo, hi, 0, out)
            if not first:
                out.append("\n}\n" if items else "\n")
            out.spill()
        return go
    return part(0, split, True), part(split, len(items), False)


_ONE_LINE_DEPTH = 3


def _emit(obj, level: int, out: list[str]) -> None:
    if (type(obj) is Entries or type(obj) is LazyEntries) and level == _ONE_LINE_DEPTH - 2 and obj:
        _emit_entries(obj, out)
    elif type(obj) is LazyEntries:           # elsewhere: as its list (an Entries) is written
        _emit(obj.tolist(), level, out)
    elif level >= _ONE_LINE_DEPTH:
        out.append(one_line(obj))
    elif type(obj) is dict and obj:
        out.append("{")
        items = list(obj.items())
        _emit_items(items, 0, len(items), level, out)
        out.append("\n" + " " * level + "}")
    elif type(obj) is list and any(type(v) is dict or type(v) is list for v in obj):
        pad = "\n" + " " * (level + 1)
        out.append("[")
        for i, v in enumerate(obj):
            out.append(pad if i == 0 else "," + pad)
            _emit(v, level + 1, out)
        out.append("\n" + " " * level + "]")
    else:
        out.append(one_line(obj))


def _emit_items(items: list, lo: int, hi: int, level: int, out: list[str]) -> None:
    """``_emit`` of the items lo..hi-1 of a dict at ``level`` (between its braces)."""
    pad = "\n" + " " * (level + 1)
    for i in range(lo, hi):
        k, v = items[i]
        out.append(pad if i == 0 else "," + pad)
        out.append(one_line(k) + ": ")
        _emit(v, level + 1, out)


def _emit_entries(entries: Entries | LazyEntries, out: list[str]) -> None:
    """``_emit`` of a section's clean entries (at level 1): each entry a dict, one key a
    line, its values on one line."""
    keys: dict[str, str] = {}
    pad = "\n" + " " * _ONE_LINE_DEPTH
    sep = ","
    one = one_line
    spill = getattr(out, "spill", None)
    out.append("[")
    for i, e in enumerate(entries):
        if spill is not None and i % ENTRIES_PER_SPILL == 0:
            spill()
        out.append("\n  " if i == 0 else ",\n  ")
        if type(e) is not dict or not e:
            _emit(e, _ONE_LINE_DEPTH - 1, out)
            continue
        parts = []
        for k, v in e.items():
            kt = keys.get(k)
            if kt is None:
                kt = keys[k] = pad + one(k) + ": "
            parts.append(kt + one(v))
        out.append("{" + sep.join(parts) + "\n  }")
    out.append("\n ]")


_TOKEN = re.compile(r"([^.\[\]]+)|\[(-?\d+)\]")


def parse_path(path: str) -> list[str | int]:
    """'kinematics[2].points.B.v' -> ['kinematics', 2, 'points', 'B', 'v']."""
    out: list[str | int] = []
    pos = 0
    for m in _TOKEN.finditer(path):
        if m.start() != pos and path[pos:m.start()] != ".":
            raise KeyError(Message("answers.bad_path_near", path=path, near=path[pos:m.start()]))
        out.append(m.group(1) if m.group(1) is not None else int(m.group(2)))
        pos = m.end()
    if pos != len(path) or not out:
        raise KeyError(Message("answers.bad_path", path=path))
    return out


# a value below this in magnitude (SI units) is the round-off of an exact zero (a velocity at a
# dead centre, a reaction's moment at a pair on the load's line): the report's tables print it
# 0 and the grading takes 0 for its reference (:func:`reference`); results.json keeps it
ROUND_OFF_ZERO = 1e-10


def reference(value: Any) -> Any:
    """A result's value as the reference of an answer: a float of magnitude below
    :data:`ROUND_OFF_ZERO` is 0.0 (so the zero reference's absolute tolerance applies to it,
    as to a zero computed exactly); anything else as it is."""
    return 0.0 if type(value) is float and abs(value) < ROUND_OFF_ZERO else value


def lookup(results: dict, path: str) -> Any:
    """The value at a path into results.json. In lists of position entries
    (kinematics, kinetostatics) `[i]` selects the entry whose `index` is i;
    elsewhere it is the list index, counted from 0 (a negative index, Python's count from
    the end, leads nowhere: ``r[-1]`` is not ``r[1]``). A path that leads nowhere raises KeyError whose
    one argument is the coded reason (a Message: `exc.args[0]`, never `str(exc)`,
    which is its quoted repr)."""
    cur: Any = results
    for tok in parse_path(path):
        if isinstance(tok, int):
            if not isinstance(cur, (list, LazyEntries)):
                raise KeyError(Message("answers.path_not_list", path=path, index=tok))
            if cur and isinstance(cur[0], dict) and "index" in cur[0]:
                hit = [e for e in cur if e.get("index") == tok]
                if not hit:
                    raise KeyError(Message("answers.path_no_entry", path=path, index=tok))
                cur = hit[0]
            else:
                if not 0 <= tok < len(cur):
                    raise KeyError(Message("answers.path_index_range", path=path, index=tok))
                cur = cur[tok]
        else:
            if not isinstance(cur, dict) or tok not in cur:
                raise KeyError(Message("answers.path_no_key", path=path, key=tok))
            cur = cur[tok]
    return cur


def leaf_paths(results: dict) -> list[tuple[str, Any]]:
    """Every path to a number, bool or string in results (position lists by [index])."""
    out: list[tuple[str, Any]] = []
    _leaves(results, "", out)
    return out


def _leaves(o, p: str, out: list) -> None:
    """:func:`leaf_paths` of ``o`` at path ``p``, appended to ``out``.  (A function of the
    module, not one nested in leaf_paths: a nested one that calls itself is a reference cycle,
    which kept the ~10^4 paths of a variant alive until the cycle collector came.)"""
    if type(o).__module__ == "numpy" and not isinstance(o, (list, dict)):
        o = o.item()             # a numpy scalar as the Python number it is (printed as such)
    if isinstance(o, dict):
        for k, v in o.items():
            _leaves(v, f"{p}.{k}" if p else str(k), out)
    elif isinstance(o, (list, LazyEntries)):
        by_index = bool(o) and all(isinstance(e, dict) and "index" in e for e in o)
        for i, v in enumerate(o):
            _leaves(v, f"{p}[{v['index'] if by_index else i}]", out)
    elif o is None or isinstance(o, (bool, int, float, str)):
        if o is not None:
            out.append((p, o))


def did_you_mean(path: str, results: dict, leaves: list[str] | None = None) -> str:
    """'did you mean <the nearest numeric path>' (in the path's section first), or 'no such path'."""
    import difflib

    cands = leaves if leaves is not None else [p for p, v in leaf_paths(results)
                                               if isinstance(v, (int, float))]
    sec = path.split(".")[0].split("[")[0]
    near = [c for c in cands if c.split(".")[0].split("[")[0] == sec] or cands
    hit = _named_alike(path, near) or difflib.get_close_matches(path, near, n=1, cutoff=0.5)
    return Message("answers.did_you_mean", path=hit[0]) if hit else Message("answers.no_such_path")


# the words a student writes for a quantity and the results' key of it ('velocities.B' is
# 'points.B.v'): a path naming every one of its parts so is suggested before a spelling alike
_SAID = {"velocity": "v", "velocities": "v", "speed": "v", "acceleration": "a", "accelerations": "a",
         "angular_velocity": "omega", "angular_acceleration": "epsilon", "w": "omega", "e": "epsilon"}


def _named_alike(path: str, near: list[str]) -> list[str]:
    """The one path of ``near`` holding every name of ``path`` (its section and index, and
    each other name or the results' key a student's word means), or none."""
    import re
    parts = re.findall(r"[^.\[\]]+|\[[^\]]*\]", path)
    if len(parts) < 2:
        return []
    names = [set(re.findall(r"[^.\[\]]+|\[[^\]]*\]", c)) for c in near]
    known = set().union(*names)
    want = set()
    for w in parts:          # a word no path has, written with '_' ('v_B'): its pieces
        pieces = [w] if w in known or "_" not in w else w.split("_")
        want |= {x if x in known else _SAID.get(x.lower(), x) for x in pieces}    # a point E is no epsilon
    hits = [c for c, n in zip(near, names) if want <= n]
    return hits if len(hits) == 1 else []
