"""Line charts written directly as SVG: the report's diagrams over the cycle
(kinematic diagrams, loads, balancing moment and reactions, the flywheel's
diagrams and the energy-mass diagram).

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


def periodic_spline(x, y, t) -> np.ndarray:
    """The periodic cubic spline through (x[i], y[i]) (y[-1] == y[0]; y may be (n, d))
    evaluated at t (taken modulo the period): the same curve as scipy's
    CubicSpline(x, y, bc_type="periodic"), without importing scipy for a drawing.
    Second derivatives M from the cyclic system
    h[i-1] M[i-1] + 2 (h[i-1] + h[i]) M[i] + h[i] M[i+1] = 6 (d[i] - d[i-1])."""
    x = np.asarray(x, float)
    y = np.asarray(y, float)
    flat = y.ndim == 1
    Y = y.reshape(len(x), -1)
    h = np.diff(x)
    m = len(h)
    d = np.diff(Y, axis=0) / h[:, None]
    A = np.zeros((m, m))
    for i in range(m):
        A[i, (i - 1) % m] += h[i - 1]
        A[i, i] += 2.0 * (h[i - 1] + h[i])
        A[i, (i + 1) % m] += h[i]
    M = np.linalg.solve(A, 6.0 * (d - np.roll(d, 1, axis=0)))
    M = np.vstack([M, M[:1]])
    t = np.asarray(t, float)
    tt = x[0] + np.mod(t - x[0], x[-1] - x[0])
    j = np.clip(np.searchsorted(x, tt, side="right") - 1, 0, m - 1)
    hj = h[j][:, None]
    a = (x[j + 1] - tt)[:, None]
    b = (tt - x[j])[:, None]
    S = (M[j] * a ** 3 + M[j + 1] * b ** 3) / (6.0 * hj) + (Y[j] / hj - M[j] * hj / 6.0) * a \
        + (Y[j + 1] / hj - M[j + 1] * hj / 6.0) * b
    return S[:, 0] if flat else S


def _nbins(length_mm: float, per_label: float) -> int:
    """How many tick intervals fit (matplotlib's 'auto': a label per 3 font sizes along
    x, per 2 along y; at most 9)."""
    return max(1, min(9, int(length_mm * PT_PER_MM / (TICK_PT * per_label))))


def tick_labels(ticks) -> list[str]:
    """Fewest decimals that show every tick exactly (as matplotlib's labels)."""
    ticks = np.asarray(ticks, float)
    for d in range(0, 7):
        if np.all(np.abs(np.round(ticks, d) - ticks) <= 1e-9 * max(1.0, float(np.max(np.abs(ticks))))):
            return [_num(t, d) for t in ticks]
    return [f"{t:.3g}".replace("-", "\u2212") for t in ticks]


_MATH = re.compile(r"\$([^$]*)\$")
_SCRIPT = re.compile(r"([_^])(\{[^}]*\}|.)")


def text_body(s: str, size_mm: float) -> str:
    """SVG text content of a label; $X_{ab}$ (matplotlib mathtext) -> italic X with a
    lowered smaller 'ab' (^ raised); its numbers as the current language writes them."""
    s = localize(s)
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
    segs = [g for g in segs if g[0]]
    if all(g[1] == 0.0 and not g[2] for g in segs):
        return escape(s)
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
        elif ch in "o.":
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
    __slots__ = ("x", "y", "color", "lw", "ls", "marker", "ms", "label", "clip", "z")

    def __init__(self, **kw):
        for k in self.__slots__:
            setattr(self, k, kw.get(k))


class Axes:
    def __init__(self, fig):
        self.fig = fig
        self.lines: list[_Line] = []
        self.hlines: list[tuple] = []
        self.vlines: list[tuple] = []
        self.notes: list[tuple] = []
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
        self.lines.append(_Line(x=x, y=y, color=css_color(color), lw=float(kw.get("lw", kw.get("linewidth", 1.0))),
                                ls=ls, marker=marker, ms=float(ms), label=kw.get("label"),
                                clip=kw.get("clip_on", True), z=kw.get("zorder", 2)))

    def axhline(self, y=0.0, color="k", lw=0.8, ls="-", **kw):
        self.hlines.append((float(y), css_color(color), float(kw.get("linewidth", lw)), kw.get("linestyle", ls)))

    def axvline(self, x=0.0, color="k", lw=0.8, ls="-", **kw):
        self.vlines.append((float(x), css_color(color), float(kw.get("linewidth", lw)), kw.get("linestyle", ls)))

    def annotate(self, text, xy, xytext=(0, 0), textcoords="offset points", color="k", fontsize=None,
                 va="baseline", **kw):
        self.notes.append((str(text), float(xy[0]), float(xy[1]), float(xytext[0]), float(xytext[1]),
                           css_color(color), float(fontsize or LABEL_PT), va))

    def set_title(self, s, fontsize=None, loc="center", **kw):
        if loc in ("left", "right"):
            self.side_titles[loc] = (str(s), float(fontsize or TITLE_PT))
            return
        self.title = str(s)
        if fontsize:
            self.title_pt = float(fontsize)

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
        self.xlabel = str(s)

    def set_ylabel(self, s, **kw):
        self.ylabel = str(s)

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
                          "frame": frameon}

    # ------------------------------------------------------------ layout
    def data_x(self) -> list[np.ndarray]:
        return [l.x for l in self.lines] + [np.array([v[0]]) for v in self.vlines]

    def data_y(self) -> list[np.ndarray]:
        return [l.y for l in self.lines] + [np.array([h[0]]) for h in self.hlines]

    def legend_entries(self):
        return [l for l in self.lines if l.label and not str(l.label).startswith("_")]

    def legend_size(self) -> tuple[float, float]:
        fs = self.legend_kw["fontsize"] * MM_PER_PT
        ent = self.legend_entries()
        w = 6.0 + max((_text_w(str(l.label), self.legend_kw["fontsize"]) for l in ent), default=0.0) + 2.0
        return w, len(ent) * fs * 1.45 + 1.6

    def margins(self) -> tuple[float, float, float, float]:
        """left, right, top, bottom in mm around the axes box."""
        yt = self._yticks_for_margin()
        tick = 1.25 + 0.9
        left = tick + max((_text_w(s, TICK_PT) for s in tick_labels(yt)), default=2.0) + 0.5
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
            for s, x, y, dx, dy, c, fpt, va in self.notes:
                if x >= self.xlim[1]:
                    right = max(right, dx * MM_PER_PT + 1.15 * _text_w(s, fpt) + 1.5)
        if self.legend_kw and self.legend_kw["outside"] and self.legend_entries():
            right += self.legend_size()[0] + 1.0
        return left + 1.0, right, top, bottom

    def _yticks_for_margin(self):
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
        if self.equal and w > 0 and h > 0:        # same data units per mm on both axes
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
        yt = nice_ticks(ylo, yhi, _nbins(h, 2.0))
        xt = xt[(xt >= xlo - 1e-9 * abs(xhi - xlo)) & (xt <= xhi + 1e-9 * abs(xhi - xlo))]
        yt = yt[(yt >= ylo - 1e-9 * abs(yhi - ylo)) & (yt <= yhi + 1e-9 * abs(yhi - ylo))]
        X, _ = self.to_mm(xt, np.zeros_like(xt))
        _, Y = self.to_mm(np.zeros_like(yt), yt)
        if self.grid_on:
            c, lw = self.grid_style
            d = " ".join([f"M{_f(x)} {_f(y0)}V{_f(y0 + h)}" for x in X] +
                         [f"M{_f(x0)} {_f(y)}H{_f(x0 + w)}" for y in Y])
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
        for ln in sorted(self.lines, key=lambda l: l.z):
            target = inside if ln.clip else free
            Lx, Ly = self.to_mm(ln.x, ln.y)
            if ln.ls:
                d = _polyline_d(Lx, Ly)
                if d:
                    target.append(self._stroke(d, ln.color, ln.lw, ln.ls))
            if ln.marker:
                r = _marker_r(ln)
                ok = np.isfinite(Lx) & np.isfinite(Ly)
                if ln.clip:
                    ok &= (Lx >= x0 - r) & (Lx <= x0 + w + r) & (Ly >= y0 - r) & (Ly <= y0 + h + r)
                d = "".join(f"M{_f(a - r)} {_f(b)}a{_f(r)} {_f(r)} 0 1 0 {_f(2 * r)} 0"
                            f"a{_f(r)} {_f(r)} 0 1 0 {_f(-2 * r)} 0" for a, b in zip(Lx[ok], Ly[ok]))
                if d:
                    target.append(f'<path d="{d}" fill="{ln.color}" stroke="none"/>')
        inside.append("</g>")
        out.extend(inside)
        out.extend(free)
        # frame, ticks, labels
        out.append(f'<rect x="{_f(x0)}" y="{_f(y0)}" width="{_f(w)}" height="{_f(h)}" fill="none" '
                   f'stroke="#000000" stroke-width="{_w(0.8 * MM_PER_PT)}"/>')
        tl = 3.5 * MM_PER_PT
        d = " ".join([f"M{_f(x)} {_f(y0 + h)}v{_f(tl)}" for x in X] + [f"M{_f(x0)} {_f(y)}h{_f(-tl)}" for y in Y])
        out.append(f'<path d="{d}" stroke="#000000" stroke-width="{_w(0.8 * MM_PER_PT)}"/>')
        fs = TICK_PT * MM_PER_PT
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
            yw = max((_text_w(s, TICK_PT) for s in ylabels), default=2.0)
            xl = x0 - tl - 0.9 - yw - 0.8 - 0.25 * lf
            out.append(_text(xl, y0 + h / 2, self.ylabel, lf, "middle", rotate=True))
        if self.title:
            tf = self.title_pt * MM_PER_PT
            out.append(_text(x0 + w / 2, y0 - 0.35 * tf - 0.8, self.title, tf, "middle"))
        for loc, (s, pt) in self.side_titles.items():
            tf = pt * MM_PER_PT
            out.append(_text(x0 if loc == "left" else x0 + w, y0 - 0.35 * tf - 0.8, s, tf,
                             "start" if loc == "left" else "end"))
        for s, x, y, dx, dy, c, fpt, va in self.notes:
            X1, Y1 = self.to_mm([x], [y])
            f = fpt * MM_PER_PT
            yy = Y1[0] - dy * MM_PER_PT + (0.35 * f if va == "center" else 0.0)
            out.append(_text(X1[0] + dx * MM_PER_PT, yy, s, f, "start", fill=c))
        if self.legend_kw and self.legend_entries():
            self._draw_legend(out)

    @staticmethod
    def _stroke(d, color, lw, ls):
        da = ""
        if ls in _DASH:
            da = ' stroke-dasharray="' + " ".join(_f(float(v) * lw * MM_PER_PT) for v in _DASH[ls].split()) + '"'
        return (f'<path d="{d}" fill="none" stroke="{color}" stroke-width="{_w(lw * MM_PER_PT)}"{da} '
                f'stroke-linejoin="round" stroke-linecap="butt"/>')

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
        for i, ln in enumerate(self.legend_entries()):
            yc = by + 0.8 + fs * 1.45 * (i + 0.5)
            if ln.ls:
                out.append(self._stroke(f"M{_f(bx + 1.0)} {_f(yc)}h5", ln.color, ln.lw, ln.ls))
            if ln.marker:
                r = _marker_r(ln)
                out.append(f'<circle cx="{_f(bx + 3.5)}" cy="{_f(yc)}" r="{_f(r)}" fill="{ln.color}"/>')
            out.append(_text(bx + 7.0, yc + 0.35 * fs, str(ln.label), fs, "start"))


def _marker_r(ln) -> float:
    """Radius (mm) of a marker: 'o' of diameter ms pt, '.' of ms/2, each with matplotlib's
    1 pt edge of the same colour."""
    return ((ln.ms if ln.marker == "o" else 0.5 * ln.ms) + 1.0) * MM_PER_PT / 2


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
                 width_ratios=None):
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

    def subplots_adjust(self, *a, **kw):
        self.tight_layout()

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
             squeeze: bool = True, height_ratios=None, width_ratios=None):
    """(Figure, axes) as matplotlib's plt.subplots: one Axes, a 1-D array (one row or
    column) or a 2-D array (squeeze=False or a grid)."""
    fig = Figure(width_mm, height_mm, nrows, ncols, sharex, height_ratios, width_ratios)
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
