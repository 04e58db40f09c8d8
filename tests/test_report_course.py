"""A fine grid of positions: the report shows the course positions one by one (plans,
per-position tables) and the whole grid as curves and in the CSV files."""
from __future__ import annotations

import csv
import json
import re
import subprocess
import sys
from pathlib import Path

from tmm_cli.report.course import COURSE_N, course_entries, course_indices, grid_count, grid_size

ROOT = Path(__file__).resolve().parents[1]


def test_course_indices():
    assert course_indices(12, 14) == list(range(14))              # a course grid: all of it
    assert course_indices(24, 24) == list(range(24))
    assert course_indices(3600, 3602) == [300 * k for k in range(12)] + [3600, 3601]
    idx = course_indices(50, 51)                                   # not a multiple of 12
    assert len(idx) == COURSE_N + 1 and idx[0] == 0 and idx[-1] == 50
    assert idx[:-1] == sorted(set(idx[:-1])) and all(i < 50 for i in idx[:-1])
    e = list(range(40))
    assert course_entries(e, 36) == [0, 3, 6, 9, 12, 15, 18, 21, 24, 27, 30, 33, 36, 37, 38, 39]


def test_grid_size_and_the_grid_positions_among_the_entries():
    """positions.count is the grid's size; of n entries (the grid's first, then the named
    extras) min(count, n) are the grid's; where the results do not say, every entry is."""
    twelve = {"positions": {"count": 12}}
    assert grid_size(twelve) == 12 and grid_count(twelve, 14) == 12     # two extras
    assert grid_count(twelve, 5) == 5                                  # kinetostatics of 5 chosen
    for unsaid in ({}, {"positions": {}}, {"positions": {"count": 0}}, {"positions": {"count": "12"}}):
        assert grid_size(unsaid) is None and grid_count(unsaid, 7) == 7


def test_fine_grid_report_shows_course_positions(tmp_path):
    task = tmp_path / "fine.yaml"
    task.write_text((ROOT / "tasks" / "forging_sixbar.yaml").read_text(encoding="utf-8")
                    .replace("count: 12", "count: 48"), encoding="utf-8")
    out = tmp_path / "o"
    p = subprocess.run([sys.executable, "-m", "tmm_cli", "run", str(task), "--format", "json,html",
                        "--quiet", "--out", str(out)], capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stderr
    res = json.loads((out / "results.json").read_text(encoding="utf-8"))
    n_all = len(res["kinematics"])
    n_extra = n_all - 48
    assert n_extra >= 1                                           # the extreme positions
    html = (out / "report.html").read_text(encoding="utf-8")
    kin = html[html.index('id="kinematics"'):]
    kin = kin[:kin.index("</section>")]
    # one block of plans a course position: 12 of the grid (every 4th) + the extras
    shown = re.findall(r'<div class="position">\s*<h\d[^>]*>.*?(\d+)', kin, re.S)
    assert len(shown) == COURSE_N + n_extra
    with open(out / "kinematics.csv", encoding="utf-8") as f:
        assert len(list(csv.reader(f))) == 1 + n_all              # the CSV keeps every position
    with open(out / "plans.csv", encoding="utf-8") as f:
        plan_rows = list(csv.DictReader(f))
    assert sorted({int(r["index"]) for r in plan_rows}) == [4 * k for k in range(12)] + \
        list(range(48, n_all))


def test_cycle_order_and_marks():
    from tmm_cli.report.course import cycle_order, position_label
    es = [{"index": i, "phi": (200.0 - 30.0 * i) % 360.0} for i in range(12)] + \
        [{"index": 12, "phi": 338.5}, {"index": 13, "phi": 8.4}, {"index": 14, "phi": 175.0}]
    got = [e["index"] for e in cycle_order(es, 200.0, -1.0)]          # clockwise from 200°
    assert got == [0, 14, 1, 2, 3, 4, 5, 6, 13, 7, 12, 8, 9, 10, 11]
    got = [e["index"] for e in cycle_order(es, 200.0, 1.0)]
    assert got[0] == 0 and got.index(12) < got.index(13)               # 138.5° before 168.4° ccw
    assert [position_label(e, 12) for e in es[10:]] == ["10", "11", "12*", "13*", "14*"]


def test_extra_positions_in_angle_order_in_every_table(tmp_path, monkeypatch):
    """The shaper's extras (338.5°, 8.4°, 175.0°; clockwise from 201.5°) stand between the
    grid positions they fall between, marked, in the same order in every table of the
    kinematics and the kinetostatics and in the plan pages; the curve of M_b and the
    reactions over the cycle closes at 360°."""
    import html as H

    from tmm_cli.pipeline import run
    from tmm_cli.report import render_html
    from tmm_cli.report import svgchart
    from tmm_cli.task import load_task
    plotted, notes = [], []
    orig, orig_note = svgchart.Axes.plot, svgchart.Axes.annotate

    def plot(self, *args, **kw):
        plotted.append(list(args[0]) if args and not isinstance(args[0], str) else None)
        return orig(self, *args, **kw)
    monkeypatch.setattr(svgchart.Axes, "plot", plot)

    def annotate(self, text, *args, **kw):
        notes.append(text)
        return orig_note(self, text, *args, **kw)
    monkeypatch.setattr(svgchart.Axes, "annotate", annotate)
    task = load_task(ROOT / "tasks" / "shaper_slotted_lever.yaml")
    res = run(task)
    page, _ = render_html(res, task, tmp_path, "en")
    pos = res["positions"]
    phase = {e["index"]: round(((e["phi"] - pos["phi0"]) * (-1 if pos["direction"] == "cw" else 1)) % 360.0, 6)
             % 360.0 for e in res["kinematics"]}
    want = [f"{i}*" if i >= 12 else str(i) for i in sorted(phase, key=phase.get)]
    assert want[:3] == ["0", "14*", "1"]
    for sec in ("kinematics", "kinetostatics"):
        body = page[page.index(f'id="{sec}"'):]
        body = body[:body.index("</section>")]
        tables = re.findall(r"<table.*?</table>", body, re.S)
        orders = []
        for t in tables:
            firsts = [H.unescape(re.sub(r"<[^>]+>", "", c)).strip()
                      for c in re.findall(r"<tr>\s*<td[^>]*>(.*?)</td>", t, re.S)]
            if len(firsts) >= len(want) and set(firsts) == set(want):
                orders.append(firsts)
        assert len(orders) >= (5 if sec == "kinematics" else 3), sec
        assert all(o == want for o in orders), sec
        heads = re.findall(r'<div class="position">\s*<h4[^>]*>\D*?(\d+\*?)', body)
        assert heads[:len(want)] == want, sec
    assert "an extra position" in page
    assert any(xs and xs[0] == 0.0 and xs[-1] == 360.0 for xs in plotted)        # M_b over the cycle
    assert {"12*", "13*", "14*"} & set(notes)           # the load diagrams' points: the extras marked too
