"""The ``kinematics`` entries of results.json (tmm_cli.linkage.kinematics.entries: values
computed a table of positions at a time, entries made a block at a time) against a
straightforward construction, one entry at a time from the result's arrays, on results
whose arrays were spoilt with NaN, inf, -0.0, singular positions and positions near a
change point with values that have no finite limit: the same dicts (keys in the same
order, 0.0 where a value is not finite, None where it has no finite limit, never -0.0),
in any table and block sizes."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import tmm_cli
from tmm_cli.linkage import kinematics
from tmm_cli.linkage.context import build
from tmm_cli.linkage.kinematics import entries as entries_mod
from tmm_cli.linkage.kinematics.entries import angle_deg
from tmm_cli.linkage.mechanism import build_mechanism
from tmm_cli.results import dumps

from test_kinetostatics_entries import _floats, _spoil_array     # NaN, inf, -0.0, ... in a copy

ROOT = Path(__file__).resolve().parents[1]


# ----------------------------------------------------------------- the reference
def _fin(v) -> float:
    v = float(v)
    return v + 0.0 if math.isfinite(v) else 0.0


def _deg360(d: float) -> float:
    """A crank angle (deg) as the entries give it: in [0, 360), a hair below 360 as 0 -- the
    number given, not taken through radians and back (30 read 29.999999999999996)."""
    d = d % 360.0
    return 0.0 if d >= 360.0 - 1e-11 else d


def _at(a, i: int) -> float:
    """The speed (or acceleration) of the crank at row i: a scalar, one value or N."""
    a = np.asarray(a, float).reshape(-1)
    return float(a[0] if a.size == 1 else a[i])


def reference_entry(kin, i: int, index: int) -> dict:
    """The entry of row i, one value at a time."""
    w, e = _at(kin.omega1, i), _at(kin.eps1, i)
    points = {}
    for p in kin.points:
        (x, y), (qx, qy), (rx, ry) = kin.pos[p][i], kin.d1[p][i], kin.d2[p][i]
        vx, vy = qx * w, qy * w
        ax, ay = rx * w ** 2 + qx * e, ry * w ** 2 + qy * e
        points[p] = {k: _fin(v) for k, v in zip(
            ("x", "y", "vx", "vy", "v", "ax", "ay", "a", "vqx", "vqy", "vq", "aqx", "aqy", "aq"),
            (x, y, vx, vy, np.hypot(vx, vy), ax, ay, np.hypot(ax, ay), qx, qy, np.hypot(qx, qy),
             rx, ry, np.hypot(rx, ry)))}
    links = {}
    for lk in kin.links:
        a1, a2 = kin.a1[lk][i], kin.a2[lk][i]
        links[lk] = {"angle": _fin(angle_deg(kin.angle[lk][i])), "omega": _fin(a1 * w),
                     "epsilon": _fin(a2 * w ** 2 + a1 * e), "i": _fin(a1), "iq2": _fin(a2)}
    near = kin.near is not None and bool(kin.near[i])
    ent = {"index": index, "phi": _fin(_deg360(float(kin.phi[i]))), "points": points, "links": links,
           "instant_centres": _centres(kin, i, w, near)}
    if kin.singular is not None and kin.singular[i]:
        ent["singular"] = True
    if kin.near is not None and kin.near[i]:
        ent["near_singular"] = True
        for key, mask in kin.undefined.items():
            what, name = key.split(":", 1)
            target = (points if what in ("v", "a") else links).get(name)
            if mask[i] and target is not None:
                for k in {"v": ("vx", "vy", "v", "vqx", "vqy", "vq"), "a": ("ax", "ay", "a", "aqx", "aqy", "aq"),
                          "omega": ("omega", "i"), "epsilon": ("epsilon", "iq2")}[what]:
                    target[k] = None
    return ent


def _centres(kin, i: int, w: float, near: bool) -> dict:
    """Every pair's instant centre at row i, one pair at a time: the pin of a revolute, null for a
    slide; else where the relative velocity field c + (w_a - w_b) k x P is zero; null where
    w_a = w_b (to 1e-12 of the largest |w| at the row) or near a change point.  Where the two
    fields agree (w_a = w_b to 1e-8 of the largest |w|, |c| within 1e-8 of the largest |c_k|) the
    same with the derivatives by the crank angle of the velocity analogues (the limit)."""
    n = len(kin.links)
    vel = [(0.0, 0.0, 0.0)]             # per link: (c_x, c_y, w) with c = v_S - w k x S
    for k, lk in enumerate(kin.links, start=1):
        (sx, sy), (qx, qy) = kin.pos[f"S{k}"][i], kin.d1[f"S{k}"][i]
        wk = float(kin.a1[lk][i]) * w
        vel.append((qx * w + wk * sy, qy * w - wk * sx, wk))
    der = [(0.0, 0.0, 0.0)]             # per link: c' = q'' - w'' k x S - w' k x q', and w''
    for k, lk in enumerate(kin.links, start=1):
        (sx, sy), (qx, qy), (rx, ry) = kin.pos[f"S{k}"][i], kin.d1[f"S{k}"][i], kin.d2[f"S{k}"][i]
        a1, a2 = float(kin.a1[lk][i]), float(kin.a2[lk][i])
        der.append((rx + a2 * sy + a1 * qy, ry - a2 * sx - a1 * qx, a2))
    with np.errstate(all="ignore"):
        scale = max(float(np.max(np.abs([v[2] for v in vel]))), 1e-300)
        c_scale = float(np.max([np.hypot(v[0], v[1]) for v in vel]))
        scale1 = max(float(np.max(np.abs([v[2] for v in der]))), 1e-300)
    out = {}
    for a in range(n + 1):
        for b in range(a + 1, n + 1):
            key = f"{a}-{b}"
            if key in kin.pins:
                pin = kin.pins[key]
                out[key] = None if pin is None else [_fin(kin.pos[pin][i][0]), _fin(kin.pos[pin][i][1])]
                continue
            cx, cy = vel[a][0] - vel[b][0], vel[a][1] - vel[b][1]
            dw = vel[a][2] - vel[b][2]
            lim = 1e-12 * scale
            if abs(dw) <= 1e-8 * scale and np.hypot(cx, cy) <= 1e-8 * c_scale and c_scale > 0:
                cx, cy = der[a][0] - der[b][0], der[a][1] - der[b][1]
                dw, lim = der[a][2] - der[b][2], 1e-12 * scale1
            if near or abs(dw) <= lim:
                out[key] = None
            else:
                with np.errstate(all="ignore"):
                    out[key] = [_fin(np.float64(-cy) / dw), _fin(np.float64(cx) / dw)]
    return out


# ----------------------------------------------------------------- spoilt results
def _spoil(kin, rng) -> None:
    """Specials in every array the entries take, flags and values with no finite limit."""
    n = len(kin.phi)
    kin.phi = _spoil_array(kin.phi, rng, 0.05)
    for d in (kin.pos, kin.d1, kin.d2, kin.angle, kin.a1, kin.a2):
        for k in d:
            d[k] = _spoil_array(d[k], rng, 0.08)
    for name in ("omega1", "eps1"):
        a = np.asarray(getattr(kin, name), float)
        if a.ndim:
            setattr(kin, name, _spoil_array(a, rng, 0.05))
    kin.singular = rng.random(n) < 0.1
    kin.near = rng.random(n) < 0.3
    p, lk = kin.points[-1], kin.links[-1]
    kin.undefined = {f"v:{p}": rng.random(n) < 0.5, f"a:{kin.points[0]}": rng.random(n) < 0.5,
                     f"omega:{lk}": rng.random(n) < 0.5, f"epsilon:{kin.links[0]}": rng.random(n) < 0.5,
                     "a:no such point": rng.random(n) < 0.5, "epsilon:no such link": rng.random(n) < 0.5}


def _forging(n: int):
    text = (ROOT / "tasks" / "forging_sixbar.yaml").read_text(encoding="utf-8").replace("count: 12", f"count: {n}")
    lk = build(tmm_cli.load_task(ROOT / "tasks" / "forging_sixbar.yaml", text=text))
    return kinematics.analyze(lk), [int(i) for i in lk.positions.index]


def _varying(n: int):
    """The six-bar with the crank's speed and acceleration given per position."""
    mech = build_mechanism(tmm_cli.load_task(ROOT / "tasks" / "forging_sixbar.yaml"))
    phi = np.linspace(0.0, 400.0, n)
    kin = kinematics.solve(mech, phi, omega1=5.0 + np.sin(phi), eps1=np.cos(phi))
    return kin, [3 * i + 1 for i in range(n)]


CASES = {"six-bar (the task)": lambda: _forging(40), "six-bar, speed per position": lambda: _varying(33)}


@pytest.mark.parametrize("case", list(CASES))
def test_entries_as_made_one_at_a_time(case, monkeypatch):
    kin, index = CASES[case]()
    clean = [reference_entry(kin, i, index[i]) for i in range(len(index))]
    assert repr(list(kin.to_entries(index))) == repr(clean)            # the task's own numbers
    rng = np.random.default_rng(sorted(CASES).index(case) + 3)
    _spoil(kin, rng)
    with np.errstate(all="ignore"):
        ref = [reference_entry(kin, i, index[i]) for i in range(len(index))]
    text = repr(ref)
    assert all(math.isfinite(v) and (v < 0 or math.copysign(1.0, v) > 0) for v in _floats(ref))
    got = kin.to_entries(index)
    assert repr(list(got)) == text
    assert dumps({"kinematics": got}) == dumps({"kinematics": ref})
    # the spoilt arrays reached the cases they are for
    assert any(e.get("singular") and e.get("near_singular") for e in ref)
    assert any(e["points"][kin.points[-1]]["v"] is None for e in ref)
    assert any(e["links"][kin.links[0]]["epsilon"] is None and e["links"][kin.links[0]]["angle"] is not None
               for e in ref)
    assert any(e.get("near_singular") and e["points"][kin.points[-1]]["v"] is not None for e in ref)
    assert any(e["points"][kin.points[0]]["x"] == 0.0 for e in ref)
    # tables and blocks of any size: the same entries; reading one entry, or a slice, anywhere
    monkeypatch.setattr(entries_mod, "TABLE_ROWS", 7)
    monkeypatch.setattr(entries_mod, "ENTRY_BLOCK", 3)
    got = kin.to_entries(index)
    assert repr(list(got)) == text
    n = len(ref)
    for i in (0, 6, 7, n - 1, 13, 2):
        assert repr(got[i]) == repr(ref[i])
    assert repr(got[5:23]) == repr(ref[5:23]) and repr(got[-9:]) == repr(ref[-9:])
