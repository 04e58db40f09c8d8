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

from ..report.svgdraw import PT_PER_MM, Canvas

LAYERS = ("contour", "thin", "dimensions", "text")


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
    height: float                  # font size, mm
    layer: str = "text"
    anchor: str = "middle"         # start | middle | end
    color: str = "#000"
    italic: bool = False
    bold: bool = False
    sub: str | None = None
    sup: str | None = None
    after: str | None = None

    @property
    def plain(self) -> str:
        return self.s + (self.sub or self.sup or "") + (self.after or "")

    def box(self) -> tuple[float, float, float, float]:
        """(x0, y0, x1, y1): the estimated box, width 0.6 x height per character."""
        w = 0.6 * self.height * len(self.plain)
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

    def text(self, x, y, s, size=7.0, color="#000", anchor="middle", italic=False, bold=False,
             sub=None, sup=None, z=8, vcenter=True, halo=False, after=None):
        fs = size / PT_PER_MM
        if halo:
            w = 0.6 * fs * (len(s) + 0.72 * len(sub or sup or "")) + 0.6
            x0 = x - w / 2 if anchor == "middle" else (x - w if anchor == "end" else x)
            yc = y if vcenter else y + 0.35 * fs
            self.polygon([(x0 - 0.3, yc - 0.62 * fs), (x0 + w - 0.3, yc - 0.62 * fs),
                          (x0 + w - 0.3, yc + 0.62 * fs), (x0 - 0.3, yc + 0.62 * fs)], "#fff")
        self.prims.append(Text(float(x), float(y if vcenter else y + 0.35 * fs), s, fs, "text", anchor,
                               color, italic, bold, sub, sup, after))

    def mtext(self, x, y, s, h=3.5, anchor="start", **kw):
        """A label of height h mm (the sheets' own labels: 2.5, 3.5, 5, 7 mm fonts)."""
        self.text(x, y, s, size=h * PT_PER_MM, anchor=anchor, **kw)

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
        return cv.to_svg()


def is_halo(p) -> bool:
    return isinstance(p, Polyline) and bool(p.fill) and p.fill.lower() in ("#fff", "#ffffff")


def arc_points(c, r, a0, a1, n=24):
    t = np.radians(np.linspace(a0, a1, n))
    return [(c[0] + r * math.cos(a), c[1] + r * math.sin(a)) for a in t]
