"""The A1 drawing sheets: DXF that re-reads, true-size plans, standard scales,
labels that neither collide nor leave the frame, the title block."""
from __future__ import annotations

import functools
import math
from collections import Counter
from pathlib import Path

import numpy as np
import pytest

from tmm_cli.sheets.frame import FRAME, std_mu
from tmm_cli.sheets.prims import Arc, Circle, Line, Polyline, PrimCanvas, Text
from tmm_cli.sheets.writers import dxf_entities, to_dxf

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def forging(shared_once):
    """(results, {lang: sheets}) of the forging machine: the session's shared ones
    (:func:`example_sheets`)."""
    from pdf_extent import results
    return results(shared_once, "forging_sixbar")[1], example_sheets("forging_sixbar", shared_once)


def _mantissa_ok(mu: float) -> bool:
    k = math.floor(math.log10(mu) + 1e-12)
    return any(abs(mu - m * 10.0 ** k) <= 1e-9 * mu for m in (1, 2, 2.5, 4, 5))


def test_std_mu_series():
    # smallest of 1, 2, 2.5, 4, 5 x 10^k not below the value
    assert std_mu(0.0123) == 0.02
    assert std_mu(0.021) == 0.025
    assert std_mu(0.3) == 0.4
    assert std_mu(4.5) == 5.0
    assert std_mu(0.05) == 0.05


@pytest.mark.parametrize("k", [0, 1])
def test_dxf_rereads_with_layers_and_counts(forging, tmp_path, k):
    import ezdxf
    _, sheets = forging
    cv, _ = sheets["ru"][k]
    path = tmp_path / "s.dxf"
    path.write_bytes(to_dxf(cv))
    doc = ezdxf.readfile(path)
    auditor = doc.audit()
    assert not auditor.has_errors
    assert doc.header["$INSUNITS"] == 4
    assert {"contour", "thin", "dimensions", "text"} <= {l.dxf.name for l in doc.layers}
    want = Counter()
    for p in dxf_entities(cv):
        if isinstance(p, Line):
            want["LINE"] += 1
        elif isinstance(p, Polyline):
            want["SOLID" if p.fill and len(p.pts) in (3, 4) else "LWPOLYLINE"] += 1
        elif isinstance(p, Circle):
            want["CIRCLE"] += 1
        elif isinstance(p, Arc):
            want["ARC"] += 1
        elif isinstance(p, Text):
            want["TEXT"] += 1
    got = Counter(e.dxftype() for e in doc.modelspace())
    assert got == want
    assert want["TEXT"] > 50 and want["LINE"] > 50 and want["LWPOLYLINE"] >= 4
    if k == 0:
        assert want["ARC"] >= 1 and want["CIRCLE"] >= 1
    # every text on the text layer, the frame on the contour layer
    texts = list(doc.modelspace().query("TEXT"))
    assert all(t.dxf.layer == "text" for t in texts)
    assert any("Вариант 7" == t.dxf.text for t in texts)
    layers = {e.dxf.layer for e in doc.modelspace()}
    assert layers == {"contour", "thin", "dimensions", "text"} if k == 0 else {"contour", "thin", "text"}


def test_primitive_kinds_each_written():
    import ezdxf
    cv = PrimCanvas(100, 100)
    cv.layer = "contour"
    cv.line((0, 0), (10, 0))
    cv.arc((50, 50), 10, 0, 90)
    cv.circle((20, 20), 3)
    cv.polyline([(0, 0), (1, 1), (2, 0)])
    cv.mtext(5, 5, "ab", 3.5)
    import io
    doc = ezdxf.read(io.StringIO(to_dxf(cv).decode()))
    arc = doc.modelspace().query("ARC")[0]
    assert (arc.dxf.radius, arc.dxf.start_angle, arc.dxf.end_angle) == (10, 0, 90)
    t = doc.modelspace().query("TEXT")[0]
    assert t.dxf.height == pytest.approx(3.5)        # the size of the lettering: the capitals
    assert [e.dxftype() for e in doc.modelspace()] == ["LINE", "ARC", "CIRCLE", "LWPOLYLINE", "TEXT"]


def test_plans_at_true_scale_and_standard_scales(forging):
    res, sheets = forging
    _, info = sheets["en"][0]
    from tmm_cli.report.figures import GOST_ENLARGEMENTS, GOST_REDUCTIONS
    unit = info["mechanism"]["unit"]
    assert any(abs(unit - n) < 1e-12 for n in GOST_REDUCTIONS) or any(
        abs(unit - 1 / n) < 1e-12 for n in GOST_ENLARGEMENTS)
    assert info["mechanism"]["mu_l"] == pytest.approx(unit / 1000)
    assert info["plans"]
    for i, plans in info["plans"].items():
        for kind in ("v", "a"):
            d = plans[kind]
            assert d["k"] == 1.0          # drawn at its own scale, not reduced to fit
            assert _mantissa_ok(d["mu"])
            plan = d["plan"]
            for v in plan.vecs:
                assert plan.length_mm(v) == pytest.approx(v.value / d["mu"], rel=1e-9, abs=1e-9)
    # the crank-pin velocity: v_A = omega1 * OA = 5.236 * 0.15 (50 rpm, 0.15 m)
    i0 = next(iter(info["plans"]))
    pv = info["plans"][i0]["v"]
    va = next(v for v in pv["plan"].vecs if v.end == "a" and v.kind == "abs")
    assert va.value == pytest.approx(50 * 2 * math.pi / 60 * 0.15, rel=1e-9)
    assert pv["plan"].length_mm(va) == pytest.approx(0.7853981633974483 / pv["mu"], rel=1e-9)
    for key in ("s", "v", "a"):
        d = info["diagrams"][key]
        assert _mantissa_ok(d["mu"])
        y0 = d["pts"][:, 1] - d["values"] / d["mu"]
        assert max(y0) - min(y0) < 1e-9            # every point at value / mu from its axis
    assert _mantissa_ok(info["diagrams"]["mu_phi"])


def _boxes(cv):
    return [(p, p.box()) for p in cv.prims if isinstance(p, Text)]


def _check_texts(sheets):
    x0f, y0f, x1f, y1f = FRAME
    for cv, _ in sheets:
        boxes = _boxes(cv)
        for p, (x0, y0, x1, y1) in boxes:
            assert x0f <= x0 and x1 <= x1f and y0f <= y0 and y1 <= y1f, p.plain
        for i in range(len(boxes)):
            a = boxes[i][1]
            for j in range(i + 1, len(boxes)):
                b = boxes[j][1]
                overlap = min(a[2], b[2]) - max(a[0], b[0]) > 1e-6 and min(a[3], b[3]) - max(a[1], b[1]) > 1e-6
                assert not overlap, (boxes[i][0].plain, boxes[j][0].plain)


@pytest.mark.parametrize("lang", ["en", "ru", "uk"])
def test_texts_do_not_collide_or_leave_the_frame(forging, lang):
    _check_texts(forging[1][lang])


TASKS = sorted(p.stem for p in (ROOT / "tasks").glob("*.yaml"))


@functools.lru_cache(maxsize=None)
def example_drawn(name: str, shared_once) -> dict:
    """{lang: (sheets, panels)}: build_sheets(results, task, lang) of tasks/<name>.yaml for en,
    ru, uk (an empty list: no sheets) and the force drawings' panels as the sheets drew them
    (tests/figure_record.py's ForceRecorder: the groups, polygons and lever of sheet 2), made
    once per test process and shared by the tests that read every example's sheets (a sheet's
    info holds local classes: not pickled to share them between the processes); the results
    `tmm run` computes, once per session (tests/pdf_extent.py)."""
    from figure_record import ForceRecorder
    from pdf_extent import results

    from tmm_cli.sheets import build_sheets
    task, res = results(shared_once, name)
    out = {}
    for lang in ("en", "ru", "uk"):
        with pytest.MonkeyPatch.context() as mp:
            rec = ForceRecorder(mp)
            out[lang] = (build_sheets(res, task, lang), rec.panels)
    return out


@functools.lru_cache(maxsize=None)
def example_sheets(name: str, shared_once) -> dict:
    """{lang: the sheets of tasks/<name>.yaml} (:func:`example_drawn`)."""
    return {lang: sheets for lang, (sheets, _) in example_drawn(name, shared_once).items()}


@pytest.mark.parametrize("name", TASKS)
def test_texts_of_every_examples_sheets(name, shared_once):
    """Every sheet of every example task, in en, ru and uk (the kinetostatics sheet's lever
    and groups, the cam's and the gears' sheets included): no two texts overlap, none
    leaves the frame."""
    for lang, sheets in example_sheets(name, shared_once).items():
        _check_texts(sheets)


def test_sheet_texts_in_every_language():
    """Every sheet table has the keys of English in ru and uk; the Ukrainian sheets carry no
    Russian-only letter (ы, э, ъ, ё)."""
    import importlib
    for name, attr in (("", "SHEETS"), (".frame", "TB_TEXT"), (".sheet1", "TXT"), (".sheet1", "UNITS"),
                       (".sheet2", "TXT"), (".sheet3", "TXT"), (".sheet4", "TXT"), (".sheet5", "TXT")):
        table = getattr(importlib.import_module("tmm_cli.sheets" + name), attr)
        for lang in ("ru", "uk"):
            assert set(table["en"]) == set(table[lang]), (name, attr, lang)
        assert not any(set(str(v)) & set("ыэъёЫЭЪЁ") for v in table["uk"].values()), (name, attr)


@pytest.mark.parametrize("name", ["press_offset_slider_crank", "crank_rocker_fourbar", "shaper_slotted_ram"])
def test_other_linkages(name):
    """An extra position next to a grid one (press), a rocker output (ψ, ω, ε), a slotted lever."""
    import io
    import ezdxf
    from tmm_cli.pipeline import run
    from tmm_cli.sheets import build_sheets
    from tmm_cli.task import load_task
    task = load_task(ROOT / "tasks" / f"{name}.yaml")
    sheets = build_sheets(run(task), task, "ru")
    assert sheets
    _check_texts(sheets)
    for cv, info in sheets:
        assert not ezdxf.read(io.StringIO(to_dxf(cv).decode())).audit().has_errors
        for key in ("s", "v", "a"):
            if "diagrams" in info:
                assert _mantissa_ok(info["diagrams"][key]["mu"])


def test_title_block(forging):
    _, sheets = forging
    tb = sheets["ru"][0][1]["title_block"]
    assert tb["title"] == "Horizontal forging machine"
    assert tb["variant"] == 7
    assert (tb["sheet"], tb["sheets"]) == (1, len(sheets["ru"]))
    assert tb["scale"] == sheets["ru"][0][1]["mechanism"]["scale"]
    texts = {p.plain for p in sheets["ru"][0][0].prims if isinstance(p, Text)}
    # the code in the drawing's letters: Cyrillic ТММ on a Russian sheet
    assert {"Вариант 7", "Лист 1", f"Листов {tb['sheets']}", tb["scale"], "ТММ.7.01", "Разраб."} <= texts


def test_cli_sheets_writes_files(tmp_path):
    from typer.testing import CliRunner
    from tmm_cli.cli import app
    r = CliRunner().invoke(app, ["sheets", str(ROOT / "tasks" / "forging_sixbar.yaml"), "--out", str(tmp_path),
                                 "--format", "svg,dxf"])
    assert r.exit_code == 0, r.output
    assert (tmp_path / "sheet-1.svg").read_text().count("<text") > 50
    assert (tmp_path / "sheet-1.dxf").stat().st_size > 10000
    assert not (tmp_path / "sheets.pdf").exists()


def test_dynamics_sheet(forging):
    res, sheets = forging
    dyn = [info for _, info in sheets["en"] if info["number"] == 3]
    assert len(dyn) == 1
    info = dyn[0]
    assert info["title_block"]["sheet"] == 3 and info["title_block"]["sheets"] == 3
    for sym, g in info["graphs"].items():
        assert _mantissa_ok(g["mu"])
        for pts, vals in zip(g["pts"], g["values"]):
            assert abs(pts[:, 1] - g["origin"][1] - vals / g["mu"]).max() < 1e-9
    em = info["energy_mass"]
    assert _mantissa_ok(em["mu_T"]) and _mantissa_ok(em["mu_J"])
    # the tangents touch the drawn diagram and leave it on one side:
    # max(ΔT - J ω_max²/2) = a, min(ΔT - J ω_min²/2) = b, here measured on the sheet in mm
    (a, sa), (b, sb) = em["tangents"]
    x = (em["pts"][:, 0] - em["origin"][0]) * em["mu_J"]
    y = (em["pts"][:, 1] - em["origin"][1]) * em["mu_T"]
    # (a, b come from the extrema located between the grid's nodes, so the drawn polygon,
    # through the nodes, lies on the inner side and within the grid's own second-order gap)
    assert max(y - sa * x) <= a + 1e-9 * abs(a) and max(y - sa * x) == pytest.approx(a, rel=1e-4)
    assert min(y - sb * x) >= b - 1e-9 * abs(b) and min(y - sb * x) == pytest.approx(b, rel=1e-4)
    fw = res["flywheel"]
    assert sa == pytest.approx(fw["energy_mass"]["omega_max"] ** 2 / 2)
    # the course's dynamics sheet: J_red(φ) and ω(φ) (about ωm) beside M, A, ΔT, each at value / μ
    assert list(info["graphs"]) == ["M", "A", "ΔT", "J", "Δω"]
    arr = fw["arrays"]
    assert np.array_equal(info["graphs"]["J"]["values"][0], np.asarray(arr["J_red"], float))
    assert np.allclose(info["graphs"]["Δω"]["values"][0] + fw["omega_m"], np.asarray(arr["omega"], float))


@pytest.mark.parametrize("name", [n for n in TASKS if "\nflywheel:" in (ROOT / "tasks" / f"{n}.yaml").read_text(encoding="utf-8")])
def test_dynamics_curves_span_their_axes_and_no_more(name, shared_once):
    """Each curve of the dynamics sheet runs the whole φ axis and stops at its end, left of
    the energy-mass diagram, its ticks in degrees of the cycle: the four-stroke engine's
    720° were drawn at 1 °/mm, their second turn 360 mm past the axis and across the
    energy-mass diagram. Now μφ = 2 °/mm there (360 mm for the cycle)."""
    cycles = 0
    for lang, sheets in example_sheets(name, shared_once).items():
        for _, info in sheets:
            if "energy_mass" not in info:
                continue
            cycles += 1
            ox = {g["origin"][0] for g in info["graphs"].values()}
            assert len(ox) == 1
            ox = ox.pop()
            end = ox + info["x_len"]
            assert info["x_len"] == pytest.approx(360.0) and _mantissa_ok(info["mu_phi"])
            for sym, g in info["graphs"].items():
                for pts in g["pts"]:
                    assert pts[:, 0].min() == pytest.approx(ox) and pts[:, 0].max() == pytest.approx(end), (lang, sym)
            assert end + 40.0 < info["energy_mass"]["origin"][0]
            # ω about its own mean: a clockwise crank's (ω < 0) drew ω + ωm, 21 rad/s off its axis
            dev = info["graphs"]["Δω"]["values"][0]
            assert abs(np.nanmean(dev)) < np.nanmax(dev) - np.nanmin(dev), (lang, np.nanmean(dev))
            # the lower tangent's intercept b on the ΔT axis, not below its end
            em = info["energy_mass"]
            (b, _), = em["tangents"][1:]
            assert em["origin"][1] + b / em["mu_T"] > em["axis_low"], lang
    assert cycles == 3


def _only_sheet(name, number, lang):
    """(results, canvas, info) of the one sheet of an example task, its labels and its
    ГОСТ 2.302 length scale checked."""
    from tmm_cli.pipeline import run
    from tmm_cli.report.figures import GOST_ENLARGEMENTS, GOST_REDUCTIONS
    from tmm_cli.sheets import build_sheets
    from tmm_cli.task import load_task
    task = load_task(ROOT / "tasks" / f"{name}.yaml")
    res = run(task)
    sheets = build_sheets(res, task, lang)
    assert [i["number"] for _, i in sheets] == [number]
    cv, info = sheets[0]
    _check_texts(sheets)
    unit = info["unit"]
    assert any(abs(unit - n) < 1e-12 for n in GOST_REDUCTIONS) or any(
        abs(unit - 1 / n) < 1e-12 for n in GOST_ENLARGEMENTS)
    assert info["title_block"]["scale"] == info["scale"]
    return res, cv, info


@pytest.mark.parametrize("name", ["cam_offset", "cam_rocker", "cam_flat"])
def test_cam_sheet(name, tmp_path):
    import ezdxf
    from tmm_cli.sheets import write_sheets
    res, cv, info = _only_sheet(name, 4, "en")
    unit = info["unit"]
    # a pitch-profile point lies r / unit mm from the cam's centre (r in model mm)
    r = math.hypot(*info["pitch"][7]) * 1000.0
    assert math.hypot(*(info["pitch_pts"][7] - info["O"])) == pytest.approx(r / unit, rel=1e-12)
    # the base circle r0 is drawn at r0 / unit
    circles = [p.r for p in cv.prims if isinstance(p, Circle)]
    assert any(abs(rc - res["cam"]["r0"] * 1000.0 / unit) < 1e-9 for rc in circles)
    for g in info["graphs"].values():
        assert _mantissa_ok(g["mu"])
        assert abs(g["pts"][:, 1] - g["origin"][1] - g["values"] / g["mu"]).max() < 1e-9
    paths = write_sheets([(cv, info)], tmp_path, {"dxf"})
    doc = ezdxf.readfile(paths[0])
    assert not doc.audit().has_errors
    assert len(doc.modelspace().query("LWPOLYLINE[layer=='contour']")) >= 4   # the profile and 3 curves


@pytest.mark.parametrize("name", ["gears_shifted", "gears_zero"])
def test_gear_sheet(name, tmp_path):
    import ezdxf
    from tmm_cli.sheets import write_sheets
    res, cv, info = _only_sheet(name, 5, "ru")
    g = res["gears"]
    unit = info["unit"]
    # the circles at r / unit; the centres aw / unit apart; N1N2 on the sheet = N1N2 / unit
    circles = sorted(p.r for p in cv.prims if isinstance(p, Circle) and p.r > 2.0)
    want = sorted(g[k][i] * 1000.0 / unit for k in ("rw", "r", "rb", "ra", "rf") for i in (0, 1))
    assert circles == pytest.approx(want, rel=1e-12)
    pts = info["points"]
    assert math.hypot(*(pts["N2"] - pts["N1"])) == pytest.approx(g["line_of_action"]["N1N2"] * 1000 / unit,
                                                                 rel=1e-9)
    # N1 is the foot of the perpendicular from O1 on the line of action: O1N1 = rb1
    M = info["M"]
    assert math.hypot(*(pts["N1"] - M((0.0, 0.0)))) == pytest.approx(g["rb"][0] * 1000 / unit, rel=1e-9)
    doc = ezdxf.readfile(write_sheets([(cv, info)], tmp_path, {"dxf"})[0])
    assert not doc.audit().has_errors
    assert len(doc.modelspace().query("CIRCLE[layer=='thin']")) == 10


def _gost_length(mu_l: float) -> bool:
    from tmm_cli.report.figures import GOST_ENLARGEMENTS, GOST_REDUCTIONS
    unit = mu_l * 1000.0
    return any(abs(unit - n) < 1e-9 * n for n in GOST_REDUCTIONS) or any(
        abs(unit - 1 / n) < 1e-12 for n in GOST_ENLARGEMENTS)


@pytest.mark.parametrize("lang", ["en", "ru", "uk"])
def test_kinetostatics_sheet(forging, lang, tmp_path):
    """Sheet 2: every group's polygon is its forces from results.json head to tail, each
    |F| / μF mm long, closing; scales standard; DXF re-reads with the counts drawn."""
    import ezdxf
    import numpy as np
    from tmm_cli.sheets import write_sheets
    from tmm_cli.sheets.frame import TB_H, TB_W
    from tmm_cli.sheets.sheet1 import course_positions
    res, sheets = forging
    cv, info = next((c, i) for c, i in sheets[lang] if i["number"] == 2)
    assert info["title_block"]["sheet"] == 2
    # the positions of the plans on sheet 1: the most loaded one and the first one
    kst = res["kinetostatics"]
    loaded = max(kst, key=lambda k: abs(k["balancing_moment"]))["index"]
    assert list(info["positions"]) == course_positions(res) == [loaded, kst[0]["index"]]
    info_k = res["kinetostatics_info"]
    idx = {l["name"]: l["index"] for l in res["structure"]["links"]}
    for i, p in info["positions"].items():
        e = next(k for k in kst if k["index"] == i)
        assert len(p["groups"]) == len(info_k["groups"])
        for d in p["groups"]:
            g = {idx[n] for n in d["group"]}
            # the forces on the group, read from results.json here: its loads and the reactions
            # of the pairs joining it to the rest (R_ij on j; R_ji = -R_ij)
            want = {f["name"]: np.array(f["F"]) for f in e["loads"] if idx[f["link"]] in g}
            for j in info_k["joints"]:
                a, b = j["a"], j["b"]
                r = e["reactions"][j["key"]]
                if b in g and a not in g:
                    want[f"R{a}{b}"] = np.array([r["x"], r["y"]])
                elif a in g and b not in g:
                    want[f"R{b}{a}"] = -np.array([r["x"], r["y"]])
            Fmax = max(np.hypot(*F) for F in want.values())
            want = {n: F for n, F in want.items() if np.hypot(*F) > 1e-9 * Fmax}
            assert {n for n, _, _ in d["vectors"]} == set(want)
            T, mu = d["tips"], d["mu_F"]
            assert _mantissa_ok(mu) and _gost_length(d["mu_l"])
            for (name, _, _), seg in zip(d["vectors"], np.diff(T, axis=0)):
                assert np.hypot(*seg) == pytest.approx(np.hypot(*want[name]) / mu, rel=1e-9)
                assert np.allclose(seg * mu, want[name], atol=1e-9 * Fmax)
            assert np.hypot(*(T[-1] - T[0])) < 0.01          # the polygon closes (mm)
            assert np.ptp(T, axis=0).max() > 40.0             # and is drawn large
        assert _mantissa_ok(p["mu_v"])
        # the lever: at least 280 mm wide, clear of the title block
        lx, ly, lw, lh = p["lever_box"]
        assert lw >= 280.0 and lh > 150.0
        assert ly >= FRAME[1] + TB_H or lx + lw <= FRAME[2] - TB_W
    texts = {t.plain for t in cv.prims if isinstance(t, Text)}
    from tmm_cli.numfmt import localize
    from tmm_cli.report.context import fmt
    for e in (k for k in kst if k["index"] in info["positions"]):
        assert any(localize(fmt(e["balancing_moment"], 5), lang) in t for t in texts)   # ru, uk: 0,5
    _check_texts([(cv, info)])
    path = write_sheets([(cv, info)], tmp_path, {"dxf"})[0]
    doc = ezdxf.readfile(path)
    assert not doc.audit().has_errors
    want = Counter()
    for p in dxf_entities(cv):
        kind = {Line: "LINE", Circle: "CIRCLE", Arc: "ARC", Text: "TEXT"}.get(type(p))
        if kind is None:
            kind = "SOLID" if p.fill and len(p.pts) in (3, 4) else "LWPOLYLINE"
        want[kind] += 1
    assert Counter(e.dxftype() for e in doc.modelspace()) == want
    assert want["SOLID"] > 40 and want["TEXT"] > 100      # arrow heads; labels


def _chain(k: int) -> dict:
    """A crank driving a chain of ``k`` <= 8 RRP dyads (rods 0.2 m), each slider on its own
    guide, alternately horizontal (y = 0, 0.3, 0.55, 0.8) and vertical (x = 0.3, 0.55, 0.8,
    1.05): k Assur groups of class II."""
    guides = [(0, 0.0), (90, 0.3), (0, 0.3), (90, 0.55), (0, 0.55), (90, 0.8), (0, 0.8), (90, 1.05)]
    near = [(0.25, 0), (0.3, 0.15), (0.45, 0.3), (0.55, 0.45), (0.7, 0.55), (0.8, 0.7), (0.95, 0.8), (1.05, 0.95)]
    links = {"crank": {"points": ["O", "P0"], "length": 0.05}}
    for i, (angle, at) in enumerate(guides[:k], start=1):
        links[f"rod{i}"] = {"points": [f"P{i - 1}", f"P{i}"], "length": 0.2}
        links[f"s{i}"] = {"slider": f"P{i}", "guide": {"through": [0, at] if angle == 0 else [at, 0], "angle": angle}}
    assembly = {f"P{i}": list(p) for i, p in enumerate(near[:k], start=1)}
    return {"schema": "tmm/1", "title": f"a chain of {k} dyads",
            "mechanism": {"ground": {"O": [0, 0]}, "links": links, "assembly": assembly},
            "drive": {"link": "crank", "speed": "100 rpm", "direction": "ccw"},
            "positions": {"output": "s1", "working": "forward"},
            "loads": {"forces": [{"on": f"s{k}", "kind": "resistance", "magnitude": 500}]},
            "kinetostatics": {"inertia": False}}


def test_kinetostatics_sheet_wraps_many_groups():
    """Sheet 2 with more groups than fit side by side at MIN_COL_W: they wrap into rows;
    every group's panels keep MIN_COL_W, stay inside their position's band and the frame,
    and overlap neither each other nor the lever."""
    from tmm_cli.pipeline import run
    from tmm_cli.sheets import build_sheets, sheet2
    from tmm_cli.task import load_task
    assert sheet2.layout(4, 536.0) == (4, 1)                      # 4 x 130 mm fit in one row
    assert sheet2.layout(9, 536.0) == (7, 2)                      # 536 // 70 = 7 columns, 2 rows
    task = load_task(_chain(8))
    res = run(task)
    assert len(res["structure"]["groups"]) == 8
    cv, info = next((c, i) for c, i in build_sheets(res, task, "en") if i["number"] == 2)
    for p in info["positions"].values():
        boxes = [d["box"] for d in p["groups"]]
        assert len(boxes) == 9                                    # 8 groups and the input link
        lx, ly, lw, lh = p["lever_box"]
        for k, (x, y, w, h) in enumerate(boxes):
            assert w >= sheet2.MIN_COL_W - 1e-9 and h > 100.0
            assert FRAME[0] <= x and x + w <= lx and FRAME[1] <= y
            for x2, y2, w2, h2 in boxes[k + 1:]:
                assert min(x + w, x2 + w2) - max(x, x2) <= 1e-6 or min(y + h, y2 + h2) - max(y, y2) <= 1e-6
    _check_texts([(cv, info)])


def test_sheets_pdf_by_typst(forging, tmp_path):
    """sheets.pdf: one A1 page per sheet, compiled by Typst (no weasyprint), the SVG of each
    sheet drawn at its real size with its texts kept as text (every word of the sheet's
    labels is on its page; a subscript joins the word before it)."""
    import re
    import shutil
    import subprocess
    import sys
    from tmm_cli.sheets import write_sheets
    _, sheets = forging
    sh = sheets["ru"]
    written = write_sheets(sh, tmp_path, {"pdf"})
    pdf = tmp_path / "sheets.pdf"
    assert written == [pdf] and pdf.read_bytes().startswith(b"%PDF")
    if not (shutil.which("pdfinfo") and shutil.which("pdftotext")):
        pytest.skip("poppler-utils not installed")
    info = subprocess.run(["pdfinfo", str(pdf)], capture_output=True, text=True, check=True).stdout
    assert int(re.search(r"Pages:\s+(\d+)", info).group(1)) == len(sh)
    w, h = map(float, re.search(r"Page size:\s+([0-9.]+) x ([0-9.]+) pts", info).groups())
    assert (w, h) == pytest.approx((841 * 72 / 25.4, 594 * 72 / 25.4), abs=0.1)
    for k, (cv, info_k) in enumerate(sh, start=1):
        page = subprocess.run(["pdftotext", "-f", str(k), "-l", str(k), str(pdf), "-"], capture_output=True,
                              text=True, check=True).stdout
        want = {wd for p in cv.prims if isinstance(p, Text) for wd in p.s.split()}
        assert len(want) > 20 and [wd for wd in want if wd not in page] == []
        assert f"Лист {k}" in page
    code = ("import sys\nfrom pathlib import Path\nfrom tmm_cli.pipeline import run\n"
            "from tmm_cli.sheets import build_sheets, write_sheets\nfrom tmm_cli.task import load_task\n"
            f"t = load_task(Path({str(ROOT / 'tasks' / 'forging_sixbar.yaml')!r}))\n"
            f"write_sheets(build_sheets(run(t), t, 'en'), Path({str(tmp_path / 'en')!r}), {{'pdf'}})\n"
            "print('weasyprint' in sys.modules)\n")
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr
    assert p.stdout.strip() == "False" and (tmp_path / "en" / "sheets.pdf").stat().st_size > 20000


GOST_2304 = (2.5, 3.5, 5.0, 7.0, 10.0, 14.0)


def test_most_examples_have_sheets(shared_once):
    """The lettering test below reads sheets: most example tasks have them (in every language)."""
    have = [name for name in TASKS if all(example_sheets(name, shared_once).values())]
    assert len(have) >= 20, have


def _dxf_text_heights(text: str) -> list[float]:
    """The height (group code 40) of every TEXT entity of a DXF file's ENTITIES section, read
    from its (group code, value) line pairs (a full ezdxf read of every example's sheets took
    8 s of the suite's CPU for these numbers)."""
    lines = text.splitlines()
    pairs = zip(lines[0::2], lines[1::2])
    out, section, entity = [], None, None
    for code, value in ((c.strip(), v.strip()) for c, v in pairs):
        if code == "2" and entity == "SECTION":
            section = value
        if code == "0":
            entity = value
        elif code == "40" and entity == "TEXT" and section == "ENTITIES":
            out.append(float(value))
    return out


def test_dxf_text_heights_reads_what_ezdxf_reads(shared_once):
    """The reader of the lettering test against ezdxf's, on the forging machine's sheets."""
    import io

    import ezdxf
    for cv, _ in example_sheets("forging_sixbar", shared_once)["en"]:
        text = to_dxf(cv).decode()
        doc = ezdxf.read(io.StringIO(text))
        assert sorted(_dxf_text_heights(text)) == sorted(t.dxf.height for t in doc.modelspace().query("TEXT"))


@pytest.mark.parametrize("name", TASKS)
def test_lettering_in_gost_sizes(name, shared_once):
    """Every text of every sheet (its capitals) in a ГОСТ 2.304 size: measured in the SVG
    (font-size x the capitals of DejaVu Sans, 1493/2048 em), in the DXF (TEXT height) and
    in the primitives; a subscript 0.72 of its text: 1.8 mm (ГОСТ 2.304's size for
    indices) under 2.5, 2.5 under 3.5."""
    import re

    from tmm_cli.sheets.writers import to_svg
    cap = 1493.0 / 2048.0
    for lang, sheets in example_sheets(name, shared_once).items():
        for cv, info in sheets:
            where = (name, lang, info["number"])
            heights = {round(p.cap, 6) for p in cv.prims if isinstance(p, Text)}
            assert heights and heights <= set(GOST_2304), (where, heights)
            svg = to_svg(cv)
            mains = {round(float(f) * cap, 3) for f in re.findall(r'<text [^>]*font-size="([0-9.]+)"', svg)}
            assert all(min(abs(h - g) for g in GOST_2304) <= 0.02 for h in mains), (where, mains)
            subs = {round(float(f) * cap, 3) for f in re.findall(r'<tspan [^>]*font-size="([0-9.]+)"', svg)}
            assert all(min(abs(h - g) for g in (1.8, *GOST_2304)) <= 0.06 for h in subs), (where, subs)
            if lang == "en":
                dxf = {round(h, 4) for h in _dxf_text_heights(to_dxf(cv).decode())}
                assert dxf and dxf <= set(GOST_2304), (where, dxf)


@pytest.mark.parametrize("lang", ["en", "ru", "uk"])
def test_planetary_only_task_writes_a_sheet(lang):
    """A task with only a planetary section: its sheet (scheme at a ГОСТ scale, the picture of
    linear velocities on the same radii at a standard μv) - each point at v/μv from the v axis
    and at r/μl above the axis as in the scheme, i1H read from the drawn lines."""
    import io

    import ezdxf
    from tmm_cli.pipeline import run
    from tmm_cli.sheets import SHEETS, build_sheets
    from tmm_cli.task import load_task
    task = load_task(ROOT / "tasks" / "planetary_A.yaml")
    res = run(task)
    sheets = build_sheets(res, task, lang)
    assert [info["number"] for _, info in sheets] == [6]
    cv, info = sheets[0]
    assert info["title_block"]["sheet_title"] == SHEETS[lang][6]
    assert info["title_block"]["scale"] == info["scale"] and _mantissa_ok(info["mu_v"])
    _check_texts(sheets)
    assert not ezdxf.read(io.StringIO(to_dxf(cv).decode())).audit().has_errors
    vp = res["planetary"]["velocity_plan"]
    vx = info["points"]["O"][0]
    for q in vp["points"]:
        x, y = info["points"][q["name"].split()[0]]
        assert x - vx == pytest.approx(q["v"] / info["mu_v"], abs=1e-9)
        assert y - info["axis_y"] == pytest.approx(q["y"] * 1000.0 / info["unit"], abs=1e-9)
    # the wheels of the scheme on the same radii: wheel 1 from the axis to point A's height
    assert info["wheels"]["1"][3] == pytest.approx(info["points"]["A"][1], abs=1e-9)

    def tan(seg):                      # v per radius of a drawn line, as the scales make it
        (xa, ya), (xb, yb) = seg
        return (xb - xa) * info["mu_v"] / ((yb - ya) * info["unit"] / 1000.0)
    assert tan(info["lines"]["1"]) / tan(info["lines"]["H"]) == pytest.approx(res["planetary"]["ratio"], rel=1e-9)


@pytest.mark.parametrize("lang", ["en", "ru", "uk"])
def test_differential_sheet(lang):
    """tasks/differential_A.yaml (z 27-30-87, m 2 mm, n1 = 1000 rpm, n3 = -200 rpm): sheet 7 alone,
    each point of the velocity picture at v/μv from the v axis (left for a negative speed) and at
    r/μl above the axis, and Willis' ratio read from the drawn lines: by hand u = -z3/z1 = -87/27,
    ωH = (ω1 - u ω3)/(1 - u) = (1000 + 87/27 (-200))/(1 + 87/27) rpm = 84.2105 rpm; each line's
    tangent in proportion to its member's speed."""
    import io

    import ezdxf
    from tmm_cli.pipeline import run
    from tmm_cli.sheets import SHEETS, build_sheets
    from tmm_cli.sheets.sheet7 import tangents
    from tmm_cli.task import load_task
    task = load_task(ROOT / "tasks" / "differential_A.yaml")
    res = run(task)
    sheets = build_sheets(res, task, lang)
    assert [info["number"] for _, info in sheets] == [7]
    cv, info = sheets[0]
    assert info["title_block"]["sheet_title"] == SHEETS[lang][7]
    _check_texts(sheets)
    assert not ezdxf.read(io.StringIO(to_dxf(cv).decode())).audit().has_errors
    vp = res["differential"]["velocity_plan"]
    vx = info["points"]["O"][0]
    assert min(q["v"] for q in vp["points"]) < 0
    for q in vp["points"]:
        x, y = info["points"][q["name"].split()[0]]
        assert x - vx == pytest.approx(q["v"] / info["mu_v"], abs=1e-9)
        assert y - info["axis_y"] == pytest.approx(q["y"] * 1000.0 / info["unit"], abs=1e-9)
    u = -87 / 27
    nH = (1000 - u * (-200)) / (1 - u)
    assert nH == pytest.approx(84.2105263, rel=1e-8)
    tg = tangents(info)
    assert info["u_plan"] == pytest.approx(u, rel=1e-9)
    assert (tg["1"] - tg["H"]) / (tg["3"] - tg["H"]) == pytest.approx(u, rel=1e-9)
    assert tg["H"] / tg["1"] == pytest.approx(nH / 1000, rel=1e-9)
    assert tg["3"] / tg["1"] == pytest.approx(-200 / 1000, rel=1e-9)
    # every drawn item on the sheet inside the frame
    x0, y0, x1, y1 = FRAME
    for name, (x, y) in info["points"].items():
        assert x0 < x < x1 and y0 < y < y1, name


@pytest.mark.parametrize("lang", ["en", "ru", "uk"])
def test_balancing_sheet(lang):
    """tasks/balancing_fourbar.yaml: sheet 8 (after kinematics and kinetostatics) - the linkage's
    points at position 0 at μl, each counterweight's disc at r/μl from its pivot at its angle from
    the link's axis; the hodograph's marks at (Fx, Fy)/μF from its origin; the rotor's polygons, one
    per correction plane, of the imbalances reduced by hand (U_i (z2 - z_i)/(z2 - z1) and
    U_i (z_i - z1)/(z2 - z1), U_i = m_i r_i e^{i angle_i} from the task), each vector |U|/μ long,
    each closed by its correction."""
    import io

    import ezdxf
    from tmm_cli.pipeline import run
    from tmm_cli.sheets import SHEETS, build_sheets
    from tmm_cli.task import load_task
    task = load_task(ROOT / "tasks" / "balancing_fourbar.yaml")
    res = run(task)
    sheets = build_sheets(res, task, lang)
    assert [info["number"] for _, info in sheets] == [1, 2, 8]
    cv, info = sheets[2]
    assert info["title_block"]["sheet_title"] == SHEETS[lang][8]
    _check_texts([sheets[2]])
    assert not ezdxf.read(io.StringIO(to_dxf(cv).decode())).audit().has_errors
    lk, e0 = info["linkage"], res["kinematics"][0]["points"]
    k = 1000.0 / lk["unit"]
    O = np.array([e0["O"]["x"], e0["O"]["y"]])
    for p in ("A", "B", "O3"):
        d = np.array([e0[p]["x"], e0[p]["y"]]) - O
        assert lk["points"][p] - lk["points"]["O"] == pytest.approx(d * k, abs=1e-9)
    for role, pivot, other in (("crank", "O", "A"), ("rocker", "O3", "B")):
        c = res["balancing"]["counterweights"][role]
        P, Q = (np.array([e0[q]["x"], e0[q]["y"]]) for q in (pivot, other))
        th = math.atan2(Q[1] - P[1], Q[0] - P[0]) + math.radians(c["angle"])
        want = lk["points"][pivot] + c["r"] * k * np.array([math.cos(th), math.sin(th)])
        assert lk["discs"][role][0] == pytest.approx(want, abs=1e-9)
    h = info["hodograph"]
    for s in res["balancing"]["shaking"]:
        i = res["positions"]["index"][res["balancing"]["shaking"].index(s)]
        assert h["marks"][i] - h["origin"] == pytest.approx(np.array([s["Fx"], s["Fy"]]) / h["mu_F"], abs=1e-9)
    # the rotor, by hand from the task's masses and planes [0, 0.3]
    masses = [(0.2, 0.10, 30, 0.05), (0.15, 0.08, 150, 0.15), (0.1, 0.12, 260, 0.25)]
    U = [m * r * complex(math.cos(math.radians(a)), math.sin(math.radians(a))) for m, r, a, _ in masses]
    z1, z2 = 0.0, 0.3
    planes = [[u * (z2 - z) / (z2 - z1) for u, (*_, z) in zip(U, masses)],
              [u * (z - z1) / (z2 - z1) for u, (*_, z) in zip(U, masses)]]
    rot = info["rotor"]
    for poly, us, corr in zip(rot["polygons"], planes, res["balancing"]["rotor"]["corrections"]):
        assert len(poly) == len(us) + 2
        for i, u in enumerate(us):
            assert np.hypot(*(poly[i + 1] - poly[i])) == pytest.approx(abs(u) / rot["mu_U"], rel=1e-9)
        assert poly[-1] == pytest.approx(poly[0], abs=1e-9)               # the correction closes it
        assert np.hypot(*(poly[-1] - poly[-2])) == pytest.approx(corr["mr"] / rot["mu_U"], rel=1e-9)
    x0, y0, x1, y1 = FRAME
    for poly in rot["polygons"]:
        assert (poly[:, 0] > x0).all() and (poly[:, 0] < x1).all() and (poly[:, 1] > y0).all() and (poly[:, 1] < y1).all()


@pytest.mark.parametrize("name", ["gears_shifted", "gears_zero"])
def test_gear_sheet_teeth_closed(name):
    """Each wheel's window of teeth one closed main-line contour: every tooth, the end ones too,
    bounded by its two flanks (each crossing the pitch circle once) and the root circle
    under it; nothing inside the root circle or outside the tip circle."""
    from tmm_cli.sheets.sheet5 import TEETH
    res, cv, info = _only_sheet(name, 5, "en")
    g, M, unit = res["gears"], info["M"], info["unit"]
    teeth = [p for p in cv.prims if isinstance(p, Polyline) and p.layer == "contour" and len(p.pts) > 100]
    assert len(teeth) == 2
    centres = [M((0.0, 0.0)), M((0.0, g["aw"]))]
    for i, (p, c) in enumerate(zip(teeth, centres)):
        assert p.closed
        P = np.asarray(p.pts)
        r = np.hypot(*(P - c).T)
        rf, ra, rp = (g[k][i] * 1000.0 / unit for k in ("rf", "ra", "r"))
        assert r.min() >= rf * (1 - 1e-9) and r.max() <= ra * (1 + 1e-9)
        closing = [P[-1], P[0]]               # the closing segment lies on the root circle too
        assert [math.hypot(*(q - c)) for q in closing] == pytest.approx([rf, rf], rel=1e-9)
        assert math.hypot(*(P[-1] - P[0])) < 0.02 * rf     # a short chord of the arc, not across
        crossings = np.count_nonzero(np.diff(np.sign(r - rp)) != 0)
        assert crossings == 2 * TEETH, crossings


@pytest.mark.parametrize("name", ["cam_offset", "cam_rocker", "cam_knife"])
def test_cam_sheet_r0_construction(name):
    """The s - ds/dφ construction of r0 on the cam sheet: the points D of the rise and the
    return at one ГОСТ 2.302 scale from O, O B0 = r0 at that scale, each tangent at the allowed
    pressure angle drawn through its point along its direction."""
    res, cv, info = _only_sheet(name, 4, "ru")
    c, k = res["cam"], res["cam"]["construction"]
    d = info["construction"]
    unit, O = d["unit"], d["O"]
    assert _gost_length(unit / 1000.0)
    for phase in ("rise", "return"):
        want = O + np.asarray(k[f"D_{phase}"]) * 1000.0 / unit
        assert np.allclose(d["D"][phase], want, atol=1e-9)
    assert math.hypot(*(d["B0"] - O)) == pytest.approx(float(c["r0"]) * 1000.0 / unit, rel=1e-6)
    assert len(d["tangents"]) == len(k["tangents"])
    for (p, q), t in zip(d["tangents"], k["tangents"]):
        u = np.asarray(t["direction"], float)
        at = O + np.asarray(t["point"], float) * 1000.0 / unit
        for end in (p, q):                               # both ends on the line through the point
            w = np.asarray(end) - at
            assert abs(u[0] * w[1] - u[1] * w[0]) < 1e-6


@pytest.mark.parametrize("name", ["cam_translating", "cam_chosen_size", "cam_knife", "cam_offset", "cam_rocker"])
def test_cam_construction_as_large_as_the_sheet_allows_and_clear_of_the_title_block(name):
    """The s - ds/dφ construction was fitted to the box above the title block only, anchored in
    its corner: the central cam's tall diagram came out at 1:1 beside room for 2:1 left of the
    title block. Now the larger of the two boxes' scales: at the next larger GOST 2.302 scale
    the diagram would fit neither; every point drawn stays in the frame, clear of the title block."""
    from tmm_cli.report.figures import GOST_ENLARGEMENTS, GOST_REDUCTIONS
    from tmm_cli.sheets.frame import FRAME, TB_H, TB_W
    res, cv, info = _only_sheet(name, 4, "en")
    d, k = info["construction"], res["cam"]["construction"]
    pts = np.vstack([*d["D"].values(), d["O"], d["B0"], *[np.asarray(t) for t in d["tangents"]]])
    x0f, y0f, x1f, y1f = FRAME
    assert (pts[:, 0] > x0f).all() and (pts[:, 0] < x1f).all() and (pts[:, 1] > y0f).all(), name
    in_block = (pts[:, 0] > x1f - TB_W) & (pts[:, 1] < y0f + TB_H)
    assert not in_block.any(), pts[in_block][:3]
    # one step larger (the next smaller model-mm per sheet-mm): the D curves' extent too big for
    # the taller box (left of the title block, up to the profile) and the wider one alike
    scales = sorted({*GOST_REDUCTIONS, *(1.0 / n for n in GOST_ENLARGEMENTS)})
    larger = max(u for u in scales if u < d["unit"] - 1e-12)
    lo, hi = np.asarray(k["box"][:2], float), np.asarray(k["box"][2:], float)
    if k.get("A") is not None:
        lo, hi = np.minimum(lo, k["A"]), np.maximum(hi, k["A"])
    size = (hi - lo) * 1000.0 / larger
    # the two boxes (w, h) the sheet gives it below the profile (from y = 300 mm down): the whole
    # width above the title block, and left of the title block down to the frame
    boxes = [(x1f - 440.0 - 5.0, 300.0 - y0f - TB_H - 12.0), (x1f - TB_W - 440.0 - 5.0, 300.0 - y0f - 12.0)]
    assert not any(size[0] <= w - 20.0 and size[1] <= h - 22.0 for w, h in boxes), (name, size, boxes)


@pytest.mark.parametrize("name", ["forging_sixbar", "crank_rocker_fourbar"])
def test_chord_method_check_on_sheet1(name):
    """The output's v (ω) and a (ε) diagrams carry the chord-method differentiation of the
    diagram above (12 intervals, at the middles, dashed) drawn at the diagram's μ, and its
    greatest deviation from the exact curve; refined, the chord method meets the exact curve
    (its ω and, for a rocker, degrees per radian are right)."""
    from tmm_cli.pipeline import run
    from tmm_cli.sheets import build_sheets
    from tmm_cli.sheets.sheet1 import chord_derivative
    from tmm_cli.task import load_task
    task = load_task(ROOT / "tasks" / f"{name}.yaml")
    res = run(task)
    (cv, info), *_ = build_sheets(res, task, "uk")
    dg = info["diagrams"]
    kc, pos = res["kinematics_curve"], res["positions"]
    sgn = -1.0 if pos.get("direction") == "cw" else 1.0
    phase = (np.asarray(kc["phi"], float) - float(pos["phi0"])) * sgn % 360.0
    o = np.argsort(phase, kind="stable")
    phase = phase[o]
    omega = abs(float(res["kinematics"][0]["links"]["crank"]["omega"]))
    rocker = kc["quantity"] != "slider"
    for key, prev in (("v", "s"), ("a", "v")):
        ch = dg[key]["chord"]
        assert len(ch["phase"]) == 12 and ch["phase"][0] == pytest.approx(15.0)
        exact = np.asarray(kc[key], float)[o]
        ym = float(np.max(np.abs(exact)))
        dev = np.abs(ch["values"] - np.interp(ch["phase"], phase, exact, period=360.0))
        assert ch["error_pct"] == pytest.approx(100 * dev.max() / ym, rel=1e-9)
        assert 0.0 < ch["error_pct"] < 25.0
        ox = ch["pts"][0][0] - ch["phase"][0] / dg["mu_phi"]
        oy = ch["pts"][:, 1] - ch["values"] / dg[key]["mu"]
        assert np.ptp(oy) < 1e-9 and ox == pytest.approx(dg[key]["pts"][0][0] - phase[0] / dg["mu_phi"])
        texts = [p.plain for p in cv.prims if isinstance(p, Text)]
        assert any(f"{ch['error_pct']:.1f} %".replace(".", ",") in t and "хорд" in t for t in texts)   # uk: 0,5 %
        # refined to 360 intervals the chords meet the exact derivative
        mids, d = chord_derivative(phase, np.asarray(kc[prev], float)[o], omega, n=360,
                                   per_deg=rocker and prev == "s")
        fine = np.abs(d - np.interp(mids, phase, exact, period=360.0)).max() / ym
        assert fine < 0.01, fine


@pytest.mark.parametrize("name", ["forging_sixbar", "shaper_slotted_lever", "press_offset_slider_crank"])
def test_sheet1_velocity_plans_of_every_position(name):
    """Sheet 1 as the course sets it: the velocity plans of all 12 positions at one standard
    μv, each at true size (every vector value / μv long) in its own cell clear of the title
    block; the acceleration plans of the two course positions."""
    from tmm_cli.pipeline import run
    from tmm_cli.sheets import build_sheets
    from tmm_cli.sheets.frame import SHEET_W, TB_H, TB_W
    from tmm_cli.task import load_task
    task = load_task(ROOT / "tasks" / f"{name}.yaml")
    res = run(task)
    sheets = build_sheets(res, task, "ru")
    _check_texts(sheets)
    cv, info = sheets[0]
    vp = info["vplans"]
    assert set(range(12)) <= set(vp)
    assert len({d["mu"] for d in vp.values()}) == 1 and _mantissa_ok(next(iter(vp.values()))["mu"])
    for i, d in vp.items():
        assert d["k"] == 1.0
        for v in d["plan"].vecs:
            assert d["plan"].length_mm(v) == pytest.approx(v.value / d["mu"], rel=1e-9, abs=1e-9)
        x, y, w, h = d["box"]
        assert not (x + w > SHEET_W - 5.0 - TB_W and y < 5.0 + TB_H), i       # clear of the title block
    assert len(info["plans"]) == 2 and all(set(p) == {"v", "a"} for p in info["plans"].values())


@pytest.mark.parametrize("name", ["gears_shifted", "gears_zero"])
def test_gear_sheet_sliding_diagrams(name):
    """The gear sheet carries the specific-sliding diagrams λ1, λ2 along the line of action:
    every drawn point at X / μX, λ / μλ from the origin (X at a ГОСТ 2.302 scale, μλ
    standard), B1, P, B2 marked where the results put them."""
    res, cv, info = _only_sheet(name, 5, "uk")
    sl, d = res["gears"]["sliding"], info["sliding"]
    assert _gost_length(d["mu_x"]) and _mantissa_ok(d["mu_lambda"])
    ox, oy = d["origin"]
    for (X, v, _), p in zip(d["curves"], d["pts"]):
        ok = np.isfinite(v)
        assert ok.sum() >= 5 and len(p) == ok.sum()
        assert np.allclose(p[:, 0], ox + X[ok] / d["mu_x"]) and np.allclose(p[:, 1], oy + v[ok] / d["mu_lambda"])
    for k in ("B1", "P", "B2"):
        assert d["marks"][k] == pytest.approx(ox + sl["marks"][k] / d["mu_x"])


@pytest.mark.parametrize("name", ["crank_rocker_fourbar", "forging_sixbar"])
def test_sheet1_coupler_curves(name):
    """The plan of positions carries the trajectories of the moving links' points (the coupler
    curves, centres of mass included): closed curves through the point's place in every grid
    position, drawn at the plan's scale."""
    from tmm_cli.pipeline import run
    from tmm_cli.sheets import build_sheets
    from tmm_cli.task import load_task
    task = load_task(ROOT / "tasks" / f"{name}.yaml")
    res = run(task)
    (cv, info), *_ = build_sheets(res, task, "en")
    mech = info["mechanism"]
    paths = mech["paths"]
    assert paths and any(p.startswith("S") for p in paths)
    if name == "crank_rocker_fourbar":
        assert "M" in paths                                   # the coupler point of the task
    drawn = [p for p in cv.prims if isinstance(p, Polyline) and p.dash == "3 1.5"]
    n = res["positions"]["count"]
    for q, d in paths.items():
        assert len(d["nodes"]) == n
        c = d["curve"]
        assert np.allclose(c[0], c[-1])                       # closed
        for node in d["nodes"]:                               # through every grid position
            assert np.hypot(*(c - node).T).min() < 1e-9
        assert any(len(p.pts) == len(c) and np.allclose(p.pts, c) for p in drawn), q
    # the nodes are the points at the plan's scale: two of them as far apart as in the results
    e0, e1 = res["kinematics"][0], res["kinematics"][1]
    q = next(iter(paths))
    dm = math.hypot(e1["points"][q]["x"] - e0["points"][q]["x"], e1["points"][q]["y"] - e0["points"][q]["y"])
    assert math.hypot(*(paths[q]["nodes"][1] - paths[q]["nodes"][0])) == pytest.approx(dm / mech["mu_l"], rel=1e-9)


@pytest.mark.parametrize("name", ["gears_shifted", "gears_zero"])
def test_gear_sheet_working_parts(name):
    """The working parts of the profiles drawn thick: on each flank of every drawn tooth, its
    points of the tooth outline from the lowest point of contact (gears.lowest_active.r_p) up to
    the tip circle."""
    from tmm_cli.sheets.sheet5 import TEETH
    res, cv, info = _only_sheet(name, 5, "en")
    g = res["gears"]
    thick = [p for p in cv.prims if isinstance(p, Polyline) and p.width == 1.4]
    assert len(thick) == 2 * 2 * TEETH
    for i, c in enumerate((np.zeros(2), np.array([0.0, g["aw"]]))):
        parts = info["drawn"][(i, "working")]
        assert len(parts) == 2 * TEETH
        r_p, ra = g["lowest_active"]["r_p"][i], g["ra"][i]
        for part in parts:
            r = np.hypot(*(part - c).T)
            assert r.min() >= r_p * (1 - 1e-9) and r.max() == pytest.approx(ra, rel=1e-9)
            assert r.min() == pytest.approx(r_p, rel=0.01)            # from the lowest point of contact


def test_sheet1_extra_positions_marked():
    """The extra positions' numbers at the crank pin's circle carry the report's mark (12*)."""
    from tmm_cli.pipeline import run
    from tmm_cli.sheets import build_sheets
    from tmm_cli.task import load_task
    task = load_task(ROOT / "tasks" / "press_offset_slider_crank.yaml")
    res = run(task)
    (cv, info), *_ = build_sheets(res, task, "ru")
    texts = {p.plain for p in cv.prims if isinstance(p, Text)}
    n = res["positions"]["count"]
    extras = [e["index"] for e in res["kinematics"] if e["index"] >= n]
    drawn = {t for t in texts if t.rstrip("*") in {str(i) for i in extras}}
    assert drawn and all(t.endswith("*") for t in drawn), drawn       # (the course ones among them)
    assert {str(i) for i in range(n)} <= texts


@pytest.mark.parametrize("name, shown", [
    ("Ivanov I. I.", "Ivanov I. I."),
    ("\u0418\u0432\u0430\u043d\u043e\u0432 \u0418\u0432\u0430\u043d \u0418\u0432\u0430\u043d\u043e\u0432\u0438\u0447",
     "\u0418\u0432\u0430\u043d\u043e\u0432 \u0418. \u0418."),
    ("Konstantinopolsky-Starodubtsev Alexander Vladimirovich", "Konstantinopolsky-Starodubtsev")])
def test_a_signers_name_stays_in_its_cell(name, shown):
    """The title block's 'developed' row (23 mm): a name is written as given where it fits, else
    as the surname and initials (GOST 2.104's practice), else the surname alone, narrowed to the
    cell -- a full Russian name ran across the signature and date columns into the title."""
    from tmm_cli.pipeline import run
    from tmm_cli.sheets import build_sheets
    from tmm_cli.sheets.frame import TB_W
    from tmm_cli.task import load_task
    from tmm_cli.yamlload import load_yaml
    data, _ = load_yaml(ROOT / "tasks" / "crank_rocker_fourbar.yaml")
    data["student"] = {"name": name, "group": "MM-21"}
    task = load_task(data)
    sheets = build_sheets(run(task), task, "ru")
    _check_texts(sheets)
    cell = (FRAME[2] - TB_W + 17, FRAME[2] - TB_W + 40)        # the surname column, mm
    for cv, _ in sheets:
        texts = [p for p in cv.prims if isinstance(p, Text) and p.plain == shown]
        assert len(texts) == 1, [p.plain for p in cv.prims if isinstance(p, Text)][:40]
        x0, _, x1, _ = texts[0].box()
        assert cell[0] <= x0 and x1 <= cell[1], (x0, x1, cell)


@pytest.mark.parametrize("name, shown", [
    ("Ivanov Ivan Ivanovich", "Ivanov I. I."), ("Ivanov I. I.", "Ivanov I. I."),
    ("Petrovskaya Ivanna I.", "Petrovskaya I. I."),                 # an initial kept as written
    ("Ivanova-Petrovskaya I.I.", "Ivanova-Petrovskaya"),            # too wide with them: the surname
    ("I. I. Ivanova-Petrovskaya-Sidorova", "Ivanova-Petrovskaya-Sidorova"),   # initials first
    ("Ivanov", "Ivanov")])
def test_signer_names_as_the_title_block_writes_them(name, shown):
    """drawings.titleblock.signer_name on its own (the sheets' 2.5 mm letters in 21.6 mm, down to
    NARROWEST): the name as given where it fits, the surname and initials, the surname; a
    surname too long for the cell narrower still, never past it."""
    from tmm_cli.drawings.titleblock import signer_name
    from tmm_cli.sheets.frame import NARROWEST
    from tmm_cli.sheets.prims import CAP_RATIO
    char_w = 0.6 * 2.5 / CAP_RATIO
    got, narrow = signer_name(name, char_w, 21.6, NARROWEST)
    assert got == shown
    assert char_w * narrow * len(got) <= 21.6 + 1e-9
    # narrower than NARROWEST only for a surname longer than the cell at NARROWEST
    assert narrow >= NARROWEST or (got == shown and char_w * NARROWEST * len(got) > 21.6)


def test_gear_sheet_names_each_number_and_lists_as_the_language_does():
    """The gear sheet's line of data names each wheel's number (z1, z2, x1, x2) and separates the
    items with '; ' where the decimal comma is written ('x = 0,44944, -0,155323' read as one
    list of three numbers)."""
    from tmm_cli.sheets.prims import Text
    res, cv, _ = _only_sheet("gears_shifted", 5, "ru")
    g = res["gears"]
    line = next(p.plain for p in cv.prims if isinstance(p, Text) and p.plain.startswith("m = "))
    assert f"; z1 = {g['z'][0]}; z2 = {g['z'][1]}; x1 = " in line, line
    res, cv, _ = _only_sheet("gears_shifted", 5, "en")
    line = next(p.plain for p in cv.prims if isinstance(p, Text) and p.plain.startswith("m = "))
    assert f", z1 = {g['z'][0]}, z2 = {g['z'][1]}, x1 = {g['x'][0]:g}, x2 = {g['x'][1]:g}," in line, line


def test_the_energy_mass_sheet_names_its_abscissa(shared_once):
    """Sheet 3's energy-mass diagram plots ΔT against the variable part of the reduced inertia
    (Popov and Timofeev's form, its intercepts a, b): the abscissa says so, J with the report's
    subscript for it (var; перем in ru), not a bare J."""
    sheets = example_sheets("forging_sixbar", shared_once)
    for lang, sub in (("en", "var"), ("ru", "\u043f\u0435\u0440\u0435\u043c")):
        (cv, info), = [(c, i) for c, i in sheets[lang] if i["number"] == 3]
        assert any(isinstance(p, Text) and p.s == "J" and p.sub == sub for p in cv.prims), lang


def _prim_points(cv):
    """Every point a canvas's primitives reach (text anchors included), as an (n, 2) array."""
    from tmm_cli.sheets.prims import Arc, Circle, Line, Polyline, Text
    pts = []
    for q in cv.prims:
        if isinstance(q, Line):
            pts += [q.p, q.q]
        elif isinstance(q, Polyline):
            pts += list(q.pts)
        elif isinstance(q, (Circle, Arc)):
            pts += [(q.c[0] - q.r, q.c[1] - q.r), (q.c[0] + q.r, q.c[1] + q.r)]
        elif isinstance(q, Text):
            pts.append((q.x, q.y))
    return np.asarray(pts, float)


@pytest.mark.parametrize("name", ["planetary_pair_given", "press_drive_train"])
def test_drive_train_sheet_draws_the_trains_plans_at_their_scales(name):
    """A drive's gear train (pairs and a planetary stage from the motor) had no sheet at all
    ('no linkage, cam or gear pair to draw'). Sheet 9 draws its scheme with the picture of
    linear velocities and the plan of angular velocities: the plan's ray of each shaft cuts the
    line at x = ω / μω from the pole's foot, ω the shaft's speed worked out here from the
    motor's speed and the stages' tooth numbers (a pair -z2/z1 or +z2/z1 inside, a planetary
    stage of scheme A 1 + z3/z1, B 1 + z2 z4/(z1 z3)); every drawing inside its own canvas (the
    pair's driven wheel ran off the report's figure) and the sheet's frame; the plan's scale the
    picture's (its rays parallel to the picture's lines: μω = μv/(H μl), it was a scale of its own)."""
    import math as m

    from tmm_cli.pipeline import run
    from tmm_cli.sheets import build_sheets
    from tmm_cli.sheets.frame import FRAME
    from tmm_cli.task import load_task
    task = load_task(ROOT / "tasks" / f"{name}.yaml")
    res = run(task)
    info = next(i for _, i in build_sheets(res, task, "en") if i["number"] == 9)
    sense = -1.0 if res["drive_train"]["motor_direction"] == "cw" else 1.0
    speeds = [sense * float(task.drive_train.motor_speed)]          # rad/s, as the task gives it
    for st in res["drive_train"]["stages"]:
        z = st["z"]
        if st["type"] == "pair":
            u = z[1] / z[0] * (1 if st.get("internal") else -1)
        elif st["scheme"] == "A":
            u = 1 + z[2] / z[0]
        else:
            u = 1 + z[1] * z[3] / (z[0] * z[2])
        speeds.append(speeds[-1] / u)
    assert np.allclose(speeds, res["drive_train"]["shafts"], rtol=1e-9), (speeds, res["drive_train"]["shafts"])
    px, py, plan = info["plan"]
    pts = _prim_points(plan)
    assert (pts >= -1e-6).all() and (pts[:, 0] <= plan.w + 1e-6).all() and (pts[:, 1] <= plan.h + 1e-6).all()
    from tmm_cli.sheets.prims import Line
    lines = [q for q in plan.prims if isinstance(q, Line)]
    pole = max(((q.p, sum(1 for r in lines if r.p == q.p)) for q in lines), key=lambda t: t[1])[0]
    ends = [q.q for q in lines if q.p == pole]
    foot = [q.q for q in lines if q.p == pole and q.dash is not None and abs(q.q[0] - pole[0]) < 1e-9]
    xs = [e[0] - pole[0] for e in ends]
    for s in speeds:                                  # each shaft's ray where ω / μω puts it
        assert min(abs(x - s / info["mu_omega"]) for x in xs) < 1e-6, (s, xs)
    assert all(abs(e[1] - pole[1]) == pytest.approx(info["H"]) for e in ends if e not in foot)
    sx, sy, scheme = info["scheme"]
    # the picture: each point's velocity a horizontal segment |v|/μv long from the axis
    drawn = [abs(q.q[0] - q.p[0]) for q in scheme.prims if isinstance(q, Line) and q.color == "#555"]
    for pt in res["drive_train"]["velocity_plan"]["points"]:
        assert min(abs(x - abs(pt["v"]) / info["mu_v"]) for x in drawn) < 1e-6, pt["name"]
    pts = _prim_points(scheme)
    assert (pts >= -1e-6).all() and (pts[:, 0] <= scheme.w + 1e-6).all() and (pts[:, 1] <= scheme.h + 1e-6).all()
    x0f, y0f, x1f, y1f = FRAME
    for (ox, oy, c) in (info["scheme"], info["plan"]):
        assert x0f < ox and ox + c.w < x1f and y0f < oy and oy + c.h < y1f
    # the plan built on the picture (Smirnov): rays parallel to the picture's lines, so that
    # μω = μv / (H μl) with the picture's own scales, each a standard one
    assert _gost_length(info["mu_l"]) and _mantissa_ok(info["mu_v"]) and _mantissa_ok(info["mu_omega"])
    assert info["mu_omega"] == pytest.approx(info["mu_v"] / (info["H"] * info["mu_l"]))
    assert m.isfinite(info["mu_omega"])


def test_a_scotch_yokes_slot_is_drawn_and_the_numbers_clear_its_blocks(shared_once):
    """The Scotch yoke's block slides in a slot of the yoke: the group drawing showed the block
    apart from the yoke (the slot not drawn), the kinematic scheme the yoke as a dash-dot line
    only, and its position numbers on the blocks at the crank pin. The slot now runs from the
    yoke's bar through the block (worked here: the bar along y = 0, the block at (0, -60) at
    90 deg: the foot (0, 0), the far end 6 mm past the block), the yoke's bar is drawn at every
    position, and no position number touches a block."""
    from tmm_cli.drawings.forces import _slot
    links = {"yoke": {"points": ["Y", "P"]}, "block": {"points": ["A"]}}
    mp = {"Y": np.array([-40.0, 0.0]), "P": np.array([60.0, 0.0]), "A": np.array([0.0, -60.0])}
    foot, end = _slot(mp["A"], np.array([0.0, 1.0]), links, {"link": "yoke"}, ["block", "yoke"], mp)
    assert np.allclose(foot, [0.0, 0.0]) and np.allclose(end, [0.0, -66.0])
    assert _slot(mp["A"], np.array([1.0, 0.0]), links, {"link": "yoke"}, ["block", "yoke"], mp) is None  # along it
    assert _slot(mp["A"], np.array([0.0, 1.0]), links, {"link": "yoke"}, ["block"], mp) is None   # not in the group
    assert _slot(mp["A"], np.array([0.0, 1.0]), links, {"link": None}, ["block", "yoke"], mp) is None
    from tmm_cli.sheets.prims import Line, Polyline, Text
    for lang, sheets in example_sheets("scotch_yoke_pump", shared_once).items():
        cv, info = next((c, i) for c, i in sheets if i["number"] == 1)
        blocks = [q for q in cv.prims if isinstance(q, Polyline) and q.closed and len(q.pts) in (4, 5)
                  and np.ptp(np.asarray(q.pts), axis=0).max() < 12.0]
        assert len(blocks) >= 24, len(blocks)                 # the block and the yoke's, 12 positions
        numbers = [q for q in cv.prims if isinstance(q, Text) and q.s.isdigit() and int(q.s) < 12]
        assert {int(t.s) for t in numbers} == set(range(12))
        for t in numbers:
            x0, y0, x1, y1 = t.box()
            for b in blocks:
                bx0, by0 = np.asarray(b.pts).min(axis=0)
                bx1, by1 = np.asarray(b.pts).max(axis=0)
                assert min(x1, bx1) <= max(x0, bx0) or min(y1, by1) <= max(y0, by0), (lang, t.s)
        # the yoke's bar Y-P at every position: 12 lines of its length on the scheme
        bar = 0.25 * 1000.0 / info["mechanism"]["unit"]
        bars = [q for q in cv.prims if isinstance(q, Line) and abs(np.hypot(*np.subtract(q.q, q.p)) - bar) < 1e-6]
        assert len(bars) >= 12, (lang, len(bars))


@pytest.mark.parametrize("name, extra", [("press_offset_slider_crank", 13), ("balancing_fourbar", 12)])
def test_an_extra_position_is_marked_on_every_sheet(name, extra, shared_once):
    """A named extra position (index >= the grid's 12: an extreme one) is '13*' in the report's
    tables and on the scheme; the kinetostatics sheet headed it 'Position 13', the velocity
    plans '(position 13)' and the balancing hodograph '12' between 6 and 7: marked everywhere."""
    import re as _re

    from tmm_cli.sheets.prims import Text
    seen = 0
    for cv, info in example_sheets(name, shared_once)["en"]:
        for t in (q.s for q in cv.prims if isinstance(q, Text)):
            bare = _re.fullmatch(r"\d+", t) or _re.search(r"[Pp]osition (\d+)(?![\d*])", t)
            num = int(bare.group(1) if bare and bare.groups() else (bare.group(0) if bare else -1))
            assert num != extra, (info["number"], t)
            seen += f"{extra}*" in t
    assert seen >= 1


@pytest.mark.parametrize("lang, word", [("en", "no sheets: the task has nothing the sheets draw"),
                                        ("uk", "\u0430\u0440\u043a\u0443\u0448\u0456\u0432 \u043d\u0435\u043c\u0430\u0454")])
def test_a_task_with_nothing_to_draw_is_told_in_its_language(tmp_path, lang, word):
    """`tmm sheets` of a task no sheet draws (a 2-DOF machine) said, in English only, that it had
    'no linkage, cam or gear pair' (a drive train has a sheet now): the note in the language."""
    from typer.testing import CliRunner

    from tmm_cli.cli import app
    res = CliRunner().invoke(app, ["sheets", str(ROOT / "tasks" / "impact_rotor.yaml"), "--out", str(tmp_path),
                                   "--lang", lang])
    assert res.exit_code == 0 and word in " ".join(res.output.split()), res.output
    assert not list(tmp_path.glob("*.pdf"))
