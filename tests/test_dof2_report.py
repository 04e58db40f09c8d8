"""Report section dof2 (en, ru): scheme, equations, motion, reactions, energy, the hit,
the centrifugal pendulum; dof2.csv beside the report."""
from __future__ import annotations

import csv
import math
import re
from html import unescape
from pathlib import Path

import pytest

from tmm_cli import numfmt
from tmm_cli.dof2 import Dof2Section, analyze
from tmm_cli.report import _context
from tmm_cli.report.context import fmt
from tmm_cli.report.sections import load
from tmm_cli.yamlload import load_yaml

ROOT = Path(__file__).resolve().parents[1]
OMEGA = 1500 * math.pi / 30           # the example's 1500 rpm


@pytest.fixture(scope="module")
def results():
    data, _ = load_yaml(ROOT / "tasks" / "impact_rotor.yaml")
    return {"schema": "tmm-results/1", "dof2": analyze(Dof2Section.model_validate(data["dof2"])).to_dict(),
            "warnings": []}


def build(results, lang, tmp_path):
    mod = load("dof2")
    with numfmt.language(lang):         # as report.render builds the sections
        return mod.build(_context(results, None, tmp_path, lang))


def text(html):
    html = re.sub(r"<svg\b.*?</svg>", "", html, flags=re.S)
    return unescape(re.sub(r"<[^>]+>", " ", html))


def test_absent_section(tmp_path):
    assert build({"schema": "tmm-results/1", "warnings": []}, "en", tmp_path) is None


@pytest.mark.parametrize("lang", ["en", "ru"])
def test_section_numbers_and_csv(results, lang, tmp_path):
    html = build(results, lang, tmp_path)
    assert '<section class="section" id="dof2">' in html
    assert html.count("<svg") == 5                        # scheme, angles, speeds, reactions, energy
    body = text(html)
    # the hit at phi = 270 deg with omega1 = const: t = (3 pi / 2) / omega1 (closed form)
    def fmt_(x, digits=4):              # the numbers as the language writes them (the comma in ru)
        return numfmt.localize(fmt(x, digits), lang)
    assert fmt_(1.5 * math.pi / OMEGA, 6) in body
    # centrifugal pendulum: omega_n = omega1 sqrt(m2 l lc / (J_C + m2 lc^2)), example values
    m2, l, lc, JC = 0.35, 0.06, 0.055, 2.4e-4
    wn = OMEGA * math.sqrt(m2 * l * lc / (JC + m2 * lc ** 2))
    assert fmt_(wn) in body and fmt_(2 * math.pi / wn) in body
    # parameters as given in the task
    for v in ("0.06000", "0.3500", "0.0550", "0.0002400"):
        assert numfmt.localize(v, lang) in body, v
    rows = list(csv.reader((tmp_path / "dof2.csv").open(encoding="utf-8")))
    head, rows = rows[0], rows[1:]
    assert len(rows) == 401
    col = {h: i for i, h in enumerate(head)}
    last = rows[-1]
    assert float(last[col["t"]]) == pytest.approx(0.04)
    assert float(last[col["phi_deg"]]) == pytest.approx(math.degrees(OMEGA * 0.04), rel=1e-12)
    assert float(last[col["omega1"]]) == pytest.approx(OMEGA)
    # balanced rotor (S1 at O): R01 = R12 at every instant (m1 a_S1 = 0, no gravity)
    for r in rows[::50]:
        assert float(r[col["R01"]]) == pytest.approx(float(r[col["R12"]]), rel=1e-12)


def test_russian_has_no_english_phrases(results, tmp_path):
    from tmm_cli.report import i18n
    ru = text(build(results, "ru", tmp_path))
    en_table = i18n.STRINGS["en"]
    ru_table = i18n.STRINGS["ru"]
    for k, v in en_table.items():
        if not k.startswith("dof2.") or ru_table.get(k, v) == v:
            continue
        lit = re.split(r"[{(]", v)[0].strip()
        if len(re.findall(r"[A-Za-z]{3,}", lit)) >= 2:
            assert lit not in ru, (k, lit)
    assert "Роторный" in ru or "роторный" in ru
    assert re.search(r"\b(the|and|of|rotor|striker)\b", ru) is None


def test_no_hit_and_moment_drive(tmp_path):
    sec = {"rotor": {"length": 0.08, "mass": 1.5, "com": 0.02, "J": 0.004},
           "striker": {"length": 0.12, "com": 0.07, "mass": 0.4, "J": 3e-4},
           "gravity": True, "drive": {"moment": 0.5}, "t_end": 0.2, "samples": 41,
           "impact": {"phi": 180}}
    res = {"dof2": analyze(Dof2Section.model_validate(sec)).to_dict(), "warnings": []}
    body = text(build(res, "en", tmp_path))
    assert "does not reach the hit angle" in body
    assert "constant driving moment M = 0.5000 N·m" in body
    assert "centrifugal pendulum" not in body
