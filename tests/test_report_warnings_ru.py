"""Stage warnings are translated in the Russian report (known forms; numbers kept)."""
from __future__ import annotations

from pathlib import Path

import pytest

import tmm_cli
from tmm_cli.report import render
from tmm_cli.report.i18n import translate_warning

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.parametrize("en,ru", [
    ("soft impact (finite jump of acceleration) at phi = 140 deg (far_dwell/return)",
     "мягкий удар (конечный скачок ускорения) при φ = 140° (дальний выстой / возвращение)"),
    ("rigid impact (jump of velocity, infinite acceleration) at phi = 90 deg (rise)",
     "жёсткий удар (скачок скорости, бесконечное ускорение) при φ = 90° (удаление)"),
    ("gears: wheel 2 (z = 15) is undercut: x2 = 0 < x_min = 0.1176",
     "зубчатая передача: колесо 2 (z = 15) подрезано: x2 = 0 < x_min = 0.1176"),
    ("swing auto: the rocker turns with the cam on the rise (r0 = 20.294 mm; against: 21.487 mm)",
     "выбор направления: коромысло на удалении вращается в сторону вращения кулачка (r0 = 20.294 мм; "
     "против вращения: 21.487 мм)"),
])
def test_known_warnings(en, ru):
    assert translate_warning(en, "ru") == ru
    assert translate_warning(en, "en") == en


def test_unknown_warning_kept():
    assert translate_warning("something new", "ru") == "something new"


def test_russian_cam_report_has_no_english_warning(tmp_path):
    task = tmm_cli.load_task(ROOT / "tasks" / "cam_offset.yaml")
    res = tmm_cli.run(task)
    assert any("soft impact" in w for w in res["warnings"])      # results stay language-neutral
    render(res, task, tmp_path, {"html"}, "ru")
    html = (tmp_path / "report.html").read_text(encoding="utf-8")
    assert "soft impact" not in html and "мягкий удар" in html
