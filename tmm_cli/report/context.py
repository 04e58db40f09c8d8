"""The context object handed to every report section's ``build(ctx)``."""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from operator import itemgetter
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..io import atomic_write
from ..numfmt import localize
from ..results import ROUND_OFF_ZERO
from . import figures
from .i18n import translate
from .notation import term

if TYPE_CHECKING:
    from ..task import Task


def templates_dir() -> Path:
    """Templates: ``tmm_cli/templates`` in an installed wheel, else ``<repo>/templates``."""
    pkg = Path(__file__).resolve().parent.parent / "templates"
    if pkg.is_dir():
        return pkg
    return Path(__file__).resolve().parents[2] / "templates"


def values_of(keys: tuple):
    """d -> the values of ``keys`` (two or more) in ``d``, a tuple, None for a missing key
    (as ``d.get``): one ``itemgetter`` call where every key is there, for the per-position
    rows of the report's tables (thousands at a fine grid)."""
    get = itemgetter(*keys)

    def values(d):
        try:
            return get(d)
        except KeyError:
            return tuple(d.get(k) for k in keys)
    return values


def fmt(x: Any, digits: int = 4) -> str:
    """Number for a table: `digits` significant digits, no exponent for
    1e-4 <= |x| < 1e7, '—' for None/NaN, '0' for |x| < 1e-10 (round-off of an
    exact zero in SI units) and '-0'; written in the current language (numfmt: the
    decimal comma and 8,9·10⁻¹⁶ in ru and uk)."""
    if x is None:
        return "—"
    if isinstance(x, bool):
        return str(x).lower()
    if isinstance(x, int):
        return str(x)
    try:
        v = float(x)
    except (TypeError, ValueError):
        return str(x)
    if not math.isfinite(v):
        return "—"
    a = abs(v)
    if a < ROUND_OFF_ZERO:      # round-off of an exact zero (a dead-centre velocity ...): graded as 0 too
        return "0"
    if a < 1e-4 or a >= 1e7:
        return localize(f"{v:.{max(digits - 1, 0)}e}")
    decimals = max(digits - 1 - int(math.floor(math.log10(a))), 0)
    s = f"{v:.{decimals}f}"
    if float(s) == 0:
        return "0"
    return localize(s)


def fmt_fixed(x: Any, decimals: int = 2) -> str:
    """Number with a fixed count of decimals (plan lengths in mm, angles)."""
    if x is None:
        return "—"
    try:
        v = float(x)
    except (TypeError, ValueError):
        return str(x)
    if not math.isfinite(v):
        return "—"
    s = f"{v:.{decimals}f}"
    if float(s) == 0:
        s = f"{0.0:.{decimals}f}"
    return localize(s)


@dataclass
class ReportContext:
    """What a section sees.

    results  -- the results.json dict: the only source of what the sections show and draw
    task     -- the validated Task, read only for its own data table and text fields
                (section 'task', the title); may be None
    lang     -- 'en' | 'ru' | 'uk'
    out_dir  -- directory of the report; CSV/figure files go beside it
    env      -- the Jinja environment over templates/
    written  -- paths of the files written so far (returned by render)
    tables_elsewhere -- sections whose long per-position table (a module's write_table)
                another process writes (report.HELPER_TABLES): their build leaves it out
    """
    results: dict
    task: Task | None
    lang: str
    out_dir: Path
    env: Any
    written: list[Path] = field(default_factory=list)
    tables_elsewhere: tuple[str, ...] = ()
    figures = figures

    # -- text
    def t(self, key: str, **kw) -> str:
        """The catalogue's text (a :class:`~.notation.Term`: plain text, written into the
        HTML with the notation's subscripts)."""
        return term(translate, key, self.lang, **kw)

    @staticmethod
    def fmt(x: Any, digits: int = 4) -> str:
        return fmt(x, digits)

    @staticmethod
    def fmt_fixed(x: Any, decimals: int = 2) -> str:
        return fmt_fixed(x, decimals)

    def sense(self, w: float | None, tiny: float = 1e-9) -> str:
        """Sense of rotation in words: ccw for w > 0, cw for w < 0."""
        if w is None or not math.isfinite(w) or abs(w) <= tiny:
            return self.t("common.none")
        return self.t("common.ccw") if w > 0 else self.t("common.cw")

    # -- templates / figures
    def render(self, template: str, **kw) -> str:
        kw.setdefault("t", self.t)
        kw.setdefault("fmt", fmt)
        kw.setdefault("fmt_fixed", fmt_fixed)
        kw.setdefault("lang", self.lang)
        kw.setdefault("results", self.results)
        kw.setdefault("task", self.task)
        return self.env.get_template(template).render(**kw)

    def svg(self, fig, name: str | None = None):
        """A figure (svgchart, SchemeView, ...: anything with ``to_svg``) -> inline SVG
        (markup-safe); `name`: its file name in figures/ (figures.named)."""
        from markupsafe import Markup
        out = Markup(fig.to_svg())
        return figures.named(out, name) if name else out

    # -- files beside the report
    def write_file(self, name: str, data: bytes | str) -> Path:
        from ..safepath import inside
        path = inside(self.out_dir, name)  # never through a linked folder inside out_dir
        atomic_write(path, data)
        return self._listed(path)

    def written_elsewhere(self, name: str) -> Path:
        """The file ``name``, which another process writes (report.HELPER_TABLES), listed
        with the files written here in the place this process would have written it (the
        order `tmm run` prints)."""
        from ..safepath import inside
        return self._listed(inside(self.out_dir, name))

    def _listed(self, path: Path) -> Path:
        if path not in self.written:
            self.written.append(path)
        return path

    def write_csv(self, name: str, header: list[str], rows) -> Path:
        """CSV (comma, UTF-8; None -> empty cell): every float in the shortest digits
        that read back as the very same float, spelt as results.json spells them
        (``tables.AS_JSON``: the long per-position tables made ~4x as fast as with
        Python's repr)."""
        from tmm_cli.tables import AS_JSON, csv_text
        return self.write_file(name, csv_text(header, rows, AS_JSON))

    # -- common look-ups
    def link_names(self) -> list[str]:
        """Link names in task order (index 1..n)."""
        links = (self.results.get("structure") or {}).get("links")
        if links:
            return [l["name"] for l in sorted(links, key=lambda l: l["index"])]
        kin = self.results.get("kinematics") or []
        return list(kin[0]["links"].keys()) if kin else []

    def link_kind_word(self, name: str) -> str | None:
        """The kind of a link in words ('crank', 'sliding block', in the report's language), None where unknown."""
        from ..plans import geometry
        from .sections.structure import link_kind
        geom = self.__dict__.get("_geometry", False)
        if geom is False:
            try:
                geom = geometry(self.results)
            except (KeyError, TypeError, ValueError):
                geom = None
            self.__dict__["_geometry"] = geom
        link = geom.by_name(name) if geom is not None else None
        return None if link is None else self.t("link." + link_kind(geom, link))

    def link_label(self, name: str) -> str:
        """A link as the text names it: its kind and number, the task's name in brackets
        ('crank 1 (crank)' in the words of the report's language); the number and the name where the kind is unknown."""
        kind = self.link_kind_word(name)
        return f"{kind} {self.link_ref(name)}" if kind else self.link_ref(name)

    def link_ref(self, name: str) -> str:
        """A link by its number and the task's name ('3 (rocker)'): in any grammatical case."""
        names = self.link_names()
        return f"{names.index(name) + 1} ({name})" if name in names else str(name)

    def link_index(self, name: str) -> int:
        try:
            return self.link_names().index(name) + 1
        except ValueError:
            return 0
