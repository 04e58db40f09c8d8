"""Sheet 1's segment tables: the length (mm) of every segment of its plans as the sheet draws
them, at the sheet's own μ, stated above the table (the report's tables are at the report's
μ; a sheet that draws at another μ carries its own lengths).  A ruler on the printed sheet
reads what the table says."""
from __future__ import annotations

from .. import locales

WORDS = locales.table("segments", "words")
H = 2.5              # mm: the lettering of the tables (GOST 2.304's smallest)
PITCH = 4.6          # mm: a row, at most
TITLE = 5.0          # mm: a title line


def drawn_lengths(plan, k: float) -> list[tuple[str, float]]:
    """[(segment, length mm on the sheet)] of a plan drawn reduced by k (draw_plan's return)."""
    return [(f"{v.start}{v.end}", plan.length_mm(v) * k) for v in plan.vecs]


def draw_table(cv, x0: float, y_top: float, y_bottom: float, titles: list[tuple], head: list[str],
               rows: list[tuple[str, list]], first_w: float, col_w: float) -> dict:
    """A table of lengths: title lines (text, or (symbol, subscript, after) for a μ), a header
    (head[0] over the segments' column, then one cell per column), then one row per segment,
    its lengths to 0.1 mm ('—' where a column has none).  Rows share what is left above
    y_bottom, PITCH mm each at most.  Returns {'box', 'cells': {(segment, column): text}}."""
    cv.layer = "text"
    y = y_top - TITLE / 2
    for t in titles:
        if isinstance(t, tuple):
            sym, sub, after = t
            cv.mtext(x0, y, sym, H, sub=sub, after=after)
        else:
            cv.mtext(x0, y, t, H, bold=True)
        y -= TITLE
    top = y_top - TITLE * len(titles) - 1.0
    pitch = min(PITCH, (top - y_bottom) / (len(rows) + 1))
    x1 = x0 + first_w + col_w * (len(head) - 1)
    bottom = top - pitch * (len(rows) + 1)
    cells = {}
    for r, (seg, vals) in enumerate([(head[0], head[1:])] + rows):
        yc = top - pitch * (r + 0.5)
        cv.mtext(x0 + first_w / 2, yc, seg, H, anchor="middle", italic=r > 0)
        for c, v in enumerate(vals):
            s = v if isinstance(v, str) else ("—" if v is None else f"{v:.1f}")
            cv.mtext(x0 + first_w + col_w * (c + 0.5), yc, s, H, anchor="middle")
            if r:
                cells[(seg, head[c + 1])] = s
    cv.layer = "thin"
    for r in range(1, len(rows) + 1):
        cv.line((x0, top - pitch * r), (x1, top - pitch * r), width=0.5 if r == 1 else 0.18)
    for c in range(len(head)):
        x = x0 + first_w + col_w * (c - 1) if c else x0 + first_w
        if c:
            cv.line((x, top), (x, bottom), width=0.18)
    cv.line((x0 + first_w, top), (x0 + first_w, bottom), width=0.5)
    cv.polyline([(x0, top), (x1, top), (x1, bottom), (x0, bottom)], width=0.5, closed=True)
    return {"box": (x0, bottom, x1, y_top), "cells": cells}


def velocity_table(cv, vplans: dict, box, lang: str, unit_txt: str, labels: dict | None = None) -> dict:
    """The velocity plans' segments, a column per position (headed by labels[index], an extra
    position marked as the report marks it, course.position_label), at their one μv;
    box = (x0, y0, w, h) mm."""
    W = WORDS[lang]
    x0, y0, w, h = box
    order = list(vplans)
    segs: dict[str, dict] = {}
    for i in order:
        d = vplans[i]
        for seg, L in drawn_lengths(d["plan"], d["k"]):
            segs.setdefault(seg, {})[i] = L
    mu = {vplans[i]["mu"] / vplans[i]["k"] for i in order}
    assert len(mu) == 1, mu                       # one μv for every plan of the sheet
    first_w = 14.0
    col_w = min(14.0, (w - first_w) / max(len(order), 1))
    rows = [(seg, [by.get(i) for i in order]) for seg, by in segs.items()]
    return draw_table(cv, x0, y0 + h, y0, [f"{W['seg.velocity']}:", ("μ", "v", f" = {mu.pop():g} {unit_txt}")],
                      [W["seg.pos"], *[(labels or {}).get(i, str(i)) for i in order]], rows, first_w, col_w)


def acceleration_table(cv, plan, k: float, box, lang: str, unit_txt: str) -> dict:
    """One acceleration plan's segments at its μa; box = (x0, y0, w, h) mm."""
    W = WORDS[lang]
    x0, y0, w, h = box
    rows = [(seg, [L]) for seg, L in drawn_lengths(plan, k)]
    return draw_table(cv, x0, y0 + h, y0, [W["seg.acceleration"], ("μ", "a", f" = {plan.mu / k:g} {unit_txt}")],
                      ["", W["seg.mm"]], rows, w / 2, w / 2)
