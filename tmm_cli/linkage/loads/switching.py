"""Where the loads switch: the crank angles of the jumps (and kinks) of the load diagrams
and the extremes of the loaded sliders, added as positions and as nodes of the dynamics
grid."""
from __future__ import annotations

import numpy as np

from .strokes import load_stroke, stroke_dependent, stroke_states


def switch_angles(mech, loads_section, positions, *, sign: float, cycle: float,
                  kinks: bool = False) -> list[float]:
    """Crank angles in [0, 360) where a task load switches: where it jumps inside a stroke
    (a repeated abscissa of an s- or phi-diagram), found to 1e-9 deg, and the extreme
    positions of every slider other than the output that carries a stroke-dependent load
    (where its own strokes begin and end, docs/methods.md §3.3); with kinks=True also
    where a diagram's slope changes (every inner abscissa: the breakpoints of a piecewise
    quadrature).  ``sign``: +1 ccw, -1 cw; ``cycle``: 360 or 720 deg."""
    if loads_section is None:
        return []
    out: list[float] = []
    phi0 = float(positions.phi0)
    cycle = float(cycle)
    output_ext = [float(a) for a in (positions.extreme or [])]
    for k, sp in enumerate(loads_section.forces):
        src = positions
        if stroke_dependent(sp) and mech is not None:
            src = load_stroke(positions, mech.link(sp.on), sp, k)
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
            for t in _stroke_roots(src, start, sign, lo + 1e-7, hi - 1e-7, jumps):
                if t is not None:
                    out.append((start + sign * t) % 360.0)
    res = []
    for a in sorted(out):
        a = 0.0 if a >= 360.0 - 1e-12 else a
        if not res or abs(a - res[-1]) > 1e-9:
            res.append(float(a))
    return res


def _stroke_roots(positions, start: float, sign: float, lo: float, hi: float, targets,
                  n: int = 257, passes: int = 3) -> list[float | None]:
    """Crank rotations t in [lo, hi] (deg from `start` along the motion, within one stroke,
    where s/H is monotonic) at which s/H equals each target: all targets at once, by
    vectorised scans (n points, then n points in every bracket, `passes` times: the
    bracket shrinks to (hi - lo)/(n - 1)^(passes + 1), about 1e-7 deg) and a final linear
    interpolation in the bracket (error ~ curvature x bracket^2, below 1e-12 deg).
    None for a target the stroke does not reach."""
    tg = np.asarray([float(x) for x in targets])
    if tg.size == 0:
        return []

    def s_of(t):
        return stroke_states(positions, np.mod(start + sign * t, 360.0))[1]

    t = np.linspace(lo, hi, n)[None, :].repeat(tg.size, 0)
    sv = s_of(t.ravel()).reshape(t.shape)
    found = np.ones(tg.size, bool)
    a = np.zeros(tg.size)
    b = np.zeros(tg.size)
    sa = np.zeros(tg.size)
    sb = np.zeros(tg.size)
    for it in range(passes + 1):
        d = sv - tg[:, None]
        hit = (d[:, :-1] * d[:, 1:]) <= 0
        found &= hit.any(axis=1)
        i = np.argmax(hit, axis=1)
        r = np.arange(tg.size)
        a, b = t[r, i], t[r, i + 1]
        sa, sb = sv[r, i], sv[r, i + 1]
        if it == passes:
            break
        t = a[:, None] + (b - a)[:, None] * np.linspace(0.0, 1.0, n)[None, :]
        sv = s_of(t.ravel()).reshape(t.shape)
    den = np.where(sb != sa, sb - sa, 1.0)
    root = np.where(sb != sa, a + (tg - sa) / den * (b - a), a)
    return [float(x) if ok else None for x, ok in zip(root, found)]
