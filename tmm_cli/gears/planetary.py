"""Synthesis of simple planetary gears: tooth numbers for a required ratio i_1H.

Convention: i_1H = omega_1 / omega_H (input: central wheel 1; output: carrier H; the
other central wheel is fixed), signed: positive when 1 and H turn the same way.
Wheels are numbered as in Popov & Timofeev: central wheel 1, satellite 2 (single row)
or the double satellite 2-3 (two rows), fixed central wheel 3 (single row) or 4.
All wheels have the same module, zero shifts, ha* = 1.  Willis' formula for the fixed
wheel: i_1H = 1 - i_1F^(H), i_1F^(H) the ratio with the carrier held.

Schemes (the report draws them)::

  A  single row (James):   1 --ext-- 2 --int-- 3 (fixed ring)
        i_1H = 1 + z3/z1                 coaxial: z1 + 2 z2 = z3
  B  two rows, ext + int:  1 --ext-- 2 ==(2-3 one block)== 3 --int-- 4 (fixed ring)
        i_1H = 1 + z2 z4 / (z1 z3)       coaxial: z1 + z2 = z4 - z3
  C  two rows, ext + ext:  1 --ext-- 2 == 3 --ext-- 4 (fixed sun)
        i_1H = 1 - z2 z4 / (z1 z3)       coaxial: z1 + z2 = z4 + z3
  D  two rows, int + int:  1 (ring) --int-- 2 == 3 --int-- 4 (fixed ring)
        i_1H = 1 - z2 z4 / (z1 z3)       coaxial: z1 - z2 = z4 - z3

Half sections above the axis (### fixed to the frame, [n] a wheel, H the carrier arm
holding the satellite axle ``o``)::

  A   ###[3]###          B   #########[4]#       C   [2]  [3]            D   [1]    ###[4]###
        [2]-o-H                 [2][3]-o-H             o-----o-H                [2][3]-o-H
      ==[1]==                 ==[1]==              ==[1]==  ##[4]##          (1 and 4 rings)
  ----axis----           ----axis----          ----axis---------     ----axis----------

Conditions for every candidate (Popov & Timofeev, "Kursovoe proektirovanie po TMM",
ch. "Sintez planetarnykh mekhanizmov"):
  * ratio:       |i - i_req| <= tolerance |i_req|;
  * coaxiality:  equal centre distances of the two meshes (equations above);
  * assembly with k equally spaced satellites: (i_1H z1 / k)(1 + k p) is an integer for
    some integer p >= 0 (the textbook form; p is reported; for a single row it reduces to
    (z1 + z3)/k integer).  Proof of sufficiency: carrying a satellite by 2 pi (1 + k p)/k
    turns wheel 1 by a whole number of its pitches;
  * adjacency:   (tip circles of neighbouring satellites do not touch)
                 2 a_w sin(pi/k) > d_a(largest satellite rim) = m (z_sat + 2 ha*);
  * no undercut / interference with zero shifts (ha* = 1): an external wheel in external
    mesh z >= z_min = 17; an external wheel in internal mesh z >= 20; an internal wheel
    z >= 85; in every internal mesh z_internal - z_external >= 8.
Candidates are ranked by size (the diameter of the smallest circle holding the pitch
circles, in modules: A, B: z_ring; C: max(z1 + 2 z2, z4 + 2 z3); D: max(z1, z4)), then by
the sum of teeth, then by |ratio error|.

Velocity (Kutzbach) plan: the radial line through the axis and the satellite centre is
the y axis (m); each link is a straight line of tangential velocity v(y) through its
instantaneous centre: wheel 1 and the carrier through the axis (y = 0), the satellite
through its contact with the fixed wheel (v = 0).  From v of the contact 1-2 (omega1 r1)
the satellite line gives the velocity of its centre and hence omega_H; omega1/omega_H from
the plan is compared with Willis' formula.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction
from typing import TYPE_CHECKING

import numpy as np

from ..errors import StageError
from ..messages import Message

if TYPE_CHECKING:
    from .spec import PlanetarySection

STAGE = "planetary"

SCHEMES = {
    "A": {"name": "single row: sun - satellite - fixed ring", "wheels": ("z1", "z2", "z3"),
          "meshes": (("z1", "z2", "ext"), ("z2", "z3", "int"))},
    "B": {"name": "two rows, double satellite: external + internal mesh",
          "wheels": ("z1", "z2", "z3", "z4"), "meshes": (("z1", "z2", "ext"), ("z3", "z4", "int"))},
    "C": {"name": "two rows, double satellite: two external meshes",
          "wheels": ("z1", "z2", "z3", "z4"), "meshes": (("z1", "z2", "ext"), ("z3", "z4", "ext"))},
    "D": {"name": "two rows, double satellite: two internal meshes",
          "wheels": ("z1", "z2", "z3", "z4"), "meshes": (("z2", "z1", "int"), ("z3", "z4", "int"))},
}
ALIASES = {"a": "A", "b": "B", "c": "C", "d": "D", "single": "A", "james": "A"}

Z_EXT = 17          # external wheel in external mesh (ha* = 1, x = 0)
Z_EXT_IN_INT = 20   # external wheel in internal mesh
Z_INT = 85          # internal wheel
Z_DIFF = 8          # z_internal - z_external in an internal mesh
HA = 1.0
RANKS = ("size", "ratio_error")


@dataclass(frozen=True)
class Limits:
    """Tooth-number limits (zero shifts, ha* = 1): external wheel in an external mesh, internal
    (ring) wheel, external wheel meshing a ring, least z_ring - z_pinion of an internal mesh."""
    external: int = Z_EXT
    internal: int = Z_INT
    satellite_in_internal: int = Z_EXT_IN_INT
    difference: int = Z_DIFF

    @classmethod
    def of(cls, z_min: int = Z_EXT) -> "Limits":
        """tmm/1 `planetary` with only z_min: an external wheel meshing a ring takes max(20, z_min)."""
        return cls(external=z_min, satellite_in_internal=max(Z_EXT_IN_INT, z_min))


def scheme_key(name: str) -> str:
    """The scheme's letter of a name the task gives.

    Parameters
    ----------
    name : str
        A letter A-D or one of the aliases (case and spaces ignored).

    Returns
    -------
    str
        The letter.

    Raises
    ------
    StageError
        An unknown scheme.
    """
    key = str(name).strip()
    key = ALIASES.get(key.lower(), key.upper())
    if key not in SCHEMES:
        raise StageError(STAGE, Message("planetary.fail.unknown_scheme", name=str(name), known=", ".join(SCHEMES)))
    return key


def ratio_exact(scheme: str, z: dict) -> Fraction:
    """Willis' ratio i_1H of a tooth set, exact.

    Parameters
    ----------
    scheme : str
        The scheme's letter, A-D.
    z : dict
        The tooth numbers by wheel name (``z1``, ``z2``, ``z3``[, ``z4``]).

    Returns
    -------
    fractions.Fraction
        i_1H = 1 + z3/z1 (A), 1 + z2 z4/(z1 z3) (B), 1 - z2 z4/(z1 z3) (C, D).

    References
    ----------
    Popov & Timofeev, *Kursovoe proektirovanie po TMM*: Willis' formula for the schemes A-D;
    docs/methods.md §6.
    """
    if scheme == "A":
        return 1 + Fraction(z["z3"], z["z1"])
    if scheme == "B":
        return 1 + Fraction(z["z2"] * z["z4"], z["z1"] * z["z3"])
    return 1 - Fraction(z["z2"] * z["z4"], z["z1"] * z["z3"])


def centre_distances(scheme: str, z: dict) -> tuple[float, float]:
    """Centre distances of the two meshes of a planetary gear.

    Parameters
    ----------
    scheme : str
        The scheme's letter, A-D.
    z : dict
        The tooth numbers by wheel name (``z1``, ``z2``, ``z3``[, ``z4``]).

    Returns
    -------
    tuple of float
        The centre distances of the first and the second mesh, in modules (equal when the
        gear is coaxial).

    References
    ----------
    Popov & Timofeev, *Kursovoe proektirovanie po TMM*: the coaxiality condition;
    docs/methods.md §6.
    """
    if scheme == "A":
        return (z["z1"] + z["z2"]) / 2, (z["z3"] - z["z2"]) / 2
    if scheme == "B":
        return (z["z1"] + z["z2"]) / 2, (z["z4"] - z["z3"]) / 2
    if scheme == "C":
        return (z["z1"] + z["z2"]) / 2, (z["z4"] + z["z3"]) / 2
    return (z["z1"] - z["z2"]) / 2, (z["z4"] - z["z3"]) / 2


def satellites_of(scheme: str, z: dict) -> list[int]:
    """The satellites' tooth numbers.

    Parameters
    ----------
    scheme : str
        The scheme's letter, A-D.
    z : dict
        The tooth numbers by wheel name (``z1``, ``z2``, ``z3``[, ``z4``]).

    Returns
    -------
    list of int
        [z2] for scheme A, [z2, z3] (the double satellite) for the others.
    """
    return [z["z2"]] if scheme == "A" else [z["z2"], z["z3"]]


def assembly_p(scheme: str, z: dict, k: int, pmax: int | None = None):
    """The assembly condition of k equally spaced satellites.

    Parameters
    ----------
    scheme : str
        The scheme's letter, A-D.
    z : dict
        The tooth numbers by wheel name (``z1``, ``z2``, ``z3``[, ``z4``]).
    k : int
        The number of satellites.
    pmax : int or None
        The largest p tried (None: the denominator of i_1H z1/k plus one).

    Returns
    -------
    int or None
        The least p >= 0 with (i_1H z1 / k)(1 + k p) whole; None when there is none.

    References
    ----------
    Popov & Timofeev, *Kursovoe proektirovanie po TMM*: the assembly condition of equally
    spaced satellites; docs/methods.md §6.
    """
    q = ratio_exact(scheme, z) * z["z1"] / k
    pmax = pmax if pmax is not None else q.denominator + 1
    for p in range(pmax + 1):
        if (q * (1 + k * p)).denominator == 1:
            return p
    return None


def _limits(z_min) -> Limits:
    return z_min if isinstance(z_min, Limits) else Limits.of(int(z_min))


def undercut_ok(scheme: str, z: dict, z_min: "int | Limits" = Z_EXT) -> list[str]:
    """The tooth-number limits a tooth set breaks.

    Parameters
    ----------
    scheme : str
        The scheme's letter, A-D.
    z : dict
        The tooth numbers by wheel name (``z1``, ``z2``, ``z3``[, ``z4``]).
    z_min : int or Limits
        The limits (an int: tmm/1's least external teeth, see :meth:`Limits.of`).

    Returns
    -------
    list of str
        The limits broken, as ``"z1 = 15 < 17"``; empty when none.

    References
    ----------
    Popov & Timofeev, *Kursovoe proektirovanie po TMM*: the least tooth numbers of external
    and internal wheels without undercut and interference; docs/methods.md §6.
    """
    lim = _limits(z_min)
    bad = []
    for a, b, kind in SCHEMES[scheme]["meshes"]:
        za, zb = z[a], z[b]
        if kind == "ext":
            for name, v in ((a, za), (b, zb)):
                if v < lim.external:
                    bad.append(f"{name} = {v} < {lim.external}")
        else:                                   # a: external wheel, b: internal wheel
            if za < lim.satellite_in_internal:
                bad.append(f"{a} = {za} < {lim.satellite_in_internal} (external wheel in internal mesh)")
            if zb < lim.internal:
                bad.append(f"{b} = {zb} < {lim.internal} (internal wheel)")
            if zb - za < lim.difference:
                bad.append(f"{b} - {a} = {zb - za} < {lim.difference}")
    return bad


def adjacency_margin(scheme: str, z: dict, k: int) -> float:
    """The adjacency condition of k satellites.

    Parameters
    ----------
    scheme : str
        The scheme's letter, A-D.
    z : dict
        The tooth numbers by wheel name (``z1``, ``z2``, ``z3``[, ``z4``]).
    k : int
        The number of satellites.

    Returns
    -------
    float
        2 a_w sin(pi/k) - (the largest satellite's z + 2 ha*), in modules: > 0 when the tip
        circles of neighbouring satellites do not overlap; inf for one satellite.

    References
    ----------
    Popov & Timofeev, *Kursovoe proektirovanie po TMM*: the adjacency (neighbourhood)
    condition; docs/methods.md §6.
    """
    aw = centre_distances(scheme, z)[0]
    if k == 1:
        return math.inf
    return 2 * abs(aw) * math.sin(math.pi / k) - (max(satellites_of(scheme, z)) + 2 * HA)


def assembling_counts(scheme: str, z: dict, most: int = 12) -> list[int]:
    """The numbers of equally spaced satellites that assemble and fit side by side.

    Parameters
    ----------
    scheme : str
        The scheme's letter, A-D.
    z : dict
        The tooth numbers by wheel name (``z1``, ``z2``, ``z3``[, ``z4``]).
    most : int
        The largest number tried.

    Returns
    -------
    list of int
        The k in 1..most meeting the assembly and the adjacency conditions.
    """
    return [k for k in range(1, most + 1) if assembly_p(scheme, z, k) is not None and adjacency_margin(scheme, z, k) > 0]


def size_key(scheme: str, z: dict) -> float:
    """The size of a planetary gear, in teeth, for the ranking.

    Parameters
    ----------
    scheme : str
        The scheme's letter, A-D.
    z : dict
        The tooth numbers by wheel name (``z1``, ``z2``, ``z3``[, ``z4``]).

    Returns
    -------
    float
        The ring's teeth (A: z3, B: z4), the larger outer diameter in teeth (C) or the larger
        ring (D).
    """
    if scheme in ("A",):
        return z["z3"]
    if scheme == "B":
        return z["z4"]
    if scheme == "C":
        return max(z["z1"] + 2 * z["z2"], z["z4"] + 2 * z["z3"])
    return max(z["z1"], z["z4"])


def verify(scheme: str, z: dict, k: int, required: float, tolerance: float,
           z_min: "int | Limits" = Z_EXT) -> dict:
    """Every condition of one tooth set.

    Parameters
    ----------
    scheme : str
        The scheme's letter, A-D.
    z : dict
        The tooth numbers by wheel name (``z1``, ``z2``, ``z3``[, ``z4``]).
    k : int
        The number of satellites.
    required : float
        The required ratio i_1H.
    tolerance : float
        The relative tolerance on the ratio.
    z_min : int or Limits
        The tooth limits.

    Returns
    -------
    dict
        ``ratio``, ``ratio_error`` (relative), ``ratio_ok``, ``coaxial``, ``assembly_p``,
        ``assembly``, ``adjacency_margin`` (modules), ``adjacency``,
        ``undercut_violations`` and ``undercut``.

    References
    ----------
    Popov & Timofeev, *Kursovoe proektirovanie po TMM*: the conditions of the synthesis of a
    planetary gear: the ratio, coaxiality, assembly, adjacency, the tooth limits;
    docs/methods.md §6.
    """
    i = ratio_exact(scheme, z)
    a1, a2 = centre_distances(scheme, z)
    p = assembly_p(scheme, z, k)
    err = (float(i) - required) / required
    return {"ratio": float(i), "ratio_error": err, "ratio_ok": abs(err) <= tolerance * (1 + 1e-12),
            "coaxial": a1 == a2 and a1 > 0, "assembly_p": p, "assembly": p is not None,
            "adjacency_margin": adjacency_margin(scheme, z, k),
            "adjacency": adjacency_margin(scheme, z, k) > 0,
            "undercut_violations": undercut_ok(scheme, z, z_min),
            "undercut": not undercut_ok(scheme, z, z_min)}


def _all_ok(v: dict) -> bool:
    return v["ratio_ok"] and v["coaxial"] and v["assembly"] and v["adjacency"] and v["undercut"]


def _assembly_vec(num, den, k):
    """Vectorised textbook assembly test: exists p >= 0 with num (1 + k p) / (k den) integer.

    k den | num (1 + k p) needs k | num (gcd(k, 1 + k p) = 1); with n' = num / k and
    d' = den / gcd(n', den), k p = -1 (mod d') is solvable iff gcd(k, d') = 1.
    """
    num = np.abs(num)
    ok = num % k == 0
    n1 = num // k
    d1 = den // np.gcd(n1, den)
    return ok & (np.gcd(k, d1) == 1)


def _order(size, teeth, err, rank, top=None):
    """Row order: ``size`` -- size, teeth, |error|; ``ratio_error`` -- |error|, size, teeth.
    ``top``: only the first ``top`` rows of that order (the same rows in the same order):
    the rows whose first key is beyond the top-th smallest cannot be among them."""
    first = np.round(err, 12) if rank == "ratio_error" else size
    sub = None
    if top is not None and 0 < top < len(first):
        sub = np.flatnonzero(first <= np.partition(first, top - 1)[top - 1])
        size, teeth, err, first = size[sub], teeth[sub], err[sub], first[sub]
    if rank == "ratio_error":
        order = np.lexsort((teeth, size, first))
    else:
        order = np.lexsort((err, teeth, size))
    return order if sub is None else sub[order[:top]]


def _pruned_ranges(scheme, z1, z2, lo, hi, z_max, lim: Limits, k, sinpk, z3min, z3max):
    """For the two-row schemes and each pair (z1, z2) (arrays of one shape): the z3 in
    first, first + step, ..., <= last that may meet the ratio window [lo, hi], the tooth limits on z3 and
    z4 (z4 <= z_max) and the adjacency of the satellites (``sinpk`` = sin(pi / k), None for
    one satellite), a superset of the z3 the conditions accept (they are checked after);
    pairs that fail a condition of z1, z2 alone get an empty range.

    For fixed z1, z2 the ratio is i = a + b / z3 (B: z4 = z1 + z2 + z3, i = 1 + c + c S / z3;
    C: i = 1 + c - c S / z3; D: i = 1 - c - c S' / z3; c = z2 / z1, S = z1 + z2,
    S' = z1 - z2), monotonic in z3, so the window is an interval of 1 / z3, widened by one
    tooth each side against round-off; z4 and the adjacency bound z3 linearly. The
    assembly condition needs k | num, and num = a_w (z3 + z2) (B) or a_w (z3 - z2) (C, D)
    with a_w = z1 + z2 (B, C) or z1 - z2 (D): z3 = -+z2 (mod k / gcd(k, a_w)), the step."""
    c = z2 / z1
    ext, sat, ring, diff = lim.external, lim.satellite_in_internal, lim.internal, lim.difference
    if scheme == "B":                                       # z4 = z1 + z2 + z3
        a, b, aw = 1 + c, c * (z1 + z2), z1 + z2
        z3lo = np.maximum(sat, np.maximum(ring, z2 + diff) - z1 - z2)
        z3hi = z_max - z1 - z2
        pair = (z1 >= ext) & (z2 >= ext)
    elif scheme == "C":                                     # z4 = z1 + z2 - z3
        a, b, aw = 1 + c, -c * (z1 + z2), z1 + z2
        z3lo, z3hi = np.maximum(ext, z1 + z2 - z_max), z1 + z2 - ext
        pair = (z1 >= ext) & (z2 >= ext)
    else:                                                   # z4 = z1 - z2 + z3
        a, b, aw = 1 - c, -c * (z1 - z2), z1 - z2
        z3lo, z3hi = np.maximum(sat, ring - z1 + z2), z_max - z1 + z2
        pair = (z1 >= ring) & (z2 >= sat) & (z1 - z2 >= diff)
    if sinpk is not None:                                   # aw sin(pi/k) > max(z2, z3) + 2 ha
        bound = aw * sinpk - 2 * HA
        z3hi = np.minimum(z3hi, np.ceil(bound) + 1)
        pair &= z2 < bound + 1
    with np.errstate(divide="ignore", invalid="ignore"):
        t1, t2 = (lo - a) / b, (hi - a) / b                 # the window of 1 / z3 (b != 0)
        tmin, tmax = np.minimum(t1, t2), np.maximum(t1, t2)
        # z3 >= 1 / tmax (tmax > 0, else no z3 > 0); z3 <= 1 / tmin (tmin > 0, else unbounded)
        rlo = np.where(tmax > 0, np.floor(1.0 / np.where(tmax > 0, tmax, 1.0)) - 1, np.inf)
        rhi = np.where(tmin > 0, np.ceil(1.0 / np.where(tmin > 0, tmin, 1.0)) + 1, np.inf)
    const = b == 0                                          # i = a for every z3
    rlo = np.where(const, np.where((a >= lo) & (a <= hi), -np.inf, np.inf), rlo)
    rhi = np.where(const | ~pair, np.inf, rhi)
    rlo = np.where(pair, rlo, np.inf)
    first = np.clip(np.maximum(z3lo, rlo), z3min, z3max + 1).astype(np.int64)
    last = np.clip(np.minimum(z3hi, rhi), z3min - 1, z3max).astype(np.int64)
    step = k // np.gcd(k, np.abs(aw))
    first = first + ((-z2 if scheme == "B" else z2) - first) % step
    return first, np.maximum(last, first - step), step


def _pruned_blocks(scheme, zs, lo, hi, z_max, lim, k, sinpk, chunk=1_000_000):
    """(z1, z2, z3) arrays, in the order of the full grid (z1, then z2, then z3), of the
    triples :func:`_pruned_ranges` leaves, in blocks of whole z1 of about ``chunk`` rows."""
    if not len(zs):
        return
    Z1, Z2 = np.meshgrid(zs, zs, indexing="ij")
    first, last, step = _pruned_ranges(scheme, Z1, Z2, lo, hi, z_max, lim, k, sinpk, int(zs[0]), int(zs[-1]))
    n = (last - first) // step + 1
    per_z1 = n.sum(axis=1)
    start = 0
    while start < len(zs):
        stop, acc = start, 0
        while stop < len(zs) and (acc == 0 or acc + per_z1[stop] <= chunk):
            acc += int(per_z1[stop])
            stop += 1
        if acc:
            nn = n[start:stop].ravel()
            z1 = np.repeat(Z1[start:stop].ravel(), nn)
            z2 = np.repeat(Z2[start:stop].ravel(), nn)
            st = np.repeat(step[start:stop].ravel(), nn)
            within = np.arange(acc) - np.repeat(np.cumsum(nn) - nn, nn)
            yield z1, z2, np.repeat(first[start:stop].ravel(), nn) + st * within
        start = stop


def _candidates(scheme, req, tol, k, z_min, z_max, rank="size", prune=True, top=None, best=False):
    """Vectorised enumeration of tooth numbers meeting every condition; rows of an int array
    (z1, z2, z3[, z4]) sorted by ``rank`` (size, teeth and ratio error by default).
    ``prune`` (two-row schemes): check the conditions only on the (z2, z3) the ratio window
    and z_max leave for each z1, z2 (:func:`_pruned_ranges`); False: on the full grid (the
    reference the tests compare with; the same rows in the same order). ``top``: only the
    first ``top`` rows of the ranking (see :func:`_order`). ``best``: return (rows, the
    smallest |ratio error| / |req| of all the rows, None when there are none)."""
    lo, hi = req - tol * abs(req), req + tol * abs(req)
    lim = _limits(z_min)
    zext = int(lim.external)
    zin_ext = int(lim.satellite_in_internal)
    Z_INT, Z_DIFF = int(lim.internal), int(lim.difference)  # noqa: N806  (the limits in force)
    sinpk = math.sin(math.pi / k) if k > 1 else None
    rows = []
    if scheme == "A":
        z1 = np.arange(zext, z_max + 1)[:, None]
        z3 = np.arange(Z_INT, z_max + 1)[None, :]
        z1, z3 = np.broadcast_arrays(z1, z3)
        z2 = (z3 - z1) // 2
        i = 1 + z3 / z1
        ok = ((i >= lo) & (i <= hi) & ((z3 - z1) % 2 == 0) & (z2 >= max(zin_ext, zext))
              & (z3 - z2 >= Z_DIFF))
        ok &= _assembly_vec(z1 + z3, np.ones_like(z1), k)
        if sinpk is not None:
            ok &= (z1 + z2) * sinpk > z2 + 2 * HA
        z1, z2, z3 = z1[ok], z2[ok], z3[ok]
        arr = np.stack([z1, z2, z3], axis=1)
        size = z3
        err = np.abs(1 + z3 / z1 - req)
        return _ranked(scheme, arr, req, _order(size, arr.sum(axis=1), err, rank, top), best)
    zlo = min(zext, zin_ext)
    zs = np.arange(zlo, z_max + 1)
    if prune:
        blocks = _pruned_blocks(scheme, zs, lo, hi, z_max, lim, k, sinpk)
    else:
        G2, G3 = np.meshgrid(zs, zs, indexing="ij")
        blocks = ((z1, G2, G3) for z1 in range(zlo, z_max + 1))
    for z1, Z2, Z3 in blocks:
        if scheme == "B":
            z4 = z1 + Z2 + Z3
            num = z1 * Z3 + Z2 * z4
            i = 1 + Z2 * z4 / (z1 * Z3)
            ok = (z1 >= zext) & (Z2 >= zext) & (Z3 >= zin_ext) & (z4 >= Z_INT) & (z4 - Z3 >= Z_DIFF)
            aw = z1 + Z2
        elif scheme == "C":
            z4 = z1 + Z2 - Z3
            num = z1 * Z3 - Z2 * z4
            i = 1 - Z2 * z4 / (z1 * Z3)
            ok = (z1 >= zext) & (Z2 >= zext) & (Z3 >= zext) & (z4 >= zext)
            aw = z1 + Z2
        else:
            z4 = z1 - Z2 + Z3
            num = z1 * Z3 - Z2 * z4
            i = 1 - Z2 * z4 / (z1 * Z3)
            ok = ((z1 >= Z_INT) & (Z2 >= zin_ext) & (z1 - Z2 >= Z_DIFF) & (Z3 >= zin_ext)
                  & (z4 >= Z_INT) & (z4 - Z3 >= Z_DIFF))
            aw = z1 - Z2
        ok &= (i >= lo) & (i <= hi) & (z4 <= z_max) & (num != 0)
        if sinpk is not None:
            ok &= aw * sinpk > np.maximum(Z2, Z3) + 2 * HA
        sel = np.flatnonzero(ok)
        if not len(sel):
            continue
        s2, s3, s4 = Z2.ravel()[sel], Z3.ravel()[sel], z4.ravel()[sel]
        keep = _assembly_vec(num.ravel()[sel], s3, k)
        if keep.any():
            s1 = np.broadcast_to(z1, ok.shape).ravel()[sel]
            rows.append(np.stack([s1[keep], s2[keep], s3[keep], s4[keep]], axis=1))
    if not rows:
        return _ranked(scheme, np.zeros((0, 4), dtype=int), req, slice(None), best)
    arr = np.concatenate(rows)
    z1, z2, z3, z4 = arr.T
    if scheme == "B":
        size = z4
        i = 1 + z2 * z4 / (z1 * z3)
    elif scheme == "C":
        size = np.maximum(z1 + 2 * z2, z4 + 2 * z3)
        i = 1 - z2 * z4 / (z1 * z3)
    else:
        size = np.maximum(z1, z4)
        i = 1 - z2 * z4 / (z1 * z3)
    return _ranked(scheme, arr, req, _order(size, arr.sum(axis=1), np.abs(i - req), rank, top), best)


def _ranked(scheme, arr, req, order, best):
    if not best:
        return arr[order]
    return arr[order], (float(np.min(np.abs(ratios_of(scheme, arr) - req)) / abs(req)) if len(arr) else None)


def velocity_plan(scheme: str, z: dict, m: float, omega1: float = 1.0) -> dict:
    """The velocity plan (Kutzbach's picture) of a planetary gear.

    Parameters
    ----------
    scheme : str
        The scheme's letter, A-D.
    z : dict
        The tooth numbers by wheel name (``z1``, ``z2``, ``z3``[, ``z4``]).
    m : float
        Module, m.
    omega1 : float
        The angular speed of wheel 1, rad/s.

    Returns
    -------
    dict
        The key points' radial positions ``y`` (m) and tangential velocities ``v`` (m/s), the
        links' lines v = slope (y - y0), the angular speeds of the carrier and the satellite
        (rad/s) and the ratio i_1H read off the plan.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*; Popov & Timofeev, *Kursovoe
    proektirovanie po TMM*: the velocity plan of a planetary gear; docs/methods.md §6.
    """
    r = {k: m * v / 2 for k, v in z.items()}
    a = centre_distances(scheme, z)[0] * m
    if scheme == "A":
        y12, yF = r["z1"], r["z3"]                 # contact with 1, contact with the fixed wheel
    elif scheme == "B":
        y12, yF = r["z1"], a + r["z3"]
    elif scheme == "C":
        y12, yF = r["z1"], a - r["z3"]
    else:
        y12, yF = r["z1"], a + r["z3"]
    v12 = omega1 * y12                             # wheel 1: line through the axis
    # satellite: v(y) linear, zero at yF, v12 at y12
    slope_sat = v12 / (y12 - yF)
    v_centre = slope_sat * (a - yF)
    omega_h = v_centre / a
    omega_sat = slope_sat                           # absolute angular velocity of the satellite
    pts = [{"name": "O", "y": 0.0, "v": 0.0}, {"name": "A (1-2)", "y": y12, "v": v12},
           {"name": "C (centre of 2)", "y": a, "v": v_centre}, {"name": "F (fixed contact)", "y": yF, "v": 0.0}]
    return {"omega1": omega1, "omega_H": omega_h, "omega_satellite": omega_sat,
            "ratio": omega1 / omega_h if omega_h != 0 else None, "points": pts,
            "lines": {"1": {"y0": 0.0, "slope": omega1}, "H": {"y0": 0.0, "slope": omega_h},
                      "satellite": {"y0": yF, "slope": slope_sat}},
            "tan_psi_1": omega1, "tan_psi_H": omega_h}


@dataclass
class PlanetaryResult:
    """The planetary synthesis: the chosen tooth numbers, the checks and the candidates."""

    scheme: str
    required: float
    tolerance: float
    satellites: int
    m: float
    z: dict
    checks: dict
    candidates: list
    plan: dict
    warnings: list = field(default_factory=list)
    best_ratio_error: float | None = None
    rank: str = "size"

    def to_dict(self) -> dict:
        radii = {k: self.m * v / 2 for k, v in self.z.items()}
        return {"z": dict(self.z), "z_list": [self.z[n] for n in SCHEMES[self.scheme]["wheels"]],
                "best_ratio_error": self.best_ratio_error, "rank": self.rank, "ratio": self.checks["ratio"], "ratio_error": self.checks["ratio_error"],
                "scheme": self.scheme, "scheme_name": SCHEMES[self.scheme]["name"],
                "required": self.required, "tolerance": self.tolerance, "satellites": self.satellites,
                "m": self.m, "r": radii, "aw": centre_distances(self.scheme, self.z)[0] * self.m,
                "ratio_willis": self.checks["ratio"], "ratio_plan": self.plan["ratio"],
                "checks": {k: v for k, v in self.checks.items() if k not in ("ratio", "ratio_error")},
                "candidates": self.candidates, "velocity_plan": self.plan, "warnings": list(self.warnings)}


def _no_candidates_hint(scheme: str, req: float, tol: float, z_min: int, z_max: int,
                        k: int = 3, limits: Limits | None = None) -> Message:
    """Why the search may have found nothing, and what to change."""
    if z_max < z_min:
        return Message("planetary.hint.z_max_below", z_max=z_max, z_min=z_min)
    if scheme in ("A", "B", "D") and z_max < Z_INT:
        return Message("planetary.hint.internal", scheme=scheme, z_int=Z_INT)
    if scheme == "A":
        # i = 1 + z3/z1: the least and the greatest ratio of the tooth sets that meet every
        # condition (coaxiality, assembly, adjacency, the tooth limits) but the tolerance
        limits = limits or Limits(external=z_min, internal=Z_INT, satellite_in_internal=max(Z_EXT_IN_INT, z_min),
                                  difference=Z_DIFF)
        def outside(n):
            lo, hi = nearest_ratio("A", 1.0, n, limits, z_max), nearest_ratio("A", 1e6, n, limits, z_max)
            return lo, hi, lo is not None and (req + tol * abs(req) < lo or req - tol * abs(req) > hi)

        lo, hi, out = outside(k)
        # out of reach with k satellites but not with one: their assembly or adjacency is the
        # cause, which the general hint names; else the tooth limits are
        if out and (k == 1 or outside(1)[2]):
            return Message("planetary.hint.scheme_a", lo=lo, hi=hi)
    return Message("planetary.hint.general")


def tooth_limits(external: int, internal: int, satellite_in_internal: int | None, difference: int) -> Limits:
    """The tooth limits of a `planetary` or `drive_train` section.

    Parameters
    ----------
    external : int
        Least teeth of an external wheel in an external mesh.
    internal : int
        Least teeth of an internal (ring) wheel.
    satellite_in_internal : int or None
        Least teeth of an external wheel meshing a ring (None: the greater of 20 and
        ``external``).
    difference : int
        Least z_ring - z_pinion of an internal mesh.

    Returns
    -------
    Limits
        The four limits as ints.

    References
    ----------
    Popov & Timofeev, *Kursovoe proektirovanie po TMM*: the limits of the tooth numbers of a
    planetary gear (no undercut, no interference in an internal mesh).
    """
    external = int(external)
    return Limits(external=external, internal=int(internal),
                  satellite_in_internal=(int(satellite_in_internal) if satellite_in_internal is not None
                                         else max(Z_EXT_IN_INT, external)),
                  difference=int(difference))


def ratios_of(scheme: str, arr: np.ndarray) -> np.ndarray:
    """Willis' ratios of many tooth sets.

    Parameters
    ----------
    scheme : str
        The scheme's letter, A-D.
    arr : numpy.ndarray
        Rows (z1, z2, z3[, z4]).

    Returns
    -------
    numpy.ndarray
        i_1H of every row.
    """
    arr = np.asarray(arr, dtype=float)
    if scheme == "A":
        return 1 + arr[:, 2] / arr[:, 0]
    q = arr[:, 1] * arr[:, 3] / (arr[:, 0] * arr[:, 2])
    return 1 + q if scheme == "B" else 1 - q


def search(scheme: str, req: float, tol: float, k: int, limits: Limits, z_max: int, rank: str = "size",
           keep: int = 10, stage: str = STAGE) -> tuple[list, float | None]:
    """The ranked tooth sets of a planetary gear meeting every condition.

    Parameters
    ----------
    scheme : str
        The scheme's letter, A-D.
    req : float
        The required ratio i_1H.
    tol : float
        The relative tolerance on the ratio.
    k : int
        The number of satellites.
    limits : Limits
        The tooth limits.
    z_max : int
        The largest tooth number tried.
    rank : str
        ``size`` (the gear's size, then the teeth) or ``ratio_error``.
    keep : int
        How many sets to return.
    stage : str
        The stage named by an internal inconsistency's error.

    Returns
    -------
    found : list of dict
        The best ``keep`` sets, every condition checked again by :func:`verify`: ``z``,
        ``ratio``, ``ratio_error``, ``size``, ``teeth``, ``assembly_p``, ``checks``.
    best : float or None
        The least |ratio error| among all the feasible sets (None: there is none).

    References
    ----------
    Popov & Timofeev, *Kursovoe proektirovanie po TMM*: the synthesis of a planetary gear by
    its conditions; docs/methods.md §6.
    """
    arr, best = _candidates(scheme, req, tol, k, limits, int(z_max), rank, top=max(keep, 1), best=True)
    names = SCHEMES[scheme]["wheels"]
    found = []
    for row in arr[: max(keep, 1)]:
        z = {n: int(v) for n, v in zip(names, row)}
        v = verify(scheme, z, k, req, tol, limits)
        if not _all_ok(v):                      # the vectorised filter and verify() disagree
            raise StageError(stage, f"internal inconsistency for candidate {z}: {v}")
        found.append({"z": z, "ratio": v["ratio"], "ratio_error": v["ratio_error"],
                      "size": size_key(scheme, z), "teeth": sum(z.values()),
                      "assembly_p": v["assembly_p"], "checks": v})
    return found, best


def nearest_ratio(scheme: str, req: float, k: int, limits: Limits, z_max: int) -> float | None:
    """The feasible ratio nearest to a required one, the tolerance aside.

    Parameters
    ----------
    scheme : str
        The scheme's letter, A-D.
    req : float
        The required ratio i_1H.
    k : int
        The number of satellites.
    limits : Limits
        The tooth limits.
    z_max : int
        The largest tooth number tried.

    Returns
    -------
    float or None
        The ratio of the tooth set nearest to ``req`` meeting every other condition (None: no
        set).
    """
    arr = _candidates(scheme, req, 1e6, k, limits, int(z_max), "ratio_error", top=1)
    return float(ratios_of(scheme, arr[:1])[0]) if len(arr) else None


def synthesize_planetary(spec: PlanetarySection) -> PlanetaryResult:
    """Tooth numbers of a planetary gear of a given ratio.

    Parameters
    ----------
    spec : PlanetarySection
        The task's ``planetary`` section: the scheme (A-D), the required ratio i_1H
        (dimensionless), the number of satellites k, the relative ratio tolerance, the
        module ``m`` (m; None: 1 mm for the velocity plan), the tooth limits, ``z_max``,
        how many candidates to list and how to rank them (``size`` or ``ratio_error``).

    Returns
    -------
    PlanetaryResult
        The chosen tooth numbers with their checks (coaxiality, assembly, adjacency, the
        tooth limits), the ranked candidates and the velocity plan (m, rad/s for a unit
        input speed); ``to_dict()`` is the results.json ``planetary`` section.

    Raises
    ------
    StageError
        No tooth set meets the conditions within the tolerance (with a hint at the cause).

    References
    ----------
    Popov & Timofeev, *Kursovoe proektirovanie po TMM*: the schemes A-D, Willis' formula,
    the conditions of coaxiality, assembly and adjacency; Artobolevsky, *Theory of
    Mechanisms and Machines*: the velocity plan; docs/methods.md §6.
    """
    scheme = scheme_key(spec.scheme)
    req = float(spec.ratio)
    if req == 0 or not math.isfinite(req):
        raise StageError(STAGE, Message("planetary.fail.ratio_zero"))
    k, tol = int(spec.satellites), float(spec.tolerance)
    m = 0.001 if spec.m is None else float(spec.m)
    limits = tooth_limits(spec.z_min_external or spec.z_min, spec.z_min_internal,
                          spec.z_min_satellite_in_internal, spec.internal_minus_external_min)
    z_min = limits.external
    z_max, n_keep, rank = spec.z_max, int(spec.candidates), spec.rank
    if scheme in ("A", "B") and req <= 1:
        raise StageError(STAGE, Message("planetary.fail.below_one", scheme=scheme, required=req))
    found, best = search(scheme, req, tol, k, limits, int(z_max), rank, n_keep)
    if not found:
        raise StageError(STAGE, Message("planetary.fail.none_found", scheme=scheme, required=req, tol=tol, k=k,
                                        z_min=z_min, z_max=z_max,
                                        hint=_no_candidates_hint(scheme, req, tol, int(z_min), int(z_max), k, limits)))
    z, v = found[0]["z"], found[0]["checks"]
    cands = [{key: c[key] for key in ("z", "ratio", "ratio_error", "size", "teeth", "assembly_p")}
             for c in found]
    plan = velocity_plan(scheme, z, m)
    warnings = []
    if plan["ratio"] is not None and abs(plan["ratio"] - v["ratio"]) > 1e-9 * max(1.0, abs(v["ratio"])):
        warnings.append(Message("planetary.plan_ratio", plan=plan["ratio"], willis=v["ratio"]))
    checks = dict(v)
    checks["adjacency_margin"] = float(checks["adjacency_margin"]) if math.isfinite(
        checks["adjacency_margin"]) else None
    return PlanetaryResult(scheme=scheme, required=req, tolerance=tol, satellites=k, m=m, z=dict(z),
                           checks=checks, candidates=cands, plan=plan, warnings=warnings,
                           best_ratio_error=best, rank=rank)
