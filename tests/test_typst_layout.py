"""The pages of report.pdf read back by their words (pdftotext -bbox): no heading left at
the foot of a page with its content on the next, no nearly empty page, the worked
formulas typeset as mathematics (spaced operators, not crammed)."""
from __future__ import annotations

import html as H
import re
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
MM = 72 / 25.4
MARGIN_TOP, MARGIN_BOTTOM = 15 * MM, 16 * MM          # the report's page margins (typst_pdf.PREAMBLE)

pytestmark = pytest.mark.skipif(shutil.which("pdftotext") is None, reason="pdftotext not installed")


def _pages(pdf: Path) -> list[tuple[float, list[tuple[float, float, str]]]]:
    """[(page height, [(y top, y bottom, word)])] of the page bodies (the footer left out)."""
    out = subprocess.run(["pdftotext", "-bbox", str(pdf), "-"], capture_output=True, text=True,
                         check=True).stdout
    pages = []
    for h, body in re.findall(r'<page width="[\d.]+" height="([\d.]+)">(.*?)</page>', out, re.S):
        h = float(h)
        words = [(float(y0), float(y1), H.unescape(w)) for y0, y1, w in
                 re.findall(r'<word xMin="[\d.]+" yMin="([\d.]+)" xMax="[\d.]+" yMax="([\d.]+)">(.*?)</word>',
                            body)]
        pages.append((h, [w for w in words if w[0] < h - MARGIN_BOTTOM]))
    return pages


def _lines(words) -> list[tuple[float, str]]:
    rows: dict[int, list] = {}
    for y0, y1, w in words:
        rows.setdefault(round(y0), []).append(w)
    return [(y, " ".join(ws)) for y, ws in sorted(rows.items())]


@pytest.fixture(scope="module", params=[("forging_sixbar", "en"), ("shaper_slotted_lever", "ru"),
                                        ("engine_slider_crank", "uk")])
def report(request, shared_once):
    # report.html and report.pdf as `tmm run --format html,pdf` writes them, made once per session
    # (tests/pdf_extent.py: the pages' extents are measured on the same)
    from pdf_extent import report_out
    name, lang = request.param
    out = report_out(shared_once, name, lang)
    page = (out / "report.html").read_text(encoding="utf-8")
    heads = {re.sub(r"\s+", " ", H.unescape(re.sub(r"<[^>]+>", "", h))).strip()
             for h in re.findall(r"<h[2-4][^>]*>(.*?)</h[2-4]>", page, re.S)}
    return name, _pages(out / "report.pdf"), heads - {""}


def test_no_heading_at_the_foot_of_a_page(report):
    """A page whose last heading has at most 15 mm of text under it while more than 60 mm of
    the page stay empty: the heading (and its note) left behind by what it introduces."""
    name, pages, heads = report
    for k, (h, words) in enumerate(pages[:-1], start=1):
        lines = _lines(words)
        at = [y for y, t in lines if re.sub(r"^\d+(\.\d+)*\.? ", "", t) in heads]
        if not at:
            continue
        below = [y for y, _ in lines if y > at[-1]]
        end = max(below, default=at[-1])
        assert not (end - at[-1] < 15 * MM and h - MARGIN_BOTTOM - end > 60 * MM), \
            (name, k, [t for y, t in lines if y >= at[-1]])


def test_no_nearly_empty_page(report):
    """Every page but the last is filled to a quarter of its body at least."""
    name, pages, _ = report
    for k, (h, words) in enumerate(pages[:-1], start=1):
        body = h - MARGIN_TOP - MARGIN_BOTTOM
        assert words and (max(y1 for _, y1, _ in words) - MARGIN_TOP) / body > 0.25, (name, k)


def test_worked_formulas_typeset_as_mathematics(report):
    """The step-by-step formulas: operators with the spaces of mathematics between numbers
    ('5.236 ⋅ 0.1500 = 0.7854'), none crammed ('5.236·0.1500=0.7854')."""
    name, pages, _ = report
    text = "\n".join(t for _, words in pages for _, t in _lines(words))
    spaced = re.findall(r"\d \u22c5 \d[\d.,]* = \d", text)          # a decimal point or comma (ru, uk)
    crammed = re.findall(r"\d[·\u22c5]\d[\d.,]*=\d", text)
    assert len(spaced) >= 10 and not crammed, (name, len(spaced), crammed[:3])
