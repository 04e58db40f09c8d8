"""No report shows a catalogue key in place of its text: a task with a `report:` section
(the position worked step by step) once showed 'task.sec.report' as a table's caption and
a bare 'detail_position' row in the task data, in every language, and the note's table list
repeated the caption ('Table 1.8 -- task.sec.report')."""
from __future__ import annotations

import re
from pathlib import Path

import pytest

import tmm_cli
from tmm_cli.report import make_env, render
from tmm_cli.report.context import ReportContext
from tmm_cli.report.sections import task as task_section

ROOT = Path(__file__).resolve().parents[1]
RAW = re.compile(r"\btask\.(?:sec|param|word|guide|extra)[._]|\bdetail_position\b")
LINKAGES = [p for p in sorted((ROOT / "tasks").glob("*.yaml")) + sorted((ROOT / "examples").glob("*.yaml"))
            if re.search(r"^(mechanism|synthesis):", p.read_text(encoding="utf-8"), re.M)]


def _with_report(path: Path) -> str:
    return path.read_text(encoding="utf-8") + "\nreport: {detail_position: 1}\n"


@pytest.mark.parametrize("lang", ["en", "ru", "uk"])
@pytest.mark.parametrize("path", LINKAGES, ids=lambda p: p.stem)
def test_task_data_has_no_raw_key(tmp_path, path, lang):
    """Every example with a `report:` section: the task data names its sections and fields."""
    task = tmm_cli.load_task(path, text=_with_report(path))
    ctx = ReportContext(results={}, task=task, lang=lang, out_dir=tmp_path, env=make_env())
    html = task_section.build(ctx)
    assert html and not RAW.findall(html), RAW.findall(html)


def test_linkage_examples_found():
    assert len(LINKAGES) >= 10


def test_russian_report_of_a_task_with_a_report_section(tmp_path):
    """The newcomer's case: the engine with `report: {detail_position: 2}`, its Russian report."""
    path = ROOT / "tasks" / "engine_slider_crank.yaml"
    text = path.read_text(encoding="utf-8") + "\nreport: {detail_position: 2}\n"
    text = re.sub(r"(?ms)^flywheel:.*?(?=^\S|\Z)", "", text)      # not needed here
    task = tmm_cli.load_task(path, text=text)
    r = tmm_cli.run(task, kinematics_curve=0)
    render(r, task, tmp_path, {"html"}, "ru")
    html = (tmp_path / "report.html").read_text(encoding="utf-8")
    assert not RAW.findall(html), RAW.findall(html)
    assert "<caption>Отчёт</caption>" in html
    assert re.search(r"<td>положение, расписанное по шагам</td><td[^>]*>2</td>", html)
