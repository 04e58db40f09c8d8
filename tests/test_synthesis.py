"""Lever synthesis from K and the stroke: every design is checked by ANALYSING the
generated mechanism (its extreme positions and its transmission angle over the cycle,
found by the kinematics) -- it must reproduce H (or psi), K and gamma_min to 1e-9 --
and against hand calculations written out here."""
import math
import re
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings, strategies as st
from typer.testing import CliRunner

from tmm_cli.cli import app
from tmm_cli.errors import StageError, TaskError
from tmm_cli.linkage.mechanism import build_mechanism
from tmm_cli.linkage.synthesis import K_of_theta, analyse, generate, theta_of_K
from tmm_cli.task import load_task

TASKS = Path(__file__).resolve().parent.parent / "tasks"
runner = CliRunner()


def design(syn, direction="ccw", drive=None):
    t, d = generate(load_task({"schema": "tmm/1", "synthesis": syn,
                               "drive": drive or {"link": "crank", "speed": 10, "direction": direction}}))
    from tmm_cli.linkage import kinematics, structure
    from tmm_cli.linkage.context import Linkage
    from tmm_cli.linkage.drive_speed import resolve
    mech = build_mechanism(t)
    pos = kinematics.find_positions(mech, t.positions, t.drive.sign)
    linkage = Linkage(mechanism=mech, structure=structure.analyze(mech, task=t), drive=resolve(t.drive, pos),
                      positions=pos, loads=t.loads)
    from tmm_cli.linkage import transmission
    from tmm_cli.linkage.synthesis import least_of
    return t, analyse(linkage, d, least_of(transmission.analyze(linkage)))


def test_spec_example_offset_slider_crank_by_hand():
    # H = 0.2, K = 1.2: theta = 180 * 0.2/2.2 = 16.3636 deg, tan(theta/2) = 0.143778,
    # r^2 = H^2/4 - (H e/2) tan(theta/2) = 0.01 - 0.005 * 0.143778 = 0.0092811 -> r = 0.096338;
    # l^2 = r^2 + H e/sin(theta) = 0.0092811 + 0.01/0.281733 = 0.044776 -> l = 0.211603;
    # gamma_min = arccos((r + e)/l) = arccos(0.146338/0.211603) = 46.245 deg
    t, r = design({"type": "offset_slider_crank", "H": 0.2, "K": 1.2, "e": 0.05})
    L = r["lengths"]
    assert L["crank"] == pytest.approx(0.096338, abs=1e-6)
    assert L["rod"] == pytest.approx(0.211603, abs=1e-6)
    assert L["offset"] == 0.05
    assert r["gamma_min"] == pytest.approx(46.245, abs=1e-3)
    assert r["H"] == pytest.approx(0.2, abs=1e-12)
    assert r["K"] == pytest.approx(1.2, abs=1e-9)
    assert r["theta"] == pytest.approx(16.363636363636, abs=1e-9)
    assert r["psi"] is None and r["working"] == "forward" and r["solutions"] == []
    # the generated section, as SPEC'd: O at the origin, guide y = -e, B to the right
    m = r["mechanism"]
    assert m["ground"] == {"O": [0.0, 0.0]}
    assert list(m["links"]) == ["crank", "rod", "slider"]
    assert m["links"]["slider"]["guide"] == {"through": [0.0, -0.05], "angle": 0.0}
    assert m["assembly"]["B"][0] > 0
    assert t.positions.output == "slider" and t.positions.working == "forward"


def test_cw_mirrors_the_guide():
    t, r = design({"type": "offset_slider_crank", "H": 0.2, "K": 1.2, "e": 0.05}, "cw")
    assert r["mechanism"]["links"]["slider"]["guide"]["through"] == [0.0, 0.05]
    assert r["K"] == pytest.approx(1.2, abs=1e-9) and r["working"] == "forward"


def test_central_slider_crank_by_hand():
    # r = H/2 = 0.08; lambda = 1/cos(70 deg) = 2.923804 -> l = 0.233904
    t, r = design({"type": "slider_crank", "H": 0.16, "gamma_min": 70})
    assert r["lengths"] == {"crank": 0.08, "rod": pytest.approx(0.08 / math.cos(math.radians(70)), rel=1e-12),
                            "offset": 0.0}
    assert r["H"] == pytest.approx(0.16, abs=1e-12) and r["K"] == pytest.approx(1.0, abs=1e-9)
    assert r["gamma_min"] == pytest.approx(70.0, abs=1e-9)
    t, r = design({"type": "slider_crank", "H": 0.16, "lambda": 4})
    assert r["lengths"]["rod"] == pytest.approx(0.32)
    assert r["gamma_min"] == pytest.approx(math.degrees(math.acos(0.25)), abs=1e-9)


def _stroke(r, l, e):
    """The stroke of a slider-crank (B ahead of A): extended minus folded dead centre."""
    return math.sqrt((l + r) ** 2 - e * e) - math.sqrt((l - r) ** 2 - e * e)


_common = dict(max_examples=6, deadline=None, suppress_health_check=[HealthCheck.too_slow])


@settings(**_common)
@given(H=st.floats(0.05, 0.5), K=st.floats(1.05, 1.8), frac=st.floats(0.05, 0.6))
def test_offset_from_e_reproduces_H_K(H, K, frac):
    e_max = H / (2 * math.tan(math.radians(theta_of_K(K)) / 2))
    e = frac * e_max
    try:
        t, r = design({"type": "offset_slider_crank", "H": H, "K": K, "e": e})
    except StageError:
        # only when the crank cannot turn (l - r < e) or the lengths of the construction
        # give another stroke (the folded extreme behind the foot of the perpendicular)
        th = math.radians(theta_of_K(K))
        r2 = H * H / 4 - H * e / 2 * math.tan(th / 2)
        rr, ll = math.sqrt(r2), math.sqrt(r2 + H * e / math.sin(th))
        assert ll - rr < e or abs(_stroke(rr, ll, e) - H) > 1e-9
        return
    L = r["lengths"]
    assert r["H"] == pytest.approx(H, rel=1e-9) and r["K"] == pytest.approx(K, abs=1e-9)
    assert r["gamma_min"] == pytest.approx(math.degrees(math.acos((L["crank"] + e) / L["rod"])), abs=1e-9)


@settings(**_common)
@given(H=st.floats(0.05, 0.5), K=st.floats(1.05, 1.8), lam=st.floats(2.5, 6.0))
def test_offset_from_lambda_reproduces_H_K_lambda(H, K, lam):
    try:
        t, r = design({"type": "offset_slider_crank", "H": H, "K": K, "lambda": lam})
    except StageError as exc:
        # lambda above cot^2(theta/2): r^2 = c H^2/(4 (lambda^2 - 1 + c)) gives 4 l r < H^2
        assert lam > 1 / math.tan(math.radians(theta_of_K(K)) / 2) ** 2 or "cannot turn" in str(exc)
        return
    L = r["lengths"]
    assert L["rod"] / L["crank"] == pytest.approx(lam, rel=1e-12)
    assert r["H"] == pytest.approx(H, rel=1e-9) and r["K"] == pytest.approx(K, abs=1e-9)
    assert r["gamma_min"] == pytest.approx(math.degrees(math.acos((L["crank"] + L["offset"]) / L["rod"])),
                                           abs=1e-9)


@settings(**_common)
@given(H=st.floats(0.05, 0.5), K=st.floats(1.05, 1.5), g=st.floats(10.0, 35.0))
def test_offset_from_gamma_reproduces_H_K_gamma(H, K, g):
    t, r = design({"type": "offset_slider_crank", "H": H, "K": K, "gamma_min": g})
    assert r["H"] == pytest.approx(H, rel=1e-9) and r["K"] == pytest.approx(K, abs=1e-9)
    assert r["gamma_min"] == pytest.approx(g, abs=1e-9)
    # both roots listed, the smaller offset chosen, each with the required gamma_min
    sols = r["solutions"]
    assert sols[0]["chosen"] and sols[0]["offset"] == r["lengths"]["offset"]
    for s in sols:
        assert math.degrees(math.acos((s["crank"] + s["offset"]) / s["rod"])) == pytest.approx(g, abs=1e-9)
    assert [s["offset"] for s in sols] == sorted(s["offset"] for s in sols)


@settings(**_common)
@given(psi=st.floats(20.0, 70.0), K=st.floats(1.05, 1.5), c=st.floats(0.2, 0.5), dc=st.floats(1.0, 1.8),
       direction=st.sampled_from(["ccw", "cw"]))
def test_crank_rocker_reproduces_psi_K_gamma(psi, K, c, dc, direction):
    syn = {"type": "crank_rocker", "psi": psi, "K": K, "rocker": c, "frame": c * dc}
    try:
        t, r = design(syn, direction)
    except StageError as exc:
        assert "synthesis" in str(exc) and "frame" in str(exc)
        return
    assert r["psi"] == pytest.approx(psi, abs=1e-9) and r["K"] == pytest.approx(K, abs=1e-9)
    assert r["H"] is None
    chosen = [s for s in r["solutions"] if s["chosen"]]
    assert len(chosen) == 1
    assert r["gamma_min"] == pytest.approx(chosen[0]["gamma_min"], abs=1e-9)
    assert all(s["gamma_min"] <= chosen[0]["gamma_min"] for s in r["solutions"])
    # the default working stroke is the slow one: K > 1 from positions with it
    assert t.positions.working == r["working"]


def test_crank_rocker_both_solutions_analysed():
    # every listed solution, generated as a mechanism, has the required psi and K
    t, r = design({"type": "crank_rocker", "psi": 40, "K": 1.2, "rocker": 0.3, "frame": 0.4})
    assert len(r["solutions"]) == 2
    for s in r["solutions"]:
        a, b, c, d = s["crank"], s["coupler"], s["rocker"], s["frame"]
        # extremes: crank and coupler collinear; rocker angles at O1 from the triangles
        b2 = math.degrees(math.acos((d * d + c * c - (a + b) ** 2) / (2 * d * c)))
        b1 = math.degrees(math.acos((d * d + c * c - (b - a) ** 2) / (2 * d * c)))
        assert abs(b1 - b2) == pytest.approx(40.0, abs=1e-9)
        p2 = math.degrees(math.acos((d * d + (a + b) ** 2 - c * c) / (2 * d * (a + b))))
        p1 = math.degrees(math.acos((d * d + (b - a) ** 2 - c * c) / (2 * d * (b - a))))
        assert abs(p1 - p2) == pytest.approx(theta_of_K(1.2), abs=1e-9)


# ---------------------------------------------------------------- crank-rocker with K = 1 (theta = 0)
K1 = {"type": "crank_rocker", "psi": 40, "K": 1, "rocker": 0.3, "frame": 0.4}


@pytest.mark.parametrize("direction", ["ccw", "cw"])
def test_crank_rocker_K1_closed_form(direction):
    # theta = 0: the crank pivot O on the line C1C2 of the rocker's extreme points, at `frame`
    # from O1; in the rocker's frame C1,2 = (+-c sin(psi/2), c cos(psi/2)), O = (x, c cos(psi/2)),
    # x = sqrt(d^2 - c^2 cos^2(psi/2)): |OC2| = x + c sin(psi/2) = b + a, |OC1| = x - c sin(psi/2) = b - a
    t, r = design(K1, direction)
    h = math.radians(20.0)
    a, b = 0.3 * math.sin(h), math.sqrt(0.16 - (0.3 * math.cos(h)) ** 2)
    L = r["lengths"]
    assert L["crank"] == pytest.approx(a, rel=1e-14) and L["coupler"] == pytest.approx(b, rel=1e-14)
    assert (L["rocker"], L["frame"]) == (0.3, 0.4)
    # analysed: the extremes 180 deg apart, the swing as asked
    assert r["K"] == pytest.approx(1.0, abs=1e-9) and r["theta"] == pytest.approx(0.0, abs=1e-7)
    assert r["psi"] == pytest.approx(40.0, abs=1e-9)
    # one solution (the mirror image across the swing's bisector is the same linkage), chosen
    assert [(s["side"], s["chosen"]) for s in r["solutions"]] == [("line", True)]
    assert r["gamma_min"] == pytest.approx(r["solutions"][0]["gamma_min"], abs=1e-9)
    assert r["construction"]["circle"] is None              # no circle: O on the line C1C2
    assert t.positions.working == r["working"]


def test_crank_rocker_continuous_at_K1():
    """K = 1 + 1e-9 gives the lengths of K = 1 to within the change the lengths' slope allows.

    theta(1 + 1e-9) = 9e-8 deg = 1.6e-9 rad. The lengths are smooth in theta (the height of O
    above the chord, y - h0 = (d^2 - c^2) tan(theta)/(2 (h0 tan(theta) +- w)), is written without
    the circle's centre and radius, which grow as 1/theta and cancelled to ~1e-8 m before), so
    they move by |dL/dtheta| theta: the slope is measured at K = 1 + 1e-6 and the tolerance is
    twice the change it gives plus a few ulps (~1e-9 m here)."""
    from tmm_cli.linkage.synthesis import crank_rocker_solutions
    at = lambda K: design({**K1, "K": K})[1]
    r0, r9, r6 = at(1.0), at(1.0 + 1e-9), at(1.0 + 1e-6)
    th9, th6 = math.radians(theta_of_K(1.0 + 1e-9)), math.radians(theta_of_K(1.0 + 1e-6))
    for k in ("crank", "coupler", "rocker", "frame"):
        slope = abs(r6["lengths"][k] - r0["lengths"][k]) / th6
        assert abs(r9["lengths"][k] - r0["lengths"][k]) <= 2.0 * slope * th9 + 4e-16, k
    assert r9["gamma_min"] == pytest.approx(r0["gamma_min"], abs=1e-6)
    assert r9["working"] == r0["working"]          # the slow stroke's limit: the side K = 1 continues
    # both sides converge on the one solution of K = 1
    sols = crank_rocker_solutions(40.0, theta_of_K(1.0 + 1e-9), 0.3, 0.4)
    assert [s["side"] for s in sols] == ["far", "near"]
    for s in sols:
        assert s["coupler"] == pytest.approx(r0["lengths"]["coupler"], abs=1e-8)


def test_crank_rocker_K1_example_runs(tmp_path):
    import json
    import yaml
    task = yaml.safe_load((TASKS / "synthesis_crank_rocker.yaml").read_text())
    task["synthesis"]["K"] = 1
    f = tmp_path / "t.yaml"
    f.write_text(yaml.safe_dump(task))
    res = runner.invoke(app, ["run", str(f), "--out", str(tmp_path / "o"), "-f", "json", "-q"])
    assert res.exit_code == 0, res.output
    r = json.loads((tmp_path / "o" / "results.json").read_text())
    assert r["positions"]["K"] == pytest.approx(1.0, abs=1e-9) and not r["warnings"]


def test_crank_rocker_K1_frame_not_beyond_the_rocker_exit_3():
    # O on the line C1C2 outside the chord needs frame > rocker
    with pytest.raises(StageError) as ei:
        design({**K1, "frame": 0.29})
    assert ei.value.message.code == "synthesis.fail.crank_rocker_none"


@pytest.mark.parametrize("key, value", [("K", 0.9), ("theta", -5.0)])
def test_crank_rocker_K_below_one_exit_2(tmp_path, key, value):
    import yaml
    syn = {k: v for k, v in K1.items() if k != "K"} | {key: value}
    with pytest.raises(TaskError) as ei:
        load_task({"schema": "tmm/1", "synthesis": syn, "drive": {"link": "crank", "speed": 10}})
    assert [f for f, *_ in ei.value.issues] == [f"synthesis.{key}"]
    f = tmp_path / "t.yaml"
    f.write_text(yaml.safe_dump({"schema": "tmm/1", "synthesis": syn, "drive": {"link": "crank", "speed": 10}}))
    res = runner.invoke(app, ["run", str(f), "--out", str(tmp_path / "o"), "-f", "json", "-q"])
    assert res.exit_code == 2 and "K >= 1" in res.output, res.output


@settings(**_common)
@given(K=st.floats(1.1, 2.5), f=st.floats(0.1, 0.6), direction=st.sampled_from(["ccw", "cw"]))
def test_slotted_lever_reproduces_K_psi(K, f, direction):
    t, r = design({"type": "slotted_lever", "K": K, "frame": f}, direction)
    th = theta_of_K(K)
    assert r["K"] == pytest.approx(K, abs=1e-9) and r["psi"] == pytest.approx(th, abs=1e-9)
    assert r["lengths"]["crank"] == pytest.approx(f * math.sin(math.radians(th) / 2), rel=1e-12)
    assert r["lengths"]["rocker"] == pytest.approx(1.5 * (f + r["lengths"]["crank"]), rel=1e-12)
    assert r["gamma_min"] == 90.0
    assert r["working"] == ("forward" if direction == "ccw" else "backward")
    assert r["mechanism"]["ground"]["O1"] == [0.0, -f if direction == "ccw" else f]


@settings(**_common)
@given(K=st.floats(1.1, 2.0), f=st.floats(0.1, 0.4), H=st.floats(0.3, 0.8), direction=st.sampled_from(["ccw", "cw"]))
def test_shaper_reproduces_H_K_psi_gamma(K, f, H, direction):
    try:
        t, r = design({"type": "shaper", "K": K, "frame": f, "H": H}, direction)
    except StageError as exc:
        assert "synthesis.rocker" in str(exc)
        th = math.radians(theta_of_K(K))
        assert H / (2 * math.sin(th / 2)) < f * (1 + math.sin(th / 2))
        return
    th = theta_of_K(K)
    assert r["H"] == pytest.approx(H, rel=1e-9) and r["K"] == pytest.approx(K, abs=1e-9)
    assert r["psi"] == pytest.approx(th, abs=1e-9)
    # at the ram the block presses normal to the slotted link: gamma = 90 - deviation from vertical
    assert r["gamma_min"] == pytest.approx(90.0 - th / 2, abs=1e-9)
    assert r["lengths"]["guide_height"] == pytest.approx(H / (2 * math.tan(math.radians(th) / 2)), rel=1e-12)
    assert r["working"] == "backward" and t.positions.output == "ram"


# ---------------------------------------------------------------- impossible requirements (exit 3)
IMPOSSIBLE = [
    ({"type": "offset_slider_crank", "H": 0.2, "K": 1.2, "e": 0.8}, "synthesis.e"),
    ({"type": "offset_slider_crank", "H": 0.2, "K": 1.2, "gamma_min": 60}, "synthesis.gamma_min"),
    ({"type": "offset_slider_crank", "H": 0.5, "K": 1.75, "lambda": 5}, "lower lambda (at most cot^2(theta/2)"),
    ({"type": "offset_slider_crank", "H": 0.2, "K": 3.5, "gamma_min": 10}, "synthesis.K"),
    ({"type": "crank_rocker", "psi": 40, "K": 1.2, "rocker": 0.3, "frame": 5.0}, "change frame or rocker"),
    ({"type": "shaper", "H": 0.4, "K": 1.6, "frame": 0.3, "guide_height": 0.3}, "synthesis.guide_height"),
    ({"type": "slotted_lever", "K": 1.6, "frame": 0.3, "rocker": 0.2}, "synthesis.rocker"),
]


@pytest.mark.parametrize("syn,needle", IMPOSSIBLE)
def test_impossible_requirement_exit_3(tmp_path, syn, needle):
    import yaml
    f = tmp_path / "t.yaml"
    f.write_text(yaml.safe_dump({"schema": "tmm/1", "synthesis": syn, "drive": {"link": "crank", "speed": 10},
                                 "positions": {"count": 12}}))
    res = runner.invoke(app, ["run", str(f), "--out", str(tmp_path / "o"), "-f", "json", "-q"])
    assert res.exit_code == 3, res.output
    assert "synthesis" in res.output and needle in res.output


@pytest.mark.parametrize("syn,needle", IMPOSSIBLE + [
    ({"type": "offset_slider_crank", "H": 0.5, "K": 1.75, "e": 0.5}, "lower e (at most 0.433252 m)"),
    ({"type": "shaper", "H": 0.4, "K": 1.6, "frame": 0.3, "rocker": 0.3}, "synthesis.rocker"),
    ({"type": "shaper", "H": 0.1, "K": 1.6, "frame": 0.3}, "synthesis.rocker"),
])
def test_impossible_requirement_is_catalogued(syn, needle):
    """Every refusal is a catalogued message: its English text as before, and the same
    parameters rendered in ru and uk with no English sentence left."""
    from tmm_cli.messages import LANGS, localize
    with pytest.raises(StageError) as ei:
        design(syn)
    m = ei.value.message
    assert m.code.startswith("synthesis.fail.") and needle in m, m
    for lang in LANGS:
        if lang != "en":
            text = localize(m.to_dict(), lang)
            assert text != str(m) and not re.search(r"\b(the|with|lower|raise|change)\b", text), text


def test_gamma_too_large_names_the_largest():
    with pytest.raises(StageError) as ei:
        design({"type": "offset_slider_crank", "H": 0.2, "K": 1.2, "gamma_min": 60})
    # the maximum of gamma(e) over the offsets (a scan of the closed form)
    th = math.radians(theta_of_K(1.2))
    best = 0.0
    for k in range(1, 20000):
        e = k / 20000 * 0.2 / (2 * math.tan(th / 2))
        r = math.sqrt(0.01 - 0.1 * e * math.tan(th / 2))
        l = math.sqrt(r * r + 0.2 * e / math.sin(th))
        best = max(best, math.degrees(math.acos(min(1, (r + e) / l))))
    assert f"{best:.3f}" in str(ei.value) or f"{best:.4f}"[:-1] in str(ei.value)


# ---------------------------------------------------------------- invalid input (exit 2)
BAD = [
    ({"synthesis": {"type": "slider_crank", "H": 0.2, "lambda": 4}, "mechanism": {"ground": {"O": [0, 0]},
      "links": {"crank": {"points": ["O", "A"], "length": 0.1}}}}, "synthesis"),
    ({"synthesis": {"type": "slider_crank", "H": 0.2, "K": 1.2, "lambda": 4}}, "synthesis.K"),
    ({"synthesis": {"type": "slider_crank", "H": 0.2, "e": 0.01, "lambda": 4}}, "synthesis.e"),
    ({"synthesis": {"type": "offset_slider_crank", "H": 0.2, "K": 1.2}}, "synthesis"),
    ({"synthesis": {"type": "offset_slider_crank", "H": 0.2, "K": 1.2, "e": 0.01, "lambda": 4}}, "synthesis"),
    ({"synthesis": {"type": "crank_rocker", "psi": 40, "K": 1.2, "rocker": 0.3}}, "synthesis.frame"),
    ({"synthesis": {"type": "slotted_lever", "K": 1.6, "frame": 0.3, "links": {"rod": {"mass": 1}}}},
     "synthesis.links.rod"),
    ({"synthesis": {"type": "slider_crank", "H": 0.2, "lambda": 0.9}}, "synthesis.lambda"),
]


@pytest.mark.parametrize("extra,field", BAD)
def test_invalid_synthesis_exit_2(extra, field):
    with pytest.raises(TaskError) as ei:
        load_task({"schema": "tmm/1", "drive": {"link": "crank", "speed": 10}, **extra})
    assert any(f == field or f.startswith(field) for f, *_ in ei.value.issues), ei.value.render()


def test_generated_links_are_checked_by_name():
    # loads, drive and positions name the generated links
    with pytest.raises(TaskError) as ei:
        t = load_task({"schema": "tmm/1", "synthesis": {"type": "slider_crank", "H": 0.2, "lambda": 4},
                       "drive": {"link": "crank", "speed": 10},
                       "loads": {"forces": [{"on": "ram", "magnitude": 100, "kind": "resistance"}]}})
        from tmm_cli.pipeline import run
        run(t)
    assert "ram" in ei.value.render()


def test_example_tasks_run(tmp_path):
    import json
    for name in ("synthesis_offset_slider_crank", "synthesis_crank_rocker", "synthesis_shaper"):
        res = runner.invoke(app, ["run", str(TASKS / f"{name}.yaml"), "--out", str(tmp_path / name), "-f", "json",
                                  "-q"])
        assert res.exit_code == 0, res.output
        r = json.loads((tmp_path / name / "results.json").read_text())
        s = r["synthesis"]
        assert set(s) >= {"type", "lengths", "H", "K", "theta", "psi", "gamma_min", "working", "solutions",
                          "mechanism"}
        # the results' positions (of the task) agree with the synthesis' own analysis
        assert r["positions"]["K"] == pytest.approx(s["K"], abs=1e-12)
        assert s["K"] == pytest.approx(K_of_theta(s["theta"]), rel=1e-12)


@pytest.mark.parametrize("psi", [40, 50])
def test_the_least_transmission_angle_lies_where_crank_and_frame_are_collinear(psi):
    """A crank-rocker's transmission angle is least with the crank along the frame line (the
    diagonal A O1 longest or shortest): gamma_min_phi is exactly 0 or 180 deg -- it was
    1.694e-07 (psi 50) and 180.00000000000347 (psi 40), the flat least's place to the search's
    accuracy -- and gamma_min is the law of cosines there, by hand."""
    import yaml
    data = yaml.safe_load((TASKS / "synthesis_crank_rocker.yaml").read_text(encoding="utf-8"))
    data["synthesis"]["psi"] = psi
    from tmm_cli import load_task, run
    res = run(load_task(data))["synthesis"]
    a, b, c, d = (res["lengths"][k] for k in ("crank", "coupler", "rocker", "frame"))
    assert res["gamma_min_phi"] in (0.0, 180.0), res["gamma_min_phi"]
    # the generated four-bar has O1 on +x from O: at 0 deg the crank points at O1 (A O1 = d - a)
    f = d - a if res["gamma_min_phi"] == 0.0 else d + a
    gamma = math.degrees(math.acos((b * b + c * c - f * f) / (2 * b * c)))
    assert min(gamma, 180 - gamma) == pytest.approx(res["gamma_min"], abs=1e-9)
    other = d + a if f == d - a else d - a
    g2 = math.degrees(math.acos((b * b + c * c - other * other) / (2 * b * c)))
    assert min(g2, 180 - g2) >= res["gamma_min"] - 1e-9


@pytest.mark.parametrize("syn", [
    {"type": "slotted_lever", "K": 1.0, "frame": 0.3},
    {"type": "slotted_lever", "theta": -10.0, "frame": 0.3},
    {"type": "offset_slider_crank", "K": 0.8, "H": 0.1, "e": 0.02},
    {"type": "shaper", "K": 0.95, "frame": 0.3, "H": 0.5}])
def test_quick_return_types_with_K_not_above_one_exit_2(tmp_path, syn):
    """A slotted lever, a shaper and an offset slider-crank have a quick return (K > 1): K <= 1
    (theta <= 0) is an input error naming its field and line (exit 2), found by `tmm validate`
    too, not a stage failure of a valid task (exit 3)."""
    import yaml
    key = "K" if "K" in syn else "theta"
    task = {"schema": "tmm/1", "synthesis": syn, "drive": {"link": "crank", "speed": 10}}
    with pytest.raises(TaskError) as ei:
        load_task(task)
    assert [f for f, *_ in ei.value.issues] == [f"synthesis.{key}"]
    f = tmp_path / "t.yaml"
    f.write_text(yaml.safe_dump(task, sort_keys=False))
    line = f.read_text().splitlines().index(f"  {key}: {syn[key]}") + 1
    res = runner.invoke(app, ["validate", str(f)])
    assert res.exit_code == 2 and "needs K > 1 (theta > 0 deg)" in res.output, res.output
    assert f"t.yaml:{line}:3: field 'synthesis.{key}'" in res.output
    ru = runner.invoke(app, ["run", str(f), "--out", str(tmp_path / "o"), "--lang", "ru"])
    assert ru.exit_code == 2 and f"поле «synthesis.{key}»: для синтеза типа {syn['type']} нужен K > 1" in ru.output


@pytest.mark.parametrize("name, calls", [("synthesis_crank_rocker", 1), ("synthesis_shaper", 1),
                                         ("synthesis_function_log10", 1), ("synthesis_function", 2)])
def test_the_least_transmission_angle_is_sought_once(name, calls, monkeypatch):
    """The synthesis reports the transmission stage's least (one search of the crank angles for
    both, the same number); a crank-rocker function generator searches its input range besides
    its full turn."""
    from pathlib import Path

    import tmm_cli
    from tmm_cli.linkage import transmission
    seen = []
    real = transmission.least
    monkeypatch.setattr(transmission, "least", lambda *a, **k: seen.append(a[2:]) or real(*a, **k))
    res = tmm_cli.run(tmm_cli.load_task(Path(__file__).resolve().parents[1] / "tasks" / f"{name}.yaml"))
    assert len(seen) == calls, seen
    if name != "synthesis_function":
        least = min((r["gamma_min"], r["phi"]) for r in res["transmission"])
        assert (res["synthesis"]["gamma_min"], res["synthesis"]["gamma_min_phi"]) == least
