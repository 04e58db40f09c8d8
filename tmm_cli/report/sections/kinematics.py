"""Report section 'kinematics': plan of positions with trajectories, scale
factors, velocity and acceleration plans of every position with their segment
tables, tables of velocities/accelerations and angular velocities (with their
sense in words), kinematic diagrams of the output link.  Writes
``kinematics.csv`` and ``plans.csv`` beside the report.

Follows docs/methods.md §2; plan notation as in Artobolevsky / Popov &
Timofeev (pole p and pi, lower-case point letters, n - end of a normal
component, k - end of the Coriolis acceleration).  Scales are chosen as
students do: mu = v_A / pa with pa = 100 mm rounded *up* to a nice value
(1, 1.5, 2, 2.5, 3, 4, 5, 6, 8 x 10^k), so pa <= 100 mm.
"""
from __future__ import annotations

import html
import math
from operator import itemgetter

import numpy as np
from markupsafe import Markup

from ... import locales
from ..context import values_of
from ..course import course_entries, cycle_order, grid_count, position_label
from ...drawings.plans import draw_plan, plan_room
from ...numfmt import num as written
from ...plans import build_plan, crank_pin, geometry, plan_label, scales
from ...scales import nice_scale

I18N = locales.table("kinematics", "words")


def _median(values) -> float:
    """np.median of a list of numbers, bit for bit (the middle value, or the mean of the
    two middle ones; NaN if any is NaN), without numpy's median: its NaN check imports
    numpy.ma (~20 ms of the report); sorted by numpy (tens of thousands of plan readings at
    a fine grid), stably as by sorted (0.0 and -0.0 kept in their order), the mean of the
    middle two taken in Python floats."""
    s = np.sort(np.asarray(values, float), kind="stable")
    if np.isnan(s).any():
        return math.nan
    m = len(s) // 2
    return float(s[m]) if len(s) % 2 else (float(s[m - 1]) + float(s[m])) / 2


def _pxy(e, p):
    d = e["points"][p]
    return np.array([float(d["x"]), float(d["y"])])


def _rotation_sign(ctx, geom, entries) -> float:
    d = (ctx.results.get("positions") or {}).get("direction")
    if d in ("ccw", "cw"):
        return 1.0 if d == "ccw" else -1.0
    w = (ctx.results.get("drive") or {}).get("omega") or 1.0
    return 1.0 if w >= 0 else -1.0


#: a value next to a change point below this share of its column's largest is shown as 0 (the
#: continuity extrapolation's round-off: ~1e-8 of the largest in the examples that have one)
NOISE = 1e-6


def _sense_mark(x, tiny: float = 1e-9) -> str:
    """↺ for a counter-clockwise (positive) value, ↻ for a clockwise one."""
    if x is None or not math.isfinite(float(x)) or abs(float(x)) <= tiny:
        return ""
    return "↺" if x > 0 else "↻"


def _grid_count(ctx, entries) -> int:
    return grid_count(ctx.results, len(entries))


# ----------------------------------------------------------------- figures
POSITIONS_BOX = dict(width_mm=165.0, min_h=60.0, max_h=150.0, margin_mm=10.0)   # the plan of positions


def positions_svg(ctx, geom, entries, grid, fine=None, extent=None, closed=True):
    """The plan of positions: the mechanism at the `grid` positions, trajectories as
    periodic splines through them -- or, given a `fine` grid, through its points (at most
    TRACE_POINTS of them, evenly spaced); ``closed=False`` (a linkage analysed over an input
    range) open curves from the first position to the last, never closed back. ``extent``:
    ``mechanism_extent(entries)`` when already known."""
    from .. import figures as F
    lo, hi = extent if extent is not None else F.mechanism_extent(entries)
    view, unit, title = F.figure_for_box(lo, hi, lang=ctx.lang, **POSITIONS_BOX)
    ranges = F.slider_ranges(entries, geom)
    for e in grid[1:]:
        F.draw_mechanism(view, geom, e, unit, light=True)
    # the position numbers at the crank pin first: the point names keep clear of them
    numbers = []
    pin = crank_pin(geom)
    if pin is not None:
        O = None
        for j in geom.joints:
            if j.kind == "R" and j.a == 0 and j.b == geom.drive:
                O = _pxy(grid[0], j.point)
        for k, e in enumerate(grid):
            a = _pxy(e, pin)
            d = a - O if O is not None else np.array([0.0, 1.0])
            d = d / (np.linalg.norm(d) or 1.0)
            q = a + d * 3.5 * unit
            numbers.append((q, str(e.get("index", k))))
    fs_mm = 6.5 * 25.4 / 72.0
    taken = [(q[0] - w / 2, q[1] - h / 2, q[0] + w / 2, q[1] + h / 2) for q, s in numbers
             for w, h in [tuple(unit * np.array(F.text_size(s, fs_mm)))]]
    F.draw_mechanism(view, geom, grid[0], unit, ranges=ranges, lw=1.3, taken=taken + [title])
    # trajectories: periodic splines through the grid positions (open ones over an input range)
    from ..svgchart import spline_through
    traced = [l.com for l in geom.links if l.com] + [p for l in geom.links if l.kind == "bar"
                                                     for p in l.points]
    if fine is not None:
        step = -(-len(fine) // TRACE_POINTS)            # every step-th point of a fine grid
        fine = fine[::step]
    seen = set()
    for p in traced:
        if p in seen or p in geom.ground or p not in grid[0]["points"]:
            continue
        seen.add(p)
        xy = F.points_xy(grid, p)
        if np.ptp(xy, axis=0).max() < 1e-9 or len(xy) < 3:
            continue
        if fine is not None:
            c = F.points_xy(fine + fine[:1] if closed else fine, p)
        else:
            c = spline_through(xy, closed, 40 * len(xy) if closed else 40 * (len(xy) - 1) + 1)
        is_com = p.startswith("S")
        if is_com:
            view.line(c, "#1f5fbf", 0.7, z=1)
        else:                                          # matplotlib's '--' at lw 0.5
            view.line(c, "0.5", 0.5, dash=(1.85, 0.8), z=1)
        for q in xy:
            view.dot(q, 1.6, "#1f5fbf" if is_com else "0.4", z=2)
    for q, s in numbers:
        view.text(q, s, size=6.5, color="#7a1f1f", z=8)
    return ctx.svg(view, "positions")


TRACE_POINTS = 720      # at most this many points of a trajectory drawn from a fine grid


PLAN_W, PLAN_H = 170.0, 86.0        # mm: the two plans side by side


def drawn_scales(results: dict, geom):
    """(mu_v, mu_a, v_A, a_A): the one scale of each kind at which the report draws the
    plans of every course position, tabulates their segments and works them out step by
    step: the course's (the crank pin's vector <= 100 mm, plans.scales), or the next
    standard one at which the plan of every position fits its half of the figure, so
    that the printed plan measures what its table says."""
    entries = results.get("kinematics") or []
    mu_v, mu_a, vA, aA = scales(entries, geom)
    if crank_pin(geom) is None:
        return mu_v, mu_a, vA, aA
    room = np.array(plan_room(PLAN_W / 2 - 1, PLAN_H))
    out = []
    for kind, mu in (("v", mu_v), ("a", mu_a)):
        need = mu
        for e in course_entries(entries, grid_count(results, len(entries))):
            xy = np.array(list(build_plan(kind, e, geom, 1.0).pts.values()))
            need = max(need, float(((xy.max(axis=0) - xy.min(axis=0)) / room).max()))
        out.append(nice_scale(need))
    return out[0], out[1], vA, aA


def plan_note(ctx, plan) -> str | None:
    """What a plan the position cannot have says instead (None for a drawable plan)."""
    return ctx.t("kin.plan_undefined", what=", ".join(plan.undefined)) if plan.undefined else None


def plans_svg(ctx, vplan, aplan):
    from ..svgdraw import Canvas
    from markupsafe import Markup as _M
    cv = Canvas(PLAN_W, PLAN_H)
    half = PLAN_W / 2
    draw_plan(cv, vplan, (0, 0, half - 1, PLAN_H), ctx.t("kin.velocity_plan"), ctx.t("kin.unit_v"),
              ctx.t("kin.si_v"), ctx.t("kin.mm"), note=plan_note(ctx, vplan))
    draw_plan(cv, aplan, (half + 1, 0, half - 1, PLAN_H), ctx.t("kin.acceleration_plan"), ctx.t("kin.unit_a"),
              ctx.t("kin.si_a"), ctx.t("kin.mm"), note=plan_note(ctx, aplan))
    cv.line((half, 1), (half, PLAN_H - 1), "#bbb", 0.2, z=0)
    return _M(cv.to_svg())


def output_series(ctx, geom, entries, out_name):
    """(kind, values dict) of the output link at the entries:
    slider -> s, v, a along its guide (s from position 0); rotating link -> psi, omega, eps."""
    l = geom.by_name(out_name)
    e0 = entries[0]
    if l is not None and l.kind == "slider":
        pin = l.points[0]
        ang = math.radians(float(e0["links"][l.name]["angle"] or 0.0))
        u = np.array([math.cos(ang), math.sin(ang)])
        r0 = _pxy(e0, pin)
        # row by row as for one entry (each row's product by itself: the same numbers),
        # the rows read in bulk (a fine grid has thousands)
        from ..figures import points_xy
        ds = [e["points"][pin] for e in entries]
        s = [float((r - r0) @ u) for r in points_xy(entries, pin)]
        v = [float(r @ u) for r in np.array(list(map(itemgetter("vx", "vy"), ds)), float)]
        a = [float(r @ u) for r in np.array(list(map(itemgetter("ax", "ay"), ds)), float)]
        return "slider", s, v, a
    name = l.name if l is not None else out_name
    a0 = float(e0["links"][name]["angle"] or 0.0)
    psi = [((float(e["links"][name]["angle"] or 0.0) - a0 + 180.0) % 360.0) - 180.0 for e in entries]
    # null next to a change point (no finite limit): not drawn
    w = [math.nan if e["links"][name]["omega"] is None else float(e["links"][name]["omega"]) for e in entries]
    eps = [math.nan if e["links"][name]["epsilon"] is None else float(e["links"][name]["epsilon"])
           for e in entries]
    return "rotating", psi, w, eps


def diagrams_svg(ctx, geom, entries, phase, out_name, curve, marks=None, span=None):
    """s, v, a (or psi, omega, epsilon) of the output link over the cycle (over the crank
    range ``span``, deg, where the positions are spread over one: no wrap-around); dots at
    the positions (at those of the boolean mask `marks` only, for a fine grid)."""
    from .. import figures as F
    kind, s, v, a = output_series(ctx, geom, entries, out_name)
    units = ([ctx.t("kin.s_unit"), ctx.t("kin.v_unit"), ctx.t("kin.a_unit")] if kind == "slider"
             else [ctx.t("kin.psi_unit"), ctx.t("kin.w_unit"), ctx.t("kin.e_unit")])
    from ..svgchart import periodic_spline, subplots
    fig, axes = subplots(165.0, 150.0, nrows=3, sharex=True)
    order = np.argsort(phase)
    ph = np.asarray(phase)[order]
    keep = np.concatenate([[True], np.diff(ph) > 1e-9])
    dots = keep if marks is None else keep & np.asarray(marks, bool)[order]
    for ax, ys, lab in zip(axes, (s, v, a), units):
        y = np.asarray(ys)[order][keep]
        x = ph[keep]
        if curve is not None:
            key = {0: "s", 1: "v", 2: "a"}[[s, v, a].index(ys)]
            cx = np.asarray(curve["phase"])
            ax.plot(cx, np.asarray(curve[key], float), color="#1f5fbf", lw=1.0)
        elif span is not None:              # a range: the points joined, no period
            ax.plot(x, y, color="#1f5fbf", lw=1.0)
        elif marks is not None:             # a fine grid is its own curve
            ax.plot(np.append(x, x[0] + 360.0), np.append(y, y[0]), color="#1f5fbf", lw=1.0)
        elif len(x) >= 3:
            tt = np.linspace(x[0], x[0] + 360.0, 721)
            ax.plot(tt % 360.0 if x[0] > 0 else tt,
                    periodic_spline(np.append(x, x[0] + 360.0), np.append(y, y[0]), tt),
                    color="#1f5fbf", lw=1.0)
        ax.plot(ph[dots], np.asarray(ys)[order][dots], ls="none", marker="o", ms=2.5, color="k",
                clip_on=False, zorder=5)
        ax.axhline(0, color="0.5", lw=0.5)
        ax.set_ylabel(lab)
        ax.grid(True, lw=0.3, color="0.85")
        ax.set_xlim(0, 360 if span is None else abs(span))
    if span is None:
        axes[-1].set_xticks(np.arange(0, 361, 30))
    else:
        step = next(st for st in (5, 10, 15, 30, 45, 60, 90) if abs(span) / st <= 12)
        axes[-1].set_xticks(np.arange(0, abs(span) + 1e-9, step))
    axes[-1].set_xlabel(ctx.t("kin.phi_axis"))
    # every axis at a standard scale μ, stated in the course's form (μs = 0.002 m/mm)
    F.std_graph(fig, axes, ctx.t("kin.mm"), x_axis=axes[-1])
    return ctx.svg(fig, "output-diagrams"), kind


def write_table(ctx) -> None:
    """kinematics.csv: every point's and link's values at every position of the results
    (thousands of rows at a fine grid), where the section is drawn (build's conditions)."""
    entries = ctx.results.get("kinematics") or []
    if not entries or geometry(ctx.results) is None:
        return
    pk, lk = ("x", "y", "vx", "vy", "v", "ax", "ay", "a"), ("angle", "omega", "epsilon")
    header = ["index", "phi"]
    pnames = list(entries[0]["points"].keys())
    for p in pnames:
        header += [f"{p}.{k}" for k in pk]
    lnames = list(entries[0]["links"].keys())
    for n in lnames:
        header += [f"{n}.{k}" for k in lk]
    rows = []
    pget, lget = values_of(pk), values_of(lk)       # a value missing: an empty cell
    for e in entries:
        row = [e["index"], float(e["phi"])]
        pts, lks = e["points"], e["links"]
        for p in pnames:
            row += pget(pts[p])
        for n in lnames:
            row += lget(lks[n])
        rows.append(row)
    ctx.write_csv("kinematics.csv", header, rows)


# ----------------------------------------------------------------- section
def build(ctx) -> str | None:
    entries = ctx.results.get("kinematics") or []
    if not entries:
        return None
    geom = geometry(ctx.results)
    if geom is None:
        return None
    res_pos = ctx.results.get("positions") or {}
    n_grid = _grid_count(ctx, entries)
    grid = entries[:n_grid]
    # a fine grid: plans and tables for the course positions, the grid as curves
    shown = course_entries(entries, n_grid)
    shown_grid = [e for e in shown[:len(shown) - (len(entries) - n_grid)]]
    fine = grid if len(shown_grid) < n_grid else None
    sgn = _rotation_sign(ctx, geom, entries)
    span = res_pos.get("span") if res_pos.get("over") == "input_range" else None
    if span is not None:        # over the input range: its own sense, from its start
        sgn = 1.0 if span >= 0 else -1.0
    phi0 = res_pos.get("phi0", grid[0]["phi"])
    # the tables and plans in the order of the crank's turn, the extras marked
    shown = cycle_order(shown, phi0, sgn)

    def num(e):
        return position_label(e, n_grid)
    phase = [((float(e["phi"]) - float(phi0)) * sgn) % 360.0 for e in entries]
    phase = [0.0 if abs(p - 360.0) < 1e-9 else p for p in phase]

    # scales
    mu_v, mu_a, vA, aA = drawn_scales(ctx.results, geom)
    pin = crank_pin(geom)
    from ..figures import box_scale, mechanism_extent
    lo, hi = mechanism_extent(entries)
    _, mu_l, _ = box_scale(lo, hi, **POSITIONS_BOX)         # the plan of positions' own
    lengths = []
    for l in geom.links:
        if l.kind == "bar" and len(l.points) >= 2:
            L = float(np.linalg.norm(_pxy(entries[0], l.points[1]) - _pxy(entries[0], l.points[0])))
            lengths.append((f"{l.index} ({l.name}), {l.points[0]}{l.points[1]}", ctx.fmt(L),
                            ctx.fmt_fixed(L / mu_l, 1)))
    scale_rows = [
        (Markup(f"μ<sub>l</sub> — {ctx.t('kin.mu_l')}"), f"{written(mu_l, 'g')} {ctx.t('kin.unit_l')}"),
        (Markup("μ<sub>v</sub> = v<sub>{}</sub>/p{} — {}").format(pin, plan_label(pin), ctx.t('kin.mu_v')),
         Markup(f"{ctx.fmt(vA)} / {ctx.fmt_fixed(vA / mu_v, 2)} ≈ {written(mu_v, 'g')} {ctx.t('kin.unit_v')}")),
        (Markup("μ<sub>a</sub> = a<sub>{}</sub>/π{} — {}").format(pin, plan_label(pin), ctx.t('kin.mu_a')),
         Markup(f"{ctx.fmt(aA)} / {ctx.fmt_fixed(aA / mu_a, 2)} ≈ {written(mu_a, 'g')} {ctx.t('kin.unit_a')}")),
    ]
    gp = (ctx.results.get("graphical_error") or {}).get("plans") or {}
    rel = [r for e in gp.get("positions", []) for d in e["points"].values() for r in d.values() if r is not None]
    if rel:
        # (the hand method's error: a plan drawn with the crank pin's vector about 100 mm)
        scale_rows.append((ctx.t("kin.reading"),
                           ctx.t("kin.reading_val", ev=written(gp["abs_v"], "g"), ea=written(gp["abs_a"], "g"),
                                 mv=written(gp["mu_v"], "g"), ma=written(gp["mu_a"], "g"),
                                 med=ctx.fmt_fixed(100 * _median(rel), 2),
                                 top=ctx.fmt_fixed(100 * max(rel), 1))))
    pos_rows = []
    if res_pos:
        pos_rows.append((ctx.t("kin.phi0"), ctx.fmt_fixed(res_pos.get("phi0"), 3) + "°"))
        if span is not None:
            pos_rows.append((ctx.t("kin.over_range"),
                             ctx.t("kin.over_range_val", start=ctx.fmt_fixed(res_pos["phi0"], 3),
                                   end=ctx.fmt_fixed(float(res_pos["phi0"]) + float(span), 3),
                                   count=res_pos.get("count"))))
        if res_pos.get("extreme"):
            pos_rows.append((ctx.t("kin.extreme_angles"),
                             ", ".join(ctx.fmt_fixed(x, 3) + "°" for x in res_pos["extreme"])))
        for key, lab, unit in (("working_stroke_angle", "kin.working_angle", "°"),
                               ("idle_stroke_angle", "kin.idle_angle", "°"), ("K", "kin.K", "")):
            if res_pos.get(key) is not None:
                pos_rows.append((ctx.t(lab), ctx.fmt_fixed(res_pos[key], 3 if unit else 4) + unit))
    for row in ctx.results.get("transmission") or []:      # each dyad's least transmission angle
        pos_rows.append((ctx.t("kin.gamma_min", group=row["group"], links=", ".join(row["links"])),
                         ctx.t("kin.gamma_min_val", gamma=ctx.fmt_fixed(row["gamma_min"], 2),
                               phi=ctx.fmt_fixed(row["phi"], 2))))

    # summary tables
    tops: dict[tuple, float] = {}

    def settled(e, x, col):
        """``x`` as the table shows it: at a position next to a change point (its values the
        limit by continuity, extrapolated from the neighbours) a value below 1e-6 of its
        column's largest is that extrapolation's round-off of a zero (the rocker's 1.7e-7 rad/s^2
        where its largest is 40): 0, no sense of rotation (results.json keeps it as computed)."""
        if x is None or not e.get("near_singular"):
            return x
        if col not in tops:
            where, name, key = col
            tops[col] = max((abs(float(v)) for v in (q[where][name][key] for q in shown) if v is not None),
                            default=0.0)
        return 0.0 if abs(float(x)) < NOISE * tops[col] else x
    moving_pts = []
    for l in geom.links:
        for p in l.points + ([l.com] if l.com else []):
            if p not in geom.ground and p not in moving_pts and p in entries[0]["points"]:
                moving_pts.append(p)
    hdr_pts = [ctx.t("common.position"), "φ, °"] + moving_pts
    v_rows = [[num(e), ctx.fmt_fixed(e["phi"], 2)] +
              [ctx.fmt(settled(e, e["points"][p]["v"], ("points", p, "v"))) for p in moving_pts] for e in shown]
    a_rows = [[num(e), ctx.fmt_fixed(e["phi"], 2)] +
              [ctx.fmt(settled(e, e["points"][p]["a"], ("points", p, "a"))) for p in moving_pts] for e in shown]
    # angular quantities: links that turn (a slider on a fixed guide never does)
    def turns(n):
        return any(abs(float(e["links"][n].get(k) or 0.0)) > 1e-12 for e in entries for k in ("omega", "epsilon"))
    rot_links = [l for l in geom.links if turns(l.name)]
    hdr_l = [ctx.t("common.position"), "φ, °"] + [f"{l.index} ({l.name})" for l in rot_links]

    def signed(x):
        return f"{ctx.fmt(x)} {_sense_mark(x)}".rstrip()
    w_rows = [[num(e), ctx.fmt_fixed(e["phi"], 2)] +
              [signed(settled(e, e["links"][l.name]["omega"], ("links", l.name, "omega"))) for l in rot_links]
              for e in shown]
    e_rows = [[num(e), ctx.fmt_fixed(e["phi"], 2)] +
              [signed(settled(e, e["links"][l.name]["epsilon"], ("links", l.name, "epsilon"))) for l in rot_links]
              for e in shown]
    hdr_ang = [ctx.t("common.position"), "φ, °"] + [f"{l.index} ({l.name})" for l in geom.links]
    ang_rows = [[num(e), ctx.fmt_fixed(e["phi"], 2)] +
                [ctx.fmt_fixed(e["links"][l.name].get("angle"), 2) for l in geom.links] for e in shown]

    # plans of every (course) position
    from .. import figures as F
    positions = []
    plan_csv = []
    for e in shown:
        vp = build_plan("v", e, geom, mu_v)
        ap = build_plan("a", e, geom, mu_a)
        vr, ar = vp.rows(), ap.rows()
        vrows = [(Markup(sym), seg, ctx.fmt_fixed(mm, 1), ctx.fmt(val)) for sym, seg, mm, val in vr]
        arows = [(Markup(sym), seg, ctx.fmt_fixed(mm, 1), ctx.fmt(val)) for sym, seg, mm, val in ar]
        for kind, rows in (("v", vr), ("a", ar)):
            for sym, seg, mm, val in rows:
                plan_csv.append([e["index"], e["phi"], kind, seg,
                                 html.unescape(sym.replace("<sub>", "_").replace("</sub>", "")
                                               .replace("<sup>", "^").replace("</sup>", "")),
                                 float(mm), float(val)])
        # a position with neither plan (next to a change point) has its notes and no figure
        fig = None if vp.undefined and ap.undefined else \
            F.named(plans_svg(ctx, vp, ap), F.pos_name("plans", e["index"]))
        positions.append({"index": num(e), "phi": ctx.fmt_fixed(e["phi"], 2), "fig": fig, "vrows": vrows,
                          "arows": arows, "vnote": plan_note(ctx, vp), "anote": plan_note(ctx, ap)})

    # diagrams
    out_name = res_pos.get("output") or geom.links[-1].name
    curve = None
    kc = ctx.results.get("kinematics_curve")
    if kc and kc.get("phi"):
        curve = dict(kc)
        curve["phase"] = [((float(p) - float(phi0)) * sgn) % 360.0 for p in kc["phi"]]
        o = np.argsort(curve["phase"])
        for k in ("phase", "s", "v", "a"):
            if k in curve:
                curve[k] = list(np.asarray(curve[k], float)[o])
    marks = None
    if fine is not None:
        ids = {id(e) for e in shown}
        marks = [id(e) in ids for e in entries]
    diag, _ = diagrams_svg(ctx, geom, entries, phase, out_name, curve, marks, span)

    # CSV (with two processes the report's helper writes kinematics.csv: report.HELPER_TABLES)
    if "kinematics" in ctx.tables_elsewhere:
        ctx.written_elsewhere("kinematics.csv")
    else:
        write_table(ctx)
    order = {e["index"]: k for k, e in enumerate(entries)}      # the CSV in the results' order
    plan_csv.sort(key=lambda r: order[r[0]])
    ctx.write_csv("plans.csv", ["index", "phi", "plan", "segment", "vector", "length_mm", "value"], plan_csv)

    return ctx.render("sections/kinematics.html.j2",
                      pos_rows=pos_rows, scale_rows=scale_rows, lengths=lengths, over_range=span is not None,
                      fig_positions=positions_svg(ctx, geom, entries, shown_grid, fine, (lo, hi),
                                                 closed=span is None),
                      n_grid=len(shown_grid),
                      hdr_pts=hdr_pts, v_rows=v_rows, a_rows=a_rows, hdr_l=hdr_l,
                      w_rows=w_rows, e_rows=e_rows, hdr_ang=hdr_ang, ang_rows=ang_rows,
                      sense_note=ctx.t("kin.sense_note"), positions=positions, fig_diagrams=diag,
                      out_name=out_name, out_label=ctx.link_label(out_name), dense=curve is not None,
                      extra_note=ctx.t("common.extra_note") if len(entries) > n_grid else None)
