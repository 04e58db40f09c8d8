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


@pytest.mark.parametrize("name, rocker, slotted", [
    ("synthesis_crank_rocker", ("\u043a\u043e\u0440\u043e\u043c\u044b\u0441\u043b", "\u043a\u043e\u0440\u043e\u043c\u0438\u0441\u043b"), False),
    ("synthesis_slotted_lever", ("\u043a\u0443\u043b\u0438\u0441", "\u043a\u0443\u043b\u0456\u0441"), True)])
def test_rocker_is_a_rocker_and_a_slotted_link_a_kulisa(tmp_path, name, rocker, slotted):
    """A crank-rocker's rocker is a rocker (ru 'korom..', uk 'korom..'), never a slotted link
    ('kulisa', a slotted lever's link): in the lengths, the solutions and the task data table."""
    task = tmm_cli.load_task(ROOT / "tasks" / f"{name}.yaml")
    r = tmm_cli.run(task, kinematics_curve=0)
    for lang, word in zip(("ru", "uk"), rocker):
        html = render_html(r, task, tmp_path / lang, lang)[0]
        text = re.sub(r"<[^>]+>", " ", html)
        # the names of the rocker's length l_O1B (the lengths, the solutions' head)
        names = re.findall(r"(\w+) l O1B", text)
        assert names and all(n.lower().startswith(word) for n in names), names
        assert "(\u043a\u0443\u043b" not in text          # the task data table: no 'rocker (kulisa)' either
        kulisa = ("\u043a\u0443\u043b\u0438\u0441", "\u043a\u0443\u043b\u0456\u0441")[lang == "uk"]
        i = html.index('id="synthesis"')
        sec = re.sub(r"<[^>]+>", "", html[i:html.index("</section>", i)])
        assert (kulisa in sec.lower()) == slotted
