"""Reports of example tasks rendered in a language and in English, for the tests that a
translated report has no text left in another language (tests/test_report_ru.py, _uk.py)."""
from __future__ import annotations

from pathlib import Path

import tmm_cli
from tmm_cli.report import render_html

ROOT = Path(__file__).resolve().parents[1]


def render_pairs(tmp_path_factory, tasks, lang: str) -> dict:
    """{task name: (html in `lang`, html in English, results)} of tasks/<name>.yaml."""
    out = {}
    for name in tasks:
        task = tmm_cli.load_task(ROOT / "tasks" / f"{name}.yaml")
        r = tmm_cli.run(task, kinematics_curve=0)
        d = tmp_path_factory.mktemp(name)
        out[name] = (render_html(r, task, d, lang)[0], render_html(r, task, d, "en")[0], r)
    return out
