"""Tables of many numeric columns in the PDF: every number stays inside its cell.

A table of loads per position has ~19 columns; laid out in equal shares of the page, its
widest numbers (-0.03337, 0.003982) overran their cells into the next ones, and the PDF
read "1.356-0.02040" for two cells. Checked on the compiled PDF by its text: pdftotext
joins glyphs that touch into one word, so every word of the table's body must be one of
the numbers put in its cells.
"""
from __future__ import annotations

import random
import re
import shutil
import subprocess

import pytest

from tmm_cli.report import typst_pdf
from tmm_cli.report.typst_pdf import to_typst

typst = pytest.importorskip("typst")


def _table(ncols: int, nrows: int, seed: int) -> tuple[str, set[str]]:
    """A table as the report makes them: numbers to 4 significant digits (its ``fmt``) of
    either sign and magnitudes 1e-3 ... 1e4 (-0.03337, 0.003982, 2500, 201.51)."""
    from tmm_cli.report.context import fmt
    rnd = random.Random(seed)
    head = "".join(f"<th>M<sub>f{k}</sub></th>" for k in range(ncols))
    body, cells = [], set()
    for _ in range(nrows):
        row = []
        for _ in range(ncols):
            x = fmt(rnd.choice([-1, 1]) * rnd.uniform(1, 10) * 10 ** rnd.randint(-3, 3))
            cells.add(x)
            row.append(f'<td class="num">{x}</td>')
        body.append("<tr>" + "".join(row) + "</tr>")
    html = (f'<html><body><section><h2>Loads</h2><table class="data compact wide"><thead><tr>{head}</tr>'
            f'</thead><tbody>{"".join(body)}</tbody></table></section></body></html>')
    return html, cells


def _words(html: str, tmp_path, name: str) -> list[str]:
    if shutil.which("pdftotext") is None:
        pytest.skip("pdftotext not installed")
    src, files = to_typst(html, "en")
    d = tmp_path / name
    d.mkdir()
    for n, data in files.items():
        (d / n).write_bytes(data)
    (d / "r.typ").write_text(src, encoding="utf-8")
    (d / "r.pdf").write_bytes(typst.compile(str(d / "r.typ"), root=str(d), font_paths=typst_pdf._font_dirs(),
                                            pdf_tags=False))
    text = subprocess.run(["pdftotext", "-layout", str(d / "r.pdf"), "-"], capture_output=True, text=True,
                          check=True).stdout
    # (the page's number "1/1" and a heading's "1." aside)
    return [w for w in text.split() if re.match(r"^-?[0-9]", w) and "/" not in w and not w.endswith(".")]


@pytest.mark.parametrize("ncols,seed", [(19, 1), (14, 2), (24, 3), (6, 4), (12, 1), (11, 5)])
def test_numbers_of_a_wide_table_stay_in_their_cells(tmp_path, ncols, seed):
    html, cells = _table(ncols, 12, seed)
    words = [w for w in _words(html, tmp_path, f"t{ncols}") if not w.isdigit() or w in cells]
    joined = [w for w in words if w not in cells]
    assert not joined, f"numbers run together (overrunning their cells): {joined[:5]}"
    assert len(words) >= 12 * ncols * 0.9             # the numbers are read, not lost


def test_a_table_that_fits_keeps_its_style():
    """A table whose numbers fit in equal shares keeps the style's size and equal columns."""
    html, _ = _table(6, 4, 4)
    src, _ = to_typst(html, "en")
    assert "#text(size: 7.5pt)" in src and "columns: (1fr, 1fr, 1fr, 1fr, 1fr, 1fr)" in src


def test_a_wide_table_gets_columns_by_content():
    """12 columns of such numbers do not fit in equal shares: each column as wide as its
    numbers, and the font a little smaller (not below 0.8 of it: then the table is split)."""
    html, _ = _table(12, 12, 1)
    src, _ = to_typst(html, "en")
    tables = re.findall(r"#text\(size: ([0-9.]+)pt\)\[.*?#table\(columns: \(([^)]*)\)", src, re.S)
    assert len(tables) == 1
    size, cols = float(tables[0][0]), tables[0][1].split(", ")
    assert cols == ["auto"] * 12 and 0.8 * 7.5 - 1e-9 <= size < 7.5


def test_a_table_too_wide_for_the_page_is_split_repeating_its_leading_columns():
    """24 columns do not fit at 0.8 of the font: the columns in parts of one table each,
    every part led by the first two columns (the position and its angle), every column in
    one part, in order."""
    html, _ = _table(24, 4, 3)
    src, _ = to_typst(html, "en")
    parts = src.split("table.header(")[1:]                 # each from its header on
    assert len(parts) >= 2
    names = [re.findall(r'#strong\[#"M"#sub\[#"f([0-9]+)"\]\]', p) for p in parts]
    assert all(n[:2] == ["0", "1"] for n in names)
    rest = [int(x) for n in names for x in n[2:]]
    assert rest == list(range(2, 24))
    assert all(float(x) == 7.5 for x in re.findall(r"#text\(size: ([0-9.]+)pt\)\[", src))
