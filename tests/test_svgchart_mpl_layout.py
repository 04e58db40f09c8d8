"""svgchart's figures laid out as matplotlib laid them out (report.figures.new_figure):
the axes' boxes of subplots_adjust (and of matplotlib's defaults) are matplotlib's own, read
from matplotlib where it is installed (it stays a dependency for its fonts); the '///'
hatch is matplotlib's 8 pt apart; an equal aspect with both limits set shrinks the box."""
from __future__ import annotations

import math
import re

import numpy as np
import pytest

from tmm_cli.report.figures import new_figure
from tmm_cli.report.svgdraw import PT_PER_MM


@pytest.mark.parametrize("kw, adjust", [
    (dict(nrows=3, sharex=True), dict(left=0.12, right=0.97, bottom=0.08, top=0.98, hspace=0.15)),
    (dict(ncols=2, gridspec_kw={"width_ratios": [1.2, 1]}), None),
    (dict(nrows=2, sharex=True, gridspec_kw={"height_ratios": [2, 1]}), dict(left=0.1, bottom=0.2)),
])
def test_boxes_are_matplotlibs(kw, adjust):
    mpl = pytest.importorskip("matplotlib")
    mpl.use("Agg", force=True)
    import matplotlib.pyplot as plt
    W, H = 170.0, 120.0
    fig, axes = new_figure(W, H, **kw)
    mfig, maxes = plt.subplots(figsize=(W / 25.4, H / 25.4), **kw)
    if adjust:
        fig.subplots_adjust(**adjust)
        mfig.subplots_adjust(**adjust)
    else:
        fig.to_svg()                      # laid out with matplotlib's defaults when drawn
    for ax, max_ in zip(np.ravel(axes), np.ravel(maxes)):
        p, q = ax.get_position(), max_.get_position()
        assert (p.x0, p.y0, p.x1, p.y1) == pytest.approx((q.x0, q.y0, q.x1, q.y1), abs=1e-9)
    plt.close(mfig)


def test_hatch_lines_are_8pt_apart():
    fig, ax = new_figure(100, 100)
    fig.subplots_adjust(0, 0, 1, 1)
    ax.set_xlim(0, 100)
    ax.set_ylim(0, 100)
    ax.axis("off")
    ax.rectangle((20, 20), 40, 30, hatch="///")
    svg = fig.to_svg()
    d = next(m for m in re.findall(r'<path d="([^"]*)" fill="none"', svg) if m.count("M") > 5)
    segs = [tuple(map(float, s)) for s in re.findall(r"M(-?[\d.]+) (-?[\d.]+)L(-?[\d.]+) (-?[\d.]+)", d)]
    c = sorted(x + y for x, y, _, _ in segs)            # lines x + y = c (y down: rising to the right)
    gaps = np.diff(c)
    assert gaps == pytest.approx(8.0 / PT_PER_MM, abs=0.011)
    for x0, y0, x1, y1 in segs:                         # at 45°, inside the rectangle (mm: y down)
        assert x1 - x0 == pytest.approx(y0 - y1, abs=0.011)
        for x, y in ((x0, y0), (x1, y1)):
            assert 20 - 0.01 <= x <= 60 + 0.01 and 50 - 0.01 <= y <= 80 + 0.01
    assert len(segs) == math.floor(70 / (8.0 / PT_PER_MM)) or len(segs) == math.ceil(70 / (8.0 / PT_PER_MM))


def test_equal_aspect_shrinks_the_box_and_keeps_the_limits():
    fig, ax = new_figure(110, 100)
    ax.set_aspect("equal")
    ax.set_xlim(-10, 10)
    ax.set_ylim(-10, 10)
    ax.circle((0, 0), 5, lw=1.0)
    svg = fig.to_svg()
    x0, y0, w, h = ax.box
    assert w == pytest.approx(h) and h == pytest.approx(0.77 * 100)        # matplotlib's default top - bottom
    assert x0 + w / 2 == pytest.approx((0.125 + 0.9) / 2 * 110)           # centred in the default box
    r = float(re.search(r'<circle [^>]*r="([\d.]+)"', svg).group(1))
    assert r == pytest.approx(5 / 20 * w, abs=0.006)
