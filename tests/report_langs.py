"""Reports of example tasks rendered in a language and in English, for the tests that a
translated report has no text left in another language (tests/test_report_ru.py, _uk.py)
that it uses the glossary's words (tests/test_glossary.py), that its numbers take the
decimal comma (tests/test_decimal_comma.py): each report (task,
language) is made once per test session and shared by those files (``shared_once``)."""
from __future__ import annotations

import json
import pickle
from pathlib import Path

import tmm_cli

ROOT = Path(__file__).resolve().parents[1]


def report_dir(shared_once, name: str, lang: str) -> Path:
    """The folder render_html wrote tasks/<name>.yaml's report into, in ``lang`` (the
    results without the kinematics curve), made once per session: report.html, its CSV
    tables, and ``results-unchanged`` ("True": the results' JSON the same after the report
    was made from them as before, the report never localises them)."""
    def build(d: Path) -> None:
        from tmm_cli.report import render_html
        task = tmm_cli.load_task(ROOT / "tasks" / f"{name}.yaml")
        r = results(shared_once, name)
        before = json.dumps(r, sort_keys=True, default=str)
        (d / "report.html").write_bytes(render_html(r, task, d, lang)[0].encode("utf-8"))
        (d / "results-unchanged").write_text(str(json.dumps(r, sort_keys=True, default=str) == before))
    return shared_once(f"html-{name}-{lang}", build)


def report_html(shared_once, name: str, lang: str) -> str:
    """report.html's text of tasks/<name>.yaml in ``lang`` (:func:`report_dir`)."""
    return (report_dir(shared_once, name, lang) / "report.html").read_bytes().decode("utf-8")


def results(shared_once, name: str) -> dict:
    """tmm_cli.run's results of tasks/<name>.yaml without the kinematics curve, once per session."""
    def build(d: Path) -> None:
        r = tmm_cli.run(tmm_cli.load_task(ROOT / "tasks" / f"{name}.yaml"), kinematics_curve=0)
        (d / "results.pickle").write_bytes(pickle.dumps(r))
    return pickle.loads((shared_once(f"run-{name}", build) / "results.pickle").read_bytes())


def render_pairs(shared_once, tasks, lang: str) -> dict:
    """{task name: (html in `lang`, html in English)} of tasks/<name>.yaml."""
    return {name: (report_html(shared_once, name, lang), report_html(shared_once, name, "en")) for name in tasks}
