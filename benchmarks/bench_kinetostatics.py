"""Kinetostatics timings (targets from issue 3) on a six-bar (crank-rocker + slider
dyad, gravity, inertia, a resistance on the slider, friction):

* 12 positions: loads + analysis (three methods, singular flags) under 20 ms;
* 3600 positions: under 0.5 s;
* the singular-position search over one turn (720-point grid + Brent), for reference.

Run: python benchmarks/bench_kinetostatics.py     (best of 5 runs)
"""
from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from tmm_cli import load_task  # noqa: E402
from tmm_cli.linkage import kinematics, structure  # noqa: E402
from tmm_cli.linkage.kinetostatics import equilibrium, find_singular  # noqa: E402
from tmm_cli.linkage.loads import evaluate_on  # noqa: E402
from tmm_cli.linkage.mechanism import build_mechanism  # noqa: E402

SIX = {"schema": "tmm/1", "mechanism": {
    "ground": {"O": [0, 0], "C": [0.28, 0]},
    "links": {"crank": {"points": ["O", "A"], "length": 0.08, "mass": 1, "J": 0.002},
              "coupler": {"points": ["A", "B"], "length": 0.30, "mass": 3, "J": 0.03},
              "rocker": {"points": ["C", "B"], "length": 0.25, "mass": 2.5, "J": 0.02, "extra": {"K": [0.32, 0.0]}},
              "link4": {"points": ["K", "D"], "length": 0.30, "mass": 2, "J": 0.015},
              "slider": {"slider": "D", "guide": {"through": [0, 0.42], "angle": 0}, "mass": 6}},
    "assembly": {"B": [0.28, 0.25], "D": [0.1, 0.42]}},
    "drive": {"link": "crank", "speed": "120 rpm"},
    "loads": {"gravity": True, "forces": [{"on": "slider", "kind": "resistance", "magnitude": 1500}]},
    "kinetostatics": {"friction": {"pin_radius": 0.01, "f": 0.1}}}


def best(fn, repeat=5) -> float:
    t = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        t.append(time.perf_counter() - t0)
    return min(t)


def main() -> None:
    task = load_task(SIX)
    mech = build_mechanism(task)
    st = structure.analyze(mech)
    pos = kinematics.find_positions(mech, task.positions, task.drive.sign)
    sing = find_singular(mech, st, "crank")
    rows = []
    for n, target in ((12, 0.020), (3600, 0.5)):
        phi = np.mod(pos.phi0 + np.arange(n) * 360.0 / n, 360.0)
        kin = kinematics.solve(mech, phi, task.drive.sign * task.drive.speed)

        def run():
            lds = evaluate_on(mech, task.loads, kin, pos, sign=task.drive.sign, cycle=task.drive.cycle, inertia=True)
            d = equilibrium(mech, st, kin, lds, task.kinetostatics, singular=sing).to_dict()
            for _ in d["kinetostatics"]:        # every entry made (they are made when read)
                pass
        rows.append((f"loads + kinetostatics, {n} positions (+ entries)", best(run), target))
    rows.append(("singular positions, one turn (balance on the crank)",
                 best(lambda: find_singular(mech, st, "crank"), 3), None))
    rows.append(("singular positions, one turn (balance on the slider)",
                 best(lambda: find_singular(mech, st, "slider"), 3), None))
    for name, t, target in rows:
        verdict = "" if target is None else ("ok" if t < target else "SLOW")
        lim = "" if target is None else f"(< {target * 1000:.0f} ms)"
        print(f"{name:58s} {t * 1000:8.1f} ms {lim:12s} {verdict}")


if __name__ == "__main__":
    main()
