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
the axis).  One report per task: the one `tmm run --format html,pdf` writes, built once per test
session and shared with the page tests (tests/pdf_extent.py)."""
from __future__ import annotations

import html as html_mod
import math
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
TASKS = sorted(p.stem for p in (ROOT / "tasks").glob("*.yaml"))


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
def test_no_label_collides_or_leaves_its_figure(name, shared_once):
    from pdf_extent import recorded, report_out, results
    # the report `tmm run` writes (html and pdf), its figures recorded as they were drawn
    lang = "ru" if name.startswith(("forging", "shaper")) else "en"
    figs = recorded(shared_once, name, lang)["texts"]
    res = results(shared_once, name)[1]
    # a differential alone draws only a chart (svgchart places its own labels): no drawing to record
    assert figs or set(res) & {"structure", "cam", "gears", "planetary", "drive_train", "dof2"} == set()
    assert problems(figs) == []
    # every scale the report states is a standard one
    html = (report_out(shared_once, name, lang) / "report.html").read_text(encoding="utf-8")
    scales = stated_scales(html)
    assert [(s, m) for s, m in scales if not standard(s, m)] == []
    if res.get("kinematics") and res.get("structure"):
        syms = {s for s, _ in scales}
        assert {"l", "v", "a", "φ"} <= syms, syms          # the mechanism, the plans, the diagrams
