"""A fine grid of positions: the report shows the course positions one by one (plans,
per-position tables) and the whole grid as curves and in the CSV files."""
from __future__ import annotations

import csv
import json
import re
import subprocess
import sys
from pathlib import Path

from tmm_cli.report.course import COURSE_N, course_entries, course_indices

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
