"""Move texts of the old, three-language kind into the catalogues (tmm_cli/locales/<lang>/<topic>.yaml).

    python tools/split_catalogue.py tmm_cli/report/sections/foo.yaml            # beside-the-module file
    python tools/split_catalogue.py tmm_cli.report.sections.cam:I18N             # a Python table
    python tools/split_catalogue.py tmm_cli.report.i18n_uk:UK --lang uk         # one language's table
    python tools/split_catalogue.py /tmp/gears.py:I18N --topic gears            # a file's literal table

SOURCE is a YAML file ``{en: {key: text}, ru: {...}, uk: {...}}`` (the kind a section kept
beside its module and read with ``i18n.words_beside(__file__)``), or ``module:VAR``, a
module-level table of an importable module, or ``file.py:VAR``, the literal table of a
Python file (read, not imported: the literal only, not later updates); a table
``{lang: table}`` -- or, with ``--lang``, one language's table.  Its keys are merged into table TABLE (default ``words``) of topic TOPIC
(default: the YAML file's stem, the module's last name) in every language's file: a new
key is appended, a key the catalogue has is given the source's text (printed as changed),
no key is removed.  For the ``words`` tables a key already in another topic's English words
goes to that topic (the report's words are one namespace: a key lives in one topic), so a
branch's additions to the old central tables (report/i18n.py, i18n_uk.py) land beside
their English.  A language the catalogues lack gets its folder.  ``--remove`` deletes a
YAML source afterwards.  The files are rewritten with their leading comment kept (comments
inside a file are not kept); every file written is read back and compared.

This is how words that branches made before the catalogues add are merged: after the merge,
run it on each beside-the-module YAML file (then delete the file: ``words_beside`` reads
the catalogues, and still lays such a file over them until it is moved) and on a Python
table a merge brought back (then replace the table by ``locales.table(...)`` as
tools/extract_catalogue.py does).
"""
from __future__ import annotations

import argparse
import importlib
import sys
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[1]
LOCALES = ROOT / "tmm_cli" / "locales"


def _plain(value):
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    return value


def _dump(data: dict) -> str:
    return yaml.safe_dump(data, allow_unicode=True, sort_keys=False, width=10 ** 6, default_flow_style=False)


def read_source(source: str, lang: str | None = None) -> tuple[dict, str]:
    """({lang: table}, default topic) of a YAML file or ``module:VAR``."""
    if ":" in source and source.split(":", 1)[0].endswith(".py"):
        # a Python file's literal table, read without importing it (e.g. `git show
        # branch:path/x.py > /tmp/x.py` of a branch whose module a merge brought into conflict)
        import ast
        path, var = source.split(":", 1)
        tree = ast.parse(Path(path).read_text(encoding="utf-8"))
        nodes = [n for n in tree.body if isinstance(n, (ast.Assign, ast.AnnAssign)) and any(
            isinstance(t, ast.Name) and t.id == var for t in (n.targets if isinstance(n, ast.Assign) else [n.target]))]
        if not nodes:
            raise SystemExit(f"{path}: no module-level assignment to {var}")
        value = ast.literal_eval(nodes[0].value)
        topic = Path(path).stem
    elif ":" in source and not Path(source).exists():
        mod, var = source.split(":", 1)
        sys.path.insert(0, str(ROOT))
        value = getattr(importlib.import_module(mod), var)
        topic = mod.rsplit(".", 1)[-1]
    else:
        path = Path(source)
        value = yaml.safe_load(path.read_text(encoding="utf-8")) or {}
        topic = path.stem
    value = _plain(value)
    if lang:
        value = {lang: value}
    if not isinstance(value, dict) or not all(isinstance(k, str) and isinstance(v, dict) for k, v in value.items()):
        raise SystemExit(f"{source}: not a table keyed by language ({{en: {{...}}, ru: {{...}}}}); "
                         f"give --lang for one language's table")
    return value, topic


def _read(path: Path) -> tuple[str, dict]:
    if not path.is_file():
        return "", {}
    text = path.read_text(encoding="utf-8")
    head = "".join(line for line in text.splitlines(keepends=True)[:10] if line.startswith("#"))
    return head, yaml.safe_load(text) or {}


def _owners(locales: Path, table: str) -> dict[str, str]:
    """{key: topic} of every key of the English ``table`` tables."""
    out = {}
    for path in sorted((locales / "en").glob("*.yaml")):
        for key in (_read(path)[1].get(table) or {}):
            out.setdefault(key, path.stem)
    return out


def merge(per_lang: dict, topic: str, table: str = "words", locales: Path = LOCALES,
          route: bool | None = None) -> list[str]:
    """Merge ``{lang: {key: value}}`` into the catalogues; returns the lines of a report."""
    route = table == "words" if route is None else route
    owners = _owners(locales, table) if route else {}
    # the English owner of a key decides its topic in every language
    target = {key: owners.get(key, topic) for words in per_lang.values() for key in words}
    report = []
    for lang, words in per_lang.items():
        by_topic: dict[str, dict] = {}
        for key, value in words.items():
            by_topic.setdefault(target[key], {})[key] = value
        for name, part in by_topic.items():
            path = locales / lang / f"{name}.yaml"
            head, data = _read(path)
            head = head or (f"# tmm's texts in language '{lang}', topic '{name}' (read through tmm_cli/locales;\n"
                            f"# docs/language.md says how to add or change a text)\n")
            old = data.setdefault(table, {})
            added = changed = 0
            for key, value in part.items():
                if key not in old:
                    added += 1
                elif old[key] != value:
                    changed += 1
                    report.append(f"changed {lang}/{name}.yaml {table}.{key}: {old[key]!r} -> {value!r}")
                old[key] = value
            text = head + _dump(data)
            if yaml.safe_load(text) != data:
                raise SystemExit(f"{path}: the written file does not read back as written")
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(text, encoding="utf-8")
            report.append(f"{lang}/{name}.yaml {table}: {added} added, {changed} changed")
    return report


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("source", help="a three-language YAML file, or module:VAR")
    ap.add_argument("--topic", help="the topic (default: the file's stem / the module's last name)")
    ap.add_argument("--table", default="words", help="the table of the topic (default: words)")
    ap.add_argument("--lang", help="the source is this one language's table")
    ap.add_argument("--no-route", action="store_true", help="keep every key in TOPIC (no routing by owner)")
    ap.add_argument("--remove", action="store_true", help="delete the YAML source afterwards")
    ap.add_argument("--locales", type=Path, default=LOCALES, help=argparse.SUPPRESS)
    a = ap.parse_args(argv)
    per_lang, topic = read_source(a.source, a.lang)
    for line in merge(per_lang, a.topic or topic, a.table, a.locales, route=False if a.no_route else None):
        print(line)
    if a.remove and Path(a.source).is_file():
        Path(a.source).unlink()
        print(f"removed {a.source}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
