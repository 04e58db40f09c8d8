"""The report's PDF reads only matplotlib's DejaVu fonts (typst_pdf._font_links): Typst
chooses the same fonts as with the whole of matplotlib's font directory, so the PDF is the
same bytes."""
from pathlib import Path

import pytest

from tmm_cli.report import typst_pdf

typst = pytest.importorskip("typst")

SOURCE = typst_pdf.PREAMBLE.replace("TITLE", '"t"').replace("LANG", '"ru"') + r"""
#par[Plain, #strong[bold], #emph[italic], #strong[#emph[both]], Кириллица ω₁ φ ≈ 1.5 − 2 × 3]
#pad(left: 6mm, text(font: "DejaVu Serif", size: 11pt)[F = m a, #strong[S], #emph[i]])
#raw("code 0O1l")
$display(frac(#[a], #[b])) + sqrt(x^2)$
#table(columns: 2, table.header(table.cell(fill: rgb("#eeeeee"))[#strong[#"Q"]], [#"v"]), "1.25", [#sub[#"x"]])
"""


def _compile(d: Path, fonts: list[str]) -> bytes:
    return typst.compile(str(d / "r.typ"), root=str(d), font_paths=fonts, pdf_tags=False)


def test_links_only_dejavu_and_same_pdf(tmp_path):
    dirs = typst_pdf._font_dirs()
    if not dirs:
        pytest.skip("matplotlib's fonts not found")
    (tmp_path / "r.typ").write_text(SOURCE, encoding="utf-8")
    links = typst_pdf._font_links(tmp_path / "fonts")
    assert links == [str(tmp_path / "fonts")]
    names = sorted(p.name for p in (tmp_path / "fonts").iterdir())
    assert names and all(n.startswith("DejaVu") and n.endswith(".ttf") for n in names)
    assert {"DejaVuSans.ttf", "DejaVuSans-Bold.ttf", "DejaVuSans-Oblique.ttf",
            "DejaVuSans-BoldOblique.ttf", "DejaVuSerif.ttf", "DejaVuSansMono.ttf"} <= set(names)
    assert len(names) < len(list(Path(dirs[0]).glob("*.ttf")))
    assert _compile(tmp_path, links) == _compile(tmp_path, dirs)


def test_links_fall_back_to_the_directory(tmp_path):
    dirs = typst_pdf._font_dirs()
    (tmp_path / "fonts").write_text("not a directory")
    assert typst_pdf._font_links(tmp_path / "fonts") == dirs
