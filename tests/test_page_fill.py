"""No half-empty page in report.pdf without a reason: on every page but the last, the body
below the last ink (the page rendered by pdftoppm at 36 dpi, grey; a pixel row with a pixel
darker than 240 of 255 is ink) is at most 55 % of the body's height, unless what the next
page starts with -- its first block, the ink down to the first gap of 6 mm -- is taller than
that space (a figure or a table that could not come there), or the next page starts a new
section (a numbered chapter heading, "3. ...": the report starts those on a new page by
design).  The cam example's page 2 once ended after 45 % of its body, its motion diagrams on
page 3; the gears' geometry table left two rows alone on page 2 (tests/test_table_breaks.py)."""
from __future__ import annotations

import re
from pathlib import Path

import pytest

import pdf_extent as X

ROOT = Path(__file__).resolve().parents[1]
TASKS = sorted(p.stem for p in (ROOT / "tasks").glob("*.yaml"))
BLANK = 0.55
GAP_MM = 6.0

pytestmark = pytest.mark.skipif(not X.have_poppler(), reason="poppler's pdftotext/pdftoppm not installed")


def fill(images: list) -> list[tuple[float, float]]:
    """Per page (blank fraction of the body below its last ink, the height of its first block as
    a fraction of the body), of the pages rendered in grey (:func:`pdf_extent.raster`)."""
    import numpy as np
    out = []
    for im in images:
        s = im.shape[0] / X.PAGE_H
        body = im[int(X.BODY[1] * s):int(X.BODY[3] * s)]
        ink = (body < 240).any(axis=1)
        rows = np.nonzero(ink)[0]
        n = body.shape[0]
        if not len(rows):
            out.append((1.0, 0.0))
            continue
        gap = GAP_MM * X.MM * s
        first_end, prev = rows[0], rows[0]
        for r in rows[1:]:
            if r - prev > gap:
                break
            first_end = prev = r
        out.append((1 - (rows[-1] + 1) / n, (first_end + 1 - rows[0]) / n))
    return out


def starts_a_section(page_words) -> bool:
    """The page's first line is a numbered chapter heading ("3. Kinematics")."""
    top = sorted((w for w in page_words if w[1] < X.BODY[3]), key=lambda w: (round(w[1]), w[0]))
    return bool(top) and re.fullmatch(r"\d+\.", top[0][4]) is not None


def half_empty(pdf: Path, words: list | None = None, images: list | None = None) -> list[tuple[int, float, float]]:
    """[(page, blank fraction, the next page's first block)] of the pages left half empty without
    a reason (``words`` and ``images`` as :func:`pdf_extent.measured` gives them, else read here)."""
    pages = fill(X.raster(pdf) if images is None else images)
    words = X.words(pdf) if words is None else words
    return [(k + 1, round(b, 2), round(pages[k + 1][1], 2)) for k, (b, _) in enumerate(pages[:-1])
            if b > BLANK and pages[k + 1][1] <= b and not starts_a_section(words[k + 1])]


@pytest.mark.parametrize("name", TASKS)
def test_no_half_empty_page_without_a_reason(shared_once, name):
    # made and read once per session (test_pdf_extent reads the same)
    found = half_empty(*X.measured(shared_once, name, "en"))
    assert not found, found


@pytest.mark.parametrize("name", ["cam_knife", "gears_shifted", "engine_slider_crank"])
def test_no_half_empty_page_without_a_reason_ru(shared_once, name):
    found = half_empty(*X.measured(shared_once, name, "ru"))
    assert not found, found


def test_the_measure_sees_a_half_empty_page(tmp_path):
    """The measurement itself: a page ended after a third of its body by a forced break, the
    next one starting with a short paragraph (and that one, a line followed by a forced break),
    is found; one whose next page starts with a block taller than the space left is not."""
    import typst
    from tmm_cli.report.typst_pdf import PREAMBLE
    pre = PREAMBLE.replace("TITLE", '"t"').replace("LANG", '"en"')
    for body, want in (("#block(width: 50%, height: 80mm, fill: black)\n#pagebreak()\nWords.\n#pagebreak()\nMore.\n", [1, 2]),
                       ("#block(width: 50%, height: 80mm, fill: black)\n#block(breakable: false, width: 50%, height: 200mm, fill: black)\n",
                        [])):
        (tmp_path / "t.typ").write_text(pre + body)
        pdf = tmp_path / "t.pdf"
        pdf.write_bytes(typst.compile(str(tmp_path / "t.typ"), root=str(tmp_path)))
        assert [k for k, _, _ in half_empty(pdf)] == want
