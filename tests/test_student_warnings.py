"""Warnings a student needs (what the input says is valid but probably not meant): the working
stroke set to the quick one (K < 1), links without mass where inertia is taken into account,
a misspelt point of a link that was meant as a ground point."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np

import tmm_cli
from tmm_cli.messages import render

ROOT = Path(__file__).resolve().parents[1]
FOURBAR = (ROOT / "tasks" / "crank_rocker_fourbar.yaml").read_text(encoding="utf-8")


def _run(tmp_path, text: str) -> dict:
    path = tmp_path / "task.yaml"
    path.write_text(text, encoding="utf-8")
    return tmm_cli.run(tmm_cli.load_task(path), kinematics_curve=0)


def _codes(results: dict, code: str) -> list[dict]:
    return [m for m in results["messages"] if m["code"] == code]


def test_quick_working_stroke_names_the_slow_one(tmp_path):
    ok = _run(tmp_path, FOURBAR)
    assert ok["positions"]["K"] > 1 and not _codes(ok, "positions.quick_working")
    r = _run(tmp_path, FOURBAR.replace("working: forward", "working: backward"))
    assert r["positions"]["K"] < 1
    (m,) = _codes(r, "positions.quick_working")
    assert m["params"]["slow"] == "forward" and m["params"]["link"] == "rocker"
    assert "the slow stroke is the forward one" in m["text"]
    assert "медленный ход — прямой" in render(m["code"], m["params"], "ru")
    assert "повільний хід — прямий" in render(m["code"], m["params"], "uk")
    assert "K = 0,878 < 1" in render(m["code"], m["params"], "uk")
    # results.json keeps K as computed (positions.K); only the text shows it to three digits
    assert m["params"]["K"] == r["positions"]["K"] != 0.878 and "(K = 0.878 < 1)" in m["text"]


def test_a_k_just_below_one_is_not_shown_as_one():
    """K = 0.99962 with three digits would read "K = 1 < 1": as many digits as show it below 1."""
    from tmm_cli.linkage.kinematics.positions import PositionsResult, stroke_warnings
    pos = PositionsResult.__new__(PositionsResult)
    for name, value in (("K", 0.99962), ("working", "forward"), ("output", "slider"), ("rests", [])):
        object.__setattr__(pos, name, value)
    (m,) = stroke_warnings(pos)
    assert "(K = 0.9996 < 1)" in m and "(K = 0,9996 < 1)" in render(m.code, m.params, "ru")
    assert m.params["K"] == 0.99962                             # the data as computed
    object.__setattr__(pos, "K", 0.5)
    assert "(K = 0.5 < 1)" in stroke_warnings(pos)[0]
    object.__setattr__(pos, "K", 1.0 - 3e-9)                    # below 1 only in the ninth digit
    assert "(K = 0.999999997 < 1)" in stroke_warnings(pos)[0]
    object.__setattr__(pos, "K", 1.0 - 1e-12)                   # 1 to round-off: no quick stroke
    assert stroke_warnings(pos) == []


def test_links_without_mass_are_named_where_inertia_counts(tmp_path):
    assert not _codes(_run(tmp_path, FOURBAR), "inertia.massless")
    text = FOURBAR.replace("length: 0.30, extra: {M: [0.15, 0.06]}, mass: 2.4,", "length: 0.30, extra: {M: [0.15, 0.06]},")
    assert text != FOURBAR
    (m,) = _codes(_run(tmp_path, text), "inertia.massless")
    assert m["params"]["links"] == ["coupler"] and "links coupler have no mass" in m["text"]
    # inertia off: the masses play no part, no warning
    off = text.replace("  balance: crank", "  balance: crank\n  inertia: false")
    assert off != text and not _codes(_run(tmp_path, off), "inertia.massless")
    # with a flywheel the reduced moment of inertia is named too
    fly = (ROOT / "tasks" / "forging_sixbar.yaml").read_text(encoding="utf-8")
    r = _run(tmp_path, fly)
    massless = [l["name"] for l in r["structure"]["links"] if not l["mass"] > 0]
    hit = _codes(r, "inertia.massless_flywheel")
    assert [m["params"]["links"] for m in hit] == ([massless] if massless else [])
    assert "reduced moment of inertia" in render("inertia.massless_flywheel", {"links": ["a"]}, "en")


def test_misspelt_point_named_at_its_link(tmp_path):
    """`rocker: [O2, B]` with the ground point O3: the error points at the rocker's line and
    names O2 with 'did you mean' O3 (was: 'O3 is used by no link' at the ground line)."""
    path = tmp_path / "bad.yaml"
    path.write_text(FOURBAR.replace("rocker:  {points: [O3, B]", "rocker:  {points: [O2, B]"), encoding="utf-8")
    line = next(i for i, s in enumerate(path.read_text(encoding="utf-8").splitlines(), 1) if "[O2, B]" in s)
    p = subprocess.run([sys.executable, "-m", "tmm_cli", "run", str(path), "--format", "json", "--out",
                        str(tmp_path / "out")], capture_output=True, text=True)
    assert p.returncode == 2 and "Traceback" not in p.stderr
    assert f"bad.yaml:{line}:" in p.stderr and "mechanism.links.rocker.points" in p.stderr
    assert "'O2'" in p.stderr and "did you mean the ground point 'O3'" in p.stderr
    # a ground point no link uses and no point like it: the ground line, as before
    path.write_text(FOURBAR.replace("    O3: [0.30, 0]\n", "    O3: [0.30, 0]\n    Q: [1, 1]\n"), encoding="utf-8")
    p = subprocess.run([sys.executable, "-m", "tmm_cli", "run", str(path), "--format", "json", "--out",
                        str(tmp_path / "out")], capture_output=True, text=True)
    assert p.returncode == 2 and "ground point 'Q' is used by no link" in p.stderr


def test_an_output_that_stands_still_is_told(tmp_path):
    """A central slider-crank whose rod equals its crank (r = l = 0.1 m) folds at its change point
    (phi = 90 deg: B at O) onto the branch where B stays at O until 270 deg (x_B = r cos phi + l cos
    psi with psi = pi - phi there: 0); its extreme positions there are no one angle, so K is one
    choice and is told; the interval found on the 0.5-degree scan is 90..270 to a step. A
    slider-crank with l = 2r moves everywhere but at its two dead centres: nothing told."""
    import tmm_cli
    from tmm_cli.linkage.kinematics.positions import rests
    text = """schema: tmm/1
mechanism:
  ground: {O: [0, 0]}
  links:
    crank:  {points: [O, A], length: 0.1}
    rod:    {points: [A, B], length: ROD}
    slider: {slider: B, guide: {through: O, angle: 0}}
drive: {link: crank, speed: 100 rpm}
positions: {count: 12, zero: 0, output: slider}
"""
    f = tmp_path / "t.yaml"
    f.write_text(text.replace("ROD", "0.1"), encoding="utf-8")
    res = tmm_cli.run(tmm_cli.load_task(f))
    (m,) = [w for w in res["messages"] if w["code"] == "positions.output_rests"]
    (a, b), = m["params"]["intervals"]
    assert abs(a - 90) <= 0.5 + 1e-9 and abs(b - 270) <= 0.5 + 1e-9
    # the extreme taken in the rest is where the crank brings the slider there, the change point
    # (90 deg ccw, 270 cw), not one of the ~200 roots of the analogue's round-off inside it (98.09 deg)
    assert m["params"]["extreme"] == res["positions"]["extreme"] == [90.0, 0.0]
    f.write_text(text.replace("ROD", "0.1").replace("100 rpm}", "100 rpm, direction: cw}"), encoding="utf-8")
    cw = tmm_cli.run(tmm_cli.load_task(f))
    assert cw["positions"]["extreme"] == [270.0, 0.0]
    # the same for another link's stroke (a stroke-dependent load's): its extremes as the output's
    from tmm_cli.linkage.kinematics.positions import link_stroke
    from tmm_cli.linkage.mechanism import build_mechanism
    assert link_stroke(build_mechanism(tmm_cli.load_task(f)), "slider", "forward", -1.0).extreme == [270.0, 0.0]
    f.write_text(text.replace("ROD", "0.2"), encoding="utf-8")
    res = tmm_cli.run(tmm_cli.load_task(f))
    assert not [w for w in res["messages"] if w["code"] == "positions.output_rests"]
    # the scan's rule on its own: a run of 1 deg or less is a dead centre, not a rest; one across 0 wraps
    ds = np.sin(np.radians(np.arange(0, 360, 0.5)))
    assert rests(ds) == []
    ds[10:20] = 0.0
    assert rests(ds) == [[5.0, 9.5]]
    ds = np.ones(720)
    ds[-4:], ds[:4] = 0.0, 0.0
    assert rests(ds) == [[358.0, 1.5]]
    # one extreme a rest, where the crank brings the output there (at a change point within a step
    # of it); the roots of the round-off inside it gone, those outside kept; a rest across 0 and
    # one over the whole turn
    from tmm_cli.linkage.kinematics.positions import _one_per_rest

    def f(x):
        return np.full(len(x), 7.0), np.zeros(len(x))
    ext = [(10.0, 1.0), (92.3, 0.0), (150.0, 0.0), (300.0, 2.0)]
    assert _one_per_rest(ext, [[90.5, 269.5]], [90.0, 270.0], 1.0, f) == [(10.0, 1.0), (90.0, 7.0), (300.0, 2.0)]
    assert _one_per_rest(ext, [[90.5, 269.5]], [], -1.0, f) == [(10.0, 1.0), (269.5, 7.0), (300.0, 2.0)]
    assert _one_per_rest([(359.2, 0.0), (0.7, 0.0), (10.0, 1.0)], [[358.0, 1.5]], [], 1.0, f) == [(10.0, 1.0),
                                                                                                 (358.0, 7.0)]
    assert _one_per_rest(ext, [[0.0, 360.0]], [], 1.0, f) == [(0.0, 7.0)]
