"""Tables side by side (typst_pdf: a div.tables2 / div.pair) on a page of their own (a
div.position, a block kept on one page) are a `stack` of two blocks, each laid out once,
not a grid, whose auto row lays its cells out twice (measured first). The claim checked
here: the PDF is the same, byte for byte, as with the grid; elsewhere (where a grid row may
break over pages) the grid stays."""
from __future__ import annotations

import pytest

from tmm_cli.report import typst_pdf
from tmm_cli.report.typst_pdf import to_typst

typst = pytest.importorskip("typst")

_HALF = "block(width: (100% - 3mm) / 2)["


def _compile(src: str, tmp_path) -> bytes:
    (tmp_path / "r.typ").write_text(src, encoding="utf-8")
    return typst.compile(str(tmp_path / "r.typ"), root=str(tmp_path),
                         font_paths=typst_pdf._font_dirs(), pdf_tags=False)


def _table(caption: str, rows: int, head=("Vector", "Segment", "Length, mm", "Value, m/s²")) -> str:
    th = "".join(f"<th>{h}</th>" for h in head)
    tr = "".join(f"<tr><td>a<sub>B{k}</sub><sup>τ</sup></td><td>πs₂{k}</td>"
                 f'<td class="num">{k * 17.3:.1f}</td><td class="num">{k / 7:.4g}</td></tr>'
                 for k in range(rows))
    return f'<table class="compact"><caption>{caption}</caption><thead><tr>{th}</tr></thead><tbody>{tr}</tbody></table>'


def _pair(left: str, right: str) -> str:
    return f'<div class="tables2"><div>{left}</div><div>{right}</div></div>'


HTML = ("<html><head><title>t</title></head><body><section><h2>Plans</h2>"
        # the left table the shorter, then the right one; a paragraph after the pair
        '<div class="position"><h4>Position 0</h4>'
        + _pair(_table("Velocity plan", 9), _table("Acceleration plan", 15))
        + "<p>after the tables</p></div>"
        # the left one the taller; a long wrapped note in the right cell
        '<div class="position"><h4>Position 1</h4>'
        + _pair(_table("Velocity plan", 14), "<p>" + "a note that wraps in its half " * 8 + "</p>"
                + _table("Acceleration plan", 3))
        + "</div>"
        # not on a page of its own: a grid
        + _pair(_table("Velocity plan", 4), _table("Acceleration plan", 5))
        + "</section></body></html>")


def test_pairs_on_one_page_are_a_stack_with_the_grids_pdf(tmp_path):
    src, _ = to_typst(HTML, "en")
    assert src.count("#stack(dir: ltr, spacing: 3mm, " + _HALF) == 2
    assert src.count("#grid(columns: (1fr, 1fr), gutter: 3mm, [") == 1
    grid = (src.replace("#stack(dir: ltr, spacing: 3mm, " + _HALF, "#grid(columns: (1fr, 1fr), gutter: 3mm, [")
            .replace("], " + _HALF, "], ["))
    assert "#stack" not in grid and _HALF not in grid
    assert _compile(src, tmp_path) == _compile(grid, tmp_path)
