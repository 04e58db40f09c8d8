"""Where the counterweights stand, shared by the report's drawing and the balancing sheet:
read from results only (the kinematics' position 0 and the balancing stage's counterweights)."""
from __future__ import annotations

import math

import numpy as np


def counterweight_points(results: dict) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """{role: (the link's fixed pivot, the counterweight's centre)} in m at position 0: the
    centre at the counterweight's radius and angle from the link's axis (fixed pivot -> its
    other pair point, ccw positive). A counterweight on a link without a fixed pivot is left out."""
    b = results["balancing"]
    e = results["kinematics"][0]
    links = {lk["name"]: lk for lk in results["structure"]["links"]}
    ground = set(results["structure"].get("ground") or {})
    out = {}
    for role, c in (b.get("counterweights") or {}).items():
        lk = links.get(c["link"])
        piv = next((q for q in lk["points"] if q in ground), None) if lk else None
        other = next((q for q in lk["points"] if q != piv), None) if piv else None
        if other is None:
            continue
        P = np.array([float(e["points"][piv]["x"]), float(e["points"][piv]["y"])])
        Q = np.array([float(e["points"][other]["x"]), float(e["points"][other]["y"])])
        th = math.atan2(Q[1] - P[1], Q[0] - P[0]) + math.radians(float(c["angle"]))
        out[role] = (P, P + float(c["r"]) * np.array([math.cos(th), math.sin(th)]))
    return out
