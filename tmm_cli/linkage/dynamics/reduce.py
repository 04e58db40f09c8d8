"""Reduced (to the crank) moment of forces and moment of inertia, docs/methods.md §4.

With the analogues (kinematic transfer functions) ``d1_P = dr_P/dphi`` and
``a1_i = dtheta_i/dphi`` (phi = crank angle, ccw, rad):

    M_red = sum(F_k . d1_Pk + M_k a1_k)            (per unit crank rotation)
    J_red = sum(m_i |d1_Si|^2 + J_Si a1_i^2)
    dJ_red/dphi = sum(2 m_i d1_Si . d2_Si + 2 J_Si a1_i a2_i)

The flywheel works with the rotation ``q`` in the direction of motion: for a
clockwise drive ``dq = -dphi``, so moments and dJ/dq change sign, J_red does not.
The functions on plain arrays (``reduced_inertia``, ``reduced_moment``) carry the
formulas; ``from_kinematics`` / ``moment_from_loads`` adapt the KinematicsResult and
Loads of the other stages to them.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ...errors import StageError
from ...messages import Message

STAGE = "dynamics"


def _perp(v: np.ndarray) -> np.ndarray:
    """k x v for v (N, 2): rotate by +90 deg."""
    return np.stack([-v[..., 1], v[..., 0]], axis=-1)


@dataclass
class ReducedInertia:
    """The reduced moment of inertia over the cycle: per link, the total, and their derivatives."""

    links: dict[str, np.ndarray]          # per link J_red,i(phi)
    dlinks: dict[str, np.ndarray | None]  # per link dJ_red,i/dphi (None: analogues d2/a2 absent)
    total: np.ndarray                     # sum over links (without extra constant inertia)
    dtotal: np.ndarray | None


def reduced_inertia(masses: dict[str, tuple[float, float]],
                    d1_S: dict[str, np.ndarray], a1: dict[str, np.ndarray],
                    d2_S: dict[str, np.ndarray] | None = None,
                    a2: dict[str, np.ndarray] | None = None) -> ReducedInertia:
    """The reduced moment of inertia per link and in total.

    Parameters
    ----------
    masses : dict
        link -> (m, kg; J_S, kg*m^2).  A link without mass and J is skipped.
    d1_S : dict
        link -> (N, 2) first analogues of the velocity of its centre of mass, m/rad.
    a1 : dict
        link -> (N,) first analogues of its angular velocity.
    d2_S, a2 : dict or None
        The second analogues (m/rad^2, 1/rad) for the derivative dJ/dphi (None: not computed).

    Returns
    -------
    ReducedInertia
        J_red,i = m_i |d1_S|^2 + J_S,i a1^2 per link and the total, kg*m^2, with their
        derivatives.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: the reduced moment of inertia by the
    equality of kinetic energies; docs/methods.md §4.
    """
    links: dict[str, np.ndarray] = {}
    dlinks: dict[str, np.ndarray | None] = {}
    n = None
    for name, (m, J) in masses.items():
        m, J = float(m), float(J)
        if m == 0 and J == 0:
            continue
        v = np.asarray(d1_S[name], float)
        w = np.asarray(a1[name], float)
        n = w.shape[0]
        links[name] = m * np.einsum("ij,ij->i", v, v) + J * w * w
        if d2_S is not None and a2 is not None and name in d2_S and name in a2:
            acc = np.asarray(d2_S[name], float)
            e = np.asarray(a2[name], float)
            dlinks[name] = 2 * m * np.einsum("ij,ij->i", v, acc) + 2 * J * w * e
        else:
            dlinks[name] = None
    if n is None:
        any_arr = next(iter(a1.values()), None)
        n = 0 if any_arr is None else np.asarray(any_arr).shape[0]
    total = np.zeros(n)
    for arr in links.values():
        total = total + arr
    if all(d is not None for d in dlinks.values()):
        dtotal = np.zeros(n)
        for d in dlinks.values():
            dtotal = dtotal + d
    else:
        dtotal = None
    return ReducedInertia(links=links, dlinks=dlinks, total=total, dtotal=dtotal)


def reduced_moment(forces, couples) -> dict[str, np.ndarray]:
    """The reduced moment per load kind.

    Parameters
    ----------
    forces : iterable
        (kind, F (N, 2) in N, d1 of the application point (N, 2) in m/rad).
    couples : iterable
        (kind, M (N,) in N*m, a1 of the link (N,)).

    Returns
    -------
    dict
        kind -> M_red (N,), N*m per unit ccw crank rotation (only the kinds present).

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: the reduced moment by the equality of
    powers; docs/methods.md §4.
    """
    out: dict[str, np.ndarray] = {}
    for kind, F, d1 in forces:
        val = np.einsum("ij,ij->i", np.asarray(F, float), np.asarray(d1, float))
        out[kind] = out.get(kind, 0.0) + val
    for kind, M, a1 in couples:
        val = np.asarray(M, float) * np.asarray(a1, float)
        out[kind] = out.get(kind, 0.0) + val
    return out


# ------------------------------------------------------------------ adapters
def inertia_from_kinematics(mech, kin) -> ReducedInertia:
    """The reduced inertia of a mechanism's links.

    Parameters
    ----------
    mech : Mechanism
        The mechanism (its links' masses, kg, and moments of inertia, kg*m^2).
    kin : KinematicsResult
        Its kinematics (the analogues).

    Returns
    -------
    ReducedInertia
        Per link and in total, kg*m^2 (:func:`reduced_inertia`).
    """
    masses, d1S, a1, d2S, a2 = {}, {}, {}, {}, {}
    for lk in mech.links:
        if lk.mass == 0 and lk.J == 0:
            continue
        s = f"S{lk.index}"
        masses[lk.name] = (lk.mass, lk.J)
        d1S[lk.name] = kin.d1[s]
        a1[lk.name] = kin.a1[lk.name]
        if s in kin.d2 and lk.name in kin.a2:
            d2S[lk.name] = kin.d2[s]
            a2[lk.name] = kin.a2[lk.name]
    return reduced_inertia(masses, d1S, a1, d2S, a2)


def point_analogue(mech, kin, link_index: int, point: np.ndarray) -> np.ndarray:
    """The first analogue of the velocity of a point moving with a link.

    Parameters
    ----------
    mech : Mechanism
        The mechanism.
    kin : KinematicsResult
        Its kinematics.
    link_index : int
        The link (1..n).
    point : numpy.ndarray
        The point's positions (N, 2), m.

    Returns
    -------
    numpy.ndarray
        d1 = d1_O + a1 k x (P - O), (N, 2), m/rad.
    """
    if link_index == 0:
        return np.zeros_like(np.asarray(point, float))
    lk = mech.link(link_index)
    o = lk.origin
    P = np.asarray(point, float)
    return np.asarray(kin.d1[o], float) + np.asarray(kin.a1[lk.name], float)[:, None] * \
        _perp(P - np.asarray(kin.pos[o], float))


def moment_from_loads(mech, kin, loads) -> dict[str, np.ndarray]:
    """The reduced moment per load kind of the external loads.

    Parameters
    ----------
    mech : Mechanism
        The mechanism.
    kin : KinematicsResult
        Its kinematics.
    loads : Loads
        The loads (inertia loads skipped).

    Returns
    -------
    dict
        kind -> M_red, N*m per unit ccw crank rotation.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: the reduced moment by the equality of
    powers; docs/methods.md §4.
    """
    forces, couples = [], []
    for f in loads.forces:
        if f.kind == "inertia" or f.link == 0:
            continue
        forces.append((f.kind, f.F, point_analogue(mech, kin, f.link, f.point)))
    for c in loads.couples:
        if c.kind == "inertia" or c.link == 0:
            continue
        couples.append((c.kind, c.M, kin.a1[mech.link(c.link).name]))
    out = reduced_moment(forces, couples)
    n = len(np.atleast_1d(kin.phi))
    for k in list(out):
        out[k] = np.broadcast_to(np.asarray(out[k], float), (n,)).copy()
        if not np.all(np.isfinite(out[k])):
            raise StageError(STAGE, Message("flywheel.fail.kind_not_finite", kind=str(k)))
    return out


@dataclass
class Sample:
    """Reduced quantities at a set of crank angles, along the motion (q)."""
    M_by_kind: dict[str, np.ndarray]     # along the motion
    M_given: np.ndarray
    J_links: dict[str, np.ndarray]
    dJ_links: dict[str, np.ndarray | None] = field(default_factory=dict)   # d/dq
    J_links_total: np.ndarray | None = None
    dJ_total: np.ndarray | None = None   # d/dq of the links' sum (None: not available)


def sample(mech, kin, loads, sign: float) -> Sample:
    """The reduced moment and inertia along the motion.

    Parameters
    ----------
    mech : Mechanism
        The mechanism.
    kin : KinematicsResult
        Its kinematics at the sample's crank angles.
    loads : Loads
        The external loads there.
    sign : float
        +1 for a ccw drive, -1 for cw.

    Returns
    -------
    Sample
        The reduced moment by kind (N*m) and the reduced inertia by link (kg*m^2), with its
        derivative, along the motion.
    """
    inert = inertia_from_kinematics(mech, kin)
    mk = {k: sign * v for k, v in moment_from_loads(mech, kin, loads).items()}
    n = len(np.atleast_1d(kin.phi))
    M_given = np.zeros(n)
    for v in mk.values():
        M_given = M_given + v
    dJ = {k: (None if v is None else sign * v) for k, v in inert.dlinks.items()}
    tot = inert.total if inert.total.shape == (n,) else np.zeros(n)
    dtot = None if inert.dtotal is None else sign * inert.dtotal
    if dtot is not None and dtot.shape != (n,):
        dtot = np.zeros(n)
    return Sample(M_by_kind=mk, M_given=M_given, J_links=inert.links, dJ_links=dJ,
                  J_links_total=tot, dJ_total=dtot)
