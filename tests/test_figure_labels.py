"""Labels of the report's figures, every figure of every example task (tasks/*.yaml):
no two text boxes intersect and none lies outside its figure; every scale the report
states (μl, μv, μa, μF, μM, ... = value) is from the standard series.

The boxes are measured, not taken from the placement code: the texts of the drawings
tmm draws itself (the SVG canvas: plans, groups, force polygons, the lever, the gear
trains) are recorded as they are written (width 0.6 x font size per character, the
font size high), and so are the texts of the charts and scale drawings laid out as
matplotlib laid them out (svgchart's figures of figures.new_figure: cam, gears, planetary,
two-DOF; ascent 0.76, descent 0.24 of the font size about the baseline, a subscript or
superscript counted full width; tick labels are written only where their tick is within
the axis).  One report per task."""
from __future__ import annotations

import html as html_mod
import math
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
TASKS = sorted(p.stem for p in (ROOT / "tasks").glob("*.yaml"))


def _record(monkeypatch) -> list:
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


def problems(figs) -> list:
    out = []
    for n, (kind, W, H, boxes) in enumerate(figs, start=1):
        for s, b in boxes:
            if b[0] < -0.01 or b[1] < -0.01 or b[2] > W + 0.01 or b[3] > H + 0.01:
                out.append(f"figure {n} ({kind}): {s!r} outside the figure")
        for i in range(len(boxes)):
            a = boxes[i][1]
            for j in range(i + 1, len(boxes)):
                b = boxes[j][1]
                if min(a[2], b[2]) - max(a[0], b[0]) > 1e-6 and min(a[3], b[3]) - max(a[1], b[1]) > 1e-6:
                    out.append(f"figure {n} ({kind}): {boxes[i][0]!r} over {boxes[j][0]!r}")
    return out


# not a product such as the worked steps' "v_B = pb·μv = 36.84·0.04" (a segment times μ)
# (the number ends where no digit follows: a formula runs its unit on, "μv=0.02м/(с·мм)"); a number
# as the report writes it: 0.005, 2e-05 (en); 0,005, 2·10⁻⁵ (ru, uk)
_MU = re.compile(r"(?<![·*×])μ\s?([^\s=()<>;,]{1,8})\s?=\s?([0-9]+(?:[.,][0-9]+)?(?:e[-+]?[0-9]+|·10[⁻⁺]?[⁰¹²³⁴⁵⁶⁷⁸⁹]+)?)(?![0-9])")


def read_number(s: str) -> float:
    """A number of the report's text in any of its languages (decimal comma, ·10ⁿ)."""
    s = s.replace(",", ".").replace("−", "-")
    if "·10" in s:
        m, e = s.split("·10")
        return float(m) * 10.0 ** int(e.translate(str.maketrans("⁰¹²³⁴⁵⁶⁷⁸⁹⁻⁺", "0123456789-+")))
    return float(s)


def stated_scales(html: str) -> list[tuple[str, float]]:
    """Every 'μX = number' the report states (in its text, tables and figures)."""
    text = " ".join(re.sub(r"<[^>]+>", "", html_mod.unescape(html)).split())
    return [(sym, read_number(v)) for sym, v in _MU.findall(text)]


def standard(sym: str, mu: float) -> bool:
    """1, 2, 2.5, 4, 5 x 10^k; a length scale also 1.5 and 7.5 x 10^k (ГОСТ 2.302: 1:15, 1:75)."""
    k = math.floor(math.log10(mu) + 1e-12)
    m = round(mu / 10 ** k, 9)
    return m in (1, 2, 2.5, 4, 5) or (sym == "l" and m in (1.5, 7.5))


def test_the_scale_reader():
    html = ('<text>μ<tspan dy="1">v</tspan><tspan> = 0.02 (m/s)/mm</tspan></text> <p>μs = 0.004 m/mm; '
            'μF = 2.5e+03 N/mm, μl = 0.015 m/mm, μφ = 3 °/mm</p>')
    got = stated_scales(html)
    assert got == [("v", 0.02), ("s", 0.004), ("F", 2500.0), ("l", 0.015), ("φ", 3.0)]
    assert [standard(s, m) for s, m in got] == [True, True, True, True, False]


def test_the_checker_sees_a_collision_and_a_label_outside():
    figs = [("drawing", 50.0, 20.0, [("R12", (1.0, 1.0, 6.0, 3.0)), ("G2", (5.0, 2.0, 8.0, 4.0)),
                                     ("Φ3", (48.0, 5.0, 52.0, 7.0))])]
    assert problems(figs) == ["figure 1 (drawing): 'Φ3' outside the figure",
                              "figure 1 (drawing): 'R12' over 'G2'"]


@pytest.mark.parametrize("name", TASKS)
def test_no_label_collides_or_leaves_its_figure(name, tmp_path, monkeypatch):
    import tmm_cli
    from tmm_cli.report import render
    monkeypatch.setenv("TMM_REPORT_JOBS", "1")       # every figure drawn in this process
    task = tmm_cli.load_task(ROOT / "tasks" / f"{name}.yaml")
    res = tmm_cli.run(task)
    figs = _record(monkeypatch)
    render(res, task, tmp_path, {"html"}, "ru" if name.startswith(("forging", "shaper")) else "en")
    # a differential alone draws only a chart (svgchart places its own labels): no drawing to record
    assert figs or set(res) & {"structure", "cam", "gears", "planetary", "drive_train", "dof2"} == set()
    assert problems(figs) == []
    # every scale the report states is a standard one
    html = (tmp_path / "report.html").read_text(encoding="utf-8")
    scales = stated_scales(html)
    assert [(s, m) for s, m in scales if not standard(s, m)] == []
    if res.get("kinematics") and res.get("structure"):
        syms = {s for s, _ in scales}
        assert {"l", "v", "a", "φ"} <= syms, syms          # the mechanism, the plans, the diagrams
