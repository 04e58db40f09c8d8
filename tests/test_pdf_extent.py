"""Nothing of a report leaves the page body: every page of every example task's
report.pdf, in en, ru and uk, has no word (pdftotext -bbox) and no ink (the page
rendered by pdftoppm) in its margins other than the footer line (the page number; on the
last page the colophon level with it).  Zhukovsky's lever of
the six-bars once ran off the bottom of each kinetostatics page, and the four-bars'
caption under it printed over the page number: a position whose drawings are taller
than a page now breaks between its figures."""
from __future__ import annotations

from pathlib import Path

import pytest

import pdf_extent as X

ROOT = Path(__file__).resolve().parents[1]
TASKS = sorted(p.stem for p in (ROOT / "tasks").glob("*.yaml"))

pytestmark = pytest.mark.skipif(not X.have_poppler(), reason="poppler's pdftotext/pdftoppm not installed")


@pytest.mark.parametrize("lang", ["en", "ru", "uk"])
@pytest.mark.parametrize("name", TASKS)
def test_every_page_inside_its_body(shared_once, name, lang):
    # made and read once per session (test_page_fill reads the same, test_page_numbers two of them)
    pdf, pages, images = X.measured(shared_once, name, lang)
    assert pages and all(X.footer_boxes(p) for p in pages)      # each page has its number
    stray = [(k + 1, w[4], [round(v / X.MM, 1) for v in w[:4]]) for k, p in enumerate(pages)
             for w in X.stray_words(p)]
    assert not stray, f"words outside the page body (page, word, box mm): {stray[:8]}"
    ink = X.stray_ink(pdf, pages, images=images)
    assert not ink, f"ink in the margins (page, margin, pixels): {ink[:8]}"


def test_the_check_sees_what_leaves_the_body(tmp_path):
    """The measurement itself: a drawing taller than the page (its block not breakable)
    runs into the bottom margin, and the check sees it."""
    import typst
    from tmm_cli.report.typst_pdf import PREAMBLE
    body = "Some words.\n#block(breakable: false, rect(width: 100mm, height: 300mm, fill: black))\nMore words.\n"
    (tmp_path / "t.typ").write_text(PREAMBLE.replace("TITLE", '"t"').replace("LANG", '"en"') + body)
    pdf = tmp_path / "t.pdf"
    pdf.write_bytes(typst.compile(str(tmp_path / "t.typ"), root=str(tmp_path)))
    pages = X.words(pdf)
    assert all(X.footer_boxes(p) for p in pages)
    assert any(m == "bottom" for _, m, _ in X.stray_ink(pdf, pages))
