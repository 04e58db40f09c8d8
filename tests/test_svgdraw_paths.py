"""svgdraw.Canvas writes a path's numbers "%.2f" all at once and trims them when the
SVG is written (trim): the same text as each number written by _f (two decimals, no
trailing zeros, "-0" as "0"), on random points (hypothesis): zeros and negative zeros,
values that round to them, halves at the second decimal, large and tiny values, NaN."""
from __future__ import annotations

import re

from hypothesis import given, settings
from hypothesis import strategies as st

from tmm_cli.report.svgdraw import Canvas, _f

special = st.sampled_from([0.0, -0.0, 0.004, -0.004, 0.005, -0.005, 0.0049999, -0.0050001, 0.1, -0.1, 0.5,
                           -0.95, 9.995, -9.995, 10.0, -10.0, 100.0, 1e-9, -1e-9, 1e6, -1e6, 1.005, 2.675,
                           float("nan"), float("inf"), -float("inf")])
number = st.one_of(st.floats(-1e4, 1e4), st.floats(-1, 1), st.integers(-3000, 3000).map(lambda k: k / 100),
                   st.integers(-3000, 3000).map(lambda k: k / 1000), special)
points = st.lists(st.tuples(number, number), min_size=1, max_size=6)


def _path(pts, h, closed):
    """The path data of the points as written before: each number by _f."""
    s = "M" + " L".join(f"{_f(float(x))} {_f(h - float(y))}" for x, y in pts)
    return s + ("Z" if closed else "")


@settings(max_examples=300, deadline=None)
@given(st.lists(st.tuples(points, st.booleans()), min_size=1, max_size=4), st.sampled_from([30.0, 41.3, 100.0]))
def test_paths_as_each_number_by_f(shapes, h):
    cv = Canvas(50.0, h)
    for pts, closed in shapes:
        cv.polyline(pts, "#000", 0.3, closed=closed)
        cv.polygon(pts, "#abcdef")
    svg = cv.to_svg()
    stroke, fill = re.findall(r'<path d="([^"]*)"', svg)
    assert stroke == " ".join(_path(p, h, c) for p, c in shapes)
    assert fill == " ".join(_path(p, h, True) for p, _ in shapes)
