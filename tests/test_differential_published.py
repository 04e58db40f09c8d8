"""Differentials and epicyclic trains against published worked examples, their printed numbers
written out here and compared with the tolerance the publication's rounding allows.

Source: R. S. Khurmi and J. K. Gupta, *Theory of Machines*, 14th ed. (Eurasia Publishing House,
New Delhi, 2009, ISBN 81-219-2524-X), ch. 13 "Gear trains" (the
printed numbers as the FOSSEE Python Textbook Companion reproduces them,
github.com/FOSSEE/Python-Textbook-Companions, folder
"Theory_Of_Machines_by_R._S._Khurmi_And_J._K._Gupta", ch13.ipynb): Examples 13.7 (p. 444),
13.10 (p. 448), 13.20 (p. 465) and 13.22 (p. 468). Members as tmm names them: "1" the first central wheel,
the last central wheel ("3" in scheme A, "4" in B-D) and the carrier "H"; speeds and torques
counter-clockwise positive.

Norton (Design of Machinery, ch. 9, the tabular and formula methods), Shigley and Uicker,
Artobolevsky, Popov and Timofeev, and Frolov could not be read here; no published example
with the efficiency of a differential was found: the power balance with losses is checked by
hand in tests/test_differential.py.
"""
import pytest

from tmm_cli import load_task, run


def _diff(**kw):
    return run(load_task({"schema": "tmm/1", "differential": kw}))["differential"]


@pytest.mark.parametrize("ring_rpm, printed, tol", [
    (0.5, 0.04, 0.005),         # "0.04 revolution anticlockwise": two decimals
    (0.0, -0.308, 0.0005),      # "0.308 revolution clockwise": three decimals
])
def test_khurmi_example_13_7_arm_speed_of_a_differential(ring_rpm, printed, tol):
    """Khurmi and Gupta, Theory of Machines, Example 13.7, p. 444: the sun A (40 teeth) and the
    annulus D (90 teeth) with two planets B and C (25 teeth) on the arm. A makes 1 revolution
    clockwise and D half a revolution anticlockwise: the arm makes 0.04 revolution
    anticlockwise (exact 0.125/3.25 = 0.03846); with D at rest, 0.308 revolution clockwise
    (exact 1/3.25 = 0.30769). Revolutions per minute stand for revolutions here: the ratios
    are what is printed."""
    d = _diff(scheme="A", z=[40, 25, 90], satellites=2, speeds={"1": "-1 rpm", "3": f"{ring_rpm} rpm"})
    assert d["u"] == pytest.approx(-90 / 40, rel=1e-15)
    assert d["speeds_rpm"]["H"] == pytest.approx(printed, abs=tol)
    assert d["speeds_rpm"]["H"] == pytest.approx((-1 + 2.25 * ring_rpm) / 3.25, rel=1e-12)


def test_khurmi_example_13_10_two_row_train_output_speed():
    """Khurmi and Gupta, Theory of Machines, Example 13.10, p. 448: the wheel C (50 teeth) on the
    input shaft at 110 rpm meshes D (20 teeth); D's compound wheel E (35 teeth) meshes the fixed
    internal wheel G (the book's 50 + 20 + 35 = 105 teeth); the arm drives the shaft B:
    tmm's scheme B with z = [50, 20, 35, 105]. Printed: the speed of B 50 rpm anticlockwise
    (the book rounds to whole rpm; exact 110/2.2 = 50)."""
    d = _diff(scheme="B", z=[50, 20, 35, 105], satellites=2, speeds={"1": "110 rpm", "4": 0})
    assert d["u"] == pytest.approx(-(20 * 105) / (50 * 35), rel=1e-15)
    assert d["speeds_rpm"]["H"] == pytest.approx(50, abs=0.5)
    assert d["speeds_rpm"]["H"] == pytest.approx(110 / 2.2, rel=1e-12)


def test_khurmi_example_13_20_holding_torque_on_the_annulus():
    """Khurmi and Gupta, Theory of Machines, Example 13.20, p. 465: the sun S (16 teeth) turns
    five times as fast as the arm, the annulus E (64 teeth, found by the book from that ratio)
    held, planets P of 24 teeth; 100 N*m on the sun. Printed: the torque to hold the annulus
    400 N*m (whole N*m, exact: the arm's 500 N*m less the sun's 100). The number of planets
    is not in the book's answer: 4 here (they assemble: (16 + 64)/4 = 20)."""
    d = _diff(scheme="A", z=[16, 24, 64], satellites=4, speeds={"1": "500 rpm", "3": 0}, torque={"1": "100 N*m"})
    assert d["speeds_rpm"]["1"] / d["speeds_rpm"]["H"] == pytest.approx(5, rel=1e-12)
    t = d["torques"]
    assert abs(t["3"]) == pytest.approx(400, abs=0.5)
    assert t["3"] == pytest.approx(400, rel=1e-12)      # on the annulus, the sun's sense
    assert t["H"] == pytest.approx(-500, rel=1e-12)     # the arm's load: the sun's power at 1/5 the speed


def test_khurmi_example_13_22_holding_torque_and_output_speed():
    """Khurmi and Gupta, Theory of Machines, Example 13.22, p. 468: the fixed sun D
    (25 teeth, the book's 60 - (20 + 15)) meshes C (20 teeth); C's compound wheel B (15 teeth)
    meshes the annulus A (60 teeth) on the input shaft Y, 740 rad/s and 130 kW; the arm drives
    the output shaft X: tmm's scheme B with z = [25, 20, 15, 60]. Printed: the speed of X
    563.8 rad/s and the torque holding D 54.9 N*m (one decimal each: +-0.05). Efficiency 1, as
    the book takes it. Three satellites here (the book's answer does not depend on them)."""
    d = _diff(scheme="B", z=[25, 20, 15, 60], satellites=3, speeds={"1": 0, "4": "740 rad/s"},
              torque={"4": f"{130e3 / 740} N*m"})
    assert d["u"] == pytest.approx(-(20 * 60) / (25 * 15), rel=1e-15)
    assert d["speeds"]["H"] == pytest.approx(563.8, abs=0.05)
    t = d["torques"]
    assert t["1"] == pytest.approx(54.9, abs=0.05)
    assert -t["H"] * d["speeds"]["H"] == pytest.approx(130e3, rel=1e-12)    # the output power, no loss
