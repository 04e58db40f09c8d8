"""Sheet 1: the mechanism in its positions, the velocity and acceleration plans of the
course positions (drawn by the report's own plan code at the sheet's scale) and the
output's s, v, a diagrams."""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from .. import locales
from ..numfmt import format_text
from ..report.figures import mu_text, scale_mark
from .frame import FRAME, TB_W, length_scale, std_mu
from .graph import draw_graph

if TYPE_CHECKING:
    from ..task import Task

TXT = locales.table("sheets", "sheet1")
UNITS = locales.table("sheets", "sheet1_units")


def _xy(e, p):
    d = e["points"][p]
    return np.array([float(d["x"]), float(d["y"])])


def course_positions(results: dict) -> list[int]:
    """The positions whose plans go on the sheet: the most loaded position of the
    kinetostatics (largest |balancing moment|) and the first one computed; without
    kinetostatics the first position after the start."""
    kst = [k for k in results.get("kinetostatics") or [] if k.get("balancing_moment") is not None]
    kin = {e["index"] for e in results.get("kinematics") or []}
    out = []
    if kst:
        out.append(max(kst, key=lambda k: abs(float(k["balancing_moment"])))["index"])
        if kst[0]["index"] not in out:
            out.append(kst[0]["index"])
    else:
        out.append(1 if 1 in kin else min(kin))
    return [i for i in out if i in kin][:2]


def _known(e: dict, p: str) -> bool:
    """Whether the entry ``e`` holds the point ``p`` with numeric coordinates (not at a singular
    position's undefined ones)."""
    q = e["points"].get(p)
    return q is not None and q.get("x") is not None and q.get("y") is not None


def draw_mechanism(cv, geom, entries, course: list[int], box, lang="en", traced_over=None,
                   closed: bool = True) -> dict:
    """Every position thin, the course positions as contour lines, at a GOST scale
    fitting box = (x0, y0, w, h) mm, the trajectories of the points of the moving links (the
    coupler curves) through the positions `traced_over` (the grid; default all), and the crank
    pin's circle; ``closed=False`` (a linkage analysed over an input range): the trajectories
    open from the first position to the last and the pin's arc over the range only.
    Returns {'unit', 'scale', 'mu_l', 'paths'}."""
    from ..report.figures import place_labels
    x0, y0, w, h = box
    pts = np.array([_xy(e, p) for e in entries for p in e["points"]]) * 1000.0
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    span = np.maximum(hi - lo, 1.0)
    unit, label = length_scale(max(span[0] / (w - 30), span[1] / (h - 40)))
    c0 = np.array([x0 + w / 2, y0 + (h - 12) / 2]) - (lo + hi) / 2 / unit

    def M(p):
        return c0 + np.asarray(p, float) * 1000.0 / unit

    main = [e for e in entries if e["index"] in course] or entries[:1]
    grid = [e for e in entries if e not in main]
    segs = []
    for e in grid + main:
        thick = e in main
        cv.layer = "contour" if thick else "thin"
        for l in geom.links:
            if l.kind != "bar" or len(l.points) < 2:
                continue
            ps = [M(_xy(e, p)) for p in l.points if p in e["points"]]
            for q in ps[1:]:
                cv.line(ps[0], q, width=0.7 if thick else 0.2)
                if thick:
                    segs.append((ps[0], q))
            if len(ps) > 2:
                cv.line(ps[1], ps[2], width=0.7 if thick else 0.2)
        for l in geom.links:
            if l.kind == "slider" and l.points[0] in e["points"]:
                ang = float(e["links"][l.name]["angle"] or 0.0)
                c = M(_xy(e, l.points[0]))
                cv.block(c, ang, 10.0, 6.0, width=0.7 if thick else 0.2)
                for q in l.points[1:]:            # a slider carrying other points: its bar (a yoke's)
                    if q in e["points"]:
                        cv.line(c, M(_xy(e, q)), width=0.7 if thick else 0.2)
                        if thick:
                            segs.append((c, M(_xy(e, q))))
                owner = geom.by_name(l.guide_link) if l.guide_link else None
                if thick and owner is not None and owner.kind == "slider" and len(owner.points) > 1 \
                        and all(_known(e, q) for q in owner.points[:2]):
                    # the slot the block slides in, on the owner's bar (a Scotch yoke's): from the
                    # bar through the block and beyond it (a bar owner, a slotted lever, is its slot)
                    from ..drawings.forces import line_meet
                    u_ = np.array([math.cos(math.radians(ang)), math.sin(math.radians(ang))])
                    foot = line_meet(c, u_, M(_xy(e, owner.points[0])), M(_xy(e, owner.points[1])))
                    if foot is not None:
                        u = (c - foot) / (np.hypot(*(c - foot)) or 1.0)
                        cv.line(foot, c + u * 8.0, width=0.7)
                        segs.append((foot, c + u * 8.0))
        if thick:
            for p in e["points"]:
                if p not in geom.ground and not p.startswith("S"):
                    cv.circle(M(_xy(e, p)), 1.2, width=0.5)
    cv.layer = "contour"
    for g in sorted(geom.ground):
        if g in entries[0]["points"]:
            cv.ground(M(_xy(entries[0], g)), size=3.0, width=0.5)
            cv.circle(M(_xy(entries[0], g)), 1.2, width=0.5)
    # the trajectories (coupler curves): periodic splines through the grid positions, dashed;
    # the centres of mass' in blue
    from ..report.svgchart import spline_through
    from ..report.course import position_label
    over = traced_over if traced_over is not None else entries
    paths = {}
    from ..plans import crank_pin
    pin = crank_pin(geom)
    traced = [l.com for l in geom.links if l.com] + [q for l in geom.links if l.kind == "bar" for q in l.points]
    cv.layer = "thin"
    for q in dict.fromkeys(traced):
        if q in geom.ground or q == pin or len(over) < 3 or q not in over[0]["points"]:
            continue
        xy = np.array([M(_xy(e, q)) for e in over])
        if np.ptp(xy, axis=0).max() < 0.5:
            continue
        curve = spline_through(xy, closed, 24 * (len(xy) if closed else len(xy) - 1) + 1)
        cv.polyline(curve, color="#1f5fbf" if q.startswith("S") else "#000", width=0.25, dash="3 1.5")
        paths[q] = {"nodes": xy, "curve": curve}
    # guides of the sliders: dash-dot centre lines over the stroke (a fixed guide's: a moving
    # one, a yoke's slot, moves with its link and is drawn with it)
    cv.layer = "thin"
    for l in geom.links:
        if l.kind == "slider" and not l.guide_link:
            ps = np.array([M(_xy(e, l.points[0])) for e in entries])
            ang = math.radians(float(entries[0]["links"][l.name]["angle"] or 0.0))
            u = np.array([math.cos(ang), math.sin(ang)])
            t = (ps - ps[0]) @ u
            cv.line(ps[0] + u * (t.min() - 12), ps[0] + u * (t.max() + 12), width=0.2, dash="6 1.5 1 1.5")
    # the crank pin's circle, the position numbers and the direction of rotation
    from ..plans import crank_pin
    pin = crank_pin(geom)
    O = next((j.point for j in geom.joints if j.kind == "R" and j.a == 0 and j.b == geom.drive), None)
    labels_at, numbers = [], []
    if pin and O:
        Oc = M(_xy(entries[0], O))
        r = float(np.hypot(*(M(_xy(entries[0], pin)) - Oc)))
        if closed:
            cv.circle(Oc, r, fill=None, width=0.2)
        else:                   # the pin's arc over the range: its angles in the range's order, unwrapped
            d = np.array([M(_xy(e, pin)) - Oc for e in over])
            a = np.degrees(np.unwrap(np.arctan2(d[:, 1], d[:, 0])))
            cv.arc(Oc, r, float(a.min()), float(a.max()), width=0.2)
        cv.layer = "dimensions"
        cv.arc(Oc, 0.45 * r, 20.0, 120.0, width=0.35)
        a = math.radians(120.0)
        tip = Oc + 0.45 * r * np.array([math.cos(a), math.sin(a)])
        cv.arrow(tip - 0.01 * np.array([-math.sin(a), math.cos(a)]),
                 tip + 2.5 * np.array([-math.sin(a), math.cos(a)]), width=0.35, head=2.5)
        wq = Oc + 0.45 * r * 1.35 * np.array([math.cos(math.radians(70)), math.sin(math.radians(70))])
        cv.mtext(wq[0], wq[1], "ω", 3.5, anchor="middle", sub="1")
        labels_at.append(wq)
        numbers.append("ω1")
        on_block = any(l.kind == "slider" and l.points and l.points[0] == pin for l in geom.links)
        for e in entries:
            if e.get("index") is None or e["index"] > 11 and len(entries) > 12 and e["index"] not in course:
                continue
            d = M(_xy(e, pin)) - Oc
            d = d / (np.hypot(*d) or 1.0)
            s = position_label(e, len(over))          # an extra marked, as in the report's tables
            q = Oc + d * (r + (10.0 if on_block else 5.0))      # clear of a block at the pin
            # an extra position next to a grid one: its number further out
            while any(abs(q[0] - p[0]) < 0.3 * 3.5 * (len(s) + len(t)) + 0.5 and abs(q[1] - p[1]) < 4.0
                      for p, t in zip(labels_at, numbers)):
                q = q + d * 4.0
            labels_at.append(q)
            numbers.append(s)
            cv.mtext(q[0], q[1], s, 3.5, anchor="middle")
    # point names at the first course position
    e = main[0]
    names = [p for p in e["points"] if not p.startswith("S")]
    anchors = [(*M(_xy(e, p)), None) for p in names]
    pos = place_labels(anchors, 60.0, avoid=[a[:2] for a in anchors] + labels_at, step=5.0,
                       segments=[(a, b) for a, b in segs])
    for p, (x, y) in zip(names, pos):
        cv.mtext(x, y, p[0], 3.5, anchor="middle", italic=True, sub=p[1:] or None)
    cv.mtext(x0 + 2, y0 + h - 4, TXT[lang]["scheme"], 5.0, bold=True)
    mu_l = unit / 1000.0
    cv.mtext(x0 + 2, y0 + h - 11, "μ", 3.5, sub="l", after=f" = {mu_l:g} {UNITS[lang]['m']}/{TXT[lang]['mm']}"
             f"   ({scale_mark(lang)} {label})")
    return {"unit": unit, "scale": label, "mu_l": mu_l, "paths": paths}


PLAN_BOX_W, PLAN_BOX_H = 200.0, 140.0
TABLE_W = 46.0       # mm: an acceleration plan's segment table, right of the plan


def _plan_note(plan, lang: str) -> str | None:
    """What a plan the position cannot have says on the sheet (None for a drawable plan)."""
    return TXT[lang]["plan_undefined"].format(what=", ".join(plan.undefined)) if plan.undefined else None


def shown_index(e: dict, n_grid: int | None) -> str:
    """A position's number as the sheets and the report's tables write it: an extra position
    (index >= the grid's count) marked '13*' (the kinetostatics sheet's heading said
    'Position 13', the scheme '13*', the balancing hodograph '12')."""
    from ..report.course import position_label
    return position_label(e, n_grid) if n_grid else str(e["index"])


def draw_plans(cv, geom, entry, box, lang="en", kinds=("v", "a"), table_w: float = 0.0,
               n_grid: int | None = None) -> dict:
    """The velocity and acceleration plans (kinds) of one position side by side, each at a
    standard μ that fits its part of box at true size (the report's draw_plan); with table_w,
    each plan's segment table (segments.acceleration_table) in the right table_w mm of its part."""
    from ..plans import build_plan
    from ..drawings.plans import draw_plan
    from .segments import acceleration_table
    x0, y0, w, h = box
    T = TXT[lang]
    U = UNITS[lang]
    out = {}
    cv.layer = "thin"
    todo = [t for t in (("v", T["vplan"], T["unit_v"], U["m/s"]), ("a", T["aplan"], T["unit_a"], U["m/s²"]))
            if t[0] in kinds]
    for k, (kind, title, unit_txt, si) in enumerate(todo):
        bx = (x0 + k * w / len(todo), y0, w / len(todo) - 2 - table_w, h)
        p1 = build_plan(kind, entry, geom, 1.0)
        xy = np.array(list(p1.pts.values()))
        span = np.maximum(xy.max(axis=0) - xy.min(axis=0), 1e-12)
        mu = std_mu(max(span[0] / (bx[2] - 12.0), span[1] / (bx[3] - 30.0)))
        plan = build_plan(kind, entry, geom, mu)
        scale = draw_plan(cv, plan, bx, f"{title} ({T['pos']} {shown_index(entry, n_grid)})", unit_txt, si, T["mm"],
                          note=_plan_note(plan, lang))
        out[kind] = {"plan": plan, "mu": mu, "k": scale}
        if table_w and not plan.undefined:
            out[kind]["table"] = acceleration_table(cv, plan, scale, (bx[0] + bx[2] + 1.0, y0 + 3.0, table_w - 2.0,
                                                                     h - 4.0), lang, unit_txt)
            cv.layer = "thin"
    return out


def chord_derivative(phase_deg, y, omega: float, n: int = 12, per_deg: bool = False, span: float | None = None):
    """The course's check of a diagram by graphical differentiation, the chord method: y at
    n equal steps of the crank's turn (of the crank range ``span``, deg, when the positions
    are spread over one; interpolated on the exact curve), the slope of each chord times ω
    (the crank turns at ω) put at the middle of its interval.  per_deg: y in degrees (a
    rocker's ψ), the slope per radian.  Returns (middles, derivative values)."""
    whole = 360.0 if span is None else abs(span)
    q = np.linspace(0.0, whole, n + 1)
    yq = np.interp(q, phase_deg, y, period=360.0) if span is None else np.interp(q, phase_deg, y)
    scale = omega * (math.pi / 180.0 if per_deg else 1.0)
    return (q[:-1] + q[1:]) / 2, np.diff(yq) / math.radians(whole / n) * scale


def draw_velocity_plans(cv, geom, entries, box, lang="en", ncol: int = 4, n_grid: int | None = None) -> dict:
    """The velocity plans of the grid's positions (the course's 12) in a grid of cells of box,
    all at one standard μv, the smallest at which every plan fits its cell at true size."""
    from ..plans import build_plan
    from ..drawings.plans import draw_plan
    x0, y0, w, h = box
    T, U = TXT[lang], UNITS[lang]
    nrow = -(-len(entries) // ncol)
    cw, ch = w / ncol, h / nrow
    need = 0.0
    for e in entries:
        xy = np.array(list(build_plan("v", e, geom, 1.0).pts.values()))
        span = np.maximum(xy.max(axis=0) - xy.min(axis=0), 1e-12)
        need = max(need, span[0] / (cw - 2.0 - 12.0), span[1] / (ch - 30.0))
    mu = std_mu(need)
    cv.layer = "thin"
    out = {}
    for n, e in enumerate(entries):
        r, c = divmod(n, ncol)
        cell = (x0 + c * cw, y0 + h - (r + 1) * ch, cw - 2, ch)
        plan = build_plan("v", e, geom, mu)
        k = draw_plan(cv, plan, cell, f"{T['vplan']} ({T['pos']} {shown_index(e, n_grid)})", T["unit_v"], U["m/s"],
                      T["mm"],
                      note=_plan_note(plan, lang))
        out[e["index"]] = {"plan": plan, "mu": mu, "k": k, "box": cell}
    return out


def draw_diagrams(cv, results, geom, box, lang="en") -> dict:
    """The output's s, v, a (or ψ, ω, ε) over the crank turn from the start position,
    each at a standard μ; the φ axis at μφ = 1 °/mm (360 mm)."""
    x0, y0, w, h = box
    kc = results.get("kinematics_curve") or {}
    pos = results.get("positions") or {}
    if not kc.get("phi"):
        return {}
    phi0 = float(pos.get("phi0", 0.0))
    sgn = -1.0 if pos.get("direction") == "cw" else 1.0
    span = pos.get("span") if pos.get("over") == "input_range" else None
    if span is not None:        # over the input range: its own sense, from its start
        sgn = 1.0 if span >= 0 else -1.0
    phase = (np.asarray(kc["phi"], float) - phi0) * sgn % 360.0
    o = np.argsort(phase, kind="stable")
    phase = phase[o]
    U = UNITS[lang]
    slider = kc.get("quantity") == "slider"
    keys = (("s", "s", U["m"]), ("v", "v", U["m/s"]), ("a", "a", U["m/s²"])) if slider else \
        (("s", "ψ", U["deg"]), ("v", "ω", U["rad/s"]), ("a", "ε", U["rad/s²"]))
    mu_phi = 1.0 if span is None else std_mu(abs(span) / 360.0)
    n_ch = 12 if span is None else max(int(pos.get("count") or 12) - 1, 1)
    ticks = [(30.0 * i, str(i) if i < 12 else "") for i in range(13)] if span is None else \
        [(abs(span) * i / n_ch, str(i)) for i in range(n_ch + 1)]
    rowh = (h - 10.0) / 3
    # the crank's steady ω
    omega = abs(float(results["drive"]["omega"])) if results.get("kinematics") and results.get("drive") else 0.0
    out = {}
    cv.mtext(x0 + 2, y0 + h - 4, TXT[lang]["diagrams"], 5.0, bold=True)
    for k, (key, sym, unit) in enumerate(keys):
        y = np.asarray(kc[key], float)[o]
        ym = float(np.nanmax(np.abs(y))) or 1.0
        mu = std_mu(ym / (rowh / 2 - 8.0))
        ax0 = x0 + 14.0
        yc = y0 + h - 10.0 - rowh * (k + 0.5)
        mm = TXT[lang]["mm"]
        pts, = draw_graph(cv, (ax0, yc), [(phase, y, "#1f5fbf")], mu_phi, mu,
                          x_len=(360.0 if span is None else abs(span)) / mu_phi,
                          y_up=rowh / 2 - 3, y_down=rowh / 2 - 3, x_sym="φ", y_sym=sym,
                          mu_text=f"{mu_text(sym, mu, unit, mm)},  μφ = {mu_phi:g} °/{mm}",
                          ticks=ticks)
        good = np.isfinite(y)
        out[key] = {"mu": mu, "pts": pts, "values": y[good]}
        prev = {"v": "s", "a": "v"}.get(key)
        if prev and omega and np.isfinite(out.get(prev, {}).get("raw", y)).all():
            # the chord method on the diagram above: dashed, with its deviation from this exact curve
            mids, d = chord_derivative(phase, out[prev]["raw"], omega, n=n_ch, per_deg=(prev == "s" and not slider),
                                       span=span)
            exact = np.interp(mids, phase, y, period=360.0) if span is None else np.interp(mids, phase, y)
            err = 100.0 * float(np.max(np.abs(d - exact))) / ym
            cv.layer = "thin"
            cp = np.c_[ax0 + mids / mu_phi, yc + d / mu]
            cv.polyline(cp, color="#b03a2e", width=0.35, dash="3 1.5")
            for p in cp:
                cv.circle(p, 0.8, stroke="#b03a2e", fill=None, width=0.3)
            cv.mtext(ax0 + 150.0, yc + rowh / 2 - 5.0, format_text(TXT[lang]["chord"], lang, n=len(mids), err=f"{err:.1f}"),
                     2.5, color="#b03a2e")
            out[key]["chord"] = {"phase": mids, "values": d, "exact": exact, "error_pct": err, "pts": cp}
        out[key]["raw"] = y
    out["mu_phi"] = mu_phi
    return out


def build(cv, results: dict, task: Task | None, lang: str = "en") -> dict:
    from ..plans import geometry
    entries = results.get("kinematics") or []
    geom = geometry(results)
    fx0, fy0, fx1, fy1 = FRAME
    course = course_positions(results)
    from ..report.course import grid_count
    over_range = (results.get("positions") or {}).get("over") == "input_range"
    info = {"mechanism": draw_mechanism(cv, geom, entries, course, (fx0 + 3, 300.0, 400.0, fy1 - 300.0 - 3),
                                        lang, traced_over=entries[:grid_count(results, len(entries))],
                                        closed=not over_range)}
    info["plans"] = {}
    by_index = {e["index"]: e for e in entries}
    # the acceleration plans of the course positions side by side at the top, the velocity
    # plans of every grid position (the course's 12) under them, at one μv
    from ..report.course import course_entries, grid_count, position_label
    n_grid = grid_count(results, len(entries))
    for k, i in enumerate(course):
        info["plans"][i] = draw_plans(cv, geom, by_index[i], (430.0 + PLAN_BOX_W * k, 445.0, PLAN_BOX_W,
                                                               PLAN_BOX_H), lang, kinds=("a",),
                                        table_w=TABLE_W, n_grid=n_grid)
    grid = course_entries(entries[:n_grid], n_grid)          # the course's 12 of a finer grid
    grid += [by_index[i] for i in course if by_index[i] not in grid]     # a course extra after them
    info["vplans"] = draw_velocity_plans(cv, geom, grid, (430.0, fy0 + 62.0, fx1 - 430.0 - 3.0,
                                                          440.0 - fy0 - 62.0), lang, n_grid=n_grid)
    for i in course:
        info["plans"][i]["v"] = info["vplans"][i]
    # the velocity plans' segments as drawn, at the sheet's μv: under the plans, left of the title block
    from .segments import velocity_table
    info["vtable"] = velocity_table(cv, info["vplans"], (432.0, fy0 + 2.0, fx1 - TB_W - 432.0 - 3.0, 58.0),
                                    lang, TXT[lang]["unit_v"], {e["index"]: position_label(e, n_grid) for e in grid})
    info["diagrams"] = draw_diagrams(cv, results, geom, (fx0 + 3, fy0 + 3, 400.0, 290.0), lang)
    info["scale"] = info["mechanism"]["scale"]
    return info
