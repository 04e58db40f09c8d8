"""Line charts written directly as SVG: the report's diagrams over the cycle
(kinematic diagrams, loads, balancing moment and reactions, the flywheel's
diagrams and the energy-mass diagram), and, laid out as matplotlib laid them out
(``mpl=True``, report.figures.new_figure / figure_at_scale), the figures matplotlib
drew before: the cam's diagrams, construction and profile, the gear mesh, sliding and
blocking contour, the planetary scheme, the two-DOF scheme and charts (patches,
'///' hatches, spans, markers, annotations with arrows: ``fill``, ``fill_rings``,
``rectangle``, ``circle``, ``axvspan``, ``annotate(arrowprops=...)``).

The interface is the small part of matplotlib's the report used for them
(``subplots``, ``ax.plot`` with format strings, ``axhline``/``axvline``,
``annotate``, labels, title, grid, ``set_xlim``/``set_xticks``, ``legend`` with
``loc="best"`` or outside on the right, ``set_aspect("equal")``), so a section
changes one line to use it; the look follows the report's matplotlib style
(DejaVu Sans, 7-9 pt text, tab10 colours, 5 % margins, nice ticks).  Why: a
matplotlib figure of this kind costs ~0.1-0.3 s to make and write as SVG (plus
~0.4 s to import matplotlib once), and its SVG has a separate element per tick;
these are made in milliseconds and are a few kB.

Coordinates inside the SVG are millimetres (viewBox), y down; width/height in pt.
"""
from __future__ import annotations

import hashlib
import math
import re
from html import escape

import numpy as np

from ..numfmt import localize
from .svgdraw import FONT, PT_PER_MM, _f, _w, css_color, trim

MM_PER_PT = 1.0 / PT_PER_MM
TAB10 = ("#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f",
         "#bcbd22", "#17becf")
TICK_PT, LABEL_PT, TITLE_PT, LEGEND_PT = 7.0, 8.0, 9.0, 7.0
CHAR_EM = 0.6                       # mean advance of a DejaVu Sans character, em


def _text_w(s: str, size_pt: float) -> float:
    """Approximate width (mm) of a label at size_pt (DejaVu Sans)."""
    plain = re.sub(r"[${}_^\\]", "", s)
    return len(plain) * CHAR_EM * size_pt * MM_PER_PT


def _num(v: float, decimals: int) -> str:
    s = f"{v:.{decimals}f}"
    if float(s) == 0:
        s = f"{0.0:.{decimals}f}"
    return localize(s).replace("-", "\u2212")


def nice_ticks(lo: float, hi: float, nbins: int) -> np.ndarray:
    """Ticks at multiples of 1, 2, 2.5, 5 x 10^k inside [lo, hi], at most nbins+1 of them."""
    span = hi - lo
    if not (span > 0 and math.isfinite(span)):
        return np.array([lo])
    raw = span / max(nbins, 1)
    k = math.floor(math.log10(raw))
    step = None
    for s in (1.0, 2.0, 2.5, 5.0, 10.0):
        if s * 10.0 ** k >= raw * (1 - 1e-9):
            step = s * 10.0 ** k
            break
    first = math.ceil(lo / step - 1e-9)
    last = math.floor(hi / step + 1e-9)
    return np.arange(first, last + 1) * step


def _knots(x, y):
    """(x, y as (n, d), whether y was flat, the intervals h, the slopes d) of a spline's knots."""
    x = np.asarray(x, float)
    y = np.asarray(y, float)
    Y = y.reshape(len(x), -1)
    h = np.diff(x)
    return x, Y, y.ndim == 1, h, np.diff(Y, axis=0) / h[:, None]


def periodic_spline(x, y, t) -> np.ndarray:
    """The periodic cubic spline through (x[i], y[i]) (y[-1] == y[0]; y may be (n, d))
    evaluated at t (taken modulo the period): the same curve as scipy's
    CubicSpline(x, y, bc_type="periodic"), without importing scipy for a drawing.
    Second derivatives M from the cyclic system
    h[i-1] M[i-1] + 2 (h[i-1] + h[i]) M[i] + h[i] M[i+1] = 6 (d[i] - d[i-1])."""
    x, Y, flat, h, d = _knots(x, y)
    m = len(h)
    A = np.zeros((m, m))
    for i in range(m):
        A[i, (i - 1) % m] += h[i - 1]
        A[i, i] += 2.0 * (h[i - 1] + h[i])
        A[i, (i + 1) % m] += h[i]
    M = np.linalg.solve(A, 6.0 * (d - np.roll(d, 1, axis=0)))
    M = np.vstack([M, M[:1]])
    t = np.asarray(t, float)
    S = _cubic(x, Y, M, x[0] + np.mod(t - x[0], x[-1] - x[0]))
    return S[:, 0] if flat else S


def _cubic(x, Y, M, tt) -> np.ndarray:
    """The cubic spline of knots x, values Y (n, d) and second derivatives M (n, d) at tt
    (within [x[0], x[-1]])."""
    h = np.diff(x)
    j = np.clip(np.searchsorted(x, tt, side="right") - 1, 0, len(h) - 1)
    hj = h[j][:, None]
    a = (x[j + 1] - tt)[:, None]
    b = (tt - x[j])[:, None]
    return (M[j] * a ** 3 + M[j + 1] * b ** 3) / (6.0 * hj) + (Y[j] / hj - M[j] * hj / 6.0) * a \
        + (Y[j + 1] / hj - M[j + 1] * hj / 6.0) * b


def natural_spline(x, y, t) -> np.ndarray:
    """The natural cubic spline through (x[i], y[i]) (y may be (n, d); M = 0 at both ends)
    evaluated at t in [x[0], x[-1]]: an open curve, as scipy's CubicSpline(x, y,
    bc_type="natural"), for a path that does not close (a linkage analysed over an input
    range).  Second derivatives M from the tridiagonal system
    h[i-1] M[i-1] + 2 (h[i-1] + h[i]) M[i] + h[i] M[i+1] = 6 (d[i] - d[i-1]), i = 1..n-2."""
    x, Y, flat, h, d = _knots(x, y)
    m = len(h)
    M = np.zeros_like(Y)
    if m > 1:
        A = np.zeros((m - 1, m - 1))
        for i in range(m - 1):
            A[i, i] = 2.0 * (h[i] + h[i + 1])
            if i > 0:
                A[i, i - 1] = h[i]
            if i < m - 2:
                A[i, i + 1] = h[i + 1]
        M[1:-1] = np.linalg.solve(A, 6.0 * (d[1:] - d[:-1]))
    S = _cubic(x, Y, M, np.clip(np.asarray(t, float), x[0], x[-1]))
    return S[:, 0] if flat else S


def spline_through(xy, closed: bool, samples: int) -> np.ndarray:
    """A point's trajectory through its positions ``xy`` (n, 2), taken in order: ``samples``
    points of the periodic spline back to the first position (``closed``, a full turn) or of
    the natural spline from the first to the last (a linkage analysed over an input range)."""
    xy = np.asarray(xy, float)
    n = len(xy)
    if closed:
        return periodic_spline(np.arange(n + 1, dtype=float), np.vstack([xy, xy[:1]]), np.linspace(0, n, samples))
    return natural_spline(np.arange(n, dtype=float), xy, np.linspace(0, n - 1, samples))


def _nbins(length_mm: float, per_label: float) -> int:
    """How many tick intervals fit (matplotlib's 'auto': a label per 3 font sizes along
    x, per 2 along y; at most 9)."""
    return max(1, min(9, int(length_mm * PT_PER_MM / (TICK_PT * per_label))))


def tick_labels(ticks) -> list[str]:
    """Fewest decimals that show every tick exactly (as matplotlib's labels)."""
    ticks = np.asarray(ticks, float)
    if not ticks.size:
        return []
    for d in range(0, 7):
        if np.all(np.abs(np.round(ticks, d) - ticks) <= 1e-9 * max(1.0, float(np.max(np.abs(ticks))))):
            return [_num(t, d) for t in ticks]
    return [f"{t:.3g}".replace("-", "\u2212") for t in ticks]


_MATH = re.compile(r"\$([^$]*)\$")
_TEX = re.compile(r"\\([A-Za-z]+)")
_GREEK = dict(zip(("alpha", "beta", "gamma", "delta", "epsilon", "varepsilon", "eta", "theta", "lambda", "mu",
                   "rho", "sigma", "tau", "phi", "varphi", "psi", "omega", "Delta", "Sigma", "Omega"),
                  "αβγδεεηθλμρστϕφψωΔΣΩ"))
_SCRIPT = re.compile(r"([_^])(\{[^}]*\}|.)")


def _txt(s) -> str:
    """A label's text: a string as given (a catalogue's :class:`~.notation.Term` stays one,
    its notation drawn with subscripts), anything else as ``str``."""
    return s if isinstance(s, str) else str(s)


def text_body(s: str, size_mm: float) -> str:
    """SVG text content of a label; $X_{ab}$ (matplotlib mathtext) -> italic X with a
    lowered smaller 'ab' (^ raised); its numbers as the current language writes them.
    A catalogue's text (:class:`~.notation.Term`) has its notation's subscripts lowered
    too (X_ab upright as the report's text writes it), the values put into it as written."""
    from .notation import Term, kept, parts
    term = isinstance(s, Term)
    if term and s._source is not None:
        s = s._source
    s = localize(s)
    if "\\" in s:                                   # mathtext's Greek letters: $\\lambda_1$
        s = _TEX.sub(lambda m: _GREEK.get(m.group(1), m.group(0)), s)
    segs: list[tuple[str, float, bool]] = []       # (text, baseline shift in em, italic)
    pos = 0
    for m in _MATH.finditer(s):
        segs.append((s[pos:m.start()], 0.0, False))
        body, p = m.group(1), 0
        for sm in _SCRIPT.finditer(body):
            segs.append((body[p:sm.start()], 0.0, True))
            segs.append((sm.group(2).strip("{}"), 0.3 if sm.group(1) == "_" else -0.4, False))
            p = sm.end()
        segs.append((body[p:], 0.0, True))
        pos = m.end()
    segs.append((s[pos:], 0.0, False))
    if term:
        segs = [piece for g in segs for piece in
                ([(p, 0.3 if low else 0.0, False) for p, low in parts(g[0])] if g[1] == 0.0 and not g[2]
                 else [(kept(g[0]), g[1], g[2])])]
    segs = [g for g in segs if g[0]]
    if all(g[1] == 0.0 and not g[2] for g in segs):
        return escape(kept(s) if term else s)
    out, cur = [], 0.0
    for text, shift, italic in segs:
        attrs = []
        if shift != cur:
            attrs.append(f'dy="{_f((shift - cur) * size_mm)}"')
            cur = shift
        if shift:
            attrs.append(f'font-size="{_f(0.72 * size_mm)}"')
        if italic:
            attrs.append('font-style="italic"')
        out.append(f'<tspan {" ".join(attrs)}>{escape(text)}</tspan>' if attrs else escape(text))
    return "".join(out)


def _parse_fmt(fmt: str) -> tuple[str | None, str | None, str | None]:
    """matplotlib format string -> (colour, marker, linestyle)."""
    color = marker = ls = None
    for sty in ("--", "-.", "-", ":"):
        if sty in fmt:
            ls = sty
            fmt = fmt.replace(sty, "", 1)
            break
    for ch in fmt:
        if ch in "bgrcmykw":
            color = ch
        elif ch in "o.s^+":
            marker = ch
    if ls is None and marker is None:
        ls = "-"
    return color, marker, ls


_DASH = {"--": "3.7 1.6", ":": "1 1.65", "-.": "6.4 1.6 1 1.6"}   # x linewidth (matplotlib's)


class _Box:
    """matplotlib's Bbox, as far as the report reads one: x0, y0, x1, y1, width, height."""

    def __init__(self, x0, y0, x1, y1):
        self.x0, self.y0, self.x1, self.y1 = float(x0), float(y0), float(x1), float(y1)
        self.width, self.height = self.x1 - self.x0, self.y1 - self.y0


class _ToDisplay:
    """ax.transData: data -> display points (dpi 72, origin at the bottom left)."""

    def __init__(self, ax):
        self.ax = ax

    def transform(self, pts):
        pts = np.asarray(pts, float).reshape(-1, 2)
        X, Y = self.ax.to_mm(pts[:, 0], pts[:, 1])
        return np.c_[X * PT_PER_MM, (self.ax.fig.h - Y) * PT_PER_MM]


class _Line:
    __slots__ = ("x", "y", "color", "lw", "ls", "marker", "ms", "label", "clip", "z", "cap")

    def __init__(self, **kw):
        for k in self.__slots__:
            setattr(self, k, kw.get(k))


class _Patch:
    """A filled or outlined shape in data coordinates (matplotlib's patches as far as the
    report draws them): ``rings`` closed polygons (holes by the even-odd rule), or a
    circle (``circle`` = (centre x, centre y, radius)); ``hatch``: '///' strokes."""
    __slots__ = ("rings", "circle", "face", "edge", "lw", "z", "hatch", "clip", "label", "ls")

    def __init__(self, **kw):
        for k in self.__slots__:
            setattr(self, k, kw.get(k))
        self.clip = kw.get("clip", True)

    def points(self):
        if self.circle is not None:
            x, y, r = self.circle
            return np.array([x - r, x + r]), np.array([y - r, y + r])
        pts = np.concatenate([np.asarray(r, float).reshape(-1, 2) for r in self.rings])
        return pts[:, 0], pts[:, 1]


class _Note:
    """A text of the axes (annotate / text): at the data point (x, y), the y an axes fraction when
    ``frac_y``; offset (dx, dy) points; ha/va as matplotlib's; an arrow from ``arrow_from``
    (data) to (x, y) when given."""
    __slots__ = ("s", "x", "y", "dx", "dy", "color", "pt", "va", "ha", "frac_y", "arrow_from", "arrow_lw",
                 "arrow_color")

    def __init__(self, **kw):
        for k in self.__slots__:
            setattr(self, k, kw.get(k))


class Axes:
    def __init__(self, fig):
        self.fig = fig
        self.lines: list[_Line] = []
        self.hlines: list[tuple] = []
        self.vlines: list[tuple] = []
        self.notes: list[_Note] = []
        self.patches: list[_Patch] = []
        self.spans: list[tuple] = []        # axvspan: (x0, x1, colour)
        self.artists: list = []             # lines and patches in the order drawn (by zorder, then added)
        self.axis_on = True
        self.yticks = None
        self.tick_pt = TICK_PT
        self.title_at = None                # (y fraction, va) of a title inside the axes
        self.title = self.xlabel = self.ylabel = None
        self.title_pt = TITLE_PT
        self.side_titles: dict[str, tuple[str, float]] = {}     # loc 'left'/'right': (text, pt)
        self.grid_on = False
        self.grid_style = ("#b0b0b0", 0.8)
        self.xlim = self.ylim = None
        self.xticks = None
        self.legend_kw = None
        self.equal = False
        self.show_xticklabels = True
        self._cycle = 0
        self.box = (0.0, 0.0, 1.0, 1.0)      # x0, y0 (top), w, h in mm
        self.view = (0.0, 1.0, 0.0, 1.0)

    # ------------------------------------------------------------ matplotlib-like API
    def plot(self, *args, **kw):
        x, y, fmt = None, None, ""
        args = list(args)
        if args and isinstance(args[-1], str):
            fmt = args.pop()
        if len(args) == 1:
            y = np.asarray(args[0], float)
            x = np.arange(len(y), dtype=float)
        else:
            x, y = np.asarray(args[0], float), np.asarray(args[1], float)
        fc, marker, ls = _parse_fmt(fmt) if fmt else (None, None, "-")
        ls = kw.get("ls", kw.get("linestyle", ls))
        if ls in ("none", "None", "", " "):
            ls = None
        marker = kw.get("marker", marker)
        color = kw.get("color", kw.get("c", fc))
        if color is None:
            color = TAB10[self._cycle % len(TAB10)]
            self._cycle += 1
        ms = kw.get("ms", kw.get("markersize", 6.0))
        x, y = np.atleast_1d(x).astype(float), np.atleast_1d(y).astype(float)
        ln = _Line(x=x, y=y, color=css_color(color), lw=float(kw.get("lw", kw.get("linewidth", 1.0))),
                   ls=ls, marker=marker, ms=float(ms), label=kw.get("label"),
                   clip=kw.get("clip_on", True), z=kw.get("zorder", 2), cap=kw.get("solid_capstyle", "butt"))
        self.lines.append(ln)
        self.artists.append(ln)

    def _patch(self, **kw):
        p = _Patch(**kw)
        self.patches.append(p)
        self.artists.append(p)
        return p

    def fill(self, x, y, color="C0", lw=0.0, zorder=1, **kw):
        """A filled polygon (matplotlib's ax.fill), no outline when lw is 0."""
        pts = np.column_stack([np.asarray(x, float), np.asarray(y, float)])
        c = css_color(kw.get("facecolor", color))
        self._patch(rings=[pts], face=c, edge=c if lw else None, lw=float(lw), z=zorder)

    def fill_rings(self, rings, facecolor, zorder=1):
        """A filled region of outer rings and holes (a compound path: even-odd rule)."""
        self._patch(rings=[np.asarray(r, float) for r in rings], face=css_color(facecolor), edge=None, lw=0.0,
                    z=zorder)

    def rectangle(self, xy, width, height, fill=False, lw=1.0, color="k", hatch=None, zorder=1):
        """matplotlib's Rectangle patch: outlined (edge ``color``), filled or not, '///' hatched."""
        x0, y0 = float(xy[0]), float(xy[1])
        ring = np.array([[x0, y0], [x0 + width, y0], [x0 + width, y0 + height], [x0, y0 + height]])
        self._patch(rings=[ring], face=css_color(color) if fill else None, edge=css_color(color), lw=float(lw),
                    z=zorder, hatch=hatch)

    def circle(self, xy, r, facecolor="white", edgecolor="k", lw=1.0, zorder=1):
        """A circle of data radius r (matplotlib's Circle patch)."""
        self._patch(circle=(float(xy[0]), float(xy[1]), float(r)), face=css_color(facecolor),
                    edge=css_color(edgecolor), lw=float(lw), z=zorder)

    def axvspan(self, a, b, color="0.9", lw=0.0, **kw):
        self.spans.append((float(a), float(b), css_color(color)))

    def axis(self, what):
        if what == "off":
            self.axis_on = False

    def set_yticks(self, ticks):
        self.yticks = np.asarray(ticks, float)

    def tick_params(self, labelsize=None, **kw):
        if labelsize:
            self.tick_pt = float(labelsize)

    def axhline(self, y=0.0, color="k", lw=0.8, ls="-", **kw):
        self.hlines.append((float(y), css_color(color), float(kw.get("linewidth", lw)), kw.get("linestyle", ls)))

    def axvline(self, x=0.0, color="k", lw=0.8, ls="-", **kw):
        self.vlines.append((float(x), css_color(color), float(kw.get("linewidth", lw)), kw.get("linestyle", ls)))

    def annotate(self, text, xy, xytext=None, textcoords=None, color="k", fontsize=None,
                 va="baseline", ha="left", xycoords="data", arrowprops=None, **kw):
        """A text at xy (data; ``xycoords`` ('data', 'axes fraction'): y a fraction of the
        axes), moved by xytext points (or, with ``arrowprops`` and no textcoords, an arrow
        from the data point xytext to xy, the text there)."""
        dx = dy = 0.0
        arrow_from = None
        if xytext is not None:
            if arrowprops is not None and textcoords in (None, "data"):
                arrow_from = (float(xytext[0]), float(xytext[1]))
            else:
                dx, dy = float(xytext[0]), float(xytext[1])
        ap = arrowprops or {}
        self.notes.append(_Note(s=_txt(text), x=float(xy[0]), y=float(xy[1]), dx=dx, dy=dy, color=css_color(color),
                                pt=float(fontsize or LABEL_PT), va=va, ha=ha,
                                frac_y=isinstance(xycoords, tuple) and xycoords[1] == "axes fraction",
                                arrow_from=arrow_from, arrow_lw=float(ap.get("lw", 1.0)),
                                arrow_color=css_color(ap.get("color", "k"))))

    def set_title(self, s, fontsize=None, loc="center", y=None, va=None, **kw):
        if loc in ("left", "right"):
            self.side_titles[loc] = (_txt(s), float(fontsize or TITLE_PT))
            return
        self.title = _txt(s)
        if fontsize:
            self.title_pt = float(fontsize)
        if y is not None and y < 1.0:          # inside the axes (a drawing without axes)
            self.title_at = (float(y), va or "baseline")

    # what figures.std_graph / std_axis and the label placement read (matplotlib's names)
    @property
    def figure(self):
        return self.fig

    def get_xlabel(self):
        return self.xlabel or ""

    def get_ylabel(self):
        return self.ylabel or ""

    def get_xlim(self):
        return self.xlim if self.xlim is not None else self.view[:2]

    def get_ylim(self):
        return self.ylim if self.ylim is not None else self.view[2:]

    @property
    def dataLim(self):
        def rng(arrays):
            v = [a[np.isfinite(a)] for a in (np.asarray(x, float).ravel() for x in arrays) if a.size]
            v = [a for a in v if a.size]
            return (min(float(a.min()) for a in v), max(float(a.max()) for a in v)) if v else (0.0, 1.0)
        (x0, x1), (y0, y1) = rng(self.data_x()), rng(self.data_y())
        return _Box(x0, y0, x1, y1)

    def get_position(self):
        """The axes box in figure fractions (from the bottom left), as laid out now."""
        x0, y0, w, h = self.box
        return _Box(x0 / self.fig.w, (self.fig.h - y0 - h) / self.fig.h,
                    (x0 + w) / self.fig.w, (self.fig.h - y0) / self.fig.h)

    def set_position(self, pos):
        x0, y0, w, h = (float(v) for v in pos)
        self.box = (x0 * self.fig.w, self.fig.h - (y0 + h) * self.fig.h, w * self.fig.w, h * self.fig.h)
        self.fig.laid_out = True

    @property
    def transData(self):
        return _ToDisplay(self)

    @property
    def bbox(self):
        x0, y0, w, h = self.box
        return _Box(x0 * PT_PER_MM, (self.fig.h - y0 - h) * PT_PER_MM, (x0 + w) * PT_PER_MM,
                    (self.fig.h - y0) * PT_PER_MM)

    def set_xlabel(self, s, **kw):
        self.xlabel = _txt(s)

    def set_ylabel(self, s, **kw):
        self.ylabel = _txt(s)

    def grid(self, on=True, lw=0.8, color="#b0b0b0", alpha=1.0, **kw):
        self.grid_on = bool(on)
        c = css_color(color)
        if alpha < 1.0:         # as drawn over white
            rgb = [int(c[i:i + 2], 16) for i in (1, 3, 5)]
            c = "#" + "".join(f"{round(255 - alpha * (255 - v)):02x}" for v in rgb)
        self.grid_style = (c, float(kw.get("linewidth", lw)))

    def set_xlim(self, lo, hi=None):
        self.xlim = (float(lo), float(hi))
        for ax in self.fig.shared(self):
            ax.xlim = self.xlim

    def set_ylim(self, lo, hi=None):
        self.ylim = (float(lo), float(hi))

    def set_xticks(self, ticks):
        self.xticks = np.asarray(ticks, float)
        for ax in self.fig.shared(self):
            ax.xticks = self.xticks

    def set_aspect(self, aspect, adjustable=None, **kw):
        self.equal = aspect == "equal"

    def legend(self, loc="best", ncol=1, fontsize=None, bbox_to_anchor=None, frameon=True, **kw):
        self.legend_kw = {"loc": loc, "fontsize": float(fontsize or LEGEND_PT),
                          "outside": bbox_to_anchor is not None and bbox_to_anchor[0] > 1.0,
                          "frame": frameon, "ncol": max(1, int(ncol))}

    # ------------------------------------------------------------ layout
    def data_x(self) -> list[np.ndarray]:
        return ([l.x for l in self.lines] + [np.array([v[0]]) for v in self.vlines] +
                [p.points()[0] for p in self.patches])

    def data_y(self) -> list[np.ndarray]:
        return ([l.y for l in self.lines] + [np.array([h[0]]) for h in self.hlines] +
                [p.points()[1] for p in self.patches])

    def legend_entries(self):
        return [l for l in self.lines if l.label and not str(l.label).startswith("_")]

    def legend_size(self) -> tuple[float, float]:
        fs = self.legend_kw["fontsize"] * MM_PER_PT
        ent = self.legend_entries()
        ncol = min(self.legend_kw.get("ncol", 1), max(len(ent), 1))
        w = 6.0 + max((_text_w(str(l.label), self.legend_kw["fontsize"]) for l in ent), default=0.0) + 2.0
        rows = -(-len(ent) // ncol)
        return w * ncol, rows * fs * 1.45 + 1.6

    def margins(self) -> tuple[float, float, float, float]:
        """left, right, top, bottom in mm around the axes box."""
        if not self.axis_on:
            return 0.0, 0.0, 0.0, 0.0
        yt = self._yticks_for_margin()
        tick = 1.25 + 0.9
        left = tick + max((_text_w(s, self.tick_pt) for s in tick_labels(yt)), default=2.0) + 0.5
        if self.ylabel:
            left += LABEL_PT * MM_PER_PT * 1.25 + 0.8
        bottom = 1.5
        if self.show_xticklabels:
            bottom = tick + TICK_PT * MM_PER_PT + 0.8
            if self.xlabel:
                bottom += LABEL_PT * MM_PER_PT * 1.3 + 0.5
        pts = ([self.title_pt] if self.title else []) + [pt for _, pt in self.side_titles.values()]
        top = max(pts) * MM_PER_PT * 1.5 + 0.8 if pts else 2.0
        right = 3.0
        if self.xlim is not None:      # labels annotated beyond the right end of the axes
            for n in self.notes:
                if n.x >= self.xlim[1]:
                    right = max(right, n.dx * MM_PER_PT + 1.15 * _text_w(n.s, n.pt) + 1.5)
        if self.legend_kw and self.legend_kw["outside"] and self.legend_entries():
            right += self.legend_size()[0] + 1.0
        return left + 1.0, right, top, bottom

    def _yticks_for_margin(self):
        if self.yticks is not None:
            return self.yticks
        lo, hi = self._limits(self.data_y(), self.ylim)
        return nice_ticks(lo, hi, 9)

    @staticmethod
    def _limits(arrays, fixed):
        if fixed is not None:
            return fixed
        vals = [a[np.isfinite(a)] for a in arrays if a is not None and np.size(a)]
        vals = [v for v in vals if v.size]
        if not vals:
            return 0.0, 1.0
        lo = min(float(v.min()) for v in vals)
        hi = max(float(v.max()) for v in vals)
        if hi - lo <= 1e-12 * max(1.0, abs(hi)):
            d = abs(hi) * 0.05 or 0.05
            return lo - d, hi + d
        m = 0.05 * (hi - lo)
        return lo - m, hi + m

    def finish_view(self):
        x0, y0, w, h = self.box
        xs = self.data_x()
        for ax in self.fig.shared(self):
            xs = xs + ax.data_x()
        xlo, xhi = self._limits(xs, self.xlim)
        ylo, yhi = self._limits(self.data_y(), self.ylim)
        if self.equal and self.fig.mpl and self.xlim is not None and self.ylim is not None and w > 0 and h > 0:
            # matplotlib's adjustable 'box' (its default): the limits stay, the box shrinks about its centre
            sx, sy = (xhi - xlo) / w, (yhi - ylo) / h
            if sx > sy * (1 + 1e-12):
                h2 = (yhi - ylo) / sx
                self.box = (x0, y0 + (h - h2) / 2, w, h2)
            elif sy > sx * (1 + 1e-12):
                w2 = (xhi - xlo) / sy
                self.box = (x0 + (w - w2) / 2, y0, w2, h)
        elif self.equal and w > 0 and h > 0:        # same data units per mm on both axes
            sx, sy = (xhi - xlo) / w, (yhi - ylo) / h
            if sx > sy:
                c, half = (ylo + yhi) / 2, sx * h / 2
                ylo, yhi = c - half, c + half
            else:
                c, half = (xlo + xhi) / 2, sy * w / 2
                xlo, xhi = c - half, c + half
        self.view = (xlo, xhi, ylo, yhi)

    def to_mm(self, x, y):
        x0, y0, w, h = self.box
        xlo, xhi, ylo, yhi = self.view
        X = x0 + (np.asarray(x, float) - xlo) / (xhi - xlo) * w
        Y = y0 + h - (np.asarray(y, float) - ylo) / (yhi - ylo) * h
        return X, Y

    # ------------------------------------------------------------ drawing
    def draw(self, out: list[str], uid: str, k: int):
        x0, y0, w, h = self.box
        xlo, xhi, ylo, yhi = self.view
        xt = self.xticks if self.xticks is not None else nice_ticks(xlo, xhi, _nbins(w, 3.0))
        yt = self.yticks if self.yticks is not None else nice_ticks(ylo, yhi, _nbins(h, 2.0))
        xt = xt[(xt >= xlo - 1e-9 * abs(xhi - xlo)) & (xt <= xhi + 1e-9 * abs(xhi - xlo))]
        yt = yt[(yt >= ylo - 1e-9 * abs(yhi - ylo)) & (yt <= yhi + 1e-9 * abs(yhi - ylo))]
        X, _ = self.to_mm(xt, np.zeros_like(xt))
        _, Y = self.to_mm(np.zeros_like(yt), yt)
        for a, b, c in self.spans:              # under the grid, as matplotlib's patches (zorder 1)
            (Xa, Xb), _ = self.to_mm([a, b], [0.0, 0.0])
            Xa, Xb = max(min(Xa, Xb), x0), min(max(Xa, Xb), x0 + w)
            if Xb > Xa:
                out.append(f'<rect x="{_f(Xa)}" y="{_f(y0)}" width="{_f(Xb - Xa)}" height="{_f(h)}" fill="{c}"/>')
        if self.grid_on and self.axis_on:
            c, lw = self.grid_style
            d = " ".join([f"M{_f(x)} {_f(y0)}V{_f(y0 + h)}" for x in X] +
                         [f"M{_f(x0)} {_f(y)}H{_f(x0 + w)}" for y in Y])
            if d:
                out.append(f'<path d="{d}" fill="none" stroke="{c}" stroke-width="{_w(lw * MM_PER_PT)}"/>')
        clip = f"{uid}-{k}"
        out.append(f'<clipPath id="{clip}"><rect x="{_f(x0)}" y="{_f(y0)}" width="{_f(w)}" '
                   f'height="{_f(h)}"/></clipPath>')
        inside = [f'<g clip-path="url(#{clip})">']
        for y, c, lw, ls in self.hlines:
            _, Yh = self.to_mm([0.0], [y])
            inside.append(self._stroke(f"M{_f(x0)} {_f(Yh[0])}H{_f(x0 + w)}", c, lw, ls))
        for x, c, lw, ls in self.vlines:
            Xv, _ = self.to_mm([x], [0.0])
            inside.append(self._stroke(f"M{_f(Xv[0])} {_f(y0)}V{_f(y0 + h)}", c, lw, ls))
        free = []
        for ln in sorted(self.artists, key=lambda l: l.z):
            target = inside if ln.clip else free
            if isinstance(ln, _Patch):
                target.extend(self._patch_svg(ln))
                continue
            Lx, Ly = self.to_mm(ln.x, ln.y)
            if ln.ls:
                if self.fig.mpl and ln.clip and len(Lx) > 2:       # as matplotlib: no path beyond the axes
                    m = ln.lw * MM_PER_PT
                    Lx, Ly = _clip_runs(Lx, Ly, x0 - m, y0 - m, x0 + w + m, y0 + h + m)
                if self.fig.mpl and len(Lx) > 8:         # and simplified (matplotlib's path.simplify)
                    Lx, Ly = _simplify(Lx, Ly, SIMPLIFY_MM)
                d = _polyline_d(Lx, Ly)
                if d:
                    target.append(self._stroke(d, ln.color, ln.lw, ln.ls, ln.cap))
            if ln.marker:
                r = _marker_r(ln)
                ok = np.isfinite(Lx) & np.isfinite(Ly)
                if ln.clip:
                    ok &= (Lx >= x0 - r) & (Lx <= x0 + w + r) & (Ly >= y0 - r) & (Ly <= y0 + h + r)
                d = _marker_d(ln.marker, r, Lx[ok], Ly[ok])
                if d and ln.marker == "+":
                    target.append(f'<path d="{d}" fill="none" stroke="{ln.color}" stroke-width="{_w(MM_PER_PT)}"/>')
                elif d:
                    target.append(f'<path d="{d}" fill="{ln.color}" stroke="none"/>')
        inside.append("</g>")
        out.extend(inside)
        out.extend(free)
        if self.axis_on:
            self._draw_axis(out, X, Y, xt, yt)
        if self.title and self.title_at is not None:
            tf = self.title_pt * MM_PER_PT
            yfrac, va = self.title_at
            # (matplotlib's title pad, 6 pt, above the given height)
            out.append(_text(x0 + w / 2, y0 + (1 - yfrac) * h - 6.0 * MM_PER_PT + _va_shift(va, tf), self.title, tf,
                             "middle"))
        for n in self.notes:
            X1, Y1 = self.to_mm([n.x], [n.y])
            if n.frac_y:
                Y1 = [y0 + (1.0 - n.y) * h]
            elif self.fig.mpl and not (x0 - 1e-9 <= X1[0] <= x0 + w + 1e-9 and y0 - 1e-9 <= Y1[0] <= y0 + h + 1e-9):
                continue        # matplotlib draws an annotation of a data point only inside the axes
            f = n.pt * MM_PER_PT
            if n.arrow_from is not None:
                Xa, Ya = self.to_mm([n.arrow_from[0]], [n.arrow_from[1]])
                out.append(_arrow_svg(Xa[0], Ya[0], X1[0], Y1[0], n.arrow_lw, n.arrow_color, n.pt))
            if n.s:
                # (svgchart's own charts: 'center' only, their other labels on the baseline)
                va = n.va if self.fig.mpl or n.va == "center" else "baseline"
                yy = Y1[0] - n.dy * MM_PER_PT + _va_shift(va, f)
                out.append(_text(X1[0] + n.dx * MM_PER_PT, yy, n.s, f, _ANCHOR.get(n.ha, "start"), fill=n.color))
        if self.legend_kw and self.legend_entries():
            self._draw_legend(out)

    def _draw_axis(self, out, X, Y, xt, yt):
        """The frame, the ticks, their labels, the axis labels and the title above."""
        x0, y0, w, h = self.box
        out.append(f'<rect x="{_f(x0)}" y="{_f(y0)}" width="{_f(w)}" height="{_f(h)}" fill="none" '
                   f'stroke="#000000" stroke-width="{_w(0.8 * MM_PER_PT)}"/>')
        tl = 3.5 * MM_PER_PT
        d = " ".join([f"M{_f(x)} {_f(y0 + h)}v{_f(tl)}" for x in X] + [f"M{_f(x0)} {_f(y)}h{_f(-tl)}" for y in Y])
        if d:
            out.append(f'<path d="{d}" stroke="#000000" stroke-width="{_w(0.8 * MM_PER_PT)}"/>')
        fs = self.tick_pt * MM_PER_PT
        if self.show_xticklabels:
            for x, s in zip(X, tick_labels(xt)):
                out.append(_text(x, y0 + h + tl + 0.9 + 0.8 * fs, s, fs, "middle"))
        ylabels = tick_labels(yt)
        for y, s in zip(Y, ylabels):
            out.append(_text(x0 - tl - 0.9, y + 0.35 * fs, s, fs, "end"))
        lf = LABEL_PT * MM_PER_PT
        if self.xlabel and self.show_xticklabels:
            out.append(_text(x0 + w / 2, y0 + h + tl + 0.9 + fs + 0.5 + 0.95 * lf, self.xlabel, lf, "middle"))
        if self.ylabel:
            yw = max((_text_w(s, self.tick_pt) for s in ylabels), default=2.0)
            xl = x0 - tl - 0.9 - yw - 0.8 - 0.25 * lf
            out.append(_text(xl, y0 + h / 2, self.ylabel, lf, "middle", rotate=True))
        if self.title and self.title_at is None:
            tf = self.title_pt * MM_PER_PT
            out.append(_text(x0 + w / 2, y0 - 0.35 * tf - 0.8, self.title, tf, "middle"))
        for loc, (s, pt) in self.side_titles.items():
            tf = pt * MM_PER_PT
            out.append(_text(x0 if loc == "left" else x0 + w, y0 - 0.35 * tf - 0.8, s, tf,
                             "start" if loc == "left" else "end"))

    def _patch_svg(self, p: _Patch) -> list[str]:
        """A patch's elements: its fill, its hatch strokes (clipped to it) and its outline."""
        out = []
        if p.circle is not None:
            cx, cy, r = p.circle
            (X,), (Y,) = self.to_mm([cx], [cy])
            xlo, xhi, ylo, yhi = self.view
            rx, ry = r / (xhi - xlo) * self.box[2], r / (yhi - ylo) * self.box[3]
            attrs = (f'fill="{p.face or "none"}" stroke="{p.edge or "none"}" stroke-width="{_w(p.lw * MM_PER_PT)}"')
            if abs(rx - ry) <= 1e-9 * max(rx, ry):
                out.append(f'<circle cx="{_f(X)}" cy="{_f(Y)}" r="{_f(rx)}" {attrs}/>')
            else:
                out.append(f'<ellipse cx="{_f(X)}" cy="{_f(Y)}" rx="{_f(rx)}" ry="{_f(ry)}" {attrs}/>')
            return out
        rings = [np.column_stack(self.to_mm(r[:, 0], r[:, 1])) for r in p.rings]
        d = trim("".join(("M" + "L".join(["%.2f %.2f"] * len(r)) + "Z") % tuple(r.ravel().tolist())
                         for r in rings if len(r) >= 2))
        if not d:
            return out
        if p.face:
            rule = ' fill-rule="evenodd"' if len(rings) > 1 else ""
            out.append(f'<path d="{d}" fill="{p.face}"{rule} stroke="none"/>')
        if p.hatch:
            out.append(self._stroke(_hatch_d(rings[0], p.hatch), p.edge or "#000000", 1.0, "-"))
        if p.edge and p.lw > 0:
            out.append(f'<path d="{d}" fill="none" stroke="{p.edge}" stroke-width="{_w(p.lw * MM_PER_PT)}" '
                       f'stroke-linejoin="miter"/>')
        return out

    @staticmethod
    def _stroke(d, color, lw, ls, cap="butt"):
        da = ""
        if ls in _DASH:
            da = ' stroke-dasharray="' + " ".join(_f(float(v) * lw * MM_PER_PT) for v in _DASH[ls].split()) + '"'
        elif isinstance(ls, tuple):         # matplotlib's (offset, (on, off, ...)) in line widths
            da = ' stroke-dasharray="' + " ".join(_f(float(v) * lw * MM_PER_PT) for v in ls[1]) + '"'
            if ls[0]:
                da += f' stroke-dashoffset="{_f(float(ls[0]) * lw * MM_PER_PT)}"'
        capa = "butt" if da or cap != "projecting" else "square"
        return (f'<path d="{d}" fill="none" stroke="{color}" stroke-width="{_w(lw * MM_PER_PT)}"{da} '
                f'stroke-linejoin="round" stroke-linecap="{capa}"/>')

    def _draw_legend(self, out):
        x0, y0, w, h = self.box
        lw_, lh = self.legend_size()
        pad = 1.2
        if self.legend_kw["outside"]:
            bx, by = x0 + w + 1.0, y0
        else:
            cands = {"upper right": (x0 + w - lw_ - pad, y0 + pad), "upper left": (x0 + pad, y0 + pad),
                     "lower left": (x0 + pad, y0 + h - lh - pad),
                     "lower right": (x0 + w - lw_ - pad, y0 + h - lh - pad),
                     "center right": (x0 + w - lw_ - pad, y0 + (h - lh) / 2),
                     "center left": (x0 + pad, y0 + (h - lh) / 2),
                     "lower center": (x0 + (w - lw_) / 2, y0 + h - lh - pad),
                     "upper center": (x0 + (w - lw_) / 2, y0 + pad)}
            loc = self.legend_kw["loc"]
            if loc in cands:
                bx, by = cands[loc]
            else:                       # "best": the place covering the fewest data points
                pts = []
                for ln in self.lines:
                    Lx, Ly = self.to_mm(ln.x, ln.y)
                    n = len(Lx)
                    if n > 1:
                        t = np.linspace(0, n - 1, min(400, 8 * n))
                        Lx, Ly = np.interp(t, np.arange(n), Lx), np.interp(t, np.arange(n), Ly)
                    pts.append(np.column_stack([Lx, Ly]))
                P = np.concatenate(pts) if pts else np.zeros((0, 2))
                P = P[np.all(np.isfinite(P), axis=1)]

                def cover(p):
                    return int(np.sum((P[:, 0] >= p[0]) & (P[:, 0] <= p[0] + lw_) &
                                      (P[:, 1] >= p[1]) & (P[:, 1] <= p[1] + lh)))
                bx, by = min(cands.values(), key=cover)
        if self.legend_kw["frame"]:
            out.append(f'<rect x="{_f(bx)}" y="{_f(by)}" width="{_f(lw_)}" height="{_f(lh)}" rx="0.5" '
                       f'fill="#ffffff" fill-opacity="0.8" stroke="#cccccc" stroke-width="{_w(0.8 * MM_PER_PT)}"/>')
        fs = self.legend_kw["fontsize"] * MM_PER_PT
        ent = self.legend_entries()
        ncol = min(self.legend_kw.get("ncol", 1), max(len(ent), 1))
        rows = -(-len(ent) // ncol)
        cw = lw_ / ncol
        for i, ln in enumerate(ent):
            col, row = divmod(i, rows)          # matplotlib fills the columns first
            cx = bx + col * cw
            yc = by + 0.8 + fs * 1.45 * (row + 0.5)
            if ln.ls:
                out.append(self._stroke(f"M{_f(cx + 1.0)} {_f(yc)}h5", ln.color, ln.lw, ln.ls))
            if ln.marker:
                r = _marker_r(ln)
                out.append(f'<circle cx="{_f(cx + 3.5)}" cy="{_f(yc)}" r="{_f(r)}" fill="{ln.color}"/>')
            out.append(_text(cx + 7.0, yc + 0.35 * fs, _txt(ln.label), fs, "start"))


_ANCHOR = {"left": "start", "center": "middle", "right": "end"}


def _va_shift(va: str, f: float) -> float:
    """From a text's anchor y (mm, y down) to its baseline, for matplotlib's vertical alignment
    (DejaVu Sans: ascent ~0.76 em, descent ~0.24 em, x-height centre ~0.35 em)."""
    return {"center": 0.35 * f, "top": 0.76 * f, "bottom": -0.24 * f}.get(va, 0.0)


def _arrow_svg(xa, ya, xb, yb, lw, color, size_pt) -> str:
    """matplotlib's annotate arrow '-|>' from (xa, ya) to (xb, yb) (mm): both ends shrunk by
    2 pt, a filled head 0.4 x 0.4 of the text size (its mutation scale)."""
    L = math.hypot(xb - xa, yb - ya)
    if L <= 1e-9:
        return ""
    hl, hw = 0.4 * size_pt * MM_PER_PT, 0.2 * size_pt * MM_PER_PT
    sh = 2.0 * MM_PER_PT if L > 4.0 * MM_PER_PT + hl else 0.0      # (a short arrow: not shrunk)
    ux, uy = (xb - xa) / L, (yb - ya) / L
    xa, ya, xb, yb = xa + ux * sh, ya + uy * sh, xb - ux * sh, yb - uy * sh
    bx, by = xb - ux * hl, yb - uy * hl
    head = (f"M{_f(xb)} {_f(yb)}L{_f(bx - uy * hw)} {_f(by + ux * hw)}L{_f(bx + uy * hw)} {_f(by - ux * hw)}Z")
    return (f'<path d="M{_f(xa)} {_f(ya)}L{_f(bx)} {_f(by)}" fill="none" stroke="{color}" '
            f'stroke-width="{_w(lw * MM_PER_PT)}"/>\n'
            f'<path d="{head}" fill="{color}" stroke="{color}" stroke-width="{_w(lw * MM_PER_PT)}" '
            f'stroke-linejoin="miter"/>')


def _hatch_d(ring, hatch: str) -> str:
    """matplotlib's '/' hatch (6 lines an inch per '/', 45°, bottom left to top right) inside the
    convex polygon ``ring`` (mm, y down): the strokes' path data."""
    n = hatch.count("/") * 6
    if not n:
        return ""
    step = 2 * 25.4 / n                          # mm between the lines along x (matplotlib's 8 pt for '///')
    # a line x - (-y) = c  (y down: rising to the right is x + y = c)
    c = ring[:, 0] + ring[:, 1]
    parts = []
    k0, k1 = math.ceil(c.min() / step), math.floor(c.max() / step)
    m = len(ring)
    for k in range(k0, k1 + 1):
        cc = k * step
        hits = []
        for i in range(m):
            (xa, ya), (xb, yb) = ring[i], ring[(i + 1) % m]
            fa, fb = xa + ya - cc, xb + yb - cc
            if (fa < 0) != (fb < 0) and fa != fb:
                t = fa / (fa - fb)
                hits.append((xa + t * (xb - xa), ya + t * (yb - ya)))
        if len(hits) >= 2:
            hits.sort()
            (p, q), (r, s_) = hits[0], hits[-1]
            parts.append(f"M{_f(p)} {_f(q)}L{_f(r)} {_f(s_)}")
    return "".join(parts)


def _marker_r(ln) -> float:
    """Radius (mm) of a marker: 'o' of diameter ms pt, '.' of ms/2, each with matplotlib's
    1 pt edge of the same colour ('s', '^', '+': half their size, the edge too)."""
    if ln.marker == "+":
        return ln.ms * MM_PER_PT / 2
    return ((ln.ms if ln.marker != "." else 0.5 * ln.ms) + 1.0) * MM_PER_PT / 2


def _marker_d(marker: str, r: float, X, Y) -> str:
    """Path data of the markers at (X, Y) (mm): circles, squares, triangles or crosses."""
    if marker == "s":
        return "".join(f"M{_f(a - r)} {_f(b - r)}h{_f(2 * r)}v{_f(2 * r)}h{_f(-2 * r)}Z" for a, b in zip(X, Y))
    if marker == "^":
        return "".join(f"M{_f(a)} {_f(b - r)}L{_f(a + r)} {_f(b + r)}L{_f(a - r)} {_f(b + r)}Z"
                       for a, b in zip(X, Y))
    if marker == "+":
        return "".join(f"M{_f(a - r)} {_f(b)}h{_f(2 * r)}M{_f(a)} {_f(b - r)}v{_f(2 * r)}" for a, b in zip(X, Y))
    return "".join(f"M{_f(a - r)} {_f(b)}a{_f(r)} {_f(r)} 0 1 0 {_f(2 * r)} 0"
                   f"a{_f(r)} {_f(r)} 0 1 0 {_f(-2 * r)} 0" for a, b in zip(X, Y))


SIMPLIFY_MM = 0.01      # the most a simplified polyline leaves its points (matplotlib's is 1/9 px, 0.04 mm)


def _simplify(X, Y, tol: float):
    """The polyline with only the points that keep it within ``tol`` of every dropped one
    (Ramer-Douglas-Peucker on each run between breaks); the ends of each run are kept."""
    X, Y = np.asarray(X, float), np.asarray(Y, float)
    ok = np.isfinite(X) & np.isfinite(Y)
    keep = ~ok                                   # (the breaks stay)
    edges = np.flatnonzero(np.diff(np.r_[0, ok.astype(np.int8), 0]))
    for a, b in zip(edges[::2], edges[1::2]):    # runs a .. b-1
        keep[a] = keep[b - 1] = True
        stack = [(a, b - 1)]
        while stack:
            i, j = stack.pop()
            if j - i < 2:
                continue
            dx, dy = X[j] - X[i], Y[j] - Y[i]
            L = math.hypot(dx, dy)
            px, py = X[i + 1:j] - X[i], Y[i + 1:j] - Y[i]
            dist = np.abs(px * dy - py * dx) / L if L > 0 else np.hypot(px, py)
            k = int(np.argmax(dist))
            if dist[k] > tol:
                k += i + 1
                keep[k] = True
                stack.append((i, k))
                stack.append((k, j))
    return X[keep], Y[keep]


def _clip_runs(X, Y, xa, ya, xb, yb):
    """The polyline without its runs of segments that lie wholly beyond the box (each such
    run replaced by a break): a segment is kept when its bounding box meets the box."""
    X, Y = np.asarray(X, float), np.asarray(Y, float)
    with np.errstate(invalid="ignore"):
        meet = ((np.maximum(X[:-1], X[1:]) >= xa) & (np.minimum(X[:-1], X[1:]) <= xb) &
                (np.maximum(Y[:-1], Y[1:]) >= ya) & (np.minimum(Y[:-1], Y[1:]) <= yb))
    if meet.all():
        return X, Y
    keep = np.zeros(len(X), bool)
    keep[:-1] |= meet
    keep[1:] |= meet
    # a break (NaN) where a dropped run starts after a kept point
    out_x, out_y = np.where(keep, X, np.nan), np.where(keep, Y, np.nan)
    nan_run = ~keep & np.r_[False, keep[:-1]]
    sel = keep | nan_run
    return out_x[sel], out_y[sel]


def _polyline_d(X, Y) -> str:
    """Path data of a polyline broken at non-finite points."""
    X, Y = np.asarray(X, dtype=float), np.asarray(Y, dtype=float)
    ok = np.isfinite(X) & np.isfinite(Y)
    # Python floats (and bools): formatted as the numpy scalars are, without making them
    if ok.all():                       # one run, the usual case: no loop over the points
        parts = [np.column_stack((X, Y)).ravel().tolist()]
    else:
        parts, run = [], []
        for good, a, b in zip(ok.tolist(), X.tolist(), Y.tolist()):
            if good:
                run.append(a)
                run.append(b)
            elif run:
                parts.append(run)
                run = []
        if run:
            parts.append(run)
    # each run's numbers written "%.2f" at once, trimmed as _f trims them (svgdraw.trim)
    return trim("".join(("M" + "L".join(["%.2f %.2f"] * (len(r) // 2))) % tuple(r)
                        for r in parts if len(r) > 2))


def _text(x, y, s, size_mm, anchor, fill=None, rotate=False) -> str:
    attrs = [f'x="{_f(x)}"', f'y="{_f(y)}"', f'font-size="{_f(size_mm)}"']
    if anchor != "start":
        attrs.append(f'text-anchor="{anchor}"')
    if fill and fill != "#000000":
        attrs.append(f'fill="{fill}"')
    if rotate:
        attrs.append(f'transform="rotate(-90 {_f(x)} {_f(y)})"')
    return f'<text {" ".join(attrs)}>{text_body(s, size_mm)}</text>'


class Figure:
    def __init__(self, width_mm, height_mm, nrows=1, ncols=1, sharex=False, height_ratios=None,
                 width_ratios=None, mpl=False):
        # mpl: laid out as matplotlib lays out a figure (report.figures.new_figure): the
        # fractions of subplots_adjust are kept (its defaults when the section calls neither it
        # nor tight_layout), and an equal aspect with both limits set shrinks the axes' box
        self.mpl = bool(mpl)
        self.w, self.h = float(width_mm), float(height_mm)
        self.nrows, self.ncols = nrows, ncols
        self.sharex = sharex
        self.hr = list(height_ratios or [1.0] * nrows)
        self.wr = list(width_ratios or [1.0] * ncols)
        self.grid = [[Axes(self) for _ in range(ncols)] for _ in range(nrows)]
        self.dpi = 72.0                 # display units are points (transData, bbox)
        self.laid_out = False           # tight_layout (or set_position) fixes the boxes

    def axes_list(self):
        return [ax for row in self.grid for ax in row]

    def shared(self, ax):
        if not self.sharex:
            return []
        for j in range(self.ncols):
            col = [self.grid[i][j] for i in range(self.nrows)]
            if ax in col:
                return [a for a in col if a is not ax]
        return []

    @property
    def axes(self):
        return self.axes_list()

    def get_figwidth(self):
        return self.w / 25.4

    def get_figheight(self):
        return self.h / 25.4

    # matplotlib calls the sections make: the layout is this module's own (the margins
    # its text needs); once made, the boxes stay, so a scale set from an axes' length
    # (figures.std_axis) is the scale drawn
    def tight_layout(self, *a, **kw):
        self.layout()
        self.laid_out = True

    def subplots_adjust(self, left=None, bottom=None, right=None, top=None, wspace=None, hspace=None):
        if not self.mpl:
            self.tight_layout()
            return
        self.adjust(left, bottom, right, top, wspace, hspace)

    def adjust(self, left=None, bottom=None, right=None, top=None, wspace=None, hspace=None):
        """The axes' boxes as matplotlib's subplot parameters (fractions of the figure; the
        gaps fractions of the mean axes width / height) put them."""
        left = 0.125 if left is None else left
        right = 0.9 if right is None else right
        bottom = 0.11 if bottom is None else bottom
        top = 0.88 if top is None else top
        wspace = 0.2 if wspace is None else wspace
        hspace = 0.2 if hspace is None else hspace
        W, H = (right - left) * self.w, (top - bottom) * self.h
        cw = W / (self.ncols + wspace * (self.ncols - 1))
        ch = H / (self.nrows + hspace * (self.nrows - 1))
        ws = [cw * self.ncols * r / sum(self.wr) for r in self.wr]
        hs = [ch * self.nrows * r / sum(self.hr) for r in self.hr]
        if self.sharex:
            for i in range(self.nrows - 1):
                for ax in self.grid[i]:
                    ax.show_xticklabels = False
        y = (1 - top) * self.h
        for i in range(self.nrows):
            x = left * self.w
            for j in range(self.ncols):
                self.grid[i][j].box = (x, y, ws[j], hs[i])
                x += ws[j] + wspace * cw
            y += hs[i] + hspace * ch
        for ax in self.axes_list():
            ax.finish_view()
        self.laid_out = True

    def layout(self):
        if self.sharex:
            for i in range(self.nrows - 1):
                for ax in self.grid[i]:
                    ax.show_xticklabels = False
        m = [[ax.margins() for ax in row] for row in self.grid]
        lefts = [max(m[i][j][0] for i in range(self.nrows)) for j in range(self.ncols)]
        rights = [max(m[i][j][1] for i in range(self.nrows)) for j in range(self.ncols)]
        tops = [max(m[i][j][2] for j in range(self.ncols)) for i in range(self.nrows)]
        bottoms = [max(m[i][j][3] for j in range(self.ncols)) for i in range(self.nrows)]
        free_w = self.w - sum(lefts) - sum(rights)
        free_h = self.h - sum(tops) - sum(bottoms)
        ws = [free_w * r / sum(self.wr) for r in self.wr]
        hs = [free_h * r / sum(self.hr) for r in self.hr]
        y = 0.0
        for i in range(self.nrows):
            x = 0.0
            y += tops[i]
            for j in range(self.ncols):
                x += lefts[j]
                self.grid[i][j].box = (x, y, ws[j], hs[i])
                x += ws[j] + rights[j]
            y += hs[i] + bottoms[i]
        for ax in self.axes_list():
            ax.finish_view()

    def to_svg(self) -> str:
        if self.laid_out:
            for ax in self.axes_list():
                ax.finish_view()
        elif self.mpl:
            self.adjust()
        else:
            self.layout()
        uid = "\x00"                    # replaced by a hash of the drawing, below
        out = [f'<svg xmlns="http://www.w3.org/2000/svg" class="fig" width="{self.w * PT_PER_MM:.1f}pt" '
               f'height="{self.h * PT_PER_MM:.1f}pt" viewBox="0 0 {_f(self.w)} {_f(self.h)}" '
               f'font-family="{FONT}">']
        for k, ax in enumerate(self.axes_list()):
            ax.draw(out, uid, k)
        out.append("</svg>")
        text = "\n".join(out)
        # clip-path ids: unique among the figures of one report and the same in every run
        # (a hash of the drawing: two identical charts share identical clip rectangles)
        return text.replace("\x00", "c" + hashlib.sha1(text.encode("utf-8")).hexdigest()[:12])


def subplots(width_mm: float, height_mm: float, nrows: int = 1, ncols: int = 1, sharex: bool = False,
             squeeze: bool = True, height_ratios=None, width_ratios=None, mpl: bool = False):
    """(Figure, axes) as matplotlib's plt.subplots: one Axes, a 1-D array (one row or
    column) or a 2-D array (squeeze=False or a grid)."""
    fig = Figure(width_mm, height_mm, nrows, ncols, sharex, height_ratios, width_ratios, mpl)
    arr = np.empty((nrows, ncols), dtype=object)
    for i in range(nrows):
        for j in range(ncols):
            arr[i, j] = fig.grid[i][j]
    if not squeeze:
        return fig, arr
    if nrows == 1 and ncols == 1:
        return fig, arr[0, 0]
    if nrows == 1 or ncols == 1:
        return fig, arr.ravel()
    return fig, arr
