"""What a PDF page shows outside its body: the words (poppler's ``pdftotext -bbox``) and
the ink (the page rendered by ``pdftoppm``, read with Pillow) in the margins of the
report's A4 pages, the page number in the footer excepted.  Used by the tests that
nothing of a report leaves the page body."""
from __future__ import annotations

import html
import re
import shutil
import subprocess
import tempfile
from pathlib import Path

MM = 72 / 25.4
# the report's page (A4) and margins, pt: typst_pdf's PREAMBLE
PAGE_W, PAGE_H = 595.28, 841.89
BODY = (18 * MM, 15 * MM, PAGE_W - 14 * MM, PAGE_H - 16 * MM)     # x0, y0, x1, y1 (from the top)
# what a glyph may reach past the body's edge: Typst aligns the first line's cap height
# (not its tallest glyph, a display fraction's numerator) with the top of the body
SLACK = 1.5 * MM

_WORD = re.compile(r'<word xMin="([\d.]+)" yMin="([\d.]+)" xMax="([\d.]+)" yMax="([\d.]+)">(.*?)</word>')
_PAGE = re.compile(r"<page [^>]*>(.*?)</page>", re.S)


def have_poppler() -> bool:
    return bool(shutil.which("pdftotext") and shutil.which("pdftoppm"))


def words(pdf: Path) -> list[list[tuple[float, float, float, float, str]]]:
    """Per page its words with their boxes, pt from the top left."""
    out = subprocess.run(["pdftotext", "-bbox", str(pdf), "-"], capture_output=True, text=True,
                         check=True).stdout
    return [[(float(a), float(b), float(c), float(d), html.unescape(w)) for a, b, c, d, w in _WORD.findall(p)]
            for p in _PAGE.findall(out)]


def footer_boxes(page_words) -> list[tuple[float, float, float, float]]:
    """The footer line in the bottom margin (the only thing the margin holds): the page number
    "n / N" and, level with it on the last page, the colophon "Computed by tmm · date"."""
    low = [w for w in page_words if w[1] > BODY[3]]
    num = [w for w in low if re.fullmatch(r"\d+|/", w[4])]
    return [w[:4] for w in low if num and abs(w[1] - num[0][1]) < 1.0]


def stray_words(page_words) -> list[tuple]:
    """Words of a page not wholly inside the body (the page number excepted); also any
    word of the body that overlaps the page number."""
    foot = footer_boxes(page_words)
    bad = []
    for w in page_words:
        x0, y0, x1, y1, s = w
        if w[:4] in foot:
            continue
        inside = (x0 >= BODY[0] - SLACK and y0 >= BODY[1] - SLACK and x1 <= BODY[2] + SLACK
                  and y1 <= BODY[3] + SLACK)
        if not inside:
            bad.append(w)
    return bad


def raster(pdf: Path, dpi: int = 36) -> list:
    """Each page of ``pdf`` rendered in grey by pdftoppm at ``dpi``: a uint8 array per page."""
    import numpy as np
    from PIL import Image
    with tempfile.TemporaryDirectory() as tmp:
        subprocess.run(["pdftoppm", "-gray", "-r", str(dpi), str(pdf), f"{tmp}/p"], check=True)
        files = sorted(Path(tmp).glob("p-*.pgm"), key=lambda p: int(p.stem.split("-")[-1]))
        return [np.asarray(Image.open(f), dtype=np.uint8) for f in files]


def stray_ink(pdf: Path, page_words, dpi: int = 36, images: list | None = None) -> list[tuple[int, str, int]]:
    """[(page, margin, dark pixels)] for each page whose margins hold ink other than the
    page number (rendered in grey at ``dpi``, or ``images`` as :func:`raster` gives them; a
    pixel darker than 240 of 255 counts)."""
    found = []
    for k, im in enumerate(raster(pdf, dpi) if images is None else images):
        h, w = im.shape
        sx, sy = w / PAGE_W, h / PAGE_H
        ink = im < 240
        # the page number's box (and a pixel round it) is allowed
        for x0, y0, x1, y1 in footer_boxes(page_words[k] if k < len(page_words) else []):
            ink[max(0, int(y0 * sy) - 1):int(y1 * sy) + 2, max(0, int(x0 * sx) - 1):int(x1 * sx) + 2] = False
        # SLACK and a pixel (antialiasing) round the body's edges
        bx0, by0 = int((BODY[0] - SLACK) * sx) - 1, int((BODY[1] - SLACK) * sy) - 1
        bx1, by1 = int((BODY[2] + SLACK) * sx) + 2, int((BODY[3] + SLACK) * sy) + 2
        for name, part in (("top", ink[:by0, :]), ("bottom", ink[by1:, :]),
                           ("left", ink[:, :bx0]), ("right", ink[:, bx1:])):
            n = int(part.sum())
            if n:
                found.append((k + 1, name, n))
    return found


def results(shared_once, name: str):
    """(task, results) of tasks/<name>.yaml as `tmm run --format html,pdf` computes them (the
    synthesised task where the file asks a synthesis), once per test session: the three
    languages' reports are made from one run."""
    import pickle

    def build(d: Path) -> None:
        from tmm_cli.orchestrate import process
        from tmm_cli.results import listed
        task, res, _ = process(Path(__file__).resolve().parents[1] / "tasks" / f"{name}.yaml", None, {"html", "pdf"},
                               "en")
        (d / "run.pickle").write_bytes(pickle.dumps((task, listed(res))))
    return pickle.loads((shared_once(f"pdfrun-{name}", build) / "run.pickle").read_bytes())


def report_out(shared_once, name: str, lang: str) -> Path:
    """The folder `tmm run --format html,pdf --lang <lang>` writes for tasks/<name>.yaml
    (report.pdf, report.html, its figures/ and CSV tables), once per test session, shared by
    the tests that read them (the report's sections built once for both formats), and
    ``results-unchanged`` ("True": the results' pickled bytes the same after the report was
    made from them as before: the report never localises them), and ``recorded.pickle``: what its
    figures drew, recorded as they were drawn (:func:`recorded`)."""
    def build(d: Path) -> None:
        import pickle

        import pytest
        from figure_record import ForceRecorder, record_placements, record_texts
        from tmm_cli.orchestrate import write_outputs
        task, res = results(shared_once, name)
        # the results' bytes as pickle writes them (every value, type and order; json.dumps with
        # sorted keys took 74 ms a dump of the forging machine's, 13 ms this way)
        before = pickle.dumps(res, protocol=5)
        with pytest.MonkeyPatch.context() as mp:
            mp.setenv("TMM_REPORT_JOBS", "1")          # every figure drawn in this process: recorded
            forces = ForceRecorder(mp)
            texts = record_texts(mp)
            # the placements are compared with the reference in English (test_label_placement)
            places = record_placements(mp) if lang == "en" else None
            write_outputs(task, res, d, {"html", "pdf"}, lang)
        (d / "results-unchanged").write_text(str(pickle.dumps(res, protocol=5) == before))
        (d / "recorded.pickle").write_bytes(pickle.dumps({"texts": texts, "panels": forces.panels,
                                                         "placements": places}))
    return shared_once(f"out-{name}-{lang}", build)


def recorded(shared_once, name: str, lang: str) -> dict:
    """What the figures of :func:`report_out`'s report drew (tests/figure_record.py):
    ``texts`` [(kind, width, height, [(text, box)])] of every figure, ``panels`` the force
    drawings' arrows, lines and names, ``placements`` every call of figures.place_labels
    (English only; None in ru and uk)."""
    import pickle
    return pickle.loads((report_out(shared_once, name, lang) / "recorded.pickle").read_bytes())


def report_pdf(shared_once, name: str, lang: str) -> Path:
    """report.pdf of tasks/<name>.yaml in ``lang`` (:func:`report_out`)."""
    return report_out(shared_once, name, lang) / "report.pdf"


def measured(shared_once, name: str, lang: str) -> tuple[Path, list, list]:
    """(report.pdf, its words per page, its pages in grey at 36 dpi) of tasks/<name>.yaml in
    ``lang`` (:func:`report_pdf`), read by poppler once per test session and shared by the
    tests that measure the pages (what leaves the body, half-empty pages)."""
    import pickle
    pdf = report_pdf(shared_once, name, lang)

    def build(d: Path) -> None:
        (d / "pages.pickle").write_bytes(pickle.dumps((words(pdf), raster(pdf))))
    page_words, images = pickle.loads((shared_once(f"measured-{name}-{lang}", build) / "pages.pickle").read_bytes())
    return pdf, page_words, images
