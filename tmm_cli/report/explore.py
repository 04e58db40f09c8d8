"""The explorable mechanism of report.html: a crank-angle slider with play/pause that
moves the linkage through the turn and redraws the mechanism, its velocity and
acceleration plans and a table of v, a, omega, epsilon for the angle shown.

HTML only: ``inject(ctx, html)`` adds the widget (templates ``explore.html.j2`` and
``explore.js``, the data as JSON in a ``<script type="application/json">``) to the
HTML text written to report.html; the PDF is made from the HTML without it.  The
data are the results' ``kinematics_explore`` (made by the pipeline with the stage
function ``tmm_cli.linkage.kinematics.explore.explore_grid``)."""
from __future__ import annotations

import json

from .context import templates_dir

I18N = {
    "en": {"explore.title": "The mechanism in motion", "explore.play": "Play", "explore.pause": "Pause",
           "explore.angle": "Crank turn from position 0", "explore.mech": "Mechanism",
           "explore.vplan": "Velocity plan", "explore.aplan": "Acceleration plan",
           "explore.point": "Point", "explore.link": "Link", "explore.pos": "position",
           "explore.v": "v, m/s", "explore.a": "a, m/s²", "explore.w": "ω, 1/s", "explore.e": "ε, 1/s²",
           "explore.hint": "Drag the slider (the marks are the course positions: the slider snaps to them "
                           "within 3°) or press Play. Values at the angle shown."},
    "ru": {"explore.title": "Механизм в движении", "explore.play": "Пуск", "explore.pause": "Пауза",
           "explore.angle": "Поворот кривошипа от положения 0", "explore.mech": "Механизм",
           "explore.vplan": "План скоростей", "explore.aplan": "План ускорений",
           "explore.point": "Точка", "explore.link": "Звено", "explore.pos": "положение",
           "explore.v": "v, м/с", "explore.a": "a, м/с²", "explore.w": "ω, 1/с", "explore.e": "ε, 1/с²",
           "explore.hint": "Передвиньте ползунок (метки — положения проекта: ползунок притягивается к ним "
                           "в пределах 3°) или нажмите «Пуск». Значения для показанного угла."},
    "uk": {"explore.title": "Механізм у русі", "explore.play": "Пуск", "explore.pause": "Пауза",
           "explore.angle": "Поворот кривошипа від положення 0", "explore.mech": "Механізм",
           "explore.vplan": "План швидкостей", "explore.aplan": "План прискорень",
           "explore.point": "Точка", "explore.link": "Ланка", "explore.pos": "положення",
           "explore.v": "v, м/с", "explore.a": "a, м/с²", "explore.w": "ω, 1/с", "explore.e": "ε, 1/с²",
           "explore.hint": "Пересуньте повзунок (позначки — положення проєкту: повзунок притягується до них "
                           "у межах 3°) або натисніть «Пуск». Значення для показаного кута."},
}


def data_json(data: dict) -> str:
    """JSON safe inside <script>: no '<', '>' or '&' at all (written as \\u003c ...), so
    user text (point and link names) can neither end the element nor open a tag."""
    s = json.dumps(data, separators=(",", ":"), ensure_ascii=True, allow_nan=False)
    return s.replace("<", "\\u003c").replace(">", "\\u003e").replace("&", "\\u0026")


def fragment(ctx) -> str | None:
    data = ctx.results.get("kinematics_explore")
    if not data:                # no linkage, or results made without the fine grid
        return None
    tr = I18N.get(ctx.lang, I18N["en"])
    from markupsafe import Markup
    js = (templates_dir() / "explore.js").read_text(encoding="utf-8")
    return ctx.render("explore.html.j2", tr=tr, data=Markup(data_json(data)),
                      labels=Markup(data_json(tr)), js=Markup(js.replace("</", "<\\/")))


def inject(ctx, html: str) -> str:
    """The HTML with the widget before the kinematics section (else before </body>)."""
    frag = fragment(ctx)
    if not frag:
        return html
    at = html.find('<section class="section" id="kinematics"')
    if at < 0:
        at = html.rfind("</body>")
    if at < 0:
        return html + frag
    return html[:at] + frag + html[at:]
