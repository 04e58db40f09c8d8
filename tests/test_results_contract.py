"""results.json carries every key of SPEC section 3 (the contract external tests read)."""
from __future__ import annotations

from pathlib import Path

import tmm_cli

ROOT = Path(__file__).resolve().parents[1]

SPEC_KEYS = {
    "structure": ["n", "p5", "p4", "W", "class", "groups", "formula"],
    "positions": ["phi0", "extreme", "working_stroke_angle"],
    "flywheel": ["J", "J_energy_mass", "J_merzalov", "J_exact", "J_n", "J_const", "delta_achieved",
                 "omega_max", "omega_min", "M_constant", "diameter", "width", "mass"],
    "cam": ["r0", "offset", "center_distance", "roller", "max_pressure_angle", "rho_min"],
    "gears": ["aw", "alpha_w", "y", "dy", "r", "rb", "rw", "ra", "rf", "s", "sa", "eps_alpha", "x_min",
              "checks"],
    "planetary": ["z", "ratio", "ratio_error"],
}
KS_KEYS = ["index", "phi", "balancing_moment", "balancing_force", "zhukovsky_moment", "virtual_power_moment",
           "discrepancy", "reactions", "inertia", "efficiency"]


def _full_task():
    from tmm_cli.yamlload import load_yaml      # YAML 1.2: the key `on:` stays a string
    d, _ = load_yaml(ROOT / "tmm_cli" / "starters" / "full.yaml")
    d["planetary"] = {"scheme": "A", "ratio": 5.0, "satellites": 3, "tolerance": 0.05}
    d["kinetostatics"]["friction"] = {"pin_radius": 0.01, "f": 0.1}
    return tmm_cli.load_task(d)


def test_every_spec_key_present():
    task = _full_task()
    res = tmm_cli.run(task)
    assert res["schema"] == "tmm-results/1"
    assert isinstance(res["warnings"], list)
    assert isinstance(res["singular"], list)
    for sec, keys in SPEC_KEYS.items():
        for k in keys:
            assert k in res[sec], f"{sec}.{k}"
    g = res["structure"]["groups"][0]
    for k in ("links", "class", "order", "type"):
        assert k in g
    assert set(res["gears"]["checks"]) >= {"undercut", "sharpening", "contact_ratio_low", "interference"}
    assert len(res["gears"]["checks"]["undercut"]) == 2
    # kinematics: every point (ground pivots included) and every link, in every entry
    names = {"O", "A", "B"}
    for e in res["kinematics"]:
        assert names <= set(e["points"])
        for p in e["points"].values():
            assert set(p) >= {"x", "y", "vx", "vy", "v", "ax", "ay", "a"}
        assert set(e["links"]) == {"crank", "rod", "slider"}
        for lk in e["links"].values():
            assert set(lk) >= {"angle", "omega", "epsilon"}
        assert e["links"]["slider"]["omega"] == 0.0          # fixed guide
    idx = [e["index"] for e in res["kinematics"]]
    assert idx[:12] == list(range(12))
    for e in res["kinetostatics"]:
        for k in KS_KEYS:
            assert k in e, k
        # each pair once as R<i><j> with i < j; ground = 0
        for key, r in e["reactions"].items():
            assert key[0] == "R" and int(key[1]) < int(key[2])
            assert set(r) >= {"x", "y", "R"}
        assert set(e["reactions"]) == {"R01", "R12", "R23", "R03"}
        assert set(e["inertia"]) >= {"rod", "slider"}
        assert 0 < e["efficiency"] <= 1
    assert res["planetary"]["ratio_error"] == (res["planetary"]["ratio"] - 5.0) / 5.0


def test_each_positions_crank_angle_is_the_same_number_everywhere(shared_once):
    """The kinematics and kinetostatics entries carry each position's crank angle as
    ``positions.phi`` has it, to the bit: the kinematics entries took it through radians and
    back (a course grid from 0: 29.999999999999996, 119.99999999999999 in results.json and
    kinematics.csv beside positions.phi's 30.0, 120.0)."""
    import pdf_extent
    tasks = sorted(p.stem for p in (ROOT / "tasks").glob("*.yaml"))
    seen = 0
    for name in tasks:
        _, res = pdf_extent.results(shared_once, name)
        if not res.get("kinematics"):
            continue
        phi = res["positions"]["phi"]
        for section in ("kinematics", "kinetostatics"):
            got = [e["phi"] for e in res.get(section) or []]
            assert got == [phi[e["index"]] for e in res.get(section) or []], (name, section, got[:4], phi[:4])
        seen += 1
    assert seen >= 15
    _, res = pdf_extent.results(shared_once, "static_gravity")          # a grid from 0 deg
    assert [e["phi"] for e in res["kinematics"]][:5] == [0.0, 30.0, 60.0, 90.0, 120.0]


def test_the_cam_constructions_crank_angles_are_the_phases_degrees(shared_once):
    """The s - ds/dphi construction's points are labelled with the cam angles the phases give in
    degrees -- 0, 1, ..., the rise; the return's start, ... -- exactly, as the task's numbers add
    up, not as degrees of radians (149.99999999999997 for 150)."""
    import pdf_extent
    from tmm_cli.yamlload import load_yaml
    seen = 0
    for path in sorted((ROOT / "tasks").glob("cam_*.yaml")):
        _, res = pdf_extent.results(shared_once, path.stem)
        con = res["cam"]["construction"]
        if con is None:
            continue
        ph = load_yaml(path)[0]["cam"]["phases"]
        rise, far, ret = (float(ph[k]) for k in ("rise", "far_dwell", "return"))     # plain numbers there
        n_r, n_t = len(con["phi_rise"]) - 1, len(con["phi_return"]) - 1
        assert con["phi_rise"] == [rise * k / n_r for k in range(n_r + 1)], path.stem
        assert con["phi_return"] == [rise + far + ret * k / n_t for k in range(n_t + 1)], path.stem
        assert con["phi_rise"][-1] == rise and con["phi_return"][-1] == rise + far + ret
        seen += 1
    assert seen >= 4
