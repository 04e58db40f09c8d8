"""The catalogues (tmm_cli/locales/<lang>/<topic>.yaml): one loader, one set per language,
every key of English in every language, a report word in one topic only, and the old
three-language files beside a module converted by tools/split_catalogue.py."""
from __future__ import annotations

import re
from pathlib import Path

import pytest

from tmm_cli import locales

ROOT = Path(__file__).resolve().parents[1]
OTHERS = [lang for lang in locales.LANGS if lang != "en"]
# keys English has and another language does not, on purpose: the batch summary's status
# words come from the warnings catalogue's `status` terms in ru and uk (test_i18n_complete)
NOT_TRANSLATED = {"summary": {"text": {"ok", "outside", "sign", "missing", "unknown_path", "not_computed",
                                       "no_answers", "invalid", "failed", "computed"}},
                  # each language's own words for a value (English's 'linear' has no Russian twin)
                  "values": {"synonyms": set(locales.topic("en", "values")["synonyms"])}}


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


@pytest.fixture
def catalogues(tmp_path, monkeypatch):
    """A copy of the catalogues the loader reads (its per-process memory emptied before and
    after), bytecode written, no PYTHONPYCACHEPREFIX: the folder and the kept copies' place."""
    import shutil
    import sys
    d = tmp_path / "locales"
    for lang in locales.LANGS:
        shutil.copytree(locales.DIR / lang, d / lang, ignore=shutil.ignore_patterns("__pycache__"))
    monkeypatch.setattr(locales, "DIR", d)
    monkeypatch.setattr(sys, "dont_write_bytecode", False)
    monkeypatch.setattr(sys, "pycache_prefix", None)
    locales._read.cache_clear()
    yield d
    locales._read.cache_clear()


def _parsed(path):
    import yaml
    return yaml.safe_load(path.read_text(encoding="utf-8")) or {}


def test_kept_catalogues_are_what_yaml_reads(catalogues, monkeypatch):
    """Every catalogue read twice: parsed and kept (``__pycache__/<topic>.<python>.pickle``),
    then read from the kept copy alone (PyYAML made to fail) -- the same tables as PyYAML's."""
    import yaml
    first = {(lang, name): locales._read(lang, name) for lang in locales.LANGS for name in locales.topics(lang)}
    assert len(first) > 60
    for (lang, name), data in first.items():
        path = catalogues / lang / f"{name}.yaml"
        assert data == _parsed(path) and data, (lang, name)
        assert any((catalogues / lang / "__pycache__").glob(f"{name}.*.pickle")), (lang, name)
    locales._read.cache_clear()
    monkeypatch.setattr(yaml, "load", lambda *a, **k: (_ for _ in ()).throw(AssertionError("parsed again")))
    for (lang, name), data in first.items():
        assert locales._read(lang, name) == data, (lang, name)


def test_a_changed_catalogue_is_read_again(catalogues):
    """A kept copy stands for its file while the file's size and modification time are those it
    was read with: an edit (a longer text; the same size, a new time) is read again, a copy that
    cannot be unpickled is parsed over, and nothing is kept where bytecode is not written."""
    import os
    import sys
    path = catalogues / "en" / "cam.yaml"
    base = locales._read("en", "cam")
    kept = next((catalogues / "en" / "__pycache__").glob("cam.*.pickle"))
    text = path.read_text(encoding="utf-8")
    path.write_text(text + "\nzz_added: [1]\n", encoding="utf-8")              # longer
    locales._read.cache_clear()
    assert locales._read("en", "cam") == {**base, "zz_added": [1]}
    path.write_text(text + "\nzz_added: [2]\n", encoding="utf-8")            # the same size
    st = path.stat()
    os.utime(path, ns=(st.st_atime_ns, st.st_mtime_ns + 1_000_000))
    locales._read.cache_clear()
    assert locales._read("en", "cam")["zz_added"] == [2]
    kept.write_bytes(b"not a pickle")
    locales._read.cache_clear()
    assert locales._read("en", "cam")["zz_added"] == [2]
    assert kept.read_bytes() != b"not a pickle"                                 # kept whole again
    sys.dont_write_bytecode = True              # (the fixture's monkeypatch restores it)
    assert locales._read("uk", "cam") and not list((catalogues / "uk" / "__pycache__").glob("cam.*"))
    assert not [p for p in catalogues.rglob("*.tmp")]


def _split():
    import importlib.util
    spec = importlib.util.spec_from_file_location("split_catalogue", ROOT / "tools" / "split_catalogue.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_split_catalogue_moves_a_three_language_file(tmp_path):
    """A beside-the-module file of the old kind goes into each language's file: new keys
    appended, a changed text replaced, a key of another topic's English words routed there,
    a new language given its folder; nothing else of the files changes."""
    import shutil

    import yaml
    loc = tmp_path / "locales"
    shutil.copytree(locales.DIR, loc, ignore=shutil.ignore_patterns("*.py", "__pycache__"))
    before = {p.relative_to(loc): yaml.safe_load(p.read_text(encoding="utf-8")) for p in loc.rglob("*.yaml")}
    src = tmp_path / "gears.yaml"
    src.write_text("en: {gears.new_word: 'new', cam.title: 'Cams'}\nru: {gears.new_word: 'новое'}\n"
                   "uk: {gears.new_word: 'нове'}\nde: {gears.new_word: 'neu'}\n", encoding="utf-8")
    out = _split().main([str(src), "--locales", str(loc), "--remove"])
    assert out == 0 and not src.exists()
    after = {p.relative_to(loc): yaml.safe_load(p.read_text(encoding="utf-8")) for p in loc.rglob("*.yaml")}
    for lang, word in (("en", "new"), ("ru", "новое"), ("uk", "нове"), ("de", "neu")):
        words = after[Path(lang) / "gears.yaml"]["words"]
        assert list(words)[-1] == "gears.new_word" and words["gears.new_word"] == word
    assert after[Path("en/cam.yaml")]["words"]["cam.title"] == "Cams"       # routed to its owner
    assert "cam.title" not in after[Path("en/gears.yaml")]["words"]
    for rel, data in before.items():          # the rest as it was, in its order
        if rel not in (Path("en/gears.yaml"), Path("ru/gears.yaml"), Path("uk/gears.yaml"), Path("en/cam.yaml")):
            assert after[rel] == data, rel
    en = after[Path("en/gears.yaml")]["words"]
    assert list(en)[:-1] == list(before[Path("en/gears.yaml")]["words"])


def test_words_beside_is_a_shim_over_the_catalogues(tmp_path):
    """words_beside(x.py) reads the catalogues' topic x, with an old x.yaml beside laid over."""
    from tmm_cli.report.i18n import words_beside
    mod = tmp_path / "cam.py"
    assert words_beside(str(mod))["ru"]["cam.title"] == locales.table("cam", "words")["ru"]["cam.title"]
    (tmp_path / "cam.yaml").write_text("en: {cam.extra: 'Extra'}\nru: {cam.title: 'Кулачки'}\n", encoding="utf-8")
    w = words_beside(str(mod))
    assert w["en"]["cam.extra"] == "Extra" and w["ru"]["cam.title"] == "Кулачки"
    assert w["uk"]["cam.title"] == locales.table("cam", "words")["uk"]["cam.title"]


def test_no_cyrillic_in_python_sources():
    """Every word a user reads is in the catalogues: no .py file of tmm_cli holds a Cyrillic
    letter (in code, strings or comments; course terms in comments are transliterated)."""
    cyr = re.compile("[\u0400-\u04FF]")
    found = [f"{p.relative_to(ROOT)}:{i}" for p in sorted((ROOT / "tmm_cli").rglob("*.py"))
             for i, line in enumerate(p.read_text(encoding="utf-8").splitlines(), 1) if cyr.search(line)]
    assert not found, found


def test_no_catalogue_file_repeats_a_key():
    """YAML keeps the last of two equal keys without a word: a key written twice in one table
    (a new word named as an old one) silently replaces the first text. Every catalogue file
    read with a loader that refuses a repeated key."""
    from pathlib import Path

    import yaml

    class Strict(yaml.SafeLoader):
        pass

    def mapping(loader, node, deep=False):
        seen = set()
        for k, _ in node.value:
            key = loader.construct_object(k, deep=deep)
            assert key not in seen, f"{node.start_mark}: key {key!r} repeated"
            seen.add(key)
        return yaml.SafeLoader.construct_mapping(loader, node, deep)

    Strict.add_constructor(yaml.resolver.BaseResolver.DEFAULT_MAPPING_TAG, mapping)
    files = sorted((Path(__file__).resolve().parents[1] / "tmm_cli" / "locales").rglob("*.yaml"))
    assert len(files) > 30
    for f in files:
        yaml.load(f.read_text(encoding="utf-8"), Loader=Strict)


@pytest.mark.parametrize("n, ru, uk, en", [
    (1, "1 положение", "1 положення", "1 position"), (2, "2 положения", "2 положення", "2 positions"),
    (4, "4 положения", "4 положення", "4 positions"), (5, "5 положений", "5 положень", "5 positions"),
    (11, "11 положений", "11 положень", "11 positions"), (12, "12 положений", "12 положень", "12 positions"),
    (14, "14 положений", "14 положень", "14 positions"), (21, "21 положение", "21 положення", "21 positions"),
    (22, "22 положения", "22 положення", "22 positions"), (24, "24 положения", "24 положення", "24 positions"),
    (111, "111 положений", "111 положень", "111 positions"), (0, "0 положений", "0 положень", "0 positions"),
    (2.5, "2,5 положения", "2,5 положення", "2.5 positions")])
def test_the_noun_after_a_count_as_each_language_chooses_it(n, ru, uk, en):
    """A catalogue's {n:|form|form|form}: the count and the noun's form the language puts after it
    (Russian and Ukrainian: one 1, 21; few 2-4, 22-24; many 0, 5-20, 25-30; a fraction the few
    form), in the report's and the messages' formatters alike; the rule is the numbers
    catalogue's `format.plural`."""
    from tmm_cli import numfmt
    from tmm_cli.messages import _Formatter, catalogue
    for lang, want, forms in (("ru", ru, "|положение|положения|положений"), ("uk", uk, "|положення|положення|положень"),
                              ("en", en, "|position|positions")):
        assert numfmt.format_text("{n:" + forms + "}", lang, n=n) == want
        assert _Formatter(catalogue(lang)["terms"], lang).format("{n:" + forms + "}", n=n) == want


def test_counted_nouns_of_the_catalogues_agree_with_their_count():
    """The texts that follow a count with a noun: the engine's 24 hand positions were
    '24 положений'; a text of 1 character, a cam phase in 4 parts, 3 satellites that do not
    assemble read right in every language."""
    from tmm_cli.messages import render
    from tmm_cli.report.i18n import translate
    assert "(24 положения через" in translate("dyn.hand", "ru", n=24, step="30", J=1, Jem=1, Jm=1, err=0, Jacc=1)
    assert "(24 положення через" in translate("dyn.hand", "uk", n=24, step="30", J=1, Jem=1, Jm=1, err=0, Jacc=1)
    assert "(12 положений через" in translate("dyn.hand", "ru", n=12, step="30", J=1, Jem=1, Jm=1, err=0, Jacc=1)
    assert "(1 position every" in translate("dyn.hand", "en", n=1, step="30", J=1, Jem=1, Jm=1, err=0, Jacc=1)
    assert "на 4 равные части" in translate("cam.division_caption", "ru", n=4)
    assert "на 6 рівних частин" in translate("cam.division_caption", "uk", n=6)
    assert "в 21 положении" in translate("kin.positions_caption", "ru", n=21)
    assert render("input.text_long", {"n": 1, "limit": 0}, "en").startswith("a text of 1 character:")
    assert render("input.text_long", {"n": 22, "limit": 0}, "ru").startswith("текст из 22 символов:")
    assert render("kinetostatics.fail.indeterminate", {"links": "2, 3", "equations": 3, "unknowns": 4},
                  "ru").endswith("(3 уравнения, 4 неизвестные составляющие реакций)")
    assert render("input.too_short", {"field_type": "список", "min_length": 1, "actual_length": 0},
                  "uk").startswith("список: потрібно щонайменше 1 елемент,")
    # pydantic's own English says 'at least 1 item': the catalogue's English is the same text (so
    # the coded message, shown in every language, is the one used: task._coded_issue)
    assert render("input.too_short", {"field_type": "List", "min_length": 1, "actual_length": 0},
                  "en") == "List should have at least 1 item after validation, not 0"
    # the structure's errors (a newcomer's trial read "механизму нужно начальных звеньев: 3",
    # "звенья link4 входят"): the count with its noun, the noun and verb by the list's length
    assert render("structure.fail.inputs", {"W": 2, "n": 4, "p5": 5, "p4": 0}, "ru").endswith(
        "механизму нужно 2 начальных звена")
    assert render("structure.fail.inputs", {"W": 2, "n": 4, "p5": 5, "p4": 0}, "uk").endswith(
        "механізму потрібно 2 початкові ланки")
    assert "звено link4 входит только" in render("structure.fail.idle", {"links": ["link4"]}, "ru")
    assert "звенья a, b входят только" in render("structure.fail.idle", {"links": ["a", "b"]}, "ru")
    assert "ланка link4 входить лише" in render("structure.fail.idle", {"links": ["link4"]}, "uk")
    assert render("differential.assembly", {"k": 3, "fits": "2"}, "ru").startswith(
        "дифференциал: 3 равномерно расположенных сателлита не собираются")
    assert render("differential.assembly", {"k": 5, "fits": "2"}, "uk").startswith(
        "диференціал: 5 рівномірно розташованих сателітів не збираються")
