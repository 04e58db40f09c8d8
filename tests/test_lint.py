"""The code base passes ruff with the project's configuration (pyproject.toml,
[tool.ruff]): pyflakes (unused names, undefined names), pycodestyle's syntax errors, and
no blind `except Exception` without a `noqa: BLE001` that says why."""
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _ruff() -> list[str]:
    try:
        import ruff  # noqa: F401  (the test extra installs it)
    except ImportError:
        exe = shutil.which("ruff")
        if exe is None:
            pytest.fail("ruff is not installed: pip install -e '.[test]'")
        return [exe]
    return [sys.executable, "-m", "ruff"]


def test_ruff_clean():
    p = subprocess.run(_ruff() + ["check", "--no-cache", "tmm_cli", "tests", "benchmarks"], cwd=ROOT,
                       capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stdout + p.stderr


def test_ruff_catches_an_unused_import(tmp_path):
    """The check is live: a file with an unused import and a blind except fails it."""
    bad = tmp_path / "bad.py"
    bad.write_text("import os\n\ntry:\n    pass\nexcept Exception:\n    pass\n")
    p = subprocess.run(_ruff() + ["check", "--no-cache", "--config", str(ROOT / "pyproject.toml"), str(bad)],
                       cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert p.returncode == 1 and "F401" in p.stdout and "BLE001" in p.stdout, p.stdout + p.stderr
