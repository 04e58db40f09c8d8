"""The task section dof2: (Dof2Section): units, defaults, errors, the example task."""
from __future__ import annotations

import math
from pathlib import Path

import pytest
from pydantic import ValidationError

from tmm_cli.dof2 import Dof2Section, analyze

ROOT = Path(__file__).resolve().parents[1]
MIN = {"rotor": {"length": 0.06}, "striker": {"length": 0.09, "mass": 0.35}, "t_end": 0.04}


def with_(**kw):
    d = {k: (dict(v) if isinstance(v, dict) else v) for k, v in MIN.items()}
    d.update(kw)
    return d


def test_units_are_converted():
    s = Dof2Section.model_validate(with_(
        rotor={"length": "60 mm", "mass": "1200 g", "com": "1 cm", "J": "12000 kg*cm^2"},
        striker={"length": "9 cm", "com": "55 mm", "mass": 0.35, "J": "2.4e-4 kg*m^2"},
        drive={"speed": "1500 rpm", "direction": "cw"}, initial={"phi": "0.5 rad", "psi": 150},
        t_end="40 ms"))
    assert s.rotor.length == pytest.approx(0.06)
    assert s.rotor.mass == pytest.approx(1.2)
    assert s.rotor.J == pytest.approx(1.2)              # 12000 kg*cm^2 = 1.2 kg*m^2
    assert s.rotor.inertia_O == pytest.approx(1.2 + 1.2 * 0.01 ** 2)   # Huygens-Steiner
    assert s.striker.l_c == pytest.approx(0.055)
    assert s.drive.omega1 == pytest.approx(-1500 * math.pi / 30)
    assert s.initial.phi == pytest.approx(math.degrees(0.5))
    assert s.t_end == pytest.approx(0.04)


def test_defaults():
    s = Dof2Section.model_validate(MIN)
    assert s.gravity is False and s.drive is None and s.impact is None
    assert s.striker.l_c == pytest.approx(0.045)       # half the striker by default
    assert s.rotor.inertia_O == 0.0
    assert (s.initial.phi, s.initial.psi, s.initial.omega, s.initial.psi_dot) == (0, 0, 0, 0)
    assert s.samples == 401
    s = Dof2Section.model_validate(with_(rotor={"length": 0.06, "mass": 2, "com": 0.01, "J_O": 0.01}))
    assert s.rotor.inertia_O == 0.01


@pytest.mark.parametrize("data, fragment", [
    (with_(rotr={"length": 1}), "did you mean 'rotor'"),
    (with_(striker={"length": 0.09, "mass": 0.35, "lc": 0.05}), "unknown key 'lc'"),
    (with_(drive={"moment": 1, "speed": 10}), "exactly one"),
    (with_(drive={}), "exactly one"),
    (with_(drive={"moment": 1, "direction": "cw"}), "direction"),
    (with_(drive={"speed": -5}), "positive"),
    (with_(drive={"speed": 10}, initial={"omega": 3}), "contradicts"),
    (with_(t_end=None), "exactly one"),
    (with_(turns=2), "exactly one"),
    (with_(t_end="40 kg"), "does not convert to s"),
    (with_(t_end=-1), "positive"),
    (with_(samples=1), "samples"),
    (with_(rotor={"length": "5 kg"}), "length"),
    (with_(rotor={"length": 0}), "positive"),
    (with_(rotor={"length": 0.06, "J": 0.1, "J_O": 0.2}), "not both"),
    (with_(rotor={"length": 0.06, "mass": 1, "com": 0.1, "J_O": 0.001}), "impossible"),
    (with_(striker={"length": 0.09, "mass": 0}), "needs a mass"),
    (with_(striker={"length": 0.09, "mass": -1}), "negative"),
    (with_(impact={"angle": 90}), "unknown key"),
])
def test_errors(data, fragment):
    with pytest.raises(ValidationError) as e:
        Dof2Section.model_validate({k: v for k, v in data.items() if v is not None})
    assert fragment in str(e.value)


def test_example_task_validates_and_runs():
    from tmm_cli.yamlload import load_yaml
    data, _ = load_yaml(ROOT / "tasks" / "impact_rotor.yaml")
    assert data["schema"] == "tmm/1" and data["title"]
    s = Dof2Section.model_validate(data["dof2"])
    r = analyze(s).to_dict()
    om = 1500 * math.pi / 30
    # held speed: phi = omega1 t, hit at phi = 270 deg after (3 pi / 2) / omega1
    assert r["impact"]["t"] == pytest.approx(1.5 * math.pi / om, rel=1e-9)
    assert r["phi"][-1] == pytest.approx(math.degrees(om * 0.04), rel=1e-12)
    assert r["energy"]["relative_error"] < 1e-8
    assert r["warnings"] == []
