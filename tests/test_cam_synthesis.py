"""Smallest cam from the allowed pressure angles: closed forms and brute force.

The brute-force checks use their own kinematics (their own frame, the cam profile in the
cam's frame by rotation, its tangent by finite differences) and the textbook definition of
the pressure angle: the angle between the normal to the pitch profile and the velocity of
the roller centre.  A cam centre is admissible when that angle never exceeds the allowed
value and the roller centre moves away from the cam centre on the rise.
"""
import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from tmm_cli.cam import synthesize
from tmm_cli.cam.laws import LAWS
from tmm_cli.errors import StageError
from cam_spec import fields, spec  # noqa: E402  (shared cam section builder)




# ------------------------------------------------------------------ closed forms
@pytest.mark.parametrize("h,Phi,theta", [(0.03, 90, 30), (0.05, 120, 25), (0.012, 60, 35), (0.1, 150, 20)])
def test_central_cosine_closed_form(h, Phi, theta):
    """Central translating follower, cosine law: r0 + s >= s'/tan(theta) for all phi.

    With s = h(1 - cos(pi x))/2 and s' = h*pi/(2*Phi) sin(pi x) the condition is
    r0 >= A sin(pi x) + (h/2) cos(pi x) - h/2 with A = h*pi/(2*Phi*tan(theta)), whose
    maximum is sqrt(A^2 + h^2/4) - h/2 (amplitude of a sum of sine and cosine).
    """
    P = math.radians(Phi)
    t = math.tan(math.radians(theta))
    A = h * math.pi / (2 * P * t)
    r0_exact = math.sqrt(A * A + h * h / 4) - h / 2
    r = synthesize(spec(stroke=h, phases=fields(rise=Phi, far_dwell=10, return_=Phi, near_dwell=350 - 2 * Phi),
                        pressure_angle=fields(rise=theta, return_=theta)))
    assert r.r0 == pytest.approx(r0_exact, rel=1e-10)
    assert r.offset == 0.0 and r.center_distance is None
    # equality at the optimum: tan(theta) = max (ds/dphi)/(r0 + s)
    x = np.linspace(0, 1, 200001)
    s = h * (1 - np.cos(np.pi * x)) / 2
    ds = h * np.pi / (2 * P) * np.sin(np.pi * x)
    assert math.degrees(math.atan(np.max(ds / (r.r0 + s)))) == pytest.approx(theta, abs=1e-7)
    assert r.max_pressure_angle == pytest.approx(theta, abs=1e-9)


@settings(max_examples=25, deadline=None)
@given(rise_law=st.sampled_from(sorted(LAWS)), ret_law=st.sampled_from(sorted(LAWS)),
       rise=st.floats(40, 150), ret=st.floats(40, 150), th_r=st.floats(15, 40), th_d=st.floats(15, 60))
def test_central_any_law_against_direct_maximum(rise_law, ret_law, rise, ret, th_r, th_d):
    """Central follower: r0 = max over each phase of |ds/dphi|/tan(theta_allowed) - s
    (the pressure-angle formula tan(theta) = |s'|/(r0 + s)), on a grid of 2e5 points."""
    h = 0.04
    r = synthesize(spec(stroke=h, laws=fields(rise=rise_law, return_=ret_law),
                        phases=fields(rise=rise, far_dwell=20, return_=ret, near_dwell=340 - rise - ret),
                        pressure_angle=fields(rise=th_r, return_=th_d)))
    best = 0.0
    for law, P, th, up in ((LAWS[rise_law], rise, th_r, True), (LAWS[ret_law], ret, th_d, False)):
        x = np.linspace(0, 1, 200001)
        f, f1, _, _ = law(x)
        s = h * f if up else h * (1 - f)
        ds = h * f1 / math.radians(P)
        best = max(best, float(np.max(ds / math.tan(math.radians(th)) - s)))
    assert r.r0 == pytest.approx(best, rel=1e-8)


def test_given_offset_against_formula():
    """Translating follower with offset e: r0^2 = e^2 + s0^2 where s0 is the smallest value
    with |s' -+ e| <= (s0 + s) tan(theta) (textbook formula tan(theta) = (s' - e)/(s0 + s)
    for the side that lowers the rise angle)."""
    h, e = 0.03, 0.006
    r = synthesize(spec(stroke=h, offset=e, laws=fields(rise="sine", return_="poly345"),
                        pressure_angle=fields(rise=30, return_=40)))
    need = []
    for law, P, th, up in ((LAWS["sine"], 90, 30, True), (LAWS["poly345"], 90, 40, False)):
        x = np.linspace(0, 1, 400001)
        f, f1, _, _ = law(x)
        s = h * f if up else h * (1 - f)
        ds = h * f1 / math.radians(P) * (1 if up else -1)
        t = math.tan(math.radians(th))
        need.append(np.max(np.abs(ds - e) / t - s))
    s0 = max(need)
    assert r.offset == e
    assert r.r0 == pytest.approx(math.hypot(e, s0), rel=1e-8)


# ------------------------------------------------------------------ brute force
def _law_motion(law_name, h, P_deg, up):
    law = LAWS[law_name]
    P = math.radians(P_deg)

    def ev(x):
        f, f1, _, _ = law(x)
        return (h * f, h * f1 / P) if up else (h * (1 - f), -h * f1 / P)
    return ev


def _admissible(kind, O, sigma, sp, tau=1, l=None, n=300):
    """Independent check: max pressure angle per phase for cam centres O (k, 2).

    Frame of this check (different from the program's): B0 = (0, 0);
    translating: the follower moves along +x (!); rocker: pivot A = (0, -l), so B0 is
    straight above A and turns about A by tau*s.  Returns a boolean array (k,).
    """
    O = np.asarray(O, dtype=float)
    ok = np.ones(len(O), dtype=bool)
    ph = sp.phases
    segs = [("rise", sp.laws.rise, ph.rise, 0.0, True, sp.pressure_angle.rise),
            ("return", sp.laws.return_, ph.return_, ph.rise + ph.far_dwell, False, sp.pressure_angle.return_)]
    hh = sp.stroke if kind == "translating" else math.radians(sp.stroke)
    for _, law, P, start, up, th in segs:
        ev = _law_motion(law, hh, P, up)
        x = np.linspace(1e-6, 1 - 1e-6, n)
        eps = 1e-7
        phis = []
        for dx in (-eps, 0.0, eps):
            xx = x + dx / math.radians(P)
            s, _ = ev(xx)
            phi = math.radians(start) + xx * math.radians(P)
            if kind == "translating":
                B = np.stack([s, np.zeros_like(s)], axis=-1)
                vdir = np.tile([1.0, 0.0], (len(s), 1))
            else:
                A = np.array([0.0, -l])
                psi = math.pi / 2 + tau * s
                B = A + l * np.stack([np.cos(psi), np.sin(psi)], axis=-1)
                vdir = np.stack([-np.sin(psi), np.cos(psi)], axis=-1)
            phis.append((phi, B, vdir))
        (_, Bm, _), (phi0, B0, v0), (_, Bp, _) = phis
        moving = np.abs(ev(x)[1]) > 1e-6 * hh
        # cam frame: rotate by -sigma*phi about O; points (k, n, 2)
        def camframe(B, phi):
            q = B[None, :, :] - O[:, None, :]
            c, s_ = np.cos(-sigma * phi), np.sin(-sigma * phi)
            return np.stack([c * q[..., 0] - s_ * q[..., 1], s_ * q[..., 0] + c * q[..., 1]], axis=-1)
        phim = phis[0][0]
        phip = phis[2][0]
        Qm, Qp = camframe(Bm, phim), camframe(Bp, phip)
        T = Qp - Qm
        with np.errstate(invalid="ignore", divide="ignore"):
            T /= np.linalg.norm(T, axis=-1, keepdims=True)
        c, s_ = np.cos(-sigma * phi0), np.sin(-sigma * phi0)
        V = np.stack([c * v0[:, 0] - s_ * v0[:, 1], s_ * v0[:, 0] + c * v0[:, 1]], axis=-1)[None]
        crossTV = np.abs(T[..., 0] * V[..., 1] - T[..., 1] * V[..., 0])
        theta = np.degrees(np.arccos(np.clip(crossTV, 0, 1)))
        # the roller centre moves away from O while the follower rises
        away = ((np.linalg.norm(Qp, axis=-1) - np.linalg.norm(Qm, axis=-1)) * (1 if up else -1) > 0) | ~moving
        ok &= np.all((theta <= th + 1e-9) & away, axis=1)
    return ok


def _brute_min(kind, sigma, sp, box, tau=1, l=None, levels=8, m=25):
    """min |O| over admissible O by successive grid refinement of a box."""
    (x0, x1), (y0, y1) = box
    best = None
    for _ in range(levels):
        X, Y = np.meshgrid(np.linspace(x0, x1, m), np.linspace(y0, y1, m))
        P = np.column_stack([X.ravel(), Y.ravel()])
        ok = _admissible(kind, P, sigma, sp, tau, l)
        assert ok.any(), "brute force box misses the region"
        d = np.linalg.norm(P, axis=1)
        d[~ok] = np.inf
        best = P[np.argmin(d)]
        dx, dy = 2 * (x1 - x0) / (m - 1), 2 * (y1 - y0) / (m - 1)
        x0, x1, y0, y1 = best[0] - dx, best[0] + dx, best[1] - dy, best[1] + dy
    return best


@pytest.mark.parametrize("laws,lim", [(("cosine", "cosine"), (30, 30)), (("sine", "poly345"), (25, 45)),
                                      (("poly345", "sine"), (30, 60))])
def test_best_offset_brute_force(laws, lim):
    sp = spec(stroke=0.04, offset="auto", laws=fields(rise=laws[0], return_=laws[1]),
              phases=fields(rise=100, far_dwell=20, return_=80, near_dwell=160),
              pressure_angle=fields(rise=lim[0], return_=lim[1]))
    r = synthesize(sp)
    # the follower moves along +x in the check's frame, the cam rotates ccw:
    O = _brute_min("translating", 1, sp, ((-0.3, 0.0), (-0.15, 0.15)))
    assert r.r0 == pytest.approx(np.linalg.norm(O), rel=1e-4)
    # offset = distance of O from the follower axis, positive on the side lowering the
    # rise pressure angle: for a ccw cam and a follower moving along +x that is O above
    # the axis (y > 0) -- the cam surface under the roller then moves along +x
    assert r.offset == pytest.approx(O[1], abs=1e-4 * r.r0)
    assert r.max_pressure_angle_rise <= lim[0] + 1e-9


def test_given_offset_brute_force():
    sp = spec(stroke=0.04, offset=-0.005, laws=fields(rise="sine", return_="sine"),
              pressure_angle=fields(rise=30, return_=35))
    r = synthesize(sp)
    # O on the line y = offset (check frame: follower along +x), nearest admissible x
    xs = np.linspace(-0.2, 0.0, 401)
    for n in (300, 1000, 3000, 3000, 3000):
        P = np.column_stack([xs, np.full_like(xs, -0.005)])
        ok = _admissible("translating", P, 1, sp, n=n)
        x = xs[ok].max()
        xs = np.linspace(x - 2 * (xs[1] - xs[0]), x + 2 * (xs[1] - xs[0]), 41)
    assert r.r0 == pytest.approx(math.hypot(x, 0.005), rel=1e-6)


@pytest.mark.parametrize("swing", ["with", "against"])
@pytest.mark.parametrize("rotation", ["ccw", "cw"])
def test_rocker_brute_force(swing, rotation):
    l = 0.1
    sp = spec(follower="rocker", stroke=20.0, rocker_length=l, offset=0.0, swing=swing,
              rotation=rotation, laws=fields(rise="sine", return_="cosine"),
              phases=fields(rise=100, far_dwell=20, return_=120, near_dwell=120),
              pressure_angle=fields(rise=40, return_=50))
    r = synthesize(sp)
    sigma = 1 if rotation == "ccw" else -1
    tau = sigma if swing == "with" else -sigma
    O = _brute_min("rocker", sigma, sp, ((-0.15, 0.15), (-0.2, 0.05)), tau=tau, l=l)
    assert r.swing == swing
    assert r.r0 == pytest.approx(np.linalg.norm(O), rel=1e-4)
    assert r.center_distance == pytest.approx(np.linalg.norm(O - np.array([0.0, -l])), rel=1e-4)
    assert r.offset is None


def test_rocker_auto_swing_picks_smaller():
    base = dict(follower="rocker", stroke=25.0, rocker_length=0.12, laws=fields(rise="poly345", return_="sine"),
                phases=fields(rise=80, far_dwell=40, return_=110, near_dwell=130),
                pressure_angle=fields(rise=35, return_=50))
    a = synthesize(spec(**base, swing="with"))
    b = synthesize(spec(**base, swing="against"))
    c = synthesize(spec(**base, swing="auto"))
    assert c.r0 == pytest.approx(min(a.r0, b.r0), rel=1e-12)
    assert c.swing == ("with" if a.r0 <= b.r0 else "against")


def test_rotation_mirrors_the_cam():
    a = synthesize(spec(offset="auto", laws=fields(rise="sine", return_="cosine"), pressure_angle=fields(rise=28, return_=40)))
    b = synthesize(spec(offset="auto", rotation="cw", laws=fields(rise="sine", return_="cosine"),
                        pressure_angle=fields(rise=28, return_=40)))
    assert a.r0 == pytest.approx(b.r0, rel=1e-12)
    assert a.offset == pytest.approx(b.offset, rel=1e-9)
    assert np.allclose(a.pitch[:, 0], -b.pitch[:, 0], atol=1e-12)
    assert np.allclose(a.pitch[:, 1], b.pitch[:, 1], atol=1e-12)


def test_empty_region_is_a_stage_error():
    with pytest.raises(StageError):
        synthesize(spec(follower="rocker", stroke=150.0, rocker_length=0.05, swing="with",
                        phases=fields(rise=30, far_dwell=0, return_=30, near_dwell=300),
                        laws=fields(rise="constant_velocity", return_="constant_velocity"),
                        pressure_angle=fields(rise=5, return_=5)))


def test_results_dict_is_plain_json():
    import json
    r = synthesize(spec(offset="auto", speed=10.0, laws=fields(rise="constant_velocity", return_="parabolic")))
    d = r.to_dict()
    text = json.dumps(d, allow_nan=False)
    assert json.loads(text)["r0"] == d["r0"]
    for key in ("r0", "offset", "center_distance", "roller", "max_pressure_angle", "rho_min"):
        assert key in d
    assert d["r0_design"] >= d["r0"] and d["r0_design"] - d["r0"] < 1e-3
    assert len(d["phi"]) == len(d["s"]) == len(d["pitch_profile"]) == 360
    # constant velocity: a rigid impact is reported; its acceleration coefficient is infinite
    assert d["laws"]["rise"]["ca"] is None
    assert any("rigid impact" in w for w in d["warnings"])
    # v = ds/dphi * omega: the constant-velocity rise moves at h/Phi*omega = 0.03/(pi/2)*10
    assert d["v"][45] == pytest.approx(0.03 / (math.pi / 2) * 10.0)


def test_an_allowed_pressure_angle_far_above_the_courses_is_told():
    """[theta] = 89 deg sizes a knife-edge cam of about the offset alone (the profile nearly
    locks the follower: 1/cos 89 = 57 times the useful force); tmm says so (above 60 deg, twice
    the force), and not at the course's 30 deg or at 60 itself."""
    from pathlib import Path

    import yaml as _yaml

    from tmm_cli import load_task, run
    base = _yaml.safe_load((Path(__file__).resolve().parents[1] / "tasks" / "cam_knife.yaml").read_text(encoding="utf-8"))
    for angle, told in ((89, True), (61, True), (60, False), (30, False)):
        base["cam"]["pressure_angle"] = angle
        warnings = run(load_task(base)).get("warnings", [])
        assert any("far above the usual" in str(w) for w in warnings) == told, (angle, warnings)


@pytest.mark.parametrize("name, shown", [("cam_knife", False), ("cam_translating", False), ("cam_rocker", True)])
def test_the_task_table_shows_a_rockers_fields_for_a_rocker_only(tmp_path, name, shown):
    """'swing: auto' (a rocker's sense of swing) and the rocker's length were listed for a
    translating or knife-edge follower, where they mean nothing."""
    from pathlib import Path

    from tmm_cli import load_task, run
    from tmm_cli.report import render_html
    task = load_task(Path(__file__).resolve().parents[1] / "tasks" / f"{name}.yaml")
    html, _ = render_html(run(task), task, tmp_path, "en")
    assert ("rocker&#39;s turn on the rise" in html or "rocker's turn on the rise" in html) == shown
    # a rocker's stroke is its swing (in degrees, named so), and it has no offset e to list
    table = html[:html.index("</table>", html.index("stroke" if not shown else "swing of the rocker"))]
    assert ("swing of the rocker" in table) == shown and ("stroke h" in table) == (not shown)
    if shown:
        assert "offset e" not in table


@pytest.mark.parametrize("follower", ["translating", "flat"])
def test_a_phase_of_few_grid_steps_is_told(follower):
    """A rise or return shorter than 10 steps of the result's 1-degree grid is shown coarsely by the
    tables, the diagrams and the profile's exports (a 0.5 deg rise not at all: the profile a circle):
    each such phase is told, for a roller and a flat follower alike; a 10-degree phase is not."""
    from cam_spec import section

    def cam(rise):
        d = dict(follower=follower, stroke=0.03, phases=fields(rise=rise, far_dwell=20, return_=10),
                 laws=fields(rise="cosine", return_="cosine"))
        if follower == "flat":
            d["rho_min_allowed"] = 0.01
        return synthesize(section("cam", d))

    def coarse(r):
        return [w for w in r.warnings if getattr(w, "code", "") == "cam.phase_coarse"]
    said = coarse(cam(5))
    assert [w.params["phase"] for w in said] == ["rise"] and said[0].params["angle"] == 5.0
    assert not coarse(cam(10))


def test_phases_a_hair_over_360_are_360_and_more_is_said_with_its_digits():
    """rise + far dwell + return written to 7 places (133.3333333 + 93.3333334 + 133.3333334 =
    360.0000001) is a full turn, as the sum of four phases is held to 1e-6; 360.00001 is over, and
    the message shows the digits that make it so (it read '360 deg exceeds 360')."""
    from tmm_cli.errors import TaskError
    from tmm_cli.task import load_task

    def task(r, f, t):
        return {"schema": "tmm/1", "cam": {"stroke": 0.03, "phases": {"rise": r, "far_dwell": f, "return": t}}}
    c = load_task(task(133.3333333, 93.3333334, 133.3333334)).cam
    assert c.phases.near_dwell == 0.0
    with pytest.raises(TaskError) as err:
        load_task(task(133.33334, 93.33333, 133.33334))
    assert "rise + far_dwell + return = 360.00001 deg exceeds 360" in err.value.render()


def test_a_knife_edge_over_corners_is_told_without_a_roller():
    """Constant velocity has velocity jumps at the rise's ends: the profile's corners are told; a
    knife-edge follower's warning names its edge, not the roller rule it has no roller for."""
    from cam_spec import section

    def codes(follower):
        d = dict(follower=follower, stroke=0.03, phases=fields(rise=120, far_dwell=30, return_=120),
                 laws=fields(rise="constant_velocity", return_="cosine"))
        return [getattr(w, "code", "") for w in synthesize(section("cam", d)).warnings]
    assert "cam.profile_corners_knife" in codes("knife") and "cam.profile_corners" not in codes("knife")
    assert "cam.profile_corners" in codes("translating")
