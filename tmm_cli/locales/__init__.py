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
where present), and reads a file once per process.  What a file holds is kept between runs as
Python keeps bytecode: pickled beside it in ``__pycache__`` (or under ``PYTHONPYCACHEPREFIX``;
nothing is written where bytecode is not), used while the file's size and modification time
and the Python version are those it was read with (a report run reads 60-75 catalogues: the
pickles load in a sixth of the time PyYAML takes to parse them; :mod:`tmm_cli.kept`).
"""
from __future__ import annotations

import copy
import functools
import sys
from pathlib import Path
from stat import S_ISREG
from typing import Any

from .. import kept

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


_FORMAT = 1            # the kept catalogues' layout: a new number makes every kept one stale


@functools.cache
def _read(lang: str, name: str) -> dict:
    path = DIR / lang / f"{name}.yaml"
    try:
        st = path.stat()
    except OSError:
        return {}
    if not S_ISREG(st.st_mode):
        return {}
    stamp = (_FORMAT, sys.version, st.st_size, st.st_mtime_ns)
    path_kept = _kept_path(path)
    data = kept.read(path_kept, stamp)
    if data is kept.MISSING:
        import yaml
        data = yaml.load(path.read_text(encoding="utf-8"), Loader=getattr(yaml, "CSafeLoader", yaml.SafeLoader)) or {}
        kept.write(path_kept, stamp, data)
    return data


def _kept_path(path: Path) -> Path:
    """Where the tables of catalogue ``path`` are kept: its bytecode's place, as if it were a
    module (``<lang>/__pycache__/<topic>.<python>.pickle``)."""
    from importlib.util import cache_from_source
    return Path(cache_from_source(str(path.with_suffix(".py")))).with_suffix(".pickle")


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
