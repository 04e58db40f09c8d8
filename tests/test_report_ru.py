"""The Russian report: every section of a whole project (linkage + kinetostatics +
flywheel, cam, gears, planetary) renders in Russian with no English heading, table
header, caption or translated phrase left, and the table of contents names the
sections by their Russian headings."""
from __future__ import annotations

import re
from html import unescape

import pytest

from tmm_cli.report import i18n, sections

from report_langs import render_pairs

TASKS = ("forging_sixbar", "cam_rocker", "gears_shifted", "planetary_A", "planetary_pair_given")


@pytest.fixture(scope="module")
def reports(shared_once):
    return render_pairs(shared_once, TASKS, "ru")


def _visible(html: str) -> str:
    """The report's own text: without CSS, figures, the task's free-text title, the
    stages' warnings (free text of the results) and the comments of the explorer's script
    (its words are the catalogue's, in its JSON)."""
    html = re.sub(r"<style>.*?</style>", "", html, flags=re.S)
    html = re.sub(r"<script\b.*?</script>", lambda m: re.sub(r"(?m)(^|\s)//\s.*$", "", m.group(0)), html, flags=re.S)
    html = re.sub(r"<svg\b.*?</svg>", "", html, flags=re.S)
    html = re.sub(r"<title>.*?</title>|<h1>.*?</h1>", "", html, flags=re.S)
    html = re.sub(r'<section class="section" id="warnings">.*?</section>', "", html, flags=re.S)
    html = re.sub(r"<tr><th>(Тема|Title)</th><td>.*?</td></tr>", "", html, flags=re.S)
    return html


def _texts(html: str, tags=("h1", "h2", "h3", "h4", "caption", "th", "figcaption", "li")) -> list[str]:
    out = []
    for tag in tags:
        for m in re.finditer(rf"<{tag}\b[^>]*>(.*?)</{tag}>", html, re.S):
            out.append(unescape(re.sub(r"<[^>]+>", "", m.group(1))).strip())
    return out


def _english_phrases() -> list[str]:
    """Every English text of the translation tables that differs from its Russian
    one and reads as words (>= 2 words of letters)."""
    for name, _ in sections.available():       # registers the sections' tables
        pass
    en, ru = i18n.STRINGS["en"], i18n.STRINGS["ru"]
    out = []
    for k, v in en.items():
        if ru.get(k, v) != v and len(re.findall(r"[A-Za-z]{3,}", v)) >= 2:
            lit = re.split(r"[{(]", v)[0].strip()          # the literal part before a placeholder
            if lit not in ru.get(k, ""):                   # not a formula both languages share
                out.append(lit)
    return [p for p in out if len(p) >= 8]


@pytest.mark.parametrize("name", TASKS)
def test_no_english_left(reports, name):
    ru, en = reports[name]
    body = _visible(ru)
    left = [p for p in _english_phrases() if p in body]
    assert not left, left
    # every heading is Russian (Cyrillic), except the task's own title (free text)
    title = re.search(r"<h1>(.*?)</h1>", ru).group(1)
    for text in _texts(body, ("h2", "h3", "h4")):
        assert re.search("[А-Яа-яЁё]", text), text
    # the English report really has these phrases: the check above can fail
    assert any(p in _visible(en) for p in _english_phrases())
    assert title


def test_table_of_contents_uses_headings(reports):
    ru = reports["forging_sixbar"][0]
    toc = re.search(r'<nav class="toc">(.*?)</nav>', ru, re.S).group(1)
    items = [unescape(re.sub(r"<[^>]+>", "", x)).strip() for x in re.findall(r"<li>(.*?)</li>", toc, re.S)]
    assert items == ["Задание", "Структурный анализ механизма", "Кинематический анализ механизма",
                     "Кинетостатика", "Расчёт одного положения по шагам", "Динамика и маховик"]


def test_task_data_has_no_python_formatting(reports):
    """No tuples, brackets or 'forces[0]' in the task data; numbers carry units."""
    ru = reports["forging_sixbar"][0]
    sec = re.search(r'<section class="section" id="task">(.*?)</section>', ru, re.S).group(1)
    cells = _texts(sec, ("td",))
    assert not [c for c in cells if re.search(r"[\[\]]|\w\[\d", c)], cells
    assert "0; 0,7; 0,7; 0,9; 1" in cells              # the s/H points of the load diagram (decimal comma)
    assert "0; 0; 6000; 15000; 15000 Н" in cells       # its forces, N
    assert "5,23599 рад/с" in cells                    # 50 rpm = 5.235988 rad/s
    assert "против часовой стрелки" in cells
