"""`tmm study` for a student: the trade first, in plain words (the coarse setting's error
against the default's), on the terminal and at the top of study.html; each row timed after
an untimed first call (no cold start in the table)."""
from __future__ import annotations

import time
from pathlib import Path

import pytest
from typer.testing import CliRunner

from tmm_cli import study as study_mod
from tmm_cli.report.sections import study as study_page
from tmm_cli.commands import app

ROOT = Path(__file__).resolve().parents[1]
STUDY = {"kinetostatics": {"setting": "positions", "default": 720,
                           "rows": [{"setting": 12, "error": 0.107, "time_ms": 2.5},
                                    {"setting": 72, "error": 0.003, "time_ms": 9.0},
                                    {"setting": 720, "error": 2.2e-11, "time_ms": 80.0}],
                           "reference": {"M_b_max": 1.0, "setting": 3600}, "order": 2.0, "theory": 2},
         "curves": {"setting": "points", "rows": [{"setting": 13, "error": 0.176, "time_ms": 1.0},
                                                  {"setting": 1441, "error": 1.3e-5, "time_ms": 4.0}],
                    "reference": {"stroke": 0.2, "setting": 3600}, "order": 2.0, "theory": 2}}


def test_a_cold_first_call_is_not_timed():
    calls = []

    def fn():
        calls.append(1)
        if len(calls) == 1:
            time.sleep(0.05)         # the first call: imports, caches
        return {}
    _, ms = study_mod._timed(fn, repeat=1)
    assert len(calls) == 2 and ms < 25.0


def test_the_trade_in_plain_words():
    en = study_page.trades(STUDY, "en")
    # every error in percent: 2.2e-11 is 2e-9 %, 1.3e-5 is 0.0013 % (a bare 2e-11 beside 10.7 %
    # read as one unit)
    assert en[0] == ("the M_b and reaction diagrams drawn through 12 positions err by 10.7 %, through 720 "
                     "(the default) by 2e-9 % (2.5 → 80 ms)")
    # no default among the rows: the coarsest against the finest
    assert en[1].startswith("the s, v, a diagrams drawn through 13 points err by 17.6 %, through 1441 by 0.0013 %")
    ru = study_page.trades(STUDY, "ru")
    assert "по 12 положениям" in ru[0] and "10,7 %" in ru[0] and "2·10⁻⁹ %" in ru[0] and "(по умолчанию)" in ru[0]
    uk = study_page.trades(STUDY, "uk")
    assert "за 12 положеннями" in uk[0] and "10,7 %" in uk[0] and "(типово)" in uk[0]


def test_study_html_and_terminal_lead_with_the_trade(tmp_path, monkeypatch):
    html = study_page.html_section(STUDY, None, "en")
    assert html.index("In short") < html.index("For each stage") < html.index("Reference")
    # the page writes the course's notation with its subscript, the terminal as plain text
    assert "The M<sub>b</sub> and reaction diagrams drawn through 12 positions err by 10.7 %" in html
    monkeypatch.setattr(study_mod, "run_study", lambda task, progress=None, repeat=3: (STUDY, {}))
    res = CliRunner().invoke(app, ["study", str(ROOT / "tasks" / "forging_sixbar.yaml"), "--out", str(tmp_path)])
    assert res.exit_code == 0, res.output
    lines = res.stdout.strip().splitlines()
    assert lines[0].startswith("The M_b and reaction diagrams drawn through 12 positions err by 10.7 %")
    assert lines[-2:] == [str(tmp_path / "study.json"), str(tmp_path / "study.html")]


def test_planetary_trade_says_the_ratio_error_and_the_change_apart():
    """planetary_A (i = 3.24 required): every search finds 3.15, 2.78 % off. The sentence said
    "the search up to z = 100 finds a ratio off by 0 %": the 0 % is the change against the
    reference search, not the ratio's error. Both are said, each for what it is."""
    import tmm_cli
    d = study_mod.study_planetary(tmm_cli.load_task(ROOT / "tasks" / "planetary_A.yaml"))
    assert d["required"] == 3.24 and d["default"] == 150
    assert d["rows"][0]["ratio_error"] == pytest.approx(0.09 / 3.24) and d["rows"][0]["error"] == 0.0
    en = study_page.trade("planetary", d, "en")
    assert en.startswith("the search up to z = 100 finds the ratio 3.15, 2.78 % off the required 3.24; "
                         "up to z = 150 (the default): 3.15, 2.78 % off (against the reference search up to "
                         "z = 150 the ratio found changes by 0 % and 0 %;"), en
    ru = study_page.trade("planetary", d, "ru")
    assert "передаточное отношение 3,15, отличающееся от заданного 3,24 на 2,78 %" in ru
    assert "по сравнению с эталонным подбором до z = 150 найденное отношение меняется на 0 %" in ru
    uk = study_page.trade("planetary", d, "uk")
    assert "передатне відношення 3,15, що відрізняється від заданого 3,24 на 2,78 %" in uk
    assert "з похибкою 0 %" not in uk and "порівняно з еталонним підбором до z = 150" in uk
