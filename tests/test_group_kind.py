"""The kind of an Assur group as the Russian and Ukrainian courses write it: В/О (вращательная,
обертальна), П (поступательная) pairs — 'ВВП', 'ООП', not the Latin 'RRP' — in the structure table
and the worked position."""
from __future__ import annotations

import pytest

from tmm_cli.report.sections.structure import group_kind


@pytest.mark.parametrize("typ, ru, uk", [("RRR", "ВВВ", "ООО"), ("RRP", "ВВП", "ООП"), ("RPR", "ВПВ", "ОПО"),
                                         ("PRP", "ПВП", "ПОП")])
def test_course_letters(typ, ru, uk):
    """The letters of the kinematic pairs table: вращательная (В), обертальна (О), поступательная (П)."""
    assert group_kind(typ, "ru") == ru
    assert group_kind(typ, "uk") == uk
    assert group_kind(typ, "en") == typ


def test_other_kinds_unchanged():
    assert group_kind("—", "ru") == "—"
    assert group_kind("triad", "ru") == "triad"
    assert group_kind("", "ru") == ""


def test_structure_table_in_russian(tmp_path):
    from tests.test_report import slider_crank_results
    from tmm_cli.report import render_html
    html = render_html({"schema": "tmm-results/1", "structure": slider_crank_results()["structure"]},
                       None, tmp_path, "ru")[0]
    assert "<td>ВВП</td>" in html and "<td>RRP</td>" not in html
    html = render_html({"schema": "tmm-results/1", "structure": slider_crank_results()["structure"]},
                       None, tmp_path / "en", "en")[0]
    assert "<td>RRP</td>" in html
