"""Where a page break may fall in a report table (the PDF read back page by page with
pdftotext): a short table (up to 15 body rows) is never split -- it goes whole to the next
page with its caption and the heading before it (the gears' geometry table once left its
last two rows alone on page 2); a long one breaks with at least 3 body rows on either side
of the break and its header row repeated on the next page."""
from __future__ import annotations

import re
import shutil
import subprocess

import pytest

from tmm_cli.report import typst_pdf
from tmm_cli.report.typst_pdf import to_typst

typst = pytest.importorskip("typst")
pytestmark = pytest.mark.skipif(shutil.which("pdftotext") is None, reason="pdftotext not installed")


def _pages(html: str, tmp_path) -> list[str]:
    src, files = to_typst(html, "en")
    for n, data in files.items():
        (tmp_path / n).write_bytes(data)
    (tmp_path / "r.typ").write_text(src, encoding="utf-8")
    (tmp_path / "r.pdf").write_bytes(typst.compile(str(tmp_path / "r.typ"), root=str(tmp_path),
                                                   font_paths=typst_pdf._font_dirs(), pdf_tags=False))
    text = subprocess.run(["pdftotext", "-layout", str(tmp_path / "r.pdf"), "-"], capture_output=True, text=True,
                          check=True).stdout
    return text.split("\f")[:-1]


def _html(filler: int, nrows: int, kv: bool) -> str:
    """``filler`` paragraphs of text, then a heading, a caption and a table of ``nrows`` body
    rows (key-value rows of a th and a td, or a data table with a header row): row k reads
    "rowk" in its first cell."""
    paras = "".join(f"<p>Filler paragraph {k} of the text before the table, long enough to take a line.</p>"
                    for k in range(filler))
    if kv:
        body = "".join(f'<tr><th>row{k} line of action, mm</th><td class="num">{k}.5</td></tr>' for k in range(nrows))
        table = f'<table class="kv"><caption>Caption words</caption><tbody>{body}</tbody></table>'
    else:
        body = "".join(f'<tr><td>row{k}</td><td class="num">{k}.25</td><td class="num">{2 * k}.5</td></tr>'
                       for k in range(nrows))
        table = (f'<table class="data"><caption>Caption words</caption><thead><tr><th>Headname</th><th>a</th>'
                 f'<th>b</th></tr></thead><tbody>{body}</tbody></table>')
    return f"<html><body><section><h2>Text</h2>{paras}<h3>Tablehead</h3>{table}</section></body></html>"


def _rows_on(page: str) -> list[int]:
    return [int(k) for k in re.findall(r"\brow(\d+)\b", page)]


@pytest.mark.parametrize("kv", [True, False])
@pytest.mark.parametrize("nrows", [3, 6, 15])
def test_a_short_table_is_never_split(tmp_path, nrows, kv):
    # the filler is chosen (by trying) so that the table starts near the page's foot: its
    # first rows would fit there, its last ones not
    split_seen = False
    for filler in range(56, 74, 3):
        d = tmp_path / f"f{filler}"
        d.mkdir()
        pages = _pages(_html(filler, nrows, kv), d)
        where = [k for k, p in enumerate(pages) if _rows_on(p)]
        assert len(where) == 1, (filler, [(_rows_on(p)) for p in pages])
        p = pages[where[0]]
        assert _rows_on(p) == list(range(nrows))
        # the caption and the heading on the table's page
        assert "Caption words" in p and "Tablehead" in p
        split_seen = split_seen or (where[0] > 0 and "Filler" in pages[where[0] - 1]
                                    and "Filler" not in p.split("Tablehead")[1])
    assert split_seen           # at least one filler put the table at the page's foot


def test_a_long_table_breaks_with_three_rows_each_side_and_its_header_repeated(tmp_path):
    seen = set()
    for filler in range(50, 76, 1):
        d = tmp_path / f"f{filler}"
        d.mkdir()
        pages = _pages(_html(filler, 40, False), d)
        parts = [_rows_on(p) for p in pages if _rows_on(p)]
        assert [r for part in parts for r in part] == list(range(40))
        for k, part in enumerate(parts):
            assert len(part) >= 3, (filler, [len(p) for p in parts])
        for p in pages:
            if _rows_on(p):
                assert "Headname" in p          # the header on every page the table is on
        seen.add(len(parts[0]) if len(parts) > 1 else 0)
    # the break fell at many places: first parts of 1 or 2 rows would have been possible
    assert len(seen) >= 3, seen
