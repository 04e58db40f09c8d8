"""The report's cheaper equivalents (made for its CPU, issue 12) give what they replace:
kinematics._median is np.median (without importing numpy.ma), explore._column and
_negated are the float-array columns they replace (None -> NaN), group_force_data is
group_forces without the arrays."""
from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from tmm_cli.report import explore
from tmm_cli.report.sections.kinematics import _median
from tmm_cli.report.sections.kinetostatics import group_force_data, group_forces

finite = st.floats(allow_nan=False, allow_infinity=False, width=64)


@settings(max_examples=400, deadline=None)
@given(st.lists(finite | st.integers(-10**6, 10**6), min_size=1, max_size=40))
def test_median_is_numpy_median(values):
    want = float(np.median(values))
    got = _median(values)
    assert got == want or (math.isnan(got) and math.isnan(want))


@pytest.mark.parametrize("values", [[1.0, math.nan, 2.0], [math.nan], [0.5, 0.25, math.inf, -math.inf]])
def test_median_nan_and_infinities(values):
    want = float(np.median(values))
    got = _median(values)
    assert (math.isnan(got) and math.isnan(want)) or got == want


vec = st.none() | st.tuples(finite | st.none(), finite | st.none())


@settings(max_examples=300, deadline=None)
@given(st.lists(vec, min_size=1, max_size=20))
def test_column_is_a_float_array_column(col):
    arr = np.array([[np.nan, np.nan] if F is None else F for F in col], float)
    for j in (0, 1):
        got = np.array(explore._column(col, j), float)
        np.testing.assert_array_equal(got, arr[:, j])
    for F in col:
        if F is not None:
            np.testing.assert_array_equal(np.array(explore._negated(F), float), -np.array(F, float))


def test_group_force_data_is_group_forces():
    e = {"loads": [{"name": "G2", "link": "AB", "point": [1.0, 2.0], "F": [0.0, -9.81], "kind": "weight"},
                   {"name": "F3", "link": "BC", "point": [3.0, 4.0], "F": [5.0, 6.0], "kind": "load"}],
         "reactions": {"01": {"x": 1.5, "y": -2.5, "pin": [0.0, 0.0]},
                       "12": {"x": -0.0, "y": 7.0, "point": [1.0, 1.0]},
                       "23": {"x": None, "y": None, "pin": [2.0, 2.0]}}}
    info = {"joints": [{"a": 0, "b": 1, "key": "01"}, {"a": 1, "b": 2, "key": "12"}, {"a": 2, "b": 3, "key": "23"}]}
    index = {"AB": 2, "BC": 3}
    for group in ({1}, {2}, {2, 3}, {1, 2}):
        raw = group_force_data(e, info, group, index)
        arrays = group_forces(e, info, group, index)
        assert [r[0] for r in raw] == [a[0] for a in arrays] and [r[4] for r in raw] == [a[3] for a in arrays]
        for (_, pt, F, flip, _), (_, apt, aF, _) in zip(raw, arrays):
            np.testing.assert_array_equal(np.array(pt, float), apt)
            want = -np.array(F, float) if flip else np.array(F, float)
            assert np.array_equal(want, aF) and all(np.signbit(want) == np.signbit(aF))
    names = [r[0] for r in group_force_data(e, info, {2}, index)]
    assert names == ["G2", "R12"]          # the reaction of link 1 on link 2; 23 has no value
    flips = {r[0]: r[3] for r in group_force_data(e, info, {1}, index)}
    assert flips == {"R01": False, "R21": True}


def _polyline_d_reference(X, Y):
    """svgchart._polyline_d as it was: each number through svgdraw._f."""
    from tmm_cli.report.svgdraw import _f
    X, Y = np.asarray(X, dtype=float), np.asarray(Y, dtype=float)
    ok = np.isfinite(X) & np.isfinite(Y)
    parts, run = [], []
    for good, a, b in zip(ok.tolist(), X.tolist(), Y.tolist()):
        if good:
            run.append(f"{_f(a)} {_f(b)}")
        elif run:
            parts.append(run)
            run = []
    if run:
        parts.append(run)
    return "".join("M" + "L".join(r) for r in parts if len(r) > 1)


coord = st.floats(allow_nan=True, allow_infinity=True, width=64, min_value=None, max_value=None) | \
    st.sampled_from([0.0, -0.0, -0.004, 0.005, -0.005, 0.995, -1.0, 10.0, 100.1, -0.001])


@settings(max_examples=400, deadline=None)
@given(st.lists(st.tuples(coord, coord), max_size=25))
def test_chart_path_data_is_per_number_formatting(pts):
    from tmm_cli.report.svgchart import _polyline_d
    X = [p[0] for p in pts]
    Y = [p[1] for p in pts]
    assert _polyline_d(X, Y) == _polyline_d_reference(X, Y)


@pytest.mark.parametrize("size", [5.0, 6.5, 7.0, 8.0, 9, 11.5])
def test_text_attributes_by_size(size):
    """Canvas.text's size-dependent attributes (made once per size) are what _f writes."""
    from tmm_cli.report.svgdraw import PT_PER_MM, Canvas, _f
    fs = size / PT_PER_MM
    cv = Canvas(50, 30)
    cv.text(10, 10, "M", size=size, sub="Φ2", after=" = 5")
    cv.text(20, 10, "x", size=size, sup="2", after="y")
    svg = cv.to_svg()
    assert f'font-size="{_f(fs)}"' in svg
    assert f'<tspan dy="{_f(0.3 * fs)}" font-size="{_f(0.72 * fs)}">Φ2</tspan>' in svg
    assert f'<tspan dy="{_f(-0.3 * fs)}" font-size="{_f(fs)}"> = 5</tspan>' in svg
    assert f'<tspan dy="{_f(-0.4 * fs)}" font-size="{_f(0.72 * fs)}">2</tspan>' in svg
    assert f'<tspan dy="{_f(0.4 * fs)}" font-size="{_f(fs)}">y</tspan>' in svg


@settings(max_examples=60, deadline=None)
@given(st.dictionaries(st.sampled_from("abcdef"), st.integers() | st.none()),
       st.lists(st.sampled_from("abcdef"), min_size=2, max_size=6))
def test_values_of_is_get_of_each_key(d, keys):
    """values_of(keys)(d) is the tuple of d.get(k), whether every key is there (the one
    itemgetter call) or some is missing (None, an empty cell of the tables)."""
    from tmm_cli.report.context import values_of
    assert values_of(tuple(keys))(d) == tuple(d.get(k) for k in keys)
