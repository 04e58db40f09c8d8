"""The instructor's loop, graded answer by answer: an unreadable answer is that answer's
`invalid`, a student's own tolerance is ignored, and every grade here is checked against
a recomputation written in this file (involute gear geometry from the textbook formulas)."""
from __future__ import annotations

import json
import csv
import math
import re
from pathlib import Path

import pytest
from typer.testing import CliRunner

from test_cli import SLIDER_CRANK
from test_instructor import _write
from tmm_cli.cli import app

runner = CliRunner()

GEARS = """schema: tmm/1
title: gears
variant: {v}
gears: {{m: 4 mm, z: [{z1}, {z2}], x: [0.3, 0.1]}}
"""


def _csv(path: Path) -> list[dict]:
    """Rows of a CSV as tmm writes it (a BOM read away, `;` or `,`, decimal commas kept as text)."""
    with open(path, encoding="utf-8-sig", newline="") as fh:
        text = fh.read()
    return list(csv.DictReader(text.splitlines(), delimiter=";" if text.split("\n")[0].count(";") else ","))


def gear_key(z1: int, z2: int, x1: float = 0.3, x2: float = 0.1, m: float = 0.004) -> dict[str, float]:
    """alpha_w (deg) from inv alpha_w = inv 20 + 2 (x1 + x2) tan 20 / (z1 + z2) (Newton),
    aw = m (z1 + z2) / 2 cos 20 / cos alpha_w (m)."""
    a = math.radians(20.0)
    target = math.tan(a) - a + 2 * (x1 + x2) * math.tan(a) / (z1 + z2)
    w = a
    for _ in range(60):
        w -= (math.tan(w) - w - target) / math.tan(w) ** 2
    return {"gears.alpha_w": math.degrees(w), "gears.aw": m * (z1 + z2) / 2 * math.cos(a) / math.cos(w)}


def expect(value: float, ref: float, rel: float = 0.05) -> str:
    """ok within rel |ref|, sign when -value is, else outside."""
    if abs(value - ref) <= rel * abs(ref):
        return "ok"
    return "sign" if abs(-value - ref) <= rel * abs(ref) else "outside"


def test_one_unreadable_answer_leaves_the_others_graded(tmp_path):
    key = gear_key(14, 30)
    t = _write(tmp_path, "g.yaml", GEARS.format(v=4, z1=14, z2=30))
    aw, alpha = key["gears.aw"] * 1.03, key["gears.alpha_w"] * 0.9
    f = _write(tmp_path, "s.yaml", "variant: 4\nstudent: {name: Ivanov}\nanswers:\n"
                                   f"  gears.aw: {aw}\n  gears.alpha_w: {alpha}\n  gears.y: около 0,6\n")
    res = runner.invoke(app, ["check", str(t), "--answers", str(f), "--out", str(tmp_path / "c")])
    assert res.exit_code == 1, res.output
    rows = {r["path"]: r for r in _csv(tmp_path / "c" / "check.csv")}
    assert rows["gears.aw"]["status"] == expect(aw, key["gears.aw"]) == "ok"
    assert rows["gears.alpha_w"]["status"] == expect(alpha, key["gears.alpha_w"]) == "outside"
    assert rows["gears.y"]["status"] == "invalid" and rows["gears.y"]["answer"] == "около 0,6"
    assert rows["gears.y"]["note"].startswith("invalid answer: 'около 0,6' is not a number")


def test_a_class_csv_with_one_bad_cell_grades_everyone(tmp_path):
    """`check` with a class CSV: one unreadable cell is that cell's `invalid`; the row's
    other answers and the other students are graded (exit 1, not 2)."""
    key = gear_key(14, 30)
    t = _write(tmp_path, "g.yaml", GEARS.format(v=4, z1=14, z2=30))
    vals = {"A": (key["gears.aw"], key["gears.alpha_w"] * 1.04), "B": ("216 kg m2", -key["gears.alpha_w"]),
            "C": (key["gears.aw"] * 1.2, key["gears.alpha_w"])}
    tab = _write(tmp_path, "class.csv", "student,group,variant,gears.aw,gears.alpha_w\n"
                 + "".join(f"{s},G,4,{a},{b}\n" for s, (a, b) in vals.items()))
    res = runner.invoke(app, ["check", str(t), "--answers", str(tab), "--out", str(tmp_path / "c")])
    assert res.exit_code == 1, res.output
    got = {(r["student"], r["path"]): r["status"] for r in _csv(tmp_path / "c" / "check.csv")}
    for s, (a, b) in vals.items():
        want_a = "invalid" if isinstance(a, str) else expect(a, key["gears.aw"])
        assert got[(s, "gears.aw")] == want_a
        assert got[(s, "gears.alpha_w")] == expect(b, key["gears.alpha_w"])
    assert got[("B", "gears.alpha_w")] == "sign" and got[("C", "gears.aw")] == "outside"


def test_batch_grades_around_an_unreadable_answer_and_writes_the_feedback(tmp_path):
    src, ans = tmp_path / "src", tmp_path / "ans"
    key = gear_key(14, 30)
    _write(src, "v4.yaml", GEARS.format(v=4, z1=14, z2=30))
    _write(ans, "ivanov.yaml", "variant: 4\nstudent: {name: Ivanov}\nanswers:\n"
                               f"  gears.aw: \"{key['gears.aw'] * 1000:.3f} mm\"\n  gears.alpha_w: около 22,5\n")
    res = runner.invoke(app, ["batch", str(src), "--answers", str(ans), "--out", str(tmp_path / "o"),
                              "--format", "json,html"])
    assert res.exit_code == 1, res.output
    row = _csv(tmp_path / "o" / "summary.csv")[0]
    assert row["gears.aw"] == expect(round(key["gears.aw"] * 1000, 3) / 1000, key["gears.aw"]) == "ok"
    assert row["gears.alpha_w"] == "invalid" and row["invalid"] == "1"
    assert row["status"] == "outside" and float(row["score"]) == 0.5 and row["message"] == "invalid: gears.alpha_w"
    assert list((tmp_path / "o" / "v4").glob("feedback-*.html"))


def test_a_students_tolerance_is_ignored_with_a_warning(tmp_path):
    """A `tolerance:` in a student's file must not let 30 % off pass: check and batch."""
    key = gear_key(14, 30)
    t = _write(tmp_path, "src" / Path("v4.yaml"), GEARS.format(v=4, z1=14, z2=30))
    aw = key["gears.aw"] * 1.3
    f = _write(tmp_path / "ans", "s.yaml", "variant: 4\nstudent: {name: Ivanov}\ntolerance: {default: 0.5}\n"
                                           f"answers:\n  gears.aw: {aw}\n")
    res = runner.invoke(app, ["check", str(t), "--answers", str(f), "--out", str(tmp_path / "c")])
    assert res.exit_code == 1, res.output
    assert "the answers file's `tolerance` is ignored" in res.output
    r = _csv(tmp_path / "c" / "check.csv")[0]
    assert r["status"] == expect(aw, key["gears.aw"]) == "outside" and r["tolerance"] == "0.05"
    res = runner.invoke(app, ["batch", str(tmp_path / "src"), "--answers", str(tmp_path / "ans"),
                              "--out", str(tmp_path / "o")])
    assert res.exit_code == 1 and "the answers file's `tolerance` is ignored" in " ".join(res.output.split())
    assert _csv(tmp_path / "o" / "summary.csv")[0]["gears.aw"] == "outside"


def test_sign_any_grades_the_magnitude(tmp_path):
    """`sign: any` in the task's tolerance: |ω| passes; without it a negated answer is `sign`."""
    from tmm_cli.check import Tol, compare, parse_tolerance
    t = parse_tolerance({"rel": 0.05, "sign": "any"}, "kinematics")
    assert t == Tol(0.05, 0.0, False, True) and t.text == "rel 0.05 sign any"
    for ref, ans in ((-12.5, 12.6), (-12.5, -12.4), (12.5, -12.0), (12.5, 14.0), (-3.0, 0.0)):
        want = "ok" if abs(abs(ans) - abs(ref)) <= 0.05 * abs(ref) else "outside"
        assert compare(ans, ref, t, False)[0] == want
        plain = "ok" if abs(ans - ref) <= 0.05 * abs(ref) else ("sign" if abs(ans + ref) <= 0.05 * abs(ref)
                                                                  else "outside")
        assert compare(ans, ref, Tol(0.05, 0.0, False), False)[0] == plain
    key = gear_key(14, 30)
    task = GEARS.format(v=4, z1=14, z2=30) + 'tolerance: {"gears.alpha_w": {rel: 0.02, sign: any}}\n'
    f = _write(tmp_path, "g.yaml", task)
    a = _write(tmp_path, "a.yaml", f"answers:\n  gears.alpha_w: {-key['gears.alpha_w'] * 1.01}\n"
                                   f"  gears.aw: {-key['gears.aw']}\n")
    res = runner.invoke(app, ["check", str(f), "--answers", str(a), "--out", str(tmp_path / "c")])
    assert res.exit_code == 1, res.output
    rows = {r["path"]: r for r in _csv(tmp_path / "c" / "check.csv")}
    assert rows["gears.alpha_w"]["status"] == "ok" and rows["gears.alpha_w"]["tolerance"] == "rel 0.02 sign any"
    assert rows["gears.aw"]["status"] == expect(-key["gears.aw"], key["gears.aw"]) == "sign"
    bad = _write(tmp_path, "b.yaml", GEARS.format(v=4, z1=14, z2=30) + "tolerance: {default: {sign: plus}}\n")
    res = runner.invoke(app, ["check", str(bad), "--answers", str(a)])
    assert res.exit_code == 2 and "Traceback" not in res.output


def test_forms_state_the_sign_conventions_and_the_filled_form_csv_reads_back(tmp_path):
    """The form's comments and form.csv's notes row say which sense is positive; the notes
    row is never read as a student's answers."""
    lever = Path(__file__).resolve().parent.parent / "tasks" / "crank_rocker_fourbar.yaml"
    out = tmp_path / "forms"
    res = runner.invoke(app, ["form", str(lever), "-q", "kinematics[1].links.coupler.omega,kinematics[1].points.B.v",
                              "--out", str(out), "--lang", "uk"])
    assert res.exit_code == 0, res.output
    form = (out / "crank_rocker_fourbar.form.yaml").read_text(encoding="utf-8")
    assert "проти годинникової стрілки — плюс" in form and "модуль, без знака" in form
    key = (out / "crank_rocker_fourbar.key.yaml").read_text(encoding="utf-8")
    assert "проти годинникової стрілки — плюс" in key
    rows = _csv(out / "form.csv")
    assert rows[0]["student"] == "# знак"
    assert rows[0]["kinematics[1].links.coupler.omega"] == "зі знаком: проти годинникової стрілки — плюс"
    assert [r["student"] for r in _csv(out / "key.csv")] == [""]
    # the filled form.csv, notes row and all, graded: one student, not two
    import yaml
    ref = yaml.safe_load(key)["answers"]
    text = (out / "form.csv").read_text(encoding="utf-8").splitlines()
    cells = text[2].split(",")
    cells[0], cells[3], cells[4] = "Ivanov", str(ref["kinematics[1].links.coupler.omega"]), "1"
    filled = _write(tmp_path, "filled.csv", "\n".join(text[:2] + [",".join(cells)]) + "\n")
    res = runner.invoke(app, ["check", str(lever), "--answers", str(filled), "--out", str(tmp_path / "c")])
    got = {r["path"]: (r["student"], r["status"]) for r in _csv(tmp_path / "c" / "check.csv")}
    assert got["kinematics[1].links.coupler.omega"] == ("Ivanov", "ok")
    assert got["kinematics[1].points.B.v"] == ("Ivanov", expect(1.0, ref["kinematics[1].points.B.v"]))
    assert len(got) == 2 and res.exit_code == 1, res.output


def test_answers_file_named_repeats_flagged_and_latest(tmp_path):
    """answers_file in summary.csv and check.csv; a student's second submission for one
    variant is flagged `repeat=`; --latest grades only the newest by modification time."""
    import os
    src, ans = tmp_path / "src", tmp_path / "ans"
    key = gear_key(14, 30)
    _write(src, "v4.yaml", GEARS.format(v=4, z1=14, z2=30))
    old = _write(ans, "ivanov-1.yaml", f"variant: 4\nstudent: {{name: Ivanov}}\nanswers: {{gears.aw: {key['gears.aw'] * 2}}}\n")
    new = _write(ans, "ivanov-2.yaml", f"variant: 4\nstudent: {{name: Ivanov}}\nanswers: {{gears.aw: {key['gears.aw']}}}\n")
    _write(ans, "anon.yaml", f"variant: 4\nanswers: {{gears.aw: {key['gears.aw'] * 1.01}}}\n")
    os.utime(old, (1_000_000, 1_000_000))
    os.utime(new, (2_000_000, 2_000_000))
    res = runner.invoke(app, ["batch", str(src), "--answers", str(ans), "--out", str(tmp_path / "o")])
    rows = {r["answers_file"]: r for r in _csv(tmp_path / "o" / "summary.csv")}
    assert set(rows) == {"ivanov-1.yaml", "ivanov-2.yaml", "anon.yaml"}, res.output
    assert rows["ivanov-1.yaml"]["flags"] == "repeat=ivanov-2.yaml"
    assert rows["ivanov-2.yaml"]["flags"] == "repeat=ivanov-1.yaml"
    assert rows["anon.yaml"]["flags"] == "" and rows["anon.yaml"]["student"] == ""
    assert rows["ivanov-1.yaml"]["gears.aw"] == expect(key["gears.aw"] * 2, key["gears.aw"]) == "outside"
    assert {r["answers_file"] for r in _csv(tmp_path / "o" / "check.csv")} == set(rows)
    fb = sorted(p.name for p in (tmp_path / "o" / "v4").glob("feedback-*.html"))
    assert fb == ["feedback-Ivanov-ivanov-1.html", "feedback-Ivanov-ivanov-2.html", "feedback-answers-anon.html"]
    res = runner.invoke(app, ["batch", str(src), "--answers", str(ans), "--out", str(tmp_path / "l"), "--latest"])
    rows = {r["answers_file"]: r for r in _csv(tmp_path / "l" / "summary.csv")}
    assert set(rows) == {"ivanov-2.yaml", "anon.yaml"} and rows["ivanov-2.yaml"]["flags"] == ""
    assert res.exit_code == 0 and "ivanov-1.yaml: an older submission of Ivanov" in " ".join(res.output.split())
    # a class table: NAME.csv:LINE; check flags the repeat, --latest keeps the later row
    tab = _write(tmp_path, "class.csv", "student,variant,gears.aw\n"
                                        f"Petrov,4,{key['gears.aw'] * 3}\nPetrov,4,{key['gears.aw']}\n")
    t = src / "v4.yaml"
    res = runner.invoke(app, ["check", str(t), "--answers", str(tab), "--out", str(tmp_path / "c")])
    assert res.exit_code == 1 and "another submission of Petrov" in " ".join(res.output.split()), res.output
    assert [r["answers_file"] for r in _csv(tmp_path / "c" / "check.csv")] == ["class.csv:2", "class.csv:3"]
    res = runner.invoke(app, ["check", str(t), "--answers", str(tab), "--latest", "--out", str(tmp_path / "c2")])
    got = [(r["answers_file"], r["status"]) for r in _csv(tmp_path / "c2" / "check.csv")]
    assert got == [("class.csv:3", expect(key["gears.aw"], key["gears.aw"]))] and res.exit_code == 0


def test_idle_stroke_angle_is_compared_modulo_360():
    from tmm_cli.check import AnswerSet, grade
    results = {"positions": {"idle_stroke_angle": 168.3, "working_stroke_angle": 191.7}}
    rows = grade(results, AnswerSet(source="s.yaml", answers={"positions.idle_stroke_angle": 168.3 - 360,
                                                              "positions.working_stroke_angle": 191.7 + 360}),
                 {"default": 0.01})
    assert [r["status"] for r in rows] == ["ok", "ok"]


def test_a_subset_against_the_whole_answers_folder_skips_the_others_with_one_note(tmp_path):
    src, ans = tmp_path / "src", tmp_path / "ans"
    key = gear_key(14, 30)
    for v in (1, 2, 3):
        _write(src, f"v{v}.yaml", GEARS.format(v=v, z1=14, z2=30))
        _write(ans, f"s{v}.yaml", f"variant: {v}\nstudent: {{name: S{v}}}\nanswers: {{gears.aw: {key['gears.aw']}}}\n")
    _write(ans, "ghost.yaml", "variant: 77\nanswers: {gears.aw: 1}\n")
    res = runner.invoke(app, ["batch", str(src / "v1.yaml"), "--answers", str(ans), "--out", str(tmp_path / "o")])
    rows = _csv(tmp_path / "o" / "summary.csv")
    assert [(r["student"], r["status"]) for r in rows] == [("S1", "ok"), ("", "invalid")], res.output
    assert "no task of this variant" in rows[1]["message"]          # variant 77 is nowhere: still invalid
    text = " ".join(res.output.split())
    assert text.count("not graded: 2 (2, 3)") == 1 and res.exit_code == 2


def test_paths_group_and_choose_positions(tmp_path):
    lever = Path(__file__).resolve().parent.parent / "tasks" / "crank_rocker_fourbar.yaml"
    full = runner.invoke(app, ["paths", str(lever), "--prefix", "kinematics_curve"]).output.splitlines()
    grouped = runner.invoke(app, ["paths", str(lever), "--prefix", "kinematics_curve", "--group"]).output.splitlines()
    arrays: dict[str, list[float]] = {}
    for ln in full:
        p, v = ln.split("\t")
        base, _, i = p.rpartition("[")
        if i.rstrip("]").isdigit():
            arrays.setdefault(base, []).append(float(v))
    long = {b: v for b, v in arrays.items() if len(v) > 12}
    assert long and len(grouped) < len(full)
    for b, vals in long.items():
        line = [g for g in grouped if g.startswith(b + "[0..")]
        assert line == [f"{b}[0..{len(vals) - 1}]\t{len(vals)} values, {min(vals):.6g} .. {max(vals):.6g}"]
    chosen = runner.invoke(app, ["paths", str(lever), "--index", "2,5-6", "--prefix", "kinematics["]).output
    assert {m for m in re.findall(r"^kinematics\[(\d+)\]", chosen, re.M)} == {"2", "5", "6"}
    assert runner.invoke(app, ["paths", str(lever), "--index", "x"]).exit_code == 2


def _group(tmp_path, answers: dict[str, tuple[int, float, float]]):
    """Gear variants 1..3 (z1 = 14, 20, 26) and an answers folder: student -> (variant, aw, alpha_w)."""
    src, ans = tmp_path / "src", tmp_path / "ans"
    for v in (1, 2, 3):
        _write(src, f"v{v}.yaml", GEARS.format(v=v, z1=8 + 6 * v, z2=30))
    for name, (v, aw, al) in answers.items():
        _write(ans, f"{name.lower()}.yaml", f"variant: {v}\nstudent: {{name: {name}, group: G1, email: "
                                            f"{name.lower()}@uni.example}}\nanswers:\n  gears.aw: {aw!r}\n"
                                            f"  gears.alpha_w: {al!r}\n")
    return src, ans


def test_copies_flagged_grades_and_a_moodle_gradebook(tmp_path):
    keys = {v: gear_key(8 + 6 * v, 30) for v in (1, 2, 3)}
    k1, k3 = keys[1], keys[3]
    answers = {"Anna": (1, k1["gears.aw"] * 1.01, k1["gears.alpha_w"] * 0.99),
               "Boris": (1, k1["gears.aw"] * 1.01, k1["gears.alpha_w"] * 0.99),      # Anna's numbers, verbatim
               "Clara": (2, k3["gears.aw"], k3["gears.alpha_w"]),                   # variant 3's key on variant 2
               "Dmitro": (3, k3["gears.aw"] * 1.08, k3["gears.alpha_w"])}
    src, ans = _group(tmp_path, answers)
    res = runner.invoke(app, ["batch", str(src), "--answers", str(ans), "--out", str(tmp_path / "o"),
                              "--grades", "5:0.9,4:0.75,3:0.6", "--gradebook", "moodle"])
    assert res.exit_code == 1, res.output
    rows = {r["student"]: r for r in _csv(tmp_path / "o" / "summary.csv")}
    # the independent recomputation: statuses, score, grade, and the copy rules
    for name, (v, aw, al) in answers.items():
        st = [expect(aw, keys[v]["gears.aw"]), expect(al, keys[v]["gears.alpha_w"])]
        score = st.count("ok") / 2
        assert [rows[name]["gears.aw"], rows[name]["gears.alpha_w"]] == st
        assert float(rows[name]["score"]) == score
        assert rows[name]["grade"] == str(next((g for g, least in ((5, .9), (4, .75), (3, .6)) if score >= least), 2))
        flags = []
        for other, (_, aw2, al2) in answers.items():
            same = [abs(x - y) <= 1e-9 * max(abs(x), abs(y)) for x, y in ((aw, aw2), (al, al2))]
            if other != name and sum(same) >= 0.8 * 2:
                flags.append(f"same_as={other}")
        own = st.count("ok")
        best = max(((sum(expect(x, keys[w][p]) == "ok" for x, p in ((aw, "gears.aw"), (al, "gears.alpha_w"))), -w)
                    for w in keys if w != v), default=(0, 0))
        if best[0] > own:
            flags.append(f"key_of={-best[1]}")
        assert rows[name]["flags"] == ";".join(flags), name
    assert rows["Boris"]["flags"] == "same_as=Anna" and rows["Clara"]["flags"] == "key_of=3"
    html = (tmp_path / "o" / "summary.html").read_text(encoding="utf-8")
    assert "key_of=3" in html and "same_as=Anna" in html                   # the flags' titles
    assert "same answers as Anna" in html and "within tolerance of variant 3&#x27;s key" in html
    # the evidence beside it: Anna's and Boris's two answers are both right (aw 1 % off, alpha_w 1 % off)
    assert [rows[n]["gears.aw"] for n in ("Anna", "Boris")] == ["ok", "ok"]
    assert "same answers as Anna (2 answers, all within tolerance: right results agree by themselves)" in html
    book = _csv(tmp_path / "o" / "gradebook-moodle.csv")
    assert list(book[0]) == ["Email address", "ID number", "Full name", "Group", "tmm grade", "Feedback"]
    assert {(b["Email address"], b["tmm grade"]) for b in book} == {
        (f"{n.lower()}@uni.example", rows[n]["grade"]) for n in answers}
    assert "no email and no ID number" not in res.output               # every line has its email
    # an answers file without an email or id: its line is told (Moodle cannot match it)
    _write(ans, "anon.yaml", f"variant: 1\nanswers: {{gears.aw: {k1['gears.aw']}}}\n")
    res = runner.invoke(app, ["batch", str(src), "--answers", str(ans), "--out", str(tmp_path / "o2"),
                              "--gradebook", "moodle"])
    text = " ".join(res.output.split())
    assert "gradebook-moodle.csv: 1 line has no email and no ID number" in text and "(anon.yaml)" in text, text


def test_feedback_pages_show_the_tolerance_the_unit_written_and_no_key_on_request(tmp_path):
    from html import unescape
    key = gear_key(14, 30)
    src = tmp_path / "src"
    _write(src, "v4.yaml", GEARS.format(v=4, z1=14, z2=30) + 'tolerance: {"gears.alpha_w": {abs: 0.5}}\n')
    aw_mm = round(key["gears.aw"] * 1000 * 1.02, 2)
    _write(tmp_path / "ans", "ivanov.yaml", "variant: 4\nstudent: {name: Ivanov}\nanswers:\n"
                                           f"  gears.aw: \"{aw_mm} mm\"\n  gears.alpha_w: {key['gears.alpha_w'] + 0.3}\n")
    for mode in ("key", "no-key"):
        out = tmp_path / mode
        res = runner.invoke(app, ["batch", str(src), "--answers", str(tmp_path / "ans"), "--out", str(out),
                                  "--format", "json,html", "--lang", "ru", "--feedback", mode])
        assert res.exit_code == 0, res.output
        page = unescape((out / "v4" / "feedback-Ivanov-ivanov.html").read_text(encoding="utf-8"))
        assert f"{aw_mm} mm" in page                                  # the value as the student wrote it
        assert "±5 %" in page and "±0,5°" in page                      # each answer's tolerance (° closed up)
        ref_mm = f"{key['gears.aw'] * 1000:.5g}".replace(".", ",")   # the reference in the student's unit
        assert (f"{ref_mm} mm" in page) == (mode == "key") and ("эталон" in page) == (mode == "key")


def test_summary_html_typo_columns_and_the_no_answer_marks(tmp_path):
    key = gear_key(14, 30)
    src = tmp_path / "src"
    _write(src, "v4.yaml", GEARS.format(v=4, z1=14, z2=30))
    _write(src, "v5.yaml", GEARS.format(v=5, z1=14, z2=30))
    ans = tmp_path / "ans"
    _write(ans, "a.yaml", f"variant: 4\nstudent: {{name: A}}\nanswers:\n  gears.aw: {key['gears.aw']}\n"
                          "  gears.a_w: 1\n  gears.alpha_ww: 3\n")
    res = runner.invoke(app, ["batch", str(src), "--answers", str(ans), "--out", str(tmp_path / "o"), "--lang", "uk"])
    html = (tmp_path / "o" / "summary.html").read_text(encoding="utf-8")
    assert 'title="gears.a_w"' not in html and 'title="gears.aw"' in html      # a typo gets no column
    row = [ln for ln in html.split("<tr>") if ">A<" in ln][0]
    assert "100 %" in row                                 # 1 ok of 1 known: the typos are not in the denominator
    assert "∅" in html and COLOUR_NONE in html            # nobody answered variant 5: not the missing mark
    assert "<span>gears.alpha_ww</span>" not in html and res.exit_code == 1


COLOUR_NONE = "#cfd8dc"


def test_excel_ru_csv_every_file_of_the_run(tmp_path):
    """--csv excel-ru: `;`, decimal commas, a UTF-8 BOM in summary.csv, check.csv (both),
    the gradebook and a variant's own tables; form.csv and key.csv too, and a filled form
    written so is read back."""
    key = gear_key(14, 30)
    src = tmp_path / "src"
    t = _write(src, "v4.yaml", GEARS.format(v=4, z1=14, z2=30))
    res = runner.invoke(app, ["form", str(t), "-q", "gears.aw,gears.alpha_w", "--out", str(tmp_path / "f"),
                              "--lang", "ru", "--csv", "excel-ru"])
    assert res.exit_code == 0, res.output
    raw = (tmp_path / "f" / "key.csv").read_bytes()
    assert raw.startswith("\ufeff".encode()) and raw.splitlines()[0] == "\ufeffstudent;group;variant;gears.aw;gears.alpha_w".encode()
    ref_aw = float(_csv(tmp_path / "f" / "key.csv")[0]["gears.aw"].replace(",", "."))
    assert ref_aw == key["gears.aw"] or abs(ref_aw / key["gears.aw"] - 1) < 1e-12
    lines = (tmp_path / "f" / "form.csv").read_text(encoding="utf-8-sig").splitlines()
    cells = lines[-1].split(";")
    cells[0], cells[3], cells[4] = "Ivanov", f"{key['gears.aw']:.6f}".replace(".", ","), "1"
    filled = _write(tmp_path, "filled.csv", "\ufeff" + "\n".join(lines[:-1] + [";".join(cells)]) + "\n")
    out = tmp_path / "o"
    res = runner.invoke(app, ["batch", str(src), "--answers", str(filled), "--out", str(out), "--csv", "excel-ru",
                              "--gradebook", "moodle", "--format", "json,html"])
    assert res.exit_code == 1, res.output
    for f in [out / "summary.csv", out / "check.csv", out / "gradebook-moodle.csv", out / "v4" / "check.csv",
              out / "v4" / "gears_sliding.csv"]:
        text = f.read_text(encoding="utf-8")
        assert text.startswith("\ufeff") and ";" in text.splitlines()[0], f
        assert not any(c.replace(".", "", 1).isdigit() and "." in c for ln in text.splitlines()
                       for c in ln.split(";")), f
    row = _csv(out / "summary.csv")[0]
    assert row["score"] == "0,5" and row["gears.aw"] == expect(round(key["gears.aw"], 6), key["gears.aw"]) == "ok"
    assert row["gears.alpha_w"] == expect(1.0, key["gears.alpha_w"]) == "outside"


def test_a_batch_compiles_the_report_templates_once(tmp_path, monkeypatch):
    """Without a bytecode cache (PYTHONDONTWRITEBYTECODE) every report compiled every
    template again; now the batch compiles them before it forks, and a second report in
    one process compiles nothing."""
    import sys
    from tmm_cli import report
    from tmm_cli.batch import warm
    monkeypatch.setattr(sys, "dont_write_bytecode", True)
    monkeypatch.setattr(report, "_SHARED_ENV", None)
    t = _write(tmp_path, "g.yaml", GEARS.format(v=4, z1=14, z2=30))
    warm([t], {"json", "html"})
    import gc
    gc.unfreeze()
    env = report.shared_env()
    monkeypatch.setattr(env, "_compile", lambda *a: (_ for _ in ()).throw(AssertionError("compiled again")))
    for out in ("a", "b"):
        res = runner.invoke(app, ["run", str(t), "--format", "json,html", "--out", str(tmp_path / out), "-q"])
        assert res.exit_code == 0, res.output
        assert (tmp_path / out / "report.html").exists()


def test_key_table_counts_what_compare_grades_ok():
    """The vectorised key_of counts, per variant, exactly the answers compare() passes
    (relative, plain against a zero reference, sign: any, angles modulo 360)."""
    import random
    from tmm_cli.check import Tol, compare
    from tmm_cli.copies import KeyTable
    rnd = random.Random(7)
    paths = [f"p{i}" for i in range(6)]
    keys = [{p: (rnd.choice([0.0, rnd.uniform(-200, 200)]), Tol(0.05, rnd.choice([0.0, 0.3]), rnd.random() < .5,
                                                               rnd.random() < .3), p == "p0") for p in paths}
            for _ in range(40)]
    table = KeyTable(keys)
    for i in range(40):
        a = {p: keys[i][p][0] * rnd.choice([1, 1.03, -1, 0.7]) + rnd.choice([0, 360]) * (p == "p0")
             for p in paths}
        got = table.counts(a)
        for k in range(40):
            assert got[k] == sum(compare(v, *keys[k][p])[0] == "ok" for p, v in a.items()), (i, k)


def test_a_form_of_a_task_without_a_variant_is_matched_by_the_batch(tmp_path):
    """`tmm form` writes a task's file stem as the form's `variant` where the task has none;
    `tmm batch` matches that filled form to the task (it was "no task of this variant")."""
    src = tmp_path / "tasks"
    _write(src, "pair.yaml", GEARS.format(v=1, z1=14, z2=30).replace("variant: 1\n", ""))
    res = runner.invoke(app, ["form", str(src), "-q", "gears.aw,gears.alpha_w", "--out", str(tmp_path / "f")])
    assert res.exit_code == 0, res.output
    form = (tmp_path / "f" / "pair.form.yaml").read_text(encoding="utf-8")
    assert 'variant: "pair"' in form
    key = gear_key(14, 30)
    filled = form.replace('"gears.aw":', f'"gears.aw": {key["gears.aw"]!r}').replace(
        '"gears.alpha_w":', f'"gears.alpha_w": {key["gears.alpha_w"] * 1.2!r}')
    _write(tmp_path / "answers", "ivanov.yaml", filled)
    res = runner.invoke(app, ["batch", str(src), "--out", str(tmp_path / "o"), "--answers", str(tmp_path / "answers")])
    rows = _csv(tmp_path / "o" / "summary.csv")
    assert [(Path(r["file"]).name, r["status"], r["ok"], r["outside"]) for r in rows] == \
        [("pair.yaml", "outside", "1", "1")], res.output
    assert res.exit_code == 1
    assert re.search(r"tmm batch: 1 row\b(?!s)", res.output), res.output      # was "1 rows"


def test_counts_are_graded_exactly_unless_the_tolerance_names_them(tmp_path):
    """Tooth numbers are counts: z3 = z1 + 2 z2 (the single-row planetary train's coaxiality,
    40 + 2*23 = 86), so 85 is wrong however close -- it was ok within the default 5 %; a
    tolerance given on the path or a prefix of it still holds; non-counts keep the default."""
    task = Path(__file__).resolve().parents[1] / "tasks" / "planetary_A.yaml"
    z1, z2 = 40, 23
    answers = _write(tmp_path, "a.yaml", f"answers:\n  planetary.z.z1: {z1}\n  planetary.z.z2: {z2}\n"
                                         f"  planetary.z.z3: {z1 + 2 * z2 - 1}\n  planetary.z.z2x: 1\n"
                                         f"  planetary.ratio: '{1 + (z1 + 2 * z2) / z1 * 1.01}'\n")
    res = runner.invoke(app, ["check", str(task), "--answers", str(answers), "--out", str(tmp_path / "o")])
    rows = {r["path"]: r for r in _csv(tmp_path / "o" / "check.csv")}
    assert float(rows["planetary.z.z3"]["reference"]) == z1 + 2 * z2
    assert [rows[f"planetary.z.z{k}"]["status"] for k in (1, 2, 3)] == ["ok", "ok", "outside"], res.output
    assert rows["planetary.z.z3"]["tolerance"] == "0"
    assert rows["planetary.ratio"]["status"] == "ok" and rows["planetary.ratio"]["tolerance"] == "0.05"
    tol = _write(tmp_path, "tol.yaml", "planetary.z: {abs: 1}\n")
    runner.invoke(app, ["check", str(task), "--answers", str(answers), "--tolerance", str(tol),
                        "--out", str(tmp_path / "o2")])
    rows = {r["path"]: r for r in _csv(tmp_path / "o2" / "check.csv")}
    assert rows["planetary.z.z3"]["status"] == "ok" and rows["planetary.z.z3"]["tolerance"] == "abs 1"


def test_the_crank_angle_of_an_event_is_an_angle():
    """gamma_min_phi (the crank angle of the least transmission angle) and the like are compared
    modulo 360: 360 deg is 0 deg."""
    from tmm_cli.check import EXACT, Tol, _is_angle, compare
    assert _is_angle("synthesis.gamma_min_phi") and _is_angle("cam.max_pressure_angle_phi")
    assert not _is_angle("synthesis.gamma_min_physics") and not _is_angle("flywheel.J")
    assert compare(360.0, 0.5, Tol(rel=0, abs=1, plain=False), True)[0] == "ok"
    assert compare(357.0, 0.5, Tol(rel=0, abs=1, plain=False), True)[0] == "outside"
    assert compare(86.0, 86.0, EXACT, False)[0] == "ok" and compare(85.0, 86.0, EXACT, False)[0] == "outside"


def test_tolerance_in_percent_and_a_share_of_one_or_more_refused(tmp_path):
    """'5 %' is the share 0.05; `default: 5` (meant for 5 %) passed every answer within 500 % --
    now an invalid tolerance file (exit 2) that says how a share is written; an absolute
    tolerance takes no percent."""
    from tmm_cli.units import tolerance_number
    assert tolerance_number("5 %") == 0.05 and tolerance_number("2,5%", "rel") == 0.025
    assert tolerance_number("0,05") == 0.05 and tolerance_number(7, "abs") == 7.0
    for bad, what in (("5 %", "abs"), (5, "plain"), ("100 %", "rel"), (1, "rel")):
        with pytest.raises(ValueError):
            tolerance_number(bad, what)
    src = tmp_path / "t"
    task = _write(src, "v1.yaml", GEARS.format(v=1, z1=14, z2=30))
    key = gear_key(14, 30)
    answers = _write(tmp_path, "a.yaml", f"variant: 1\nanswers:\n  gears.aw: {key['gears.aw'] * 1.04!r}\n")
    tol = _write(tmp_path, "tol.yaml", "default: 5\n")
    res = runner.invoke(app, ["check", str(task), "--answers", str(answers), "--tolerance", str(tol)])
    assert res.exit_code == 2 and "tol.yaml" in res.output and "did you mean 0.05" in res.output, res.output
    assert "Traceback" not in res.output
    tol.write_text('default: "3 %"\n', encoding="utf-8")
    res = runner.invoke(app, ["check", str(task), "--answers", str(answers), "--tolerance", str(tol),
                              "--out", str(tmp_path / "o")])
    rows = _csv(tmp_path / "o" / "check.csv")
    assert [(r["status"], r["tolerance"]) for r in rows] == [("outside", "0.03")], res.output


def test_a_misspelt_tolerance_key_is_told_with_the_key_meant(tmp_path):
    """`differential.sped` (for differential.speeds) matched nothing, so the speeds were graded
    at the default 5 % without a word: now a warning names it and the key meant, in `tmm check`
    and once in `tmm batch`; a key of a section the task has not (`kinematics` for a gear
    pair: another task's) and keys that do match are not told."""
    src = tmp_path / "t"
    task = _write(src, "v1.yaml", GEARS.format(v=1, z1=14, z2=30))
    _write(src, "v2.yaml", GEARS.format(v=2, z1=15, z2=30))
    key = gear_key(14, 30)
    answers = _write(tmp_path / "ans", "v1.yaml", f"variant: 1\nanswers:\n  gears.aw: {key['gears.aw']!r}\n")
    tol = _write(tmp_path, "tol.yaml", "gears.alpha_ww: 0.01\ngears.aw: 0.01\ngears.r: 0.01\nkinematics: 0.02\n")
    res = runner.invoke(app, ["check", str(task), "--answers", str(answers), "--tolerance", str(tol)])
    assert res.exit_code == 0, res.output
    told = [ln for ln in res.output.splitlines() if ln.startswith("warning:")]
    assert len(told) == 1 and "'gears.alpha_ww'" in told[0] and "did you mean 'gears.alpha_w'" in told[0], res.output
    res = runner.invoke(app, ["batch", str(src), "--out", str(tmp_path / "o"), "--answers", str(tmp_path / "ans"),
                              "--tolerance", str(tol), "--format", "json"])
    assert res.output.count("'gears.alpha_ww'") == 1, res.output


def test_the_task_files_own_answers_are_read_as_an_answers_files(tmp_path):
    """The task's `answers:` take what an answers file takes ('8,8', '-200 N*m' in Cyrillic
    letters) -- they were refused with pydantic's "unable to parse string as a number" -- and an
    unreadable one is that answer's `invalid`; `tolerance: 0.05` (meant for {default: 0.05})
    says how it is written."""
    key = gear_key(14, 30)
    aw_mm = f"{key['gears.aw'] * 1000:.3f}".replace(".", ",")
    alpha = f"{key['gears.alpha_w']:.4f}".replace(".", ",")
    text = GEARS.format(v=1, z1=14, z2=30) + (f"answers:\n  gears.aw: '{aw_mm} \u043c\u043c'\n"
                                              f"  gears.alpha_w: '{alpha}'\n  gears.y: abc\n")
    task = _write(tmp_path, "v1.yaml", text)
    res = runner.invoke(app, ["check", str(task), "--out", str(tmp_path / "o")])
    rows = {r["path"]: r for r in _csv(tmp_path / "o" / "check.csv")}
    assert {p: r["status"] for p, r in rows.items()} == {"gears.aw": "ok", "gears.alpha_w": "ok", "gears.y": "invalid"}
    assert float(rows["gears.aw"]["answer"]) == pytest.approx(key["gears.aw"], abs=1e-6)
    assert res.exit_code == 1, res.output
    task.write_text(text + "tolerance: 0.05\n", encoding="utf-8")
    res = runner.invoke(app, ["check", str(task)])
    assert res.exit_code == 2 and "tolerance: {default: 0.05}" in res.output and "Traceback" not in res.output


def test_a_missing_answers_or_tolerance_file_is_named_as_what_it_is(tmp_path):
    """A missing --answers file was "error: invalid task", a missing --tolerance file in a batch
    "error: invalid answers / not a regular file": each is headed by what it is, and says it is
    not there."""
    src = tmp_path / "t"
    task = _write(src, "v1.yaml", GEARS.format(v=1, z1=14, z2=30))
    answers = _write(tmp_path, "a.yaml", "variant: 1\nanswers:\n  gears.aw: 0.09\n")
    cases = [(["check", str(task), "--answers", str(tmp_path / "gone.yaml")], "answers file"),
             (["check", str(task), "--answers", str(answers), "--tolerance", str(tmp_path / "gone.yaml")],
              "tolerance file"),
             (["batch", str(src), "--out", str(tmp_path / "o"), "--answers", str(answers),
               "--tolerance", str(tmp_path / "gone.yaml"), "--format", "json"], "tolerance file"),
             (["batch", str(src), "--out", str(tmp_path / "o"), "--answers", str(tmp_path / "gone"),
               "--format", "json"], "answers file")]
    for args, kind in cases:
        res = runner.invoke(app, args)
        assert res.exit_code == 2 and f"error: invalid {kind}\n" in res.output, (args, res.output)
        assert "no such file or folder" in " ".join(res.output.split()) and "Traceback" not in res.output


def test_what_students_write_degrees_minutes_percent_and_a_unit_left_off(tmp_path):
    """36°8′ is 36 + 8/60 degrees (36°08′30″ with seconds; 60 minutes is refused); '97 %' is the
    share 0.97 in a task's efficiency; an answer without a unit that is right in the unit a
    student works in -- 98,5 for 0,0985 m (mm), 0,2856 for 16,36° (rad), 1000 for 104,72 rad/s
    (rpm) -- stays outside and says so."""
    from tmm_cli.check import Tol, _unit_slip
    from tmm_cli.numbers import answer, read
    from tmm_cli.units import quantity
    assert read("36\u00b08\u2032").value == pytest.approx(36 + 8 / 60)
    assert read("36\u00b0 08' 30\"").value == pytest.approx(36 + 8 / 60 + 30 / 3600)
    assert read("-12\u00b030\u2032").value == -12.5 and answer("16\u00b021\u2032", None, angle=True) == pytest.approx(16.35)
    for bad in ("36\u00b060\u2032", "36.5\u00b08\u2032"):
        with pytest.raises(ValueError):
            read(bad)
    assert quantity("97 %", "dimensionless")[0] == pytest.approx(0.97)
    key = gear_key(14, 30)
    aw = key["gears.aw"]
    assert "mm" in str(_unit_slip("gears.aw", aw * 1000, aw, Tol()))
    assert "rad" in str(_unit_slip("gears.alpha_w", math.radians(key["gears.alpha_w"]), key["gears.alpha_w"], Tol()))
    assert "rpm" in str(_unit_slip("kinematics[1].links.crank.omega", 1000.0, 1000 * math.pi / 30, Tol()))
    assert _unit_slip("gears.aw", aw * 1.01, aw, Tol()) is None and _unit_slip("gears.aw", 7.0, aw, Tol()) is None
    task = _write(tmp_path, "v1.yaml", GEARS.format(v=1, z1=14, z2=30)
                  + f"answers:\n  gears.aw: {aw * 1000:.3f}\n  gears.alpha_w: '{int(key['gears.alpha_w'])}"
                    f"\u00b0{(key['gears.alpha_w'] % 1) * 60:.1f}\u2032'\n")
    res = runner.invoke(app, ["check", str(task), "--out", str(tmp_path / "o")])
    rows = {r["path"]: r for r in _csv(tmp_path / "o" / "check.csv")}
    assert rows["gears.alpha_w"]["status"] == "ok" and rows["gears.aw"]["status"] == "outside"
    assert "read in mm it is right" in rows["gears.aw"]["note"] and "read in mm" in " ".join(res.output.split())


# test_cli's slider-crank with its rod shorter than its crank, as variant 5
SHORT_ROD = (SLIDER_CRANK.replace("length: 0.4}", "length: 0.08}")
             .replace("title: slider-crank\n", "title: short rod\nvariant: 5\n"))


def test_a_student_of_a_variant_whose_task_failed_is_told_so(tmp_path):
    """A variant whose task fails (its rod, 0.08 m, shorter than the crank, 0.1 m: no assembly at
    53.13..126.87 deg, where 0.1 sin phi > 0.08) is each of its students' row, status failed with the
    failure, not "no task of this variant"; a variant nobody answered keeps its own row."""
    src, ans = tmp_path / "src", tmp_path / "ans"
    _write(src, "v4.yaml", GEARS.format(v=4, z1=14, z2=30))
    _write(src, "v5.yaml", SHORT_ROD)
    _write(ans, "a.yaml", "variant: 5\nstudent: {name: Savchenko}\nanswers: {positions.phi0: 0}\n")
    res = runner.invoke(app, ["batch", str(src), "--answers", str(ans), "--out", str(tmp_path / "o")])
    rows = _csv(tmp_path / "o" / "summary.csv")
    assert [(r["student"], r["variant"], r["status"]) for r in rows] == [("", "4", "no_answers"),
                                                                      ("Savchenko", "5", "failed")], res.output
    assert "does not assemble for crank angles 53.130102..126.869898" in rows[1]["message"]
    assert rows[1]["answers_file"] == "a.yaml" and "no task" not in res.output
    assert res.exit_code == 3


def test_check_against_a_folder_names_the_files_it_cannot_read(tmp_path):
    """`tmm check TASK --answers FOLDER`: a file of the folder that cannot be read (broken YAML, no
    answers) is named with its reason, not counted as a set of another variant (it was listed as
    variant "None"); the other variants are listed by value (3 before 12)."""
    src, ans = tmp_path / "src", tmp_path / "ans"
    key = gear_key(14, 30)
    _write(src, "v4.yaml", GEARS.format(v=4, z1=14, z2=30))
    _write(ans, "mine.yaml", f"variant: 4\nstudent: {{name: A}}\nanswers: {{gears.aw: {key['gears.aw']}}}\n")
    _write(ans, "v12.yaml", "variant: 12\nanswers: {gears.aw: 1}\n")
    _write(ans, "v3.yaml", "variant: 3\nanswers: {gears.aw: 1}\n")
    _write(ans, "broken.yaml", "answers: {gears.aw: 1\n")
    _write(ans, "empty.yaml", "")
    res = runner.invoke(app, ["check", str(src / "v4.yaml"), "--answers", str(ans)])
    text = " ".join(res.output.split())
    assert "2 answer set(s) of other variants (3, 12) left for their own tasks" in text, text
    assert "None" not in text
    assert text.count("warning: not read: ") == 2 and "broken.yaml:" in text and "empty.yaml:" in text
    assert "1 of 1 answers within tolerance" in text and res.exit_code == 0


def test_form_says_what_it_wrote_in_the_language(tmp_path):
    """`tmm form --lang uk`: the line of what was written, in Ukrainian with the noun in the form
    its count takes."""
    src = tmp_path / "src"
    for v in (1, 2):
        _write(src, f"v{v}.yaml", GEARS.format(v=v, z1=14, z2=30))
    res = runner.invoke(app, ["form", str(src), "--quantities", "gears", "--out", str(tmp_path / "f"), "--lang", "uk"])
    assert res.exit_code == 0, res.output
    assert f"записано 2 бланки і ключі до {tmp_path / 'f'}" in res.output


def test_the_feedback_page_gives_the_stroke_its_unit():
    """positions.H is a slider's stroke in m or a rocker's swing in degrees: the feedback page shows
    the reference with the unit its mechanism gives it (it showed a bare 0,15022)."""
    from types import SimpleNamespace

    from tmm_cli.check import AnswerSet, grade
    from tmm_cli.feedback import feedback_html
    task = SimpleNamespace(title="t", name="t")
    for kind, ref, answer, shown in (("slider", 0.15022, 0.15, "0,15022 м"), ("rocker", 45.591, 45.6, "45,591°")):
        results = {"positions": {"H": ref, "output_kind": kind}}
        rows = grade(results, AnswerSet(source="a.yaml", answers={"positions.H": answer}), {})
        assert rows[0]["unit"] == ("m" if kind == "slider" else "deg") and rows[0]["status"] == "ok"
        page = feedback_html(task, {"rows": rows, "student": "A", "group": "", "variant": 1}, "ru")
        assert shown in page, (kind, page[page.find("positions.H"):][:600])


def test_an_answers_files_unknown_keys_all_named_and_a_keys_blanks_dropped(tmp_path):
    """Every unknown top-level key of an answers file is named at its line (Cyrillic keys written for
    `student` and `variant`: both, not the first); a path written with a trailing blank is the path
    (it was an unknown path beside a missing one that looked the same)."""
    src = tmp_path / "src"
    key = gear_key(14, 30)
    _write(src, "v4.yaml", GEARS.format(v=4, z1=14, z2=30))
    bad = _write(tmp_path, "cyr.yaml", "\u0441\u0442\u0443\u0434\u0435\u043d\u0442: A\n"
                                      "\u0432\u0430\u0440\u0456\u0430\u043d\u0442: 4\nanswers: {gears.aw: 1}\n")
    res = runner.invoke(app, ["check", str(src / "v4.yaml"), "--answers", str(bad)])
    lines = [x for x in res.output.splitlines() if "unknown key" in x]
    assert [x.split(":")[1] for x in lines] == ["1", "2"] and res.exit_code == 2, res.output
    ok = _write(tmp_path, "blank.yaml", f'variant: 4\nanswers:\n  "gears.aw ": {key["gears.aw"]}\n')
    res = runner.invoke(app, ["check", str(src / "v4.yaml"), "--answers", str(ok), "--quantities", "gears.aw"])
    assert "1 of 1 answers within tolerance" in " ".join(res.output.split()) and res.exit_code == 0, res.output
    both = _write(tmp_path, "both.yaml", f'variant: 4\nanswers:\n  gears.aw: 1\n  "gears.aw ": {key["gears.aw"]}\n')
    res = runner.invoke(app, ["check", str(src / "v4.yaml"), "--answers", str(both)])
    assert "gears.aw is answered twice" in " ".join(res.output.split()) and res.exit_code == 1, res.output


def test_a_copy_flag_says_whether_the_agreement_is_in_mistakes():
    """summary.html's same_as: the answers that agree, and how many of them are wrong (shared
    mistakes are what suggests a copy; shared right results need not)."""
    from tmm_cli.copies import agreed
    from tmm_cli.summary import flag_text
    assert sorted(agreed({"a": 1.0, "b": 2.0, "c": 3.0}, {"a": 1.0, "b": 2.0000001, "d": 3.0})) == ["a"]
    assert flag_text("same_as=Anna", "en", {"Anna": (10, 3)}) == \
        "same answers as Anna (10 answers, 3 of them outside tolerance: the same mistakes)"
    assert flag_text("same_as=Anna", "en") == "same answers as Anna"
    assert flag_text("key_of=3", "ru") == "\u0432 \u0434\u043e\u043f\u0443\u0441\u043a\u0435 \u043a\u043b\u044e\u0447\u0430 \u0432\u0430\u0440\u0438\u0430\u043d\u0442\u0430 3"


def test_a_set_shows_its_tasks_variant(tmp_path):
    """A set that answers a task shows the task's variant in summary.csv and check.csv: '04' that
    matched variant 4 is 4 (it stood as 04 beside the others' 4), and a file matched by its name
    (no `variant` in it) has the variant too (check.csv left it empty)."""
    src, ans = tmp_path / "src", tmp_path / "ans"
    key = gear_key(14, 30)
    _write(src, "v4.yaml", GEARS.format(v=4, z1=14, z2=30))
    _write(ans, "a.yaml", f"variant: '04'\nstudent: {{name: A}}\nanswers: {{gears.aw: {key['gears.aw']}}}\n")
    _write(ans, "v4.yaml", f"student: {{name: B}}\nanswers: {{gears.aw: {key['gears.aw']}}}\n")
    res = runner.invoke(app, ["batch", str(src), "--answers", str(ans), "--out", str(tmp_path / "o")])
    assert res.exit_code == 0, res.output
    assert {(r["student"], r["variant"]) for r in _csv(tmp_path / "o" / "summary.csv")} == {("A", "4"), ("B", "4")}
    assert {(r["student"], r["variant"]) for r in _csv(tmp_path / "o" / "check.csv")} == {("A", "4"), ("B", "4")}
    res = runner.invoke(app, ["check", str(src / "v4.yaml"), "--answers", str(ans / "v4.yaml"), "--out", str(tmp_path / "c")])
    assert res.exit_code == 0 and [r["variant"] for r in _csv(tmp_path / "c" / "check.csv")] == ["4"], res.output


def test_swapped_strokes_are_outside_a_links_negated_angle_a_sign(tmp_path):
    """An offset press's working and idle strokes (181.98 and 178.02 deg, summing to 360)
    answered the other way round were graded "right magnitude, wrong sign": modulo 360,
    -178.02 is 181.98. A stroke's arc is a size: its negation is not taken modulo 360, and the
    swap is outside (its sign, -theta, still the wrong sign). A link's angle is a direction:
    its negation is the wrong sign, and 360 less it the same angle."""
    src = (Path(__file__).resolve().parents[1] / "tasks" / "press_offset_slider_crank.yaml").read_text(encoding="utf-8")
    res = runner.invoke(app, ["run", str(_write(tmp_path, "p.yaml", src)), "--format", "json",
                              "--out", str(tmp_path / "run")])
    assert res.exit_code == 0, res.output
    r = json.loads((tmp_path / "run" / "results.json").read_text(encoding="utf-8"))
    work, idle = r["positions"]["working_stroke_angle"], r["positions"]["idle_stroke_angle"]
    assert work + idle == pytest.approx(360.0) and abs(work - idle) > 1.0
    rod = r["kinematics"][2]["links"]["rod"]["angle"]
    answers = {"positions.working_stroke_angle": idle, "positions.idle_stroke_angle": work,
               "positions.theta": -r["positions"]["theta"],
               "kinematics[2].links.rod.angle": -rod, "kinematics[3].links.rod.angle": r["kinematics"][3]["links"]["rod"]["angle"] - 360.0}
    task = _write(tmp_path, "a.yaml", src + "answers:\n" + "".join(f"  '{p}': {v!r}\n" for p, v in answers.items()))
    tol = _write(tmp_path, "tol.yaml", "positions: {abs: 0.5}\nkinematics: {abs: 0.5}\n")
    runner.invoke(app, ["check", str(task), "--tolerance", str(tol), "--out", str(tmp_path / "o")])
    rows = {row["path"]: row["status"] for row in _csv(tmp_path / "o" / "check.csv")}
    assert rows == {"positions.working_stroke_angle": "outside", "positions.idle_stroke_angle": "outside",
                    "positions.theta": "sign", "kinematics[2].links.rod.angle": "sign",
                    "kinematics[3].links.rod.angle": "ok"}, rows


def test_the_angle_tolerance_advice_is_a_note_in_batch_as_in_check(tmp_path):
    """The advice that angles were graded with a relative tolerance was printed as `note:` by
    `tmm check` and as `warning:` by `tmm batch`: a note in both."""
    key = gear_key(14, 30)
    src = tmp_path / "src"
    task = _write(src, "v1.yaml", GEARS.format(v=1, z1=14, z2=30) + f"answers: {{gears.alpha_w: {key['gears.alpha_w']}}}\n")
    for cmd in (["batch", str(src)], ["check", str(task)]):
        res = runner.invoke(app, [*cmd, "--out", str(tmp_path / cmd[0])], env={"COLUMNS": "200"})
        lines = [ln for ln in res.output.splitlines() if "relative tolerance" in ln]
        assert len(lines) == 1 and lines[0].startswith("note: angles were graded"), (cmd[0], res.output)
