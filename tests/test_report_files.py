"""The report's figures also stand beside it as SVG files (SPEC 2: 'with figures and
CSV tables beside them'), each a well-formed SVG, listed with its caption."""
from __future__ import annotations

import csv
import re
import xml.dom.minidom
from pathlib import Path

import tmm_cli
from tmm_cli.report import render

ROOT = Path(__file__).resolve().parents[1]


def test_figures_beside_the_report(tmp_path):
    task = tmm_cli.load_task(ROOT / "tasks" / "cam_translating.yaml")
    res = tmm_cli.run(task)
    written = render(res, task, tmp_path, {"html"}, "en")
    html = (tmp_path / "report.html").read_text(encoding="utf-8")
    n_fig = len(re.findall(r"<figure\b", html))
    files = sorted((tmp_path / "figures").glob("*.svg"))
    assert n_fig > 0 and len(files) == n_fig
    for f in files:
        doc = xml.dom.minidom.parse(str(f))
        assert doc.documentElement.tagName == "svg"
        assert f in written
    rows = list(csv.DictReader((tmp_path / "figures" / "index.csv").open(encoding="utf-8")))
    assert sorted(r["file"] for r in rows) == [f"figures/{f.name}" for f in files]
    # named by content, each with its caption
    assert {r["file"] for r in rows} == {"figures/cam-motion-law.svg", "figures/cam-construction.svg",
                                         "figures/cam-profile.svg", "figures/cam-pressure-angle.svg"}
    assert all(r["caption"] for r in rows)
    assert not list(tmp_path.rglob("*.tmp"))


def test_figure_files_named_by_content_and_position_with_captions_in_the_report_language(tmp_path):
    """A linkage in Ukrainian: the plans and Zhukovsky's lever of every position, the groups,
    the positions, each file listed in index.csv with a caption in Ukrainian."""
    task = tmm_cli.load_task(ROOT / "tasks" / "crank_rocker_fourbar.yaml")
    res = tmm_cli.run(task)
    render(res, task, tmp_path, {"html"}, "uk")
    rows = list(csv.DictReader((tmp_path / "figures" / "index.csv").open(encoding="utf-8")))
    files = {r["file"] for r in rows}
    html = (tmp_path / "report.html").read_text(encoding="utf-8")
    assert len(rows) == len(re.findall(r"<figure\b", html)) == len(files)
    idx = [e["index"] for e in res["kinetostatics"]]
    for i in idx:
        for kind in ("plans", "groups", "lever"):
            assert f"figures/{kind}-pos{i:02d}.svg" in files
    assert {"figures/scheme.svg", "figures/positions.svg"} <= files
    assert not any(re.search(r"/fig-\d+", f) for f in files)
    for r in rows:
        assert r["caption"] and (tmp_path / r["file"]).is_file()
        assert re.search("[а-яіїєґ]", r["caption"], re.I), r      # in Ukrainian
        assert "data-name" not in (tmp_path / r["file"]).read_text(encoding="utf-8")
    plans = next(r for r in rows if r["file"] == f"figures/plans-pos{idx[2]:02d}.svg")
    assert plans["caption"].startswith(f"Положення {idx[2]},")


def test_figures_found_as_the_regex_finds_them():
    """report._figures (str.find) gives what the regex it replaced gives, on random text
    made of the tags' pieces (word boundaries, missing ends, nesting)."""
    import random
    import re
    from tmm_cli.report import _figures
    rx = re.compile(r"<figure\b.*?(<svg\b.*?</svg>)(.*?)</figure>", re.S)
    rng = random.Random(5)
    toks = ["<figure", "<figure>", "<figurex", "<figure ", "<svg", "<svg ", "<svgé", "</svg>",
            "</figure>", "x", "<", ">", "é", "_", "1", " ", "\n"]
    found = 0
    for _ in range(20000):
        h = "".join(rng.choice(toks) for _ in range(rng.randint(0, 14)))
        want = [(m.start(), m.group(1), m.group(2)) for m in rx.finditer(h)]
        assert list(_figures(h)) == want, h
        found += len(want)
    assert found > 50
