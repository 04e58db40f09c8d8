"""The kinetostatics drawings of the report: for every position and every Assur group
(and the input link) the force polygon drawn is the group's forces to scale mu_F, head
to tail, and it closes (the group is in equilibrium) to drawing precision.

The expected forces are collected here independently from the numbers of results.json:
the loads of the group's links plus, for every pair joining the group to a link outside
it, the reaction of that link (R_ij acts on j; on i it is -R_ij, SPEC section 3)."""
from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest

import tmm_cli
from tmm_cli.report import make_env, sections
from tmm_cli.report.context import ReportContext

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module", params=["forging_sixbar", "shaper_slotted_lever"])
def case(request, tmp_path_factory):
    task = tmm_cli.load_task(ROOT / "tasks" / f"{request.param}.yaml")
    r = tmm_cli.run(task, kinematics_curve=0)
    kst = sections.load("kinetostatics")
    ctx = ReportContext(results=r, task=task, lang="ru", out_dir=tmp_path_factory.mktemp("k"), env=make_env())
    return task, r, kst, ctx


def expected_forces(r, e, group_names):
    """[(name, F)] on the links `group_names` in entry e, from results only."""
    idx = {l["name"]: l["index"] for l in r["structure"]["links"]}
    g = {idx[n] for n in group_names}
    out = [(f["name"], np.array(f["F"], float)) for f in e["loads"] if f["link"] in group_names]
    for key, R in e["reactions"].items():
        i, j = int(key[1]), int(key[2])            # 'R<i><j>': links numbered < 10 here
        F = np.array([R["x"], R["y"]], float)
        if j in g and i not in g:
            out.append((f"R{i}{j}", F))
        elif i in g and j not in g:
            out.append((f"R{j}{i}", -F))
    return out


def _mantissa(mu):
    return round(mu / 10 ** math.floor(math.log10(mu) + 1e-12), 9)


def test_polygons_close_and_match_the_results(case):
    task, r, kst, ctx = case
    info = r["kinetostatics_info"]
    links = {l["name"]: l for l in r["structure"]["links"]}
    kin = {k["index"]: k for k in r["kinematics"]}
    checked = 0
    for e in r["kinetostatics"]:
        figs, drawn = kst.position_figures(ctx, e, kin[e["index"]], info, links, "A", None)
        assert len(figs) in (1, 2) and len(drawn) == len(info["groups"]) + 1
        assert _mantissa(drawn[-1]["lever"]) in (1, 2, 2.5, 4, 5)
        for d in drawn[:-1]:
            exp = expected_forces(r, e, set(d["group"]))
            Fmax = max(np.hypot(*F) for _, F in exp)
            exp = {n: F for n, F in exp if np.hypot(*F) > 1e-9 * Fmax}
            # the drawn vectors are exactly these forces, each F / mu_F mm long
            assert {n for n, _, _ in d["vectors"]} == set(exp)
            T, mu = d["tips"], d["mu_F"]
            seg = np.diff(T, axis=0)
            for (name, _, _), s in zip(d["vectors"], seg):
                assert np.allclose(s * mu, exp[name], rtol=0, atol=1e-9 * Fmax), name
            # the polygon closes: the sum of the drawn vectors is zero to 0.01 mm
            assert np.hypot(*(T[-1] - T[0])) < 0.01
            # ... while being drawn large: its extent is at least a quarter of the panel (~60 mm)
            assert np.ptp(T, axis=0).max() > 15.0
            # mu_F from the standard series 1, 2, 2.5, 4, 5 x 10^k N/mm; mu_l a ГОСТ 2.302 scale
            assert _mantissa(mu) in (1, 2, 2.5, 4, 5)
            from tmm_cli.report.figures import GOST_ENLARGEMENTS, GOST_REDUCTIONS
            unit = d["mu_l"] * 1000.0                  # model mm per paper mm
            assert any(abs(unit - n) < 1e-9 * n for n in GOST_REDUCTIONS) or any(
                abs(unit - 1 / n) < 1e-9 for n in GOST_ENLARGEMENTS) or (
                unit > GOST_REDUCTIONS[-1] and _mantissa(unit) in (1, 2, 2.5, 4, 5))
            checked += 1
    assert checked >= 12 * len(info["groups"])


def test_drawings_name_the_forces_as_the_course(case):
    """Labels in the drawing: R with the pair's digits as a subscript, G_i, Phi_i for the
    inertia forces, M_Phi_i for the inertia couples, the scales mu_l, mu_F, mu_v."""
    task, r, kst, ctx = case
    info = r["kinetostatics_info"]
    links = {l["name"]: l for l in r["structure"]["links"]}
    e = r["kinetostatics"][3]
    kin_e = next(k for k in r["kinematics"] if k["index"] == e["index"])
    figs, _ = kst.position_figures(ctx, e, kin_e, info, links, "A", None)
    svg = "".join(str(f) for f in figs)
    labels = {re.sub(r"<[^>]+>", "", m) for m in re.findall(r"<text[^>]*>(.*?)</text>", svg, re.S)}
    idx = {l["name"]: l["index"] for l in r["structure"]["links"]}
    group_of = {idx[n]: k for k, g in enumerate(info["groups"]) for n in g}
    for j in info["joints"]:
        if group_of.get(j["a"], -1) == group_of.get(j["b"], -1):
            continue                              # a pair inside a group: not on its free-body diagram
        assert j["key"] in labels or f"R{j['key'][2]}{j['key'][1]}" in labels, j["key"]
    for f in e["loads"]:
        if np.hypot(*f["F"]) == 0:
            continue
        want = {"inertia": f"Φ{idx[f['link']]}", "gravity": f"G{idx[f['link']]}"}.get(f["kind"])
        if want:
            assert want in labels, want
    assert any(t.startswith("μl = ") for t in labels)
    assert any(t.startswith("μF = ") and t.endswith("Н/мм") for t in labels)
    assert any(t.startswith("μv = ") for t in labels)
    assert "Рычаг Жуковского" in labels and "План сил" in labels


def test_label_parts():
    lp = sections.load("kinetostatics").label_parts
    assert lp("R12") == ("R", "12") and lp("G2") == ("G", "2")
    assert lp("Fi2") == ("Φ", "2") and lp("Mi3") == ("M", "Φ3")
    assert lp("Ff03", "ru") == ("F", "тр03") and lp("Mf12", "en") == ("M", "f12")
    assert lp("F1") == ("F", "1") and lp("Pres") == ("Pres", "")


def test_loads_table_inertia_forces(case):
    """The merged loads table: |Phi_i| = m_i a_Si (d'Alembert) from the task's masses and
    the kinematics' accelerations of the centres of mass, for every position."""
    task, r, kst, ctx = case
    hdr, rows, const = kst._loads_table(ctx, r["kinetostatics"])
    names = [re.sub(r"<[^>]+>", "", str(h)) for h in hdr]
    kin = {k["index"]: k for k in r["kinematics"]}
    masses = {i + 1: spec.mass for i, spec in enumerate(task.mechanism.links.values())}
    checked = 0
    for i, m in masses.items():
        col = f"Φ{i}"
        if col not in names or not m:
            continue
        c = names.index(col)
        for row in rows:
            a = kin[row[0]]["points"][f"S{i}"]["a"]
            assert row[c] == ctx.fmt(m * a, 4), (col, row[0])
            checked += 1
    assert checked >= 2 * len(rows)
    # the weights m g (g = 9.81 m/s², tmm_cli/linkage/loads.py) are constant: listed once below the table
    for i, m in masses.items():
        if m:
            assert f"G<sub>{i}</sub> = {ctx.fmt(m * 9.81, 5)}" in str(const), i
