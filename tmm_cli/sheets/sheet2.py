"""Sheet 2: the kinetostatics of one or two positions - each structural group detached
from the mechanism at a GOST 2.302 length scale with its loads and reactions, its force
polygon at a standard μF, the input link, and Zhukovsky's lever large enough to read
every force and arm.  Drawn by the panels the report draws too (tmm_cli/drawings/forces.py)."""
from __future__ import annotations

from typing import TYPE_CHECKING

from .. import locales
from .frame import FRAME, TB_H, TB_W

if TYPE_CHECKING:
    from ..task import Task

TXT = locales.table("sheets", "sheet2")
COL_W = 130.0          # mm: the width of one group's column (its drawing above its polygon)
MIN_COL_W = 70.0       # mm: narrower columns wrap into a second row of groups (many groups)
LEVER_MIN_W = 280.0    # mm: the lever keeps at least this width
HEAD = 9.0             # mm: the position's heading


def positions(results: dict) -> list[int]:
    """The positions of the sheet: the ones whose plans are on sheet 1."""
    from .sheet1 import course_positions
    kst = {k["index"] for k in results.get("kinetostatics") or []
           if k.get("balancing_moment") is not None or k.get("balancing_force") is not None}
    return [i for i in course_positions(results) if i in kst]


def layout(n: int, width: float) -> tuple[int, int]:
    """(columns, rows) of ``n`` group columns in ``width`` mm: one row while a column keeps
    MIN_COL_W, else as many rows as it takes at the widest columns that fit."""
    import math
    if n * MIN_COL_W <= width:
        return n, 1
    ncol = max(1, int(width // MIN_COL_W))
    return ncol, math.ceil(n / ncol)


def build(cv, results: dict, task: Task | None, lang: str = "en") -> dict:
    from ..drawings import forces as K
    from ..drawings.words import Words
    from ..plans import crank_pin, geometry
    words = Words(lang)
    info_k = results["kinetostatics_info"]
    links = K.links_by_name(results)
    kin = {k["index"]: k for k in results.get("kinematics") or []}
    kst = {k["index"]: k for k in results["kinetostatics"]}
    geom = geometry(results)
    pin = crank_pin(geom) if geom is not None else None
    x0f, y0f, x1f, y1f = FRAME
    course = positions(results)
    from ..report.course import grid_count
    from .sheet1 import shown_index
    n_grid = grid_count(results, len(results.get("kinematics") or []))
    band_h = (y1f - y0f) / max(len(course), 1)
    out = {"positions": {}, "scale": "—"}
    for k, i in enumerate(course):
        e, ke = kst[i], kin[i]
        top = y1f - k * band_h
        bottom = top - band_h
        cv.layer = "text"
        cv.mtext(x0f + 4, top - 5.5, TXT[lang]["pos"].format(i=shown_index(e, n_grid), phi=float(e["phi"])), 5.0,
                 bold=True)
        rows = K.position_rows(words, e, ke, info_k, links)
        n = len(rows)
        ncol, nrow = layout(n, x1f - x0f - LEVER_MIN_W)
        col_w = min(COL_W, (x1f - x0f - LEVER_MIN_W) / ncol)
        row_h = (band_h - HEAD - 2.0) / nrow     # a row of groups: drawings above polygons
        ph = row_h / 2                           # a panel's height
        drawn = []
        for c, (g, forces, couples, title) in enumerate(rows):
            r, cc = divmod(c, ncol)
            x = x0f + cc * col_w
            row_top = top - HEAD - r * row_h
            y_up, y_lo = row_top - ph, row_top - 2 * ph
            cv.layer = "contour"          # the groups and their polygons: main lines
            mu_l = K.group_panel(words, cv, (x + 1, y_up, col_w - 2, ph), ke, links, g, forces, couples, title)
            mu_F, T = K.polygon_panel(words, cv, (x + 1, y_lo + 1, col_w - 2, ph - 1), forces)
            drawn.append({"group": g, "mu_l": mu_l, "mu_F": mu_F, "tips": T, "vectors": K.polygon(forces)[0],
                          "box": (x, y_lo, col_w, 2 * ph)})
            cv.layer = "thin"
            cv.line((x + col_w, y_lo + 1), (x + col_w, row_top), "#999", 0.18)
            if r and cc == 0:
                cv.line((x0f, row_top), (x0f + ncol * col_w, row_top), "#999", 0.18)
        # the lever: the rest of the band, above the title block on the bottom band
        lx = x0f + ncol * col_w + 1
        lb = bottom + 1
        if bottom - y0f < TB_H + 1 and lx + LEVER_MIN_W > x1f - TB_W:
            lb = y0f + TB_H + 2
        cv.layer = "thin"                 # the lever: the turned plan and the arms, thin lines
        mu_v = K.lever_panel(words, cv, (lx, lb, x1f - lx - 1, top - HEAD - lb), e, ke, pin,
                              (results.get("drive") or {}).get("omega"), info_k.get("balance_kind"))
        if k:
            cv.layer = "thin"
            cv.line((x0f, top), (x1f, top), width=0.35)
        out["positions"][i] = {"groups": drawn, "mu_v": mu_v, "entry": e,
                               "lever_box": (lx, lb, x1f - lx - 1, top - HEAD - lb)}
    return out
