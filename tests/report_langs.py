"""Reports of example tasks rendered in a language and in English, for the tests that a
translated report has no text left in another language (tests/test_report_ru.py, _uk.py)
that it uses the glossary's words (tests/test_glossary.py), that its numbers take the
decimal comma (tests/test_decimal_comma.py): each report (task, language) is made once per
test session and shared by those files and the tests of the PDF (``shared_once``)."""
from __future__ import annotations

from pathlib import Path

from pdf_extent import report_out


def report_dir(shared_once, name: str, lang: str) -> Path:
    """The folder `tmm run --format html,pdf --lang <lang>` writes for tasks/<name>.yaml, made
    once per session and shared with the tests of the PDF (:func:`pdf_extent.report_out`):
    report.html, its figures and CSV tables, report.pdf, and ``results-unchanged``."""
    return report_out(shared_once, name, lang)


def report_html(shared_once, name: str, lang: str) -> str:
    """report.html's text of tasks/<name>.yaml in ``lang`` (:func:`report_dir`)."""
    return (report_dir(shared_once, name, lang) / "report.html").read_bytes().decode("utf-8")


def render_pairs(shared_once, tasks, lang: str) -> dict:
    """{task name: (html in `lang`, html in English)} of tasks/<name>.yaml."""
    return {name: (report_html(shared_once, name, lang), report_html(shared_once, name, "en")) for name in tasks}
