"""Report sections 'gears' and 'planetary' render in both languages and show the numbers."""
from pathlib import Path
from types import SimpleNamespace as NS

import pytest

from tmm_cli.gears import analyze, synthesize_planetary


@pytest.mark.parametrize("lang,word", [("en", "Region of (x<sub>1</sub>, x<sub>2</sub>)"),
                                       ("ru", "Область (x<sub>1</sub>, x<sub>2</sub>)")])
def test_sections_render(tmp_path: Path, lang, word):
    from tmm_cli.report import render_html

    g = analyze(NS(m=0.003, z=(12, 42), x=(0.63, 0.67))).to_dict()
    p = synthesize_planetary(NS(scheme="A", ratio=7, satellites=3, tolerance=0.005, m=0.002)).to_dict()
    html, ctx = render_html({"schema": "tmm-results/1", "gears": g, "planetary": p, "warnings": []},
                            None, tmp_path, lang)
    assert word in html and "figure failed" not in html
    assert "84.42" in html                                   # a_w = 84.42 mm (hand value)
    assert "z1 = 18, z2 = 45, z3 = 108" in html
    names = {q.name for q in ctx.written}
    assert {"gears_outline.dxf", "gears_wheel1_outline.csv", "gears_sliding.csv"} <= names


def test_ru_symbols_and_words(tmp_path: Path):
    """In Russian the gear tables name the quantities in words with their course symbols
    (a_w, alpha_w, eps_alpha as subscripts), no raw identifiers are left."""
    from tmm_cli.report import render_html

    g = analyze(NS(m=0.003, z=(12, 42), x=(0.63, 0.67))).to_dict()
    html, _ = render_html({"schema": "tmm-results/1", "gears": g, "warnings": []}, None, tmp_path, "ru")
    for text in ("межосевое расстояние, a<sub>w</sub>, мм", "угол зацепления, α<sub>w</sub>",
                 "коэффициент перекрытия, ε<sub>α</sub>", "радиус основной окружности, r<sub>b</sub>, мм"):
        assert text in html, text
    for raw in ("eps_alpha", "alpha_w", "x_min", "a_w,"):
        assert raw not in html, raw
