"""The fast paths give the same numbers as the slow ones they replace, and a JSON run
imports only what it needs (scipy, matplotlib, weasyprint, ezdxf, pint stay out)."""
from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from tmm_cli import lazy, units
from tmm_cli.results import clean, dumps

ROOT = Path(__file__).resolve().parents[1]
HEAVY = ("scipy", "matplotlib", "weasyprint", "ezdxf", "pint", "jinja2")


def _imported_by(args: list[str], tmp_path: Path) -> set[str]:
    code = ("import sys\nfrom tmm_cli.cli import main\n"
            "try:\n    main()\nexcept SystemExit as e:\n    code = e.code\nelse:\n    code = 0\n"
            "print('MODULES', ' '.join(sorted({m.split('.')[0] for m in sys.modules})), file=sys.stderr)\n"
            "sys.exit(code)\n")
    p = subprocess.run([sys.executable, "-c", code, *args], cwd=tmp_path, capture_output=True,
                       text=True, timeout=300)
    assert p.returncode == 0, p.stderr
    line = [ln for ln in p.stderr.splitlines() if ln.startswith("MODULES ")][-1]
    return set(line.split()[1:])


def test_json_run_imports_no_heavy_module(tmp_path):
    mods = _imported_by(["run", str(ROOT / "tasks" / "forging_sixbar.yaml"), "--format", "json",
                         "-o", str(tmp_path / "o")], tmp_path)
    assert "numpy" in mods                       # the stages ran
    assert not mods & set(HEAVY), sorted(mods & set(HEAVY))
    assert json.loads((tmp_path / "o" / "results.json").read_text())["kinetostatics"]


def test_validate_imports_no_heavy_module(tmp_path):
    mods = _imported_by(["validate", str(ROOT / "tasks" / "forging_sixbar.yaml")], tmp_path)
    assert not mods & set(HEAVY), sorted(mods & set(HEAVY))


@pytest.mark.parametrize("kind", sorted(units._FAST_UNITS))
def test_fast_units_equal_pint(kind):
    """Each factor of the table is pint's, and the product is pint's result to the bit."""
    target = units.KINDS[kind][0]
    reg = units.ureg()
    for unit, factor in units._FAST_UNITS[kind].items():
        for value in ("1", "50", "-3.25", "0.001", "2.5e3", "137.5"):
            q = reg.Quantity(f"{value} {unit}")
            if kind == "force_or_pressure":
                want = q.to("N" if q.check("[force]") else "Pa").magnitude
            else:
                want = q.to(target).magnitude
            assert units._fast(f"{value} {unit}", kind) == want, (value, unit)
            if abs(want) <= units.LIMIT:
                assert units.convert(f"{value} {unit}", kind) == want


def test_fast_units_leave_the_rest_to_pint():
    assert units._fast("50 RPM", "speed") is None           # pint decides (and rejects)
    assert units._fast("3 ft", "length") is None
    assert units.convert("3 ft", "length") == pytest.approx(0.9144)
    assert units.convert("300mm", "length") == pytest.approx(0.3)
    with pytest.raises(ValueError):
        units.convert("5 kg", "length")


def _fns():
    rng = np.random.default_rng(7)
    for _ in range(200):
        c = rng.normal(size=4)
        yield lambda x, c=c: c[0] + c[1] * x + c[2] * math.sin(3 * x) + c[3] * x ** 3


def test_brentq_is_scipys_to_the_bit():
    from scipy.optimize import brentq
    n = 0
    for f in _fns():
        if f(-3.0) * f(3.0) >= 0:
            continue
        for kw in ({}, {"xtol": 1e-12, "rtol": 1e-14}, {"xtol": 1e-15, "rtol": 8.9e-16, "maxiter": 400}):
            assert lazy.brentq(f, -3.0, 3.0, **kw) == brentq(f, -3.0, 3.0, **kw)
            n += 1
    assert n > 100
    assert lazy.brentq(lambda x: x * x - 2.0, 0.0, 2.0) == pytest.approx(math.sqrt(2.0), abs=1e-11)
    with pytest.raises(ValueError):
        lazy.brentq(lambda x: x * x + 1.0, -1.0, 1.0)


def test_bounded_minimum_is_scipys_to_the_bit():
    from scipy.optimize import minimize_scalar
    for f in _fns():
        g = lambda x, f=f: abs(f(x))  # noqa: E731
        a = minimize_scalar(g, bounds=(-3.0, 3.0), method="bounded", options={"xatol": 1e-10})
        b = lazy.minimize_scalar(g, bounds=(-3.0, 3.0), method="bounded", options={"xatol": 1e-10})
        assert (a.x, a.fun, a.nfev) == (b.x, b.fun, b.nfev)
    r = lazy.minimize_scalar(lambda x: (x - 1.25) ** 2, bounds=(0.0, 2.0), options={"xatol": 1e-10})
    assert r.success and r.x == pytest.approx(1.25, abs=1e-8)


def test_results_text_is_json_readable_and_deterministic():
    data = {"a": [1.0, 2.5, None], "b": {"c": [[1, 2], [3, 4]], "d": [], "e": {}},
            "f": [{"g": "ω"}], "h": np.arange(3.0), "i": -0.0}
    text = dumps(data)
    assert json.loads(text) == clean(data)
    assert text == dumps(data)
    assert '"a": [1.0, 2.5, null]' in text and '  "c": [\n   [1, 2],' in text
    assert '"g": "ω"' in text and '"i": 0.0' in text
    assert json.loads(dumps({"x": float("nan")})) == {"x": None}


def test_unwrap_is_numpys():
    from tmm_cli.linkage.kinematics.solver import _unwrap, _unwrap_sorted
    rng = np.random.default_rng(3)
    for n in (1, 2, 5, 36, 400):
        for scale in (0.01, 1.0, 5.0):
            x = rng.uniform(-10, 10, n) * scale
            assert np.array_equal(_unwrap(x), np.unwrap(x))
            order = np.argsort(rng.uniform(size=n))
            want = x.copy()
            want[order] = np.unwrap(x[order])
            assert np.array_equal(_unwrap_sorted(x, order), want)
    x = np.array([0.0, np.pi, 0.0, -np.pi, 3 * np.pi, 2.0])      # the ambiguous jumps of +-pi
    assert np.array_equal(_unwrap(x), np.unwrap(x))
