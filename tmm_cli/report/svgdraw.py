"""A small direct SVG writer for the report's per-position drawings (velocity and
acceleration plans, free-body diagrams of the Assur groups, force polygons,
Zhukovsky's lever).

Why not matplotlib: a plan drawn by matplotlib costs ~0.1 s to make, and its SVG
has a separate path and text for every axis tick.  Here a drawing is a handful of merged paths (one per stroke
style), filled arrow heads merged per colour and one <text> per label: made in
milliseconds and painted several times faster.

Coordinates are millimetres on paper, origin at the bottom left, y up (as in
the drawings of the course); the SVG is emitted with width/height in pt so the
figure prints at its real size.
"""
from __future__ import annotations

import functools
import math
import re
from html import escape

import numpy as np

from .. import numfmt

PT_PER_MM = 72.0 / 25.4
FONT = "DejaVu Sans"


def _f(x: float) -> str:
    s = f"{x:.2f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


# _f's trimming done to a whole path's data at once (its numbers written "%.2f"): the
# trailing zeros of the decimals (and then the point) dropped, "-0" written "0"
_ZZ = re.compile(r"\.00(?!\d)")
# the zero of ".d0" (not before a digit) dropped: as (\.\d)0(?!\d) -> \1 (such matches never
# overlap), a literal first and no replacement template (~4x as fast over a drawing's paths)
_Z = re.compile(r"0(?!\d)(?<=\.\d0)")
_M0 = re.compile(r"-0(?![\d.])")
_PD: dict[int, str] = {}      # path data formats by the number of points


def trim(data: str) -> str:
    """Path data whose numbers are written "%.2f", each number as _f writes it."""
    return _M0.sub("0", _Z.sub("", _ZZ.sub("", data)))


def _w(x: float) -> str:
    """A stroke width: plain decimal digits (no exponent, which CSS numbers lack)."""
    s = f"{x:.2f}" if x >= 0.01 else f"{x:.6f}"
    s = s.rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


_HEX = frozenset("0123456789abcdef")
# matplotlib's one-letter colours (as matplotlib.colors.to_hex gives them)
_BASE = {"k": "#000000", "w": "#ffffff", "r": "#ff0000", "g": "#008000", "b": "#0000ff", "c": "#00bfbf",
         "m": "#bf00bf", "y": "#bfbf00"}


_CSS: dict[str, str] = {}        # the colours converted so far (a drawing uses a handful, thousands of times)


def css_color(c) -> str:
    """Any colour our drawings are given (a matplotlib-style spec as well: 'k', '0.35',
    'tab:blue', an RGB tuple) as a valid SVG 1.1 / CSS colour: '#rrggbb' or 'none'.
    Browsers draw nothing for colours such as 'k' or '0.35' (weasyprint tolerates
    them), so every colour is converted here, at the writer."""
    if isinstance(c, str):
        got = _CSS.get(c)
        if got is None:
            got = _css_color(c)
            if len(_CSS) < 4096:
                _CSS[c] = got
        return got
    return _css_color(c)


def _css_color(c) -> str:
    s = c.strip().lower() if isinstance(c, str) else None
    if s == "none":
        return s
    if s and s[0] == "#" and len(s) in (4, 7) and set(s[1:]) <= _HEX:
        return s if len(s) == 7 else "#" + "".join(ch * 2 for ch in s[1:])
    if s in _BASE:
        return _BASE[s]
    if s and s.replace(".", "", 1).isdigit() and 0.0 <= float(s) <= 1.0:     # a grey level
        return "#" + f"{round(255 * float(s)):02x}" * 3
    if s in _NAMED:
        return _NAMED[s]
    if s and s[0] == "c" and s[1:].isdigit():          # matplotlib's cycle 'C0'..'C9' (tab10)
        return _TAB10[int(s[1:]) % 10]
    if not isinstance(c, str):                         # an RGB(A) tuple of 0..1
        try:
            v = [float(x) for x in c][:3]
        except (TypeError, ValueError):
            v = []
        if len(v) == 3 and all(0.0 <= x <= 1.0 for x in v):
            return "#" + "".join(f"{round(255 * x):02x}" for x in v)
    raise ValueError(f"not a colour: {c!r}")


# tab10, matplotlib's default cycle ('C0'..'C9', 'tab:blue'...), and the CSS names the drawings use
_TAB10 = ("#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f",
          "#bcbd22", "#17becf")
_NAMED = {"tab:" + n: c for n, c in zip(("blue", "orange", "green", "red", "purple", "brown", "pink", "gray",
                                        "olive", "cyan"), _TAB10)}
_NAMED.update({"tab:grey": _TAB10[7], "black": "#000000", "white": "#ffffff", "red": "#ff0000",
               "green": "#008000", "blue": "#0000ff", "gray": "#808080", "grey": "#808080",
               "orange": "#ffa500", "purple": "#800080", "brown": "#a52a2a", "cyan": "#00ffff",
               "magenta": "#ff00ff", "yellow": "#ffff00", "navy": "#000080", "darkgreen": "#006400",
               "darkred": "#8b0000", "lightgray": "#d3d3d3", "lightgrey": "#d3d3d3", "silver": "#c0c0c0"})



def block_corners(c, angle_deg: float, w: float, h: float) -> list[np.ndarray]:
    """The four corners of a slider block w (along angle_deg) x h centred at c,
    shared by the drawings and the sheets."""
    a = math.radians(angle_deg)
    u = np.array([math.cos(a), math.sin(a)])
    v = np.array([-u[1], u[0]])
    c = np.asarray(c, float)
    return [c + u * w / 2 + v * h / 2, c - u * w / 2 + v * h / 2,
            c - u * w / 2 - v * h / 2, c + u * w / 2 - v * h / 2]

_TEXT_SIZES: dict[float, dict[str, str]] = {}


def _text_sizes(size: float) -> dict[str, str]:
    """The attributes of a label of font size ``size`` pt that depend on the size only
    (Canvas.text, thousands of labels in a handful of sizes): made once per size."""
    got = _TEXT_SIZES.get(size)
    if got is None:
        fs = size / PT_PER_MM
        got = {"fs": f'font-size="{_f(fs)}"',
               "sub": f'<tspan dy="{_f(0.3 * fs)}" font-size="{_f(0.72 * fs)}">',
               "sup": f'<tspan dy="{_f(-0.4 * fs)}" font-size="{_f(0.72 * fs)}">',
               "after_sub": f'<tspan dy="{_f(-0.3 * fs)}" font-size="{_f(fs)}">',
               "after_sup": f'<tspan dy="{_f(0.4 * fs)}" font-size="{_f(fs)}">'}
        if len(_TEXT_SIZES) < 256:
            _TEXT_SIZES[size] = got
    return got


_TEXT_STYLES: dict[tuple, str] = {}      # a label style's attributes after x and y (Canvas.text)
_CIRCLE_TAILS: dict[tuple, str] = {}     # a circle style's attributes after its centre and radius
# html.escape(s), remembered for the labels' texts (a drawing's few hundred, over and over)
_escape = functools.lru_cache(maxsize=4096)(escape)


_ARCS: dict[bool, list[tuple[float, float]]] = {}


def _arc_unit(ccw: bool) -> list[tuple[float, float]]:
    """(cos t, sin t) at Canvas.moment's 24 angles of its 3/4 arc (ccw or cw): the same
    numbers for every couple, computed once."""
    got = _ARCS.get(ccw)
    if got is None:
        sgn = 1.0 if ccw else -1.0
        t = np.linspace(math.radians(200), math.radians(200) + sgn * math.radians(260), 24)
        got = _ARCS[ccw] = [(math.cos(a), math.sin(a)) for a in t.tolist()]
    return got


class Canvas:
    """A drawing of width_mm x height_mm; see the module docstring."""

    # polyline and polygon as here: arrow, text (halo) and circle write their path data and
    # elements straight into the merged paths (a subclass that records the primitives instead,
    # sheets.prims.PrimCanvas, gets them through its own polyline and polygon)
    _plain = True

    def __init_subclass__(cls, **kw):
        super().__init_subclass__(**kw)
        cls._plain = cls.polyline is Canvas.polyline and cls.polygon is Canvas.polygon

    def __init__(self, width_mm: float, height_mm: float):
        self.w = float(width_mm)
        self.h = float(height_mm)
        self._strokes: dict[tuple, list[str]] = {}   # style -> path data pieces
        self._fills: dict[tuple, list[str]] = {}
        self._items: list[tuple[int, str]] = []       # (z, element) drawn after the paths of lower z
        self._order: list[tuple] = []
        self._arrows: dict[tuple, tuple[list[str], list[str]]] = {}   # an arrow style's two path lists

    def _stroke_list(self, color, width, dash, z) -> list[str]:
        """The path data pieces of a stroke style (registered in the drawing order when new)."""
        key = ("s", z, css_color(color), round(width, 3), dash)
        got = self._strokes.get(key)
        if got is None:
            got = self._strokes[key] = []
            self._order.append(key)
        return got

    def _fill_list(self, fill, z) -> list[str]:
        key = ("f", z, css_color(fill))
        got = self._fills.get(key)
        if got is None:
            got = self._fills[key] = []
            self._order.append(key)
        return got

    # ------------------------------------------------------------ geometry
    def _y(self, y: float) -> float:
        return self.h - y

    def _pd(self, pts, closed=False) -> str:
        """Path data of the points, its numbers "%.2f" (to_svg trims them as _f does, a
        whole path at once: one formatting of all the numbers, not one call per number)."""
        h = self.h
        if type(pts) is np.ndarray and pts.ndim == 2 and pts.shape[1] == 2:
            a = pts.astype(float)                  # (a copy: the same float(x), h - float(y))
            a[:, 1] = h - a[:, 1]
            xy = a.ravel().tolist()
        else:
            xy = []
            for p in pts:
                xy.append(float(p[0]))
                xy.append(h - float(p[1]))
        n = len(xy) // 2
        fmt = _PD.get(n)
        if fmt is None:
            fmt = "M" + " L".join(["%.2f %.2f"] * n)
            if len(_PD) < 256:
                _PD[n] = fmt
        return fmt % tuple(xy) + ("Z" if closed else "")

    # ------------------------------------------------------------ primitives
    def polyline(self, pts, color="#000", width=0.25, dash=None, z=1, closed=False):
        """A stroked polyline (mm); merged with every other of the same style."""
        self._stroke_list(color, width, dash, z).append(self._pd(pts, closed))

    def line(self, p, q, color="#000", width=0.25, dash=None, z=1):
        self.polyline([p, q], color, width, dash, z)

    def polygon(self, pts, fill="#000", z=2, stroke=None, width=0.2):
        """A filled polygon (merged per fill colour); optional outline."""
        self._fill_list(fill, z).append(self._pd(pts, True))
        if stroke:
            self.polyline(pts, stroke, width, z=z, closed=True)

    def circle(self, c, r, stroke="#000", fill="#fff", width=0.25, z=5):
        key = (fill, stroke, width)
        tail = _CIRCLE_TAILS.get(key)
        if tail is None:
            tail = (f'fill="{css_color(fill)}" stroke="{css_color(stroke)}" '
                    f'stroke-width="{_w(width)}"/>')
            if len(_CIRCLE_TAILS) < 1024:
                _CIRCLE_TAILS[key] = tail
        self._items.append((z, f'<circle cx="{_f(c[0])}" cy="{_f(self._y(c[1]))}" r="{_f(r)}" {tail}'))

    def dot(self, c, r=0.5, color="#000", z=6):
        self.circle(c, r, stroke="none", fill=color, width=0, z=z)

    def arrow(self, p, q, color="#000", width=0.3, head=2.2, head_w=None, dash=None, z=3):
        """Vector p -> q with a filled head of length `head` mm (shortened for
        short vectors); nothing for a zero vector."""
        # in plain floats: the same operations, x and y apart, as on 2-vectors
        px, py = float(p[0]), float(p[1])
        qx, qy = float(q[0]), float(q[1])
        dx, dy = qx - px, qy - py
        L = float(np.hypot(dx, dy))
        if L < 1e-9:
            return
        ux, uy = dx / L, dy / L
        hl = min(head, 0.45 * L) if L < 2.2 * head else head
        hw = (head_w if head_w is not None else 0.36 * head) * hl / head
        bx, by = qx - ux * hl, qy - uy * hl        # the head's base
        nx, ny = -uy, ux
        sx, sy = bx + ux * 0.1 * hl, by + uy * 0.1 * hl          # the shaft's end
        lx, ly, rx, ry = bx + nx * hw, by + ny * hw, bx - nx * hw, by - ny * hw
        if not (self._plain and type(color) is str):
            self.polyline([(px, py), (sx, sy)], color, width, dash, z)
            self.polygon([(qx, qy), (lx, ly), (rx, ry)], color, z + 1)
            return
        # the same path data as polyline and polygon write (_pd), straight into their lists
        key = (color, width, dash, z)
        lists = self._arrows.get(key)
        if lists is None:
            lists = self._arrows[key] = (self._stroke_list(color, width, dash, z), self._fill_list(color, z + 1))
        h = self.h
        lists[0].append("M%.2f %.2f L%.2f %.2f" % (px, h - py, sx, h - sy))
        lists[1].append("M%.2f %.2f L%.2f %.2f L%.2f %.2fZ" % (qx, h - qy, lx, h - ly, rx, h - ry))

    def font_mm(self, size: float) -> float:
        """The font size in mm that a label asked for at ``size`` pt is drawn at (a drawing
        sheet's canvas sets its labels in the standard sizes of lettering)."""
        return size / PT_PER_MM

    def text(self, x, y, s, size=7.0, color="#000", anchor="middle", italic=False, bold=False,
             sub: str | None = None, sup: str | None = None, z=8, vcenter=True, halo=False,
             after: str | None = None):
        """A label at (x, y) mm; size in pt.  vcenter: (x, y) is the middle of the
        text height (else the baseline).  sub/sup: a smaller lowered/raised tail
        (M + sub 'Φ2' -> M_Φ2); after: normal text after the sub/sup ('μ' 'F' ' = 5 N/mm')."""
        fs = size / PT_PER_MM
        yb = self._y(y) + (0.35 * fs if vcenter else 0.0)
        fsz = _text_sizes(size)
        style = (size, anchor, color, italic, bold)
        attrs = _TEXT_STYLES.get(style)
        if attrs is None:                      # the attributes after x and y, made once per style
            attrs = [fsz["fs"]]
            if anchor != "start":
                attrs.append(f'text-anchor="{anchor}"')
            c = css_color(color)
            if c != "#000000":
                attrs.append(f'fill="{c}"')
            if italic:
                attrs.append('font-style="italic"')
            if bold:
                attrs.append('font-weight="bold"')
            attrs = " ".join(attrs)
            if len(_TEXT_STYLES) < 1024:
                _TEXT_STYLES[style] = attrs
        if numfmt.comma():                     # a label's numbers as the language writes them
            s, after = numfmt.localize(s), after and numfmt.localize(after)
        body = _escape(s)
        if sub:
            body += f'{fsz["sub"]}{_escape(sub)}</tspan>'
        elif sup:
            body += f'{fsz["sup"]}{_escape(sup)}</tspan>'
        if after and (sub or sup):
            body += f'{fsz["after_sub" if sub else "after_sup"]}{_escape(after)}</tspan>'
        elif after:
            body += _escape(after)
        el = f'<text x="{_f(x)}" y="{_f(yb)}" {attrs}>{body}</text>'
        if halo:
            # a white box under the label keeps it readable over lines (merged into one path)
            w = 0.6 * fs * (len(s) + 0.72 * len(sub or sup or "")) + 0.6
            x0 = x - w / 2 if anchor == "middle" else (x - w if anchor == "end" else x)
            yc = y if vcenter else y + 0.35 * fs
            xa, xb, ya, yb = x0 - 0.3, x0 + w - 0.3, yc - 0.62 * fs, yc + 0.62 * fs
            if self._plain:                    # polygon's path data (_pd), written here
                h = self.h
                xa, xb, ya, yb = float(xa), float(xb), h - float(ya), h - float(yb)
                self._fill_list("#fff", z - 1).append(
                    "M%.2f %.2f L%.2f %.2f L%.2f %.2f L%.2f %.2fZ" % (xa, ya, xb, ya, xb, yb, xa, yb))
            else:
                self.polygon([(xa, ya), (xb, ya), (xb, yb), (xa, yb)], "#fff", z=z - 1)
        self._items.append((z, el))

    def hatch(self, p, q, outward, depth=1.2, step=1.6, color="#000", width=0.25, z=1):
        """A ground line p-q hatched on the side `outward` (fixed link)."""
        p = np.asarray(p, float)
        q = np.asarray(q, float)
        o = np.asarray(outward, float)
        o = o / (np.hypot(*o) or 1.0)
        self.line(p, q, color, width * 1.4, z=z)
        L = float(np.hypot(*(q - p)))
        if L <= 0:
            return
        t = (q - p) / L
        n = max(2, int(L / step))
        for s in np.linspace(0, L, n + 1)[1:]:
            a = p + t * s
            self.line(a, a + o * depth - t * depth, color, width * 0.8, z=z)

    def ground(self, c, size=1.6, color="#000", width=0.25, z=1):
        """A fixed pivot: a triangle under the joint on a hatched base."""
        c = np.asarray(c, float)
        h = 1.7 * size
        self.polyline([c + (-size, -h), c, c + (size, -h)], color, width, z=z)
        self.hatch(c + (-1.6 * size, -h), c + (1.6 * size, -h), (0, -1), depth=0.7 * size,
                   step=0.9 * size, color=color, width=width, z=z)

    def block(self, c, angle_deg, w=7.0, h=4.0, color="#000", width=0.3, fill="#fff", z=4):
        """A slider block centred at c, its long side along angle_deg."""
        pts = block_corners(c, angle_deg, w, h)
        self.polygon(pts, fill, z)
        self.polyline(pts, color, width, z=z, closed=True)

    def moment(self, c, r, M, color="#000", width=0.3, z=3):
        """A couple M (ccw positive) as a 3/4 circular arrow of radius r around c."""
        if M == 0 or not math.isfinite(M):
            return
        # in plain floats: the same operations, x and y apart, as on 2-vectors
        cx, cy = (float(v) for v in np.asarray(c, float))
        pts = [(cx + r * ca, cy + r * sa) for ca, sa in _arc_unit(M > 0)]
        (x1, y1), (x2, y2) = pts[-1], pts[-2]
        self.polyline(pts[:-2], color, width, z=z)
        self.arrow(pts[-3], (x1 + (x1 - x2) * 0.5, y1 + (y1 - y2) * 0.5), color, width, head=1.8, z=z)

    # ------------------------------------------------------------ output
    def to_svg(self) -> str:
        out = [f'<svg xmlns="http://www.w3.org/2000/svg" class="fig" width="{self.w * PT_PER_MM:.1f}pt" '
               f'height="{self.h * PT_PER_MM:.1f}pt" viewBox="0 0 {_f(self.w)} {_f(self.h)}" '
               f'font-family="{FONT}">']
        layers: dict[int, list[str]] = {}
        for key in self._order:
            if key[0] == "s":
                _, z, color, width, dash = key
                da = f' stroke-dasharray="{dash}"' if dash else ""
                el = (f'<path d="{trim(" ".join(self._strokes[key]))}" fill="none" stroke="{color}" '
                      f'stroke-width="{_w(width)}"{da} '
                      f'stroke-linejoin="round" stroke-linecap="round"/>')
            else:
                _, z, fill = key
                el = f'<path d="{trim(" ".join(self._fills[key]))}" fill="{fill}" stroke="none"/>'
            layers.setdefault(z, []).append(el)
        for z, el in self._items:
            layers.setdefault(z, []).append(el)
        for z in sorted(layers):
            out.extend(layers[z])
        out.append("</svg>")
        return "\n".join(out)

