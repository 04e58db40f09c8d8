"""Report section 'dynamics': renders in en and ru from results only, writes flywheel.csv,
and the flywheel read off the Wittenbauer drawing (segment kl between the tangents on the
dT axis, J = kl mu_T/(omega_m^2 delta)) equals the solver's Wittenbauer-tangent value
(a second route: intercepts of lines vs. max/min over the nodes)."""
from __future__ import annotations

import csv
import re

import numpy as np
import pytest

from tmm_cli.linkage.dynamics import EPS_DEG, Sample, analyze_sampler
from tmm_cli.linkage.spec import FlywheelSection


def _results():
    def sampler(q, side):
        x = np.deg2rad(q + side * EPS_DEG)
        M = -200 * (1 + np.sin(x)) - np.where(np.mod(q + side * EPS_DEG, 360) < 90, 300.0, 0.0)
        Jv = 0.3 + 0.2 * np.cos(2 * x)
        return Sample(M_by_kind={"resistance": M}, M_given=M,
                      J_links={"crank": np.full(q.shape, 0.05), "rod": Jv},
                      dJ_links={"crank": np.zeros(q.shape), "rod": -0.4 * np.sin(2 * x)})
    sec = FlywheelSection(delta=1 / 15, constant="driving", method="merzalov", resolution=360,
                          shape={"type": "rim", "density": 7200.0, "width_ratio": 0.15}, reduced_J=0.1)
    r = analyze_sampler(sampler, sec, 8.0, switch_q=(0.0, 90.0))
    return r, {"schema": "tmm-results/1", "flywheel": r.to_dict(), "warnings": []}


@pytest.mark.parametrize("lang", ["en", "ru"])
def test_dynamics_section_renders(tmp_path, lang):
    from tmm_cli.report import make_env
    from tmm_cli.report.context import ReportContext
    from tmm_cli.report.sections import load
    r, res = _results()
    mod = load("dynamics")
    ctx = ReportContext(results=res, task=None, lang=lang, out_dir=tmp_path, env=make_env())
    html = mod.build(ctx)
    assert html and html.count("<svg") == 3
    assert ("Wittenbauer" in html) if lang == "en" else ("Виттенбауэра" in html)
    rows = list(csv.reader(open(tmp_path / "flywheel.csv")))
    assert rows[0][:2] == ["phi_cycle", "phi"] and len(rows) == 1 + r.q_deg.size
    # kl from the caption (μ_T with a real subscript) -> J; compare with the solver's Wittenbauer flywheel
    # (the decimal comma in Russian)
    m = re.search(r"kl = ([0-9.,]+) ", html)
    muT = float(re.search(r"μ<sub>T</sub> = ([0-9.,e+-]+) ", html).group(1).replace(",", "."))
    J_drawn = float(m.group(1).replace(",", ".")) * muT / (8.0**2 / 15)
    assert J_drawn == pytest.approx(r.cycle.J_fly["wittenbauer"], rel=2e-3)   # kl printed to 0.1 mm
    assert mod.build(ReportContext(results={}, task=None, lang=lang, out_dir=tmp_path, env=make_env())) is None
