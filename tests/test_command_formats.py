"""Every option of the commands that write files, with every format they accept: exit 0
and the files the format promises.  `tmm run --study` with the default formats (the PDF
included) once failed on every task with an internal Typst error, because the only test
of it asked for json,html: the study's plots have no width in pt and the PDF's figure
macro compared their 100 % with a length."""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
from typer.testing import CliRunner

from tmm_cli.cli import app

runner = CliRunner()
ROOT = Path(__file__).resolve().parents[1]
TASK = str(ROOT / "tasks" / "crank_rocker_fourbar.yaml")

RUN_FORMATS = [None, "json", "html", "pdf", "sheets", "json,html,pdf,sheets"]
EXPECT = {"json": [], "html": ["report.html"], "pdf": ["report.pdf"], "sheets": ["sheets"]}


def _expected(fmt: str | None) -> list[str]:
    names = ["results.json"]
    for f in (fmt or "json,html,pdf").split(","):
        names += EXPECT[f]
    return names


@pytest.mark.parametrize("study", [False, True], ids=["plain", "study"])
@pytest.mark.parametrize("fmt", RUN_FORMATS, ids=lambda f: f or "default")
def test_run_every_format_with_and_without_study(tmp_path, fmt, study):
    # the languages taken in turn: each format is seen in more than one of them
    lang = ["en", "ru", "uk"][(RUN_FORMATS.index(fmt) + study) % 3]
    out = tmp_path / "o"
    args = ["run", TASK, "--out", str(out), "--quiet", "--lang", lang]
    if fmt is not None:
        args += ["--format", fmt]
    if study:
        args.append("--study")
    res = runner.invoke(app, args)
    assert res.exit_code == 0, res.output
    assert "internal error" not in res.output
    for name in _expected(fmt):
        assert (out / name).exists(), (name, res.output)
    if "report.pdf" in _expected(fmt):
        assert (out / "report.pdf").read_bytes()[:5] == b"%PDF-"
    assert (out / "study.json").exists() == study and (out / "study.html").exists() == study


@pytest.mark.parametrize("fmt", [None, "pdf", "svg", "dxf"], ids=lambda f: f or "default")
def test_sheets_every_format(tmp_path, fmt):
    out = tmp_path / "s"
    args = ["sheets", TASK, "--out", str(out), "--lang", "uk"]
    if fmt:
        args += ["--format", fmt]
    res = runner.invoke(app, args)
    assert res.exit_code == 0, res.output
    made = {p.suffix for p in out.rglob("*") if p.is_file() and p.suffix in {".pdf", ".svg", ".dxf"}}
    assert made == ({"." + fmt} if fmt else {".pdf", ".svg", ".dxf"}), made


@pytest.mark.parametrize("fmt", ["json", "html", "pdf", "json,html,pdf"])
def test_batch_every_format(tmp_path, fmt):
    out = tmp_path / "b"
    # a process of its own, as a user starts it: its workers are forked, and a fork of a
    # process in which Typst has run (this one, by the tests above) can hang in Typst
    res = subprocess.run([sys.executable, "-m", "tmm_cli", "batch", TASK, "--out", str(out), "--format", fmt,
                          "--lang", "ru"], capture_output=True, text=True, timeout=300)
    assert res.returncode in (0, 1), res.stdout + res.stderr       # 1: answers outside tolerance
    assert "internal error" not in res.stdout + res.stderr
    for f in fmt.split(","):
        for name in EXPECT[f] or ["results.json"]:
            assert list(out.rglob(name)), (name, res.stdout)


@pytest.mark.parametrize("fmt", ["text", "json"])
def test_paths_every_format(fmt):
    res = runner.invoke(app, ["paths", TASK, "--format", fmt, "--prefix", "positions"])
    assert res.exit_code == 0, res.output
    if fmt == "json":
        assert json.loads(res.output)
    else:
        assert "\t" in res.output


def test_study_every_language(tmp_path):
    for lang in ("en", "ru", "uk"):
        out = tmp_path / lang
        res = runner.invoke(app, ["study", TASK, "--out", str(out), "--repeat", "1", "--lang", lang])
        assert res.exit_code == 0, res.output
        assert (out / "study.json").exists() and (out / "study.html").exists()
