"""A sheet's primitives written as SVG, PDF and DXF (ezdxf: one layer per kind of line,
real LINE / LWPOLYLINE / CIRCLE / ARC / TEXT entities, units mm)."""
from __future__ import annotations

from ..reproducible import dxf_text
from .prims import Arc, Circle, Line, Polyline, PrimCanvas, Text, is_halo

# layer -> (ACI colour, lineweight in 1/100 mm)
DXF_LAYERS = {"contour": (7, 50), "thin": (8, 25), "dimensions": (3, 25), "text": (7, 25)}


def to_svg(cv: PrimCanvas) -> str:
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + cv.to_svg().replace(
        f'width="{cv.w * 72 / 25.4:.1f}pt" height="{cv.h * 72 / 25.4:.1f}pt"',
        f'width="{cv.w:g}mm" height="{cv.h:g}mm"', 1)


def to_pdf(svgs: list[str], w_mm: float, h_mm: float) -> bytes:
    """One PDF page per sheet, each sheet's SVG drawn at its real size (vector, the texts
    in DejaVu Sans) by Typst, the engine of report.pdf: ~10x faster than weasyprint
    (which wrote them before) and no weasyprint import."""
    import tempfile
    from pathlib import Path

    from ..report.typst_pdf import _font_links, compile_file
    with tempfile.TemporaryDirectory(prefix="tmm-sheets-") as tmp:
        d = Path(tmp)
        pages = []
        for k, svg in enumerate(svgs, start=1):
            (d / f"sheet-{k}.svg").write_text(svg, encoding="utf-8")
            pages.append(f'#image("sheet-{k}.svg", width: {w_mm:g}mm, height: {h_mm:g}mm)')
        src = (f"#set document(date: none)\n#set page(width: {w_mm:g}mm, height: {h_mm:g}mm, margin: 0pt)\n"
               + "\n#pagebreak()\n".join(pages) + "\n")
        (d / "sheets.typ").write_text(src, encoding="utf-8")
        return compile_file(d / "sheets.typ", _font_links(d / "fonts"))      # the DejaVu files only, as the report


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
            t = msp.add_text(p.plain, height=round(p.cap, 6), dxfattribs={**at, "style": "TMM"})
            if p.narrow != 1.0:
                t.dxf.width = round(p.narrow, 4)
            t.set_placement((p.x, p.y), align=align[p.anchor])
    return dxf_text(doc).encode("utf-8")
