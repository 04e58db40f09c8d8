"""The A1 sheet: the frame (GOST 2.301/2.104: 20 mm on the left for binding, 5 mm on
the other sides) and the title block of GOST 2.104 form 1 (185 x 55 mm), the scales
of the course's drawings (GOST 2.302 for lengths, 1, 2, 2.5, 4, 5 x 10^k for the others)."""
from __future__ import annotations

import re

from .. import locales
from ..report.figures import drawing_scale, nice_scale

SHEET_W, SHEET_H = 841.0, 594.0
FRAME = (20.0, 5.0, SHEET_W - 5.0, SHEET_H - 5.0)        # x0, y0, x1, y1
TB_W, TB_H = 185.0, 55.0
MU_SERIES = (1.0, 2.0, 2.5, 4.0, 5.0, 10.0)


def std_mu(value: float) -> float:
    """The smallest scale factor >= value from 1, 2, 2.5, 4, 5 x 10^k."""
    return nice_scale(value, MU_SERIES)


def length_scale(model_mm_per_paper_mm: float) -> tuple[float, str]:
    """The GOST 2.302 drawing scale for a length drawing: (model mm per paper mm, '1:5')."""
    return drawing_scale(model_mm_per_paper_mm)


NARROWEST = 0.6      # GOST 2.304 type B: capitals 6/10 of h wide, about 0.6 of DejaVu Sans'


def fit_text(cv, x, y, s, h, max_w, anchor="start", **kw):
    """A label of size h mm, set a GOST 2.304 size smaller while it would be wider than max_w;
    at 2.5 mm, the smallest size, its letters narrower (down to NARROWEST) to fit."""
    from .prims import CAP_RATIO, GOST_SIZES
    if s:
        def width(g):
            return 0.6 * g / CAP_RATIO * len(s)
        fits = [g for g in GOST_SIZES if g <= h and width(g) <= max_w]
        g = max(fits, default=GOST_SIZES[0])
        narrow = 1.0 if fits else max(NARROWEST, max_w / width(g))
        cv.mtext(x, y, s, g, anchor=anchor, narrow=narrow, **kw)


def fit_lines(cv, x, yc, s, h, max_w, max_h):
    """A centred text of size h mm around (x, yc), wrapped at its spaces into as few lines as fit
    max_w at the largest GOST 2.304 size <= h whose lines (pitch 1.7 h) fit max_h; the
    smallest size's last line narrowed (fit_text) when even that does not fit."""
    import textwrap

    from .prims import CAP_RATIO, GOST_SIZES
    if not s:
        return
    for g in sorted((g for g in GOST_SIZES if g <= h), reverse=True):
        per_line = max(1, int(max_w / (0.6 * g / CAP_RATIO)))
        lines = textwrap.wrap(s, per_line, break_long_words=False) or [s]
        if 1.7 * g * (len(lines) - 1) + g <= max_h and all(len(t) <= per_line for t in lines):
            break
    else:
        g = GOST_SIZES[0]
        n = max(1, int((max_h - g) // (1.7 * g)) + 1)
        lines = textwrap.wrap(s, max(1, int(max_w / (0.6 * g / CAP_RATIO))), break_long_words=False) or [s]
        lines = lines[:n - 1] + [" ".join(lines[n - 1:])]
    y = yc + 1.7 * g * (len(lines) - 1) / 2
    for t in lines:
        fit_text(cv, x, y, t, g, max_w, anchor="middle")
        y -= 1.7 * g


TB_TEXT = locales.table("sheets", "title_block")


def draw_frame(cv, *, title: str, sheet_title: str, variant, student: str, group: str,
               n: int, total: int, scale: str, lang: str = "en", supervisor: str = "",
               designation: str = "", university: str = "") -> dict:
    """The frame and the title block; returns the title block's fields as written. The task's
    ``course`` header gives the supervisor (row 'checked'), the designation (the sheet's code:
    the note's designation less the note's code -- the catalogues' sheets `note_code` --, and
    the sheet's number) and the university (with the group, in the organisation's cell)."""
    T = TB_TEXT[lang]
    x0, y0, x1, y1 = FRAME
    cv.layer = "thin"
    cv.polyline([(0, 0), (SHEET_W, 0), (SHEET_W, SHEET_H), (0, SHEET_H)], width=0.18, closed=True)
    cv.layer = "contour"
    cv.polyline([(x0, y0), (x1, y0), (x1, y1), (x0, y1)], width=0.7, closed=True)
    # title block, form 1: bottom right corner of the frame
    bx, by = x1 - TB_W, y0
    cv.polyline([(bx, by), (x1, by), (x1, by + TB_H), (bx, by + TB_H)], width=0.7, closed=True)
    # left part: 65 mm, 11 rows of 5 mm; columns 7, 10, 23, 15, 10
    cols = [bx, bx + 7, bx + 17, bx + 40, bx + 55, bx + 65]
    for c in cols[1:]:
        # the names of the signing rows span the first two columns
        cv.line((c, by + 25 if c == cols[1] else by), (c, by + TB_H), width=0.7 if c == cols[-1] else 0.5)
    for k in range(1, 11):
        y = by + 5 * k
        cv.layer = "contour" if k in (6, 8) else "thin"
        cv.line((bx, y), (cols[-1], y), width=0.5 if k in (6, 8) else 0.18)
    cv.layer = "contour"
    # right part: designation 120 x 15 on top; title 70 x 40; lit./mass/scale; sheet n of N; group
    rx = bx + 65
    cv.line((rx, by + 40), (x1, by + 40), width=0.5)
    cv.line((rx + 70, by), (rx + 70, by + 40), width=0.5)
    for y in (by + 15, by + 20, by + 35):
        cv.line((rx + 70, y), (x1, y), width=0.5)
    for x in (rx + 85, rx + 102):
        cv.line((x, by + 20), (x, by + 40), width=0.5)
    cv.line((rx + 90, by + 15), (rx + 90, by + 20), width=0.5)
    # texts
    h = 2.5
    for c, s in zip(cols, (T["ch"], T["sh"], T["doc"], T["sign"], T["date"])):
        fit_text(cv, c + 0.7, by + 27.5, s, h, 1.0 + (cols[cols.index(c) + 1] - c) - 2.4)
    rows = [(T["dev"], student), (T["chk"], supervisor), (T["tcn"], ""), (T["ncn"], ""), (T["apr"], "")]
    for k, (lab, val) in enumerate(rows):
        y = by + 22.5 - 5 * k
        fit_text(cv, bx + 0.7, y, lab, h, 15.6)
        if val:                       # GOST 2.104: the surname (and initials), narrowed to the cell
            from ..drawings.titleblock import signer_name
            from .prims import CAP_RATIO
            shown, narrow = signer_name(val, 0.6 * h / CAP_RATIO, 21.6, NARROWEST)
            cv.mtext(bx + 17.7, y, shown, h, narrow=narrow)
    codes = sorted({re.escape(locales.of("sheets", "note_code", other)) for other in locales.LANGS})
    base = re.sub(rf"\s*({'|'.join(codes)})\s*$", "", designation or "").strip()
    tmm = T["code"]                   # the course's code in the drawing's letters (Latin or Cyrillic)
    code = f"{base}.{n:02d}" if base else (f"{tmm}.{variant}.{n:02d}" if variant not in (None, "") else f"{tmm}.{n:02d}")
    fit_text(cv, rx + 60, by + 47.5, code, 7.0, 116, anchor="middle")
    fit_lines(cv, rx + 35, by + 31.5, title, 5.0, 66, 12.5)   # its descenders clear of the sheet title
    fit_text(cv, rx + 35, by + 20, sheet_title, 3.5, 66, anchor="middle")
    fit_text(cv, rx + 35, by + 12, f"{T['variant']} {variant}" if variant not in (None, "") else "", 3.5, 66,
             anchor="middle")
    fit_text(cv, rx + 35, by + 5, T["course"], 2.5, 66, anchor="middle")
    fit_text(cv, rx + 77.5, by + 37.5, T["lit"], h, 13, anchor="middle")
    fit_text(cv, rx + 93.5, by + 37.5, T["mass"], h, 15, anchor="middle")
    fit_text(cv, rx + 111, by + 37.5, T["scale"], h, 16, anchor="middle")
    fit_text(cv, rx + 111, by + 27.5, scale, 3.5, 16, anchor="middle")
    fit_text(cv, rx + 71, by + 17.5, f"{T['sheet']} {n}", h, 18)
    fit_text(cv, rx + 91, by + 17.5, f"{T['sheets']} {total}", h, 28)
    org = ", ".join(x for x in (university, group) if x)
    fit_text(cv, rx + 95, by + 7.5, org, 3.5, 46, anchor="middle")
    return {"title": title, "sheet_title": sheet_title, "variant": variant, "student": student,
            "group": group, "sheet": n, "sheets": total, "scale": scale, "code": code,
            "supervisor": supervisor, "organisation": org}
