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


class _Recorder(Canvas):
    """A canvas recording the points of its polylines and polygons (a subclass with its own
    primitives, as sheets.prims.PrimCanvas: the arrow goes through them)."""

    def __init__(self, *a):
        super().__init__(*a)
        self.got = []

    def polyline(self, pts, *a, **k):
        self.got.append([tuple(map(float, x)) for x in pts])

    def polygon(self, pts, *a, **k):
        self.got.append([tuple(map(float, x)) for x in pts])


@settings(max_examples=400, deadline=None)
@given(st.tuples(st.floats(-100, 100), st.floats(-100, 100)),
       st.tuples(st.floats(-1e-6, 1e-6), st.floats(-30, 30), st.integers(-12, 2)),
       st.floats(0.5, 4), st.one_of(st.none(), st.floats(0.1, 2)))
def test_arrow_as_on_vectors(p, step, head, head_w):
    """The arrow's points in plain floats: the very numbers of the 2-vector operations; a
    plain canvas writes them as its polyline and polygon would (its own path data)."""
    q = (p[0] + step[0], p[1] + step[1] * 10.0 ** step[2])
    rec = _Recorder(50.0, 40.0)
    rec.arrow(p, q, "#000", 0.3, head, head_w)
    want = _arrow_points(p, q, head, head_w)
    assert rec.got == ([] if want is None else [[tuple(map(float, x)) for x in w] for w in want])
    cv, ref = Canvas(50.0, 40.0), Canvas(50.0, 40.0)
    for color, dash in (("#000", None), ("0.35", "1 0.5"), ("#000", None)):
        cv.arrow(p, q, color, 0.3, head, head_w, dash=dash, z=2)
        if want is not None:
            ref.polyline(want[0], color, 0.3, dash, 2)
            ref.polygon(want[1], color, 3)
    assert cv.to_svg() == ref.to_svg()


_labels = st.text(alphabet="AB<&'\"Φμ 12", max_size=4)


@settings(max_examples=300, deadline=None)
@given(st.lists(st.tuples(st.floats(-50, 150), st.floats(-50, 150), _labels,
                          st.one_of(st.none(), _labels), st.one_of(st.none(), _labels),
                          st.sampled_from([5.5, 6.5, 7, 7.0]), st.sampled_from(["#000", "#555", "0.35", "k"]),
                          st.sampled_from(["middle", "start", "end"]), st.booleans(), st.booleans(),
                          st.booleans(), st.booleans()), min_size=1, max_size=5))
def test_text_as_before(labels):
    """Canvas.text (its style's attributes made once, the halo's path written directly) gives
    the elements and the halo path of the text written attribute by attribute, the halo
    through polygon."""
    from html import escape

    from tmm_cli.report.svgdraw import PT_PER_MM

    cv, ref = Canvas(100.0, 80.0), Canvas(100.0, 80.0)
    for x, y, s, sub, after, size, color, anchor, italic, bold, halo, vcenter in labels:
        cv.text(x, y, s, size=size, color=color, anchor=anchor, italic=italic, bold=bold, sub=sub or None,
                halo=halo, vcenter=vcenter, after=after)
        fs = size / PT_PER_MM
        yb = (80.0 - y) + (0.35 * fs if vcenter else 0.0)
        attrs = [f'x="{_f(x)}"', f'y="{_f(yb)}"', f'font-size="{_f(fs)}"']
        if anchor != "start":
            attrs.append(f'text-anchor="{anchor}"')
        c = {"#000": "#000000", "#555": "#555555", "0.35": "#595959", "k": "#000000"}[color]
        if c != "#000000":
            attrs.append(f'fill="{c}"')
        if italic:
            attrs.append('font-style="italic"')
        if bold:
            attrs.append('font-weight="bold"')
        body = escape(s)
        if sub:
            body += f'<tspan dy="{_f(0.3 * fs)}" font-size="{_f(0.72 * fs)}">{escape(sub)}</tspan>'
            if after:
                body += f'<tspan dy="{_f(-0.3 * fs)}" font-size="{_f(fs)}">{escape(after)}</tspan>'
        elif after:
            body += escape(after)
        if halo:
            w = 0.6 * fs * (len(s) + 0.72 * len(sub or "")) + 0.6
            x0 = x - w / 2 if anchor == "middle" else (x - w if anchor == "end" else x)
            yc = y if vcenter else y + 0.35 * fs
            ref.polygon([(x0 - 0.3, yc - 0.62 * fs), (x0 + w - 0.3, yc - 0.62 * fs),
                         (x0 + w - 0.3, yc + 0.62 * fs), (x0 - 0.3, yc + 0.62 * fs)], "#fff", z=7)
        ref._items.append((8, f'<text {" ".join(attrs)}>{body}</text>'))
    assert cv.to_svg() == ref.to_svg()


@settings(max_examples=100, deadline=None)
@given(st.lists(st.tuples(points, st.booleans()), min_size=1, max_size=4), st.sampled_from([30.0, 41.3]))
def test_array_points_as_lists(shapes, h):
    """Points given as an (n, 2) array: the same path data as given as a list of pairs."""
    import numpy as np

    cv, ref = Canvas(50.0, h), Canvas(50.0, h)
    for pts, closed in shapes:
        cv.polyline(np.array(pts, float), "#000", 0.3, closed=closed)
        ref.polyline(pts, "#000", 0.3, closed=closed)
    assert cv.to_svg() == ref.to_svg()


def test_moment_arc_as_before():
    """Canvas.moment's arc (its unit points computed once) as computed per couple."""
    import math

    import numpy as np

    for M in (2.5, -0.1):
        cv, ref = Canvas(50.0, 40.0), Canvas(50.0, 40.0)
        cv.moment((10.3, 20.7), 3.2, M, "#1f5fbf", 0.35, z=3)
        sgn = 1.0 if M > 0 else -1.0
        t = np.linspace(math.radians(200), math.radians(200) + sgn * math.radians(260), 24)
        pts = [(10.3 + 3.2 * math.cos(a), 20.7 + 3.2 * math.sin(a)) for a in t.tolist()]
        (x1, y1), (x2, y2) = pts[-1], pts[-2]
        ref.polyline(pts[:-2], "#1f5fbf", 0.35, z=3)
        ref.arrow(pts[-3], (x1 + (x1 - x2) * 0.5, y1 + (y1 - y2) * 0.5), "#1f5fbf", 0.35, head=1.8, z=3)
        assert cv.to_svg() == ref.to_svg()


@settings(max_examples=2000, deadline=None)
@given(st.text(alphabet="0123456789.-MLZ ,e", max_size=40))
def test_trim_patterns_as_before(data):
    """trim's patterns give, on any text, what the ones before gave: the zero of '.d0'
    (not before a digit) dropped, as (\\.\\d)0(?!\\d) -> \\1."""
    from tmm_cli.report.svgdraw import trim

    before = re.sub(r"-0(?![\d.])", "0", re.sub(r"(\.\d)0(?!\d)", r"\1", re.sub(r"\.00(?!\d)", "", data)))
    assert trim(data) == before
