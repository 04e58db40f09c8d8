"""Every page of report.pdf carries its own number in its footer ("k / N"): no construct of the
layout (a page break made inside a `context`, which Typst counts apart) may restart it. The
engine's Ukrainian report showed "1 / 37" on pages 19-20 and 35-37 when the sections' break
was such a construct."""
import re
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
pytestmark = pytest.mark.skipif(shutil.which("pdftotext") is None, reason="pdftotext (poppler-utils) is missing")


@pytest.mark.parametrize("task, lang", [("engine_slider_crank", "uk"), ("forging_sixbar", "ru")])
def test_footer_numbers_follow_the_pages(task, lang, shared_once):
    # report.pdf as `tmm run --format pdf --lang <lang>` writes it, made once per session
    # (tests/test_pdf_extent.py reads the same)
    from pdf_extent import report_pdf
    xml = subprocess.run(["pdftotext", "-bbox", str(report_pdf(shared_once, task, lang)), "-"], capture_output=True,
                         text=True, check=True).stdout
    pages = xml.split("<page ")[1:]
    n = len(pages)
    for k, page in enumerate(pages, start=1):
        height = float(re.search(r'height="([\d.]+)"', page).group(1))
        words = re.findall(r'yMin="([\d.]+)" xMax="[\d.]+" yMax="[\d.]+">([^<]*)</word>', page)
        foot = [w for y, w in words if float(y) > height - 16 * 72 / 25.4]      # the bottom margin (16 mm)
        text = " ".join(foot)
        assert f"{k} / {n}" in text or f"{k} /" in text and str(n) in text, (k, text)


@pytest.mark.parametrize("task, lang", [("engine_slider_crank", "uk"), ("forging_sixbar", "ru")])
def test_the_colophon_in_the_last_pages_margin(task, lang, shared_once):
    """'Computed by tmm · date' stands in the bottom margin of the last page, level with its
    number: it takes no room in the text, so it is never left alone on a page of its own (the
    balancing example's English report had a 52nd page with only this line on it)."""
    from pdf_extent import report_pdf

    from tmm_cli import locales
    first = locales.of("report", "words", lang)["report.generated"].split()[0]
    xml = subprocess.run(["pdftotext", "-bbox", str(report_pdf(shared_once, task, lang)), "-"], capture_output=True,
                         text=True, check=True).stdout
    pages = xml.split("<page ")[1:]
    hits = [(k, float(y)) for k, page in enumerate(pages, start=1)
            for y, w in re.findall(r'yMin="([\d.]+)" xMax="[\d.]+" yMax="[\d.]+">([^<]*)</word>', page)
            if w == first and float(y) > float(re.search(r'height="([\d.]+)"', page).group(1)) - 16 * 72 / 25.4]
    assert [k for k, _ in hits] == [len(pages)], hits
    last = pages[-1]
    height = float(re.search(r'height="([\d.]+)"', last).group(1))
    num = [float(y) for y, w in re.findall(r'yMin="([\d.]+)" xMax="[\d.]+" yMax="[\d.]+">([^<]*)</word>', last)
           if w == str(len(pages))]
    assert hits[0][1] > height - 16 * 72 / 25.4                   # in the bottom margin (16 mm)
    assert any(abs(hits[0][1] - y) < 0.5 for y in num)           # level with the page number
