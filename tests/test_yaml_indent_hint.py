"""A misindented line: YAML reports the line after it ('mapping values are not allowed here');
the message also names both lines and their columns, so a student sees which one to fix."""
from __future__ import annotations

import pytest

from tmm_cli.errors import TaskError
from tmm_cli.yamlload import load_yaml

GOOD = "schema: tmm/1\npositions:\n  count: 12\n  zero: extreme\n  output: piston\n"


@pytest.mark.parametrize("text, lines", [
    (GOOD.replace("  count: 12", " count: 12"), "lines 3 and 4"),
    (GOOD.replace("  zero: extreme", "   zero: extreme"), "lines 3 and 4"),
])
def test_misindented_key_names_both_lines(text, lines):
    with pytest.raises(TaskError) as ei:
        load_yaml("t.yaml", text=text)
    msg = str(ei.value) + " ".join(str(i) for i in getattr(ei.value, "issues", []))
    assert "YAML syntax error" in msg and "indentation" in msg and lines in msg, msg


def test_no_hint_for_an_unclosed_bracket():
    with pytest.raises(TaskError) as ei:
        load_yaml("t.yaml", text="schema: tmm/1\nmechanism:\n  ground: {O: [0, 0]\n  links: {}\n")
    msg = str(ei.value) + " ".join(str(i) for i in getattr(ei.value, "issues", []))
    assert "YAML syntax error" in msg and "indentation" not in msg, msg
