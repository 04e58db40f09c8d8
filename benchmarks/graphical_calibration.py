"""How far a careful hand solution is from the exact values: the calibration of the
`graphical` tolerance (tmm_cli.graphical.READ_MM).

The course project in benchmarks/reference/engine_two_slider.yaml (two slider-crank groups
on one crank) solved the velocity plans by hand at all 12 positions (its table 2.1,
transcribed below as printed, decimal commas read). Each hand value is compared with tmm's
exact one. The error is given three ways: relative (|hand - exact| / |exact|, where the exact
value is above 10 % of v_A), as a fraction of the crank pin's velocity v_A (the plan's
reading error: a plan is drawn with v_A a fixed length, so a segment's error is a fraction
of that length), and as millimetres on a plan whose v_A is 100 mm long (tmm's plans:
`tmm_cli.plans.scales`). An angular velocity is read off its relative velocity segment:
its error is |d omega| * l.

    .venv/bin/python benchmarks/graphical_calibration.py          # the table and the percentiles
"""
from __future__ import annotations

import json
import statistics
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
TASK = HERE / "reference" / "engine_two_slider.yaml"

# table 2.1 of the project: position -> (V_B, V_S2, V_D, V_S4, V_BA, V_DC, omega_2, omega_4)
HAND = {
    0: (0, 14, 20.8, 20.8, 20.8, 0, 60.03, 0),
    1: (13.4, 16.6, 21.2, 20.4, 18, 10.8, 51.95, 31.17),
    2: (21.2, 20.4, 13.4, 16.6, 10.8, 18, 31.17, 51.95),
    3: (20.8, 20.8, 0, 0, 0, 20.8, 0, 60.03),
    4: (15, 18.2, 13.4, 16.6, 10.8, 18, 31.17, 51.95),
    5: (7.6, 15.6, 21.2, 20.4, 18, 10.8, 51.95, 31.17),
    6: (0, 14, 20.8, 20.8, 20.8, 0, 60.03, 0),
    7: (7.6, 15.6, 15, 18.4, 18, 10.8, 51.95, 31.17),
    8: (15, 18.2, 7.6, 14.8, 10.8, 18, 31.17, 51.95),
    9: (20.8, 20.8, 0, 0, 0, 20.8, 0, 60.03),
    10: (21.2, 20.4, 7.6, 14.8, 10.8, 18, 31.17, 51.95),
    11: (13.4, 16.6, 15, 18.4, 18, 10.8, 51.95, 31.17),
}
COLUMNS = ("B.v", "S2.v", "D.v", "S4.v", "BA", "DC", "rod1.omega", "rod2.omega")
V_A = 20.8          # the project's crank pin velocity, m/s
L_ROD = 0.3465


def exact(results: dict, i: int) -> tuple[float, ...]:
    e = next(k for k in results["kinematics"] if k["index"] == i)
    p, lk = e["points"], e["links"]
    w2, w4 = abs(lk["rod1"]["omega"]), abs(lk["rod2"]["omega"])
    return (p["B"]["v"], p["S2"]["v"], p["D"]["v"], p["S4"]["v"], w2 * L_ROD, w4 * L_ROD, w2, w4)


def measure() -> list[dict]:
    from tmm_cli.orchestrate import compute, prepare
    from tmm_cli.results import listed
    results = listed(compute(prepare(TASK, stage_errors=False)))
    rows = []
    for i, hand in HAND.items():
        for col, h, x in zip(COLUMNS, hand, exact(results, i)):
            seg = abs(h - x) * (L_ROD if col.endswith("omega") else 1.0)      # the segment's error, m/s
            ref_v = x * (L_ROD if col.endswith("omega") else 1.0)
            rows.append({"position": i, "quantity": col, "hand": h, "exact": round(x, 4),
                         "of_vA": seg / V_A, "mm_at_100": 100 * seg / V_A,
                         "rel": abs(h - x) / abs(x) if ref_v > 0.1 * V_A else None})
    return rows


def percentiles(xs: list[float]) -> dict:
    xs = sorted(xs)
    q = statistics.quantiles(xs, n=20, method="inclusive")
    return {"n": len(xs), "median": statistics.median(xs), "p90": q[17], "p95": q[18], "max": xs[-1]}


BLUNDER_MM = 10.0    # an error of a tenth of v_A is a slip (a wrong segment), not the drawing's precision


def summary(rows: list[dict]) -> tuple[dict, dict, list[dict]]:
    """(segment errors in mm at v_A = 100 mm, relative errors, the blunders left out of both)."""
    good = [r for r in rows if r["mm_at_100"] <= BLUNDER_MM]
    return (percentiles([r["mm_at_100"] for r in good]),
            percentiles([r["rel"] for r in good if r["rel"] is not None]),
            [r for r in rows if r["mm_at_100"] > BLUNDER_MM])


def main() -> None:
    rows = measure()
    mm, rel, blunders = summary(rows)
    if "--json" in sys.argv:
        print(json.dumps({"rows": rows, "mm_at_100": mm, "rel": rel, "blunders": blunders}, indent=1))
        return
    print(f"{'pos':>3} {'quantity':<11} {'hand':>7} {'exact':>8} {'mm@100':>7} {'rel %':>6}")
    for r in rows:
        rel_s = "" if r["rel"] is None else f"{100 * r['rel']:.2f}"
        print(f"{r['position']:>3} {r['quantity']:<11} {r['hand']:>7g} {r['exact']:>8.3f} {r['mm_at_100']:>7.2f} {rel_s:>6}")
    print(f"left out as blunders (over {BLUNDER_MM:g} mm):",
          ", ".join(f"{b['quantity']} at {b['position']} ({b['hand']:g} for {b['exact']:g})" for b in blunders))
    print("segment error, mm on a plan with v_A = 100 mm:", {k: round(v, 2) if isinstance(v, float) else v
                                                             for k, v in mm.items()})
    print("relative error, % (exact above 10 % of v_A):", {k: round(100 * v, 2) if isinstance(v, float) else v
                                                          for k, v in rel.items()})


if __name__ == "__main__":
    main()
