"""Function generators whose crank does not turn fully (double-rockers, double-cranks): the
positions spread over the input range, the assembly checked over it only, the stages that
need a full cycle skipped with a notice. Every number against an independent value written
out here: Freudenstein's equation solved by Cramer's rule, the four-bar's position by the
intersection of two circles, the instant centres by Kennedy's theorem as two line
intersections, the edge of assembly by the triangle inequality."""
import json
import re
import math
from pathlib import Path

import numpy as np
import pytest
import yaml
from hypothesis import HealthCheck, given, settings, strategies as st
from typer.testing import CliRunner

from tmm_cli import load_task, run
from tmm_cli.cli import app
from tmm_cli.errors import StageError
from tmm_cli import locales

ROOT = Path(__file__).resolve().parents[1]
runner = CliRunner()
LOG10 = {"type": "function", "function": "log10(x)", "x": [1, 2], "points": 3, "frame": 0.1}
# Freudenstein's classic ranges for y = log10 x on [1, 2]: crank 60 deg, rocker 90 deg; the starts
# chosen so that every length is positive (a double-rocker)
CLASSIC = {**LOG10, "input": {"start": 45, "range": 60}, "output": {"start": 300, "range": 90}}


def _task(syn, **top):
    return load_task({"schema": "tmm/1", "synthesis": syn, "drive": {"link": "crank", "speed": 6.0}, **top})


def _cramer(phi_deg, psi_deg):
    """K1, K2, K3 of K1 cos psi - K2 cos phi + K3 = cos(phi - psi) through three points, by
    Cramer's rule with the 3x3 determinants written out."""
    p, q = np.radians(phi_deg), np.radians(psi_deg)
    rows = [[math.cos(q[j]), -math.cos(p[j]), 1.0] for j in range(3)]
    rhs = [math.cos(p[j] - q[j]) for j in range(3)]

    def det(m):
        return (m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
                + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]))
    D = det(rows)
    out = []
    for col in range(3):
        m = [r[:] for r in rows]
        for j in range(3):
            m[j][col] = rhs[j]
        out.append(det(m) / D)
    return out


def _ideal(syn, x):
    x0, x1 = syn["x"]
    f = np.log10
    phi = syn["input"]["start"] + syn["input"]["range"] * (x - x0) / (x1 - x0)
    psi = syn["output"]["start"] + syn["output"]["range"] * (f(x) - f(x0)) / (f(x1) - f(x0))
    return phi, psi


def _psi_circles(a, b, c, d, phi_deg, near_deg):
    """The rocker angle (deg) for each crank angle: B is where the circle about A (radius b)
    meets the circle about O1 = (d, 0) (radius c); of the two, the one nearest ``near_deg``
    (the ideal angle there: the branch the generator was assembled on)."""
    out = []
    for f, q0 in zip(np.radians(phi_deg), np.radians(near_deg)):
        ax, ay = a * math.cos(f), a * math.sin(f)
        dx, dy = d - ax, -ay
        L = math.hypot(dx, dy)
        k = (b * b - c * c + L * L) / (2 * L)
        h = math.sqrt(b * b - k * k)
        cands = [math.atan2(ay + (k * dy + s * h * dx) / L, ax + (k * dx - s * h * dy) / L - d) for s in (1, -1)]
        out.append(math.degrees(min(cands, key=lambda t: abs((t - q0 + math.pi) % (2 * math.pi) - math.pi))))
    return np.array(out)


def _wrap(e):
    return (np.asarray(e) + 180.0) % 360.0 - 180.0


def test_classic_log10_lengths_by_cramer_and_grashof():
    r = run(_task(CLASSIC))
    syn = r["synthesis"]
    # Chebyshev's points on [1, 2]: 1.5 - 0.5 cos(30 deg), 1.5, 1.5 + 0.5 cos(30 deg)
    xs = np.array([1.5 - 0.5 * math.sqrt(3) / 2, 1.5, 1.5 + 0.5 * math.sqrt(3) / 2])
    phi, psi = _ideal(CLASSIC, xs)
    K1, K2, K3 = _cramer(phi, psi)
    d = 0.1
    a, c = d / K1, d / K2
    b = math.sqrt(a * a + c * c + d * d - 2 * a * c * K3)
    assert syn["K"] == pytest.approx([K1, K2, K3], rel=1e-11)
    L = syn["lengths"]
    assert [L["crank"], L["coupler"], L["rocker"], L["frame"]] == pytest.approx([a, b, c, d], rel=1e-11)
    s_, *mid, l_ = sorted([a, b, c, d])
    assert s_ + l_ > sum(mid)          # Grashof fails (0.1 + 0.4015 > 0.2122 + 0.2786): no link turns fully
    assert syn["grashof"] == "double-rocker"


def test_positions_over_the_input_range_and_structural_error_there():
    r = run(_task(CLASSIC))
    pos, syn = r["positions"], r["synthesis"]
    n = 12
    want_phi = 45.0 + 60.0 * np.arange(n) / (n - 1)           # both ends included
    assert pos["over"] == "input_range" and pos["span"] == 60.0
    assert pos["phi"] == pytest.approx(want_phi, abs=1e-12) and pos["phi0"] == 45.0
    assert pos["extreme"] is None and pos["K"] is None
    assert any("input range 45..105 deg" in w for w in r["warnings"])
    L = syn["lengths"]
    xs = 1.0 + np.arange(n) / (n - 1)
    _, ideal = _ideal(CLASSIC, xs)
    got = _psi_circles(L["crank"], L["coupler"], L["rocker"], L["frame"], want_phi, ideal)
    at = syn["structural_error"]["positions"]
    assert [p["x"] for p in at] == pytest.approx(xs, abs=1e-12)
    assert np.abs(_wrap(np.array([p["psi_generated"] for p in at]) - got)).max() <= 1e-9
    assert np.abs(np.array([p["error"] for p in at]) - _wrap(got - ideal)).max() <= 1e-9
    # the kinematics at the same positions: the rocker's angle
    ang = [e["links"]["rocker"]["angle"] for e in r["kinematics"]]
    assert np.abs(_wrap(np.array(ang) - got)).max() <= 1e-9
    # the largest error over the range (401 points) is at least the positions' largest
    assert syn["structural_error"]["max"] >= max(abs(p["error"]) for p in at) - 1e-12
    assert syn["structural_error"]["max"] < 0.2


def test_instant_centres_over_the_range_by_kennedy():
    r = run(_task(CLASSIC))

    def meet(p1, p2, p3, p4):
        (x1, y1), (x2, y2), (x3, y3), (x4, y4) = p1, p2, p3, p4
        den = (x1 - x2) * (y3 - y4) - (y1 - y2) * (x3 - x4)
        t = ((x1 - x3) * (y3 - y4) - (y1 - y3) * (x3 - x4)) / den
        return [x1 + t * (x2 - x1), y1 + t * (y2 - y1)]
    for e in r["kinematics"]:
        P = {k: (v["x"], v["y"]) for k, v in e["points"].items()}
        ic = e["instant_centres"]
        # P13 (crank, rocker) on the line AB (P12, P23) and on the frame line O O1 (P01, P03)
        assert ic["1-3"] == pytest.approx(meet(P["A"], P["B"], P["O"], P["O1"]), abs=1e-9)
        # P02 (frame, coupler) on the crank line O A and the rocker line O1 B
        assert ic["0-2"] == pytest.approx(meet(P["O"], P["A"], P["O1"], P["B"]), abs=1e-9)


@pytest.mark.parametrize("lang", ["en", "ru", "uk"])
def test_double_rocker_end_to_end(tmp_path, lang):
    f = tmp_path / "t.yaml"
    f.write_text(yaml.safe_dump({"schema": "tmm/1", "title": "log10", "synthesis": CLASSIC,
                                 "drive": {"link": "crank", "speed": 6.0}}), encoding="utf-8")
    out = tmp_path / "o"
    res = runner.invoke(app, ["run", str(f), "--format", "json,html,pdf,sheets,note", "--lang", lang,
                              "--out", str(out)])
    assert res.exit_code == 0, res.output
    r = json.loads((out / "results.json").read_text(encoding="utf-8"))
    assert r["positions"]["over"] == "input_range" and "errors" not in r
    assert (out / "report.pdf").is_file() and (out / "sheets" / "sheets.pdf").is_file()
    html = (out / "report.html").read_text(encoding="utf-8")
    words = locales.of("report", "words", lang)
    head = words["kin.over_range_val"].split("{")[0]
    assert head and head in html             # the report says the positions are the input range's
    assert "105,000" in html or "105.000" in html
    assert any(p.name.startswith("note") for p in out.iterdir())


def test_flywheel_skipped_with_a_notice():
    t = load_task({"schema": "tmm/1", "synthesis": {**CLASSIC, "links": {"rocker": {"mass": 1.0, "J": 0.01}}},
                   "drive": {"link": "crank", "speed": 6.0}, "flywheel": {"delta": 0.05},
                   "loads": {"gravity": True}})
    r = run(t)
    assert "flywheel" not in r
    assert any(m["code"] == "flywheel.skipped_range" for m in r["messages"])


def test_failing_range_exit_3_names_the_crank_angle(tmp_path):
    syn = {**LOG10, "input": {"start": 45, "range": 160}, "output": {"start": 135, "range": 60}}
    with pytest.raises(StageError) as exc:
        run(_task(syn))
    msg = exc.value.message
    assert msg.code == "synthesis.fail.function_assembly"
    # the edge by the triangle inequality: |A O1| reaches b + c or |b - c| where the linkage stops
    from tmm_cli.linkage.synthesis import design
    L = design(_task(syn).synthesis, 1.0).lengths
    a, b, c, d = L["crank"], L["coupler"], L["rocker"], L["frame"]
    edges = []
    for reach in (b + c, abs(b - c)):
        cs = (a * a + d * d - reach * reach) / (2 * a * d)
        if abs(cs) <= 1:
            edges += [math.degrees(math.acos(cs)), 360 - math.degrees(math.acos(cs))]
    inside = [e for e in edges if 45 < e < 205]
    assert inside and msg.params["phi"] == pytest.approx(min(inside), abs=1e-3)
    assert msg.params["x"] == pytest.approx(1 + (msg.params["phi"] - 45) / 160, rel=1e-12)
    f = tmp_path / "t.yaml"
    f.write_text(yaml.safe_dump({"schema": "tmm/1", "synthesis": syn, "drive": {"link": "crank", "speed": 6.0}}))
    res = runner.invoke(app, ["run", str(f), "--format", "json", "--out", str(tmp_path / "o")])
    assert res.exit_code == 3 and "does not assemble at the crank angle" in res.output
    assert "input.range" in res.output and "Traceback" not in res.output
    for lang in ("ru", "uk"):
        from tmm_cli.messages import render
        text = render(msg.code, msg.params, lang)
        assert "input.range" in text and "{" not in text


def test_negative_length_is_the_same_fourbar_with_its_angle_scale_turned():
    """A negative length d/K is that link pointing the other way: psi -> psi + 180 deg changes
    cos psi and cos(phi - psi) in sign, so Freudenstein's K1 cos psi - K2 cos phi + K3 = cos(phi - psi)
    is solved by (K1, -K2, -K3), phi -> phi + 180 deg by (-K1, K2, -K3); b^2 = a^2 + c^2 + d^2 - 2 a c K3
    is the same. The error names the start to turn and the linkage that gives."""
    syn = {**LOG10, "input": {"start": 45, "range": 60}, "output": {"start": 135, "range": 90}}
    xs = np.array([1.5 - 0.5 * math.sqrt(3) / 2, 1.5, 1.5 + 0.5 * math.sqrt(3) / 2])
    K1, K2, K3 = _cramer(*_ideal(syn, xs))
    assert K1 > 0 > K2                         # the rocker d/K2 comes out negative
    d = 0.1
    a, c = d / K1, d / K2
    b = math.sqrt(a * a + c * c + d * d - 2 * a * c * K3)
    with pytest.raises(StageError) as exc:
        run(_task(syn))
    msg = exc.value.message
    assert msg.code == "synthesis.fail.function_turn"
    p = msg.params
    assert p["what"] == "rocker" and p["c"] == pytest.approx(c, rel=1e-11)
    assert [p["crank"], p["coupler"], p["rocker"]] == pytest.approx([a, b, -c], rel=1e-11)
    assert p["fix"] == ["`output.start: 315`"]
    assert "no positive" not in str(exc.value) and "`output.start: 315`" in str(exc.value)
    # the start it names: Cramer's rule gives (K1, -K2, -K3), all lengths positive, the same four-bar
    turned = {**syn, "output": {"start": 315, "range": 90}}
    assert _cramer(*_ideal(turned, xs)) == pytest.approx([K1, -K2, -K3], rel=1e-11)
    L = run(_task(turned))["synthesis"]["lengths"]
    assert [L["crank"], L["coupler"], L["rocker"]] == pytest.approx([a, b, -c], rel=1e-11)
    # the crank turned as well: both negative, both starts named; the crank alone: input.start
    both = {**syn, "input": {"start": 225, "range": 60}}
    with pytest.raises(StageError) as exc:
        run(_task(both))
    assert exc.value.message.params["what"] == "both"
    assert exc.value.message.params["fix"] == ["`input.start: 45`", "`output.start: 315`"]
    crank = {**turned, "input": {"start": 225, "range": 60}}
    assert _cramer(*_ideal(crank, xs)) == pytest.approx([-K1, -K2, K3], rel=1e-11)
    with pytest.raises(StageError) as exc:
        run(_task(crank))
    p = exc.value.message.params
    assert p["what"] == "crank" and p["a"] == pytest.approx(-a, rel=1e-11) and p["fix"] == ["`input.start: 45`"]
    for lang in ("ru", "uk"):
        from tmm_cli.messages import render
        text = render(exc.value.message.code, p, lang)
        assert "`input.start: 45`" in text and "{" not in text


def test_crank_rocker_example_keeps_the_full_cycle():
    r = run(load_task(ROOT / "tasks" / "synthesis_function.yaml"))
    pos = r["positions"]
    assert "over" not in pos and r["synthesis"]["grashof"] == "crank-rocker"
    assert len(pos["phi"]) >= 12 and pos["K"] is not None        # the turn's grid and the extremes
    steps = np.diff(np.asarray(pos["phi"][:12]))
    assert np.allclose(np.mod(steps, 360.0), 30.0)
    assert "structural_error" in r["synthesis"] and "positions" not in r["synthesis"]["structural_error"]


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(ps=st.integers(0, 355), dp=st.integers(20, 150), qs=st.integers(0, 355), dq=st.integers(20, 150),
       neg=st.booleans())
def test_accepted_generators_meet_their_precision_points(ps, dp, qs, dq, neg):
    syn = {**LOG10, "input": {"start": ps, "range": dp}, "output": {"start": qs, "range": -dq if neg else dq}}
    try:
        r = run(_task(syn))
    except StageError:
        return                                  # refused (exit 3): nothing to check
    for p in r["synthesis"]["precision_points"]:
        assert abs(_wrap(p["psi_generated"] - p["psi"])) <= 1e-9


def test_starter_and_example_are_the_classic_generator(tmp_path):
    res = runner.invoke(app, ["new", "synthesis_function"])
    assert res.exit_code == 0
    f = tmp_path / "s.yaml"
    f.write_text(res.output, encoding="utf-8")
    r = run(load_task(f))
    ex = run(load_task(ROOT / "tasks" / "synthesis_function_log10.yaml"))
    # 100 mm read as the classic's 0.1 m: the lengths of Cramer's rule above
    xs = np.array([1.5 - 0.5 * math.sqrt(3) / 2, 1.5, 1.5 + 0.5 * math.sqrt(3) / 2])
    K1, K2, _ = _cramer(*_ideal(CLASSIC, xs))
    for res_ in (r, ex):
        L = res_["synthesis"]["lengths"]
        assert L["crank"] == pytest.approx(0.1 / K1, rel=1e-11) and L["rocker"] == pytest.approx(0.1 / K2, rel=1e-11)
        assert res_["positions"]["over"] == "input_range"


def _pose(a, b, c, d, phi_deg, near_deg):
    """A and B of the four-bar at the crank angle (circle intersection, the branch nearest near_deg)."""
    q = math.radians(_psi_circles(a, b, c, d, [phi_deg], [near_deg])[0])
    f = math.radians(phi_deg)
    return np.array([a * math.cos(f), a * math.sin(f)]), np.array([d + c * math.cos(q), c * math.sin(q)])


def test_kinetostatics_over_the_range_by_virtual_work():
    """Gravity alone (no inertia): the balancing moment on the crank by virtual work,
    M_b omega1 = g sum m_i vy(S_i), the centres' velocities by central differences of the
    circle-intersection positions (S at a bar's middle, the crank's at its ground pivot O: the
    defaults of docs/task-file.md)."""
    masses = {"crank": 0.5, "coupler": 1.0, "rocker": 1.0}
    t = load_task({"schema": "tmm/1", "synthesis": {**CLASSIC, "links": {k: {"mass": m, "J": 0.01}
                                                                         for k, m in masses.items()}},
                   "drive": {"link": "crank", "speed": 6.0}, "loads": {"gravity": True},
                   "kinetostatics": {"inertia": False}})
    r = run(t)
    L = r["synthesis"]["lengths"]
    a, b, c, d = L["crank"], L["coupler"], L["rocker"], L["frame"]
    O1 = np.array([d, 0.0])
    assert len(r["kinetostatics"]) == 12 and r["singular"] == []
    for k, e in zip(r["kinetostatics"], r["kinematics"]):
        near = e["links"]["rocker"]["angle"]
        h = 1e-4

        def centres(f):
            A, B = _pose(a, b, c, d, f, near)
            return {"crank": np.zeros(2), "coupler": (A + B) / 2, "rocker": (O1 + B) / 2}
        lo, hi = centres(e["phi"] - h), centres(e["phi"] + h)
        dphi = math.radians(2 * h)
        vy = {n: (hi[n][1] - lo[n][1]) / dphi * 6.0 for n in masses}
        want = 9.81 * sum(masses[n] * vy[n] for n in masses) / 6.0
        assert k["balancing_moment"] == pytest.approx(want, rel=1e-6)


def test_sheet_chord_method_over_a_range():
    """The sheet's graphical differentiation over a crank range (no period): for y = phase^2
    (phase in deg) each chord's slope is (q0 + q1) per deg, i.e. 2 mid * 180/pi per rad."""
    from tmm_cli.sheets.sheet1 import chord_derivative
    ph = np.linspace(0.0, 60.0, 601)
    mids, d = chord_derivative(ph, ph ** 2, 2.0, n=11, span=60.0)
    assert mids == pytest.approx((np.arange(11) + 0.5) * 60.0 / 11, abs=1e-12)
    assert d == pytest.approx(2.0 * 2 * mids * 180.0 / math.pi, rel=1e-4)    # the data's linear interpolation


def test_largest_structural_error_and_the_note():
    """The largest |psi - psi_ideal| over the range (the 401 values of x tmm samples) by the
    circle intersections, and the note's conclusion that states it in each language."""
    from tmm_cli.report.note import conclusions
    r = run(_task(CLASSIC))
    L = r["synthesis"]["lengths"]
    xs = np.linspace(1.0, 2.0, 401)
    phi, ideal = _ideal(CLASSIC, xs)
    err = _wrap(_psi_circles(L["crank"], L["coupler"], L["rocker"], L["frame"], phi, ideal) - ideal)
    k = int(np.argmax(np.abs(err)))
    se = r["synthesis"]["structural_error"]
    assert se["max"] == pytest.approx(abs(err[k]), abs=1e-9) and se["at_x"] == pytest.approx(xs[k], abs=1e-12)
    for lang, num in (("en", f"{se['max']:.4g}"), ("ru", f"{se['max']:.4g}".replace(".", ",")),
                      ("uk", f"{se['max']:.4g}".replace(".", ","))):
        text = " ".join(conclusions(r, lang))
        assert num in text and "45°…105°" in text


def test_explorer_grid_over_the_range():
    from tmm_cli.pipeline import run_listed
    r = run_listed(_task(CLASSIC), explore=True)
    g = r["kinematics_explore"]
    assert g["phi"][0] == pytest.approx(45.0) and g["phi"][-1] == pytest.approx(105.0)
    assert len(g["phi"]) == 61 and g["step"] == pytest.approx(1.0)       # 60 deg at 1 deg, both ends
    assert [m["turn"] for m in g["positions"]] == pytest.approx(60.0 * np.arange(12) / 11, abs=1e-9)
    # the mechanism in motion at the range's end: the rocker's angle of the circle intersections
    L = r["synthesis"]["lengths"]
    _, ideal = _ideal(CLASSIC, np.array([2.0]))
    q = _psi_circles(L["crank"], L["coupler"], L["rocker"], L["frame"], [105.0], ideal)[0]
    B = (g["points"]["B"]["x"][-1], g["points"]["B"]["y"][-1])
    assert B == pytest.approx((L["frame"] + L["rocker"] * math.cos(math.radians(q)),
                               L["rocker"] * math.sin(math.radians(q))), rel=1e-6)     # 7 digits kept


def test_zero_given_over_a_range_is_said_to_be_unused():
    r = run(_task(CLASSIC, positions={"zero": 10}))
    assert r["positions"]["phi0"] == 45.0
    assert any(m["code"] == "positions.zero_range" for m in r["messages"])
    assert not any(m["code"] == "positions.zero_range" for m in run(_task(CLASSIC))["messages"])


def test_study_says_the_linkage_is_left_out(tmp_path):
    """`tmm study` and `tmm run --study` of a generator over its input range left the linkage's
    study out without a word (study.json empty, no section): the terminal, study.html and the
    report say why, with the range of the task file (start 45, range 60: 45..105 deg)."""
    task = str(ROOT / "tasks" / "synthesis_function_log10.yaml")
    said = "The linkage is not studied: the generated four-bar works over its input range only (45..105°)"
    res = runner.invoke(app, ["study", task, "--out", str(tmp_path / "s")])
    assert res.exit_code == 0 and said in res.output, res.output
    assert said in (tmp_path / "s" / "study.html").read_text(encoding="utf-8")
    res = runner.invoke(app, ["run", task, "--study", "--format", "json,html", "--out", str(tmp_path / "r"), "-q"])
    assert res.exit_code == 0, res.output
    assert said in (tmp_path / "r" / "report.html").read_text(encoding="utf-8")


def test_generated_psi_written_in_the_ideal_psis_turn():
    """The log10 example's rocker starts at 300 deg: the precision points' table printed the ideal
    308.419 beside the generated -51.581 (the same direction, 360 deg apart), which reads as an
    error of 360 deg. The generated angle is written in the ideal one's turn: within the
    structural error of it, and the same direction of O1B as the analysis's atan2."""
    res = run(load_task(ROOT / "tasks" / "synthesis_function_log10.yaml"))["synthesis"]
    for p in res["precision_points"]:
        assert abs(p["psi_generated"] - p["psi"]) <= 1e-9
    assert res["precision_points"][0]["psi"] > 300.0 and res["precision_points"][2]["psi"] > 360.0


def _trajectory_ends(svg: str) -> list[float]:
    """For each trajectory of a plan of positions (the dashed paths of the points, the blue ones of
    the centres of mass: paths of many points), the distance from its first point to its last."""
    out = []
    for d, rest in re.findall(r'<path d="(M[^"]+)"([^>]*)>', svg):
        if "stroke-dasharray" not in rest and 'stroke="#1f5fbf"' not in rest:
            continue
        for part in d.split("M")[1:]:                # the lines of one style share a path: M starts each
            xy = np.array(re.findall(r"(-?[\d.]+) (-?[\d.]+)", part), float)
            if len(xy) > 40:
                out.append(float(np.hypot(*(xy[-1] - xy[0]))))
    return out


@pytest.mark.parametrize("name, closed", [("synthesis_function_log10", False), ("crank_rocker_fourbar", True)])
def test_trajectories_open_over_a_range_closed_over_a_cycle(shared_once, name, closed):
    """Over an input range a point's trajectory runs from the first position to the last: the
    plan of positions (report) and sheet 1 once closed it with a spline back to the start, a
    line across the drawing; the crank pin's circle on sheet 1 is then the arc of the range
    (the course's full circle over a cycle)."""
    from pdf_extent import report_out
    from tmm_cli.sheets import build_sheets
    from tmm_cli.sheets.prims import Arc, Circle
    ends = _trajectory_ends((report_out(shared_once, name, "en") / "figures" / "positions.svg").read_text())
    assert len(ends) >= 3
    assert all((e < 1e-6) == closed for e in ends), ends            # open: apart by the path's length
    task = load_task(ROOT / "tasks" / f"{name}.yaml")
    res = run(task)
    cv, info = build_sheets(res, task, "en")[0]
    paths = info["mechanism"]["paths"]
    assert len(paths) >= 3
    for p in paths.values():
        gap = float(np.hypot(*(p["curve"][-1] - p["curve"][0])))
        if closed:
            assert gap < 1e-6
        else:                                                         # from the first node to the last
            assert np.allclose(p["curve"][0], p["nodes"][0]) and np.allclose(p["curve"][-1], p["nodes"][-1])
            assert gap > 1.0
    pos = res["positions"]
    arcs = [a for a in cv.prims if isinstance(a, Arc) and a.layer == "thin"]
    circles = [c for c in cv.prims if isinstance(c, Circle) and c.layer == "thin" and c.r > 5]
    if closed:
        assert len(circles) == 1 and not arcs
    else:
        assert not circles and len(arcs) == 1
        assert arcs[0].a1 - arcs[0].a0 == pytest.approx(abs(pos["span"]), abs=1e-6)     # the positions span it
