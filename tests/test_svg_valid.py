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


def ink_outside(svg: str) -> tuple[float, str]:
    """How far (mm) the farthest point of the figure's drawing lies outside its viewBox: every
    point of its paths (absolute M, L, C commands, as tmm's canvases write them) and every
    text's anchor; with the element it belongs to."""
    x0, y0, w, h = map(float, re.search(r'viewBox="([-\d.]+) ([-\d.]+) ([-\d.]+) ([-\d.]+)"', svg).groups())
    worst, what = 0.0, ""
    for el in re.findall(r"<(?:path|text)\b[^>]*>", svg):
        pts = []
        d = re.search(r'\sd="([^"]+)"', el)
        if d:
            pts = [(float(a), float(b)) for a, b in re.findall(r"[MLC]\s*([-\d.e]+)[ ,]([-\d.e]+)", d.group(1))]
        elif el.startswith("<text"):
            xy = re.search(r'\sx="([-\d.]+)"[^>]*\sy="([-\d.]+)"', el)
            pts = [(float(xy.group(1)), float(xy.group(2)))] if xy else []
        for x, y in pts:
            out = max(x0 - x, x - x0 - w, y0 - y, y - y0 - h)
            if out > worst:
                worst, what = out, el[:160]
    return worst, what


@pytest.mark.parametrize("path", TASKS, ids=[p.stem for p in TASKS])
def test_no_figure_is_cut_off_at_its_edge(path, shared_once):
    """Every figure of every example draws inside its own frame, to half a millimetre (an arrow
    head's side): the rocker cam's pivot A with its ground lay 54 mm left of the construction's
    figure, the knife-edge cam's follower axes 19 mm past the profile's, a force arrow on
    Zhukovsky's lever 8.6 mm below its figure, the drive train's driven wheel off the scheme
    -- each cut off where the page shows the figure."""
    out = report_out(shared_once, path.stem, "en")
    bad = []
    for f in sorted((out / "figures").glob("*.svg")):
        far, what = ink_outside(f.read_text(encoding="utf-8"))
        if far > 0.5:
            bad.append(f"{f.name}: {far:.2f} mm outside: {what}")
    assert not bad, "\n".join(bad)


def test_the_cut_off_check_sees_a_line_past_the_edge():
    svg = ('<svg viewBox="0 0 100 50"><path d="M10 10 L20 20"/><text x="50" y="25">a</text></svg>')
    assert ink_outside(svg)[0] == 0.0
    assert ink_outside(svg.replace("L20 20", "L20 53"))[0] == pytest.approx(3.0)
    assert ink_outside(svg.replace('x="50"', 'x="-4"'))[0] == pytest.approx(4.0)
