"""Report section 'study': accuracy against computing time per stage (`tmm run --study`).

Shown only when the report is built with a study (results.json itself never carries it:
the timings would make it non-deterministic); the tables and log-log plots are those of
`tmm_cli.study.html_section`, its texts the table below."""
from __future__ import annotations

from ... import locales

I18N = locales.table("study", "words")


def build(ctx) -> str | None:
    st = ctx.results.get("study")
    if not st:
        return None
    from markupsafe import Markup
    from ...study import html_section
    return Markup(html_section(st, ctx.results.get("study_trapezoid"), ctx.lang))
