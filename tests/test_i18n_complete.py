"""Catalogue completeness: every English text of the report, the task section's tables,
the batch summary and the feedback page exists in every other language."""
from __future__ import annotations

import pytest

from tmm_cli import feedback, summary
from tmm_cli.report import i18n, sections
from tmm_cli.report.sections import task as task_section

OTHERS = [lang for lang in i18n.LANGS if lang != "en"]


def _register_all():
    for _name, _ in sections.available():       # imports every section module: registers its I18N
        pass


def test_languages():
    assert i18n.LANGS == ("en", "ru", "uk")


@pytest.mark.parametrize("lang", OTHERS)
def test_report_strings_complete(lang):
    _register_all()
    missing = sorted(set(i18n.STRINGS["en"]) - set(i18n.STRINGS[lang]))
    assert not missing, missing


@pytest.mark.parametrize("lang", OTHERS)
def test_section_tables_complete(lang):
    _register_all()
    mods = [m for _n, m in sections.available() if m is not None]
    import tmm_cli.report.explore as explore
    import tmm_cli.report.failure as failure
    assert mods
    for mod in mods + [failure, explore]:
        table = getattr(mod, "I18N", None)
        if not table:
            continue
        # a section's own key in English is translated (in its table or the central one)
        missing = [k for k in table["en"] if k not in table.get(lang, {}) and k not in i18n.STRINGS[lang]]
        assert not missing, (mod.__name__, missing)


@pytest.mark.parametrize("lang", OTHERS)
def test_task_tables_complete(lang):
    for table in (task_section.PARAMS, task_section.ITEMS, task_section._UNITS):
        assert set(table["en"]) <= set(table[lang]), sorted(set(table["en"]) - set(table[lang]))
    # word values: every Russian one has its form in every other language
    assert set(task_section.WORDS["ru"]) <= set(task_section.WORDS[lang])


@pytest.mark.parametrize("lang", OTHERS)
def test_summary_and_feedback_complete(lang):
    from tmm_cli.messages import catalogue
    # the status words come from the message catalogue's `status` table
    status = set(catalogue(lang)["terms"]["status"])
    assert set(summary.I18N["en"]) == set(summary.I18N[lang]) | status
    assert set(feedback.TEXT["en"]) == set(feedback.TEXT[lang])
    assert set(feedback.STEPS["en"]) == set(feedback.STEPS[lang])


def test_uk_is_not_russian():
    """The Ukrainian table is its own text: no Russian-only letters, and most texts differ from
    the Russian ones (equal ones are symbols, units and shared words such as "Маховик")."""
    _register_all()
    uk, ru = i18n.STRINGS["uk"], i18n.STRINGS["ru"]
    bad = {k: v for k, v in uk.items() if set(v) & set("ыэъёЫЭЪЁ")}
    assert not bad, bad
    same = [k for k in uk if k in ru and uk[k] == ru[k] and any("а" <= c <= "я" for c in uk[k].lower())
            and len(uk[k]) > 12]
    assert len(same) < 0.05 * len(uk), same
