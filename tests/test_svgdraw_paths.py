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


def _arrow_points(p, q, head, head_w):
    """Canvas.arrow's shaft and head as the 2-vector operations it did (numpy), or None."""
    import numpy as np
    p, q = np.asarray(p, float), np.asarray(q, float)
    d = q - p
    L = float(np.hypot(*d))
    if L < 1e-9:
        return None
    u = d / L
    hl = min(head, 0.45 * L) if L < 2.2 * head else head
    hw = (head_w if head_w is not None else 0.36 * head) * hl / head
    base = q - u * hl
    n = np.array([-u[1], u[0]])
    return [p, base + u * 0.1 * hl], [q, base + n * hw, base - n * hw]


@settings(max_examples=400, deadline=None)
@given(st.tuples(st.floats(-100, 100), st.floats(-100, 100)),
       st.tuples(st.floats(-1e-6, 1e-6), st.floats(-30, 30), st.integers(-12, 2)),
       st.floats(0.5, 4), st.one_of(st.none(), st.floats(0.1, 2)))
def test_arrow_as_on_vectors(p, step, head, head_w):
    """The arrow's points in plain floats: the very numbers of the 2-vector operations."""
    q = (p[0] + step[0], p[1] + step[1] * 10.0 ** step[2])
    got = []
    cv = Canvas(50.0, 40.0)
    cv.polyline = lambda pts, *a, **k: got.append([tuple(map(float, x)) for x in pts])
    cv.polygon = lambda pts, *a, **k: got.append([tuple(map(float, x)) for x in pts])
    cv.arrow(p, q, "#000", 0.3, head, head_w)
    want = _arrow_points(p, q, head, head_w)
    assert got == ([] if want is None else [[tuple(map(float, x)) for x in w] for w in want])
