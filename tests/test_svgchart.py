"""The report's direct-SVG charts (tmm_cli/report/svgchart.py) and the report's PDF
path through Typst (tmm_cli/report/typst_pdf.py)."""
from __future__ import annotations

import re

import numpy as np
import pytest

from svg_check import problems
from tmm_cli.report import svgchart as C


# ---------------------------------------------------------------- periodic spline
@pytest.mark.parametrize("n", [3, 4, 7, 12, 24])
def test_periodic_spline_is_scipys_periodic_cubic_spline(n):
    from scipy.interpolate import CubicSpline
    rng = np.random.default_rng(n)
    x = np.sort(rng.uniform(0.0, 360.0, n))
    x = np.append(x, x[0] + 360.0)
    y = rng.normal(size=(n, 2))
    y = np.vstack([y, y[:1]])
    t = np.linspace(x[0] - 90.0, x[-1] + 200.0, 997)       # also beyond one period
    ref = CubicSpline(x, y, bc_type="periodic")(t)
    assert np.allclose(C.periodic_spline(x, y, t), ref, atol=1e-12)
    assert np.allclose(C.periodic_spline(x, y[:, 0], t), ref[:, 0], atol=1e-12)


@pytest.mark.parametrize("n", [2, 3, 4, 7, 12])
def test_natural_spline_is_scipys_natural_cubic_spline(n):
    """The open trajectories over an input range: scipy's natural cubic spline (M = 0 at both ends)
    between the first and the last point, passing through every one."""
    from scipy.interpolate import CubicSpline
    rng = np.random.default_rng(10 + n)
    x = np.sort(rng.uniform(0.0, 60.0, n))
    y = rng.normal(size=(n, 2))
    t = np.linspace(x[0], x[-1], 501)
    ref = CubicSpline(x, y, bc_type="natural")(t)
    assert np.allclose(C.natural_spline(x, y, t), ref, atol=1e-12)
    assert np.allclose(C.natural_spline(x, y[:, 0], t), ref[:, 0], atol=1e-12)
    assert np.allclose(C.natural_spline(x, y, x), y, atol=1e-12)


def test_periodic_spline_by_hand():
    """Three intervals h = 1 through y = 0, 1, 0, (0): slopes d = (1, -1, 0), right-hand
    sides 6 (d_i - d_{i-1}) = (6, -12, 6), matrix [[4,1,1],[1,4,1],[1,1,4]]; the rows sum to
    6 (M0 + M1 + M2) = 0, so 3 M0 = 6, 3 M1 = -12: M = (2, -4, 2).  At t = 0.5:
    S = (M0 + M1) 0.5^3 / 6 + (y0 - M0/6) 0.5 + (y1 - M1/6) 0.5 = -1/24 - 1/6 + 5/6 = 0.625."""
    x = [0.0, 1.0, 2.0, 3.0]
    y = [0.0, 1.0, 0.0, 0.0]
    s = C.periodic_spline(x, y, [0.0, 1.0, 0.5, 3.5])
    M0, M1 = 2.0, -4.0
    expect = (M0 + M1) / 48.0 + ((0.0 - M0 / 6.0) + (1.0 - M1 / 6.0)) / 2.0
    assert s[0] == pytest.approx(0.0, abs=1e-14) and s[1] == pytest.approx(1.0)
    assert s[2] == pytest.approx(expect, rel=1e-12) and expect == pytest.approx(0.625)
    assert s[3] == pytest.approx(s[2], rel=1e-12)             # one period later


# ---------------------------------------------------------------- ticks and labels
@pytest.mark.parametrize("lo, hi, n, expect", [
    (0.0, 360.0, 9, [0, 50, 100, 150, 200, 250, 300, 350]),
    (0.0, 360.0, 6, [0, 100, 200, 300]),
    (-0.108, 0.005, 6, [-0.10, -0.08, -0.06, -0.04, -0.02, 0.0]),
    (-3.5, 1.9, 6, [-3, -2, -1, 0, 1]),
    (0.0, 1.0, 4, [0.0, 0.25, 0.5, 0.75, 1.0]),
])
def test_nice_ticks(lo, hi, n, expect):
    assert np.allclose(C.nice_ticks(lo, hi, n), expect)


def test_tick_labels_fewest_decimals_and_a_true_minus():
    assert C.tick_labels([-0.1, -0.05, 0.0, 0.05]) == ["\u22120.10", "\u22120.05", "0.00", "0.05"]
    assert C.tick_labels([0, 2500, 5000]) == ["0", "2500", "5000"]
    assert C.tick_labels([0.0, 0.25, 0.5]) == ["0.00", "0.25", "0.50"]


def test_mathtext_subscripts():
    body = C.text_body("$R_{12}$ and $M_b$: crank", 3.0)
    assert re.sub(r"<[^>]+>", "", body) == "R12 and Mb: crank"
    assert body.count('font-size="2.16"') == 2 and 'font-style="italic"' in body
    assert C.text_body("plain, m/s", 3.0) == "plain, m/s"


# ---------------------------------------------------------------- a chart
def _chart():
    fig, (a1, a2) = C.subplots(170, 95, nrows=2, sharex=True)
    q = np.linspace(0, 360, 73)
    a1.plot(q, np.sin(np.radians(q)), "k.-", label="$M_b$")
    a1.axhline(0, color="0.5", lw=0.5)
    a1.annotate("ω_max", (360, 1.0), xytext=(2, 0), textcoords="offset points", fontsize=6, va="center")
    a1.set_ylabel("M, N·m")
    a1.grid(True, lw=0.3, alpha=0.5)
    a2.plot(q, np.where(q > 200, np.nan, q), ".-", ms=3, label="$R_{12}$")
    a2.plot(q, 400 - q, "--", label="dashed")
    a2.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), frameon=False)
    a2.set_xlim(0, 360)
    a2.set_xticks(np.arange(0, 361, 30))
    a2.set_xlabel("φ, deg")
    return fig, a1, a2


def test_chart_is_valid_svg_with_its_content():
    fig, a1, a2 = _chart()
    svg = fig.to_svg()
    assert not problems(svg, "chart")
    for s in (">M, N·m<", ">φ, deg<", ">ω_max<", ">dashed<", ">\u22121.0<"):
        assert s in svg, s
    assert re.search(r'>R</tspan><tspan dy="[0-9.]+" font-size="[0-9.]+">12</tspan>', svg)
    # x tick labels only under the lower axes (shared x): 13 of them (0..360 by 30)
    assert len(re.findall(r'text-anchor="middle">(?:0|30|60|90|120|150|180|210|240|270|300|330|360)</text>', svg)) == 13
    # the axes of one column are aligned, the outside legend and the label beyond 360
    # deg fit in the figure
    assert a1.box[0] == a2.box[0] and a1.box[2] == a2.box[2]
    assert a1.box[0] + a1.box[2] + 7 < 170


def test_chart_maps_data_to_the_box():
    fig, ax = C.subplots(100, 60)
    ax.plot([0, 10], [0, 5])
    ax.set_xlim(0, 10)
    ax.set_ylim(0, 5)
    fig.layout()
    x0, y0, w, h = ax.box
    X, Y = ax.to_mm([0, 10, 5], [0, 5, 2.5])
    assert np.allclose(X, [x0, x0 + w, x0 + w / 2]) and np.allclose(Y, [y0 + h, y0, y0 + h / 2])


def test_equal_aspect_same_units_per_mm():
    fig, ax = C.subplots(120, 150)
    ax.plot([0, 70], [-60, 40])
    ax.set_aspect("equal", adjustable="datalim")
    fig.layout()
    xlo, xhi, ylo, yhi = ax.view
    assert (xhi - xlo) / ax.box[2] == pytest.approx((yhi - ylo) / ax.box[3], rel=1e-12)


# ---------------------------------------------------------------- HTML -> Typst
def test_typst_translation_keeps_every_text_and_figure():
    from tmm_cli.report.typst_pdf import to_typst
    fig, _, _ = _chart()
    html = ("<html><head><title>Т</title><style>p{}</style></head><body><section class='section'>"
            "<h2>Кинематика</h2><p class='note'>v<sub>A</sub> = 1 \"q\" \\ #x</p>"
            "<table class='data'><caption>Таблица</caption><thead><tr><th>a</th><th>b</th></tr></thead>"
            "<tbody><tr><td class='num'>1.5</td><td>текст</td></tr></tbody></table>"
            f"<figure class='fig'>{fig.to_svg()}<figcaption>Рис</figcaption></figure></section></body></html>")
    src, files = to_typst(html, "ru")
    assert len(files) == 1 and next(iter(files.values())).startswith(b"<svg")
    for s in ('#"Кинематика"', '#sub[#"A"]', '#" = 1 \\"q\\" \\\\ #x"', '#"Таблица"', ', "1.5", "текст")',
              '#"Рис"', "table.header(", "align: (right, left,)"):
        assert s in src, s
    assert "p{}" not in src                               # style sheets are not text


def test_typst_pdf_has_the_cyrillic_text():
    pytest.importorskip("typst")
    import shutil
    import subprocess
    from tmm_cli.report.typst_pdf import pdf_bytes
    html = "<html><body><h1>Курсовой проект</h1><p>Привод · ω₁ = 5.24 рад/с</p></body></html>"
    pdf = pdf_bytes(html, "ru")
    assert pdf.startswith(b"%PDF-")
    if shutil.which("pdftotext"):
        out = subprocess.run(["pdftotext", "-", "-"], input=pdf, capture_output=True).stdout.decode()
        assert "Курсовой проект" in out and "ω" in out
