"""The batch and run tests once more with every fork taken away (TMM_START_METHOD=spawn), as
Windows and macOS run them: a nested pytest of those files in a process whose environment
forces spawn (the fork-only tests skip themselves there)."""
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
FILES = ["tests/test_instructor.py", "tests/test_portable.py", "tests/test_run_outputs.py"]


def test_batch_and_run_suites_pass_under_spawn():
    if os.environ.get("TMM_START_METHOD") == "spawn":
        pytest.skip("the whole suite runs under spawn already")
    env = dict(os.environ, TMM_START_METHOD="spawn")
    p = subprocess.run([sys.executable, "-m", "pytest", "-n", "0", "-p", "no:cacheprovider", *FILES],
                       cwd=ROOT, env=env, capture_output=True, text=True, timeout=1800)
    assert p.returncode == 0, p.stdout[-4000:] + p.stderr[-2000:]
    assert " passed" in p.stdout
