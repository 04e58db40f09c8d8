"""Velocities and accelerations at ill-conditioned and singular positions: the limit by
continuity, or null (docs/methods.md §2.1).

At a crank angle where a group's normalised determinant s (see :mod:`.changepoints`) is
below ``ILL_DET`` the exact derivatives of the group and of every group it drives carry
round-off errors of about eps / s^2 (velocities) and eps / s^3 (accelerations) of the
cycle's values; where s is zero (a toggle of the group, a change point, the crank pin of a
slotted lever on the lever's pivot) they are 0 / 0. There each analogue (d/dphi, d2/dphi2)
of the links of that group and of the groups solved after it, and of their points, is
taken from either side instead (those of the groups before it, of the crank and of the
ground are regular there and kept):

* on each side the crank angles phi0 +- h STEPS (1, 1.5, 2, 2.5), h the least of LADDER
  (1e-4 deg x 2^k) where every group is assembled and has |s| >= NODE_DET;
* the value at phi0 from each side: the cubic through the four exact values (WEIGHTS),
  checked against the quadratic through the first three (WEIGHTS2); the positions
  extrapolated the same way;
* a side counts where its positions at phi0 are the reported ones (POSE_TOL); a side in
  another pose (POSE_FLIP: a link turned over, the slotted lever at its pivot) is the
  other branch and left out; where the reported pose is neither side's (0 / 0 itself),
  the + side's positions are taken;
* both sides agreeing to ``AGREE`` of the cycle's largest analogue of the kind: their
  mean, the limit by continuity; one side only: its value; next to (not at: |s| >=
  SING_DET) the point, the sides differing (one crosses it), the side the exact value
  agrees with; else (the sides differ at the point: the linkage leaves it along another
  branch, the value jumps -- or a side's cubic and quadratic differ, or its pose is in
  doubt) null.
"""
from __future__ import annotations

import numpy as np

from ...messages import Message
from .changepoints import ILL_DET, SING_DET

LADDER = 1e-4 * 2.0 ** np.arange(17)     # deg: 1e-4 .. 6.6 deg
NODE_DET = 3.0 * ILL_DET                 # the least |s| at the nodes (noise of their accelerations: ~1e-7)
AGREE = 1e-4          # one-sided limits this close (a fraction of the cycle's largest value): one limit
POSE_TOL = 1e-3       # a side whose positions at the point are this close (a fraction of the size; rad) to the reported ones counts
POSE_FLIP = 0.1       # ... this far: another pose (a link turned over: the closure's other branch)
STEPS = np.array([1.0, 1.5, 2.0, 2.5])    # the nodes on a side: phi0 +- h STEPS
WEIGHTS = (10.0, -20.0, 15.0, -4.0)      # the cubic through them, at phi0
WEIGHTS2 = (6.0, -8.0, 3.0, 0.0)         # the quadratic through the first three (its check)
SYMBOL = {"v": "v", "a": "a", "omega": "ω", "epsilon": "ε"}


def det_min(solver, phi_deg: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The least normalised determinant over the groups at each crank angle.

    Parameters
    ----------
    solver : Solver
        The linkage's kinematic model.
    phi_deg : numpy.ndarray
        Crank angles, deg.

    Returns
    -------
    tuple of numpy.ndarray
        The least |s| (NaN where a group does not assemble) and the group that has it.
    """
    st = solver.run(np.radians(np.asarray(phi_deg, float)), strict=False, fallback=False, dets=True)
    return dets_of(solver, st)


def dets_of(solver, st) -> tuple[np.ndarray, np.ndarray]:
    """:func:`det_min` of a run made with ``dets=True``.

    Parameters
    ----------
    solver : Solver
        The linkage's kinematic model.
    st : State
        The run's state.

    Returns
    -------
    tuple of numpy.ndarray
        The least |s| and its group.
    """
    S = np.stack([np.abs(np.asarray(st.gdet[gi], float)) for gi in sorted(st.gdet)])
    for gi in sorted(st.gdet):
        m = st.margins.get(gi) if st.margins else None
        if m is not None:
            S[:, ~(np.asarray(m) >= -solver.tol)] = np.nan
    with np.errstate(invalid="ignore"):
        bad = np.isnan(S).any(axis=0)
        g = np.argmin(np.where(np.isnan(S), np.inf, S), axis=0)
        s = np.where(bad, np.nan, S[g, np.arange(S.shape[1])])
    return s, g


def _reference(mech, solver, solve_raw) -> dict[str, float]:
    """The largest size of each value ('v:P', 'a:P', 'omega:L', 'epsilon:L') over one turn,
    on a 0.5-deg grid at the well-conditioned positions (cached on the solver)."""
    ref = solver.__dict__.get("_limit_reference")
    if ref is not None:
        return ref
    grid = np.arange(0.0, 360.0, 0.5)
    s, _ = det_min(solver, grid)
    grid = grid[s >= ILL_DET]
    ref = {}
    if grid.size:
        k = solve_raw(mech, grid, 1.0, 0.0)
        for p in k.points:
            ref[f"v:{p}"] = float(np.max(np.hypot(*k.d1[p].T)))
            ref[f"a:{p}"] = float(np.max(np.hypot(*k.d2[p].T)))
        for lk in k.links:
            ref[f"omega:{lk}"] = float(np.max(np.abs(k.a1[lk])))
            ref[f"epsilon:{lk}"] = float(np.max(np.abs(k.a2[lk])))
    solver.__dict__["_limit_reference"] = ref
    return ref


def _nodes(solver, phi0: float) -> dict[int, np.ndarray]:
    """Per side (+1, -1): the crank angles phi0 + side h STEPS nearest to phi0 (h from LADDER)
    where every group is assembled and well conditioned (|s| >= NODE_DET); a side is
    missing where no such h exists."""
    off = (LADDER[:, None] * STEPS[None, :]).reshape(-1)
    cand = np.concatenate([phi0 + side * off for side in (1.0, -1.0)])
    s, _ = det_min(solver, cand)
    with np.errstate(invalid="ignore"):
        good = (s >= NODE_DET).reshape(2, LADDER.size, STEPS.size).all(axis=2)
    out = {}
    for k, side in enumerate((1, -1)):
        j = np.flatnonzero(good[k])
        if j.size:
            out[side] = phi0 + side * LADDER[j[0]] * STEPS
    return out


def _values(k, i: int) -> dict[str, np.ndarray]:
    """The analogues of result ``k`` at its position i, by key."""
    out = {}
    for p in k.points:
        out[f"v:{p}"] = np.asarray(k.d1[p][i], float)
        out[f"a:{p}"] = np.asarray(k.d2[p][i], float)
    for lk in k.links:
        out[f"omega:{lk}"] = np.asarray(k.a1[lk][i], float)
        out[f"epsilon:{lk}"] = np.asarray(k.a2[lk][i], float)
    return out


def _poses(k, i: int) -> dict[str, np.ndarray]:
    """The positions of result ``k`` at its position i: 'x:P' (a point's), 'th:L' (a link's angle)."""
    out = {f"x:{p}": np.asarray(k.pos[p][i], float) for p in k.points}
    out.update({f"th:{lk}": np.asarray(k.angle[lk][i], float) for lk in k.links})
    return out


def _extrapolated(k, j: int, get, weights=WEIGHTS) -> dict[str, np.ndarray]:
    """The cubic (``weights``) through side j's positions (rows n j .. n j + n - 1 of ``k``)
    at phi0."""
    n = STEPS.size
    vals = [get(k, n * j + m) for m in range(n)]
    out = {}
    for key in vals[0]:
        v = [x[key] for x in vals]
        if key.startswith("th:"):                 # angles: unwrapped along the side
            v = [v[0]] + [v[0] + _wrap(x - v[0]) for x in v[1:]]
        out[key] = sum(w * x for w, x in zip(weights, v))
    return out


def _wrap(d):
    return (np.asarray(d, float) + np.pi) % (2.0 * np.pi) - np.pi


def _side_limits(mech, solver, solve_raw, phi0: float) -> list[tuple[dict, dict, dict]]:
    """Per side where the nodes exist: (the analogues, the positions, the analogues by the
    quadratic: the check of the cubic's truncation) extrapolated to phi0."""
    nodes = _nodes(solver, phi0)
    if not nodes:
        return []
    sides = list(nodes.values())
    k = solve_raw(mech, np.concatenate(sides), 1.0, 0.0)
    return [(_extrapolated(k, j, _values), _extrapolated(k, j, _poses), _extrapolated(k, j, _values, WEIGHTS2))
            for j in range(len(sides))]


def _pose_gap(a: dict, b: dict, L: float) -> float:
    """How far two sets of positions are apart: points as a fraction of L, angles in rad."""
    gap = 0.0
    for key, x in a.items():
        y = b[key]
        d = _wrap(x - y) if key.startswith("th:") else np.hypot(*(x - y)) / L
        gap = max(gap, float(np.max(np.abs(d))))
    return gap


def _set(res, key: str, i: int, value) -> None:
    what, name = key.split(":", 1)
    arrs = {"v": res.d1, "a": res.d2, "omega": res.a1, "epsilon": res.a2, "x": res.pos, "th": res.angle}[what]
    a = np.array(arrs[name], float, copy=True)        # its own array (a result's may be shared)
    a[i] = value
    arrs[name] = a


def _scales(ref: dict[str, float]) -> dict[str, float]:
    """The size a difference of one-sided limits is measured against: the largest analogue
    (first or second) of any point (for 'v', 'a') or of any link ('omega', 'epsilon')."""
    pts = max([v for k, v in ref.items() if k[0] in "va"] + [1e-300])
    lks = max([v for k, v in ref.items() if k[0] in "oe"] + [1e-300])
    return {"v": pts, "a": pts, "omega": lks, "epsilon": lks}


def by_continuity(mech, solver, res, s: np.ndarray, g: np.ndarray, solve_raw) -> None:
    """The analogues at ill-conditioned positions, by continuity.

    Parameters
    ----------
    mech : Mechanism
        The mechanism.
    solver : Solver
        Its kinematic model.
    res : KinematicsResult
        The result, changed in place: the analogues by continuity or null
        (``res.undefined``), ``near`` (and ``singular`` below SING_DET) set, a warning per
        position in ``res.warnings``.
    s : numpy.ndarray
        The least normalised determinant at each position (below ILL_DET: treated here).
    g : numpy.ndarray
        Its group.
    solve_raw : callable
        :func:`.solver.solve_raw`.

    Notes
    -----
    A side counts where its positions extrapolated to the point are the reported ones (a
    slotted lever whose crank pin passes through the lever's pivot: the closure turns the
    lever by 180 deg there, the two sides are two poses); where neither side's are (the
    reported pose itself is 0 / 0), the positions too are taken from the side of increasing
    crank angle.
    """
    with np.errstate(invalid="ignore"):
        rows = np.flatnonzero(s < ILL_DET)
    if rows.size == 0:
        return
    N = len(res.phi)
    ref = _reference(mech, solver, solve_raw)
    scale = _scales(ref)
    near = np.zeros(N, bool) if res.near is None else np.array(res.near, bool)
    sing = np.zeros(N, bool) if res.singular is None else np.array(res.singular, bool)
    undef = {k: np.array(v, bool) for k, v in res.undefined.items()}
    warnings = list(res.warnings)
    for i in rows:
        phi0 = float(res.phi[i])
        near[i] = True
        if s[i] < SING_DET:
            sing[i] = True
        for v in undef.values():
            v[i] = False
        lims = _side_limits(mech, solver, solve_raw, phi0)
        here = _poses(res, i)
        gaps = [_pose_gap(pose, here, solver.L) for _, pose, _ in lims]
        sides = [(v, v2) for (v, _, v2), gap in zip(lims, gaps) if gap <= POSE_TOL]
        if any(POSE_TOL < gap < POSE_FLIP for gap in gaps):
            sides = []                               # a side's extrapolation not to be trusted: null
        elif lims and not sides:                     # the reported pose is not a limit: the + side's
            for key, x in lims[0][1].items():
                _set(res, key, i, x)
            sides = [(lims[0][0], lims[0][2])]
        taken, nulled = [], []
        named = _named(solver, int(g[i]))
        for key in _values(res, i):
            if key not in named:               # a body of an earlier group, the crank, the ground: regular
                continue
            tol = AGREE * scale[key.split(":", 1)[0]]
            # the sides whose cubic and quadratic agree (their truncation small)
            good = [v[key] for v, v2 in sides if np.all(np.abs(v[key] - v2[key]) <= tol)]
            ok, val = False, None
            if len(good) == len(sides) == 1:
                ok, val = True, good[0]
            elif len(good) == len(sides) == 2 and np.all(np.abs(good[0] - good[1]) <= tol):
                ok, val = True, 0.5 * (good[0] + good[1])
            elif s[i] >= SING_DET:
                # next to (not at) the point the sides differ (one of them crosses it): the one
                # the exact value (its error eps / s^2, eps / s^3) agrees with is the branch there
                raw = _values(res, i)[key]
                match = [v for v in good if np.all(np.abs(v - raw) <= tol)]
                if len(match) == 1:
                    ok, val = True, match[0]
            if ok:
                _set(res, key, i, val)
                taken.append(key)
            else:
                undef.setdefault(key, np.zeros(N, bool))[i] = True
                nulled.append(key)
        grp = solver.groups[int(g[i])]
        common = dict(phi=phi0 % 360.0, **grp.message_params(), det=float(s[i]), ill=ILL_DET)
        if taken:
            warnings.append(Message("kinematics.by_continuity", **common, quantities=_names(taken)))
        if nulled:
            warnings.append(Message("kinematics.no_limit", **common, quantities=_names(nulled)))
    res.near, res.singular = near, sing
    res.undefined = {k: v for k, v in undef.items() if v.any()}
    res.warnings = list(dict.fromkeys(warnings))


def _named(solver, gi: int) -> set[str]:
    """The keys a warning about group gi names: the values of the links of that group and of
    the groups solved after it, and of their points (those of the groups before it, of the
    crank and of the ground are regular there)."""
    bodies = {b for grp in solver.groups[gi:] for b in grp.links}
    _, moving, _, _, links = solver.outputs()
    keys = {f"{w}:{p}" for p, b, _ in moving if b in bodies for w in ("v", "a")}
    keys |= {f"{w}:{nm}" for nm, b in links if b in bodies for w in ("omega", "epsilon")}
    return keys


def _names(keys: list[str]) -> list[str]:
    return [f"{SYMBOL[k.split(':', 1)[0]]} {k.split(':', 1)[1]}" for k in keys]
