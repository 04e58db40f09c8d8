"""The internal model of a planar linkage, built once from the task's `mechanism`.

Links are numbered 1..n in the order of the task file (ground = 0). Every point is
stored in the local frame of each link that carries it:

* bar ``points: [P, Q]``: origin at P, u-axis from P to Q, v to the left; ``extra``
  points are given in that frame;
* slider ``slider: P``: origin at its pin P, u-axis along its guide.

A point name shared by two links (or by a link and ``ground``) is a revolute pair;
a point shared by k bodies is a compound hinge of k - 1 pairs (each with the first
body). Each slider adds one prismatic pair with its guide's link (0 = a fixed guide).
A moving guide on link L is the line through L's origin along L's u-axis, turned by
``guide.angle`` and shifted by ``guide.offset`` to the left, so a slider can itself
carry a guide (RPP / PRP groups).
"""
from __future__ import annotations

import difflib
import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from ..limits import lookalike, script_note
from ..messages import Message
from .spec import MechanismSection

if TYPE_CHECKING:       # the type only: the task model imports no stage, no stage the task model
    from ..task import Task


@dataclass(frozen=True)
class Guide:
    """The line a slider translates along: fixed (a point and an angle) or on a guide link."""

    link: str | None                   # None: fixed (ground)
    point: tuple[float, float] | None  # fixed guide: a global point on the line
    angle: float                       # deg: absolute (fixed) or relative to the guide link's u-axis
    offset: float                      # m, moving guide: shift to the left of the link's u-axis


@dataclass(frozen=True)
class Link:
    """A moving link: a bar or a slider, its points in its own frame, its mass properties."""

    name: str
    index: int
    kind: str                                   # 'bar' | 'slider'
    local: dict[str, tuple[float, float]]       # points on the link, local frame
    mass: float
    J: float
    com: tuple[float, float]
    guide: Guide | None = None
    length: float | None = None

    @property
    def origin(self) -> str:
        return next(iter(self.local))


@dataclass(frozen=True)
class Joint:
    """A lower pair between links ``a`` < ``b`` (0 the ground): revolute (R) or prismatic (P)."""

    kind: str               # 'R' | 'P'
    a: int                  # link index, a < b, 0 = ground
    b: int
    point: str | None       # R: the shared point; P: None
    slider: int | None = None   # P: index of the slider (block)

    @property
    def name(self) -> str:
        return f"{self.kind}{self.a}{self.b}" + (f"({self.point})" if self.point else "")


@dataclass
class Mechanism:
    """The linkage the stages compute on: the ground points, the links, the pairs, the drive link."""

    ground: dict[str, tuple[float, float]]
    links: list[Link]
    joints: list[Joint]
    drive: int
    owner: dict[str, list[int]]
    assembly: dict[str, tuple[float, float]] = field(default_factory=dict)

    def link(self, key: str | int) -> Link:
        if isinstance(key, int):
            return self.links[key - 1]
        for lk in self.links:
            if lk.name == key:
                return lk
        raise KeyError(key)

    def index(self, name: str) -> int:
        return self.link(name).index

    @property
    def n(self) -> int:
        return len(self.links)

    @property
    def crank(self) -> Link:
        return self.links[self.drive - 1]

    @property
    def crank_pivot(self) -> str:
        """The crank's ground pivot."""
        return next(p for p in self.crank.local if 0 in self.owner.get(p, []))

    @property
    def crank_pin(self) -> str:
        """The point of the crank that defines its angle (the other end of the bar)."""
        piv = self.crank_pivot
        return next(p for p in self.crank.local if p != piv and p != f"S{self.drive}")

    @property
    def com_names(self) -> dict[int, str]:
        """Name under which each link's centre of mass is reported (S<i>)."""
        return {lk.index: f"S{lk.index}" for lk in self.links}

    def all_points(self) -> list[str]:
        names = list(self.ground)
        for lk in self.links:
            for p in lk.local:
                if p not in names:
                    names.append(p)
        for i, s in self.com_names.items():
            if s not in names:
                names.append(s)
        return names

    def structure_info(self) -> dict:
        """Links and pairs as plain data (a results.json extension for the report)."""
        return {
            "links": [{"name": lk.name, "index": lk.index, "kind": lk.kind,
                       "points": [p for p in lk.local], "com": f"S{lk.index}",
                       "mass": float(lk.mass), "J": float(lk.J),
                       "guide": (None if lk.guide is None else
                                 {"link": lk.guide.link, "angle": lk.guide.angle,
                                  "offset": lk.guide.offset,
                                  "point": list(lk.guide.point) if lk.guide.point else None})}
                      for lk in self.links],
            "joints": [{"kind": j.kind, "a": j.a, "b": j.b, "point": j.point, "slider": j.slider}
                       for j in self.joints],
            "ground": {k: list(v) for k, v in self.ground.items()},
            "drive_link": self.crank.name,
        }


def build_mechanism(task: Task) -> Mechanism:
    """The internal model of the task's ``mechanism``, its references checked.

    Parameters
    ----------
    task : Task
        The validated task (its ``mechanism`` section: ground points and links, m).

    Returns
    -------
    Mechanism
        The links numbered 1..n in the task's order, their pairs and points (m), the
        ground's pivots.

    Raises
    ------
    TaskError
        Inconsistent input (an unknown point or link, a broken guide), naming the field and
        its line.
    """
    sec: MechanismSection = task.mechanism
    assert sec is not None
    P = ("mechanism",)
    names = list(sec.links)
    index = {n: i + 1 for i, n in enumerate(names)}
    for g in sec.ground:
        if g in index:
            raise task.error(P + ("ground", g), Message("input.ground_is_link", name=g))
    owner: dict[str, list[int]] = {g: [0] for g in sec.ground}
    links: list[Link] = []
    # first pass: bars (their frames are known from lengths)
    for name, spec in sec.links.items():
        i = index[name]
        lp = P + ("links", name)
        if spec.kind == "bar":
            p, q = spec.points
            local = {p: (0.0, 0.0), q: (float(spec.length), 0.0)}
            for en, (u, v) in spec.extra.items():
                if en in local:
                    raise task.error(lp + ("extra", en), Message("input.extra_repeats", point=en))
                local[en] = (float(u), float(v))
        else:
            local = {spec.slider: (0.0, 0.0)}
            if spec.extra:
                for en, (u, v) in spec.extra.items():
                    local[en] = (float(u), float(v))
        for pt in local:
            owner.setdefault(pt, [])
            if i not in owner[pt]:
                owner[pt].append(i)
        links.append(Link(name=name, index=i, kind=spec.kind, local=local, mass=spec.mass, J=spec.J,
                          com=(0.0, 0.0), guide=None, length=spec.length))
    # points used by no link: most often a misspelt point of a link ('rocker: [O2, B]' with
    # the ground point O3): the link's line, its point and the ground point it resembles
    for g in sec.ground:
        if owner[g] == [0]:
            lone = [pt for pt, o in owner.items() if len(o) == 1 and o[0] != 0 and pt not in sec.ground
                    and sec.links[names[o[0] - 1]].kind == "bar" and pt in sec.links[names[o[0] - 1]].points]
            alike = [pt for pt in lone if lookalike(g, pt)]          # one typed with Cyrillic letters
            near = alike or difflib.get_close_matches(g, lone, n=1, cutoff=0.5)
            if near:
                link = names[owner[near[0]][0] - 1]
                raise task.error(P + ("links", link, "points"),
                                 Message("input.point_not_ground_script", point=near[0], link=link, ground=g,
                                         note=script_note(g, near[0])) if alike else
                                 Message("input.point_not_ground", point=near[0], link=link, ground=g))
            raise task.error(P + ("ground", g), Message("input.ground_unused", point=g))
    # drive link
    drive_name = task.drive.link
    if drive_name not in index:
        raise task.error(("drive", "link"), _unknown_link(drive_name, names))
    drive = index[drive_name]
    dspec = sec.links[drive_name]
    if dspec.kind != "bar":
        raise task.error(("drive", "link"), Message("input.drive_slider", link=drive_name))
    if not any(0 in owner[p] for p in dspec.points):
        raise task.error(("drive", "link"), Message("input.drive_no_pivot", link=drive_name, points=repr(dspec.points)))
    # second pass: sliders' guides, centres of mass
    final: list[Link] = []
    for lk in links:
        spec = sec.links[lk.name]
        lp = P + ("links", lk.name)
        guide = None
        if spec.kind == "slider":
            g = spec.guide
            if g.link is not None:
                if g.link not in index:
                    raise task.error(lp + ("guide", "link"), _unknown_link(g.link, names))
                if g.link == lk.name:
                    raise task.error(lp + ("guide", "link"), Message("input.slider_self"))
                guide = Guide(link=g.link, point=None, angle=float(g.angle or 0.0), offset=float(g.offset))
            else:
                if isinstance(g.through, str):
                    if g.through not in sec.ground:
                        raise task.error(lp + ("guide", "through"), Message("input.guide_through", point=g.through))
                    pt = sec.ground[g.through]
                else:
                    pt = g.through
                # `offset` shifts the line to the left of its direction (as on a moving guide):
                # the point it passes through moves by offset along the left normal (-sin a, cos a)
                a = math.radians(float(g.angle))
                off = float(g.offset)
                guide = Guide(link=None, point=(float(pt[0]) - off * math.sin(a), float(pt[1]) + off * math.cos(a)),
                              angle=float(g.angle), offset=0.0)
        # centre of mass
        if spec.com is None:
            if lk.index == drive:
                piv = next(p for p in lk.local if 0 in owner[p])
                com = lk.local[piv]
            elif spec.kind == "bar":
                com = (float(spec.length) / 2, 0.0)
            else:
                com = (0.0, 0.0)
        elif isinstance(spec.com, str):
            if spec.com not in lk.local:
                raise task.error(lp + ("com",), Message("input.com_point", point=spec.com, link=lk.name, points=list(lk.local)))
            com = lk.local[spec.com]
        else:
            com = (float(spec.com[0]), float(spec.com[1]))
        final.append(Link(name=lk.name, index=lk.index, kind=lk.kind, local=lk.local, mass=lk.mass, J=lk.J,
                          com=com, guide=guide, length=lk.length))
    links = final
    # joints
    joints: list[Joint] = []
    for pt, owners in owner.items():
        if len(owners) < 2:
            continue
        first = min(owners)
        for o in sorted(owners):
            if o != first:
                joints.append(Joint("R", first, o, pt))
    for lk in links:
        if lk.kind == "slider":
            gi = 0 if lk.guide.link is None else index[lk.guide.link]
            a, b = sorted((gi, lk.index))
            joints.append(Joint("P", a, b, None, slider=lk.index))
    # every moving link must be connected to something
    for lk in links:
        if not any(lk.index in (j.a, j.b) for j in joints):
            raise task.error(P + ("links", lk.name), Message("input.link_alone", link=lk.name))
    # a point named in assembly must exist
    for pt in sec.assembly:
        if pt not in owner:
            raise task.error(P + ("assembly", pt), Message("input.assembly_point", point=pt))
    # S<i>, the centre of mass of link i, is no user point's name: not another link's, nor
    # the link's own (its extra point S2 would vanish, the centre of mass reported in its place)
    for lk in links:
        s = f"S{lk.index}"
        if s in owner:
            where = next((P + ("links", sec_name, "extra", s) for sec_name, spec in sec.links.items()
                          if s in spec.extra), None)
            if where is None:
                where = P + (("ground", s) if s in sec.ground else ("links", lk.name))
            raise task.error(where, Message("input.reserved_point", point=s, index=lk.index))
    _check_references(task, names, owner, links)
    return Mechanism(ground={k: (float(v[0]), float(v[1])) for k, v in sec.ground.items()},
                     links=links, joints=joints, drive=drive, owner=owner,
                     assembly={k: (float(v[0]), float(v[1])) for k, v in sec.assembly.items()})


def _check_references(task: Task, names: list[str], owner: dict[str, list[int]], links: list[Link]) -> None:
    """Names used by the other linkage sections (positions, loads, kinetostatics) must
    exist: an unknown name is an invalid task (exit 2) found by `tmm validate` too, not a
    stage failure discovered in the middle of a run."""
    by_name = {lk.name: lk for lk in links}
    pos = task.positions
    if pos is not None and pos.output is not None and pos.output not in by_name:
        raise task.error(("positions", "output"), _unknown_link(pos.output, names))
    ks = task.kinetostatics
    if ks is not None:
        if ks.balance is not None and ks.balance not in by_name:
            raise task.error(("kinetostatics", "balance"), _unknown_link(ks.balance, names))
        if ks.motion is True and task.flywheel is None:
            raise task.error(("kinetostatics", "motion"), Message("input.motion_flywheel"))
    if task.loads is None:
        return
    points = set(owner) | {f"S{lk.index}" for lk in links}
    for k, sp in enumerate(task.loads.forces):
        fp = ("loads", "forces", k)
        lk = by_name.get(sp.on)
        if lk is None:
            raise task.error(fp + ("on",), _unknown_link(sp.on, names))
        if sp.moment is not None:
            continue
        if isinstance(sp.at, str) and sp.at not in points:
            raise task.error(fp + ("at",), Message("input.load_point", point=sp.at, link=lk.name, points=list(lk.local)))
        phi_diagram = sp.diagram is not None and sp.diagram.phi is not None
        if sp.direction is None and lk.kind != "slider" and (sp.kind is None or phi_diagram):
            raise task.error(fp, Message("input.force_direction", link=lk.name))


def _unknown_link(name: str, names: list[str]) -> str:
    import difflib
    alike = [n for n in names if lookalike(name, n)]          # one typed with Cyrillic letters
    if alike:
        return Message("input.no_link_script", name=name, hint=alike[0], note=script_note(name, alike[0]))
    close = difflib.get_close_matches(name, names, n=1)
    if close:
        return Message("input.no_link", name=name, hint=close[0])
    return Message("input.no_link_list", name=name, links=names)


def rotate(u: float, v: float, ang: float) -> tuple[float, float]:
    """Turn a plane vector.

    Parameters
    ----------
    u, v : float
        The vector's components.
    ang : float
        The angle, rad (ccw positive).

    Returns
    -------
    tuple of float
        The turned vector's components.
    """
    c, s = math.cos(ang), math.sin(ang)
    return (c * u - s * v, s * u + c * v)
