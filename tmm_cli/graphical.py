"""The hand method's own error: what a student reading the drawings may be off by.

* Plans of velocities and accelerations, drawn at the scales the report chooses
  (mu_v, mu_a: the crank pin's vector about 100 mm long, `tmm_cli.plans.scales`): a
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
"""
from __future__ import annotations

import math

from .results import Entries

READ_MM = 0.5


def _rel(err_abs: float, value) -> float | None:
    if value is None:
        return None
    v = abs(float(value))
    if not math.isfinite(v) or v <= err_abs:
        return None
    r = err_abs / v + 0.0
    return r if math.isfinite(r) else None


def _plans(results: dict) -> dict | None:
    kin = results.get("kinematics") or []
    if not kin:
        return None
    from .plans import geometry, scales
    geom = geometry(results)
    if geom is None:
        return None
    mu_v, mu_a, _, _ = scales(kin, geom)
    ev, ea = READ_MM * mu_v, READ_MM * mu_a
    positions = Entries()       # clean by construction (tmm_cli.results.Entries)
    for e in kin:
        pts = e.get("points") or {}
        p_out = {}
        for name, p in pts.items():
            if name in geom.ground:
                continue
            p_out[name] = {"v": _rel(ev, p.get("v")), "a": _rel(ea, p.get("a"))}
        l_out = {}
        for lk in geom.links:
            lv = (e.get("links") or {}).get(lk.name)
            have = [q for q in lk.points if q in pts]
            if lv is None or len(have) < 2 or lk.kind == "slider":
                continue
            P, Q = pts[have[0]], pts[have[1]]
            ln = math.hypot(Q["x"] - P["x"], Q["y"] - P["y"])
            om, ep = lv.get("omega"), lv.get("epsilon")
            l_out[lk.name] = {"omega": None if om is None else _rel(ev, abs(om) * ln),
                              "epsilon": None if ep is None else _rel(ea, abs(ep) * ln)}
        positions.append({"index": e.get("index"), "points": p_out, "links": l_out})
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
    p = _plans(results)
    if p is not None:
        out["plans"] = p
    f = _flywheel(results)
    if f is not None:
        out["flywheel"] = f
    return out if len(out) > 1 else None


def graphical_tolerance(results: dict) -> dict[str, float]:
    """{path into results.json: relative tolerance} of the quantities a student gets from
    the drawings: 'kinematics[i].points.B.v', 'kinematics[i].links.rod.omega',
    'flywheel.J', 'flywheel.J_n', 'flywheel.M_constant' (from `graphical_error`, computed
    when the results lack it)."""
    g = results.get("graphical_error") or graphical_error(results) or {}
    out: dict[str, float] = {}
    for e in (g.get("plans") or {}).get("positions", []):
        i = e["index"]
        for name, d in e["points"].items():
            for q, r in d.items():
                if r is not None:
                    out[f"kinematics[{i}].points.{name}.{q}"] = r
        for name, d in e["links"].items():
            for q, r in d.items():
                if r is not None:
                    out[f"kinematics[{i}].links.{name}.{q}"] = r
    f = g.get("flywheel") or {}
    for key in ("J", "J_n", "M_constant"):
        if f.get(key) is not None:
            out[f"flywheel.{key}"] = f[key]
    return out
