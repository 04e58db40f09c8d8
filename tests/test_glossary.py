"""One term per concept: every text tmm writes in Russian and Ukrainian -- the message
catalogues, every file of tmm_cli/locales/<lang>/, the report's tables, every module's
language tables -- and the reports of the example tasks use the glossary's term,
never a spelling it lists to avoid (docs/glossary.yaml)."""
from __future__ import annotations

import importlib
import pkgutil
import re
from html import unescape
from pathlib import Path

import pytest
import yaml

import tmm_cli

ROOT = Path(__file__).resolve().parents[1]
GLOSSARY = yaml.safe_load((ROOT / "docs" / "glossary.yaml").read_text(encoding="utf-8"))
LANGS = ("ru", "uk")
REPORT_TASKS = ("shaper_slotted_lever", "shaper_slotted_ram", "forging_sixbar", "cam_rocker", "scotch_yoke_pump",
                "synthesis_shaper", "press_drive_train")


def _avoid(lang: str, report: bool) -> list[tuple[str, re.Pattern]]:
    return [(e["concept"], re.compile(r"(?<!\w)" + a, re.I)) for e in GLOSSARY[lang]
            for a in e["avoid"] if report or not e.get("report_only")]


def _strings(value):
    if isinstance(value, str):
        yield value
    elif isinstance(value, dict):
        for v in value.values():
            yield from _strings(v)
    elif isinstance(value, (list, tuple)):
        for v in value:
            yield from _strings(v)


def _tables(value, lang: str, depth: int = 0):
    """The strings of ``lang`` in a module's table: a dict keyed by language (at any depth)."""
    if depth > 4 or not isinstance(value, dict):
        return
    if lang in value and all(isinstance(k, str) and len(k) == 2 for k in value):
        yield from _strings(value[lang])
        return
    for v in value.values():
        yield from _tables(v, lang, depth + 1)


def texts(lang: str) -> list[str]:
    """Every text of ``lang`` tmm holds: catalogues, the report's tables, every module's tables."""
    from tmm_cli.messages import catalogue
    from tmm_cli.report import i18n, sections
    sections.available()
    out = list(_strings(catalogue(lang))) + list(i18n.STRINGS[lang].values())
    from tmm_cli import locales
    for name in locales.topics(lang):          # every catalogue file of the language
        out += list(_strings(locales.topic(lang, name)))
    for mod in pkgutil.walk_packages(tmm_cli.__path__, "tmm_cli."):
        if mod.name.endswith("__main__"):
            continue
        m = importlib.import_module(mod.name)
        for name, value in vars(m).items():
            if name.endswith("_" + lang.upper()) or (lang == "uk" and name == "UK"):
                out += list(_strings(value))
            elif isinstance(value, dict):
                out += list(_tables(value, lang))
    return out


@pytest.mark.parametrize("lang", LANGS)
def test_every_text_uses_the_glossary(lang):
    all_texts = texts(lang)
    assert len(all_texts) > 1000            # the collection reaches the tables
    bad = sorted({(concept, t[:120]) for t in all_texts for concept, p in _avoid(lang, False) if p.search(t)})
    assert not bad, bad


def test_the_glossary_is_one_term_per_concept():
    for lang in LANGS:
        concepts = [e["concept"] for e in GLOSSARY[lang]]
        assert len(concepts) == len(set(concepts))
        for e in GLOSSARY[lang]:           # a term never matches what it says to avoid
            assert not any(re.search(r"(?<!\w)" + a, e["use"], re.I) for a in e["avoid"]), e


@pytest.fixture(scope="module")
def reports(shared_once):
    """The reports made once per session, shared with tests/test_report_ru.py and _uk.py."""
    from report_langs import report_html
    out = {}
    for name in REPORT_TASKS:
        task = tmm_cli.load_task(ROOT / "tasks" / f"{name}.yaml")
        for lang in LANGS:
            html = report_html(shared_once, name, lang)
            html = re.sub(r"<style\b.*?</style>|<script\b.*?</script>", "", html, flags=re.S)
            out[name, lang] = (unescape(re.sub(r"<[^>]+>", " ", html)), task)
    return out


@pytest.mark.parametrize("lang", LANGS)
@pytest.mark.parametrize("name", REPORT_TASKS)
def test_reports_use_the_glossary(reports, name, lang):
    text, task = reports[name, lang]
    bad = sorted({(concept, m.group(0)) for concept, p in _avoid(lang, True) for m in p.finditer(text)})
    assert not bad, bad


def test_links_named_by_kind_number_and_task_name(reports):
    """The shaper's sliding block is the block of the slotted link (камень кулисы / камінь
    куліси), the ram a slider; the output link is named by its kind and number with the
    task's name in brackets; the worked steps' slotted group in the letters of the pairs."""
    ru, _ = reports["shaper_slotted_lever", "ru"]
    uk, _ = reports["shaper_slotted_lever", "uk"]
    assert "камень кулисы" in ru and "камінь куліси" in uk
    assert re.search(r"Выходное звено:\s+ползун \d \(\w+\)", ru), re.findall(r"Выходное звено:.{0,30}", ru)
    assert re.search(r"Вихідна ланка:\s+повзун \d \(\w+\)", uk), re.findall(r"Вихідна ланка:.{0,30}", uk)
    assert re.search(r"реакция на камень кулисы\s+\d\s+\(\w+\)", ru), re.findall(r"реакция на.{0,30}", ru)
    assert "l, м" in ru and "l, м" in uk and "l, m " not in ru      # the link lengths' column
    ru_ram, _ = reports["shaper_slotted_ram", "ru"]
    assert "(ПВП)" in ru_ram and "(ПОП)" in reports["shaper_slotted_ram", "uk"][0]


def test_words_agree_with_their_labels(reports):
    """The task table's words agree with the noun of their label: «сталий момент: рушійний»,
    «постоянный момент: движущий» (not the force's «рушійна»)."""
    uk, _ = reports["forging_sixbar", "uk"]
    ru, _ = reports["forging_sixbar", "ru"]
    assert re.search(r"сталий момент\s+рушійний", uk) and not re.search(r"сталий момент\s+рушійна", uk)
    assert re.search(r"постоянный момент\s+движущий", ru)


@pytest.mark.parametrize("lang, words", [("uk", ("tmm: підсумки групи", "Рядків: 1")),
                                         ("ru", ("tmm: сводка по группе", "Строк: 1"))])
def test_group_summary_title_and_row_count(lang, words):
    """summary.html: «підсумки групи» (зведення is the reduction of ТММ), the number of rows
    after its label (no «1 рядків»)."""
    from tmm_cli.summary import summary_html
    page = summary_html([{"student": "S", "group": "G", "variant": 1, "status": "ok", "score": 1.0,
                          "answers": 1}], [], "answers", lang)
    for w in words:
        assert w in page, w
    assert not re.search(r"<p>\d+ \w+</p>", page)


@pytest.mark.parametrize("lang, names", [("ru", {("M", "д"), ("M", "с"), ("M", "пр"), ("A", "д"), ("ΔT", None)}),
                                         ("uk", {("M", "р"), ("M", "о"), ("M", "зв"), ("A", "о"), ("ΔT", None)})])
def test_dynamics_sheet_names_its_curves_in_the_language(lang, names, shared_once):
    """Sheet 3's curves are named as the course writes them (M_д, M_пр; uk M_р, M_зв), not
    'M d', 'M red', 'A c', 'dT'."""
    from test_sheets import example_sheets

    from tmm_cli.sheets.prims import Text
    sheets = example_sheets("forging_sixbar", shared_once)[lang]       # built once (tests/test_sheets.py)
    (cv,) = [cv for cv, info in sheets if info["number"] == 3]
    texts = {(t.s, t.sub) for t in cv.prims if isinstance(t, Text)}
    assert names <= texts, names - texts
    assert not {s for s, _ in texts} & {"M d", "M c", "M red", "A d", "A c", "dT"}


def test_drive_train_stages_numbered_as_the_task_lists_them(reports):
    """The drive train's stages are numbered 1, 2, 3 in the report as in the task file (the
    results keep their list index from 0): the stage table, the shafts, the satellites."""
    ru, _ = reports["press_drive_train", "ru"]
    assert "выходной вал ступени 1" in ru and "выходной вал ступени 3" in ru
    assert "ступени 0" not in ru
    uk, _ = reports["press_drive_train", "uk"]
    assert "вихідний вал ступеня 1" in uk and "ступеня 0" not in uk
