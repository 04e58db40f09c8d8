"""Where the loads switch: the crank angles of the jumps (and kinks) of the load diagrams
and the extremes of the loaded sliders, added as positions and as nodes of the dynamics
grid."""
from __future__ import annotations

import numpy as np

from .strokes import load_stroke, stroke_dependent, stroke_states


def switch_angles(mech, loads_section, positions, *, sign: float, cycle: float,
                  kinks: bool = False, roots: dict | None = None) -> list[float]:
    """Crank angles where a task load switches.

    Parameters
    ----------
    mech : Mechanism
        The mechanism.
    loads_section : LoadsSection
        The task's ``loads``.
    positions : PositionsResult
        The positions.
    sign : float
        +1 for a ccw crank, -1 for cw.
    cycle : float
        360 or 720 deg.
    kinks : bool
        True: also where a diagram's slope changes (every inner abscissa: the breakpoints of
        a piecewise quadrature).
    roots : dict or None
        The crank rotations already found for this task's strokes
        (``PositionsResult._roots``), read and added to, so that a root is searched once.

    Returns
    -------
    list of float
        Angles in [0, 360), deg: where a load jumps inside a stroke (a repeated abscissa of
        an s- or phi-diagram), found to 1e-9 deg, and the extreme positions of every slider
        other than the output that carries a stroke-dependent load (docs/methods.md §3.3).
    """
    if loads_section is None:
        return []
    out: list[float] = []
    phi0 = float(positions.phi0)
    cycle = float(cycle)
    output_ext = [float(a) for a in (positions.extreme or [])]
    groups: list[tuple] = []       # (stroke, start, sign, lo, hi, targets) of the s-diagram jumps
    names: list[tuple] = []        # per group: the stroke's link and sense (None: the output's)
    for k, sp in enumerate(loads_section.forces):
        src = positions
        if stroke_dependent(sp) and mech is not None:
            src = load_stroke(positions, mech.link(sp.on), sp, k)
        name = None if src is positions else (src.link, src.working)
        ext = src.extreme
        start = float(ext[0]) if ext else phi0          # the working stroke begins here
        wa = src.working_stroke_angle
        if src is not positions and ext:
            # a slider's own extremes: its load switches there (stroke, s/H from 0)
            out.extend(float(a) for a in ext
                       if all(abs(((a - b) + 180.0) % 360.0 - 180.0) > 1e-9 for b in output_ext))
        d = sp.diagram
        if d is None:
            continue
        xs = d.phi if d.phi is not None else d.s
        jumps = [xs[i] for i in range(len(xs) - 1)
                 if xs[i + 1] == xs[i] and d.value[i + 1] != d.value[i]]
        if kinks:
            jumps = sorted(set(jumps) | {float(x) for x in xs[1:-1]})
        if d.phi is not None:
            for x in jumps:
                if 0 < x % cycle:
                    out.append((phi0 + sign * x) % 360.0)
            continue
        jumps = [x for x in jumps if 0 < x < 1]
        if not jumps or wa is None:
            continue
        if sp.kind is None and "stroke" not in sp.model_fields_set:
            strokes = ["working", "idle"]
        else:
            strokes = ["working", "idle"] if sp.stroke == "both" else [sp.stroke]
        for stroke in strokes:
            lo, hi = (0.0, float(wa)) if stroke == "working" else (float(wa), 360.0)
            groups.append((src, start, sign, lo + 1e-7, hi - 1e-7, jumps))
            names.append(name)
    # every stroke's roots at once: one kinematics call per scan for all of them; a root the
    # positions already found (the positions stage's jumps, asked again with the kinks) is
    # not searched again
    known = {} if roots is None else roots
    keys = [(name,) + tuple(float(x) for x in g[1:5]) for name, g in zip(names, groups)]
    todo = [(src, start, sign_g, lo, hi, [x for x in tg if (key, float(x)) not in known])
            for (src, start, sign_g, lo, hi, tg), key in zip(groups, keys)]
    for g, key, roots in zip(todo, keys, _stroke_roots_many(todo, _s_many(mech))):
        known.update(((key, float(x)), r) for x, r in zip(g[5], roots))
    for (_, start, sign_g, _lo, _hi, tg), key in zip(groups, keys):
        roots = [known[(key, float(x))] for x in tg]
        out.extend((start + sign_g * t) % 360.0 for t in roots if t is not None)
    res = []
    for a in sorted(out):
        a = 0.0 if a >= 360.0 - 1e-12 else a
        if not res or abs(a - res[-1]) > 1e-9:
            res.append(float(a))
    return res


def _s_many(mech):
    """s_many([(stroke, phi), ...]) -> [s/H at phi, ...]: with the mechanism, one kinematics
    call for all of them (each stroke reads its link off it); else each stroke alone."""
    def alone(items):
        return [stroke_states(src, phi)[1] for src, phi in items]

    if mech is None:
        return alone

    def together(items):
        from ..kinematics.solver import solve
        phi = np.concatenate([np.asarray(p, float).ravel() for _, p in items])
        kin = solve(mech, phi)
        out, i = [], 0
        for src, p in items:
            n = np.asarray(p).size
            out.append(stroke_states(src, phi, kin)[1][i:i + n])
            i += n
        return out
    return together


def _stroke_roots(positions, start: float, sign: float, lo: float, hi: float, targets,
                  n: int = 257, passes: int = 1) -> list[float | None]:
    """Crank rotations t in [lo, hi] (deg from `start` along the motion, within one stroke,
    where s/H is monotonic) at which s/H equals each target (see `_stroke_roots_many`).
    None for a target the stroke does not reach."""
    return _stroke_roots_many([(positions, start, sign, lo, hi, targets)], _s_many(None), n, passes)[0]


def _stroke_roots_many(groups, s_many, n: int = 257, passes: int = 1) -> list[list[float | None]]:
    """Per group (stroke, start, sign, lo, hi, targets): the crank rotations t in [lo, hi]
    (deg from `start` along the motion, within one stroke, where s/H is monotonic) at which
    s/H equals each target: all targets of all groups at once, by vectorised scans (n
    points, then n points in every bracket, `passes` times: the bracket shrinks to
    (hi - lo)/(n - 1)^(passes + 1), about 5e-3 deg; each scan one call of s_many) and a
    final cubic through the four samples around the bracket, solved by Newton's method from
    the linear interpolation (error ~ bracket^4, below 1e-12 deg; the linear value where
    the cubic's root leaves the bracket).  None for a target the stroke does not reach."""
    tgs = [np.asarray([float(x) for x in g[5]]) for g in groups]
    live = [k for k, tg in enumerate(tgs) if tg.size]
    out: list[list[float | None]] = [[] for _ in groups]
    if not live:
        return out

    def scan(ts):
        vals = s_many([(groups[k][0], np.mod(groups[k][1] + groups[k][2] * t.ravel(), 360.0))
                       for k, t in zip(live, ts)])
        return [v.reshape(t.shape) for v, t in zip(vals, ts)]

    # the first scan is the same for every target of a group: sampled once, one row a target
    t1 = [np.linspace(groups[k][3], groups[k][4], n)[None, :] for k in live]
    ts = [t.repeat(tgs[k].size, 0) for t, k in zip(t1, live)]
    svs = [sv.repeat(tgs[k].size, 0) for sv, k in zip(scan(t1), live)]
    found = [np.ones(tgs[k].size, bool) for k in live]
    for it in range(passes + 1):
        brackets = []
        for m, k in enumerate(live):
            tg, t, sv = tgs[k], ts[m], svs[m]
            r = np.arange(tg.size)
            d = sv - tg[:, None]
            hit = (d[:, :-1] * d[:, 1:]) <= 0
            found[m] &= hit.any(axis=1)
            i = np.argmax(hit, axis=1)
            brackets.append((i, t[r, i], t[r, i + 1], sv[r, i], sv[r, i + 1]))
        if it == passes:
            break
        ts = [a[:, None] + (b - a)[:, None] * np.linspace(0.0, 1.0, n)[None, :] for (_, a, b, _, _) in brackets]
        svs = scan(ts)
    for m, k in enumerate(live):
        out[k] = _cubic_root(tgs[k], ts[m], svs[m], found[m], *brackets[m])
    return out


def _cubic_root(tg, t, sv, found, i, a, b, sa, sb) -> list[float | None]:
    """The roots in the final brackets: linear interpolation refined by the cubic through the
    four samples i-1 .. i+2 (Newton's divided differences, Newton's method on the cubic)."""
    r = np.arange(tg.size)
    den = np.where(sb != sa, sb - sa, 1.0)
    root = np.where(sb != sa, a + (tg - sa) / den * (b - a), a)
    j = np.clip(i - 1, 0, t.shape[1] - 4)
    X = t[r[:, None], j[:, None] + np.arange(4)]
    Y = sv[r[:, None], j[:, None] + np.arange(4)] - tg[:, None]
    c1 = (Y[:, 1:] - Y[:, :-1]) / (X[:, 1:] - X[:, :-1])
    c2 = (c1[:, 1:] - c1[:, :-1]) / (X[:, 2:] - X[:, :-2])
    c3 = (c2[:, 1:] - c2[:, :-1]) / (X[:, 3] - X[:, 0])[:, None]
    x = root.copy()
    with np.errstate(all="ignore"):
        for _ in range(4):
            u0, u1, u2 = x - X[:, 0], x - X[:, 1], x - X[:, 2]
            f = Y[:, 0] + u0 * (c1[:, 0] + u1 * (c2[:, 0] + u2 * c3[:, 0]))
            df = (c1[:, 0] + c2[:, 0] * (u0 + u1) + c3[:, 0] * (u0 * u1 + u0 * u2 + u1 * u2))
            x = x - np.where(df != 0, f / np.where(df != 0, df, 1.0), 0.0)
    good = np.isfinite(x) & (x >= np.minimum(a, b)) & (x <= np.maximum(a, b)) & (sb != sa)
    root = np.where(good, x, root)
    return [float(x) if ok else None for x, ok in zip(root, found)]
