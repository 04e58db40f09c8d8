"""mkdocs hooks: the reference pages of the documentation site, generated at build time from
the sources they document, so the site never drifts from the program:

* ``<!-- tmm:fields -->``   every task-file field with its default and meaning (the task model;
  the same table as ``tmm fields``);
* ``<!-- tmm:commands -->`` every command's ``--help`` (the Typer app);
* ``<!-- tmm:messages -->`` every warning and error code with its English text (the catalogue);
* ``<!-- tmm:starter KIND -->`` a starter task as ``tmm new KIND`` prints it.
"""
from __future__ import annotations

import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))


def _cell(text: str) -> str:
    return str(text).replace("|", "\\|").replace("\n", " ")


def fields_table() -> str:
    from tmm_cli.task import field_docs
    rows = ["| field | default | meaning |", "|---|---|---|"]
    for path, default, text in field_docs():
        rows.append(f"| `{path}` | {_cell(default)} | {_cell(text)} |")
    return "\n".join(rows)


def commands_help() -> str:
    from typer.testing import CliRunner

    from tmm_cli.commands import app
    runner = CliRunner()
    names = sorted(c.name or c.callback.__name__ for c in app.registered_commands)
    out = []
    for name in names:
        res = runner.invoke(app, [name, "--help"], env={"COLUMNS": "100", "NO_COLOR": "1", "TERM": "dumb"})
        text = re.sub(r"\x1b\[[0-9;]*m", "", res.output).rstrip()
        out += [f"## `tmm {name}`", "", "```text", text, "```", ""]
    return "\n".join(out)


def messages_table() -> str:
    from tmm_cli.messages import catalogue
    rows = ["| code | English text |", "|---|---|"]
    for code, text in sorted(catalogue("en")["messages"].items()):
        if code == "text":
            continue
        rows.append(f"| `{code}` | {_cell(text)} |")
    return "\n".join(rows)


def starter(kind: str) -> str:
    text = (ROOT / "tmm_cli" / "starters" / f"{kind}.yaml").read_text(encoding="utf-8")
    return f"```yaml\n{text.rstrip()}\n```"


def on_page_markdown(markdown: str, **kwargs) -> str:
    markdown = markdown.replace("<!-- tmm:fields -->", fields_table()) if "<!-- tmm:fields -->" in markdown \
        else markdown
    if "<!-- tmm:commands -->" in markdown:
        markdown = markdown.replace("<!-- tmm:commands -->", commands_help())
    if "<!-- tmm:messages -->" in markdown:
        markdown = markdown.replace("<!-- tmm:messages -->", messages_table())
    return re.sub(r"<!-- tmm:starter (\w+) -->", lambda m: starter(m.group(1)), markdown)
