"""The terminal speaks the report's language: `tmm run --lang ru|uk` prints its progress, the
summary table (words from the catalogue, numbers with the decimal comma), the warnings, the
files written and a failure in that language, and `tmm batch --lang` its table; results.json
stays English; without --lang everything is as before (English, the decimal point)."""
from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from typer.testing import CliRunner

from tmm_cli.cli import app

runner = CliRunner()
ROOT = Path(__file__).resolve().parents[1]


def _run(tmp_path, name: str, *extra):
    out = tmp_path / f"{name}-{'-'.join(extra) or 'en'}"
    res = runner.invoke(app, ["run", str(ROOT / "tasks" / f"{name}.yaml"), "--out", str(out), "--format", "json",
                              *extra])
    assert res.exit_code == 0, res.output
    return res, out


def _rows(stdout: str) -> list[tuple[str, str]]:
    """The summary table's body rows (quantity, value) as printed."""
    return [tuple(c.strip() for c in line.strip("│").split("│")) for line in stdout.splitlines()
            if line.startswith("│")]


def _comma(value: str) -> str:
    """An English summary value written the Russian way by hand: the decimal comma, the minus
    sign U+2212, and 'x' between two numbers as '×'."""
    value = re.sub(r"(?<=\d)\.(?=\d)", ",", value)
    value = re.sub(r"(?<![\w)])-(?=\d)", "\u2212", value)
    return value.replace(" x ", " × ")


def test_run_summary_in_russian(tmp_path):
    en, _ = _run(tmp_path, "forging_sixbar")
    ru, out = _run(tmp_path, "forging_sixbar", "--lang", "ru")
    head = next(line for line in ru.stdout.splitlines() if line.startswith("┃"))
    assert "величина" in head and "значение" in head
    want = {"W = 3n - 2p5 - p4": "степень подвижности W = 3n − 2p5 − p4",
            "structure formula": "формула строения", "phi0, deg": "угол крайнего положения кривошипа φ0, град",
            "K (mean speed increase)": "K (коэффициент изменения средней скорости)",
            "least transmission angle, deg": "наименьший угол передачи, град",
            "flywheel J, kg*m^2": "момент инерции маховика J, кг·м²",
            "flywheel D x b, m": "размеры маховика D × b, м"}
    en_rows, ru_rows = _rows(en.stdout), _rows(ru.stdout)
    assert [q for q, _ in en_rows] == list(want)                # every row of this task
    for (q_en, v_en), (q_ru, v_ru) in zip(en_rows, ru_rows):
        assert q_ru == want[q_en]
        assert v_ru == (v_en.replace(" -> ", " → ") if q_en == "structure formula" else _comma(v_en)), q_en
    rows = dict(ru_rows)
    assert rows["угол крайнего положения кривошипа φ0, град"] == "6,4242"
    assert rows["размеры маховика D × b, м"] == "1,2053 × 0,12053"
    assert rows["формула строения"] == "I(0,1) → II(2,3) → II(4,5)"
    # the warning (K < 1 with working: backward) in Russian, its numbers with the comma
    text = " ".join(ru.stdout.split())
    assert "предупреждение: positions.working = backward: рабочий ход звена «slider»" in text
    assert "K = 0,78 < 1" in text and "warning:" not in text and "quick one" not in text
    assert f"записан{out / 'results.json'}" in re.sub(r"\s+", "", ru.stdout) and "wrote " not in ru.stdout
    # progress on stderr: the stages' names
    assert ru.stderr.splitlines()[:3] == ["  структурный анализ...", "  положения механизма...",
                                          "  кинематический анализ..."]
    # results.json is the same English file either way
    data = json.loads((out / "results.json").read_text(encoding="utf-8"))
    assert data["warnings"][0].startswith("positions.working = backward makes the working stroke")


def test_run_summary_in_ukrainian_and_english_unchanged(tmp_path):
    uk, _ = _run(tmp_path, "press_drive_train", "--lang", "uk")
    rows = dict(_rows(uk.stdout))
    assert rows["числа зубців ступенів приводу"] == "18/36 | 20/44 | 44/28/100"
    assert rows["передатне відношення приводу"] == "14,4"
    assert rows["формула будови"] == "I(0,1) → II(2,3)"
    assert "записано " in uk.stdout
    assert uk.stderr.splitlines()[-1] == "  зубчастий привід..."
    en, _ = _run(tmp_path, "press_drive_train")
    assert dict(_rows(en.stdout))["drive train ratio"] == "14.4"
    assert [line for line in en.stdout.splitlines() if line.startswith("┃")] == [
        "┃ quantity                      ┃                     value ┃"]
    assert en.stderr.splitlines()[-1] == "  drive_train..."


def test_lists_are_separated_by_semicolons_where_the_comma_is_decimal():
    from tmm_cli.summary import _summary_rows
    results = {"differential": {"u": -2.5, "speeds_rpm": {"1": 100.5, "satellite": -20.25}},
               "singular": [12.5, 190.25], "balancing": {"rotor": {"corrections": [{"m": 0.5}, {"m": 1.25}]}}}
    en, ru = dict(_summary_rows(results)), dict(_summary_rows(results, "ru"))
    assert en["differential speeds, rpm"] == "1: 100.5, satellite: -20.25"
    assert ru["частоты вращения звеньев дифференциала, об/мин"] == "1: 100,5; сателлит: \u221220,25"
    assert en["singular crank angles, deg"] == "12.5, 190.25"
    assert ru["особые положения кривошипа, град"] == "12,5; 190,25"
    assert ru["корректирующие массы ротора m, кг"] == "0,5; 1,25"
    assert ru["передаточное отношение при остановленном водиле u"] == "\u22122,5"


@pytest.mark.parametrize("lang", ["ru", "uk"])
def test_plain_summary_is_what_rich_prints_in_the_language(lang, monkeypatch, capsys):
    """The summary written without Rich equals Rich's in ru and uk too (Cyrillic, the
    catalogue's words in the head, the warning and file lines)."""
    from tmm_cli import load_task, run, summary
    for k in ("COLUMNS", "LINES", "FORCE_COLOR", "TTY_COMPATIBLE"):
        monkeypatch.delenv(k, raising=False)
    paths = [Path("out") / "x" / "results.json"]
    plain, real = 0, summary._plain_summary
    for name in ("forging_sixbar", "press_drive_train", "gears_zero", "cam_offset", "crank_rocker_fourbar",
                 "engine_slider_crank"):
        results = run(load_task(ROOT / "tasks" / f"{name}.yaml"))
        summary.print_summary(results, paths, lang)
        got = capsys.readouterr()
        T = summary.run_words(lang)
        words = (T["quantity"], T["value"], T["warning"], T["wrote"])
        title = f"tmm: {results['task']['title']}"
        from tmm_cli.messages import render_list
        plain += real(title, summary._summary_rows(results, lang), render_list(results, lang),
                      [str(p) for p in paths], words) is not None
        monkeypatch.setattr(summary, "_plain_summary", lambda *a: None)
        summary.print_summary(results, paths, lang)
        want = capsys.readouterr()
        monkeypatch.setattr(summary, "_plain_summary", real)
        assert got.out == want.out and T["value"] in got.out, name
    assert plain >= 2, plain             # the plain text was written and compared


def test_a_title_with_brackets_and_colons_is_printed_as_written(tmp_path):
    """Rich reads neither markup nor emoji codes in the task's title or a warning."""
    import io

    from tmm_cli import summary
    buf = io.StringIO()
    con = summary._console()            # the summary's own console (its markup and emoji settings)
    con.file, con.width = buf, 100
    orig = summary._console
    summary._console = lambda: con
    try:
        summary.print_summary({"task": {"title": "variant [b]7[/b] :smile:"},
                               "warnings": ["a [red]x[/red] y :thumbs_up:"]}, [Path("out/[a]:x:.json")])
    finally:
        summary._console = orig
    text = " ".join(buf.getvalue().split())
    assert "variant [b]7[/b] :smile:" in text and "a [red]x[/red] y :thumbs_up:" in text
    assert "wrote out/[a]:x:.json" in text


def test_batch_table_in_russian(tmp_path):
    src = tmp_path / "src"
    src.mkdir()
    for n in ("gears_zero", "cam_knife"):
        (src / f"{n}.yaml").write_text((ROOT / "tasks" / f"{n}.yaml").read_text(encoding="utf-8"), encoding="utf-8")
    (src / "bad.yaml").write_text("schema: tmm/1\ngears: {m: 4 mm, z: [14, x]}\n", encoding="utf-8")
    out = tmp_path / "b"
    res = runner.invoke(app, ["batch", str(src), "--out", str(out), "--format", "json", "--lang", "ru"])
    assert res.exit_code == 2, res.output
    text = " ".join(res.stdout.split())
    assert "tmm batch: 3 строки" in text
    assert all(w in text for w in ("студент / файл", "вар.", "статус", "балл", "сообщение"))
    flat = re.sub(r"[\s│]+", "", res.stdout)               # the cells' text, however a cell wraps
    assert "рассчитано" in text and "ошибка в данных" in text and "ожидаетсяцелоечисло" in flat
    assert "computed" not in text and "invalid" not in text and "Inputshouldbe" not in flat
    assert f"записаны{out / 'summary.csv'},summary.htmlиcheck.csv" in re.sub(r"\s+", "", res.stdout)
    en = runner.invoke(app, ["batch", str(src), "--out", str(tmp_path / "e"), "--format", "json"])
    text = " ".join(en.stdout.split())
    assert "tmm batch: 3 rows" in text and "computed" in text and "Inputshouldbe" in re.sub(r"[\s│]+", "", en.stdout)


def test_batch_names_every_row_whole_and_says_computed_once(tmp_path, monkeypatch):
    """The batch table at 80 columns: a file name whole where the room allows (the longest of
    the examples, 34 characters, folded rather than every message wrapped: the fewest lines), no
    line past the terminal's width in en or ru, a variant without answers 'computed' with the
    message 'no answers to check' (not 'computed' twice); summary.html names an unsigned
    variant by its task file, as the terminal does."""
    import io

    from rich.console import Console

    from tmm_cli import summary
    rows = [{"file": f"/x/{n}.yaml", "status": "ok", "variant": 3, "message": "no answers to check",
             "folder": n} for n in ("crank_rocker_fourbar", "synthesis_offset_slider_crank", "cam_flat")]
    for lang in ("en", "ru"):
        buf = io.StringIO()
        monkeypatch.setattr(summary, "_console", lambda: Console(file=buf, width=80, emoji=False, highlight=False))
        summary.print_batch(rows, tmp_path, lang=lang)
        lines = buf.getvalue().splitlines()
        assert lines and max(len(ln) for ln in lines) <= 80, lines
        table = [ln for ln in lines if ln.startswith("│")]
        if lang == "en":          # the long name in two lines, every message in one: 4 lines, not 6
            assert len(table) == 4, lines
            assert any("│ crank_rocker_fourbar.yaml " in ln for ln in table)
            assert any("│ synthesis_offset_slider_cran" in ln for ln in table)
            assert sum(ln.count("computed") == 1 and "no answers to check" in ln for ln in table) == 3
    html = summary.summary_html(rows, [], "x")
    assert "<td>crank_rocker_fourbar.yaml</td>" in html and "<th>student / file</th>" in html
    assert "<td>Ivanov</td>" in summary.summary_html([dict(rows[0], student="Ivanov")], [], "x")
    assert "<th>студент / файл</th>" in summary.summary_html(rows, [], "x", lang="ru")


def test_two_rows_that_would_read_alike_name_their_files():
    """One student's two submissions of a variant (or two copies of a starter signed with its
    placeholder name) are told apart by their files' names, in the terminal and summary.html;
    a name met once stays alone, and the same student's other variants too."""
    from tmm_cli import summary
    rows = [{"student": "Petrov P.", "variant": 1, "file": "/g/petrov_v1.yaml", "status": "ok"},
            {"student": "Petrov P.", "variant": 1, "file": "/g/petrov_v1_new.yaml", "status": "ok"},
            {"student": "Petrov P.", "variant": 2, "file": "/g/petrov_v2.yaml", "status": "ok"},
            {"variant": 3, "file": "/g/anon.yaml", "status": "ok"}]
    assert summary.row_names(rows) == ["Petrov P. (petrov_v1.yaml)", "Petrov P. (petrov_v1_new.yaml)",
                                       "Petrov P.", "anon.yaml"]
    html = summary.summary_html(rows, [], "g")
    assert "<td>Petrov P. (petrov_v1_new.yaml)</td>" in html and "<td>Petrov P.</td>" in html
    two = [{"student": "Petrov P.", "variant": 1, "file": f"/{d}/task.yaml", "status": "ok"} for d in ("a", "b")]
    assert summary.row_names(two) == ["Petrov P. (a/task.yaml)", "Petrov P. (b/task.yaml)"]


def test_the_batch_table_splits_its_room_for_the_fewest_lines():
    """Worked by hand: 33 names of 10 characters and one of 34, each message 'no answers to
    check' (19), 47 columns of room. A name column of 34 leaves the messages 13: each wraps
    ('no answers to' / 'check'), 34 rows x 2 = 68 lines. Of 28 the long name folds to 2 lines
    and every message fits: 33 + 2 = 35 lines, the fewest (any width from 17 to 28 gives 35;
    the widest wins the tie). Both fitting: each column its longest cell."""
    from tmm_cli.summary import _split_width
    names = ["b" * 10] * 33 + ["a" * 34]
    msgs = ["no answers to check"] * 34
    assert _split_width(47, names, msgs) == (28, 19)
    assert _split_width(60, names, msgs) == (34, 19)
    assert _split_width(47, ["b" * 10], ["no answers to check"]) == (10, 19)


def test_an_invalid_task_in_the_language(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("schema: tmm/1\ngears: {m: 4 mm, z: [14, x]}\n", encoding="utf-8")
    res = runner.invoke(app, ["run", str(bad), "--out", str(tmp_path / "o"), "--lang", "uk"])
    assert res.exit_code == 2
    assert res.stderr.splitlines()[:2] == [
        "Помилки у файлі завдання:",
        f"{bad}:2:26: поле «gears.z[1]»: очікується ціле число, а записано текст"]
    en = runner.invoke(app, ["run", str(bad), "--out", str(tmp_path / "o")])
    assert en.stderr.splitlines()[:2] == [
        "error: invalid task",
        f"{bad}:2:26: field 'gears.z[1]': Input should be a valid integer, unable to parse string as an integer"]


def test_two_degree_of_freedom_machine_has_its_summary_rows():
    """A dof2 task (the rotary impact mechanism) printed an empty table: now the state at the hit
    (v_M, the striker's energy), the largest v_M, |R01| and driving moment and the energy balance.
    The hit's numbers checked by hand from the hit's angles and speeds: v_M = |v_O1 + omega2 x O1M|,
    T2 = m2 v_C^2 / 2 + J_C omega2^2 / 2 with v_C = v_O1 + omega2 x O1C."""
    import math

    from tmm_cli import load_task, run
    from tmm_cli.summary import _summary_rows
    r = run(load_task(ROOT / "tasks" / "impact_rotor.yaml"))
    d, p = r["dof2"], r["dof2"]["parameters"]
    hit = d["impact"]
    phi, th2 = math.radians(hit["phi"]), math.radians(hit["theta2"])
    w1, w2 = hit["omega"], hit["omega2"]
    vo1 = (-p["l"] * w1 * math.sin(phi), p["l"] * w1 * math.cos(phi))

    def v_at(dist):
        return math.hypot(vo1[0] - dist * w2 * math.sin(th2), vo1[1] + dist * w2 * math.cos(th2))
    vM, vC = v_at(p["l_M"]), v_at(p["l_c"])
    T2 = 0.5 * p["m2"] * vC ** 2 + 0.5 * p["J_C"] * w2 ** 2
    rows = dict(_summary_rows(r))
    assert rows["striker speed v_M at the hit, m/s"] == f"{vM:.5g}"
    assert rows["striker energy at the hit, J"] == f"{T2:.5g}"
    # the largest values over the samples, by hand from each sample's angles, speeds and accelerations
    # (no gravity; the rotor balanced and turning at a constant speed): v_M as at the hit; the
    # striker's only force acts at O1, R = m2 a_C, a_C = a_O1 + eps2 x O1C - omega2^2 O1C; the
    # rotor's moment balance about O: M_d = r_O1 x R
    assert p["g"] == 0 and p["s1"] == 0 and p["drive"] == "speed"
    vMs, Rs, Mds = [], [], []
    for ph, t2, w, w2, e2 in zip(d["phi"], d["theta2"], d["omega"], d["omega2"], d["epsilon2"]):
        ph, t2 = math.radians(ph), math.radians(t2)
        vo = (-p["l"] * w * math.sin(ph), p["l"] * w * math.cos(ph))
        vMs.append(math.hypot(vo[0] - p["l_M"] * w2 * math.sin(t2), vo[1] + p["l_M"] * w2 * math.cos(t2)))
        c, s_ = p["l_c"] * math.cos(t2), p["l_c"] * math.sin(t2)
        ax = -p["l"] * w * w * math.cos(ph) - e2 * s_ - w2 * w2 * c
        ay = -p["l"] * w * w * math.sin(ph) + e2 * c - w2 * w2 * s_
        Rs.append(p["m2"] * math.hypot(ax, ay))
        Mds.append(p["l"] * (math.cos(ph) * p["m2"] * ay - math.sin(ph) * p["m2"] * ax))
    assert float(rows["largest v_M, m/s"]) == pytest.approx(max(vMs), rel=1e-4)
    assert float(rows["largest |R01|, N"]) == pytest.approx(max(Rs), rel=1e-4)
    assert float(rows["largest driving moment, N*m"]) == pytest.approx(max(Mds), rel=1e-4)
    assert float(rows["energy balance, relative error"]) < 1e-8
    ru = dict(_summary_rows(r, "ru"))
    assert ru["скорость точки M ударника в момент удара, м/с"] == f"{vM:.5g}".replace(".", ",")


@pytest.mark.parametrize("lang, wrote", [("en", "wrote"), ("ru", "записан")])
def test_a_failed_stage_still_lists_the_files_written(tmp_path, lang, wrote):
    """A linkage that does not assemble over part of the turn fails its kinematics (exit 3), yet
    results.json and the report are written with the other sections and the failure in place:
    the terminal says so, as after a run that succeeds (stdout; not with --quiet)."""
    task = tmp_path / "t.yaml"
    task.write_text("schema: tmm/1\nmechanism:\n  ground: {O: [0, 0]}\n  links:\n"
                    "    crank: {points: [O, A], length: 0.1}\n    rod: {points: [A, B], length: 0.05}\n"
                    "    slider: {slider: B, guide: {through: O, angle: 0}}\n"
                    "drive: {link: crank, speed: 10 rad/s}\n" + "gears: {m: 4 mm, z: [14, 30], x: [0, 0]}\n",
                    encoding="utf-8")
    out = tmp_path / "o"
    res = runner.invoke(app, ["run", str(task), "--out", str(out), "--format", "json,html", "--lang", lang])
    assert res.exit_code == 3
    listed = [line.split(" ", 1)[1] for line in res.stdout.splitlines() if line.startswith(wrote + " ")]
    assert listed[0] == str(out / "results.json") and str(out / "report.html") in listed
    # every file of the folder, and only those (the gears' drawings and tables among them)
    assert sorted(listed) == sorted(str(p) for p in out.rglob("*") if p.is_file())
    assert "gears" in json.loads((out / "results.json").read_text(encoding="utf-8"))
    quiet = runner.invoke(app, ["run", str(task), "--out", str(out), "--format", "json", "--lang", lang, "-q"])
    assert quiet.exit_code == 3 and quiet.stdout == ""


def test_check_table_in_russian(tmp_path):
    """`tmm check --lang ru`: the heads, the statuses and the count in Russian, the numbers with the
    decimal comma (each cell the English one written the Russian way), the note on an unknown
    path rendered from its code; check.csv stays English."""
    ans = tmp_path / "ans.yaml"
    ans.write_text("answers:\n  flywheel.J: 180\n  positions.K: 0,78\n  positions.phi0: 7\n"
                   "  kinematics[3].links.zz.omega: 1\n", encoding="utf-8")
    task = str(ROOT / "tasks" / "forging_sixbar.yaml")
    en = runner.invoke(app, ["check", task, "--answers", str(ans)])
    ru = runner.invoke(app, ["check", task, "--answers", str(ans), "--lang", "ru", "--out", str(tmp_path / "o")])
    assert en.exit_code == ru.exit_code == 1
    head = next(line for line in ru.stdout.splitlines() if line.startswith("┃"))
    assert [c.strip() for c in head.strip("┃").split("┃")] == ["величина", "ответ", "эталон", "погр.", "допуск",
                                                              "статус"]
    en_rows, ru_rows = _rows(en.stdout), _rows(ru.stdout)
    assert len(en_rows) == len(ru_rows) == 4
    words = {"ok": "верно", "outside": "вне допуска", "unknown_path": "неизвестная величина"}
    for e, r in zip(en_rows, ru_rows):
        assert r[0] == e[0] and list(r[1:5]) == [_comma(c) for c in e[1:5]] and r[5] == words[e[5]], (e, r)
    assert ru_rows[0][1:3] == ("180", "179,83")
    text = " ".join(ru.stdout.split())
    # the misspelt path answers no quantity: 3 answers, as summary.csv counts them
    assert "в допуске 2 из 3 ответов; вне допуска: 1; неизвестная величина: 1" in text
    assert "путь не найден (kinematics[3].links.zz.omega: нет ключа «zz»)" in text
    assert "2 of 3 answers within tolerance, 1 outside, 1 unknown_path" in " ".join(en.stdout.split())
    csv = (tmp_path / "o" / "check.csv").read_text(encoding="utf-8")
    assert "outside" in csv and "вне допуска" not in csv


def test_check_names_an_invalid_answers_file_in_the_language(tmp_path):
    """A folder of answers with one file whose path cannot be read: that file named as an
    error (exit 2), the others graded; with --lang ru the error line is Russian too (its
    coded message through the catalogue), without --lang the English line as before."""
    folder = tmp_path / "answers"
    folder.mkdir()
    (folder / "a.yaml").write_text('variant: 7\nstudent: {name: Ivanov}\nanswers:\n  "flywheel..J": 180\n',
                                   encoding="utf-8")
    (folder / "b.yaml").write_text("variant: 7\nstudent: {name: Petrov}\nanswers:\n  flywheel.J: 180\n",
                                   encoding="utf-8")
    task = str(ROOT / "tasks" / "forging_sixbar.yaml")
    en = runner.invoke(app, ["check", task, "--answers", str(folder)])
    ru = runner.invoke(app, ["check", task, "--answers", str(folder), "--lang", "ru"])
    assert en.exit_code == ru.exit_code == 2
    where = f"{folder / 'a.yaml'}:4:3: "
    assert f"error: {where}field 'answers.flywheel..J': bad path 'flywheel..J' near '..'" in en.stderr.splitlines()
    (line,) = [x for x in ru.stderr.splitlines() if where in x]
    assert line.startswith(f"ошибка: {where}поле «answers.flywheel..J»: ") and "bad path" not in line, line
    assert "в допуске 1 из 1 ответа" in ru.stdout


def test_a_long_batch_message_is_cut_with_a_mark():
    """The batch table shows a row's message to 200 characters: 199 and an ellipsis where it is
    longer, in every language (English was once cut mid-word without a mark)."""
    from tmm_cli.summary import _cut
    text = "x" * 150 + "y" * 100
    assert _cut(text, 200) == "x" * 150 + "y" * 49 + "\u2026"
    assert _cut("short", 200) == "short"


def test_check_notes_and_an_invalid_answers_file_in_the_language(tmp_path):
    """`tmm check --lang`: the note on answer sets of other variants (a folder of the group's
    answers), and an answers file that is none, headed and said in the language; English as before."""
    folder = tmp_path / "answers"
    folder.mkdir()
    (folder / "a.yaml").write_text("variant: 2\nanswers:\n  positions.K: 1\n", encoding="utf-8")
    (folder / "b.yaml").write_text("variant: 5\nanswers:\n  positions.K: 1\n", encoding="utf-8")
    task = str(ROOT / "tasks" / "synthesis_slider_crank.yaml")          # variant 2
    ru = runner.invoke(app, ["check", task, "--answers", str(folder), "--lang", "ru"])
    assert "примечание: наборов ответов других вариантов: 1 (5); они оставлены для своих заданий" in ru.stderr
    en = runner.invoke(app, ["check", task, "--answers", str(folder)])
    assert "note: 1 answer set(s) of other variants (5) left for their own tasks" in en.stderr
    bad = tmp_path / "bad.yaml"
    bad.write_text("foo: 1\n", encoding="utf-8")
    uk = runner.invoke(app, ["check", task, "--answers", str(bad), "--lang", "uk"])
    assert uk.exit_code == 2 and uk.stderr.splitlines()[0] == "Помилки у файлі відповідей:"
    assert "не файл відповідей" in uk.stderr and "not an answers file" not in uk.stderr
    en = runner.invoke(app, ["check", task, "--answers", str(bad)])
    assert en.stderr.splitlines()[:2] == [
        "error: invalid answers file",
        f"{bad}: not an answers file (a YAML file with an `answers:` mapping of result paths to values)"]


def test_validate_in_the_language(tmp_path):
    """`tmm validate --lang ru|uk`: an invalid task's errors and a valid one that cannot be
    computed (a linkage that does not assemble over part of the turn) in the language;
    'FILE: ok' as ever; without --lang English as before."""
    bad = tmp_path / "bad.yaml"
    bad.write_text("schema: tmm/1\ngears: {m: 4 mm, z: [14, x]}\n", encoding="utf-8")
    part = tmp_path / "part.yaml"
    part.write_text("schema: tmm/1\nmechanism:\n  ground: {O: [0, 0], C: [0.5, 0]}\n  links:\n"
                    "    crank: {points: [O, A], length: 0.2}\n    rod: {points: [A, B], length: 0.4}\n"
                    "    rocker: {points: [B, C], length: 0.15}\n  assembly: {B: [0.3, 0.1]}\n"
                    "drive: {link: crank, speed: 100 rpm}\n", encoding="utf-8")
    good = str(ROOT / "tasks" / "cam_knife.yaml")
    ru = runner.invoke(app, ["validate", str(bad), str(part), good, "--lang", "ru"])
    assert ru.exit_code == 3 and ru.stdout == f"{good}: ok\n"
    err = ru.stderr.splitlines()
    assert err[:2] == ["Ошибки в файле задания:",
                       f"{bad}:2:26: поле «gears.z[1]»: ожидается целое число, а записан текст"]
    assert err[2].startswith(f"ошибка: {part}: Этап «кинематический анализ» не выполнен при угле кривошипа φ = ")
    assert "не собирается при углах кривошипа φ = 93,6…266,4°" in err[2]
    en = runner.invoke(app, ["validate", str(bad), str(part), good])
    assert en.stderr.splitlines()[0] == "error: invalid task"
    assert en.stderr.splitlines()[2].startswith(f"error: {part}: stage 'kinematics' failed at crank angle ")


def test_a_synthesis_prints_the_generated_lengths_and_the_least_transmission_angle(tmp_path):
    """A synthesis task's answer is the mechanism it generates: its lengths in the summary, and the
    least transmission angle of its dyads, here a crank-rocker's by the cosine rule with the crank
    along the frame line (cos mu = (b^2 + c^2 - (d -+ a)^2) / 2bc, the acute angle of the two)."""
    import math

    from tmm_cli import load_task, run
    from tmm_cli.summary import _summary_rows
    r = run(load_task(ROOT / "tasks" / "synthesis_crank_rocker.yaml"))
    L = r["synthesis"]["lengths"]
    rows = dict(_summary_rows(r))
    for name in ("crank", "coupler", "rocker", "frame"):
        assert rows[f"synthesis: {name}, m"] == f"{L[name]:.5g}"
    a, b, c, d = L["crank"], L["coupler"], L["rocker"], L["frame"]
    mus = [math.degrees(math.acos((b * b + c * c - q * q) / (2 * b * c))) for q in (d - a, d + a)]
    want = min(min(m, 180.0 - m) for m in mus)
    assert rows["least transmission angle, deg"] == f"{want:.5g} (II(2,3))"
    ru = dict(_summary_rows(r, "ru"))
    assert ru["синтез: coupler, м"] == f"{L['coupler']:.5g}".replace(".", ",")
    assert ru["наименьший угол передачи, град"] == f"{want:.5g} (II(2,3))".replace(".", ",")


def test_a_missing_or_non_utf8_file_and_a_task_without_answers_in_the_language(tmp_path):
    """The file-level errors a student meets first (a file not there, one saved from Notepad in
    cp1251, `tmm check` of a task with no answers) in the language of --lang, as English
    without it."""
    bad = tmp_path / "cp1251.yaml"
    bad.write_bytes("schema: tmm/1\ntitle: Четырёхзвенник\n".encode("cp1251"))
    res = runner.invoke(app, ["validate", str(bad), str(tmp_path / "nofile.yaml"), "--lang", "ru"])
    assert res.exit_code == 2
    text = res.output
    assert "cp1251.yaml:2: это не текстовый файл в кодировке UTF-8 (" in text and "сохраните его в UTF-8" in text
    assert "nofile.yaml: файл не найден" in text and "not found" not in text
    en = runner.invoke(app, ["validate", str(bad), str(tmp_path / "nofile.yaml")]).output
    assert "cp1251.yaml:2: not a UTF-8 text file (invalid continuation byte at byte" in en
    assert "nofile.yaml: file not found" in en
    task = tmp_path / "t.yaml"
    task.write_text((ROOT / "tasks" / "gears_zero.yaml").read_text(encoding="utf-8"), encoding="utf-8")
    uk = runner.invoke(app, ["check", str(task), "--lang", "uk"])
    assert uk.exit_code == 2 and "відповідей для перевірки немає: додайте розділ `answers:`" in uk.output


def test_short_names_leave_the_message_the_room():
    """Names of 7 characters or fewer (a student 'Ivanov' under the 7-letter header 'student')
    beside messages longer than the room: the name column is the longest name, the message the
    rest (it had half the room each: the split's search began below the name's width, found
    nothing, and fell back to halves, every message wrapped at 23 columns instead of 38)."""
    from tmm_cli.summary import _split_width
    assert _split_width(45, ["Ivanov", "Petrov"], ["word " * 40] * 2, 7, 7) == (7, 38)
    assert _split_width(45, ["Ivanov"], ["word " * 40], 6, 7) == (6, 39)


@pytest.mark.parametrize("lang", ["ru", "uk"])
def test_checks_notes_are_said_in_the_language(lang, capsys, monkeypatch):
    """A wrong sign's note (and the other notes grade writes) is coded: `tmm check --lang` says it
    in the language, check.csv keeps its English text."""
    from tmm_cli import summary
    from tmm_cli.check import grade
    from tmm_cli.check import AnswerSet
    from tmm_cli.messages import localize
    monkeypatch.setenv("COLUMNS", "120")
    results = {"kinematics": [{"index": 1, "phi": 30.0, "points": {}, "links": {"rod": {"omega": -2.5}}}]}
    aset = AnswerSet(source="a.yaml", answers={"kinematics[1].links.rod.omega": 2.5, "kinematics[1].links.rod.x": None})
    rows = grade(results, aset, {})
    sign = next(r for r in rows if r["status"] == "sign")
    assert sign["note"] == "right magnitude, wrong sign" and sign["note"].code == "answers.note_sign"
    summary.print_check(rows, "a.yaml", lang)
    out = capsys.readouterr().out
    assert localize(sign["note"].to_dict(), lang) in out and "wrong sign" not in out


def test_an_invalid_answer_is_shown_as_written(capsys, monkeypatch):
    """`tmm check --lang ru` shows an answer that is not a number as the student wrote it: its
    points are not turned into decimal commas ('11.644,6' is not shown as '11,644,6')."""
    from tmm_cli import summary
    from tmm_cli.check import AnswerSet, grade
    monkeypatch.setenv("COLUMNS", "120")
    results = {"flywheel": {"J": 11644.6}}
    aset = AnswerSet(source="a.yaml")
    aset.invalid["flywheel.J"] = ("11.644,6", "x")
    aset.answers["flywheel.J"] = None
    rows = grade(results, aset, {})
    assert rows[0]["status"] == "invalid"
    summary.print_check(rows, "a.yaml", "ru")
    out = capsys.readouterr().out
    assert "11.644,6" in out and "11,644,6" not in out and "11645" in out
