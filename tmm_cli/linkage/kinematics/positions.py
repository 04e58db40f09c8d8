"""Positions of the course project (docs/methods.md §0; task section ``positions``).

The output link (``positions.output``, default the last link) has a coordinate s:

* a slider on a fixed guide: the position of its pin along the guide direction,
  measured from the guide's point (m);
* a slider on a moving guide: its pin's coordinate along the guide, measured from
  the origin of the link carrying the guide (m);
* a bar: its angle, ccw positive (deg, continuous).

Its extreme positions are the roots of the analogue ds/dphi over one crank turn:
bracketed on a 0.5-deg scan and refined (all brackets at once) by Newton's method on the
exact second derivative, kept inside its bracket, to 1e-11 deg; the global
minimum and maximum are the two extremes. The working stroke moves the output toward
increasing s (``working: forward``, it starts at the minimum) or decreasing s
(``backward``, it starts at the maximum). Position 0 is the extreme where the working
stroke begins (``zero: extreme``) or the given crank angle; ``count`` positions follow
every 360/count deg in the drive direction (cw: decreasing crank angle), then the
user's ``extra`` angles, then the second extreme (end of the working stroke), then any
angles the pipeline adds (``extra_added``, e.g. load switch points). An angle already
in the list (within 1e-9 deg) is not repeated. All angles are in [0, 360).

K = working-stroke crank angle / idle-stroke crank angle = (180 + theta)/(180 - theta).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from ...errors import StageError
from ...messages import Message
from ..mechanism import Mechanism
from .solver import solve_raw

SCAN_STEP = 0.5       # deg
XTOL = 1e-11          # deg
# an extreme position found this close to a change point (deg) is the change point: the output
# reverses there by the jump of its branch, and within ~1e-6 deg of it the analogue's sign is
# round-off (a Grashof-limit four-bar's rocker: an extreme 1.1e-7 deg off, K = 0.9999999987)
AT_CHANGE_POINT = 1e-5


def _output_coordinate(mech: Mechanism, name: str):
    """(kind, f) with f(phi_deg array) -> (s, ds/dphi) (s in m or deg; ds per rad);
    f(phi, second=True) -> (s, ds/dphi, d2s/dphi2) (per rad, per rad^2);
    ``f.from_kin(kin, second=False)`` gives the same from a kinematics result already
    solved at phi."""
    lk = mech.link(name)
    if lk.kind == "slider":
        pin = lk.origin
        g = lk.guide
        if g.link is None:
            a = math.radians(g.angle)
            e = np.array([math.cos(a), math.sin(a)])
            p0 = np.array(g.point, float)

            def of(k, second=False):
                # the products by BLAS on row-major copies: its rounding depends on the layout
                # (the kinematics' pairs are held column by column, state.pairs)
                c = np.ascontiguousarray
                out = c(k.pos[pin] - p0) @ e, c(k.d1[pin]) @ e
                return out + (c(k.d2[pin]) @ e,) if second else out
        else:
            carrier = mech.link(g.link)
            a = math.radians(g.angle)
            org = carrier.origin

            def of(k, second=False):
                psi = k.angle[carrier.name] + a
                e = np.stack([np.cos(psi), np.sin(psi)], axis=-1)
                n = np.stack([-e[:, 1], e[:, 0]], axis=-1)
                d = k.pos[pin] - k.pos[org]
                dd = k.d1[pin] - k.d1[org]
                w = k.a1[carrier.name]
                s = np.sum(e * d, axis=1)
                ds = w * np.sum(n * d, axis=1) + np.sum(e * dd, axis=1)
                if not second:
                    return s, ds
                # e' = w n, n' = -w e
                ddd = k.d2[pin] - k.d2[org]
                d2s = (k.a2[carrier.name] * np.sum(n * d, axis=1) - w * w * s
                       + 2 * w * np.sum(n * dd, axis=1) + np.sum(e * ddd, axis=1))
                return s, ds, d2s
        kind = "slider"
    else:
        def of(k, second=False):
            out = np.degrees(k.angle[name]), k.a1[name]
            return out + (k.a2[name],) if second else out
        kind = "rocker"

    def f(phi, second=False):
        return of(solve_raw(mech, phi), second)
    f.from_kin = of
    return kind, f


@dataclass
class Stroke:
    """The stroke of one link with extreme positions (the output, or any slider that
    carries a stroke-dependent load, docs/methods.md §3.3): its extreme crank angles
    [start, end] of the working stroke, its coordinate there, the working-stroke crank
    angle and the sense of the drive."""
    link: str
    kind: str                        # 'slider' (s in m) | 'rocker' (angle in deg)
    extreme: list[float]             # [start, end] of the working stroke, deg
    s_extreme: list[float]           # coordinate at [start, end]
    working_stroke_angle: float      # deg of crank rotation
    sign: float                      # +1 ccw drive, -1 cw
    working: str                     # 'forward' | 'backward'
    _f: object = field(default=None, repr=False)

    @property
    def H(self) -> float:
        return abs(self.s_extreme[1] - self.s_extreme[0])

    def stroke_state(self, phi_deg, kin=None) -> tuple[np.ndarray, np.ndarray]:
        """For each crank angle: 'working' or 'idle', and s_rel in [0, 1], the link's
        displacement from the start of the current stroke relative to the stroke H.
        At the start extreme the working stroke applies, at the end extreme the idle.
        ``kin``: the kinematics already solved at these angles (not solved again)."""
        phi = np.atleast_1d(np.asarray(phi_deg, float))
        rel = np.mod((phi - self.extreme[0]) * self.sign, 360.0)
        rel = np.where(rel > 360.0 - 1e-9, 0.0, rel)
        working = rel < self.working_stroke_angle - 1e-9
        s, _ = self._f(phi) if kin is None else self._f.from_kin(kin)
        s0, s1 = self.s_extreme
        if self.kind == "rocker":
            mid = 0.5 * (s0 + s1)
            s = mid + (np.mod(s - mid + 180.0, 360.0) - 180.0)
        span = s1 - s0
        if abs(span) < 1e-300:
            srel = np.zeros_like(s)
        else:
            srel = np.where(working, (s - s0) / span, (s - s1) / (-span))
        srel = np.clip(srel, 0.0, 1.0) + 0.0
        return np.where(working, "working", "idle"), srel

    def to_dict(self) -> dict:
        return {"extreme": [float(x) for x in self.extreme], "s_extreme": [float(x) for x in self.s_extreme],
                "H": float(self.H), "working": self.working,
                "working_stroke_angle": float(self.working_stroke_angle)}


def _working_stroke(ext: list[tuple[float, float]], working: str, sign: float):
    """(start, end, working-stroke crank angle) from the extremes (phi, s) of a link."""
    i_min = min(range(len(ext)), key=lambda i: ext[i][1])
    i_max = max(range(len(ext)), key=lambda i: ext[i][1])
    start, end = (ext[i_min], ext[i_max]) if working == "forward" else (ext[i_max], ext[i_min])
    return start, end, float(np.mod((end[0] - start[0]) * sign, 360.0))


def link_stroke(mech: Mechanism, name: str, working: str, sign: float) -> Stroke | None:
    """The stroke of a link between its own extreme positions.

    Parameters
    ----------
    mech : Mechanism
        The mechanism.
    name : str
        The link.
    working : str
        ``forward`` (working toward the increasing coordinate) or ``backward``.
    sign : float
        +1 for a ccw crank, -1 for cw.

    Returns
    -------
    Stroke or None
        The extremes (crank angles, deg), the stroke H (m, or deg for a rocker) and the
        working sense; None when the link has no two extreme positions.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: extreme (dead) positions;
    docs/methods.md §2.
    """
    kind, f = _output_coordinate(mech, name)
    ext, _ = _extremes_and_rests(mech, f, kind, sign)
    if len(ext) < 2:
        return None
    start, end, wsa = _working_stroke(ext, working, sign)
    return Stroke(link=name, kind=kind, extreme=[start[0], end[0]], s_extreme=[start[1], end[1]],
                  working_stroke_angle=wsa, sign=sign, working=working, _f=f)


@dataclass
class PositionsResult:
    """The reported crank positions and the output's extreme positions, stroke and K."""

    phi: np.ndarray                  # reported crank angles, deg in [0, 360)
    index: np.ndarray                # position numbers
    kinds: list[str]                 # 'grid' | 'extra' | 'extreme' | 'added' per position
    phi0: float
    extreme: list[float] | None      # [start, end] of the working stroke, deg
    working_stroke_angle: float | None
    idle_stroke_angle: float | None
    K: float | None
    theta: float | None              # angle of overlap (180 (K-1)/(K+1)), deg
    output: str
    output_kind: str                 # 'slider' (s in m) | 'rocker' (angle in deg)
    H: float | None                  # stroke: m (slider) or deg (rocker)
    s_extreme: list[float] | None    # output coordinate at [start, end]
    count: int
    direction: str                   # 'ccw' | 'cw'
    sign: float
    working: str
    extreme_index: int | None = None  # index of the position at the end of the working stroke
    over: str = "cycle"              # 'cycle' | 'input_range' (the grid spread over a crank range)
    span: float | None = None        # the crank range, deg, signed (over 'input_range')
    rests: list = field(default_factory=list)   # [from, to] deg where the output stands still (rests())
    _f: object = field(default=None, repr=False)
    _mech: object = field(default=None, repr=False)
    _strokes: dict = field(default_factory=dict, repr=False)
    _phis: list | None = field(default=None, repr=False)     # the angles as added (before 360 -> 0)
    _roots: dict = field(default_factory=dict, repr=False)   # crank angles where a stroke reaches an s/H
    #                                                          (loads.switching), found once a task

    def with_added(self, extra_added) -> "PositionsResult":
        """These positions with the crank angles ``extra_added`` (deg, where a load
        switches) added as positions of kind 'added' (an angle within 1e-9 deg of a
        position is that position): what `find_positions` gives with ``extra_added``,
        without finding the extremes again."""
        phis = list(self._phis if self._phis is not None else self.phi)
        kinds = list(self.kinds)
        for a in extra_added:
            _add(phis, kinds, a, "added")
        return replace(self, phi=_phi_array(phis), index=np.arange(len(phis)), kinds=kinds, _phis=phis)

    def output_value(self, phi_deg) -> tuple[np.ndarray, np.ndarray]:
        """(s, ds/dphi) of the output at crank angles phi_deg (s: m or deg)."""
        return self._f(np.atleast_1d(np.asarray(phi_deg, float)))

    def output_stroke(self) -> Stroke:
        """The output link's stroke (positions.output, positions.working)."""
        if self.extreme is None:
            raise StageError("positions", Message("positions.fail.output_turns" if self.over == "cycle"
                                                  else "positions.fail.range_no_stroke", link=self.output))
        return Stroke(link=self.output, kind=self.output_kind, extreme=list(self.extreme),
                      s_extreme=list(self.s_extreme), working_stroke_angle=self.working_stroke_angle,
                      sign=self.sign, working=self.working, _f=self._f)

    def stroke_state(self, phi_deg, kin=None) -> tuple[np.ndarray, np.ndarray]:
        """For each crank angle: 'working' or 'idle', and s_rel in [0, 1], the output's
        displacement from the start of the current stroke relative to the stroke H.
        At the start extreme the working stroke applies, at the end extreme the idle.
        ``kin``: the kinematics already solved at these angles."""
        return self.output_stroke().stroke_state(phi_deg, kin)

    def stroke_for(self, name: str, working: str | None = None) -> Stroke:
        """The stroke of link ``name``: the output's own for the output link (unless
        another ``working`` sense is asked for); for any other link its own extreme
        positions and stroke, working in the sense ``working`` along its own coordinate
        (default: ``positions.working``), docs/methods.md §3.3."""
        working = working or self.working
        if name == self.output and working == self.working:
            return self.output_stroke()
        key = (name, working)
        if key not in self._strokes:
            st = link_stroke(self._mech, name, working, self.sign) if self._mech is not None else None
            if st is None:
                raise StageError("positions", Message("positions.fail.load_no_extremes", link=name))
            self._strokes[key] = st
        return self._strokes[key]

    def to_dict(self) -> dict:
        def f(x):
            return None if x is None else float(x)
        return {"phi0": float(self.phi0),
                "extreme": None if self.extreme is None else [float(x) for x in self.extreme],
                "working_stroke_angle": f(self.working_stroke_angle),
                "idle_stroke_angle": f(self.idle_stroke_angle),
                "K": f(self.K), "theta": f(self.theta), "output": self.output,
                "output_kind": self.output_kind, "H": f(self.H),
                "s_extreme": None if self.s_extreme is None else [float(x) for x in self.s_extreme],
                "count": int(self.count), "direction": self.direction,
                "phi": [float(x) for x in self.phi], "index": [int(i) for i in self.index],
                "kinds": list(self.kinds), "extreme_index": self.extreme_index,
                **({} if self.over == "cycle" else {"over": self.over, "span": float(self.span)})}


def _extremes(f, period=None, scan: dict | None = None, changes=()) -> list[tuple[float, float]]:
    """(phi, s) of every root of ds/dphi over [0, 360); ``period`` (a rocker: 360 deg)
    makes s continuous with the scan; ``scan`` (a dict) receives the scan's ``ds``; a root
    within AT_CHANGE_POINT of one of the ``changes`` (the change points' crank angles, deg)
    is that change point."""
    grid = np.arange(0.0, 360.0, SCAN_STEP)
    s, ds = f(grid)
    if scan is not None:
        scan["ds"] = np.asarray(ds, float)
    n = len(grid)
    out = []                       # (scan index, root), in the order of the scan
    lo, hi, at = [], [], []
    for k in range(n):
        fa, fb = ds[k], ds[(k + 1) % n]
        if fa == 0.0:
            out.append((k, grid[k]))
        elif fa * fb < 0:
            lo.append(grid[k])
            hi.append(grid[k] + SCAN_STEP)
            at.append(k)
    if lo:
        roots = _roots_in_brackets(f, np.array(lo), np.array(hi), ds_of=ds, grid=grid)
        out += [(k, float(r) % 360.0) for k, r in zip(at, roots)]
    out = [r for _, r in sorted(out, key=lambda kr: kr[0])]
    for i, r in enumerate(out):
        for c in changes:
            if abs(((r - c) + 180.0) % 360.0 - 180.0) <= AT_CHANGE_POINT:
                out[i] = float(c) % 360.0
    res = []
    for r in out:
        if all(abs(((r - q) + 180) % 360 - 180) > 1e-7 for q, _ in res):
            res.append([r, None])
    if res:
        vals = f(np.array([r for r, _ in res]))[0]
        for item, v in zip(res, vals):
            v = float(v)
            if period:
                near = float(s[int(round(item[0] / SCAN_STEP)) % n])
                v += period * round((near - v) / period)
            item[1] = v
    return [(r, v) for r, v in res]


def _extremes_and_rests(mech: Mechanism, f, kind: str, sign: float) -> tuple[list, list]:
    """(the extremes (phi, s) of the coordinate ``f`` of a link of ``kind`` over a turn, the
    intervals where it stands still): a root at a change point is the change point, and a rest
    gives one extreme (:func:`_one_per_rest`)."""
    period = 360.0 if kind == "rocker" else None
    scan: dict = {}
    changes = _change_angles(mech)
    ext = _extremes(f, period, scan, changes)
    still = rests(scan["ds"])
    if still:
        ext = _one_per_rest(ext, still, changes, sign, f, period)
    return ext, still


def _change_angles(mech: Mechanism) -> list[float]:
    """The crank angles (deg) of the linkage's change points (:mod:`.changepoints`, cached on
    its solver)."""
    from .changepoints import change_points
    from .solver import get_solver
    return [float(c.phi) for c in change_points(get_solver(mech))]


REST = 1e-9             # |ds/dphi| below this share of its largest: the output does not move


def _one_per_rest(ext: list[tuple[float, float]], still: list[list[float]], changes: list[float], sign: float,
                  f, period=None) -> list[tuple[float, float]]:
    """The extremes ``ext`` (:func:`_extremes`) with the roots inside each interval where the
    output stands still (``still``: :func:`rests`) -- the round-off of an analogue that is 0
    there, a different set on every machine -- replaced by one: where the crank brings the
    output to its rest (the interval's start for a ccw crank, its end for a cw one), at the
    change point there when one lies within a scan step of it (a slider-crank whose rod equals
    its crank: its slider reaches O at 90 deg and stays to 270).  ``period`` (a rocker: 360
    deg): its value continuous with those of the roots it replaces."""
    out = list(ext)
    for a, b in still:
        lo = a - 0.5 * SCAN_STEP
        span = (b - a if b - a >= 360.0 else (b - a) % 360.0) + SCAN_STEP      # [0, 360]: the whole turn
        inside = [(x, v) for x, v in out if (x - lo) % 360.0 <= span + 1e-9]
        out = [xv for xv in out if xv not in inside]
        edge = a if sign > 0 else b
        near = [c for c in changes if abs(((c - edge) + 180.0) % 360.0 - 180.0) <= SCAN_STEP + 1e-9]
        x = float(near[0]) % 360.0 if near else float(edge) % 360.0
        v = float(f(np.array([x]))[0][0])
        if period and inside:
            v += period * round((inside[0][1] - v) / period)
        out.append((x, v))
    return sorted(out)


def rests(ds: np.ndarray) -> list[list[float]]:
    """The crank-angle intervals [from, to] (deg, on the SCAN_STEP scan ``ds``) over which the
    output stands still -- ds/dphi below REST of its largest over 1 deg or more, as a slider-crank
    whose rod equals its crank on the branch folded at its change point, its slider at O from 90
    to 270 deg: its extreme positions there are no one angle."""
    ds = np.abs(np.asarray(ds, float))
    top = float(ds.max()) if ds.size else 0.0
    if not top > 0:
        return []
    still = ds <= REST * top
    if still.all():
        return [[0.0, 360.0]]
    n, out = len(still), []
    k0 = int(np.flatnonzero(~still)[0])                 # start the walk where it moves (wrap at 360)
    run = None
    for j in range(1, n + 1):
        k = (k0 + j) % n
        if still[k] and run is None:
            run = k
        elif not still[k] and run is not None:
            steps = (k - run) % n
            if steps * SCAN_STEP > 1.0:
                out.append([run * SCAN_STEP, ((k - 1) % n) * SCAN_STEP])
            run = None
    return sorted(out)


def _roots_in_brackets(f, a, b, *, ds_of, grid, maxiter: int = 100) -> np.ndarray:
    """The root of ds/dphi in each bracket [a_i, b_i] (deg, a sign change), all brackets
    at once (one kinematics call per step): Newton's method on ds with the exact second
    derivative, kept inside the bracket (a step that leaves it is a bisection), to XTOL
    deg; a bracket narrowed to XTOL gives its end with the smaller |ds|."""
    n = len(grid)
    fa = np.array([ds_of[int(round(x / SCAN_STEP)) % n] for x in a])
    fb = np.array([ds_of[int(round(x / SCAN_STEP)) % n] for x in b])
    x = a - fa * (b - a) / (fb - fa)                        # the secant point to start
    done = np.zeros(len(a), bool)
    rad = math.pi / 180.0
    for _ in range(maxiter):
        act = np.flatnonzero(~done)
        if not len(act):
            break
        _, g, dg = f(np.mod(x[act], 360.0), second=True)
        for j, i in enumerate(act):
            gi = float(g[j])
            if gi == 0.0:
                done[i] = True
                continue
            if (gi < 0) == (fa[i] < 0):
                a[i], fa[i] = x[i], gi
            else:
                b[i], fb[i] = x[i], gi
            step = gi / (float(dg[j]) * rad) if dg[j] != 0 else math.inf
            xn = x[i] - step
            if not (a[i] <= xn <= b[i]):
                xn = 0.5 * (a[i] + b[i])
                step = x[i] - xn
            if b[i] - a[i] <= XTOL:
                x[i] = a[i] if abs(fa[i]) < abs(fb[i]) else b[i]
                done[i] = True
                continue
            x[i] = xn
            if abs(step) <= XTOL:
                done[i] = True
    return x


def find_positions(mech: Mechanism, positions_section, sign: float, extra_added=(), *,
                   crank_range=None) -> PositionsResult:
    """The reported crank positions and the output's extreme positions.

    Parameters
    ----------
    mech : Mechanism
        The linkage.
    positions_section : PositionsSection or None
        The task's ``positions`` (``count``, ``zero``, ``output``, ``working``, ``extra``;
        None: the defaults).
    sign : float
        Sense of rotation of the crank, +1.0 ccw, -1.0 cw (``Drive.sign``).
    extra_added : sequence of float
        Crank angles (deg) the tool adds as positions (where a load switches).
    crank_range : CrankRange, optional
        The crank's working range when it does not turn fully (a function generator's
        input range, ``linkage.context.CrankRange``): ``count`` positions spread evenly
        from its start to its end (both included), position 0 at the start, then the
        ``extra`` angles; no extreme positions, stroke or K (they need a full turn).

    Returns
    -------
    PositionsResult
        ``phi`` (deg in [0, 360)), ``phi0``, ``extreme`` (deg), ``H`` (m, or deg for a
        rocker output), ``K``, ``theta`` (deg) and the stroke state of the output.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: extreme (dead) positions and the
    coefficient of the mean speed K = (180 + theta)/(180 - theta); module docstring.
    """
    from ..spec import PositionsSection
    sec = positions_section if positions_section is not None else PositionsSection()
    direction = "ccw" if sign > 0 else "cw"
    out_name = sec.output or mech.links[-1].name      # a name the task model checked
    kind, f = _output_coordinate(mech, out_name)
    if crank_range is not None:
        return _over_range(mech, sec, sign, crank_range, out_name, kind, f).with_added(extra_added)
    ext, still = _extremes_and_rests(mech, f, kind, sign)
    extreme = wsa = isa = K = theta = H = s_ext = None
    if len(ext) >= 2:
        start, end, wsa = _working_stroke(ext, sec.working, sign)
        extreme = [start[0], end[0]]
        s_ext = [start[1], end[1]]
        isa = 360.0 - wsa
        K = wsa / isa if isa > 0 else None
        theta = 180.0 * (K - 1) / (K + 1) if K is not None else None
        H = abs(end[1] - start[1])
    if sec.zero == "extreme":
        if extreme is None:
            raise StageError("positions", Message("positions.fail.no_zero", link=out_name))
        phi0 = extreme[0]
    else:
        phi0 = float(sec.zero) % 360.0
    count = int(sec.count)
    phis = [(phi0 + sign * k * 360.0 / count) % 360.0 for k in range(count)]
    kinds = ["grid"] * count
    extreme_index = None
    for a in sec.extra:
        phis.append(float(a) % 360.0)
        kinds.append("extra")
    if extreme is not None:
        extreme_index = _add(phis, kinds, extreme[1], "extreme")
    base = PositionsResult(phi=_phi_array(phis), index=np.arange(len(phis)), kinds=kinds, phi0=float(phi0),
                           extreme=extreme, working_stroke_angle=wsa, idle_stroke_angle=isa, K=K, theta=theta,
                           output=out_name, output_kind=kind, H=H, s_extreme=s_ext, count=count,
                           direction=direction, sign=sign, working=sec.working, extreme_index=extreme_index, _f=f,
                           _mech=mech, _phis=phis, rests=still)
    return base.with_added(extra_added) if len(extra_added) else base


def _over_range(mech, sec, sign, crank_range, out_name, kind, f) -> PositionsResult:
    """find_positions over a crank range: the grid from its start to its end, then the extras."""
    count = int(sec.count)
    phis = [float(a) % 360.0 for a in crank_range.angles(count)]
    kinds = ["grid"] * count
    for a in sec.extra:
        phis.append(float(a) % 360.0)
        kinds.append("extra")
    return PositionsResult(phi=_phi_array(phis), index=np.arange(len(phis)), kinds=kinds, phi0=phis[0],
                           extreme=None, working_stroke_angle=None, idle_stroke_angle=None, K=None, theta=None,
                           output=out_name, output_kind=kind, H=None, s_extreme=None, count=count,
                           direction="ccw" if sign > 0 else "cw", sign=sign, working=sec.working,
                           over="input_range", span=float(crank_range.span), _f=f, _mech=mech, _phis=phis)


def _add(phis: list, kinds: list, a, kd: str) -> int:
    """Add the crank angle ``a`` (deg) of kind ``kd`` to the positions unless one lies
    within 1e-9 deg of it; its index."""
    a = float(a) % 360.0
    if a >= 360.0 - 1e-12:
        a = 0.0
    for i, q in enumerate(phis):
        if abs(((a - q) + 180.0) % 360.0 - 180.0) <= 1e-9:
            return i
    phis.append(a)
    kinds.append(kd)
    return len(phis) - 1


def _phi_array(phis: list) -> np.ndarray:
    return np.array([0.0 if x >= 360.0 - 1e-12 else x for x in phis])


def stroke_warnings(pos: PositionsResult) -> list:
    """A warning where the output's strokes are not what they seem: it stands still over part of
    the turn (its extreme positions no one angle: ``positions.output_rests``), or the working
    stroke named is the quick one (``positions.quick_working``).

    Parameters
    ----------
    pos : PositionsResult
        The positions (``rests``, K and ``working``).

    Returns
    -------
    list
        The one warning that applies, else empty.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: the working stroke of a machine is its
    slow one, K = working / idle crank angle >= 1.
    """
    if pos.rests:           # its extreme positions no one angle: K and the strokes are one choice
        return [Message("positions.output_rests", link=pos.output, intervals=pos.rests,
                        extreme=pos.extreme or [])]
    if pos.K is None or pos.K >= 1.0 - 1e-9:
        return []
    slow = "backward" if pos.working == "forward" else "forward"
    # K as computed (results.json's data); the catalogue's spec `below1` shows it to three digits
    # or as many more as keep it below 1 (numfmt.below_one)
    return [Message("positions.quick_working", working=pos.working, link=pos.output, K=float(pos.K), slow=slow)]
