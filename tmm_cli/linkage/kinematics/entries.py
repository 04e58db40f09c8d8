"""The ``kinematics`` entries of results.json (one dict per position), made from a
:class:`~tmm_cli.linkage.kinematics.result.KinematicsResult`'s arrays when read
(:func:`tmm_cli.entrytable.tabled`: two levels, each at the size it runs fastest at):

* the numbers, vectorised over ``TABLE_ROWS`` positions at a time (:func:`_table`): one
  float array of every value of the entries (a row per value: phi, then each point's
  ``PKEYS``, then each link's ``LKEYS``), clean: -0.0 made 0.0, a value that is not
  finite 0.0, NaN (None in the entry) where the value has no finite limit (``undefined``
  at a position near a change point);
* the entries, ``ENTRY_BLOCK`` positions at a time (:func:`_assemble`): one ``tolist``
  of the block's columns, then the dicts zipped from them (dict displays,
  :func:`tmm_cli.entrytable.dicts`), made and freed in the CPU's cache; then the flags
  ``"singular": true`` and ``"near_singular": true`` of the few positions that have them.

Every value depends on its own position only: the entries do not depend on the blocks.
"""
from __future__ import annotations

from bisect import bisect_left

import numpy as np

from ...entrytable import clean, dicts, nan_rows, tabled, values
from ...results import LazyEntries

TABLE_ROWS = 4096      # positions whose values are computed at a time (numpy)
ENTRY_BLOCK = 64       # entries made at a time (dicts and floats)

PKEYS = ("x", "y", "vx", "vy", "v", "ax", "ay", "a", "vqx", "vqy", "vq", "aqx", "aqy", "aq")
LKEYS = ("angle", "omega", "epsilon", "i", "iq2")
# the values nulled where ``undefined['v:P']`` (a point's), ... (a link's) holds
NULLED = {"v": ("vx", "vy", "v", "vqx", "vqy", "vq"), "a": ("ax", "ay", "a", "aqx", "aqy", "aq"),
          "omega": ("omega", "i"), "epsilon": ("epsilon", "iq2")}


def angle_deg(rad) -> np.ndarray:
    """Angle in degrees in [0, 360)."""
    return deg360(np.degrees(np.asarray(rad, float)))


def deg360(deg) -> np.ndarray:
    """An angle in degrees taken into [0, 360) (a hair below 360: 0)."""
    d = np.mod(np.asarray(deg, float), 360.0)
    return np.where(d >= 360.0 - 1e-11, 0.0, d)


def lazy_entries(kin, index: list[int]) -> LazyEntries:
    """The ``kinematics`` entries of a result, computed when first read.

    Parameters
    ----------
    kin : KinematicsResult
        The kinematics.
    index : list of int
        The N position numbers.

    Returns
    -------
    LazyEntries
        The values of ``TABLE_ROWS`` positions computed when first read (the last two such
        tables kept), the entries made from them ``ENTRY_BLOCK`` at a time.
    """
    lay = (tuple(kin.points), tuple(kin.links))
    return tabled(len(index), lambda sl: _table(kin, sl, index), lambda tab, a, b: _assemble(lay, tab, a, b),
                  TABLE_ROWS, ENTRY_BLOCK)


def _table(kin, sl: slice, index: list[int]) -> tuple:
    """The values of the entries of the rows ``sl``: (values (1 + 14 points + 5 links, k),
    the running count of the rows holding a NaN (k + 1 ints), the rows' position numbers,
    the rows (in ``sl``) flagged singular, those flagged near a change point)."""
    idx = index[sl]
    k = len(idx)
    F = np.empty((1 + len(PKEYS) * len(kin.points) + len(LKEYS) * len(kin.links) + 2 * len(pairs(len(kin.links))),
                  k))
    F[0] = deg360(kin.phi[sl])            # the crank angles as given (through radians, 30 read 29.999999999999996)
    w, e = kin._w(), kin._e()
    w = w if w.ndim == 0 or w.shape[0] == 1 else w[sl]
    e = e if e.ndim == 0 or e.shape[0] == 1 else e[sl]
    wc = w if w.ndim == 0 else w[:, None]
    w2 = w ** 2 if w.ndim == 0 else (w ** 2)[:, None]
    ec = e if e.ndim == 0 else e[:, None]
    row: dict[str, int] = {}                 # first row of each point's ("P:name") and link's values
    r = 1
    for p in kin.points:
        q, d2 = kin.d1[p][sl], kin.d2[p][sl]
        v, a = q * wc, d2 * w2 + q * ec          # vel(p), acc(p) at the rows
        x = kin.pos[p][sl]
        row["P:" + p] = r
        for c in (x[:, 0], x[:, 1], v[:, 0], v[:, 1], np.hypot(v[:, 0], v[:, 1]),
                  a[:, 0], a[:, 1], np.hypot(a[:, 0], a[:, 1]), q[:, 0], q[:, 1], np.hypot(q[:, 0], q[:, 1]),
                  d2[:, 0], d2[:, 1], np.hypot(d2[:, 0], d2[:, 1])):
            F[r] = c
            r += 1
    for lk in kin.links:
        a1, a2 = kin.a1[lk][sl], kin.a2[lk][sl]
        row["L:" + lk] = r
        for c in (angle_deg(kin.angle[lk][sl]), a1 * w, a2 * w ** 2 + a1 * e, a1, a2):
            F[r] = c
            r += 1
    row["IC"] = r
    nulls = []
    for x, y, null in centre_columns(kin, sl, wc):
        F[r], F[r + 1] = x, y
        nulls.append(null)
        r += 2
    clean(F, 0.0)
    near = np.zeros(k, bool) if kin.near is None else np.asarray(kin.near[sl], bool)
    for j, null in enumerate(nulls):
        F[row["IC"] + 2 * j:row["IC"] + 2 * j + 2, null] = np.nan
    if near.any():                           # no finite limit there: None
        for key, mask in kin.undefined.items():
            what, name = key.split(":", 1)
            r0 = row.get(("P:" if what in ("v", "a") else "L:") + name)
            if r0 is None:
                continue
            keys = PKEYS if what in ("v", "a") else LKEYS
            rows = [r0 + keys.index(f) for f in NULLED[what]]
            F[np.ix_(rows, np.flatnonzero(near & np.asarray(mask, bool)[sl]))] = np.nan
    sing = [] if kin.singular is None else np.flatnonzero(kin.singular[sl]).tolist()
    return F, nan_rows(F), idx, sing, np.flatnonzero(near).tolist()


def pairs(n: int) -> list[tuple[int, int]]:
    """Every pair of links.

    Parameters
    ----------
    n : int
        The number of moving links.

    Returns
    -------
    list of tuple of int
        (i, j), i < j, of the frame 0 and the links 1..n.
    """
    return [(i, j) for i in range(n + 1) for j in range(i + 1, n + 1)]


def instant_centres(kin, sl: slice, wc) -> list[tuple[np.ndarray, np.ndarray, np.ndarray, bool]]:
    """The instant centres of every pair of links.

    Parameters
    ----------
    kin : KinematicsResult
        The kinematics.
    sl : slice
        The rows.
    wc : dict
        The links' angular velocities and centres of mass' velocities at the rows.

    Returns
    -------
    list of tuple
        Per pair (the frame 0, the links 1..n in the task's order): (x, y in m, at infinity,
        a pin).

    Notes
    -----
    Link i moves as v_i(P) = v_Si + w_i k x (P - S_i); the relative velocity of i and j at P
    is c + (w_i - w_j) k x P with c = (v_Si - w_i k x S_i) - (v_Sj - w_j k x S_j), zero at
    P = (-c_y, c_x)/(w_i - w_j).  Where w_i = w_j the relative motion is a translation: the
    centre lies at infinity (null).  Where the two links move alike (c = 0 as well: at an
    extreme position the rocker, its rod and the slider beyond it are all at rest) the
    velocities do not fix the centre; it is their limit as the crank turns on, by l'Hopital's
    rule P = (-c'_y, c'_x)/(w_i' - w_j') with the derivatives by the crank angle of the
    velocity analogues (c'_i = q''_Si - w_i' k x S_i - w_i k x q'_Si), which is Kennedy's
    construction there (null only where that limit is a translation too).  Two links joined
    directly have their pin as the centre (a slide: at infinity).  Kennedy's theorem (the
    three centres of three links on one line) holds for these; tests check it.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: instantaneous centres of velocity,
    the Aronhold-Kennedy theorem.
    """
    n = len(kin.links)
    k = len(kin.phi[sl])
    C, W = [np.zeros((k, 2))], [np.zeros(k)]
    for i, lk in enumerate(kin.links, start=1):
        s, q = kin.pos[f"S{i}"][sl], kin.d1[f"S{i}"][sl]
        w = kin.a1[lk][sl] * (wc if np.ndim(wc) == 0 else wc[:, 0])
        v = q * wc
        C.append(v - w[:, None] * _perp(s))
        W.append(w)
    scale = np.maximum(np.max(np.abs(np.stack(W)), axis=0), 1e-300)      # per row: its own position only
    # the size of the velocity fields at each row (the largest c_i): two fields within 1e-8 of it
    # of each other move alike
    c_scale = np.max(np.stack([np.hypot(c[:, 0], c[:, 1]) for c in C]), axis=0)
    limit = None                             # the velocity analogues' derivatives, made where needed
    out = []
    for i, j in pairs(n):
        key = f"{i}-{j}"
        if key in kin.pins:                  # joined directly: the pin, or a slide (at infinity)
            pin = kin.pins[key]
            if pin is None:
                out.append((np.zeros(k), np.zeros(k), np.ones(k, bool), False))
            else:
                x = kin.pos[pin][sl]
                out.append((x[:, 0], x[:, 1], np.zeros(k, bool), True))
            continue
        c, dw = C[i] - C[j], W[i] - W[j]
        at_inf = np.abs(dw) <= 1e-12 * scale
        d = np.where(at_inf, 1.0, dw)
        x, y = -c[:, 1] / d, c[:, 0] / d
        alike = (np.abs(dw) <= 1e-8 * scale) & (np.hypot(c[:, 0], c[:, 1]) <= 1e-8 * c_scale) & (c_scale > 0)
        if alike.any():                      # moving alike: the limit (l'Hopital, the Notes)
            if limit is None:
                limit = _analogue_derivatives(kin, sl)
            c1, dw1 = limit[0][i] - limit[0][j], limit[1][i] - limit[1][j]
            inf1 = np.abs(dw1) <= 1e-12 * limit[2]
            d1 = np.where(inf1, 1.0, dw1)
            x = np.where(alike, -c1[:, 1] / d1, x)
            y = np.where(alike, c1[:, 0] / d1, y)
            at_inf = np.where(alike, inf1, at_inf)
        out.append((x, y, at_inf, False))
    return out


def _perp(s: np.ndarray) -> np.ndarray:
    """k x s of the rows of ``s`` (x, y): (-s_y, s_x)."""
    return np.stack([-s[:, 1], s[:, 0]], axis=1)


def _analogue_derivatives(kin, sl: slice) -> tuple[list[np.ndarray], list[np.ndarray], np.ndarray]:
    """Per link (the frame 0 first) the derivatives by the crank angle of c_i = q'_Si - w'_i k x S_i
    and of w'_i (the velocity analogues of :func:`instant_centres`): c_i' = q''_Si - w''_i k x S_i
    - w'_i k x q'_Si and w''_i, at the rows ``sl``; and per row the largest |w''_i| (at least
    1e-300), the scale a difference of two is compared with."""
    k = len(kin.phi[sl])
    C1, W1 = [np.zeros((k, 2))], [np.zeros(k)]
    for i, lk in enumerate(kin.links, start=1):
        s, q, q2 = kin.pos[f"S{i}"][sl], kin.d1[f"S{i}"][sl], kin.d2[f"S{i}"][sl]
        a1, a2 = kin.a1[lk][sl], kin.a2[lk][sl]
        C1.append(q2 - a2[:, None] * _perp(s) - a1[:, None] * _perp(q))
        W1.append(a2)
    return C1, W1, np.maximum(np.max(np.abs(np.stack(W1)), axis=0), 1e-300)


def centre_columns(kin, sl: slice, wc) -> list[tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """The instant centres as results carry them: per pair (in :func:`pairs`' order) x, y (m)
    and where the entry holds null: at infinity (a relative translation), or found from the
    velocities within a change point's neighbourhood (no finite limit there; a pin is
    still its centre).  The ``kinematics`` entries and the HTML explorer read these.

    Parameters
    ----------
    kin : KinematicsResult
        The kinematics.
    sl : slice
        The rows.
    wc : float or numpy.ndarray
        The crank's angular velocity at the rows (a scalar, or a (k, 1) column).

    Returns
    -------
    list of tuple
        (x, y, null) per pair, each of the rows' length.
    """
    k = len(kin.phi[sl])
    near = np.zeros(k, bool) if kin.near is None else np.asarray(kin.near[sl], bool)
    return [(x, y, at_inf | (near & (not pin))) for x, y, at_inf, pin in instant_centres(kin, sl, wc)]


def _assemble(lay: tuple, tab: tuple, a: int, b: int) -> list[dict]:
    """The entries of the rows a..b-1 of the table ``tab`` (taking its values in order)."""
    points, links = lay
    F, nans, idx, sing, near = tab
    n = b - a
    f = iter(values(F[:, a:b], nans[b] != nans[a])).__next__
    phi = f()
    pts = dicts(points, [dicts(PKEYS, [f() for _ in PKEYS], n) for _ in points], n)
    lks = dicts(links, [dicts(LKEYS, [f() for _ in LKEYS], n) for _ in links], n)
    names = tuple(f"{i}-{j}" for i, j in pairs(len(links)))
    cols = []
    for _ in names:
        xs, ys = f(), f()
        cols.append([None if x is None else [x, y] for x, y in zip(xs, ys)])
    ics = dicts(names, cols, n)
    out = dicts(("index", "phi", "points", "links", "instant_centres"), [idx[a:b], phi, pts, lks, ics], n)
    for flagged, key in ((sing, "singular"), (near, "near_singular")):
        for i in flagged[bisect_left(flagged, a):bisect_left(flagged, b)]:
            out[i - a][key] = True
    return out
