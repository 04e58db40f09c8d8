"""Report section 'synthesis': the lever mechanism designed from K and the stroke --
the lengths, the analysed H, K, theta, psi and gamma_min, the construction (extreme
positions, the angle theta, the circle through the extreme points, the chosen
solution) and the transmission angle over the cycle. Drawn directly as SVG."""
from __future__ import annotations

import math

import numpy as np

from ... import locales
from ...messages import unit
from ..notation import Term

I18N = locales.table("synthesis", "words")

_LEN = locales.table("synthesis", "lengths")


def _length_name(key: str, lang: str, typ: str | None = None):
    """A link length's name (``crank l_OA``), its notation written with subscripts in the HTML;
    the rocker of a slotted-lever type (``typ``) is its slotted link."""
    if key == "rocker" and typ in ("slotted_lever", "shaper"):
        key = "slotted_rocker"
    return Term(_LEN.get(lang, _LEN["en"]).get(key, key))
_SCALES = (1, 2, 2.5, 4, 5, 10, 15, 20, 25, 40, 50, 75, 100, 200, 500, 1000)


def _pts(r: dict) -> dict:
    c = r.get("construction") or {}
    return {k: np.asarray(v, float) for k, v in c.items() if isinstance(v, list) and len(v) == 2}


def construction_svg(r: dict, w_mm: float = 165.0, h_mm: float = 100.0) -> tuple[str, float]:
    """(svg, scale denominator) of the construction of a `synthesis` result."""
    from ..svgdraw import Canvas

    c = r["construction"]
    P = _pts(r)
    L = r["lengths"]
    typ = r["type"]
    a = L["crank"]
    extra = []
    circ = c.get("circle")
    if typ == "crank_rocker":
        o1, rc = P["O1"], L["rocker"]
        extra += [o1 + (rc, rc), o1 - (rc, rc)]
    allp = np.array(list(P.values()) + extra + [(a, a), (-a, -a)])
    lo, hi = allp.min(axis=0), allp.max(axis=0)
    span = np.maximum(hi - lo, 1e-9)
    need = max(span[0] / (w_mm - 16), span[1] / (h_mm - 12)) * 1000.0   # mm of paper per m -> 1:need
    scale = next((s for s in _SCALES if s >= need), need)
    k = 1000.0 / scale
    cv = Canvas(w_mm, h_mm)
    off = np.array([w_mm, h_mm]) / 2 - (lo + hi) / 2 * k

    def m(p):
        return np.asarray(p, float) * k + off

    def label(p, s, d=(2.2, 2.2)):
        q = m(p)
        cv.text(q[0] + d[0], q[1] + d[1], s, size=7, italic=True, halo=True)

    def arc(centre, r_mm, a1, a2, text):
        a2 = a1 + ((a2 - a1 + math.pi) % (2 * math.pi) - math.pi)
        t = np.linspace(a1, a2, 24)
        q = m(centre)
        cv.polyline([q + r_mm * np.array([math.cos(x), math.sin(x)]) for x in t], "#b00", 0.3)
        mid = (a1 + a2) / 2
        cv.text(q[0] + (r_mm + 3) * math.cos(mid), q[1] + (r_mm + 3) * math.sin(mid), text, size=7, color="#b00")

    if circ:
        # the circle through O and the extreme points, clipped to the drawing
        t = np.linspace(0, 2 * math.pi, 721)
        cc, R = np.asarray(circ["centre"]), circ["radius"]
        run = []
        for x in t:
            q = m(cc + R * np.array([math.cos(x), math.sin(x)]))
            if 1.0 <= q[0] <= w_mm - 1.0 and 1.0 <= q[1] <= h_mm - 1.0:
                run.append(q)
            elif run:
                if len(run) > 1:
                    cv.polyline(run, "#777", 0.2, dash="1.5,1")
                run = []
        if len(run) > 1:
            cv.polyline(run, "#777", 0.2, dash="1.5,1")
    O = P["O"]
    cv.ground(m(O))
    label(O, "O", (-3, 2.5))
    if typ in ("slider_crank", "offset_slider_crank", "crank_rocker"):
        p1, p2 = (P["B1"], P["B2"]) if "B1" in P else (P["C1"], P["C2"])
        u1, u2 = p1 / np.linalg.norm(p1), p2 / np.linalg.norm(p2)
        A1, A2 = -a * u1, a * u2
        # the crank circle and the two extreme positions (crank and coupler collinear)
        t = np.linspace(0, 2 * math.pi, 121)
        cv.polyline([m(a * np.array([math.cos(x), math.sin(x)])) for x in t], "#555", 0.2)
        for A, B in ((A1, p1), (A2, p2)):
            cv.line(m(O), m(A), "#000", 0.5)
            cv.line(m(A), m(B), "#1f4e99", 0.4)
            cv.dot(m(A), 0.6)
            cv.dot(m(B), 0.6)
        cv.line(m(O), m(p1), "#888", 0.2, dash="3,1,0.5,1")
        nm = ("B", "B") if "B1" in P else ("C", "C")
        label(A1, "A₁", (-2.5, -3))
        label(A2, "A₂", (0, -3))
        label(p1, f"{nm[0]}₁")
        label(p2, f"{nm[1]}₂")
        arc(O, 9.0, math.atan2(p1[1], p1[0]), math.atan2(p2[1], p2[0]), "θ")
        if "guide_y" in c:
            y = c["guide_y"]
            x0, x1 = lo[0] - 0.05 * span[0], hi[0] + 0.05 * span[0]
            cv.line(m((x0, y)), m((x1, y)), "#000", 0.25, dash="4,1,1,1")
            q1, q2 = m(p1), m(p2)
            cv.line(q1 + (0, -6), q2 + (0, -6), "#000", 0.2)
            cv.text((q1[0] + q2[0]) / 2, q1[1] - 8.5, "H", size=7, italic=True)
        if typ == "crank_rocker":
            O1 = P["O1"]
            cv.ground(m(O1))
            label(O1, "O₁", (2.5, 2.5))
            b1, b2 = math.atan2(*(p1 - O1)[::-1]), math.atan2(*(p2 - O1)[::-1])
            rr = L["rocker"]
            t = np.linspace(b1, b1 + ((b2 - b1 + math.pi) % (2 * math.pi) - math.pi), 40)
            cv.polyline([m(O1 + rr * np.array([math.cos(x), math.sin(x)])) for x in t], "#000", 0.2)
            cv.line(m(O1), m(p1), "#000", 0.5)
            cv.line(m(O1), m(p2), "#000", 0.5)
            arc(O1, 12.0, b1, b2, "ψ")
    else:
        O1 = P["O1"]
        cv.ground(m(O1))
        label(O1, "O₁", (2.5, -2.5))
        t = np.linspace(0, 2 * math.pi, 121)
        cv.polyline([m(a * np.array([math.cos(x), math.sin(x)])) for x in t], "#555", 0.25)
        for An, Bn in (("A1", "B1"), ("A2", "B2")):
            cv.line(m(O1), m(P[Bn]), "#000", 0.5)
            cv.line(m(O), m(P[An]), "#000", 0.5)
            cv.dot(m(P[An]), 0.6)
        label(P["A1"], "A₁", (-4, 0))
        label(P["A2"], "A₂", (3, 0))
        b1 = math.atan2(*(P["B1"] - O1)[::-1])
        b2 = math.atan2(*(P["B2"] - O1)[::-1])
        arc(O1, 14.0, b1, b2, "ψ")
        # theta between OA2 and OA1 produced beyond O (drawn thin, dash-dotted)
        cv.line(m(O), m(-np.asarray(P["A1"], float)), "#888", 0.2, dash="3,1,0.5,1")
        arc(O, 6.0, math.atan2(*P["A2"][::-1]), math.atan2(*P["A1"][::-1]) + math.pi, "θ")
        if "guide_y" in c:
            y = c["guide_y"]
            x0, x1 = lo[0] - 0.05 * span[0], hi[0] + 0.05 * span[0]
            cv.line(m((x0, y)), m((x1, y)), "#000", 0.25, dash="4,1,1,1")
            for n in ("C1", "C2"):
                cv.dot(m(P[n]), 0.6)
            label(P["C1"], "C₁", (-3, 2.5))
            label(P["C2"], "C₂", (3, 2.5))
    return cv.to_svg(), scale


def gamma_svg(r: dict, t_turn: str, w_mm: float = 165.0, h_mm: float = 60.0, mm: str = "mm") -> str:
    """gamma over the cycle: a direct-SVG chart with the least value marked, both axes at
    a standard scale (μφ, μγ in °/mm from 1, 2, 2.5, 4, 5 x 10^k), stated."""
    from ...scales import nice_scale
    from ..svgdraw import Canvas

    tr = r["transmission"]
    x = np.asarray(tr["turn"], float)
    g = np.asarray(tr["gamma"], float)
    cv = Canvas(w_mm, h_mm)
    gmax = 90.0
    gmin_axis = max(0.0, 10.0 * math.floor(min(g.min(), r["gamma_min"]) / 10.0) - 10.0)
    mu_phi = nice_scale(360.0 / (w_mm - 20.0))          # deg per mm of paper
    mu_g = nice_scale((gmax - gmin_axis) / (h_mm - 16.0))
    x0, y0, W, H = 14.0, 10.0, 360.0 / mu_phi, (gmax - gmin_axis) / mu_g

    def m(u, v):
        return (x0 + u / 360.0 * W, y0 + (v - gmin_axis) / (gmax - gmin_axis) * H)

    cv.line((x0, y0), (x0 + W, y0), "#000", 0.3)
    cv.line((x0, y0), (x0, y0 + H), "#000", 0.3)
    for u in range(0, 361, 60):
        cv.line(m(u, gmin_axis), (m(u, gmin_axis)[0], y0 - 1.2), "#000", 0.25)
        cv.text(m(u, gmin_axis)[0], y0 - 3.5, str(u), size=6.5)
    for v in range(int(gmin_axis), 91, 10 if gmax - gmin_axis <= 60 else 20):
        cv.line((x0 - 1.2, m(0, v)[1]), (x0, m(0, v)[1]), "#000", 0.25)
        cv.text(x0 - 2.0, m(0, v)[1], str(v), size=6.5, anchor="end")
    cv.text(x0 + W, y0 - 7.5, f"{t_turn};  μφ = {mu_phi:g} °/{mm}", size=6.5, anchor="end")
    cv.text(x0 + 2, y0 + H + 3, "γ, °", size=7, anchor="start", italic=True)
    cv.text(x0 + 12, y0 + H + 3, f"μγ = {mu_g:g} °/{mm}", size=6.5, anchor="start")   # beside "γ, °"
    cv.polyline([m(u, v) for u, v in zip(x, g)], "#1f4e99", 0.45)
    gm = r["gamma_min"]
    cv.line(m(0, gm), m(360, gm), "#b00", 0.25, dash="2,1")
    cv.text(m(360, gm)[0] - 1, m(360, gm)[1] + 2.5, "γ", sub="min", after=f" = {gm:.3f}°", size=6.5, color="#b00",
            anchor="end")
    return cv.to_svg()


def error_chart(ctx, r):
    """The structural error over the range of x."""
    from ..svgchart import subplots
    c = r["error_curve"]
    fig, ax = subplots(150, 70)
    ax.plot(c["x"], c["error"], lw=1.2)
    pts = r["precision_points"]
    ax.plot([p["x"] for p in pts], [0.0] * len(pts), "ko", ms=3)
    ax.axhline(0.0, color="k", lw=0.6)
    ax.set_xlabel(ctx.t("syn.fn.x"))
    ax.set_ylabel(ctx.t("syn.fn.error_axis"))
    ax.grid(True)
    return fig


def _function(ctx, r) -> str:
    f, t = ctx.fmt, ctx.t
    mu = unit("m", ctx.lang)
    lens = [(_length_name(k, ctx.lang), f"{f(v, 6)} {mu}") for k, v in r["lengths"].items()]
    pts = r["precision_points"]
    info = [(t("syn.type"), t("syn.type.function")), (t("syn.fn.K"), ", ".join(f(k, 6) for k in r["K"])),
            (t("syn.fn.grashof"), t(f"syn.grashof.{r['grashof']}"))]
    if r.get("gamma_min") is not None:       # over the generator's working range
        info.append((t("syn.fn.gamma"), t("syn.gamma_at", g=f(r["gamma_min"], 6), p=f(r.get("gamma_min_phi"), 5))))
    rows = [(f(p["x"], 6), f(p["phi"], 6), f(p["psi"], 6), f(p["psi_generated"], 6)) for p in pts]
    se = r["structural_error"]
    return ctx.render("sections/synthesis_function.html.j2", info=info, lens=lens, rows=rows,
                      method=t("syn.fn.method", f=r["function"], n=len(pts), ls=t("syn.fn.ls") if len(pts) > 3 else ""),
                      error=t("syn.fn.error", e=f(se["max"], 4), x=f(se["at_x"], 5)),
                      fig=ctx.svg(error_chart(ctx, r), "synthesis-structural-error"))


def build(ctx) -> str | None:
    r = (ctx.results or {}).get("synthesis")
    if not r:
        return None
    if r.get("type") == "function":
        return _function(ctx, r)
    if r.get("type") in ("positions", "path"):
        from . import synthesis_motion
        names = {k: _length_name(k, ctx.lang) for k in _LEN.get(ctx.lang, _LEN["en"])}
        return getattr(synthesis_motion, f"build_{r['type']}")(ctx, r, names)

    f, t, lang = ctx.fmt, ctx.t, ctx.lang
    mu = unit("m", lang)
    typ = t(f"syn.type.{r['type']}")
    lens = [(_length_name(k, lang, r["type"]), f"{f(v, 6)} {mu}") for k, v in r["lengths"].items()]
    out = r.get("output", "")
    info = [(t("syn.type"), typ)]
    if r.get("H") is not None:
        info.append((t("syn.H"), f"{f(r['H'], 6)} {mu}"))
    info += [(t("syn.K"), f(r["K"], 6)), (t("syn.theta"), f"{f(r['theta'], 6)}°")]
    if r.get("psi") is not None:
        info.append((t("syn.psi"), f"{f(r['psi'], 6)}°"))
    info.append((t("syn.gamma"), t("syn.gamma_at", g=f(r["gamma_min"], 6), p=f(r.get("gamma_min_phi"), 5))))
    info.append((t("syn.working", o=ctx.link_ref(out)), t(f"syn.{r['working']}")))
    sols = []
    for s in r.get("solutions") or []:
        sols.append([t(f"syn.side.{s['side']}") if s.get("side") else ""] + [f(s[k], 6) for k in r["lengths"] if k in s]
                    + [f(s["gamma_min"], 6), t("syn.chosen") if s.get("chosen") else ""])
    sol_head = ([t("syn.side")] + [_length_name(k, lang, r["type"]) for k in r["lengths"]
                                   if r.get("solutions") and k in r["solutions"][0]] + [Term("γ_min, °"), ""])
    svg, scale = construction_svg(r)
    return ctx.render("sections/synthesis.html.j2", info=info, lens=lens, sols=sols, sol_head=sol_head,
                      fig=ctx.figures.named(svg, "synthesis-construction"),
                      fig_gamma=ctx.figures.named(gamma_svg(r, t("syn.turn"), mm=t("kin.mm")), "synthesis-transmission-angle"),
                      scale=f(scale, 4))
