"""Balancing: the shaking force and moment against a second method (the total centre of mass
and the angular momentum differentiated numerically), counterweights against hand formulas
and their purpose (a fully balanced four-bar's shaking force is zero), rotors by hand."""
import json
import math
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from tmm_cli import load_task, run
from tmm_cli.balancing.rotor import balance_rotor
from tmm_cli.cli import app
from tmm_cli.linkage.kinematics import solve
from tmm_cli.linkage.mechanism import build_mechanism

ROOT = Path(__file__).resolve().parents[1]
runner = CliRunner()

FOURBAR = {"ground": {"O": [0, 0], "O3": [0.30, 0]},
           "links": {"crank": {"points": ["O", "A"], "length": 0.08, "mass": 1.0, "J": 0.0015},
                     "coupler": {"points": ["A", "B"], "length": 0.30, "mass": 2.4, "J": 0.02, "com": [0.12, 0.02]},
                     "rocker": {"points": ["O3", "B"], "length": 0.22, "mass": 1.8, "J": 0.0085}},
           "assembly": {"B": [0.33, 0.21]}}
SLIDER = {"ground": {"O": [0, 0]},
          "links": {"crank": {"points": ["O", "A"], "length": 0.045, "mass": 2.5, "J": 0.004},
                    "rod": {"points": ["A", "B"], "length": 0.17, "mass": 1.2, "J": 0.0055, "com": [0.05, 0]},
                    "piston": {"slider": "B", "guide": {"through": "O", "angle": 90}, "mass": 0.9}}}


def _task(mech, balancing, speed=12.566370614359172):
    return load_task({"schema": "tmm/1", "mechanism": mech, "drive": {"link": "crank", "speed": speed},
                      "positions": {"count": 12, "zero": 0}, "balancing": balancing})


def _momenta(task, phi, omega):
    """Total linear momentum sum m v_S and angular momentum about O, sum [m (S - O) x v_S + J w]."""
    mech = build_mechanism(task)
    k = solve(mech, phi, omega)
    P = np.zeros((len(phi), 2))
    H = np.zeros(len(phi))
    for lk in mech.links:
        s, v = k.pos[f"S{lk.index}"], k.vel(f"S{lk.index}")
        P += lk.mass * v
        H += lk.mass * (s[:, 0] * v[:, 1] - s[:, 1] * v[:, 0]) + lk.J * k.omega(lk.name)
    return P, H


def test_shaking_force_and_moment_are_the_rates_of_the_momenta():
    """F = dP/dt and M = dH_O/dt: central differences in time (t = phi/omega), h = 1e-4 deg."""
    w = 120 * math.pi / 30
    task = _task(FOURBAR, {})
    res = run(task)
    sh = res["balancing"]["shaking"]
    phi = np.array([e["phi"] for e in sh])
    h = 1e-4
    dt = math.radians(h) / w
    Pp, Hp = _momenta(task, phi + h, w)
    Pm, Hm = _momenta(task, phi - h, w)
    F = (Pp - Pm) / (2 * dt)
    M = (Hp - Hm) / (2 * dt)
    scale = max(e["F"] for e in sh)
    for e, f, m in zip(sh, F, M):
        assert e["Fx"] == pytest.approx(f[0], abs=1e-6 * scale)
        assert e["Fy"] == pytest.approx(f[1], abs=1e-6 * scale)
        assert e["M"] == pytest.approx(m, abs=1e-6 * scale)
    assert res["balancing"]["about"] == "O"


def test_full_balancing_of_a_four_bar_stills_the_centre_of_mass():
    res = run(_task(FOURBAR, {"counterweights": {"method": "full", "radius": {"crank": 0.06, "rocker": 0.08}}}))
    b = res["balancing"]
    assert b["max"]["F"] > 10
    # exactly 0: the sums' round-off (about 1e-15 of their terms) is written 0 (see below)
    assert b["max"]["F_balanced"] == 0.0
    for e in b["shaking_balanced"]:
        assert e["F"] == e["Fx"] == e["Fy"] == 0.0
    assert set(b["hodograph"]["Fx_balanced"]) == set(b["hodograph"]["Fy_balanced"]) == {0.0}


def _fourbar_balanced(n=721):
    from tmm_cli.balancing import linkage
    task = _task(FOURBAR, {"counterweights": {"method": "full", "radius": {"crank": 0.06, "rocker": 0.08}}})
    mech = build_mechanism(task)
    k = solve(mech, np.linspace(0, 360, n), 12.566370614359172)
    cws, _ = linkage.counterweights(mech, k, task.balancing.counterweights)
    return linkage, mech, k, cws


def test_balanced_force_is_round_off_of_zero(monkeypatch):
    """Berkof and Lowen's conditions keep the total centre of mass still identically (at every
    crank angle), so the exact shaking force is 0; the computed sum of the links' and the
    counterweights' m a is left at a few eps of the sum of its terms' sizes (measured: at most
    1.4e-15 of it over the turn), far below ROUNDOFF (1e-12): tmm writes 0."""
    linkage, mech, k, cws = _fourbar_balanced()
    monkeypatch.setattr(linkage, "ROUNDOFF", 0.0)
    raw = linkage.shaking(mech, k, "O", cws)
    size_x = size_y = 0.0
    for lk in mech.links:
        a = k.acc(f"S{lk.index}")
        size_x, size_y = size_x + lk.mass * np.abs(a[:, 0]), size_y + lk.mass * np.abs(a[:, 1])
    for cw in cws:
        _, a = linkage._cw_motion(k, cw)
        size_x, size_y = size_x + cw.m * np.abs(a.real), size_y + cw.m * np.abs(a.imag)
    assert np.max(raw["F"]) > 0                                   # not 0 before the cleaning
    assert np.all(np.abs(raw["Fx"]) <= 1e-14 * size_x) and np.all(np.abs(raw["Fy"]) <= 1e-14 * size_y)
    monkeypatch.undo()
    clean = linkage.shaking(mech, k, "O", cws)
    assert np.all(clean["F"] == 0) and np.all(clean["Fx"] == 0) and np.all(clean["Fy"] == 0)
    np.testing.assert_array_equal(clean["M"], raw["M"])           # the moment is no round-off


def test_round_off_cleaning_keeps_a_real_remainder():
    """A crank counterweight heavier by 1e-9 of itself leaves that extra mass's inertia force,
    dm r w^2 at every position (the crank turns at constant speed; the rest still cancels),
    about 1e-8 N: far above round-off, so it is written as it is."""
    from dataclasses import replace
    linkage, mech, k, cws = _fourbar_balanced()
    crank = next(c for c in cws if c.role == "crank")
    off = [replace(c, m=c.m * (1 + 1e-9)) if c is crank else c for c in cws]
    sh = linkage.shaking(mech, k, "O", off)
    dm = crank.m * (1 + 1e-9) - crank.m
    want = dm * crank.r * 12.566370614359172 ** 2
    assert np.all(sh["F"] > 0)
    np.testing.assert_allclose(sh["F"], want, rtol=1e-4)


def test_balanced_force_zero_in_every_form(tmp_path):
    """results.json, the report, the explanatory note's conclusions, the terminal summary and
    the answer check all say 0 for the fully balanced four-bar's shaking force."""
    import csv

    from tmm_cli.report.note import WORDS, conclusions
    from tmm_cli.summary import _summary_rows
    res = runner.invoke(app, ["run", str(ROOT / "tasks" / "balancing_fourbar.yaml"), "--format", "json,html",
                              "--out", str(tmp_path / "o"), "-q"])
    assert res.exit_code == 0, res.output
    d = json.loads((tmp_path / "o" / "results.json").read_text(encoding="utf-8"))
    assert d["balancing"]["max"]["F_balanced"] == 0
    html = (tmp_path / "o" / "report.html").read_text(encoding="utf-8")
    assert "With the counterweights: largest shaking force 0 N" in html
    for lang in ("en", "ru", "uk"):
        after = WORDS[lang]["c_bal_after"].format(Fb="0")             # ", 0 N with the counterweights"
        assert after in " ".join(conclusions(d, lang))
    assert ("with counterweights, N", "0") in _summary_rows(d)
    ans = tmp_path / "a.yaml"
    ans.write_text("variant: 3\nanswers:\n  balancing.max.F_balanced: 0.001\n", encoding="utf-8")
    runner.invoke(app, ["check", str(ROOT / "tasks" / "balancing_fourbar.yaml"), "--answers", str(ans),
                        "-o", str(tmp_path / "c")])
    rows = {r["path"]: r for r in csv.DictReader((tmp_path / "c" / "check.csv").open(encoding="utf-8"))}
    assert float(rows["balancing.max.F_balanced"]["reference"]) == 0
    res = runner.invoke(app, ["form", str(ROOT / "tasks" / "balancing_fourbar.yaml"), "-q", "balancing",
                              "-o", str(tmp_path / "f")])
    assert res.exit_code == 0, res.output
    key = (tmp_path / "f" / "balancing_fourbar.key.yaml").read_text(encoding="utf-8")
    assert '"balancing.max.F_balanced": 0.0 ' in key


def test_four_bar_counterweights_by_hand():
    """Coupler's centre of mass on AB at s2 = 0.12 of l2 = 0.30 (no offset), the crank's at its
    pivot O (tmm's default for the drive link) and the rocker's at its middle. The crank's mass
    moment about O must become -m2 l1 (1 - s2/l2): the counterweight takes m2 l1 (1 - s2/l2)
    = 2.4 (0.08)(0.6) = 0.1152 kg m, opposite the crank (180 deg); the rocker's about O3
    -m2 l3 s2/l2: m2 l3 s2/l2 + m3 l3/2 = 2.4 (0.22)(0.4) + 1.8 (0.11) = 0.4092 kg m at 180 deg."""
    mech = json.loads(json.dumps(FOURBAR))
    mech["links"]["coupler"]["com"] = [0.12, 0]
    res = run(_task(mech, {"counterweights": {"method": "full", "radius": {"crank": 0.06, "rocker": 0.08}}}))
    cw = res["balancing"]["counterweights"]
    assert cw["crank"]["m"] == pytest.approx(0.1152 / 0.06, rel=1e-12)
    assert cw["crank"]["angle"] == pytest.approx(180, abs=1e-9)
    assert cw["rocker"]["m"] == pytest.approx(0.4092 / 0.08, rel=1e-12)
    assert cw["rocker"]["angle"] == pytest.approx(180, abs=1e-9)
    assert cw["crank"]["r"] == 0.06 and cw["rocker"]["r"] == 0.08


@pytest.mark.parametrize("share", [0.0, 0.5, 1.0])
def test_slider_crank_counterweight_leaves_the_reciprocating_force(share):
    """With the rod's centre of mass on AB (s2 = 0.05 of l2 = 0.17), the rotating masses cancel
    exactly and what remains is m_rec a_B - share m_rec a_A, m_rec = m3 + m2 s2/l2."""
    w = 12.566370614359172
    task = _task(SLIDER, {"counterweights": {"method": "crank", "radius": {"crank": 0.05},
                                             "reciprocating_share": share}}, speed=w)
    res = run(task)
    b = res["balancing"]
    m_rec = 0.9 + 1.2 * 0.05 / 0.17
    assert b["remains"]["reciprocating_mass"] == pytest.approx(m_rec, rel=1e-14)
    # counterweight by hand (the crank's centre of mass at O): m2 l1 (1 - s2/l2) + share m_rec l1,
    # opposite the crank
    assert b["counterweights"]["crank"]["m"] * 0.05 == pytest.approx(
        1.2 * 0.045 * (1 - 0.05 / 0.17) + share * m_rec * 0.045, rel=1e-12)
    assert b["counterweights"]["crank"]["angle"] == pytest.approx(180, abs=1e-9)
    mech = build_mechanism(task)
    phi = np.array([e["phi"] for e in b["shaking_balanced"]])
    k = solve(mech, phi, w)
    want = m_rec * k.acc("B") - share * m_rec * k.acc("A")
    for e, f in zip(b["shaking_balanced"], want):
        assert e["Fx"] == pytest.approx(f[0], abs=1e-9) and e["Fy"] == pytest.approx(f[1], abs=1e-9)
    lam = 0.045 / 0.17
    assert b["remains"]["secondary_amplitude"] == pytest.approx(m_rec * 0.045 * w ** 2 * lam, rel=1e-12)
    assert b["remains"]["primary_amplitude"] == pytest.approx((1 - share) * m_rec * 0.045 * w ** 2, rel=1e-12)


def _rotor(masses, planes, radius):
    return load_task({"schema": "tmm/1", "balancing": {"rotor": {"masses": masses, "planes": planes,
                                                                  "radius": radius}}}).balancing.rotor


def test_rotor_dynamic_by_the_lever_rule():
    """One mass 1 kg at r = 0.1 m, 0 deg, z = 0.1 m between planes z = 0 and 0.3: plane 1 takes
    2/3 of m r, plane 2 takes 1/3, both opposite (180 deg)."""
    r = balance_rotor(_rotor([{"m": 1, "r": 0.1, "angle": 0, "z": 0.1}], [0, 0.3], 0.05))
    c1, c2 = r["corrections"]
    assert c1["mr"] == pytest.approx(0.1 * 2 / 3, rel=1e-14) and c2["mr"] == pytest.approx(0.1 / 3, rel=1e-14)
    assert c1["m"] == pytest.approx(0.1 * 2 / 3 / 0.05, rel=1e-14)
    assert c1["angle"] == pytest.approx(180) and c2["angle"] == pytest.approx(180)
    assert r["imbalance"] == pytest.approx({"mr": 0.1, "angle": 0.0, "z": 0.1, "couple": 0.0}, abs=1e-15)


def test_rotor_corrections_cancel_force_and_moment():
    masses = [{"m": 0.2, "r": 0.1, "angle": 30, "z": 0.05}, {"m": 0.15, "r": 0.08, "angle": 150, "z": 0.15},
              {"m": 0.1, "r": 0.12, "angle": 260, "z": 0.25}]
    r = balance_rotor(_rotor(masses, [0, 0.3], 0.12))

    def vec(m, rr, a):
        return m * rr * complex(math.cos(math.radians(a)), math.sin(math.radians(a)))
    U = [vec(m["m"], m["r"], m["angle"]) for m in masses]
    Uc = [vec(c["m"], c["r"], c["angle"]) for c in r["corrections"]]
    assert abs(sum(U) + sum(Uc)) < 1e-15
    assert abs(sum(m["z"] * u for m, u in zip(masses, U)) + sum(c["z"] * u for c, u in
                                                                 zip(r["corrections"], Uc))) < 1e-15


def test_rotor_static_one_plane_leaves_the_couple():
    masses = [{"m": 1, "r": 0.1, "angle": 0, "z": 0.0}, {"m": 1, "r": 0.1, "angle": 180, "z": 0.2}]
    r = balance_rotor(_rotor(masses, [0.1], 0.1))
    assert r["method"] == "static"
    assert r["corrections"][0]["mr"] == pytest.approx(0, abs=1e-15)     # statically balanced already
    assert r["couple_left"] == pytest.approx(0.1 * 0.2, rel=1e-12)     # m r times the distance 0.2 m


def _run(tmp_path, text):
    f = tmp_path / "t.yaml"
    f.write_text(text, encoding="utf-8")
    res = runner.invoke(app, ["run", str(f), "--format", "json", "--out", str(tmp_path / "o")])
    return res.exit_code, res.output


def test_full_method_on_a_slider_crank_exit_2(tmp_path):
    text = (ROOT / "tasks" / "engine_slider_crank.yaml").read_text(encoding="utf-8")
    text += "balancing:\n  counterweights: {method: full, radius: {crank: 0.05, rocker: 0.05}}\n"
    code, out = _run(tmp_path, text)
    assert code == 2, out
    assert "balancing.counterweights.method" in out and "four-bar" in out and "Traceback" not in out


def test_counterweights_without_a_mechanism_exit_2(tmp_path):
    code, out = _run(tmp_path, "schema: tmm/1\nbalancing:\n  counterweights: {method: crank, radius: {crank: 0.05}}\n")
    assert code == 2 and "balancing.counterweights" in out and "mechanism" in out


def test_missing_rocker_radius_exit_2(tmp_path):
    text = (ROOT / "tasks" / "balancing_fourbar.yaml").read_text(encoding="utf-8")
    text = text.replace("radius: {crank: 60 mm, rocker: 80 mm}", "radius: {crank: 60 mm}")
    code, out = _run(tmp_path, text)
    assert code == 2 and "balancing.counterweights.radius" in out and "rocker" in out


def test_example_task(tmp_path):
    res = runner.invoke(app, ["run", str(ROOT / "tasks" / "balancing_fourbar.yaml"), "--format", "json",
                              "--out", str(tmp_path / "o")])
    assert res.exit_code == 0, res.output
    d = json.loads((tmp_path / "o" / "results.json").read_text())
    b = d["balancing"]
    n = len(d["positions"]["phi"])
    assert len(b["shaking"]) == n and len(b["shaking_balanced"]) == n
    assert [e["phi"] for e in b["shaking"]] == d["positions"]["phi"]
    assert b["max"]["F_balanced"] == 0.0
    assert len(b["hodograph"]["phi"]) == 361 and b["rotor"]["method"] == "dynamic"


# ---------------------------------------------------------------- balancing.apply
APPLY_LOADS = {"forces": [{"on": "rocker", "kind": "resistance", "moment": 20}]}


def _apply_task(apply: bool):
    return load_task({"schema": "tmm/1", "mechanism": FOURBAR, "drive": {"link": "crank", "speed": "120 rpm"},
                      "positions": {"count": 12, "zero": 0, "output": "rocker"}, "loads": APPLY_LOADS,
                      "kinetostatics": {}, "flywheel": {"delta": 0.05},
                      "balancing": {"counterweights": {"method": "full", "radius": {"crank": 0.06, "rocker": 0.08}},
                                    "apply": apply}})


@pytest.fixture(scope="module")
def applied():
    return run(_apply_task(False)), run(_apply_task(True))


def test_applied_counterweights_leave_the_frame_no_net_force(applied):
    """Without gravity and with only a couple as the load, the frame's reactions on the links
    sum to the links' sum m a_S: the shaking force of the balancing stage (a second method:
    kinetostatics against the momenta). With the full-balancing counterweights applied that sum
    is zero at every position; without them it is the `shaking` force."""
    plain, bal = applied
    for res, key in ((plain, "shaking"), (bal, None)):
        sh = res["balancing"]["shaking"]
        scale = max(e["F"] for e in sh)
        for e, k in zip(res["kinetostatics"], sh):
            R = e["reactions"]
            fx = R["R01"]["x"] + R["R03"]["x"]
            fy = R["R01"]["y"] + R["R03"]["y"]
            want = (k["Fx"], k["Fy"]) if key else (0.0, 0.0)
            assert fx == pytest.approx(want[0], abs=1e-9 * scale)
            assert fy == pytest.approx(want[1], abs=1e-9 * scale)
    assert max(e["F"] for e in plain["balancing"]["shaking"]) > 10


def test_applied_counterweights_in_the_reduced_moment_of_inertia(applied):
    """Each counterweight turns with its link about a fixed pivot: it adds m r^2 to the link's
    moment of inertia about the pivot. The crank's (centre of mass at O): J_O = 0.0015 + m1' r1^2;
    the rocker's reduced share J_O3 (w3/w1)^2 scales by (J_O3 + m3' r3^2)/J_O3 with
    J_O3 = J_S3 + m3 (l3/2)^2 = 0.0085 + 1.8 (0.11)^2 = 0.03028 kg m^2; the coupler's is unchanged."""
    plain, bal = applied
    cw = bal["balancing"]["counterweights"]
    m1, m3 = cw["crank"]["m"], cw["rocker"]["m"]
    a0, a1 = plain["flywheel"]["arrays"]["J_links"], bal["flywheel"]["arrays"]["J_links"]
    assert a1["crank"][0] == pytest.approx(0.0015 + m1 * 0.06 ** 2, rel=1e-12)
    assert a0["crank"][0] == pytest.approx(0.0015, rel=1e-12)
    J_O3 = 0.0085 + 1.8 * 0.11 ** 2
    k = 1 + m3 * 0.08 ** 2 / J_O3
    for x0, x1 in zip(a0["rocker"], a1["rocker"]):
        assert x1 == pytest.approx(k * x0, rel=1e-9, abs=1e-15)
    assert a1["coupler"] == pytest.approx(a0["coupler"], rel=1e-12)
    assert bal["flywheel"]["J"] != pytest.approx(plain["flywheel"]["J"], rel=1e-6)


def test_applied_links_by_hand(applied):
    """`balancing.applied`: the crank (1.0 kg at O, J 0.0015) with m1' at r1 = 0.06 opposite A:
    mass 1 + m1', centre of mass at -m1' 0.06/(1 + m1') on its axis, J about it by parallel axes."""
    _, bal = applied
    m1 = bal["balancing"]["counterweights"]["crank"]["m"]
    ang = math.radians(bal["balancing"]["counterweights"]["crank"]["angle"])
    c = bal["balancing"]["applied"]["crank"]
    M = 1.0 + m1
    sx, sy = m1 * 0.06 * math.cos(ang) / M, m1 * 0.06 * math.sin(ang) / M
    assert c["mass"] == pytest.approx(M, rel=1e-12)
    assert c["com"] == pytest.approx([sx, sy], abs=1e-12)
    assert c["J"] == pytest.approx(0.0015 + 1.0 * (sx ** 2 + sy ** 2) + m1 * ((0.06 * math.cos(ang) - sx) ** 2
                                                                           + (0.06 * math.sin(ang) - sy) ** 2), rel=1e-12)
    assert "applied" not in applied[0]["balancing"]


def test_apply_without_counterweights_exit_2(tmp_path):
    text = (ROOT / "tasks" / "balancing_fourbar.yaml").read_text(encoding="utf-8")
    cut = "  counterweights:\n    method: full\n    radius: {crank: 60 mm, rocker: 80 mm}\n"
    assert cut in text and "  apply: true\n" in text
    text = text.replace(cut, "")
    code, out = _run(tmp_path, text)
    assert code == 2 and "`apply: true` needs `counterweights`" in out and "balancing.apply" in out
    assert "Traceback" not in out


def test_counterweights_drawing_names_each_mass(shared_once):
    """The report's drawing of the counterweights labels each disc with its mass in kg (the
    word `bal.kg` is '{m} kg'): the masses of results, as the report formats them."""
    from pdf_extent import report_out
    out = report_out(shared_once, "balancing_fourbar", "ru")      # as tmm run writes it, once a session
    svg = (out / "figures" / "balancing-counterweights.svg").read_text(encoding="utf-8")
    cw = json.loads((out / "results.json").read_text())["balancing"]["counterweights"]
    for c in cw.values():
        assert f"{c['m']:.4g}".replace(".", ",") + " кг" in svg


@pytest.mark.parametrize("lang", ["en", "uk"])
def test_task_table_counterweight_radii_alike(lang, shared_once):
    """The task-data table writes both counterweights' radii alike: the names carry the unit
    (', m'), the values none — `rocker` is a link's name here, not the synthesis' rocker length."""
    import re as _re

    from pdf_extent import report_out
    html = (report_out(shared_once, "balancing_fourbar", lang) / "report.html").read_text(encoding="utf-8")
    cells = _re.findall(r"<tr><td>([^<]*(?:crank|rocker|кривошип|коромисл)[^<]*(?:radius|радіус)[^<]*)</td>"
                        r"<td[^>]*>([^<]*)</td>", html)
    assert len(cells) == 2, cells
    assert sorted(v for _, v in cells) == (["0.06", "0.08"] if lang == "en" else ["0,06", "0,08"])


def test_apply_with_nothing_to_act_on_is_said(tmp_path):
    """`apply: true` in a task with neither kinetostatics nor a flywheel changed nothing, without a
    word; the example (which asks for the kinetostatics) has no such warning."""
    text = (ROOT / "tasks" / "balancing_fourbar.yaml").read_text(encoding="utf-8")
    assert "\nkinetostatics: {}\n" in text and "apply: true" in text and "\nflywheel:" not in text
    f = tmp_path / "t.yaml"
    f.write_text(text.replace("\nkinetostatics: {}\n", "\n"), encoding="utf-8")
    res = run(load_task(f))
    said = "`apply: true` changes nothing here"
    assert any(said in w for w in res["warnings"]), res["warnings"]
    assert not any(said in w for w in run(load_task(ROOT / "tasks" / "balancing_fourbar.yaml"))["warnings"])


def test_the_largest_shaking_force_and_moment_are_the_maxima_not_a_grids():
    """balancing.max is the maximum over the turn: the largest |F| and |M| of the momenta's rates
    (the second method above) on a 0.001-degree grid in the degree either side of the 1-degree
    grid's peak agree with it to 1e-7 (the differences' own error), and it is above the 1-degree
    grid's largest, which alone was low by O(step^2) (59.0557 N against 59.0582 N for
    tasks/balancing_fourbar.yaml)."""
    w = 120 * math.pi / 30
    task = _task(FOURBAR, {})
    b = run(task)["balancing"]
    phi1 = np.arange(361) * 1.0
    h = 1e-4
    dt = math.radians(h) / w

    def rates(phi):
        (Pp, Hp), (Pm, Hm) = _momenta(task, phi + h, w), _momenta(task, phi - h, w)
        return np.hypot(*((Pp - Pm) / (2 * dt)).T), np.abs((Hp - Hm) / (2 * dt))
    F1, M1 = rates(phi1)
    for grid, key in ((F1, 0), (M1, 1)):
        fine = phi1[int(np.argmax(grid))] + np.arange(-1.0, 1.0 + 1e-9, 0.001)
        best = rates(fine)[key].max()
        want = b["max"]["FM"[key]]
        assert best == pytest.approx(want, rel=1e-7)
        assert want >= grid.max() * (1 - 1e-9)
