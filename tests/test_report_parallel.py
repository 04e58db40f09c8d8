"""render() splits the work over two processes (a forked helper builds the kinetostatics
section and compiles the PDF); the report must not depend on it: the same HTML and CSV
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
    # the tables the helper writes (HELPER_TABLES) are the lone process's, byte for byte
    assert R.HELPER_TABLES == ("kinematics",)
    for name in ("kinematics.csv", "kinetostatics.csv"):
        assert (tmp_path / "par" / name).read_bytes() == (tmp_path / "ser" / name).read_bytes()


def test_helper_tables_listed_in_the_lone_process_order(tmp_path, shaper, monkeypatch):
    """kinematics.csv, written by the helper, is listed where the kinematics section
    would write it (the order `tmm run` prints the files in)."""
    task, r = shaper
    par = [p.name for p in R.render(r, task, tmp_path / "par", {"html"}, "en")]
    monkeypatch.setenv("TMM_REPORT_JOBS", "1")
    ser = [p.name for p in R.render(r, task, tmp_path / "ser", {"html"}, "en")]
    assert par.index("kinematics.csv") < par.index("plans.csv")
    assert [n for n in par if n != "kinetostatics.csv"] == [n for n in ser if n != "kinetostatics.csv"]


def test_helper_failure_falls_back(tmp_path, shaper, monkeypatch):
    task, r = shaper

    def broken(conn, *a):
        conn.send(("error", "boom"))
        conn.close()
    monkeypatch.setattr(R, "_helper", broken)
    h, files = _render(tmp_path, task, r, "fail")
    assert 'id="kinetostatics"' in h and "kinetostatics.csv" in files
    # the helper's table written by the main process instead
    assert (tmp_path / "fail" / "kinematics.csv").read_text(encoding="utf-8").count("\n") == 1 + len(r["kinematics"])


@pytest.mark.skipif(__import__("os").environ.get("TMM_START_METHOD") == "spawn",
                    reason="TMM_START_METHOD=spawn: no forked helper to compile the first PDF")
def test_pdf_in_a_process_that_already_used_typst(tmp_path):
    """Typst runs thread pools: a helper forked after the process compiled a PDF would wait
    for ever inside Typst.  render() then compiles the PDF itself; both reports are written
    (in a subprocess with a time limit, so that a hang fails instead of blocking)."""
    pytest.importorskip("typst")
    import subprocess
    import sys
    code = (
        "import sys, tmm_cli, tmm_cli.report as R\n"
        "from pathlib import Path\n"
        f"task = tmm_cli.load_task(Path({str(ROOT / 'tasks' / 'engine_slider_crank.yaml')!r}))\n"
        "r = tmm_cli.run(task, kinematics_curve=0)\n"
        "out = Path(sys.argv[1])\n"
        "R.render(r, task, out / '0', {'html', 'pdf'}, 'en')\n"
        "print('typst' in sys.modules)\n"
        "from tmm_cli.report.typst_pdf import pdf_bytes\n"
        "pdf_bytes('<html><body><p>x</p></body></html>')\n"
        "R.render(r, task, out / '1', {'html', 'pdf'}, 'en')\n")
    p = subprocess.run([sys.executable, "-c", code, str(tmp_path)], capture_output=True, text=True,
                       timeout=240, cwd=ROOT)
    assert p.returncode == 0, p.stderr[-2000:]
    assert p.stdout.strip() == "False"         # the first PDF was compiled by the helper
    for k in ("0", "1"):
        data = (tmp_path / k / "report.pdf").read_bytes()
        assert data.startswith(b"%PDF-") and len(data) > 10_000
