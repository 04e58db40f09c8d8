"""The loads at given positions: gravity, inertia (d'Alembert) and the task's forces and
couples (the package docstring)."""
from __future__ import annotations

import math

import numpy as np

from ...errors import StageError
from ...messages import Message
from .diagrams import cycle_angle, diagram_curve, interp_right
from .model import G, AppliedCouple, AppliedForce, Loads
from .strokes import load_stroke, stroke_dependent, stroke_states


# ------------------------------------------------------------------ kinematics access
def _rot90(r: np.ndarray) -> np.ndarray:
    return np.stack([-r[..., 1], r[..., 0]], axis=-1)


def point_motion(kin, lk, at) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The motion of a point fixed on a link.

    Parameters
    ----------
    kin : KinematicsResult
        The kinematics at N crank angles.
    lk : Link
        The link.
    at : str or sequence of float
        A point's name (from the kinematics) or local [u, v] in m (rigid-body formulas).

    Returns
    -------
    tuple of numpy.ndarray
        The position (m), dr/dphi (m/rad) and d2r/dphi2 (m/rad^2), (N, 2) each.
    """
    if isinstance(at, str):
        if at in kin.pos:
            return (np.asarray(kin.pos[at], float), np.asarray(kin.d1[at], float),
                    np.asarray(kin.d2[at], float))
        if at not in lk.local:
            raise KeyError(f"no point '{at}' on link '{lk.name}'")
        at = lk.local[at]
    u, v = float(at[0]), float(at[1])
    o = lk.origin
    th = np.asarray(kin.angle[lk.name], float)
    a1 = np.asarray(kin.a1[lk.name], float)
    a2 = np.asarray(kin.a2[lk.name], float)
    c, s = np.cos(th), np.sin(th)
    r = np.stack([c * u - s * v, s * u + c * v], axis=-1)
    jr = _rot90(r)
    p0 = np.asarray(kin.pos[o], float)
    d10 = np.asarray(kin.d1[o], float)
    d20 = np.asarray(kin.d2[o], float)
    return p0 + r, d10 + a1[:, None] * jr, d20 + a2[:, None] * jr - (a1 ** 2)[:, None] * r


def _w(kin, n: int) -> tuple[np.ndarray, np.ndarray]:
    w = np.broadcast_to(np.asarray(kin.omega1, float), (n,)).astype(float)
    e = np.broadcast_to(np.asarray(kin.eps1, float), (n,)).astype(float)
    return w, e


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


def evaluate(linkage, kin, *, inertia: bool = True) -> Loads:
    """The loads on the links at the crank angles of ``kin`` (the module docstring).

    Parameters
    ----------
    linkage : Linkage
        The mechanism, its ``loads`` section (None: gravity and inertia only), the
        positions (position 0, the strokes) and the drive (sense of rotation, cycle).
    kin : KinematicsResult
        The kinematics at the crank angles (deg) where the loads are wanted.
    inertia : bool
        Add the inertia loads F_in = -m a_S (N), M_in = -J_S eps (N*m).

    Returns
    -------
    Loads
        Per position: forces (N) at their points (m), couples (N*m, ccw positive), and the
        diagram value of every task load (``info``).

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*, kinetostatics: d'Alembert's inertia
    forces; Popov, the force of production resistance over the working stroke given by
    its diagram; docs/methods.md §3.1.
    """
    return evaluate_on(linkage.mechanism, linkage.loads, kin, linkage.positions, sign=linkage.drive.sign,
                       cycle=linkage.drive.cycle, inertia=inertia)


def link_loads(mech, kin, *, gravity: bool, inertia: bool) -> Loads:
    """Gravity and the inertia loads of every link.

    Parameters
    ----------
    mech : Mechanism
        The mechanism (masses in kg, moments of inertia in kg*m^2).
    kin : KinematicsResult
        The kinematics (accelerations at the crank's omega1, eps1).
    gravity : bool
        True: G_i = m_i g at S_i, N.
    inertia : bool
        True: F_in = -m_i a_Si (N) and M_in = -J_Si eps_i (N*m).

    Returns
    -------
    Loads
        The forces and couples at the crank angles of ``kin``.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: the inertia forces and couples of the
    links (d'Alembert's principle); docs/methods.md §3.
    """
    phi = np.atleast_1d(np.asarray(kin.phi, float))
    n = len(phi)
    w, e = _w(kin, n)
    out = Loads(phi=phi)
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
            eps = np.asarray(kin.a2[lk.name], float) * w ** 2 + np.asarray(kin.a1[lk.name], float) * e
            out.couples.append(AppliedCouple(lk.index, f"Mi{lk.index}", -lk.J * eps, "inertia"))
    return out


def evaluate_on(mech, loads_section, kin, positions, *, sign: float, cycle: float,
                inertia: bool = True) -> Loads:
    """The task's loads at the positions of given kinematics.

    Parameters
    ----------
    mech : Mechanism
        The mechanism.
    loads_section : LoadsSection
        The task's ``loads`` section.
    kin : KinematicsResult
        The kinematics.
    positions : PositionsResult or None
        The positions (or a stand-in with ``phi0`` and ``stroke_state``; None when no load
        depends on a stroke).
    sign : float
        +1 for a ccw crank, -1 for cw.
    cycle : float
        360 or 720 deg: how phi-diagrams are read.
    inertia : bool
        True: the links' inertia loads too.

    Returns
    -------
    Loads
        The forces (N) and couples (N*m) at the crank angles of ``kin``.
    """
    out = link_loads(mech, kin, gravity=loads_section is not None and loads_section.gravity, inertia=inertia)
    phi = out.phi
    n = len(phi)
    w, e = _w(kin, n)
    Lc = _length_scale(mech)
    if loads_section is None:
        return out
    specs = list(loads_section.forces)
    need_stroke = any(stroke_dependent(sp) for sp in specs)
    if need_stroke and positions is None:
        raise StageError("loads", Message("loads.fail.no_positions"))
    no_stroke = (np.ones(n, bool), np.zeros(n))
    phi0 = float(positions.phi0) if positions is not None else 0.0
    cycle = float(cycle)
    for k, sp in enumerate(specs, start=1):
        lk = mech.link(sp.on)       # links, points and directions of the loads: checked by build_mechanism
        stroke_given = "stroke" in sp.model_fields_set
        if need_stroke and stroke_dependent(sp):
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
                a1 = np.asarray(kin.a1[lk.name], float)
                a2 = np.asarray(kin.a2[lk.name], float)
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
        p, d1, d2 = point_motion(kin, lk, at)
        # line of action
        if sp.direction is not None:
            ang = math.radians(float(sp.direction))
            ev = np.tile([math.cos(ang), math.sin(ang)], (n, 1))
        elif lk.kind == "slider":
            th = np.asarray(kin.angle[lk.name], float)
            ev = np.stack([np.cos(th), np.sin(th)], axis=-1)
        else:       # a resistance/driving force over a stroke on a bar: along the velocity
            vv = d1 * np.sign(w)[:, None]
            nv = np.linalg.norm(vv, axis=1)
            rest = nv <= 1e-9 * Lc
            vv[rest] = d2[rest]
            nv = np.linalg.norm(vv, axis=1)
            if np.any(nv == 0):
                raise StageError("loads", Message("loads.fail.point_still", k=k, link=lk.name))
            ev = vv / nv[:, None]
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
                         "diagram_value": np.where(active, val, 0.0), "curve": diagram_curve(sp, scale)})
    return out
