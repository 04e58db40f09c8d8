"""The report in a real browser: headless Chromium (the system's, driven by
playwright) draws every figure of report.html with as much ink as the PDF shows.

A figure that one renderer draws differently from the other (a colour a browser does
not accept, such as stroke="k" or fill="0.35", an SVG feature one of them lacks)
shows here.  For each figure the ink is the mean darkness (0 white .. 1 black) of
its pixels: in the browser a screenshot of the <svg> element in report.html, in the
PDF the same SVG put through the report's PDF engine (Typst, an image on a page of
the figure's size), rasterised by pdftoppm.  Measured on the examples (the tasks below
and forging_sixbar): the two agree within 0.92..1.01; a plan drawn without its lines falls
below the band (test_the_comparison_sees_lines_a_renderer_drops).

Each kind of figure is compared in its first and last position (:func:`sampled`): the
velocity plans of the twelve positions, or their force drawings, are one writer's drawings
of one kind, and a screenshot costs Chromium about 0.13 s (the shaper's 51 figures took 8 s
of the suite's time, its 21 samples 3.5 s).

Needs Chromium (Debian: apt-get install chromium), pdftoppm (poppler-utils) and the
playwright package (pip install -e '.[test]'); `.ci/run` installs them.  Where the
browser cannot be installed or launched the test is skipped, saying which part is
missing."""
from __future__ import annotations

import io
import re
import subprocess
from pathlib import Path

import pytest


ROOT = Path(__file__).resolve().parents[1]
# every writer of figures: linkage plans and force drawings (svgdraw), Coriolis plans,
# matplotlib diagrams, cam, gears, planetary and dof2 figures
TASKS = ["engine_slider_crank", "shaper_slotted_lever", "cam_rocker", "gears_shifted", "planetary_A",
         "impact_rotor"]
BAND = (0.85, 1.15)        # browser ink / PDF ink, per figure
DPI = 192                  # the PDF raster; the browser draws at device scale 2 (192 dpi)
def _ink(png) -> float:
    """Mean darkness of an image: 0 all white, 1 all black."""
    import numpy as np
    from PIL import Image
    im = Image.open(io.BytesIO(png) if isinstance(png, bytes) else png)
    a = np.asarray(im.convert("L"), dtype=float)
    return float((255.0 - a).mean() / 255.0)


_SIZE = re.compile(r'width="([0-9.]+)pt"\s+height="([0-9.]+)pt"')


def pdf_inks(svgs: list[str], tmp: Path) -> list[float]:
    """Each SVG painted by the report's PDF engine on a page of its own size."""
    import typst
    from tmm_cli.report.typst_pdf import _font_dirs
    src = []
    for k, s in enumerate(svgs):
        w, h = _SIZE.search(s[:500]).groups()
        if "xmlns=" not in s[:300]:
            s = s.replace("<svg", '<svg xmlns="http://www.w3.org/2000/svg"', 1)
        (tmp / f"f{k}.svg").write_text(s, encoding="utf-8")
        src.append(f'#page(width: {w}pt, height: {h}pt, margin: 0pt, '
                   f'image("f{k}.svg", width: 100%, height: 100%))')
    (tmp / "figs.typ").write_text("\n".join(src), encoding="utf-8")
    (tmp / "figs.pdf").write_bytes(typst.compile(str(tmp / "figs.typ"), root=str(tmp),
                                                 font_paths=_font_dirs()))
    # PPM, not PNG: the same pixels without pdftoppm's PNG compression (7.3 s -> 1.1 s for the
    # shaper's 51 figures)
    subprocess.run(["pdftoppm", "-r", str(DPI), str(tmp / "figs.pdf"), str(tmp / "pg")], check=True)
    pages = sorted(tmp.glob("pg-*.ppm"), key=lambda p: int(re.search(r"-(\d+)\.ppm$", p.name).group(1)))
    return [_ink(p) for p in pages]


def sampled(html: str) -> list[int]:
    """The indices (in document order) of the figures compared: each kind of figure in its
    first and last place.  A figure's kind is its caption, or without one the words before it
    (a plan's heading "Position 3, phi = 111.51 deg"), with the numbers taken out."""
    kinds: dict[str, list[int]] = {}
    for k, m in enumerate(re.finditer(r"<figure\b.*?</figure>", html, re.S)):
        cap = re.search(r"<figcaption>(.*?)</figcaption>", m.group(0), re.S)
        # without a caption: the last text before it (a position's heading)
        before = html[max(0, m.start() - 400):m.start()].rstrip()
        while before.endswith(">"):
            before = before[:before.rfind("<")].rstrip()
        words = cap.group(1) if cap else "before: " + before.rpartition(">")[2]
        kinds.setdefault(re.sub(r"[\d.,*\s]+", " ", re.sub(r"<[^>]+>", "", words)).strip(), []).append(k)
    return sorted({k for ks in kinds.values() for k in (ks[0], ks[-1])})


def browser_inks(browser, html: Path, only: list[int] | None = None, total: int | None = None) -> list[float]:
    """The ink of each figure's <svg> as Chromium draws it (``only``: of these figures, by
    index; ``total``: the figures the page must hold)."""
    page = browser.new_page(device_scale_factor=DPI / 96, viewport={"width": 1000, "height": 800})
    try:
        page.goto(html.resolve().as_uri())
        # every figure inside the viewport: a figure taller than it is captured beyond the
        # viewport, about three times slower (the shaper's 816 px levers) for the same pixels
        tallest = page.evaluate("() => Math.max(0, ...[...document.querySelectorAll('figure svg')]"
                                ".map(e => Math.ceil(e.getBoundingClientRect().height)))")
        page.set_viewport_size({"width": 1000, "height": max(800, tallest + 40)})
        # a figure's screenshot waits for it to be still; on a loaded CI machine that can take
        # longer than playwright's 30 s default (no CSS animation needs to run for the ink)
        els = page.query_selector_all("figure svg")
        assert total is None or len(els) == total, (len(els), total)
        return [_ink(els[k].screenshot(animations="disabled", timeout=180_000))
                for k in (range(len(els)) if only is None else only)]
    finally:
        page.close()


@pytest.mark.parametrize("name", TASKS)
def test_browser_draws_what_the_pdf_shows(browser, name, tmp_path, shared_once):
    from pdf_extent import report_out
    html = report_out(shared_once, name, "en") / "report.html"      # as `tmm run` writes it
    text = html.read_text(encoding="utf-8")
    svgs = re.findall(r"<svg\b.*?</svg>", text, re.S)
    assert len(svgs) == len(re.findall(r"<figure\b", text)) > 0         # one drawing a figure
    only = sampled(text)
    b = browser_inks(browser, html, only, total=len(svgs))
    (tmp_path / "pdf").mkdir()
    p = pdf_inks([svgs[k] for k in only], tmp_path / "pdf")
    assert len(only) == len(b) == len(p) > 0
    bad = [f"figure {k + 1}: browser ink {bi:.4f}, PDF ink {pi:.4f} (ratio {bi / pi:.2f})"
           for k, bi, pi in zip(only, b, p)
           if not (pi > 0.002 and BAND[0] <= bi / pi <= BAND[1])]
    assert not bad, "\n".join(bad)


def test_each_kind_of_figure_is_sampled_first_and_last():
    fig = '<figure class="fig "><svg></svg>{}</figure>'
    cap = "<figcaption>{}</figcaption>"
    html = "".join([fig.format(cap.format("Kinematic scheme (position 0)"))]
                   + [fig.format(cap.format(f"Position {k}*, &phi; = {30.5 * k}&deg;. The lever")) for k in range(1, 5)]
                   + [f"<p>Position {k}, phi = {k}.5</p>" + fig.format("") for k in range(1, 4)]
                   + [fig.format(cap.format("Load diagrams"))])
    assert sampled(html) == [0, 1, 4, 5, 7, 8]


def test_the_comparison_sees_lines_a_renderer_drops(browser, tmp_path):
    """The test itself: a plan written with matplotlib colour names (the defect: browsers
    and Typst both drop such colours) has far less ink than the complete plan, in the
    browser and in the PDF, so a figure one renderer draws without its lines falls
    outside the band; the complete plan agrees."""
    from tmm_cli.report.svgdraw import Canvas
    cv = Canvas(80, 40)
    for k in range(6):
        cv.arrow((5, 5 + 5 * k), (75, 8 + 5 * k), "#000000", 0.45)
    good = cv.to_svg()
    broken = good.replace('stroke="#000000"', 'stroke="k"').replace('fill="#000000"', 'fill="k"')
    html = tmp_path / "r.html"
    html.write_text(f"<html><body><figure>{good}</figure><figure>{broken}</figure></body></html>")
    b = browser_inks(browser, html)
    p = pdf_inks([good, broken], tmp_path)
    assert BAND[0] <= b[0] / p[0] <= BAND[1]
    assert b[1] / p[0] < BAND[0]                        # lines missing in the browser: seen
    assert p[1] / b[0] < BAND[0]                        # lines missing in the PDF: seen
