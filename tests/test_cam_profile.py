"""Cam profile by inverted motion: working profile, reconstruction of the motion,
pressure angle, radius of curvature, roller rule, export."""
import io
import math

import numpy as np
import pytest
from scipy.optimize import brentq, minimize_scalar

from tmm_cli.cam import synthesize
from tmm_cli.cam.export import profile_csv_rows, profile_dxf
from tmm_cli.errors import StageError
from cam_spec import fields, spec  # noqa: E402  (shared cam section builder)




CASES = {
    "offset": spec(stroke=0.04, offset="auto", laws=fields(rise="sine", return_="poly345"),
                   phases=fields(rise=120, far_dwell=20, return_=100, near_dwell=120),
                   pressure_angle=fields(rise=25, return_=40)),
    "offset_cw": spec(stroke=0.04, offset=0.004, rotation="cw", laws=fields(rise="cosine", return_="sine"),
                      pressure_angle=fields(rise=30, return_=45)),
    "rocker": spec(follower="rocker", stroke=18.0, rocker_length=0.12, swing="against",
                   laws=fields(rise="poly345", return_="cosine"),
                   phases=fields(rise=100, far_dwell=30, return_=110, near_dwell=120),
                   pressure_angle=fields(rise=40, return_=50)),
    "rocker_cw": spec(follower="rocker", stroke=22.0, rocker_length=0.1, swing="with", rotation="cw",
                      laws=fields(rise="sine", return_="sine"),
                      phases=fields(rise=90, far_dwell=40, return_=120, near_dwell=110),
                      pressure_angle=fields(rise=35, return_=45)),
}


@pytest.fixture(scope="module", params=sorted(CASES))
def case(request):
    return request.param, synthesize(CASES[request.param])


def _nearest_on(curve_fn, dense_phi, dense_pts, P):
    """min over phi' of |curve(phi') - P| (dense search, then Brent on the bracket)."""
    d = np.hypot(dense_pts[:, 0] - P[0], dense_pts[:, 1] - P[1])
    i = int(np.argmin(d))
    lo, hi = dense_phi[max(i - 1, 0)], dense_phi[min(i + 1, len(dense_phi) - 1)]
    res = minimize_scalar(lambda t: float(np.hypot(*(curve_fn(np.array([t]))[0] - P))),
                          bounds=(lo, hi), method="bounded", options={"xatol": 1e-13})
    return min(res.fun, float(d[i]))


def test_working_profile_at_roller_distance(case):
    """Every working-profile point lies at exactly the roller radius from the pitch curve
    (its nearest point on the whole pitch curve: no undercut)."""
    _, r = case
    prof = r.profile
    dense = np.radians(np.linspace(0, 360, 7201))
    pitch_dense = prof.pitch(dense)[0]
    for W in r.working[::10]:
        dist = _nearest_on(lambda t: prof.pitch(t)[0], dense, pitch_dense, W)
        assert dist == pytest.approx(r.roller, rel=1e-9)


def test_motion_reconstructed_from_the_working_profile(case):
    """Put the roller on the working profile turned by phi (inverted motion backwards):
    the roller-centre position where the roller touches the cam reproduces s(phi)."""
    name, r = case
    prof = r.profile
    sigma = 1 if r.rotation == "ccw" else -1
    dense = np.radians(np.linspace(0, 360, 7201))
    work_dense = prof.working(dense, r.roller)
    B0 = np.array(r.construction["B0"])
    rocker = r.follower == "rocker"
    if rocker:
        A = np.array(r.construction["A"])
        l = r.rocker_length
        psi0 = math.atan2(B0[1] - A[1], B0[0] - A[0])
        tau = r.geometry.tau

    def centre(p):
        if rocker:
            return A + l * np.array([math.cos(psi0 + tau * p), math.sin(psi0 + tau * p)])
        return B0 + np.array([0.0, p])

    for phi_deg in np.arange(3.0, 360.0, 13.0):
        phi = math.radians(phi_deg)
        c, s_ = math.cos(-sigma * phi), math.sin(-sigma * phi)

        def gap(p):
            C = centre(p)
            Cc = np.array([c * C[0] - s_ * C[1], s_ * C[0] + c * C[1]])   # into the cam frame
            return _nearest_on(lambda t: prof.working(t, r.roller), dense, work_dense, Cc) - r.roller

        s_exp = float(r.motion.evaluate(np.array([phi]))[0][0])
        delta = 0.2 * r.roller / (l if rocker else 1.0)
        p = brentq(gap, s_exp - delta, s_exp + delta, xtol=1e-15, rtol=1e-15)
        scale = l if rocker else 1.0
        assert p * scale == pytest.approx(s_exp * scale, abs=1e-9), (name, phi_deg)


def test_pressure_angle_array_from_profile_tangent(case):
    """Pressure angle = angle between the normal of the pitch profile (tangent by finite
    differences of the profile points) and the velocity of the roller centre."""
    _, r = case
    prof = r.profile
    sigma = 1 if r.rotation == "ccw" else -1
    phi = np.radians(r.phi)
    d = 1e-6
    T = prof.pitch(phi + d)[0] - prof.pitch(phi - d)[0]
    T /= np.linalg.norm(T, axis=1)[:, None]
    Bfix = prof.follower_at(phi)                          # roller centre, fixed frame, O at 0
    if r.follower == "rocker":
        A = np.array(r.construction["A"])
        V = np.column_stack([-(Bfix[:, 1] - A[1]), Bfix[:, 0] - A[0]])
    else:
        V = np.tile([0.0, 1.0], (len(phi), 1))
    c, s_ = np.cos(-sigma * phi), np.sin(-sigma * phi)
    V = np.column_stack([c * V[:, 0] - s_ * V[:, 1], s_ * V[:, 0] + c * V[:, 1]])
    V /= np.linalg.norm(V, axis=1)[:, None]
    theta = np.degrees(np.arccos(np.clip(np.abs(T[:, 0] * V[:, 1] - T[:, 1] * V[:, 0]), 0, 1)))
    assert np.max(np.abs(theta - r.pressure_angle)) < 1e-4
    assert r.max_pressure_angle >= np.max(r.pressure_angle) - 1e-9
    assert r.max_pressure_angle_rise <= r.allowed["rise"] + 1e-9
    assert r.max_pressure_angle_return <= r.allowed["return"] + 1e-9


def test_rho_min_by_finite_differences(case):
    """Curvature of the pitch points by finite differences (no derivatives of the program)."""
    _, r = case
    prof = r.profile
    sigma = 1 if r.rotation == "ccw" else -1
    phi = np.radians(np.linspace(0, 360, 72001)[:-1])
    d = 1e-4
    Q0, Qp, Qm = prof.pitch(phi)[0], prof.pitch(phi + d)[0], prof.pitch(phi - d)[0]
    d1 = (Qp - Qm) / (2 * d)
    d2 = (Qp - 2 * Q0 + Qm) / d ** 2
    conv = -sigma * (d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) / np.linalg.norm(d1, axis=1) ** 3
    assert r.rho_min == pytest.approx(1 / np.max(conv), rel=1e-5)


def test_rho_min_central_closed_form():
    """Central translating follower: rho = ((r0+s)^2 + s'^2)^1.5 / ((r0+s)^2 + 2 s'^2 - s''(r0+s))
    (textbook radius of curvature of the pitch curve in polar form), minimum over the
    convex parts; and the automatic roller = min(0.7 rho_min, 0.4 r0)."""
    h, P = 0.03, math.pi / 2
    r = synthesize(spec(stroke=h, laws=fields(rise="cosine", return_="cosine")))
    A = h * math.pi / (2 * P * math.tan(math.radians(30)))
    r0 = math.sqrt(A * A + h * h / 4) - h / 2                 # closed form, see test_cam_synthesis
    x = np.linspace(0, 1, 400001)
    s = h * (1 - np.cos(np.pi * x)) / 2
    s1 = h * np.pi / (2 * P) * np.sin(np.pi * x)
    s2 = h * np.pi ** 2 / (2 * P * P) * np.cos(np.pi * x)
    R = r0 + s
    den = R ** 2 + 2 * s1 ** 2 - s2 * R
    rho = np.where(den > 0, (R ** 2 + s1 ** 2) ** 1.5 / np.where(den > 0, den, 1), np.inf)
    rho_min = min(float(np.min(rho)), r0)                     # (the base circle: rho = r0)
    assert r.rho_min == pytest.approx(rho_min, rel=1e-8)
    assert r.roller == pytest.approx(min(0.7 * rho_min, 0.4 * r0), rel=1e-8)


def test_roller_undercut_and_rules():
    base = dict(stroke=0.03, laws=fields(rise="cosine", return_="cosine"))
    r = synthesize(spec(**base))
    with pytest.raises(StageError, match="undercut"):
        synthesize(spec(**base, roller=r.rho_min * 1.001))
    ok = synthesize(spec(**base, roller=r.rho_min * 0.99))
    assert ok.roller == r.rho_min * 0.99
    assert any("0.8 rho_min" in w for w in ok.warnings)
    fine = synthesize(spec(**base, roller=0.005))
    assert fine.roller == 0.005 and not any("course rule" in w for w in fine.warnings)
    d = fine.to_dict()
    assert d["roller_rule"] == "given"


def test_base_circle_and_start_point():
    r = synthesize(CASES["offset"])
    # the near dwell is an arc of the base circle: radius r0 on the pitch profile
    radii = np.hypot(r.pitch[:, 0], r.pitch[:, 1])
    assert np.min(radii) == pytest.approx(r.r0, rel=1e-12)
    assert radii[0] == pytest.approx(r.r0, rel=1e-12)
    # the translating follower's axis is at x = offset (ccw cam)
    assert r.construction["B0"][0] == pytest.approx(r.offset, abs=1e-15)


def test_export_csv_and_dxf():
    import ezdxf

    r = synthesize(CASES["rocker"])
    header, rows = profile_csv_rows(r.to_dict())
    assert header[0] == "phi_deg" and len(rows) == 360
    assert rows[10][1:3] == pytest.approx(list(r.pitch[10]))
    doc = ezdxf.read(io.StringIO(profile_dxf(r)))
    msp = doc.modelspace()
    polys = msp.query("LWPOLYLINE")
    assert len(polys) == 2 and all(len(p) == 360 and p.closed for p in polys)
    circles = sorted(c.dxf.radius for c in msp.query("CIRCLE"))
    assert r.r0 * 1000 in [pytest.approx(c) for c in circles]
    assert r.roller * 1000 in [pytest.approx(c) for c in circles]
