"""`tmm fields --lang ru|uk`: every task-file field's meaning in the language (the catalogue's
`fields` table, by path: none missing, none left over from a field that is gone), the code the
user types kept as written (the backticked spans and the numbers of the English text), and the
table's words; without --lang the English of the schema itself."""
from __future__ import annotations

import re

import pytest
from typer.testing import CliRunner

from tmm_cli import locales
from tmm_cli.cli import app
from tmm_cli.task import field_docs

runner = CliRunner()
CYR = re.compile("[\u0400-\u04ff]")


@pytest.mark.parametrize("lang", ["ru", "uk"])
def test_every_field_has_its_meaning_and_no_other(lang):
    english = {p: t for p, _, t in field_docs()}
    table = locales.topic(lang, "fields")["fields"]
    assert list(table) == list(english)          # the same paths in the same order
    for path, text in table.items():
        en = english[path]
        assert re.findall(r"`[^`]*`", text) == re.findall(r"`[^`]*`", en), path
        assert sorted(re.findall(r"\d+(?:\.\d+)?", text)) == sorted(re.findall(r"\d+(?:\.\d+)?", en)), path
        if re.search(r"[a-z]{4}", re.sub(r"`[^`]*`|\{[^}]*\}|'[^']*'", "", en)):
            assert CYR.search(text), (path, text)     # prose translated, not left in English


@pytest.mark.parametrize("lang, head, required", [("ru", "по умолчанию", "обязательно"),
                                                  ("uk", "за замовчуванням", "обов'язково")])
def test_fields_table_in_the_language(lang, head, required):
    res = runner.invoke(app, ["fields", "flywheel", "--lang", lang], env={"COLUMNS": "200"})
    assert res.exit_code == 0, res.output
    want = locales.topic(lang, "fields")["fields"]["flywheel.delta"]
    text = " ".join(res.stdout.split())
    assert head in text and required in text and " ".join(want.split()) in text
    en = runner.invoke(app, ["fields", "flywheel"], env={"COLUMNS": "200"})
    english = dict((p, t) for p, _, t in field_docs())["flywheel.delta"]
    assert "tmm task file fields (schema tmm/1)" in en.stdout and english in " ".join(en.stdout.split())
    assert "required" in en.stdout and not CYR.search(en.stdout)


def test_an_unknown_section_in_the_language():
    res = runner.invoke(app, ["fields", "flywhel", "--lang", "uk"])
    assert res.exit_code == 2
    assert "помилка: немає розділу або поля «flywhel»; можливо, малося на увазі «flywheel»?" in res.output
    res = runner.invoke(app, ["fields", "flywhel"])
    assert res.exit_code == 2 and "error: no section or field 'flywhel'; did you mean 'flywheel'?" in res.output
    res = runner.invoke(app, ["fields", "--lang", "de"])
    assert res.exit_code == 2 and "--lang must be" in res.output


def test_a_section_asked_for_in_the_course_words():
    """`tmm fields маховик` lists the flywheel's fields (every language's words serve, as a
    student types them); each word names a section the task file has."""
    top = {p.split(".")[0].split("[")[0] for p, _, _ in field_docs()}
    for lang in ("ru", "uk"):
        words = locales.topic(lang, "fields")["sections"]
        assert set(words.values()) <= top, set(words.values()) - top
    res = runner.invoke(app, ["fields", "маховик", "--lang", "ru"], env={"COLUMNS": "200"})
    assert res.exit_code == 0 and "flywheel.delta" in res.stdout and "cam.stroke" not in res.stdout
    res = runner.invoke(app, ["fields", "Зубчасті колеса"], env={"COLUMNS": "200"})
    assert res.exit_code == 0 and "gears.z" in res.stdout
