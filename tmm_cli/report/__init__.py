"""The report: results.json (+ the task) -> report.html / report.pdf + CSV tables.

``render(results, task, out_dir, formats, lang) -> list[Path]`` renders one
Jinja HTML source (``templates/report.html.j2``) with inline CSS and inline
SVG figures to a self-contained ``report.html`` and, with weasyprint, to
``report.pdf``.  The report reads numbers only from ``results``; the task
gives names and the task-data table.

How to add a section (e.g. for the stage ``cam``)
-------------------------------------------------
1. Create ``tmm_cli/report/sections/cam.py`` with::

       I18N = {"en": {"cam.title": "Cam mechanism", ...},
               "ru": {"cam.title": "Кулачковый механизм", ...}}

       def build(ctx) -> str | None:
           data = ctx.results.get("cam")
           if not data:
               return None                  # section absent -> nothing in the report
           fig, ax = ctx.figures.new_figure(170, 90)   # matplotlib, Agg, mm size
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
``draw_block``, ``draw_joint``, ``arrow``, ``place_labels``, and
``figures.draw_mechanism`` for the linkage).
"""
from __future__ import annotations

import datetime as _dt
import re
from pathlib import Path

from .context import ReportContext, templates_dir
from . import sections as _sections

__all__ = ["render", "render_html", "make_env"]


_NUM = re.compile(r"^[−+-]?(\d+(\.\d*)?|\.\d+)([eE][−+-]?\d+)?( [↺↻])?$")


def _is_numeric(value) -> bool:
    """Jinja test: a number or a string that reads as one (right-aligned cells)."""
    if isinstance(value, bool):
        return False
    if isinstance(value, (int, float)):
        return True
    return isinstance(value, str) and bool(_NUM.match(value.strip()))


def make_env():
    import jinja2
    from .context import fmt, fmt_fixed
    env = jinja2.Environment(
        loader=jinja2.FileSystemLoader(str(templates_dir())),
        autoescape=jinja2.select_autoescape(["html", "j2", "xml"], default_for_string=True,
                                            default=True),
        trim_blocks=True, lstrip_blocks=True, keep_trailing_newline=True,
    )
    env.filters["fmt"] = fmt
    env.filters["fmt_fixed"] = fmt_fixed
    env.tests["numeric"] = _is_numeric
    return env


def render_html(results: dict, task, out_dir: Path, lang: str = "en") -> tuple[str, ReportContext]:
    """Build the HTML text (sections may write CSV files into out_dir)."""
    from markupsafe import Markup
    env = make_env()
    ctx = ReportContext(results=results, task=task, lang=lang if lang in ("en", "ru") else "en",
                        out_dir=Path(out_dir), env=env)
    parts = []
    for name, mod in _sections.available():
        frag = mod.build(ctx)
        if frag:
            m = _H2.search(frag)
            head = re.sub(r"<[^>]+>", "", m.group(1)).strip() if m else ctx.t(f"{name}.title")
            parts.append({"name": name, "html": Markup(frag), "title": Markup(head)})
    css_path = templates_dir() / "base.css"
    css = css_path.read_text(encoding="utf-8") if css_path.exists() else ""
    title = getattr(task, "title", None) if task is not None else None
    html = ctx.render("report.html.j2", sections=parts, css=Markup(css),
                      title=title or ctx.t("report.title"),
                      variant=getattr(task, "variant", None) if task is not None else None,
                      warnings=results.get("warnings") or [],
                      date=_dt.date.today().isoformat())
    return html, ctx


_H2 = re.compile(r"<h2\b[^>]*>(.*?)</h2>", re.S)
_SVG = re.compile(r"<svg\b.*?</svg>", re.S)
_W = re.compile(r'\bwidth="([0-9.]+)pt"')


def _svg_as_images(html: str) -> str:
    """For weasyprint: inline <svg> -> <img src="data:image/svg+xml;base64,...">.

    Same picture, but the SVG nodes stay out of the HTML style cascade:
    about twice as fast to lay out and paint."""
    import base64

    def repl(m):
        s = m.group(0)
        w = _W.search(s[:400])
        style = f' style="width:{w.group(1)}pt"' if w else ""
        data = base64.b64encode(s.encode("utf-8")).decode("ascii")
        return f'<img class="fig"{style} alt="" src="data:image/svg+xml;base64,{data}">'

    return _SVG.sub(repl, html)


def render(results: dict, task, out_dir: Path, formats: set[str], lang: str = "en") -> list[Path]:
    """Write report.html and/or report.pdf (+ CSV tables) into out_dir; return the paths."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    formats = {f.lower() for f in formats}
    if not formats & {"html", "pdf"}:
        return []
    html, ctx = render_html(results, task, out_dir, lang)
    written = list(ctx.written)
    if "html" in formats:
        written.append(ctx.write_file("report.html", html))
    if "pdf" in formats:
        import logging
        import weasyprint
        for name in ("weasyprint", "fontTools"):
            logging.getLogger(name).setLevel(logging.ERROR)
        pdf = weasyprint.HTML(string=_svg_as_images(html), base_url=str(out_dir)).write_pdf()
        written.append(ctx.write_file("report.pdf", pdf))
    # unique, in write order
    seen, out = set(), []
    for p in written:
        if p not in seen:
            seen.add(p)
            out.append(p)
    return out
