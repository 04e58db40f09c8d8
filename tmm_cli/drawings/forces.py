"""The kinetostatics drawings the report and sheet 2 both draw (public: docs/ARCHITECTURE.md):
a structural group detached from the mechanism with its loads and reactions (group_panel),
its force polygon (polygon_panel), Zhukovsky's lever (lever_panel), the groups of a position
in the order they are solved (position_rows), and the names of the forces as the course
writes them (label_parts).  ``words``: what the drawings write (drawings.words.Words, or the
report's context: lang, t, fmt)."""
from __future__ import annotations

import functools
import math
import re

import numpy as np
from markupsafe import Markup, escape

from ..report import figures

KIND_COLOR = {"resistance": "#c0392b", "driving": "#1e8449", "load": "#8e44ad", "gravity": "#6b7b7c",
              "inertia": "#1f5fbf", "friction": "#b9770e", "reaction": "#000", "balance": "#117a65"}


def _xy(d):
    return np.array([float(d["x"]), float(d["y"])])


def links_by_name(results):
    st = results.get("structure") or {}
    return {l["name"]: l for l in st.get("links") or []}


# ----------------------------------------------------------------- names
@functools.lru_cache(maxsize=4096)
def label_parts(name: str, lang: str = "en") -> tuple[str, str]:
    """A load/reaction name of the results -> (symbol, subscript) (_label_parts), remembered
    (a report draws the same few dozen names over and over)."""
    return _label_parts(name, lang)


def _label_parts(name: str, lang: str = "en") -> tuple[str, str]:
    """A load/reaction name of the results -> (symbol, subscript) as the course
    writes it: 'R12' -> ('R', '12'); 'G2' -> ('G', '2'); 'Fi2' -> ('Φ', '2');
    'Mi2' -> ('M', 'Φ2'); 'Ff03' -> ('F', 'f03'), in ru and uk the subscript of friction of the
    words `kst.friction_sub`; 'F1' -> ('F', '1')."""
    from .. import locales
    if "\u0000" in name:                 # already split: 'M\0b' -> ('M', 'b')
        a, b = name.split("\u0000", 1)
        # the balancing moment and force: M_b, P_b, in ru and uk with the course's subscript
        from .words import balance_sub
        return a, (balance_sub(lang) if b == "b" else b)
    fr = locales.of("kinetostatics", "words", lang).get("kst.friction_sub", "f")
    m = re.fullmatch(r"(Fi|Mi|Ff|Mf|[A-Za-z])(\d+)", name)
    if not m:
        return name, ""
    head, num = m.groups()
    if head == "Fi":
        return "Φ", num
    if head == "Mi":
        return "M", "Φ" + num
    if head in ("Ff", "Mf"):
        return head[0], fr + num
    return head, num


def label_html(name: str, lang: str = "en") -> Markup:
    s, sub = label_parts(name, lang)
    return Markup(f"{escape(s)}<sub>{escape(sub)}</sub>") if sub else Markup(escape(s))


# ----------------------------------------------------------------- forces of a group
def group_forces(e: dict, info: dict, group_idx: set[int], index_by_name: dict, arm_link: int | None = None):
    """Forces on the links ``group_idx`` in position entry ``e``: their loads, then the
    reactions of the links outside the group (R_ji = -R_ij), then, for a balancing
    force on a slider of the group, P_b along its guide.  -> [(name, point (2,), F (2,), kind)]."""
    return [(name, np.array(pt, float), -np.array(F, float) if flip else np.array(F, float), kind)
            for name, pt, F, flip, kind in group_force_data(e, info, group_idx, index_by_name)]


def group_force_data(e: dict, info: dict, group_idx: set[int], index_by_name: dict):
    """group_forces' forces as the results give them (no arrays made):
    -> [(name, point, F (x, y), reversed: F acts as -F, kind)]."""
    out = []
    for f in e.get("loads", []):
        li = index_by_name.get(f["link"])
        if li in group_idx:
            out.append((f["name"], f["point"], f["F"], False, f["kind"]))
    for j in info["joints"]:
        a, b = j["a"], j["b"]
        if (a in group_idx) == (b in group_idx):
            continue
        r = e["reactions"][j["key"]]
        if r.get("x") is None:
            continue
        pt = r.get("point") or r.get("pin")
        if b in group_idx:
            out.append((f"R{a}{b}", pt, (r["x"], r["y"]), False, "reaction"))
        else:
            out.append((f"R{b}{a}", pt, (r["x"], r["y"]), True, "reaction"))
    return out


def group_couples(e: dict, group_names: set[str]):
    """The couples on the group's links to draw: none that is a round-off zero (an inertia couple
    at a dead centre, 1e-15 N*m, which the tables print as 0; results.reference's rule)."""
    from ..results import reference
    return [(c["name"], c["link"], float(c["M"]), c["kind"]) for c in e.get("couples", [])
            if c["link"] in group_names and c.get("M") is not None and reference(float(c["M"])) != 0.0]


def force_norms(forces) -> list[float]:
    """|F| of each force (name, point, F, kind): np.hypot of all at once (the same numbers
    as one by one)."""
    if not forces:
        return []
    return np.hypot(np.array([float(F[0]) for _, _, F, _ in forces]),
                    np.array([float(F[1]) for _, _, F, _ in forces])).tolist()


def polygon(forces, rel_tol: float = 1e-9, norms=None):
    """The force polygon: nonzero forces head to tail, loads first, then reactions.
    -> (vectors [(name, F, kind)], tips (k+1, 2)) in N; tips[-1] ~ 0 (equilibrium).
    ``norms``: force_norms(forces) when already known."""
    norms = force_norms(forces) if norms is None else norms
    Fmax = max(norms, default=0.0)
    keep = [(n, F, k) for (n, _, F, k), nF in zip(forces, norms) if nF > rel_tol * Fmax]
    keep.sort(key=lambda t: t[2] == "reaction")           # stable: loads, then reactions
    keep = apart_order(keep)
    tips = np.cumsum([np.zeros(2)] + [F for _, F, _ in keep], axis=0)
    return keep, tips


def _along(p, d, a, b, tol: float) -> bool:
    """Whether the segment a-b lies along the side p -> p + d: both its ends within ``tol`` of
    that side's line, sharing more than ``tol`` of its length."""
    L = math.hypot(d[0], d[1])
    if L <= 1e-300:
        return False
    ux, uy = d[0] / L, d[1] / L
    ra, rb = (a[0] - p[0], a[1] - p[1]), (b[0] - p[0], b[1] - p[1])
    if abs(ra[0] * uy - ra[1] * ux) > tol or abs(rb[0] * uy - rb[1] * ux) > tol:
        return False
    lo, hi = sorted((ra[0] * ux + ra[1] * uy, rb[0] * ux + rb[1] * uy))
    return min(hi, L) - max(lo, 0.0) > tol


def _covers(a, F, segs, tol: float) -> bool:
    """Whether the side a -> a + F and one of ``segs`` [(start, G)] lie along each other (the
    whole of one within ``tol`` of the other's line, sharing more than ``tol``: two parallel
    forces the other way round, a short side running back along a long one)."""
    b = (a[0] + F[0], a[1] + F[1])
    for p, G in segs:
        q = (p[0] + G[0], p[1] + G[1])
        if _along(p, G, a, b, tol) or _along(a, F, p, q, tol):
            return True
    return False


def _apart_search(order: list, at: tuple, segs: list, rest: list, Fs: list, loads: set, tol: float,
                  steps: list) -> list | None:
    """:func:`apart_order`'s search, depth first: ``order`` extended by the forces of ``rest``
    (loads first) so that no side lies along one drawn before (``segs``, from the point ``at``);
    None where none does or after ``steps`` = [steps taken, limit].  (A function of the module,
    not one nested in apart_order: a nested one that calls itself is a reference cycle.)"""
    if not rest:
        return order
    steps[0] += 1
    if steps[0] > steps[1]:
        return None
    pool = [i for i in rest if i in loads] or rest          # loads first
    for i in pool:
        F = Fs[i]
        if _covers(at, F, segs, tol):
            continue
        got = _apart_search(order + [i], (at[0] + F[0], at[1] + F[1]), segs + [(at, F)], [j for j in rest if j != i],
                            Fs, loads, tol, steps)
        if got is not None:
            return got
    return None


def apart_order(vecs, rel_tol: float = 0.01, limit: int = 4000) -> list:
    """The polygon's vectors [(name, F, kind)] in an order in which no side lies along another
    (two parallel forces one after the other the other way round -- a link's weight and its
    inertia force, a ram's load and its friction -- were drawn on top of each other, one name
    hiding the other): the given order where it draws every side apart, else the first order
    (loads before reactions, then in the given order) that does, found by a search of at most
    ``limit`` steps; when none is found, the given order.  The polygon closes in any order
    (the sum is the same); the course's books lay such forces one after another this way."""
    n = len(vecs)
    if n < 3:
        return list(vecs)
    Fs = [(float(F[0]), float(F[1])) for _, F, _ in vecs]
    tol = rel_tol * max(math.hypot(*F) for F in Fs)
    loads = [i for i in range(n) if vecs[i][2] != "reaction"]
    reactions = [i for i in range(n) if vecs[i][2] == "reaction"]
    got = _apart_search([], (0.0, 0.0), [], loads + reactions, Fs, set(loads), tol, [0, limit])
    if got is not None:
        return [vecs[i] for i in got]
    # no such order: the loads, then the reactions, each by their direction (forces in one
    # sense one after another) when that draws fewer sides along others; the sides that still
    # lie along others are drawn beside their place (polygon_panel)
    convex = [i for part in (loads, reactions) for i in sorted(part, key=lambda i: math.atan2(Fs[i][1], Fs[i][0]))]
    if covered([Fs[i] for i in convex], tol).count(True) < covered(Fs, tol).count(True):
        return [vecs[i] for i in convex]
    return list(vecs)


def covered(Fs, tol: float) -> list[bool]:
    """Which sides of the polygon drawn head to tail from the vectors Fs [(x, y)] lie along an
    earlier side (_covers)."""
    at, segs, out = (0.0, 0.0), [], []
    for F in Fs:
        F = (float(F[0]), float(F[1]))
        out.append(_covers(at, F, segs, tol))
        segs.append((at, F))
        at = (at[0] + F[0], at[1] + F[1])
    return out


# ----------------------------------------------------------------- drawing
def _arrow_len(F, Fmax):
    return _arrow_len_n(float(np.hypot(*F)), Fmax)


def _arrow_len_n(nF, Fmax):
    """_arrow_len of a force of norm nF."""
    return 5.5 + 7.5 * math.sqrt(min(nF / Fmax, 1.0)) if Fmax > 0 else 9.0


LEADER = 2.0          # mm: a label farther than this from its anchor is tied to it by a leader line


def _labels(cv, items, step, segments, avoid, lang, size=7.0, box=None, taken=None, halo=True, italic=True,
            leaders=False):
    """items: (anchor xy, preferred dir, name, color); each label a box clear of the others
    and of `taken` (a list, extended), inside box below its title; `segments`: a list, or
    figures.segment_set of it (shared by a panel's label calls).  leaders: a label the
    placer had to put farther than LEADER mm from its anchor gets a thin line, in its
    colour, from the anchor to its box (which force it names stays plain).  Returns the
    labels' boxes (x0, y0, x1, y1)."""
    if not items:
        return []
    parts = [label_parts(name, lang) for _, _, name, _ in items]
    fs = cv.font_mm(size)
    sizes = [figures.text_size(s, fs, sub) for s, sub in parts]
    bounds = None
    if box is not None:
        x0, y0, w, h = box
        bounds = (x0 + 0.5, y0 + 0.5, x0 + w - 0.5, y0 + h - TITLE_H + 1.0)
    pos = figures.place_labels([(a[0], a[1], d) for a, d, _, _ in items], 10 * step, avoid=avoid,
                               step=step, segments=segments, sizes=sizes,
                               taken=taken if taken is not None else [], bounds=bounds)
    out = []
    for (a, d, name, col), (s, sub), (x, y), (tw, th) in zip(items, parts, pos, sizes):
        cv.text(x, y, s, size=size, color=col, italic=italic, sub=sub or None, halo=halo)
        bx = (x - tw / 2, y - th / 2, x + tw / 2, y + th / 2)
        out.append(bx)
        if leaders:
            near = (min(max(float(a[0]), bx[0]), bx[2]), min(max(float(a[1]), bx[1]), bx[3]))
            if math.hypot(near[0] - float(a[0]), near[1] - float(a[1])) > LEADER:
                cv.line((float(a[0]), float(a[1])), near, col, 0.15, z=1)
    return out


def along_line(start, u, L: float, drawn: list, gap: float = 1.0):
    """The start of an arrow of length L along the unit vector u from `start`, moved along its
    own line of action off every arrow in ``drawn`` [(start, tip, u)] it would cover: after the
    tip of one in the same sense, to the start of one in the opposite sense (a force slides
    along its line of action: the same force on a rigid link).  Forces at one point along one
    line -- a ram's load, its friction and its inertia force -- were drawn on top of each
    other, their names stacked around one point."""
    s = np.asarray(start, float)
    u = np.asarray(u, float)
    for _ in range(4 * len(drawn) + 1):
        for p, q, v in drawn:
            c = float(u @ v)
            if abs(c) < math.cos(math.radians(5.0)):
                continue
            d = q - p
            n = np.array([-v[1], v[0]])
            if abs(float((s - p) @ n)) > 0.5:            # not on its line
                continue
            t0, t1 = float((s - p) @ v), float((s + u * L - p) @ v)
            lo, hi = min(t0, t1), max(t0, t1)
            if min(hi, float(d @ v)) - max(lo, 0.0) <= 0.5:   # the shafts share at most half a millimetre
                continue
            s = q + u * gap if c > 0 else p.copy()
            break
        else:
            return s
    return s


def _off(x, a, b) -> float:
    """The distance (mm) of the point x from the segment a-b."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    d = b - a
    t = min(1.0, max(0.0, float((x - a) @ d) / max(float(d @ d), 1e-12)))
    return float(np.hypot(*(a + t * d - x)))


def line_meet(c, u, a, b):
    """Where the line through ``c`` along the unit vector ``u`` meets the line ab (paper mm), or
    None when they are parallel."""
    c, u, a, b = (np.asarray(x, float) for x in (c, u, a, b))
    d = b - a
    den = u[0] * d[1] - u[1] * d[0]
    if abs(den) < 1e-9 * (float(np.hypot(*d)) or 1.0):
        return None
    w = a - c
    return c + (w[0] * d[1] - w[1] * d[0]) / den * u


def _slot(c, u, links, guide: dict, names, mp):
    """(foot, far end) on the paper of the slot a block at ``c`` (direction ``u``) slides in
    when its guide is a link of the group (a Scotch yoke's slot, a slotted lever drawn by its own
    bar already): from where the slot meets the owner's bar, through the block and 6 mm beyond
    it; None for a fixed guide, an owner outside the group or one with no bar drawn."""
    owner = guide.get("link")
    if owner is None or owner not in names:
        return None
    pts = [mp[p] for p in links[owner]["points"] if p in mp]
    if len(pts) < 2:
        return None
    foot = line_meet(c, u, pts[0], pts[1])     # None: the slot along the bar, the bar is the slot
    if foot is None:
        return None
    t = float((foot - np.asarray(c, float)) @ np.asarray(u, float))
    return foot, np.asarray(c, float) - np.sign(t or 1.0) * np.asarray(u, float) * 6.0


def group_panel(words, cv, box, kin_e, links, names, forces, couples, title, norms=None):
    """Free-body diagram of the links `names` inside box = (x0, y0, w, h) (mm); ``norms``:
    force_norms(forces) when already known."""
    x0, y0, w, h = box
    P = kin_e["points"]
    pts_names = [p for n in names for p in links[n]["points"] if p in P]
    xy = np.array([_xy(P[p]) for p in pts_names] + [f[1] for f in forces])
    far = _far(xy, len(pts_names), [_xy(P[f"S{links[n]['index']}"]) for n in names
                                    if f"S{links[n]['index']}" in P])
    m = 11.0 if w > 60 else 15.0                       # room for the arrows

    def scale(pts):
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        span = np.maximum(hi - lo, 0.02)     # a group all in one point (a block on a block): at 20 mm
        # a GOST 2.302 length scale (1:1, 1:2, 1:2.5, 1:4, 1:5, 1:10, ...), stated as μl in m/mm
        return figures.drawing_scale(1000.0 * max(span[0] / (w - 2 * m), span[1] / (h - TITLE_H - 2 * m),
                                                  1e-9))[0] / 1000.0, lo, hi
    bases = {k: _base(xy, far, k, names, links, kin_e, pts_names) for k in np.nonzero(far)[0].tolist()}
    ext = xy[~far]
    mu_l, lo, hi = scale(ext)
    for _ in range(3):           # room for the broken part: BROKEN mm towards each far point
        if not bases:
            break
        virt = [xy[b] + (xy[k] - xy[b]) / float(np.hypot(*(xy[k] - xy[b]))) * BROKEN * mu_l for k, b in bases.items()]
        ext = np.vstack([xy[~far]] + virt)
        mu_new, lo, hi = scale(ext)
        if mu_new == mu_l:
            break
        mu_l = mu_new
    c_box = (lo + hi) / 2
    c_pan = np.array([x0 + w / 2, y0 + (h - TITLE_H) / 2])

    def M(p):
        return c_pan + (np.asarray(p, float) - c_box) / mu_l

    # the points and the forces' points on the paper at once (row by row what M gives)
    on_paper = c_pan + (xy - c_box) / mu_l
    broken = {}                # a far point drawn nearer: {its place on the paper: its true place}
    for k, b in bases.items():
        near = on_paper[b]
        d = on_paper[k] - near
        L = float(np.hypot(*d))
        t = _room(near, d / L, (x0 + m, y0 + m, x0 + w - m, y0 + h - TITLE_H - m))
        if t < L:
            on_paper[k] = near + d / L * max(t, 12.0)
            broken[tuple(on_paper[k].tolist())] = xy[k]
    mp = dict(zip(pts_names, on_paper))
    segs, avoid = [], []
    axes = []                   # the sliders' blocks and directions
    for n in names:
        lk = links[n]
        ps = [p for p in lk["points"] if p in P]
        if lk["kind"] == "slider":
            if ps:
                ang = float(kin_e["links"][n]["angle"] or 0.0)
                c = mp[ps[0]]
                cv.block(c, ang, 8.0, 4.6, width=0.35, z=4)
                u = np.array([math.cos(math.radians(ang)), math.sin(math.radians(ang))])
                cv.line(c - u * 9, c + u * 9, "#777", 0.2, dash="2 0.6 0.4 0.6", z=1)
                segs.append((c - u * 4, c + u * 4))
                axes.append((c, u))
                for p in ps[1:]:                       # a slider carrying other points (a yoke)
                    q = mp[p]
                    cv.line(c, q, "#000", 0.6, z=2)
                    segs.append((c, q))
                    cv.circle(q, 0.8, width=0.3, z=5)
                    avoid.append(q)
                slot = _slot(c, u, links, lk.get("guide") or {}, names, mp)
                if slot is not None:                   # its guide a slot of a link of the group (the yoke's)
                    foot, far_end = slot
                    cv.line(foot, far_end, "#000", 0.6, z=2)
                    segs.append((foot, far_end))
            continue
        q = np.array([mp[p] for p in ps])
        if len(q) >= 3 and _area(q) > 1.0:
            order = np.argsort(np.arctan2(q[:, 1] - q[:, 1].mean(), q[:, 0] - q[:, 0].mean()))
            cv.polygon(q[order], "#e8e8e8", z=2, stroke="#000", width=0.5)
            segs.extend((q[order][k], q[order][(k + 1) % len(q)]) for k in range(len(q)))
        elif len(q) >= 2:
            d = q[1] - q[0]
            u = d / (np.hypot(*d) or 1.0)
            t = (q - q[0]) @ u
            a, b = q[0] + u * t.min(), q[0] + u * t.max()
            cv.line(a, b, "#000", 0.6, z=2)
            segs.append((a, b))
        for p in q:
            cv.circle(p, 0.8, width=0.3, z=5)
            avoid.append(p)
    # centres of mass
    held = [np.asarray(q, float) for q in mp.values()]
    for n in names:
        s = f"S{links[n]['index']}"
        if s in P and links[n]["kind"] != "slider":
            c = M(_xy(P[s]))
            cv.dot(c, 0.55, z=6)
            held.append(c)
    # a force at a point off the drawn links (a guide's reaction at its offset along a ram,
    # a tool's load below it): the link carried on to it -- a slider's ram along its axis
    # from the block, else from the nearest point -- so that every force acts on the group
    drawn = list(segs)
    lengths = []               # the true lengths of the parts drawn broken
    for q in dict.fromkeys(map(tuple, on_paper[len(pts_names):].tolist())):
        q = np.array(q)
        if min(float(np.hypot(*(q - h))) for h in held) < 1.0 or any(_off(q, a, b) < 0.3 for a, b in drawn):
            continue
        ram = [c for c, u in axes if abs(float((q - c) @ np.array([-u[1], u[0]]))) < 0.3]
        near = ram[0] if ram else min(held, key=lambda h: float(np.hypot(*(q - h))))
        true = broken.get(tuple(q.tolist()))
        if true is None:
            cv.line(near, q, "#000", 0.6, z=2)
        else:
            # drawn shorter than it is: a break on it (GOST 2.303), its true length beside
            d = (q - near) / float(np.hypot(*(q - near)))
            n_ = np.array([-d[1], d[0]])
            mid = (near + q) / 2
            cv.polyline([near, mid - d * 1.2, mid - d * 0.4 + n_ * 1.8, mid + d * 0.4 - n_ * 1.8, mid + d * 1.2, q],
                        "#000", 0.6, z=2)
            dist = float(np.hypot(*(true - (c_box + (near - c_pan) * mu_l))))
            lengths.append((mid + n_ * 2.5, tuple(n_), f"{words.fmt(dist, 3)} {words.t('kst.s_unit')}\u0000", "#000"))
        segs.append((near, q))
        drawn.append((near, q))
        held.append(q)
    # point names
    norms = force_norms(forces) if norms is None else norms
    Fmax = max(norms, default=0.0)
    items = []
    for p in dict.fromkeys(pts_names):
        items.append((mp[p], None, p, "#555"))
    arrows = []
    placed = []                 # (start, tip, u) of the arrows drawn: none covers another
    # in plain floats: the same operations, x and y apart, as on 2-vectors
    for (name, pt, F, kind), nF, (ax, ay) in zip(forces, norms, on_paper[len(pts_names):].tolist()):
        if nF <= 1e-9 * max(Fmax, 1e-300):
            continue
        ux, uy = float(F[0]) / nF, float(F[1]) / nF
        L = _arrow_len_n(nF, Fmax)
        q, b, name_at, name_u = _arrow_in((ax, ay), (ux, uy), L, placed, (x0, y0, x0 + w, y0 + h))
        (ax, ay), (bx, by) = q.tolist(), b.tolist()
        placed.append((np.array([ax, ay]), np.array([bx, by]), np.array([ux, uy])))
        col = KIND_COLOR.get(kind, "#000")
        cv.arrow((ax, ay), (bx, by), col, 0.45 if kind == "reaction" else 0.4, head=2.2, z=3)
        segs.append(((ax, ay), (bx, by)))
        arrows.append((tuple(name_at.tolist()), name_u, name, col))
    rings = []
    for name, link, Mv, kind in couples:
        lk = links.get(link)
        if lk is None:
            continue
        s = f"S{lk['index']}"
        c = M(_xy(P[s])) if s in P else M(np.mean([_xy(P[p]) for p in lk["points"] if p in P], axis=0))
        col = KIND_COLOR.get(kind, "#000")
        r = 3.2 + 1.4 * sum(1 for q in rings if float(np.hypot(*(q - c))) < 0.5)   # a couple more: a ring out
        rings.append(c)
        cv.moment(c, r, Mv, col, 0.35, z=3)
        arrows.append((c + np.array([0.0, r + 1.0]), (0.0, 1.0), name, col))
    taken = panel_title(cv, box, title, f"μl = {mu_l:g} {words.t('kst.unit_l')}")
    # point letters (upright, grey, small) next to their points, then the force names
    segs = figures.segment_set(segs)
    _labels(cv, [(a, (-1.0, 1.0), p, col) for a, _, p, col in items], 1.6, segs, avoid, words.lang, size=6,
            box=box, taken=taken, halo=False, italic=False)
    _labels(cv, arrows, 2.6, segs, avoid, words.lang, box=box, taken=taken, leaders=True)
    _labels(cv, lengths, 2.6, segs, avoid, words.lang, size=6, box=box, taken=taken, italic=False, leaders=True)
    return mu_l


BROKEN = 30.0         # mm: a part drawn broken (a far point of application) is drawn this long


def _base(xy, far, k: int, names, links, kin_e, pts_names) -> int:
    """The row of xy a far point k is drawn from: the block of the slider whose axis it is on
    (a guide's reaction on a ram), else the nearest point not far."""
    P = kin_e["points"]
    for n in names:
        ps = [p for p in links[n]["points"] if p in P]
        if links[n]["kind"] == "slider" and ps:
            a = math.radians(float(kin_e["links"][n]["angle"] or 0.0))
            b = _xy(P[ps[0]])
            if abs(float((xy[k] - b) @ np.array([-math.sin(a), math.cos(a)]))) <= 1e-6 * (1.0 + float(
                    np.hypot(*(xy[k] - b)))):
                return pts_names.index(ps[0])
    rows = np.nonzero(~far)[0]
    return int(rows[int(np.argmin(np.hypot(*(xy[rows] - xy[k]).T)))])


def _far(xy, n_pts: int, coms) -> np.ndarray:
    """Which rows of xy (the links' n_pts points, then the forces' points) are forces' points
    farther from the links (their points and centres of mass) than twice the links' size:
    a guide's reaction acting at x = M/N far along a ram.  The group is drawn at the scale of
    the rest, such a point nearer on a broken line (its true length written beside)."""
    far = np.zeros(len(xy), bool)
    core = np.array(list(xy[:n_pts]) + list(coms), float).reshape(-1, 2)
    if not len(core):
        return far
    lo, hi = core.min(axis=0), core.max(axis=0)
    reach = 2.0 * max(float(np.hypot(*(hi - lo))), 0.02)
    out = np.maximum(np.maximum(lo - xy[n_pts:], xy[n_pts:] - hi), 0.0)
    far[n_pts:] = np.hypot(out[:, 0], out[:, 1]) > reach
    return far


def _room(p, u, rect) -> float:
    """How far from p along the unit vector u the rectangle (x0, y0, x1, y1) goes on."""
    t = np.inf
    for i, (lo_, hi_) in enumerate(((rect[0], rect[2]), (rect[1], rect[3]))):
        if u[i] > 1e-12:
            t = min(t, (hi_ - p[i]) / u[i])
        elif u[i] < -1e-12:
            t = min(t, (lo_ - p[i]) / u[i])
    return max(float(t), 0.0)


TITLE_H = 11.0               # mm at the top of a panel: its title and scale


def panel_title(cv, box, title, scale) -> list:
    """The panel's title and scale at its top left; returns their boxes (the labels keep clear)."""
    text_size = figures.text_size
    x0, y0, w, h = box
    title = title[:1].upper() + title[1:]
    cv.text(x0 + 1.5, y0 + h - 3.2, title, size=7, anchor="start", bold=True)
    sym, rest = scale.split(" = ", 1)          # 'μF = 400 N/mm' -> μ with subscript F
    cv.text(x0 + 1.5, y0 + h - 7.2, sym[0], size=6.5, anchor="start", sub=sym[1:], after=f" = {rest}")
    out = []
    for s, yc, pt in ((title, h - 3.2, 7), (scale, h - 7.2, 6.5)):
        tw, th = text_size(s, cv.font_mm(pt))
        out.append((x0 + 1.5, y0 + yc - th / 2, x0 + 1.5 + tw, y0 + yc + th / 2))
    return out


def _area(q):
    x, y = q[:, 0], q[:, 1]
    return 0.5 * abs(float(np.dot(x, np.roll(y, 1)) - np.dot(y, np.roll(x, 1))))


SIDE_TOL = 0.5        # mm: a polygon's side this near along an earlier one is drawn beside it
SIDE_GAP = 1.4        # mm: ... this far to its left


def beside(T, tol: float = SIDE_TOL) -> list[int]:
    """How far (in SIDE_GAP) each side of the polygon through the drawn tips T (mm) is drawn
    beside its place: 0 for a side clear of the sides before it; one more than the farthest
    of those it lies along (parallel, on one line to ``tol`` mm, sharing more than ``tol`` mm)
    otherwise -- parallel forces no order draws apart (all loads along one line: a piston's
    weight, inertia force and gas force) stay side by side, every arrow and name seen."""
    out = []
    for k in range(len(T) - 1):
        a, b = T[k], T[k + 1]
        F = (b[0] - a[0], b[1] - a[1])
        lvl = 0
        if math.hypot(*F) > tol:
            for j in range(k):
                c, e = T[j], T[j + 1]
                if _covers(a, F, [(c, (e[0] - c[0], e[1] - c[1]))], tol):
                    lvl = max(lvl, out[j] + 1)
        out.append(lvl)
    return out


def polygon_panel(words, cv, box, forces, norms=None, out=None):
    """The force polygon to scale inside box; returns (mu_F, drawn tips in mm); ``norms``:
    force_norms(forces) when already known; ``out``: a list that gets the vectors drawn."""
    x0, y0, w, h = box
    vecs, tips = polygon(forces, norms=norms)
    if out is not None:
        out.extend(vecs)
    if not vecs:
        return None, None
    lo, hi = tips.min(axis=0), tips.max(axis=0)
    span = np.maximum(hi - lo, 1e-12)
    m = 8.0
    mu_F = figures.nice_scale(max(span[0] / (w - 2 * m), span[1] / (h - TITLE_H - 2 * m)))
    c = np.array([x0 + w / 2, y0 + (h - TITLE_H) / 2]) - (lo + hi) / 2 / mu_F
    T = c + tips / mu_F
    # the sides' lengths at once (np.hypot as one by one); in plain floats, x and y apart,
    # the same operations as on 2-vectors
    d = T[1:] - T[:-1]
    Ls = np.hypot(d[:, 0], d[:, 1]).tolist()
    Tl = T.tolist()
    shift = beside(Tl, SIDE_TOL)
    segs = []
    items = []
    for (name, F, kind), (ax, ay), (bx, by), (dx, dy), L, k in zip(vecs, Tl[:-1], Tl[1:], d.tolist(), Ls, shift):
        col = KIND_COLOR.get(kind, "#000")
        if k:                    # along an earlier side: drawn beside it, k * SIDE_GAP mm to its left
            nx, ny = -dy / (L or 1.0) * k * SIDE_GAP, dx / (L or 1.0) * k * SIDE_GAP
            ax, ay, bx, by = ax + nx, ay + ny, bx + nx, by + ny
            cv.line((ax - nx, ay - ny), (ax, ay), col, 0.15, dash="0.5 0.5", z=2)   # to its true ends
            cv.line((bx - nx, by - ny), (bx, by), col, 0.15, dash="0.5 0.5", z=2)
        segs.append(((ax, ay), (bx, by)))
        cv.arrow((ax, ay), (bx, by), col, 0.45, head=2.4, z=3)
        L = L or 1.0
        items.append((((ax + bx) / 2, (ay + by) / 2), (-dy / L, dx / L), name, col))
    cv.dot(T[0], 0.6, z=6)
    taken = panel_title(cv, box, words.t("kst.polygon"), f"μF = {mu_F:g} {words.t('kst.unit_F')}")
    _labels(cv, items, 2.8, segs, [T[0]], words.lang, box=box, taken=taken)
    return mu_F, T


def _clip_to(p, q, rect):
    """The point of the segment p -> q where it leaves rect (x0, y0, x1, y1), or q inside it."""
    d = q - p
    t = 1.0
    for i, (lo_, hi_) in enumerate(((rect[0], rect[2]), (rect[1], rect[3]))):
        if d[i] > 1e-12:
            t = min(t, (hi_ - p[i]) / d[i])
        elif d[i] < -1e-12:
            t = min(t, (lo_ - p[i]) / d[i])
    return p + max(t, 0.0) * d


def _point_name(kin_e, xy, tol=1e-9):
    for p, d in kin_e["points"].items():
        if math.hypot(float(d["x"]) - xy[0], float(d["y"]) - xy[1]) <= tol * (1 + math.hypot(*xy)):
            return p
    return None


LEVER_TEXT_H = 13.0          # mm: the lines of M_b under the lever
LEVER_STEP = 3.2             # mm: the placing step of the lever's force and arm names (wider than the
                             # groups' 2.6: more of them clear of the plan's rays and the arms)


def lever_extent(e, kin_e):
    """The turned velocities {point: rot90(v)}, the loads drawn, and the extent lo, hi
    (m/s) of the lever: the turned velocities, the pole and the feet of the arms near
    them."""
    P = kin_e["points"]
    vx = [float(d.get("vx") or 0.0) for d in P.values()]
    vy = [float(d.get("vy") or 0.0) for d in P.values()]
    moving = (np.hypot(np.array(vx), np.array(vy)) > 1e-12).tolist()      # (as one by one)
    vel = {p: np.array([-y, x]) for p, x, y, mv in zip(P, vx, vy, moving) if mv}    # turned by +90 deg
    loads = [f for f in e.get("loads", []) if float(np.hypot(*f["F"])) > 0]
    turned = list(vel.values()) + [np.array([-f["v"][1], f["v"][0]], float) for f in loads]
    # the feet of the arms h (the pole's projection on each line of action) stay inside too
    feet = []
    for f in loads:
        tv = np.array([-f["v"][1], f["v"][0]], float)
        u = np.asarray(f["F"], float) / float(np.hypot(*f["F"]))
        feet.append(tv - u * float(tv @ u))
    T = np.array(turned + [np.zeros(2)])
    lo, hi = T.min(axis=0), T.max(axis=0)
    span = np.maximum(hi - lo, 1e-12)
    # (a foot far outside the plan would shrink the lever: its arm is then drawn up to the edge)
    near = [q for q in feet if np.all(q >= lo - 0.5 * span) and np.all(q <= hi + 0.5 * span)]
    T = np.array(turned + near + [np.zeros(2)])
    return vel, loads, T.min(axis=0), T.max(axis=0)


def lever_scale(e, kin_e, w: float, h: float) -> float:
    """The standard μv at which Zhukovsky's lever of a position is drawn in a box w x h
    mm, the largest at which it fits."""
    _, _, lo, hi = lever_extent(e, kin_e)
    span = np.maximum(hi - lo, 1e-12)
    m = 10.0
    return figures.nice_scale(max(span[0] / (w - 2 * m), span[1] / (h - TITLE_H - LEVER_TEXT_H - 2 * m)))


def lever_height(e, kin_e, w: float, h_min: float, h_max: float) -> float:
    """The height (mm) of a lever panel w mm wide: h_min, or more -- up to h_max -- when the
    turned plan is tall (a shaper's, a press's: drawn 110 mm high, its forces' arrows and
    names swamped it): as high as the plan needs at the standard μv at which it fits in
    w x h_max."""
    _, _, lo, hi = lever_extent(e, kin_e)
    mu = lever_scale(e, kin_e, w, h_max)
    need = float(max(hi[1] - lo[1], 1e-12)) / mu + TITLE_H + LEVER_TEXT_H + 2 * 10.0
    return min(max(h_min, math.ceil(need)), h_max)


def _inside(p, box) -> bool:
    """Whether the point ``p`` lies in ``box`` = (x0, y0, x1, y1)."""
    return box[0] <= p[0] <= box[2] and box[1] <= p[1] <= box[3]


def _arrow_in(at, u, L: float, placed: list, box):
    """(start, tip, its name's anchor, the name's direction) of a force arrow of length L along
    ``u`` at the point ``at`` (:func:`along_line` off the arrows ``placed``): drawn from the
    point, or, where its tip would leave ``box`` (the figure's edge cut its head off), the
    other way along its line of action, its tip at the point and its name at its tail."""
    u = np.asarray(u, float)
    q = along_line(at, u, L, placed)
    b = q + u * L
    if _inside(b, box):
        return q, b, b + u * 0.6, tuple(u)
    r = along_line(np.asarray(at, float) - u * L, u, L, placed)
    if _inside(r, box) and _inside(r + u * L, box):
        return r, r + u * L, r - u * 0.6, tuple(-u)
    # pushed past the edge either way (off another arrow on its line): drawn from its place,
    # shortened until its tip is in (3 mm at the least)
    while L > 3.0 and not _inside(q + u * L, box):
        L -= 0.5
    return q, q + u * L, q + u * (L + 0.6), tuple(u)


def lever_panel(words, cv, box, e, kin_e, pin, omega1, balance_kind):
    """Zhukovsky's lever: the velocity plan turned by +90 deg (ends rot90(v)/mu_v, mu_v
    lever_scale), the loads moved to the ends of the turned velocities with their arms
    about the pole, P_b at the crank pin; M_b below."""
    from ..plans import plan_label
    x0, y0, w, h = box
    P = kin_e["points"]
    text_h = LEVER_TEXT_H
    vel, loads, lo, hi = lever_extent(e, kin_e)
    mu_v = lever_scale(e, kin_e, w, h)
    c = np.array([x0 + w / 2, y0 + text_h + (h - TITLE_H - text_h) / 2])
    pole = c - (lo + hi) / 2 / mu_v

    def end(tv):
        return pole + np.asarray(tv, float) / mu_v

    segs, avoid = [], [pole]
    ends = {}
    for p, tv in vel.items():
        q = end(tv)
        ends[p] = q
        cv.line(pole, q, "#9a9a9a", 0.3, z=1)
        segs.append((pole, q))
        cv.dot(q, 0.45, "#555", z=5)
    Fmax = max((float(np.hypot(*f["F"])) for f in loads), default=0.0)
    arrows, arms = [], []
    placed = []                 # (start, tip, u) of the arrows drawn: none covers another
    for f in loads:
        F = np.asarray(f["F"], float)
        q = end(np.array([-f["v"][1], f["v"][0]], float))
        if not any(_off(q, a, b) <= 0.3 for a, b in segs):
            # a point of no drawn ray (a crank's centre of mass beyond O, with its counterweight):
            # its own turned velocity ps, so that the force stands on the lever, not beside it
            cv.line(pole, q, "#9a9a9a", 0.3, z=1)
            segs.append((pole, q))
            cv.dot(q, 0.45, "#555", z=5)
            m = re.fullmatch(r"(?:Fi|G)(\d+)", str(f.get("name", "")))
            if m:                       # lettered as the plan's points: s1, the link's centre of mass
                ends.setdefault(f"S{m.group(1)}", q)
        nF = float(np.hypot(*F))
        u = F / nF
        col = KIND_COLOR.get(f["kind"], "#000")
        L = 5.0 + 6.0 * math.sqrt(nF / Fmax)
        q, b, name_at, name_u = _arrow_in(q, u, L, placed, (x0, y0, x0 + w, y0 + h))
        placed.append((q, b, u))
        cv.arrow(q, b, col, 0.4, head=1.9, z=3)
        segs.append((q, b))
        foot = q + u * float(np.dot(pole - q, u))      # arm h: pole to the line of action
        foot = _clip_to(pole, foot, (x0 + 2, y0 + 2, x0 + w - 2, y0 + h - TITLE_H))
        if float(np.hypot(*(foot - pole))) > 4.0:
            cv.line(pole, foot, col, 0.2, dash="0.8 0.6", z=1)
            cv.line(q, foot, col, 0.15, dash="0.3 0.6", z=1)     # the line of action up to the foot
            segs.append((pole, foot))
            d = foot - pole
            arms.append(((pole + foot) / 2, (-d[1], d[0]), "h\u0000" + "".join(label_parts(f["name"], words.lang)),
                         col, foot))
        arrows.append((name_at, name_u, f["name"], col))
    # the balancing force at the crank pin: its power P_b . v_A = M_b omega_1
    Mb = e.get("balancing_moment")
    if pin and pin in P and Mb is not None and balance_kind == "moment" and omega1:
        vA = np.array([float(P[pin]["vx"]), float(P[pin]["vy"])])
        if np.hypot(*vA) > 0 and Mb != 0:
            Pb = (float(Mb) * float(omega1) / float(vA @ vA)) * vA
            q = end(np.array([-vA[1], vA[0]]))
            u = Pb / np.hypot(*Pb)
            q, b, name_at, name_u = _arrow_in(q, u, 10.0, placed, (x0, y0, x0 + w, y0 + h))
            col = KIND_COLOR["balance"]
            cv.arrow(q, b, col, 0.5, head=2.2, z=3)
            segs.append((q, b))
            arrows.append((name_at, name_u, "P\u0000b", col))
    cv.dot(pole, 0.7, z=6)
    taken = panel_title(cv, box, words.t("kst.lever"), f"μv = {mu_v:g} {words.t('kst.unit_v')}")
    # the balancing moment by the lever and by the groups
    if balance_kind == "moment":
        lines = [f"{words.t('kst.mb_lever')} = {words.fmt(e.get('zhukovsky_moment'), 5)} {words.t('kst.Nm')}",
                 f"{words.t('kst.mb_groups')} = {words.fmt(e.get('balancing_moment'), 5)} {words.t('kst.Nm')}"]
    else:                    # the tables' 'P_b (groups), N': the unit after the value
        lines = []
        for key, v in (("kst.fzh", e.get("zhukovsky_force")), ("kst.fb", e.get("balancing_force"))):
            name, _, unit = words.t(key).rpartition(", ")
            lines.append(f"{name} = {words.fmt(v, 5)} {unit}" if name else f"{unit} = {words.fmt(v, 5)}")
    if e.get("discrepancy") is not None:
        lines.append(f"Δ = {words.fmt(100.0 * e['discrepancy'], 2)} %")
    yy = y0 + text_h - 2.5
    for s in lines:
        # 'M_b by the lever = ...': M with the subscript b (it was printed with its underscore)
        m = re.match(r"([A-Za-z])_([^\s(]+)(.*)", s)
        if m:
            cv.text(x0 + 1, yy, m.group(1), size=6.5, anchor="start", sub=m.group(2), after=m.group(3))
        else:
            cv.text(x0 + 1, yy, s, size=6.5, anchor="start")
        s = s.replace("_", "", 1) if m else s
        tw, th = figures.text_size(s, cv.font_mm(6.5))
        taken.append((x0 + 1, yy - th / 2, x0 + 1 + tw, yy + th / 2))
        yy -= 3.8
    # the pole, then the letters of the turned plan (merged where ends coincide), then the forces
    cv.text(pole[0] - 1.8, pole[1] - 1.8, "p", size=7, italic=True)
    tw, th = figures.text_size("p", cv.font_mm(7))
    taken.append((pole[0] - 1.8 - tw / 2, pole[1] - 1.8 - th / 2, pole[0] - 1.8 + tw / 2, pole[1] - 1.8 + th / 2))
    groups: list[tuple[np.ndarray, list[str], int]] = []
    if ends:                 # the ends' distances to each other (np.hypot of the differences, as one by one)
        e_xy = np.array(list(ends.values()))
        ex, ey = e_xy[:, 0], e_xy[:, 1]
        apart = np.hypot(ex[:, None] - ex, ey[:, None] - ey).tolist()
    for j, (p, q) in enumerate(ends.items()):
        for g in groups:
            if apart[g[2]][j] < 1.2:
                g[1].append(p)
                break
        else:
            groups.append((q, [p], j))
    letters = [(q, tuple(q - pole), ", ".join(plan_label(p) for p in names) + "\u0000", "#555")
               for q, names, _ in groups]
    segs = figures.segment_set(segs)
    _labels(cv, letters, 1.8, segs, avoid, words.lang, size=5.5, box=box, taken=taken, halo=False)
    _labels(cv, arrows + _arm_anchors(pole, merge_arms(arms)), LEVER_STEP, segs, avoid, words.lang, size=6.5, box=box, taken=taken,
            leaders=True)
    return mu_v


def merge_arms(arms) -> list:
    """Arms [(mid, d, name 'h\\0<sub>', colour, foot)] ending at one foot (within 0.3 mm: forces
    on one line of action, a link's weight and inertia force at one end of the turned plan)
    as one arm named once with all its forces, h with the subscript 'G3, Φ3, F1' -- as a
    lecturer names a shared arm; their names one by one had no room on it."""
    out: list[list] = []
    for mid, d, name, col, foot in arms:
        for a in out:
            if float(np.hypot(*(a[4] - foot))) < 0.3:
                a[2] = a[2] + ", " + name.split("\u0000", 1)[1]
                if a[3] != col:
                    a[3] = "#444"
                break
        else:
            out.append([mid, d, name, col, foot])
    return [tuple(a) for a in out]


def _arm_anchors(pole, arms) -> list:
    """The arms' label items: an arm's name at the middle of the part of it no shorter arm on
    the same ray from the pole covers (the weights' arms all lie on one horizontal line: their
    names were stacked about the middle of the shortest)."""
    out = []
    for k, (mid, d, name, col, foot) in enumerate(arms):
        r = foot - pole
        L = float(np.hypot(*r))
        u = r / L
        start = 0.0
        same = []                               # the arms ending at this one's foot (k among them)
        for j, (_, _, _, _, f2) in enumerate(arms):
            r2 = f2 - pole
            t = float(r2 @ u)
            if abs(float(r2 @ np.array([-u[1], u[0]]))) >= 0.3:
                continue
            if abs(t - L) <= 0.3:
                same.append(j)
            elif j != k and start < t < L - 0.3:
                start = t                       # the foot of a shorter arm on this one
        # arms with one foot (two forces on one line of action, at one end or at two) share
        # the part: each name at the middle of its own piece of it, in the order of the forces
        i, m = same.index(k), len(same)
        out.append([start + (L - start) * (i + 0.5) / m, u, L, d, name, col])
    # the names at least ARM_GAP apart where there is room (arms whose feet are a millimetre
    # apart, arms a few degrees apart, short arms about the pole), each on its own arm:
    # the shortest arms first, each at the place along it (0.5 mm from its ends) farthest, up
    # to ARM_GAP, from the names placed, the nearest such place to the middle of its own part
    chosen: list[np.ndarray] = []
    for a in sorted(out, key=lambda a: a[2]):
        want, u, L = a[0], a[1], a[2]
        ts = np.unique(np.clip(np.append(np.linspace(0.5, L - 0.5, 25), want), min(0.5, L / 2), max(L - 0.5, L / 2)))
        best = None
        for t in ts.tolist():
            q = pole + u * t
            room = min([float(np.hypot(*(q - c))) for c in chosen] + [ARM_GAP])
            key = (round(room, 6), -abs(t - want))
            if best is None or key > best[0]:
                best = (key, t)
        a[0] = best[1]
        chosen.append(pole + u * a[0])
    return [(pole + u * t, d, name, col) for t, u, L, d, name, col in out]


ARM_GAP = 4.0          # mm: the least distance between two arms' names along one ray of the lever


def position_rows(words, e, kin_e, info, links):
    """The groups of one position as they are solved, the last one first and the input
    link last: [(link names, forces, couples, title)] (shared by the report and sheet 2)."""
    index_by_name = {n: l["index"] for n, l in links.items()}
    groups = [list(g) for g in info["groups"]]
    order = list(reversed(groups[:-1])) + [groups[-1]]
    rows = []
    for k, g in enumerate(order):
        gi = {index_by_name[n] for n in g}
        forces = group_forces(e, info, gi, index_by_name)
        # a balancing force on a slider of this group (balance_kind == 'force')
        if info.get("balance_kind") == "force" and info.get("balance") in g and e.get("balancing_force") is not None:
            bl = links[info["balance"]]
            pnt = kin_e["points"][bl["points"][0]]
            ang = math.radians(float(kin_e["links"][bl["name"]]["angle"] or 0.0))
            Fb = float(e["balancing_force"]) * np.array([math.cos(ang), math.sin(ang)])
            forces.append(("P\u0000b", _xy(pnt), Fb, "balance"))
        couples = group_couples(e, set(g))
        if k == len(order) - 1 and info.get("balance_kind") == "moment" and e.get("balancing_moment") is not None:
            couples.append(("M\u0000b", g[0], float(e["balancing_moment"]), "balance"))
        if k == len(order) - 1:
            title = words.t("kst.crank_row", i=index_by_name[g[0]], name=g[0])
        else:
            title = words.t("kst.group_links", k=len(order) - 1 - k,
                          links=", ".join(str(index_by_name[n]) for n in g))
        rows.append((g, forces, couples, title))
    return rows
