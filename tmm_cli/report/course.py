"""Which positions the report draws and tabulates one by one.

A course project works on 12 (or 24) positions of the crank plus a few named ones
(extreme positions, the positions asked for by angle).  A task may compute a fine
grid (``positions.count: 3600``) for smooth curves; the report then still draws the
plans and the per-position tables for the course positions only -- 12 grid positions
spread evenly over the cycle from the zero position, plus every named extra -- and
shows the fine grid as curves (the diagrams) and in full in the CSV files beside it.
"""
from __future__ import annotations

COURSE_MAX = 24     # grids up to this many positions are shown in full
COURSE_N = 12       # a finer grid shows this many of its positions


def course_indices(n_grid: int, n_total: int) -> list[int]:
    """Indices (into the results list) of the positions shown one by one: the whole
    grid if it has at most COURSE_MAX positions, else COURSE_N evenly spread grid
    positions (the first one included); then the named extras after the grid."""
    n_grid = max(0, min(int(n_grid), int(n_total)))
    if n_grid <= COURSE_MAX:
        grid = list(range(n_grid))
    else:
        grid = sorted({round(k * n_grid / COURSE_N) for k in range(COURSE_N)})
    return grid + list(range(n_grid, int(n_total)))


def course_entries(entries: list, n_grid: int) -> list:
    """The entries at course_indices (all of them for a course-sized grid)."""
    idx = course_indices(n_grid, len(entries))
    if len(idx) == len(entries):
        return entries
    return [entries[i] for i in idx]


def cycle_order(entries: list, phi0: float, sign: float) -> list:
    """The entries in the order of the crank's turn from the zero position (phi0, sign +1
    counter-clockwise): a named extra between the grid positions it falls between, as the
    tables and drawings show them (the results keep the grid first, the extras after it)."""
    def phase(e):
        q = ((float(e["phi"]) - float(phi0)) * sign) % 360.0
        return 0.0 if q > 360.0 - 1e-9 else q
    return sorted(entries, key=phase)


def position_label(e: dict, n_grid: int) -> str:
    """A position's number as the tables show it: a named extra (index >= the grid's count)
    marked with an asterisk."""
    return f"{e['index']}*" if int(e["index"]) >= n_grid else str(e["index"])


def grid_size(results: dict) -> int | None:
    """The number of the grid's positions (results' ``positions.count``), None when the results
    do not say: a position numbered from it on is an extra one."""
    c = (results.get("positions") or {}).get("count")
    return c if isinstance(c, int) and c > 0 else None


def grid_count(results: dict, n_entries: int) -> int:
    """The number of grid positions among n_entries, the grid's first (:func:`grid_size`, at
    most n_entries), the rest being named extras; all of them when the results do not say."""
    size = grid_size(results)
    return n_entries if size is None else min(size, n_entries)
