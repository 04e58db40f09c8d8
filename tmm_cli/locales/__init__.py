"""Every word tmm shows a user, one catalogue set per language: ``tmm_cli/locales/<lang>/<topic>.yaml``.

A topic file is a YAML mapping of named tables: ``words`` (the report's dotted keys ->
text, merged over every topic into :data:`tmm_cli.report.i18n.STRINGS`) and the tables a
module reads as data (``params``, ``units``, ``text``, ...), each ``{key: value}`` where a
value is a string, a list or a nested mapping.  The topic is the module that reads it
(``report`` for the report's shared words, ``cam`` for the cam section, ``forms`` for
``tmm form``, ...).  English is complete; another language may lack a key -- the lookups
fall back to English, then to the key itself (:func:`tmm_cli.report.i18n.translate`).

Adding a language is adding a folder ``locales/<lang>/`` with the same files (tests check
that every key of English exists in every language).  This module is the one loader: the
report's words, the sections' tables, the forms', feedback pages', summaries' and sheets'
tables all come through :func:`topic` / :func:`table`; it imports only PyYAML (C loader
where present), and reads a file once per process.
"""
from __future__ import annotations

import copy
import functools
from pathlib import Path
from typing import Any

DIR = Path(__file__).resolve().parent
# the languages: one folder each, English first
LANGS = ("en",) + tuple(sorted(p.name for p in DIR.iterdir() if p.is_dir() and p.name != "en"
                               and not p.name.startswith(("_", "."))))


# topics without report words (skipped by :func:`words`: the warnings' catalogue is large)
NO_WORDS = ("messages",)


def topics(lang: str = "en") -> tuple[str, ...]:
    """The topic names of ``lang`` (its file names without ``.yaml``), sorted."""
    d = DIR / lang
    return tuple(sorted(p.stem for p in d.glob("*.yaml"))) if d.is_dir() else ()


@functools.cache
def _read(lang: str, name: str) -> dict:
    path = DIR / lang / f"{name}.yaml"
    if not path.is_file():
        return {}
    import yaml
    data = yaml.load(path.read_text(encoding="utf-8"), Loader=getattr(yaml, "CSafeLoader", yaml.SafeLoader))
    return data or {}


def topic(lang: str, name: str) -> dict[str, Any]:
    """The tables of topic ``name`` in ``lang`` (``{}`` when the language lacks the file); a copy."""
    return copy.deepcopy(_read(lang, name))


def table(name: str, key: str, langs: tuple[str, ...] | None = None) -> dict[str, Any]:
    """``{lang: value}``: table ``key`` of topic ``name`` in every language that has it (English
    first) -- the shape of the language-keyed dicts the modules held before the catalogues.
    A copy each call, so a caller may change it."""
    out = {}
    for lang in langs or LANGS:
        data = _read(lang, name)
        if key in data:
            out[lang] = copy.deepcopy(data[key])
    return out


def of(name: str, key: str, lang: str) -> Any:
    """Table ``key`` of topic ``name`` in ``lang``, English's where ``lang`` lacks it: the cached
    table itself (read it, don't change it), for lookups made many times (a batch's pages)."""
    data = _read(lang, name)
    return data[key] if key in data else _read("en", name)[key]


def words(lang: str) -> dict[str, str]:
    """Every ``words`` table of ``lang`` merged: ``report`` first, then the other topics sorted
    by name (a key lives in one topic; tests/test_locales.py checks it); not :data:`NO_WORDS`."""
    out: dict[str, str] = {}
    names = tuple(n for n in topics(lang) if n not in NO_WORDS)
    for name in (("report",) if "report" in names else ()) + tuple(n for n in names if n != "report"):
        out.update(_read(lang, name).get("words") or {})
    return out


def beside(module_file: str) -> dict[str, dict[str, str]]:
    """The old form of a section's words -- ``x.yaml`` beside ``x.py``, ``{lang: {key: text}}``
    -- kept as a shim: the ``words`` of topic ``x`` in every language, with such a file (if one
    is still there, e.g. from a branch made before the catalogues) laid over them.  Move such
    a file's words into the catalogues with ``tools/split_catalogue.py``."""
    stem = Path(module_file).stem
    out = table(stem, "words")
    old = Path(module_file).with_suffix(".yaml")
    if old.is_file():
        import yaml
        for lang, w in (yaml.safe_load(old.read_text(encoding="utf-8")) or {}).items():
            out.setdefault(lang, {}).update(w or {})
    return out


__all__ = ["DIR", "LANGS", "beside", "of", "table", "topic", "topics", "words"]
