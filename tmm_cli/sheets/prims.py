"""The drawing abstraction of the sheets: a sheet is one list of primitives in
millimetres (origin at the bottom left, y up), written two ways (SVG/PDF and DXF).

`PrimCanvas` has the interface of the report's SVG canvas (tmm_cli.report.svgdraw.Canvas)
but records primitives instead of SVG text, so the report's own drawing functions
(the velocity and acceleration plans, ...) draw onto a sheet unchanged: the report
figures and the sheets come from the same drawing code.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import numfmt
from ..report.svgdraw import PT_PER_MM, Canvas

LAYERS = ("contour", "thin", "dimensions", "text")
# GOST 2.304: the sizes of lettering, h = the height of the capitals in mm; a text on a
# sheet is set in DejaVu Sans, whose capitals are CAP_RATIO of the font size (1493/2048 em).
GOST_SIZES = (2.5, 3.5, 5.0, 7.0, 10.0, 14.0)
CAP_RATIO = 1493.0 / 2048.0


def gost_size(cap_mm: float) -> float:
    """The GOST 2.304 size nearest to a capital height of cap_mm (2.5 mm the smallest)."""
    return min(GOST_SIZES, key=lambda h: (abs(math.log(h / max(cap_mm, 1e-9))), h))


@dataclass(frozen=True)
class Line:
    p: tuple
    q: tuple
    layer: str
    color: str = "#000"
    width: float = 0.25
    dash: str | None = None


@dataclass(frozen=True)
class Polyline:
    pts: tuple
    layer: str
    closed: bool = False
    color: str = "#000"
    width: float = 0.25
    dash: str | None = None
    fill: str | None = None        # a filled polygon (arrow heads, halos under labels)


@dataclass(frozen=True)
class Circle:
    c: tuple
    r: float
    layer: str
    color: str = "#000"
    width: float = 0.25
    fill: str | None = None


@dataclass(frozen=True)
class Arc:
    c: tuple
    r: float
    a0: float                      # start angle, degrees, counter-clockwise to a1
    a1: float
    layer: str
    color: str = "#000"
    width: float = 0.25


@dataclass(frozen=True)
class Text:
    x: float
    y: float                       # the middle of the text height
    s: str
    height: float                  # font size, mm (its capitals: cap)
    layer: str = "text"
    anchor: str = "middle"         # start | middle | end
    color: str = "#000"
    italic: bool = False
    bold: bool = False
    sub: str | None = None
    sup: str | None = None
    after: str | None = None
    narrow: float = 1.0            # the letters' width factor (a title block's narrow cells)

    @property
    def cap(self) -> float:
        """The height of the capitals, mm: the size of the lettering (GOST 2.304)."""
        return self.height * CAP_RATIO

    @property
    def plain(self) -> str:
        return self.s + (self.sub or self.sup or "") + (self.after or "")

    def box(self) -> tuple[float, float, float, float]:
        """(x0, y0, x1, y1): the estimated box, width 0.6 x height per character."""
        w = 0.6 * self.height * len(self.plain) * self.narrow
        x0 = self.x - w / 2 if self.anchor == "middle" else (self.x - w if self.anchor == "end" else self.x)
        return x0, self.y - self.height / 2, x0 + w, self.y + self.height / 2


def _t(p) -> tuple:
    return (float(p[0]), float(p[1]))


class PrimCanvas(Canvas):
    """A Canvas that records primitives; `layer` is the layer of the lines drawn next."""

    def __init__(self, width_mm: float, height_mm: float):
        super().__init__(width_mm, height_mm)
        self.prims: list = []
        self.layer = "thin"

    def polyline(self, pts, color="#000", width=0.25, dash=None, z=1, closed=False):
        pts = tuple(_t(p) for p in pts)
        if len(pts) == 2 and not closed:
            self.prims.append(Line(pts[0], pts[1], self.layer, color, width, dash))
        else:
            self.prims.append(Polyline(pts, self.layer, closed, color, width, dash))

    def polygon(self, pts, fill="#000", z=2, stroke=None, width=0.2):
        self.prims.append(Polyline(tuple(_t(p) for p in pts), self.layer, True, fill, 0.0, None, fill))
        if stroke:
            self.polyline(pts, stroke, width, z=z, closed=True)

    def circle(self, c, r, stroke="#000", fill="#fff", width=0.25, z=5):
        self.prims.append(Circle(_t(c), float(r), self.layer, stroke, width, fill))

    def arc(self, c, r, a0, a1, color="#000", width=0.25):
        self.prims.append(Arc(_t(c), float(r), float(a0), float(a1), self.layer, color, width))

    def font_mm(self, size: float) -> float:
        """A label asked for at size pt is set in the nearest GOST 2.304 size."""
        return gost_size(size / PT_PER_MM * CAP_RATIO) / CAP_RATIO

    def text(self, x, y, s, size=7.0, color="#000", anchor="middle", italic=False, bold=False,
             sub=None, sup=None, z=8, vcenter=True, halo=False, after=None, narrow=1.0):
        if numfmt.comma():                     # the sheet's numbers as its language writes them
            s, after = numfmt.localize(s), after and numfmt.localize(after)
        # every text on a sheet in a GOST 2.304 size: the report's figures drawn here ask
        # for screen sizes in pt, the sheets' own labels (mtext) for h exactly
        fs = self.font_mm(size)
        if halo:
            w = 0.6 * fs * (len(s) + 0.72 * len(sub or sup or "")) + 0.6
            x0 = x - w / 2 if anchor == "middle" else (x - w if anchor == "end" else x)
            yc = y if vcenter else y + 0.35 * fs
            self.polygon([(x0 - 0.3, yc - 0.62 * fs), (x0 + w - 0.3, yc - 0.62 * fs),
                          (x0 + w - 0.3, yc + 0.62 * fs), (x0 - 0.3, yc + 0.62 * fs)], "#fff")
        self.prims.append(Text(float(x), float(y if vcenter else y + 0.35 * fs), s, fs, "text", anchor,
                               color, italic, bold, sub, sup, after, float(narrow)))

    def mtext(self, x, y, s, h=3.5, anchor="start", **kw):
        """A label of size h mm (GOST 2.304: the height of its capitals, 2.5, 3.5, 5, 7, 10, 14)."""
        self.text(x, y, s, size=h / CAP_RATIO * PT_PER_MM, anchor=anchor, **kw)

    def to_svg(self) -> str:
        """The primitives replayed onto the report's SVG canvas."""
        cv = Canvas(self.w, self.h)
        for p in self.prims:
            if isinstance(p, Line):
                cv.line(p.p, p.q, p.color, p.width, p.dash)
            elif isinstance(p, Polyline):
                if p.fill:
                    cv.polygon(p.pts, p.fill, z=2 if p.fill.lower() not in ("#fff", "#ffffff") else 7)
                else:
                    cv.polyline(p.pts, p.color, p.width, p.dash, closed=p.closed)
            elif isinstance(p, Circle):
                cv.circle(p.c, p.r, p.color, p.fill or "none", p.width)
            elif isinstance(p, Arc):
                a1 = p.a1 if p.a1 > p.a0 else p.a1 + 360.0
                t = np.radians(np.linspace(p.a0, a1, max(8, int((a1 - p.a0) / 5))))
                cv.polyline(np.c_[p.c[0] + p.r * np.cos(t), p.c[1] + p.r * np.sin(t)], p.color, p.width)
            else:
                cv.text(p.x, p.y, p.s, size=p.height * PT_PER_MM, color=p.color, anchor=p.anchor,
                        italic=p.italic, bold=p.bold, sub=p.sub, sup=p.sup, after=p.after)
                if p.narrow != 1.0:          # narrower letters: scaled about the anchor
                    z, el = cv._items[-1]
                    cv._items[-1] = (z, el.replace("<text ", f'<text transform="matrix({p.narrow:.4g} 0 0 1 '
                                                          f'{p.x * (1.0 - p.narrow):.3f} 0)" ', 1))
        return cv.to_svg()


def is_halo(p) -> bool:
    return isinstance(p, Polyline) and bool(p.fill) and p.fill.lower() in ("#fff", "#ffffff")


def arc_points(c, r, a0, a1, n=24):
    t = np.radians(np.linspace(a0, a1, n))
    return [(c[0] + r * math.cos(a), c[1] + r * math.sin(a)) for a in t]


def place(dst: PrimCanvas, src: PrimCanvas, dx: float, dy: float) -> None:
    """The primitives drawn on ``src`` (a drawing made at its own origin) added to ``dst``,
    moved by (dx, dy) mm: a drawing the report and a sheet share, put where the sheet wants it."""
    import dataclasses

    def m(p):
        return (p[0] + dx, p[1] + dy)
    for q in src.prims:
        if isinstance(q, Line):
            q = dataclasses.replace(q, p=m(q.p), q=m(q.q))
        elif isinstance(q, Polyline):
            q = dataclasses.replace(q, pts=tuple(m(t) for t in q.pts))
        elif isinstance(q, (Circle, Arc)):
            q = dataclasses.replace(q, c=m(q.c))
        elif isinstance(q, Text):
            q = dataclasses.replace(q, x=q.x + dx, y=q.y + dy)
        dst.prims.append(q)

