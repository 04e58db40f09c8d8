"""The project is self-contained: what users get (the package, its messages and --help,
the report templates, the README, docs/, the example tasks and the benchmarks) cites
only the project's own documents -- never the development contract or methods notes
("SPEC", "METHODS") or files outside the repository ("../shared", reference texts)."""
from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
FORBIDDEN = re.compile(r"\bSPEC\b|\bMETHODS\b|\.\./shared|/work/shared|\breference/[\w.-]+\.txt")
PLACES = ["tmm_cli", "templates", "docs", "tasks", "examples", "benchmarks", "README.md"]
SUFFIXES = {".py", ".j2", ".html", ".css", ".md", ".yaml", ".yml", ".txt", ".sh", ".csv", ".toml"}


def _user_files() -> list[Path]:
    files = []
    for place in PLACES:
        p = ROOT / place
        if p.is_file():
            files.append(p)
        elif p.is_dir():
            files += sorted(f for f in p.rglob("*") if f.is_file() and f.suffix in SUFFIXES
                            and "__pycache__" not in f.parts)
    return files


def _hits(text: str) -> list[tuple[int, str]]:
    return [(i, line.strip()) for i, line in enumerate(text.splitlines(), 1)
            if FORBIDDEN.search(line)]


def test_the_pattern_catches_every_kind_of_outside_citation():
    # the check itself must be able to fail
    for bad in ("(SPEC 1)", "see METHODS 4", "`../shared/SPEC.md`", "METHODS.md section 2",
                "(reference/rotary-impact-mechanism-ocr.txt)"):
        assert _hits(bad), bad
    for good in ("docs/methods.md §4", "FLYWHEEL_METHODS = (", "GearSpec", "spec.py"):
        assert not _hits(good), good


def test_user_files_are_found():
    names = {f.relative_to(ROOT).as_posix() for f in _user_files()}
    assert {"README.md", "docs/methods.md", "tmm_cli/cli.py", "templates/report.html.j2"} <= names


@pytest.mark.parametrize("path", _user_files(), ids=lambda p: p.relative_to(ROOT).as_posix())
def test_no_citation_of_documents_users_do_not_have(path):
    hits = _hits(path.read_text(encoding="utf-8", errors="replace"))
    assert not hits, f"{path.relative_to(ROOT)} cites documents users do not have: {hits}"


def test_methods_doc_has_the_sections_the_code_cites():
    """Every 'docs/methods.md §N' (or 'methods.md §N.M') cited anywhere exists as a heading."""
    doc = (ROOT / "docs" / "methods.md").read_text(encoding="utf-8")
    headings = set(re.findall(r"^#{2,3} (\d+(?:\.\d+)?)\.? ", doc, flags=re.M))
    cited = set()
    for f in _user_files():
        for m in re.finditer(r"methods\.md §(\d+(?:\.\d+)?)(?: and §(\d+(?:\.\d+)?))?",
                             f.read_text(encoding="utf-8", errors="replace")):
            cited |= {g for g in m.groups() if g}
    assert cited, "nothing cites docs/methods.md"
    missing = sorted(cited - headings)
    assert not missing, f"cited sections missing in docs/methods.md: {missing}"
