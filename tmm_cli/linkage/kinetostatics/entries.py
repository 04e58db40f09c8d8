"""The ``kinetostatics`` entries of results.json (one dict per position), made from a
:class:`~tmm_cli.linkage.kinetostatics.analysis.KinetostaticsResult`'s arrays when read
(:func:`tmm_cli.entrytable.tabled`: two levels, each at the size it runs fastest at):

* the numbers, vectorised over ``TABLE_ROWS`` positions at a time (:func:`_table`): every
  value of the entries, clean (-0.0 made 0.0; NaN where the entry holds None: not finite,
  or a position not solved), as one float array of the scalar values (a row per value,
  in the order the entries take them), one of the points (x, y) and a few lists of
  flags (bool or int per position);
* the entries, ``ENTRY_BLOCK`` positions at a time (:func:`_assemble`): one ``tolist``
  of the block's columns, then the dicts zipped from them (dict displays for the keyed
  dicts, :func:`tmm_cli.entrytable.dicts`), made and freed in the CPU's cache.

Every value depends on its own position only: the entries do not depend on the blocks.
"""
from __future__ import annotations

import numpy as np

from ...entrytable import clean, dicts, nan_rows, tabled, values
from ...results import LazyEntries

TABLE_ROWS = 4096      # positions whose values are computed at a time (numpy)
ENTRY_BLOCK = 64       # entries made at a time (dicts and floats: ~0.4 MB)


def lazy_entries(res, detail: bool) -> LazyEntries:
    """The ``kinetostatics`` entries of a result, computed when first read.

    Parameters
    ----------
    res : KinetostaticsResult
        The result.
    detail : bool
        True: the detailed entries too.

    Returns
    -------
    LazyEntries
        The values of ``TABLE_ROWS`` positions computed when first read (the last two such
        tables kept), the entries made from them ``ENTRY_BLOCK`` at a time.
    """
    n = len(res.phi)
    with np.errstate(all="ignore"):
        # the two whole-turn columns the entries take (the rest is computed per table)
        disc = res.discrepancy()
        a, b = res.reactions, res.reactions_matrix
        mdisc = np.max(np.abs(a - b), axis=1) / np.maximum(np.max(np.abs(b), axis=1), 1e-300)
    lay = _layout(res, detail)
    return tabled(n, lambda sl: _table(res, sl, detail, disc, mdisc), lambda tab, a, b: _assemble(lay, tab, a, b),
                  TABLE_ROWS, ENTRY_BLOCK)


def _layout(res, detail: bool) -> dict:
    """What the entries hold besides the numbers: the keys, the pairs' kinds, the names."""
    mech = res.mech
    names = res._link_names()
    lds = res.loads
    moment = res.balance_kind == "moment"
    top = ["index", "phi"]
    if moment:
        top += ["balancing_moment", "balancing_force", "zhukovsky_moment", "virtual_power_moment", "matrix_moment"]
    else:
        top += ["balancing_moment", "balancing_force", "zhukovsky_moment", "virtual_power_moment", "matrix_moment",
                "zhukovsky_force", "virtual_power_force", "matrix_force"]
    top += ["discrepancy", "matrix_discrepancy", "reactions", "inertia"]
    if detail:
        top += ["loads", "couples"]
    top.append("diagram")
    friction = res.efficiency is not None
    top += ["efficiency", "friction_power", "driving_power", "friction_pairs"] if friction else ["efficiency"]
    top.append("near_singular")
    return {
        "top": tuple(top), "moment": moment, "with_force": bool(moment and res.arm), "friction": friction,
        "detail": detail,
        "joints": tuple(f"R{j.a}{j.b}" for j in mech.joints), "pin": tuple(j.kind == "R" for j in mech.joints),
        "links": tuple(lk.name for lk in mech.links),
        "forces": tuple((f.name, names[f.link], f.kind) for f in lds.forces) if detail else (),
        "couples": tuple((c.name, names[c.link], c.kind) for c in lds.couples) if detail else (),
        "diagrams": tuple((d["name"], d["link"], d["kind"], d["stroke"], d.get("x") is not None)
                          for d in lds.info),
    }


def _table(res, sl: slice, detail: bool, disc: np.ndarray, mdisc: np.ndarray) -> tuple:
    """The values of the entries of the rows ``sl``: (scalars (C, k), points (Q, k, 2),
    flags [lists of k], the running count of the rows holding a NaN (k + 1 ints)).
    NaN stands for None; never -0.0."""
    mech, geo = res.mech, res.geo
    k = len(range(*sl.indices(len(res.phi))))
    ok = res.ok[sl]
    nan = np.nan
    col: list[np.ndarray] = []
    pts: list[np.ndarray] = []
    flags: list[list] = [[int(i) for i in res.index[sl]]]

    def solved(a):
        """The values at the positions solved (elsewhere None)."""
        col.append(np.where(ok, a, nan))

    col.append(res.phi[sl] % 360.0)
    Mb = res.M_b[sl]
    solved(Mb)
    if res.balance_kind == "moment" and res.arm:
        solved(Mb / res.arm)
    solved(res.M_zhukovsky[sl])
    solved(res.M_virtual[sl])
    solved(res.M_matrix[sl])
    solved(disc[sl])
    solved(mdisc[sl])
    # the reactions: where the position is solved and its reactions finite, else None
    reactions = res.reactions[sl]
    good = ok & np.all(np.isfinite(reactions), axis=1)
    scale = np.maximum(np.max(np.abs(np.nan_to_num(reactions)), axis=1), 1e-300)
    for j_, j in enumerate(mech.joints):
        x = reactions[:, 2 * j_]
        y = reactions[:, 2 * j_ + 1]
        p = geo.jpoint[j_][sl]
        if j.kind == "R":
            col += [np.where(good, x, nan), np.where(good, y, nan), np.where(good, np.hypot(x, y), nan)]
            pts.append(p)
        else:
            # a slider's pair: the normal force N along n = rot90(e), the couple M, the
            # force's point of action on the guide at offset M / N from the pin
            e = geo.jdir[j_][sl]
            nx, ny = -e[:, 1], e[:, 0]
            N_, M_ = x, y
            has = np.abs(N_) > 1e-12 * scale
            off = np.where(has, M_ / np.where(has, N_, 1.0), 0.0)
            col += [np.where(good, N_ * nx, nan), np.where(good, N_ * ny, nan),
                    np.where(good, np.abs(N_), nan), np.where(good, N_, nan), np.where(good, M_, nan),
                    np.where(good & has, off, nan)]
            pts += [p + off[:, None] * e, p]
            flags.append((good & has).tolist())
    # the inertia loads per link (summed)
    inert = {lk.index: [np.zeros(k), np.zeros(k), np.zeros(k)] for lk in mech.links}
    for f in res.loads.forces:
        if f.kind == "inertia" and f.link:
            inert[f.link][0] += f.F[sl, 0]
            inert[f.link][1] += f.F[sl, 1]
    for c in res.loads.couples:
        if c.kind == "inertia" and c.link:
            inert[c.link][2] += c.M[sl]
    for lk in mech.links:
        col += inert[lk.index]
    if detail:
        g = geo.take(sl)
        # where a link's velocities have no limit (a change point) the velocities of its loads have none
        none = np.zeros(len(res.phi), bool)
        for f in res.loads.forces:
            point = f.point[sl]
            bad = res.undefined_velocity.get(f.link, none)[sl]
            pts += [point, f.F[sl], np.where(bad[:, None], nan, g.point_vel(f.link, point))]
        for c in res.loads.couples:
            col += [c.M[sl], np.where(res.undefined_velocity.get(c.link, none)[sl], nan, g.omega(c.link))]
    n_all = len(res.phi)
    for d in res.loads.info:
        flags.append(np.broadcast_to(np.asarray(d["active"], bool), (n_all,))[sl].tolist())
        if d.get("x") is not None:
            col.append(np.asarray(d["x"], float)[sl])
        col.append(np.asarray(d["value"], float)[sl])
    if res.efficiency is not None:
        for a in (res.efficiency[sl], res.friction_power[sl], res.driving_power[sl]):
            solved(a)
        for j_ in range(len(mech.joints)):
            solved(res.friction_pairs[sl, j_])
    flags.append((res.near[sl] | ~ok).tolist())
    F = clean(np.array(col, float).reshape(len(col), k))
    P = clean(np.array(pts, float).reshape(len(pts), k, 2))
    return F, P, flags, nan_rows(F, P)


def _assemble(lay: dict, tab: tuple, a: int, b: int) -> list[dict]:
    """The entries of the rows a..b-1 of the table ``tab`` (taking its values in order)."""
    F, P, flags, nans = tab
    n = b - a
    nan = nans[b] != nans[a]
    fv, pv = values(F[:, a:b], nan), values(P[:, a:b], nan)
    f, p, g = iter(fv).__next__, iter(pv).__next__, iter(flags).__next__
    none = [None] * n
    cols = [g()[a:b], f(), f()]                                 # index, phi, balancing moment (force)
    if lay["moment"]:
        cols += [f() if lay["with_force"] else none, f(), f(), f()]
    else:
        cols = cols[:2] + [none, cols[2], none, none, none, f(), f(), f()]
    cols += [f(), f()]                                          # discrepancy, matrix_discrepancy
    reactions = []
    for pin in lay["pin"]:
        if pin:
            reactions.append([{"x": x, "y": y, "R": r, "point": q} for x, y, r, q in zip(f(), f(), f(), p())])
        else:
            reactions.append([{"x": x, "y": y, "R": r, "N": N_, "M": M_, "offset": o, "point": q if h else None,
                               "pin": pin_} for x, y, r, N_, M_, o, q, pin_, h in
                              zip(f(), f(), f(), f(), f(), f(), p(), p(), g()[a:b])])
    cols.append(dicts(lay["joints"], reactions, n))
    cols.append(dicts(lay["links"], [[{"Fx": x, "Fy": y, "M": m} for x, y, m in zip(f(), f(), f())]
                                      for _ in lay["links"]], n))
    if lay["detail"]:
        loads = [[{"name": nm, "link": lk, "kind": kd, "point": q, "F": F_, "v": v}
                  for q, F_, v in zip(p(), p(), p())] for nm, lk, kd in lay["forces"]]
        couples = [[{"name": nm, "link": lk, "kind": kd, "M": M_, "omega": w} for M_, w in zip(f(), f())]
                   for nm, lk, kd in lay["couples"]]
        cols += [[list(r) for r in zip(*loads)] if loads else [[] for _ in range(n)],
                 [list(r) for r in zip(*couples)] if couples else [[] for _ in range(n)]]
    diagrams = [[{"link": lk, "kind": kd, "stroke": sk, "active": ac, "x": x, "value": v}
                 for ac, x, v in zip(g()[a:b], f() if has_x else none, f())]
                for _, lk, kd, sk, has_x in lay["diagrams"]]
    cols.append(dicts(tuple(d[0] for d in lay["diagrams"]), diagrams, n))
    if lay["friction"]:
        cols += [f(), f(), f(), dicts(lay["joints"], [f() for _ in lay["joints"]], n)]
    else:
        cols.append(none)
    cols.append(g()[a:b])                                       # near_singular
    return dicts(lay["top"], cols, n)
