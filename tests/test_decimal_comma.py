"""Russian and Ukrainian write numbers with the decimal comma and powers of ten as
8,9·10⁻¹⁶: every example task's report in ru and uk -- its HTML text, the inline figures'
labels and tick labels, the Typst source report.pdf is compiled from and its figure files --
has no number with a decimal point and no Python exponent (`e-16`).  English keeps the point;
results.json and the CSV files are never localised."""
from __future__ import annotations

import csv
import io
import re
from html import unescape
from pathlib import Path

import pytest

import tmm_cli
from tmm_cli import numfmt
from tmm_cli.report.typst_pdf import to_typst

from report_langs import report_dir, report_html

ROOT = Path(__file__).resolve().parents[1]
TASKS = sorted(p.stem for p in (ROOT / "tasks").glob("*.yaml"))

# a number written with a decimal point (not a part of a name such as 'O1.x', a date or a
# designation such as 'ТММ.КП.07.00') and a number with an exponent
POINT = re.compile(r"(?<![\w.])[-−]?\d+\.\d+(?![\w.])")
EXPONENT = re.compile(r"(?<![\w.])[-−]?\d+(?:\.\d+)?[eE][-+−]?\d+(?!\w)")


def _visible(html: str, title: str) -> str:
    """The report's text as a reader sees it: the text nodes (the inline figures' labels
    among them), without CSS, scripts and the task's own free-text title."""
    html = re.sub(r"<style\b.*?</style>|<script\b.*?</script>", "", html, flags=re.S)
    text = unescape(re.sub(r"<[^>]+>", "\n", html))
    return text.replace(title, "") if title else text


def _typst_text(src: str) -> str:
    """The Typst source without its code: the text the PDF typesets."""
    src = re.sub(r'numbering\("[^"]*"', "", src)                       # heading numbers: 1.1.
    src = re.sub(r'rgb\("#[0-9a-fA-F]{6}"\)', "", src)                   # colours: #1e8449 is no 1·10⁸⁴⁴⁹
    return re.sub(r"\d+(?:\.\d+)?(?:pt|mm|em|fr|cm|%|deg)\b", "", src)  # lengths of the layout


def _bad(text: str, given: str = "") -> list[str]:
    """Lines with a number written the English way (``given``: the task's own formula, as typed)."""
    out = []
    for line in text.splitlines():
        if given:
            line = line.replace(given, "")
        if POINT.search(line) or EXPONENT.search(line):
            out.append(line.strip()[:160])
    return out


@pytest.mark.parametrize("name", TASKS)
@pytest.mark.parametrize("lang", ["ru", "uk"])
def test_numbers_take_the_decimal_comma(shared_once, name, lang):
    # the report (and its CSV tables) made once per session, shared with test_report_ru/_uk, test_glossary
    folder = report_dir(shared_once, name, lang)
    task = tmm_cli.load_task(ROOT / "tasks" / f"{name}.yaml")
    html = (folder / "report.html").read_bytes().decode("utf-8")
    title = getattr(task, "title", None) or ""
    typed = re.search(r'function: "([^"]+)"', (ROOT / "tasks" / f"{name}.yaml").read_text(encoding="utf-8"))
    given = typed.group(1) if typed else ""      # a function the task gives as typed ('x**1.5')
    bad = _bad(_visible(html, title), given)
    assert not bad, bad[:20]
    src, files = to_typst(html, lang)
    bad = _bad(_typst_text(src).replace(title, ""), given)
    assert not bad, bad[:20]
    for fname, data in files.items():
        if fname.endswith(".svg"):
            bad = _bad(_visible(data.decode("utf-8"), title), given)
            assert not bad, (fname, bad[:20])
    # the numbers are there, with the comma: the check above can fail
    assert re.search(r"\d,\d", _visible(html, title))
    # the results are never localised (their JSON compared before and after the report)
    assert (folder / "results-unchanged").read_text() == "True"
    for path in folder.glob("*.csv"):
        rows = list(csv.reader(io.StringIO(path.read_text(encoding="utf-8"))))
        assert not [c for row in rows for c in row if re.fullmatch(r"[-−]?\d+,\d+|.*·10.*", c)], path.name


def test_english_keeps_the_point(shared_once):
    task = tmm_cli.load_task(ROOT / "tasks" / "engine_slider_crank.yaml")
    text = _visible(report_html(shared_once, "engine_slider_crank", "en"), task.title or "")
    assert POINT.search(text) and not re.search(r"\d,\d{1,3}(?!\d)\s*(?:m|mm|rad|N)\b", text)


@pytest.mark.parametrize("lang", ["ru", "uk"])
def test_localize(lang):
    assert numfmt.localize("8.9e-16", lang) == "8,9·10⁻¹⁶"
    assert numfmt.localize("1.23e+07 м", lang) == "1,23·10⁷ м"
    assert numfmt.localize("μl = 0.005 м/мм (М 1:2.5)", lang) == "μl = 0,005 м/мм (М 1:2,5)"
    assert numfmt.localize("0.5..1.25", lang) == "0,5..1,25"
    # designations, dates, names stay
    for s in ("ТММ.КП.07.00.00 ПЗ", "06.12.2026", "O1", "B3"):
        assert numfmt.localize(s, lang) == s
    assert numfmt.localize("8.9e-16", "en") == "8.9e-16"
    with numfmt.language(lang):
        from tmm_cli.report.context import fmt, fmt_fixed
        assert fmt(0.123456) == "0,1235" and fmt(8.9e-6) == "8,900·10⁻⁶" and fmt_fixed(2.5, 2) == "2,50"
    assert fmt(0.123456) == "0.1235"


@pytest.mark.parametrize("name", ["forging_sixbar", "cam_rocker", "gears_shifted"])
@pytest.mark.parametrize("lang", ["ru", "uk"])
def test_sheets_take_the_decimal_comma(shared_once, name, lang):
    """The A1 sheets' labels (scales, values, the title block) in ru and uk: the decimal comma."""
    from test_sheets import example_sheets

    from tmm_cli.sheets.prims import Text
    task = tmm_cli.load_task(ROOT / "tasks" / f"{name}.yaml")
    # every example's sheets, built once per worker from the session's results (tests/test_sheets.py)
    texts = [" ".join(x for x in (t.s, t.sub, t.after) if x) for cv, _ in example_sheets(name, shared_once)[lang]
             for t in cv.prims if isinstance(t, Text)]
    bad = _bad("\n".join(texts).replace(getattr(task, "title", None) or "\0", ""))
    assert not bad, bad[:20]
    assert any(re.search(r"\d,\d", x) for x in texts)


def test_note_conclusions_write_powers_of_ten():
    """The explanatory note's conclusions (their own numbers): 8,9·10⁻¹⁶, not 8,9e-16."""
    from tmm_cli.report.note import _num
    assert _num(8.9e-16, "ru") == "8,9·10⁻¹⁶" and _num(0.25, "uk") == "0,25" and _num(0.25, "en") == "0.25"
