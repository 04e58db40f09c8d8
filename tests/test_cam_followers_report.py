"""Report of the new cam cases: flat-faced, knife-edge and chosen-size cams (en/ru), the
division-point table, the drawing scales; `tmm new` starters and `tmm fields`."""
from __future__ import annotations

import re
from pathlib import Path

import pytest
import yaml
from typer.testing import CliRunner

import tmm_cli
from tmm_cli.cli import app
from tmm_cli.report.figures import drawing_scale

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.parametrize("name", ["cam_flat", "cam_knife", "cam_chosen_size"])
@pytest.mark.parametrize("lang", ["en", "ru"])
def test_report_of_the_new_cams(name, lang, tmp_path):
    from tmm_cli.report import render

    task = tmm_cli.load_task(ROOT / "tasks" / f"{name}.yaml")
    res = tmm_cli.run(task)
    render(res, task, tmp_path, {"html"}, lang)
    html = (tmp_path / "report.html").read_text(encoding="utf-8")
    assert "figure failed" not in html
    c = res["cam"]
    # the division table: a row per division point, the s of the middle of the rise printed
    n = sum(1 for r in c["division_table"] if r["phase"] == "rise") - 1
    assert n == task.cam.divisions
    heading = "Values at the division points" if lang == "en" else "Значения в точках деления"
    assert heading in html
    table = html[html.index(heading):]
    assert table.count("<tr") >= 2 * (n + 1)
    # the profile at a standard scale, stated
    # (its mark as the language writes it: the Cyrillic capital Em in ru and uk, GOST 2.302)
    mark = "M" if lang == "en" else "\u041c"
    assert re.search(mark + r" (\d+(\.\d+)?:1|1:\d+(\.\d+)?)", html)
    if name == "cam_flat":
        assert "38.197" in html or "38,197" in html          # 2 max|ds/dphi| = 2 * 2h/P = 38.197 mm
    if name == "cam_chosen_size":
        assert "36.435" in html or "36,435" in html          # r0_min beside the chosen 40 mm


def test_standard_drawing_scales():
    """GOST 2.302: 1:1, 1:2, 1:2.5, 1:4, 1:5, 1:10, ...; 2:1, 2.5:1, 4:1, ... (model mm per paper mm)."""
    assert drawing_scale(1.0) == (1.0, "1:1")
    assert drawing_scale(1.01) == (2.0, "1:2")
    assert drawing_scale(2.2) == (2.5, "1:2.5")
    assert drawing_scale(3.0) == (4.0, "1:4")
    assert drawing_scale(6.0) == (10.0, "1:10")
    assert drawing_scale(0.45) == (0.5, "2:1")
    assert drawing_scale(0.3) == (0.4, "2.5:1")


@pytest.mark.parametrize("kind,follower", [("cam_flat", "flat"), ("cam_knife", "knife"), ("cam_rocker", "rocker")])
def test_starters_for_each_follower(kind, follower, tmp_path):
    runner = CliRunner()
    res = runner.invoke(app, ["new", kind])
    assert res.exit_code == 0
    assert yaml.safe_load(res.output)["cam"]["follower"] == follower
    p = tmp_path / f"{kind}.yaml"
    p.write_text(res.output, encoding="utf-8")
    assert runner.invoke(app, ["validate", str(p)]).exit_code == 0
    assert tmm_cli.run(tmm_cli.load_task(p))["cam"]["follower"] == follower


def test_fields_document_the_new_keys():
    from tmm_cli.task import field_docs

    assert CliRunner().invoke(app, ["fields"]).exit_code == 0
    docs = {path: text for path, _, text in field_docs()}
    for key in ("cam.r0", "cam.center_distance", "cam.rho_min_allowed", "cam.divisions",
                "kinetostatics.friction.f_pin", "kinetostatics.friction.f_slide"):
        assert docs.get(key), key
    assert "flat" in docs["cam.follower"] and "knife" in docs["cam.follower"]


def test_exit_codes_through_the_cli(tmp_path):
    runner = CliRunner()
    d = yaml.safe_load((ROOT / "tasks" / "cam_chosen_size.yaml").read_text())
    d["cam"]["r0"] = "30 mm"                   # below r0_min = 36.4 mm: the pressure angle exceeds 30
    p = tmp_path / "small.yaml"
    p.write_text(yaml.safe_dump(d), encoding="utf-8")
    res = runner.invoke(app, ["run", str(p), "-o", str(tmp_path / "o"), "-f", "json", "-q"])
    assert res.exit_code == 3
    d["cam"]["offset"] = "35 mm"               # r0 < |offset|
    p.write_text(yaml.safe_dump(d), encoding="utf-8")
    res = runner.invoke(app, ["run", str(p), "-o", str(tmp_path / "o"), "-f", "json", "-q"])
    assert res.exit_code == 2
