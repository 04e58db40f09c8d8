"""The ``kinetostatics`` entries of results.json (tmm_cli.linkage.kinetostatics.entries:
values computed a table of positions at a time, entries made a block at a time) against
a straightforward construction, one entry at a time from the result's arrays, on results
whose arrays were spoilt with NaN, inf, -0.0, positions not solved and slider pairs
without a normal force: the same dicts (keys in the same order, None where a value is
not finite or the position not solved, never -0.0), in any table and block sizes."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import tmm_cli
from tmm_cli.linkage import kinematics, kinetostatics
from tmm_cli.linkage.context import build
from tmm_cli.linkage.kinetostatics import entries as entries_mod
from tmm_cli.results import dumps

ROOT = Path(__file__).resolve().parents[1]


def _result(task: str, edits: tuple[tuple[str, str], ...]):
    text = (ROOT / "tasks" / task).read_text(encoding="utf-8")
    for old, new in edits:
        assert old in text
        text = text.replace(old, new)
    t = tmm_cli.load_task(ROOT / "tasks" / task, text=text)
    lk = build(t)
    return kinetostatics.analyze(lk, t.kinetostatics, kinematics.analyze(lk))


# ----------------------------------------------------------------- the reference
def _fin(v):
    v = float(v)
    return v + 0.0 if math.isfinite(v) else None


def _pt(p):
    return [_fin(p[0]), _fin(p[1])]


def reference_entry(res, i: int, detail: bool) -> dict:
    """The entry of row i, one value at a time."""
    mech, geo, lds = res.mech, res.geo, res.loads
    names = {lk.index: lk.name for lk in mech.links}
    names[0] = "ground"
    ok = bool(res.ok[i])

    def sol(v):
        return _fin(v) if ok else None
    e = {"index": res.index[i], "phi": _fin(res.phi[i] % 360.0)}
    mb, mz, mv, mm = (sol(a[i]) for a in (res.M_b, res.M_zhukovsky, res.M_virtual, res.M_matrix))
    if res.balance_kind == "moment":
        e.update(balancing_moment=mb, balancing_force=sol(res.M_b[i] / res.arm) if res.arm else None,
                 zhukovsky_moment=mz, virtual_power_moment=mv, matrix_moment=mm)
    else:
        e.update(balancing_moment=None, balancing_force=mb, zhukovsky_moment=None, virtual_power_moment=None,
                 matrix_moment=None, zhukovsky_force=mz, virtual_power_force=mv, matrix_force=mm)
    a, b = res.reactions[i], res.reactions_matrix[i]
    e["discrepancy"] = sol(res.discrepancy()[i])
    e["matrix_discrepancy"] = sol(np.max(np.abs(a - b)) / np.maximum(np.max(np.abs(b)), 1e-300))
    good = ok and bool(np.all(np.isfinite(a)))
    scale = np.maximum(np.max(np.abs(np.nan_to_num(a))), 1e-300)
    reactions = {}
    for k, j in enumerate(mech.joints):
        x, y, p = a[2 * k], a[2 * k + 1], geo.jpoint[k][i]
        if j.kind == "R":
            r = {"x": _fin(x), "y": _fin(y), "R": _fin(np.hypot(x, y)), "point": _pt(p)} if good else \
                {"x": None, "y": None, "R": None, "point": _pt(p)}
        else:
            u = geo.jdir[k][i]
            has = abs(x) > 1e-12 * scale
            off = y / x if has else 0.0
            r = {"x": _fin(x * -u[1]), "y": _fin(x * u[0]), "R": _fin(abs(x)), "N": _fin(x), "M": _fin(y),
                 "offset": _fin(off) if has else None,
                 "point": _pt([p[0] + off * u[0], p[1] + off * u[1]]) if has else None, "pin": _pt(p)}
            if not good:
                r.update(x=None, y=None, R=None, N=None, M=None, offset=None, point=None)
        reactions[f"R{j.a}{j.b}"] = r
    e["reactions"] = reactions
    inertia = {}
    for lk in mech.links:
        fx = fy = m = 0.0
        for f in lds.forces:
            if f.kind == "inertia" and f.link == lk.index:
                fx, fy = fx + f.F[i, 0], fy + f.F[i, 1]
        for c in lds.couples:
            if c.kind == "inertia" and c.link == lk.index:
                m = m + c.M[i]
        inertia[lk.name] = {"Fx": _fin(fx), "Fy": _fin(fy), "M": _fin(m)}
    e["inertia"] = inertia
    if detail:
        g = geo.take(slice(i, i + 1))
        e["loads"] = [{"name": f.name, "link": names[f.link], "kind": f.kind, "point": _pt(f.point[i]),
                       "F": _pt(f.F[i]), "v": _pt(g.point_vel(f.link, f.point[i:i + 1])[0])} for f in lds.forces]
        e["couples"] = [{"name": c.name, "link": names[c.link], "kind": c.kind, "M": _fin(c.M[i]),
                         "omega": _fin(g.omega(c.link)[0])} for c in lds.couples]
    n = len(res.phi)
    e["diagram"] = {d["name"]: {"link": d["link"], "kind": d["kind"], "stroke": d["stroke"],
                                "active": bool(np.broadcast_to(np.asarray(d["active"], bool), (n,))[i]),
                                "x": None if d.get("x") is None else _fin(d["x"][i]), "value": _fin(d["value"][i])}
                    for d in lds.info}
    if res.efficiency is not None:
        e.update(efficiency=sol(res.efficiency[i]), friction_power=sol(res.friction_power[i]),
                 driving_power=sol(res.driving_power[i]),
                 friction_pairs={f"R{j.a}{j.b}": sol(res.friction_pairs[i, k]) for k, j in enumerate(mech.joints)})
    else:
        e["efficiency"] = None
    e["near_singular"] = bool(res.near[i]) or not ok
    return e


def _floats(o):
    if isinstance(o, float):
        yield o
    elif isinstance(o, dict):
        for v in o.values():
            yield from _floats(v)
    elif isinstance(o, list):
        for v in o:
            yield from _floats(v)


# ----------------------------------------------------------------- spoilt results
SPECIAL = np.array([np.nan, np.inf, -np.inf, -0.0, 0.0, 1e-300, -1e308, 5e307])


def _spoil_array(a, rng, frac: float = 0.12) -> np.ndarray:
    a = np.array(a, float)
    flat = a.reshape(-1)
    hit = rng.random(flat.size) < frac
    flat[hit] = rng.choice(SPECIAL, int(hit.sum()))
    return a


def _spoil(res, rng) -> None:
    """Specials in every array the entries take (copies: the task's arrays stay)."""
    n = len(res.phi)
    for name in ("M_b", "M_matrix", "M_zhukovsky", "M_virtual", "reactions_matrix", "efficiency",
                 "friction_power", "friction_pairs", "driving_power"):
        if getattr(res, name) is not None:
            setattr(res, name, _spoil_array(getattr(res, name), rng))
    x = _spoil_array(res.reactions, rng, 0.03)
    x[rng.random(n) < 0.1] = np.nan                       # a position not solved
    for k, j in enumerate(res.mech.joints):
        if j.kind == "P":                                 # no normal force: no point of action
            x[rng.random(n) < 0.2, 2 * k] = 1e-20
            x[rng.random(n) < 0.1, 2 * k] = -0.0
    res.reactions = x
    res.ok = res.ok & (rng.random(n) < 0.85)
    res.near = rng.random(n) < 0.2
    geo = res.geo
    geo.jpoint = [_spoil_array(p, rng, 0.05) for p in geo.jpoint]
    geo.omega1 = _spoil_array(geo.omega1, rng, 0.05)
    for f in res.loads.forces:
        f.F, f.point = _spoil_array(f.F, rng), _spoil_array(f.point, rng, 0.05)
    for c in res.loads.couples:
        c.M = _spoil_array(c.M, rng)
    for d in res.loads.info:
        d["value"] = _spoil_array(np.broadcast_to(d["value"], (n,)), rng)
        if d.get("x") is not None:
            d["x"] = _spoil_array(np.broadcast_to(d["x"], (n,)), rng)
        d["active"] = rng.random(n) < 0.5


FRICTION = ("balance: crank\n", "balance: crank\n  friction: {pin_radius: 10 mm, f: 0.1}\n")
CASES = {
    "six-bar, friction": ("forging_sixbar.yaml", (("count: 12", "count: 40"), FRICTION)),
    "six-bar": ("forging_sixbar.yaml", (("count: 12", "count: 30"),)),
    "slider-crank, balance on the piston": ("engine_slider_crank.yaml",
                                            (("count: 12", "count: 36"), ("balance: crank ", "balance: piston "))),
}


@pytest.mark.parametrize("case", list(CASES))
@pytest.mark.parametrize("detail", [True, False])
def test_entries_as_made_one_at_a_time(case, detail, monkeypatch):
    res = _result(*CASES[case])
    clean = [reference_entry(res, i, detail) for i in range(len(res.phi))]
    assert repr(list(entries_mod.lazy_entries(res, detail))) == repr(clean)       # the task's own numbers
    rng = np.random.default_rng(sorted(CASES).index(case) + 10 * detail)
    _spoil(res, rng)
    if case == "six-bar":
        res.arm = None                                    # a balance link without an arm: no balancing force
    with np.errstate(all="ignore"):
        ref = [reference_entry(res, i, detail) for i in range(len(res.phi))]
    text = repr(ref)
    assert all(math.isfinite(v) and (v < 0 or math.copysign(1.0, v) > 0) for v in _floats(ref))
    got = entries_mod.lazy_entries(res, detail)
    assert repr(list(got)) == text
    assert dumps({"kinetostatics": got}) == dumps({"kinetostatics": ref})
    # the spoilt arrays reached the cases they are for
    assert any(all(r["x"] is None for r in e["reactions"].values()) for e in ref)
    assert any(e["balancing_moment"] is None and e["phi"] is not None for e in ref)
    slider = [k for k, j in zip(ref[0]["reactions"], res.mech.joints) if j.kind == "P"]
    assert any(e["reactions"][slider[0]]["N"] is not None and e["reactions"][slider[0]]["point"] is None
               for e in ref)
    assert any(e["reactions"][slider[0]]["point"] is not None for e in ref)
    # tables and blocks of any size: the same entries; reading one entry, or a slice, anywhere
    monkeypatch.setattr(entries_mod, "TABLE_ROWS", 7)
    monkeypatch.setattr(entries_mod, "ENTRY_BLOCK", 3)
    got = entries_mod.lazy_entries(res, detail)
    assert repr(list(got)) == text
    n = len(ref)
    for i in (0, 6, 7, n - 1, 13, 2):
        assert repr(got[i]) == repr(ref[i])
    assert repr(got[5:23]) == repr(ref[5:23]) and repr(got[-9:]) == repr(ref[-9:])
