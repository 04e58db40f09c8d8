"""The instant centres on the drawing of the worked position (report section 'worked'):
every centre the results hold is drawn at its coordinates at the figure's scale (read back
from the SVG), listed in the caption with its coordinates when far outside the drawing, or
listed as at infinity; for a four-bar the centres not joined directly are checked against
Kennedy's construction done here (P02: the lines OA and O3B crossed, P13: the lines OO3 and
AB crossed)."""
from __future__ import annotations

import itertools
import re
from pathlib import Path

import numpy as np
import pytest

import tmm_cli
from test_figure_labels import read_number, stated_scales

ROOT = Path(__file__).resolve().parents[1]
COLOR = "#b03060"


def _report(name, tmp_path, lang="en"):
    from tmm_cli.report import render
    task = tmm_cli.load_task(ROOT / "tasks" / f"{name}.yaml")
    res = tmm_cli.run(task, kinematics_curve=0)
    render(res, task, tmp_path, {"html"}, lang)
    n = res["positions"]["detail_position"]
    svg = (tmp_path / "figures" / f"centres-pos{n:02d}.svg").read_text(encoding="utf-8")
    html = (tmp_path / "report.html").read_text(encoding="utf-8")
    sec = html[html.index('id="worked"'):]
    cap = re.sub(r"<svg.*?</svg>", "", sec, flags=re.S)
    cap = cap[cap.index("<figcaption>"):cap.index("</figcaption>")]
    return res, next(e for e in res["kinematics"] if e["index"] == n), svg, cap


def _circles(svg):
    """(cx, cy, r, stroke) of every circle, mm (y down)."""
    out = []
    for m in re.finditer(r"<circle ([^>]*)/>", svg):
        a = dict(re.findall(r'([a-z-]+)="([^"]*)"', m.group(1)))
        out.append((float(a["cx"]), float(a["cy"]), float(a["r"]), a["stroke"]))
    return out


def _frame(svg, entry):
    """(metres per mm, the model point at the canvas' top left): the scale as the figure states
    it; the offset that puts the most joints of the results on the drawn pin circles."""
    mu = [m for s, m in stated_scales(svg) if s == "l"]
    assert len(mu) == 1
    mu = mu[0]
    pins = [(x, y) for x, y, r, s in _circles(svg) if s == "#000000" and abs(r - 1.1) < 0.01]
    pts = [(v["x"], v["y"]) for v in entry["points"].values()]
    best, score = None, -1
    for (cx, cy), (x, y) in itertools.product(pins, pts):
        o = np.array([x - cx * mu, y + cy * mu])          # model = o + (cx, -cy) * mu
        hits = sum(min(np.hypot(*(o + np.array([px, -py]) * mu - np.array(q))) for px, py in pins) < 1e-3 * mu
                   for q in pts)
        if hits > score:
            best, score = o, hits
    assert score >= 3
    return mu, best


def _cross_lines(p, q, r, s):
    """The point where the line pq meets the line rs."""
    d1, d2 = q - p, s - r
    t = ((r[0] - p[0]) * d2[1] - (r[1] - p[1]) * d2[0]) / (d1[0] * d2[1] - d1[1] * d2[0])
    return p + t * d1


def _check_drawn(svg, cap, entry):
    mu, o = _frame(svg, entry)
    rings = [np.array([x, y]) for x, y, r, s in _circles(svg) if s == COLOR]
    drawn = [o + np.array([x, -y]) * mu for x, y in rings]         # metres
    seen = [False] * len(drawn)
    for key, xy in entry["instant_centres"].items():
        name = "<i>P</i><sub>{}</sub>".format(key.replace("-", ""))
        if xy is None:
            assert name in cap, key                                # listed as at infinity
            continue
        d = [np.hypot(*(q - np.array(xy))) for q in drawn]
        k = int(np.argmin(d)) if d else -1
        if k >= 0 and d[k] <= 0.02 * mu:                           # drawn where it is (0.02 mm)
            seen[k] = True
            assert svg.count(f">{key.replace('-', '')}<") >= 1, key   # and labelled P_ij
        else:
            assert name in cap, key                                # listed with its coordinates
            got = re.search(re.escape(name) + r" \(([^;()]+); ([^;()]+)\)", cap)
            assert got, key
            assert read_number(got.group(1)) == pytest.approx(xy[0], rel=1e-3, abs=1e-9)
            assert read_number(got.group(2)) == pytest.approx(xy[1], rel=1e-3, abs=1e-9)
    assert all(seen)                                                # no circle that is no centre
    return mu, o, drawn


def test_four_bar_centres_drawn_at_their_places_and_by_kennedy(tmp_path):
    res, e, svg, cap = _report("crank_rocker_fourbar", tmp_path)
    mu, o, drawn = _check_drawn(svg, cap, e)
    P = {k: np.array([v["x"], v["y"]]) for k, v in e["points"].items()}
    ic = e["instant_centres"]
    p02 = _cross_lines(P["O"], P["A"], P["O3"], P["B"])            # Kennedy: 0-1-2 and 0-3-2
    p13 = _cross_lines(P["O"], P["O3"], P["A"], P["B"])            # 1-0-3 and 1-2-3
    size = np.hypot(*(P["O3"] - P["O"]))
    assert np.allclose(ic["0-2"], p02, atol=1e-9 * size)
    assert np.allclose(ic["1-3"], p13, atol=1e-9 * size)
    for key, want in (("0-1", P["O"]), ("1-2", P["A"]), ("2-3", P["B"]), ("0-3", P["O3"]), ("1-3", p13)):
        assert min(np.hypot(*(q - want)) for q in drawn) <= 0.02 * mu, key
    # P02 is far above the mechanism at this position: listed, the drawing keeps its scale
    assert "<i>P</i><sub>02</sub>" in cap and len(drawn) == 5


@pytest.mark.parametrize("name", ["forging_sixbar", "scotch_yoke_pump", "shaper_slotted_lever"])
def test_centres_of_other_linkages(name, tmp_path):
    res, e, svg, cap = _report(name, tmp_path)
    _check_drawn(svg, cap, e)


def test_the_caption_in_russian(tmp_path):
    from tmm_cli import locales
    words = locales.of("worked", "words", "ru")
    res, e, svg, cap = _report("shaper_slotted_lever", tmp_path, "ru")
    _check_drawn(svg, cap, e)
    assert words["worked.centres_inf"] in cap and words["worked.centres_far"] in cap
