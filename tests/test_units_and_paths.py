"""Unit conversion (pint), fractions, results paths and answer checking."""
from __future__ import annotations

import math

import pytest

from tmm_cli.check import check_task, tolerance_for
from tmm_cli.results import clean, dumps, lookup, parse_path
from tmm_cli.units import convert


@pytest.mark.parametrize("value,kind,expected", [
    ("300 mm", "length", 0.3),
    ("50 rpm", "speed", 50 * 2 * math.pi / 60),
    # revolutions as texts abbreviate them: rev/min, ISO 80000's r/min, and per second
    ("50 rev/min", "speed", 50 * 2 * math.pi / 60),
    ("50 r/min", "speed", 50 * 2 * math.pi / 60),
    ("2 rev/s", "speed", 2 * 2 * math.pi),
    ("2 r/s", "speed", 2 * 2 * math.pi),
    # min^-1 printed with its superscript lost, as texts give n = 1450 min-1
    ("180 min-1", "speed", 180 * 2 * math.pi / 60),
    ("180 \u043c\u0438\u043d-1", "speed", 180 * 2 * math.pi / 60),
    ("180 \u043c\u0438\u043d\u22121", "speed", 180 * 2 * math.pi / 60),
    ("12.5 s-1", "speed", 12.5),
    ("5.24 rad/s", "speed", 5.24),
    ("10 MPa", "pressure", 10e6),
    ("0.15 kg*m^2", "inertia", 0.15),
    ("20 deg", "angle", 20.0),
    (f"{math.pi} rad", "angle", 180.0),
    ("1/18", "dimensionless", 1 / 18),
    ("3 kN", "force", 3000.0),
    ("78.5 cm^2", "area", 78.5e-4),
    (0.5, "length", 0.5),
    (7, "mass", 7.0),
])
def test_convert(value, kind, expected):
    assert convert(value, kind) == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("value,kind,frag", [
    ("5 kg", "length", "is not a length"),
    ("3 N", "speed", "is not an angular speed"),
    (True, "length", "got True"),
    ("abc", "dimensionless", "fraction"),
    ("nan", "length", "finite"),
    ("50 rev", "speed", "'rev' is not defined"),       # a revolution is no speed
    ("50 r", "speed", "'r' is not defined"),
    ("3 m-1", "length", "cannot read the unit"),        # a bare -1 after a minute or second only
    ("180 min-12", "speed", "cannot read the unit"),
])
def test_convert_errors(value, kind, frag):
    with pytest.raises(ValueError) as e:
        convert(value, kind)
    assert frag in str(e.value)


def test_paths():
    assert parse_path("kinematics[2].points.B.v") == ["kinematics", 2, "points", "B", "v"]
    res = {"kinematics": [{"index": 0, "v": 1.0}, {"index": 12, "v": 5.0}, {"index": 2, "v": 3.0}],
           "gears": {"r": [0.018, 0.063]}, "structure": {"W": 1}}
    assert lookup(res, "kinematics[2].v") == 3.0       # by entry index, not list position
    assert lookup(res, "kinematics[12].v") == 5.0
    assert lookup(res, "gears.r[1]") == 0.063
    with pytest.raises(KeyError):
        lookup(res, "kinematics[5].v")
    with pytest.raises(KeyError):
        lookup(res, "structure.X")


def test_check_verdicts():
    res = {"structure": {"W": 1}, "flywheel": {"J": 10.0}, "cam": {"offset": 0.0}}
    rows = check_task(res, {"structure.W": 1, "flywheel.J": 9.1, "cam.offset": 0.001, "gears.aw": 1.0},
                      {"default": 0.05, "flywheel.J": 0.1})
    by = {r["quantity"]: r for r in rows}
    assert by["structure.W"]["verdict"] == "ok" and by["structure.W"]["rel_error"] == 0
    assert by["flywheel.J"]["rel_error"] == pytest.approx(0.09)   # |9.1-10|/10
    assert by["flywheel.J"]["verdict"] == "ok"                   # within its own 10 %
    assert by["cam.offset"]["verdict"] == "ok"                   # zero reference: absolute 0.001 <= 0.05
    assert by["gears.aw"]["verdict"] == "not_computed"             # the task has no gears stage
    assert tolerance_for("kinematics[2].points.B.v", {"kinematics": 0.02}) == 0.02
    assert tolerance_for("x", {}) == 0.05


def test_clean_no_nan():
    import numpy as np
    d = clean({"a": np.float64("nan"), "b": np.arange(3), "c": [float("inf"), 1.5], "d": np.int64(4)})
    assert d == {"a": None, "b": [0, 1, 2], "c": [None, 1.5], "d": 4}
    assert "NaN" not in dumps({"x": float("nan")})
    assert dumps({"x": -0.0, "y": np.float64(-0.0)}) == '{\n "x": 0.0,\n "y": 0.0\n}\n'


def test_pint_disk_cache_is_one_folder_per_installation(tmp_path, monkeypatch):
    """pint's shared cache (`:auto:`) let one installation read another's parsed definitions,
    with the other's file paths inside: removing a virtual environment broke every other
    one's registry. tmm keeps one folder per pint installation, and none if it can't make it."""
    from types import SimpleNamespace

    import platformdirs

    from tmm_cli.numbers import _pint_cache_folder

    monkeypatch.setattr(platformdirs, "user_cache_path", lambda **kw: tmp_path / "cache" / kw["appname"])
    a = _pint_cache_folder(SimpleNamespace(__file__="/venv-a/site-packages/pint/__init__.py", __version__="0.24"))
    b = _pint_cache_folder(SimpleNamespace(__file__="/venv-b/site-packages/pint/__init__.py", __version__="0.24"))
    c = _pint_cache_folder(SimpleNamespace(__file__="/venv-a/site-packages/pint/__init__.py", __version__="0.25"))
    assert len({a, b, c}) == 3 and all(p.is_dir() and p.parent == tmp_path / "cache" / "pint" for p in (a, b, c))
    assert a == _pint_cache_folder(SimpleNamespace(__file__="/venv-a/site-packages/pint/__init__.py",
                                                   __version__="0.24"))
    (tmp_path / "file").write_text("x")
    monkeypatch.setattr(platformdirs, "user_cache_path", lambda **kw: tmp_path / "file" / "sub")
    assert _pint_cache_folder(SimpleNamespace(__file__="/v/pint/__init__.py", __version__="0.24")) is None
