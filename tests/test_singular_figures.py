"""The mechanism drawn at each singular angle of the kinetostatics (report section
'kinetostatics'): a crank-rocker four-bar with the rocker as balance link is singular where
crank and coupler are in line (the cosine rule in the triangle O-B-O3 gives the two crank
angles); results ``singular_positions`` hold the mechanism there, the report draws it with
the two links highlighted, its joints where the hand construction puts them."""
from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest

import tmm_cli
from test_worked_centres import _circles, _frame

ROOT = Path(__file__).resolve().parents[1]
A_, B_, C_, D_ = 0.08, 0.30, 0.22, 0.30        # crank OA, coupler AB, rocker O3B, frame OO3 (the task)


def _dead_points():
    """(phi deg, {point: xy}) where crank and coupler are in line: extended |OB| = a + b (B at
    the crank's angle), folded |OB| = b - a (B opposite to A); B above OO3."""
    out = []
    for L, add in ((A_ + B_, 0.0), (B_ - A_, 180.0)):
        t = math.acos((L ** 2 + D_ ** 2 - C_ ** 2) / (2 * L * D_))       # angle of OB
        phi = math.degrees(t) + add
        u = np.array([math.cos(math.radians(phi)), math.sin(math.radians(phi))])
        out.append((phi, {"O": np.zeros(2), "O3": np.array([D_, 0.0]), "A": A_ * u,
                          "B": L * np.array([math.cos(t), math.sin(t)])}))
    return out


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    from tmm_cli.report import render
    tmp = tmp_path_factory.mktemp("singular")
    text = (ROOT / "tasks" / "crank_rocker_fourbar.yaml").read_text(encoding="utf-8")
    assert "  balance: crank\n" in text
    path = tmp / "rocker_balance.yaml"
    path.write_text(text.replace("  balance: crank\n", "  balance: rocker\n"), encoding="utf-8")
    task = tmm_cli.load_task(path)
    res = tmm_cli.run(task, kinematics_curve=0)
    render(res, task, tmp / "o", {"html"}, "en")
    return res, tmp / "o"


def test_results_hold_the_mechanism_at_each_singular_angle(report):
    res, _ = report
    want = _dead_points()
    assert res["singular"] == pytest.approx([p for p, _ in want], abs=1e-6)
    assert len(res["singular_positions"]) == 2
    for (phi, pts), got in zip(want, res["singular_positions"]):
        assert got["phi"] == pytest.approx(phi, abs=1e-6)
        for p, xy in pts.items():
            assert [got["points"][p]["x"], got["points"][p]["y"]] == pytest.approx(list(xy), abs=1e-7), p
        assert got["links"]["crank"]["angle"] == pytest.approx(phi % 360.0, abs=1e-6)


def test_the_figures_draw_it_with_the_dyad_in_line_highlighted(report):
    res, out = report
    html = (out / "report.html").read_text(encoding="utf-8")
    sec = re.sub(r"<svg.*?</svg>", "", html[html.index('id="kinetostatics"'):], flags=re.S)
    caps = re.findall(r"<figcaption>(The mechanism at the singular angle[^<]*)</figcaption>", sec)
    assert len(caps) == 2
    for k, ((phi, pts), cap) in enumerate(zip(_dead_points(), caps), start=1):
        assert float(re.search(r"φ = ([-0-9.]+)°", cap).group(1)) == pytest.approx(phi, abs=6e-4)
        assert "links 1 and 2 in line" in cap and "O, A, B" in cap
        svg = (out / "figures" / f"singular-{k}.svg").read_text(encoding="utf-8")
        entry = res["singular_positions"][k - 1]
        mu, o = _frame(svg, entry)

        def mm(xy):                                          # model metres -> SVG mm (y down)
            q = (np.asarray(xy) - o) / mu
            return np.array([q[0], -q[1]])
        pins = [np.array([x, y]) for x, y, r, s in _circles(svg) if s == "#000000" and abs(r - 1.1) < 0.01]
        for p, xy in pts.items():
            assert min(np.hypot(*(q - mm(xy))) for q in pins) <= 0.02, (k, p)
        d = re.search(r'<path d="([^"]*)" fill="none" stroke="#c0392b"', svg).group(1)
        ends = np.array([float(v) for v in re.findall(r"[-0-9.]+", d)]).reshape(-1, 2)
        for p in ("O", "A", "B"):                            # the highlighted links: O-A and A-B
            assert min(np.hypot(*(q - mm(pts[p]))) for q in ends) <= 0.02, (k, p)


def test_no_figure_without_a_singular_angle(tmp_path):
    from tmm_cli.report import render
    task = tmm_cli.load_task(ROOT / "tasks" / "crank_rocker_fourbar.yaml")
    res = tmm_cli.run(task, kinematics_curve=0)
    assert res["singular"] == [] and "singular_positions" not in res
    render(res, task, tmp_path, {"html"}, "en")
    assert not list((tmp_path / "figures").glob("singular-*.svg"))


def test_their_labels_neither_overlap_nor_leave(report, tmp_path, monkeypatch):
    from figure_record import record_texts
    from test_figure_labels import problems
    from tmm_cli.report import render
    monkeypatch.setenv("TMM_REPORT_JOBS", "1")
    res, out = report
    task = tmm_cli.load_task(out.parent / "rocker_balance.yaml")
    figs = record_texts(monkeypatch)
    render(res, task, tmp_path, {"html"}, "ru")
    assert len(figs) > 2 and problems(figs) == []


def test_slider_balance_of_an_offset_slider_crank(tmp_path):
    """Balance on the ram: singular where crank (r = 0.08) and rod (l = 0.35) are in line, B on
    the vertical guide x = e = 0.025: |OB| = r + l with cos(phi) = e / (r + l), or |OB| = l - r
    with A opposite to B, cos(phi + 180) = e / (l - r)."""
    from tmm_cli.report import render
    r, l, e = 0.08, 0.35, 0.025
    text = (ROOT / "tasks" / "press_offset_slider_crank.yaml").read_text(encoding="utf-8")
    assert "  balance: crank\n" in text
    path = tmp_path / "ram_balance.yaml"
    path.write_text(text.replace("  balance: crank\n", "  balance: ram\n"), encoding="utf-8")
    task = tmm_cli.load_task(path)
    res = tmm_cli.run(task, kinematics_curve=0)
    c1, c2 = math.degrees(math.acos(e / (r + l))), math.degrees(math.acos(e / (l - r)))
    want = sorted(x % 360.0 for x in (c1, -c1, 180.0 + c2, 180.0 - c2))
    assert len(res["singular"]) == 2
    for phi, pos in zip(res["singular"], res["singular_positions"]):
        assert min(abs(phi - w) for w in want) < 1e-6
        P = {k: np.array([v["x"], v["y"]]) for k, v in pos["points"].items()}
        A = r * np.array([math.cos(math.radians(phi)), math.sin(math.radians(phi))])
        assert P["A"] == pytest.approx(A, abs=1e-9)
        assert P["B"][0] == pytest.approx(e, abs=1e-9)
        assert abs(A[0] * P["B"][1] - A[1] * P["B"][0]) <= 1e-7 * r * (r + l)      # O, A, B in line
    render(res, task, tmp_path / "o", {"html"}, "en")
    html = (tmp_path / "o" / "report.html").read_text(encoding="utf-8")
    caps = re.findall(r"<figcaption>(The mechanism at the singular angle[^<]*)</figcaption>", html)
    assert len(caps) == 2 and all("links 1 and 2 in line" in c and "O, A, B" in c for c in caps)
    assert len(list((tmp_path / "o" / "figures").glob("singular-*.svg"))) == 2
