"""The report's words: ``translate(key, lang)`` over the catalogues' ``words`` tables.

The words live in the catalogues, one set per language (:mod:`tmm_cli.locales`:
``tmm_cli/locales/<lang>/<topic>.yaml``, the table ``words`` of every topic merged into
:data:`STRINGS`).  Keys are dotted, ``"<section>.<name>"`` (``"kin.velocity_plan"``),
common words live under ``"common."``.  Missing keys fall back to English, then to the key
itself, so a missing translation never breaks a report.

A section reads its own table as ``I18N = locales.table("<section>", "words")``; the
section loader registers it again (:func:`register`, later registrations win), as it did
when the tables were Python dicts.  Russian terms follow the standard course books
(Artobolevsky; Popov & Timofeev; Frolov), the Ukrainian ones the Ukrainian textbooks;
docs/glossary.yaml holds the terms.
"""
from __future__ import annotations

from .. import locales

LANGS = locales.LANGS

# the tables registered by the sections (applied to a language's words when it is read)
_REGISTERED: list[dict[str, dict[str, str]]] = []


class _Strings(dict):
    """``{lang: {key: text}}``, a language's words read from the catalogues when first asked
    for (a report reads English and its own language only), the registered tables over them."""

    def __missing__(self, lang: str) -> dict[str, str]:
        if lang not in LANGS:
            raise KeyError(lang)
        words = locales.words(lang)
        for table in _REGISTERED:
            words.update(table.get(lang) or {})
        self[lang] = words
        return words

    def get(self, lang, default=None):
        try:
            return self[lang]
        except KeyError:
            return default

    def __contains__(self, lang) -> bool:
        return lang in LANGS or dict.__contains__(self, lang)


STRINGS: dict[str, dict[str, str]] = _Strings()


def words_beside(module_file: str) -> dict[str, dict[str, str]]:
    """A section's words ``{lang: {key: text}}``: the catalogues' ``words`` of the topic named
    as the module (``x.py`` -> ``locales/<lang>/x.yaml``), with an old-style three-language
    ``x.yaml`` beside the module laid over them if one is there (:func:`tmm_cli.locales.beside`;
    ``tools/split_catalogue.py`` moves such a file into the catalogues)."""
    return locales.beside(module_file)


def register(table: dict[str, dict[str, str]]) -> None:
    """Merge ``{lang: {key: text}}`` into the tables (later registrations win)."""
    _REGISTERED.append(table)
    for lang, words in table.items():
        if dict.__contains__(STRINGS, lang):          # a language read already
            STRINGS[lang].update(words)
        elif lang not in LANGS:                       # a language without catalogues
            dict.__setitem__(STRINGS, lang, dict(words))


def translate(key: str, lang: str, **kw) -> str:
    """Text for ``key`` in ``lang`` (fallback: English, then the key itself).

    Keyword arguments are substituted with ``str.format`` (a number in ``lang``'s writing:
    the decimal comma in ru and uk, :mod:`tmm_cli.numfmt`).
    """
    text = STRINGS.get(lang, {}).get(key)
    if text is None:
        text = STRINGS["en"].get(key, key)
    if kw:
        from ..numfmt import format_text
        try:
            text = format_text(text, lang, **kw)
        except (KeyError, IndexError, ValueError):
            pass
    return text
