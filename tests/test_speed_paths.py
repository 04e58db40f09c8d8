"""The fast paths give the same numbers as the slow ones they replace, and a JSON run
imports only what it needs (scipy, matplotlib, typst, ezdxf, pint stay out)."""
from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from hypothesis import event, given, settings
from hypothesis import strategies as hst

from tmm_cli import lazy, units
from tmm_cli.results import clean, dumps

ROOT = Path(__file__).resolve().parents[1]
HEAVY = ("scipy", "matplotlib", "typst", "ezdxf", "pint", "jinja2")
# a plain `tmm run` / `tmm validate` never builds the Typer app (tmm_cli.cli, the fast path)
CLI_APP = ("typer", "click", "shellingham", "tmm_cli.commands")


def _imported_by(args: list[str], tmp_path: Path, env: dict | None = None) -> set[str]:
    code = ("import sys\nfrom tmm_cli.cli import main\n"
            "try:\n    main()\nexcept SystemExit as e:\n    code = e.code\nelse:\n    code = 0\n"
            "print('MODULES', ' '.join(sorted({m.split('.')[0] for m in sys.modules}\n"
            "                                  | {m for m in sys.modules if m.startswith(('tmm_cli.report',\n"
            "                                                                            'tmm_cli.commands',\n"
            "                                                                            'numpy.ma',\n"
            "                                                                            'numpy.polynomial'))})),\n"
            "      file=sys.stderr)\n"
            "sys.exit(code)\n")
    import os
    # no terminal and no console settings: the summary's text is Rich's without Rich
    base = {k: v for k, v in os.environ.items() if k not in ("COLUMNS", "LINES", "FORCE_COLOR", "TTY_COMPATIBLE")}
    p = subprocess.run([sys.executable, "-c", code, *args], cwd=tmp_path, capture_output=True,
                       text=True, timeout=300, env={**base, **(env or {})}, stdin=subprocess.DEVNULL)
    assert p.returncode == 0, p.stderr
    line = [ln for ln in p.stderr.splitlines() if ln.startswith("MODULES ")][-1]
    return set(line.split()[1:])


def test_json_run_imports_no_heavy_module(tmp_path):
    mods = _imported_by(["run", str(ROOT / "tasks" / "forging_sixbar.yaml"), "--format", "json",
                         "-o", "o"], tmp_path)
    assert "numpy" in mods                       # the stages ran
    assert not mods & set(HEAVY), sorted(mods & set(HEAVY))
    assert not mods & set(CLI_APP), sorted(mods & set(CLI_APP))
    assert "rich" not in mods                    # the summary (not quiet) written as Rich would
    assert "numpy.ma" not in mods                # np.unique's import (tmm_cli.lazy.unique)
    assert "numpy.polynomial" not in mods        # the flywheel's Gauss points (tmm_cli.lazy.leggauss)
    # the report package neither (the hand-method error reads tmm_cli.plans, not the report)
    assert not {m for m in mods if m.startswith("tmm_cli.report")}, sorted(mods)
    assert json.loads((tmp_path / "o" / "results.json").read_text())["kinetostatics"]


def test_linkage_html_report_imports_no_matplotlib(tmp_path):
    """The linkage report draws every figure itself (the scheme, the plan of positions,
    the plans, the diagrams): no matplotlib, in one process (no helper to hide it)."""
    mods = _imported_by(["run", str(ROOT / "tasks" / "forging_sixbar.yaml"), "--format", "html",
                         "-o", str(tmp_path / "o")], tmp_path, env={"TMM_REPORT_JOBS": "1"})
    assert "tmm_cli.report.figures" in mods and "jinja2" in mods       # the report was made
    assert "matplotlib" not in mods
    html = (tmp_path / "o" / "report.html").read_text(encoding="utf-8")
    assert 'μl = 0.01 m/mm  (M 1:10)' in html and 'μl = 0.015 m/mm  (M 1:15)' in html


@pytest.mark.parametrize("task", ["cam_rocker", "gears_shifted", "planetary_A", "impact_rotor"])
def test_every_report_imports_no_matplotlib(tmp_path, task):
    """The cam, gear, planetary and two-DOF reports draw their figures themselves too
    (svgchart's matplotlib-like axes): no matplotlib in the HTML and PDF report."""
    mods = _imported_by(["run", str(ROOT / "tasks" / f"{task}.yaml"), "--format", "html,pdf",
                         "-o", str(tmp_path / "o")], tmp_path, env={"TMM_REPORT_JOBS": "1"})
    assert "tmm_cli.report.figures" in mods and "jinja2" in mods       # the report was made
    assert "matplotlib" not in mods
    assert (tmp_path / "o" / "report.pdf").stat().st_size > 10000


def test_validate_imports_no_heavy_module(tmp_path):
    mods = _imported_by(["validate", str(ROOT / "tasks" / "forging_sixbar.yaml")], tmp_path)
    assert not mods & set(HEAVY), sorted(mods & set(HEAVY))
    assert not mods & set(CLI_APP), sorted(mods & set(CLI_APP))


# a path synthesis is an optimisation (scipy's differential evolution): validating its task checks
# the linkage it generates, so it runs the search; every other task validates without scipy
SEARCHED = {"synthesis_path.yaml"}


def test_validate_every_task_imports_no_heavy_module(tmp_path):
    """Validation needs no scipy (a cam's region check), no pint (times, output speeds in
    the fast units table), no Typer."""
    tasks = sorted(str(p) for p in (ROOT / "tasks").glob("*.yaml") if p.name not in SEARCHED)
    mods = _imported_by(["validate", *tasks], tmp_path)
    assert not mods & set(HEAVY + CLI_APP), sorted(mods & set(HEAVY + CLI_APP))


def test_validate_a_folder_imports_no_heavy_module(tmp_path):
    """`tmm validate DIR` (a folder, expanded as `tmm batch` does) stays as light."""
    folder = tmp_path / "tasks"
    folder.mkdir()
    for p in (ROOT / "tasks").glob("*.yaml"):
        if p.name not in SEARCHED:
            (folder / p.name).write_bytes(p.read_bytes())
    mods = _imported_by(["validate", str(folder)], tmp_path)
    assert not mods & set(HEAVY + CLI_APP), sorted(mods & set(HEAVY + CLI_APP))


def test_validating_a_path_synthesis_runs_its_search(tmp_path):
    """The one exception above, stated: the path's search is scipy's (when it searches: no
    answer kept from an earlier run, TMM_CACHE_DIR=off)."""
    mods = _imported_by(["validate", str(ROOT / "tasks" / "synthesis_path.yaml")], tmp_path,
                        env={"TMM_CACHE_DIR": "off"})
    assert "scipy" in mods and not mods & set(CLI_APP)


@pytest.mark.parametrize("name", ["gears_zero", "planetary_A", "synthesis_shaper", "press_drive_train",
                                  "engine_slider_crank", "static_gravity"])
def test_json_runs_import_no_heavy_module(name, tmp_path):
    mods = _imported_by(["run", str(ROOT / "tasks" / f"{name}.yaml"), "-f", "json", "-q", "-o", "o"], tmp_path)
    assert not mods & set(HEAVY + CLI_APP), sorted(mods & set(HEAVY + CLI_APP))


def test_other_command_lines_build_the_typer_app(tmp_path):
    """--help, an option spelt `--format=json`, a bad value: the Typer app parses them."""
    task = str(ROOT / "tasks" / "forging_sixbar.yaml")
    for args in (["run", "--help"], ["validate", "--help"], ["run", task, "--format=json", "-q", "-o", "o"]):
        assert "tmm_cli.commands" in _imported_by(args, tmp_path), args


def test_fast_path_answers_as_the_typer_app(tmp_path):
    """The same exit code, stdout, stderr and results.json from the fast path (a
    subprocess, `python -m tmm_cli`) as from the Typer app (CliRunner), on good and bad tasks."""
    from typer.testing import CliRunner

    from tmm_cli.cli import _fast, app
    good = str(ROOT / "tasks" / "forging_sixbar.yaml")
    bad = tmp_path / "bad.yaml"
    bad.write_text("schema: tmm/1\nmechanism:\n  ground: {O: [0, 0]}\n  linkz: {}\n", encoding="utf-8")
    stuck = tmp_path / "stuck.yaml"          # valid, but the rod is too short to assemble anywhere
    stuck.write_text(
        "schema: tmm/1\nmechanism: {ground: {O: [0, 0]}, links: {crank: {points: [O, A], length: 0.1},\n"
        "  rod: {points: [A, B], length: 0.05}, slider: {slider: B, guide: {through: O, angle: 0}}}}\n"
        "drive: {link: crank, speed: 10}\n", encoding="utf-8")
    lines = [["validate", good], ["validate", good, str(bad), str(stuck), "--no-assembly"],
             ["validate", str(bad), good, str(stuck), str(tmp_path / "missing.yaml")],
             ["validate", str(bad), str(stuck), "--lang", "ru"], ["validate", "-l", "UK", str(stuck), good],
             ["run", good, "-f", "json", "-q", "-o", "{out}"], ["run", "-q", str(bad), "--format", "json", "--out", "{out}"],
             ["run", str(stuck), "-f", "json", "-o", "{out}", "-l", "ru"],
             ["run", good, "--format", "JSON", "-o", "{out}", "--quiet"]]
    runner = CliRunner()
    for k, line in enumerate(lines):
        fast = [a.replace("{out}", str(tmp_path / f"f{k}")) for a in line]
        slow = [a.replace("{out}", str(tmp_path / f"s{k}")) for a in line]
        assert _fast(fast) is not None, line
        p = subprocess.run([sys.executable, "-m", "tmm_cli", *fast], capture_output=True, text=True,
                           cwd=tmp_path, timeout=300)
        r = runner.invoke(app, slow)
        assert p.returncode == r.exit_code, (line, p.stderr, r.stderr)
        assert p.stdout == r.stdout.replace(f"s{k}", f"f{k}"), line
        assert p.stderr == r.stderr.replace(f"s{k}", f"f{k}"), line
        if line[0] == "run" and p.returncode != 2:
            assert (tmp_path / f"f{k}" / "results.json").read_bytes() == \
                (tmp_path / f"s{k}" / "results.json").read_bytes(), line
    for line in (["run", good, "--format=json"], ["run", good, "-f", "xml"], ["run", good, "-l", "de"],
                 ["run", good, "-qf", "json"], ["run", good, good], ["run", "--help"], ["validate"],
                 ["run", good, "-o", ""], ["run", "--", good], ["check", good], ["--version"],
                 ["validate", good, "--lang", "de"], ["validate", good, "-l"]):
        assert _fast(line) is None, line


def test_run_holds_its_results_to_the_program_end(tmp_path):
    """`tmm run`'s fast path keeps the results to the program's end (its command holds them:
    a fine grid's ~10^6 objects are not freed one by one by a process about to end), listed
    where a report was made (as the report read them), lazy in a JSON run."""
    from tmm_cli.cli import _fast, run_task
    from tmm_cli.results import Entries, LazyEntries
    good = ROOT / "tasks" / "forging_sixbar.yaml"
    for fmt, kind in (("html", Entries), ("json", LazyEntries)):
        held: list = []
        assert run_task(good, tmp_path / fmt, {fmt}, "en", True, False, held=held) == 0
        assert len(held) == 1 and type(held[0]["kinetostatics"]) is kind, fmt
        assert json.loads((tmp_path / fmt / "results.json").read_text())["kinetostatics"] == list(held[0]["kinetostatics"])
    command = _fast(["run", str(good), "-f", "html", "-q", "-o", str(tmp_path / "fast")])
    lists = [c.cell_contents for c in command.__closure__ if type(c.cell_contents) is list]
    assert lists == [[]]
    assert command() == 0
    assert len(lists[0]) == 1 and type(lists[0][0]["kinematics"]) is Entries
    assert held[0].keys() == lists[0][0].keys() - {"kinematics_explore", "kinetostatics_explore"}


@pytest.mark.parametrize("command", ["validate-good", "validate-bad", "run-json", "run-html,pdf"])
def test_program_ends_at_once_unless_shutdown_has_work(tmp_path, command):
    """The program (`tmm`, `python -m tmm_cli`: cli.entry) ends a plain run / validate
    without the interpreter's shutdown (a global's finalizer never runs), its output all
    written and its exit code kept, its atexit callbacks run first (a report's:
    multiprocessing's, tempfile's); `main()` called by a program that goes on or a running
    thread take the ordinary exit (which runs the finalizer). One test per command line
    (each runs its programs one after another)."""
    good = str(ROOT / "tasks" / "engine_slider_crank.yaml")   # a linkage with kinetostatics and a report
    bad = tmp_path / "bad.yaml"
    bad.write_text("schema: tmm/1\nmechanism:\n  ground: {O: [0, 0]}\n  linkz: {}\n", encoding="utf-8")
    head = ("import sys, atexit, threading\n"
            "class Last:\n    def __del__(self):\n        print('SHUTDOWN', file=sys.stderr)\n"
            "last = Last()\n")
    ends = {"entry": "from tmm_cli.cli import entry\nentry()\n",
            "main": "from tmm_cli.cli import main\nmain()\n",
            "atexit": "atexit.register(lambda: print('ATEXIT', file=sys.stderr))\n"
                      "from tmm_cli.cli import entry\nentry()\n",
            "thread": "threading.Thread(target=threading.main_thread().join).start()\n"     # to the end
                      "from tmm_cli.cli import entry\nentry()\n"}
    cases = {"validate-good": (["validate", good], 0, f"{good}: ok\n"), "validate-bad": (["validate", str(bad)], 2, ""),
             "run-json": (["run", good, "-f", "json", "-o", "o"], 0, None),
             "run-html,pdf": (["run", good, "-f", "html,pdf", "-o", "r"], 0, None)}
    for args, code, out in [cases[command]]:
        for name, tail in ends.items():
            if "html,pdf" in args and name not in ("entry", "atexit"):
                continue                            # a report: the early exit after its atexit work
            p = subprocess.run([sys.executable, "-c", head + tail, *args], capture_output=True, text=True,
                               cwd=tmp_path, timeout=300)
            assert p.returncode == code, (name, args, p.stderr)
            assert ("SHUTDOWN" in p.stderr) == (name not in ("entry", "atexit")), (name, args, p.stderr)
            assert ("ATEXIT" in p.stderr) == (name == "atexit"), (name, args)
            if out is not None:
                assert p.stdout == out, (name, args)
            else:                                   # the summary table, to its last line
                o = args[-1]
                assert p.stdout.endswith(f"wrote {o}/.tmm-manifest.json\n"), (name, p.stdout)
                assert json.loads((tmp_path / o / "results.json").read_text())["kinetostatics"]
                if o == "r":                        # the report whole, the helper's files in place
                    assert (tmp_path / "r" / "report.html").read_text(encoding="utf-8").rstrip().endswith("</html>")
                    assert (tmp_path / "r" / "report.pdf").read_bytes().rstrip().endswith(b"%%EOF")
                    assert not list(tmp_path.glob("r/.*tmp*")), name
            if code == 2:
                assert "error: invalid task" in p.stderr and "linkz" in p.stderr, (name, p.stderr)


@pytest.mark.parametrize("kind", sorted(units._FAST_UNITS))
def test_fast_units_equal_pint(kind):
    """Each factor of the table is pint's, and the product is pint's result to the bit."""
    from tmm_cli.numbers import parse_unit, unit_expression, ureg
    target = units.KINDS[kind][0]
    reg = ureg()
    for unit, factor in units._FAST_UNITS[kind].items():
        expression = unit_expression(parse_unit(unit)[0])
        tables = ("force", "pressure") if kind == "force_or_pressure" else (kind,)
        assert any(expression in units._fast_table(t) for t in tables), unit      # read without pint
        for value in ("1", "50", "-3.25", "0.001", "2.5e3", "137.5"):
            q = reg.Quantity(f"{value} {unit}")
            if kind == "force_or_pressure":
                want = q.to("N" if q.check("[force]") else "Pa").magnitude
            else:
                want = q.to(target).magnitude
            assert units.quantity(f"{value} {unit}", kind)[0] == want, (value, unit)
            if abs(want) <= units.LIMIT:
                assert units.convert(f"{value} {unit}", kind) == want


def test_fast_units_leave_the_rest_to_pint():
    assert "RPM" not in units._fast_table("speed")           # pint decides (and rejects)
    assert "ft" not in units._fast_table("length")
    with pytest.raises(ValueError):
        units.convert("50 RPM", "speed")
    assert units.convert("3 ft", "length") == pytest.approx(0.9144)
    assert units.convert("300mm", "length") == pytest.approx(0.3)
    with pytest.raises(ValueError):
        units.convert("5 kg", "length")


def _fns():
    rng = np.random.default_rng(7)
    for _ in range(200):
        c = rng.normal(size=4)
        yield lambda x, c=c: c[0] + c[1] * x + c[2] * math.sin(3 * x) + c[3] * x ** 3


def test_brentq_is_scipys_to_the_bit():
    from scipy.optimize import brentq
    n = 0
    for f in _fns():
        if f(-3.0) * f(3.0) >= 0:
            continue
        for kw in ({}, {"xtol": 1e-12, "rtol": 1e-14}, {"xtol": 1e-15, "rtol": 8.9e-16, "maxiter": 400}):
            assert lazy.brentq(f, -3.0, 3.0, **kw) == brentq(f, -3.0, 3.0, **kw)
            n += 1
    assert n > 100
    assert lazy.brentq(lambda x: x * x - 2.0, 0.0, 2.0) == pytest.approx(math.sqrt(2.0), abs=1e-11)
    with pytest.raises(ValueError):
        lazy.brentq(lambda x: x * x + 1.0, -1.0, 1.0)


def test_bounded_minimum_is_scipys_to_the_bit():
    from scipy.optimize import minimize_scalar
    for f in _fns():
        g = lambda x, f=f: abs(f(x))  # noqa: E731
        a = minimize_scalar(g, bounds=(-3.0, 3.0), method="bounded", options={"xatol": 1e-10})
        b = lazy.minimize_scalar(g, bounds=(-3.0, 3.0), method="bounded", options={"xatol": 1e-10})
        assert (a.x, a.fun, a.nfev) == (b.x, b.fun, b.nfev)
    r = lazy.minimize_scalar(lambda x: (x - 1.25) ** 2, bounds=(0.0, 2.0), options={"xatol": 1e-10})
    assert r.success and r.x == pytest.approx(1.25, abs=1e-8)


def test_results_text_is_json_readable_and_deterministic():
    data = {"a": [1.0, 2.5, None], "b": {"c": [[1, 2], [3, 4]], "d": [], "e": {}},
            "f": [{"g": "ω"}], "h": np.arange(3.0), "i": -0.0}
    text = dumps(data)
    assert json.loads(text) == clean(data)
    assert text == dumps(data)
    assert '"a": [1.0,2.5,null]' in text and '  "c": [\n   [1,2],' in text
    assert '"g": "ω"' in text and '"i": 0.0' in text
    assert json.loads(dumps({"x": float("nan")})) == {"x": None}


def test_unique_is_numpys():
    rng = np.random.default_rng(5)
    cases = [np.array([]), np.array([0.0, -0.0, 1.0]), np.array([-0.0, 0.0, 1.0]), np.array([1.0, -0.0, 0.0]),
             np.array([np.nan, 1.0, np.nan, -np.inf, 1.0, np.inf]), np.array([3, 1, 3, 2]),
             np.array([[2.0, 1.0], [1.0, 0.5]]), [0.25, 0.25, 0.1], np.array([1 + 1j, np.nan, 1 + 1j, complex(np.nan, 1)])]
    for n in (1, 2, 7, 100, 5000):
        x = np.round(rng.normal(size=n), 2)                 # many repeats
        cases.append(np.concatenate([x, -x, np.zeros(3) * -1.0, [np.nan] * (n % 3)]))
    for x in cases:
        want, got = np.unique(x), lazy.unique(x)
        assert got.dtype == want.dtype and got.shape == want.shape
        assert np.array_equal(got, want, equal_nan=True), x
        assert np.array_equal(np.signbit(got.real), np.signbit(want.real)), x   # -0.0 kept as numpy keeps it


def test_leggauss_is_numpys():
    """The Gauss-Legendre rule of the flywheel's works, bit for bit numpy's (which imports
    all of numpy.polynomial), for every count a task can ask (quadrature <= 8) and far beyond."""
    from numpy.polynomial.legendre import leggauss
    for n in range(1, 121):
        (xw, ww), (xg, wg) = leggauss(n), lazy.leggauss(n)
        assert xg.dtype == xw.dtype and xg.shape == xw.shape == wg.shape
        assert np.array_equal(xg, xw) and np.array_equal(wg, ww), n
        assert np.array_equal(np.signbit(xg), np.signbit(xw)), n
    with pytest.raises(ValueError):
        lazy.leggauss(0)


def test_unwrap_is_numpys():
    from tmm_cli.linkage.kinematics.solver import _unwrap, _unwrap_sorted
    rng = np.random.default_rng(3)
    for n in (1, 2, 5, 36, 400):
        for scale in (0.01, 1.0, 5.0):
            x = rng.uniform(-10, 10, n) * scale
            assert np.array_equal(_unwrap(x), np.unwrap(x))
            order = np.argsort(rng.uniform(size=n))
            want = x.copy()
            want[order] = np.unwrap(x[order])
            assert np.array_equal(_unwrap_sorted(x, order), want)
    x = np.array([0.0, np.pi, 0.0, -np.pi, 3 * np.pi, 2.0])      # the ambiguous jumps of +-pi
    assert np.array_equal(_unwrap(x), np.unwrap(x))


def _run_json(task: Path, out: Path, seed: str) -> bytes:
    import os
    env = {**os.environ, "PYTHONHASHSEED": seed}
    subprocess.run([sys.executable, "-m", "tmm_cli", "run", str(task), "-f", "json", "-o", str(out), "-q"],
                   check=True, cwd=ROOT, env=env, timeout=300)
    return (out / "results.json").read_bytes()


def test_results_json_identical_across_runs_and_hash_seeds(tmp_path):
    """Two runs of one task (different string hashing, so set and dict orders built from
    them could differ) write byte-identical results.json: no timings, no order of a set."""
    task = ROOT / "tasks" / "forging_sixbar.yaml"          # kinematics, kinetostatics, flywheel
    a = _run_json(task, tmp_path / "a", "1")
    b = _run_json(task, tmp_path / "b", "2")
    assert a == b
    d = json.loads(a)
    assert d["kinetostatics"] and d["flywheel"]["accuracy"] is None     # the accuracy study only when asked


def test_batch_workers_start_warm_and_write_what_run_writes(tmp_path):
    """`tmm batch` imports the variants' modules and builds the task validator once, before
    the workers fork (no heavy module for a JSON batch); each variant's results.json is
    byte-identical to `tmm run --format json` of the same file."""
    src = (ROOT / "tasks" / "forging_sixbar.yaml").read_text(encoding="utf-8")
    vdir = tmp_path / "v"
    vdir.mkdir()
    (vdir / "a.yaml").write_text(src, encoding="utf-8")
    (vdir / "b.yaml").write_text(src.replace("speed: 50 rpm", "speed: 60 rpm"), encoding="utf-8")
    (vdir / "c.yaml").write_text(src.replace("length: 0.15", "length: 1.5"), encoding="utf-8")  # cannot assemble
    code = ("import sys\nfrom pathlib import Path\nfrom tmm_cli import batch\n"
            f"batch.warm(sorted(Path({str(vdir)!r}).glob('*.yaml')), {{'json'}})\n"
            "from tmm_cli.task import Task\n"
            "print('BUILT', Task.__pydantic_complete__)\n"
            "print('MODULES', ' '.join(sorted(sys.modules)))\n")
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, timeout=300)
    assert p.returncode == 0, p.stderr
    mods = set(p.stdout.split("MODULES ")[1].split())
    assert "BUILT True" in p.stdout
    assert {"tmm_cli.pipeline", "tmm_cli.linkage.kinetostatics", "tmm_cli.linkage.dynamics"} <= mods
    assert not {m.split(".")[0] for m in mods} & set(HEAVY)
    r = subprocess.run([sys.executable, "-m", "tmm_cli", "batch", str(vdir), "--jobs", "2", "-f", "json",
                        "-o", str(tmp_path / "b")], capture_output=True, text=True, cwd=ROOT, timeout=600)
    assert r.returncode == 3, r.stderr                      # c.yaml failed; the others still ran
    for name in ("a", "b"):
        want = _run_json(vdir / f"{name}.yaml", tmp_path / f"r{name}", "0")
        got = json.loads((tmp_path / "b" / name / "results.json").read_bytes())
        # the same numbers; only the task's file name differs (the batch reads the same file)
        assert got == json.loads(want)
    import csv
    with open(tmp_path / "b" / "summary.csv", encoding="utf-8", newline="") as fh:
        status = {Path(r["file"]).stem: r["status"] for r in csv.DictReader(fh)}
    assert status == {"a": "ok", "b": "ok", "c": "failed"}


def test_extremes_equal_brents_roots():
    """The output's extremes (bracketed Newton on the exact second derivative, all brackets
    at once) are the roots Brent's method finds on the same brackets, to 1e-10 deg."""
    from tmm_cli import load_task
    from tmm_cli.linkage.kinematics import positions as P
    from tmm_cli.linkage.mechanism import build_mechanism
    n = 0
    for name in ("forging_sixbar", "engine_slider_crank", "shaper_slotted_lever", "crank_rocker_fourbar",
                 "scotch_yoke_pump", "triad_class3", "press_offset_slider_crank"):
        task = load_task(ROOT / "tasks" / f"{name}.yaml")
        mech = build_mechanism(task)
        out = task.positions.output or mech.links[-1].name
        kind, f = P._output_coordinate(mech, out)
        ext = P._extremes(f, 360.0 if kind == "rocker" else None)
        grid = np.arange(0.0, 360.0, P.SCAN_STEP)
        _, ds = f(grid)
        g = lambda x: float(f(np.array([x % 360.0]))[1][0])  # noqa: E731
        want = []
        for k in range(len(grid)):
            a, b = ds[k], ds[(k + 1) % len(grid)]
            if a == 0.0:
                want.append(grid[k])
            elif a * b < 0:
                want.append(lazy.brentq(g, grid[k], grid[k] + P.SCAN_STEP, xtol=1e-12, rtol=1e-15) % 360.0)
        assert len(ext) == len(want) >= 2, name
        for (r, s), w in zip(ext, want):
            assert abs((r - w + 180.0) % 360.0 - 180.0) < 1e-10, (name, r, w)
            n += 1
    assert n >= 14


def test_plain_summary_is_what_rich_prints(monkeypatch, capsys):
    """The run summary written without Rich (summary._plain_summary) is, character for
    character, what Rich prints; where Rich could print anything else (a line to wrap,
    markup, an emoji code, characters of another width, COLUMNS) Rich prints it."""
    from tmm_cli import load_task, run, summary
    for k in ("COLUMNS", "LINES", "FORCE_COLOR", "TTY_COMPATIBLE"):
        monkeypatch.delenv(k, raising=False)
    cases = [run(load_task(ROOT / "tasks" / f"{n}.yaml"))
             for n in ("forging_sixbar", "press_drive_train", "gears_zero", "synthesis_shaper")]
    base = cases[0]
    more = {"title": "Горизонтально-ковочная машина, φ0", "warnings": ["a warning", "φ = 12.5 deg (ω: 5)"]}
    for title, warnings in (("Horizontal forging machine", []), (more["title"], more["warnings"]),
                            ("x" * 60, []), ("x" * 52, []), ("x" * 53, []), ("Її ґ", []), ("a [b] c", []),
                            ("a :smile: b", []), ("tab\there", []), (" padded", []), ("", []),
                            ("ok", ["w" * 70]), ("ok", ["w" * 71]), ("ok", ["w" * 72]), ("ok", ["[red]x"]),
                            ("ok", ["wide 日本"]), ("ok", ["ellipsis …"]), ("ok", ["two\nlines"]),
                            ("ok", ["a long warning of many words " * 5]), ("ok", ["word " * 16 + "x" * 90]),
                            ("ok", ["exactly " + "y" * 63 + " then more words follow here"])):
        cases.append({**base, "task": {**base["task"], "title": title}, "warnings": warnings})
    cases.append({"task": {"title": "no rows"}, "warnings": []})
    paths = [Path("out") / "x" / "results.json", Path("out") / "x" / ".tmm-manifest.json"]
    plain, real = 0, summary._plain_summary
    for results in cases:
        summary.print_summary(results, paths)
        got = capsys.readouterr()
        rows = summary._summary_rows(results)
        title = f"tmm: {results['task']['title'] or ''}"
        plain += real(title, rows, results["warnings"], [str(p) for p in paths]) is not None
        monkeypatch.setattr(summary, "_plain_summary", lambda *a: None)          # Rich itself
        summary.print_summary(results, paths)
        want = capsys.readouterr()
        monkeypatch.setattr(summary, "_plain_summary", real)
        assert got.out == want.out and got.err == want.err == "", (title, results["warnings"])
    assert plain >= 8, plain                  # the plain text was written and compared
    monkeypatch.setenv("COLUMNS", "200")
    assert real("tmm: x", [("a", "b")], [], []) is None


_SPECIAL = [0.0, -0.0, 1.0, -1.0, 1e-300, -5e-324, 1e300, -1e308, math.pi, float("inf"), -float("inf")]


@settings(max_examples=200, deadline=None)
@given(x=hst.one_of(hst.sampled_from(_SPECIAL), hst.floats(allow_nan=False)), seed=hst.integers(0, 2 ** 16))
def test_zero_d_constants_give_the_python_floats_bits(x, seed):
    """The kinematics passes its constants to numpy as 0-d arrays (state.const: no scalar
    conversion per call): every ufunc it so calls gives the bits the Python float gives, on
    either side, into a new array or in place, signed zeros, infinities, subnormals and NaN
    among the operands; a comparison the same mask."""
    from numpy._core.umath import clip
    from tmm_cli.linkage.kinematics.state import const
    rng = np.random.default_rng(seed)
    a = np.concatenate([rng.normal(size=20) * 10.0 ** rng.uniform(-300, 300, 20), _SPECIAL, [np.nan]])
    k = const(x)
    assert np.asarray(k).tobytes() == np.float64(x).tobytes() and not k.flags.writeable
    for f in (np.add, np.subtract, np.multiply, np.divide, np.maximum, np.minimum, np.arctan2, np.hypot):
        with np.errstate(all="ignore"):
            assert f(a, x).tobytes() == f(a, k).tobytes(), (f, x)
            assert f(x, a).tobytes() == f(k, a).tobytes(), (f, x)
            out = a.copy()
            assert f(a, x).tobytes() == f(out, k, out=out).tobytes(), (f, x)
    for f in (np.greater, np.greater_equal):
        with np.errstate(all="ignore"):
            assert np.array_equal(f(a, x), f(a, k)) and np.array_equal(f(x, a), f(k, a))
    if x <= 1.0:
        with np.errstate(all="ignore"):
            assert np.clip(a, x, 1.0).tobytes() == clip(a, k, const(1.0)).tobytes()


def test_clearly_regular_implies_the_exact_singularity_test():
    """dyad_derivatives' squared test (no hypot) passes only where the exact test
    |det| >= 1e-10 |cA| |cB| finds no singular position, at every scale; it passes on a
    regular set and fails where a position is singular, or a value overflows or is NaN."""
    from tmm_cli.linkage.kinematics.dyads import _clearly_regular
    rng = np.random.default_rng(3)

    def exact_regular(det, cA, cB):
        nn = np.hypot(cA[0], cA[1]) * np.hypot(cB[0], cB[1])
        return not (~(np.abs(det) >= 1e-10 * nn)).any()

    passed = 0
    for k in range(400):
        scale = 10.0 ** rng.uniform(-160, 160)
        cA = tuple(rng.normal(size=50) * scale for _ in range(2))
        cB = (rng.normal(size=1), rng.normal(size=1)) if k % 3 == 0 else tuple(rng.normal(size=50) for _ in range(2))
        det = cA[0] * cB[1] - cA[1] * cB[0]
        # a few positions near the threshold: det = f 1e-10 |cA||cB|, f near 1
        nn = np.hypot(cA[0], cA[1]) * np.hypot(cB[0], cB[1])
        f = np.array([1.0 - 1e-12, 1.0 + 1e-12, 1.0004]) if k % 2 else np.array([1.002, 1.01, 3.0])
        det[:3] = f * rng.choice([1.0, -1.0]) * 1e-10 * nn[:3]
        if _clearly_regular(det, cA, cB):
            passed += 1
            assert exact_regular(det, cA, cB), k
    assert passed > 100
    a = (np.array([1.0, 2.0]), np.array([0.5, -1.0]))
    b = (np.array([0.0, 1.0]), np.array([1.0, 0.0]))
    det = a[0] * b[1] - a[1] * b[0]
    assert _clearly_regular(det, a, b) and exact_regular(det, a, b)
    assert not _clearly_regular(np.array([1.0, 0.0]), a, b)
    assert not _clearly_regular(np.array([1.0, np.nan]), a, b)
    big = (np.array([1e200, 1.0]), np.array([1.0, 1.0]))
    assert not _clearly_regular(np.array([1e200, 1.0]), big, b)


@pytest.mark.parametrize("seed", range(6))
def test_dyads_many_rows_paths_equal_the_generic_ones(seed, monkeypatch):
    """From WORK_ROWS_FROM positions on, the dyads take a fixed guide's constant rows
    once and skip the hypot of the singularity test: every pose and derivative of a random
    slider-crank (offset, guide angle, either closure) and four-bar is the generic paths'
    bit for bit."""
    from tmm_cli.linkage.kinematics import dyads
    from tmm_cli.linkage.kinematics.solver import Solver
    from tmm_cli.linkage.kinematics.state import WORK_ROWS_FROM
    from tmm_cli.linkage.mechanism import build_mechanism
    from tmm_cli.task import load_task
    rng = np.random.default_rng(seed)
    r, l = rng.uniform(0.02, 0.1), rng.uniform(0.25, 0.5)
    ang, off = rng.uniform(-180, 180), rng.uniform(-0.5, 0.5) * (l - r)
    a = math.radians(ang)
    gp = [-off * math.sin(a), off * math.cos(a)]
    ahead = [gp[0] + rng.choice([1, -1]) * l * math.cos(a), gp[1] + rng.choice([1, -1]) * l * math.sin(a)]
    tasks = [{"schema": "tmm/1", "mechanism": {
        "ground": {"O": [0, 0]},
        "links": {"crank": {"points": ["O", "A"], "length": r}, "rod": {"points": ["A", "B"], "length": l},
                  "piston": {"slider": "B", "guide": {"through": gp, "angle": ang}}},
        "assembly": {"B": ahead}}, "drive": {"link": "crank", "speed": "100 rpm"}},
        {"schema": "tmm/1", "mechanism": {
            "ground": {"O": [0, 0], "O3": [0.30, 0]},
            "links": {"crank": {"points": ["O", "A"], "length": 0.05 + 0.03 * rng.random()},
                      "coupler": {"points": ["A", "B"], "length": 0.30},
                      "rocker": {"points": ["O3", "B"], "length": 0.22}},
            "assembly": {"B": [0.33, rng.choice([0.21, -0.21])]}}, "drive": {"link": "crank", "speed": "100 rpm"}}]
    phi = np.radians(rng.uniform(0.0, 360.0, WORK_ROWS_FROM + 100))
    for src in tasks:
        mech = build_mechanism(load_task(src))
        many = Solver(mech).run(phi)
        monkeypatch.setattr(dyads, "WORK_ROWS_FROM", 10 ** 9)
        generic = Solver(mech).run(phi)
        monkeypatch.undo()
        for name in ("o", "th", "o1", "th1", "o2", "th2"):
            for b, v in getattr(generic, name).items():
                assert np.asarray(getattr(many, name)[b]).tobytes() == np.asarray(v).tobytes(), (name, b)
        for gi, s in generic.sing.items():
            assert np.array_equal(many.sing[gi], s)


@pytest.mark.parametrize("seed", range(8))
def test_fixed_slide_dyad_equals_the_generic_paths(seed, monkeypatch):
    """The fused path of an RRP dyad whose slider runs on a fixed guide (dyads._FixedSlide)
    gives every pose, derivative, margin, singular mask and normalised determinant of the
    generic _rrp / dyad_derivatives bit for bit: random slider-cranks (offset, guide angle,
    either closure, the links in either order: the pair's two sign conventions), few and
    many positions, positions where it does not assemble."""
    from tmm_cli.linkage.kinematics import dyads
    from tmm_cli.linkage.kinematics.solver import Solver
    from tmm_cli.linkage.kinematics.state import WORK_ROWS_FROM
    from tmm_cli.linkage.mechanism import build_mechanism
    from tmm_cli.task import load_task
    rng = np.random.default_rng(100 + seed)
    r, l = rng.uniform(0.02, 0.1), rng.uniform(0.25, 0.5)
    ang, off = rng.uniform(-180, 180), rng.uniform(-0.5, 0.5) * (l - r)
    if seed < 4:                                # centric, on an axis: exact zeros (their signs)
        r, l, ang, off = 0.045, 0.17, 90.0 * seed, 0.0
    if seed == 7:
        off = l - r + 0.3 * r                   # does not assemble over part of the turn
    a = math.radians(ang)
    gp = [-off * math.sin(a), off * math.cos(a)]
    ahead = [gp[0] + rng.choice([1, -1]) * l * math.cos(a), gp[1] + rng.choice([1, -1]) * l * math.sin(a)]
    links = {"crank": {"points": ["O", "A"], "length": r}, "rod": {"points": ["A", "B"], "length": l},
             "piston": {"slider": "B", "guide": {"through": gp, "angle": ang}}}
    if seed % 2:
        links = {k: links[k] for k in ("crank", "piston", "rod")}
    mech = build_mechanism(load_task({"schema": "tmm/1", "mechanism": {
        "ground": {"O": [0, 0]}, "links": links, "assembly": {"B": ahead}},
        "drive": {"link": "crank", "speed": "100 rpm"}}))
    plan = Solver(mech).plans[0]
    assert plan.slide is not None and plan.slide.x_sign == (seed % 2 == 0)
    grids = [np.radians(rng.uniform(0.0, 360.0, WORK_ROWS_FROM + 100)), np.radians(rng.uniform(0.0, 360.0, 37)),
             np.radians([0.0]), np.radians(np.arange(720) * 0.5)]
    for phi in grids:
        for kw in ({"strict": False}, {"strict": False, "dets": True}, {"strict": False, "fallback": False}):
            fused = Solver(mech).run(phi, **kw)
            monkeypatch.setattr(dyads, "FIXED_SLIDE", False)
            generic = Solver(mech).run(phi, **kw)
            monkeypatch.undo()
            for name in ("o", "th", "o1", "th1", "o2", "th2"):
                for b, v in getattr(generic, name).items():
                    assert np.asarray(getattr(fused, name)[b]).tobytes() == np.asarray(v).tobytes(), (name, b)
            for name in ("margins", "sing", "gdet"):
                for gi, v in getattr(generic, name).items():
                    assert np.asarray(getattr(fused, name)[gi]).tobytes() == np.asarray(v).tobytes(), (name, gi)
            assert (fused.singular is None) == (generic.singular is None)
            assert fused.const_th == generic.const_th


@pytest.mark.parametrize("seed", range(4))
def test_fixed_slide_bound_covers_the_squared_test(seed):
    """_FixedSlide.bound is not below _clearly_regular's right-hand side at any position
    (so that det^2 > bound implies its test), and by no more than a relative 1e-11: random
    slider-cranks of lengths from 1e-3 to 1e3, many positions."""
    from tmm_cli.linkage.kinematics.solver import Solver
    from tmm_cli.linkage.mechanism import build_mechanism
    from tmm_cli.task import load_task
    rng = np.random.default_rng(300 + seed)
    k = 10.0 ** rng.uniform(-3, 3)
    r, l = k * rng.uniform(0.02, 0.1), k * rng.uniform(0.25, 0.5)
    ang, off = rng.uniform(-180, 180), rng.uniform(-0.5, 0.5) * (l - r)
    a = math.radians(ang)
    gp = [-off * math.sin(a), off * math.cos(a)]
    mech = build_mechanism(load_task({"schema": "tmm/1", "mechanism": {
        "ground": {"O": [0, 0]},
        "links": {"crank": {"points": ["O", "A"], "length": r}, "rod": {"points": ["A", "B"], "length": l},
                  "piston": {"slider": "B", "guide": {"through": gp, "angle": ang}}},
        "assembly": {"B": [gp[0] + l * math.cos(a), gp[1] + l * math.sin(a)]}},
        "drive": {"link": "crank", "speed": "100 rpm"}}))
    solver = Solver(mech)
    sl = solver.plans[0].slide
    st = solver.run(np.radians(rng.uniform(0.0, 360.0, 5000)))
    ru, ruM = st.rot(sl.X, sl.uX1), st.rot(sl.X, sl.uXC)
    a0, a1 = ru[:, 1] - ruM[:, 1], ruM[:, 0] - ru[:, 0]
    b0, b1 = sl.cY
    q = (a0 * a0 + a1 * a1) * (b0 * b0 + b1 * b1)
    q *= 1.001e-20
    q += 1e-290
    assert (q <= sl.bound).all() and (sl.bound <= q * (1 + 1e-11)).all()


# ---------------------------------------------------------------- the fused RRR dyad
def _kin_outcome(fn):
    """fn()'s result, or the StageError it raised as (text, results.json entry, the links
    named as never assembling)."""
    from tmm_cli.errors import StageError
    try:
        return fn()
    except StageError as exc:
        return ("error", str(exc), repr(exc.to_dict()), getattr(exc, "never_assembles", None))


def _same_runs(make_mech, phi, monkeypatch, kws=({"strict": False}, {"strict": False, "dets": True},
                                                 {"strict": False, "fallback": False}, {})):
    """Solver.run with dyads.GROUND_RRR on and off (a new Solver each: its closures chosen
    by that path too): every pose, derivative, margin, singular mask, normalised
    determinant, or the same error, bit for bit."""
    from tmm_cli.linkage.kinematics import dyads
    from tmm_cli.linkage.kinematics.solver import Solver
    for kw in kws:
        fused = _kin_outcome(lambda: Solver(make_mech()).run(phi, **kw))
        monkeypatch.setattr(dyads, "GROUND_RRR", False)
        generic = _kin_outcome(lambda: Solver(make_mech()).run(phi, **kw))
        monkeypatch.undo()
        if isinstance(generic, tuple) or isinstance(fused, tuple):
            assert fused == generic, kw
            continue
        for name in ("o", "th", "o1", "th1", "o2", "th2"):
            assert sorted(getattr(fused, name)) == sorted(getattr(generic, name))
            for b, v in getattr(generic, name).items():
                assert np.asarray(getattr(fused, name)[b]).tobytes() == np.asarray(v).tobytes(), (kw, name, b)
        for name in ("margins", "sing", "gdet"):
            for gi, v in getattr(generic, name).items():
                assert np.asarray(getattr(fused, name)[gi]).tobytes() == np.asarray(v).tobytes(), (kw, name, gi)
        assert (fused.singular is None) == (generic.singular is None)
        if generic.singular is not None:
            assert np.array_equal(fused.singular, generic.singular)
        assert fused.const_th == generic.const_th


def _same_solves(make_mech, phi_deg, monkeypatch):
    """kinematics.solve and check_assembly (tmm validate) with dyads.GROUND_RRR on and off
    (a new Mechanism each): every output, warning and mask, or the same error."""
    from tmm_cli.linkage.kinematics import dyads
    from tmm_cli.linkage.kinematics import solver as sv
    from tmm_cli.linkage.kinematics.solver import check_assembly, solve

    def both():
        mech = make_mech()
        return _kin_outcome(lambda: check_assembly(mech)), _kin_outcome(lambda: solve(mech, phi_deg, 2.0, 0.5))
    sv.FAST = False                     # the general solver's two paths (not the complex fast path)
    try:
        (chk_f, fused) = both()
        monkeypatch.setattr(dyads, "GROUND_RRR", False)
        (chk_g, generic) = both()
        monkeypatch.undo()
    finally:
        sv.FAST = True
    assert chk_f == chk_g
    if isinstance(generic, tuple) or isinstance(fused, tuple):
        assert fused == generic
        return generic
    for name in ("pos", "d1", "d2", "angle", "a1", "a2", "undefined"):
        f, g = getattr(fused, name), getattr(generic, name)
        assert sorted(f) == sorted(g), name
        for k in g:
            assert np.asarray(f[k]).tobytes() == np.asarray(g[k]).tobytes(), (name, k)
    assert fused.warnings == generic.warnings
    for name in ("singular", "near"):
        f, g = getattr(fused, name), getattr(generic, name)
        assert (f is None) == (g is None) and (g is None or np.array_equal(f, g)), name
    return generic


def test_ground_rrr_dyad_equals_the_generic_paths_on_the_tasks(monkeypatch):
    """The fused path of an RRR dyad with one pivot on the ground (dyads._GroundRRR) gives
    every pose, derivative, margin, singular mask and normalised determinant of the generic
    _rrr / dyad_derivatives bit for bit on every linkage task that has one (few and many
    positions, positions where it does not assemble, the change points' determinants), and
    solve's results and warnings."""
    import glob
    from tmm_cli.linkage.kinematics.solver import Solver
    from tmm_cli.linkage.kinematics.state import WORK_ROWS_FROM
    from tmm_cli.linkage.mechanism import build_mechanism
    from tmm_cli.orchestrate import prepare
    rng = np.random.default_rng(11)
    seen = []
    for path in sorted(glob.glob(str(ROOT / "tasks" / "*.yaml"))):
        task = prepare(path, assembly=False)         # a synthesis's mechanism generated
        if getattr(task, "mechanism", None) is None:
            continue
        make = lambda: build_mechanism(prepare(path, assembly=False))      # noqa: E731
        if not any(getattr(p, "rrr", None) is not None for p in Solver(make()).plans):
            continue
        seen.append(Path(path).stem)
        for phi in (np.radians(rng.uniform(0.0, 360.0, WORK_ROWS_FROM + 100)),
                    np.radians(rng.uniform(0.0, 360.0, 37)), np.radians([0.0]), np.radians(np.arange(720) * 0.5)):
            _same_runs(make, phi, monkeypatch)
        _same_solves(make, np.arange(360) * 1.0, monkeypatch)
        _same_solves(make, rng.uniform(0.0, 360.0, 1500), monkeypatch)
    # the four-bars and the six-bar's first group (a test that cannot pass empty)
    assert {"crank_rocker_fourbar", "forging_sixbar", "static_gravity", "synthesis_crank_rocker"} <= set(seen)


def _four_bar(g, r, lb, lc, up, order, rod_rev, rocker_rev, tri):
    """A four-bar task: crank O-A (r), coupler A-B (lb), rocker B-O3 (lc), O3 = g; ``up``:
    B's hint above or below the line O -> O3 (the two closures); ``order``: the order of the
    links (which is A and which B of the group, and the pair's order); ``rod_rev``,
    ``rocker_rev``: the links' points listed the other way round (their local origin at the
    other end); ``tri`` 1, 2, 3: B (1) or A (2) an extra point of a triangular coupler, O3
    (3) one of a triangular rocker, off the link's axis (local coordinates (0.8 l, 0.6 l))."""
    gx, gy = g
    coupler = {"points": ["B", "A"] if rod_rev else ["A", "B"], "length": lb}
    rocker = {"points": ["B", "O3"] if rocker_rev else ["O3", "B"], "length": lc}
    if tri == 1:
        coupler = {"points": ["A", "P"], "length": lb * 1.3, "extra": {"B": [lb * 0.8, lb * 0.6]}}
    elif tri == 2:
        coupler = {"points": ["B", "P"], "length": lb * 1.3, "extra": {"A": [lb * 0.8, lb * 0.6]}}
    elif tri == 3:
        rocker = {"points": ["B", "Q"], "length": lc * 1.3, "extra": {"O3": [lc * 0.8, lc * 0.6]}}
    links = [("crank", {"points": ["O", "A"], "length": r}), ("coupler", coupler), ("rocker", rocker)]
    if order:
        links = [links[0], links[2], links[1]]
    n = math.hypot(gx, gy)
    hint = [gx / 2 - (1 if up else -1) * gy / n * lc, gy / 2 + (1 if up else -1) * gx / n * lc]
    return {"schema": "tmm/1", "mechanism": {
        "ground": {"O": [0, 0], "O3": [gx, gy]}, "links": dict(links), "assembly": {"B": hint}},
        "drive": {"link": "crank", "speed": "60 rpm"}}


def _toggle_angles(g, r, lb, lc) -> list[float]:
    """Crank angles (deg) where |O3 - A| = lb + lc or |lb - lc| (the coupler and the rocker
    in line: the dyad's toggles, its singular positions), where there are any."""
    gx, gy = g
    dist, gam = math.hypot(gx, gy), math.atan2(gy, gx)
    out = []
    for L in (lb + lc, abs(lb - lc)):
        c = (r * r + dist * dist - L * L) / (2 * r * dist)
        if abs(c) <= 1:
            out += [math.degrees(gam + s * math.acos(c)) % 360.0 for s in (1, -1)]
    return out


@settings(max_examples=60, deadline=None)
@given(gx=hst.floats(0.1, 0.6), gy=hst.floats(-0.3, 0.3), r=hst.floats(0.02, 0.3), lb=hst.floats(0.05, 0.8),
       lc=hst.floats(0.05, 0.8), up=hst.booleans(), order=hst.booleans(), rod_rev=hst.booleans(),
       rocker_rev=hst.booleans(), tri=hst.integers(0, 3))
def test_ground_rrr_dyad_equals_the_generic_paths_on_random_four_bars(gx, gy, r, lb, lc, up, order, rod_rev,
                                                                       rocker_rev, tri):
    """Random four-bars (either closure, the links in either order, their points either way
    round, a triangular coupler): the fused RRR dyad's runs and solve's results equal the
    generic path's bit for bit, at its toggles (singular positions: the limit by
    continuity) and where it does not assemble (the same error, its intervals and reason),
    at few and many positions."""
    from tmm_cli.linkage.kinematics.solver import Solver
    from tmm_cli.linkage.kinematics.state import WORK_ROWS_FROM
    from tmm_cli.linkage.mechanism import build_mechanism
    from tmm_cli.task import load_task
    src = _four_bar((gx, gy), r, lb, lc, up, order, rod_rev, rocker_rev, tri)
    task = load_task(src)                          # validated once; a new Mechanism each
    make = lambda: build_mechanism(task)                    # noqa: E731
    plans = Solver(make()).plans
    assert plans[0].rrr is not None
    mp = pytest.MonkeyPatch()
    try:
        tog = _toggle_angles((gx, gy), r, lb, lc)
        rng = np.random.default_rng(int(1e6 * (gx + r + lb + lc)))
        grid = np.concatenate([np.arange(72) * 5.0, tog, np.array(tog) + 1e-9, np.array(tog) - 1e-7])
        for phi in (np.radians(grid), np.radians(rng.uniform(0.0, 360.0, WORK_ROWS_FROM + 10))):
            _same_runs(make, phi, mp, kws=({"strict": False}, {"strict": False, "dets": True}, {}))
        out = _same_solves(make, grid, mp)
    finally:
        mp.undo()
    event("does not assemble" if isinstance(out, tuple) else
          "singular positions" if out.singular is not None else "assembles")


@pytest.mark.parametrize("up", [True, False])
@pytest.mark.parametrize("g", [(0.3, 0.0), (0.0, 0.3)])
@pytest.mark.parametrize("r,lb,lc", [(0.1, 0.3, 0.3), (0.1, 0.3, 0.1), (0.3, 0.3, 0.3)])
def test_ground_rrr_dyad_equals_the_generic_paths_with_exact_zeros(g, r, lb, lc, up, monkeypatch):
    """Four-bars with the ground pivots on an axis, at crank angles of whole 45 deg (exact
    zeros among the coordinates and derivatives: their signs), every closure (one test
    each), order of the links and of their points, triangular links: the fused RRR dyad
    equals the generic path bit for bit (a signed zero lost in its derivatives shows here)."""
    import itertools
    from tmm_cli.linkage.mechanism import build_mechanism
    from tmm_cli.task import load_task
    grid = np.arange(8) * 45.0
    for order, rod_rev, rocker_rev, tri in itertools.product((True, False), (True, False), (True, False),
                                                             (0, 1, 2, 3)):
        src = _four_bar(g, r, lb, lc, up, order, rod_rev, rocker_rev, tri)
        task = load_task(src)                           # validated once; a new Mechanism each
        make = lambda: build_mechanism(task)            # noqa: E731
        _same_runs(make, np.radians(grid), monkeypatch, kws=({"strict": False}, {"strict": False, "dets": True}))
        _same_solves(make, grid, monkeypatch)


@pytest.mark.parametrize("case", ["part", "never", "change_point", "toggle_grid"])
def test_ground_rrr_dyad_fails_and_warns_as_the_generic_path(case, monkeypatch):
    """Where the RRR dyad does not assemble over part of the turn, at no angle, or passes
    its change points, the fused path raises the same error (the same text, intervals,
    reason, position, links) from solve and from check_assembly (tmm validate), and gives
    the same singular positions and warnings, as the generic path."""
    from tmm_cli.linkage.mechanism import build_mechanism
    from tmm_cli.task import load_task
    g, r, lb, lc, grid = {"part": ((0.3, 0.05), 0.12, 0.2, 0.15, np.arange(360) * 1.0),
                          "never": ((0.9, 0.0), 0.1, 0.2, 0.15, np.arange(36) * 10.0),
                          "change_point": ((0.3, 0.0), 0.1, 0.3, 0.1, np.arange(720) * 0.5),
                          "toggle_grid": ((0.0, 0.3), 0.3, 0.3, 0.3, np.arange(8) * 45.0)}[case]
    src = _four_bar(g, r, lb, lc, True, False, False, False, 0)
    out = _same_solves(lambda: build_mechanism(load_task(src)), grid, monkeypatch)
    if case in ("part", "never"):
        assert isinstance(out, tuple) and "does not assemble" in out[1], out
        assert (out[3] is not None) == (case == "never")        # never: the links named
        if case == "part":
            assert "'code': 'kinematics.fail.intervals'" in out[2]
    else:
        assert not isinstance(out, tuple) and out.singular is not None and out.singular.sum() >= 2
        assert any("change point" in str(w) for w in out.warnings)


@pytest.mark.parametrize("seed", range(4))
def test_ground_rrr_bound_covers_the_squared_test(seed):
    """_GroundRRR.bound is not below _clearly_regular's right-hand side at any position
    (so that det^2 > bound implies its test), and by no more than a relative 1e-11: random
    four-bars (their links' points either way round, a triangular coupler) of sizes from
    1e-3 to 1e3, many positions."""
    from tmm_cli.linkage.kinematics.solver import Solver
    from tmm_cli.linkage.mechanism import build_mechanism
    from tmm_cli.task import load_task
    rng = np.random.default_rng(400 + seed)
    k = 10.0 ** rng.uniform(-3, 3)
    src = _four_bar((k * 0.3, k * rng.uniform(-0.1, 0.1)), k * rng.uniform(0.02, 0.08), k * rng.uniform(0.25, 0.35),
                    k * rng.uniform(0.2, 0.3), True, seed % 2 == 1, seed in (1, 2), seed in (2, 3), seed % 3)
    solver = Solver(build_mechanism(load_task(src)))
    plan = solver.plans[0]
    rr = plan.rrr
    st = solver.run(np.radians(rng.uniform(0.0, 360.0, 5000)))

    def col(X, u1, uC):
        ru, ruM = st.rot(X, u1), st.rot(X, uC)
        return ru[:, 1] - ruM[:, 1], ruM[:, 0] - ru[:, 0]
    a0, a1 = col(rr.A, rr.uA1, rr.uAC)
    b0, b1 = col(rr.B, rr.uB1, rr.uBC)
    q = (a0 * a0 + a1 * a1) * (b0 * b0 + b1 * b1)
    q *= 1.001e-20
    q += 1e-290
    assert (q <= rr.bound).all() and (rr.bound <= q * (1 + 1e-11)).all()
