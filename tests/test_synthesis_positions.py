"""Motion generation through three positions (the pole method): a known four-bar's own coupler
positions, computed here by a closed-form circle intersection, give back its fixed pivots and
lengths; the fixed pivot by the perpendicular bisectors written out by hand; the poles; the
branch and order defects; collinear positions (exit 2) and a linkage whose crank cannot turn
(exit 3)."""
import json
import math
from pathlib import Path

import pytest
from typer.testing import CliRunner

from tmm_cli import load_task, run
from tmm_cli.cli import app

ROOT = Path(__file__).resolve().parents[1]
runner = CliRunner()
MP = {"A": [-0.15, -0.06], "B": [0.15, -0.06]}


def _task(positions, moving_pivots=MP, direction="ccw"):
    return load_task({"schema": "tmm/1", "synthesis": {"type": "positions", "positions": positions,
                                                        "moving_pivots": moving_pivots},
                      "drive": {"link": "crank", "speed": 6.0, "direction": direction}})


def _fourbar_pose(O, O1, a, b, c, phi_deg, branch=1):
    """A, B of a four-bar with the crank at phi: B where the circles about A (radius b) and O1
    (radius c) meet, on the left (branch +1) or the right (-1) of the line A -> O1."""
    f = math.radians(phi_deg)
    A = (O[0] + a * math.cos(f), O[1] + a * math.sin(f))
    dx, dy = O1[0] - A[0], O1[1] - A[1]
    L = math.hypot(dx, dy)
    k = (b * b - c * c + L * L) / (2 * L)
    h = math.sqrt(b * b - k * k)
    B = (A[0] + (k * dx - branch * h * dy) / L, A[1] + (k * dy + branch * h * dx) / L)
    return A, B


def _plane(A, B):
    """The coupler plane's pose for the moving pivots MP: P and the plane's angle. MP's A->B is
    along the plane's x, so the plane's angle is the line AB's; P = A - R(angle) MP.A."""
    ang = math.atan2(B[1] - A[1], B[0] - A[0])
    c, s = math.cos(ang), math.sin(ang)
    ax, ay = MP["A"]
    P = (A[0] - (c * ax - s * ay), A[1] - (s * ax + c * ay))
    return {"P": list(P), "angle": math.degrees(ang)}


# a crank-rocker: O (0.02, -0.01), O1 (0.33, 0.04), crank 0.08, coupler 0.3 (|AB| of MP), rocker 0.22
O, O1, a, b, c = (0.02, -0.01), (0.33, 0.04), 0.08, 0.30, 0.22


def test_known_fourbar_recovered():
    poses = [_plane(*_fourbar_pose(O, O1, a, b, c, phi)) for phi in (40.0, 100.0, 160.0)]
    r = run(_task(poses))["synthesis"]
    assert r["fixed_pivots"]["O"] == pytest.approx(O, abs=1e-12)
    assert r["fixed_pivots"]["O1"] == pytest.approx(O1, abs=1e-12)
    L = r["lengths"]
    assert [L["crank"], L["coupler"], L["rocker"], L["frame"]] == pytest.approx(
        [a, b, c, math.dist(O, O1)], rel=1e-11)
    # the crank angles of the analysed positions: those the poses were made at
    assert [p["crank_angle"] for p in r["positions"]] == pytest.approx([40.0, 100.0, 160.0], abs=1e-9)
    for p, q in zip(r["positions"], poses):
        assert p["P"] == pytest.approx(q["P"], abs=1e-12)
        assert p["deviation"] < 1e-12 and abs(p["angle_error"]) < 1e-9
    assert r["defects"] == {"branch": False, "order": False}
    assert r["grashof"] == "crank-rocker"       # 0.08 + 0.3 < 0.22 + 0.314
    m = r["mechanism"]
    assert m["ground"]["O"] == pytest.approx(O, abs=1e-12)
    # the plane's point P in the coupler's frame: midway along AB (u = 0.15), 0.06 to its left
    assert m["links"]["coupler"]["extra"]["P"] == pytest.approx([0.15, 0.06], abs=1e-15)


def _example_positions():
    import yaml
    sec = yaml.safe_load((ROOT / "tasks" / "synthesis_positions.yaml").read_text(encoding="utf-8"))["synthesis"]
    return [((float(p["P"][0]), float(p["P"][1])), float(p["angle"])) for p in sec["positions"]]


def test_fixed_pivot_by_perpendicular_bisectors_by_hand():
    # the task's example: A_j = P_j + R(angle_j) (-0.15, -0.06)
    task = load_task(ROOT / "tasks" / "synthesis_positions.yaml")
    r = run(task)["synthesis"]
    pos = _example_positions()
    A = []
    for (px, py), ang in pos:
        cs, sn = math.cos(math.radians(ang)), math.sin(math.radians(ang))
        A.append((px + cs * -0.15 - sn * -0.06, py + sn * -0.15 + cs * -0.06))
    # bisector of A1A2: (A2 - A1).X = (|A2|^2 - |A1|^2)/2; likewise A2A3; Cramer's rule
    (x1, y1), (x2, y2), (x3, y3) = A
    a1, b1, c1 = x2 - x1, y2 - y1, (x2 ** 2 + y2 ** 2 - x1 ** 2 - y1 ** 2) / 2
    a2, b2, c2 = x3 - x2, y3 - y2, (x3 ** 2 + y3 ** 2 - x2 ** 2 - y2 ** 2) / 2
    det = a1 * b2 - a2 * b1
    Ox, Oy = (c1 * b2 - c2 * b1) / det, (a1 * c2 - a2 * c1) / det
    assert r["fixed_pivots"]["O"] == pytest.approx([Ox, Oy], abs=1e-13)
    assert r["lengths"]["crank"] == pytest.approx(math.hypot(x1 - Ox, y1 - Oy), rel=1e-12)
    assert r["lengths"]["coupler"] == pytest.approx(0.3, rel=1e-14)


def test_example_gives_its_fourbar_back_exactly(tmp_path):
    """The example's positions are the four-bar O (0, 0), O1 (0.3, 0), 0.08, 0.3, 0.22 at the
    crank angles 40, 100, 160 deg, written to 1e-12 m and 1e-10 deg (closed form here). The
    construction (circumcentres, no iteration) then gives that four-bar back to the data's
    last digit: O at the origin (the report prints 0, not the 1.5e-5 m that positions rounded
    to 0.1 mm and 0.01 deg put there), O1 at (0.3, 0), the lengths and the crank angles."""
    pos = _example_positions()
    for ((px, py), ang), phi in zip(pos, (40.0, 100.0, 160.0)):
        q = _plane(*_fourbar_pose((0.0, 0.0), (0.3, 0.0), 0.08, 0.30, 0.22, phi))
        assert (px, py) == pytest.approx(q["P"], abs=6e-13) and ang == pytest.approx(q["angle"], abs=6e-11)
    r = run(load_task(ROOT / "tasks" / "synthesis_positions.yaml"))["synthesis"]
    # the data's rounding (5e-13 m, 5e-11 deg = 9e-13 rad over 0.3 m) moves the circumcentres by ~1e-11
    assert r["fixed_pivots"]["O"] == pytest.approx([0.0, 0.0], abs=1e-11)
    assert r["fixed_pivots"]["O1"] == pytest.approx([0.3, 0.0], abs=5e-11)
    L = r["lengths"]
    assert [L["crank"], L["coupler"], L["rocker"], L["frame"]] == pytest.approx([0.08, 0.3, 0.22, 0.3], abs=5e-11)
    assert [p["crank_angle"] for p in r["positions"]] == pytest.approx([40, 100, 160], abs=1e-8)
    # the least transmission angle of the crank-rocker, by hand: at phi = 0 (crank along OO1),
    # the triangle A B O1 with |AO1| = 0.3 - 0.08: cos(gamma) = (b^2 + c^2 - 0.22^2)/(2 b c)
    g = math.degrees(math.acos((0.3 ** 2 + 0.22 ** 2 - 0.22 ** 2) / (2 * 0.3 * 0.22)))
    assert r["gamma_min"] == pytest.approx(g, abs=1e-6)
    assert r["gamma_min_phi"] == pytest.approx(0.0, abs=1e-5)      # 0, not 360 (a flat least: ~1e-6 deg)
    res = runner.invoke(app, ["run", str(ROOT / "tasks" / "synthesis_positions.yaml"), "-o", str(tmp_path / "o"),
                              "--format", "html", "--quiet"])
    assert res.exit_code == 0, res.output
    import re
    text = re.sub(r"\s+", " ", re.sub(r"<[^>]+>", " ", (tmp_path / "o" / "report.html").read_text(encoding="utf-8")))
    assert "Fixed pivot O (0; 0) m" in text and "(0.300000; 0) m" in text


def test_poles_fixed_by_both_displacements():
    poses = [_plane(*_fourbar_pose(O, O1, a, b, c, phi)) for phi in (40.0, 100.0, 160.0)]
    r = run(_task(poses))["synthesis"]
    for key, (i, k) in {"12": (0, 1), "13": (0, 2), "23": (1, 2)}.items():
        X = r["construction"]["poles"][key]
        # the pole keeps its place: P_k + R(angle_k - angle_i)(X - P_i) = X
        d = math.radians(poses[k]["angle"] - poses[i]["angle"])
        px, py = X[0] - poses[i]["P"][0], X[1] - poses[i]["P"][1]
        Y = (poses[k]["P"][0] + math.cos(d) * px - math.sin(d) * py,
             poses[k]["P"][1] + math.sin(d) * px + math.cos(d) * py)
        assert Y == pytest.approx(X, abs=1e-12)
        # and O, the centre of A's circle, is as far from A_i as from A_k; it sees A_iA_k from the pole
        Ai, Ak = r["construction"]["A_positions"][i], r["construction"]["A_positions"][k]
        assert math.dist(X, Ai) == pytest.approx(math.dist(X, Ak), rel=1e-10)


def test_branch_defect():
    # position 2 on the other branch of the same four-bar: the circles still pass, the linkage
    # assembled on position 1's branch does not reach position 2
    poses = [_plane(*_fourbar_pose(O, O1, a, b, c, 40.0)), _plane(*_fourbar_pose(O, O1, a, b, c, 100.0, -1)),
             _plane(*_fourbar_pose(O, O1, a, b, c, 160.0))]
    r = run(_task(poses))["synthesis"]
    assert r["fixed_pivots"]["O1"] == pytest.approx(O1, abs=1e-12)
    assert r["defects"]["branch"] is True and r["defects"]["order"] is False
    assert r["positions"][1]["deviation"] > 1e-3       # the analysed linkage is elsewhere
    assert r["positions"][2]["deviation"] < 1e-12


def test_order_defect_by_the_drive_sense():
    poses = [_plane(*_fourbar_pose(O, O1, a, b, c, phi)) for phi in (40.0, 160.0, 100.0)]
    assert run(_task(poses))["synthesis"]["defects"] == {"branch": False, "order": True}
    # ccw from 40 deg: 160 lies 120 deg on, 100 lies 60 deg on (position 3 first: the defect);
    # cw from 40 deg: 160 lies 240 deg on, 100 lies 300 deg on (position 2 first: in order)
    assert run(_task(poses, direction="cw"))["synthesis"]["defects"]["order"] is False


def test_collinear_positions_exit_2(tmp_path):
    f = tmp_path / "t.yaml"
    f.write_text("schema: tmm/1\nsynthesis:\n  type: positions\n  positions:\n"
                 "    - {P: [0, 0], angle: 0}\n    - {P: [0.1, 0], angle: 0}\n    - {P: [0.2, 0], angle: 0}\n"
                 "  moving_pivots: {A: [0, 0], B: [0.1, 0.05]}\ndrive: {link: crank, speed: 6}\n")
    res = runner.invoke(app, ["run", str(f), "-o", str(tmp_path / "o"), "--format", "json"])
    assert res.exit_code == 2
    assert "moving_pivots" in res.output and "one line" in res.output and "Traceback" not in res.output
    assert "t.yaml:8:" in res.output                   # the line of moving_pivots
    assert "(0, 0), (0.1, 0), (0.2, 0)" in res.output


def test_crank_that_cannot_turn_exit_3(tmp_path):
    # a double-rocker's coupler positions (crank 0.25 longer than half the others allow)
    Od, O1d, ad, bd, cd = (0.0, 0.0), (0.3, 0.0), 0.25, 0.30, 0.22
    poses = [_plane(*_fourbar_pose(Od, O1d, ad, bd, cd, phi)) for phi in (60.0, 80.0, 100.0)]
    f = tmp_path / "t.yaml"
    f.write_text(json.dumps({"schema": "tmm/1", "synthesis": {"type": "positions", "positions": poses,
                                                               "moving_pivots": MP},
                             "drive": {"link": "crank", "speed": 6}}))
    res = runner.invoke(app, ["run", str(f), "-o", str(tmp_path / "o"), "--format", "json"])
    assert res.exit_code == 3
    assert "Grashof" in res.output and "moving_pivots" in res.output


def test_wrong_points_for_the_type(tmp_path):
    f = tmp_path / "t.yaml"
    f.write_text("schema: tmm/1\nsynthesis:\n  type: function\n  function: x\n  x: [0, 1]\n"
                 "  input: {range: 90}\n  output: {range: 60}\n  frame: 0.3\n  points: [[0, 0], [1, 1], [2, 0], "
                 "[3, 1], [4, 0]]\ndrive: {link: crank, speed: 6}\n")
    res = runner.invoke(app, ["validate", str(f)])
    assert res.exit_code == 2 and "number of precision points" in res.output


def test_starter_runs(tmp_path):
    res = runner.invoke(app, ["new", "synthesis_positions"])
    assert res.exit_code == 0
    f = tmp_path / "s.yaml"
    f.write_text(res.output)
    r = run(load_task(f))["synthesis"]
    # 150 mm and 60 mm read as the example's 0.15 m and 0.06 m: the same fixed pivots
    ex = run(load_task(ROOT / "tasks" / "synthesis_positions.yaml"))["synthesis"]
    assert r["fixed_pivots"]["O1"] == pytest.approx(ex["fixed_pivots"]["O1"], abs=1e-14)


def test_coinciding_moving_pivots_exit_2(tmp_path):
    f = tmp_path / "t.yaml"
    f.write_text("schema: tmm/1\nsynthesis:\n  type: positions\n  positions:\n"
                 "    - {P: [0, 0], angle: 0}\n    - {P: [0.1, 0], angle: 20}\n    - {P: [0.2, 0.1], angle: 40}\n"
                 "  moving_pivots: {A: [0.05, 0.02], B: [0.05, 0.02]}\ndrive: {link: crank, speed: 6}\n")
    res = runner.invoke(app, ["validate", str(f)])
    assert res.exit_code == 2 and "coincide" in res.output and "t.yaml:8:" in res.output


# Norton, *Design of Machinery*, section 5.7 "Three-position motion generation by analytical
# synthesis", Example 5-2 (p. 247 in the edition quoted): the given data and the free choices
# as printed (lengths in the book's units).  The book's printed results (w, z, u, s, the
# pivots O2, O4) could not be obtained; the dyad equations the book solves (its eq. 5.25,
# W (e^{i beta_k} - 1) + Z (e^{i alpha_k} - 1) = P_k1, k = 2, 3, likewise U, S with gamma_k)
# are solved here by Cramer's rule instead.
NORTON_5_2 = {"p21": 2.798, "delta2": -31.19, "p31": 3.919, "delta3": -16.34, "alpha2": -45.0, "alpha3": 9.3,
              "beta2": 342.3, "beta3": 324.8, "gamma2": 30.9, "gamma3": 80.6}


def _norton_dyad(b2, b3, e):
    """Norton's dyad (W, Z) for the arm's turns b2, b3 (deg): the 2x2 complex system by Cramer."""
    import cmath
    r = math.radians
    p21 = e["p21"] * cmath.exp(1j * r(e["delta2"]))
    p31 = e["p31"] * cmath.exp(1j * r(e["delta3"]))
    a11, a12 = cmath.exp(1j * r(b2)) - 1, cmath.exp(1j * r(e["alpha2"])) - 1
    a21, a22 = cmath.exp(1j * r(b3)) - 1, cmath.exp(1j * r(e["alpha3"])) - 1
    det = a11 * a22 - a12 * a21
    return (p21 * a22 - a12 * p31) / det, (a11 * p31 - a21 * p21) / det


def test_norton_example_5_2_fixed_pivots_by_the_dyad_equations(tmp_path):
    """Norton's Example 5-2 through tmm: the coupler point P at the origin in position 1 (the
    plane's angle 0 there), at P21 and P31 turned by alpha2 and alpha3; the moving pivots in
    the plane's frame are the book's dyads' ends, A = -Z, B = -S. tmm's circumcentres of A's
    and B's three positions must be the book's ground pivots O2 = -Z - W and O4 = -S - U, and
    A's positions the crank W turned by beta2, beta3 about O2 (B's: U by gamma2, gamma3 about O4).
    The linkage (crank |W| = 6.832, coupler |Z - S| = 1.399, rocker |U| = 3.200, frame 9.030)
    is not Grashof (1.399 + 9.030 > 6.832 + 3.200): tmm refuses it with exit 3, naming them."""
    import cmath
    from tmm_cli.linkage.spec import pivot_positions
    from tmm_cli.linkage.synthesis_positions import circumcentre
    e = NORTON_5_2
    W, Z = _norton_dyad(e["beta2"], e["beta3"], e)
    U, S = _norton_dyad(e["gamma2"], e["gamma3"], e)
    r = math.radians
    P = [0j, e["p21"] * cmath.exp(1j * r(e["delta2"])), e["p31"] * cmath.exp(1j * r(e["delta3"]))]
    poses = [{"P": [p.real, p.imag], "angle": ang} for p, ang in zip(P, (0.0, e["alpha2"], e["alpha3"]))]
    sec = {"type": "positions", "positions": poses, "moving_pivots": {"A": [-Z.real, -Z.imag], "B": [-S.real, -S.imag]}}
    task = load_task({"schema": "tmm/1", "synthesis": sec, "drive": {"link": "crank", "speed": 6.0}})
    pts = pivot_positions(task.synthesis)
    O2, O4 = -Z - W, -S - U
    for k, (turn_w, turn_u) in enumerate(((0.0, 0.0), (e["beta2"], e["gamma2"]), (e["beta3"], e["gamma3"]))):
        A = O2 + W * cmath.exp(1j * r(turn_w))
        B = O4 + U * cmath.exp(1j * r(turn_u))
        assert pts["A"][k] == pytest.approx((A.real, A.imag), abs=1e-12)
        assert pts["B"][k] == pytest.approx((B.real, B.imag), abs=1e-12)
    assert circumcentre(*pts["A"]) == pytest.approx((O2.real, O2.imag), abs=1e-11)
    assert circumcentre(*pts["B"]) == pytest.approx((O4.real, O4.imag), abs=1e-11)
    a, b, c, d = abs(W), abs(Z - S), abs(U), abs(O4 - O2)
    assert (a, b, c, d) == pytest.approx((6.832, 1.3993, 3.1997, 9.0298), abs=5e-4)
    f = tmp_path / "t.json"
    f.write_text(json.dumps({"schema": "tmm/1", "synthesis": sec, "drive": {"link": "crank", "speed": 6}}))
    res = runner.invoke(app, ["run", str(f), "-o", str(tmp_path / "o"), "--format", "json"])
    assert res.exit_code == 3 and "Grashof" in res.output, res.output
    import re
    got = [float(v) for v in re.findall(r"(\d+\.\d+) m", res.output)[:4]]
    assert got == pytest.approx([a, b, c, d], rel=1e-3), res.output
