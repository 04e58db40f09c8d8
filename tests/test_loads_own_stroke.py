"""A stroke-dependent load on a slider that is not the output follows that slider's own
stroke: its own extreme crank angles (added as positions), its own stroke H and its own
working sense (the load's `working`, default positions.working along its own guide),
docs/methods.md §3.3. Checked against a hand calculation of a two-piston machine."""
from __future__ import annotations

import math

import pytest

import tmm_cli

R, L, E = 0.05, 0.2, 0.03          # crank, both rods, offset of cylinder 2's axis (m)
P1 = 500.0                          # constant resistance on piston 1's working stroke, N
P2 = 1000.0                         # piston 2: resistance growing linearly with its s/H


def _task(working2: str | None = "backward") -> dict:
    """Two pistons on one crank pin A: piston 1 on the x axis through O (the output),
    piston 2 on the vertical line x = E (an offset V at 90 deg)."""
    load2 = {"on": "piston2", "kind": "resistance", "diagram": {"s": [0, 1], "value": [0, P2]}}
    if working2:
        load2["working"] = working2
    return {"schema": "tmm/1",
            "mechanism": {"ground": {"O": [0, 0]}, "links": {
                "crank": {"points": ["O", "A"], "length": R},
                "rod1": {"points": ["A", "B"], "length": L},
                "piston1": {"slider": "B", "guide": {"through": "O", "angle": 0}},
                "rod2": {"points": ["A", "C"], "length": L},
                "piston2": {"slider": "C", "guide": {"through": [E, 0], "angle": 90}}},
                "assembly": {"B": [0.25, 0], "C": [E, 0.2]}},
            "drive": {"link": "crank", "speed": "100 rpm", "direction": "ccw"},
            "positions": {"output": "piston1", "working": "forward"},
            "loads": {"forces": [{"on": "piston1", "kind": "resistance", "magnitude": P1}, load2]},
            "kinetostatics": {"inertia": False}}


# ---- hand calculation ------------------------------------------------------------
# piston 2's extremes: crank and rod 2 in one line, C on x = E:
#   outer dead centre |OC| = L + R: y = sqrt((L+R)^2 - E^2) = sqrt(0.0616) = 0.248193 m,
#     crank along OC: phi = atan2(0.248193, 0.03) = 83.1079 deg;
#   inner dead centre |OC| = L - R: y = sqrt((L-R)^2 - E^2) = sqrt(0.0216) = 0.146969 m,
#     crank opposite to OC: phi = atan2(0.146969, 0.03) + 180 = 258.4630 deg.
#   H2 = 0.248193 - 0.146969 = 0.101224 m (not 2R: the axis is offset).
# `working: backward`: the working stroke runs from the outer (max y) to the inner dead
# centre, ccw from 83.1079 to 258.4630 deg (175.355 deg of crank rotation).
Y_OUT = math.sqrt((L + R) ** 2 - E ** 2)
Y_IN = math.sqrt((L - R) ** 2 - E ** 2)
PHI_OUT = math.degrees(math.atan2(Y_OUT, E))
PHI_IN = math.degrees(math.atan2(Y_IN, E)) + 180.0
H2 = Y_OUT - Y_IN


def _hand(phi_deg: float) -> tuple[float, float, float]:
    """(F1 along +x, F2 along +y, balancing moment) at a crank angle, by hand."""
    p = math.radians(phi_deg)
    xa, ya = R * math.cos(p), R * math.sin(p)
    dxa, dya = -R * math.sin(p), R * math.cos(p)               # d/dphi of A
    # piston 1: x_B = xa + sqrt(L^2 - ya^2); its working stroke (forward, +x) is the
    # crank's half-turn 180 -> 360 deg (phi0 = 180, the inner dead centre)
    root1 = math.sqrt(L ** 2 - ya ** 2)
    dxb = dxa - ya * dya / root1
    on1 = (phi_deg % 360.0) >= 180.0 - 1e-9
    f1 = -P1 if on1 else 0.0                                   # against the +x motion
    # piston 2: y_C = ya + sqrt(L^2 - (E - xa)^2); dy_C/dphi from the loop's derivative
    yc = ya + math.sqrt(L ** 2 - (E - xa) ** 2)
    dyc = dya + (E - xa) * dxa / (yc - ya)
    on2 = PHI_OUT - 1e-9 <= phi_deg % 360.0 < PHI_IN - 1e-9
    s_rel = (Y_OUT - yc) / H2                                   # from the start of its stroke
    f2 = P2 * s_rel if on2 else 0.0                             # against the -y motion: +y
    # virtual power: M_b*omega + F1*v_B + F2*v_C = 0, v = (d/dphi)*omega
    mb = -(f1 * dxb + f2 * dyc)
    return f1, f2, mb


def test_hand_values_of_the_stroke():
    assert PHI_OUT == pytest.approx(83.10790, abs=1e-5)
    assert PHI_IN == pytest.approx(258.46304, abs=1e-5)
    assert H2 == pytest.approx(0.101224, abs=1e-6)


@pytest.fixture(scope="module")
def results():
    return tmm_cli.run(tmm_cli.load_task(_task()), kinematics_curve=0)


def test_own_extremes_are_added_as_positions(results):
    pos = results["positions"]
    assert pos["phi0"] == pytest.approx(180.0, abs=1e-8)        # the output's (piston 1)
    assert pos["extreme"] == pytest.approx([180.0, 0.0], abs=1e-8)
    phis = pos["phi"]
    for a in (PHI_OUT, PHI_IN):
        assert any(abs(p - a) < 1e-7 for p in phis), (a, phis)


def test_own_stroke_is_reported(results):
    st = results["positions"]["strokes"]
    assert list(st) == ["piston2"]                  # piston 1 is the output: positions.extreme
    p2 = st["piston2"]
    assert p2["extreme"] == pytest.approx([PHI_OUT, PHI_IN], abs=1e-7)
    assert p2["s_extreme"] == pytest.approx([Y_OUT, Y_IN], abs=1e-9)
    assert p2["H"] == pytest.approx(H2, abs=1e-9)
    assert p2["working"] == "backward"
    assert p2["working_stroke_angle"] == pytest.approx(PHI_IN - PHI_OUT, abs=1e-7)


def test_each_piston_follows_its_own_stroke(results):
    entries = results["kinetostatics"]
    assert len(entries) == 14
    for e in entries:
        f1, f2, mb = _hand(e["phi"])
        loads = {ld["name"]: ld for ld in e["loads"]}
        assert loads["F1"]["F"] == pytest.approx([f1, 0.0], abs=1e-6)
        assert loads["F2"]["F"] == pytest.approx([0.0, f2], abs=1e-6), e["phi"]
        assert e["balancing_moment"] == pytest.approx(mb, rel=1e-9, abs=1e-9), e["phi"]


def test_a_position_by_hand():
    # phi = 180: piston 2 in its working stroke; A = (-0.05, 0), C = (0.03, y),
    # y = sqrt(0.2^2 - 0.08^2) = 0.183303; s/H = (0.248193 - 0.183303)/0.101224 = 0.64106
    # F2 = 641.06 N; dy_C/dphi = dy_A/dphi = -0.05 m/rad (x_A' = 0) -> M_b = 641.06*0.05 = 32.053
    f1, f2, mb = _hand(180.0)
    assert f2 == pytest.approx(641.06, abs=0.01)
    assert mb == pytest.approx(32.053, abs=0.001)


def test_default_working_sense_is_positions_working_along_its_own_guide():
    # without `working` piston 2 works forward (+y, outward): from the inner to the outer
    # dead centre, ccw 258.463 -> 83.108 deg; at phi = 0 it is in that stroke, moving up:
    # y_C(0) = sqrt(0.04 - 0.0004) = 0.198997 m, s/H = (0.198997 - 0.146969)/0.101224
    r = tmm_cli.run(tmm_cli.load_task(_task(working2=None)), kinematics_curve=0)
    e = next(e for e in r["kinetostatics"] if abs(e["phi"]) < 1e-9)
    f2 = next(ld for ld in e["loads"] if ld["name"] == "F2")["F"][1]
    y0 = math.sqrt(L ** 2 - (E - R) ** 2)
    assert f2 == pytest.approx(-P2 * (y0 - Y_IN) / H2, abs=1e-6)     # against the upward motion
    assert f2 == pytest.approx(-513.99, abs=0.01)


def test_working_on_a_bar_is_invalid():
    t = _task()
    t["loads"]["forces"].append({"on": "rod2", "kind": "resistance", "magnitude": 10, "direction": 0,
                                 "working": "forward"})
    with pytest.raises(tmm_cli.TaskError) as exc:
        tmm_cli.run(tmm_cli.load_task(t), kinematics_curve=0)
    assert "loads.forces[2].working" in str(exc.value.issues)


def test_flywheel_grid_sees_both_pistons_switch():
    # the dynamics grid holds piston 2's dead centres too: M_red jumps there are resolved
    t = _task()
    t["flywheel"] = {"delta": 0.05, "constant": "driving", "resolution": 360}
    r = tmm_cli.run(tmm_cli.load_task(t), kinematics_curve=0)
    # cycle work of the resistances by hand: piston 1 P1*H1 (H1 = 2R), piston 2 the
    # triangle area P2*H2/2 over its working stroke
    # (with piston 1's stroke instead, P2*2R/2: 1.2 % less); the trapezoid rule over the
    # 360-step grid is good to ~2e-5 here
    work = P1 * 2 * R + P2 * H2 / 2.0
    assert r["flywheel"]["M_constant"] == pytest.approx(work / (2 * math.pi), rel=1e-4)


def test_load_diagrams_drawn_against_each_sliders_displacement(results, tmp_path):
    """The report's load diagrams: abscissa the displacement s = (s/H)·H of the load's own
    slider in m (not the normalised s/H), at a standard μs stated under the axis."""
    from tmm_cli.report import render_html
    from tmm_cli.report.sections.kinetostatics import _strokes

    # piston 1 (the output, in line with O): H = 2R = 0.1 m; piston 2 its own H2 (by hand above)
    assert _strokes(results["positions"]) == pytest.approx({"piston1": 2 * R, "piston2": H2}, abs=1e-9)
    html, _ = render_html(results, tmm_cli.load_task(_task()), tmp_path, "en")
    i = html.index('data-name="load-diagrams"')
    svg = html[i:html.index("</svg>", i)]
    assert "s/H" not in svg
    # 0.1 m over an axis of 110-200 mm of paper: 0.1/L in (0.0005, 0.00091] -> the series' 0.001
    assert svg.count("μs = 0.001 m/mm") == svg.count("F, N") >= 1
