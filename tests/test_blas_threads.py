"""The CLI runs BLAS on one thread (its pool costs a short run more than it gains), unless
the user's environment sets the thread count."""
import json
import os
import subprocess
import sys

from tmm_cli.cli import BLAS_THREADS, single_blas_thread

PROBE = ("import os, sys, json; sys.argv = ['tmm', '--version'];"
         "import tmm_cli.cli as c;"
         "c.main = lambda exit_now: print(json.dumps({k: os.environ.get(k) for k in c.BLAS_THREADS}));"
         "c.entry()")


def _env_seen(extra):
    env = {k: v for k, v in os.environ.items() if k not in BLAS_THREADS}
    env.update(extra)
    p = subprocess.run([sys.executable, "-c", PROBE], capture_output=True, text=True, env=env, timeout=60)
    assert p.returncode == 0, p.stderr
    return json.loads(p.stdout)


def test_entry_sets_one_thread_before_numpy():
    seen = _env_seen({})
    assert seen == {k: "1" for k in BLAS_THREADS}


def test_users_setting_is_kept():
    seen = _env_seen({"OPENBLAS_NUM_THREADS": "2"})
    assert seen["OPENBLAS_NUM_THREADS"] == "2" and seen["OMP_NUM_THREADS"] == "1"


def test_entry_runs_before_numpy_is_imported():
    """The setting only takes effect if numpy is not yet loaded when entry() runs."""
    code = "import sys, tmm_cli.cli; print('numpy' in sys.modules)"
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert p.stdout.strip() == "False", p.stderr


def test_single_blas_thread_on_a_mapping():
    env = {"MKL_NUM_THREADS": "4"}
    single_blas_thread(env)
    assert env == {"MKL_NUM_THREADS": "4", "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1"}
