"""tables.round_sig (the explorable report's data: every value of the fine grid) formats
the values all at once: the same list, value for value and type for type (0 as the int
0, NaN/inf/None as None), as each value rounded on its own (_round_sig_each), on random
lists and arrays (hypothesis)."""
from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from tmm_cli.tables import _round_sig_each, round_sig

value = st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.floats(-1e3, 1e3),
                  st.sampled_from([0.0, -0.0, 5e-324, -1e-320, 1.0, 0.1, 2.5, 1234567.5, 9.9999995, 1e308]),
                  st.integers(-10**6, 10**6))


def _same(got, want):
    assert [type(x) for x in got] == [type(x) for x in want]
    assert repr(got) == repr(want)


@settings(max_examples=300, deadline=None)
@given(st.lists(st.one_of(value, st.none()), max_size=40), st.integers(2, 9))
def test_lists_as_one_by_one(vals, digits):
    _same(round_sig(vals, digits), _round_sig_each(vals, f"%.{digits - 1}e"))
    _same(round_sig(tuple(vals), digits), _round_sig_each(vals, f"%.{digits - 1}e"))


@settings(max_examples=300, deadline=None)
@given(st.lists(st.floats(allow_nan=True, allow_infinity=True), max_size=60), st.integers(2, 9))
def test_arrays_as_one_by_one(vals, digits):
    a = np.array(vals, float)
    _same(round_sig(a, digits), _round_sig_each(a.tolist(), f"%.{digits - 1}e"))
    _same(round_sig(a.reshape(-1, 1) if len(a) else a, digits), _round_sig_each(a.tolist(), f"%.{digits - 1}e"))
    _same(round_sig(list(a), digits), _round_sig_each(a.tolist(), f"%.{digits - 1}e"))   # numpy floats
