"""The report is a reader of results (docs/ARCHITECTURE.md, "The report's contract"):

* its modules import no stage computation: outside tmm_cli.report only the file helpers
  and the stages' own drawing-data / file-format functions of their results;
* no blind ``except`` in tmm_cli/report: a figure that cannot be drawn is an error the
  suite sees, never a silent box in the report;
* every section but 'task' is the same whether the task is given or not (the task
  gives only its own data table and names);
* what the figures need is in the results (the gears' admissible region, the driving
  link, the fine kinematic grid of the mechanism in motion) and is right."""
from __future__ import annotations

import ast
import math
import re
from pathlib import Path

import numpy as np
import pytest

import tmm_cli
from task_sections import gears  # noqa: E402  (sections through the task model)

ROOT = Path(__file__).resolve().parents[1]
REPORT = ROOT / "tmm_cli" / "report"

# modules outside tmm_cli.report the report may import, and why
ALLOWED = {
    "tmm_cli.io": "atomic file writing",
    "tmm_cli.results": "the results file's own helpers: its entries as lists, its JSON writer (the widget's data)",
    "tmm_cli.safepath": "paths kept inside the output folder",
    "tmm_cli.tables": "CSV text",
    "tmm_cli.units": "number formatting of the task-data table",
    "tmm_cli.cam.export": "file formats (CSV, DXF) of results['cam']",
    "tmm_cli.gears.drawing": "tooth outlines drawn from results['gears'] (the stage's drawing data)",
    "tmm_cli.study": "the tables of the accuracy study (its own results)",
    "tmm_cli.plans": "the velocity and acceleration plans constructed from results' numbers",
    "tmm_cli.task": "the task model, for its type only (under TYPE_CHECKING: the report reads the task's data)",
    # the drawings the report and the sheets share, drawn from results' numbers (they read as
    # the report reads: checked below with it)
    "tmm_cli.drawings.plans": "a velocity or acceleration plan drawn",
    "tmm_cli.drawings.balancing": "where the counterweights stand, from results' numbers",
    "tmm_cli.drawings.forces": "groups, force polygons, Zhukovsky's lever drawn",
    "tmm_cli.drawings.mesh": "a gear pair's wheels and line of action",
    "tmm_cli.drawings.train": "a drive's gear train: its scheme, velocity picture and angular-velocity plan",
    "tmm_cli.drawings.words": "the drawings' terms and numbers in the report's language",
    "tmm_cli.drawings.titleblock": "a signer's name in its title-block cell (the note's form 2, as the sheets')",
    "tmm_cli.scales": "the standard series of the scale factors μ",
    "tmm_cli.messages": "the warnings' catalogues: results['messages'] rendered in the report's language",
    "tmm_cli.locales": "the catalogues: every word of the report in its language (tmm_cli/locales/<lang>/)",
    "tmm_cli.reproducible": "the same files on every run: the figures' SVG ids, the report's date",
    "tmm_cli.schemacache": "the task model's serializer (the task-data table from the task as given)",
    "tmm_cli.numfmt": "numbers written as the report's language writes them (the decimal comma in ru, uk)",
}
# (file, function) where a broad except is allowed, and why
BROAD_EXCEPT_OK = {
    ("__init__.py", "_helper"): "the helper process forwards any failure to the main process, "
                                "which then builds the sections itself (and so raises it)",
}


def _modules():
    for f in sorted(REPORT.rglob("*.py")) + sorted((ROOT / "tmm_cli" / "drawings").rglob("*.py")):
        rel = f.relative_to(ROOT).with_suffix("")
        parts = list(rel.parts)
        package = parts[:-1]           # a package's __init__ and its modules: the same package
        if f.name == "__init__.py":
            parts = parts[:-1]
        yield f, ".".join(parts), package


def _imports(tree, package):
    for n in ast.walk(tree):
        if isinstance(n, ast.ImportFrom):
            if n.level:
                base = package[:len(package) - (n.level - 1)]
                mod = ".".join(base + ([n.module] if n.module else []))
            else:
                mod = n.module
            names = [a.name for a in n.names]
            yield n.lineno, mod, names
        elif isinstance(n, ast.Import):
            for a in n.names:
                yield n.lineno, a.name, []


def test_report_imports_no_stage_computation():
    bad = []
    for f, _, package in _modules():
        for line, mod, names in _imports(ast.parse(f.read_text(encoding="utf-8")), package):
            if not mod.startswith("tmm_cli") or mod.startswith("tmm_cli.report"):
                continue
            full = [mod] + [f"{mod}.{n}" for n in names]
            if not any(m in ALLOWED for m in full):
                bad.append(f"{f.relative_to(ROOT)}:{line}: imports {mod} {names}")
    assert not bad, "\n".join(bad)


def test_the_import_check_sees_a_stage_import(tmp_path):
    """The check above finds a relative import of a stage (as the report once had)."""
    tree = ast.parse("from ..linkage.kinematics.explore import explore_grid\nfrom tmm_cli.gears import Wheel\n")
    found = [m for _, m, _ in _imports(tree, ["tmm_cli", "report"])]
    assert found == ["tmm_cli.linkage.kinematics.explore", "tmm_cli.gears"]
    assert not set(found) & set(ALLOWED)


def test_the_import_check_resolves_a_packages_init():
    """A relative import in tmm_cli/report/__init__.py is resolved from tmm_cli.report
    (the check once read ``..linkage`` there as tmm_cli.report.linkage and let it pass)."""
    init = {f.name: package for f, _, package in _modules() if f.parent == REPORT}["__init__.py"]
    tree = ast.parse("from ..linkage import kinematics\nfrom .figures import place_labels\n")
    assert [m for _, m, _ in _imports(tree, init)] == ["tmm_cli.linkage", "tmm_cli.report.figures"]


def _broad(handler: ast.ExceptHandler) -> bool:
    t = handler.type
    if t is None:
        return True
    names = t.elts if isinstance(t, ast.Tuple) else [t]
    return any(isinstance(n, ast.Name) and n.id in ("Exception", "BaseException") for n in names)


def _handlers(tree):
    """(handler, name of the innermost function around it or None) of every except clause."""
    def walk(node, fn):
        for child in ast.iter_child_nodes(node):
            if isinstance(child, ast.ExceptHandler):
                yield child, fn
            yield from walk(child, child.name if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef))
                            else fn)
    yield from walk(tree, None)


def test_no_blind_except_in_the_report():
    bad = []
    for f, _, _ in _modules():
        for h, fn in _handlers(ast.parse(f.read_text(encoding="utf-8"))):
            if _broad(h) and (f.name, fn) not in BROAD_EXCEPT_OK:
                bad.append(f"{f.relative_to(ROOT)}:{h.lineno} (in {fn})")
    assert not bad, "broad except in the report:\n" + "\n".join(bad)


def test_the_except_check_sees_a_blind_except():
    tree = ast.parse("def f():\n    try:\n        g()\n    except Exception:\n        pass\n"
                     "    try:\n        g()\n    except (ValueError, BaseException):\n        pass\n"
                     "try:\n    g()\nexcept:\n    pass\ntry:\n    g()\nexcept OSError:\n    pass\n")
    assert [(h.lineno, fn, _broad(h)) for h, fn in _handlers(tree)] == \
        [(4, "f", True), (8, "f", True), (12, None, True), (16, None, False)]


# ------------------------------------------------------------------ figure failures
def _gears_results():
    from tmm_cli.gears import analyze
    return {"schema": "tmm-results/1", "warnings": [],
            "gears": analyze(gears(m=0.003, z=(12, 42), x=(0.63, 0.67))).to_dict()}


def _task_results(name):
    task = tmm_cli.load_task(ROOT / "tasks" / f"{name}.yaml")
    return task, tmm_cli.run(task, kinematics_curve=0, explore=False)


@pytest.mark.parametrize("section, func, source", [
    ("gears", "mesh_figure", "gears"), ("gears", "contour_figure", "gears"),
    ("cam", "profile_figure", "cam_rocker"), ("cam", "construction_figure", "cam_translating"),
    ("planetary", "figure", "planetary_A"), ("drive_train", "angular_plan", "press_drive_train"),
    ("dof2", "plots", "impact_rotor")])
def test_a_failing_figure_is_an_error(tmp_path, monkeypatch, section, func, source):
    """A figure that raises makes the report raise (no 'figure failed' text instead)."""
    import importlib

    from tmm_cli.report import render_html
    results = _gears_results() if source == "gears" else _task_results(source)[1]
    mod = importlib.import_module(f"tmm_cli.report.sections.{section}")

    def broken(*a, **k):
        raise RuntimeError("drawing bug")
    monkeypatch.setattr(mod, func, broken)
    with pytest.raises(RuntimeError, match="drawing bug"):
        render_html(results, None, tmp_path, "en")


# ------------------------------------------------------------------ the task is not read
_IDS = re.compile(r'\b(id|xlink:href|href|clip-path)="[^"]*"|url\(#[^)]*\)')

READER_TASKS = ["forging_sixbar", "shaper_slotted_lever", "cam_rocker", "gears_auto", "planetary_A", "press_drive_train",
                "impact_rotor", "synthesis_crank_rocker"]


@pytest.mark.parametrize("name", READER_TASKS)
def test_sections_do_not_read_the_task(tmp_path, name):
    """Every section but 'task' renders the same HTML with and without the task."""
    from tmm_cli.report import _build, _context
    from tmm_cli.report import sections
    task, results = _task_results(name)
    names = [n for n, _ in sections.available() if n != "task"]
    with_task = _build(_context(results, task, tmp_path / "a", "en"), names)
    without = _build(_context(results, None, tmp_path / "b", "en"), names)
    shown = [n for n in names if with_task[n]]
    assert shown, name
    for n in names:
        a, b = (None if x is None else _IDS.sub("", x) for x in (with_task[n], without[n]))
        assert a == b, (name, n)


# ------------------------------------------------------------------ what the figures need
def _area(ring) -> float:
    r = np.asarray(ring, float)
    return 0.5 * abs(float(np.dot(r[:, 0], np.roll(r[:, 1], 1)) - np.dot(r[:, 1], np.roll(r[:, 0], 1))))


@pytest.mark.parametrize("x", [(0.63, 0.67), (0.0, 0.0), "auto"])
def test_gears_region_is_the_admissible_set(x):
    """results['gears']['blocking_contour']['region'] (shaded in the report) is where every check
    holds: its area is the admissible fraction of the window, and points well inside / outside
    it pass / fail the checks written out here from the closed forms."""
    from matplotlib.path import Path as MPath

    from tmm_cli.gears import analyze
    from tmm_cli.gears.geometry import pair
    m, z1, z2 = 0.003, 12, 42
    g = analyze(gears(m=m, z=(z1, z2), x=x)).to_dict()
    bc = g["blocking_contour"]
    (a1, b1), (a2, b2) = bc["x1_range"], bc["x2_range"]
    box = (b1 - a1) * (b2 - a2)
    area = sum(_area(p[0]) - sum(_area(h) for h in p[1:]) for p in bc["region"])
    cell = max(b1 - a1, b2 - a2) / 160
    perimeter = sum(float(np.sum(np.hypot(*np.diff(np.asarray(r), axis=0).T))) for p in bc["region"] for r in p)
    assert area / box == pytest.approx(bc["admissible_fraction"], abs=perimeter * cell / box + 1e-9)
    paths = [MPath(np.asarray(r)) for p in bc["region"] for r in p]
    rng = np.random.default_rng(1)
    X = np.column_stack([rng.uniform(a1, b1, 400), rng.uniform(a2, b2, 400)])
    inside = np.zeros(len(X), bool)
    for k, p in enumerate(paths):        # even-odd: holes cancel
        inside ^= p.contains_points(X)
    near = np.zeros(len(X), bool)
    for p in paths:
        v = p.vertices
        d = np.min(np.hypot(X[:, None, 0] - v[None, :, 0], X[:, None, 1] - v[None, :, 1]), axis=1)
        near |= d < 3 * cell
    geo = pair(m, z1, z2, X[:, 0], X[:, 1])
    ok = (geo["valid"] & (X[:, 0] >= geo["x_min1"]) & (X[:, 1] >= geo["x_min2"])
          & (geo["sa1"] / m >= 0.25) & (geo["sa2"] / m >= 0.25) & (geo["eps"] >= 1.2)
          & (geo["rho_p1"] >= np.maximum(geo["rho_l1"], 0)) & (geo["rho_p2"] >= np.maximum(geo["rho_l2"], 0)))
    far = ~near
    assert far.sum() > 300
    assert np.array_equal(inside[far], ok[far])


def test_results_hold_the_driving_link_and_the_fine_grid():
    task, _ = _task_results("forging_sixbar")
    r = tmm_cli.run(task, kinematics_curve=0, explore=True)
    assert r["structure"]["drive_link"] == task.drive.link
    ex = r["kinematics_explore"]
    assert len(ex["turn"]) == 360 and ex["step"] == 1.0
    # the grid's first angle is position 0: the same point positions as results' kinematics
    k0 = r["kinematics"][0]
    for p, d in k0["points"].items():
        assert ex["points"][p]["x"][0] == pytest.approx(d["x"], rel=1e-6, abs=1e-12)
        assert ex["points"][p]["vy"][0] == pytest.approx(d["vy"], rel=1e-6, abs=1e-9)
    assert "kinematics_explore" not in tmm_cli.run(task, kinematics_curve=0, explore=False)


def test_the_widget_shows_the_results_grid(tmp_path):
    """The mechanism in motion embeds results['kinematics_explore'] as it is; without it
    there is no widget (the task is not used to make one)."""
    import json

    from tmm_cli.report import _context, explore
    task, _ = _task_results("crank_rocker_fourbar")
    r = tmm_cli.run(task, kinematics_curve=0, explore=True)
    frag = explore.fragment(_context(r, None, tmp_path, "en"))
    data = re.search(r'<script type="application/json" id="ex-data">(.*?)</script>', frag, re.S).group(1)
    assert json.loads(data) == json.loads(json.dumps(r["kinematics_explore"]))
    r.pop("kinematics_explore")
    assert explore.fragment(_context(r, task, tmp_path, "en")) is None


def test_the_fine_grid_is_made_for_the_html_report_only(tmp_path):
    """A JSON run neither computes nor writes the widget's grid; an HTML run draws the
    widget from it, and its results.json is the JSON run's, byte for byte."""
    from typer.testing import CliRunner

    from tmm_cli.cli import app
    task_file = str(ROOT / "tasks" / "crank_rocker_fourbar.yaml")
    runner = CliRunner()
    for fmt in ("json", "json,html"):
        res = runner.invoke(app, ["run", task_file, "--out", str(tmp_path / fmt), "--format", fmt, "--quiet"])
        assert res.exit_code == 0, res.output
    a = (tmp_path / "json" / "results.json").read_bytes()
    assert a == (tmp_path / "json,html" / "results.json").read_bytes()
    assert b"kinematics_explore" not in a
    assert 'id="ex-data"' in (tmp_path / "json,html" / "report.html").read_text()


def test_wittenbauer_caption_reads_the_result(tmp_path):
    """The caption's J is results' J_wittenbauer; checked against the construction's own
    numbers: J = (k - l) / (omega_m^2 delta), k, l the cuts of the tangents on the dT axis."""
    from tmm_cli.report import render_html
    task, r = _task_results("engine_slider_crank")
    d = r["flywheel"]
    em, wm, delta, Jc = d["energy_mass"], d["omega_m"], d["delta"], d["J_const"]
    k = em["a_wittenbauer"] - Jc * wm ** 2 * (1 + delta) / 2
    l_ = em["b_wittenbauer"] - Jc * wm ** 2 * (1 - delta) / 2
    assert d["J_wittenbauer"] == pytest.approx((k - l_) / (wm ** 2 * delta), rel=1e-12)
    html = render_html(r, task, tmp_path, "en")[0]
    from tmm_cli.report.context import fmt
    assert f"J = {fmt(d['J_wittenbauer'], 5)}" in html or fmt(d["J_wittenbauer"], 5) in html
    assert math.isfinite(d["J_wittenbauer"])
