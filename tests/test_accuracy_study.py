"""Accurate flywheel defaults, the accuracy study and the hand method's own error.

Independent references:
* a central slider-crank with a constant resistance F over its working stroke (crank
  0 -> 180 deg) and constant reduced inertia, where the works are closed forms:
  s(q) = r + l - r cos q - sqrt(l^2 - r^2 sin^2 q), A_c = F s(q) on the working stroke,
  A_c = 2 F r after it, M_d = 2 F r/(2 pi) = F r/pi, dT = M_d q - A_c; the extrema of
  dT where s'(q) = r/pi, located here by scipy's brentq on the closed-form s'(q);
  J_n = range(dT)/(omega_m^2 delta) (constant inertia: all three methods agree);
* the theoretical orders of the rules: the trapezoid 2, n-point Gauss-Legendre 2n;
* the reading error of a plan: 0.5 mm times the scale over the value, scale = the
  nice number >= v_A/100 mm written out here.
"""
from __future__ import annotations

import json
import math
import subprocess
import sys

import numpy as np
import pytest

from tmm_cli.linkage.dynamics import EPS_DEG, Sample, analyze_sampler
from tmm_cli.linkage.dynamics import flywheel as fw
from task_sections import flywheel  # noqa: E402  (the section through the task model)

R, L, F, J0, WM = 0.1, 0.35, 2000.0, 0.05, 20.0


def _sp(q):
    """ds/dq of the central slider-crank (closed form)."""
    return R * np.sin(q) + R * R * np.sin(q) * np.cos(q) / np.sqrt(L * L - R * R * np.sin(q) ** 2)


def _s(q):
    return R + L - R * np.cos(q) - np.sqrt(L * L - R * R * np.sin(q) ** 2)


def _sampler(q, side):
    qe = np.mod(q + side * EPS_DEG, 360.0)
    x = np.deg2rad(qe)
    M = np.where(qe < 180.0, -F * _sp(x), 0.0)
    return Sample(M_by_kind={"resistance": M}, M_given=M, J_links={"crank": np.full(q.shape, J0)},
                  dJ_links={"crank": np.zeros(q.shape)})


def _closed_form(delta):
    from scipy.optimize import brentq
    Md = F * R / math.pi

    def dT(q):
        return Md * q - F * _s(q) if q <= math.pi else Md * q - 2 * F * R

    g = lambda q: _sp(q) - R / math.pi   # noqa: E731  dT' = 0
    qs = np.linspace(1e-9, math.pi - 1e-9, 2001)
    gv = g(qs)
    roots = [brentq(g, qs[i], qs[i + 1], xtol=1e-15) for i in range(qs.size - 1) if gv[i] * gv[i + 1] < 0]
    cands = [dT(0.0), dT(math.pi), *[dT(x) for x in roots]]
    return (max(cands) - min(cands)) / (WM**2 * delta), Md


def section(delta, resolution=360, quadrature=2, method="energy-mass"):
    return flywheel(delta=delta, constant="driving", method=method, resolution=resolution,
                    quadrature=quadrature, shape=dict(type="disk", density=7800.0, width_ratio=0.1),
                    reduced_J=0.0)


@pytest.mark.parametrize("delta", [1 / 18, 0.1])
def test_converged_flywheel_against_closed_form_slider_crank(delta):
    Jn, Md = _closed_form(delta)
    r = analyze_sampler(_sampler, section(delta), WM, switch_q=(0.0, 180.0), accuracy=False)
    c = r.cycle
    assert c.work.M_constant == pytest.approx(Md, rel=1e-10)   # Gauss 2 points: O(h^4)
    for m in ("energy-mass", "merzalov", "exact"):
        assert c.J_n[m] == pytest.approx(Jn, rel=1e-9), m
    # the old default (trapezoid on the same grid, extrema at the nodes) is far less accurate
    t = analyze_sampler(_sampler, section(delta, quadrature=0), WM, switch_q=(0.0, 180.0),
                        accuracy=False).cycle
    assert abs(t.J_n["energy-mass"] / Jn - 1) > 1e-6
    # the hand method (12 positions) is reported beside it with its own error
    h = r.to_dict()["hand"]
    assert h["positions"] == 12
    assert h["err_J_n"] == pytest.approx(abs(h["J_n"] / c.J_n["energy-mass"] - 1), rel=1e-12)


@pytest.mark.parametrize("n", [1, 2, 3])
def test_gauss_legendre_order_is_2n(n):
    """Composite n-point Gauss-Legendre on a smooth integrand: error ~ h^(2n)."""
    f = lambda x: np.exp(np.sin(3 * x)) * np.cos(x)   # noqa: E731
    from scipy.integrate import quad
    exact = quad(f, 0.0, 1.3, epsabs=1e-14, epsrel=1e-14, limit=200)[0]
    Ns = [4, 8, 16, 32]
    errs = []
    for N in Ns:
        q = np.linspace(0.0, 1.3, N + 1)
        errs.append(abs(fw.gauss_increments(q, f(fw.gauss_points(q, n)).ravel(), n).sum() - exact))
    from tmm_cli.study import fit_order
    assert fit_order(Ns, errs) == pytest.approx(2 * n, abs=0.5)
    # the trapezoid on the same nodes: order 2
    errs_t = [abs(fw.cumtrapz(np.linspace(0, 1.3, N + 1), f(np.linspace(0, 1.3, N + 1)))[-1] - exact)
              for N in Ns]
    assert fit_order(Ns, errs_t) == pytest.approx(2.0, abs=0.3)


def test_hermite_extremum_of_a_sine():
    """The located maximum of sin on a coarse grid: within O(h^4) of 1."""
    for N, tol in ((12, 1e-4), (48, 1e-6)):
        q = np.linspace(0.1, 2 * np.pi + 0.1, N + 1)
        x = fw.hermite_critical(q, np.sin(q), np.cos(q))
        v = fw.hermite_at(q, np.sin(q), np.cos(q), x)
        assert max(v) == pytest.approx(1.0, abs=tol) and min(v) == pytest.approx(-1.0, abs=tol)
        assert max(np.sin(q)) < max(v) or N > 100


def test_study_json_shape_and_orders(tmp_path):
    import tmm_cli
    from tmm_cli import study
    from tmm_cli.report.sections import study as study_page
    task = tmm_cli.load_task("tasks/engine_slider_crank.yaml")
    st, trap = study.run_study(task, repeat=1)
    assert set(st) == {"curves", "flywheel", "kinetostatics"}
    for stage, d in st.items():
        assert {"setting", "reference", "rows", "order", "theory"} <= set(d)
        assert "setting" in d["reference"]
        chk = d["reference"]["check"]            # the reference is itself checked
        assert chk["difference"] is not None and chk["setting"] is not None
        for r in d["rows"]:
            assert {"setting", "error", "time_ms"} <= set(r) and r["time_ms"] >= 0
    fly = st["flywheel"]
    assert fly["setting"] == "resolution" and fly["theory"] == 4
    assert set(fly["rows"][0]) - {"setting", "error", "time_ms"} == \
        set(fly["reference"]) - {"setting", "check", "converged"}
    # Gauss-Legendre 2 points: order 4 (the coarse rows are pre-asymptotic); trapezoid 2
    assert 2.5 <= fly["order"] <= 5.0
    assert trap["flywheel"]["order"] < fly["order"]
    # the task's setting (720 over this engine's 720-deg cycle) within 1e-6 of the reference
    assert next(r for r in fly["rows"] if r["setting"] == 720)["error"] <= 1e-6
    # linear interpolation of the diagrams: order 2 (the theoretical one)
    for stage in ("curves", "kinetostatics"):
        assert st[stage]["theory"] == 2
        assert st[stage]["order"] == pytest.approx(2.0, abs=0.25), stage
    paths = study_page.write(st, tmp_path, trap)
    assert json.loads((tmp_path / "study.json").read_text()) == json.loads(json.dumps(st))
    html = (tmp_path / "study.html").read_text()
    assert "<svg" in html and "<table>" in html and len(paths) == 2


def test_results_deterministic_without_timings(tmp_path):
    outs = []
    for k in (1, 2):
        o = tmp_path / f"r{k}"
        subprocess.run([sys.executable, "-m", "tmm_cli", "run", "tasks/engine_slider_crank.yaml",
                        "-f", "json", "-o", str(o), "-q"], check=True)
        outs.append((o / "results.json").read_bytes())
    assert outs[0] == outs[1]
    text = outs[0].decode()
    assert "time_ms" not in text
    d = json.loads(text)
    assert d["flywheel"]["accuracy"] is None and d["flywheel"]["hand"]["positions"] == 24


def test_graphical_error_and_tolerance():
    import tmm_cli
    from tmm_cli.graphical import graphical_tolerance
    from tmm_cli.pipeline import run
    d = run(tmm_cli.load_task("tasks/forging_sixbar.yaml"), kinematics_curve=0)
    g = d["graphical_error"]
    assert g["reading_mm"] == 0.5
    # the report's scale: the crank pin A's velocity (constant) drawn <= 100 mm with a
    # nice number from 1, 1.2, 1.5, 2, 2.5, 3, 4, 5, 6, 8 x 10^k
    vA = d["kinematics"][0]["points"]["A"]["v"]
    mu = g["plans"]["mu_v"]
    assert vA / mu <= 100 + 1e-9 and vA / mu > 100 / 1.34
    e = d["kinematics"][3]
    tol = graphical_tolerance(d)
    B = e["points"]["B"]
    # the tolerance: a careful hand solution's plan error, 2.5 % of the crank pin's vector, over the segment
    aA = max(k["points"]["A"]["a"] for k in d["kinematics"])
    assert tol["kinematics[3].points.B.v"] == pytest.approx(0.025 * vA / B["v"], rel=1e-12)
    assert tol["kinematics[3].points.B.a"] == pytest.approx(0.025 * aA / B["a"], rel=1e-12)
    # a link's omega read off its relative velocity segment |omega| l
    A, Bp = e["points"]["A"], e["points"]["B"]
    l_ab = math.hypot(Bp["x"] - A["x"], Bp["y"] - A["y"])
    w = abs(e["links"]["rod"]["omega"])
    assert tol["kinematics[3].links.rod.omega"] == pytest.approx(0.025 * vA / (w * l_ab), rel=1e-12)
    # the 12-position flywheel: the band from its J to the accurate one, 2.5 % of the larger beyond
    h, J = d["flywheel"]["hand"]["J"], d["flywheel"]["J"]
    m = 0.025 * max(h, J)
    assert tol["flywheel.J"] == pytest.approx((min(h, J) - m, max(h, J) + m), rel=1e-12)
    assert 0.01 < abs(h / J - 1) < 0.2 and g["flywheel"]["J"] == pytest.approx(abs(h / J - 1), rel=1e-9)


def test_cli_study_and_run_study(tmp_path):
    o = tmp_path / "p"
    subprocess.run([sys.executable, "-m", "tmm_cli", "study", "tasks/planetary_A.yaml", "-o", str(o),
                    "--repeat", "1"], check=True, capture_output=True)
    st = json.loads((o / "study.json").read_text())
    assert set(st) == {"planetary"} and st["planetary"]["setting"] == "z_max"
    assert st["planetary"]["order"] is None        # a search, not a discretisation
    assert st["planetary"]["reference"]["setting"] == 150
    o = tmp_path / "d"
    subprocess.run([sys.executable, "-m", "tmm_cli", "run", "tasks/impact_rotor.yaml", "-f", "json,html",
                    "-o", str(o), "-q", "--study"], check=True)
    # the report carries the study section (tables and SVG plots); results.json does not
    html = (o / "report.html").read_text()
    assert "Accuracy against computing time" in html and "rtol" in html
    st = json.loads((o / "study.json").read_text())
    d = st["dof2"]
    assert d["setting"] == "rtol" and d["reference"]["setting"] == 1e-12
    # an adaptive integrator's error is proportional to its tolerance: order about 1
    assert 0.7 <= d["order"] <= 1.5
    assert "time_ms" not in (o / "results.json").read_text()
