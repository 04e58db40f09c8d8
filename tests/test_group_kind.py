"""The kind of an Assur group as a Russian course writes it: В (вращательная), П (поступательная)
pairs — 'ВВП', not the Latin 'RRP' — in the structure table and the worked position."""
from __future__ import annotations

import pytest

from tmm_cli.report.sections.structure import group_kind


@pytest.mark.parametrize("typ, ru", [("RRR", "ВВВ"), ("RRP", "ВВП"), ("RPR", "ВПВ"), ("PRP", "ПВП")])
def test_russian_letters(typ, ru):
    assert group_kind(typ, "ru") == ru
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
