"""render() splits the work over two processes (a forked helper builds the kinetostatics
section and paints the PDF); the report must not depend on it: the same HTML and CSV
files with the helper, without it (TMM_REPORT_JOBS=1) and when the helper fails."""
from __future__ import annotations

import re
from pathlib import Path

import pytest

import tmm_cli
import tmm_cli.report as R

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def shaper():
    task = tmm_cli.load_task(ROOT / "tasks" / "shaper_slotted_lever.yaml")
    return task, tmm_cli.run(task, kinematics_curve=0)


def _render(tmp_path, task, r, name):
    out = tmp_path / name
    paths = R.render(r, task, out, {"html"}, "en")
    return (out / "report.html").read_text(encoding="utf-8"), sorted(p.name for p in paths)


def _strip_ids(html):
    # matplotlib's random clip-path ids differ from run to run
    return re.sub(r'(id="|#)[a-z]?[0-9a-f]{8,}', "", html)


def test_same_report_with_and_without_helper(tmp_path, shaper, monkeypatch):
    task, r = shaper
    h1, f1 = _render(tmp_path, task, r, "par")
    monkeypatch.setenv("TMM_REPORT_JOBS", "1")
    h2, f2 = _render(tmp_path, task, r, "ser")
    assert f1 == f2 and "kinetostatics.csv" in f1
    assert _strip_ids(h1) == _strip_ids(h2)
    assert 'id="kinetostatics"' in h1


def test_helper_failure_falls_back(tmp_path, shaper, monkeypatch):
    task, r = shaper

    def broken(conn, *a):
        conn.send(("error", "boom"))
        conn.close()
    monkeypatch.setattr(R, "_helper", broken)
    h, files = _render(tmp_path, task, r, "fail")
    assert 'id="kinetostatics"' in h and "kinetostatics.csv" in files
