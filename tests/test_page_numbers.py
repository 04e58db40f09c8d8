"""Every page of report.pdf carries its own number in its footer ("k / N"): no construct of the
layout (a page break made inside a `context`, which Typst counts apart) may restart it. The
engine's Ukrainian report showed "1 / 37" on pages 19-20 and 35-37 when the sections' break
was such a construct."""
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
pytestmark = pytest.mark.skipif(shutil.which("pdftotext") is None, reason="pdftotext (poppler-utils) is missing")


@pytest.mark.parametrize("task, lang", [("engine_slider_crank", "uk"), ("forging_sixbar", "ru")])
def test_footer_numbers_follow_the_pages(task, lang, tmp_path):
    p = subprocess.run([sys.executable, "-m", "tmm_cli", "run", str(ROOT / "tasks" / f"{task}.yaml"), "--out",
                        str(tmp_path), "--format", "pdf", "--lang", lang, "--quiet"], capture_output=True, text=True,
                       timeout=600)
    assert p.returncode == 0, p.stderr
    xml = subprocess.run(["pdftotext", "-bbox", str(tmp_path / "report.pdf"), "-"], capture_output=True, text=True,
                         check=True).stdout
    pages = xml.split("<page ")[1:]
    n = len(pages)
    for k, page in enumerate(pages, start=1):
        height = float(re.search(r'height="([\d.]+)"', page).group(1))
        words = re.findall(r'yMin="([\d.]+)" xMax="[\d.]+" yMax="[\d.]+">([^<]*)</word>', page)
        foot = [w for y, w in words if float(y) > height - 16 * 72 / 25.4]      # the bottom margin (16 mm)
        text = " ".join(foot)
        assert f"{k} / {n}" in text or f"{k} /" in text and str(n) in text, (k, text)
