"""The kinetostatics report section renders in both languages from results only, and
its CSV carries the results' numbers at full precision."""
from __future__ import annotations

import csv
import copy

import pytest

import tmm_cli
from tmm_cli.report import render

from test_kinetostatics_pipeline import SHAPER


@pytest.fixture(scope="module")
def shaper():
    task = tmm_cli.load_task(copy.deepcopy(SHAPER))
    return task, tmm_cli.run(task, kinematics_curve=0)


@pytest.mark.parametrize("lang,word", [("en", "Zhukovsky lever"), ("ru", "Рычаг Жуковского")])
def test_section_renders(tmp_path, shaper, lang, word):
    task, r = shaper
    render(r, task, tmp_path, {"html"}, lang)
    html = (tmp_path / "report.html").read_text(encoding="utf-8")
    assert 'id="kinetostatics"' in html and word in html
    assert html.count("<svg") >= 12            # a free-body figure per grid position at least
    with open(tmp_path / "kinetostatics.csv", encoding="utf-8") as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) == len(r["kinetostatics"])
    for row, e in zip(rows, r["kinetostatics"]):
        assert int(row["index"]) == e["index"]
        assert float(row["balancing_moment"]) == e["balancing_moment"]
        assert float(row["R01_R"]) == e["reactions"]["R01"]["R"]


def test_section_absent_without_kinetostatics(tmp_path, shaper):
    task, r = shaper
    r = {k: v for k, v in r.items() if k not in ("kinetostatics", "kinetostatics_info")}
    render(r, task, tmp_path, {"html"}, "en")
    assert 'id="kinetostatics"' not in (tmp_path / "report.html").read_text(encoding="utf-8")
