"""The transmission angle of each dyad of a linkage and its least over the cycle.

The transmission angle gamma of a dyad is the angle at its middle pair between the force a
link passes on and the motion it drives: 90 deg transmits best, 0 is a dead point (the
dyad's velocity equations singular, its joint forces without bound).  The joint forces of
the dyad grow about as 1 / sin(gamma).

* RRR (links AB and BC, pairs A, B, C): the acute angle at B between the lines B-A and
  B-C (a four-bar: between the coupler and the rocker).
* RRP (a rod AB and a block at B on a guide): 90 deg minus the acute angle between the rod
  and the guide (a slider-crank: gamma_min = arccos((r + e) / l)).
* RPR (a block pinned at A, sliding in a slot of a link that turns about its other pair O1: the
  slotted lever): 90 deg minus the acute angle between the slot and the line O1A (the block
  presses normal to the slot; the slotted link's point under it moves normal to O1A): 90 deg
  with the slot through O1, 90 - asin(e / |O1A|) with the slot offset by e.
* PRP (a block in a slot of one link, pinned to a slider on a guide: the shaper's ram driven by
  the rocker's slot): the acute angle between the slot and the guide (the block presses normal
  to the slot; the slider moves along its guide).
* RPP (a block pinned at A in the slot of a link that slides on a guide: the Scotch yoke): the
  acute angle between the slot and the guide, as the PRP's (the block presses normal to the
  slot; the slotted link moves along its guide): 90 deg with the slot square to the guide, at
  every position (the link does not turn).
* Triads: none is reported.

The least over the cycle: the sine of gamma on a 0.5-deg grid of crank angles. Where it
changes sign anywhere between neighbours the dyad passes a dead point: the least is 0 at its
zero (a steep one can hide between points that are not the grid's least). Else at every least
of its magnitude between neighbours that could be the least, the zero of its exact derivative
(the kinematic analogues of velocity, d/dphi): grids of 129 points nested in the bracket each
finds, to 2e-9 deg, then the line between its ends (a least near a dead point is sharp); the
nested grids read the solver's own values (``solve_raw``), smooth through a singular position.

References
----------
Artobolevsky, *Theory of Mechanisms and Machines*, the transmission and pressure angles of
lever mechanisms; Popov & Timofeev, *Kursovoe proektirovanie po TMM*; docs/methods.md §2.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from .context import Linkage
    from .mechanism import Mechanism
    from .structure import Group

#: below this least transmission angle (deg) a warning is given: the joint forces of the
#: dyad exceed about 2.9 times those of a square transmission (1 / sin 20 deg)
LOW = 20.0
#: the course's recommended least for a lever mechanism in design (deg), said in the warning
RECOMMENDED = 40.0
#: at or below this least (deg) the dyad is at a dead point: the round-off of an angle found
#: at an exact Grashof limit is ~3e-6 deg, and 1e-4 deg would already be a force 5.7e5 times
DEAD = 1e-4


@dataclass(frozen=True)
class DyadAngle:
    """How one dyad's transmission angle is read from the kinematics."""

    group: "Group"
    kind: str                       # "RRR" | "RRP" | "RPR" | "PRP" | "RPP"
    middle: str                     # the middle pair's point
    ends: tuple[str, str]           # RRR: the outer pairs' points; RRP: (rod's outer point, middle)
    guide_angle: float = 0.0        # RRP, PRP, RPP: the (first) guide's angle (deg; on a link: to its axis)
    guide_link: str | None = None   # RRP, PRP, RPP: the link that carries it (None: fixed)
    guide2_angle: float = 0.0       # PRP, RPP: the other guide's
    guide2_link: str | None = None
    through_pivot: bool = False     # RPR: the slot's line passes through the pivot (gamma = 90 deg always)


def dyads(mech: "Mechanism", groups: list["Group"]) -> list[DyadAngle]:
    """The dyads of ``groups`` whose transmission angle is defined (RRR, RRP/PRR, RPR, PRP,
    RPP/PPR)."""
    out = []
    for g in groups:
        if len(g.links) != 2 or len(g.joints) != 3:
            continue
        kinds = "".join(j.kind for j in g.joints)
        joints = list(g.joints)
        if kinds in ("PRR", "PPR"):
            joints, kinds = joints[::-1], kinds[::-1]
        if kinds == "RRR":
            out.append(DyadAngle(g, "RRR", joints[1].point, (joints[0].point, joints[2].point)))
        elif kinds == "RRP" and joints[2].slider is not None:
            guide = mech.link(joints[2].slider).guide
            if guide is None:
                continue
            out.append(DyadAngle(g, "RRP", joints[1].point, (joints[0].point, joints[1].point),
                                 float(guide.angle), guide.link))
        elif kinds == "RPR" and joints[1].slider is not None:
            block = mech.link(joints[1].slider)
            guide = block.guide
            pin = next(iter(block.local), None)
            pivot = [j.point for j in (joints[0], joints[2]) if j.point != pin]
            if guide is None or guide.link not in g.names or pin is None or len(pivot) != 1:
                continue
            # the slotted link turns about its other pair: the slot against the line from there to
            # the block, as a rod against its guide (RRP); the pivot's distance from the slot's line
            # (n . p = offset in the slotted link's frame) is the same at every position
            slotted = mech.link(guide.link)
            px, py = slotted.local[pivot[0]]
            a = math.radians(guide.angle)
            e = abs(-math.sin(a) * px + math.cos(a) * py - guide.offset)
            scale = max(math.hypot(px, py), abs(guide.offset), float(slotted.length or 0.0), 1e-300)
            out.append(DyadAngle(g, "RPR", pin, (pivot[0], pin), float(guide.angle), guide.link,
                                 through_pivot=e <= 1e-12 * scale))
        elif kinds in ("PRP", "RPP"):
            # two guides: PRP the slot and the slider's guide (named at the pin between them),
            # RPP the slot (the block's guide, on the slotted link) and the slotted link's guide
            # (named at the block's pin)
            first, pin = (0, 1) if kinds == "PRP" else (1, 0)
            if joints[first].slider is None or joints[2].slider is None:
                continue
            g1, g2 = mech.link(joints[first].slider).guide, mech.link(joints[2].slider).guide
            if g1 is None or g2 is None:
                continue
            p = joints[pin].point
            out.append(DyadAngle(g, kinds, p, (p, p), float(g1.angle), g1.link, float(g2.angle), g2.link))
    return out


def sine(d: DyadAngle, kin) -> tuple[np.ndarray, np.ndarray]:
    """(s, ds/dphi) at every position of ``kin``: s = sin(gamma) with a sign (|s| = sin gamma;
    a change of sign is a dead point), its derivative by the crank angle (rad) from the
    analogues of velocity."""
    if d.kind == "RRR":
        b, db = kin.pos[d.middle], kin.d1[d.middle]
        u, du = kin.pos[d.ends[0]] - b, kin.d1[d.ends[0]] - db
        v, dv = kin.pos[d.ends[1]] - b, kin.d1[d.ends[1]] - db
        c = u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]
        dc = du[:, 0] * v[:, 1] + u[:, 0] * dv[:, 1] - du[:, 1] * v[:, 0] - u[:, 1] * dv[:, 0]
        lu, lv = np.hypot(u[:, 0], u[:, 1]), np.hypot(v[:, 0], v[:, 1])
        s = c / (lu * lv)
        ds = dc / (lu * lv) - s * ((u * du).sum(axis=1) / lu ** 2 + (v * dv).sum(axis=1) / lv ** 2)
        return s, ds
    if d.kind in ("PRP", "RPP"):                    # the slot and the guide: sin of the angle between them
        (t1, dt1), (t2, dt2) = (_guide(kin, d.guide_angle, d.guide_link, len(kin.phi)),
                                _guide(kin, d.guide2_angle, d.guide2_link, len(kin.phi)))
        return np.sin(t2 - t1), np.cos(t2 - t1) * (dt2 - dt1)
    r = kin.pos[d.ends[1]] - kin.pos[d.ends[0]]
    dr = kin.d1[d.ends[1]] - kin.d1[d.ends[0]]
    th, dth = _guide(kin, d.guide_angle, d.guide_link, len(r))
    g = np.column_stack([np.cos(th), np.sin(th)])
    dg = np.column_stack([-np.sin(th), np.cos(th)]) * dth[:, None]
    lr = np.hypot(r[:, 0], r[:, 1])
    s = (r * g).sum(axis=1) / lr                    # cos(rod, guide) = sin(gamma)
    ds = ((dr * g).sum(axis=1) + (r * dg).sum(axis=1)) / lr - s * (r * dr).sum(axis=1) / lr ** 2
    return s, ds


def gamma(d: DyadAngle, kin) -> np.ndarray:
    """The transmission angle (deg) of the dyad ``d`` at every position of ``kin``."""
    if d.through_pivot:
        return np.full(len(kin.phi), 90.0)
    return np.degrees(np.arcsin(np.minimum(1.0, np.abs(sine(d, kin)[0]))))


def _guide(kin, angle: float, link: str | None, n: int) -> tuple[np.ndarray, np.ndarray]:
    """(direction, rad; its derivative by the crank angle) of a guide at the positions of ``kin``:
    fixed at ``angle`` (deg), or at ``angle`` to the axis of the link ``link``."""
    th = np.full(n, math.radians(angle))
    if link is None:
        return th, np.zeros(n)
    return th + kin.angle[link], np.asarray(kin.a1[link], float)


def least(mech: "Mechanism", ds: list[DyadAngle], start: float = 0.0, span: float = 360.0,
          step: float = 0.5) -> list[tuple[float, float]]:
    """(gamma_min, deg; the crank angle where it is, deg in [0, 360)) of each dyad of ``ds``
    over the crank angles ``start`` .. ``start + span`` (deg; ``span`` signed, as a function
    generator's input range: a cw range is the same angles read from its other end; a full
    turn by default).  A least at or below :data:`DEAD` is a dead point and is 0 (a sine that
    touches 0 reads ~1e-16 where it does: a slider-crank whose rod equals its crank gave
    3.5e-15 deg)."""
    from .kinematics import solve, solve_raw

    if span < 0.0:
        start, span = start + span, -span
    full = span >= 360.0
    n = max(1, int(math.ceil(span / step)))
    grid = start + np.arange(n if full else n + 1) * (span / n)
    kin = solve(mech, grid)

    def root(d, x0, x1, which):
        """The zero in [x0, x1] of the sine (which 0) or of the slope of |sine| (1): grids of 129
        points nested in the bracket each finds (0.5 deg -> 0.004 -> 3e-5 -> 2e-7 -> 2e-9 deg),
        then the line between the ends of the last (a least near a dead point is sharp, its
        slope turning within 1e-3 deg: one grid's line put it 0.001 deg off, its angle a third
        too large); None where no point of the first grid brackets it.  A point where it is
        exactly 0 is the zero (a sine that touches 0 without changing its sign: a deltoid's
        change point, where the coupler and the rocker fold onto each other).  The grids are
        the solver's own values (:func:`solve_raw`): smooth through a singular position, where
        the limits by continuity would stand for each point near it (a search, not a report)."""
        f0 = f1 = None
        while x1 - x0 > 1e-8:
            xs = np.linspace(x0, x1, 129)
            sv, dv = sine(d, solve_raw(mech, xs))
            v = sv if which == 0 else np.sign(sv) * dv
            ch = np.flatnonzero(np.signbit(v[:-1]) != np.signbit(v[1:]))
            zero = np.flatnonzero(v == 0.0)
            if len(zero) and (not len(ch) or zero[0] <= ch[0]):
                return float(xs[zero[0]])
            if not len(ch):
                if f0 is None:
                    return None
                break                   # the bracket's ends again, but rounded alike: it stands
            k = int(ch[0])
            x0, x1, f0, f1 = float(xs[k]), float(xs[k + 1]), float(v[k]), float(v[k + 1])
        return x0 if f0 == f1 else x0 + (x1 - x0) * f0 / (f0 - f1)

    out = []
    m = len(grid)
    pairs = [(i, (i + 1) % m) for i in range(m if full else m - 1)]      # neighbours (a turn: round)
    for d in ds:
        if d.through_pivot:             # 90 deg at every position (|sin| = 1 to round-off: no least to seek)
            out.append((90.0, _turn(float(grid[0]))))
            continue
        s, dsd = sine(d, kin)
        a = np.abs(s)
        k = int(np.argmin(a))
        best_x, best = float(grid[k]), float(a[k])
        slope = np.where(s < 0.0, -dsd, dsd)                           # d|s|/dphi
        for i, j in pairs:
            x0, x1 = float(grid[i]), float(grid[j]) + (360.0 if full and j == 0 else 0.0)
            if s[i] * s[j] < 0.0:       # a dead point: the zero of the sine (a steep one can hide
                x = root(d, x0, x1, 0)  # between points that are not the grid's least)
                best_x, best = (x0 + (x1 - x0) * s[i] / (s[i] - s[j]) if x is None else x), 0.0
                break
        else:
            for i, j in pairs:          # every least of |s| between neighbours, not only the grid's least
                if not slope[i] < 0.0 < slope[j] or min(a[i], a[j]) > 2.0 * best + 1e-3:
                    continue
                x0, x1 = float(grid[i]), float(grid[j]) + (360.0 if full and j == 0 else 0.0)
                x = root(d, x0, x1, 1)                  # |s| falls, then rises: its least
                if x is None:                           # the grid's point stands
                    continue
                v = abs(float(sine(d, solve(mech, np.array([x])))[0][0]))
                if v < best:
                    best_x, best = x, v
        g = math.degrees(math.asin(min(1.0, best)))
        out.append((0.0 if g <= DEAD else g, _turn(best_x)))       # a dead point: 0, not its round-off
    return out


def _turn(x: float) -> float:
    """A crank angle in [0, 360): a root found a hair below 0 (-6e-14) is 0, not
    359.99999999999994 (which a 5-digit table shows as 360)."""
    x = x % 360.0
    return 0.0 if 360.0 - x < 1e-9 else x


def analyze(linkage: "Linkage", crank_range=None) -> list[dict]:
    """The stage: each dyad's least transmission angle over the cycle (over ``crank_range``,
    a function generator's input range, where one is given).

    Parameters
    ----------
    linkage : Linkage
        The mechanism and its Assur groups.
    crank_range : CrankRange or None
        The input range (start, span, deg) of a function generator; None: a full turn.

    Returns
    -------
    list of dict
        results.json ``transmission``: per dyad (RRR, RRP, PRR, RPR, PRP, RPP, PPR) ``group`` (its
        label), ``links``, ``type`` (the group's, as ``structure`` names it), ``joint`` (the middle pair's point),
        ``gamma_min`` (deg) and ``phi`` (the crank angle where it is, deg, ccw from the x axis).

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: the transmission angle; docs/methods.md §2.
    """
    ds = dyads(linkage.mechanism, linkage.structure.groups)
    if not ds:
        return []
    lo, span = (0.0, 360.0) if crank_range is None else (float(crank_range.start), float(crank_range.span))
    return [{"group": d.group.label, "links": list(d.group.names), "type": d.group.type, "joint": d.middle,
             "gamma_min": g, "phi": x} for d, (g, x) in zip(ds, least(linkage.mechanism, ds, lo, span))]


def warnings(rows: list[dict]) -> list:
    """A warning for each dyad of ``rows`` (:func:`analyze`) whose least transmission angle is
    below :data:`LOW`; at a dead point (at most :data:`DEAD`) the warning says so (no factor
    1/sin gamma)."""
    from ..messages import Message
    out = []
    for r in rows:
        if r["gamma_min"] >= LOW:
            continue
        at = {"group": r["group"], "links": list(r["links"]), "joint": r["joint"], "phi": r["phi"],
              "recommended": RECOMMENDED}
        if r["gamma_min"] > DEAD:
            out.append(Message("kinematics.transmission_low", **at, gamma=r["gamma_min"], low=LOW,
                               factor=1.0 / math.sin(math.radians(r["gamma_min"]))))
        else:
            out.append(Message("kinematics.transmission_dead", **at))
    return out
