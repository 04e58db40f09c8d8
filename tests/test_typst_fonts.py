"""The report's PDF reads only matplotlib's DejaVu fonts (typst_pdf._font_links): Typst
chooses the same fonts as with the whole of matplotlib's font directory, so the PDF is the
same bytes."""
import os
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


def test_system_dejavu_linked_and_system_fonts_left_out(tmp_path):
    """Where the system has DejaVu (here: on this machine), the compilation gets links to the
    DejaVu Sans and Serif files, the system's copies, and does not search the system's fonts:
    the PDF is the same bytes as with the system's fonts searched (Typst chose those copies)
    but for `raw` text (DejaVu Sans Mono: Typst's own copy, not the system's), whose page is
    the same to the pixel at 300 ppi."""
    system = next((d for d in typst_pdf._SYSTEM_DEJAVU if (Path(d) / "DejaVuSans.ttf").is_file()), None)
    if system is None or not typst_pdf._font_dirs():
        pytest.skip("no system DejaVu in the known places, or matplotlib's fonts not found")
    fonts, no_system = typst_pdf._fonts(tmp_path / "fonts")
    assert no_system and fonts == [str(tmp_path / "fonts")]
    links = {p.name: p.resolve() for p in (tmp_path / "fonts").iterdir()}
    assert set(links) <= set(typst_pdf._DEJAVU_USED) and "DejaVuSans.ttf" in links
    assert links["DejaVuSans.ttf"] == (Path(system) / "DejaVuSans.ttf").resolve()
    before = typst_pdf._font_links(tmp_path / "all")

    def out(src: str, fmt: str, **kw):
        (tmp_path / "r.typ").write_text(src, encoding="utf-8")
        return typst.compile(str(tmp_path / "r.typ"), root=str(tmp_path), format=fmt, **kw)

    no_raw = SOURCE.replace('#raw("code 0O1l")\n', "")
    assert no_raw != SOURCE
    assert (out(no_raw, "pdf", font_paths=fonts, ignore_system_fonts=True, pdf_tags=False)
            == out(no_raw, "pdf", font_paths=before, pdf_tags=False))
    assert (out(SOURCE, "png", ppi=300, font_paths=fonts, ignore_system_fonts=True)
            == out(SOURCE, "png", ppi=300, font_paths=before))


def test_system_copies_first_then_matplotlib(tmp_path):
    mpl = typst_pdf._font_dirs()
    if not mpl:
        pytest.skip("matplotlib's fonts not found")
    system = tmp_path / "system"
    system.mkdir()
    (system / "DejaVuSans.ttf").symlink_to(Path(mpl[0]) / "DejaVuSans.ttf")
    (system / "Other.ttf").symlink_to(Path(mpl[0]) / "DejaVuSans.ttf")
    fonts, no_system = typst_pdf._fonts(tmp_path / "fonts", (str(tmp_path / "none"), str(system)))
    assert no_system and fonts == [str(tmp_path / "fonts")]
    links = {p.name: Path(os.readlink(p)) for p in (tmp_path / "fonts").iterdir()}
    assert links["DejaVuSans.ttf"] == system / "DejaVuSans.ttf" and "Other.ttf" not in links
    assert links["DejaVuSans-Bold.ttf"] == Path(mpl[0]) / "DejaVuSans-Bold.ttf"
    assert set(links) == {n for n in typst_pdf._DEJAVU_USED if n == "DejaVuSans.ttf" or (Path(mpl[0]) / n).is_file()}
    # no system copy: the system's fonts searched, matplotlib's DejaVu linked (as before)
    fonts, no_system = typst_pdf._fonts(tmp_path / "fonts2", (str(tmp_path / "none"),))
    assert not no_system and fonts == [str(tmp_path / "fonts2")]
