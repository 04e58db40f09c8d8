"""Hostile inputs of issue 37 (items 4 to 13): no input hangs, crashes, costs without bound
or mixes two runs. Each test fails without its fix."""
from __future__ import annotations

import csv
import json
import os
import subprocess
import sys
import time
from pathlib import Path

import pytest
from typer.testing import CliRunner

from tmm_cli.cli import app

runner = CliRunner()
ROOT = Path(__file__).resolve().parents[1]
TMM = [sys.executable, "-m", "tmm_cli"]

GEARS = """\
schema: tmm/1
title: zero-shift pair
student: {name: A. Student, group: MM-1}
gears: {m: 4 mm, z: [14, 30], x: [0, 0]}
"""
R1, R2 = 0.028, 0.060          # m z / 2 of the zero-shift pair


def _write(tmp_path: Path, name: str, text: str) -> Path:
    p = tmp_path / name
    p.write_text(text, encoding="utf-8")
    return p


# ---------------------------------------------------------------- item 12
def test_negative_index_is_an_unknown_path(tmp_path):
    """`gears.r[-1]` is no quantity of results.json (Python's count from the end is not the
    course's): unknown_path, never graded against r[1]."""
    from tmm_cli.results import lookup
    results = {"gears": {"r": [R1, R2]}}
    with pytest.raises(KeyError):
        lookup(results, "gears.r[-1]")
    assert lookup(results, "gears.r[1]") == R2
    f = _write(tmp_path, "g.yaml", GEARS + f"answers: {{'gears.r[-1]': {R2}, 'gears.r[1]': {R2}}}\n")
    res = runner.invoke(app, ["check", str(f), "--out", str(tmp_path / "o")])
    assert res.exit_code == 1, res.output
    with open(tmp_path / "o" / "check.csv", encoding="utf-8", newline="") as fh:
        rows = {r["path"]: r["status"] for r in csv.DictReader(fh)}
    assert rows == {"gears.r[-1]": "unknown_path", "gears.r[1]": "ok"}


# ---------------------------------------------------------------- items 10, 8 (tables)
def _answers_csv(tmp_path: Path, rows: list[str]) -> Path:
    return _write(tmp_path, "answers.csv", "student,group,variant,gears.aw\n" + "".join(r + "\n" for r in rows))


def test_csv_cell_over_the_field_limit_names_the_line(tmp_path):
    """A cell over the csv module's field limit (128 KiB) was 'internal error ... field larger
    than field limit': exit 2 naming the file and the line."""
    task = _write(tmp_path, "g.yaml", GEARS)
    big = _answers_csv(tmp_path, ["A,MM-1,,0.088", "B,MM-1,," + "x" * 200_000])
    res = runner.invoke(app, ["check", str(task), "--answers", str(big)])
    assert res.exit_code == 2, res.output
    assert "answers.csv:3: a cell longer than 131072 characters" in res.output, res.output
    assert "internal error" not in res.output and "Traceback" not in res.output
    tmpl = _write(tmp_path, "t.yaml", GEARS.replace("[14, 30]", '["{z1}", 30]'))
    table = _write(tmp_path, "v.csv", "variant,z1\n1,14\n2," + "9" * 200_000 + "\n")
    res = runner.invoke(app, ["variants", str(tmpl), str(table), "--out", str(tmp_path / "v")])
    assert res.exit_code == 2, res.output
    assert "v.csv:3: a cell longer than" in res.output, res.output
    assert "internal error" not in res.output and "Traceback" not in res.output


def test_answers_table_rows_are_bounded(tmp_path):
    """An answers table of more rows than the limit is refused at once (10^6 rows took
    about 17 minutes), naming the first row past it."""
    from tmm_cli.limits import MAX_TABLE_ROWS
    task = _write(tmp_path, "g.yaml", GEARS)
    big = _answers_csv(tmp_path, [f"S{i},MM-1,,0.088" for i in range(MAX_TABLE_ROWS + 5)])
    t0 = time.process_time()                # CPU time: a busy machine's wall time says little
    res = runner.invoke(app, ["check", str(task), "--answers", str(big)])
    assert time.process_time() - t0 < 5
    assert res.exit_code == 2, res.output
    assert str(MAX_TABLE_ROWS) in res.output and str(MAX_TABLE_ROWS + 2) in res.output, res.output


# ---------------------------------------------------------------- items 8, 9, 13 (the task)
FOURBAR = (ROOT / "tasks" / "crank_rocker_fourbar.yaml").read_text(encoding="utf-8")


def _validate(tmp_path: Path, text: str):
    f = _write(tmp_path, "task.yaml", text)
    t0 = time.process_time()
    res = runner.invoke(app, ["validate", str(f)])
    return res, time.process_time() - t0


@pytest.mark.parametrize("escape,shown,field", [
    (r"A\x01B", "U+0001", "title"),
    (r"A\0B", "U+0000", "title"),
    (r"A\uFFFEB", "U+FFFE", "title"),
    (r"A\ud800B", "U+D800", "title"),
    (r"A\x85B", "U+0085", "title"),
    (r"A\x7fB", "U+007F", "student.name"),
    (r"A\tB\rC", "U+000D", "student.group"),
])
def test_control_characters_in_free_text_are_refused(tmp_path, escape, shown, field):
    """A control character, a noncharacter or a lone surrogate in a text field was 'ok' for
    validate and an internal error (or nothing written) for run: exit 2 naming the field."""
    key = field.split(".")[-1]
    text = FOURBAR.replace("variant: 3\n", 'variant: 3\nstudent: {name: "Ann", group: "MM-1"}\n')
    if field == "title":
        text = text.replace("title: Conveyor drive, crank-rocker four-bar", f'title: "{escape}"')
    else:
        text = text.replace(f'{key}: "{"Ann" if key == "name" else "MM-1"}"', f'{key}: "{escape}"')
    res, _ = _validate(tmp_path, text)
    assert res.exit_code == 2, res.output
    assert f"field '{field}'" in res.output and shown in res.output, res.output
    assert "Traceback" not in res.output


@pytest.mark.parametrize("place", ["point", "link", "variant"])
def test_control_characters_in_names_are_refused(tmp_path, place):
    """Names (keys and references) follow the same rule, tab and newline included."""
    if place == "point":
        text = FOURBAR.replace("extra: {M: [0.15, 0.06]}", r'extra: {"M\x02": [0.15, 0.06]}')
        field = r"mechanism.links.coupler.extra.M\u0002"
    elif place == "link":
        text = FOURBAR.replace("coupler: {points", r'"coupler\n": {points')
        field = r"mechanism.links.coupler\u000a"
    else:
        text = FOURBAR.replace("variant: 3", r'variant: "3\x03"')
        field = "variant"
    res, _ = _validate(tmp_path, text)
    assert res.exit_code == 2, res.output
    assert f"field '{field}'" in res.output, res.output


def test_tab_and_newline_are_allowed_in_the_title(tmp_path):
    text = FOURBAR.replace("title: Conveyor drive, crank-rocker four-bar", r'title: "Conveyor\tdrive\nfour-bar"')
    res, _ = _validate(tmp_path, text)
    assert res.exit_code == 0, res.output


def test_text_length_and_combining_marks_are_bounded(tmp_path):
    """One letter and 70,000 combining marks aborted the PDF engine (SIGABRT): a text over
    the length limit, or with more combining marks in a row than Unicode's stream-safe
    limit, is refused at validation within a second; accented letters are fine."""
    from tmm_cli.limits import MAX_COMBINING, MAX_TEXT
    title = "title: Conveyor drive, crank-rocker four-bar"
    res, dt = _validate(tmp_path, FOURBAR.replace(title, "title: a" + "\u0301" * 70_000))
    assert res.exit_code == 2 and "field 'title'" in res.output and str(MAX_TEXT) in res.output, res.output
    res, dt = _validate(tmp_path, FOURBAR.replace(title, "title: a" + "\u0301" * (MAX_COMBINING + 1)))
    assert res.exit_code == 2 and "field 'title'" in res.output and "combining" in res.output, res.output
    res, _ = _validate(tmp_path, FOURBAR.replace(title, "title: Привод конвейера, ё й \u1ec7" + "e\u0301" * 20))
    assert res.exit_code == 0, res.output


def test_positions_count_their_extras(tmp_path):
    """`positions.extra` bypassed the 3600-position cap (16,000 extras: minutes, gigabytes,
    each extra position with its own figures): count + extras over the limit, or more
    extra positions than their own limit, is exit 2 naming positions.extra."""
    from tmm_cli.limits import MAX_EXTRA_POSITIONS, MAX_POSITIONS

    def given(count, n):
        extras = ", ".join(str(i / 7) for i in range(n))
        return FOURBAR.replace("  count: 12\n", f"  count: {count}\n  extra: [{extras}]\n")
    res, _ = _validate(tmp_path, given(MAX_POSITIONS - 10, 11))
    assert res.exit_code == 2, res.output
    assert "field 'positions.extra'" in res.output and f"{MAX_POSITIONS + 1} positions" in res.output, res.output
    res, _ = _validate(tmp_path, given(12, MAX_EXTRA_POSITIONS + 1))
    assert res.exit_code == 2, res.output
    assert "field 'positions.extra'" in res.output and f"{MAX_EXTRA_POSITIONS + 1} extra positions" in res.output
    res, _ = _validate(tmp_path, given(12, MAX_EXTRA_POSITIONS))
    assert res.exit_code == 0, res.output


def test_extra_points_and_forces_are_bounded(tmp_path):
    """4,000 extra points ended in MemoryError and 1,700 forces too: refused at validation,
    naming the link (or loads.forces)."""
    from tmm_cli.limits import MAX_EXTRA_POINTS, MAX_FORCES
    pts = ", ".join(f"P{i}: [0.1, {i * 1e-4}]" for i in range(MAX_EXTRA_POINTS + 1))
    text = FOURBAR.replace("extra: {M: [0.15, 0.06]}", f"extra: {{{pts}}}")
    res, dt = _validate(tmp_path, text)
    assert res.exit_code == 2 and dt < 10, res.output
    assert "field 'mechanism.links.coupler.extra'" in res.output and str(MAX_EXTRA_POINTS + 1) in res.output
    force = "    - {on: rocker, kind: resistance, stroke: idle, moment: 8}"
    assert FOURBAR.count(force) == 1 and FOURBAR.count("- {on:") == 2
    res, dt = _validate(tmp_path, FOURBAR.replace(force, "\n".join([force] * MAX_FORCES)))
    assert res.exit_code == 2 and "field 'loads.forces'" in res.output, res.output
    assert f"{MAX_FORCES + 1} forces" in res.output, res.output
    res, dt = _validate(tmp_path, FOURBAR.replace(force, "\n".join([force] * (MAX_FORCES - 1))))
    assert res.exit_code == 0, res.output


def test_kinetostatics_positions_empty_and_repeated(tmp_path):
    """`positions: []` computed nothing without a word: exit 2 naming the field. A position
    listed twice was computed twice: once now."""
    res, _ = _validate(tmp_path, FOURBAR.replace("  positions: all\n", "  positions: []\n"))
    assert res.exit_code == 2 and "field 'kinetostatics.positions'" in res.output, res.output
    f = _write(tmp_path, "dup.yaml", FOURBAR.replace("  positions: all\n", "  positions: [3, 1, 3, 1]\n"))
    res = runner.invoke(app, ["run", str(f), "--format", "json", "--out", str(tmp_path / "o")])
    assert res.exit_code == 0, res.output
    data = json.loads((tmp_path / "o" / "results.json").read_text(encoding="utf-8"))
    assert [e["index"] for e in data["kinetostatics"]] == [3, 1]


# ---------------------------------------------------------------- item 4
@pytest.mark.parametrize("extra,field", [
    ("{M: [0.15, 0.06], S2: [0.15, 0.06]}", "mechanism.links.coupler.extra.S2"),     # the link's own
    ("{M: [0.15, 0.06], S3: [0.15, 0.06]}", "mechanism.links.coupler.extra.S3"),     # another link's
])
def test_extra_point_named_like_a_centre_of_mass(tmp_path, extra, field):
    """`extra: {S2: ...}` on link 2 vanished: the results gave the centre of mass under that
    name. A clash with the automatic name S<i> is exit 2 naming the point."""
    text = FOURBAR.replace("extra: {M: [0.15, 0.06]}", f"extra: {extra}")
    res, _ = _validate(tmp_path, text)
    assert res.exit_code == 2, res.output
    assert f"field '{field}'" in res.output and "reserved for the centre of mass" in res.output, res.output


# ---------------------------------------------------------------- item 6
@pytest.mark.parametrize("out", ["rel", "default"])
def test_manifest_with_a_relative_output_folder(tmp_path, monkeypatch, out):
    """A relative --out (and the default out/<task>/) stored paths relative to the working
    directory, so the next run removed nothing: a linkage's figures stayed beside a gear
    task's results. Now the next run removes them, and stale temporary files in the
    sub-folders are swept."""
    monkeypatch.chdir(tmp_path)
    _write(tmp_path, "task.yaml", FOURBAR.replace("  count: 12\n", "  count: 4\n"))
    args = ["--out", "res"] if out == "rel" else []
    folder = tmp_path / ("res" if out == "rel" else "out/task")
    res = runner.invoke(app, ["run", "task.yaml", "--format", "json,html", *args])
    assert res.exit_code == 0, res.output
    figures = sorted((folder / "figures").iterdir())
    assert figures and (folder / "report.html").exists()
    manifest = json.loads((folder / ".tmm-manifest.json").read_text(encoding="utf-8"))
    assert "report.html" in manifest["files"] and manifest["files"]["report.html"] is not None
    stale = folder / "figures" / ".plans-pos01.svg.abcd1234.tmp"
    stale.write_text("half", encoding="utf-8")
    os.utime(stale, (time.time() - 60, time.time() - 60))
    _write(tmp_path, "task.yaml", GEARS)
    res = runner.invoke(app, ["run", "task.yaml", "--format", "json", *args])
    assert res.exit_code == 0, res.output
    left = sorted(p.relative_to(folder).as_posix() for p in folder.rglob("*"))
    assert left == [".tmm-manifest.json", "results.json"], left


# ---------------------------------------------------------------- item 7
_HOLD = """
import sys, time
from tmm_cli.io import folder_lock
with folder_lock(sys.argv[1]):
    print("held", flush=True)
    time.sleep(float(sys.argv[2]))
    released = time.time()
print(released, flush=True)
"""


def _holder(folder: Path, seconds: float) -> subprocess.Popen:
    """A second process holding the output folder's lock for ``seconds``."""
    p = subprocess.Popen([sys.executable, "-c", _HOLD, str(folder), str(seconds)], stdout=subprocess.PIPE, text=True)
    assert p.stdout.readline().strip() == "held"
    return p


def _tmm(*args, wait: float, cwd: Path) -> subprocess.CompletedProcess:
    env = {**os.environ, "TMM_LOCK_WAIT": str(wait)}
    return subprocess.run([*TMM, *args], cwd=cwd, env=env, capture_output=True, text=True, timeout=120)


def test_two_processes_into_one_folder_do_not_interleave(tmp_path):
    """Two `tmm run` into one folder at once both exited 0, one's results.json beside the
    other's report: the output folder is locked. A run finding it busy waits; past the
    wait it fails (exit 3) naming the folder, writing nothing; once free it runs."""
    _write(tmp_path, "g.yaml", GEARS)
    out = tmp_path / "res"
    holder = _holder(out, 30)
    try:
        res = _tmm("run", "g.yaml", "--format", "json", "--out", "res", wait=0.3, cwd=tmp_path)
        assert res.returncode == 3, res.stderr
        assert "res" in res.stderr and "another tmm run or batch is writing into this folder" in res.stderr
        assert "Traceback" not in res.stderr
        assert not (out / "results.json").exists()
        _write(tmp_path, "v1.yaml", GEARS)
        res = _tmm("batch", "v1.yaml", "--out", "res", wait=0.3, cwd=tmp_path)
        assert res.returncode == 3 and "another tmm run or batch" in res.stderr, res.stderr
        assert not (out / "summary.csv").exists()
        _write(tmp_path, "c.yaml", GEARS + "answers: {gears.aw: 0.088}\n")
        res = _tmm("check", "c.yaml", "--out", "res", wait=0.3, cwd=tmp_path)
        assert res.returncode == 3 and "another tmm run or batch" in res.stderr, res.stderr
        assert not (out / "check.csv").exists()
    finally:
        holder.kill()
        holder.wait()
    res = _tmm("run", "g.yaml", "--format", "json", "--out", "res", wait=1, cwd=tmp_path)
    assert res.returncode == 0, res.stderr
    assert json.loads((out / "results.json").read_text(encoding="utf-8"))["gears"]["r"][0] == pytest.approx(R1)


def test_a_run_waits_for_the_folder(tmp_path):
    """Within the wait, the second run writes once the first is done."""
    _write(tmp_path, "g.yaml", GEARS)
    holder = _holder(tmp_path / "res", 1.5)
    try:
        res = _tmm("run", "g.yaml", "--format", "json", "--out", "res", wait=60, cwd=tmp_path)
        assert res.returncode == 0, res.stderr
        released = float(holder.stdout.readline())
    finally:
        holder.kill()
        holder.wait()
    assert (tmp_path / "res" / "results.json").stat().st_mtime >= released - 0.05     # written after it let go


# ---------------------------------------------------------------- item 11
def test_control_characters_of_student_names_never_written_raw(tmp_path):
    """NUL bytes (and other control characters) of a student's name in an answers table
    went raw into summary.csv, check.csv and the HTML pages: replaced now."""
    d = tmp_path / "tasks"
    d.mkdir()
    _write(d, "v1.yaml", GEARS.replace("title: zero-shift pair\n", "title: zero-shift pair\nvariant: 1\n"))
    (tmp_path / "answers.csv").write_bytes("student,group,variant,gears.aw\n"
                                           "Ann\x00Lee\x01,MM\x1b[31m-1\x85,1,0.088\n".encode("utf-8"))
    res = runner.invoke(app, ["batch", str(d), "--answers", str(tmp_path / "answers.csv"),
                              "--out", str(tmp_path / "out"), "--format", "json,html"])
    assert res.exit_code in (0, 1), res.output
    out = tmp_path / "out"
    pages = [out / "summary.csv", out / "check.csv", out / "summary.html", *out.rglob("feedback-*.html")]
    assert len(pages) >= 4, sorted(out.rglob("*"))
    for page in pages:
        text = page.read_text(encoding="utf-8")
        assert "Ann" in text, page
        bad = sorted({f"U+{ord(c):04X}" for c in text if ord(c) < 0x20 and c not in "\t\n\r" or 0x7F <= ord(c) <= 0x9F})
        assert not bad, (page, bad)


# ---------------------------------------------------------------- item 13 (file names)
def test_no_file_or_folder_name_starts_with_a_dash(tmp_path):
    """`variants` wrote `-1_1.yaml` for the variant `-1 1` (a name a command reads as an
    option), and a batch made a folder `-2` of the task file `-2.yaml`: neither now."""
    tmpl = _write(tmp_path, "t.yaml", GEARS.replace("[14, 30]", '["{z1}", 30]'))
    table = _write(tmp_path, "v.csv", "variant,z1\n-1 1,14\n--x,15\n.-y,16\n7,17\n")
    res = runner.invoke(app, ["variants", str(tmpl), str(table), "--out", str(tmp_path / "v")])
    assert res.exit_code == 0, res.output
    names = sorted(p.name for p in (tmp_path / "v").iterdir())
    assert len(names) == 5 and "7.yaml" in names and "variants.csv" in names, names
    assert not [n for n in names if n.startswith(("-", "."))], names
    d = tmp_path / "tasks"
    d.mkdir()
    _write(d, "-2.yaml", GEARS)
    res = runner.invoke(app, ["batch", str(d), "--out", str(tmp_path / "b")])
    assert res.exit_code == 0, res.output
    folders = [p.name for p in (tmp_path / "b").iterdir() if p.is_dir()]
    assert folders == ["v_-2"], folders


def test_answers_file_follows_the_rule_for_every_text(tmp_path):
    """An answers file with a lone surrogate in a path was an internal error
    (UnicodeEncodeError) of `tmm check`: exit 2 naming the file, line and field."""
    task = _write(tmp_path, "g.yaml", GEARS)
    ans = _write(tmp_path, "a.yaml", 'student: {name: "Ann"}\nanswers:\n  "gears.a\\ud800w": 0.088\n'
                                     '  "gears.\\x01aw": 0.088\n')
    res = subprocess.run([*TMM, "check", str(task), "--answers", str(ans)], capture_output=True, text=True,
                         timeout=120, errors="backslashreplace")
    assert res.returncode == 2, res.stderr
    assert r"a.yaml:3:3: field 'answers.gears.a\ud800w': the character U+D800" in res.stderr, res.stderr
    assert r"a.yaml:4:3: field 'answers.gears.\u0001aw': the character U+0001" in res.stderr, res.stderr
    assert "internal error" not in res.stderr


# ---------------------------------------------------------------- item 8 (the labels' memory)
def test_label_distances_in_bounded_memory(monkeypatch):
    """The label placement's distances to the drawing's lines and points made a (lines,
    candidates) temporary: 1,500 extra points took 4.4 GB, 4,000 a MemoryError. Now a
    block of candidates at a time: the same numbers, memory in proportion to the count."""
    import tracemalloc

    import numpy as np

    from tmm_cli.report import figures
    rng = np.random.default_rng(37)
    segs = rng.uniform(-1, 1, (600, 2, 2))
    px, py = rng.uniform(-1, 1, 700), rng.uniform(-1, 1, 700)
    cx, cy = rng.uniform(-1.2, 1.2, 30_000), rng.uniform(-1.2, 1.2, 30_000)
    seg = figures.segment_set(segs)
    tracemalloc.start()
    try:
        d_seg = seg.dists(cx, cy)
        d_pts = figures._point_dists(cx, cy, px, py)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 100e6, peak                   # one (600, 30000) temporary alone is 144 MB
    monkeypatch.setattr(figures, "_BLOCK", 1 << 40)     # one call: the very same numbers
    assert np.array_equal(seg.dists(cx, cy), d_seg)
    assert np.array_equal(figures._point_dists(cx, cy, px, py), d_pts)
    monkeypatch.setattr(figures, "_BLOCK", 7)           # blocks of one candidate
    assert np.array_equal(seg.dists(cx[:500], cy[:500]), d_seg[:500])
    assert np.array_equal(figures._point_dists(cx[:500], cy[:500], px, py), d_pts[:500])
