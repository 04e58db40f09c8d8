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
        said = text.translate(SUPER)                     # 'кг·м²' says the 2 of 'kg*m^2'
        assert sorted(re.findall(r"\d+(?:\.\d+)?", said)) == sorted(re.findall(r"\d+(?:\.\d+)?", en)), path
        if re.search(r"[a-z]{4}", re.sub(r"`[^`]*`|\{[^}]*\}|'[^']*'", "", en)):
            assert CYR.search(text), (path, text)     # prose translated, not left in English


# the units the ru and uk meanings write, each with the English spelling it stands for and
# the kind of field it is written for
UNITS = {"ru": [("м", "m", "length"), ("мм", "mm", "length"), ("кг", "kg", "mass"),
                ("кг·м²", "kg*m^2", "inertia"), ("кг/м³", "kg/m^3", "density"), ("Н", "N", "force"),
                ("Н·м", "N*m", "moment"), ("Па", "Pa", "pressure"), ("м²", "m^2", "area"),
                ("рад/с", "rad/s", "speed"), ("об/мин", "rpm", "speed"), ("град/с", "deg/s", "speed"),
                ("м/с", "m/s", "linear_speed"), ("с", "s", "time")],
         "uk": [("об/хв", "rpm", "speed")]}         # uk: the rest as ru
SUPER = str.maketrans({"²": "^2", "³": "^3"})


@pytest.mark.parametrize("lang", ["ru", "uk"])
def test_the_meanings_write_units_as_the_language_does_and_the_task_file_reads_them(lang):
    """`tmm fields --lang ru` wrote kg*m^2, N*m, rad/s, rpm in Russian prose: now кг·м²,
    Н·м, рад/с, об/мин (об/хв in uk), each a spelling the task file reads as that unit."""
    from tmm_cli.units import convert
    text = " ".join(locales.topic(lang, "fields")["fields"].values())
    text = re.sub(r"`[^`]*`", "", text)                            # field names and YAML stay as typed
    latin = re.findall(r"\b(?:kg|N\*m|rad/s|rpm|m/s|deg/s|Pa|mm)\b", text)
    assert not latin, latin
    own = {english: word for word, english, _ in UNITS[lang]}
    for word, english, kind in UNITS["ru"]:
        word = own.get(english, word)                               # uk's own spelling where it has one
        assert convert(f"3 {word}", kind) == convert(f"3 {english}", kind), word
        assert re.search(rf"(?<![\w/·]){re.escape(word)}(?![\w/·²³])", text), (lang, word)


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
