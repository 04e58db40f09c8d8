"""Move a language-keyed table of a module into the catalogues (tmm_cli/locales/<lang>/<topic>.yaml).

    python tools/extract_catalogue.py MODULE VAR TOPIC KEY [--replace] [--split-uk]

imports MODULE, takes the value of its module-level VAR -- ``{lang: table}``, as the module
holds it once imported (literal and later updates, e.g. a language added by another module)
-- and writes ``table`` of every language under KEY of ``locales/<lang>/TOPIC.yaml`` (the
file's other tables kept, in their order; the table's key order kept).  Tuples become lists.
The written file is read back and compared with the value.  ``--replace`` rewrites the
statement ``VAR = {...}`` in MODULE's source to ``VAR = locales.table("TOPIC", "KEY")``
(further updates of VAR in the source are left for the hand to remove).

This is the script issue 41 moved the Python string tables with; it stays for a table a
branch still adds in Python.  For a three-language YAML file beside a module use
tools/split_catalogue.py.
"""
from __future__ import annotations

import argparse
import ast
import importlib
import sys
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[1]
LOCALES = ROOT / "tmm_cli" / "locales"


def plain(value):
    """The value with tuples as lists (YAML has no tuples)."""
    if isinstance(value, dict):
        return {k: plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    return value


def dump(data: dict) -> str:
    return yaml.safe_dump(data, allow_unicode=True, sort_keys=False, width=10 ** 6, default_flow_style=False)


def header(topic: str, lang: str) -> str:
    return (f"# tmm's texts in language '{lang}', topic '{topic}' (read through tmm_cli/locales;\n"
            f"# docs/language.md says how to add or change a text)\n")


def write(topic: str, key: str, per_lang: dict) -> None:
    for lang, table in per_lang.items():
        path = LOCALES / lang / f"{topic}.yaml"
        path.parent.mkdir(parents=True, exist_ok=True)
        data = yaml.safe_load(path.read_text(encoding="utf-8")) if path.is_file() else {}
        data = data or {}
        data[key] = plain(table)
        text = header(topic, lang) + dump(data)
        assert yaml.safe_load(text) == data, (path, key)
        path.write_text(text, encoding="utf-8")


def replace(module: str, var: str, topic: str, key: str) -> None:
    path = ROOT / (module.replace(".", "/") + ".py")
    if not path.is_file():
        path = ROOT / module.replace(".", "/") / "__init__.py"
    src = path.read_text(encoding="utf-8")
    tree = ast.parse(src)
    for node in tree.body:
        targets = node.targets if isinstance(node, ast.Assign) else [node.target] if isinstance(node, ast.AnnAssign) else []
        if any(isinstance(t, ast.Name) and t.id == var for t in targets):
            lines = src.splitlines(keepends=True)
            ann = ""
            if isinstance(node, ast.AnnAssign):
                ann = ": " + ast.get_source_segment(src, node.annotation)
            new = f'{var}{ann} = locales.table("{topic}", "{key}")\n'
            lines[node.lineno - 1:node.end_lineno] = [new]
            path.write_text("".join(lines), encoding="utf-8")
            return
    sys.exit(f"{path}: no module-level assignment to {var}")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("module")
    ap.add_argument("var")
    ap.add_argument("topic")
    ap.add_argument("key")
    ap.add_argument("--replace", action="store_true")
    a = ap.parse_args(argv)
    sys.path.insert(0, str(ROOT))
    value = getattr(importlib.import_module(a.module), a.var)
    assert isinstance(value, dict) and "en" in value and all(isinstance(k, str) and len(k) == 2 for k in value), \
        f"{a.module}.{a.var} is not keyed by language"
    write(a.topic, a.key, value)
    if a.replace:
        replace(a.module, a.var, a.topic, a.key)


if __name__ == "__main__":
    main()
