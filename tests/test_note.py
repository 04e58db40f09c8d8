"""The explanatory note (`--format note`): the title page's fields, the ЕСКД frame where the
standard puts it, the title block's designation and page number on every page after the
title page, nothing outside the frame, the conclusions from the results, the references."""
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
MM = 72 / 25.4
pytestmark = pytest.mark.skipif(shutil.which("pdftotext") is None, reason="pdftotext (poppler-utils) is missing")

HEADER = """student: {name: "Іваненко П. С.", group: "МТ-31"}
course: {university: "Національний технічний університет", department: "Кафедра теорії механізмів",
         supervisor: "Петренко О. В.", city: "Харків", year: 2026, designation: "ТММ.КП.07.00.00 ПЗ"}
"""


@pytest.fixture(scope="module")
def note(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("note")
    task = tmp / "engine.yaml"
    task.write_text((ROOT / "tasks" / "engine_slider_crank.yaml").read_text(encoding="utf-8") + HEADER,
                    encoding="utf-8")
    p = subprocess.run([sys.executable, "-m", "tmm_cli", "run", str(task), "--out", str(tmp / "out"),
                        "--format", "json,note", "--lang", "uk"], capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stderr
    assert not (tmp / "out" / "report.pdf").exists() and not (tmp / "out" / "report.html").exists()
    return tmp / "out" / "note.pdf"


def _pages(pdf: Path) -> list[list[tuple[float, float, float, float, str]]]:
    """Every page's words as (x0, y0, x1, y1, word) in pt from the top left."""
    xml = subprocess.run(["pdftotext", "-bbox", str(pdf), "-"], capture_output=True, text=True, check=True).stdout
    pages = []
    for page in xml.split("<page ")[1:]:
        words = [(float(a), float(b), float(c), float(d), w) for a, b, c, d, w in
                 re.findall(r'<word xMin="([\d.]+)" yMin="([\d.]+)" xMax="([\d.]+)" yMax="([\d.]+)">([^<]*)</word>',
                            page)]
        pages.append(words)
    return pages


def test_title_page_fields(note):
    words = " ".join(w for *_, w in _pages(note)[0])
    for text in ("ПОЯСНЮВАЛЬНА ЗАПИСКА", "Національний технічний університет", "Кафедра теорії механізмів",
                 "Іваненко П. С.", "МТ-31", "Петренко О. В.", "Харків 2026", "ТММ.КП.07.00.00 ПЗ",
                 "Four-stroke engine, central slider-crank"):
        assert text in words, text


def test_every_page_after_the_title_has_its_block(note):
    pages = _pages(note)
    assert len(pages) > 10
    for k, words in enumerate(pages[1:], start=2):
        block_top = (297 - 5 - (40 if k == 2 else 15)) * MM
        inside = [w for x0, y0, x1, y1, w in words if y0 >= block_top - 0.5]
        text = " ".join(inside)
        assert "ТММ.КП.07.00.00" in text, (k, text)
        assert re.search(rf"(^|\s){k}(\s|$)", text), (k, text)            # the page number in the block
        # nothing outside the frame, and the text clear of the block
        for x0, y0, x1, y1, w in words:
            assert 20 * MM - 0.5 <= x0 and x1 <= (210 - 5) * MM + 0.5, (k, w, x0, x1)
            assert 5 * MM - 0.5 <= y0 and y1 <= (297 - 5) * MM + 0.5, (k, w, y0, y1)
            assert y1 <= block_top + 0.5 or y0 >= block_top - 0.5, (k, w, y0, y1)


def test_the_frame_is_where_the_standard_puts_it(note, tmp_path):
    """Page 3 rendered at 1 px = 1 pt: the frame's left line 20 mm from the left edge, its top
    line 5 mm from the top, the right line 5 mm from the right edge."""
    from PIL import Image
    subprocess.run(["pdftoppm", "-png", "-r", "72", "-f", "3", "-l", "3", "-singlefile", str(note),
                    str(tmp_path / "p3")], check=True)
    im = Image.open(tmp_path / "p3.png").convert("L")
    w, h = im.size
    px = im.load()

    def dark_column(x):
        return sum(px[x, y] < 128 for y in range(h)) > 0.8 * h

    def dark_row(y):
        return sum(px[x, y] < 128 for x in range(w)) > 0.75 * w
    cols = [x for x in range(w) if dark_column(x)]
    rows = [y for y in range(h) if dark_row(y)]
    assert any(abs(x - 20 * MM) <= 1.5 for x in cols), cols
    assert any(abs(x - (210 - 5) * MM) <= 1.5 for x in cols), cols
    assert any(abs(y - 5 * MM) <= 1.5 for y in rows), rows


def test_contents_conclusions_and_references(note):
    text = subprocess.run(["pdftotext", str(note), "-"], capture_output=True, text=True, check=True).stdout
    assert "Зміст" in text and "Вступ" in text and "Висновки" in text and "Список літератури" in text
    assert "Артоболевский И. И." in text and "Таблиця 1.1" in text and "Рисунок 2.1" in text
    # the worked formulas numbered by section, in order: (k.1), (k.2), ...
    nums = re.findall(r"\((\d+)\.(\d+)\)", text)
    worked = sorted(int(b) for a, b in nums if a == nums[0][0])     # (text order: a tall line's number may trail)
    assert len(worked) >= 5 and worked == list(range(1, len(worked) + 1))
    import json
    res = json.loads((note.parent / "results.json").read_text())
    J = res["flywheel"]["J"]
    assert f"J = {J:.4g}".replace(".", ",") + " кг·м²" in text.replace("\n", " ")
    # the conclusions as typeset text: subscripts set (no raw a_w, ε_α, M_зр), the structure's
    # arrow, and no colophon of the report (it was printed over the last page's title block)
    start = text.rindex("Висновки")
    concl = text[start:text.index("Список літератури", start)]
    assert "_" not in concl and "->" not in concl and "→" in concl, concl
    assert "ступенів рухомості механізму W = 1" in concl.replace("\n", " ")
    assert "Розрахунок виконано програмою tmm" not in text
    assert ".csv" not in text                  # 'All numbers: kinematics.csv': no folder beside a note


def test_the_note_leaves_out_the_reports_files_and_warnings():
    """The report tells its reader the files beside it and warns its user (the task file's keys,
    what to write there): neither belongs in a text the student hands in."""
    from tmm_cli.report.note import _strip_head
    html = ('<section class="section" id="kinematics"><p class="note">Plans. <span class="files">All numbers: '
            'kinematics.csv.</span></p><p class="note files">All arrays: flywheel.csv.</p><p class="files">Tables: '
            '<code>cam_profile.csv</code></p><p>kept</p></section>\n<section class="section" id="warnings"><h2>Warnings'
            '</h2><ul><li>positions.working = backward</li></ul></section>\n<section id="x">after</section>')
    out = _strip_head(html)
    assert ".csv" not in out and "Warnings" not in out and "working" not in out
    assert '<p class="note">Plans.</p>' in out and "<p>kept</p>" in out and "after" in out


def test_sheets_title_blocks_take_the_course_header(tmp_path):
    """The A1 sheets' title blocks: the supervisor in the row 'checked', the designation (less its
    'ПЗ') with the sheet's number as the code, the university beside the group."""
    import tmm_cli
    from tmm_cli.sheets import build_sheets
    task_file = tmp_path / "engine.yaml"
    task_file.write_text((ROOT / "tasks" / "engine_slider_crank.yaml").read_text(encoding="utf-8") + HEADER,
                         encoding="utf-8")
    task = tmm_cli.load_task(task_file)
    sheets = build_sheets(tmm_cli.run(task), task, "uk")
    assert sheets
    for n, (_, info) in enumerate(sheets, start=1):
        tb = info["title_block"]
        assert tb["code"] == f"ТММ.КП.07.00.00.{n:02d}"
        assert tb["supervisor"] == "Петренко О. В." and tb["student"] == "Іваненко П. С."
        assert tb["organisation"] == "Національний технічний університет, МТ-31"


def test_every_figure_has_a_numbered_caption_with_a_title(note):
    """GOST 2.105: "Рисунок <section>.<n> — <title>" under every figure, numbered 1, 2, ... in each
    section; the figures the report leaves bare (a position's drawings) take their heading."""
    text = subprocess.run(["pdftotext", str(note), "-"], capture_output=True, text=True, check=True).stdout
    caps = re.findall(r"^Рисунок (\d+)\.(\d+)(.*)$", text, re.M)
    assert len(caps) >= 10
    for sec, n, rest in caps:
        assert rest.startswith(" — ") and len(rest.strip(" —")) > 3, (sec, n, rest)
    by_section: dict[str, list[int]] = {}
    for sec, n, _ in caps:
        by_section.setdefault(sec, []).append(int(n))
    for sec, ns in by_section.items():
        assert ns == list(range(1, len(ns) + 1)), (sec, ns)
    assert any("Положення 0, φ = " in rest for *_, rest in caps)


def test_bare_figures_take_the_heading_they_stand_under():
    from tmm_cli.report.note import _caption_bare_figures
    html = ('<h3>A</h3><figure class="fig"><svg/></figure>'
            '<h4>Position 1, φ = 30°</h4><figure class="fig"><svg/></figure>'
            '<figure class="fig"><svg/><figcaption>own</figcaption></figure>')
    out = _caption_bare_figures(html)
    assert out.count("<figcaption>") == 3
    assert '<svg/><figcaption>A</figcaption></figure>' in out
    assert '<svg/><figcaption>Position 1, φ = 30°</figcaption></figure>' in out
    assert out.endswith('<figcaption>own</figcaption></figure>')


def test_a_signers_name_fits_its_cell_of_form_2():
    """The note's title block (form 2), 'developed' and 'checked' rows (23 mm at 6 pt): a name
    that does not fit on one line (in type down to 5.1 pt) is written as the surname and initials, a
    surname longer than the cell in smaller type -- a full Russian name wrapped over the row below.
    The width is DejaVu Sans's advance of each letter (the note's font), measured by matplotlib."""
    from matplotlib.font_manager import FontProperties
    from matplotlib.textpath import TextPath

    from tmm_cli.report.note import _signer

    def width_mm(text: str, pt: float) -> float:
        path = TextPath((0, 0), text, size=pt, prop=FontProperties(family="DejaVu Sans"))
        return (path.get_extents().x1 - path.get_extents().x0) * 25.4 / 72
    assert _signer("Ivanov I. I.") == 'cell("Ivanov I. I.", size: 6pt)'
    for name, shown in (("\u0418\u0432\u0430\u043d\u043e\u0432 \u0418\u0432\u0430\u043d \u0418\u0432\u0430\u043d\u043e\u0432\u0438\u0447",
                         "\u0418\u0432\u0430\u043d\u043e\u0432 \u0418. \u0418."),
                        ("Konstantinopolsky-Starodubtsev Alexander Vladimirovich", "Konstantinopolsky-Starodubtsev")):
        m = re.fullmatch(r'cell\("(.*)", size: ([\d.]+)pt\)', _signer(name))
        assert m and m.group(1) == shown, _signer(name)
        assert width_mm(shown, float(m.group(2))) <= 23.0, (shown, m.group(2))


def test_the_conclusions_name_a_drive_trains_ratio_and_round_off_deviations():
    """A press driven through two pairs and a planetary stage had no word of its gear drive in
    the conclusions; a ratio met exactly read 'deviation -1.23e-14 %'. Worked here: 36/18 x 44/20 x
    (1 + 100/44) = 2 x 2.2 x 3.2727 = 14.4."""
    from tmm_cli.report.note import conclusions
    u = (36 / 18) * (44 / 20) * (1 + 100 / 44)
    res = {"drive_train": {"ratio": u, "ratio_error": -1.23e-16, "stages": [{"z": [18, 36]}, {"z": [20, 44]},
                                                                            {"z": [44, 28, 100]}],
                           "motor_power": 950.71, "motor_power_computed": True},
           "planetary": {"scheme": "A", "z": {"z1": 44, "z2": 28, "z3": 100}, "ratio": 1 + 100 / 44,
                         "ratio_error": 3e-17}}
    text = " ".join(conclusions(res, "en"))
    assert "stages 18/36, 20/44, 44/28/100" in text and "U = 14.4 (0 % from the required)" in text, text
    assert "the motor's power 950.7 W" in text and "e-1" not in text and "10⁻" not in text
    ru = " ".join(conclusions(res, "ru"))
    assert "18/36; 20/44; 44/28/100" in ru and "U = 14,4" in ru and "0 %" in ru


def test_balancings_applied_counterweights_say_what_took_them(tmp_path):
    """'the kinetostatics and the flywheel take the links with the counterweights' of a task with
    no flywheel: now what the task computes."""
    import tmm_cli
    from tmm_cli.report import render_html
    task = tmm_cli.load_task(ROOT / "tasks" / "balancing_fourbar.yaml")
    res = tmm_cli.run(task, kinematics_curve=0, explore=False)
    assert res.get("kinetostatics") and not res.get("flywheel") and res["balancing"].get("applied")
    html = render_html(res, task, tmp_path, "en")[0]
    i = html.index("The counterweights are applied")
    assert html[i:].startswith("The counterweights are applied: the kinetostatics takes the links with them"), html[i:i + 120]


def test_bare_tables_take_the_heading_they_stand_under():
    """GOST 2.105 titles every table ('Table 4.1 - ...'); the report left many under a heading
    that names them without a caption, and the note numbered only the captioned ones."""
    from tmm_cli.report.note import _caption_bare_tables
    html = ('<h3>Scales</h3><table class="info"><tr><td>1</td></tr></table>'
            '<table><caption>Own</caption><tr><td>2</td></tr></table>'
            '<h4>Gear <i>pair</i></h4><table class="data"><tr><td>3</td></tr></table>')
    out = _caption_bare_tables(html)
    assert out.count("<caption>") == 3
    assert '<table class="info"><caption>Scales</caption>' in out and "<caption>Own</caption>" in out
    assert '<table class="data"><caption>Gear pair</caption>' in out
    assert _caption_bare_tables("<table><tr><td>0</td></tr></table>") == "<table><tr><td>0</td></tr></table>"


def test_the_references_are_the_ones_the_note_cites_as_written():
    """A linkage's note listed the gear standard it never cites; '[и др.]' (GOST 7.1) was printed
    '(и др.)'."""
    from tmm_cli.report.note import WORDS, _books
    W = WORDS["ru"]
    gear = [b for b in W["bibliography_gears"] if "16532" in b]
    assert gear and not set(gear) & set(_books(W, {"kinematics": [1]}))
    assert _books(W, {"kinematics": [1]}) == W["bibliography"]
    for res in ({"gears": {"aw": 0.1}}, {"drive_train": {"ratio": 3}}):
        assert _books(W, res) == W["bibliography"] + gear


def test_the_references_keep_their_brackets(note):
    text = subprocess.run(["pdftotext", str(note), "-"], capture_output=True, text=True, check=True).stdout
    refs = text[text.rindex("Список літератури"):]
    assert "[и др.]" in " ".join(refs.split()) and "(и др.)" not in refs
