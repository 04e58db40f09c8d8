"""The kinetostatics report section renders in both languages from results only, and
its CSV carries the results' numbers at full precision."""
from __future__ import annotations

import csv
import copy

import pytest

import tmm_cli
from tmm_cli.report import render

from test_kinetostatics_pipeline import SHAPER


@pytest.fixture(scope="module")
def shaper():
    task = tmm_cli.load_task(copy.deepcopy(SHAPER))
    return task, tmm_cli.run(task, kinematics_curve=0)


@pytest.mark.parametrize("lang,word", [("en", "Zhukovsky lever"), ("ru", "Рычаг Жуковского")])
def test_section_renders(tmp_path, shaper, lang, word):
    task, r = shaper
    render(r, task, tmp_path, {"html"}, lang)
    html = (tmp_path / "report.html").read_text(encoding="utf-8")
    assert 'id="kinetostatics"' in html and word in html
    assert html.count("<svg") >= 12            # a free-body figure per grid position at least
    with open(tmp_path / "kinetostatics.csv", encoding="utf-8") as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) == len(r["kinetostatics"])
    for row, e in zip(rows, r["kinetostatics"]):
        assert int(row["index"]) == e["index"]
        assert float(row["balancing_moment"]) == e["balancing_moment"]
        assert float(row["R01_R"]) == e["reactions"]["R01"]["R"]


def test_section_absent_without_kinetostatics(tmp_path, shaper):
    task, r = shaper
    r = {k: v for k, v in r.items() if k not in ("kinetostatics", "kinetostatics_info")}
    render(r, task, tmp_path, {"html"}, "en")
    assert 'id="kinetostatics"' not in (tmp_path / "report.html").read_text(encoding="utf-8")


def test_every_force_of_a_group_drawing_acts_on_a_drawn_link():
    """The groups' drawings: each force's arrow starts on a drawn link (a bar, a joint, a
    centre of mass, a block or the ram of a slider). The shaper's guide reaction R05 acts
    at its offset along the ram, far from the block: it was drawn alone in the air; the
    ram now reaches it."""
    import numpy as np
    from pathlib import Path as _P
    from tmm_cli.drawings import forces as K
    from tmm_cli.drawings.words import Words
    from tmm_cli.pipeline import run
    from tmm_cli.report.svgdraw import Canvas
    from tmm_cli.task import load_task
    root = _P(__file__).resolve().parents[1]
    task = load_task(root / "tasks" / "shaper_slotted_lever.yaml")
    res = run(task)
    ctx = Words("en")
    links = K.links_by_name(res)
    kin = {k["index"]: k for k in res["kinematics"]}

    class Rec(Canvas):
        def __init__(self, *a):
            super().__init__(*a)
            self.solid, self.starts, self.tips, self.blocks, self.joints = [], [], [], [], []

        def line(self, p, q, color="#000", width=0.25, dash=None, z=1):
            if dash is None and color == "#000":
                self.solid.append((np.asarray(p, float), np.asarray(q, float)))
            return super().line(p, q, color, width, dash, z)

        def polyline(self, pts, color="#000", width=0.25, dash=None, z=1, closed=False):
            if dash is None and color == "#000" and not closed and len(pts) > 2:     # a ram drawn broken
                ps = [np.asarray(p, float) for p in pts]
                self.solid.extend(zip(ps, ps[1:]))
            return super().polyline(pts, color, width, dash, z, closed)

        def arrow(self, p, q, *a, **kw):
            self.starts.append(np.asarray(p, float))
            self.tips.append(np.asarray(q, float))
            return super().arrow(p, q, *a, **kw)

        def block(self, c, *a, **kw):
            self.blocks.append(np.asarray(c, float))
            return super().block(c, *a, **kw)

        def circle(self, c, r, *a, **kw):
            self.joints.append(np.asarray(c, float))
            return super().circle(c, r, *a, **kw)

        def dot(self, c, *a, **kw):
            self.joints.append(np.asarray(c, float))
            return super().dot(c, *a, **kw)

    def near_segment(x, p, q):
        d = q - p
        t = np.clip((x - p) @ d / max(d @ d, 1e-12), 0, 1)
        return float(np.hypot(*(p + t * d - x)))

    checked = 0
    for e in res["kinetostatics"]:
        for g, forces, couples, title in K.position_rows(ctx, e, kin[e["index"]], res["kinetostatics_info"], links):
            cv = Rec(90.0, 72.0)
            K.group_panel(ctx, cv, (0, 0, 90.0, 72.0), kin[e["index"]], links, g, forces, couples, title)
            norms = K.force_norms(forces)
            shown = sum(n > 1e-9 * max(max(norms), 1e-300) for n in norms)
            acting = []
            for k, s in enumerate(cv.starts[:shown]):      # the forces' arrows (then the couples')
                on = (any(near_segment(s, p, q) < 0.3 for p, q in cv.solid)
                      or any(np.hypot(*(s - b)) < 5.0 for b in cv.blocks)
                      or any(np.hypot(*(s - j)) < 1.0 for j in cv.joints))
                # or slid along its line of action off an arrow that acts there (drawings.forces.along_line):
                # a millimetre past its tip in the same sense, or from its start the other way
                u = (cv.tips[k] - s) / np.hypot(*(cv.tips[k] - s))
                for j in acting:
                    v = cv.tips[j] - cv.starts[j]
                    v = v / np.hypot(*v)
                    if abs(float(u @ v)) > 0.995 and (np.hypot(*(s - cv.tips[j] - u * 1.0)) < 1e-6
                                                      or np.hypot(*(s - cv.starts[j])) < 1e-6):
                        on = True
                assert on, (e["index"], g, s)
                acting.append(k)
                checked += 1
    assert checked > 100


def _kinetostatics_html(html: str) -> str:
    start = html.index('id="kinetostatics"')
    end = html.find("<section", start)
    return html[start:end if end > 0 else len(html)]


def _position_cells(sec: str) -> list[str]:
    """The position column of the section's tables (the first cell of a row)."""
    import re
    return re.findall(r'<tr><td(?: class="num")?>([^<]*)</td><td class="num">', sec)


@pytest.mark.parametrize("chosen,extra,marked", [
    ([2], None, set()),                 # a grid position chosen: not an extra
    ([2, 5], None, set()),
    ([2, 12], [100.0], {"12*"}),        # position 12 is the extra (the grid has 12: 0..11)
])
def test_only_extra_positions_are_starred(tmp_path, chosen, extra, marked):
    """kinetostatics.positions: [2, 5] labels them '2', '5': the asterisk (whose legend says
    'an extra position') marks only the positions beyond the equal steps of the grid."""
    data = copy.deepcopy(SHAPER)
    data["kinetostatics"]["positions"] = chosen
    if extra:
        data["positions"] = {"extra": extra}
    task = tmm_cli.load_task(data)
    r = tmm_cli.run(task, kinematics_curve=0)
    assert r["positions"]["count"] == 12
    render(r, task, tmp_path, {"html"}, "en")
    sec = _kinetostatics_html((tmp_path / "report.html").read_text(encoding="utf-8"))
    cells = set(_position_cells(sec))
    expect = {str(i) for i in chosen if i < 12} | marked
    assert cells == expect
    assert ("an extra position" in sec) == bool(marked)


def test_each_position_figure_captions_what_it_shows(shared_once):
    """A position's groups and its lever are two figures; the one caption under the lever
    described both ('Left: the groups ... Bottom: Zhukovsky's lever') and the note, numbering
    them, captioned the groups by the position only. Now each its own, headed by the position."""
    import re as _re

    from pdf_extent import report_out
    html = (report_out(shared_once, "forging_sixbar", "en") / "report.html").read_text(encoding="utf-8")
    kst = html[html.index('id="kinetostatics"'):]
    kst = kst[kst.index('<div class="position">'):]
    kst = kst[:kst.index("</section>")]
    blocks = kst.split('<div class="position">')[1:]
    pairs = [_re.findall(r'<figure[^>]*>.*?</figure>', b, _re.S) for b in blocks]
    assert pairs and all(len(p) >= 2 for p in pairs), [len(p) for p in pairs]
    # every page of groups (a six-bar's may fill two) and the lever: each captioned
    groups, levers = [g for p in pairs for g in p[:-1]], [p[-1] for p in pairs for _ in p[:-1]]

    def caption(f):
        m = _re.search(r"<figcaption>(.*?)</figcaption>", f, _re.S)
        return _re.sub(r"<[^>]+>", "", m.group(1)) if m else ""
    for g, lv in zip(groups, levers):
        cg, cl = caption(g), caption(lv)
        assert cg.startswith("Position ") and "force polygons" in cg and "lever" not in cg, cg
        assert cl.startswith("Position ") and "Zhukovsky" in cl and "groups" not in cl, cl
        assert cg.split(".")[0] == cl.split(".")[0]            # the same position
