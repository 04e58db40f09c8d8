"""Figure helpers of the report: matplotlib (Agg) -> inline SVG, nice scales,
and the drawing primitives of kinematic schemes (ground pivots with hatching,
slider blocks, guides, joints, plan vectors with labels).

matplotlib is imported lazily (inside functions): importing this module is cheap.
Text uses DejaVu Sans (ships with matplotlib, has Cyrillic and Greek).
"""
from __future__ import annotations

import io
import math
import re

import numpy as np

MM = 1.0 / 25.4  # inch per mm

_STYLE = {
    "font.family": "DejaVu Sans",
    "font.size": 8,
    "axes.titlesize": 9,
    "axes.labelsize": 8,
    "xtick.labelsize": 7,
    "ytick.labelsize": 7,
    "legend.fontsize": 7,
    "lines.linewidth": 1.0,
    "svg.fonttype": "none",      # text stays text: small, searchable SVG
    "svg.hashsalt": None,        # random clip-path ids: unique across inline SVGs
    "axes.unicode_minus": True,
}

_configured = False


def plt():
    """The pyplot module with the Agg backend and the report style."""
    global _configured
    import matplotlib
    if not _configured:
        matplotlib.use("Agg", force=True)
        matplotlib.rcParams.update(_STYLE)
        _configured = True
    import matplotlib.pyplot as _plt
    return _plt


def new_figure(width_mm: float = 170.0, height_mm: float = 100.0, **kw):
    """A new figure of the given size in millimetres; returns (fig, ax or axes)."""
    p = plt()
    fig, ax = p.subplots(figsize=(width_mm * MM, height_mm * MM), **kw)
    return fig, ax


_HEAD = re.compile(r"^.*?(<svg\b)", re.S)
_SIZE = re.compile(r'(<svg\b[^>]*?)\swidth="([0-9.]+)pt"\s+height="([0-9.]+)pt"', re.S)


def svg(fig) -> str:
    """Render a matplotlib figure as an inline SVG string and close the figure.

    The XML prolog/doctype are stripped; width/height stay in pt (printed at
    the figure's real size) and the CSS caps them at the text width.
    """
    buf = io.StringIO()
    try:
        fig.savefig(buf, format="svg", metadata={"Date": None, "Creator": None})
    finally:
        plt().close(fig)
    text = _HEAD.sub(r"\1", buf.getvalue(), count=1)
    text = _SIZE.sub(r'\1 class="fig" width="\2pt" height="\3pt"', text, count=1)
    return text


# ---------------------------------------------------------------- scales
NICE_SERIES = (1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0)


def nice_scale(value: float, series=NICE_SERIES) -> float:
    """Smallest 'nice' number >= value from series x 10^k (scale factors as
    students choose them: mu = v_A / pa rounded up, so pa <= its target).

    >>> nice_scale(0.012566)
    0.015
    """
    if not (value > 0 and math.isfinite(value)):
        return 1.0
    k = math.floor(math.log10(value))
    for e in (k - 1, k, k + 1):
        base = 10.0 ** e
        for s in series:
            cand = float(f"{s * base:.12g}")
            if cand >= value * (1 - 1e-12):
                return cand
    return float(f"{10.0 ** (k + 1):.12g}")


# ---------------------------------------------------------------- primitives
def draw_ground(ax, xy, size: float, angle_deg: float = -90.0, lw=0.8, color="k"):
    """A fixed pivot: small triangle ending in a hatched base, pointing away
    from angle_deg (default: base below the pivot)."""
    x, y = xy
    a = math.radians(angle_deg)
    d = np.array([math.cos(a), math.sin(a)])      # from pivot towards the base
    nrm = np.array([-d[1], d[0]])
    c = np.array([x, y])
    h = 1.6 * size
    b1 = c + d * h + nrm * size
    b2 = c + d * h - nrm * size
    ax.plot([c[0], b1[0]], [c[1], b1[1]], color=color, lw=lw, zorder=3)
    ax.plot([c[0], b2[0]], [c[1], b2[1]], color=color, lw=lw, zorder=3)
    e1 = c + d * h + nrm * 1.6 * size
    e2 = c + d * h - nrm * 1.6 * size
    draw_hatch(ax, e1, e2, size * 0.7, d, lw=lw, color=color)


def draw_hatch(ax, p, q, depth, outward, lw=0.8, color="k", n=None):
    """A ground line p-q with short hatch strokes on the side `outward`."""
    p = np.asarray(p, float)
    q = np.asarray(q, float)
    outward = np.asarray(outward, float)
    outward = outward / (np.linalg.norm(outward) or 1.0)
    ax.plot([p[0], q[0]], [p[1], q[1]], color=color, lw=lw * 1.3, zorder=3)
    L = float(np.linalg.norm(q - p))
    if L <= 0:
        return
    t = (q - p) / L
    if n is None:
        n = max(3, int(L / depth * 1.2))
    segs = []
    for s in np.linspace(0, L, n + 1)[1:]:
        a0 = p + t * s
        a1 = a0 + outward * depth - t * depth
        segs.append([a0, a1])
    from matplotlib.collections import LineCollection
    ax.add_collection(LineCollection(segs, colors=color, linewidths=lw * 0.7, zorder=3))


def draw_joint(ax, xy, r: float, color="k", lw=0.8, z=5):
    """A revolute pair: small open circle."""
    from matplotlib.patches import Circle
    ax.add_patch(Circle(xy, r, facecolor="white", edgecolor=color, lw=lw, zorder=z))


def draw_block(ax, xy, angle_deg: float, w: float, h: float, color="k", lw=0.9,
               face="white", z=4):
    """A slider block (rectangle w along the guide x h), centred at xy."""
    from matplotlib.patches import Polygon
    a = math.radians(angle_deg)
    u = np.array([math.cos(a), math.sin(a)])
    v = np.array([-u[1], u[0]])
    c = np.asarray(xy, float)
    pts = [c + u * w / 2 + v * h / 2, c - u * w / 2 + v * h / 2,
           c - u * w / 2 - v * h / 2, c + u * w / 2 - v * h / 2]
    ax.add_patch(Polygon(pts, closed=True, facecolor=face, edgecolor=color, lw=lw, zorder=z))


def arrow(ax, p, q, color="k", lw=1.0, head=None, z=4, style="-|>", ls="-"):
    """A vector p -> q (data coordinates); head size in points."""
    from matplotlib.patches import FancyArrowPatch
    if head is None:
        head = 6
    if math.hypot(q[0] - p[0], q[1] - p[1]) <= 1e-12:
        return
    ax.add_patch(FancyArrowPatch(tuple(p), tuple(q), arrowstyle=style,
                                 mutation_scale=head, color=color, lw=lw,
                                 linestyle=ls, shrinkA=0, shrinkB=0, zorder=z))


def place_labels(anchors, extent: float, avoid=(), step: float | None = None):
    """Greedy label placement.

    anchors: list of (x, y, preferred_direction (dx, dy) or None).
    Returns list of (x, y) label positions: each label is put at one of 12
    candidate directions around its anchor, the one farthest from the already
    placed labels and the `avoid` points, preferring `preferred_direction`.
    """
    if step is None:
        step = 0.045 * extent
    placed: list[np.ndarray] = []
    avoid = [np.asarray(a, float) for a in avoid]
    out = []
    dirs = [np.array([math.cos(t), math.sin(t)]) for t in np.linspace(0, 2 * math.pi, 12, endpoint=False)]
    for (x, y, pref) in anchors:
        c = np.array([x, y], float)
        best = None
        best_score = -1e300
        pv = None
        if pref is not None:
            n = math.hypot(*pref)
            if n > 0:
                pv = np.array(pref, float) / n
        for mult in (1.0, 1.6):
            for d in dirs:
                cand = c + d * step * mult
                others = placed + avoid
                dmin = min((float(np.linalg.norm(cand - o)) for o in others), default=extent)
                score = min(dmin, 2.5 * step) - 0.3 * step * (mult - 1)
                if pv is not None:
                    score += 0.35 * step * float(d @ pv)
                if score > best_score:
                    best_score, best = score, cand
        placed.append(best)
        out.append((float(best[0]), float(best[1])))
    return out
