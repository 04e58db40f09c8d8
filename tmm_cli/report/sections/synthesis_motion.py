"""Report parts of the four-bar syntheses by positions of the coupler (type positions) and by
points of a path (type path): the construction drawn directly as SVG, the positions or
points asked for against the analysed linkage. Words: synthesis.yaml (read by synthesis.py)."""
from __future__ import annotations

import math

import numpy as np

_SCALES = (1, 2, 2.5, 4, 5, 10, 15, 20, 25, 40, 50, 75, 100, 200, 500, 1000)


class _Sheet:
    """A canvas fitted to a set of points (m) at a standard scale 1:s."""

    def __init__(self, pts, w_mm=165.0, h_mm=110.0):
        from ..svgdraw import Canvas
        allp = np.asarray(pts, float)
        lo, hi = allp.min(axis=0), allp.max(axis=0)
        span = np.maximum(hi - lo, 1e-9)
        need = max(span[0] / (w_mm - 16), span[1] / (h_mm - 12)) * 1000.0
        self.scale = next((s for s in _SCALES if s >= need), need)
        self.k = 1000.0 / self.scale
        self.cv = Canvas(w_mm, h_mm)
        self.off = np.array([w_mm, h_mm]) / 2 - (lo + hi) / 2 * self.k

    def m(self, p):
        return np.asarray(p, float) * self.k + self.off

    def label(self, p, s, d=(2.2, 2.2), color="#000"):
        q = self.m(p)
        self.cv.text(q[0] + d[0], q[1] + d[1], s, size=6.5, italic=True, halo=True, color=color)

    def arc(self, centre, r, a1, a2, color="#777", width=0.2, dash="1.5,1"):
        t = np.linspace(a1, a2, 60)
        self.cv.polyline([self.m(np.asarray(centre) + r * np.array([math.cos(x), math.sin(x)])) for x in t],
                         color, width, dash=dash)


def _span(centre, pts):
    """The arc (a1, a2, rad) about ``centre`` that covers ``pts``, a little widened."""
    ang = np.unwrap([math.atan2(p[1] - centre[1], p[0] - centre[0]) for p in pts])
    return ang.min() - 0.15, ang.max() + 0.15


_SUB = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")


def positions_svg(r: dict) -> tuple[str, float]:
    """The pole method drawn: the three positions of the coupler AB with its point P, the
    perpendicular bisectors of A1A2, A2A3 (B likewise) meeting at O (O1), the arcs through
    the pivots' positions, the poles P12, P13, P23 within the sheet, the linkage in position 1."""
    c = r["construction"]
    A, B = np.asarray(c["A_positions"]), np.asarray(c["B_positions"])
    O, O1 = np.asarray(c["O"]), np.asarray(c["O1"])
    P = np.asarray([t["P"] for t in r["targets"]])
    sh = _Sheet(np.vstack([A, B, O, O1, P]))
    cv, m = sh.cv, sh.m
    for centre, pts, colour in ((O, A, "#b00"), (O1, B, "#1f4e99")):
        for i in range(2):
            mid = (pts[i] + pts[i + 1]) / 2
            cv.line(m(pts[i]), m(pts[i + 1]), "#999", 0.15, dash="0.8,0.8")
            cv.line(m(mid), m(centre), colour, 0.2, dash="3,1,0.5,1")
            cv.dot(m(mid), 0.35, colour)
        rad = float(np.linalg.norm(pts[0] - centre))
        sh.arc(centre, rad, *_span(centre, pts), color=colour)
    for j in range(3):
        cv.line(m(A[j]), m(B[j]), "#000" if j == 0 else "#555", 0.45 if j == 0 else 0.3)
        cv.polyline([m(A[j]), m(P[j]), m(B[j])], "#000" if j == 0 else "#777", 0.2)
        for q in (A[j], B[j], P[j]):
            cv.dot(m(q), 0.5)
        n = str(j + 1).translate(_SUB)
        sh.label(A[j], f"A{n}", (-4.5, 1.5))
        sh.label(B[j], f"B{n}", (1.5, 1.5))
        sh.label(P[j], f"P{n}", (1.5, -3.0))
    cv.line(m(O), m(A[0]), "#000", 0.5)
    cv.line(m(O1), m(B[0]), "#000", 0.5)
    cv.ground(m(O))
    cv.ground(m(O1))
    sh.label(O, "O", (-4.0, -3.0))
    sh.label(O1, "O₁", (2.0, -3.0))
    w, h = cv.w, cv.h
    for k, q in (c.get("poles") or {}).items():
        if q is None:
            continue
        qq = m(q)
        if 2 <= qq[0] <= w - 2 and 2 <= qq[1] <= h - 2:
            cv.dot(qq, 0.5, "#080")
            sh.label(q, f"P{k[0].translate(_SUB)}{k[1].translate(_SUB)}", (1.5, 1.5), color="#080")
    return cv.to_svg(), sh.scale


def coupler_curve(r: dict, n: int = 361):
    """The coupler point's curve of the generated four-bar, from the results' `curve`."""
    cu = r.get("curve") or {}
    return np.asarray(cu.get("M") or [], float).reshape(-1, 2)


def path_svg(r: dict) -> tuple[str, float]:
    """The coupler curve of the found crank-rocker, the points it must pass (crosses) with
    their deviations, the linkage in its first position."""
    mech = r["mechanism"]
    O, O1 = np.asarray(mech["ground"]["O"]), np.asarray(mech["ground"]["O1"])
    T = np.asarray(r["points"], float)
    curve = coupler_curve(r)
    L = r["lengths"]
    f = r["first"]
    A, B, M = (np.asarray(f[k]) for k in ("A", "B", "M"))
    pts = [O, O1, A, B, M, *T, *curve, O + (L["crank"], L["crank"]), O - (L["crank"], L["crank"])]
    sh = _Sheet(np.vstack(pts))
    cv, m = sh.cv, sh.m
    if len(curve):
        cv.polyline([m(p) for p in curve], "#1f4e99", 0.4, closed=True)
    t = np.linspace(0, 2 * math.pi, 121)
    cv.polyline([m(O + L["crank"] * np.array([math.cos(x), math.sin(x)])) for x in t], "#777", 0.2, dash="1.5,1")
    cv.line(m(O), m(A), "#000", 0.5)
    cv.polygon([m(A), m(B), m(M)], fill="#ddd", z=0, stroke="#000", width=0.35)
    cv.line(m(O1), m(B), "#000", 0.5)
    for q in (A, B, M):
        cv.dot(m(q), 0.5)
    cv.ground(m(O))
    cv.ground(m(O1))
    sh.label(O, "O", (-4.0, -3.0))
    sh.label(O1, "O₁", (2.0, -3.0))
    sh.label(A, "A", (-3.5, 1.5))
    sh.label(B, "B", (1.5, 1.5))
    # each point's number outward from the points' centroid; M's label toward it (M sits at point 1)
    c0 = m(T.mean(axis=0))
    out = [(m(p) - c0) / (np.linalg.norm(m(p) - c0) or 1.0) for p in T]
    qm = m(M) - 4.0 * out[0]
    cv.text(qm[0], qm[1], "M", size=6.5, italic=True, halo=True)
    for j, p in enumerate(T):
        q = m(p)
        cv.line(q + (-1.2, -1.2), q + (1.2, 1.2), "#b00", 0.35)
        cv.line(q + (-1.2, 1.2), q + (1.2, -1.2), "#b00", 0.35)
        qt = q + 3.5 * out[j]
        cv.text(qt[0], qt[1], str(j + 1), size=5.5, color="#b00", halo=True)
    return cv.to_svg(), sh.scale


def _lens(ctx, r, names):
    f = ctx.fmt
    mu = ctx.t("syn.m")
    return [(names.get(k, k), f"{f(v, 6)} {mu}") for k, v in r["lengths"].items()]


def _xy(ctx, p, digits=6):
    return f"({ctx.fmt(p[0], digits)}; {ctx.fmt(p[1], digits)})"


def _given(p):
    """A point as the task gives it (no padding zeros), in the language's writing."""
    from .task import num
    return f"({num(float(p[0]))}; {num(float(p[1]))})"


def _scale(ctx, s):
    from ...numfmt import localize
    return localize(f"{s:g}", ctx.lang)


def build_positions(ctx, r, names) -> str:
    f, t = ctx.fmt, ctx.t
    mu = t("syn.m")
    fp = r["fixed_pivots"]
    df = r["defects"]
    info = [(t("syn.type"), t("syn.type.positions")),
            (t("syn.pos.O"), f"{_xy(ctx, fp['O'])} {mu}"), (t("syn.pos.O1"), f"{_xy(ctx, fp['O1'])} {mu}"),
            (t("syn.fn.grashof"), t(f"syn.grashof.{r['grashof']}")),
            (t("syn.gamma"), t("syn.gamma_at", g=f(r["gamma_min"], 6), p=f(r["gamma_min_phi"], 5))),
            (t("syn.pos.branch"), t("syn.pos.defect" if df["branch"] else "syn.pos.none")),
            (t("syn.pos.order"), t("syn.pos.defect" if df["order"] else "syn.pos.none"))]
    rows = []
    for j, (g, q) in enumerate(zip(r["positions"], r["targets"])):
        rows.append((str(j + 1), _given(q["P"]), f(q["angle"], 6), f(g["crank_angle"], 6), _xy(ctx, g["P"]),
                     f(g["angle"], 6), f(g["deviation"], 3), f(g["angle_error"], 3)))
    head = [t("syn.pos.n"), t("syn.pos.P_target"), t("syn.pos.angle_target"), t("syn.pos.phi"),
            t("syn.pos.P_got"), t("syn.pos.angle_got"), t("syn.pos.dev"), t("syn.pos.dangle")]
    svg, scale = positions_svg(r)
    warn = [t(f"syn.pos.{k}_text") for k in ("branch", "order") if df[k]]
    return ctx.render("sections/synthesis_motion.html.j2", method=t("syn.pos.method"), info=info,
                      lens=_lens(ctx, r, names), head=head, rows=rows, warn=warn, rows_title=t("syn.pos.table"),
                      fig=ctx.figures.named(svg, "synthesis-positions"),
                      fig_caption=t("syn.pos.fig", s=_scale(ctx, scale)))


def build_path(ctx, r, names) -> str:
    f, t = ctx.fmt, ctx.t
    mu = t("syn.m")
    mech = r["mechanism"]
    info = [(t("syn.type"), t("syn.type.path")),
            (t("syn.pos.O"), f"{_xy(ctx, mech['ground']['O'])} {mu}"),
            (t("syn.pos.O1"), f"{_xy(ctx, mech['ground']['O1'])} {mu}"),
            (t("syn.path.M"), f"{_xy(ctx, r['M'])} {mu}"),
            (t("syn.fn.grashof"), t(f"syn.grashof.{r['grashof']}")),
            (t("syn.gamma"), t("syn.gamma_at", g=f(r["gamma_min"], 6), p=f(r["gamma_min_phi"], 5))),
            (t("syn.path.max"), f"{f(r['max_deviation'], 4)} {mu}")]
    rows = [(str(j + 1), _given(p), f(dv, 4), f(phi, 5))
            for j, (p, dv, phi) in enumerate(zip(r["points"], r["deviations"], r["crank_angles"]))]
    head = [t("syn.pos.n"), t("syn.path.point"), t("syn.path.dev"), t("syn.pos.phi")]
    svg, scale = path_svg(r)
    return ctx.render("sections/synthesis_motion.html.j2", method=t("syn.path.method", n=len(r["points"])),
                      info=info, lens=_lens(ctx, r, names), head=head, rows=rows, warn=[],
                      rows_title=t("syn.path.table"), fig=ctx.figures.named(svg, "synthesis-path"),
                      fig_caption=t("syn.path.fig", s=_scale(ctx, scale)))
