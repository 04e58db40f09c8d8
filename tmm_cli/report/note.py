"""The explanatory note (poyasnitel'naya zapiska): the report's content laid out as the text
document a student hands in (GOST 2.105, 2.106): an A4 title page from the task's header
(``student``, ``course``), then pages in the ESKD frame (20 mm from the left edge, 5 mm from
the others; GOST 2.104) with the title block of form 2 on the first page of the text (the
contents) and of form 2a on the rest, each with the designation and the page number; an
introduction, the report's sections with numbered figures and tables, conclusions made from
the results, and the references.

One content, two layouts: the sections are the report's HTML, translated to Typst by
:mod:`tmm_cli.report.typst_pdf` exactly as for report.pdf; only the page, the title page,
the captions' numbering and the parts around the sections are the note's own.
"""
from __future__ import annotations

import datetime
import re
from typing import TYPE_CHECKING

from ..numfmt import localize
from . import typst_pdf
from .. import locales

if TYPE_CHECKING:
    from ..task import Task

WORDS = locales.table("note", "text")


# the page: the frame 20 mm from the left edge, 5 mm from the others; the text 5 mm inside it,
# clear of the title block (form 2: 40 mm, on the contents page; form 2a: 15 mm, on the rest)
FRAME = {"left": 20.0, "top": 5.0, "right": 5.0, "bottom": 5.0}
FORM2, FORM2A = 40.0, 15.0


def _q(text) -> str:
    """A Typst string literal."""
    return '"' + str(text).replace("\\", "\\\\").replace('"', '\\"') + '"'


def _arr(items) -> str:
    """A Typst array of strings."""
    return "(" + ", ".join(_q(x) for x in items) + ",)"


def _pct(share, lang: str) -> str:
    """A ratio's deviation in per cent, 3 digits; a round-off one (|share| < 1e-9) is 0 %
    (it read -1.23e-14 %)."""
    v = float(share or 0.0)
    return localize(f"{100 * v:.3g} %" if abs(v) >= 1e-9 else "0 %", lang)


def _num(x, lang: str, digits: int = 4) -> str:
    if x is None:
        return "—"
    return localize(f"{float(x):.{digits}g}", lang)      # ru, uk: 0,25 and 8,9·10⁻¹⁶


def conclusions(results: dict, lang: str) -> list[str]:
    """Facts of the results, one sentence each, in the language (numbers from the results only)."""
    W = WORDS[lang]
    out = []
    st = results.get("structure")
    if st:
        out.append(W["c_structure"].format(W=st.get("W"), formula=str(st.get("formula")).replace("->", "\u2192")))
    pos = results.get("positions") or {}
    syn = results.get("synthesis") or {}
    if pos.get("over") == "input_range" and syn.get("structural_error"):
        se = syn["structural_error"]
        out.append(W["c_range"].format(start=_num(pos["phi0"], lang), end=_num(pos["phi0"] + pos["span"], lang),
                                       err=_num(se["max"], lang), x=_num(se["at_x"], lang)))
    if pos.get("K") is not None and pos.get("working_stroke_angle") is not None:
        out.append(W["c_K"].format(K=_num(pos["K"], lang), ws=_num(pos["working_stroke_angle"], lang)))
    ks = results.get("kinetostatics") or []
    mb = [e.get("balancing_moment") for e in ks if e.get("balancing_moment") is not None]
    if mb:
        top = max(abs(m) for m in mb)
        diff = max((abs(e["balancing_moment"] - e["zhukovsky_moment"]) for e in ks
                    if e.get("balancing_moment") is not None and e.get("zhukovsky_moment") is not None), default=0.0)
        share = f"{100 * diff / top:.2g} %" if top > 0 else "0 %"
        out.append(W["c_mb"].format(diff=localize(share, lang),
                                    mb=_num(top, lang)))
    fw = results.get("flywheel")
    if fw and fw.get("J") is not None:
        out.append(W["c_fly"].format(J=_num(fw["J"], lang), delta=_num(fw.get("delta"), lang)))
    cam = results.get("cam")
    if cam and cam.get("r0") is not None:
        out.append(W["c_cam"].format(r0=_num(1e3 * cam["r0"], lang), pa=_num(cam.get("max_pressure_angle"), lang)))
    g = results.get("gears")
    if g and g.get("aw") is not None:
        out.append(W["c_gears"].format(aw=_num(1e3 * g["aw"], lang), eps=_num(g.get("eps_alpha"), lang)))
    pl = results.get("planetary")
    if pl and pl.get("ratio") is not None:
        out.append(W["c_plan"].format(s=pl.get("scheme"), z=", ".join(str(v) for v in (pl.get("z") or {}).values()),
                                      i=_num(pl["ratio"], lang, 6), err=_pct(pl.get("ratio_error"), lang)))
    dt = results.get("drive_train")
    if dt and dt.get("ratio") is not None:
        from ..numfmt import list_sep
        power = (W["c_train_power"].format(P=_num(dt["motor_power"], lang))
                 if dt.get("motor_power_computed") and dt.get("motor_power") is not None else "")
        out.append(W["c_train"].format(stages=list_sep(lang).join("/".join(str(v) for v in st["z"]) for st in dt["stages"]),
                                       U=_num(dt["ratio"], lang, 6), err=_pct(dt.get("ratio_error"), lang), power=power))
    df = results.get("differential")
    if df:
        out.append(W["c_diff"].format(nH=_num(df["speeds_rpm"]["H"], lang), loss=_num(df.get("power_loss") or 0, lang)))
    bal = results.get("balancing")
    if bal and bal.get("max"):
        after = W["c_bal_after"].format(Fb=_num(bal["max"]["F_balanced"], lang)) if "F_balanced" in bal["max"] else ""
        out.append(W["c_bal"].format(F=_num(bal["max"]["F"], lang), after=after))
    return out


def _books(W: dict, results: dict) -> list[str]:
    """The references a note cites: the catalogue's `bibliography`, and its `bibliography_gears`
    (the gear standard) only where gears are designed (a linkage's note listed it uncited). Each
    as written ('[and others]' in its brackets, GOST 7.1: a Typst string, not content, keeps them)."""
    gears = any(results.get(k) for k in ("gears", "planetary", "drive_train", "differential"))
    return list(W["bibliography"]) + (list(W.get("bibliography_gears") or []) if gears else [])


def _parts(results: dict, lang: str) -> str:
    names = WORDS[lang]["parts"]
    order = ("synthesis", "structure", "kinematics", "kinetostatics", "flywheel", "balancing", "cam", "gears",
             "planetary", "drive_train", "differential", "dof2")
    return ", ".join(names[k] for k in order if results.get(k))


def _header(task: Task | None) -> dict:
    """The title page's fields: the task's ``student`` and ``course`` (each may be absent)."""
    co = task.course if task is not None else None
    if co is None:
        university = department = supervisor = city = designation = year = None
    else:
        university, department, supervisor, city, designation, year = (
            co.university, co.department, co.supervisor, co.city, co.designation, co.year)
    return {"title": (task.title if task is not None else "") or "",
            "variant": task.variant if task is not None else None,
            "student": task.who[0] if task is not None else "",
            "group": task.who[1] if task is not None else "",
            "university": university or "", "department": department or "",
            "supervisor": supervisor or "", "city": city or "",
            "year": year or datetime.date.today().year, "designation": designation or ""}


def _signer(name: str) -> str:
    """A signing row's name cell of form 2 (23 mm, 6 pt): the name as given where it fits on one
    line in type down to 5.1 pt, else the surname and initials, else the surname
    (drawings.titleblock), smaller still only where a surname is longer than the cell (a long
    name wrapped over the row below)."""
    from ..drawings.titleblock import signer_name
    shown, k = signer_name(name, 0.6 * 6 * 25.4 / 72, 21.0, 0.85)
    return f"cell({_q(shown)}, size: {6 * k:.4g}pt)"


def _preamble(h: dict, lang: str) -> str:
    W = WORDS[lang]
    ch, roles = W["changes"], W["roles"]
    fr = FRAME
    return rf"""
#set document(title: {_q(h['title'])}, date: none)
#let designation = {_q(h['designation'])}
#let cell(x, size: 7pt) = align(center + horizon, text(size: size, x))
#let small = (7mm, 10mm, 23mm, 15mm, 10mm)
#let form2a(pn) = table(columns: (..small, 110mm, 10mm), rows: (5mm, 5mm, 5mm), stroke: 0.5pt, inset: 0pt,
  [], [], [], [], [], table.cell(rowspan: 3, cell(designation, size: 14pt)), cell({_q(W['sheet'])}),
  [], [], [], [], [], table.cell(rowspan: 2, cell(str(pn), size: 10pt)),
  ..{_arr(ch)}.map(c => cell(c, size: 6pt)))
#let form2(pn, total) = table(columns: (..small, 70mm, 15mm, 15mm, 20mm),
  rows: (5mm,) * 8, stroke: 0.5pt, inset: 0pt,
  [], [], [], [], [], table.cell(colspan: 4, rowspan: 3, cell(designation, size: 14pt)),
  [], [], [], [], [],
  ..{_arr(ch)}.map(c => cell(c, size: 6pt)),
  table.cell(colspan: 2, cell({_q(roles[0])}, size: 6pt)), {_signer(h['student'])}, [], [],
  table.cell(rowspan: 5, cell({_q(h['title'])}, size: 9pt)), cell({_q(W['lit'])}, size: 6pt),
  cell({_q(W['sheet'])}, size: 6pt), cell({_q(W['sheets'])}, size: 6pt),
  table.cell(colspan: 2, cell({_q(roles[1])}, size: 6pt)), {_signer(h['supervisor'])}, [], [],
  [], cell(str(pn), size: 8pt), cell(str(total), size: 8pt),
  table.cell(colspan: 2, cell({_q(roles[2])}, size: 6pt)), [], [], [],
  table.cell(colspan: 3, rowspan: 3, cell({_q(h['university'] or h['group'])}, size: 7pt)),
  table.cell(colspan: 2, cell({_q(roles[3])}, size: 6pt)), [], [], [],
  table.cell(colspan: 2, cell({_q(roles[4])}, size: 6pt)), [], [], [])
#let frame = context {{
  // the sheets counted as they lie (the title page is sheet 1), not by a counter a page run may reset
  let pn = here().page()
  let total = locate(<note-end>).page()
  place(top + left, dx: {fr['left']}mm, dy: {fr['top']}mm,
    rect(width: {210 - fr['left'] - fr['right']}mm, height: {297 - fr['top'] - fr['bottom']}mm, stroke: 0.7pt))
  if pn == 2 {{
    place(bottom + left, dx: {fr['left']}mm, dy: -{fr['bottom']}mm, form2(pn, total))
  }} else {{
    place(bottom + left, dx: {fr['left']}mm, dy: -{fr['bottom']}mm, form2a(pn))
  }}
}}
#let textmargin(block) = (left: {fr['left'] + 5}mm, right: {fr['right'] + 5}mm, top: {fr['top'] + 5}mm,
  bottom: {fr['bottom']}mm + block + 4mm)
"""


def _title_page(h: dict, lang: str) -> str:
    W = WORDS[lang]
    who = h["student"] + (f", {W['group']} {h['group']}" if h["group"] else "")
    sup = f"{W['supervisor']}: {h['supervisor']}" if h["supervisor"] else ""
    var = W["variant"].format(v=h["variant"]).lstrip(", ") if h["variant"] not in (None, "") else ""
    return rf"""
#page(margin: (left: 30mm, right: 15mm, top: 20mm, bottom: 20mm), foreground: none, footer: none)[
  #set align(center)
  #text(size: 12pt, {_q(h['university'])}) \
  #text(size: 12pt, {_q(h['department'])})
  #v(1fr)
  #text(size: 16pt, weight: "bold", {_q(W['kind'])}) \
  #v(2mm)
  #text(size: 13pt, {_q(W['to'])}) \
  #v(4mm)
  #text(size: 14pt, weight: "bold", {_q('«' + h['title'] + '»')}) \
  #text(size: 12pt, {_q(var)}) \
  #v(2mm)
  #text(size: 12pt, {_q(h['designation'])})
  #v(1fr)
  #align(right, block(width: 90mm, align(left, [
    #text(size: 12pt, {_q(W['student'] + ': ' + who if h['student'] else '')}) \
    #text(size: 12pt, {_q(sup)})
  ])))
  #v(1fr)
  #text(size: 12pt, {_q((h['city'] + ' ' if h['city'] else '') + str(h['year']))})
]
"""


def _strip_head(html: str) -> str:
    """The report's HTML less its own title block and contents (the note has its own), its
    colophon (the report prints it in the bottom margin: on the note's page that is the title
    block's top row), its mentions of the files written beside it and its warnings section."""
    html = re.sub(r'<header class="report-head">.*?</header>', "", html, count=1, flags=re.S)
    html = re.sub(r'<footer class="report-foot">.*?</footer>', "", html, count=1, flags=re.S)
    # the files the run wrote beside the report ('All numbers: kinematics.csv'): a handed-in
    # note has no folder beside it
    html = re.sub(r'<p class="(?:note )?files">.*?</p>\s*', "", html, flags=re.S)
    html = re.sub(r'\s*<span class="files">.*?</span>', "", html, flags=re.S)
    # the program's warnings to its user (the task file's keys, what to write there): the report's,
    # not a text the student hands in
    html = re.sub(r'<section class="section" id="warnings">.*?</section>\s*', "", html, count=1, flags=re.S)
    return re.sub(r'<nav class="toc">.*?</nav>', "", html, count=1, flags=re.S)


_SUB = re.compile(r"(?<=\w)_(\w+)")


def _par(text: str) -> str:
    """A paragraph of the note's own text as Typst markup: a_w, eps_alpha (Greek letters), M_b (any script) with
    their subscripts set as subscripts, the rest as written (Typst strings: nothing read as markup)."""
    out, at = [], 0
    for m in _SUB.finditer(text):
        out.append(typst_pdf._s(text[at:m.start()]) + f"#sub({_q(m.group(1))})")
        at = m.end()
    out.append(typst_pdf._s(text[at:]))
    return "#par[" + "".join(out) + "]"


_FIGURE = re.compile(r"<figure\b[^>]*>.*?</figure>", re.S)
_HEADING = re.compile(r"<h([2-4])\b[^>]*>(.*?)</h\1>", re.S)


def _under_headings(html: str, rx: re.Pattern, caption) -> str:
    """``html`` with ``caption(match, heading)`` -> (position, text) inserted for each match of
    ``rx`` (None: nothing), ``heading`` the text of the last heading before it."""
    out, last, heading = [], 0, None
    marks = sorted([(m.start(), "h", m) for m in _HEADING.finditer(html)]
                   + [(m.start(), "x", m) for m in rx.finditer(html)], key=lambda t: t[0])
    for _, kind, m in marks:
        if kind == "h":
            heading = re.sub(r"<[^>]+>", "", m.group(2)).strip()
            continue
        put = caption(m, heading) if heading else None
        if put is not None:
            out += [html[last:put[0]], put[1]]
            last = put[0]
    out.append(html[last:])
    return "".join(out)


def _caption_bare_figures(html: str) -> str:
    """Every figure of a text document has a caption (GOST 2.105): a figure the report leaves
    without one (a position's drawings under their heading "Position 3, φ = 96.42°", a diagram
    under its subsection's heading) takes the text of the heading it stands under."""
    return _under_headings(html, _FIGURE, lambda m, h: None if "<figcaption" in m.group(0) else
                           (m.end() - len("</figure>"), f"<figcaption>{h}</figcaption>"))


_TABLE = re.compile(r"<table\b[^>]*>(\s*<caption\b)?", re.S)


def _caption_bare_tables(html: str) -> str:
    """Every table of a text document has a title (GOST 2.105, the note numbers it "Table
    4.1 -" in its language): a table the report leaves without a caption (under a heading that
    names it) takes the text of the heading it stands under, as a bare figure does."""
    return _under_headings(html, _TABLE, lambda m, h: None if m.group(1) else (m.end(), f"<caption>{h}</caption>"))


def to_typst(html: str, results: dict, task: Task | None, lang: str = "en") -> tuple[str, dict[str, bytes]]:
    """(Typst source, {file name: bytes}) of the explanatory note."""
    W = WORDS.get(lang, WORDS["en"])
    h = _header(task)
    # the report's body as report.pdf has it; its preamble (fonts, tables, headings) less its page,
    # figure and caption settings, which are the note's own
    root, svgs = typst_pdf._parse(_caption_bare_tables(_caption_bare_figures(_strip_head(html))))
    w = typst_pdf._Writer(svgs, None)
    body, files = w.block(root), w.files
    # the report keeps a position's drawings on one page; the note's text area is shorter (the title
    # block), so there they may flow on to the next page (each drawing itself stays whole)
    body = body.replace("#block(breakable: false)[", "#block[")
    head = _shared_preamble().replace("TITLE", typst_pdf._s(h["title"])[1:]).replace("LANG", f'"{lang}"')
    var = W["variant"].format(v=h["variant"]) if h["variant"] not in (None, "") else ""
    intro = W["intro_text"].format(title=h["title"], variant=var, parts=_parts(results, lang))
    concl = conclusions(results, lang)
    numbering = rf"""
#let figno = counter("note-figure")
#let tabno = counter("note-table")
#let eqno = counter("note-equation")
#show heading.where(level: 1): it => {{ figno.update(0); tabno.update(0); eqno.update(0); it }}
#let wf(x) = {{ eqno.step(); block(above: 0.8em, below: 0.8em, grid(columns: (1fr, auto), column-gutter: 3mm,
  align: (left + horizon, right + horizon), x, context [(#counter(heading).get().first().#eqno.display())])) }}
#let fig(file, w, c, labels: none) = {{
  figno.step()
  block(above: 2mm, below: 3mm, breakable: false, width: 100%, align(center, {{
    // a drawing never taller than the page's text leaves room for (its caption below it)
    layout(size => {{
      let body = if labels == none {{ image(file, width: calc.min(w, size.width)) }} else {{
        block(width: w, {{ image(file, width: w); set text(top-edge: "baseline", bottom-edge: "baseline"); labels }}) }}
      let m = measure(body)
      let k = calc.min(1.0, size.width / m.width, MAXH / m.height)
      if k < 1.0 {{ scale(x: k * 100%, y: k * 100%, reflow: true, body) }} else {{ body }}
    }})
    v(1mm, weak: true)
    text(size: 9pt, context [{W['figure']} #counter(heading).get().first().#figno.display() #if c != none [— #c]])
  }}))
}}
#let cap(x) = {{ tabno.step(); block(below: 1mm, sticky: true,
  context [{W['table']} #counter(heading).get().first().#tabno.display() — #x]) }}
"""
    page = rf"""
#set page(margin: textmargin({FORM2A}mm), foreground: frame, footer: none, header: none)
"""
    numbering = numbering.replace("MAXH", f"{297 - 10 - FORM2A - 4 - 5 - 14}mm")
    contents = rf"""
#page(margin: textmargin({FORM2}mm), foreground: frame, footer: none)[
  #align(center, text(size: 13pt, weight: "bold", {_q(W['contents'])}))
  #outline(title: none, depth: 2)
]
"""
    intro_block = rf"""
#heading(numbering: none, {_q(W['intro'])})
#par({_q(intro)})
"""
    tail = rf"""
#heading(numbering: none, {_q(W['conclusions'])})
{''.join(_par(c) + chr(10) for c in concl)}
#heading(numbering: none, {_q(W['biblio'])})
#enum(numbering: "1.", {', '.join(_q(b) for b in _books(W, results))})
#metadata("end") <note-end>
"""
    out = head + numbering + _title_page(h, lang) + contents + page + intro_block + body + tail
    return out, files


def _shared_preamble() -> str:
    """The parts of the report's preamble the note shares: the document, type, headings, tables,
    the kept blocks and section breaks -- not the report's page, nor its figure, table and
    formula captions (the note sets its own page and numbers its captions)."""
    t = typst_pdf
    return "\n" + t.PREAMBLE_DOC + t.PREAMBLE_STYLE + t.PREAMBLE_KEEP + t.PREAMBLE_BREAK


def pdf_bytes(html: str, results: dict, task: Task | None, lang: str = "en") -> bytes:
    """Compile the explanatory note to PDF bytes."""
    import tempfile
    from pathlib import Path

    src, files = to_typst(html, results, task, lang)
    with tempfile.TemporaryDirectory(prefix="tmm-note-") as tmp:
        d = Path(tmp)
        for name, data in files.items():
            (d / name).write_bytes(data)
        (d / "note.typ").write_text(_preamble(_header(task), lang) + src, encoding="utf-8")
        return typst_pdf.compile_file(d / "note.typ", typst_pdf._font_links(d / "fonts"))
