"""Issue 10, item 3: user text never reaches report.html or an SVG figure as markup.
Every name and free-text field of the task (title, variant, student, point and link
names) is hostile markup; the report must show it as text (escaped once), nowhere as a tag."""
from __future__ import annotations

from pathlib import Path

import pytest
from typer.testing import CliRunner

from tmm_cli.cli import app

from hostile import ROOT, hostile_task, raw_markup, write_hostile

runner = CliRunner()


def _run(tmp_path: Path, data: dict | None) -> Path:
    task = write_hostile(tmp_path / "hostile.yaml", data)
    out = tmp_path / "out"
    res = runner.invoke(app, ["run", str(task), "--out", str(out), "--format", "json,html", "--quiet"])
    assert res.exit_code == 0, res.output
    return out


@pytest.mark.parametrize("base", [None, "shaper_slotted_lever"])
def test_no_raw_markup_in_report_and_figures(tmp_path, base):
    data = None if base is None else hostile_task(ROOT / "tasks" / f"{base}.yaml")
    out = _run(tmp_path, data)
    html = (out / "report.html").read_text(encoding="utf-8")
    # the report's own scripts (the mechanism in motion) are no user text: drop their tags
    own = ('<script type="application/json" id="ex-data">', '<script type="application/json" id="ex-labels">',
           '<script type="application/json" id="ex-forces">', '<script>(function () {')
    stripped = html
    for tag in own:
        stripped = stripped.replace(tag, "")
    assert raw_markup(stripped) == []
    # the names are there, as text: escaped once, not dropped and not escaped twice
    assert "&lt;script&gt;alert(" in html and "&lt;img src=x onerror=alert(" in html
    assert "&amp;lt;" not in html
    svgs = sorted((out / "figures").glob("*.svg"))
    assert svgs
    shown = 0
    for f in svgs:
        text = f.read_text(encoding="utf-8")
        assert raw_markup(text) == [], f.name
        assert "&amp;lt;" not in text, f.name
        shown += text.count("&lt;script&gt;") + text.count("&lt;img")
    assert shown > 0  # the figures do carry the hostile point names


def test_plan_segment_csv_has_plain_names(tmp_path):
    out = _run(tmp_path, hostile_task(ROOT / "tasks" / "crank_rocker_fourbar.yaml"))
    text = (out / "plans.csv").read_text(encoding="utf-8")
    # the symbol column holds the point names as written, not HTML entities
    assert "v_B<img src=x onerror=alert('B')>" in text
    assert "&lt;" not in text
