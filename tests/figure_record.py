"""What the report's figures draw, recorded as they are drawn (the figure writers patched for
the time of a build): the texts of every figure with their boxes (:func:`record_texts`), the
force drawings' arrows, lines and names (:class:`ForceRecorder`) and every call of
figures.place_labels with what it gave (:func:`record_placements`).  Used by the label tests
(test_figure_labels, test_force_labels, test_label_placement) on the reports that
:func:`pdf_extent.report_out` builds once per test session, and on the sheets they build."""
from __future__ import annotations

import copy
import re

import numpy as np


def record_texts(monkeypatch) -> list:
    """Patch the figure writers to record (kind, width mm, height mm, [(text, box)])."""
    from tmm_cli.report import svgchart
    from tmm_cli.report.svgdraw import PT_PER_MM, Canvas
    figs, open_ = [], {}
    text0, to_svg0 = Canvas.text, Canvas.to_svg
    chart_text0, chart_svg0 = svgchart._text, svgchart.Figure.to_svg
    chart: list = []

    def text(self, x, y, s, size=7.0, color="#000", anchor="middle", italic=False, bold=False, sub=None,
             sup=None, z=8, vcenter=True, halo=False, after=None):
        fs = size / PT_PER_MM
        w = 0.6 * fs * (len(s) + len(sub or sup or "") + len(after or ""))
        x0 = x - w / 2 if anchor == "middle" else (x - w if anchor == "end" else x)
        yc = y if vcenter else y + 0.35 * fs
        open_.setdefault(id(self), []).append((s + (sub or sup or "") + (after or ""),
                                               (x0, yc - fs / 2, x0 + w, yc + fs / 2)))
        return text0(self, x, y, s, size, color, anchor, italic, bold, sub, sup, z, vcenter, halo, after)

    def to_svg(self):
        figs.append(("drawing", self.w, self.h, open_.pop(id(self), [])))
        return to_svg0(self)

    def chart_text(x, y, s, size_mm, anchor, fill=None, rotate=False):
        plain = re.sub(r"\\[A-Za-z]+", "x", s)
        plain = re.sub(r"[${}_^]", "", plain)
        if plain.strip() and chart:
            w = 0.6 * size_mm * len(plain)
            a = x - w / 2 if anchor == "middle" else (x - w if anchor == "end" else x)
            # along the text: a .. a + w; across: the baseline y, ascent above (y down)
            lo, hi = y - 0.76 * size_mm, y + 0.24 * size_mm
            if rotate:          # turned by -90° about (x, y): along the text is up the page
                box = (x - (y - lo), y - (a + w - x), x + (hi - y), y - (a - x))
            else:
                box = (a, lo, a + w, hi)
            chart[-1].append((s, box))
        return chart_text0(x, y, s, size_mm, anchor, fill, rotate)

    def chart_svg(self):
        chart.append([])
        try:
            out = chart_svg0(self)
        finally:
            boxes = chart.pop()
        if self.mpl:            # (y down in the SVG: the boxes as measured from the top)
            figs.append(("chart", self.w, self.h, boxes))
        return out

    monkeypatch.setattr(Canvas, "text", text)
    monkeypatch.setattr(Canvas, "to_svg", to_svg)
    monkeypatch.setattr(svgchart, "_text", chart_text)
    monkeypatch.setattr(svgchart.Figure, "to_svg", chart_svg)
    return figs


class ForceRecorder:
    """The panels drawn while patched: [{'kind', 'arrows': [(p, q)], 'lines': [(p, q)],
    'labels': [(anchor, u, name, box, leader)], 'texts': [box]}]."""

    def __init__(self, monkeypatch):
        from tmm_cli.drawings import forces
        from tmm_cli.report.svgdraw import Canvas
        self.panels, self.cur = [], None
        arrow0, line0, labels0 = Canvas.arrow, Canvas.line, forces._labels
        rec = self

        def arrow(cv, p, q, *a, **kw):
            if rec.cur is not None and not rec.cur.get("in_moment"):
                rec.cur["arrows"].append((tuple(map(float, p)), tuple(map(float, q))))
            return arrow0(cv, p, q, *a, **kw)

        def line(cv, p, q, *a, **kw):
            if rec.cur is not None:
                rec.cur["lines"].append((tuple(map(float, p)), tuple(map(float, q))))
            return line0(cv, p, q, *a, **kw)

        moment0 = Canvas.moment

        def moment(cv, *a, **kw):
            if rec.cur is not None:
                rec.cur["in_moment"] = True
            try:
                return moment0(cv, *a, **kw)
            finally:
                if rec.cur is not None:
                    rec.cur["in_moment"] = False

        def labels(cv, items, *a, leaders=False, **kw):
            boxes = labels0(cv, items, *a, leaders=leaders, **kw)
            if rec.cur is not None:
                for (anchor, u, name, col), box in zip(items, boxes):
                    rec.cur["labels"].append((np.asarray(anchor, float), u, name, box, leaders))
            return boxes

        def wrap(kind, fn):
            def run(*a, **kw):
                rec.cur = {"kind": kind, "arrows": [], "lines": [], "labels": []}
                try:
                    return fn(*a, **kw)
                finally:
                    rec.panels.append(rec.cur)
                    rec.cur = None
            return run

        monkeypatch.setattr(Canvas, "arrow", arrow)
        monkeypatch.setattr(Canvas, "line", line)
        monkeypatch.setattr(Canvas, "moment", moment)
        monkeypatch.setattr(forces, "_labels", labels)
        monkeypatch.setattr(forces, "group_panel", wrap("group", forces.group_panel))
        monkeypatch.setattr(forces, "lever_panel", wrap("lever", forces.lever_panel))
        monkeypatch.setattr(forces, "polygon_panel", wrap("polygon", forces.polygon_panel))


def record_placements(monkeypatch) -> list:
    """Every call of figures.place_labels while patched, as (anchors, extent, keywords) as
    they were passed (copied before the call), what it gave, and the caller's ``taken`` list
    right after it (the boxes it appended): [(anchors, extent, kw, got, taken)]."""
    from tmm_cli.report import figures
    new, calls = figures.place_labels, []

    def place(anchors, extent, **kw):
        before = copy.deepcopy((anchors, kw))
        got = new(anchors, extent, **kw)
        calls.append((before[0], extent, before[1], copy.deepcopy(got), copy.deepcopy(kw.get("taken"))))
        return got

    monkeypatch.setattr(figures, "place_labels", place)
    return calls
