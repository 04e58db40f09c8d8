"""Report section 'kinematics': plan of positions with trajectories, scale
factors, velocity and acceleration plans of every position with their segment
tables, tables of velocities/accelerations and angular velocities (with their
sense in words), kinematic diagrams of the output link.  Writes
``kinematics.csv`` and ``plans.csv`` beside the report.

Follows METHODS.md section 2; plan notation as in Artobolevsky / Popov &
Timofeev (pole p and pi, lower-case point letters, n - end of a normal
component, k - end of the Coriolis acceleration).  Scales are chosen as
students do: mu = v_A / pa with pa = 100 mm rounded *up* to a nice value
(1, 1.5, 2, 2.5, 3, 4, 5, 6, 8 x 10^k), so pa <= 100 mm.
"""
from __future__ import annotations

import math

import numpy as np
from markupsafe import Markup

from ..plans import build_plan, crank_pin, geometry, plan_label, scales

I18N = {
    "en": {"kin.unit_v": "(m/s)/mm", "kin.unit_a": "(m/s²)/mm", "kin.unit_l": "m/mm",
           "kin.plan_axis": "mm on the plan", "kin.output": "Output link",
           "kin.s_unit": "s, m", "kin.v_unit": "v, m/s", "kin.a_unit": "a, m/s²",
           "kin.psi_unit": "ψ, deg", "kin.w_unit": "ω, rad/s", "kin.e_unit": "ε, rad/s²",
           "kin.formula_w": "ω = v_rel / l", "kin.csv_note": "All numbers: kinematics.csv, plans.csv."},
    "ru": {"kin.unit_v": "м/(с·мм)", "kin.unit_a": "м/(с²·мм)", "kin.unit_l": "м/мм",
           "kin.plan_axis": "мм на плане", "kin.output": "Выходное звено",
           "kin.s_unit": "s, м", "kin.v_unit": "v, м/с", "kin.a_unit": "a, м/с²",
           "kin.psi_unit": "ψ, град", "kin.w_unit": "ω, рад/с", "kin.e_unit": "ε, рад/с²",
           "kin.formula_w": "ω = v_отн / l", "kin.csv_note": "Все числа: kinematics.csv, plans.csv."},
}

COLORS = {"abs": "k", "rel": "0.35", "n": "#1f5fbf", "t": "#c0392b", "k": "#1e8449", "r": "#8e44ad"}


def _pxy(e, p):
    d = e["points"][p]
    return np.array([float(d["x"]), float(d["y"])])


def _rotation_sign(ctx, geom, entries) -> float:
    d = getattr(getattr(ctx.task, "drive", None), "direction", None)
    if d in ("ccw", "cw"):
        return 1.0 if d == "ccw" else -1.0
    l = geom.link(geom.drive)
    if l is not None and entries:
        w = entries[0]["links"].get(l.name, {}).get("omega") or 1.0
        return 1.0 if w >= 0 else -1.0
    return 1.0


def _grid_count(ctx, entries) -> int:
    c = getattr(getattr(ctx.task, "positions", None), "count", None)
    if isinstance(c, int) and c > 0:
        return min(c, len(entries))
    return len(entries)


# ----------------------------------------------------------------- figures
def positions_svg(ctx, geom, entries, grid):
    from .. import figures as F
    lo, hi = F.mechanism_extent(entries)
    fig, ax, unit = F.figure_for_box(lo, hi, 165.0, min_h=60.0, max_h=150.0, margin_mm=10.0)
    ranges = F.slider_ranges(entries, geom)
    for e in grid[1:]:
        F.draw_mechanism(ax, geom, e, unit, light=True)
    F.draw_mechanism(ax, geom, grid[0], unit, ranges=ranges, lw=1.3)
    # trajectories: periodic splines through the grid positions
    from scipy.interpolate import CubicSpline
    traced = [l.com for l in geom.links if l.com] + [p for l in geom.links if l.kind == "bar"
                                                     for p in l.points]
    seen = set()
    pin = crank_pin(geom)
    for p in traced:
        if p in seen or p in geom.ground or p not in grid[0]["points"]:
            continue
        seen.add(p)
        xy = np.array([_pxy(e, p) for e in grid])
        if np.ptp(xy, axis=0).max() < 1e-9 or len(xy) < 3:
            continue
        t = np.arange(len(xy) + 1, dtype=float)
        closed = np.vstack([xy, xy[:1]])
        tt = np.linspace(0, len(xy), 40 * len(xy))
        cs = CubicSpline(t, closed, bc_type="periodic")
        c = cs(tt)
        is_com = p.startswith("S")
        ax.plot(c[:, 0], c[:, 1], lw=0.7 if is_com else 0.5, ls="-" if is_com else "--",
                color="#1f5fbf" if is_com else "0.5", zorder=1)
        ax.plot(xy[:, 0], xy[:, 1], ls="none", marker="o", ms=1.6,
                color="#1f5fbf" if is_com else "0.4", zorder=2)
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
            ax.text(q[0], q[1], str(e.get("index", k)), fontsize=6.5, color="#7a1f1f",
                    ha="center", va="center", zorder=8)
    return ctx.svg(fig)


def draw_plan(ax, plan, title, unit_txt, width_mm, height_mm):
    from .. import figures as F
    pts = plan.pts
    xy = np.array(list(pts.values()))
    lo, hi = xy.min(axis=0), xy.max(axis=0)
    span = max(float((hi - lo).max()), 10.0)
    c = (lo + hi) / 2
    lo2, hi2 = np.minimum(lo, c - span * 0.12), np.maximum(hi, c + span * 0.12)
    unit = F.fit_axes(ax, lo2, hi2, width_mm, height_mm, margin_mm=7.0)
    segs = []
    for v in plan.vecs:
        p, q = pts[v.start], pts[v.end]
        segs.append((p, q))
        if np.linalg.norm(q - p) < 0.2:
            continue
        if v.kind == "abs":
            F.arrow(ax, p, q, color=COLORS["abs"], lw=1.1, head=7, z=5)
        elif v.kind == "rel":
            F.arrow(ax, p, q, color=COLORS["rel"], lw=0.7, head=5, z=4)
        else:
            F.arrow(ax, p, q, color=COLORS[v.kind], lw=0.9, head=6, z=4,
                    ls="--" if v.kind in ("n", "k") else "-")
    # labels: merge coincident points
    groups: list[tuple[np.ndarray, list[str]]] = []
    for name, p in pts.items():
        for g in groups:
            if np.linalg.norm(g[0] - p) < 1.2 * unit:
                g[1].append(name)
                break
        else:
            groups.append((p, [name]))
    anchors = []
    for p, names in groups:
        d = p / (np.linalg.norm(p) or 1.0)
        anchors.append((p[0], p[1], tuple(d) if np.linalg.norm(p) > 0 else (-1.0, -1.0)))
    pos = F.place_labels(anchors, span, avoid=[g[0] for g in groups], step=3.2 * unit,
                         segments=segs)
    for (p, names), (x, y) in zip(groups, pos):
        names = sorted(names, key=lambda s: (s != plan.pole, s))
        ax.text(x, y, ", ".join(names), fontsize=7.5, style="italic", ha="center", va="center",
                zorder=8, color="k" if plan.pole in names or not names[0].startswith(("n", "k"))
                else "0.25")
    ax.plot([0], [0], marker="o", ms=2.5, color="k", zorder=6)
    ax.set_title(f"{title}, μ = {plan.mu:g} {unit_txt}", fontsize=7.5, pad=3)
    from matplotlib.ticker import MaxNLocator
    ax.xaxis.set_major_locator(MaxNLocator(5))
    ax.yaxis.set_major_locator(MaxNLocator(5))
    ax.tick_params(labelsize=5.5, length=2, pad=1)
    ax.grid(True, lw=0.25, color="0.85")
    for s in ax.spines.values():
        s.set_linewidth(0.4)
        s.set_color("0.6")


def plans_svg(ctx, vplan, aplan):
    from .. import figures as F
    W, H = 170.0, 82.0
    fig = F.plt().figure(figsize=(W * F.MM, H * F.MM))
    ax1 = fig.add_axes([0.045, 0.07, 0.43, 0.85])
    ax2 = fig.add_axes([0.545, 0.07, 0.43, 0.85])
    draw_plan(ax1, vplan, ctx.t("kin.velocity_plan"), ctx.t("kin.unit_v"), W * 0.43, H * 0.85)
    draw_plan(ax2, aplan, ctx.t("kin.acceleration_plan"), ctx.t("kin.unit_a"), W * 0.43, H * 0.85)
    return ctx.svg(fig)


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
        s = [float((_pxy(e, pin) - r0) @ u) for e in entries]
        v = [float(np.array([e["points"][pin]["vx"], e["points"][pin]["vy"]], float) @ u) for e in entries]
        a = [float(np.array([e["points"][pin]["ax"], e["points"][pin]["ay"]], float) @ u) for e in entries]
        return "slider", s, v, a
    name = l.name if l is not None else out_name
    a0 = float(e0["links"][name]["angle"] or 0.0)
    psi = [((float(e["links"][name]["angle"] or 0.0) - a0 + 180.0) % 360.0) - 180.0 for e in entries]
    w = [float(e["links"][name]["omega"] or 0.0) for e in entries]
    eps = [float(e["links"][name]["epsilon"] or 0.0) for e in entries]
    return "rotating", psi, w, eps


def diagrams_svg(ctx, geom, entries, phase, out_name, curve):
    from scipy.interpolate import CubicSpline
    from .. import figures as F
    kind, s, v, a = output_series(ctx, geom, entries, out_name)
    units = ([ctx.t("kin.s_unit"), ctx.t("kin.v_unit"), ctx.t("kin.a_unit")] if kind == "slider"
             else [ctx.t("kin.psi_unit"), ctx.t("kin.w_unit"), ctx.t("kin.e_unit")])
    fig, axes = F.new_figure(165.0, 150.0, nrows=3, sharex=True)
    order = np.argsort(phase)
    ph = np.asarray(phase)[order]
    keep = np.concatenate([[True], np.diff(ph) > 1e-9])
    for ax, ys, lab in zip(axes, (s, v, a), units):
        y = np.asarray(ys)[order][keep]
        x = ph[keep]
        if curve is not None:
            key = {0: "s", 1: "v", 2: "a"}[[s, v, a].index(ys)]
            cx = np.asarray(curve["phase"])
            ax.plot(cx, np.asarray(curve[key], float), color="#1f5fbf", lw=1.0)
        elif len(x) >= 3:
            cs = CubicSpline(np.append(x, x[0] + 360.0), np.append(y, y[0]), bc_type="periodic")
            tt = np.linspace(x[0], x[0] + 360.0, 721)
            ax.plot(tt % 360.0 if x[0] > 0 else tt, cs(tt), color="#1f5fbf", lw=1.0)
        ax.plot(x, y, ls="none", marker="o", ms=2.5, color="k", clip_on=False, zorder=5)
        ax.axhline(0, color="0.5", lw=0.5)
        ax.set_ylabel(lab)
        ax.grid(True, lw=0.3, color="0.85")
        ax.set_xlim(0, 360)
    axes[-1].set_xticks(np.arange(0, 361, 30))
    axes[-1].set_xlabel(ctx.t("kin.phi_axis"))
    fig.subplots_adjust(left=0.1, right=0.98, top=0.98, bottom=0.08, hspace=0.12)
    return ctx.svg(fig), kind


# ----------------------------------------------------------------- section
def build(ctx) -> str | None:
    entries = ctx.results.get("kinematics") or []
    if not entries:
        return None
    geom = geometry(ctx.results, ctx.task)
    if geom is None:
        return None
    res_pos = ctx.results.get("positions") or {}
    n_grid = _grid_count(ctx, entries)
    grid = entries[:n_grid]
    sgn = _rotation_sign(ctx, geom, entries)
    phi0 = res_pos.get("phi0", grid[0]["phi"])
    phase = [((float(e["phi"]) - float(phi0)) * sgn) % 360.0 for e in entries]
    phase = [0.0 if abs(p - 360.0) < 1e-9 else p for p in phase]

    # scales
    mu_v, mu_a, vA, aA = scales(entries, geom)
    pin = crank_pin(geom)
    from ..figures import nice_scale, mechanism_extent
    lo, hi = mechanism_extent(entries)
    lOA = None
    dl = geom.link(geom.drive)
    if dl is not None and len(dl.points) >= 2:
        lOA = float(np.linalg.norm(_pxy(entries[0], dl.points[1]) - _pxy(entries[0], dl.points[0])))
    mu_l = nice_scale(max((lOA or 0.0) / 50.0, float((hi - lo).max()) / 250.0))
    lengths = []
    for l in geom.links:
        if l.kind == "bar" and len(l.points) >= 2:
            L = float(np.linalg.norm(_pxy(entries[0], l.points[1]) - _pxy(entries[0], l.points[0])))
            lengths.append((f"{l.index} ({l.name}), {l.points[0]}{l.points[1]}", ctx.fmt(L),
                            ctx.fmt_fixed(L / mu_l, 1)))
    scale_rows = [
        (Markup(f"μ<sub>l</sub> — {ctx.t('kin.mu_l')}"), f"{mu_l:g} {ctx.t('kin.unit_l')}"),
        (Markup(f"μ<sub>v</sub> = v<sub>{pin}</sub>/p{plan_label(pin)} — {ctx.t('kin.mu_v')}"),
         Markup(f"{ctx.fmt(vA)} / {ctx.fmt_fixed(vA / mu_v, 2)} → {mu_v:g} {ctx.t('kin.unit_v')}")),
        (Markup(f"μ<sub>a</sub> = a<sub>{pin}</sub>/π{plan_label(pin)} — {ctx.t('kin.mu_a')}"),
         Markup(f"{ctx.fmt(aA)} / {ctx.fmt_fixed(aA / mu_a, 2)} → {mu_a:g} {ctx.t('kin.unit_a')}")),
    ]
    pos_rows = []
    if res_pos:
        pos_rows.append((ctx.t("kin.phi0"), ctx.fmt_fixed(res_pos.get("phi0"), 3) + "°"))
        if res_pos.get("extreme"):
            pos_rows.append((ctx.t("kin.extreme_angles"),
                             ", ".join(ctx.fmt_fixed(x, 3) + "°" for x in res_pos["extreme"])))
        for key, lab, unit in (("working_stroke_angle", "kin.working_angle", "°"),
                               ("idle_stroke_angle", "kin.idle_angle", "°"), ("K", "kin.K", "")):
            if res_pos.get(key) is not None:
                pos_rows.append((ctx.t(lab), ctx.fmt_fixed(res_pos[key], 3 if unit else 4) + unit))

    # summary tables
    moving_pts = []
    for l in geom.links:
        for p in l.points + ([l.com] if l.com else []):
            if p not in geom.ground and p not in moving_pts and p in entries[0]["points"]:
                moving_pts.append(p)
    link_names = [l.name for l in geom.links]
    hdr_pts = [ctx.t("common.position"), "φ, °"] + moving_pts
    v_rows = [[str(e["index"]), ctx.fmt_fixed(e["phi"], 2)] +
              [ctx.fmt(e["points"][p]["v"]) for p in moving_pts] for e in entries]
    a_rows = [[str(e["index"]), ctx.fmt_fixed(e["phi"], 2)] +
              [ctx.fmt(e["points"][p]["a"]) for p in moving_pts] for e in entries]
    hdr_l = [ctx.t("common.position"), "φ, °"] + [f"{l.index} ({l.name})" for l in geom.links]
    w_rows = [[str(e["index"]), ctx.fmt_fixed(e["phi"], 2)] +
              [Markup(f"{ctx.fmt(e['links'][n]['omega'])}<br><small>{ctx.sense(e['links'][n]['omega'])}</small>")
               for n in link_names] for e in entries]
    e_rows = [[str(e["index"]), ctx.fmt_fixed(e["phi"], 2)] +
              [Markup(f"{ctx.fmt(e['links'][n]['epsilon'])}<br><small>{ctx.sense(e['links'][n]['epsilon'])}</small>")
               for n in link_names] for e in entries]

    # plans of every position
    positions = []
    plan_csv = []
    for e in entries:
        vp = build_plan("v", e, geom, mu_v)
        ap = build_plan("a", e, geom, mu_a)
        vrows = [(Markup(sym), seg, ctx.fmt_fixed(mm, 1), ctx.fmt(val)) for sym, seg, mm, val in vp.rows()]
        arows = [(Markup(sym), seg, ctx.fmt_fixed(mm, 1), ctx.fmt(val)) for sym, seg, mm, val in ap.rows()]
        for kind, pl in (("v", vp), ("a", ap)):
            for sym, seg, mm, val in pl.rows():
                plan_csv.append([e["index"], e["phi"], kind, seg,
                                 sym.replace("<sub>", "_").replace("</sub>", "").replace("<sup>", "^").replace("</sup>", ""),
                                 float(mm), float(val)])
        ang_rows = []
        for l in geom.links:
            d = e["links"].get(l.name, {})
            ang_rows.append((f"{l.index} ({l.name})", ctx.fmt_fixed(d.get("angle"), 2),
                             ctx.fmt(d.get("omega")), ctx.sense(d.get("omega")),
                             ctx.fmt(d.get("epsilon")), ctx.sense(d.get("epsilon"))))
        positions.append({"index": e["index"], "phi": ctx.fmt_fixed(e["phi"], 2),
                          "fig": plans_svg(ctx, vp, ap), "vrows": vrows, "arows": arows,
                          "ang_rows": ang_rows})

    # diagrams
    out_name = res_pos.get("output") or getattr(getattr(ctx.task, "positions", None), "output", None) \
        or geom.links[-1].name
    curve = None
    kc = ctx.results.get("kinematics_curve")
    if kc and kc.get("phi"):
        curve = dict(kc)
        curve["phase"] = [((float(p) - float(phi0)) * sgn) % 360.0 for p in kc["phi"]]
        o = np.argsort(curve["phase"])
        for k in ("phase", "s", "v", "a"):
            if k in curve:
                curve[k] = list(np.asarray(curve[k], float)[o])
    diag, _ = diagrams_svg(ctx, geom, entries, phase, out_name, curve)

    # CSV
    header = ["index", "phi"]
    pnames = list(entries[0]["points"].keys())
    for p in pnames:
        header += [f"{p}.{k}" for k in ("x", "y", "vx", "vy", "v", "ax", "ay", "a")]
    lnames = list(entries[0]["links"].keys())
    for n in lnames:
        header += [f"{n}.{k}" for k in ("angle", "omega", "epsilon")]
    rows = []
    for e in entries:
        row = [e["index"], float(e["phi"])]
        for p in pnames:
            row += [e["points"][p].get(k) for k in ("x", "y", "vx", "vy", "v", "ax", "ay", "a")]
        for n in lnames:
            row += [e["links"][n].get(k) for k in ("angle", "omega", "epsilon")]
        rows.append(row)
    ctx.write_csv("kinematics.csv", header, rows)
    ctx.write_csv("plans.csv", ["index", "phi", "plan", "segment", "vector", "length_mm", "value"], plan_csv)

    return ctx.render("sections/kinematics.html.j2",
                      pos_rows=pos_rows, scale_rows=scale_rows, lengths=lengths,
                      fig_positions=positions_svg(ctx, geom, entries, grid), n_grid=len(grid),
                      hdr_pts=hdr_pts, v_rows=v_rows, a_rows=a_rows, hdr_l=hdr_l,
                      w_rows=w_rows, e_rows=e_rows, positions=positions, fig_diagrams=diag,
                      out_name=out_name, dense=curve is not None)
