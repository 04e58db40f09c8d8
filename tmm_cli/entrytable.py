"""Per-position results entries made from float tables, in two sizes: the generic pieces of
the ``kinematics`` and ``kinetostatics`` builders (linkage/kinematics/entries.py,
linkage/kinetostatics/entries.py).

* :func:`tabled`: a :class:`tmm_cli.results.LazyEntries` whose values are computed
  (numpy) a table of ``rows`` positions at a time, kept for the last two tables, and
  whose dicts are made ``block`` entries at a time from them. A block's ~100 objects per
  entry (a dict per entry, point, pair, link; a float per value) stay in the CPU's cache
  from made to freed: with blocks of 512 entries, freeing them took as long as half of
  making them.
* :func:`clean`: a table's values as the entries hold them: -0.0 made 0.0 and a value
  that is not finite made ``fill`` (NaN: None in the entries; or a number);
  :func:`values`: its ``tolist`` with NaN as None.
* :func:`dicts`: per position a dict of given keys from one list of values per key, as
  a generated comprehension of dict displays (:func:`_maker`).

Every value depends on its own position only: the entries do not depend on the tables
or the blocks.
"""
from __future__ import annotations

from typing import Any, Callable

import numpy as np

from .results import LazyEntries, bulk


def tabled(n: int, table: Callable[[slice], Any], assemble: Callable[[Any, int, int], list],
           rows: int, block: int) -> LazyEntries:
    """The ``n`` entries as a :class:`LazyEntries`: ``table(slice)`` the values of those
    positions (computed ``rows`` at a time, under ``np.errstate(all="ignore")``, when an
    entry of them is first read; the last two tables kept), ``assemble(tab, a, b)`` the
    entries of the table's rows a..b-1, made ``block`` at a time."""
    tables: dict[int, tuple[int, Any]] = {}

    def find(i: int) -> tuple[int, int, Any]:
        """(first row, end row, the table) of the table holding row ``i``."""
        for t0, (t1, tab) in tables.items():
            if t0 <= i < t1:
                return t0, t1, tab
        t0 = i - i % rows
        t1 = min(t0 + rows, n)
        with np.errstate(all="ignore"):
            tab = table(slice(t0, t1))
        if len(tables) >= 2:
            del tables[next(iter(tables))]
        tables[t0] = (t1, tab)
        return t0, t1, tab

    def build(i0: int, i1: int) -> list[dict]:
        out: list[dict] = []
        with bulk():
            while i0 < i1:
                t0, t1, tab = find(i0)
                k = min(i1, t1)
                out += assemble(tab, i0 - t0, k - t0)
                i0 = k
        return out
    return LazyEntries(n, build, block)


def clean(a: np.ndarray, fill: float = np.nan) -> np.ndarray:
    """``a`` (in place) with -0.0 made 0.0 and every value not finite ``fill`` (NaN:
    None in the entries, or a number)."""
    a += 0.0
    a[~np.isfinite(a)] = fill
    return a


def nan_rows(*tabs: np.ndarray) -> list[int]:
    """The running count of the positions holding a NaN in any of ``tabs`` (each with the
    positions along its axis 1: (values, n) or (points, n, 2)), n + 1 ints: positions
    a..b-1 hold none if ``r[b] == r[a]`` (then :func:`values` need not look for them)."""
    bad = False
    for t in tabs:
        m = np.isnan(t)
        bad = bad | m.any(axis=tuple(i for i in range(m.ndim) if i != 1))
    return [0] + np.cumsum(bad).tolist()


def values(a: np.ndarray, nan: bool = True) -> list:
    """``a.tolist()`` with NaN as None (``nan`` False: ``a`` holds no NaN)."""
    return np.where(np.isnan(a), None, a).tolist() if nan else a.tolist()


def dicts(keys: tuple, cols: list[list], n: int) -> list[dict]:
    """Per position a dict of ``keys`` with the values of ``cols`` (one list of n values
    per key, in the order of ``keys``)."""
    if not keys:
        return [{} for _ in range(n)]
    return _maker(keys)(cols)


_MAKERS: dict[tuple, Callable] = {}


def _maker(keys: tuple) -> Callable[[list[list]], list[dict]]:
    """The function making :func:`dicts` of ``keys``: a comprehension of dict displays
    with the keys as variables (a presized dict filled from the stack, about twice as
    fast as ``dict(zip(keys, row))``), written for the number of keys; the keys are
    bound as arguments, never written into the code."""
    f = _MAKERS.get(keys)
    if f is None:
        k = [f"k{i}" for i in range(len(keys))]
        v = [f"v{i}" for i in range(len(keys))]
        src = (f"def make({', '.join(k)}):\n"
               f"    return lambda cols: [{{{', '.join(f'{a}: {b}' for a, b in zip(k, v))}}} "
               f"for {', '.join(v)}, in zip(*cols)]\n")
        ns: dict = {}
        exec(compile(src, "<tmm_cli.entrytable>", "exec"), ns)
        if len(_MAKERS) >= 256:
            _MAKERS.clear()
        f = _MAKERS[keys] = ns["make"](*keys)
    return f
