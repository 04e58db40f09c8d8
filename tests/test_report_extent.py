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


def test_output_series_of_a_slider_as_entry_by_entry():
    """kinematics.output_series reads the slider's pin in bulk: the numbers of the
    products taken entry by entry."""
    import math
    from tmm_cli.plans import geometry
    from tmm_cli.report.sections.kinematics import output_series
    src = ROOT / "tasks" / "forging_sixbar.yaml"
    task = tmm_cli.load_task(src, text=src.read_text(encoding="utf-8").replace("count: 12", "count: 120"))
    res = tmm_cli.run(task)
    entries = res["kinematics"]
    kind, s, v, a = output_series(None, geometry(res), entries, "slider")
    assert kind == "slider" and len(s) == len(v) == len(a) == len(entries)
    ang = math.radians(float(entries[0]["links"]["slider"]["angle"]))
    u = np.array([math.cos(ang), math.sin(ang)])
    r0 = F._pxy(entries[0], "D")
    assert s == [float((F._pxy(e, "D") - r0) @ u) for e in entries]
    assert v == [float(np.array([e["points"]["D"]["vx"], e["points"]["D"]["vy"]], float) @ u) for e in entries]
    assert a == [float(np.array([e["points"]["D"]["ax"], e["points"]["D"]["ay"]], float) @ u) for e in entries]
    assert max(s) - min(s) > 0.05 and max(map(abs, v)) > 0.1
