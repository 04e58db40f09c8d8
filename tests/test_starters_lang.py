"""`tmm new KIND --lang ru|uk`: the starter task with its comments and title in the language and
the same data as the English one (a student who starts in Russian computes the same variant),
line for line; every one a valid task; an unknown kind said in the language."""
from __future__ import annotations

import re
from pathlib import Path

import pytest
import yaml
from typer.testing import CliRunner

from tmm_cli.cli import app
from tmm_cli.commands import STARTERS

ROOT = Path(__file__).resolve().parents[1]
DIR = ROOT / "tmm_cli" / "starters"
runner = CliRunner()
CYR = re.compile("[\u0400-\u04ff]")


def _comments(text: str) -> list[str]:
    """The comment of each line ('' where none): the text after a '#' outside quotes."""
    out = []
    for line in text.splitlines():
        m = re.match(r"""^((?:[^#'"]|'[^']*'|"[^"]*")*)#(.*)$""", line)
        out.append(m.group(2) if m else "")
    return out


@pytest.mark.parametrize("lang", ["ru", "uk"])
@pytest.mark.parametrize("kind", STARTERS)
def test_a_starter_in_the_language_is_the_english_data(kind, lang):
    en_text = (DIR / f"{kind}.yaml").read_text(encoding="utf-8")
    text = (DIR / lang / f"{kind}.yaml").read_text(encoding="utf-8")
    en, tr = yaml.safe_load(en_text), yaml.safe_load(text)
    assert CYR.search(str(tr["title"])) and tr["title"] != en["title"]
    for d in (en, tr):
        d.pop("title")
        d.pop("student", None)
    assert tr == en                                   # the same variant, whatever the language
    assert len(text.splitlines()) == len(en_text.splitlines())
    for k, (a, b) in enumerate(zip(_comments(en_text), _comments(text))):
        if re.search(r"[A-Za-z]{3}", re.sub(r"`[^`]*`|tmm \S+ \S+", "", a)):
            assert CYR.search(b), (kind, lang, k + 1, a, b)     # each comment with words translated


@pytest.mark.parametrize("lang", ["ru", "uk"])
def test_every_starter_in_the_language_is_a_valid_task(lang, tmp_path):
    import tmm_cli
    for kind in STARTERS:
        f = tmp_path / f"{kind}.yaml"
        f.write_text((DIR / lang / f"{kind}.yaml").read_text(encoding="utf-8"), encoding="utf-8")
        tmm_cli.load_task(f)


def test_new_prints_the_starter_in_the_language():
    res = runner.invoke(app, ["new", "full", "--lang", "ru"])
    assert res.exit_code == 0 and res.stdout == (DIR / "ru" / "full.yaml").read_text(encoding="utf-8")
    res = runner.invoke(app, ["new", "full"])
    assert res.exit_code == 0 and res.stdout == (DIR / "full.yaml").read_text(encoding="utf-8")
    res = runner.invoke(app, ["new", "rocker", "-l", "uk"])
    assert res.exit_code == 2 and "помилка: невідомий вид «rocker»; можливо, малося на увазі «cam_rocker»?" in res.output
    res = runner.invoke(app, ["new", "rocker"])
    assert res.exit_code == 2 and "error: unknown kind 'rocker'; did you mean 'cam_rocker'? choose from" in res.output


@pytest.mark.parametrize("kind", [k for k in STARTERS if k in ("linkage", "full", "synthesis")])
def test_a_starter_does_not_warn_about_its_own_working_stroke(kind, tmp_path):
    """A student's first run of a starter, unchanged, gives no quick-working-stroke warning
    (the six-bar starter's slider works downward, K = 1.28 > 1; it said forward, K = 0.78)."""
    import tmm_cli
    f = tmp_path / f"{kind}.yaml"
    f.write_text((DIR / f"{kind}.yaml").read_text(encoding="utf-8"), encoding="utf-8")
    res = tmm_cli.run(tmm_cli.load_task(f))
    assert not [m for m in res["messages"] if m["code"] == "positions.quick_working"], res["warnings"]
    if res.get("positions", {}).get("K") is not None:
        assert res["positions"]["K"] >= 1.0 - 1e-12      # a central slider-crank: 1
