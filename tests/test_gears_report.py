"""Report sections 'gears' and 'planetary' render in both languages and show the numbers."""
from pathlib import Path

import pytest

from tmm_cli.gears import analyze, synthesize_planetary
from task_sections import gears, planetary  # noqa: E402  (sections through the task model)


@pytest.mark.parametrize("lang,word", [("en", "Region of (x<sub>1</sub>, x<sub>2</sub>)"),
                                       ("ru", "Область (x<sub>1</sub>, x<sub>2</sub>)")])
def test_sections_render(tmp_path: Path, lang, word):
    from tmm_cli.report import render_html

    g = analyze(gears(m=0.003, z=(12, 42), x=(0.63, 0.67))).to_dict()
    p = synthesize_planetary(planetary(scheme="A", ratio=7, satellites=3, tolerance=0.005, m=0.002)).to_dict()
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

    g = analyze(gears(m=0.003, z=(12, 42), x=(0.63, 0.67))).to_dict()
    html, _ = render_html({"schema": "tmm-results/1", "gears": g, "warnings": []}, None, tmp_path, "ru")
    for text in ("межосевое расстояние, a<sub>w</sub>, мм", "угол зацепления, α<sub>w</sub>",
                 "коэффициент перекрытия, ε<sub>α</sub>", "радиус основной окружности, r<sub>b</sub>, мм"):
        assert text in html, text
    for raw in ("eps_alpha", "alpha_w", "x_min", "a_w,"):
        assert raw not in html, raw


def test_mesh_labels_do_not_overlap_and_contour_styles_distinct():
    """B1 lies close to N1 on a shifted pinion (z = 12): the label boxes of N1, N2, B1, B2 and P
    must not intersect; every check of the blocking contour has its own colour and line style."""
    from tmm_cli.report.sections import gears as sec

    for z, x in (((12, 42), (0.63, 0.67)), ((14, 30), (0.0, 0.0)), ((17, 17), (0.0, 0.0)), ((10, 60), (0.5, 0.2))):
        g = analyze(gears(m=0.003, z=z, x=x)).to_dict()
        pts = sec.line_points(g)
        la = g["line_of_action"]
        # the points lie on the line at the (signed) distances reported from N1
        u = (pts["N2"] - pts["N1"]) / la["N1N2"]
        for name in ("N2", "B1", "B2", "P"):
            v = pts[name] - pts["N1"]
            assert float(v @ u) == pytest.approx(la["N1" + name], abs=1e-12)
            assert abs(float(v[0] * u[1] - v[1] * u[0])) < 1e-12
        boxes = sec.label_boxes(g, pts, 4.0 * g["m"] * 3)
        for i, (_, _, a) in enumerate(boxes):
            for _, _, b in boxes[i + 1:]:
                assert not (a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3])
        # the arc of action on the rolling circle: its length rw * angle = B1B2 * rw / rb
        for i in (0, 1):
            t0, t1 = sec.action_arc(g, i)
            assert (t1 - t0) * g["rb"][i] == pytest.approx(la["B1B2"])
        names = list(g["blocking_contour"]["lines"])
        st = sec.contour_styles(names)
        assert len({c for c, _ in st.values()}) == len(names)
        assert len({str(ls) for _, ls in st.values()}) == len(names)
