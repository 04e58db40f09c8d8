"""Every page of report.pdf carries its own number in its footer ("k / N"): no construct of the
layout (a page break made inside a `context`, which Typst counts apart) may restart it. The
engine's Ukrainian report showed "1 / 37" on pages 19-20 and 35-37 when the sections' break
was such a construct."""
import shutil

import pytest

pytestmark = pytest.mark.skipif(shutil.which("pdftotext") is None, reason="pdftotext (poppler-utils) is missing")


FOOT = 16 * 72 / 25.4          # the bottom margin (16 mm), pt


@pytest.mark.parametrize("task, lang", [("engine_slider_crank", "uk"), ("forging_sixbar", "ru")])
def test_footer_numbers_follow_the_pages(task, lang, shared_once):
    # report.pdf as `tmm run --format pdf --lang <lang>` writes it and its words (pdftotext -bbox),
    # made and read once per session (tests/test_pdf_extent.py reads the same)
    from pdf_extent import PAGE_H, measured
    _, pages, _ = measured(shared_once, task, lang)
    n = len(pages)
    for k, words in enumerate(pages, start=1):
        text = " ".join(w[4] for w in words if w[1] > PAGE_H - FOOT)
        assert f"{k} / {n}" in text or f"{k} /" in text and str(n) in text, (k, text)


@pytest.mark.parametrize("task, lang", [("engine_slider_crank", "uk"), ("forging_sixbar", "ru")])
def test_the_colophon_in_the_last_pages_margin(task, lang, shared_once):
    """'Computed by tmm · date' stands in the bottom margin of the last page, level with its
    number: it takes no room in the text, so it is never left alone on a page of its own (the
    balancing example's English report had a 52nd page with only this line on it)."""
    from pdf_extent import PAGE_H, measured

    from tmm_cli import locales
    first = locales.of("report", "words", lang)["report.generated"].split()[0]
    _, pages, _ = measured(shared_once, task, lang)
    hits = [(k, w[1]) for k, words in enumerate(pages, start=1) for w in words
            if w[4] == first and w[1] > PAGE_H - FOOT]
    assert [k for k, _ in hits] == [len(pages)], hits
    num = [w[1] for w in pages[-1] if w[4] == str(len(pages))]
    assert hits[0][1] > PAGE_H - FOOT                             # in the bottom margin (16 mm)
    assert any(abs(hits[0][1] - y) < 0.5 for y in num)           # level with the page number
