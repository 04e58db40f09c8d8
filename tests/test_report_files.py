"""The report's figures also stand beside it as SVG files (SPEC 2: 'with figures and
CSV tables beside them'), each a well-formed SVG, listed with its caption."""
from __future__ import annotations

import csv
import re
import xml.dom.minidom
from pathlib import Path

import tmm_cli
from tmm_cli.report import render

ROOT = Path(__file__).resolve().parents[1]


def test_figures_beside_the_report(tmp_path):
    task = tmm_cli.load_task(ROOT / "tasks" / "cam_translating.yaml")
    res = tmm_cli.run(task)
    written = render(res, task, tmp_path, {"html"}, "en")
    html = (tmp_path / "report.html").read_text(encoding="utf-8")
    n_fig = len(re.findall(r"<figure\b", html))
    files = sorted((tmp_path / "figures").glob("fig-*.svg"))
    assert n_fig > 0 and len(files) == n_fig
    for f in files:
        doc = xml.dom.minidom.parse(str(f))
        assert doc.documentElement.tagName == "svg"
        assert f in written
    rows = list(csv.DictReader((tmp_path / "figures" / "index.csv").open(encoding="utf-8")))
    assert [r["file"] for r in rows] == [f"figures/{f.name}" for f in files]
    assert not list(tmp_path.rglob("*.tmp"))
