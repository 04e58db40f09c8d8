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
