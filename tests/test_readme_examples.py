"""The README's "Examples:" block runs as written, command by command, in a fresh directory
holding only the repository's tasks/ and examples/ (as a newcomer's clone has them): each
command exits 0, or the code its comment names ("# exit 1: ..."), and writes what it says (a
`check` whose comment says how many answers are off has that many outside)."""
from __future__ import annotations

import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent


def _examples_block() -> list[str]:
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    m = re.search(r"^Examples:\n\n```sh\n(.*?)^```", text, re.S | re.M)
    assert m, "README: no 'Examples:' sh block"
    return [ln for ln in m.group(1).splitlines() if ln.strip()]


def test_the_block_is_found():
    lines = _examples_block()
    assert len(lines) >= 6 and all(ln.startswith("tmm ") for ln in lines), lines


@pytest.fixture(scope="module")
def fresh(tmp_path_factory) -> Path:
    d = tmp_path_factory.mktemp("readme")
    shutil.copytree(ROOT / "tasks", d / "tasks")
    shutil.copytree(ROOT / "examples", d / "examples")
    return d


@pytest.mark.parametrize("line", _examples_block())
def test_readme_example_runs(line: str, fresh: Path):
    code = line.split("#", 1)
    want = 0
    if len(code) == 2:
        m = re.match(r"\s*exit (\d+)", code[1])
        if m:
            want = int(m.group(1))
    # `tmm` as this interpreter's module (the test needs no installed script on PATH)
    cmd = f"tmm() {{ {shlex.quote(sys.executable)} -m tmm_cli \"$@\"; }}; {code[0]}"
    p = subprocess.run(["bash", "-c", cmd], cwd=fresh, capture_output=True, text=True, timeout=600)
    assert p.returncode == want, f"{line!r}: exit {p.returncode}\n{p.stdout[-2000:]}\n{p.stderr[-2000:]}"
    assert "Traceback" not in p.stderr, p.stderr[-2000:]
    args = shlex.split(code[0])
    if args[1] == "check" and len(code) == 2:
        # "# exit 1: one answer is off": the table's count says so too
        m = re.search(r"(\w+) answers? (?:is|are) off", code[1])
        if m:
            n = {"one": 1, "two": 2, "three": 3}.get(m.group(1), m.group(1))
            assert f", {n} outside" in p.stdout, p.stdout[-2000:]
    if args[1] == "run":
        # the default folder: out/<task name>/
        out = fresh / (args[args.index("--out") + 1] if "--out" in args else f"out/{Path(args[2]).stem}")
        assert (out / "results.json").is_file()
        fmt = args[args.index("--format") + 1] if "--format" in args else "json,html,pdf"
        assert (out / "report.html").is_file() == ("html" in fmt)
        assert (out / "report.pdf").is_file() == ("pdf" in fmt)
    if ">" in args:
        assert (fresh / args[args.index(">") + 1]).stat().st_size > 0
    if args[1] == "batch":
        out = fresh / args[args.index("--out") + 1]
        assert (out / "summary.csv").is_file()
        rows = (out / "summary.csv").read_text(encoding="utf-8").splitlines()
        assert len(rows) - 1 == len(list((fresh / "tasks").glob("*.yaml")))
    if args[1] == "schema":
        assert (fresh / args[args.index("--out") + 1]).stat().st_size > 1000


def test_ci_runs_exactly_the_quick_starts_test_command():
    """`.ci/run` ends with the README's Quick start test command, character for character (after
    the system packages), and the macOS line is the same command."""
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    quick = re.search(r"^Install and run the whole test suite.*?```sh\n(.*?)\n```", text, re.S | re.M).group(1)
    assert quick.startswith("python3 -m venv .venv && ") and quick.endswith(" && .venv/bin/python -m pytest")
    ci = [ln for ln in (ROOT / ".ci" / "run").read_text(encoding="utf-8").splitlines() if ln.strip()]
    assert ci[-1] == quick
    mac = re.search(r"^\*\*macOS\*\*.*?```sh\n(.*?)\n```", text, re.S | re.M).group(1).splitlines()
    assert mac[-1] == quick
