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


# the long lists and arrays (numpy's arithmetic, tables._round_sig_vector): the same values and
# types as the formatting, at ties and near-ties of the last digit, at powers of ten (where
# the decimal exponent may come out one off), across the whole range of floats
_EDGE = [0.0, -0.0, 5e-324, -1e-320, 1.0, 0.1, 2.5, 1234567.5, 9.9999995, 1e308, 1.75e308,
         1e22, 1e23, 1e-22, 1e-23, 999999.95, 0.99999995, 1000.0, 99.999995, 1e-5, 9.9999999e6,
         0.125, 12345.5, -0.0625, 3.0000005, float("nan"), float("inf"), float("-inf")]
_LONG = st.one_of(value, st.sampled_from(_EDGE),
                  st.builds(lambda m, e: m * 10.0 ** e, st.integers(1, 10**9), st.integers(-30, 30)),
                  st.builds(lambda e, up: float(np.nextafter(10.0 ** e, np.inf if up else 0.0)),
                            st.integers(-25, 25), st.booleans()))


@settings(max_examples=200, deadline=None)
@given(st.lists(_LONG, min_size=48, max_size=200), st.integers(1, 12))
def test_long_lists_as_one_by_one(vals, digits):
    want = _round_sig_each(vals, f"%.{digits - 1}e")
    _same(round_sig(vals, digits), want)
    _same(round_sig(np.array(vals, float), digits), want)


def test_long_arrays_every_value_as_one_by_one():
    """~10^5 values of every magnitude and the exact and near ties of 5 and 7 digits."""
    rng = np.random.default_rng(12)
    m = rng.integers(10**4, 10**7, 20000) * 10 + 5          # ...5 after the digits kept
    ties = m * 10.0 ** rng.integers(-12, 6, m.size).astype(float) / 10**7
    a = np.concatenate([rng.standard_normal(20000) * np.exp(rng.uniform(-740, 709, 20000)),
                        rng.standard_normal(20000) * 100, ties, np.nextafter(ties, np.inf),
                        np.nextafter(ties, 0.0), np.array(_EDGE * 10)])
    for digits in (5, 7):
        _same(round_sig(a, digits), _round_sig_each(a.tolist(), f"%.{digits - 1}e"))
