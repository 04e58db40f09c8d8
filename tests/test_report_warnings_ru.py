"""Stage warnings are rendered in the Russian report from their codes (numbers kept as in
the English text; phase names and senses in course terms)."""
from __future__ import annotations

from pathlib import Path

import pytest

import tmm_cli
from tmm_cli.messages import Message, localize, render
from tmm_cli.report import render as render_report

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.parametrize("code,params,en,ru", [
    ("cam.soft_impact", {"phi": 140.0, "where": "far_dwell/return"},
     "soft impact (finite jump of acceleration) at phi = 140 deg (far_dwell/return)",
     "мягкий удар (конечный скачок ускорения) при φ = 140° (дальнее стояние / возвращение)"),
    ("cam.rigid_impact", {"phi": 90.0, "where": "rise"},
     "rigid impact (jump of velocity, infinite acceleration) at phi = 90 deg (rise)",
     "жёсткий удар (скачок скорости, бесконечное ускорение) при φ = 90° (удаление)"),
    ("gears.undercut", {"wheel": 2, "z": 15, "x": 0.0, "x_min": 0.11764705882352944},
     "gears: wheel 2 (z = 15) is undercut: x2 = 0 < x_min = 0.1176",
     "зубчатая передача: колесо 2 (z = 15) подрезано: x2 = 0 < x_min = 0,1176"),
    ("cam.swing_auto", {"swing": "with", "r0": 20.29442991, "other": "against", "r0_other": 21.4868449},
     "swing auto: the rocker turns with the cam on the rise (r0 = 20.294 mm; against: 21.487 mm)",
     "выбор направления: коромысло на удалении вращается в сторону вращения кулачка (r0 = 20,294 мм; "
     "против вращения: 21,487 мм)"),
])
def test_known_warnings(code, params, en, ru):
    m = Message(code, **params)
    assert m == en and m.code == code
    assert render(code, m.params, "ru") == ru
    assert localize(m.to_dict(), "ru") == ru
    assert render(code, m.params, "en") == en


def test_unknown_code_shows_the_english_text():
    """A results.json from a newer tmm (a code this version does not know): its English text."""
    entry = {"code": "cam.something_new", "params": {}, "text": "something new"}
    assert localize(entry, "ru") == "something new"


def test_russian_cam_report_has_no_english_warning(tmp_path):
    task = tmm_cli.load_task(ROOT / "tasks" / "cam_offset.yaml")
    res = tmm_cli.run(task)
    assert any("soft impact" in w for w in res["warnings"])      # results stay language-neutral
    assert [m["text"] for m in res["messages"]] == res["warnings"]
    render_report(res, task, tmp_path, {"html"}, "ru")
    html = (tmp_path / "report.html").read_text(encoding="utf-8")
    assert "soft impact" not in html and "мягкий удар" in html
