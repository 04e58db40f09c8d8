"""The documentation site's pictures (docs/gallery/*.png), made from the example tasks, never
pasted: each example's report pages and drawing sheets rendered by pdftoppm.

    python tools/gallery.py            # all pictures (needs the typst package and pdftoppm)

The pages each picture shows are listed in PICTURES; docs/gallery.md and the tutorial use them.
"""
from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "docs" / "gallery"
DPI = 45

# (task, language, what, pages of that PDF, picture name): a page by its number (1-based) or by
# a text on it (the first page whose text holds it), so a picture follows its section
PICTURES = [
    ("engine_slider_crank", "en", "report", ["3.1. Plan of positions", "Position 1, φ = 120.00°\nVelocity plan",
                                              "Position 1, φ = 120.00°\nGroup 1"], "engine"),
    ("engine_slider_crank", "en", "sheets", [1, 2], "engine-sheet"),
    ("forging_sixbar", "ru", "report", ["План положений", "Положение 1, φ"], "forging-ru"),
    ("cam_translating", "en", "report", ["motion law", "profile"], "cam"),
    ("gears_shifted", "uk", "report", ["Зубчаста передача", "Зачеплення"], "gears-uk"),
    ("press_drive_train", "en", "report", ["drive"], "drive-train"),
    ("differential_A", "en", "report", ["Velocity picture"], "differential"),
    ("balancing_fourbar", "en", "report", ["Hodograph"], "balancing"),
]


def page_of(pdf: Path, page) -> int:
    """The page number ``page`` (an int), or the first page whose text holds ``page`` (a str)."""
    if isinstance(page, int):
        return page
    text = subprocess.run(["pdftotext", "-layout", str(pdf), "-"], capture_output=True, text=True, check=True).stdout
    pages = text.split("\f")
    lines = [" ".join(p.split()) for p in pages]
    for k, (raw, flat) in enumerate(zip(pages, lines), start=1):
        if page in raw or " ".join(page.split()) in flat:
            return k
    for k, flat in enumerate(lines, start=1):            # any case
        if " ".join(page.split()).lower() in flat.lower():
            return k
    raise SystemExit(f"gallery: no page of {pdf} holds {page!r}")


def render(task: str, lang: str, what: str, pages: list[int], name: str, work: Path) -> list[Path]:
    out = work / f"{task}-{lang}"
    fmt = "pdf" if what == "report" else "sheets"
    subprocess.run([sys.executable, "-m", "tmm_cli", "run", str(ROOT / "tasks" / f"{task}.yaml"), "--out", str(out),
                    "--format", f"json,{fmt}", "--lang", lang, "--quiet"], check=True, cwd=ROOT)
    pdf = out / "report.pdf" if what == "report" else out / "sheets" / "sheets.pdf"
    made = []
    for k, page in enumerate(pages, start=1):
        page = page_of(pdf, page)
        stem = OUT / f"{name}-{k}"
        subprocess.run(["pdftoppm", "-png", "-r", str(DPI if what == "report" else DPI // 2), "-f", str(page),
                        "-l", str(page), "-singlefile", str(pdf), str(stem)], check=True)
        made.append(stem.with_suffix(".png"))
    return made


def main() -> int:
    if shutil.which("pdftoppm") is None:
        print("gallery: pdftoppm is missing (apt-get install poppler-utils)", file=sys.stderr)
        return 2
    OUT.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        for pic in PICTURES:
            for p in render(*pic, Path(tmp)):
                print(p.relative_to(ROOT))
    return 0


if __name__ == "__main__":
    sys.exit(main())
