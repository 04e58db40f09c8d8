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


# a study as run_study gives it (numbers of the student's trial: 0.0266, 2.99e-05, a stroke of 39.99999342)
_WRITTEN = {
    "curves": {"setting": "points", "default": 361, "order": 2.02, "theory": 2, "output": "rocker",
               "reference": {"stroke": 39.99999342, "v_max": 5.914371513, "a_max": 99.5986613, "setting": 3600,
                             "check": {"setting": 7200, "points": 361, "difference": 0.00752}},
               "rows": [{"setting": 13, "err_s": 0.0266, "err_v": 0.0411, "err_a": 0.0498, "error": 0.0498,
                         "time_ms": 1.43},
                        {"setting": 1441, "err_s": 2.99e-05, "err_v": 2.98e-06, "err_a": 3.62e-06,
                         "error": 2.99e-05, "time_ms": 2.07}]},
    "kinetostatics": {"setting": "positions", "default": 12, "order": 1.84, "theory": 2, "balancing": "moment",
                      "reference": {"M_b_max": 273.290474, "R_max": 17645.84958, "setting": 3600,
                                    "check": {"setting": 7200, "positions": 12, "difference": 0.000642}},
                      "rows": [{"setting": 12, "err_M_b": 0.0985, "err_R": 0.0293, "error": 0.0985, "time_ms": 8.39},
                               {"setting": 720, "err_M_b": 0.000685, "err_R": 5.01e-05, "error": 0.000685,
                                "time_ms": 16.0}]},
    "flywheel": {"setting": "resolution", "default": 720, "order": 3.79, "theory": 4,
                 "reference": {"J_n": 0.4190182407, "J_n_merzalov": 0.4206370129, "J_n_exact": 0.4190182407,
                               "setting": 2880, "check": {"setting": 5760, "difference": 3.83e-13}},
                 "rows": [{"setting": 12, "J_n": 0.4190249132, "J_n_merzalov": 0.4206436851,
                           "J_n_exact": 0.4190249132, "error": 1.59e-05, "time_ms": 18.0},
                          {"setting": 720, "J_n": 0.4190182406, "J_n_merzalov": 0.4206370128,
                           "J_n_exact": 0.4190182406, "error": 1.03e-10, "time_ms": 12.9}]},
}


def _visible(html: str) -> str:
    """The page's text as a reader sees it: the tags dropped, the plots' labels kept, a subscript
    written _{...} (r<sub>0</sub> is not the key r0)."""
    import re
    html = re.sub(r'<sub>|<tspan baseline-shift="sub"[^>]*>', "_{", html)
    html = re.sub(r"</sub>|</tspan>", "}", html)
    labels = " ".join(re.findall(r"<text[^>]*>(.*?)</text>", html, flags=re.S))
    html = re.sub(r"<svg.*?</svg>", " ", html, flags=re.S)
    return re.sub(r"<[^>]+>", "", html + " " + labels)


@pytest.mark.parametrize("lang", ["ru", "uk"])
def test_study_page_numbers_names_and_units_in_the_language(lang):
    """study.html in ru and uk wrote 0.0266 and 2.99e-05 in its tables, the keys of study.json as
    names (err_s, err_M_b, ratio, ratio_error, M_b_max) and values without units (stroke =
    39.99999342): every number is now written as the report writes it (the decimal comma,
    2,99·10⁻⁵), every name comes from the catalogue with its unit."""
    import re
    from tmm_cli.messages import unit
    st = {**_WRITTEN, "cam": study.study_cam(tmm_cli.load_task("tasks/cam_knife.yaml"), repeat=1),
          "planetary": study.study_planetary(tmm_cli.load_task("tasks/planetary_A.yaml"))}
    text = _visible(study_page.html_section(st, lang=lang))
    assert not re.findall(r"\d\.\d|\de[-+]?\d", text), re.findall(r".{20}(?:\d\.\d|\de[-+]?\d).{10}", text)
    for d in st.values():                   # no key of study.json as a name
        keys = {k for r in d["rows"] for k in r} | set(d["reference"])
        for k in keys - {"setting", "check", "time_ms", "error", "converged"}:
            assert not re.search(rf"(?<![\w.]){re.escape(k)}(?!\w)", text), (lang, k)
    assert "2,99·10⁻⁵" in text and "0,0266" in text
    sec = study_page.I18N[lang]
    # a rocker's stroke is an angle; M_b a moment; J_n in kg·m²; the ratio's deviation in percent
    assert f"{sec['study.col.stroke']} = 39,99999342°" in text
    assert f"{sec['study.col.v_max_rocker']} = 5,914371513 {unit('rad/s', lang)}" in text
    assert f"{sec['study.col.a_max_rocker']} = 99,5986613 {unit('rad/s^2', lang)}" in text
    assert f"{sec['study.col.R_max']} = 17645,84958 {unit('N', lang)}" in text
    assert f"{unit('N*m', lang)}" in text and "кг·м²" in text
    html = study_page.html_section(st, lang=lang)
    assert f"<th>{sec['study.col.ratio_error']}, %</th>" in html and "<td>2,78</td>" in html
    assert f"<th>{sec['study.col.deviation']}, {unit('m', lang)}</th>" in html
    assert "1·10⁻" in html                 # the plots' powers of ten
    # a slider's stroke in metres, a balancing force in newtons
    other = {"curves": {**_WRITTEN["curves"], "output": "slider"},
             "kinetostatics": {**_WRITTEN["kinetostatics"], "balancing": "force"}}
    text = _visible(study_page.html_section(other, lang=lang))
    assert f"{sec['study.col.stroke']} = 39,99999342 {unit('m', lang)}" in text
    assert f"= 273,290474 {unit('N', lang)}," in text


def test_study_records_the_units_kind():
    """The units of the curves and of M_b follow the output (a slider, a rocker) and the balance link."""
    for name, output in (("engine_slider_crank", "slider"), ("crank_rocker_fourbar", "rocker")):
        task = tmm_cli.load_task(f"tasks/{name}.yaml")
        linkage = build(task)
        assert study.study_curves(linkage, repeat=1)["output"] == output
    task = tmm_cli.load_task("tasks/engine_slider_crank.yaml")
    assert study.study_kinetostatics(task, build(task), repeat=1)["balancing"] == "moment"


def test_a_rocker_outputs_curves_are_named_omega_and_epsilon(tmp_path):
    """A rocker output's curves are angular (rad/s, rad/s^2): study.html named them v and a with
    those units; now omega and epsilon (a slider's stay v and a), in the values and in the
    method's line (its error relative to the swing and the largest |omega| and |epsilon|)."""
    import html as _html
    import re as _re
    from pathlib import Path

    from typer.testing import CliRunner

    from tmm_cli.cli import app
    root = Path(__file__).resolve().parents[1] / "tasks"
    for name, want, not_want in (("crank_rocker_fourbar", "largest |\u03c9| =", "largest |v| ="),
                                 ("engine_slider_crank", "largest |v| =", "largest |\u03c9| =")):
        res = CliRunner().invoke(app, ["study", str(root / f"{name}.yaml"), "-o", str(tmp_path / name)])
        assert res.exit_code == 0, res.output
        text = _html.unescape(_re.sub(r"<[^>]+>", "", (tmp_path / name / "study.html").read_text(encoding="utf-8")))
        assert want in text and not_want not in text, name
        line = ("to the swing and to the largest |\u03c9| and |\u03b5|" if name == "crank_rocker_fourbar" else
                "to the stroke and to the largest |v| and |a|")
        assert line in text, name
