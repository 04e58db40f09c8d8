"""The report's bulk reads of the points over all positions (figures.points_xy,
mechanism_extent) give what reading them entry by entry gives."""
from __future__ import annotations

from pathlib import Path

import numpy as np

import tmm_cli
from tmm_cli.report import figures as F

ROOT = Path(__file__).resolve().parents[1]


def test_points_and_extent_as_entry_by_entry():
    src = ROOT / "tasks" / "forging_sixbar.yaml"
    task = tmm_cli.load_task(src, text=src.read_text(encoding="utf-8").replace("count: 12", "count: 120"))
    entries = tmm_cli.run(task)["kinematics"]
    names = list(entries[0]["points"])
    for p in names:
        ref = np.array([F._pxy(e, p) for e in entries])
        got = F.points_xy(entries, p)
        assert got.shape == (len(entries), 2) and np.array_equal(got, ref)
    assert F.points_xy([], names[0]).shape == (0,)
    xy = np.array([F._pxy(e, p) for e in entries for p in names])
    lo, hi = F.mechanism_extent(entries)
    assert np.array_equal(lo, xy.min(axis=0)) and np.array_equal(hi, xy.max(axis=0))
    assert lo[0] < hi[0] and lo[1] < hi[1]
    some = {"B", "D"}
    xy = np.array([F._pxy(e, p) for e in entries for p in names if p in some])
    lo, hi = F.mechanism_extent(entries, some)
    assert np.array_equal(lo, xy.min(axis=0)) and np.array_equal(hi, xy.max(axis=0))
    lo, hi = F.mechanism_extent([])
    assert np.array_equal(lo, np.zeros(2)) and np.array_equal(hi, np.zeros(2))
