"""Geometry of the mechanism as the results give it, and the velocity /
acceleration plans (pure numpy, from results only: drawn by the report and the sheets,
measured by the hand-method error, tmm_cli.graphical).

The plans are built from the results only (exact point velocities and
accelerations, link omega/epsilon), the way the course draws them
(Artobolevsky; Popov & Timofeev): every absolute vector starts at the pole
(p for velocities, pi for accelerations); for two points of a link the
relative vector joins the ends; the acceleration of the second point of a link
is split  a_Q = a_P + a^n_QP + a^t_QP  (a^n = omega^2 l along QP towards P,
a^t = epsilon x r_QP), and for a slider on a moving guide (a slotted link)
a_X = a_Y + a^k + a^r with the Coriolis term a^k = 2 omega_guide x v_XY,
drawn from the point known first (structure order) to the other one.
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass, field

import numpy as np

SUB = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")


def plan_label(name: str) -> str:
    """Point name -> plan letter: 'S2' -> 's₂', 'O1' -> 'o₁', 'B' -> 'b'; a point P is p′,
    p being the velocity plan's pole (the scotch yoke's P once took the pole's place, and
    every segment from p was measured from P's end).

    >>> plan_label("P"), plan_label("P2")
    ('p′', 'p₂')
    """
    m = re.match(r"^(.*?)(\d+)$", name)
    if m and m.group(1):
        return m.group(1).lower() + m.group(2).translate(SUB)
    return "p\u2032" if name == "P" else name.lower()


def sub_html(sym: str, sub: str) -> str:
    """``sym<sub>sub</sub>`` as HTML text; both parts (point names) are escaped."""
    from markupsafe import escape
    return f"{escape(sym)}<sub>{escape(sub)}</sub>"


@dataclass
class LinkG:
    """A link as the plans draw it: its structural points and kind."""

    name: str
    index: int
    points: list[str]          # structural points (pairs + extras), in task order
    kind: str                  # 'bar' | 'slider'
    com: str | None = None     # 'S<i>' when reported
    guide_link: str | None = None   # a slider's moving guide: the link its slot is on (a yoke's)


@dataclass
class JointG:
    """A pair as the plans draw it: R or P between links ``a`` and ``b``."""

    kind: str                  # 'R' | 'P'
    a: int
    b: int
    point: str | None


@dataclass
class Geometry:
    """The linkage as the plans read it: links, pairs, ground points and the order of attachment."""

    links: list[LinkG]
    joints: list[JointG]
    ground: set[str]
    order: dict[int, int] = field(default_factory=dict)   # link index -> attach order (ground -1)
    drive: int = 1

    def link(self, idx: int) -> LinkG | None:
        for l in self.links:
            if l.index == idx:
                return l
        return None

    def by_name(self, name: str) -> LinkG | None:
        for l in self.links:
            if l.name == name:
                return l
        return None


def geometry(results: dict) -> Geometry | None:
    """Links, pairs, ground points and the driving link from results['structure'] (its
    'links', 'joints', 'ground' and 'drive_link' keys); None without them: the report draws
    what the results hold."""
    st = results.get("structure") or {}
    if not st.get("links"):
        return None
    kin = results.get("kinematics") or []
    pts0 = kin[0]["points"] if kin else {}
    links: list[LinkG] = []
    joints: list[JointG] = []
    for l in sorted(st["links"], key=lambda l: l["index"]):
        links.append(LinkG(l["name"], int(l["index"]), [p for p in l.get("points", [])
                                                        if not re.fullmatch(r"S\d+", p)],
                           l.get("kind", "bar"), guide_link=(l.get("guide") or {}).get("link")))
    for j in st.get("joints") or []:
        joints.append(JointG(j.get("kind", "R"), int(j["a"]), int(j["b"]), j.get("point")))
    ground = {j.point for j in joints if j.kind == "R" and j.a == 0 and j.point}
    ground |= set(st.get("ground") or {})
    for l in links:
        s = f"S{l.index}"
        if s in pts0 and s not in l.points:
            # a centre of mass on a pair point (crank on its pivot, slider on its pin)
            # adds nothing to the plans: not shown
            c = (float(pts0[s]["x"]), float(pts0[s]["y"]))
            if not any(p in pts0 and math.hypot(c[0] - float(pts0[p]["x"]), c[1] - float(pts0[p]["y"]))
                       <= 1e-9 * (1.0 + math.hypot(*c)) for p in l.points):
                l.com = s
    # attach order from the Assur groups
    order = {0: -1}
    name_to_idx = {l.name: l.index for l in links}
    drive = name_to_idx.get(st.get("drive_link"), 1)
    order[drive] = 0
    for k, g in enumerate(st.get("groups") or [], start=1):
        for ln in g.get("links", []):
            idx = name_to_idx.get(ln, ln if isinstance(ln, int) else None)
            if idx is not None:
                order[int(idx)] = k
    for l in links:
        order.setdefault(l.index, 100 + l.index)
    return Geometry(links, joints, ground, order, drive)


# --------------------------------------------------------------- plan model
@dataclass
class Vec:
    """One segment of a plan: from ``start`` to ``end``, its quantity and magnitude (SI)."""

    start: str                 # label of the start point on the plan
    end: str                   # label of the end point
    kind: str                  # 'abs' | 'rel' | 'n' | 't' | 'k' | 'r'
    symbol: str                # HTML symbol of the quantity, e.g. 'v<sub>BA</sub>'
    value: float               # magnitude, SI


@dataclass
class Plan:
    """A velocity or acceleration plan: its scale, pole, the points (mm) and the segments."""

    kind: str                  # 'v' | 'a'
    mu: float                  # scale, (m/s)/mm or (m/s^2)/mm
    pole: str                  # 'p' | 'π'
    pts: dict[str, np.ndarray]  # label -> plan coordinates, mm
    vecs: list[Vec]
    # the quantities the plan needs that the position has not ('v B', 'ω rocker': null next to a
    # change point, no limit by continuity): then no plan (no point, no segment) is drawn
    undefined: tuple[str, ...] = ()

    def length_mm(self, v: Vec) -> float:
        return float(np.linalg.norm(self.pts[v.end] - self.pts[v.start]))

    def rows(self) -> list[tuple[str, str, float, float]]:
        """(symbol html, segment, length mm, value SI) for the segment table."""
        return [(v.symbol, f"{v.start}{v.end}", self.length_mm(v), v.value) for v in self.vecs]


def _xy(d: dict, kx: str, ky: str) -> np.ndarray:
    return np.array([float(d.get(kx) or 0.0), float(d.get(ky) or 0.0)])


def _cross(w: float, r: np.ndarray) -> np.ndarray:
    return w * np.array([-r[1], r[0]])


def _point_order(geom: Geometry, p: str, exclude: int) -> int:
    if p in geom.ground:
        return -1
    best = 10 ** 6
    for l in geom.links:
        if l.index != exclude and p in l.points:
            best = min(best, geom.order.get(l.index, 10 ** 5))
    return best


def _base_other(geom: Geometry, link: LinkG) -> tuple[str, str | None]:
    pts = link.points
    if len(pts) == 1:
        return pts[0], None
    base = min(pts, key=lambda p: (_point_order(geom, p, link.index), pts.index(p)))
    main = [p for p in pts[:2] if p != base]
    other = main[0] if main else next(p for p in pts if p != base)
    return base, other


def _guides(geom: Geometry):
    """(slider link, guide link, pin) for each slider on a moving guide."""
    out = []
    for j in geom.joints:
        if j.kind != "P" or j.a == 0:
            continue
        la, lb = geom.link(j.a), geom.link(j.b)
        if la is None or lb is None:
            continue
        if lb.kind == "slider":
            s, g = lb, la
        elif la.kind == "slider":
            s, g = la, lb
        else:
            continue
        out.append((s, g, s.points[0]))
    return out


def coincident_name(pin: str, guide: LinkG) -> str:
    return f"{pin}{guide.index}"


def undefined(kind: str, entry: dict, geom: Geometry) -> tuple[str, ...]:
    """The quantities of one kinematics entry that a plan of ``kind`` reads and the entry has
    null (a point's velocity or acceleration, a link's ω or ε: next to a change point, where
    they have no limit by continuity), named as the warnings name them ('v B', 'ω rocker').
    An acceleration plan reads the velocities too (the normal and Coriolis components)."""
    P, L = entry["points"], entry["links"]
    out: list[str] = []
    for k in ("v", "a") if kind == "a" else ("v",):
        for l in geom.links:
            for p in l.points + ([l.com] if l.com else []):
                name = f"{k} {p}"
                if p in P and p not in geom.ground and name not in out and \
                        (P[p].get(f"{k}x") is None or P[p].get(f"{k}y") is None):
                    out.append(name)
    for k, key in (("ω", "omega"), ("ε", "epsilon")) if kind == "a" else (("ω", "omega"),):
        out += [f"{k} {l.name}" for l in geom.links if l.name in L and L[l.name].get(key) is None]
    return tuple(out)


def build_plan(kind: str, entry: dict, geom: Geometry, mu: float) -> Plan:
    """The velocity ('v') or acceleration ('a') plan of one kinematics entry; at a position
    whose plan reads a null quantity (:func:`undefined`) an empty plan that says which: a
    null is never drawn as a zero."""
    P = entry["points"]
    L = entry["links"]
    pole = "p" if kind == "v" else "π"
    missing = undefined(kind, entry, geom)
    if missing:
        return Plan(kind, mu, pole, {pole: np.zeros(2)}, [], missing)
    vk = ("vx", "vy") if kind == "v" else ("ax", "ay")
    sym = "v" if kind == "v" else "a"
    pts: dict[str, np.ndarray] = {pole: np.zeros(2)}
    vecs: list[Vec] = []

    def lab(p):
        return pole if p in geom.ground else plan_label(p)

    def vec_of(p):
        return _xy(P[p], *vk)

    moving = []
    for l in geom.links:
        for p in l.points + ([l.com] if l.com else []):
            if p in P and p not in geom.ground and p not in moving:
                moving.append(p)
    # absolute vectors
    for p in moving:
        pts[lab(p)] = vec_of(p) / mu
        vecs.append(Vec(pole, lab(p), "abs", sub_html(sym, p), float(np.linalg.norm(vec_of(p)))))
    guides = _guides(geom)
    # coincident points on moving guides (A3: the guide's point under the pin)
    coinc = {}
    for s, g, pin in guides:
        if pin not in P or not g.points:
            continue
        gb = _base_other(geom, g)[0] if g.kind == "bar" else g.points[0]
        w = float(L[g.name]["omega"] or 0.0)
        e = float(L[g.name]["epsilon"] or 0.0)
        r = _xy(P[pin], "x", "y") - _xy(P[gb], "x", "y")
        v3 = _xy(P[gb], "vx", "vy") + _cross(w, r)
        a3 = _xy(P[gb], "ax", "ay") + _cross(e, r) - w * w * r
        cname = coincident_name(pin, g)
        coinc[cname] = (s, g, pin, gb, r, v3, a3, w, e)
        val = v3 if kind == "v" else a3
        pts[plan_label(cname)] = val / mu
        vecs.append(Vec(pole, plan_label(cname), "abs", sub_html(sym, cname), float(np.linalg.norm(val))))
    # relative vectors / components per bar link
    for l in geom.links:
        if l.kind != "bar" or len(l.points) < 2:
            continue
        base, other = _base_other(geom, l)
        w = float(L[l.name]["omega"] or 0.0)
        e = float(L[l.name]["epsilon"] or 0.0)
        rb = _xy(P[base], "x", "y")
        targets = [p for p in l.points if p != base]
        my_coinc = [c for c, d in coinc.items() if d[1].index == l.index]
        for q in targets:
            if q not in P:
                continue
            rel = vec_of(q) - vec_of(base)
            if kind == "v" or q != other or my_coinc:
                if base not in geom.ground:   # from a fixed point: the absolute vector itself
                    vecs.append(Vec(lab(base), lab(q), "rel", sub_html(sym, q + base),
                                    float(np.linalg.norm(rel))))
                continue
            # acceleration: n and t components of the main point
            r = _xy(P[q], "x", "y") - rb
            an = -w * w * r
            at = _cross(e, r)
            nlab = f"n{l.index}".translate(SUB)
            pts[nlab] = pts[lab(base)] + an / mu
            vecs.append(Vec(lab(base), nlab, "n", sub_html("a", f"{q}{base}") + "<sup>n</sup>",
                            float(np.linalg.norm(an))))
            vecs.append(Vec(nlab, lab(q), "t", sub_html("a", f"{q}{base}") + "<sup>τ</sup>",
                            float(np.linalg.norm(at))))
        if kind == "a":
            for cname in my_coinc:
                s, g, pin, gb, r, v3, a3, _, _ = coinc[cname]
                an = -w * w * r
                at = _cross(e, r)
                nlab = f"n{l.index}".translate(SUB)
                if nlab in pts:
                    nlab = nlab + "′"
                pts[nlab] = pts[lab(gb)] + an / mu
                c = plan_label(cname)
                vecs.append(Vec(lab(gb), nlab, "n", sub_html("a", f"{cname}{gb}") + "<sup>n</sup>",
                                float(np.linalg.norm(an))))
                vecs.append(Vec(nlab, c, "t", sub_html("a", f"{cname}{gb}") + "<sup>τ</sup>",
                                float(np.linalg.norm(at))))
    # pin <-> coincident point: relative (and Coriolis) along the guide
    for cname, (s, g, pin, gb, r, v3, a3, w, e) in coinc.items():
        # the point known first is the start: the pin when the link carrying it
        # (other than the slider) is attached before the guide
        pin_first = _point_order(geom, pin, s.index) < geom.order.get(g.index, 10 ** 5) or \
            _point_order(geom, pin, s.index) == -1
        pa_, ca_ = plan_label(pin), plan_label(cname)
        vpin, apin = _xy(P[pin], "vx", "vy"), _xy(P[pin], "ax", "ay")
        if pin_first:
            k_from, k_to = pin, cname
            vrel = v3 - vpin
            arel_total = a3 - apin
            start, end = pa_, ca_
        else:
            k_from, k_to = cname, pin
            vrel = vpin - v3
            arel_total = apin - a3
            start, end = ca_, pa_
        if kind == "v":
            vecs.append(Vec(start, end, "rel", sub_html("v", f"{k_to}{k_from}"),
                            float(np.linalg.norm(vrel))))
        else:
            ak = 2.0 * _cross(w, vrel)
            ar = arel_total - ak
            klab = "k" if "k" not in pts else f"k{g.index}".translate(SUB)
            pts[klab] = pts[start] + ak / mu
            vecs.append(Vec(start, klab, "k", sub_html("a", f"{k_to}{k_from}") + "<sup>k</sup>",
                            float(np.linalg.norm(ak))))
            vecs.append(Vec(klab, end, "r", sub_html("a", f"{k_to}{k_from}") + "<sup>r</sup>",
                            float(np.linalg.norm(ar))))
    return Plan(kind, mu, pole, pts, vecs)


def crank_pin(geom: Geometry) -> str | None:
    l = geom.link(geom.drive)
    if l is None:
        return None
    for p in l.points:
        if p not in geom.ground:
            return p
    return None


def scales(entries: list[dict], geom: Geometry, pa_mm: float = 100.0):
    """(mu_v, mu_a, v_A, a_A): nice scales so that pa, pi-a <= pa_mm.

    v_A, a_A: the largest crank-pin velocity/acceleration over the entries
    (constant for a crank at constant speed)."""
    from .scales import nice_scale
    pin = crank_pin(geom)
    if pin is None:
        return 1.0, 1.0, 0.0, 0.0
    vA = max(float(e["points"][pin].get("v") or 0.0) for e in entries)
    aA = max(float(e["points"][pin].get("a") or 0.0) for e in entries)
    return nice_scale(vA / pa_mm), nice_scale(aA / pa_mm), vA, aA
