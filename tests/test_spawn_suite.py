"""The batch and run tests once more with every fork taken away (TMM_START_METHOD=spawn), as
Windows and macOS run them: a nested pytest of those files in a process whose environment
forces spawn (the fork-only tests skip themselves there).

The files' tests are shared out among a few nested runs (one test here each, which the
suite's workers run side by side), and the tests that choose their start method themselves
(the `start_method` fixture's fork and spawn, a test that sets TMM_START_METHOD=spawn, a
test without os.fork at all) are left out of them: the suite itself runs those, each with
the start method it names, and the nested run would only repeat them."""
import ast
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
FILES = ["tests/test_instructor.py", "tests/test_portable.py", "tests/test_run_outputs.py"]
SHARES = 4
# set in the nested runs: the `start_method` fixture (tests/test_instructor.py) skips there
NESTED = "TMM_SPAWN_SUITE"
# tests that set their own start method (spawn, or no os.fork): run as they are in the suite
OWN_START = ["test_a_spawned_workers_start_is_not_the_variants_time",
             "test_watched_memory_counts_from_the_variants_start_not_the_workers",
             "test_every_module_imports_without_unix_only_modules",
             "test_batch_with_limits_and_run_without_unix_only_modules"]


def _tests() -> list[str]:
    """Every test function of FILES as a node id (its parameters with it), in file order."""
    out = []
    for f in FILES:
        tree = ast.parse((ROOT / f).read_text(encoding="utf-8"))
        out += [f"{f}::{n.name}" for n in tree.body
                if isinstance(n, ast.FunctionDef) and n.name.startswith("test_") and n.name not in OWN_START]
    return out


def test_the_shares_hold_every_test_once():
    ids = _tests()
    shares = [ids[k::SHARES] for k in range(SHARES)]
    assert sorted(sum(shares, [])) == sorted(ids) and len(set(ids)) == len(ids)
    assert all(shares) and len(ids) > 60
    names = {i.split("::")[1] for i in ids}
    assert "test_batch_survives_dead_slow_and_greedy_workers" in names       # skipped there by the fixture
    for f in FILES:                                                          # the left-out tests exist
        text = (ROOT / f).read_text(encoding="utf-8")
        names |= {n for n in OWN_START if f"def {n}(" in text}
    assert set(OWN_START) <= names


@pytest.mark.parametrize("share", range(SHARES))
def test_batch_and_run_suites_pass_under_spawn(share):
    if os.environ.get("TMM_START_METHOD") == "spawn":
        pytest.skip("the whole suite runs under spawn already")
    env = dict(os.environ, TMM_START_METHOD="spawn", **{NESTED: "1"})
    p = subprocess.run([sys.executable, "-m", "pytest", "-n", "0", "-p", "no:cacheprovider",
                        *_tests()[share::SHARES]], cwd=ROOT, env=env, capture_output=True, text=True, timeout=1800)
    assert p.returncode == 0, p.stdout[-4000:] + p.stderr[-2000:]
    assert " passed" in p.stdout
