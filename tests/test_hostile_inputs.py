"""Hostile inputs of issue 37 (items 4 to 13): no input hangs, crashes, costs without bound
or mixes two runs. Each test fails without its fix."""
from __future__ import annotations

import csv
import json
import os
import subprocess
import sys
import time
from pathlib import Path

import pytest
from typer.testing import CliRunner

from tmm_cli.cli import app

runner = CliRunner()
ROOT = Path(__file__).resolve().parents[1]
TMM = [sys.executable, "-m", "tmm_cli"]

GEARS = """\
schema: tmm/1
title: zero-shift pair
student: {name: A. Student, group: MM-1}
gears: {m: 4 mm, z: [14, 30], x: [0, 0]}
"""
R1, R2 = 0.028, 0.060          # m z / 2 of the zero-shift pair


def _write(tmp_path: Path, name: str, text: str) -> Path:
    p = tmp_path / name
    p.write_text(text, encoding="utf-8")
    return p


# ---------------------------------------------------------------- item 12
def test_negative_index_is_an_unknown_path(tmp_path):
    """`gears.r[-1]` is no quantity of results.json (Python's count from the end is not the
    course's): unknown_path, never graded against r[1]."""
    from tmm_cli.results import lookup
    results = {"gears": {"r": [R1, R2]}}
    with pytest.raises(KeyError):
        lookup(results, "gears.r[-1]")
    assert lookup(results, "gears.r[1]") == R2
    f = _write(tmp_path, "g.yaml", GEARS + f"answers: {{'gears.r[-1]': {R2}, 'gears.r[1]': {R2}}}\n")
    res = runner.invoke(app, ["check", str(f), "--out", str(tmp_path / "o")])
    assert res.exit_code == 1, res.output
    with open(tmp_path / "o" / "check.csv", encoding="utf-8", newline="") as fh:
        rows = {r["path"]: r["status"] for r in csv.DictReader(fh)}
    assert rows == {"gears.r[-1]": "unknown_path", "gears.r[1]": "ok"}
