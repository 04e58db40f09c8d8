"""Speed targets of issue 12 as ratios measured side by side in one run.

The machine may be shared and noisy, so every figure is a ratio of two things timed
interleaved (A, B, A, B, ...), each repeated (>= 5 times); medians and the spread
(min-max) are printed.

* JSON run and `tmm validate` of tasks/forging_sixbar.yaml against the interpreter's
  floor `python -c "import numpy, pydantic, yaml"` (target <= 2x);
* with --report: the whole report (HTML + PDF) against the JSON run of the same task
  (target <= 4x; absolute wall and CPU printed too), and the HTML report of a
  3600-position grid against the 12-position task (target <= 2x);
* the kinematics core (tmm_cli.linkage.kinematics.solve) against a hand-written numpy closed
  form of the same central slider-crank and four-bar, N = 36 ... 36000 (target <= 3x at
  N >= 3600), and the fixed cost per call.

Run: python benchmarks/bench_speed.py [--report] [--repeat 5]
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


def _run(cmd: list[str]) -> tuple[float, float]:
    """(wall, cpu) of one subprocess."""
    c0, t0 = _child_cpu(), time.perf_counter()
    p = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT)
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


def cli(repeat: int, report: bool) -> None:
    py = [sys.executable]
    tmm = py + ["-m", "tmm_cli"]
    with tempfile.TemporaryDirectory() as tmp:
        cmds = {"floor": py + ["-c", "import numpy, pydantic, yaml"],
                "validate": tmm + ["validate", str(TASK)],
                "json": tmm + ["run", str(TASK), "--format", "json", "--quiet", "--out", f"{tmp}/j"]}
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
        print(f"  {k:10s} wall {_stat([w for w, _ in v])}   cpu {_stat([c for _, c in v])}")
    w = {k: [x for x, _ in v] for k, v in res.items()}
    c = {k: [x for _, x in v] for k, v in res.items()}
    _ratio_line("run --format json / import floor (wall)", w["json"], w["floor"], 2.0)
    _ratio_line("validate / import floor (wall)", w["validate"], w["floor"], 2.0)
    if report:
        _ratio_line("report html+pdf / json run (wall)", w["report"], w["json"], 4.0)
        _ratio_line("report html+pdf / json run (cpu)", c["report"], c["json"], None)
        _ratio_line("html report 3600 positions / 12 (wall)", w["html3600"], w["html12"], 2.0)
        _ratio_line("html report 3600 positions / 12 (cpu)", c["html3600"], c["html12"], 2.0)
        print(f"  whole report absolute: wall {statistics.median(w['report']):.2f} s (target <= 3), "
              f"cpu {statistics.median(c['report']):.2f} s (target <= 4)")


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


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--report", action="store_true", help="also time the whole report (slow)")
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--no-cli", action="store_true")
    a = ap.parse_args()
    print(f"{os.cpu_count()} cores, load average {os.getloadavg()[0]:.2f}")
    if not a.no_cli:
        cli(max(5, a.repeat), a.report)
    kinematics(max(5, a.repeat))


if __name__ == "__main__":
    main()
