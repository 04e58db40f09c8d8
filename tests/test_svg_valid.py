"""Every figure of every example task is valid SVG 1.1 / CSS: a browser and the PDF
engine draw the same (a colour such as stroke="k" or fill="0.35" is dropped by browsers
and by Typst, which then draw no line).  The figures are read by an XML parser and every value is
checked with the grammar written out in svg_check.py."""
from __future__ import annotations

import re
from pathlib import Path

import pytest

from pdf_extent import report_out
from svg_check import is_color, problems

TASKS = sorted((Path(__file__).resolve().parents[1] / "tasks").glob("*.yaml"))


@pytest.mark.parametrize("path", TASKS, ids=[p.stem for p in TASKS])
def test_every_figure_is_valid_svg(path, shared_once):
    # report.html and figures/ as `tmm run --format html,pdf` writes them, made once per session
    # (tests/test_pdf_extent.py reads the same folder's PDF)
    out = report_out(shared_once, path.stem, "en")
    html = (out / "report.html").read_text(encoding="utf-8")
    inline = re.findall(r"<svg\b.*?</svg>", html, re.S)
    files = sorted((out / "figures").glob("*.svg"))
    assert inline and len(files) == len(inline)
    bad = []
    for k, svg in enumerate(inline, start=1):
        bad += problems(svg, f"report.html figure {k}")
    for f in files:
        bad += problems(f.read_text(encoding="utf-8"), f.name)
    assert not bad, "\n".join(bad[:20])


@pytest.mark.parametrize("spec, hexa", [
    ("k", "#000000"), ("0.35", "#595959"), ("0", "#000000"), ("1", "#ffffff"), ("w", "#ffffff"),
    ("#000", "#000000"), ("#1F5FBF", "#1f5fbf"), ("red", "#ff0000"), ((0.0, 0.5, 1.0), "#0080ff"),
    ("tab:blue", "#1f77b4"), ("none", "none")])
def test_css_color_converts_matplotlib_specs(spec, hexa):
    from tmm_cli.report.svgdraw import css_color
    assert css_color(spec) == hexa
    assert hexa == "none" or is_color(hexa)


def test_css_color_rejects_nonsense():
    from tmm_cli.report.svgdraw import css_color
    for spec in ("1.5", "blu", "#12345"):
        with pytest.raises(ValueError):
            css_color(spec)


def test_canvas_writes_valid_colours_and_widths():
    """A drawing given matplotlib-style colours and a hairline width still comes out valid."""
    from tmm_cli.report.svgdraw import Canvas
    cv = Canvas(50, 30)
    cv.arrow((2, 2), (40, 20), "k", 0.4)
    cv.line((0, 0), (10, 10), "0.35", 0.00001, dash="1 0.5")
    cv.circle((5, 5), 1, stroke="0.2", fill="w")
    cv.text(10, 10, "A", color="0.5", halo=True)
    svg = cv.to_svg()
    assert problems(svg) == []
    assert 'stroke="#000000"' in svg and 'stroke="#595959"' in svg and 'fill="#808080"' in svg


def test_checker_finds_browser_invalid_values():
    """The checker itself: the values of the defect are reported."""
    bad = problems('<svg xmlns="http://www.w3.org/2000/svg"><path d="M0 0 L1 1" stroke="k" '
                   'fill="0.35"/><text style="fill: 0.5">a</text><path d="L 1"/></svg>')
    assert len(bad) == 4
