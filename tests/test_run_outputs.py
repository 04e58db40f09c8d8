"""What `tmm run` leaves in its output folder: files readable as ordinary files
(the umask, not 0600), a manifest by which a new run removes what the previous run
wrote and this one did not (and nothing else), no stale temporary files; the PDF
skipped with one warning line where its engine cannot run; a failing stage that
keeps the independent ones and the report (with a failure box), exit 3."""
from __future__ import annotations

import builtins
import json
import os
import re
import stat
import time
from pathlib import Path

import pytest
from typer.testing import CliRunner

from tmm_cli.cli import app
from tmm_cli.io import MANIFEST, Manifest, atomic_write

runner = CliRunner()
ROOT = Path(__file__).resolve().parents[1]

GEARS = "gears: {m: 4 mm, z: [14, 30], x: [0, 0]}\n"
CAM = (ROOT / "tasks" / "cam_offset.yaml").read_text(encoding="utf-8").split("\ncam:", 1)[1]
CAM = "cam:" + CAM
# scheme A: i_1H = 1 + z3/z1 with z3 = z1 + 2 z2 and z2 >= 17 (no undercut), so z3/z1 > 34/150
# and i_1H > 2 (tmm says: at least 2.367 with the assembly condition): 1.2 cannot be met
PLANETARY_IMPOSSIBLE = "planetary: {scheme: A, ratio: 1.2, satellites: 3, m: 2 mm}\n"


def task_file(tmp_path, *parts, name="t.yaml", title="outputs"):
    f = tmp_path / name
    f.write_text(f"schema: tmm/1\ntitle: {title}\n" + "".join(parts), encoding="utf-8")
    return f


def tmm_run(f, out, fmt="json,html", *extra):
    return runner.invoke(app, ["run", str(f), "--out", str(out), "--format", fmt, "--quiet", *extra])


# ---------------------------------------------------------------- modes
@pytest.mark.parametrize("mask, mode", [(0o022, 0o644), (0o027, 0o640), (0o002, 0o664)])
def test_atomic_write_respects_umask(tmp_path, mask, mode):
    old = os.umask(mask)
    try:
        p = atomic_write(tmp_path / "sub" / "a.txt", "x")
    finally:
        os.umask(old)
    assert stat.S_IMODE(p.stat().st_mode) == mode          # 0o666 & ~umask, as open() gives
    assert [q.name for q in p.parent.iterdir()] == ["a.txt"]


def test_run_files_are_world_readable_under_umask_022(tmp_path):
    f = task_file(tmp_path, GEARS)
    old = os.umask(0o022)
    try:
        res = tmm_run(f, tmp_path / "o")
    finally:
        os.umask(old)
    assert res.exit_code == 0, res.output
    files = [p for p in (tmp_path / "o").rglob("*") if p.is_file()]
    assert len(files) > 5
    assert {oct(stat.S_IMODE(p.stat().st_mode)) for p in files} == {oct(0o644)}


# ---------------------------------------------------------------- manifest
def test_rerun_removes_the_previous_runs_files_only(tmp_path):
    out = tmp_path / "o"
    f = task_file(tmp_path, CAM, GEARS)
    assert tmm_run(f, out).exit_code == 0
    first = json.loads((out / MANIFEST).read_text())["files"]
    assert "cam_profile.dxf" in first and "gears_outline.dxf" in first
    n_fig_first = len(list((out / "figures").glob("*.svg")))
    # the user's own files, and a file of the first run the user edited since
    (out / "my_notes.txt").write_text("mine")
    (out / "figures" / "my_sketch.svg").write_text("<svg/>")
    time.sleep(0.01)
    (out / "gears_sliding.csv").write_text("edited by hand\n")
    f2 = task_file(tmp_path, CAM, name="t.yaml")                 # the gears section removed
    assert tmm_run(f2, out).exit_code == 0
    second = json.loads((out / MANIFEST).read_text())["files"]
    assert not any(k.startswith("gears") for k in second)
    assert not (out / "gears_outline.dxf").exists()
    assert not (out / "gears_wheel1_outline.csv").exists()
    assert (out / "cam_profile.dxf").exists()
    figs = sorted(p.name for p in (out / "figures").glob("*.svg") if p.name != "my_sketch.svg")
    assert n_fig_first > len(figs) > 0
    assert figs and all(f.startswith("cam-") for f in figs)             # no stale gear figure
    assert (out / "my_notes.txt").read_text() == "mine"                 # not ours: untouched
    assert (out / "figures" / "my_sketch.svg").exists()
    assert (out / "gears_sliding.csv").read_text() == "edited by hand\n"  # changed since: kept
    assert set(second) == {p.relative_to(out).as_posix() for p in out.rglob("*")
                           if p.is_file() and p.name != MANIFEST} - {
        "my_notes.txt", "figures/my_sketch.svg", "gears_sliding.csv"}


def test_a_run_that_writes_nothing_says_the_folder_holds_an_earlier_run(tmp_path):
    """A run whose task file is invalid (exit 2) writes nothing, and says that its folder still
    holds an earlier run's outputs, with that run's time (its manifest's), so that a student
    does not read the old report as this file's; every file of the earlier run is kept. Into a
    folder no run has written, it says nothing more."""
    bad = "gearz: {m: 4 mm, z: [14, 30]}\n"
    fresh = tmm_run(task_file(tmp_path, bad, name="bad.yaml"), tmp_path / "none")
    assert fresh.exit_code == 2 and "gearz" in fresh.output and "earlier run" not in fresh.output
    out = tmp_path / "o"
    f = task_file(tmp_path, GEARS)
    assert tmm_run(f, out).exit_code == 0
    os.utime(out / MANIFEST, (1700000000, 1700000000))             # the earlier run: 14 Nov 2023
    before = {p: p.read_bytes() for p in out.rglob("*") if p.is_file()}
    res = tmm_run(task_file(tmp_path, bad), out)
    assert res.exit_code == 2, res.output
    when = time.strftime("%Y-%m-%d %H:%M", time.localtime(1700000000))
    assert (f"note: {out}/ still holds the outputs of an earlier run ({when}): they are not of the task "
            "file as it is now") in res.output
    assert {p: p.read_bytes() for p in out.rglob("*") if p.is_file()} == before


def test_manifest_unit(tmp_path):
    d = tmp_path / "o"
    m = Manifest(d)
    a, b = atomic_write(d / "a.csv", "1"), atomic_write(d / "sub" / "b.csv", "2")
    assert m.commit([a, b]) == []
    (tmp_path / "outside.txt").write_text("x")
    # a manifest naming paths outside the folder (edited by someone) is not followed
    data = json.loads((d / MANIFEST).read_text())
    data["files"]["../outside.txt"] = [1, 1]
    (d / MANIFEST).write_text(json.dumps(data))
    m2 = Manifest(d)
    removed = m2.commit([atomic_write(d / "a.csv", "1")])
    assert removed == [d / "sub" / "b.csv"]
    assert not (d / "sub").exists()               # the folder it emptied goes too
    assert (tmp_path / "outside.txt").exists()
    assert json.loads((d / MANIFEST).read_text())["files"].keys() == {"a.csv"}
    # an unreadable manifest: nothing removed
    (d / MANIFEST).write_text("{not json")
    atomic_write(d / "c.csv", "3")
    assert Manifest(d).commit([d / "a.csv"]) == [] and (d / "c.csv").exists()


def test_stale_temporary_files_of_a_killed_run_are_removed(tmp_path):
    out = tmp_path / "o"
    out.mkdir()
    (out / "figures").mkdir()
    stale = [out / ".report.pdf.k2j4_x9a.tmp", out / "figures" / ".fig-03.svg.abcdefgh.tmp"]
    keep = [out / ".hidden.tmp", out / "notes.tmp", out / ".report.pdf.SHORT.tmp"]
    for p in stale + keep:
        p.write_text("partial")
        os.utime(p, (time.time() - 60, time.time() - 60))
    fresh = out / ".results.json.zzzzzzzz.tmp"      # another run writing right now: not stale
    fresh.write_text("x")
    os.utime(fresh, (time.time() + 5, time.time() + 5))
    assert tmm_run(task_file(tmp_path, GEARS), out).exit_code == 0
    assert not any(p.exists() for p in stale)
    assert all(p.exists() for p in keep) and fresh.exists()


# ---------------------------------------------------------------- PDF without its engine
def test_pdf_skipped_when_typst_is_missing(tmp_path, monkeypatch):
    real_import = builtins.__import__

    def fake_import(name, *a, **kw):
        if name == "typst" or name.startswith("typst."):
            raise ImportError("No module named 'typst'")
        return real_import(name, *a, **kw)

    monkeypatch.setattr(builtins, "__import__", fake_import)
    for mod in [m for m in list(__import__("sys").modules) if m.split(".")[0] == "typst"]:
        monkeypatch.delitem(__import__("sys").modules, mod)
    out = tmp_path / "o"
    res = tmm_run(task_file(tmp_path, GEARS), out, "json,html,pdf")
    assert res.exit_code == 0, res.output
    assert "Traceback" not in res.output
    lines = [ln for ln in res.output.splitlines() if "pdf" in ln.lower()]
    assert len(lines) == 1 and lines[0].startswith("warning: report.pdf skipped")
    assert "not installed" in lines[0] and "pip install typst" in lines[0]
    assert (out / "report.html").exists() and (out / "results.json").exists()
    assert not (out / "report.pdf").exists()
    assert "report.pdf" not in json.loads((out / MANIFEST).read_text())["files"]


# ---------------------------------------------------------------- a failing stage
def test_failing_planetary_keeps_cam_gears_and_the_report(tmp_path):
    out = tmp_path / "o"
    f = task_file(tmp_path, PLANETARY_IMPOSSIBLE, CAM, GEARS)
    res = runner.invoke(app, ["run", str(f), "--out", str(out), "--format", "json,html"])
    assert res.exit_code == 3
    assert "stage 'planetary' failed" in res.output and "Traceback" not in res.output
    data = json.loads((out / "results.json").read_text())
    assert "cam" in data and "gears" in data and "planetary" not in data
    assert data["error"]["stage"] == "planetary"
    assert [e["stage"] for e in data["errors"]] == ["planetary"]
    html = (out / "report.html").read_text(encoding="utf-8")
    ids = re.findall(r'<section class="section[^"]*" id="([^"]+)"', html)
    assert ids[:4] == ["task", "cam", "gears", "planetary-failed"]
    box = html.split('id="planetary-failed"', 1)[1].split("</section>", 1)[0]
    assert 'class="failure"' in box
    assert "ratio" in box or "i_1H" in box                        # what failed
    assert "“planetary”" in box                                   # what to change: that section
    assert (out / "cam_profile.dxf").exists() and (out / "gears_outline.dxf").exists()


@pytest.mark.parametrize("lang, words", [("ru", "ни один набор чисел зубьев схемы A не даёт i_1H = 1,2"),
                                         ("uk", "жоден набір чисел зубів схеми A не дає i_1H = 1,2")])
def test_stage_failure_in_the_report_language(tmp_path, lang, words):
    """A stage's failure: English in results.json `errors[].message` (with its code and
    parameters beside it); on stderr and in the report's failure box in the report's language
    (English on stderr without --lang)."""
    out = tmp_path / "o"
    f = task_file(tmp_path, PLANETARY_IMPOSSIBLE)
    res = runner.invoke(app, ["run", str(f), "--out", str(out), "--format", "json,html", "--lang", lang])
    assert res.exit_code == 3
    head = {"ru": "ошибка: ", "uk": "помилка: "}[lang]
    stage = {"ru": "Этап «синтез планетарного механизма» не выполнен: ",
             "uk": "Етап «синтез планетарного механізму» не виконано: "}[lang]
    assert f"{head}{f}: {stage}{words}" in res.output and "no tooth numbers" not in res.output
    en = runner.invoke(app, ["run", str(f), "--out", str(tmp_path / "en"), "--format", "json"])
    assert "error: " in en.output and "no tooth numbers for scheme A give i_1H = 1.2 within 0.05" in en.output
    err = json.loads((out / "results.json").read_text())["errors"][0]
    assert err["code"] == "planetary.fail.none_found" and err["params"]["scheme"] == "A"
    assert err["message"].startswith("no tooth numbers for scheme A give i_1H = 1.2 within 0.05 with 3 satellites")
    assert err["params"]["hint"]["code"].startswith("planetary.hint.")        # the hint: a message inside
    box = (out / "report.html").read_text(encoding="utf-8").split('id="planetary-failed"', 1)[1]
    box = box.split("</section>", 1)[0]
    assert words in box and "no tooth numbers" not in box


def test_linkage_that_does_not_assemble_does_not_stop_cam_and_gears(tmp_path):
    out = tmp_path / "o"
    linkage = ("mechanism:\n  ground: {O: [0, 0]}\n  links:\n    crank: {points: [O, A], length: 0.1}\n"
               "    rod: {points: [A, B], length: 0.05}\n"
               "    slider: {slider: B, guide: {through: O, angle: 0}}\n"
               "drive: {link: crank, speed: 10 rad/s}\n")
    f = task_file(tmp_path, linkage, CAM, GEARS, PLANETARY_IMPOSSIBLE)
    res = tmm_run(f, out, "json,html,pdf")
    assert res.exit_code == 3
    assert "stage 'kinematics' failed" in res.output and "stage 'planetary' failed" in res.output
    data = json.loads((out / "results.json").read_text())
    assert data["structure"]["W"] == 1 and "cam" in data and "gears" in data
    assert [e["stage"] for e in data["errors"]] == ["kinematics", "planetary"]
    assert data["error"] == data["errors"][0]
    html = (out / "report.html").read_text(encoding="utf-8")
    ids = re.findall(r'<section class="section[^"]*" id="([^"]+)"', html)
    assert ids[:6] == ["task", "structure", "kinematics-failed", "cam", "gears", "planetary-failed"]
    assert (out / "report.pdf").read_bytes().startswith(b"%PDF-")


@pytest.mark.parametrize("lang, words", [
    ("ru", "группа II(2,3) (звенья rod, slider) не собирается при углах кривошипа"),
    ("uk", "група II(2,3) (ланки rod, slider) не складається за кутів кривошипа")])
def test_linkage_failure_in_the_report_language(tmp_path, lang, words):
    """A linkage that does not assemble over part of the cycle (rod 0.05 m on a 0.1 m
    crank): the sentence on stderr in the report's language (its crank angles with the decimal
    comma), its code in results.json, the report's box in its language, with the reason
    (|AB| < crank) in that language too."""
    out = tmp_path / "o"
    linkage = ("mechanism:\n  ground: {O: [0, 0]}\n  links:\n    crank: {points: [O, A], length: 0.1}\n"
               "    rod: {points: [A, B], length: 0.05}\n"
               "    slider: {slider: B, guide: {through: O, angle: 0}}\n"
               "drive: {link: crank, speed: 10 rad/s}\n")
    res = runner.invoke(app, ["run", str(task_file(tmp_path, linkage)), "--out", str(out), "--format", "json,html",
                              "--lang", lang, "-q"])
    assert res.exit_code == 3
    assert words in res.output and "does not assemble" not in res.output
    where = {"ru": "при угле кривошипа φ = 30,5°", "uk": "за кута кривошипа φ = 30,5°"}[lang]
    assert where in res.output
    err = json.loads((out / "results.json").read_text())["errors"][0]
    assert err["code"] == "kinematics.fail.intervals" and err["params"]["links"] == ["rod", "slider"]
    assert err["params"]["reason"]["code"] == "kinematics.reason.rrp_short"
    box = (out / "report.html").read_text(encoding="utf-8").split('id="kinematics-failed"', 1)[1]
    box = box.split("</section>", 1)[0]
    assert words in box and "does not assemble" not in box and "too short" not in box
    where = {"ru": "при угле кривошипа φ = 30,5°", "uk": "за кута кривошипа φ = 30,5°"}[lang]   # decimal comma
    assert where in box                       # the failure's crank angle (the first bad one found)


def test_failure_box_in_russian(tmp_path):
    out = tmp_path / "o"
    f = task_file(tmp_path, GEARS, PLANETARY_IMPOSSIBLE)
    res = runner.invoke(app, ["run", str(f), "--out", str(out), "--format", "html", "--lang", "ru", "-q"])
    assert res.exit_code == 3
    html = (out / "report.html").read_text(encoding="utf-8")
    box = html.split('id="planetary-failed"', 1)[1].split("</section>", 1)[0]
    assert "Синтез планетарного механизма — не рассчитано" in box
    assert "Этап «синтез планетарного механизма» не выполнен" in box and "раздела «planetary»" in box
    assert 'id="gears"' in html
