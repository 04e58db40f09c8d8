"""The report: results.json (+ the task) -> report.html / report.pdf + CSV tables.

``render(results, task, out_dir, formats, lang) -> list[Path]`` renders one
Jinja HTML source (``templates/report.html.j2``) with inline CSS and inline
SVG figures to a self-contained ``report.html`` and, translated to Typst markup
(``typst_pdf``) and compiled in-process by the ``typst`` package, to
``report.pdf``.  The report reads numbers only from ``results``; the task gives
names and the task-data table.

How to add a section (e.g. for the stage ``cam``)
-------------------------------------------------
1. Put the section's words in the catalogues, a file a language
   (``tmm_cli/locales/<lang>/cam.yaml``, table ``words``: ``cam.title: Cam mechanism``),
   and create ``tmm_cli/report/sections/cam.py`` with::

       I18N = locales.table("cam", "words")

       def build(ctx) -> str | None:
           data = ctx.results.get("cam")
           if not data:
               return None                  # section absent -> nothing in the report
           fig, ax = ctx.figures.new_figure(170, 90)   # SVG chart (svgchart), mm size
           ax.plot(...)
           ctx.write_csv("cam.csv", ["phi", "s"], rows)  # beside the report
           return ctx.render("sections/cam.html.j2", data=data,
                             fig_profile=ctx.svg(fig))

2. Create ``templates/sections/cam.html.j2``; start it with
   ``<section class="section" id="cam"><h2>{{ t('cam.title') }}</h2>`` and
   close ``</section>``; ``{% from "macros.html.j2" import table, figure %}``
   gives ``table(header, rows)`` and ``figure(svg, caption)``.  Inside
   templates: ``t(key)``, ``fmt(x, digits=4)``, ``fmt_fixed(x, decimals)``,
   ``results``, ``task``, ``lang`` are available.
3. The section names and their order are fixed in ``sections/__init__.py``
   (ORDER); a missing module is skipped.  Headings h2/h3 are numbered by CSS.

``ctx`` (``context.ReportContext``): ``results``, ``task``, ``lang``,
``out_dir``, ``env``, ``t(key, **fmt)``, ``render(template, **kw)``,
``svg(fig)``, ``write_csv(name, header, rows)``, ``write_file(name, data)``,
``fmt``, ``fmt_fixed``, ``sense(omega)`` (cw/ccw in words), ``link_names()``,
``figures`` (helpers: ``new_figure``, ``nice_scale``, ``draw_ground``,
``draw_joint``, ``figure_at_scale``, ``place_labels``, and ``figures.figure_for_box`` +
``figures.draw_mechanism`` for the linkage, drawn directly as SVG).
"""
from __future__ import annotations

import re
from typing import TYPE_CHECKING

from pathlib import Path

from .. import locales, numfmt
from ..messages import render_grouped, unit
from ..reproducible import source_date
from .context import ReportContext, templates_dir
from . import sections as _sections

if TYPE_CHECKING:
    from ..task import Task

__all__ = ["render", "render_html", "make_env", "PdfSkipped"]


# a number as the report writes it: 0.25, 8.9e-16 (en); 0,25, 8,9·10⁻¹⁶ (ru, uk)
_NUM = re.compile(r"^[−+-]?(\d+([.,]\d*)?|[.,]\d+)([eE][−+-]?\d+|·10[⁻⁺]?[⁰¹²³⁴⁵⁶⁷⁸⁹]+)?( [↺↻])?$")


def _is_numeric(value) -> bool:
    """Jinja test: a number or a string that reads as one (right-aligned cells)."""
    if isinstance(value, bool):
        return False
    if isinstance(value, (int, float)):
        return True
    return isinstance(value, str) and bool(_NUM.match(value.strip()))


def _bytecode_cache():
    """Jinja's compiled templates kept between runs like Python's bytecode: in the
    templates' ``__pycache__`` (or under ``PYTHONPYCACHEPREFIX``), keyed by each template's
    source and the Python version; none where bytecode is not written. A folder that
    cannot be written is no cache (the templates are compiled as without one)."""
    import sys
    if sys.dont_write_bytecode:
        return None
    import os
    import jinja2
    from importlib.util import cache_from_source

    class _Cache(jinja2.FileSystemBytecodeCache):
        def load_bytecode(self, bucket):
            try:
                super().load_bytecode(bucket)
            except (OSError, EOFError, ValueError, TypeError):   # an unreadable entry: compiled afresh
                bucket.reset()

        def dump_bytecode(self, bucket):
            try:
                os.makedirs(self.directory, exist_ok=True)
                super().dump_bytecode(bucket)
            except OSError:
                pass

    folder = os.path.dirname(cache_from_source(str(templates_dir() / "report.py")))
    return _Cache(folder, "jinja-%s.cache")


def make_env():
    import jinja2
    from .context import fmt, fmt_fixed
    env = jinja2.Environment(
        loader=jinja2.FileSystemLoader(str(templates_dir())),
        autoescape=jinja2.select_autoescape(["html", "j2", "xml"], default_for_string=True,
                                            default=True),
        trim_blocks=True, lstrip_blocks=True, keep_trailing_newline=True,
        bytecode_cache=_bytecode_cache(),
    )
    env.filters["fmt"] = fmt
    env.filters["fmt_fixed"] = fmt_fixed
    env.tests["numeric"] = _is_numeric
    env.globals["unit"] = unit                  # a task-file unit in the report's language
    return env


_SHARED_ENV = None


def shared_env():
    """One environment per process, so its templates are compiled once for every report the
    process renders (without a bytecode cache -- PYTHONDONTWRITEBYTECODE -- each report compiled
    them all again). A batch compiles them before it forks its workers (:func:`warm_templates`)."""
    global _SHARED_ENV
    if _SHARED_ENV is None:
        _SHARED_ENV = make_env()
    return _SHARED_ENV


def warm_templates() -> None:
    """Compile every template into the shared environment (the forked workers inherit them)."""
    env = shared_env()
    root = templates_dir()
    for p in sorted(root.rglob("*.j2")):
        env.get_template(p.relative_to(root).as_posix())


def _context(results: dict, task: Task | None, out_dir: Path, lang: str) -> ReportContext:
    """The sections' context; the results' per-position entries as lists (the sections
    read them many times and tell them apart by identity)."""
    from ..results import listed
    results = listed(results)
    return ReportContext(results=results, task=task, lang=lang if lang in locales.LANGS else "en",
                         out_dir=Path(out_dir), env=shared_env())


def _build(ctx: ReportContext, names) -> dict[str, str | None]:
    """HTML fragments of the sections `names` (None for an absent section)."""
    mods = dict(_sections.available())
    return {name: (mods[name].build(ctx) if name in mods else None) for name in names}


def _write_tables(ctx: ReportContext, names) -> None:
    """The per-position tables of the sections `names` (HELPER_TABLES) written."""
    mods = dict(_sections.available())
    for name in names:
        if name in mods:
            mods[name].write_table(ctx)


def _assemble(ctx: ReportContext, frags: dict[str, str | None]) -> str:
    from markupsafe import Markup
    from . import failure
    boxes: dict[str | None, list[str]] = {}
    for err in failure.failures(ctx.results):
        boxes.setdefault(failure.placement(err)[0], []).append(failure.box(ctx, err))
    parts = []
    for name, _ in _sections.available():
        frag = frags.get(name)
        # a failed stage: in its section's place, what failed, where and what to change
        extra = boxes.pop(name, []) + (boxes.pop(None, []) if name == "task" else [])
        if extra:
            frag = "\n".join(([frag] if frag else []) + extra)
        if frag:
            m = _H2.search(frag)
            head = re.sub(r"<[^>]+>", "", m.group(1)).strip() if m else ctx.t(f"{name}.title")
            parts.append({"name": name, "html": Markup(frag), "title": Markup(head)})
    css_path = templates_dir() / "base.css"
    css = css_path.read_text(encoding="utf-8") if css_path.exists() else ""
    task = ctx.task
    return ctx.render("report.html.j2", sections=parts, css=Markup(css),
                      title=(task.title if task is not None else None) or ctx.t("report.title"),
                      variant=task.variant if task is not None else None,
                      warnings=render_grouped(ctx.results, ctx.lang),
                      date=source_date().date().isoformat())


def render_html(results: dict, task: Task | None, out_dir: Path, lang: str = "en") -> tuple[str, ReportContext]:
    """Build the HTML text (sections may write CSV files into out_dir)."""
    with numfmt.language(lang):
        ctx = _context(results, task, out_dir, lang)
        frags = _build(ctx, [name for name, _ in _sections.available()])
        return _assemble(ctx, frags), ctx


_H2 = re.compile(r"<h2\b[^>]*>(.*?)</h2>", re.S)


class PdfSkipped(Exception):
    """The PDF engine (the typst package) cannot run on this machine: everything else
    is still written."""


def _typst_ready() -> None:
    """PdfSkipped naming the reason when the PDF engine (the typst package) cannot be loaded."""
    try:
        import typst  # noqa: F401
    except (ImportError, OSError) as exc:
        first = (str(exc).strip().splitlines() or [type(exc).__name__])[0]
        raise PdfSkipped(f"the PDF engine (typst) is not installed: {first}; "
                         "install it with: pip install typst") from None


def _pdf_bytes(html: str, lang: str = "en") -> bytes:
    """report.pdf from the report's HTML, compiled by Typst (see typst_pdf)."""
    from . import typst_pdf
    _typst_ready()
    return typst_pdf.pdf_bytes(html, lang)


# sections the helper process builds while the main process builds the others (and then
# the helper compiles the PDF): the kinetostatics takes about as long as all the others
# together (the dynamics section, results key "flywheel", stays in the main process: with
# it the helper would be the longer by more)
HELPER_SECTIONS = ("kinetostatics",)
# sections built by the main process whose per-position table (the module's write_table)
# the helper writes meanwhile: at a fine grid kinematics.csv is a fifth of the report's
# time, and the main process (all the other sections) is the longer one
HELPER_TABLES = ("kinematics",)


PR_SET_PDEATHSIG = 1  # <linux/prctl.h>


def _die_with_parent(parent_pid: int, parent_end) -> None:
    """In the forked helper: end when the main process ends, however it ends (killed by a
    scheduler, by a timeout, by the out-of-memory killer). On Linux the kernel sends the
    helper SIGKILL when its parent dies (prctl PR_SET_PDEATHSIG); everywhere the helper
    drops its inherited copy of the main process' end of the pipe (so the pipe reports
    EOF once the main process is gone) and _recv_from checks the parent while it waits."""
    import os
    import signal
    import sys
    if sys.platform.startswith("linux"):
        try:
            import ctypes
            libc = ctypes.CDLL(None, use_errno=True)
            libc.prctl(PR_SET_PDEATHSIG, int(signal.SIGKILL), 0, 0, 0)
        except (OSError, AttributeError):
            pass
    try:
        parent_end.close()
    except OSError:
        pass
    if os.getppid() != parent_pid:  # the parent died before the request took effect
        os._exit(0)


def _recv_from(conn, parent_pid: int, poll: float = 0.5):
    """conn.recv(), but the helper exits as soon as its parent is gone."""
    import os
    while not conn.poll(poll):
        if os.getppid() != parent_pid:
            os._exit(0)
    return conn.recv()


def _helper(conn, results, task, out_dir, lang, names, pdf, parent_pid=None, parent_end=None, tables=()):
    """The second process: build `names` and write the tables of `tables`, send
    (fragments, written paths), then receive the whole HTML and send the PDF bytes
    (compiled while the main process writes report.html and the figure files)."""
    if parent_pid is not None:
        _die_with_parent(parent_pid, parent_end)
    numfmt.language(lang).__enter__()     # this process's numbers: the report's language
    try:
        ctx = _context(results, task, out_dir, lang)
        frags = _build(ctx, names)
        _write_tables(ctx, tables)
        conn.send(("frags", frags, [str(p) for p in ctx.written]))
        if pdf:
            msg = _recv_from(conn, parent_pid) if parent_pid is not None else conn.recv()
            if msg is not None:
                conn.send(("pdf", _pdf_bytes(msg, lang)))
    except BaseException as exc:  # noqa: BLE001 - reported to the main process, which then works alone
        try:
            conn.send(("error", f"{type(exc).__name__}: {exc}"))
        except (OSError, ValueError):     # the pipe is gone: the main process works alone
            pass
    finally:
        conn.close()


def _finish(ctx, proc, conn, formats, all_names, helper_names, out_dir, notes=None,
            helper_pdf=False) -> list[Path]:
    """Build the sections not given to the helper, assemble, write html/pdf."""
    want_pdf = "pdf" in formats
    frags = _build(ctx, [n for n in all_names if proc is None or n not in helper_names])
    helper_ok = False
    if proc is not None:
        try:
            msg = conn.recv()
            if msg[0] == "frags":
                frags.update(msg[1])
                ctx.written.extend(Path(p) for p in msg[2] if Path(p) not in ctx.written)
                helper_ok = True
        except (EOFError, OSError):
            pass
        if not helper_ok:
            frags.update(_build(ctx, helper_names))
            _write_tables(ctx, ctx.tables_elsewhere)
    html, figure_files = _figure_files(ctx, _assemble(ctx, frags))
    sent = False
    if want_pdf and helper_pdf and proc is not None and helper_ok:
        try:
            conn.send(html)            # the helper compiles the PDF meanwhile
            sent = True
        except OSError:
            pass
    figure_files()                     # the figures as files, while the helper compiles
    written = list(ctx.written)
    if "html" in formats:
        from . import explore   # the slider widget: report.html only, not the PDF
        written.append(ctx.write_file("report.html", explore.inject(ctx, html)))
    if want_pdf:
        pdf = None
        if sent:
            try:
                msg = conn.recv()
                if msg[0] == "pdf":
                    pdf = msg[1]
            except (EOFError, OSError):
                pdf = None
        try:
            if pdf is None:
                pdf = _pdf_bytes(html, ctx.lang)
        except PdfSkipped as exc:
            if notes is None:
                raise
            notes.append(f"report.pdf skipped: {exc}")
        else:
            written.append(ctx.write_file("report.pdf", pdf))
    if "note" in formats:              # the explanatory note: the same content, as a text document
        try:
            from . import note
            _typst_ready()
            written.append(ctx.write_file("note.pdf", note.pdf_bytes(html, ctx.results, ctx.task, ctx.lang)))
        except PdfSkipped as exc:
            if notes is None:
                raise
            notes.append(f"note.pdf skipped: {exc}")
    return written


_WORD = re.compile(r"\w")


def _word_ends(html: str, i: int) -> bool:
    """A word boundary (regex \\b) at i, after a word character: none at i (or the end)."""
    return i >= len(html) or not _WORD.match(html, i)


def _figures(html: str):
    """The figures of the report's HTML, as (start, svg, after) of each match of
    ``<figure\\b.*?(<svg\\b.*?</svg>)(.*?)</figure>`` (re.S) in turn: the first svg
    element after each figure's start, the text between it and the figure's end.  Found
    by str.find (the lazy regex stepped through the ~1.2 MB of SVG text a character at
    a time: ~25x the time)."""
    pos = 0
    while True:
        start = html.find("<figure", pos)
        while start >= 0 and not _word_ends(html, start + 7):
            start = html.find("<figure", start + 1)
        if start < 0:
            return
        s = html.find("<svg", start + 7)
        while s >= 0 and not _word_ends(html, s + 4):
            s = html.find("<svg", s + 1)
        e = html.find("</svg>", s + 4) if s >= 0 else -1
        f = html.find("</figure>", e + 6) if e >= 0 else -1
        if f < 0:         # no figure here: none further on either (the regex's backtracking)
            return
        yield start, html[s:e + 6], html[e + 6:f]
        pos = f + 9
_CAPTION = re.compile(r"<figcaption[^>]*>(.*?)</figcaption>", re.S)
_TAGS = re.compile(r"<[^>]+>")
_HEADING = re.compile(r"<h[2-4]\b[^>]*>(.*?)</h[2-4]>", re.S)
_DATA_NAME = re.compile(r'^<svg\b[^>]*?\sdata-name="([a-z0-9-]+)"')


def _figure_files(ctx, html: str):
    """(the HTML without the figures' file names (data-name attributes), a function that
    writes every figure of the report as a file beside it), so the HTML can go to the PDF
    while the files are written.  The files are named by their content and position
    (figures/plans-pos02.svg, figures/lever-pos02.svg, figures/cam-profile.svg; a figure
    without a name: fig-NN.svg, NN its number in the report), with figures/index.csv giving
    each file its caption in the report's language (the figure's caption, else the
    heading it stands under)."""
    import html as _html

    def plain(s):
        return " ".join(_html.unescape(_TAGS.sub("", s)).split())

    def write():
        rows, used = [], set()
        heads = [(m.start(), plain(m.group(1))) for m in _HEADING.finditer(html)]
        for k, (at, svg, tail) in enumerate(_figures(html), start=1):
            dn = _DATA_NAME.match(svg)
            stem = dn.group(1) if dn else f"fig-{k:02d}"
            name, n = stem, 1
            while name in used:
                n += 1
                name = f"{stem}-{n}"
            used.add(name)
            if dn:
                svg = svg.replace(f' data-name="{stem}"', "", 1)
            if "xmlns=" not in svg[:300]:
                svg = svg.replace("<svg", '<svg xmlns="http://www.w3.org/2000/svg"', 1)
            path = f"figures/{name}.svg"
            ctx.write_file(path, '<?xml version="1.0" encoding="utf-8"?>\n' + svg + "\n")
            cap = _CAPTION.search(tail)
            text = plain(cap.group(1)) if cap else ""
            if not text:
                text = next((h for hat, h in reversed(heads) if hat < at), "")
            rows.append([path, text])
        if rows:
            ctx.write_csv("figures/index.csv", ["file", "caption"], rows)

    return re.sub(r'(<svg\b[^>]*?) data-name="[a-z0-9-]+"', r"\1", html), write


def render(results: dict, task: Task | None, out_dir: Path, formats: set[str], lang: str = "en",
           notes: list[str] | None = None) -> list[Path]:
    """Write report.html and/or report.pdf (+ CSV tables) into out_dir; return the paths
    (:func:`_render`), every number written in ``lang``'s way (:mod:`tmm_cli.numfmt`)."""
    with numfmt.language(lang):
        return _render(results, task, out_dir, formats, lang, notes)


def _render(results: dict, task: Task | None, out_dir: Path, formats: set[str], lang: str = "en",
            notes: list[str] | None = None) -> list[Path]:
    """Write report.html and/or report.pdf (+ CSV tables) into out_dir; return the paths.

    If the PDF engine cannot run here, ``notes`` (when given) receives one line
    saying that report.pdf was skipped and why, and the rest is written; without
    ``notes`` the PdfSkipped exception propagates.

    With two cores the work is split over two processes: a helper (forked) builds
    the kinetostatics section and writes kinematics.csv (HELPER_TABLES) while the main
    process builds the other sections; the helper then compiles the PDF while the main process
    writes report.html.  Any failure of the helper falls back to doing everything here."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    formats = {f.lower() for f in formats}
    if not formats & {"html", "pdf", "note"}:
        return []
    want_pdf = "pdf" in formats
    from ..results import listed
    results = listed(results)      # once, before the helper is forked (it shares them)
    ctx = _context(results, task, out_dir, lang)
    all_names = [name for name, _ in _sections.available()]
    helper_names = [n for n in HELPER_SECTIONS if n in all_names and results.get(n)]
    proc = conn = None
    froze = False
    # Typst's compiler runs thread pools: a process forked after this one has used Typst
    # would wait for them for ever, so the helper compiles the PDF only where Typst has not
    # been loaded here yet (a `tmm run`); in a process that already made a PDF (tests, a
    # long-lived caller) this process compiles it
    import sys
    helper_pdf = want_pdf and "typst" not in sys.modules
    from ..io import workers_wanted
    if (helper_names or helper_pdf) and workers_wanted():
        try:
            import multiprocessing
            import os
            mp = multiprocessing.get_context("fork")
            # the objects made so far out of the cycle collector's reach while the helper
            # runs: neither process's collections then walk them, and their memory pages
            # stay shared instead of being copied into the helper (0.1-0.2 s of CPU)
            import gc
            if gc.get_freeze_count() == 0:       # a caller's own freeze is left alone
                gc.freeze()
                froze = True
            conn, child = mp.Pipe()
            tables = tuple(n for n in HELPER_TABLES if n in all_names and results.get(n))
            proc = mp.Process(target=_helper, args=(child, results, task, out_dir, ctx.lang, helper_names,
                                                    helper_pdf, os.getpid(), conn, tables), daemon=True)
            proc.start()
            child.close()
            ctx.tables_elsewhere = tables
        except OSError:                    # no second process here: everything in this one
            proc = conn = None
    try:
        written = _finish(ctx, proc, conn, formats, all_names, helper_names, out_dir, notes, helper_pdf)
    finally:
        if proc is not None:
            try:
                conn.close()
            except OSError:
                pass
            proc.join(timeout=5)
            if proc.is_alive():
                proc.terminate()
                proc.join(timeout=5)
            if proc.is_alive():
                proc.kill()
                proc.join()
        if froze:
            import gc
            gc.unfreeze()
    # unique, in write order
    seen, out = set(), []
    for p in written:
        if p not in seen:
            seen.add(p)
            out.append(p)
    return out
