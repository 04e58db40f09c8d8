"""Function generation (Freudenstein): the precision points at Chebyshev spacing, the equation
solved through them, the link lengths, and the generated linkage's structural error against an
independent closed-form position analysis of the four-bar written out here; the expression
grammar (never evaluated as code); the errors a student meets."""
import json
import math
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from tmm_cli import load_task, run
from tmm_cli.cli import app
from tmm_cli.expr import ExprError, compile_expr

ROOT = Path(__file__).resolve().parents[1]
runner = CliRunner()
BASE = {"type": "function", "function": "x**1.5", "x": [1, 4], "input": {"start": 30, "range": 90},
        "output": {"start": 60, "range": 60}, "frame": 0.3}


def _task(**kw):
    return load_task({"schema": "tmm/1", "synthesis": {**BASE, **kw}, "drive": {"link": "crank", "speed": 6.0}})


def _psi_closed_form(a, b, c, d, phi_deg, branch_psi0):
    """The rocker angle of a four-bar (O at 0, O1 at (d, 0)) for crank angles phi, by the circle
    intersection of B around A (radius b) and around O1 (radius c), on the branch nearest psi0."""
    out = []
    prev = math.radians(branch_psi0)
    for f in np.radians(phi_deg):
        ax, ay = a * math.cos(f), a * math.sin(f)
        dx, dy = d - ax, -ay
        L = math.hypot(dx, dy)
        k = (b * b - c * c + L * L) / (2 * L)
        h = math.sqrt(max(b * b - k * k, 0.0))
        cands = []
        for s in (1, -1):
            bx = ax + (k * dx - s * h * dy) / L
            by = ay + (k * dy + s * h * dx) / L
            cands.append(math.atan2(by, bx - d))
        q = min(cands, key=lambda t: abs((t - prev + math.pi) % (2 * math.pi) - math.pi))
        out.append(math.degrees(q))
        prev = q
    return np.array(out)


def test_chebyshev_points_and_freudenstein_by_hand():
    r = run(_task())["synthesis"]
    pts = r["precision_points"]
    # x_j = 2.5 - 1.5 cos((2j - 1) pi/6): 2.5 - 1.5 (sqrt 3/2), 2.5, 2.5 + 1.5 (sqrt 3/2)
    assert [p["x"] for p in pts] == pytest.approx([2.5 - 1.5 * math.sqrt(3) / 2, 2.5, 2.5 + 1.5 * math.sqrt(3) / 2],
                                                  rel=1e-14)
    for p in pts:
        assert p["phi"] == pytest.approx(30 + 90 * (p["x"] - 1) / 3, rel=1e-14)
        assert p["psi"] == pytest.approx(60 + 60 * (p["x"] ** 1.5 - 1) / 7, rel=1e-14)
    K1, K2, K3 = r["K"]
    for p in pts:                       # Freudenstein's equation holds at each precision point
        f, q = math.radians(p["phi"]), math.radians(p["psi"])
        assert K1 * math.cos(q) - K2 * math.cos(f) + K3 == pytest.approx(math.cos(f - q), abs=1e-13)
    L = r["lengths"]
    d = 0.3
    assert L["crank"] == pytest.approx(d / K1, rel=1e-14) and L["rocker"] == pytest.approx(d / K2, rel=1e-14)
    a, c = L["crank"], L["rocker"]
    assert L["coupler"] == pytest.approx(math.sqrt(a * a + c * c + d * d - 2 * a * c * K3), rel=1e-13)
    # the analysed linkage passes the precision points
    for p in pts:
        assert p["psi_generated"] == pytest.approx(p["psi"], abs=1e-9)
    assert r["grashof"] == "crank-rocker"        # s + l = 0.1516 + 0.3 <= 0.1973 + 0.2814, the crank shortest


def test_structural_error_against_a_closed_form_analysis():
    r = run(_task())["synthesis"]
    L = r["lengths"]
    xs = np.linspace(1, 4, 2001)
    phi = 30 + 90 * (xs - 1) / 3
    ideal = 60 + 60 * (xs ** 1.5 - 1) / 7
    got = _psi_closed_form(L["crank"], L["coupler"], L["rocker"], L["frame"], phi, r["precision_points"][0]["psi"])
    err = (got - ideal + 180) % 360 - 180
    k = int(np.argmax(np.abs(err)))
    assert r["structural_error"]["max"] == pytest.approx(abs(err[k]), rel=1e-3)
    assert r["structural_error"]["at_x"] == pytest.approx(xs[k], abs=0.01)
    # the error vanishes at the precision points and changes sign between them (Chebyshev)
    e = np.interp([p["x"] for p in r["precision_points"]], xs, err)
    assert np.all(np.abs(e) < 1e-3)


def test_five_points_by_least_squares():
    r = run(_task(points=5))["synthesis"]
    assert len(r["precision_points"]) == 5
    K1, K2, K3 = r["K"]
    res = [K1 * math.cos(math.radians(p["psi"])) - K2 * math.cos(math.radians(p["phi"])) + K3
           - math.cos(math.radians(p["phi"] - p["psi"])) for p in r["precision_points"]]
    # least squares: the residuals are orthogonal to the columns (cos psi, -cos phi, 1)
    cols = [[math.cos(math.radians(p["psi"])) for p in r["precision_points"]],
            [-math.cos(math.radians(p["phi"])) for p in r["precision_points"]], [1.0] * 5]
    for col in cols:
        assert abs(sum(a * b for a, b in zip(col, res))) < 1e-12


@pytest.mark.parametrize("text, value", [("x**1.5", 8.0), ("sqrt(x) + 1", 3.0), ("log10(x) * 2", 2 * math.log10(4)),
                                         ("-x + exp(0)", -3.0), ("sin(x)/cos(x) - tan(x)", 0.0)])
def test_expression_grammar_values(text, value):
    assert float(compile_expr(text)(np.array([4.0]))[0]) == pytest.approx(value, abs=1e-12)


@pytest.mark.parametrize("text", ["__import__('os').system('true')", "x.real", "open('f')", "y + 1", "[x]",
                                  "x if x else 1", "lambda: 1", "2" + "**2" * 12, "sin(x, x)", ""])
def test_expression_grammar_refuses(text):
    with pytest.raises(ExprError):
        compile_expr(text)


def _run(tmp_path, **kw):
    import yaml
    f = tmp_path / "t.yaml"
    f.write_text(yaml.safe_dump({"schema": "tmm/1", "synthesis": {**BASE, **kw},
                                 "drive": {"link": "crank", "speed": 6.0}}, allow_unicode=True), encoding="utf-8")
    res = runner.invoke(app, ["run", str(f), "--format", "json", "--out", str(tmp_path / "o")])
    return res.exit_code, res.output


@pytest.mark.parametrize("kw, code, words", [
    ({"function": "import os"}, 2, "synthesis.function"),
    ({"function": "z**2"}, 2, "unknown name 'z'"),
    ({"x": [2, 2]}, 2, "synthesis.x"),
    ({"K": 1.2}, 2, "synthesis.K"),
    ({"output": {"start": 60, "range": 0}}, 2, "synthesis.output.range"),
    ({"output": {"start": 170, "range": -160}, "frame": 0.05}, 3, "synthesis"),
    ({"function": "1"}, 2, "takes the same value 1 at both ends"),     # a constant: no range of y
    ({"function": "1/0"}, 2, "not a finite number at x = 1"),
])
def test_errors(tmp_path, kw, code, words):
    got, out = _run(tmp_path, **kw)
    assert got == code, out
    assert words in out and "Traceback" not in out


def test_example_task(tmp_path):
    res = runner.invoke(app, ["run", str(ROOT / "tasks" / "synthesis_function.yaml"), "--format", "json,html",
                              "--out", str(tmp_path / "o")])
    assert res.exit_code == 0, res.output
    r = json.loads((tmp_path / "o" / "results.json").read_text())["synthesis"]
    assert r["type"] == "function" and r["structural_error"]["max"] < 2.0
    assert (tmp_path / "o" / "figures" / "synthesis-structural-error.svg").is_file()


def test_known_fourbar_given_back_through_its_own_three_points():
    """A four-bar of known lengths (a 0.1, b 0.35, c 0.25, d 0.3 m) has the rocker angle psi(phi)
    of the circle intersection (closed form here). The generator asked for the function
    through its three points at Chebyshev's spacing of phi in [40, 120] deg (the quadratic
    through them, written out as Lagrange's polynomial; phi = x and psi = y by the ranges)
    must be that four-bar: Freudenstein's equation holds on it at any three of its positions."""
    a, b, c, d = 0.1, 0.35, 0.25, 0.3
    x0, x1 = 40.0, 120.0
    xs = [80.0 - 40.0 * math.cos((2 * j - 1) * math.pi / 6) for j in (1, 2, 3)]
    psi = []
    for f in xs:
        ax, ay = a * math.cos(math.radians(f)), a * math.sin(math.radians(f))
        dx, dy = d - ax, -ay
        L = math.hypot(dx, dy)
        k = (b * b - c * c + L * L) / (2 * L)
        h = math.sqrt(b * b - k * k)
        B = max(((ax + (k * dx - s * h * dy) / L, ay + (k * dy + s * h * dx) / L) for s in (1, -1)),
                key=lambda p: p[1])                         # B above the frame
        psi.append(math.degrees(math.atan2(B[1], B[0] - d)))
    terms = []
    for j in range(3):
        o = [i for i in range(3) if i != j]
        terms.append(f"{psi[j]!r}*(x - {xs[o[0]]!r})*(x - {xs[o[1]]!r})/"
                     f"(({xs[j]!r} - {xs[o[0]]!r})*({xs[j]!r} - {xs[o[1]]!r}))")
    expr = " + ".join(terms)

    def lag(x):
        return sum(psi[j] * math.prod((x - xs[i]) / (xs[j] - xs[i]) for i in range(3) if i != j) for j in range(3))
    y0, y1 = lag(x0), lag(x1)
    r = run(_task(function=expr, x=[x0, x1], input={"start": x0, "range": x1 - x0},
                  output={"start": y0, "range": y1 - y0}, frame=d))["synthesis"]
    L = r["lengths"]
    assert [L["crank"], L["coupler"], L["rocker"], L["frame"]] == pytest.approx([a, b, c, d], rel=1e-9)
    for p, q in zip(r["precision_points"], psi):
        assert p["psi"] == pytest.approx(q, abs=1e-9) and p["psi_generated"] == pytest.approx(q, abs=1e-7)


def _freudenstein_by_cramer(phi, psi):
    """K1, K2, K3 of Freudenstein's equation K1 cos psi - K2 cos phi + K3 = cos(phi - psi) through
    three points (phi, psi in degrees), by Cramer's rule written out (3 x 3 determinants)."""
    M = [[math.cos(math.radians(q)), -math.cos(math.radians(f)), 1.0] for f, q in zip(phi, psi)]
    rhs = [math.cos(math.radians(f - q)) for f, q in zip(phi, psi)]

    def det3(m):
        return (m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
                + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]))
    D = det3(M)
    return [det3([[rhs[i] if j == col else M[i][j] for j in range(3)] for i in range(3)]) / D for col in range(3)]


def test_log10_generator_by_cramers_rule():
    """y = log10(x), 1 <= x <= 2 (the function of Freudenstein's 1955 paper, Trans. ASME 77,
    853-861; its printed ranges and results could not be obtained: the ranges here are
    phi 90 deg from 90 deg, psi 60 deg from 90 deg, which give a crank-rocker), three
    Chebyshev points worked by hand:
    x = 1.5 -+ 0.5 cos 30 deg = 1.066987, 1.5, 1.933013; y = 0.028159, 0.176091, 0.286235;
    phi = 90 + 90 (x - 1), psi = 90 + 60 y / log10 2; K1..K3 by Cramer's rule of
    [cos psi_j, -cos phi_j, 1] K = cos(phi_j - psi_j), then a = d/K1, c = d/K2,
    b^2 = a^2 + c^2 + d^2 - 2 a c K3 with d = 0.3 m."""
    xs = [1.5 - 0.5 * math.cos(math.pi / 6), 1.5, 1.5 + 0.5 * math.cos(math.pi / 6)]
    assert xs == pytest.approx([1.066987, 1.5, 1.933013], abs=5e-7)
    ys = [math.log10(x) for x in xs]
    assert ys == pytest.approx([0.028159, 0.176091, 0.286235], abs=5e-7)
    phi = [90 + 90 * (x - 1) for x in xs]
    psi = [90 + 60 * y / math.log10(2) for y in ys]
    K = _freudenstein_by_cramer(phi, psi)
    d = 0.3
    a, c = d / K[0], d / K[1]
    b = math.sqrt(a * a + c * c + d * d - 2 * a * c * K[2])
    r = run(_task(function="log10(x)", x=[1, 2], input={"start": 90, "range": 90},
                  output={"start": 90, "range": 60}, frame=d))["synthesis"]
    assert r["K"] == pytest.approx(K, rel=1e-12)
    L = r["lengths"]
    assert [L["crank"], L["coupler"], L["rocker"]] == pytest.approx([a, b, c], rel=1e-12)
    for p, f, q in zip(r["precision_points"], phi, psi):
        assert (p["phi"], p["psi"]) == pytest.approx((f, q), abs=1e-12)
        assert p["psi_generated"] == pytest.approx(q, abs=1e-7)


def test_least_transmission_angle_over_the_input_range_by_the_cosine_rule():
    """The generator works over its input range: its least transmission angle there, against
    the cosine rule of the four-bar (O at 0, O1 at (d, 0)): |AO1|^2 = a^2 + d^2 - 2 a d cos phi,
    cos mu = (b^2 + c^2 - |AO1|^2) / (2 b c), gamma = min(mu, 180 - mu), its least on a grid of
    0.001 deg over the range 30..120 deg. The
    example's crank-rocker has its full-turn least (30.08 deg at phi = 0) outside the range:
    the range's, 40.92 at its end phi = 30, is larger; both printed at the terminal."""
    res = run(_task())
    s = res["synthesis"]
    a, b, c, d = (s["lengths"][k] for k in ("crank", "coupler", "rocker", "frame"))
    phi = np.radians(np.linspace(30.0, 120.0, 90001))
    ao1 = a * a + d * d - 2 * a * d * np.cos(phi)
    mu = np.degrees(np.arccos((b * b + c * c - ao1) / (2 * b * c)))
    gam = np.minimum(mu, 180.0 - mu)
    k = int(np.argmin(gam))
    assert s["gamma_min"] == pytest.approx(gam[k], abs=1e-6)
    assert s["gamma_min_phi"] == pytest.approx(math.degrees(phi[k]), abs=2e-3)
    full = min(r["gamma_min"] for r in res["transmission"])
    assert s["grashof"] == "crank-rocker" and full < s["gamma_min"] - 5.0     # the turn's least lies outside
    from tmm_cli.summary import _summary_rows
    rows = dict(_summary_rows(res))
    assert rows["least transmission angle in the input range, deg"] == f"{s['gamma_min']:.5g}"
    assert rows["least transmission angle, deg"].startswith(f"{full:.5g} ")


def test_a_double_rocker_generators_range_least_is_the_transmission_stages():
    """A generator that is no crank-rocker (tasks/synthesis_function_log10) has its transmission
    stage over the input range already: the synthesis's least over the range is the same number
    at the same angle (two routes through one search), and the terminal prints it once."""
    res = run(load_task(ROOT / "tasks" / "synthesis_function_log10.yaml"))
    s = res["synthesis"]
    assert s["grashof"] != "crank-rocker"
    (t,) = res["transmission"]
    assert s["gamma_min"] == t["gamma_min"] and s["gamma_min_phi"] == t["phi"]
    from tmm_cli.summary import _summary_rows
    assert "least transmission angle in the input range, deg" not in dict(_summary_rows(res))


def test_negative_rocker_names_the_output_start_to_turn(tmp_path):
    """y = sin x on [0, 1.5], phi from 20 deg over 120, psi from 100 deg over -70, d = 0.2 m: at the
    Chebyshev points x = 0.75 -+ 0.75 cos 30 deg, 0.75 Cramer's rule gives K2 < 0, a rocker d/K2 < 0:
    the four-bar with the rocker's angles counted from the other side, psi + 180 deg (K1, -K2, -K3).
    The error says so and names `output.start: 280`; with it the lengths are d/K1, the same b, -d/K2."""
    xs = [0.75 - 0.75 * math.cos(math.pi / 6), 0.75, 0.75 + 0.75 * math.cos(math.pi / 6)]
    phi = [20 + 120 * x / 1.5 for x in xs]
    psi = [100 - 70 * math.sin(x) / math.sin(1.5) for x in xs]
    K1, K2, K3 = _freudenstein_by_cramer(phi, psi)
    d = 0.2
    a, c = d / K1, d / K2
    b = math.sqrt(a * a + c * c + d * d - 2 * a * c * K3)
    assert a > 0 > c
    assert [a, b, -c] == pytest.approx([0.067110, 0.191634, 0.093198], abs=5e-7)     # the audit's fg1b
    kw = {"function": "sin(x)", "x": [0, 1.5], "input": {"start": 20, "range": 120},
          "output": {"start": 100, "range": -70}, "points": 3, "frame": d}
    code, out = _run(tmp_path, **kw)
    assert code == 3, out
    text = " ".join(out.split())
    assert "negative rocker length" in text and "`output.start: 280`" in text
    assert "no positive rocker length" not in text
    r = run(_task(**{**kw, "output": {"start": 280, "range": -70}}))["synthesis"]
    assert r["K"] == pytest.approx([K1, -K2, -K3], rel=1e-11)
    L = r["lengths"]
    assert [L["crank"], L["coupler"], L["rocker"]] == pytest.approx([a, b, -c], rel=1e-11)
