"""The hand method's own error: what a student reading the drawings may be off by.

* Plans of velocities and accelerations, drawn at the course's scales as on a sheet
  (mu_v, mu_a: the crank pin's vector about 100 mm long, `tmm_cli.plans.scales`; the
  report's A4 plans may be at larger ones, report.sections.kinematics.drawn_scales): a
  segment read to +/- READ_MM is off by READ_MM mu, i.e. relatively READ_MM mu / value
  for a point's velocity or acceleration, READ_MM mu_v / (|omega| l) for a link's omega
  read off the relative velocity segment (l: the distance of two of its points),
  READ_MM mu_a / (|epsilon| l) for epsilon read off the tangential segment.  Where a
  segment is shorter than the reading error itself (a value near zero) the relative
  error is null: only the absolute one, READ_MM mu, applies.
* The flywheel by the 12-position graphical integration (trapezoid over the positions,
  extrema at the positions; 24 over a 720-deg cycle): its relative error against the
  accurate calculation, from the `hand` row of the flywheel results.

`graphical_error(results)` is the deterministic block written to results.json;
`graphical_tolerance(results)` turns it into {path in results.json: relative tolerance}
for `tmm check` (`tolerance: graphical`).

A whole hand solution is off by more than one reading: every point of a plan is built on
the ones before it. Measured on a course project's hand-drawn velocity plans (12 positions,
8 quantities: benchmarks/graphical_calibration.py), a careful solution's segments are off by
up to 2.3 % of the crank pin's vector (median 0.13 %, 90th percentile 1.2 %). So the
tolerance of a plan quantity is HAND_SHARE of the crank pin's velocity (acceleration), over
the quantity's own segment: HAND_SHARE v_A / v, HAND_SHARE v_A / (|omega| l),
HAND_SHARE a_A / a, HAND_SHARE a_A / (|epsilon| l).
"""
from __future__ import annotations

import math

from .results import Entries, bulk, listed

READ_MM = 0.5
HAND_SHARE = 0.025    # a careful hand solution's plan segment error, a share of the crank pin's vector


def _rel(err_abs: float, values) -> list:
    """Per position, the relative reading error err_abs / |value|: None where the value
    is None, not finite, or not larger than the reading error itself."""
    import numpy as np
    v = np.abs(np.array([math.nan if x is None else x for x in values], float))
    with np.errstate(all="ignore"):
        good = np.isfinite(v) & ~(v <= err_abs)
        r = err_abs / np.where(good, v, 1.0) + 0.0
    return np.where(good & np.isfinite(r), r, None).tolist()


def _plans(results: dict) -> dict | None:
    """The plans' reading errors at every position, column by column (the points and
    links of the first entry: every entry of a run has the same)."""
    kin = listed(results.get("kinematics") or [])     # read five times below: made once
    if not kin:
        return None
    from .plans import geometry, scales
    geom = geometry(results)
    if geom is None:
        return None
    mu_v, mu_a, _, _ = scales(kin, geom)
    ev, ea = READ_MM * mu_v, READ_MM * mu_a
    pts0 = kin[0].get("points") or {}
    lks0 = kin[0].get("links") or {}
    P = [e.get("points") or {} for e in kin]
    L = [e.get("links") or {} for e in kin]
    pcols = {}
    for name in pts0:
        if name in geom.ground:
            continue
        col = [p.get(name) or {} for p in P]
        pcols[name] = [{"v": v, "a": a} for v, a in zip(_rel(ev, [c.get("v") for c in col]),
                                                       _rel(ea, [c.get("a") for c in col]))]
    lcols = {}
    for lk in geom.links:
        have = [q for q in lk.points if q in pts0]
        if lk.name not in lks0 or len(have) < 2 or lk.kind == "slider":
            continue
        ln = [math.hypot(p[have[1]]["x"] - p[have[0]]["x"], p[have[1]]["y"] - p[have[0]]["y"]) for p in P]
        lv = [lo.get(lk.name) or {} for lo in L]
        om = [None if c.get("omega") is None else abs(c["omega"]) * d for c, d in zip(lv, ln)]
        ep = [None if c.get("epsilon") is None else abs(c["epsilon"]) * d for c, d in zip(lv, ln)]
        lcols[lk.name] = [{"omega": o, "epsilon": x} for o, x in zip(_rel(ev, om), _rel(ea, ep))]
    pn, lnm = list(pcols), list(lcols)
    prow = zip(*pcols.values()) if pn else [()] * len(kin)
    lrow = zip(*lcols.values()) if lnm else [()] * len(kin)
    # clean by construction (tmm_cli.results.Entries)
    positions = Entries({"index": e.get("index"), "points": dict(zip(pn, pr)), "links": dict(zip(lnm, lr))}
                        for e, pr, lr in zip(kin, prow, lrow))
    return {"mu_v": mu_v, "mu_a": mu_a, "abs_v": ev, "abs_a": ea, "positions": positions}


def _flywheel(results: dict) -> dict | None:
    hand = (results.get("flywheel") or {}).get("hand")
    if not hand:
        return None
    return {"positions": hand.get("positions"), "step": hand.get("step"),
            "J": hand.get("err_J"), "J_n": hand.get("err_J_n"),
            "M_constant": hand.get("err_M_constant")}


def graphical_error(results: dict) -> dict | None:
    """The block `graphical_error` of results.json (None when no stage drawn by hand)."""
    out: dict = {"reading_mm": READ_MM}
    with bulk():
        p = _plans(results)
    if p is not None:
        out["plans"] = p
    f = _flywheel(results)
    if f is not None:
        out["flywheel"] = f
    return out if len(out) > 1 else None


def _pin(results: dict) -> tuple[float, float]:
    """The crank pin's velocity and acceleration (the largest over the positions)."""
    from .plans import geometry, scales
    kin = listed(results.get("kinematics") or [])
    geom = geometry(results) if kin else None
    if geom is None:
        return 0.0, 0.0
    _, _, v_a, a_a = scales(kin, geom)
    return v_a, a_a


def graphical_tolerance(results: dict) -> dict[str, float | tuple[float, float]]:
    """{path into results.json: relative tolerance, or the interval (lo, hi) an answer must lie
    in} of the quantities a student gets from the drawings (the plans': HAND_SHARE of the crank
    pin's vector over the segment): 'kinematics[i].points.B.v', 'kinematics[i].links.rod.omega';
    the flywheel's 'flywheel.J', 'flywheel.J_n', 'flywheel.M_constant': the interval between the
    12-position (hand) value and the accurate one, widened by HAND_SHARE of the larger (the
    relative error of `graphical_error` where the results lack the hand values)."""
    g = results.get("graphical_error") or graphical_error(results) or {}
    out: dict[str, float | tuple[float, float]] = {}
    plans = g.get("plans") or {}
    if plans.get("positions"):
        # the reading error r = READ_MM mu / segment, as the hand solution's: HAND_SHARE v_A / segment
        v_a, a_a = _pin(results)
        scale = {"v": HAND_SHARE * v_a / plans["abs_v"] if plans.get("abs_v") and v_a > 0 else 1.0,
                 "a": HAND_SHARE * a_a / plans["abs_a"] if plans.get("abs_a") and a_a > 0 else 1.0}
        scale["omega"], scale["epsilon"] = scale["v"], scale["a"]
    for e in plans.get("positions", []):
        i = e["index"]
        for name, d in e["points"].items():
            for q, r in d.items():
                if r is not None:
                    out[f"kinematics[{i}].points.{name}.{q}"] = r * scale[q]
        for name, d in e["links"].items():
            for q, r in d.items():
                if r is not None:
                    out[f"kinematics[{i}].links.{name}.{q}"] = r * scale[q]
    f = g.get("flywheel") or {}
    fly = results.get("flywheel") or {}
    hand = fly.get("hand") or {}
    for key in ("J", "J_n", "M_constant"):
        if f.get(key) is None:
            continue
        a, h = fly.get(key), hand.get(key)
        if isinstance(a, (int, float)) and isinstance(h, (int, float)):
            # the 12-position integration's own error is one-sided (the hand value lies on one side
            # of the accurate one): the band from one to the other, widened by a reading error of
            # HAND_SHARE, passes a careful hand solution, the accurate value and nothing far outside
            # both (a band about the accurate value as wide as that error passed twice it)
            m = HAND_SHARE * max(abs(a), abs(h))
            out[f"flywheel.{key}"] = (min(a, h) - m, max(a, h) + m)
        else:
            out[f"flywheel.{key}"] = f[key]
    return out
