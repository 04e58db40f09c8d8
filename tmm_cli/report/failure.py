"""A failed stage in the report: in place of the section that could not be computed,
a box saying what failed, where, and what to change in the task file; the
sections that were computed stay in the report.

The failures are results.json's ``errors`` (every independent part that failed:
stage, message, position), or its single ``error`` in older results."""
from __future__ import annotations

from .. import locales
from .i18n import register

# stage of a StageError -> (report section it replaces, its title key, the task-file section to change)
STAGES = {
    "structure": ("structure", "struct.title", "mechanism"),
    "positions": ("kinematics", "kin.title", "mechanism"),
    "kinematics": ("kinematics", "kin.title", "mechanism"),
    "loads": ("kinetostatics", "kst.title", "loads"),
    "kinetostatics": ("kinetostatics", "kst.title", "kinetostatics"),
    "dynamics": ("dynamics", "dyn.title", "flywheel"),
    "flywheel": ("dynamics", "dyn.title", "flywheel"),
    "cam": ("cam", "cam.title", "cam"),
    "gears": ("gears", "gears.title", "gears"),
    "planetary": ("planetary", "plan.title", "planetary"),
    "dof2": ("dof2", "dof2.title", "dof2"),
    "differential": ("differential", "diff.title", "differential"),
    "balancing": ("balancing", "bal.title", "balancing"),
}
# a linkage that fails stops the sections after it in its chain
CHAIN = ("structure", "kinematics", "kinetostatics", "dynamics")

I18N = locales.table("failure", "words")
register(I18N)


def failures(results: dict) -> list[dict]:
    errs = results.get("errors")
    if not errs and results.get("error"):
        errs = [results["error"]]
    return [e for e in errs or [] if isinstance(e, dict)]


def placement(err: dict) -> tuple[str | None, str, str]:
    """(report section replaced or None, title key, task-file section) of a failure."""
    stage = str(err.get("stage") or "")
    return STAGES.get(stage, (None, "report.title", stage or "?"))


def stage_name(stage, lang: str) -> str:
    """A stage's name in the report's language (the catalogue's `stage` terms; English: the
    stage's own name, as on stderr and in results.json)."""
    from ..messages import catalogue
    names = catalogue(lang)["terms"].get("stage") or {}
    return str(names.get(str(stage), stage))


def what(err: dict, lang: str, t=None) -> str:
    """The failure's sentence (``fail.what``) in ``lang``: the stage's name, where it failed
    (a crank angle in the language's writing, or a named position), its message (a coded one
    in the language). ``t(key, **kw)``: the catalogue's text (the report's ``ctx.t``; default
    plain text, as the terminal prints it: :func:`tmm_cli.console.stage_text`)."""
    if t is None:
        from .i18n import translate

        def t(key: str, **kw) -> str:
            return translate(key, lang, **kw)
    pos = err.get("position")
    message = err.get("message") or ""
    if err.get("code"):                 # a coded message: in the language
        from ..messages import localize
        message = localize({"code": err["code"], "params": err.get("params") or {}, "text": message}, lang)
    if pos in (None, ""):
        where = ""
    elif isinstance(pos, (int, float)):          # a StageError's position: a crank angle, deg
        where = t("fail.where_angle", position=f"{float(pos):.6g}")
    else:
        where = t("fail.where", position=pos)
    return t("fail.what", stage=stage_name(err.get("stage"), lang), where=where, message=message)


def box(ctx, err: dict) -> str:
    """The HTML fragment shown in place of the failed section."""
    section, title_key, task_section = placement(err)
    return ctx.render("sections/failure.html.j2", sid=f"{section or 'stage'}-failed",
                      title=ctx.t(title_key) if section else stage_name(err.get("stage"), ctx.lang),
                      what=what(err, ctx.lang, ctx.t),
                      change=ctx.t("fail.change", section=task_section))
