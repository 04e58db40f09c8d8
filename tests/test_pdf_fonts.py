"""Every PDF tmm writes (report.pdf, the drawing sheets, the explanatory note) is typeset with
the DejaVu fonts matplotlib ships and Typst's own, never the system's: the same PDF on every
machine.  A Linux with fonts-dejavu installed had its own DejaVu Sans chosen over matplotlib's
copy (the text and the pages were the same, measured on all 198 report and sheet PDFs of the
examples in three languages; the embedded font file was not)."""
from __future__ import annotations

from pathlib import Path

import typst

import tmm_cli
from tmm_cli.report import typst_pdf

ROOT = Path(__file__).resolve().parents[1]


def _calls(monkeypatch) -> list[dict]:
    seen: list[dict] = []
    real = typst.compile

    def compile(*a, **kw):          # the font files as they are then (a temporary folder of links)
        seen.append({**kw, "files": [f.resolve() for d in kw.get("font_paths", []) for f in Path(d).iterdir()]})
        return real(*a, **kw)
    monkeypatch.setattr(typst, "compile", compile)
    return seen


def test_every_pdf_typeset_with_the_shipped_fonts_only(tmp_path, monkeypatch):
    from tmm_cli.orchestrate import write_outputs
    from tmm_cli.report.note import pdf_bytes as note_pdf
    from tmm_cli.report import render_html
    seen = _calls(monkeypatch)
    task = tmm_cli.load_task(ROOT / "tasks" / "engine_slider_crank.yaml")
    res = tmm_cli.run(task)
    write_outputs(task, res, tmp_path / "o", {"pdf", "sheets"}, "ru")
    html = render_html(res, task, tmp_path / "n", "ru")[0]
    assert note_pdf(html, res, task, "ru")[:5] == b"%PDF-"
    assert len(seen) == 3                                  # the report, the sheets, the note
    for kw in seen:
        assert kw["ignore_system_fonts"] is True
        shipped = Path(typst_pdf._font_dirs()[0]).resolve()          # matplotlib's mpl-data/fonts/ttf
        assert kw["files"] and all(f.parent == shipped for f in kw["files"]), kw["files"]
        assert any(f.name == "DejaVuSans.ttf" for f in kw["files"])


def test_the_systems_fonts_where_matplotlibs_are_not_found(tmp_path, monkeypatch):
    """Without matplotlib's fonts Typst would have only its own (no DejaVu Sans): the system's are
    used then."""
    seen = _calls(monkeypatch)
    (tmp_path / "a.typ").write_text("Text", encoding="utf-8")
    assert typst_pdf.compile_file(tmp_path / "a.typ", [])[:5] == b"%PDF-"
    assert seen[-1]["ignore_system_fonts"] is False
