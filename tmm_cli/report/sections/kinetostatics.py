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

import math

import numpy as np
from markupsafe import Markup, escape

from ... import locales
from ...messages import unit as spelt
from .. import figures
from ..context import values_of
from ..course import position_label
from ..svgdraw import Canvas
from ...drawings import forces as D
from ...drawings.forces import (KIND_COLOR, group_couples, group_force_data, group_forces,  # noqa: F401
                                label_html, label_parts, links_by_name, polygon, position_rows)

I18N = locales.table("kinetostatics", "words")

MAX_FIG_POSITIONS = 24       # pages of drawings for at most this many positions (time, size)
ROW_H = 72.0                 # mm: one row (a group's diagram + its polygon)
GROUP_W = 90.0               # mm: width of a group's diagram
CRANK_W = 50.0               # mm: the input link's diagram in the last row
FIG_W = 170.0                # mm
PAGE_H = 245.0               # mm of drawings per page at most


LEVER_H = 110.0              # mm: Zhukovsky's lever, a figure of its own under the groups ...
LEVER_H_MAX = 200.0          # mm: ... higher, up to this, for a tall plan (its page has room)


def lever_box_height(e, kin_e) -> float:
    """The report's lever figure's height (mm): LEVER_H, or up to LEVER_H_MAX for a tall
    turned plan (drawings.forces.lever_height)."""
    return D.lever_height(e, kin_e, FIG_W, LEVER_H, LEVER_H_MAX)


def lever_scale(e, kin_e, w: float | None = None, h: float | None = None) -> float:
    """The standard μv at which Zhukovsky's lever of a position is drawn in a box w x h
    mm (the report's, by default: lever_box_height), the largest at which it fits; the
    worked section's lever is at the same."""
    return D.lever_scale(e, kin_e, FIG_W if w is None else w, lever_box_height(e, kin_e) if h is None else h)


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
            norms = D.force_norms(forces)
            mu_l = D.group_panel(ctx, cv, (0, y, wd, ROW_H), kin_e, links, g, forces, couples, title, norms)
            vecs = []
            mu_F, T = D.polygon_panel(ctx, cv, (wd + 1, y, FIG_W - wd - 1, ROW_H), forces, norms, vecs)
            drawn.append({"group": g, "mu_l": mu_l, "mu_F": mu_F, "tips": T, "vectors": vecs})
            cv.line((wd, y + 1), (wd, y + ROW_H - 1), "#bbb", 0.2, z=0)
        figs.append(figures.named(cv.to_svg(), figures.pos_name("groups", e["index"])))
        start = stop
    lh = lever_box_height(e, kin_e)
    cv = Canvas(FIG_W, lh)
    mu_v = D.lever_panel(ctx, cv, (0, 0, FIG_W, lh), e, kin_e, pin, omega1, info.get("balance_kind"))
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
    from ...drawings.words import balance_sub
    sub = balance_sub(ctx.lang)
    a1.set_title(f"$M_{{{sub}}}$" if key == "balancing_moment" else f"$P_{{{sub}}}$", fontsize=8)
    for j in info["joints"]:
        jk = j["key"]
        vals = [nan if (v := r[1]["reactions"][jk]["R"]) is None else v for r in rows]
        a2.plot(q, vals, f"{dot}-", label=f"$R_{{{j['key'][1:]}}}$", lw=0.8, ms=3)
    # inside the axes, where the curves leave it room: right of them the standard μφ put the axes'
    # end 9 mm from the figure's, and a PDF clipped the names there ('R01' read 'R0')
    a2.legend(ncol=1, fontsize=6.5, loc="best", frameon=True)
    a2.set_ylabel("|R|, " + ctx.t("kst.N"))
    a2.set_xlabel(ctx.t("kst.rotation"))
    a2.set_xticks(np.arange(0, 361, 30))
    a2.set_xlim(0, 360)
    a2.grid(True, lw=0.3)
    fig.subplots_adjust(left=0.1, right=0.9, top=0.93, bottom=0.1, hspace=0.3)
    figures.std_graph(fig, (a1, a2), ctx.t("kin.mm"), x_axis=a2, tight=False)      # μM, μR, μφ
    return ctx.svg(fig, "balancing-cycle")


# ----------------------------------------------------------------- singular positions
SINGULAR_COLOR = "#c0392b"      # the links that make the equations singular
COLLINEAR_TOL = 1e-6            # sine of the angle between two links taken as in line


def collinear_dyads(geom, entry) -> list[tuple[int, int, str, str, str]]:
    """The pairs of moving links joined by a pin whose pins lie on one line at the kinematics
    entry (a dead point: the dyad cannot pass a moment): [(link a, link b, pin of a, the
    common pin, pin of b)]."""
    P = entry["points"]
    pins: dict[int, list[str]] = {}
    for j in geom.joints:
        if j.kind == "R" and j.point in P:
            for k in (j.a, j.b):
                if j.point not in pins.setdefault(k, []):
                    pins[k].append(j.point)

    def xy(p):
        return np.array([float(P[p]["x"]), float(P[p]["y"])])
    out = []
    for j in geom.joints:
        if j.kind != "R" or 0 in (j.a, j.b) or j.point not in P:
            continue
        X = xy(j.point)
        for Y in pins.get(j.a, []):
            for Z in pins.get(j.b, []):
                if j.point in (Y, Z) or Y == Z:
                    continue
                u, v = xy(Y) - X, xy(Z) - X
                nu, nv = float(np.hypot(*u)), float(np.hypot(*v))
                if nu > 0 and nv > 0 and abs(float(u[0] * v[1] - u[1] * v[0])) <= COLLINEAR_TOL * nu * nv:
                    out.append((j.a, j.b, Y, j.point, Z))
    return out


def singular_figures(ctx, geom, entries, info) -> list[tuple]:
    """The mechanism at each singular angle of the balance link (results ``singular_positions``):
    [(svg, caption)]; the links of a dyad in line highlighted."""
    from .. import figures as F
    out = []
    ranges = F.slider_ranges(entries, geom) if entries else {}
    for k, e in enumerate(ctx.results.get("singular_positions") or []):
        if any(v is None for d in e["points"].values() for v in d.values()):
            continue                     # (a position without finite coordinates is not drawn)
        lo, hi = F.mechanism_extent([e])
        for a, b in ranges.values():
            lo, hi = np.minimum(lo, np.minimum(a, b)), np.maximum(hi, np.maximum(a, b))
        view, unit, title = F.figure_for_box(lo, hi, 110.0, min_h=40.0, max_h=90.0, margin_mm=10.0,
                                             lang=ctx.lang)
        F.draw_mechanism(view, geom, e, unit, ranges=ranges, taken=[title])
        dyads = collinear_dyads(geom, e)
        P = e["points"]
        for a, b, Y, X, Z in dyads:
            for p, q in ((Y, X), (X, Z)):
                view.line([[P[p]["x"], P[p]["y"]], [P[q]["x"], P[q]["y"]]], SINGULAR_COLOR, 2.4, z=3)
        phi = ctx.fmt_fixed(e["phi"], 3)
        if dyads:
            why = "; ".join(ctx.t("kst.singular_dyad", a=a, b=b, pts=f"{Y}, {X}, {Z}") for a, b, Y, X, Z in dyads)
        else:
            why = ctx.t("kst.singular_other")
        out.append((ctx.svg(view, f"singular-{k + 1}"),
                    ctx.t("kst.singular_caption", phi=phi, why=why, balance=info["balance"])))
    return out


# ----------------------------------------------------------------- section
def build(ctx) -> str | None:
    entries = ctx.results.get("kinetostatics")
    info = ctx.results.get("kinetostatics_info")
    if not entries or not info:
        return None
    fmt = ctx.fmt
    lang = ctx.lang
    links = links_by_name(ctx.results)
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
    from ..course import course_entries, cycle_order, grid_size
    # the task may choose some positions (kinetostatics.positions: [2, 5]): the grid's ones are
    # those numbered below the grid's size, only the rest are extras (marked)
    size = grid_size(ctx.results)
    n_grid = len(entries) if size is None else sum(1 for e in entries if int(e["index"]) < size)
    mark = n_grid if size is None else size
    # the tables and drawings in the order of the crank's turn, the extras marked
    shown = cycle_order(course_entries(entries, n_grid), phi0, sign)
    mb_rows = []
    csv_rows = []
    # the CSV row of every position (a fine grid has thousands) read by values_of
    values, xyr = values_of(keys + ("discrepancy", "efficiency")), values_of(("x", "y", "R"))
    jkeys = [j["key"] for j in info["joints"]]
    for e in shown:
        disc = None if e.get("discrepancy") is None else 100.0 * e["discrepancy"]
        row = [position_label(e, mark), ctx.fmt_fixed(e["phi"], 2)] + [fmt(e.get(k), 6) for k in keys] + [
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
        row = [position_label(e, mark)]
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
        eff_rows = [[position_label(e, mark), ctx.fmt_fixed(e["phi"], 2), fmt(e.get("friction_power"), 5),
                     fmt(e.get("driving_power"), 5), fmt(e.get("efficiency"), 4)] for e in shown]
    # loads of every position in one table: the varying loads by position, the constant ones below
    loads_hdr, loads_rows, const = _loads_table(ctx, shown, mark)
    # per position drawings
    from ...plans import crank_pin, geometry
    geom = geometry(ctx.results)
    geom_pin = crank_pin(geom) if geom is not None else None
    positions = []
    for e in shown[:MAX_FIG_POSITIONS]:
        if "loads" not in e or e["index"] not in kin:
            continue
        ke = kin[e["index"]]
        w1 = (ctx.results.get("drive") or {}).get("omega")
        if e.get("balancing_moment") is None and e.get("balancing_force") is None:
            figs = []
        else:
            figs, _ = position_figures(ctx, e, ke, info, links, geom_pin, w1)
        # each figure its own caption (a note numbers them: the groups' said the lever's), every
        # page of groups (a six-bar's may fill two) and the lever, headed by the position
        head = ctx.t("kst.position_n", i=position_label(e, mark), phi=e["phi"])
        caps = [f"{head}. {ctx.t('kst.fbd_caption')}"] * (len(figs) - 1) + [f"{head}. {ctx.t('kst.lever_caption')}"]
        positions.append({"index": position_label(e, mark), "phi": e["phi"], "figs": list(zip(figs, caps))})
    sing = ctx.results.get("singular") or []
    sing_figs = singular_figures(ctx, geom, ctx.results.get("kinematics") or [], info) \
        if sing and geom is not None else []
    bk = ctx.t("kst.bk_moment") if info["balance_kind"] == "moment" else ctx.t("kst.bk_force")
    return ctx.render("sections/kinetostatics.html.j2", info=info, mb_hdr=hdr, mb_rows=mb_rows,
                      r_hdr=r_hdr, r_rows=r_rows, eff_rows=eff_rows, positions=positions,
                      balance_text=f"{info['balance']} ({bk})",
                      loads_hdr=loads_hdr, loads_rows=loads_rows,
                      loads_note=Markup(escape(ctx.t("kst.loads_note", const="\u0001"))).replace(
                          "\u0001", const or "—"),
                      fig_diagrams=_diagrams_fig(ctx, info, shown, mark),
                      fig_cycle=_cycle_fig(ctx, entries, phi0, sign, info),
                      singular=", ".join(ctx.fmt_fixed(s, 6) for s in sing), sing_figs=sing_figs,
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
            F_ = f["F"]
            fval[f["name"]].append(None if F_ is None or None in F_ else float(np.hypot(*F_)))   # None: no limit
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
