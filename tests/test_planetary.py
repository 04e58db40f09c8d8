"""Planetary synthesis: every returned set is checked here independently (Willis' formula
as a product of signed mesh ratios, coaxiality by centre distances, the exact assembly
condition for rigid identical satellites, adjacency of satellite tip circles, the textbook
tooth-number limits), the velocity plan against Willis, and a published example."""
import math
from math import gcd

import pytest
from pydantic import ValidationError
from hypothesis import given, settings
from hypothesis import strategies as st

from tmm_cli.errors import StageError
from tmm_cli.gears import synthesize_planetary
from task_sections import planetary  # noqa: E402  (sections through the task model)

# mesh chains with the carrier held: (driving, driven, kind); the last wheel is fixed
CHAINS = {"A": [("z1", "z2", "ext"), ("z2", "z3", "int")],
          "B": [("z1", "z2", "ext"), ("z3", "z4", "int")],
          "C": [("z1", "z2", "ext"), ("z3", "z4", "ext")],
          "D": [("z1", "z2", "int"), ("z3", "z4", "int")]}
INTERNAL = {"A": {"z3"}, "B": {"z4"}, "C": set(), "D": {"z1", "z4"}}


def willis(scheme, z):
    i_h = 1.0
    for a, b, kind in CHAINS[scheme]:
        i_h *= (-1 if kind == "ext" else 1) * z[b] / z[a]       # omega_a / omega_b, carrier held
    return 1 - i_h                                                # i_1H = 1 - i_1F^(H)


def centre_distance(scheme, za_name, zb_name, z):
    a, b = z[za_name], z[zb_name]
    if za_name in INTERNAL[scheme] or zb_name in INTERNAL[scheme]:
        return abs(a - b) / 2
    return (a + b) / 2


def independent_check(scheme, z, k, required, tol):
    i = willis(scheme, z)
    assert abs(i - required) <= tol * abs(required) * (1 + 1e-12), "ratio"
    (a1, b1, _), (a2, b2, _) = CHAINS[scheme]
    aw1 = centre_distance(scheme, a1, b1, z)
    aw2 = centre_distance(scheme, a2, b2, z)
    assert aw1 == aw2 and aw1 > 0, "coaxiality"
    # exact assembly condition for k rigid identical satellites (rims s1 meshing 1 and s2
    # meshing the fixed wheel): wheel 1 turns by i_1H z1 / k of its pitches per 2 pi / k of
    # the carrier, and the satellite can re-index by gcd(s1, s2)/s2 of them.
    sat = ["z2"] if scheme == "A" else ["z2", "z3"]
    s2 = z[sat[-1]]
    num = round(abs(i * z["z1"] * s2))                           # i_1H z1 s2 is an integer
    assert abs(i * z["z1"] * s2 - (num if i * z["z1"] >= 0 else -num)) < 1e-6
    g = gcd(z[sat[0]], s2)
    assert num % (k * g) == 0, "assembly"
    # adjacency: neighbouring satellite centres further apart than the tip diameter
    if k > 1:
        assert 2 * aw1 * math.sin(math.pi / k) > max(z[s] for s in sat) + 2, "adjacency"
    # textbook limits (Popov & Timofeev): external wheel in external mesh >= 17, external
    # wheel in internal mesh >= 20, internal wheel >= 85, z_int - z_ext >= 8
    for a, b, _ in CHAINS[scheme]:
        for w, o in ((a, b), (b, a)):
            if w in INTERNAL[scheme]:
                assert z[w] >= 85 and z[w] - z[o] >= 8, "internal wheel"
            elif o in INTERNAL[scheme]:
                assert z[w] >= 20, "external wheel in internal mesh"
            else:
                assert z[w] >= 17, "external wheel"


CASES = [("A", 3.24, 3, 0.05), ("A", 7.0, 3, 0.01), ("A", 5.5, 4, 0.02), ("B", 12.0, 3, 0.05),
         ("B", 8.0, 3, 0.02), ("C", -2.24, 3, 0.05), ("C", 0.05, 3, 0.05), ("D", 0.1, 3, 0.05),
         ("D", -0.2, 2, 0.05), ("A", 4.0, 1, 0.01)]


@pytest.mark.parametrize("scheme,ratio,k,tol", CASES)
def test_every_returned_set_meets_all_conditions(scheme, ratio, k, tol):
    res = synthesize_planetary(planetary(scheme=scheme, ratio=ratio, satellites=k, tolerance=tol))
    d = res.to_dict()
    assert d["candidates"], "candidates"
    for c in d["candidates"]:
        independent_check(scheme, c["z"], k, ratio, tol)
        assert c["ratio"] == pytest.approx(willis(scheme, c["z"]), rel=1e-12)
    assert d["candidates"][0]["z"] == d["z"]
    assert d["ratio"] == pytest.approx(willis(scheme, d["z"]), rel=1e-12)
    assert d["ratio_error"] == pytest.approx((willis(scheme, d["z"]) - ratio) / ratio, rel=1e-9, abs=1e-15)
    # ranking: sizes never decrease down the list
    sizes = [c["size"] for c in d["candidates"]]
    assert sizes == sorted(sizes)


@given(st.sampled_from(["A", "B"]), st.floats(min_value=3.0, max_value=12.0), st.integers(2, 4))
@settings(max_examples=15, deadline=None)
def test_property_positive_ratio_schemes(scheme, ratio, k):
    try:
        res = synthesize_planetary(planetary(scheme=scheme, ratio=ratio, satellites=k, tolerance=0.03))
    except StageError:
        return                                                    # nothing fits: reported, fine
    for c in res.to_dict()["candidates"]:
        independent_check(scheme, c["z"], k, ratio, 0.03)


def test_ukrbukva_piston_pump_scheme_a_ratio_7():
    """Published course project (ukrbukva.net, «Поршневий насос для перекачування рідини»,
    planetary stage of scheme A, i_1H = 7, k = 3): z1 = 18, z2 = 45, z3 = 108 (z1 = 17 gives
    no integer z2 for the exact ratio)."""
    res = synthesize_planetary(planetary(scheme="A", ratio=7, satellites=3, tolerance=0.005))
    assert res.z == {"z1": 18, "z2": 45, "z3": 108}
    assert res.to_dict()["ratio_error"] == 0.0


def test_velocity_plan_matches_willis():
    for scheme, ratio in (("A", 3.24), ("B", 12.0), ("C", -2.24), ("D", 0.1)):
        res = synthesize_planetary(planetary(scheme=scheme, ratio=ratio, satellites=3, tolerance=0.05, m=0.002))
        d = res.to_dict()
        z = d["z"]
        i = willis(scheme, z)
        assert d["ratio_plan"] == pytest.approx(i, rel=1e-10)
        # satellite angular velocity, Willis with the carrier held: (w2 - wH)/(w1 - wH) = -+ z1/z2
        plan = d["velocity_plan"]
        w1, wh = plan["omega1"], plan["omega_H"]
        sign = 1 if scheme == "D" else -1
        assert plan["omega_satellite"] - wh == pytest.approx(sign * (w1 - wh) * z["z1"] / z["z2"], rel=1e-10)
        # the fixed contact has zero velocity, the 1-2 contact moves with wheel 1
        pts = {p["name"][0]: p for p in plan["points"]}
        assert pts["F"]["v"] == 0.0
        assert pts["A"]["v"] == pytest.approx(w1 * pts["A"]["y"], rel=1e-12)
        assert pts["C"]["v"] == pytest.approx(wh * pts["C"]["y"], rel=1e-12)


def test_errors():
    with pytest.raises(ValidationError):                  # an unknown scheme: the task model's error
        planetary(scheme="Z", ratio=3, satellites=3, tolerance=0.05)
    with pytest.raises(StageError):
        synthesize_planetary(planetary(scheme="A", ratio=0.5, satellites=3, tolerance=0.05))
    with pytest.raises(StageError):                       # 12 satellites never fit in scheme A
        synthesize_planetary(planetary(scheme="A", ratio=4, satellites=12, tolerance=0.001))


def test_scheme_a_hint_states_the_feasible_range():
    """No set of scheme A meets the ratio: the hint gives the least and the greatest ratio of
    the sets that meet every other condition. By hand, 3 satellites, z in [17, 150], z2 >= 20
    (a satellite in internal mesh): i = 1 + z3/z1 with z3 = z1 + 2 z2 and (z1 + z3)/3 whole.
    Least: z2 = 20, z3 as large as allowed: z3 = 150, z1 = 110 (260/3 not whole), so z3 = 149,
    z1 = 109 (258/3 = 86): i = 1 + 149/109 = 2.36697. Greatest: z1 = 17, z3 = 17 + 2 z2 <= 150:
    z3 = 149 (166/3 no), 147 (164/3 no), 145 (162/3 = 54): i = 1 + 145/17 = 9.52941."""
    for ratio in (1.2, 12.0):
        with pytest.raises(StageError) as e:
            synthesize_planetary(planetary(scheme="A", ratio=ratio, satellites=3, tolerance=0.05, m=0.002))
        hint = e.value.message.params["hint"]
        assert hint["code"] == "planetary.hint.scheme_a"
        assert hint["params"]["lo"] == pytest.approx(1 + 149 / 109, rel=1e-12)
        assert hint["params"]["hi"] == pytest.approx(1 + 145 / 17, rel=1e-12)
        assert "only between 2.367 and 9.529" in str(e.value)
