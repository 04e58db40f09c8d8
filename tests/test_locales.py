"""The catalogues (tmm_cli/locales/<lang>/<topic>.yaml): one loader, one set per language,
every key of English in every language, a report word in one topic only, and the old
three-language files beside a module converted by tools/split_catalogue.py."""
from __future__ import annotations

from pathlib import Path

import pytest

from tmm_cli import locales

ROOT = Path(__file__).resolve().parents[1]
OTHERS = [lang for lang in locales.LANGS if lang != "en"]
# keys English has and another language does not, on purpose: the batch summary's status
# words come from the warnings catalogue's `status` terms in ru and uk (test_i18n_complete)
NOT_TRANSLATED = {"summary": {"text": {"ok", "outside", "sign", "missing", "unknown_path", "not_computed",
                                       "no_answers", "invalid", "failed", "computed"}}}


def _missing(en, other, path=()):
    """The key paths of ``en`` (nested mappings) that ``other`` lacks."""
    out = []
    for k, v in en.items():
        if k not in other:
            out.append(path + (k,))
        elif isinstance(v, dict) and isinstance(other[k], dict):
            out += _missing(v, other[k], path + (k,))
    return out


def test_languages_and_topics():
    assert locales.LANGS == ("en", "ru", "uk")
    for lang in OTHERS:      # the same files in every language
        assert locales.topics(lang) == locales.topics("en")
    assert {"report", "task", "cam", "note", "summary"} <= set(locales.topics("en"))


@pytest.mark.parametrize("lang", OTHERS)
def test_every_english_key_in_every_language(lang):
    for name in locales.topics("en"):
        skip = NOT_TRANSLATED.get(name, {})
        missing = [p for p in _missing(locales.topic("en", name), locales.topic(lang, name))
                   if not (len(p) == 2 and p[1] in skip.get(p[0], ()))]
        assert not missing, (name, missing)


@pytest.mark.parametrize("lang", locales.LANGS)
def test_a_report_word_lives_in_one_topic(lang):
    seen: dict[str, str] = {}
    for name in locales.topics(lang):
        for key in locales.topic(lang, name).get("words") or {}:
            assert key not in seen, (key, seen.get(key), name)
            seen[key] = name


def test_fallback_english_then_key():
    from tmm_cli.report import i18n
    assert i18n.translate("report.contents", "ru") == "Содержание"
    assert i18n.translate("report.contents", "xx") == "Contents"          # a language without it
    assert i18n.translate("no.such.key", "uk") == "no.such.key"


def test_loader_gives_copies():
    a = locales.table("cam", "words")
    a["en"]["cam.title"] = "changed"
    assert locales.table("cam", "words")["en"]["cam.title"] != "changed"
