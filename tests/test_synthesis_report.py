"""The report's synthesis section: rendered in en and ru with the construction drawn
at a standard scale that fits the page and the analysed numbers of results.json."""
from __future__ import annotations

import re
from pathlib import Path

import pytest

import tmm_cli
from tmm_cli.report import render_html
from tmm_cli.report.sections.synthesis import construction_svg

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.parametrize("name", ["synthesis_offset_slider_crank", "synthesis_crank_rocker", "synthesis_shaper",
                                  "synthesis_slotted_lever"])
def test_section_en_ru(tmp_path, name):
    task = tmm_cli.load_task(ROOT / "tasks" / f"{name}.yaml")
    r = tmm_cli.run(task, kinematics_curve=0)
    s = r["synthesis"]
    for lang, title in (("en", "Synthesis of the lever mechanism"), ("ru", "Синтез рычажного механизма")):
        html = render_html(r, task, tmp_path / lang, lang)[0]
        i = html.index('id="synthesis"')
        sec = html[i:html.index("</section>", i)]
        assert title in sec
        assert sec.count("<svg") == 2
        assert "syn." not in re.sub(r"<[^>]+>", " ", sec)          # every phrase translated
        assert f"{s['K']:.5f}"[:6] in sec.replace(",", ".")
    svg, scale = construction_svg(s)
    # every point of the construction lies inside the 165 x 100 mm drawing at 1:scale
    k = 1000.0 / scale
    pts = [v for v in s["construction"].values() if isinstance(v, list) and len(v) == 2]
    xs, ys = [p[0] for p in pts], [p[1] for p in pts]
    assert (max(xs) - min(xs)) * k <= 165 and (max(ys) - min(ys)) * k <= 100
