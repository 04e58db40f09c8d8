"""Accuracy of the flywheel against the resolution (issue 4): J (primary method),
omega_max/min of the motion with the converged flywheel on each grid, their relative
errors to the converged value (3600 positions), the fluctuation the row's J really
gives, and the time taken; then the 12-position hand calculation (trapezoid every
30 deg, no inserted jump points) beside the accurate result.

Run: python benchmarks/accuracy_flywheel.py [TASK.yaml]
"""
from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from _dyn_tasks import prepare  # noqa: E402


def main() -> None:
    from tmm_cli.linkage import dynamics
    task, linkage = prepare(sys.argv[1] if len(sys.argv) > 1 else None)
    r = dynamics.analyze(linkage, task.flywheel, accuracy=True)
    acc = r.to_dict()["accuracy"]
    print(f"task: {task.title}; method {acc['method']}; delta = {task.flywheel.delta:.6g}")
    print(f"{'positions':>9} {'J, kg*m^2':>14} {'err J':>10} {'omega_max':>11} {'err':>9} "
          f"{'omega_min':>11} {'err':>9} {'delta true':>11} {'time, ms':>9}")
    for x in acc["rows"]:
        t = "—" if x["time_ms"] is None else f"{x['time_ms']:.2f}"
        print(f"{x['resolution']:>9} {x['J']:>14.6f} {x['err_J']:>10.2e} {x['omega_max']:>11.6f} "
              f"{x['err_omega_max']:>9.1e} {x['omega_min']:>11.6f} {x['err_omega_min']:>9.1e} "
              f"{x['delta_true']:>11.6f} {t:>9}")
    h = acc["hand"]
    print(f"hand calculation, {h['positions']} positions every {h['step']:g} deg: J = {h['J']:.6f} "
          f"(energy-mass {h['J_energy_mass']:.6f}, Merzalov {h['J_merzalov']:.6f}), "
          f"error {100 * h['err_J']:.2f} %, delta really {h['delta_true']:.6f}; "
          f"accurate J = {h['accurate']['J']:.6f} ({h['accurate']['resolution']} positions)")


if __name__ == "__main__":
    main()
