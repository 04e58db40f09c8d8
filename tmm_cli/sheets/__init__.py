"""The drawing sheets of the course project (A1, GOST 2.301/2.104/2.302) as SVG, PDF and
DXF: `tmm sheets TASK` (README, *Drawing sheets*).  A sheet is one list of primitives in
mm (tmm_cli.sheets.prims) written two ways (tmm_cli.sheets.writers)."""
from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from .. import locales, numfmt

if TYPE_CHECKING:
    from ..task import Task

SHEETS = locales.table("sheets", "titles")


def build_sheets(results: dict, task: Task | None, lang: str = "en") -> list[tuple]:
    """[(PrimCanvas, info)] for each sheet whose section the results have."""
    from ..results import listed
    results = listed(results)        # the entries as lists: read many times
    from . import sheet1, sheet2, sheet3, sheet4, sheet5, sheet6, sheet7, sheet8, sheet9
    from .frame import SHEET_H, SHEET_W, draw_frame
    from .prims import PrimCanvas
    makers = []
    if results.get("kinematics") and results.get("structure"):
        makers.append((1, sheet1.build))
    if results.get("kinetostatics_info") and results.get("kinematics") and sheet2.positions(results):
        makers.append((2, sheet2.build))
    if (results.get("flywheel") or {}).get("arrays"):
        makers.append((3, sheet3.build))
    if (results.get("cam") or {}).get("working_profile"):
        makers.append((4, sheet4.build))
    if (results.get("gears") or {}).get("line_of_action"):
        makers.append((5, sheet5.build))
    if (results.get("planetary") or {}).get("velocity_plan"):
        makers.append((6, sheet6.build))
    if (results.get("differential") or {}).get("velocity_plan"):
        makers.append((7, sheet7.build))
    if (results.get("drive_train") or {}).get("velocity_plan"):
        makers.append((9, sheet9.build))
    bal = results.get("balancing") or {}
    if bal.get("rotor") or (bal.get("shaking") and results.get("kinematics")):
        makers.append((8, sheet8.build))
    out = []
    student, group = task.who if task is not None else ("", "")
    meta = results.get("task") or {}
    course = task.course if task is not None else None
    supervisor, designation, university = ((course.supervisor, course.designation, course.university)
                                           if course is not None else (None, None, None))
    for n, (num, make) in enumerate(makers, start=1):
        cv = PrimCanvas(SHEET_W, SHEET_H)
        with numfmt.language(lang):          # the numbers as the sheet's language writes them
            info = make(cv, results, task, lang)
            info["title_block"] = draw_frame(cv, title=meta.get("title") or (task.title if task is not None else ""),
                                             sheet_title=SHEETS[lang][num], variant=meta.get("variant", ""),
                                             student=student, group=str(group), n=n, total=len(makers),
                                             scale=info.get("scale", ""), lang=lang,
                                             supervisor=supervisor or "", designation=designation or "",
                                             university=university or "")
        info["number"] = num
        out.append((cv, info))
    return out


def write_sheets(sheets: list[tuple], out: Path, formats: set[str]) -> list[Path]:
    """sheet-<n>.svg / sheet-<n>.dxf per sheet (n: its number in the title block) and sheets.pdf (all pages), atomically."""
    from ..io import atomic_write
    from .frame import SHEET_H, SHEET_W
    from .writers import to_dxf, to_pdf, to_svg
    out = Path(out)
    written = []
    svgs = [to_svg(cv) for cv, _ in sheets]
    for n, ((cv, info), svg) in enumerate(zip(sheets, svgs), start=1):
        if "svg" in formats:
            written.append(atomic_write(out / f"sheet-{n}.svg", svg))
        if "dxf" in formats:
            written.append(atomic_write(out / f"sheet-{n}.dxf", to_dxf(cv)))
    if "pdf" in formats and svgs:
        written.append(atomic_write(out / "sheets.pdf", to_pdf(svgs, SHEET_W, SHEET_H)))
    return written
