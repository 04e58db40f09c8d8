"""Kinematics on a fine grid of crank angles for the explorable HTML report.

``explore_grid(linkage, step=1.0)`` solves the linkage (its context,
:class:`tmm_cli.linkage.context.Linkage`) at every ``step`` degrees of one crank turn,
counted from position 0 in the sense of rotation, with the linkage's crank speed, and returns compact
data: positions, velocities and accelerations of every point, omega and epsilon of
every link, the instant centres of every pair of links, rounded to 7 significant digits (the table shows 4: one
rounding of 7 digits changes a shown 4-digit value only when it ends in 5 within 5e-7) (None where a value has no finite limit,
next to a change point).  The report draws the mechanism and its plans from it."""
from __future__ import annotations

import numpy as np

from ...tables import round_sig

__all__ = ["explore_grid", "round_sig"]


def explore_grid(linkage, step: float = 1.0) -> dict:
    """Dense kinematics of the linkage (see module doc).

    Parameters
    ----------
    linkage : tmm_cli.linkage.context.Linkage
        The mechanism, its drive (omega in rad/s, signed; the sense of rotation) and
        its positions (position 0 at ``positions.phi0``, deg).
    step : float
        Grid step, deg (at least 12 angles a turn; over a crank range, ``positions.over``
        'input_range', at least 12 angles from its start to its end, both included).

    Returns
    -------
    dict
        ``turn`` (deg from position 0), ``phi`` (crank angle, deg), ``points``
        (x, y m; vx, vy m/s; ax, ay m/s² of every point), ``links`` (omega rad/s,
        epsilon rad/s²), ``centres`` (the instant centre of each pair of links "i-j", 0 the
        frame, as the results' ``kinematics[k].instant_centres``: x, y m, None at infinity;
        ``{"pin": name}`` for two links joined by a pin, the point's coordinates),
        ``shapes`` (what to draw), 7 significant digits.
    """
    from .solver import solve
    mech = linkage.mechanism
    omega1 = float(linkage.drive.omega)
    sign = float(linkage.drive.sign)
    phi0 = float(linkage.positions.phi0)
    span = linkage.positions.span
    if span is None:
        n = max(int(round(360.0 / step)), 12)
        dstep = 360.0 / n
    else:               # over a crank range (positions.over 'input_range'): from its start to its end
        sign = 1.0 if span >= 0 else -1.0
        n = max(int(round(abs(span) / step)) + 1, 12)
        dstep = abs(span) / (n - 1)
    turn = np.arange(n) * dstep
    phi = np.mod(phi0 + sign * turn, 360.0)
    kin = solve(mech, phi, omega1)
    und = kin.undefined

    def masked(arr, key):
        m = und.get(key)
        a = np.array(arr, float)
        if m is not None:
            a[np.asarray(m, bool)] = np.nan
        return a

    points = {}
    for p in kin.points:
        xy = np.asarray(kin.pos[p], float)
        v = masked(kin.vel(p), f"v:{p}")
        a = masked(kin.acc(p), f"a:{p}")
        points[p] = {"x": round_sig(xy[:, 0]), "y": round_sig(xy[:, 1]),
                     "vx": round_sig(v[:, 0]), "vy": round_sig(v[:, 1]),
                     "ax": round_sig(a[:, 0]), "ay": round_sig(a[:, 1])}
    # the instant centres of every pair of links (i-j, 0 the frame): those results carry
    from .entries import centre_columns, pairs
    w = kin._w()
    wc = w if w.ndim == 0 else w[:, None]
    centres = {}
    for (i, j), (x, y, null) in zip(pairs(len(kin.links)), centre_columns(kin, slice(None), wc)):
        key = f"{i}-{j}"
        if kin.pins.get(key):                # joined by a pin: the pin (a point drawn anyway)
            centres[key] = {"pin": kin.pins[key]}
            continue
        x, y = np.array(x, float), np.array(y, float)
        x[null], y[null] = np.nan, np.nan
        centres[key] = {"x": round_sig(x), "y": round_sig(y)}
    links = {}
    for name in kin.links:
        w = masked(np.broadcast_to(kin.omega(name), phi.shape), f"omega:{name}")
        e = masked(np.broadcast_to(kin.epsilon(name), phi.shape), f"epsilon:{name}")
        links[name] = {"omega": round_sig(w), "epsilon": round_sig(e)}
    # what to draw: each link as the polygon of its named points, sliders as blocks
    shapes = []
    for link in mech.links:
        names = [q for q in link.local if q in points and not q.startswith("S")]
        shapes.append({"link": link.name, "kind": link.kind, "points": names,
                       "origin": link.origin if link.kind == "slider" else None})
    marks = []
    pos = linkage.positions
    for k, ph, kind in zip(pos.index, pos.phi, pos.kinds):
        if kind != "grid":
            continue
        marks.append({"index": int(k), "turn": float(np.mod(sign * (float(ph) - phi0), 360.0))})
    return {"step": dstep, "phi0": phi0, "sign": sign, "turn": round_sig(turn),
            "phi": round_sig(phi), "points": points, "links": links, "centres": centres, "shapes": shapes,
            "ground": sorted(mech.ground), "positions": marks}
