"""A sheet's primitives written as SVG, PDF and DXF (ezdxf: one layer per kind of line,
real LINE / LWPOLYLINE / CIRCLE / ARC / TEXT entities, units mm)."""
from __future__ import annotations

import io

from .prims import Arc, Circle, Line, Polyline, PrimCanvas, Text, is_halo

# layer -> (ACI colour, lineweight in 1/100 mm)
DXF_LAYERS = {"contour": (7, 50), "thin": (8, 25), "dimensions": (3, 25), "text": (7, 25)}


def to_svg(cv: PrimCanvas) -> str:
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + cv.to_svg().replace(
        f'width="{cv.w * 72 / 25.4:.1f}pt" height="{cv.h * 72 / 25.4:.1f}pt"',
        f'width="{cv.w:g}mm" height="{cv.h:g}mm"', 1)


def to_pdf(svgs: list[str], w_mm: float, h_mm: float) -> bytes:
    """One PDF page per sheet (weasyprint paints the SVG at its real size, each one an
    image: the SVG stays out of the HTML style cascade, several times faster)."""
    import base64

    from weasyprint import HTML
    body = "".join(f'<img class="s" alt="" src="data:image/svg+xml;base64,'
                   f'{base64.b64encode(s.encode("utf-8")).decode("ascii")}">' for s in svgs)
    html = (f"<html><head><style>@page {{ size: {w_mm:g}mm {h_mm:g}mm; margin: 0 }}"
            f" body {{ margin: 0 }} .s {{ width: {w_mm:g}mm; height: {h_mm:g}mm; display: block;"
            f" page-break-after: always }}</style></head><body>{body}</body></html>")
    return HTML(string=html).write_pdf()


def dxf_entities(cv: PrimCanvas) -> list:
    """The primitives that become DXF entities (the white halos under plan labels do not)."""
    return [p for p in cv.prims if not is_halo(p)]


def to_dxf(cv: PrimCanvas) -> bytes:
    import ezdxf
    from ezdxf.enums import TextEntityAlignment

    doc = ezdxf.new("R2010", setup=True)
    doc.header["$INSUNITS"] = 4          # millimetres
    doc.header["$MEASUREMENT"] = 1
    doc.header["$LIMMAX"] = (cv.w, cv.h)
    for name, (color, lw) in DXF_LAYERS.items():
        doc.layers.add(name, color=color, lineweight=lw)
    doc.styles.add("TMM", font="DejaVuSans.ttf")
    msp = doc.modelspace()
    align = {"start": TextEntityAlignment.MIDDLE_LEFT, "middle": TextEntityAlignment.MIDDLE_CENTER,
             "end": TextEntityAlignment.MIDDLE_RIGHT}
    for p in dxf_entities(cv):
        at = {"layer": p.layer}
        if isinstance(p, Line):
            msp.add_line(p.p, p.q, dxfattribs=at)
        elif isinstance(p, Polyline):
            if p.fill and len(p.pts) in (3, 4):
                pts = list(p.pts) if len(p.pts) == 3 else [p.pts[0], p.pts[1], p.pts[3], p.pts[2]]
                msp.add_solid(pts, dxfattribs=at)
            else:
                msp.add_lwpolyline(p.pts, close=p.closed or bool(p.fill), dxfattribs=at)
        elif isinstance(p, Circle):
            msp.add_circle(p.c, p.r, dxfattribs=at)
        elif isinstance(p, Arc):
            msp.add_arc(p.c, p.r, p.a0, p.a1, dxfattribs=at)
        elif isinstance(p, Text):
            t = msp.add_text(p.plain, height=0.7 * p.height, dxfattribs={**at, "style": "TMM"})
            t.set_placement((p.x, p.y), align=align[p.anchor])
    buf = io.StringIO()
    doc.write(buf)
    return buf.getvalue().encode("utf-8")
