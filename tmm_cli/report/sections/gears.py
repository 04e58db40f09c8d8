"""Report section 'gears': geometry and checks tables, the mesh drawing (three rack-generated
teeth per wheel, circles, line of action and its active part), the blocking contour and the
specific-sliding diagrams; tooth outlines exported as CSV and DXF beside the report."""
from __future__ import annotations

import math

import numpy as np

from ... import locales
from ...drawings.mesh import action_points
from ...messages import render_list
from ..notation import Term
from ...numfmt import localize

I18N = locales.table("gears", "words")

MM = 1e3


def _symbols(text: str):
    """Course symbols written with subscripts: x_min, eps_alpha, s_a, a_w, N1N2, B1B2."""
    import re
    from markupsafe import Markup, escape
    h = str(escape(text))
    h = h.replace("eps_alpha", "ε<sub>α</sub>").replace("x_min", "x<sub>min</sub>")
    h = re.sub(r"\b([sa])_([aw])\b", r"\1<sub>\2</sub>", h)
    h = re.sub(r"\b([NB])([12])([NB]|\b)", lambda m: f"{m.group(1)}<sub>{m.group(2)}</sub>{m.group(3)}", h)
    h = re.sub(r"([NB])<sub>([12])</sub>([NB])([12])", r"\1<sub>\2</sub>\3<sub>\4</sub>", h)
    h = re.sub(r"\(x([12]), x([12])\)", r"(x<sub>\1</sub>, x<sub>\2</sub>)", h)
    return Markup(h)


SCALES = (50, 40, 20, 10, 5, 4, 2.5, 2, 1, 1 / 2, 1 / 2.5, 1 / 4, 1 / 5, 1 / 10)   # GOST 2.302
AX_L, AX_B, AX_W, AX_H = 14.0, 14.0, 150.0, 130.0     # mm of paper: the mesh drawing's axes


def drawing_scale(width_mm: float, height_mm: float) -> float:
    """The largest standard scale at which a window of width x height (mm, real) fits the axes."""
    for k in SCALES:
        if width_mm * k <= AX_W and height_mm * k <= AX_H:
            return k
    return SCALES[-1]


def scale_text(k: float) -> str:
    return localize(f"{k:g}:1" if k >= 1 else f"1:{1 / k:g}")


def line_points(g) -> dict:
    """N1, N2, B1, B2 and the pole P on the line of action (m, wheel 1 at the origin, P above it)."""
    return action_points(g, (0.0, g["aw"]))


def action_arc(g, i: int) -> tuple[float, float]:
    """The arc of action on the rolling circle of wheel i, as angles (rad) from the pole's
    direction: the profile through a contact point at s along the line of action from P crosses
    the rolling circle s / r_b away from P (the involute unwinds on the base circle)."""
    la = g["line_of_action"]
    rb = g["rb"][i]
    s1, s2 = la["N1B1"] - la["N1P"], la["N1B2"] - la["N1P"]
    sg = 1.0 if i == 0 else -1.0
    a, b = sorted((-sg * s1 / rb, -sg * s2 / rb))
    return a, b


def label_boxes(g, pts: dict, span: float) -> list:
    """(name, point, box) of the labels of the line of action; the boxes (x0, y0, x1, y1, m) never
    overlap one another: each label goes beside its point, perpendicular to the line, on the
    first free side at a growing distance."""
    awa = math.radians(g["alpha_w"])
    n = np.array([math.sin(awa), math.cos(awa)])            # normal to the line of action
    h = 0.05 * span
    placed = []
    for name in ("P", "N1", "N2", "B1", "B2"):
        p = pts[name]
        w = 0.035 * span * (len(name) + 0.5)
        for k in range(1, 12):
            side = 1.0 if k % 2 else -1.0
            c = p + side * n * (0.6 + 0.9 * ((k - 1) // 2)) * h * 1.2
            box = (c[0] - w / 2, c[1] - h / 2, c[0] + w / 2, c[1] + h / 2)
            if not any(_overlap(box, b) for _, _, b in placed):
                break
        placed.append((name, p, box))
    return placed


def _overlap(a, b) -> bool:
    return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]


def mesh_window(g, span: float) -> tuple[float, float, float]:
    """(width, height, the centre's ordinate), mm real, of what the mesh drawing shows: the zone
    of 2 span x 1.5 span about the pole, each side no larger than the pair itself (with 4 % a
    side to spare); centred on the pole, or on the pair where the whole pair's height is shown."""
    ra1, ra2 = (1000.0 * float(r) for r in g["ra"])
    aw = 1000.0 * float(g["aw"])
    w = min(2.0 * span * 1000.0, 2.0 * max(ra1, ra2) * 1.08)
    pair_h = (aw + ra1 + ra2) * 1.08
    if pair_h < 1.5 * span * 1000.0:
        return w, pair_h, (aw + ra2 - ra1) / 2.0
    return w, 1.5 * span * 1000.0, 1000.0 * float(g["rw"][0])


def mesh_figure(ctx, g):
    from tmm_cli.gears.drawing import mesh
    fp = ctx.figures
    wheels = mesh(g, teeth=3)         # the stage's tooth outlines of the result, in mesh
    c2 = wheels[1]["centre"]
    fig, ax = fp.new_figure(170, 150)
    th = np.linspace(0, 2 * np.pi, 721)
    span = 4.0 * g["m"] * 3
    for i, w in enumerate(wheels):
        c, X, Y = w["centre"], w["x"], w["y"]
        ax.plot(X * MM, Y * MM, color="k", lw=1.2)
        for rad, st in ((g["rw"][i], "--"), (g["rb"][i], "-."), (g["ra"][i], ":"), (g["rf"][i], ":"),
                        (g["r"][i], (0, (1, 3)))):
            ax.plot((c[0] + rad * np.cos(th)) * MM, (c[1] + rad * np.sin(th)) * MM, ls=st, lw=0.6, color="0.4")
    pts = line_points(g)
    ax.plot([pts["N1"][0] * MM, pts["N2"][0] * MM], [pts["N1"][1] * MM, pts["N2"][1] * MM], color="tab:blue", lw=0.8)
    ax.plot([pts["B1"][0] * MM, pts["B2"][0] * MM], [pts["B1"][1] * MM, pts["B2"][1] * MM], color="tab:red", lw=2.5)
    # the working parts of the profiles: from the radius of the active point (B2 on wheel 1, B1 on
    # wheel 2: where the profile leaves / enters the contact) to the tip
    for i, (w, b) in enumerate(zip(wheels, ("B1", "B2"))):
        c, X, Y = w["centre"], w["x"], w["y"]
        r_lo = float(np.hypot(*(pts[b] - np.asarray(c, float))))
        rr = np.hypot(X - c[0], Y - c[1])
        work = (rr >= r_lo - 1e-12) & (rr <= g["ra"][i] * (1 - 2e-3))      # the flanks, not the tip land
        Xw = np.where(work, X, np.nan)
        Yw = np.where(work, Y, np.nan)
        ax.plot(Xw * MM, Yw * MM, color="tab:orange", lw=2.2, solid_capstyle="butt")
    for (c, i, ang0) in (((0.0, 0.0), 0, math.pi / 2), (tuple(c2), 1, -math.pi / 2)):
        t0, t1 = action_arc(g, i)
        ta = np.linspace(ang0 + t0, ang0 + t1, 40)
        rw = g["rw"][i]
        ax.plot((c[0] + rw * np.cos(ta)) * MM, (c[1] + rw * np.sin(ta)) * MM, color="tab:green", lw=2.0)
    for name, p, box in label_boxes(g, pts, span):
        ax.plot(p[0] * MM, p[1] * MM, "o", ms=2.5, color="tab:red" if name.startswith("B") else "tab:blue")
        ax.annotate(f"${name[0]}_{{{name[1:]}}}$" if name[1:].isdigit() else name,
                    ((box[0] + box[2]) / 2 * MM, (box[1] + box[3]) / 2 * MM), ha="center", va="center", fontsize=7)
    # a standard drawing scale (GOST 2.302): the axes are exactly AX_W x AX_H mm of paper. The
    # window is the zone of the mesh about the pole (12 modules either side), or the whole pair
    # where that is smaller (few teeth: z = 5 and 8 filled a fifth of the axes at 1:1)
    w, h, yc = mesh_window(g, span)
    k = drawing_scale(w, h)
    ax.set_position([AX_L / 170, AX_B / 150, AX_W / 170, AX_H / 150])
    ax.set_xlim(-AX_W / 2 / k, AX_W / 2 / k)
    ax.set_ylim(yc - AX_H / 2 / k, yc + AX_H / 2 / k)
    ax.set_xlabel(ctx.t("gears.mm") + ", " + ctx.t("gears.scale", s=scale_text(k)))
    return fig


CONTOUR_STYLES = (("tab:blue", "-"), ("tab:red", "--"), ("tab:green", "-."), ("tab:purple", ":"),
                  ("tab:orange", (0, (5, 1, 1, 1, 1, 1))), ("tab:olive", (0, (8, 2))),   # not brown: beside red dashes
                  ("tab:cyan", (0, (1, 1))), ("black", (0, (3, 1, 3, 1, 1, 1))))


def contour_styles(names: list) -> dict:
    """Each check of the blocking contour (undercut_1, sharpening_2, ...) its own colour and its own
    line style, in the order given (the legend tells them apart in colour and in print)."""
    return {name: CONTOUR_STYLES[i % len(CONTOUR_STYLES)] for i, name in enumerate(names)}


def contour_figure(ctx, g):
    fp = ctx.figures
    bc = g["blocking_contour"]
    fig, ax = fp.new_figure(120, 100)
    styles = contour_styles(list(bc["lines"]))
    seen = set()
    for name, segs in bc["lines"].items():
        col, ls = styles[name]
        for seg in segs:
            a = np.asarray(seg)
            kind = next(k for k in ("undercut", "sharpening", "contact_ratio", "interference") if name.startswith(k))
            lab = Term(ctx.t(f"gears.{kind}_l") + (f" {name.rsplit('_', 1)[-1]}" if name[-1:].isdigit() else ""))
            ax.plot(a[:, 0], a[:, 1], color=col, ls=ls, lw=1.1, label=None if name in seen else lab)
            seen.add(name)
    # the admissible region (the stage's polygons: outer ring, then holes)
    for rings in bc["region"]:
        ax.fill_rings(rings, facecolor="#cfe8cf", zorder=0)
    ax.plot(*bc["chosen"], "ko", ms=4)
    ax.set_xlim(*bc["x1_range"])
    ax.set_ylim(*bc["x2_range"])
    ax.set_xlabel("$x_1$")
    ax.set_ylabel("$x_2$")
    ax.legend(loc="upper right", fontsize=6)
    ax.grid(True, lw=0.3)
    return fig


def sliding_figure(ctx, g):
    fp = ctx.figures
    sl = g["sliding"]
    fig, ax = fp.new_figure(150, 80)
    X = np.array(sl["X"]) * MM
    for key, col, lab in (("lambda1", "tab:blue", "$\\lambda_1$"), ("lambda2", "tab:red", "$\\lambda_2$")):
        v = np.array([np.nan if y is None else y for y in sl[key]], float)
        v = np.where((v < -5) | (v > 1.5), np.nan, v)     # drawn over -5 <= λ <= 1.5 only
        ax.plot(X, v, color=col, label=lab)
    for name, x in sl["marks"].items():
        if x is not None:
            ax.axvline(x * MM, color="0.6", lw=0.5)
            # the point's name inside the top of the graph (the scale stands above it)
            ax.annotate(f"${name[0]}_{{{name[1:]}}}$" if name[1:].isdigit() else name, (x * MM, 1.0),
                        xycoords=("data", "axes fraction"), xytext=(2, -10), textcoords="offset points",
                        fontsize=7)
    ax.axvspan(sl["marks"]["B1"] * MM, sl["marks"]["B2"] * MM, color="0.9")
    ax.set_ylim(-5, 1.5)
    ax.set_xlabel(f"$N_1X$, {ctx.t('gears.mm')}")
    ax.set_ylabel("λ, 1")
    ax.legend(fontsize=7)
    ax.grid(True, lw=0.3)
    # the ordinate at a standard scale μλ (1/mm), stated; laid out with the axis label inside
    fp.std_graph(fig, [ax], ctx.t("kin.mm"))
    return fig


def build(ctx) -> str | None:
    g = (ctx.results or {}).get("gears")
    if not g:
        return None
    f = ctx.fmt
    t = ctx.t
    from markupsafe import Markup, escape
    mm, deg = t("gears.mm"), t("gears.deg")

    def sym(html, unit=""):
        return Markup(html + (f", {unit}" if unit else ""))

    def row(key, html, value, unit=""):
        return ((escape(t(key)) + Markup(", ")) + sym(html, unit), value)
    rows = [row("g.aw", "a<sub>w</sub>", f(g["aw"] * MM, 6), mm),
            row("g.alpha_w", "α<sub>w</sub>", f(g["alpha_w"], 6), deg),
            row("g.inv", "inv α<sub>w</sub>", f(g["inv_alpha_w"], 6)),
            row("g.y", "y", f(g["y"], 6)), row("g.dy", "Δy", f(g["dy"], 6)),
            row("g.eps", "ε<sub>α</sub>", f(g["eps_alpha"], 5)),
            row("g.p", "p", f(g["p"] * MM, 6), mm), row("g.pb", "p<sub>b</sub>", f(g["pb"] * MM, 6), mm),
            row("g.h", "h", f(g["h"] * MM, 6), mm)]
    per = [("g.x", "x", "x", 1, ""), ("g.x_min", "x<sub>min</sub>", "x_min", 1, ""),
           ("g.r", "r", "r", MM, mm), ("g.rb", "r<sub>b</sub>", "rb", MM, mm),
           ("g.rw", "r<sub>w</sub>", "rw", MM, mm), ("g.ra", "r<sub>a</sub>", "ra", MM, mm),
           ("g.rf", "r<sub>f</sub>", "rf", MM, mm), ("g.s", "s", "s", MM, mm), ("g.e", "e", "e", MM, mm),
           ("g.sa", "s<sub>a</sub>", "sa", MM, mm), ("g.sb", "s<sub>b</sub>", "sb", MM, mm)]
    wheel_rows = [((escape(t(key)) + Markup(", ")) + sym(html, unit), f(g[k][0] * sc, 6), f(g[k][1] * sc, 6))
                  for key, html, k, sc, unit in per]
    la = g["line_of_action"]

    def seg_html(k):
        return "".join(f"{c}<sub>{n}</sub>" if n else c for c, n in
                       __import__("re").findall(r"([A-Za-z])(\d*)", k)) if k[:1] in "NB" else k
    la_rows = [(((escape(t('g.' + k)) + Markup(", ")) + sym(seg_html(k), mm)) if k[:1] in "NB" else
                ((escape(t('g.' + k)) + Markup(", ")) + sym("", mm)[2:]) if not t("g." + k).startswith("g.")
                else k + ", " + mm, f(v * MM, 6)) for k, v in la.items() if v is not None]
    ch = g["checks"]
    yes, no = t("gears.defect"), t("gears.ok")
    check_rows = [(t("gears.undercut"), yes if ch["undercut"][0] else no, yes if ch["undercut"][1] else no),
                  (t("gears.sharpening", k=g.get("sa_min", 0.25)), yes if ch["sharpening"][0] else no,
                   yes if ch["sharpening"][1] else no),
                  (t("gears.contact"), (t("gears.formal") if ch["interference"] else t("gears.formal_pointed"))
                   if g.get("eps_alpha_formal") else yes if ch["contact_ratio_low"] else no, ""),
                  (t("gears.interference"), *(yes if v else no for v in g["checks_detail"]["interference"]))]
    check_rows = [(_symbols(r[0]),) + tuple(r[1:]) for r in check_rows]
    figs = []
    # the specific-sliding diagrams right under the mesh, as on the sheet
    for fn, cap in ((mesh_figure, "gears.mesh_caption"), (sliding_figure, "gears.sliding_caption"),
                    (contour_figure, "gears.contour_caption")):
        figs.append((ctx.svg(fn(ctx, g), "gear-" + fn.__name__.replace("_figure", "")), _symbols(t(cap))))
    from tmm_cli.gears.drawing import outline_csv, outline_dxf, outlines
    files = []
    polys = {}
    for i, (X, Y) in enumerate(outlines(g, teeth=3)):
        files.append(ctx.write_file(f"gears_wheel{i + 1}_outline.csv", outline_csv(X, Y)).name)
        polys[f"wheel{i + 1}"] = (X, Y + (g["aw"] if i else 0.0))
    files.append(ctx.write_file("gears_outline.dxf", outline_dxf(polys)).name)
    sl = g["sliding"]
    files.append(ctx.write_csv("gears_sliding.csv", ["X_m", "lambda1", "lambda2"],
                               zip(sl["X"], sl["lambda1"], sl["lambda2"])).name)
    rule_name = t(f"g.rule.{g['rule']}") if g.get("rule") else None
    if rule_name and rule_name.startswith("g.rule."):
        rule_name = g["rule"]
    rule = t("gears.rule", rule=rule_name) if g.get("rule") else None
    return ctx.render("sections/gears.html.j2", rows=[r[:2] for r in rows], wheel_rows=wheel_rows,
                      la_rows=la_rows, check_rows=check_rows, figs=figs, files=files, rule=rule,
                      warnings=render_list(g, ctx.lang))
