"""Loads on the links of a linkage, evaluated at the computed positions.

``evaluate(mech, loads_section, kin, positions, *, inertia=True) -> Loads`` turns
the task's ``loads`` section (README, *loads*) into per-position applied forces (link,
point of application, force vector) and couples (link, moment), all (N,)-arrays
over the positions of ``kin``:

* gravity (``gravity: true``): G_i = m_i g along -y at S_i, g = 9.81 m/s^2;
* inertia loads (d'Alembert, docs/methods.md §3.1): F_in = -m a_S at S_i, M_in = -J_S eps_i;
* task forces. A force acts along the guide of a slider (unit vector e along the
  guide direction) or along ``direction`` (deg from +x, absolute) on any link; a bar
  with a resistance/driving force and no ``direction`` gets the force along the
  velocity of its point. Its point of application is ``at`` (a point name or local
  ``[u, v]``), default the link's centre of mass S.

  - ``kind: resistance`` opposes the motion of its point (F = -|P| e sign(v.e)),
    ``kind: driving`` acts along it; the magnitude |P| is ``magnitude`` (constant) or
    an ``s``-diagram over the relative stroke s/H in [0, 1] measured from the start of
    the stroke (working, idle or both) in which the load acts (``stroke``); outside
    that stroke the load is zero.  ``positions.stroke_state(phi)`` gives the stroke
    and s/H of the output link; at an extreme position (velocity zero) the stroke that
    begins there applies (position 0 carries the working-stroke load), and the sense
    of motion is that of the motion about to begin (the sign of the acceleration
    analogue d2r/dphi2 . e, since v = 0 there).
  - a ``phi``-diagram is the signed force along e over the crank angle of the cycle
    **measured from position 0** (phi_rel = (phi - phi0) * sign(omega1) mod cycle, so
    an engine's indicator diagram starts at its TDC = position 0; for a 720-deg cycle
    the reported positions are read in the first turn after position 0 and unwrapped
    angles phi0 + sign*q, q in [360, 720), in the second: see cycle_angle). Between the given
    abscissae the value is interpolated linearly, beyond them it is held constant.
    ``stroke`` and ``kind`` do not change a phi-diagram (the sign is in the diagram).
  - a force with no ``kind`` and a ``magnitude`` or an ``s``-diagram is a signed force
    along e; it acts over the whole cycle unless ``stroke`` is given explicitly.
  - ``area``: the magnitude / diagram values are pressures (Pa), force = p * area.
  - ``moment``: a couple, ccw positive; with ``kind: resistance`` (``driving``) it is
    |M| against (along) the rotation of its link, on ``stroke``; without a kind it is
    the signed constant couple over the whole cycle (or over ``stroke`` if given).

  A diagram with a repeated abscissa (``s: [0, 0.2, 0.2, 1]``) jumps there; at the
  jump the value after it (in the direction of motion) applies.
  ``switch_angles(mech, loads_section, positions)`` gives the crank angles of such
  jumps inside a stroke, which the pipeline adds as extra positions.

All of this follows docs/methods.md §3.1 and, where it is silent, Artobolevsky's and Popov's
textbooks (force of production resistance acting against the motion of the
working member over the working stroke given by its diagram over the stroke).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from ..errors import StageError, TaskError

G = 9.81
_SNAP = 1e-9          # s/H or deg: abscissae this close to a jump are put on it


# ------------------------------------------------------------------ data
@dataclass
class AppliedForce:
    link: int
    name: str
    point: np.ndarray          # (N, 2) position of the point of application
    F: np.ndarray              # (N, 2)
    kind: str                  # resistance | driving | load | gravity | inertia | friction
    local: tuple[float, float] | None = None   # point in the link's local frame (if fixed on it)
    point_name: str | None = None


@dataclass
class AppliedCouple:
    link: int
    name: str
    M: np.ndarray              # (N,) ccw positive
    kind: str


@dataclass
class Loads:
    phi: np.ndarray
    forces: list[AppliedForce] = field(default_factory=list)
    couples: list[AppliedCouple] = field(default_factory=list)
    info: list[dict] = field(default_factory=list)     # task loads: diagram values per position

    def external(self) -> "Loads":
        """The loads without the inertia loads."""
        return Loads(self.phi, [f for f in self.forces if f.kind != "inertia"],
                     [c for c in self.couples if c.kind != "inertia"], self.info)

    def select(self, rows) -> "Loads":
        """The loads at the positions ``rows`` only."""
        rows = np.asarray(rows, dtype=int)
        return Loads(np.asarray(self.phi)[rows],
                     [replace(f, point=f.point[rows], F=f.F[rows]) for f in self.forces],
                     [replace(c, M=c.M[rows]) for c in self.couples],
                     [{k: (np.asarray(v)[rows] if isinstance(v, np.ndarray) else v) for k, v in d.items()}
                      for d in self.info])

    def __len__(self) -> int:
        return len(self.phi)


# ------------------------------------------------------------------ kinematics access
def _get(d: dict, lk) -> np.ndarray:
    for key in (lk.name, lk.index, str(lk.index)):
        if key in d:
            return np.asarray(d[key], dtype=float)
    raise KeyError(f"kinematics has no entry for link '{lk.name}'")


def _rot90(r: np.ndarray) -> np.ndarray:
    return np.stack([-r[..., 1], r[..., 0]], axis=-1)


def point_motion(kin, lk, at) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Position, dr/dphi, d2r/dphi2 ((N,2) each) of a point fixed on link ``lk``:
    a point name (from the kinematics) or local [u, v] (rigid-body formulas)."""
    if isinstance(at, str):
        if at in kin.pos:
            return (np.asarray(kin.pos[at], float), np.asarray(kin.d1[at], float),
                    np.asarray(kin.d2[at], float))
        if at not in lk.local:
            raise KeyError(f"no point '{at}' on link '{lk.name}'")
        at = lk.local[at]
    u, v = float(at[0]), float(at[1])
    o = lk.origin
    th = _get(kin.angle, lk)
    a1 = _get(kin.a1, lk)
    a2 = _get(kin.a2, lk)
    c, s = np.cos(th), np.sin(th)
    r = np.stack([c * u - s * v, s * u + c * v], axis=-1)
    jr = _rot90(r)
    p0 = np.asarray(kin.pos[o], float)
    d10 = np.asarray(kin.d1[o], float)
    d20 = np.asarray(kin.d2[o], float)
    return p0 + r, d10 + a1[:, None] * jr, d20 + a2[:, None] * jr - (a1 ** 2)[:, None] * r


def _w(kin, n: int) -> tuple[np.ndarray, np.ndarray]:
    w = np.broadcast_to(np.asarray(kin.omega1, float), (n,)).astype(float)
    e = np.broadcast_to(np.asarray(getattr(kin, "eps1", 0.0), float), (n,)).astype(float)
    return w, e


def com_point(lk):
    return lk.com


# ------------------------------------------------------------------ diagrams
def interp_right(x: np.ndarray, xp, fp) -> np.ndarray:
    """Piecewise-linear interpolation, constant beyond the ends, right-continuous at a
    repeated abscissa (the value after the jump); x within 1e-9 of an abscissa is
    snapped onto it."""
    xp = np.asarray(xp, float)
    fp = np.asarray(fp, float)
    x = np.array(x, dtype=float, copy=True)
    j = np.clip(np.searchsorted(xp, x), 0, len(xp) - 1)
    for jj in (j, np.clip(j - 1, 0, len(xp) - 1)):
        near = np.abs(x - xp[jj]) <= _SNAP * max(1.0, float(np.max(np.abs(xp))))
        x[near] = xp[jj][near]
    i = np.searchsorted(xp, x, side="right") - 1
    out = np.empty_like(x)
    lo = i < 0
    hi = i >= len(xp) - 1
    mid = ~(lo | hi)
    out[lo] = fp[0]
    out[hi] = fp[-1]
    im = i[mid]
    x0, x1 = xp[im], xp[im + 1]
    t = (x[mid] - x0) / (x1 - x0)
    out[mid] = fp[im] + t * (fp[im + 1] - fp[im])
    return out


def stroke_states(positions, phi: np.ndarray, kin=None) -> tuple[np.ndarray, np.ndarray]:
    """(working: bool (N,), s/H (N,)) from ``positions.stroke_state`` (scalar or vector;
    ``kin``: the kinematics at phi, passed on so that it is not solved again)."""
    phi = np.asarray(phi, float)
    try:
        st, s = positions.stroke_state(phi) if kin is None else _stroke_state_kin(positions, phi, kin)
        st_arr = np.asarray(st)
        s_arr = np.asarray(s, float)
        if st_arr.shape == phi.shape and s_arr.shape == phi.shape:
            return st_arr == "working", s_arr
    except (TypeError, ValueError):
        pass
    work = np.zeros(phi.shape, bool)
    s = np.zeros(phi.shape)
    for k, p in enumerate(phi.ravel()):
        stk, sk = positions.stroke_state(float(p))
        work.ravel()[k] = stk == "working"
        s.ravel()[k] = float(sk)
    return work, s


def _stroke_state_kin(positions, phi, kin):
    try:
        return positions.stroke_state(phi, kin=kin)
    except TypeError:            # a stand-in without the kin argument
        return positions.stroke_state(phi)


def _drive_sign(positions, kin=None) -> float:
    sg = getattr(positions, "sign", None)
    if sg in (1, -1, 1.0, -1.0):
        return float(sg)
    if kin is not None:
        w = np.asarray(kin.omega1, float).ravel()
        if w.size and w[0] != 0:
            return 1.0 if w[0] > 0 else -1.0
    ext = getattr(positions, "extreme", None)
    wa = getattr(positions, "working_stroke_angle", None)
    if ext is not None and wa is not None and len(ext) == 2:
        d = (ext[1] - ext[0] - wa) % 360.0
        return 1.0 if min(d, 360 - d) < 1e-3 else -1.0
    return 1.0


# ------------------------------------------------------------------ evaluate
def _motion_sign(d1e: np.ndarray, d2e: np.ndarray, w: np.ndarray, scale: float) -> np.ndarray:
    """Sign of the velocity along e; at rest the sign of the motion about to begin."""
    v = d1e * np.sign(w)
    tol = 1e-9 * max(scale, 1e-12)
    sg = np.sign(v)
    rest = np.abs(d1e) <= tol
    sg[rest] = np.sign(d2e[rest])
    return sg


def _length_scale(mech) -> float:
    L = [abs(lk.length) for lk in mech.links if lk.length]
    return max(L + [1e-3])


def _cycle(loads_section, positions, cycle) -> float:
    if cycle:
        return float(cycle)
    c = getattr(positions, "cycle", None)
    if c:
        return float(c)
    for sp in getattr(loads_section, "forces", []) or []:
        if sp.diagram is not None and sp.diagram.phi is not None and max(sp.diagram.phi) > 360.0 + 1e-9:
            return 720.0
    return 360.0


def cycle_angle(phi, phi0: float, sign: float, cycle: float) -> np.ndarray:
    """Crank rotation from position 0 along the motion, in [0, cycle). Angles at or
    after phi0 (along the motion, unwrapped: phi0 + sign*q) give q mod cycle; angles
    numerically before phi0 (the reported positions are in [0, 360)) are read in the
    first turn: q mod 360."""
    q = (np.asarray(phi, float) - phi0) * sign
    q = np.where(q < 0, np.mod(q, 360.0), np.mod(q, cycle))
    return np.where(q > cycle - _SNAP, 0.0, q)


def _stroke_dependent(sp) -> bool:
    """A load that depends on a stroke: a `kind` or a `stroke`, and not a phi diagram."""
    return ((sp.kind is not None or "stroke" in sp.model_fields_set)
            and not (sp.diagram is not None and sp.diagram.phi is not None))


def load_stroke(positions, lk, sp, k: int):
    """The stroke a stroke-dependent load follows (docs/methods.md §3.3): a slider's own
    (its extremes, stroke H and working sense: the load's `working`, default
    positions.working, along its own guide); for a bar, the output's. ``positions``
    without ``stroke_for`` (a bare stand-in) is the stroke itself."""
    working = getattr(sp, "working", None)
    if lk.kind != "slider":
        if working is not None:
            raise _field_error(f"loads.forces[{k}].working", f"`working` sets the stroke of a slider; "
                                                            f"'{lk.name}' is not a slider")
        return positions
    if not hasattr(positions, "stroke_for"):
        return positions
    return positions.stroke_for(lk.name, working)


def slider_strokes(mech, loads_section, positions) -> dict:
    """The own strokes of the loaded sliders other than the output (name -> Stroke; a
    slider loaded in both senses: 'name (forward)' and 'name (backward)'), for the results."""
    found = []
    for k, sp in enumerate(getattr(loads_section, "forces", []) or []):
        try:
            lk = mech.link(sp.on)
        except KeyError:
            continue
        if not (_stroke_dependent(sp) and lk.kind == "slider" and hasattr(positions, "stroke_for")):
            continue
        st = load_stroke(positions, lk, sp, k)
        if (st.link, st.working) != (positions.output, positions.working) and \
                all((s.link, s.working) != (st.link, st.working) for s in found):
            found.append(st)
    names = [s.link for s in found]
    return {(s.link if names.count(s.link) == 1 else f"{s.link} ({s.working})"): s for s in found}


def evaluate(mech, loads_section, kin, positions=None, *, inertia: bool = True,
             cycle: float | None = None) -> Loads:
    """Per-position loads of the mechanism (see the module docstring). ``cycle``: 360 or
    720 deg (default: ``positions.cycle`` if present, else 720 when a phi-diagram reaches
    beyond 360 deg, else 360)."""
    phi = np.atleast_1d(np.asarray(kin.phi, float))
    n = len(phi)
    w, e = _w(kin, n)
    out = Loads(phi=phi)
    Lc = _length_scale(mech)
    gravity = bool(getattr(loads_section, "gravity", False)) if loads_section is not None else False
    for lk in mech.links:
        sname = f"S{lk.index}"
        if (gravity and lk.mass > 0) or (inertia and (lk.mass > 0 or lk.J > 0)):
            p, d1, d2 = point_motion(kin, lk, sname if sname in kin.pos else lk.com)
        if gravity and lk.mass > 0:
            F = np.zeros((n, 2))
            F[:, 1] = -lk.mass * G
            out.forces.append(AppliedForce(lk.index, f"G{lk.index}", p, F, "gravity", lk.com, sname))
        if inertia and lk.mass > 0:
            a = d2 * (w ** 2)[:, None] + d1 * e[:, None]
            out.forces.append(AppliedForce(lk.index, f"Fi{lk.index}", p, -lk.mass * a, "inertia",
                                           lk.com, sname))
        if inertia and lk.J > 0:
            eps = _get(kin.a2, lk) * w ** 2 + _get(kin.a1, lk) * e
            out.couples.append(AppliedCouple(lk.index, f"Mi{lk.index}", -lk.J * eps, "inertia"))
    if loads_section is None:
        return out
    specs = list(getattr(loads_section, "forces", []) or [])
    need_stroke = any(_stroke_dependent(sp) for sp in specs)
    if need_stroke and positions is None:
        raise StageError("loads", "loads given over a stroke need the positions (extreme positions)")
    no_stroke = (np.ones(n, bool), np.zeros(n))
    phi0 = float(getattr(positions, "phi0", 0.0)) if positions is not None else 0.0
    sign = _drive_sign(positions, kin) if positions is not None else (1.0 if w[0] >= 0 else -1.0)
    cycle = _cycle(loads_section, positions, cycle)
    for k, sp in enumerate(specs, start=1):
        try:
            lk = mech.link(sp.on)
        except KeyError:
            names = ", ".join(l.name for l in mech.links)
            raise _field_error(f"loads.forces[{k - 1}].on", f"no link named '{sp.on}' (links: {names})") from None
        stroke_given = "stroke" in sp.model_fields_set
        if need_stroke and _stroke_dependent(sp):
            working, s_rel = stroke_states(load_stroke(positions, lk, sp, k - 1), phi, kin)
        else:
            working, s_rel = no_stroke
        if sp.kind is None and not stroke_given:
            active = np.ones(n, bool)
        elif sp.stroke == "both":
            active = np.ones(n, bool)
        elif sp.stroke == "working":
            active = working.copy()
        else:
            active = ~working
        scale = sp.area if sp.area is not None else 1.0
        if sp.moment is not None:
            M = np.full(n, float(sp.moment))
            if sp.kind is not None:
                a1 = _get(kin.a1, lk)
                a2 = _get(kin.a2, lk)
                sg = _motion_sign(a1, a2, w, 1.0)
                M = abs(float(sp.moment)) * sg * (1.0 if sp.kind == "driving" else -1.0)
            M = np.where(active, M, 0.0)
            name = f"M{k}"
            out.couples.append(AppliedCouple(lk.index, name, M, sp.kind or "load"))
            out.info.append({"name": name, "link": lk.name, "type": "moment", "kind": sp.kind or "load",
                             "stroke": sp.stroke if (sp.kind or stroke_given) else "cycle",
                             "active": active, "value": M, "x": None, "abscissa": None,
                             "curve": {"x": [0.0, 1.0], "value": [float(sp.moment)] * 2}})
            continue
        # point of application
        at = sp.at if sp.at is not None else (f"S{lk.index}" if f"S{lk.index}" in kin.pos else lk.com)
        if isinstance(at, str) and at not in kin.pos and at not in lk.local:
            raise _field_error(f"loads.forces[{k - 1}].at", f"'{at}' is not a point of link '{lk.name}' "
                               f"(its points: {', '.join(lk.local)})")
        p, d1, d2 = point_motion(kin, lk, at)
        # line of action
        if sp.direction is not None:
            ang = math.radians(float(sp.direction))
            ev = np.tile([math.cos(ang), math.sin(ang)], (n, 1))
        elif lk.kind == "slider":
            th = _get(kin.angle, lk)
            ev = np.stack([np.cos(th), np.sin(th)], axis=-1)
        elif sp.kind is not None and not (sp.diagram is not None and sp.diagram.phi is not None):
            vv = d1 * np.sign(w)[:, None]
            nv = np.linalg.norm(vv, axis=1)
            rest = nv <= 1e-9 * Lc
            vv[rest] = d2[rest]
            nv = np.linalg.norm(vv, axis=1)
            if np.any(nv == 0):
                raise StageError("loads", f"the point of load {k} on '{lk.name}' does not move: give `direction`")
            ev = vv / nv[:, None]
        else:
            raise _field_error(f"loads.forces[{k - 1}]", f"a force on the bar '{lk.name}' needs `direction` (deg)")
        # magnitude (signed along e)
        x = None
        if sp.diagram is not None and sp.diagram.phi is not None:
            rel = cycle_angle(phi, phi0, sign, cycle)
            val = interp_right(rel, sp.diagram.phi, sp.diagram.value) * scale
            x = rel
            mag = val
            active = np.ones(n, bool)
            stroke_label = "cycle"
        else:
            if sp.diagram is not None:
                val = interp_right(s_rel, sp.diagram.s, sp.diagram.value) * scale
                x = s_rel
            else:
                val = np.full(n, float(sp.magnitude) * scale)
            if sp.kind is None:
                mag = val
            else:
                sg = _motion_sign(np.einsum("ij,ij->i", d1, ev), np.einsum("ij,ij->i", d2, ev), w, Lc)
                if lk.kind != "slider" and sp.direction is None:
                    sg = np.ones(n)       # e is along the velocity already
                mag = np.abs(val) * sg * (1.0 if sp.kind == "driving" else -1.0)
            stroke_label = sp.stroke if (sp.kind or stroke_given) else "cycle"
        mag = np.where(active, mag, 0.0)
        F = ev * mag[:, None]
        name = f"F{k}"
        if isinstance(at, str):
            local = lk.local.get(at, lk.com if at == f"S{lk.index}" else None)
        else:
            local = (float(at[0]), float(at[1]))
        out.forces.append(AppliedForce(lk.index, name, p, F, sp.kind or "load", local,
                                       at if isinstance(at, str) else None))
        out.info.append({"name": name, "link": lk.name, "type": "force", "kind": sp.kind or "load",
                         "stroke": stroke_label, "active": active,
                         "abscissa": "phi" if (sp.diagram is not None and sp.diagram.phi is not None) else "s",
                         "x": x if x is not None else s_rel, "value": mag,
                         "diagram_value": np.where(active, val, 0.0), "curve": _curve(sp, scale)})
    return out


def _curve(sp, scale: float) -> dict:
    """The load's diagram as given (abscissa s/H or phi from position 0), in N."""
    if sp.diagram is not None:
        xs = sp.diagram.phi if sp.diagram.phi is not None else sp.diagram.s
        return {"x": [float(v) for v in xs], "value": [float(v) * scale for v in sp.diagram.value]}
    return {"x": [0.0, 1.0], "value": [float(sp.magnitude) * scale] * 2}


# ------------------------------------------------------------------ switch angles
def switch_angles(mech, loads_section, positions, kinks: bool = False) -> list[float]:
    """Crank angles in [0, 360) where a task load switches: where it jumps inside a stroke
    (a repeated abscissa of an s- or phi-diagram), found to 1e-9 deg, and the extreme
    positions of every slider other than the output that carries a stroke-dependent load
    (where its own strokes begin and end, docs/methods.md §3.3); with kinks=True also
    where a diagram's slope changes (every inner abscissa: the breakpoints of a piecewise
    quadrature)."""
    if loads_section is None:
        return []
    out: list[float] = []
    phi0 = float(getattr(positions, "phi0", 0.0))
    sign = _drive_sign(positions)
    cycle = _cycle(loads_section, positions, None)
    output_ext = [float(a) for a in (getattr(positions, "extreme", None) or [])]
    groups: list[tuple] = []       # (stroke, start, sign, lo, hi, targets) of the s-diagram jumps
    for k, sp in enumerate(getattr(loads_section, "forces", []) or []):
        src = positions
        if _stroke_dependent(sp) and mech is not None:
            try:
                lk = mech.link(sp.on)
            except KeyError:
                lk = None
            if lk is not None:
                src = load_stroke(positions, lk, sp, k)
        ext = getattr(src, "extreme", None)
        start = float(ext[0]) if ext else phi0          # the working stroke begins here
        wa = getattr(src, "working_stroke_angle", None)
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
    # every stroke's roots at once: one kinematics call per scan for all of them
    for (_, start, sign_g, *_r), roots in zip(groups, _stroke_roots_many(groups, _s_many(mech))):
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
        from .kinematics.solver import solve
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

    ts = [np.linspace(groups[k][3], groups[k][4], n)[None, :].repeat(tgs[k].size, 0) for k in live]
    svs = scan(ts)
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


__all__ = ["AppliedForce", "AppliedCouple", "Loads", "evaluate", "switch_angles", "point_motion",
           "interp_right", "stroke_states", "G"]


def _field_error(field: str, message: str) -> TaskError:
    """A TaskError naming its field; the pipeline adds the file and line (Task.locate)."""
    return TaskError(message, issues=[(field, None, None, message)])
