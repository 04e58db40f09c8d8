"""Sheet 4: the cam - its pitch and working profiles with the base circle at a GOST 2.302
scale, and the follower's motion law s(φ), ds/dφ, d²s/dφ² at standard μ."""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from .. import locales
from ..report.figures import scale_mark
from .frame import FRAME, TB_H, TB_W, length_scale, std_mu
from .graph import draw_graph

if TYPE_CHECKING:
    from ..task import Task

GX = 28.0         # mm: the diagrams' φ axes start this far into the frame (room for d²s/dφ²)
TXT = locales.table("sheets", "sheet4")


def _extent(k: dict) -> tuple[np.ndarray, np.ndarray]:
    """The s - ds/dφ construction's corners (m), a rocker's pivot A with it."""
    lo, hi = np.asarray(k["box"][:2], float), np.asarray(k["box"][2:], float)
    if k.get("A") is not None:      # a rocker's pivot A: on the drawing too
        lo, hi = np.minimum(lo, np.asarray(k["A"], float)), np.maximum(hi, np.asarray(k["A"], float))
    return lo, hi


def _construction_scale(k: dict, box) -> tuple[float, str]:
    """The GOST 2.302 scale (model mm per sheet mm, its label) at which the construction fills
    ``box`` (x, y, w, h; room for its heading and margins)."""
    lo, hi = _extent(k)
    _, _, w, h = box
    return length_scale(max((hi - lo)[0] * 1000.0 / (w - 20.0), (hi - lo)[1] * 1000.0 / (h - 22.0)))


def draw_construction(cv, k, c, box, results: dict, task: Task | None, lang: str = "en") -> dict:
    """The s - ds/dφ diagram that gives the least base radius (the report's figure): the
    follower's points B (s along its path) and D (ds/dφ across it) over the rise and the
    return, the tangents at the allowed pressure angles bounding the zone of the cam's
    centre, O and B0 (O B0 = r0), at one GOST 2.302 scale for s and ds/dφ alike."""
    from pathlib import Path

    from ..report.context import ReportContext
    from ..report.sections import load
    C = load("cam")                  # registers its texts in the three languages
    ctx = ReportContext(results=results, task=task, lang=lang, out_dir=Path("."), env=None)
    x0, y0, w, h = box
    lo, hi = _extent(k)
    unit, label = _construction_scale(k, box)
    O = np.array([x0 + 10.0, y0 + 6.0]) - lo * 1000.0 / unit

    def M(p):
        return O + np.asarray(p, float) * 1000.0 / unit

    mm = TXT[lang]["mm"]
    cv.mtext(x0 + 5, y0 + h - 2, ctx.t("cam.construction_title"), 5.0, bold=True)
    cv.mtext(x0 + 5, y0 + h - 9, "μ", 3.5, sub="s", after=f" = μds/dφ = {unit / 1000.0:g} {TXT[lang]['m']}/{mm}"
             f"   ({scale_mark(lang)} {label})")
    B0 = M(k["B0"])
    # the axes of the diagram through B0: s along the follower's path, ds/dφ across it
    cv.layer = "thin"
    ax_lo, ax_hi = M(lo), M(hi)
    cv.arrow((ax_lo[0], B0[1]), (ax_hi[0], B0[1]), width=0.25, head=2.5)
    cv.arrow((B0[0], ax_lo[1]), (B0[0], ax_hi[1]), width=0.25, head=2.5)
    cv.mtext(ax_hi[0] - 2.0, B0[1] + 3.5, C._loc(lang, "ds/dφ, mm"), 2.5, anchor="end")
    cv.mtext(B0[0] + 2.0, ax_hi[1] - 2.0, C._loc(lang, "s, mm"), 2.5)
    drawn = {}
    for phase in ("rise", "return"):
        B, D = M(k[f"B_{phase}"]), M(k[f"D_{phase}"])
        cv.layer = "thin"
        cv.polyline(B, width=0.25)
        step = max(1, len(B) // 8)
        for b, d in zip(B[::step], D[::step]):
            cv.line(b, d, width=0.18)
        cv.layer = "contour"
        cv.polyline(D, width=0.6)
        drawn[phase] = D
    # the tangents at the allowed pressure angles: the cam's centre on the safe side of both
    cv.layer = "dimensions"
    tangents = []
    for t in k["tangents"]:
        seg = C._clip_line(np.asarray(t["point"], float), np.asarray(t["direction"], float), (*lo, *hi))
        if seg is not None:
            q = [M(p) for p in seg]
            cv.line(q[0], q[1], width=0.3, dash="4 1.5")
            tangents.append(q)
    cv.layer = "contour"
    cv.line(O, B0, width=0.5)
    for name, p in (("O", O), ("B0", B0)) + ((("A", M(k["A"])),) if k.get("A") is not None else ()):
        cv.circle(p, 1.0, width=0.5)
        cv.mtext(p[0] + 2.5, p[1] - 3.5, name[0], 3.5, italic=True, sub=name[1:] or None)
    mid = (O + B0) / 2
    cv.mtext(mid[0] + 2.5, mid[1], "r₀", 3.5, italic=True)
    return {"unit": unit, "scale": label, "O": O, "B0": B0, "D": drawn, "tangents": tangents, "M": M}


def build(cv, results: dict, task: Task | None, lang: str = "en") -> dict:
    c = results["cam"]
    T = TXT[lang]
    mm = T["mm"]
    x0f, y0f, x1f, y1f = FRAME
    info = {}
    # --- the motion law: three diagrams over the cam turn, μφ = 1 °/mm
    phi = np.asarray(c["phi"], float)
    rocker = c.get("follower") == "rocker"
    units = ("°", f"1/{mm}", f"1/{mm}") if rocker else (T["m"], T["m"], T["m"])
    syms = ("ψ", "dψ/dφ", "d²ψ/dφ²") if rocker else ("s", "ds/dφ", "d²s/dφ²")
    box_h = (y1f - y0f - 20.0) / 3
    cv.mtext(x0f + 5, y1f - 6, T["law"], 5.0, bold=True)
    info["graphs"] = {}
    ticks = [(30.0 * i, f"{30 * i}" if i < 12 else "") for i in range(13)]
    for k, (key, sym, unit) in enumerate(zip(("s", "ds", "d2s"), syms, units)):
        y = np.asarray(c[key], float)
        hi, lo = max(0.0, float(np.nanmax(y))), min(0.0, float(np.nanmin(y)))
        mu = std_mu(max(hi - lo, 1e-12) / (box_h - 22.0))
        yc = y1f - 20.0 - k * box_h - hi / mu
        per = "" if unit.startswith("1/") else f"/{mm}"
        pts, = draw_graph(cv, (x0f + GX, yc), [(np.append(phi, 360.0), np.append(y, y[0]), "#1f5fbf")],
                          1.0, mu, x_len=360.0, y_up=hi / mu + 5.0, y_down=-lo / mu + 3.0, x_sym="φ",
                          y_sym=sym, mu_text=f"μ = {mu:g} {unit}{per},  μφ = 1 °/{mm}", ticks=ticks)
        info["graphs"][key] = {"mu": mu, "pts": pts, "origin": (x0f + GX, yc),
                               "values": np.append(y, y[0])}
    # --- the profile: centre of the cam in the middle of the right half
    pitch = np.asarray(c["pitch_profile"], float)
    work = np.asarray(c["working_profile"], float)
    roller = float(c.get("roller") or 0.0)
    R = float(np.hypot(pitch[:, 0], pitch[:, 1]).max()) + roller
    kc = c.get("construction")
    # the profile over the right half; with the s - ds/dφ construction of r0 in its lower part
    by0 = 300.0 if kc else 70.0
    bx0, bw, bh = 440.0, x1f - 440.0 - 5.0, y1f - by0 - 5.0
    if kc:
        # the construction over the whole width above the title block, or left of it down to the
        # frame (taller, narrower): whichever draws it larger (a tall diagram drawn at 1:1 in the
        # corner of the wide box missed 2:1 by 6 mm of height the left part had to spare)
        wide = (bx0, y0f + TB_H + 5.0, bw, by0 - y0f - TB_H - 12.0)
        tall = (bx0, y0f + 5.0, x1f - TB_W - bx0 - 5.0, by0 - y0f - 12.0)
        box = min((wide, tall), key=lambda b: _construction_scale(kc, b)[0])
        info["construction"] = draw_construction(cv, kc, c, box, results, task, lang)
    unit, label = length_scale(2 * R * 1000.0 / (min(bw, bh) - 50.0))
    O = np.array([bx0 + bw / 2, by0 + (bh - 20.0) / 2])

    def M(p):
        return O + np.asarray(p, float) * 1000.0 / unit

    cv.mtext(bx0 + 5, y1f - 6, T["profile"], 5.0, bold=True)
    mu_l = unit / 1000.0
    cv.mtext(bx0 + 5, y1f - 13, "μ", 3.5, sub="l", after=f" = {mu_l:g} {T['m']}/{mm}   ({scale_mark(lang)} {label})")
    cv.layer = "contour"
    cv.polyline([M(p) for p in work], width=0.7, closed=True)
    cv.layer = "thin"
    if roller > 0:
        cv.polyline([M(p) for p in pitch], width=0.25, closed=True, dash="6 1.5 1 1.5")
        cv.circle(M(pitch[0]), roller * 1000.0 / unit, fill=None, width=0.5)
    r0 = float(c["r0"]) * 1000.0 / unit
    cv.circle(O, r0, fill=None, width=0.25)
    cv.layer = "dimensions"
    ext = R * 1000.0 / unit + 8.0
    cv.line(O - (ext, 0), O + (ext, 0), width=0.2, dash="6 1.5 1 1.5")
    cv.line(O - (0, ext), O + (0, ext), width=0.2, dash="6 1.5 1 1.5")
    ccw = c.get("rotation", "ccw") == "ccw"
    a0, a1 = (200.0, 250.0) if ccw else (250.0, 200.0)
    rr = 0.3 * r0
    cv.arc(O, rr, min(a0, a1), max(a0, a1), width=0.35)
    t = math.radians(a1)
    tip = O + rr * np.array([math.cos(t), math.sin(t)])
    tan = np.array([-math.sin(t), math.cos(t)]) * (1.0 if ccw else -1.0)
    cv.arrow(tip - 0.01 * tan, tip + 2.5 * tan, width=0.35, head=2.5)
    wq = O + 1.5 * rr * np.array([math.cos(math.radians(225)), math.sin(math.radians(225))])
    cv.mtext(wq[0], wq[1] - 3.0, "ω", 3.5, anchor="middle")
    cv.mtext(O[0] + r0 * 0.72 + 2.0, O[1] - r0 * 0.72 - 2.0, "r₀", 3.5, italic=True)
    cv.layer = "contour"
    cv.circle(O, 1.2, width=0.5)
    info.update({"unit": unit, "scale": label, "mu_l": mu_l, "O": O, "pitch_pts": [M(p) for p in pitch],
                 "pitch": pitch})
    return info
