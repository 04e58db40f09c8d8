"""Figure labels placed by Typst (typst_pdf._labels): the <text> elements a figure draws last
are taken out of the SVG and placed over the image by Typst (usvg's handling of SVG text was
~30 % of the forging report's compilation). The claims checked here: the page looks the same
as with the labels left in the SVG (both rendered by Typst to PNG and compared pixel by
pixel; a label moved by a fraction of a millimetre is seen), the same text is in the PDF,
and only the labels drawn last, outside groups and of the plain kinds are moved."""
from __future__ import annotations

import io

import pytest

from tmm_cli.report import typst_pdf
from tmm_cli.report.typst_pdf import _labels, to_typst

typst = pytest.importorskip("typst")
np = pytest.importorskip("numpy")
Image = pytest.importorskip("PIL.Image")

# a plan as tmm's svgdraw writes it (user units, DejaVu Sans): lines and circles, then the
# labels: anchors start/middle/end, colours, italics, bold, subscripts (tspans with dy and a
# size), Cyrillic, a character reference and runs of white space
SVG = ('<svg xmlns="http://www.w3.org/2000/svg" class="fig" width="340.2pt" height="170.1pt" '
       'viewBox="0 0 120 60" font-family="DejaVu Sans">\n'
       '<path d="M10 50 L60 10 L110 50" fill="none" stroke="#000000" stroke-width="0.5"/>\n'
       '<circle cx="60" cy="10" r="1" fill="#ffffff" stroke="#000000" stroke-width="0.3"/>\n'
       '<text x="2" y="5" font-size="3.2" font-weight="bold">Группа 2: звенья 4, 5</text>\n'
       '<text x="2" y="9" font-size="2.29">μ<tspan dy="0.69" font-size="1.65">l</tspan>'
       '<tspan dy="-0.69" font-size="2.29"> = 0.025 m/mm</tspan></text>\n'
       '<text x="60" y="7" font-size="2.47" text-anchor="middle" fill="#1f5fbf" font-style="italic">'
       'Φ<tspan dy="0.74" font-size="1.78">4</tspan></text>\n'
       '<text x="110" y="56" font-size="2.47" text-anchor="end">R<tspan dy="0.74" font-size="1.78">'
       '43</tspan></text>\n'
       '<text x="10" y="56" font-size="2.12" fill="#555555">A &amp;  B</text>\n'
       '</svg>')


def _html(svg: str) -> str:
    return (f"<html><head><title>t</title></head><body><section><h2>Plan</h2>"
            f"<figure>{svg}<figcaption>A plan</figcaption></figure></section></body></html>")


def _png(src: str, files: dict[str, bytes], tmp_path, name: str) -> np.ndarray:
    d = tmp_path / name
    d.mkdir()
    for n, data in files.items():
        (d / n).write_bytes(data)
    (d / "r.typ").write_text(src, encoding="utf-8")
    png = typst.compile(str(d / "r.typ"), root=str(d), font_paths=typst_pdf._font_dirs(),
                        format="png", ppi=200)
    png = png[0] if isinstance(png, list) else png
    return np.asarray(Image.open(io.BytesIO(png)).convert("L"), dtype=float)


def _pdf_text(src: str, files: dict[str, bytes], tmp_path, name: str) -> str:
    import shutil
    import subprocess
    if shutil.which("pdftotext") is None:
        pytest.skip("pdftotext not installed")
    d = tmp_path / name
    d.mkdir()
    for n, data in files.items():
        (d / n).write_bytes(data)
    (d / "r.typ").write_text(src, encoding="utf-8")
    (d / "r.pdf").write_bytes(typst.compile(str(d / "r.typ"), root=str(d),
                                            font_paths=typst_pdf._font_dirs(), pdf_tags=False))
    return subprocess.run(["pdftotext", str(d / "r.pdf"), "-"], capture_output=True, text=True,
                          check=True).stdout


def _sources(svg: str, monkeypatch):
    """(Typst source and files with the labels placed by Typst, the same with them left in
    the SVG)."""
    placed = to_typst(_html(svg), "ru")
    with monkeypatch.context() as m:
        m.setattr(typst_pdf, "_labels", lambda s, w: (s, ""))
        kept = to_typst(_html(svg), "ru")
    return placed, kept


def _differ(a: np.ndarray, b: np.ndarray) -> int:
    """Pixels of ``a`` more than a quarter of the grey range outside the range of ``b``'s
    pixels within one pixel of them (sub-pixel placement of glyphs aside, 0.13 mm at 200 ppi)."""
    from scipy.ndimage import maximum_filter, minimum_filter
    assert a.shape == b.shape
    # the least and the greatest of each pixel's 3 x 3 neighbourhood (the edge repeated outside)
    lo, hi = minimum_filter(b, size=3, mode="nearest"), maximum_filter(b, size=3, mode="nearest")
    return int(((lo - a > 64) | (a - hi > 64)).sum())


def test_placed_labels_look_as_svg_text(tmp_path, monkeypatch):
    (src, files), (src0, files0) = _sources(SVG, monkeypatch)
    assert "<text" not in files["fig-000.svg"].decode() and "place(" in src
    assert "<text" in files0["fig-000.svg"].decode() and "place(" not in src0
    a = _png(src, files, tmp_path, "placed")
    b = _png(src0, files0, tmp_path, "kept")
    ink = int((b < 128).sum())
    # the same page: the labels at the same places (to a pixel at 200 ppi)
    assert _differ(a, b) <= 0.001 * ink, (_differ(a, b), ink)
    # ... which a label moved by 0.5 user units (0.5 mm here) would not be, nor an anchor ignored
    for k, wrong in enumerate((SVG.replace('x="60" y="7"', 'x="60.5" y="7"'),
                               SVG.replace('text-anchor="end"', 'text-anchor="start"'))):
        (srcw, filesw), _ = _sources(wrong, monkeypatch)
        assert _differ(_png(srcw, filesw, tmp_path, f"wrong{k}"), b) > 0.004 * ink


def test_placed_labels_keep_the_text(tmp_path, monkeypatch):
    (src, files), (src0, files0) = _sources(SVG, monkeypatch)
    words = sorted(_pdf_text(src, files, tmp_path, "placed").split())
    assert words == sorted(_pdf_text(src0, files0, tmp_path, "kept").split())
    assert {"Группа", "звенья", "Φ4", "R43", "A&B"} <= set(words)   # pdftotext: narrow spaces


def test_only_labels_drawn_last_are_moved():
    head = SVG[:SVG.index("<text")]
    tail = ('<text x="5" y="5" font-size="2">a</text>\n'
            '<path d="M0 0 L1 1"/>\n'                                   # a drawing after it
            '<g clip-path="url(#c)"><text x="6" y="6" font-size="2">b</text></g>\n'  # in a group
            '<text x="7" y="7" font-size="2" transform="rotate(-90 7 7)">c</text>\n'  # turned
            '<text x="8" y="8" font-size="2" text-decoration="underline">d</text>\n'  # not known
            '<text x="9" y="9" font-size="2">e<tspan font-family="Serif">f</tspan></text>\n'
            '<text x="10" y="10" font-size="2" fill="#0000ff">g</text>\n'
            '<text x="11" y="11" font-size="2">   </text>\n'               # no text: dropped
            '</svg>')
    out, calls = _labels(head + tail, 340.2)
    for kept in ">a<", ">b<", ">c<", ">d<", ">e<":
        assert kept in out
    assert ">g<" not in out and 'x="11"' not in out
    assert calls.count("place(") == 1 and '"g"' in calls and 'fill: rgb("#0000ff")' in calls
    # 10 user units at 340.2 pt / 120 units, the size alike
    assert "dx: 28.350pt, dy: 28.350pt" in calls and "size: 5.67pt" in calls


def test_a_figure_not_at_its_width_keeps_its_labels():
    """Wider than the page's text or in a cell (its width not known): drawn scaled, its
    labels stay in the SVG."""
    wide = SVG.replace('width="340.2pt" height="170.1pt"', 'width="600pt" height="300pt"')
    src, files = to_typst(_html(wide), "en")
    assert "place(" not in src and b"<text" in files["fig-000.svg"]
    cell = f"<html><body><table><tr><td>{SVG}</td></tr></table></body></html>"
    src, files = to_typst(cell, "en")
    assert "place(" not in src and b"<text" in files["fig-000.svg"]


def test_labels_of_one_style_share_one_text_call(tmp_path, monkeypatch):
    """The labels of one style are placed inside one text() call (fewer calls for Typst to
    evaluate and lay out), the styles in the order of their first label; the PDF is the same
    bytes as with a text() call in each place()."""
    import re
    svg = SVG.replace("</svg>", '<text x="20" y="56" font-size="2.12" fill="#555555">C</text>\n'
                                '<text x="30" y="56" font-size="2.12" fill="#555555">D</text>\n'
                                '<text x="40" y="56" font-size="2.12">E</text>\n'
                                '<text x="50" y="56" font-size="2.12" fill="#555555">F</text>\n</svg>')
    src, files = to_typst(_html(svg), "en")
    figure = src[src.rindex("#fig("):]
    assert figure.count('fill: rgb("#555555")') == 1 and figure.count("place(") == 9
    assert re.search(r'text\(size: 6\.01pt, fill: rgb\("#555555"\), \{place\([^{}]*"A & B"\); '
                     r'place\([^{}]*"C"\); place\([^{}]*"D"\); place\([^{}]*"F"\)\}\); '
                     r'text\(size: 6\.01pt, \{place\([^{}]*"E"\)\}\)\}\)$', figure.strip()), figure

    def one_each(head, places):           # the form before: each label its own text() call
        out = []
        for p in places:
            m = re.fullmatch(r"(place\(top \+ \w+, dx: \S+, dy: \S+, )(.*)\)", p, re.S)
            out.append(f"{m.group(1)}{head}{m.group(2)}))" if head != "text(" else p)
        return "{" + "; ".join(out) + "}"

    monkeypatch.setattr(typst_pdf, "_styled", one_each)
    src0, files0 = to_typst(_html(svg), "en")
    assert src0 != src and src0[src0.rindex("#fig("):].count("text(size: 6.01pt, fill") == 4

    def pdf(s, fs, name):
        d = tmp_path / name
        d.mkdir()
        for n, data in fs.items():
            (d / n).write_bytes(data)
        (d / "r.typ").write_text(s, encoding="utf-8")
        return typst.compile(str(d / "r.typ"), root=str(d), font_paths=typst_pdf._font_dirs(), pdf_tags=False)

    assert pdf(src, files, "grouped") == pdf(src0, files0, "each")
