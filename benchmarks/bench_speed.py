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
  form of the same central slider-crank and four-bar computing the same outputs, and against
  pylinkage's numba solver when installed, N = 36 ... 36000 (targets: <= 3x the closed form
  at N >= 3600, faster than pylinkage at N >= 360): bench_kinematics.core;
* with --batch: `tmm batch` of 300 variants of the forging machine (kinetostatics and
  flywheel) with --jobs 2 --format json (target <= 15 s wall), interleaved with one JSON
  run of the same task;
* with --kinetostatics: loads + kinetostatics + the results entries at 36,000 positions of
  the six-bar of bench_kinetostatics.py, each in a fresh process (target <= 1 s and
  <= 200 MB peak; the entries are made when read, so every one is made once, as the
  results file's writer reads them; then, timed apart, the stage's sections written as
  results.json is, to a null sink), interleaved with the kinematics alone at the same positions, and with
  `tmm run --format json` of the six-bar at 3600 positions (the most `positions.count`
  allows) and at 12, and the import floor (CPU and peak RSS of each process).

The commands run as an installed tmm does: with the bytecode cache (pip compiles it at
install), so a PYTHONDONTWRITEBYTECODE of the environment is dropped for them (the cache
goes to a temporary PYTHONPYCACHEPREFIX).

* with --against DIR: the JSON run and `tmm validate` (with --report also the whole report)
  of this checkout and of another one (DIR: e.g. `git archive <commit> | tar -x -C DIR`),
  and the import floor, all interleaved (not with --no-cli); with --scaling also DIR's html
  runs at 12 and 3600 positions, interleaved with this checkout's; with --batch also the batch run
  by DIR, and with --kinetostatics DIR's loads + kinetostatics + entries at 36,000 positions,
  interleaved with this checkout's.
* with --scaling: `tmm run` of the task at 12 and at 3600 positions (made on the fly),
  --format json and --format html, interleaved (target for HTML: 3600 <= 2x 12).

Run: python benchmarks/bench_speed.py [--report] [--scaling] [--batch] [--kinetostatics] [--against DIR] [--repeat 5]
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


ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
TASK = ROOT / "tasks" / "forging_sixbar.yaml"


# ----------------------------------------------------------------- processes
def _child_cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


_ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
_ENV["PYTHONPYCACHEPREFIX"] = os.path.join(tempfile.gettempdir(), "tmm-bench-pycache")


def _run(cmd: list[str], cwd: Path = ROOT) -> tuple[float, float]:
    """(wall, cpu) of one subprocess (``python -m tmm_cli`` runs the checkout in ``cwd``)."""
    c0, t0 = _child_cpu(), time.perf_counter()
    p = subprocess.run(cmd, capture_output=True, text=True, cwd=cwd, env=_ENV)
    wall, cpu = time.perf_counter() - t0, _child_cpu() - c0
    if p.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)} failed ({p.returncode}):\n{p.stderr[-2000:]}")
    return wall, cpu


def _interleaved(cmds: dict[str, list[str]], repeat: int,
                 cwds: dict[str, Path] | None = None) -> dict[str, list[tuple[float, float]]]:
    out: dict[str, list[tuple[float, float]]] = {k: [] for k in cmds}
    cwd = cwds or {}
    for k, c in cmds.items():        # one warm-up each (disk cache, pint/matplotlib caches)
        _run(c, cwd.get(k, ROOT))
    for _ in range(repeat):
        for k, c in cmds.items():
            out[k].append(_run(c, cwd.get(k, ROOT)))
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


def scaling(repeat: int, n: int = 3600, base: Path | None = None) -> None:
    """`tmm run` of the task at its 12 positions and at ``n`` (the task with
    `positions.count: n`, made on the fly), --format json and --format html, interleaved
    (target for HTML: n positions <= 2x the 12); with ``base`` (another checkout of tmm)
    also its html runs at 12 and ``n``, interleaved with these."""
    tmm = [sys.executable, "-m", "tmm_cli", "run"]
    with tempfile.TemporaryDirectory() as tmp:
        fine = Path(tmp) / "fine.yaml"
        fine.write_text(TASK.read_text(encoding="utf-8").replace("count: 12", f"count: {n}"), encoding="utf-8")
        cmds, cwds = {}, {}
        for fmt in ("json", "html"):
            for name, t in (("12", TASK), (str(n), fine)):
                cmds[f"{fmt}{name}"] = tmm + [str(t), "--format", fmt, "--quiet", "--out", f"{tmp}/{fmt}{name}"]
                if base is not None and fmt == "html":
                    cmds[f"base {fmt}{name}"] = tmm + [str(t), "--format", fmt, "--quiet", "--out",
                                                       f"{tmp}/base{fmt}{name}"]
                    cwds[f"base {fmt}{name}"] = Path(base).resolve()
        res = _interleaved(cmds, repeat, cwds)
    print(f"scaling, {TASK.name} at 12 and {n} positions, {repeat} interleaved rounds; wall / cpu in s: "
          "median [min-max]" + (f"; base: {Path(base).resolve()}" if base is not None else ""))
    for k, v in res.items():
        print(f"  {k:10s} wall {_stat([w for w, _ in v])}   cpu {_stat([c for _, c in v])}")
    for fmt, tgt in (("json", None), ("html", 2.0)):
        for i, what in ((0, "wall"), (1, "cpu")):
            _ratio_line(f"run --format {fmt} {n} positions / 12 ({what})", [x[i] for x in res[f"{fmt}{n}"]],
                        [x[i] for x in res[f"{fmt}12"]], tgt)
    if base is not None:
        for i, what in ((0, "wall"), (1, "cpu")):
            _ratio_line(f"base: run --format html {n} positions / 12 ({what})", [x[i] for x in res[f"base html{n}"]],
                        [x[i] for x in res["base html12"]], 2.0)
        for name in ("12", str(n)):
            for i, what in ((0, "wall"), (1, "cpu")):
                _ratio_line(f"html {name} positions: this / base ({what})", [x[i] for x in res[f"html{name}"]],
                            [x[i] for x in res[f"base html{name}"]], None)


# ----------------------------------------------------------------- kinematics core
def kinematics(repeat: int) -> None:
    """The kinematics core against the numpy closed form (and pylinkage when installed):
    benchmarks/bench_kinematics.py."""
    sys.path.insert(0, str(ROOT / "benchmarks"))
    from bench_kinematics import core
    core(repeat)


# ----------------------------------------------------------------- batch
def batch(repeat: int, n: int, base: Path | None = None) -> None:
    """`tmm batch` of n variants (crank speed 40-69 rpm, upsetting force 10-20 kN) with
    --jobs 2 --format json, interleaved with one JSON run of the task (and with the same
    batch run by the checkout ``base``, when given)."""
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
        cwds = {}
        if base is not None:
            cmds["batch base"] = py + ["batch", str(d), "--jobs", "2", "--format", "json", "--out", f"{tmp}/bb"]
            cwds["batch base"] = Path(base).resolve()
        res = _interleaved(cmds, repeat, cwds)
    w = {k: [x for x, _ in v] for k, v in res.items()}
    c = {k: [x for _, x in v] for k, v in res.items()}
    print(f"batch of {n} variants, --jobs 2 --format json, {repeat} interleaved rounds; s: median [min-max]")
    print(f"  batch      wall {_stat(w['batch'])}   cpu {_stat(c['batch'])}   "
          f"(target <= 15 s wall) {'ok' if statistics.median(w['batch']) <= 15 else 'OVER'}")
    print(f"  json run   wall {_stat(w['json'])}   cpu {_stat(c['json'])}")
    if base is not None:
        print(f"  batch of {Path(base).resolve()}   wall {_stat(w['batch base'])}   cpu {_stat(c['batch base'])}")
        _ratio_line("batch: this / base (wall)", w["batch"], w["batch base"], None)
        _ratio_line("batch: this / base (cpu)", c["batch"], c["batch base"], None)
    print(f"  per variant: wall {statistics.median(w['batch']) / n * 1e3:.0f} ms, "
          f"cpu {statistics.median(c['batch']) / n * 1e3:.0f} ms")
    _ratio_line(f"batch of {n} / one json run (wall)", w["batch"], w["json"], None)


# ----------------------------------------------------------------- kinetostatics at 36,000
_KS_CODE = """
import resource, sys, time
import numpy as np
sys.path.insert(0, {bench!r})
from bench_kinetostatics import SIX
from tmm_cli import load_task
from tmm_cli.linkage import kinematics, structure
from tmm_cli.linkage.kinetostatics import equilibrium, find_singular
from tmm_cli.linkage.loads import evaluate_on
from tmm_cli.linkage.mechanism import build_mechanism
try:
    from tmm_cli.results import dump
except ImportError:                     # an older checkout (--against): no results writer to time
    dump = None
task = load_task(SIX); mech = build_mechanism(task); st = structure.analyze(mech)
pos = kinematics.find_positions(mech, task.positions, task.drive.sign)
sing = find_singular(mech, st, "crank")
phi = np.mod(pos.phi0 + np.arange({n}) * 360.0 / {n}, 360.0)
base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
t0, c0 = time.perf_counter(), time.process_time()
kin = kinematics.solve(mech, phi, task.drive.sign * task.drive.speed)
made = 0
if {full}:
    lds = evaluate_on(mech, task.loads, kin, pos, sign=task.drive.sign, cycle=task.drive.cycle, inertia=True)
    res = equilibrium(mech, st, kin, lds, task.kinetostatics, singular=sing)
    t1, c1 = time.perf_counter(), time.process_time()
    d = res.to_dict()
    for e in d["kinetostatics"]:        # made when read: each entry made once
        made += 1
else:
    t1, c1 = time.perf_counter(), time.process_time()
    if {entries}:
        for e in kin.to_entries():
            made += 1
assert made == ({n} if {entries} else 0), made
t2, c2 = time.perf_counter(), time.process_time()
if {full} and dump is not None:         # the sections written as results.json is, to a null sink
    dump(d, lambda b: None)
print(t2 - t0, c2 - c0,
      (resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - base) / 1024.0,
      resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0, c2 - c1, time.process_time() - c2)
"""


def _run_peak(cmd: list[str]) -> tuple[float, float, float]:
    """(wall, cpu, peak RSS in MB) of one subprocess (its own rusage, by wait4)."""
    t0 = time.perf_counter()
    p = subprocess.Popen(cmd, cwd=ROOT, env=_ENV, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, ru = os.wait4(p.pid, 0)
    wall = time.perf_counter() - t0
    err = p.stderr.read().decode(errors="replace")
    p.stderr.close()
    p.returncode = os.waitstatus_to_exitcode(status)
    if p.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)} failed ({p.returncode}):\n{err[-2000:]}")
    return wall, ru.ru_utime + ru.ru_stime, ru.ru_maxrss / 1024.0


def _six_task(path: Path, count: int) -> Path:
    """The six-bar of bench_kinetostatics.py as a task file at ``count`` positions (written
    by a child process: this one stays small, as the peak RSS of a child it starts counts
    this process's size at the start)."""
    code = ("import sys, yaml; sys.path.insert(0, sys.argv[1]); from bench_kinetostatics import SIX; "
            "open(sys.argv[2], 'w', encoding='utf-8').write(yaml.safe_dump({**SIX, 'positions': "
            "{'count': int(sys.argv[3])}}, sort_keys=False))")
    subprocess.run([sys.executable, "-c", code, str(ROOT / "benchmarks"), str(path), str(count)], check=True,
                   cwd=ROOT, env=_ENV)
    return path


def kinetostatics_big(repeat: int, n: int = 36000, n_cli: int = 3600, base: Path | None = None) -> None:
    """Each in a fresh process, interleaved: the kinematics alone (solve), the kinematics
    and its results entries, and loads + kinetostatics + its results entries (in one
    process, at ``n`` positions); and the command line, `tmm run --format json` of the
    same six-bar at ``n_cli`` positions (a task's `positions.count` is at most 3600) and
    at 12, against the import floor (peak RSS and CPU of each process). With ``base``
    (another checkout of tmm) also its loads + kinetostatics + entries, interleaved."""
    cases = [("kinematics", False, False), ("kinematics+entries", False, True),
             ("kinetostatics", True, True)]
    tree = {c[0]: ROOT for c in cases}
    if base is not None:
        cases.append(("kinetostatics base", True, True))
        tree["kinetostatics base"] = Path(base).resolve()
    out: dict[str, list[list[float]]] = {c[0]: [] for c in cases}
    with tempfile.TemporaryDirectory() as tmp:
        tmm = [sys.executable, "-m", "tmm_cli", "run"]
        clis = {"floor": [sys.executable, "-c", "import numpy, pydantic, yaml"],
                "cli json 12": tmm + [str(_six_task(Path(tmp) / "six12.yaml", 12)), "--format", "json",
                                      "--quiet", "--out", f"{tmp}/o12"],
                f"cli json {n_cli}": tmm + [str(_six_task(Path(tmp) / "six.yaml", n_cli)), "--format", "json",
                                            "--quiet", "--out", f"{tmp}/o"]}
        cli_out: dict[str, list[tuple[float, float, float]]] = {k: [] for k in clis}
        for c in clis.values():                     # warm-up (bytecode and disk caches)
            _run_peak(c)
        for _ in range(repeat):
            for name, full, entries in cases:
                code = _KS_CODE.format(bench=str(tree[name] / "benchmarks"), n=n, full=full, entries=entries)
                p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=tree[name],
                                   env=_ENV, check=True)
                out[name].append([float(x) for x in p.stdout.split()])
            for k, c in clis.items():
                cli_out[k].append(_run_peak(c))
    print(f"kinetostatics at {n} positions (six-bar with friction: loads, three methods, the results "
          f"entries, each made once), {repeat} interleaved rounds, each in a fresh process; s and MB: "
          "median [min-max]; 'written': then the sections written as results.json is, to a null sink "
          "(not in the target's time; in the peak)")
    for name, rows in out.items():
        cols = list(zip(*rows))
        wr = f"   written cpu {_stat(list(cols[5]))}" if name.startswith("kinetostatics") else ""
        print(f"  {name:19s} wall {_stat(list(cols[0]))}   cpu {_stat(list(cols[1]))} (entries {_stat(list(cols[4]))})"
              f"   peak added {_stat(list(cols[2]))} (process {statistics.median(cols[3]):.0f}){wr}")
    k = list(zip(*out["kinetostatics"]))
    print(f"  target: <= 1 s {'ok' if statistics.median(k[1]) <= 1 else 'OVER'} (cpu), "
          f"<= 200 MB {'ok' if statistics.median(k[3]) <= 200 else 'OVER'} (process peak)")
    _ratio_line("kinetostatics / kinematics alone (cpu)", list(k[1]), [r[1] for r in out["kinematics"]], None)
    if base is not None:
        print(f"  base: {tree['kinetostatics base']}")
        kb = list(zip(*out["kinetostatics base"]))
        _ratio_line("kinetostatics: this / base (cpu)", list(k[1]), list(kb[1]), None)
        _ratio_line("kinetostatics entries: this / base (cpu)", list(k[4]), list(kb[4]), None)
        if min(kb[5]) > 1e-3:                # (an older checkout has no results writer to time)
            _ratio_line("kinetostatics written: this / base (cpu)", list(k[5]), list(kb[5]), None)
    print("  the command line, the same six-bar, interleaved with the above; peak RSS of each process")
    for name, rows in cli_out.items():
        cols = list(zip(*rows))
        print(f"  {name:19s} wall {_stat(list(cols[0]))}   cpu {_stat(list(cols[1]))}   peak RSS {_stat(list(cols[2]))}")
    for name in clis:
        if name != "floor":
            _ratio_line(f"{name} / import floor (cpu)", [r[1] for r in cli_out[name]],
                        [r[1] for r in cli_out["floor"]], None)
    _ratio_line(f"cli json {n_cli} / 12 (cpu)", [r[1] for r in cli_out[f"cli json {n_cli}"]],
                [r[1] for r in cli_out["cli json 12"]], None)


def against(repeat: int, base: Path, report: bool = True) -> None:
    """The JSON run and `tmm validate` (and with ``report`` the whole report) of this
    checkout against another checkout of tmm (e.g. `git archive <commit> | tar -x -C DIR`),
    with the import floor, all interleaved: a change measured under the same load."""
    py = [sys.executable, "-m", "tmm_cli"]
    trees = {"this": ROOT, "base": Path(base).resolve()}

    def run_in(tree: Path, args: list[str]) -> tuple[float, float]:
        c0, t0 = _child_cpu(), time.perf_counter()
        p = subprocess.run(args, capture_output=True, text=True, cwd=tree, env=_ENV)
        if p.returncode != 0:
            raise SystemExit(f"{tree}: {' '.join(args)} failed ({p.returncode}):\n{p.stderr[-2000:]}")
        return time.perf_counter() - t0, _child_cpu() - c0

    with tempfile.TemporaryDirectory() as tmp:
        cmds = {"floor": (ROOT, [sys.executable, "-c", "import numpy, pydantic, yaml"])}
        for tag, tree in trees.items():
            task = str(tree / "tasks" / TASK.name)
            cmds[f"json {tag}"] = (tree, py + ["run", task, "--format", "json", "--quiet", "--out", f"{tmp}/j{tag}"])
            cmds[f"validate {tag}"] = (tree, py + ["validate", task])
            if report:
                cmds[f"report {tag}"] = (tree, py + ["run", task, "--quiet", "--out", f"{tmp}/r{tag}"])
        out: dict[str, list[tuple[float, float]]] = {k: [] for k in cmds}
        for tree, args in cmds.values():        # warm-up
            run_in(tree, args)
        for _ in range(repeat):
            for k, (tree, args) in cmds.items():
                out[k].append(run_in(tree, args))
    print(f"this checkout against {trees['base']}, {TASK.name}, {repeat} interleaved rounds; wall / cpu in s")
    for k, v in out.items():
        print(f"  {k:15s} wall {_stat([w for w, _ in v])}   cpu {_stat([c for _, c in v])}")
    floor = out["floor"]
    for what in ("json", "validate"):
        for tag in trees:
            for i, kind in ((0, "wall"), (1, "cpu")):
                _ratio_line(f"{tag}: {what} / import floor ({kind})", [r[i] for r in out[f"{what} {tag}"]],
                            [r[i] for r in floor], 2.0)
        for i, kind in ((0, "wall"), (1, "cpu")):
            _ratio_line(f"{what}: this / base ({kind})", [r[i] for r in out[f"{what} this"]],
                        [r[i] for r in out[f"{what} base"]], None)
    if not report:
        return
    for tag in trees:
        for i, what in ((0, "wall"), (1, "cpu")):
            _ratio_line(f"{tag}: report html+pdf / json run ({what})", [r[i] for r in out[f"report {tag}"]],
                        [r[i] for r in out[f"json {tag}"]], 4.0)
    for i, what in ((0, "wall"), (1, "cpu")):
        _ratio_line(f"report: this / base ({what})", [r[i] for r in out["report this"]],
                    [r[i] for r in out["report base"]], None)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--report", action="store_true", help="also time the whole report (slow)")
    ap.add_argument("--batch", action="store_true", help="also time a batch of 300 variants (slow)")
    ap.add_argument("--variants", type=int, default=300)
    ap.add_argument("--kinetostatics", action="store_true", help="also kinetostatics at 36,000 positions")
    ap.add_argument("--scaling", action="store_true",
                    help="also tmm run at 12 and 3600 positions, json and html, interleaved")
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--tasks", default="", help="more tasks (names in tasks/, comma-separated) for the floor ratios")
    ap.add_argument("--no-cli", action="store_true", help="no timings of the command line (nor --against's)")
    ap.add_argument("--no-kinematics", action="store_true")
    ap.add_argument("--against", metavar="DIR", help="also the report and JSON run of another checkout "
                                                    "of tmm (DIR), interleaved with this one's")
    a = ap.parse_args()
    print(f"{os.cpu_count()} cores, load average {os.getloadavg()[0]:.2f}")
    if not a.no_cli:
        cli(max(5, a.repeat), a.report, [t for t in a.tasks.split(",") if t])
    if a.scaling:
        scaling(max(5, a.repeat), base=Path(a.against) if a.against else None)
    if a.batch:
        batch(max(3, a.repeat), a.variants, Path(a.against) if a.against else None)
    if a.kinetostatics:
        kinetostatics_big(max(5, a.repeat), base=Path(a.against) if a.against else None)
    if a.against and not a.no_cli:
        against(max(5, a.repeat), Path(a.against), report=a.report)
    if not a.no_kinematics:
        kinematics(max(5, a.repeat))


if __name__ == "__main__":
    main()
