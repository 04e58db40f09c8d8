"""Figure helpers of the report: charts and drawings written directly as SVG (svgchart's
matplotlib-like axes: ``new_figure``, ``figure_at_scale``), nice scales, label placement,
and the kinematic scheme of a linkage (ground pivots with hatching, slider blocks, guides,
joints, link numbers; SchemeView on an svgdraw canvas).  The report imports no matplotlib.

Text uses DejaVu Sans (it has Cyrillic and Greek).
"""
from __future__ import annotations

import math
import re
from itertools import chain
from operator import itemgetter

import numpy as np

from .svgdraw import PT_PER_MM
from ..numfmt import superscript

MM = 1.0 / 25.4  # inch per mm
_SUBS = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")


def new_figure(width_mm: float = 170.0, height_mm: float = 100.0, nrows: int = 1, ncols: int = 1,
               sharex: bool = False, gridspec_kw: dict | None = None):
    """A new figure of the given size in millimetres (svgchart, laid out as matplotlib lays
    out a figure: subplots_adjust's fractions, tight_layout); returns (fig, ax or axes)."""
    from .svgchart import subplots
    gk = gridspec_kw or {}
    return subplots(width_mm, height_mm, nrows=nrows, ncols=ncols, sharex=sharex,
                    height_ratios=gk.get("height_ratios"), width_ratios=gk.get("width_ratios"), mpl=True)


_NAME_OK = re.compile(r"[^a-z0-9-]+")


def named(svg_text, name: str):
    """The SVG with its file name beside the report: figures/<name>.svg (content and
    position, e.g. 'plans-pos02', 'lever-pos02', 'cam-profile'), kept as a data-name
    attribute of the root element until the report writes its figure files."""
    from markupsafe import Markup
    name = _NAME_OK.sub("-", str(name).lower()).strip("-") or "figure"
    return Markup(re.sub(r"<svg\b", f'<svg data-name="{name}"', str(svg_text), count=1))


def pos_name(kind: str, index) -> str:
    """'plans', 2 -> 'plans-pos02'."""
    return f"{kind}-pos{int(index):02d}"


# ---------------------------------------------------------------- scales
# the course's scale factors μ (velocity, acceleration, force, moment, work, inertia, the
# diagrams' ordinates): 1, 2, 2.5, 4, 5 x 10^k, the same series as the sheets
from ..scales import NICE_SERIES, nice_scale  # noqa: E402,F401  (the series, used here and by the sheets)


def std_axis(ax, lo: float, hi: float, axis: str = "y", pad: float = 0.04, zero: bool = True) -> float:
    """Limits of one axis of a graph whose span is a standard μ (nice_scale, units per paper
    mm) times the axis' length on the paper (the axes as laid out now: call it after
    tight_layout / subplots_adjust), the values lo..hi (and 0 when `zero`) centred in it;
    returns μ."""
    if zero:
        lo, hi = min(lo, 0.0), max(hi, 0.0)
    if not (math.isfinite(lo) and math.isfinite(hi)):
        lo, hi = 0.0, 1.0
    fig = ax.figure
    pos = ax.get_position()
    length = (pos.width * fig.get_figwidth() if axis == "x" else pos.height * fig.get_figheight()) * 25.4
    span = max(hi - lo, 1e-12 * max(abs(lo), abs(hi), 1e-300)) * (1 + 2 * pad)
    mu = nice_scale(span / length)
    extra = (mu * length - (hi - lo)) / 2
    if zero and lo == 0.0 and axis == "y":       # values of one sign (magnitudes): the axis starts
        extra_lo, extra_hi = 0.0, 2 * extra       # at 0 (|R| ran down to -2500)
    elif zero and hi == 0.0 and axis == "y":
        extra_lo, extra_hi = 2 * extra, 0.0
    else:
        extra_lo = extra_hi = extra
    (ax.set_xlim if axis == "x" else ax.set_ylim)(lo - extra_lo, hi + extra_hi)
    return mu


def std_graph(fig, axes, mm: str = "mm", x_axis=None, x_sym: str = "φ", x_unit: str = "°",
              tight: bool = True, zero: bool = True) -> dict:
    """Every graph of the figure at standard scales, stated in the course's form: each
    axes' ordinate (its label 'M, N·m' gives the symbol and unit) at μ over its data,
    the title 'μM = 20 (N·m)/mm' at its top right; `x_axis`: the axes whose abscissa
    (shared, from 0) gets μφ too, stated after its label.  The layout is made
    (tight_layout) with the titles in place, then the limits are set; `zero`: the ordinate
    axes include 0.  Returns {symbol: μ}."""
    axes = [ax for ax in axes if ", " in ax.get_ylabel()]
    for ax in axes:
        ax.set_title("μ = 0.0025 (N·m)/mm", loc="right", fontsize=7, pad=2)
    if x_axis is not None:
        x_axis.set_xlabel(f"{x_axis.get_xlabel()};  μ{x_sym} = 2.5 {x_unit}/{mm}")
    if tight or hasattr(fig, "to_svg"):    # an svgchart figure lays itself out with the titles
        fig.tight_layout()
    out = {}
    for ax in axes:
        sym, unit = ax.get_ylabel().split(", ", 1)
        sym = sym.replace("$", "").strip("|").split("_")[0]
        lo, hi = ax.dataLim.y0, ax.dataLim.y1
        mu = std_axis(ax, lo, hi, zero=zero)
        out[sym] = mu
        ax.set_title(mu_text(sym, mu, unit, mm), loc="right", fontsize=7, pad=2)
    if x_axis is not None:
        lo, hi = x_axis.dataLim.x0, x_axis.dataLim.x1
        lo = min(lo, 0.0)
        # the next smaller standard μ, when the axes can grow into the right margin to hold it
        fw = fig.get_figwidth() * 25.4
        pos = x_axis.get_position()
        L = pos.width * fw
        up = nice_scale((hi - lo) / L)
        down = max((c for c in (nice_scale(up * f) for f in (0.4, 0.5, 0.6, 0.8, 0.9)) if c < up), default=up)
        grow = (hi - lo) / down - L
        # (only into free paper: not when another graph stands to the right)
        right_free = not any(o.get_position().x0 >= pos.x1 - 1e-6 for o in fig.axes)
        if right_free and 0 < grow <= (1.0 - pos.x1) * fw - 1.5:
            for ax in fig.axes:
                p = ax.get_position()
                if abs(p.x1 - pos.x1) < 1e-6:
                    ax.set_position([p.x0, p.y0, p.width + grow / fw, p.height])
        mu = std_axis(x_axis, lo, hi, axis="x", pad=0.0)
        x_axis.set_xlim(0.0, float(np.ptp(x_axis.get_xlim())))
        label = x_axis.get_xlabel().rsplit(";  μ", 1)[0]
        x_axis.set_xlabel(f"{label};  {mu_text(x_sym, mu, x_unit, mm)}")
        out[x_sym] = mu
    return out


def mu_text(sym: str, mu: float, unit: str, mm: str = "mm") -> str:
    """The scale in the course's form: 'μs = 0.002 m/mm', 'μv = 0.05 (m/s)/mm' (in Russian and
    Ukrainian the unit's numerator over the bracketed product with the millimetre, as the course
    writes it)."""
    # a scale's power of ten as a drawing writes it in every language (2·10⁻⁵, not 2e-05)
    m, _, e = f"{mu:g}".partition("e")
    value = f"{m}·10{superscript(str(int(e)))}" if e else m
    if mm != "mm" and "/" in unit and not unit.startswith("("):   # ru, uk: m/(s·mm) in their letters
        num, den = unit.split("/", 1)
        return f"μ{sym} = {value} {num}/({den}·{mm})"
    u = f"({unit})" if "/" in unit and not unit.startswith("(") else unit
    return f"μ{sym} = {value} {u}/{mm}"


def scale_mark(lang: str) -> str:
    """The letter before a drawing scale (GOST 2.302: 'M 1:10'): the words' `common.scale_mark`
    (the Cyrillic capital Em in Russian and Ukrainian)."""
    from .. import locales
    return locales.of("report", "words", lang).get("common.scale_mark", "M")


# standard drawing scales (GOST 2.302): enlargements n:1 and reductions 1:n, as model mm per paper mm
GOST_ENLARGEMENTS = (100.0, 50.0, 40.0, 20.0, 10.0, 5.0, 4.0, 2.5, 2.0)
GOST_REDUCTIONS = (1.0, 2.0, 2.5, 4.0, 5.0, 10.0, 15.0, 20.0, 25.0, 40.0, 50.0, 75.0, 100.0, 200.0, 400.0,
                   500.0, 800.0, 1000.0)


def drawing_scale(unit: float) -> tuple[float, str]:
    """Smallest standard drawing scale (GOST 2.302) whose model mm per paper mm is >= unit:
    (model mm per paper mm, label such as '1:2.5' or '2:1').

    >>> drawing_scale(1.7)
    (2.0, '1:2')
    >>> drawing_scale(0.3)
    (0.4, '2.5:1')
    """
    for n in GOST_ENLARGEMENTS:
        if 1.0 / n >= unit * (1 - 1e-12):
            return 1.0 / n, f"{n:g}:1"
    for n in GOST_REDUCTIONS:
        if n >= unit * (1 - 1e-12):
            return n, f"1:{n:g}"
    n = nice_scale(unit)
    return n, f"1:{n:g}"


def figure_at_scale(lo, hi, unit: float, margin_mm: float = 8.0):
    """A figure sized so that the box lo..hi (model mm) is drawn at ``unit`` model mm per paper mm
    with the given margin; one equal-aspect axes without frame; returns (fig, ax)."""
    lo = np.asarray(lo, float)
    hi = np.asarray(hi, float)
    w, h = (hi - lo) / unit + 2 * margin_mm
    fig, ax = new_figure(float(w), float(h))
    fig.subplots_adjust(0, 0, 1, 1)
    c = (lo + hi) / 2
    ax.set_xlim(c[0] - unit * w / 2, c[0] + unit * w / 2)
    ax.set_ylim(c[1] - unit * h / 2, c[1] + unit * h / 2)
    ax.set_aspect("equal", adjustable="box")
    ax.axis("off")
    return fig, ax


# ---------------------------------------------------------------- primitives
def _ground_lines(xy, size: float, angle_deg: float = -90.0):
    """A fixed pivot's strokes: the two sides of its triangle (pivot -> base ends) and its
    base line (to hatch), the outward direction."""
    a = math.radians(angle_deg)
    d = np.array([math.cos(a), math.sin(a)])      # from pivot towards the base
    nrm = np.array([-d[1], d[0]])
    c = np.asarray(xy, float)
    h = 1.6 * size
    sides = [(c, c + d * h + nrm * size), (c, c + d * h - nrm * size)]
    return sides, (c + d * h + nrm * 1.6 * size, c + d * h - nrm * 1.6 * size), d


def _hatch_strokes(p, q, depth, outward, n=None):
    """The short strokes hatching the line p-q on the side `outward`."""
    p = np.asarray(p, float)
    q = np.asarray(q, float)
    outward = np.asarray(outward, float)
    outward = outward / (np.linalg.norm(outward) or 1.0)
    L = float(np.linalg.norm(q - p))
    if L <= 0:
        return []
    t = (q - p) / L
    if n is None:
        n = max(3, int(L / depth * 1.2))
    return [(p + t * s, p + t * s + outward * depth - t * depth) for s in np.linspace(0, L, n + 1)[1:]]


def draw_ground(ax, xy, size: float, angle_deg: float = -90.0, lw=0.8, color="k"):
    """A fixed pivot (svgchart axes): small triangle ending in a hatched base, pointing
    away from angle_deg (default: base below the pivot)."""
    sides, (e1, e2), d = _ground_lines(xy, size, angle_deg)
    for p, q in sides:
        ax.plot([p[0], q[0]], [p[1], q[1]], color=color, lw=lw, zorder=3)
    draw_hatch(ax, e1, e2, size * 0.7, d, lw=lw, color=color)


def draw_hatch(ax, p, q, depth, outward, lw=0.8, color="k", n=None):
    """A ground line p-q with short hatch strokes on the side `outward` (svgchart axes)."""
    ax.plot([p[0], q[0]], [p[1], q[1]], color=color, lw=lw * 1.3, zorder=3)
    segs = _hatch_strokes(p, q, depth, outward, n)
    if segs:            # one polyline broken by NaN: one path, as matplotlib's LineCollection
        xs = [v for a, b in segs for v in (a[0], b[0], np.nan)]
        ys = [v for a, b in segs for v in (a[1], b[1], np.nan)]
        ax.plot(xs, ys, color=color, lw=lw * 0.7, zorder=3)


def draw_joint(ax, xy, r: float, color="k", lw=0.8, z=5):
    """A revolute pair: small open circle."""
    ax.circle(xy, r, facecolor="white", edgecolor=color, lw=lw, zorder=z)


class _Segments:
    """Distances from points to the nearest of segments (k, 2, 2), the segments' parts
    computed once (x and y apart: no reductions over a length-2 axis), as columns (k, 1):
    the points run along the arrays' long last axis (numpy's inner loop over the points,
    not over the few segments)."""

    def __init__(self, segs):
        a, b = segs[:, 0], segs[:, 1]
        d = b - a
        self.ax, self.ay = a[:, 0, None], a[:, 1, None]
        self.dx, self.dy = d[:, 0, None], d[:, 1, None]
        self.L2 = np.maximum(self.dx * self.dx + self.dy * self.dy, 1e-300)

    def dists(self, cx, cy):
        """Distance from each point (cx[i], cy[i]) to the nearest segment; the points a
        block at a time (:func:`_by_blocks`: the same numbers in bounded memory)."""
        return _by_blocks(self._dists, cx, cy, len(self.L2))

    def _dists(self, cx, cy):
        rx = cx - self.ax                          # (segments, points)
        ry = cy - self.ay
        t = rx * self.dx
        t += ry * self.dy
        t /= self.L2
        np.minimum(np.maximum(t, 0.0, out=t), 1.0, out=t)        # np.clip(t, 0, 1), without its wrapper
        # q = r - d t, |q|^2 (the same operations as written out, in place)
        rx -= self.dx * t
        ry -= self.dy * t
        rx *= rx
        ry *= ry
        rx += ry
        return np.sqrt(_min_over(rx, 0))


def segment_set(segments):
    """The segments' parts as place_labels computes them (_Segments), for several calls with
    the same segments (a panel's point letters and force names); None for none."""
    if isinstance(segments, _Segments) or segments is None:
        return segments
    return _Segments(np.asarray(segments, float).reshape(-1, 2, 2)) if len(segments) else None


# elements of one (segments or points, candidates) temporary of the label placement: 2**20
# (8 MB): the candidates a block at a time beyond it, so that many labels and many lines
# (a hundred extra points) need memory in proportion to their number, not its square
_BLOCK = 1 << 20


def _by_blocks(f, cx, cy, k: int):
    """``f(cx, cy)`` (a value per point, from a (k, points) temporary) for the points a
    block at a time, each block's temporary at most _BLOCK elements: every column is
    computed on its own (elementwise operations and a minimum down the column), so the
    values are those of one call."""
    n = len(cx)
    if k * n <= _BLOCK or n < 2:
        return f(cx, cy)
    step = max(1, _BLOCK // max(k, 1))
    return np.concatenate([f(cx[i:i + step], cy[i:i + step]) for i in range(0, n, step)])


def _point_dists(cx, cy, px, py):
    """Distance from each point (cx[i], cy[i]) to the nearest of the points (px, py)."""
    return _by_blocks(lambda x, y: _point_dists_block(x, y, px, py), cx, cy, len(px))


def _point_dists_block(cx, cy, px, py):
    dx = cx - px[:, None]                          # (points, candidates)
    dy = cy - py[:, None]
    dx *= dx
    dy *= dy
    dx += dy
    return np.sqrt(_min_over(dx, 0))


_min_over = np.minimum.reduce        # (the exact minimum: the same number in any order)
_gt = np.greater                     # of booleans: a > b is a & ~b, in one operation


_DIRS = np.array([[math.cos(t), math.sin(t)] for t in np.linspace(0, 2 * math.pi, 16, endpoint=False)])
_MULTS = (1.0, 1.5, 2.1)
_FAR = (3.0, 4.2, 5.8, 8.0, 11.0)          # rings tried when a label box finds no room nearer


def text_size(s: str, size_mm: float, sub: str | None = None) -> tuple[float, float]:
    """(width, height) mm of a label of font size size_mm (a subscript counted full
    width): the box the drawings keep clear, and the one the tests check."""
    return 0.6 * size_mm * (len(s) + len(sub or "")) + 0.6, 1.15 * size_mm


def place_labels(anchors, extent: float, avoid=(), step: float | None = None, segments=None,
                 boxes=(), sizes=None, taken=(), bounds=None):
    """Greedy label placement.

    anchors: list of (x, y, preferred_direction (dx, dy) or None).
    Returns list of (x, y) label positions: each label is put at one of 16
    candidate directions around its anchor (three distances), the one farthest
    from the already placed labels, the `avoid` points and the `segments`
    (lines of the drawing), preferring `preferred_direction`; never inside one
    of the `boxes` (centre, u-axis unit vector, half width, half height).
    With `sizes` [(w, h)] the labels are boxes: a label never overlaps another placed
    one nor one of `taken` (x0, y0, x1, y1), and stays inside `bounds` (x0, y0, x1, y1);
    when no place near its anchor is free it moves further out (rings up to 11 steps),
    and it is appended to `taken` (the caller's list) once placed.
    Vectorised over the candidates of all the anchors (numpy): what does not depend on
    the labels placed before (the distances to the `avoid` points and the segments, the
    bounds) is computed for every anchor at once; the distances to the placed labels and
    the overlaps with their boxes are brought up to date as each label is placed.
    """
    if step is None:
        step = 0.045 * extent
    taken = taken if isinstance(taken, list) else list(taken)
    na = len(anchors)
    if not na:
        return []
    offs, offx, offy, ring, dirs = _candidates(step, sizes is not None)
    ncand = len(offx)
    n_near = min(len(_DIRS) * len(_MULTS), ncand)   # the nearer rings' candidates come first
    ax = np.array([a[0] for a in anchors], float)
    ay = np.array([a[1] for a in anchors], float)
    CX = ax[:, None] + offx                    # (anchors, candidates): x + offx of each anchor
    CY = ay[:, None] + offy
    # the nearer rings' candidates apart: their scores are computed for every anchor; the
    # farther rings' only for an anchor whose nearer ones are not good enough (~1 in 10)
    CXn, CYn = (CX, CY) if n_near == ncand else (CX[:, :n_near].copy(), CY[:, :n_near].copy())
    big = 9 * step
    lim_l, lim_a, lim_s = 2.2 * step, 1.2 * step, 0.8 * step
    # the terms of the score that the placed labels do not change, (anchors, candidates)
    avoid_a = np.asarray([np.asarray(a, float) for a in avoid], float).reshape(-1, 2)
    avx, avy = avoid_a[:, 0].copy(), avoid_a[:, 1].copy()
    seg = segment_set(segments)                # (given as segment_set(...): made once for several calls)

    def fixed_terms(cx, cy):
        """min(distance to the avoided points, lim_a) + min(distance to the segments,
        lim_s) - the ring penalty of the candidates (cx, cy) (of one anchor or all)."""
        shape = cx.shape
        if len(avoid_a):
            t = np.minimum(_point_dists(cx.ravel(), cy.ravel(), avx, avy).reshape(shape), lim_a)
        else:
            t = np.full(shape, min(big, lim_a))
        if seg is not None:
            return t, np.minimum(seg.dists(cx.ravel(), cy.ravel()).reshape(shape), lim_s)
        return t, np.full(shape, lim_s)

    MDA, MDS = fixed_terms(CXn, CYn)
    D2 = np.full((na, n_near), np.inf)         # squared distance to the nearest placed label
    box_tests = [(np.asarray(bc, float), np.asarray(bu, float), np.array([-bu[1], bu[0]], float), hw, hh)
                 for (bc, bu, hw, hh) in boxes]
    nt = len(taken)
    if sizes is not None:
        # the label boxes' half sizes, repeated to (anchors, candidates): the operations with
        # CX, CY then run over same-shape arrays (numpy's fast loop, not a broadcast)
        h0s = [float(s[0]) / 2 for s in sizes[:na]]
        h1s = [float(s[1]) / 2 for s in sizes[:na]]
        H0 = np.repeat(np.array(h0s, float), ncand).reshape(-1, ncand)
        H1 = np.repeat(np.array(h1s, float), ncand).reshape(-1, ncand)
        h_max = max(map(abs, h0s + h1s))
        if bounds is not None:
            bx0, by0, bx1, by1 = bounds
            free_all = (CX - H0 >= bx0) & (CX + H0 <= bx1) & (CY - H1 >= by0) & (CY + H1 <= by1)
        else:
            free_all = np.ones((na, ncand), bool)
        for box in taken:                      # not overlapping a taken box (and inside the bounds)
            if bounds is None or not _beyond(box, bounds, h_max):
                _gt(free_all, _overlaps(CX, CY, H0, H1, box), free_all)
    every = np.arange(ncand)
    # the most a candidate of a farther ring can score (without the preferred direction's
    # term), with a margin for rounding
    far_top = lim_l + lim_a + lim_s - float(ring[n_near]) + 1e-9 * step if n_near < ncand else np.inf
    full_l = np.full(ncand, min(big, lim_l))
    ring_n, ring_f = ring[:n_near], ring[n_near:]
    lim_l0 = np.array(lim_l)                   # (a 0-d array: no scalar conversion in each np.minimum)
    # the preferred directions as unit vectors, every anchor's at once (the same divisions
    # as np.asarray(pref, float) / hypot(pref) one by one); norms[k] > 0: anchor k has one
    norms = [0.0 if a[2] is None else math.hypot(*a[2]) for a in anchors]
    if any(n > 0 for n in norms):
        units = np.array([a[2] if n > 0 else (0.0, 0.0) for a, n in zip(anchors, norms)], float)
        units /= np.array([n if n > 0 else 1.0 for n in norms], float)[:, None]
    px: list[float] = []                       # the labels placed so far
    py: list[float] = []
    out = []
    for k_a, (x, y, pref) in enumerate(anchors):
        ok = _clear_of_boxes(x, y, offs, box_tests, step)
        if sizes is not None:
            free = free_all[k_a] if nt or bounds is not None else None
            ok = _admissible(ok, free)
        best = None
        if ok is None:
            idx = every
        else:
            idx = ok.nonzero()[0]
        n_ok = len(idx)
        if n_ok:
            # the score of every candidate (the same sums, in the same order, as one by one)
            row = np.minimum(np.sqrt(D2[k_a]), lim_l0) if k_a else full_l[:n_near].copy()
            row += MDA[k_a]
            row += MDS[k_a]
            row -= ring_n
            lean = None
            if norms[k_a] > 0:
                # (dirs.take: the same rows as dirs[idx], without the fancy index's cost; the
                # product over exactly the admissible rows: its bits depend on them)
                lean = 0.5 * step * (dirs.take(idx, 0) @ units[k_a])
            else:
                pref = None
            # the nearer rings first: when one of them scores above the most a farther
            # one can, the farther ones are not looked at (the same choice: the first best)
            n_in = n_ok if n_near >= ncand else (n_near if ok is None else int(idx.searchsorted(n_near)))
            score = None
            if n_in:                           # (n_ok > 0 here)
                near = row if ok is None else row[idx[:n_in]]
                if lean is not None:
                    near = near + (lean if n_in == n_ok else lean[:n_in])
                k = int(near.argmax())         # (near[k]: near.max(), NaN as NaN, without the reduction)
                if n_in == n_ok or near[k] > (far_top if pref is None else far_top + 0.5 * step):
                    score = near
            if score is None:                  # the farther rings' scores too
                cxf, cyf = CX[k_a, n_near:], CY[k_a, n_near:]
                if k_a:
                    dx = cxf[:, None] - np.array(px)
                    dy = cyf[:, None] - np.array(py)
                    dx *= dx
                    dy *= dy
                    dx += dy
                    far = np.minimum(np.sqrt(dx.min(axis=1)), lim_l)
                else:
                    far = full_l[n_near:].copy()
                mda, mds = fixed_terms(cxf, cyf)
                far += mda
                far += mds
                far -= ring_f
                row = np.concatenate((row, far))
                score = row if ok is None else row[idx]
                if lean is not None:
                    score = score + lean
                k = int(score.argmax())
            if math.isfinite(score[k]):
                best = (float(CX[k_a, idx[k]]), float(CY[k_a, idx[k]]))
        if best is None:
            b = np.array([x, y], float) + _DIRS[4] * step * 2.5
            best = (float(b[0]), float(b[1]))
        last = k_a == na - 1
        if not last:                           # the later anchors' distances to this label
            dx = CXn[k_a + 1:] - best[0]
            dy = CYn[k_a + 1:] - best[1]
            dx *= dx
            dy *= dy
            dx += dy
            rest = D2[k_a + 1:]
            np.minimum(rest, dx, out=rest)
            px.append(best[0])
            py.append(best[1])
        if sizes is not None:
            h0, h1 = float(sizes[k_a][0]) / 2, float(sizes[k_a][1]) / 2
            box = (best[0] - h0, best[1] - h1, best[0] + h0, best[1] + h1)
            taken.append(box)
            nt += 1
            if not last:
                rest = free_all[k_a + 1:]
                _gt(rest, _overlaps(CX[k_a + 1:], CY[k_a + 1:], H0[k_a + 1:], H1[k_a + 1:], box), rest)
        out.append(best)
    return out


def _clear_of_boxes(x, y, offs, box_tests, step):
    """Whether each candidate (x, y) + offs keeps clear of the slider boxes (None: no boxes)."""
    if not box_tests:
        return None
    cand = np.array([x, y], float) + offs
    ok = np.ones(len(offs), bool)
    for bc, bu, bv, hw, hh in box_tests:
        r = cand - bc
        ok &= ~((np.abs(r @ bu) < hw + 0.5 * step) & (np.abs(r @ bv) < hh + 0.4 * step))
    return ok


def _admissible(ok, free):
    """The candidates to choose from: those clear of the slider boxes (``ok``, None: all)
    and free (clear of the taken boxes, inside the bounds; None: all); when none is both,
    the free ones, else those ``ok`` (the boxes' test yields); None: every candidate.
    (``count_nonzero`` for ``any``: the same answer without ndarray.any's Python wrapper.)"""
    if free is None:
        return None if ok is not None and not _count(ok) else ok
    if ok is None:
        return free if _count(free) else None
    if _count(ok & free):
        ok &= free
        return ok
    return free if _count(free) else ok


_count = np.count_nonzero


def _beyond(box, bounds, h_max) -> bool:
    """Whether ``box`` (x0, y0, x1, y1) lies beyond ``bounds`` (x0, y0, x1, y1) by more than a
    margin far above rounding (1e-9 of the numbers), so that no label box inside the bounds
    (half sizes at most h_max) can overlap it: its overlap test would leave every candidate
    inside the bounds free (a panel's title above the labels' bounds).  NaN: False."""
    x0, y0, x1, y1 = (float(v) for v in box)
    bx0, by0, bx1, by1 = (float(v) for v in bounds)
    m = 1e-9 * max(abs(x0), abs(y0), abs(x1), abs(y1), abs(bx0), abs(by0), abs(bx1), abs(by1), h_max)
    return x1 < bx0 - m or x0 > bx1 + m or y1 < by0 - m or y0 > by1 + m


def _overlaps(CX, CY, H0, H1, box):
    """Whether each candidate's label box (centres CX, CY (anchors, candidates), half
    sizes H0, H1 (the same shape, or (anchors, 1))) overlaps ``box`` (x0, y0, x1, y1), the box taken as its
    centre and half sizes (the same numbers as the one-by-one test)."""
    x0, y0, x1, y1 = (float(v) for v in box)
    cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
    hx, hy = (x1 - x0) / 2, (y1 - y0) / 2
    ov = np.abs(CX - cx) < H0 + hx
    ov &= np.abs(CY - cy) < H1 + hy
    return ov


_CANDIDATES: dict[tuple[float, bool], tuple] = {}


def _candidates(step: float, far: bool):
    """(offsets (n, 2), their x, their y, ring penalty, unit directions) of the label
    candidates around an anchor: 16 directions at each distance of _MULTS (and _FAR)."""
    key = (step, far)
    got = _CANDIDATES.get(key)
    if got is None:
        mults = _MULTS + (_FAR if far else ())
        offs = np.concatenate([_DIRS * step * m for m in mults])
        ring = 0.35 * step * (np.repeat(np.array(mults), len(_DIRS)) - 1)
        dirs = np.tile(_DIRS, (len(mults), 1))
        got = (offs, offs[:, 0].copy(), offs[:, 1].copy(), ring, dirs)
        if len(_CANDIDATES) > 64:
            _CANDIDATES.clear()
        _CANDIDATES[key] = got
    return got


# ---------------------------------------------------------------- linkage
def _pxy(entry, p):
    d = entry["points"][p]
    return np.array([float(d["x"]), float(d["y"])])


_XY = itemgetter("x", "y")


def points_xy(entries, p) -> np.ndarray:
    """(n, 2): the point ``p`` of each entry, ``np.array([_pxy(e, p) for e in entries])``
    without an array per entry (a fine grid has thousands): the numbers read as one flat
    run (x0, y0, x1, ...), each through float as by _pxy."""
    ds = [e["points"][p] for e in entries]
    if not ds:
        return np.array([])
    return np.fromiter(chain.from_iterable(map(_XY, ds)), float, 2 * len(ds)).reshape(-1, 2)


def mechanism_extent(entries, names=None) -> tuple[np.ndarray, np.ndarray]:
    """Bounding box (min xy, max xy) of the points over the entries."""
    if names is None:
        pts = list(chain.from_iterable(e["points"].values() for e in entries))
    else:
        pts = [d for e in entries for p, d in e["points"].items() if p in names]
    if not pts:
        return np.zeros(2), np.zeros(2)
    try:                            # read straight into the arrays (a fine grid has ~10^5)
        x = np.fromiter(map(itemgetter("x"), pts), float, len(pts))
        y = np.fromiter(map(itemgetter("y"), pts), float, len(pts))
    except TypeError:               # a None (NaN here) that fromiter refuses
        x = np.array(list(map(itemgetter("x"), pts)), float)
        y = np.array(list(map(itemgetter("y"), pts)), float)
    return np.array([x.min(), y.min()]), np.array([x.max(), y.max()])


def slider_ranges(entries, geom) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """For each slider on a fixed guide: the extreme pin positions along its guide."""
    out = {}
    for j in geom.joints:
        if j.kind != "P" or j.a != 0:
            continue
        s = geom.link(j.b)
        if s is None or not s.points:
            continue
        pin = s.points[0]
        pts = points_xy([e for e in entries if pin in e["points"]], pin)
        if not len(pts):
            continue
        ang = math.radians(float(entries[0]["links"][s.name]["angle"] or 0.0))
        u = np.array([math.cos(ang), math.sin(ang)])
        t = pts @ u
        out[s.name] = (pts[int(np.argmin(t))], pts[int(np.argmax(t))])
    return out


class SchemeView:
    """A drawing in model units (metres) on a direct-SVG canvas (svgdraw.Canvas): the
    kinematic scheme and the plan of positions.  ``unit`` metres per paper mm; the model
    point ``origin`` sits at the canvas' bottom left.  Line widths and font sizes in pt,
    marker sizes as matplotlib's (``ms`` pt across, plus a 1 pt edge), so the drawings
    look as they did when matplotlib drew them; ``to_svg`` writes the figure."""

    def __init__(self, width_mm: float, height_mm: float, origin, unit: float):
        from .svgdraw import Canvas
        self.cv = Canvas(width_mm, height_mm)
        self.origin = np.asarray(origin, float)
        self.unit = float(unit)

    def mm(self, xy) -> np.ndarray:
        """Model point(s) -> paper mm."""
        return (np.asarray(xy, float) - self.origin) / self.unit

    def line(self, pts, color="#000", lw=1.0, dash=None, z=2):
        """A polyline of model points; lw in pt; dash: (on, off, ...) in pt."""
        da = " ".join(_num(d / PT_PER_MM) for d in dash) if dash else None
        self.cv.polyline(self.mm(pts), color, lw / PT_PER_MM, da, z)

    def polygon(self, pts, face="none", edge="#000", lw=1.0, z=2):
        xy = self.mm(pts)
        if face != "none":      # just under the outlines of its layer (they are merged per style)
            self.cv.polygon(xy, face, z - 0.1)
        self.cv.polyline(xy, edge, lw / PT_PER_MM, z=z, closed=True)

    def circle(self, c, r, face="#fff", edge="#000", lw=1.0, z=5):
        """A circle of model radius r."""
        self.cv.circle(self.mm(c), r / self.unit, stroke=edge, fill=face, width=lw / PT_PER_MM, z=z)

    def dot(self, c, ms=2.5, color="#000", z=6):
        """A matplotlib 'o' marker of size ms."""
        self.cv.dot(self.mm(c), (ms + 1.0) / PT_PER_MM / 2, color, z)

    def text(self, xy, s, size=8.0, z=7, **kw):
        x, y = self.mm(xy)
        self.cv.text(float(x), float(y), s, size=size, z=z, **kw)

    def to_svg(self) -> str:
        return self.cv.to_svg()


def _num(x: float) -> str:
    return f"{x:.3f}".rstrip("0").rstrip(".") or "0"


def box_scale(lo, hi, width_mm, min_h=40.0, max_h=150.0, margin_mm=8.0) -> tuple[float, float, str]:
    """The height (mm), the scale (metres per paper mm, μl) and its GOST 2.302 label at
    which figure_for_box draws lo..hi (metres): the tables of a drawing state the
    lengths at the scale it is drawn at."""
    span = np.maximum(np.asarray(hi, float) - np.asarray(lo, float), 1e-12)
    h = float(np.clip((width_mm - 2 * margin_mm) * span[1] / span[0] + 2 * margin_mm, min_h, max_h))
    fit = max(span[0] / max(width_mm - 2 * margin_mm, 1.0), span[1] / max(h - 2 * margin_mm, 1.0))
    model, label = drawing_scale(fit * 1000.0)
    return h, model / 1000.0, label


def figure_for_box(lo, hi, width_mm, min_h=40.0, max_h=150.0, margin_mm=8.0, lang="en"):
    """A drawing (SchemeView) showing lo..hi (metres), centred, at the largest GOST 2.302
    scale that leaves the margin, stated at its top left ('μl = 0.005 m/mm (M 1:5)');
    returns (view, unit: metres per paper mm, the statement's box (x0, y0, x1, y1) in
    metres: the labels keep clear of it)."""
    lo = np.asarray(lo, float)
    hi = np.asarray(hi, float)
    h, unit, label = box_scale(lo, hi, width_mm, min_h, max_h, margin_mm)
    c = (lo + hi) / 2
    view = SchemeView(width_mm, h, c - unit * np.array([width_mm / 2, h / 2]), unit)
    from ..messages import unit as spelt
    m, mm = spelt("m", lang), spelt("mm", lang)
    title = f"{mu_text('l', unit, m, mm)}  ({scale_mark(lang)} {label})"
    size = 7.0
    fs = size / PT_PER_MM
    x0, top = 0.01 * width_mm, 0.99 * h          # the text's top left, as matplotlib put it
    view.cv.text(x0, top - 0.5 * fs, title, size=size, anchor="start", z=8)
    w, th = text_size(title, fs)
    box = tuple(float(v) for v in np.tile(view.origin, 2) + unit * np.array([x0, top - th, x0 + w, top]))
    return view, unit, box


def draw_mechanism(view: SchemeView, geom, entry, unit: float, *, labels=True, numbers=True,
                   color="k", lw=1.5, light=False, ranges=None, label_fs=8, taken=(), placed=None):
    """Draw the linkage of one kinematics entry on `view` (model units: metres).

    unit: metres per paper millimetre (sets pivot/block/label sizes).
    light: thin grey drawing (for the overlaid positions of the positions plan).
    ranges: output of slider_ranges() so fixed guides cover the whole stroke.
    taken: boxes (x0, y0, x1, y1, data units) of texts already there: the labels keep clear.
    placed: a list that gets `taken` and the boxes of the labels placed here (for labels
    placed after them: the instant centres of the worked position).
    Returns a list of (label, xy) placed, for the caller's bookkeeping.
    """
    size = 50.0 * unit
    P = entry["points"]
    jr = 1.1 * unit
    ground_size = 2.2 * unit
    bh = 5.5 * unit
    bw = 9.0 * unit
    lwl = 0.6 if light else lw
    col = "0.55" if light else color
    anchors = []       # (text, xy, pref dir)
    avoid = []
    segs = []
    boxes = []
    # bars
    for l in geom.links:
        if l.kind != "bar":
            continue
        pts = [p for p in l.points if p in P]
        if len(pts) < 2:
            continue
        xy = np.array([_pxy(entry, p) for p in pts])
        c = xy.mean(axis=0)
        main = xy[:2]
        d = main[1] - main[0]
        n = np.linalg.norm(d)
        u = d / n if n > 0 else np.array([1.0, 0.0])
        off = [abs(float(u[0] * (x - main[0])[1] - u[1] * (x - main[0])[0])) for x in xy]
        if len(xy) > 2 and max(off) > 0.02 * size:
            # a body link: a closed outline through its points (convex hull order)
            ang = np.arctan2(xy[:, 1] - c[1], xy[:, 0] - c[0])
            poly = xy[np.argsort(ang)]
            view.polygon(poly, face="none" if light else "0.93", edge=col, lw=lwl, z=2)
            segs.extend([(poly[k], poly[(k + 1) % len(poly)]) for k in range(len(poly))])
        else:
            t = (xy - main[0]) @ u
            a0, a1 = main[0] + u * t.min(), main[0] + u * t.max()
            view.line([a0, a1], col, lwl, z=2)
            segs.append((a0, a1))
        if numbers and not light:
            nrm = np.array([-u[1], u[0]])
            mid = (main[0] + main[1]) / 2
            anchors.append((str(l.index), mid, nrm, True))
    # sliders and guides
    for j in geom.joints:
        if j.kind != "P":
            continue
        la, lb = geom.link(j.a), geom.link(j.b)
        s = lb if (lb is not None and lb.kind == "slider") else la
        if s is None or not s.points or s.points[0] not in P:
            continue
        pin = _pxy(entry, s.points[0])
        ang = float(entry["links"][s.name]["angle"] or 0.0)
        a = math.radians(ang)
        u = np.array([math.cos(a), math.sin(a)])
        v = np.array([-u[1], u[0]])
        if j.a == 0 and not light:
            lo, hi = (ranges or {}).get(s.name, (pin, pin))
            t0 = float((lo - pin) @ u) - bw
            t1 = float((hi - pin) @ u) + bw
            g0, g1 = pin + u * t0, pin + u * t1
            view.line([g0, g1], col, 0.5, dash=(4.0, 1.0, 0.5, 1.0), z=1)     # dash-dot axis
            _hatch(view, g0 - v * bh / 2, g1 - v * bh / 2, 0.35 * bh, -v, lw=0.8, color=col)
            segs.append((g0 - v * bh * 0.7, g1 - v * bh * 0.7))
        from .svgdraw import block_corners
        view.polygon(block_corners(pin, ang, bw * (0.8 if light else 1.0), bh * (0.8 if light else 1.0)),
                     face="none" if light else "#fff", edge=col, lw=lwl * 0.8, z=4)
        boxes.append((pin, u, bw / 2, bh / 2))
        for sgn in (-1, 1):
            segs.append((pin - u * bw / 2 + sgn * v * bh / 2, pin + u * bw / 2 + sgn * v * bh / 2))
        if numbers and not light:
            anchors.append((str(s.index), pin, v, True))
    # revolute pairs and ground pivots
    done = set()
    for j in geom.joints:
        if j.kind != "R" or not j.point or j.point not in P or j.point in done:
            continue
        done.add(j.point)
        xy = _pxy(entry, j.point)
        if j.point in geom.ground and not light:
            _ground(view, xy, ground_size, color=col)
            segs.append((xy + np.array([-1.6, -3.5]) * ground_size, xy + np.array([1.6, -3.5]) * ground_size))
            segs.append((xy, xy + np.array([0, -3.5]) * ground_size))
        view.circle(xy, jr * (0.7 if light else 1.0), edge=col, lw=lwl * 0.6, z=5)
        avoid.append(xy)
    # centres of mass
    for l in geom.links:
        if l.com and l.com in P and not light:
            xy = _pxy(entry, l.com)
            if any(np.linalg.norm(xy - _pxy(entry, p)) < 1e-9 for p in l.points if p in P):
                continue
            view.dot(xy, 2.5, col, z=6)
            anchors.append((l.com, xy, None, False))
    if labels and not light:
        for p in sorted(done | {q for l in geom.links for q in l.points if q in P}):
            xy = _pxy(entry, p)
            anchors.insert(0, (p, xy, None, False))
    if not anchors:
        if placed is not None:
            placed.extend(taken)
        return []
    fs_mm = label_fs * 25.4 / 72.0
    sizes = [tuple(unit * np.array(text_size("00" if a[3] else a[0], fs_mm * (0.95 if a[3] else 1.0))))
             for a in anchors]
    tk = list(taken)
    pos = place_labels([(a[1][0], a[1][1], a[2]) for a in anchors], size,
                       avoid=avoid + [a[1] for a in anchors], step=3.6 * unit, segments=segs,
                       boxes=boxes, sizes=sizes, taken=tk)
    if placed is not None:
        placed.extend(tk)
    out = []
    seen = set()
    for (text, xy, _, is_num), (x, y) in zip(anchors, pos):
        if (text, is_num) in seen:
            continue
        seen.add((text, is_num))
        if is_num:
            # a link number in a thin circle (as matplotlib's circle box, pad 0.15 em)
            fs = label_fs - 1
            r = max(0.65 * fs, (0.6 * fs * len(text) + 0.3 * fs) / 2) / PT_PER_MM * unit
            view.circle((x, y), r, face="#fff", edge="0.3", lw=0.5, z=7)
            view.text((x, y), text, size=fs, z=7)
        else:
            view.text((x, y), text.translate(_SUBS), size=label_fs, z=7, italic=True)
        out.append((text, (x, y)))
    return out


def _ground(view: SchemeView, xy, size: float, lw=0.8, color="k"):
    """A fixed pivot (base below) on a SchemeView, as draw_ground draws it."""
    sides, (e1, e2), d = _ground_lines(xy, size)
    view.line([sides[0][1], sides[0][0], sides[1][1]], color, lw, z=3)
    _hatch(view, e1, e2, size * 0.7, d, lw=lw, color=color)


def _hatch(view: SchemeView, p, q, depth, outward, lw=0.8, color="k"):
    """A hatched ground line on a SchemeView, as draw_hatch draws it."""
    view.line([p, q], color, lw * 1.3, z=3)
    for a0, a1 in _hatch_strokes(p, q, depth, outward):
        view.line([a0, a1], color, lw * 0.7, z=3)
