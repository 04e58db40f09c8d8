"""Every ```yaml block of README.md and docs/*.md is a task tmm accepts, checked as `tmm validate`
checks a file (tmm_cli.orchestrate.prepare: the schema, the references, the linkage assembling
over the cycle; nothing is computed, so this takes seconds):

- a block with `schema:` is a whole task, validated as written;
- any other block is a fragment (one or more sections), validated merged into a small base task:
  its sections replace the base's. The base is chosen by the sections the block gives (`BASES`:
  a slider-crank with a drive and a load by default; a four-bar for `balancing`; the header and
  a drive for `synthesis`, which generates the mechanism; the header alone for the sections
  that stand alone). An HTML comment right before the block (mkdocs does not show it) may name
  another base: `<!-- base: tasks/NAME.yaml -->`, a shipped task, or `<!-- base: above -->`, the
  nearest whole task above it on the same page (a tutorial's task the block is appended to);
- a block that shows a mistake on purpose is marked `<!-- invalid: TEXT -->` and must fail
  validation with a message containing TEXT (the message the page quotes).

The YAML is read by tmm's own reader (YAML 1.2: `on:` is a key, not `true`), so a block is read
as a student's task file would be."""
from __future__ import annotations

import re
from pathlib import Path

import pytest
import yaml

from tmm_cli.errors import StageError, TaskError
from tmm_cli.orchestrate import prepare
from tmm_cli.yamlload import load_yaml

ROOT = Path(__file__).resolve().parents[1]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]

# a ```yaml fence (perhaps indented, in a list item) with the HTML comments right before it
BLOCK = re.compile(r"(?P<notes>(?:^[ \t]*<!--.*?-->[ \t]*\n)*)^(?P<indent>[ \t]*)```yaml[ \t]*\n"
                   r"(?P<body>.*?)^(?P=indent)```", re.M | re.S)
NOTE = re.compile(r"<!--\s*(base|invalid):\s*(.*?)\s*-->", re.S)

_HEADER = {"schema": "tmm/1", "title": "Base of a docs example"}
_SLIDER_CRANK = {
    **_HEADER,
    "mechanism": {"ground": {"O": [0, 0]}, "links": {
        "crank": {"points": ["O", "A"], "length": "100 mm", "mass": 5, "J": 0.05},
        "rod": {"points": ["A", "B"], "length": "400 mm", "mass": 8, "J": 0.12},
        "slider": {"slider": "B", "guide": {"through": "O", "angle": 0}, "mass": 20}}},
    "drive": {"link": "crank", "speed": "120 rpm", "direction": "ccw"},
    "loads": {"forces": [{"on": "slider", "kind": "resistance", "magnitude": 1000}]},
}
_FOUR_BAR = {
    **_HEADER,
    "mechanism": {"ground": {"O": [0, 0], "O1": ["300 mm", 0]}, "links": {
        "crank": {"points": ["O", "A"], "length": "80 mm", "mass": 1},
        "coupler": {"points": ["A", "B"], "length": "300 mm", "mass": 2},
        "rocker": {"points": ["O1", "B"], "length": "250 mm", "mass": 1.5}}},
    "drive": {"link": "crank", "speed": "120 rpm", "direction": "ccw"},
}
# (the sections a fragment gives, its base): the first whose section the fragment has
BASES = [
    ({"cam", "gears", "planetary", "differential", "dof2", "drive_train"}, _HEADER),
    ({"synthesis"}, {**_HEADER, "drive": _SLIDER_CRANK["drive"]}),
    ({"balancing"}, _FOUR_BAR),
]


def _blocks() -> list:
    return list(_each_block())


def _each_block():
    for page in PAGES:
        text = page.read_text(encoding="utf-8")
        whole = None                    # the nearest whole task above, for `base: above`
        for m in BLOCK.finditer(text):
            indent = len(m.group("indent"))
            body = "".join(ln[indent:] for ln in m.group("body").splitlines(keepends=True))
            line = text.count("\n", 0, m.start("body")) + 1
            notes = dict(NOTE.findall(m.group("notes")))
            yield pytest.param(page, line, body, notes, whole, id=f"{page.relative_to(ROOT)}:{line}")
            if re.search(r"(?m)^schema:", body):
                whole = body


def _base(body: str, notes: dict, above: str | None) -> dict | None:
    """The base task (a dict) the fragment ``body`` is merged into; None: a whole task."""
    data, _ = load_yaml(Path("fragment.yaml"), text=body)
    assert isinstance(data, dict), "a docs YAML block is a mapping of sections"
    if "schema" in data:
        return None
    base = notes.get("base")
    if base == "above":
        assert above is not None, "`base: above` with no whole task above it on the page"
        return load_yaml(Path("above.yaml"), text=above)[0]
    if base:
        return load_yaml(ROOT / base)[0]
    return next((b for sections, b in BASES if sections & data.keys()), _SLIDER_CRANK)


def _task_text(body: str, base: dict | None) -> str:
    """The task validated: the block as written after the base's other sections (so the block's
    own text, read by tmm's reader, is what is checked)."""
    if base is None:
        return body
    data, _ = load_yaml(Path("fragment.yaml"), text=body)
    rest = {k: v for k, v in base.items() if k not in data}
    return yaml.safe_dump(rest, allow_unicode=True, sort_keys=False) + body


def _problem(page: Path, line: int, text: str) -> str | None:
    """The message validation gives (None: the task is valid)."""
    try:
        prepare(Path(f"{page.name}-line{line}.yaml"), text=text)
    except (TaskError, StageError) as exc:
        return str(exc)
    return None


def test_the_blocks_are_found():
    found = list(_blocks())
    assert len(found) >= 25
    # the task file's page holds most of them: one section each at least
    assert sum(p.values[0].name == "task-file.md" for p in found) >= 20


def _verdict(page: Path, line: int, body: str, notes: dict, above: str | None) -> str | None:
    """What is wrong with the block (None: nothing): a problem validation finds in a block not
    marked invalid, or a block marked invalid that validates or fails with another message."""
    text = _task_text(body, _base(body, notes, above))
    problem = _problem(page, line, text)
    if "invalid" in notes:
        if problem is None:
            return f"marked invalid, but validates:\n{text}"
        if notes["invalid"] not in problem:
            return f"fails, but not with the message its mark quotes ({notes['invalid']!r}):\n{problem}"
        return None
    return None if problem is None else f"{problem}\n--- the task validated:\n{text}"


@pytest.mark.parametrize("page, line, body, notes, above", _blocks())
def test_docs_yaml_block_validates(page, line, body, notes, above):
    verdict = _verdict(page, line, body, notes, above)
    assert verdict is None, verdict


def test_the_marks_are_read_and_kept():
    """A mark is found before its block (indented too), and the verdict keeps it: a block marked
    invalid that validates, or that fails with another message, is a failure."""
    page = ("Text.\n<!-- base: above -->\n```yaml\ngears: {m: 5 mm, z: [13, 28]}\n```\n"
            "  <!-- invalid: tolerance -->\n  ```yaml\n  tolerance: 0.05\n  ```\n")
    found = [(m.group("body"), dict(NOTE.findall(m.group("notes")))) for m in BLOCK.finditer(page)]
    assert [n for _, n in found] == [{"base": "above"}, {"invalid": "tolerance"}]
    gears = "gears: {m: 5 mm, z: [13, 28]}\n"
    wrong = gears + "tolerance: 0.05\n"
    where = (ROOT / "x.md", 1)
    assert _verdict(*where, gears, {}, None) is None
    assert _verdict(*where, wrong, {}, None) is not None
    assert _verdict(*where, wrong, {"invalid": "tolerance"}, None) is None
    assert _verdict(*where, wrong, {"invalid": "no such message"}, None) is not None
    assert _verdict(*where, gears, {"invalid": "tolerance"}, None) is not None
