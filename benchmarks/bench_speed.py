"""Speed targets of issue 12 as ratios measured side by side in one run.

The machine may be shared and noisy, so every figure is a ratio of two things timed
interleaved (A, B, A, B, ...), each repeated (>= 5 times); medians and the spread
(min-max) are printed.

* JSON run and `tmm validate` of tasks/forging_sixbar.yaml (and of each task of --tasks)
  against the interpreter's floor `python -c "import numpy, pydantic, yaml"` (target <= 2x);
* with --report: the whole report (HTML + PDF) against the JSON run of the same task
  (target <= 4x; absolute wall and CPU printed too), and the HTML report of a
  3600-position grid against the 12-position task (target <= 2x): the whole
  `tmm run --format html` (pipeline and results.json included) and the report alone
  (`report.render` in one process, the results computed beforehand);
* the kinematics core (tmm_cli.linkage.kinematics.solve) against a hand-written numpy closed
  form of the same central slider-crank and four-bar, N = 36 ... 36000 (target <= 3x at
  N >= 3600), and the fixed cost per call;
* with --batch: `tmm batch` of 300 variants of the forging machine (kinetostatics and
  flywheel) with --jobs 2 --format json (target <= 15 s wall), interleaved with one JSON
  run of the same task;
* with --kinetostatics: loads + kinetostatics + the results entries at 36,000 positions of
  the six-bar of bench_kinetostatics.py, each in a fresh process (target <= 1 s and
  <= 200 MB peak), interleaved with the kinematics alone at the same positions.

The commands run as an installed tmm does: with the bytecode cache (pip compiles it at
install), so a PYTHONDONTWRITEBYTECODE of the environment is dropped for them (the cache
goes to a temporary PYTHONPYCACHEPREFIX).

Run: python benchmarks/bench_speed.py [--report] [--batch] [--kinetostatics] [--repeat 5]
                                      [--tasks engine_slider_crank,gears_zero]
"""
from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
TASK = ROOT / "tasks" / "forging_sixbar.yaml"


# ----------------------------------------------------------------- processes
def _child_cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


_ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
_ENV["PYTHONPYCACHEPREFIX"] = os.path.join(tempfile.gettempdir(), "tmm-bench-pycache")


def _run(cmd: list[str]) -> tuple[float, float]:
    """(wall, cpu) of one subprocess."""
    c0, t0 = _child_cpu(), time.perf_counter()
    p = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT, env=_ENV)
    wall, cpu = time.perf_counter() - t0, _child_cpu() - c0
    if p.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)} failed ({p.returncode}):\n{p.stderr[-2000:]}")
    return wall, cpu


def _interleaved(cmds: dict[str, list[str]], repeat: int) -> dict[str, list[tuple[float, float]]]:
    out: dict[str, list[tuple[float, float]]] = {k: [] for k in cmds}
    for k, c in cmds.items():        # one warm-up each (disk cache, pint/matplotlib caches)
        _run(c)
    for _ in range(repeat):
        for k, c in cmds.items():
            out[k].append(_run(c))
    return out


def _stat(xs: list[float]) -> str:
    return f"{statistics.median(xs):7.3f} [{min(xs):.3f}-{max(xs):.3f}]"


def _ratio_line(name: str, num: list[float], den: list[float], target: float | None) -> None:
    ratios = [a / b for a, b in zip(num, den)]
    med = statistics.median(ratios)
    verdict = "" if target is None else ("ok" if med <= target else "OVER")
    tgt = "" if target is None else f"(target <= {target:g})"
    print(f"  {name:46s} ratio median {med:6.2f} [{min(ratios):.2f}-{max(ratios):.2f}] {tgt} {verdict}")


def cli(repeat: int, report: bool, tasks: list[str] = ()) -> None:
    py = [sys.executable]
    tmm = py + ["-m", "tmm_cli"]
    with tempfile.TemporaryDirectory() as tmp:
        cmds = {"floor": py + ["-c", "import numpy, pydantic, yaml"],
                "validate": tmm + ["validate", str(TASK)],
                "json": tmm + ["run", str(TASK), "--format", "json", "--quiet", "--out", f"{tmp}/j"]}
        for name in tasks:
            path = str(ROOT / "tasks" / f"{name}.yaml")
            cmds[f"validate:{name}"] = tmm + ["validate", path]
            cmds[f"json:{name}"] = tmm + ["run", path, "--format", "json", "--quiet", "--out", f"{tmp}/{name}"]
        if report:
            fine = Path(tmp) / "fine.yaml"
            fine.write_text(TASK.read_text(encoding="utf-8").replace("count: 12", "count: 3600"),
                            encoding="utf-8")
            cmds["report"] = tmm + ["run", str(TASK), "--quiet", "--out", f"{tmp}/r"]
            cmds["html12"] = tmm + ["run", str(TASK), "--format", "html", "--quiet", "--out", f"{tmp}/h"]
            cmds["html3600"] = tmm + ["run", str(fine), "--format", "html", "--quiet", "--out", f"{tmp}/f"]
        res = _interleaved(cmds, repeat)
    print(f"command line, {TASK.name}, {repeat} interleaved rounds; wall / cpu in s: median [min-max]")
    for k, v in res.items():
        print(f"  {k:10s} wall {_stat([x for x, _ in v])}   cpu {_stat([y for _, y in v])}")
    w = {k: [x for x, _ in v] for k, v in res.items()}
    c = {k: [x for _, x in v] for k, v in res.items()}
    _ratio_line("run --format json / import floor (wall)", w["json"], w["floor"], 2.0)
    _ratio_line("run --format json / import floor (cpu)", c["json"], c["floor"], 2.0)
    _ratio_line("validate / import floor (wall)", w["validate"], w["floor"], 2.0)
    _ratio_line("validate / import floor (cpu)", c["validate"], c["floor"], 2.0)
    for name in tasks:
        for what in ("json", "validate"):
            _ratio_line(f"{what} {name} / import floor (wall)", w[f"{what}:{name}"], w["floor"], 2.0)
            _ratio_line(f"{what} {name} / import floor (cpu)", c[f"{what}:{name}"], c["floor"], 2.0)
    if report:
        _ratio_line("report html+pdf / json run (wall)", w["report"], w["json"], 4.0)
        _ratio_line("report html+pdf / json run (cpu)", c["report"], c["json"], None)
        _ratio_line("html report 3600 positions / 12 (wall)", w["html3600"], w["html12"], 2.0)
        _ratio_line("html report 3600 positions / 12 (cpu)", c["html3600"], c["html12"], 2.0)
        print(f"  whole report absolute: wall {statistics.median(w['report']):.2f} s (target <= 3), "
              f"cpu {statistics.median(c['report']):.2f} s (target <= 4)")
        report_scaling(repeat)


def report_scaling(repeat: int) -> None:
    """The report alone (HTML: sections, figures, CSV files, report.html) of the
    3600-position grid against the 12-position task, interleaved in one process."""
    import tmm_cli
    from tmm_cli.report import render
    from tmm_cli.results import dumps
    import json
    fine_task = tmm_cli.load_task(TASK, text=TASK.read_text(encoding="utf-8").replace("count: 12", "count: 3600"))
    task = tmm_cli.load_task(TASK)
    cases = {n: (t, json.loads(dumps(tmm_cli.run(t)))) for n, t in (("12", task), ("3600", fine_task))}
    out: dict[str, list[tuple[float, float]]] = {k: [] for k in cases}
    with tempfile.TemporaryDirectory() as tmp:
        for k in range(repeat + 1):
            for n, (t, r) in cases.items():
                c0, t0 = time.process_time() + _child_cpu(), time.perf_counter()
                render(r, t, Path(tmp) / f"{n}-{k}", {"html"}, "en")
                if k:                                       # the first round warms up
                    out[n].append((time.perf_counter() - t0, time.process_time() + _child_cpu() - c0))
    print(f"report alone (render, html), {repeat} interleaved rounds: wall / cpu in s")
    for n, v in out.items():
        print(f"  {n:>4s} positions wall {_stat([x for x, _ in v])}   cpu {_stat([y for _, y in v])}")
    _ratio_line("report alone 3600 positions / 12 (wall)", [x for x, _ in out["3600"]],
                [x for x, _ in out["12"]], 2.0)
    _ratio_line("report alone 3600 positions / 12 (cpu)", [y for _, y in out["3600"]],
                [y for _, y in out["12"]], 2.0)


# ----------------------------------------------------------------- kinematics core
SLIDER_CRANK = {"schema": "tmm/1", "mechanism": {
    "ground": {"O": [0, 0]},
    "links": {"crank": {"points": ["O", "A"], "length": 0.045},
              "rod": {"points": ["A", "B"], "length": 0.170},
              "piston": {"slider": "B", "guide": {"through": "O", "angle": 90}}},
    "assembly": {"B": [0, 0.16]}},
    "drive": {"link": "crank", "speed": "3000 rpm"}}
FOUR_BAR = {"schema": "tmm/1", "mechanism": {
    "ground": {"O": [0, 0], "O3": [0.30, 0]},
    "links": {"crank": {"points": ["O", "A"], "length": 0.08},
              "coupler": {"points": ["A", "B"], "length": 0.30},
              "rocker": {"points": ["O3", "B"], "length": 0.22}},
    "assembly": {"B": [0.33, 0.21]}},
    "drive": {"link": "crank", "speed": "120 rpm"}}


def slider_crank_closed(phi_deg, r=0.045, l=0.170):
    """Central slider-crank, guide along y through O: positions of A, B, the rod angle
    and their first and second derivatives in phi (the same quantities tmm returns)."""
    f = np.radians(phi_deg)
    c, s = np.cos(f), np.sin(f)
    R = np.sqrt(l * l - (r * c) ** 2)
    y = r * s + R
    g = r * r * c * s / R
    y1 = r * c + g
    y2 = -r * s + r * r * (c * c - s * s) / R - g * g / R
    A, A1, A2 = np.stack([r * c, r * s], 1), np.stack([-r * s, r * c], 1), np.stack([-r * c, -r * s], 1)
    ux, uy = -r * c / l, (y - r * s) / l
    th = np.arctan2(uy, ux)
    th1 = (ux * (y1 - r * c) - uy * (r * s)) / l
    th2 = (ux * (y2 + r * s) - uy * (r * c)) / l
    z = np.zeros_like(y)
    return A, A1, A2, np.stack([z, y], 1), np.stack([z, y1], 1), np.stack([z, y2], 1), th, th1, th2


def four_bar_closed(phi_deg, a=0.08, b=0.30, c=0.22, d=0.30):
    """Crank-rocker O-A-B-O3 (O3 = (d, 0)), the assembly with B above the line A-O3."""
    f = np.radians(phi_deg)
    cf, sf = np.cos(f), np.sin(f)
    A = np.stack([a * cf, a * sf], 1)
    A1 = np.stack([-a * sf, a * cf], 1)
    A2 = -A
    AC = np.array([d, 0.0]) - A
    L = np.hypot(AC[:, 0], AC[:, 1])
    base = np.arctan2(AC[:, 1], AC[:, 0])
    gam = np.arccos((b * b + L * L - c * c) / (2 * b * L))
    t2 = base + gam                       # coupler angle (B to the left of A->O3)
    B = A + b * np.stack([np.cos(t2), np.sin(t2)], 1)
    t3 = np.arctan2(B[:, 1], B[:, 0] - d)
    e2, e3 = np.stack([-np.sin(t2), np.cos(t2)], 1), np.stack([-np.sin(t3), np.cos(t3)], 1)
    # A1 + w2 b e2 = w3 c e3  ->  2x2 by Cramer
    det = -b * e2[:, 0] * c * e3[:, 1] + b * e2[:, 1] * c * e3[:, 0]
    rx, ry = -A1[:, 0], -A1[:, 1]
    w2 = (rx * (-c * e3[:, 1]) - ry * (-c * e3[:, 0])) / det
    w3 = (b * e2[:, 0] * ry - b * e2[:, 1] * rx) / det
    B1 = c * w3[:, None] * e3
    u2 = np.stack([np.cos(t2), np.sin(t2)], 1)
    u3 = np.stack([np.cos(t3), np.sin(t3)], 1)
    # A2 + a2 b e2 - w2^2 b u2 = a3 c e3 - w3^2 c u3
    rhs = -A2 + (w2 ** 2)[:, None] * b * u2 - (w3 ** 2)[:, None] * c * u3
    rx, ry = rhs[:, 0], rhs[:, 1]
    al2 = (rx * (-c * e3[:, 1]) - ry * (-c * e3[:, 0])) / det
    al3 = (b * e2[:, 0] * ry - b * e2[:, 1] * rx) / det
    B2 = c * al3[:, None] * e3 - c * (w3 ** 2)[:, None] * u3
    return A, A1, A2, B, B1, B2, t2, w2, al2, t3, w3, al3


def _time_calls(fn, n_calls: int) -> float:
    t0 = time.perf_counter()
    for _ in range(n_calls):
        fn()
    return (time.perf_counter() - t0) / n_calls


def kinematics(repeat: int) -> None:
    from tmm_cli.linkage.kinematics import solve
    from tmm_cli.linkage.mechanism import build_mechanism
    from tmm_cli.task import load_task
    cases = [("slider-crank", build_mechanism(load_task(SLIDER_CRANK)), slider_crank_closed, "B", "rod"),
             ("four-bar", build_mechanism(load_task(FOUR_BAR)), four_bar_closed, "B", "rocker")]
    print(f"kinematics core vs numpy closed form, {repeat} interleaved rounds; time per call, "
          "median [min-max]")
    for name, mech, closed, pt, link in cases:
        phi = np.linspace(0.0, 360.0, 3600, endpoint=False)
        k = solve(mech, phi, 1.0)                 # same mechanism, same branch: check first
        ref = closed(phi)
        assert np.allclose(k.pos[pt], ref[3], atol=1e-9), f"{name}: not the same assembly"
        assert np.allclose(k.d2[pt], ref[5], atol=1e-8), f"{name}: second derivatives differ"
        for n in (36, 360, 3600, 36000):
            phi = np.linspace(0.0, 360.0, n, endpoint=False)
            calls = max(1, 20000 // n)
            ts, tc = [], []
            for _ in range(repeat):
                ts.append(_time_calls(lambda: solve(mech, phi, 1.0), calls))
                tc.append(_time_calls(lambda: closed(phi), calls))
            r = [a / b for a, b in zip(ts, tc)]
            tgt = " (target <= 3)" if n >= 3600 else ""
            print(f"  {name:12s} N={n:6d}  tmm {statistics.median(ts) * 1e3:8.3f} ms   closed form "
                  f"{statistics.median(tc) * 1e3:8.3f} ms   ratio {statistics.median(r):6.2f} "
                  f"[{min(r):.2f}-{max(r):.2f}]{tgt}")


# ----------------------------------------------------------------- batch
def batch(repeat: int, n: int) -> None:
    """`tmm batch` of n variants (crank speed 40-69 rpm, upsetting force 10-20 kN) with
    --jobs 2 --format json, interleaved with one JSON run of the task."""
    py = [sys.executable, "-m", "tmm_cli"]
    src = TASK.read_text(encoding="utf-8")
    with tempfile.TemporaryDirectory() as tmp:
        d = Path(tmp) / "variants"
        d.mkdir()
        for i in range(n):
            f = 10 + i % 11
            (d / f"v{i + 1:03d}.yaml").write_text(
                src.replace("variant: 7", f"variant: {i + 1}").replace("speed: 50 rpm", f"speed: {40 + i % 30} rpm")
                .replace("15 kN, 15 kN", f"{f} kN, {f} kN"), encoding="utf-8")
        cmds = {"batch": py + ["batch", str(d), "--jobs", "2", "--format", "json", "--out", f"{tmp}/b"],
                "json": py + ["run", str(TASK), "--format", "json", "--quiet", "--out", f"{tmp}/j"]}
        res = _interleaved(cmds, repeat)
    w = {k: [x for x, _ in v] for k, v in res.items()}
    c = {k: [x for _, x in v] for k, v in res.items()}
    print(f"batch of {n} variants, --jobs 2 --format json, {repeat} interleaved rounds; s: median [min-max]")
    print(f"  batch      wall {_stat(w['batch'])}   cpu {_stat(c['batch'])}   "
          f"(target <= 15 s wall) {'ok' if statistics.median(w['batch']) <= 15 else 'OVER'}")
    print(f"  json run   wall {_stat(w['json'])}   cpu {_stat(c['json'])}")
    print(f"  per variant: wall {statistics.median(w['batch']) / n * 1e3:.0f} ms, "
          f"cpu {statistics.median(c['batch']) / n * 1e3:.0f} ms")
    _ratio_line(f"batch of {n} / one json run (wall)", w["batch"], w["json"], None)


# ----------------------------------------------------------------- kinetostatics at 36,000
_KS_CODE = """
import resource, sys, time
sys.path.insert(0, {bench!r})
import numpy as np
from bench_kinetostatics import SIX
from tmm_cli import load_task
from tmm_cli.linkage import kinematics, structure
from tmm_cli.linkage.kinetostatics import analyze, find_singular
from tmm_cli.linkage.loads import evaluate
from tmm_cli.linkage.mechanism import build_mechanism
task = load_task(SIX); mech = build_mechanism(task); st = structure.analyze(mech)
pos = kinematics.find_positions(mech, task.positions, task.drive)
sing = find_singular(mech, st, "crank")
phi = np.mod(pos.phi0 + np.arange({n}) * 360.0 / {n}, 360.0)
base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
t0, c0 = time.perf_counter(), time.process_time()
kin = kinematics.solve(mech, phi, task.drive.omega1)
if {full}:
    lds = evaluate(mech, task.loads, kin, pos, inertia=True)
    d = analyze(mech, st, kin, lds, task.kinetostatics, singular=sing).to_dict()
print(time.perf_counter() - t0, time.process_time() - c0,
      (resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - base) / 1024.0,
      resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0)
"""


def kinetostatics_big(repeat: int, n: int = 36000) -> None:
    out: dict[str, list[list[float]]] = {"kinetostatics": [], "kinematics": []}
    for _ in range(repeat):
        for name, full in (("kinetostatics", True), ("kinematics", False)):
            code = _KS_CODE.format(bench=str(ROOT / "benchmarks"), n=n, full=full)
            p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, env=_ENV,
                               check=True)
            out[name].append([float(x) for x in p.stdout.split()])
    print(f"kinetostatics at {n} positions (six-bar with friction: loads, three methods, the results "
          f"entries), {repeat} interleaved rounds, each in a fresh process")
    for name, rows in out.items():
        cols = list(zip(*rows))
        print(f"  {name:14s} wall {_stat(list(cols[0]))} s   cpu {_stat(list(cols[1]))} s   "
              f"peak memory added {_stat(list(cols[2]))} MB (process peak {statistics.median(cols[3]):.0f} MB)")
    k = list(zip(*out["kinetostatics"]))
    print(f"  target: <= 1 s {'ok' if statistics.median(k[1]) <= 1 else 'OVER'} (cpu), "
          f"<= 200 MB {'ok' if statistics.median(k[3]) <= 200 else 'OVER'} (process peak)")
    _ratio_line("kinetostatics / kinematics alone (cpu)", list(k[1]), [r[1] for r in out["kinematics"]], None)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--report", action="store_true", help="also time the whole report (slow)")
    ap.add_argument("--batch", action="store_true", help="also time a batch of 300 variants (slow)")
    ap.add_argument("--variants", type=int, default=300)
    ap.add_argument("--kinetostatics", action="store_true", help="also kinetostatics at 36,000 positions")
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--tasks", default="", help="more tasks (names in tasks/, comma-separated) for the floor ratios")
    ap.add_argument("--no-cli", action="store_true")
    ap.add_argument("--no-kinematics", action="store_true")
    a = ap.parse_args()
    print(f"{os.cpu_count()} cores, load average {os.getloadavg()[0]:.2f}")
    if not a.no_cli:
        cli(max(5, a.repeat), a.report, [t for t in a.tasks.split(",") if t])
    if a.batch:
        batch(max(5, a.repeat), a.variants)
    if a.kinetostatics:
        kinetostatics_big(max(5, a.repeat))
    if not a.no_kinematics:
        kinematics(max(5, a.repeat))


if __name__ == "__main__":
    main()
