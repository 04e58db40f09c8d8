"""The explorer's drawings (report.html's mechanism in motion: the mechanism, the velocity
and acceleration plans, the force polygons, Zhukovsky's lever): at every crank angle of
its grid, no two texts overlap and none leaves its drawing.  Its plans once wrote the
letters of coincident ends over each other ("b3" on "a3" of the slotted lever).  Checked with
the instant centres P_ij drawn on the mechanism too (their box ticked).

The explorer is JavaScript: it runs here in Node on a minimal document
(tests/explore_harness.js), the report's own data and script."""
from __future__ import annotations

import json
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from pdf_extent import report_out

ROOT = Path(__file__).resolve().parents[1]
LINKAGES = sorted(p.stem for p in (ROOT / "tasks").glob("*.yaml")
                  if re.search(r"^mechanism:", p.read_text(encoding="utf-8"), re.M))

pytestmark = pytest.mark.skipif(not shutil.which("node"), reason="Node.js not installed")


def explorer_problems(html: str, centres: bool = False) -> list:
    def script(id_):
        m = re.search(rf'<script type="application/json" id="{id_}">(.*?)</script>', html, re.S)
        return json.loads(m.group(1)) if m else None
    figs = {i: [int(w), int(h)] for i, w, h in
            re.findall(r'<div class="ex-fig" id="([^"]+)" data-w="(\d+)" data-h="(\d+)"', html)}
    payload = {"js": (ROOT / "templates" / "explore.js").read_text(encoding="utf-8"),
               "data": script("ex-data"), "labels": script("ex-labels"), "forces": script("ex-forces"),
               "figs": figs, "centres": centres}
    out = subprocess.run(["node", str(ROOT / "tests" / "explore_harness.js")], input=json.dumps(payload),
                         capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout)


@pytest.mark.parametrize("name", LINKAGES)
def test_explorer_texts_neither_overlap_nor_leave(shared_once, name):
    # report.html as `tmm run --format html,pdf` writes it, made once per session (tests/test_pdf_extent.py
    # measures the same report's PDF)
    page = (report_out(shared_once, name, "en") / "report.html").read_text(encoding="utf-8")
    if 'id="ex-data"' not in page:
        pytest.skip("no explorer")
    bad = explorer_problems(page)
    assert not bad, f"{len(bad)} overlaps, e.g. {bad[:6]}"
    bad = explorer_problems(page, centres=True)         # the instant centres drawn too
    assert not bad, f"with the instant centres: {len(bad)} overlaps, e.g. {bad[:6]}"
