"""The feedback page in Russian or Ukrainian writes the units as the course's texts do
(кг·м², Н·м, °), not the English unit strings of the answer forms (kg*m^2, N*m, deg)."""
from __future__ import annotations

import string
from pathlib import Path
from types import SimpleNamespace

import pytest

from tmm_cli.feedback import feedback_html
from tmm_cli.forms import NOTATION, PATH_NOTATION, local_unit, notation

ROWS = [{"path": "flywheel.J", "status": "ok", "answer": 58.46, "reference": 58.46, "error": 0.0,
         "tolerance": "rel 0.01", "note": ""},
        {"path": "kinetostatics[1].balancing_moment", "status": "sign", "answer": -1.19, "reference": 1.19,
         "error": 2.0, "tolerance": "rel 0.01", "note": ""},
        {"path": "positions.phi0", "status": "ok", "answer": 84.8, "reference": 84.8, "error": 0.0,
         "tolerance": "rel 0.01", "note": ""}]


@pytest.mark.parametrize("lang, words", [("ru", ["J_fly, кг·м² — момент инерции маховика", "M_ур, Н·м —", "φ0, ° —"]),
                                         ("uk", ["J_fly, кг·м² — момент інерції маховика", "M_зр, Н·м —", "φ0, ° —"])])
def test_feedback_units_in_the_page_language(lang, words):
    task = SimpleNamespace(title="Crank press, variant 3", name="03")
    page = feedback_html(task, {"rows": ROWS, "student": "Иванов", "group": "МТ-21", "variant": 3}, lang)
    for w in words:
        assert w in page, w
    assert "kg*m^2" not in page and "N*m" not in page and ", deg —" not in page


def test_every_unit_has_its_local_form():
    units = ({n[1] for n in NOTATION.values()} | {n[1] for n in PATH_NOTATION.values()}) - {""}
    for lang in ("ru", "uk"):
        for unit in units:
            local = local_unit(unit, lang)
            assert not any(c in string.ascii_letters for c in local), (lang, unit, local)
    # the forms keep the English units an answer may be written in
    assert notation("flywheel.J", "ru") == "J_fly, kg*m^2 — момент инерции маховика"
    assert units


def test_feedback_pdf_skipped_without_its_engine(tmp_path, monkeypatch):
    """Without the typst package (ImportError) the feedback page is written as HTML only,
    no half-written PDF and no failure of the grading."""
    import sys
    from tmm_cli.feedback import write_feedback
    monkeypatch.setitem(sys.modules, "typst", None)      # import raises ImportError
    task = SimpleNamespace(title="Crank press, variant 3", name="03")
    s = {"rows": ROWS, "student": "Ivanov", "group": "MT-21", "variant": 3, "index": 0}
    notes: list = []
    written = write_feedback(task, s, tmp_path, "en", pdf=True, notes=notes)
    assert [p.name for p in written] == ["feedback-Ivanov-1.html"]
    assert len(notes) == 1 and notes[0].startswith("feedback pages written as HTML only: the PDF engine (typst)")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["feedback-Ivanov-1.html"]
    assert "flywheel.J" in written[0].read_text(encoding="utf-8")


def _pdf_text(pdf: Path) -> str | None:
    import shutil
    import subprocess
    if shutil.which("pdftotext") is None:
        return None
    return subprocess.run(["pdftotext", "-layout", str(pdf), "-"], capture_output=True, text=True,
                          check=True).stdout


@pytest.mark.parametrize("lang", ["en", "ru"])
def test_feedback_pdf_carries_the_grades(tmp_path, lang):
    """The feedback PDF is compiled by Typst (the report's writer) and carries the page:
    the student, the score (2 of the 3 rows are ok: 2 / 3), each value and reference as
    the rows give them (58.46 written 58,46 in ru), the verdicts in the page's language."""
    from tmm_cli.feedback import feedback_html, write_feedback
    from tmm_cli.report.typst_pdf import to_typst
    task = SimpleNamespace(title="Crank press, variant 3", name="03")
    s = {"rows": ROWS, "student": "Ivanov", "group": "MT-21", "variant": 3, "index": 0}
    notes: list = []
    written = write_feedback(task, s, tmp_path, lang, pdf=True, notes=notes)
    assert [p.name for p in written] == ["feedback-Ivanov-1.html", "feedback-Ivanov-1.pdf"] and not notes
    assert written[1].read_bytes().startswith(b"%PDF-")
    comma = (lambda x: x.replace(".", ",").replace("-", "\u2212")) if lang == "ru" else (lambda x: x)   # −1,19
    ok, sign = ("верно", "ошибка знака") if lang == "ru" else ("correct", "sign error")
    words = ["Ivanov", "MT-21", "flywheel.J", comma("58.46"), comma("-1.19"), comma("1.19"), comma("84.8"), ok, sign]
    text = _pdf_text(written[1])
    if text is None:                   # no poppler here: the Typst source the PDF is compiled from
        text = to_typst(feedback_html(task, s, lang), lang)[0]
    for w in words:
        assert w in text, w
    import re
    assert re.search(r"2\s*/\s*3", text)
    # the verdicts' colours of the HTML page are the PDF's cells' fills
    src = to_typst(feedback_html(task, s, lang), lang)[0]
    assert 'fill: rgb("#c8e6c9")' in src and 'fill: rgb("#e1bee7")' in src


def test_batch_prints_the_notes_as_warnings(tmp_path, capsys):
    """print_batch ends with each note as one warning line (after the table)."""
    from tmm_cli.summary import print_batch
    print_batch([], tmp_path, notes=["feedback pages written as HTML only: x"])
    out = capsys.readouterr()
    text = out.out + out.err
    assert "warning: feedback pages written as HTML only: x" in text
    assert text.index("tmm batch: 0 rows") < text.index("warning: feedback")


@pytest.mark.parametrize("lang", ["ru", "uk"])
def test_feedback_numbers_take_the_decimal_comma(lang):
    """The page's answers, references and errors are written with the decimal comma in ru and
    uk (58,46), powers of ten as 8,9·10⁻¹⁶ (not 8,9e-16), with the point in English."""
    import re
    from tmm_cli.feedback import _num
    task = SimpleNamespace(title="Crank press", name="03")
    s = {"rows": ROWS, "student": "S", "group": "G", "variant": 3}
    page = feedback_html(task, s, lang)
    assert "58,46" in page and not re.search(r"<td>-?\d+\.\d+", page)
    assert "58.46" in feedback_html(task, s, "en")
    assert _num(8.9e-16, lang) == "8,9·10⁻¹⁶" and _num(8.9e-16, "en") == "8.9e-16"


@pytest.mark.parametrize("written, path, ref, want", [
    ("0,234 \u043a\u041d", "kinetostatics[1].reactions.R03.R", 233.98, (0.23398, "\u043a\u041d")),   # кН
    ("0.234 kN", "kinetostatics[1].reactions.R03.R", 233.98, (0.23398, "kN")),
    ("160 mm", "positions.H", 0.16019, (160.19, "mm")),              # a path outside the presets
    ("12,5 \u043c/\u0441", "kinematics[2].points.B.v", 12.4, (12.4, "\u043c/\u0441")),          # м/с
    ("1450 \u043e\u0431/\u043c\u0438\u043d", "kinematics[2].links.crank.omega", 151.8,          # об/мин
     (151.8 * 30 / 3.141592653589793, "\u043e\u0431/\u043c\u0438\u043d")),
    ("12", "positions.phi0", 12.4, None)])                          # no unit written: none to convert to
def test_the_reference_in_the_unit_the_student_wrote(written, path, ref, want):
    """The feedback page gives the reference in the unit of the student's answer, every unit the
    answers reader reads: a Russian 'кН' was shown against the reference in N ('233,98 Н'), a
    length of a path outside the presets without its unit ('0.16019' against '160 mm')."""
    from tmm_cli.feedback import _in_written_unit
    got = _in_written_unit({"written": written, "reference": ref, "path": path})
    if want is None:
        assert got is None
    else:
        assert got[1] == want[1] and got[0] == pytest.approx(want[0], rel=1e-12)


def test_degrees_closed_up_and_errors_to_three_digits():
    """A value in degrees is printed 16,36° (no space before the degree sign, as the report and
    the drawings print it; it was '16,36 °'), other units after a space; an error in percent to
    three digits (0,0408 %, not 0,040793 %)."""
    from tmm_cli.feedback import _pct, _q
    assert _q(16.36, "\u00b0", "ru") == "16,36\u00b0" and _q(0.25, "\u043c", "ru") == "0,25 \u043c"
    assert _q(12, "", "en") == "12" and _pct(0.00040793, "ru") == "0,0408 %" and _pct(0.05, "en") == "5 %"


def test_a_reference_for_an_answer_in_degrees_and_minutes_is_in_degrees():
    """'16°22′' as written: the reference was shown as '11,973 °22′' (the minutes taken for the
    unit); it is in degrees. And a unit-slip note names its units in the page's language."""
    from tmm_cli.feedback import _in_written_unit
    from tmm_cli.messages import Message, render
    assert _in_written_unit({"written": "16\u00b022\u2032", "reference": 16.36, "path": "synthesis.theta"}) == \
        (16.36, "\u00b0")
    m = Message("answers.note_unit_slip", unit="mm", si="m", value=98.5)
    assert render(m.code, m.params, "ru").endswith("(98,5 \u043c\u043c)")
