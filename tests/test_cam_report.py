"""Cam report section: en/ru HTML, figures, files beside the report."""
import math
from pathlib import Path

import pytest

from tmm_cli import numfmt

import tmm_cli

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def central():
    task = tmm_cli.load_task({
        "schema": "tmm/1", "title": "central cam",
        "cam": {"follower": "translating", "stroke": "30 mm", "offset": 0,
                "phases": {"rise": 90, "far_dwell": 30, "return": 90},
                "laws": {"rise": "cosine", "return": "cosine"}, "pressure_angle": 30,
                "rotation": "ccw", "speed": "100 rpm"}})
    return task, tmm_cli.run(task)


def test_pipeline_section_matches_closed_form(central):
    _, res = central
    h, P, t = 0.03, math.pi / 2, math.tan(math.radians(30))
    A = h * math.pi / (2 * P * t)
    assert res["cam"]["r0"] == pytest.approx(math.sqrt(A * A + h * h / 4) - h / 2, rel=1e-10)
    assert res["cam"]["speed"] == pytest.approx(100 * math.pi / 30)
    assert "warnings" not in res["cam"] or isinstance(res["cam"]["warnings"], list)


@pytest.mark.parametrize("lang,word", [("en", "Cam mechanism"), ("ru", "Кулачковый механизм"),
                                       ("uk", "Кулачковий механізм")])
def test_html_section(central, tmp_path, lang, word):
    from tmm_cli.report import render

    task, res = central
    paths = render(res, task, tmp_path, {"html"}, lang)
    html = (tmp_path / "report.html").read_text(encoding="utf-8")
    assert 'id="cam"' in html and word in html
    assert html.count("<svg") >= 4 and "figure failed" not in html
    assert "ds/dφ" in html and "dphi" not in html          # the course's notation, as in the tables
    # the diagrams' scales as the course writes them: μ with the quantity as its subscript, a
    # quotient unit bracketed before the millimetre (it read "ds/dφ = 2,500 мм/рад/мм")
    line = html[html.index("μ<sub>φ</sub>"):].split("</p>")[0]
    assert "μ<sub>s</sub> = " in line and "μ<sub>ds/dφ</sub> = " in line and ")/" in line and "/рад/" not in line
    # r0 in mm with 6 significant digits, as computed from the closed form above
    h, P, t = 0.03, math.pi / 2, math.tan(math.radians(30))
    A = h * math.pi / (2 * P * t)
    r0_mm = (math.sqrt(A * A + h * h / 4) - h / 2) * 1000
    assert numfmt.localize(f"{r0_mm:.4f}", lang) in html       # ru, uk: the decimal comma
    names = {p.name for p in paths}
    assert {"cam_profile.csv", "cam_motion.csv", "cam_profile.dxf"} <= names
    rows = (tmp_path / "cam_profile.csv").read_text().splitlines()
    assert len(rows) == 361


@pytest.mark.parametrize("name", ["cam_translating", "cam_offset", "cam_rocker"])
def test_example_tasks_run(name):
    res = tmm_cli.run(tmm_cli.load_task(ROOT / "tasks" / f"{name}.yaml"))
    c = res["cam"]
    assert c["r0"] > 0 and c["roller"] < c["rho_min"]
    assert c["max_pressure_angle_rise"] <= c["pressure_angle_allowed"]["rise"] + 1e-9
    assert c["max_pressure_angle_return"] <= c["pressure_angle_allowed"]["return"] + 1e-9


@pytest.mark.parametrize("lang", ["en", "ru", "uk"])
def test_the_report_says_which_r0_the_profile_is_drawn_on(central, tmp_path, lang):
    """r0 computed (no r0 in the task): the profile is built on the exact least r0 (closed form
    above: the pitch point at s = 0, a central follower, lies r0 from the cam's centre), not on
    the rounded design radius printed beside it; the report says so and gives the task line
    that builds it on the rounded radius (its unit as the language writes it, which the task
    files take too) -- which, run, puts that pitch point at the whole mm."""
    import re

    from tmm_cli.report import render
    task, res = central
    c = res["cam"]
    h, P, t = 0.03, math.pi / 2, math.tan(math.radians(30))
    A = h * math.pi / (2 * P * t)
    r0 = math.sqrt(A * A + h * h / 4) - h / 2
    whole = math.ceil(r0 * 1000)                         # 31.96... mm -> 32
    k = min(range(len(c["phi"])), key=lambda i: abs(c["s"][i]))      # a point of the near dwell
    assert math.hypot(*c["pitch_profile"][k]) == pytest.approx(r0, rel=1e-9)
    render(res, task, tmp_path, {"html"}, lang)
    html = (tmp_path / "report.html").read_text(encoding="utf-8")
    unit = {"en": "mm", "ru": "мм", "uk": "мм"}[lang]
    line = f"<code>r0: {whole} {unit}</code>"
    assert html.count(line) == 1
    note = re.search(r"<p>([^<]*)" + re.escape(line), html).group(1)
    assert numfmt.localize(f"{r0 * 1000:.4f}", lang) in note and f" {whole} " in note
    given = tmm_cli.load_task({
        "schema": "tmm/1", "title": "central cam",
        "cam": {"follower": "translating", "stroke": "30 mm", "offset": 0, "r0": f"{whole} {unit}",
                "phases": {"rise": 90, "far_dwell": 30, "return": 90},
                "laws": {"rise": "cosine", "return": "cosine"}, "pressure_angle": 30,
                "rotation": "ccw", "speed": "100 rpm"}})
    g = tmm_cli.run(given)["cam"]
    assert math.hypot(*g["pitch_profile"][k]) == pytest.approx(whole / 1000, rel=1e-9)
    render(tmm_cli.run(given), given, tmp_path / "given", {"html"}, lang)
    assert "<code>r0:" not in (tmp_path / "given" / "report.html").read_text(encoding="utf-8")
