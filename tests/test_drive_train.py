"""drive_train: compound gear drives. Reference values are independent: Willis' formula
written mesh by mesh (carrier held), a two-stage train computed by hand below, the velocity
plan read graphically, and a brute-force enumeration of the planetary conditions."""
from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from typer.testing import CliRunner

from tmm_cli.cli import app
from tmm_cli.errors import TaskError
from tmm_cli.gears import train
from tmm_cli.pipeline import PartialResults, run
from tmm_cli.task import load_task

ROOT = Path(__file__).resolve().parents[1]
runner = CliRunner()


def _train(**section):
    return run(load_task({"schema": "tmm/1", "drive_train": section}))["drive_train"]


# ---------------------------------------------------------------- Willis per stage
def _willis(scheme, z):
    """u_1H from the carrier-held train, mesh by mesh: an external mesh -z_driven/z_driving,
    an internal one +z_driven/z_driving; omega_F = 0 gives u_1H = 1 - u_1F^H."""
    if scheme == "A":
        z1, z2, z3 = z
        u_h = (-z2 / z1) * (z3 / z2)
    elif scheme == "B":
        z1, z2, z3, z4 = z
        u_h = (-z2 / z1) * (z4 / z3)
    elif scheme == "C":
        z1, z2, z3, z4 = z
        u_h = (-z2 / z1) * (-z4 / z3)
    else:
        z1, z2, z3, z4 = z
        u_h = (z2 / z1) * (z4 / z3)
    return 1 - u_h


@pytest.mark.parametrize("scheme,z", [("A", [17, 34, 85]), ("B", [19, 40, 26, 85]),
                                      ("C", [20, 40, 21, 39]), ("D", [100, 20, 22, 102])])
def test_planetary_stage_by_willis(scheme, z):
    u = train.stage_ratio(scheme, z)
    assert u == pytest.approx(_willis(scheme, z), rel=1e-12)
    # satellite: with the carrier held, omega_2^H = omega_1^H * (-z1/z2) external, +z1/z2 internal
    w1, wh = 7.0, 7.0 / u
    sat, rel = train.satellite_speeds(scheme, z, w1, wh)
    k = (z[0] / z[1]) * (1 if scheme == "D" else -1)
    assert rel == pytest.approx(k * (w1 - wh), rel=1e-12)
    assert sat == pytest.approx(wh + k * (w1 - wh), rel=1e-12)


def test_pair_signs():
    assert train.stage_ratio("pair", [20, 60]) == pytest.approx(-3.0)
    assert train.stage_ratio("pair", [20, 60], internal=True) == pytest.approx(3.0)


# ---------------------------------------------------------------- hand calculation
def test_two_stage_train_by_hand():
    """Pair 20/96 then scheme A 17/34/85 at n = 1440 rpm, motor ccw.
    u12 = -96/20 = -4.8; u3H = 1 + 85/17 = 6; U = -4.8 * 6 = -28.8.
    omega_m = 1440 * 2 pi / 60 = 150.796447 rad/s; omega_2 = 150.796447 / -4.8 = -31.415927;
    omega_H = -31.415927 / 6 = -5.235988; satellite relative to H:
    -(17/34)(-31.415927 + 5.235988) = 13.089969; absolute 13.089969 - 5.235988 = 7.853982."""
    d = _train(motor_speed="1440 rpm", ratio=-28.8, stages=[
        {"type": "pair", "z": [20, 96]}, {"type": "planetary", "scheme": "A", "z": [17, 34, 85]}])
    assert d["ratio"] == pytest.approx(-28.8, rel=1e-12)
    assert d["ratio_error"] == pytest.approx(0.0, abs=1e-12)
    assert d["shafts"] == pytest.approx([150.796447372, -31.415926536, -5.235987756], rel=1e-9)
    s0, s1 = d["stages"]
    assert s0["ratio"] == pytest.approx(-4.8) and s1["ratio"] == pytest.approx(6.0)
    assert s1["omega_carrier"] == pytest.approx(-5.235987756, rel=1e-9)
    assert s1["omega_satellite_rel"] == pytest.approx(13.089969390, rel=1e-9)
    assert s1["omega_satellite"] == pytest.approx(7.853981634, rel=1e-9)
    assert s1["checks"] == {"coaxial": True, "assembly": True, "adjacency": True, "undercut": True}
    assert d["candidates"][0]["z"] == [[20, 96], [17, 34, 85]] and d["candidates"][0]["size"] == 96
    # no flywheel: no mean driving moment, so no power (0 as the results format fixes it)
    assert d["motor_power"] == 0.0 and d["motor_power_computed"] is False


def test_no_motor_no_drive_gives_transfer_ratios():
    d = _train(stages=[{"type": "pair", "z": [20, 60], "internal": True}, {"type": "pair", "z": [18, 36]}])
    # 1 rad/s in; u = (+3)(-2) = -6
    assert d["shafts"] == pytest.approx([1.0, 1 / 3, -1 / 6])
    assert "ratio_error" not in d


# ---------------------------------------------------------------- the velocity plan
@pytest.mark.parametrize("stages", [
    [{"type": "pair", "z": [20, 96]}, {"type": "planetary", "scheme": "A", "z": [17, 34, 85]}],
    [{"type": "planetary", "scheme": "B", "z": [19, 40, 26, 85]}, {"type": "pair", "z": [18, 54]},
     {"type": "pair", "z": [20, 60], "internal": True}],
    [{"type": "planetary", "scheme": "C", "z": [20, 40, 21, 39]},
     {"type": "planetary", "scheme": "D", "z": [100, 20, 22, 102]}],
])
def test_velocity_plan_read_graphically(stages):
    d = _train(motor_speed="960 rpm", satellites=1, stages=stages)
    plan = d["velocity_plan"]
    for row, st in zip(plan["stages"], d["stages"]):
        assert row["ratio_plan"] == pytest.approx(st["ratio"], rel=1e-9)
    assert plan["ratio_plan"] == pytest.approx(d["ratio"], rel=1e-9)
    # the segments cut off by the rays are omega / mu_omega: omega read from the plan
    rays = {r["name"]: r["x"] for r in plan["rays"]}
    assert rays["0"] * plan["mu_omega"] == pytest.approx(d["shafts"][0], rel=1e-9)
    # the picture stays inside its frame (the scale was chosen for it)
    assert max(abs(p["v"]) / plan["mu_v"] for p in plan["points"]) <= 60 + 1e-9


# ---------------------------------------------------------------- synthesis
def _brute_A(req, tol, k, zmax=150, zext=17, zint=85, zsat=20, diff=8):
    """Every (z1, z2, z3) of scheme A meeting the conditions, written out independently."""
    out = []
    for z1 in range(5, zmax + 1):
        for z2 in range(5, zmax + 1):
            z3 = z1 + 2 * z2                                   # coaxiality
            if z3 > zmax:
                break
            u = 1 + z3 / z1
            if abs(u - req) > tol * abs(req) + 1e-15:
                continue
            if (z1 + z3) % k:                                  # assembly
                continue
            if not (z1 + z2) * math.sin(math.pi / k) > z2 + 2:  # adjacency
                continue
            if z1 < zext or z2 < zext or z2 < zsat or z3 < zint or z3 - z2 < diff:
                continue
            out.append(((z1, z2, z3), (u - req) / req))
    return out


def test_user_example_both_sets_shown():
    d = _train(ratio=3.24, satellites=3, stages=[{"type": "planetary", "scheme": "A"}])
    zs = [c["z"][0] for c in d["candidates"]]
    assert [40, 23, 86] in zs and [39, 24, 87] in zs
    brute = _brute_A(3.24, 0.05, 3)
    assert d["candidates"][0]["z"][0] == [40, 23, 86]       # size first: the smallest ring
    assert min(z[2] for z, _ in brute) == 86
    # best_ratio_error: what size-first traded (the brute force's most accurate set)
    assert d["best_ratio_error"] == pytest.approx(min(abs(e) for _, e in brute), abs=1e-15)
    for c in d["candidates"]:
        assert tuple(c["z"][0]) in {z for z, _ in brute}
    d2 = _train(ratio=3.24, satellites=3, rank="ratio_error", stages=[{"type": "planetary", "scheme": "A"}])
    assert abs(d2["ratio_error"]) == pytest.approx(d2["best_ratio_error"], abs=1e-15)


def test_planetary_section_gains_rank_and_z_list():
    p = run(load_task({"schema": "tmm/1", "planetary": {"scheme": "A", "ratio": 3.24, "satellites": 3}}))["planetary"]
    assert p["z_list"] == [40, 23, 86] and p["z"] == {"z1": 40, "z2": 23, "z3": 86}
    brute = _brute_A(3.24, 0.05, 3)
    assert p["best_ratio_error"] == pytest.approx(min(abs(e) for _, e in brute), abs=1e-15)
    p2 = run(load_task({"schema": "tmm/1", "planetary": {"scheme": "A", "ratio": 3.24, "satellites": 3,
                                                           "rank": "ratio_error", "z_max": 100}}))["planetary"]
    brute = _brute_A(3.24, 0.05, 3, zmax=100)
    best = min(brute, key=lambda t: (abs(t[1]), t[0][2]))
    assert tuple(p2["z_list"]) == best[0]


def test_tooth_limits_are_fields():
    d = _train(ratio=4.0, satellites=3, z_min_external=22, z_min_internal=90, z_min_satellite_in_internal=24,
               internal_minus_external_min=10, stages=[{"type": "planetary", "scheme": "A"}])
    brute = {z for z, _ in _brute_A(4.0, 0.05, 3, zext=22, zint=90, zsat=24, diff=10)}
    assert d["candidates"] and all(tuple(c["z"][0]) in brute for c in d["candidates"])


def test_split_equal_share_and_pair_rule():
    # u = -100 over a pair (free, external) and scheme A (free): |u|^(1/2) = 10 each, the sign to the pair
    # z2 nearest to 10 * 17 = 170 -- beyond z_max = 150 is an error naming the stage and z_max
    with pytest.raises(PartialResults, match=r"stage 0 \(stages\[0\], pair\).*z2 = 170.*z_max = 150"):
        _train(ratio=-100, stages=[{"type": "pair"}, {"type": "planetary", "scheme": "A"}])
    d = _train(ratio=-100, z_max=200, stages=[{"type": "pair"}, {"type": "planetary", "scheme": "A"}])
    assert [s["ratio"] for s in d["split"]] == pytest.approx([-10.0, 10.0])
    assert d["stages"][0]["z"] == [17, 170]
    for c in d["candidates"]:
        assert abs(c["ratio_error"]) <= 0.05 + 1e-12


def test_whole_train_candidates_meet_every_condition():
    d = _train(ratio=30, satellites=3, stages=[{"type": "pair", "z": [20, 40]}, {"type": "pair", "z": [17, 34]},
                                               {"type": "planetary", "scheme": "B"}])
    from tmm_cli.gears import planetary as pl
    for c in d["candidates"]:
        z1, z2, z3, z4 = c["z"][2]
        assert z1 + z2 == z4 - z3                                  # coaxial
        u = 1 + z2 * z4 / (z1 * z3)
        assert abs(4 * u - 30) <= 0.05 * 30 + 1e-12                # the train within the tolerance
        assert (z1 + z2) * math.sin(math.pi / 3) > max(z2, z3) + 2  # adjacency
        assert min(z1, z2) >= 17 and z3 >= 20 and z4 >= 85 and z4 - z3 >= 8
        # assembly: some p with u z1 (1 + 3 p)/3 whole (checked directly with fractions)
        from fractions import Fraction
        q = Fraction(z1 * z3 + z2 * z4, z3) / 3
        assert any((q * (1 + 3 * p)).denominator == 1 for p in range(200))
        assert pl.size_key("B", dict(zip(("z1", "z2", "z3", "z4"), c["z"][2]))) <= c["size"]


# ---------------------------------------------------------------- bad input
def _write(tmp_path, text):
    f = tmp_path / "t.yaml"
    f.write_text(text)
    return f


def test_coaxiality_violation_exit_2(tmp_path):
    f = _write(tmp_path, "schema: tmm/1\ndrive_train:\n  stages:\n    - {type: pair, z: [20, 40]}\n"
                         "    - {type: planetary, scheme: A, z: [17, 34, 86]}\n")
    res = runner.invoke(app, ["run", str(f), "--out", str(tmp_path / "o"), "--format", "json"])
    assert res.exit_code == 2
    assert "drive_train.stages[1].z" in res.output and "coaxial" in res.output
    assert ":5" in res.output                                     # the line of the stage


def test_not_assemblable_given_teeth_computed_with_a_warning(tmp_path):
    """Given teeth are the user's: 3 satellites do not assemble with z1 + z3 = 104 (not a multiple
    of 3), so the stage is computed with a warning naming the numbers that do: 104/k whole for
    k = 1, 2, 4, 8; adjacency 2 a_w sin(pi/k) > z2 + 2 = 36 with a_w = 26 keeps 1, 2 and 4
    (52 sin(pi/4) = 36.77), not 8 (52 sin(pi/8) = 19.9)."""
    f = _write(tmp_path, "schema: tmm/1\ndrive_train:\n  satellites: 3\n  stages:\n"
                         "    - {type: planetary, scheme: A, z: [18, 34, 86]}\n")
    res = runner.invoke(app, ["run", str(f), "--out", str(tmp_path / "o"), "--format", "json"])
    assert res.exit_code == 0, res.output
    d = json.loads((tmp_path / "o" / "results.json").read_text())
    assert d["drive_train"]["ratio"] == pytest.approx(1 + 86 / 18, rel=1e-15)
    assert d["drive_train"]["stages"][0]["checks"]["assembly"] is False
    (m,) = [m for m in d["messages"] if m["code"] == "drive_train.given_assembly"]
    assert m["params"]["fits"] == [1, 2, 4] and m["params"]["k"] == 3


def test_book_train_ring_72_sun_32_one_planet():
    """A textbook's train (sun 32, planet 20, ring 72, one planet) breaks the internal-wheel limit
    z >= 85 of zero-shift wheels: computed as given (i_1H = 1 + 72/32), the limit named."""
    res = run(load_task({"schema": "tmm/1", "drive_train": {"satellites": 1, "stages": [
        {"type": "planetary", "scheme": "A", "z": [32, 20, 72]}]}}))
    assert res["drive_train"]["ratio"] == pytest.approx(3.25, rel=1e-15)
    (m,) = [m for m in res["messages"] if m["code"] == "drive_train.given_tooth_limits"]
    assert m["params"]["violations"] == ["z3 = 72 < 85 (internal wheel)"]
    assert not [m for m in res["messages"] if m["code"] == "drive_train.given_assembly"]


def test_unmet_ratio_exit_3(tmp_path):
    f = _write(tmp_path, "schema: tmm/1\ndrive_train:\n  ratio: 30\n  tolerance: 0.001\n  stages:\n"
                         "    - {type: planetary, scheme: A}\n")
    res = runner.invoke(app, ["run", str(f), "--out", str(tmp_path / "o"), "--format", "json"])
    assert res.exit_code == 3
    assert "stage 0" in res.output and "tolerance" in res.output and "nearest feasible ratio" in res.output


def test_given_train_missing_ratio_warns():
    res = run(load_task({"schema": "tmm/1", "drive_train": {"ratio": -20, "stages": [{"type": "pair", "z": [20, 96]}]}}))
    assert any("misses the required" in w for w in res["warnings"])


def test_stage_shape_errors():
    with pytest.raises(TaskError, match="drive_train.stages.0..z|takes 3 tooth numbers"):
        load_task({"schema": "tmm/1", "drive_train": {"stages": [{"type": "planetary", "scheme": "A",
                                                                   "z": [17, 34]}]}})
    with pytest.raises(TaskError):
        load_task({"schema": "tmm/1", "drive_train": {"stages": [{"type": "planetary"}]}})


# ---------------------------------------------------------------- motor and flywheel
def test_example_press_flywheel_on_motor_shaft(tmp_path):
    res = runner.invoke(app, ["run", str(ROOT / "tasks" / "press_drive_train.yaml"), "--out", str(tmp_path),
                              "--format", "json", "-q"])
    assert res.exit_code == 0, res.output
    r = json.loads((tmp_path / "results.json").read_text())
    d, fw = r["drive_train"], r["flywheel"]
    # required ratio 1440 rpm / 100 rpm = 14.4; the crank turns cw, two external pairs (+) and A (+)
    assert d["required"] == pytest.approx(14.4)
    assert d["motor_direction"] == "cw"
    assert d["shafts"][0] == pytest.approx(-1440 * 2 * math.pi / 60)           # the motor, cw
    assert d["shafts"][-1] == pytest.approx(d["shafts"][0] / d["ratio"])       # the crank, cw too
    assert abs(d["ratio_error"]) == pytest.approx(d["best_ratio_error"], abs=1e-15)  # rank: ratio_error
    assert fw["J_motor_shaft"] == pytest.approx(fw["J"] / d["ratio"] ** 2, rel=1e-12)
    assert fw["J_n_motor_shaft"] == pytest.approx(fw["J_n"] / d["ratio"] ** 2, rel=1e-12)
    assert d["motor_power"] == pytest.approx(fw["M_constant"] * fw["omega_m"] / 0.9, rel=1e-12)
    assert d["motor_power_computed"] is True
    # GD^2 = 4 g J
    assert fw["GD2_motor_shaft"] == pytest.approx(4 * 9.80665 * fw["J_motor_shaft"])


def test_example_given_teeth():
    r = run(load_task(ROOT / "tasks" / "planetary_pair_given.yaml"))
    d = r["drive_train"]
    u = (1 + 40 * 85 / (19 * 26)) * (-54 / 18)
    assert d["ratio"] == pytest.approx(u, rel=1e-12)
    assert d["shafts"][0] == pytest.approx(960 * 2 * math.pi / 60)
    assert "candidates" in d and d["candidates"][0]["z"] == [[19, 40, 26, 85], [18, 54]]


# ---------------------------------------------------------------- report
@pytest.mark.parametrize("lang,title,plan", [("en", "Gear drive", "Angular-velocity plan"),
                                             ("ru", "Зубчатый привод", "План угловых скоростей")])
def test_report_section(tmp_path, lang, title, plan):
    import re

    from tmm_cli.report import render_html

    task = load_task(ROOT / "tasks" / "planetary_pair_given.yaml")
    res = run(task)
    html, _ = render_html(res, task, tmp_path, lang)
    sec = html[html.index('id="drive_train"'):]
    sec = sec[:sec.index("</section>")]
    assert title in sec and plan in sec and "figure failed" not in sec
    assert sec.count("<svg") == 2
    # every stage row: the analytic ratio and the one read off the plan agree to 1e-9
    # (Russian: the decimal comma and powers of ten, 8,9·10⁻¹⁶)
    diffs = re.findall(r"<td[^>]*>(\d[.,]\d(?:e[-+]\d\d|·10[⁻⁺]?[⁰¹²³⁴⁵⁶⁷⁸⁹]+)?)</td>", sec)
    assert len(diffs) == len(res["drive_train"]["stages"])

    def read(x):
        m, _, e = x.replace(",", ".").partition("·10")
        return float(m) * 10.0 ** int(e.translate(str.maketrans("⁰¹²³⁴⁵⁶⁷⁸⁹⁻⁺", "0123456789-+")) or 0)
    assert all(read(x) <= 1e-9 for x in diffs)
    assert ("7.8825911" if lang == "en" else "7,8825911") in sec   # u1H = 1 + 40*85/(19*26) = 7.88259109


def test_chosen_pair_respects_tooth_limit():
    # |u| = 0.5 for a chosen external pair: z2 = 0.5 * 17 -> 8 or 9 teeth, below z_min_external = 17
    with pytest.raises(PartialResults, match=r"stage 0 \(stages\[0\], pair\).*z_min_external = 17"):
        _train(ratio=3, stages=[{"type": "pair", "ratio": -0.5}, {"type": "pair"}])
    d = _train(ratio=-7.5, stages=[{"type": "pair", "ratio": -1.5}, {"type": "pair", "internal": True}])
    # the own ratio -1.5: z1 = 17, z2 = round(25.5) = 26 (ties to even) -> u = -26/17;
    # the rest -7.5 / -1.5 = 5 to the internal pair: z1 = 20, z2 = 100 -> U = -26/17 * 5 = -7.647 (+1.96 %)
    assert d["stages"][0]["z"] == [17, 26] and d["stages"][1]["z"] == [20, 100]
    assert d["ratio"] == pytest.approx(-26 / 17 * 5) and d["ratio_error"] == pytest.approx((-130 / 17 + 7.5) / -7.5)
