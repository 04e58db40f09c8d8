"""Report section 'kinetostatics' (docs/methods.md §3): conventions, the load diagrams with the
positions marked, tables of the balancing moment by the three methods, the reactions,
the loads of every position and the efficiency, M_b and the reactions over the cycle,
and for every position one page of drawings, one row per Assur group (from the last
group to the crank, as the groups are solved):

* left, the group detached from the mechanism, drawn to a length scale mu_l, with every
  load and the reactions of the removed links at their points of application (the
  arrows give direction and point, their length is not to scale);
* right, its force polygon to scale mu_F (N/mm): the vectors head to tail, loads first,
  then the reactions; it closes because the group is in equilibrium;
* last row, Zhukovsky's lever: the velocity plan turned by 90 deg with the loads moved
  parallel to themselves to the ends of the turned velocities, their arms h about the
  pole, and the balancing force P_b at the crank pin.

Force names as the course writes them (Popov & Timofeev; Frolov): R_ij reaction of
link i on link j, G_i weight, Phi_i inertia force, M_Phi_i moment of the inertia
couple, F_f (F_tr in ru and uk) friction.  Writes ``kinetostatics.csv`` beside the report.  Reads
numbers only from results.
"""
from __future__ import annotations

import functools
import math
import re

import numpy as np
from markupsafe import Markup, escape

from ... import locales
from ...numfmt import unit as spelt
from .. import figures
from ..context import values_of
from ..course import position_label
from ..svgdraw import Canvas

I18N = locales.table("kinetostatics", "words")

KIND_COLOR = {"resistance": "#c0392b", "driving": "#1e8449", "load": "#8e44ad", "gravity": "#6b7b7c",
              "inertia": "#1f5fbf", "friction": "#b9770e", "reaction": "#000", "balance": "#117a65"}
MAX_FIG_POSITIONS = 24       # pages of drawings for at most this many positions (time, size)
ROW_H = 72.0                 # mm: one row (a group's diagram + its polygon)
GROUP_W = 90.0               # mm: width of a group's diagram
CRANK_W = 50.0               # mm: the input link's diagram in the last row
FIG_W = 170.0                # mm
PAGE_H = 245.0               # mm of drawings per page at most


def _xy(d):
    return np.array([float(d["x"]), float(d["y"])])


def _links(results):
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
    if "\u0000" in name:                 # already split: 'M\0b' -> ('M', 'b')
        a, b = name.split("\u0000", 1)
        return a, b
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
    return [(c["name"], c["link"], float(c["M"]), c["kind"]) for c in e.get("couples", [])
            if c["link"] in group_names and c.get("M") is not None and abs(float(c["M"])) > 0]


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
    tips = np.cumsum([np.zeros(2)] + [F for _, F, _ in keep], axis=0)
    return keep, tips


# ----------------------------------------------------------------- drawing
def _arrow_len(F, Fmax):
    return _arrow_len_n(float(np.hypot(*F)), Fmax)


def _arrow_len_n(nF, Fmax):
    """_arrow_len of a force of norm nF."""
    return 5.5 + 7.5 * math.sqrt(min(nF / Fmax, 1.0)) if Fmax > 0 else 9.0


def _labels(cv, items, step, segments, avoid, lang, size=7.0, box=None, taken=None, halo=True, italic=True):
    """items: (anchor xy, preferred dir, name, color); each label a box clear of the others
    and of `taken` (a list, extended), inside box below its title; `segments`: a list, or
    figures.segment_set of it (shared by a panel's label calls)."""
    if not items:
        return
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
    for (a, d, name, col), (s, sub), (x, y) in zip(items, parts, pos):
        cv.text(x, y, s, size=size, color=col, italic=italic, sub=sub or None, halo=halo)


def _off(x, a, b) -> float:
    """The distance (mm) of the point x from the segment a-b."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    d = b - a
    t = min(1.0, max(0.0, float((x - a) @ d) / max(float(d @ d), 1e-12)))
    return float(np.hypot(*(a + t * d - x)))


def _fbd_panel(ctx, cv, box, kin_e, links, names, forces, couples, title, norms=None):
    """Free-body diagram of the links `names` inside box = (x0, y0, w, h) (mm); ``norms``:
    force_norms(forces) when already known."""
    x0, y0, w, h = box
    P = kin_e["points"]
    pts_names = [p for n in names for p in links[n]["points"] if p in P]
    xy = np.array([_xy(P[p]) for p in pts_names] + [f[1] for f in forces])
    lo, hi = xy.min(axis=0), xy.max(axis=0)
    span = np.maximum(hi - lo, 0.02)     # a group all in one point (a block on a block): at 20 mm
    m = 11.0 if w > 60 else 15.0                       # room for the arrows
    # a GOST 2.302 length scale (1:1, 1:2, 1:2.5, 1:4, 1:5, 1:10, ...), stated as μl in m/mm
    mu_l = figures.drawing_scale(1000.0 * max(span[0] / (w - 2 * m), span[1] / (h - TITLE_H - 2 * m), 1e-9))[0] \
        / 1000.0
    c_box = (lo + hi) / 2
    c_pan = np.array([x0 + w / 2, y0 + (h - TITLE_H) / 2])

    def M(p):
        return c_pan + (np.asarray(p, float) - c_box) / mu_l

    # the points and the forces' points on the paper at once (row by row what M gives)
    on_paper = c_pan + (xy - c_box) / mu_l
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
    for q in dict.fromkeys(map(tuple, on_paper[len(pts_names):].tolist())):
        q = np.array(q)
        if min(float(np.hypot(*(q - h))) for h in held) < 1.0 or any(_off(q, a, b) < 0.3 for a, b in drawn):
            continue
        ram = [c for c, u in axes if abs(float((q - c) @ np.array([-u[1], u[0]]))) < 0.3]
        near = ram[0] if ram else min(held, key=lambda h: float(np.hypot(*(q - h))))
        cv.line(near, q, "#000", 0.6, z=2)
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
    # in plain floats: the same operations, x and y apart, as on 2-vectors
    for (name, pt, F, kind), nF, (ax, ay) in zip(forces, norms, on_paper[len(pts_names):].tolist()):
        if nF <= 1e-9 * max(Fmax, 1e-300):
            continue
        ux, uy = float(F[0]) / nF, float(F[1]) / nF
        L = _arrow_len_n(nF, Fmax)
        bx, by = ax + ux * L, ay + uy * L
        col = KIND_COLOR.get(kind, "#000")
        cv.arrow((ax, ay), (bx, by), col, 0.45 if kind == "reaction" else 0.4, head=2.2, z=3)
        segs.append(((ax, ay), (bx, by)))
        arrows.append(((bx + ux * 0.6, by + uy * 0.6), (ux, uy), name, col))
    for name, link, Mv, kind in couples:
        lk = links.get(link)
        if lk is None:
            continue
        s = f"S{lk['index']}"
        c = M(_xy(P[s])) if s in P else M(np.mean([_xy(P[p]) for p in lk["points"] if p in P], axis=0))
        col = KIND_COLOR.get(kind, "#000")
        cv.moment(c, 3.2, Mv, col, 0.35, z=3)
        arrows.append((c + np.array([0.0, 4.2]), (0.0, 1.0), name, col))
    taken = _title(cv, box, title, f"μl = {mu_l:g} {ctx.t('kst.unit_l')}")
    # point letters (upright, grey, small) next to their points, then the force names
    segs = figures.segment_set(segs)
    _labels(cv, [(a, (-1.0, 1.0), p, col) for a, _, p, col in items], 1.6, segs, avoid, ctx.lang, size=6,
            box=box, taken=taken, halo=False, italic=False)
    _labels(cv, arrows, 2.6, segs, avoid, ctx.lang, box=box, taken=taken)
    return mu_l


TITLE_H = 11.0               # mm at the top of a panel: its title and scale


def _title(cv, box, title, scale) -> list:
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


def _polygon_panel(ctx, cv, box, forces, norms=None, out=None):
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
    segs = list(zip(Tl[:-1], Tl[1:]))
    items = []
    for (name, F, kind), (ax, ay), (bx, by), (dx, dy), L in zip(vecs, Tl[:-1], Tl[1:], d.tolist(), Ls):
        col = KIND_COLOR.get(kind, "#000")
        cv.arrow((ax, ay), (bx, by), col, 0.45, head=2.4, z=3)
        L = L or 1.0
        items.append((((ax + bx) / 2, (ay + by) / 2), (-dy / L, dx / L), name, col))
    cv.dot(T[0], 0.6, z=6)
    taken = _title(cv, box, ctx.t("kst.polygon"), f"μF = {mu_F:g} {ctx.t('kst.unit_F')}")
    _labels(cv, items, 2.8, segs, [T[0]], ctx.lang, box=box, taken=taken)
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


def _lever_extent(e, kin_e):
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


def lever_scale(e, kin_e, w: float | None = None, h: float | None = None) -> float:
    """The standard μv at which Zhukovsky's lever of a position is drawn in a box w x h
    mm (the report's, by default), the largest at which it fits; the worked section's
    lever is at the same."""
    w = FIG_W if w is None else w
    h = LEVER_H if h is None else h
    _, _, lo, hi = _lever_extent(e, kin_e)
    span = np.maximum(hi - lo, 1e-12)
    m = 10.0
    return figures.nice_scale(max(span[0] / (w - 2 * m), span[1] / (h - TITLE_H - LEVER_TEXT_H - 2 * m)))


def _lever_panel(ctx, cv, box, e, kin_e, pin, omega1, balance_kind):
    """Zhukovsky's lever: the velocity plan turned by +90 deg (ends rot90(v)/mu_v, mu_v
    lever_scale), the loads moved to the ends of the turned velocities with their arms
    about the pole, P_b at the crank pin; M_b below."""
    from ...plans import plan_label
    x0, y0, w, h = box
    P = kin_e["points"]
    text_h = LEVER_TEXT_H
    vel, loads, lo, hi = _lever_extent(e, kin_e)
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
    for f in loads:
        F = np.asarray(f["F"], float)
        q = end(np.array([-f["v"][1], f["v"][0]], float))
        nF = float(np.hypot(*F))
        u = F / nF
        col = KIND_COLOR.get(f["kind"], "#000")
        b = q + u * (5.0 + 6.0 * math.sqrt(nF / Fmax))
        cv.arrow(q, b, col, 0.4, head=1.9, z=3)
        segs.append((q, b))
        foot = q + u * float(np.dot(pole - q, u))      # arm h: pole to the line of action
        foot = _clip_to(pole, foot, (x0 + 2, y0 + 2, x0 + w - 2, y0 + h - TITLE_H))
        if float(np.hypot(*(foot - pole))) > 4.0:
            cv.line(pole, foot, col, 0.2, dash="0.8 0.6", z=1)
            cv.line(q, foot, col, 0.15, dash="0.3 0.6", z=1)     # the line of action up to the foot
            segs.append((pole, foot))
            d = foot - pole
            arms.append(((pole + foot) / 2, (-d[1], d[0]), "h\u0000" + "".join(label_parts(f["name"], ctx.lang)),
                         col))
        arrows.append((b + u * 0.6, tuple(u), f["name"], col))
    # the balancing force at the crank pin: its power P_b . v_A = M_b omega_1
    Mb = e.get("balancing_moment")
    if pin and pin in P and Mb is not None and balance_kind == "moment" and omega1:
        vA = np.array([float(P[pin]["vx"]), float(P[pin]["vy"])])
        if np.hypot(*vA) > 0 and Mb != 0:
            Pb = (float(Mb) * float(omega1) / float(vA @ vA)) * vA
            q = end(np.array([-vA[1], vA[0]]))
            u = Pb / np.hypot(*Pb)
            b = q + u * 10.0
            col = KIND_COLOR["balance"]
            cv.arrow(q, b, col, 0.5, head=2.2, z=3)
            segs.append((q, b))
            arrows.append((b + u * 0.6, tuple(u), "P\u0000b", col))
    cv.dot(pole, 0.7, z=6)
    taken = _title(cv, box, ctx.t("kst.lever"), f"μv = {mu_v:g} {ctx.t('kst.unit_v')}")
    # the balancing moment by the lever and by the groups
    if balance_kind == "moment":
        lines = [f"{ctx.t('kst.mb_lever')} = {ctx.fmt(e.get('zhukovsky_moment'), 5)} {ctx.t('kst.Nm')}",
                 f"{ctx.t('kst.mb_groups')} = {ctx.fmt(e.get('balancing_moment'), 5)} {ctx.t('kst.Nm')}"]
    else:
        lines = [f"{ctx.t('kst.fzh')} = {ctx.fmt(e.get('zhukovsky_force'), 5)}",
                 f"{ctx.t('kst.fb')} = {ctx.fmt(e.get('balancing_force'), 5)}"]
    if e.get("discrepancy") is not None:
        lines.append(f"Δ = {ctx.fmt(100.0 * e['discrepancy'], 2)} %")
    yy = y0 + text_h - 2.5
    for s in lines:
        cv.text(x0 + 1, yy, s, size=6.5, anchor="start")
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
    _labels(cv, letters, 1.8, segs, avoid, ctx.lang, size=5.5, box=box, taken=taken, halo=False)
    _labels(cv, arrows + arms, 2.6, segs, avoid, ctx.lang, size=6.5, box=box, taken=taken)
    return mu_v


def position_rows(ctx, e, kin_e, info, links):
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
            title = ctx.t("kst.crank_row", i=index_by_name[g[0]], name=g[0])
        else:
            title = ctx.t("kst.group_links", k=len(order) - 1 - k,
                          links=", ".join(str(index_by_name[n]) for n in g))
        rows.append((g, forces, couples, title))
    return rows


def drive_omega(geom, kin_e):
    """The angular velocity of the input link in one kinematics entry (None without it)."""
    if geom is None:
        return None
    dl = geom.link(geom.drive)
    if dl is not None and dl.name in kin_e["links"]:
        return kin_e["links"][dl.name].get("omega")
    return None


LEVER_H = 110.0              # mm: Zhukovsky's lever, a figure of its own under the groups


def position_figures(ctx, e, kin_e, info, links, pin=None, omega1=None):
    """The drawings of one position: a list of SVG strings (the groups, one page each at
    most, named groups-posNN; then Zhukovsky's lever over the whole width, lever-posNN),
    and the data drawn: [{'group': [...], 'mu_l', 'mu_F', 'tips' (mm), 'vectors'}] and,
    last, {'lever': mu_v}."""
    rows = position_rows(ctx, e, kin_e, info, links)
    figs, drawn = [], []
    start = 0
    n = len(rows)
    per_page = max(1, int(PAGE_H // ROW_H))
    while start < n:
        stop = min(n, start + per_page)
        H = (stop - start) * ROW_H
        cv = Canvas(FIG_W, H)
        for r in range(start, stop):
            y = H - (r - start + 1) * ROW_H
            if r > start:
                cv.line((0, y + ROW_H), (FIG_W, y + ROW_H), "#bbb", 0.2, z=0)
            g, forces, couples, title = rows[r]
            wd = CRANK_W if r == n - 1 else GROUP_W
            norms = force_norms(forces)
            mu_l = _fbd_panel(ctx, cv, (0, y, wd, ROW_H), kin_e, links, g, forces, couples, title, norms)
            vecs = []
            mu_F, T = _polygon_panel(ctx, cv, (wd + 1, y, FIG_W - wd - 1, ROW_H), forces, norms, vecs)
            drawn.append({"group": g, "mu_l": mu_l, "mu_F": mu_F, "tips": T, "vectors": vecs})
            cv.line((wd, y + 1), (wd, y + ROW_H - 1), "#bbb", 0.2, z=0)
        figs.append(figures.named(cv.to_svg(), figures.pos_name("groups", e["index"])))
        start = stop
    cv = Canvas(FIG_W, LEVER_H)
    mu_v = _lever_panel(ctx, cv, (0, 0, FIG_W, LEVER_H), e, kin_e, pin, omega1, info.get("balance_kind"))
    drawn.append({"lever": mu_v})
    figs.append(figures.named(cv.to_svg(), figures.pos_name("lever", e["index"])))
    return figs, drawn


# ----------------------------------------------------------------- graphs
def _diagrams_fig(ctx, info, entries, grid_n):
    ld = [d for d in info.get("load_diagrams", []) if d.get("type") == "force" and d.get("curve")]
    if not ld:
        return None
    from .. import figures
    from ..svgchart import subplots
    fig, axes = subplots(170, 55 * len(ld), nrows=len(ld), squeeze=False)
    marks = []
    strokes = _strokes(ctx.results.get("positions") or {})
    for ax, d in zip(axes[:, 0], ld):
        cur = d["curve"]
        # a stroke diagram's abscissa: the displacement s = (s/H)·H of its slider, in m
        H = strokes.get(d["link"], 1.0) if d["abscissa"] == "s" else 1.0
        ax.plot(np.asarray(cur["x"], float) * H, cur["value"], "k-", lw=1.0)
        xs, ys, labels = [], [], []
        for e in entries:
            dd = e.get("diagram", {}).get(d["name"])
            if not dd or dd.get("x") is None or not dd.get("active", True):
                continue
            xs.append(dd["x"] * H)
            val = dd.get("value")
            # the diagram value (magnitude for a stroke load, signed for a phi-diagram)
            ys.append(abs(val) if d["abscissa"] == "s" and d["kind"] in ("resistance", "driving") else val)
            labels.append(position_label(e, grid_n))       # an extra marked, as in the tables
        ax.plot(xs, ys, "o", ms=3.5, color="#c0392b")
        marks.append((ax, xs, ys, labels))
        ax.set_xlabel(ctx.t("kst.s_axis") if d["abscissa"] == "s" else ctx.t("kst.phi_axis"))
        ax.set_ylabel(ctx.t("kst.force_axis"))
        s, sub = label_parts(d["name"], ctx.lang)
        kind = ctx.t(f"kind.{d['kind']}") if d.get("kind") else ""
        stroke = ctx.t(f"stroke.{d['stroke']}") if d.get("stroke") else ""
        extra = ", ".join(x for x in (kind, stroke) if x and not x.startswith(("kind.", "stroke.")))
        ax.set_title(f"${s}_{{{sub}}}$: {d['link']}" + (f" ({extra})" if extra else ""), fontsize=8, loc="left")
        ax.grid(True, lw=0.3)
    figures.std_graph(fig, axes[:, 0], ctx.t("kin.mm"))          # μF
    for ax, d in zip(axes[:, 0], ld):                               # μs (μφ) of each abscissa, from 0
        sym, unit = ("s", ctx.t("kst.s_unit")) if d["abscissa"] == "s" else ("φ", "°")
        lo, hi = min(ax.dataLim.x0, 0.0), ax.dataLim.x1
        mu = figures.std_axis(ax, lo, hi, axis="x", pad=0.0)
        # the axis as long as the stroke at that μ (as drawn on a sheet), not the whole width
        p, fw = ax.get_position(), fig.get_figwidth() * 25.4
        need = (hi - lo) / mu * 1.03
        if need < p.width * fw:
            ax.set_position([p.x0, p.y0, need / fw, p.height])
        ax.set_xlim(0.0, need * mu if need < p.width * fw else float(np.ptp(ax.get_xlim())))
        ax.set_xlabel(f"{ax.get_xlabel()};  {figures.mu_text(sym, mu, unit, ctx.t('kin.mm'))}")
    # the position numbers next to their points, none over another (positions that fall on
    # one spot, e.g. s/H = 1 twice, side by side): placed in paper points once the layout is set
    for ax, xs, ys, labels in marks:
        fig_pt = ax.transData.transform(np.c_[xs, ys]) * 72.0 / fig.dpi if xs else []
        placed = []
        x_lo, y_lo = ax.bbox.x0 * 72.0 / fig.dpi, ax.bbox.y0 * 72.0 / fig.dpi
        x_hi, y_hi = ax.bbox.x1 * 72.0 / fig.dpi, ax.bbox.y1 * 72.0 / fig.dpi
        for (px, py), x, y, l in zip(fig_pt, xs, ys, labels):
            w, h = 6.5 * 0.62 * len(l) + 1.0, 7.5
            for dx, dy in sorted(((sx * (2 + 7.5 * i) - (w if sx < 0 else 0), dy) for i in range(10) for sx in (1, -1)
                                  for dy in (3, -10, 10, -17, 17, -24)), key=lambda o: math.hypot(*o)):
                b = (px + dx, py + dy, px + dx + w, py + dy + h)
                if b[0] >= x_lo and b[2] <= x_hi and b[1] >= y_lo and b[3] <= y_hi and not any(
                        b[0] < q[2] and q[0] < b[2] and b[1] < q[3] and q[1] < b[3] for q in placed):
                    break
            placed.append(b)
            ax.annotate(l, (x, y), fontsize=6.5, xytext=(dx, dy), textcoords="offset points", va="bottom")
    return ctx.svg(fig, "load-diagrams")


def _strokes(pos: dict) -> dict:
    """{slider link: its stroke H, m}: the output's and each loaded slider's own."""
    out = {name: float(st["H"]) for name, st in (pos.get("strokes") or {}).items() if st.get("H")}
    if pos.get("output") and pos.get("H"):
        out.setdefault(pos["output"], float(pos["H"]))
    return out


def _cycle_fig(ctx, entries, phi0, sign, info):
    rows = []
    for e in entries:
        q = ((e["phi"] - phi0) * sign) % 360.0
        rows.append((q, e))
    rows.sort(key=lambda r: r[0])
    if len(rows) < 2:
        return None
    if rows[0][0] < 1e-6:            # a periodic curve closes: the zero position again at 360°
        rows.append((360.0, rows[0][1]))
    key = "balancing_moment" if info["balance_kind"] == "moment" else "balancing_force"
    from .. import figures
    from ..svgchart import subplots
    fig, (a1, a2) = subplots(170, 120, nrows=2, sharex=True)
    q = [r[0] for r in rows]
    from ..course import COURSE_MAX
    dot = "" if len(rows) > COURSE_MAX else "."      # a fine grid: curves without a dot a position
    nan = math.nan                                   # (the lists below are a position each)
    a1.plot(q, [nan if (v := r[1][key]) is None else v for r in rows], f"k{dot}-")
    a1.set_ylabel(ctx.t("kst.moment_axis") if key == "balancing_moment" else ctx.t("kst.force_axis"))
    a1.grid(True, lw=0.3)
    a1.axhline(0, color="0.5", lw=0.5)
    a1.set_title("$M_b$" if key == "balancing_moment" else "$P_b$", fontsize=8)
    for j in info["joints"]:
        jk = j["key"]
        vals = [nan if (v := r[1]["reactions"][jk]["R"]) is None else v for r in rows]
        a2.plot(q, vals, f"{dot}-", label=f"$R_{{{j['key'][1:]}}}$", lw=0.8, ms=3)
    a2.legend(ncol=1, fontsize=6.5, loc="upper left", bbox_to_anchor=(1.01, 1.0), frameon=False)
    a2.set_ylabel("|R|, " + ctx.t("kst.N"))
    a2.set_xlabel(ctx.t("kst.rotation"))
    a2.set_xticks(np.arange(0, 361, 30))
    a2.set_xlim(0, 360)
    a2.grid(True, lw=0.3)
    fig.subplots_adjust(left=0.1, right=0.9, top=0.93, bottom=0.1, hspace=0.3)
    figures.std_graph(fig, (a1, a2), ctx.t("kin.mm"), x_axis=a2, tight=False)      # μM, μR, μφ
    return ctx.svg(fig, "balancing-cycle")


# ----------------------------------------------------------------- section
def build(ctx) -> str | None:
    entries = ctx.results.get("kinetostatics")
    info = ctx.results.get("kinetostatics_info")
    if not entries or not info:
        return None
    fmt = ctx.fmt
    lang = ctx.lang
    links = _links(ctx.results)
    kin = {k["index"]: k for k in ctx.results.get("kinematics") or []}
    pos = ctx.results.get("positions") or {}
    phi0 = float(pos.get("phi0") or 0.0)
    sign = 1.0 if pos.get("direction", "ccw") == "ccw" else -1.0
    force_bal = info["balance_kind"] == "force"
    # balancing moment table
    if force_bal:
        hdr = [ctx.t("kst.position"), "φ, °", ctx.t("kst.fb"), ctx.t("kst.fzh"), ctx.t("kst.fvp"),
               ctx.t("kst.fmx"), ctx.t("kst.disc")]
        keys = ("balancing_force", "zhukovsky_force", "virtual_power_force", "matrix_force")
    else:
        hdr = [ctx.t("kst.position"), "φ, °", ctx.t("kst.mb"), ctx.t("kst.zh"), ctx.t("kst.vp"), ctx.t("kst.mx"),
               ctx.t("kst.pb"), ctx.t("kst.disc")]
        keys = ("balancing_moment", "zhukovsky_moment", "virtual_power_moment", "matrix_moment", "balancing_force")
    has_eff = any(e.get("efficiency") is not None for e in entries)
    has_near = any(e.get("near_singular") for e in entries)
    if has_near:
        hdr.append(ctx.t("kst.near"))
    # a fine grid: tables and drawings of the course positions (report/course.py), CSV in full
    from ..course import course_entries, cycle_order, grid_count
    n_grid = grid_count(ctx.results, len(entries))
    # the tables and drawings in the order of the crank's turn, the extras marked
    shown = cycle_order(course_entries(entries, n_grid), phi0, sign)
    mb_rows = []
    csv_rows = []
    # the CSV row of every position (a fine grid has thousands) read by values_of
    values, xyr = values_of(keys + ("discrepancy", "efficiency")), values_of(("x", "y", "R"))
    jkeys = [j["key"] for j in info["joints"]]
    for e in shown:
        disc = None if e.get("discrepancy") is None else 100.0 * e["discrepancy"]
        row = [position_label(e, n_grid), ctx.fmt_fixed(e["phi"], 2)] + [fmt(e.get(k), 6) for k in keys] + [
            fmt(disc, 2)]
        if has_near:
            row.append("✓" if e.get("near_singular") else "")
        mb_rows.append(row)
    for e in entries:
        crow = [e["index"], e["phi"], *values(e)]
        reactions = e["reactions"]
        for k in jkeys:
            crow += xyr(reactions[k])
        csv_rows.append(crow)
    csv_hdr = ["index", "phi"] + list(keys) + ["discrepancy", "efficiency"]
    for j in info["joints"]:
        csv_hdr += [f"{j['key']}_x", f"{j['key']}_y", f"{j['key']}_R"]
    ctx.write_csv("kinetostatics.csv", csv_hdr, csv_rows)
    # reactions table
    r_hdr = [ctx.t("kst.position")] + [label_html(j["key"], lang) + Markup(f", {spelt('N', lang)}")
                                       if j["kind"] == "R" else
                                       label_html(j["key"], lang) + Markup(f": N, {spelt('N', lang)}; x, {spelt('m', lang)}")
                                       for j in info["joints"]]
    r_rows = []
    for e in shown:
        row = [position_label(e, n_grid)]
        for j in info["joints"]:
            r = e["reactions"][j["key"]]
            if j["kind"] == "P":
                off = r.get("offset")
                row.append(f"{fmt(r.get('N'), 5)}; {fmt(off, 3)}" if r.get("N") is not None else "—")
            else:
                row.append(fmt(r.get("R"), 5))
        r_rows.append(row)
    # friction table
    eff_rows = None
    if has_eff:
        eff_rows = [[position_label(e, n_grid), ctx.fmt_fixed(e["phi"], 2), fmt(e.get("friction_power"), 5),
                     fmt(e.get("driving_power"), 5), fmt(e.get("efficiency"), 4)] for e in shown]
    # loads of every position in one table: the varying loads by position, the constant ones below
    loads_hdr, loads_rows, const = _loads_table(ctx, shown, n_grid)
    # per position drawings
    from ...plans import crank_pin, geometry
    geom = geometry(ctx.results)
    geom_pin = crank_pin(geom) if geom is not None else None
    positions = []
    for e in shown[:MAX_FIG_POSITIONS]:
        if "loads" not in e or e["index"] not in kin:
            continue
        ke = kin[e["index"]]
        w1 = drive_omega(geom, ke)
        if e.get("balancing_moment") is None and e.get("balancing_force") is None:
            figs = []
        else:
            figs, _ = position_figures(ctx, e, ke, info, links, geom_pin, w1)
        positions.append({"index": position_label(e, n_grid), "phi": e["phi"], "figs": figs})
    sing = ctx.results.get("singular") or []
    bk = ctx.t("kst.bk_moment") if info["balance_kind"] == "moment" else ctx.t("kst.bk_force")
    return ctx.render("sections/kinetostatics.html.j2", info=info, mb_hdr=hdr, mb_rows=mb_rows,
                      r_hdr=r_hdr, r_rows=r_rows, eff_rows=eff_rows, positions=positions,
                      balance_text=f"{info['balance']} ({bk})",
                      loads_hdr=loads_hdr, loads_rows=loads_rows,
                      loads_note=Markup(escape(ctx.t("kst.loads_note", const="\u0001"))).replace(
                          "\u0001", const or "—"),
                      fbd_caption=ctx.t("kst.fbd_caption"),
                      fig_diagrams=_diagrams_fig(ctx, info, shown, n_grid),
                      fig_cycle=_cycle_fig(ctx, entries, phi0, sign, info),
                      singular=", ".join(ctx.fmt_fixed(s, 6) for s in sing),
                      extra_note=ctx.t("common.extra_note") if len(entries) > n_grid else None)


def _loads_table(ctx, entries, n_grid=None):
    """Header, rows (one per position) of the loads that vary, and the text of the
    constant ones ('G₁ = 14.72 N, ...')."""
    lang = ctx.lang
    with_loads = [e for e in entries if "loads" in e]
    if not with_loads:
        return None, None, ""
    fnames, cnames = [], []
    fval: dict[str, list] = {}
    cval: dict[str, list] = {}
    for e in with_loads:
        for f in e["loads"]:
            if f["name"] not in fval:
                fnames.append(f["name"])
                fval[f["name"]] = []
            fval[f["name"]].append(float(np.hypot(*f["F"])))
        for c in e.get("couples", []):
            if c["name"] not in cval:
                cnames.append(c["name"])
                cval[c["name"]] = []
            cval[c["name"]].append(None if c.get("M") is None else float(c["M"]))
    n = len(with_loads)

    def constant(vals):
        v = [x for x in vals if x is not None]
        return len(v) == n and (max(v) - min(v)) <= 1e-9 * max(1.0, max(abs(x) for x in v))

    const_parts, fcols, ccols = [], [], []
    N = spelt("N", lang)
    Nm = spelt("N*m", lang)
    for nm in fnames:
        if constant(fval[nm]):
            if fval[nm][0] > 0:
                const_parts.append(Markup(f"{label_html(nm, lang)} = {ctx.fmt(fval[nm][0], 5)} {N}"))
        else:
            fcols.append(nm)
    for nm in cnames:
        if constant(cval[nm]):
            if cval[nm][0]:
                const_parts.append(Markup(f"{label_html(nm, lang)} = {ctx.fmt(cval[nm][0], 5)} {Nm}"))
        else:
            ccols.append(nm)
    hdr = [ctx.t("kst.position"), "φ, °"] + [label_html(nm, lang) for nm in fcols] + \
        [label_html(nm, lang) for nm in ccols]
    rows = []
    for k, e in enumerate(with_loads):
        rows.append([e["index"] if n_grid is None else position_label(e, n_grid), ctx.fmt_fixed(e["phi"], 2)]
                    + [ctx.fmt(fval[nm][k], 4) for nm in fcols]
                    + [ctx.fmt(cval[nm][k], 4) for nm in ccols])
    return hdr, rows, Markup(", ").join(const_parts)
