"""The accuracy study of the cam profile, the blocking contour and the kinetostatic and
kinematic diagrams (tmm_cli.study, tmm_cli.cam.polygon, tmm_cli.gears.shifts).

Independent values:
* the circle through three points of a circle is that circle: a cam whose rho_min lies on
  its base circle (a dwell) gives rho_min = r0 at any step;
* the polygon's deviation against a brute-force distance from dense points of the exact
  profile to the nearest segment of the polygon;
* a linear margin (the undercut lines x_i - x_min_i) is traced exactly by marching squares;
* the central slider-crank's rod stops turning (omega_2 = 0) at crank angles 90 and 270 deg
  (omega_2 = omega_1 r cos(phi) / (l cos(beta))): there the friction at the rod-slider pin
  reverses;
* the kinetostatics at the task's positions by the pipeline (a second path);
* the theoretical orders of the rules: a chord's sagitta (2), linear interpolation (2).
"""
from __future__ import annotations

import glob

import numpy as np
import pytest

import tmm_cli
from tmm_cli import study
from tmm_cli.report.sections import study as study_page
from tmm_cli.cam import polygon
from tmm_cli.linkage.context import build


def _cam(name):
    from tmm_cli import cam
    return cam.synthesize(tmm_cli.load_task(f"tasks/{name}.yaml").cam)


@pytest.mark.parametrize("step", [10.0, 1.0, 0.25])
def test_rho_min_on_the_base_circle_is_exact(step):
    r = _cam("cam_translating")
    assert r.rho_min == pytest.approx(r.r0, rel=1e-12)     # on the near dwell: the base circle
    assert polygon.polygon_rho_min(r, step) == pytest.approx(r.r0, rel=1e-9)


@pytest.mark.parametrize("name", ["cam_knife", "cam_rocker", "cam_flat"])
def test_polygon_deviation_against_brute_force(name):
    r = _cam(name)
    step = 5.0
    phi, _ = polygon.vertices(r, step)
    P = polygon.polygon(r, step)
    dense = np.linspace(0.0, 360.0, 20001)
    Q = polygon._exact(r, "working")(np.radians(dense))
    a, b = P[:-1], P[1:]
    d = b - a
    t = np.clip(np.einsum("qsk,sk->qs", Q[:, None, :] - a[None], d) / np.einsum("sk,sk->s", d, d), 0, 1)
    near = a[None] + t[..., None] * d[None]
    brute = np.min(np.hypot(*(Q[:, None, :] - near).transpose(2, 0, 1)), axis=1).max()
    assert polygon.polygon_deviation(r, step) == pytest.approx(brute, rel=2e-3)
    # the phase boundaries are vertices (a corner of the profile is never cut)
    for s in np.degrees(r.motion.starts):
        assert np.min(np.abs(phi - s)) < 1e-9


@pytest.mark.parametrize("path", sorted(glob.glob("tasks/cam_*.yaml")))
def test_cam_study_order_is_two(path):
    st = study.study_cam(tmm_cli.load_task(path), repeat=1)
    assert st["theory"] == 2 and st["setting"] == "step"
    assert st["orders"]["deviation"] == pytest.approx(2.0, abs=0.1)
    assert st["order"] == pytest.approx(2.0, abs=0.3)
    assert st["reference"]["check"]["difference"] < 1e-6          # the polygon at 0.01 deg
    # the profile tmm writes (1 deg) deviates by less than 1e-3 of r0
    row = next(x for x in st["rows"] if x["setting"] == 1.0)
    assert row["deviation"] < 1e-3 * st["reference"]["r0"]


def test_cam_rho_min_order_inside_a_phase():
    r = _cam("cam_knife")                    # rho_min inside the rise
    steps = [2.0, 1.0, 0.5, 0.25, 0.1]
    errs = [abs(polygon.polygon_rho_min(r, h) / r.rho_min - 1) for h in steps]
    assert study.fit_order(steps, errs, inverse=True) == pytest.approx(2.0, abs=0.35)


def test_blocking_contour_deviation():
    from tmm_cli import gears
    from tmm_cli.gears import shifts
    g = gears.analyze(tmm_cli.load_task("tasks/gears_zero.yaml").gears)
    args = (g.m, g.z[0], g.z[1], g.alpha, g.ha, g.c, g.sa_min, g.rho_f)
    rng = (tuple(g.contour["x1_range"]), tuple(g.contour["x2_range"]))
    for n in (21, 81):
        d = shifts.contour_deviation(shifts.blocking_contour(*args, *rng, n=n), *args)
        assert d["undercut_1"] < 1e-12 and d["undercut_2"] < 1e-12      # linear margins: exact
        assert 0 < d["contact_ratio"] < 0.5 * (rng[0][1] - rng[0][0]) / (n - 1)
    st = study.study_gears(tmm_cli.load_task("tasks/gears_zero.yaml"), repeat=1)
    assert st["theory"] == 2 and st["order"] == pytest.approx(2.0, abs=0.25)
    assert st["reference"]["check"]["difference"] < 1e-12


def test_kinetostatic_diagrams_match_the_pipeline_and_friction_reversals():
    from tmm_cli.pipeline import run
    task = tmm_cli.load_task("tasks/engine_slider_crank.yaml")
    d = study.KinetostaticDiagrams(build(task), task.kinetostatics)
    # the guide is vertical: the rod stops turning (its pin friction reverses) with the crank
    # horizontal, 0 and 180 deg; the piston stops (its guide friction reverses) at the dead
    # centres, 90 and 270 deg
    phi_rev = np.mod(d.phi0 + d.sign * np.asarray(d.reversals()), 360.0)
    for target in (0.0, 90.0, 180.0, 270.0):
        assert np.min(np.abs(np.mod(phi_rev - target + 180.0, 360.0) - 180.0)) < 1e-6
    # at the task's positions: the pipeline's M_b (a second path through the stages)
    res = run(task, kinematics_curve=0)
    q = np.mod(d.sign * (np.asarray([e["phi"] for e in res["kinetostatics"]]) - d.phi0), 360.0)
    mb = d.at(q, np.zeros(q.size))[:, 0]
    ref = [e["balancing_moment"] for e in res["kinetostatics"]]
    # not at a reversal itself, where the friction's direction is undefined (0 or 180 deg)
    keep = np.abs(np.mod(np.asarray([e["phi"] for e in res["kinetostatics"]]) + 90.0, 180.0) - 90.0) > 1e-6
    mb, ref = mb[keep], np.asarray(ref)[keep]
    assert keep.sum() >= 10
    assert mb == pytest.approx(np.asarray(ref, float), rel=1e-9, abs=1e-9 * max(map(abs, ref)))


@pytest.mark.parametrize("name", ["forging_sixbar", "scotch_yoke_pump"])
def test_kinetostatics_and_curves_orders(name):
    task = tmm_cli.load_task(f"tasks/{name}.yaml")
    linkage = build(task)
    k = study.study_kinetostatics(task, linkage, repeat=1)
    c = study.study_curves(linkage, repeat=1)
    assert k["order"] == pytest.approx(2.0, abs=0.25) and c["order"] == pytest.approx(2.0, abs=0.25)
    # the errors are measured on a fine enough set of angles (the check)
    assert k["reference"]["check"]["difference"] < 0.02 and c["reference"]["check"]["difference"] < 0.02


def test_study_section_in_every_language():
    from tmm_cli.report import i18n
    from tmm_cli.report.sections import study as sec
    st = {"cam": study.study_cam(tmm_cli.load_task("tasks/cam_knife.yaml"), repeat=1)}
    en = study_page.html_section(st, lang="en")
    for lang in ("ru", "uk"):
        html = study_page.html_section(st, lang=lang)
        assert sec.I18N[lang]["study.title"] in html
        for key, text in sec.I18N["en"].items():     # no English sentence left
            if len(text) > 12 and key.split(".")[1] not in ("series", "col"):
                assert text.split("{")[0][:30] not in html, (lang, key)
        assert html.count("<tr>") == en.count("<tr>")
    assert i18n.translate("study.title", "ru") == sec.I18N["ru"]["study.title"]


def test_cli_study_lang(tmp_path):
    import json
    import subprocess
    import sys
    from tmm_cli.report.sections import study as sec
    subprocess.run([sys.executable, "-m", "tmm_cli", "study", "tasks/cam_knife.yaml", "-o", str(tmp_path),
                    "--repeat", "1", "--lang", "uk"], check=True, capture_output=True)
    html = (tmp_path / "study.html").read_text()
    assert sec.I18N["uk"]["study.stage.cam"] in html and "lang='uk'" in html
    st = json.loads((tmp_path / "study.json").read_text())
    assert st["cam"]["setting"] == "step" and st["cam"]["theory"] == 2
    bad = subprocess.run([sys.executable, "-m", "tmm_cli", "study", "tasks/cam_knife.yaml", "-o", str(tmp_path),
                          "--lang", "de"], capture_output=True, text=True)
    assert bad.returncode == 2 and "Traceback" not in bad.stderr
