"""Test configuration: hypothesis runs derandomized, so CI sees the same examples on
every run (a property test must not pass or fail by the luck of the draw); set
HYPOTHESIS_PROFILE=explore locally to search with fresh random examples."""
import os
import shutil
import sys

import pytest
from hypothesis import settings

settings.register_profile("ci", derandomize=True, print_blob=True)
settings.register_profile("explore", derandomize=False)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))

# Bytecode caches even where PYTHONDONTWRITEBYTECODE is set (as on some CI images): the suite
# starts a few hundred Python processes (`python -m tmm_cli`, the batch's spawned workers, the
# nested spawn run), and without the caches every one of them compiles tmm's sources afresh
# (0.2 s of a 0.6 s JSON run; tests/test_spawn_suite.py 56 s -> 40 s).  Popped here, in the
# process that starts pytest-xdist's workers and every subprocess, before any of them starts.
os.environ.pop("PYTHONDONTWRITEBYTECODE", None)
sys.dont_write_bytecode = False

# One BLAS thread in the test processes, as `tmm` sets it for itself (cli.single_blas_thread):
# the tests that call tmm's stages in-process run them as the program does.  Set here, before
# numpy is first imported in this process and before pytest-xdist's workers start (they inherit
# it).  Not a measurable saving: side by side on one machine the suite took 206 s (335 s of user
# CPU) with it and 211 s (346 s) without, within the machine's noise.
from tmm_cli.cli import single_blas_thread  # noqa: E402  (after the bytecode setting above)

single_blas_thread()

# tmm's answers kept between runs (the path synthesis's searches, TMM_CACHE_DIR) in one folder
# for the test session: shared by its workers and the processes they start, never the user's
# cache, removed when the session ends (pytest_unconfigure).  The tests of the search itself
# turn it off or point it elsewhere.
if "TMM_CACHE_DIR" not in os.environ:
    import tempfile
    _SESSION_CACHE = os.environ["TMM_CACHE_DIR"] = tempfile.mkdtemp(prefix="tmm-tests-cache-")
else:
    _SESSION_CACHE = None


def pytest_unconfigure(config):
    if _SESSION_CACHE is not None:
        shutil.rmtree(_SESSION_CACHE, ignore_errors=True)


# headless Chromium for the tests that look at report.html in a real browser (test_browser,
# test_explore, test_worked): the system's, driven by playwright
CHROMIUM_ARGS = ["--no-sandbox", "--disable-gpu", "--disable-background-networking", "--disable-component-update",
                 "--no-first-run", "--disable-sync"]


def _chromium() -> str | None:
    env = os.environ.get("TMM_CHROMIUM")
    if env:
        return env
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    return None


@pytest.fixture(scope="session")
def browser():
    """A Chromium browser (playwright's), launched once per test process for every module that
    uses it (a launch with playwright's driver costs about a second of CPU); skipped, saying
    which part is missing, where playwright, Chromium, pdftoppm or the PDF engine is not there."""
    try:
        from playwright.sync_api import Error, sync_playwright
    except ImportError:
        pytest.skip("browser test skipped: the playwright package is missing (pip install -e '.[test]')")
    exe = _chromium()
    if exe is None:
        pytest.skip("browser test skipped: no Chromium found (Debian/Ubuntu: apt-get install chromium; "
                    "or set TMM_CHROMIUM to a Chromium executable)")
    if not shutil.which("pdftoppm"):
        pytest.skip("browser test skipped: pdftoppm is missing (Debian/Ubuntu: apt-get install poppler-utils)")
    try:
        import typst  # noqa: F401
    except (ImportError, OSError) as exc:
        pytest.skip(f"browser test skipped: the PDF engine cannot run here ({exc})")
    pw = sync_playwright().start()
    try:
        b = pw.chromium.launch(executable_path=exe, args=CHROMIUM_ARGS)
    except Error as exc:
        pw.stop()
        first = (str(exc).strip().splitlines() or ["?"])[0]
        pytest.skip(f"browser test skipped: Chromium ({exe}) cannot be launched here: {first}")
    yield b
    b.close()
    pw.stop()


@pytest.fixture(scope="session")
def shared_once(tmp_path_factory, request):
    """``shared_once(key, build)``: the folder ``build(folder)`` filled, built once per test
    session for all of pytest-xdist's workers (a file lock in the session's common temporary
    folder, pytest-xdist's documented pattern), so the tests that only read an example's
    outputs (a report in one language, its PDF) share one run of it instead of each
    repeating it.  Per session only: a new session (changed code) builds afresh."""
    from filelock import FileLock
    base = tmp_path_factory.getbasetemp()
    # a worker's basetemp is <session>/popen-gwN: their parent is the session's own folder
    root = (base.parent if hasattr(request.config, "workerinput") else base) / "shared-once"
    root.mkdir(exist_ok=True)

    def once(key: str, build):
        d = root / key
        with FileLock(str(d) + ".lock"):
            if not (d / ".built").exists():
                shutil.rmtree(d, ignore_errors=True)         # a build that failed half-way
                d.mkdir()
                build(d)
                (d / ".built").touch()
        return d
    return once


def pytest_collection_finish(session):
    """In each worker, once the tests are collected: what lives on to the end (the modules,
    the collected tests, the shared examples' tables) out of the cycle collector's reach
    (gc.freeze), and the collector's first generation passed over every 50,000 new objects,
    not every 2,000 (tests make millions of short-lived ones): measured on the whole suite, the
    workers' CPU 358 s -> 338 s, nothing else changed (the tmm processes the tests start keep
    the collector as tmm sets it)."""
    import gc
    gc.collect()
    gc.freeze()
    gc.set_threshold(50_000, 20, 20)


def pytest_collection(session):
    """A worker's test modules imported before its collection, starting at its own share of
    them (worker k of n at the k-th n-th of the list, round to the start): pytest rewrites a
    module's asserts on its first import and keeps the result in tests/__pycache__, and from a
    clean clone (no cache yet) each worker rewrote every module, the same ones at the same time
    (6.5 s of a worker's start).  Each now rewrites its share and finds the others' in the
    cache; the collection then takes the modules imported (the same modules, in its own order)."""
    info = getattr(session.config, "workerinput", None)     # pytest-xdist's worker, else None
    if not info or int(info.get("workercount", 1)) < 2:
        return
    worker, count = str(info.get("workerid", "gw0")), int(info["workercount"])
    import importlib
    from pathlib import Path
    # the modules the session collects: those in or under the paths it was given
    given = [(session.config.invocation_params.dir / a.split("::")[0]).resolve() for a in session.config.args]
    names = sorted(p.stem for p in Path(__file__).resolve().parent.glob("test_*.py")
                   if any(p == g or g in p.parents for g in given))
    k = int(worker[2:]) % count
    start = k * len(names) // count
    for name in names[start:] + names[:start]:
        try:
            importlib.import_module(name)
        except Exception:  # noqa: BLE001 - the collection imports it again and reports its error
            pass
