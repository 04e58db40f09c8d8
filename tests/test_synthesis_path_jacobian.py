"""The exact Jacobian of the path synthesis's least-squares refinement (coupler_jacobian,
violation_gradient, _jacobian) against central differences taken here, column by column, at
a seeded sample of non-degenerate linkages; the penalty row's derivative likewise away from its
kinks; zero where the linkage does not close."""
import math

import numpy as np
import pytest

from tmm_cli.linkage.synthesis_path import _jacobian, coupler_jacobian, coupler_points, violation, violation_gradient

H = 1e-6                                        # the central differences' step (the lengths are ~1)


def _residuals(z, s, T, gamma):
    """_refine's residuals written out: Mx_j - Tx_j, My_j - Ty_j, 30 * violation."""
    mx, my = coupler_points(np.concatenate([z[:9], [s]]), z[9:])
    return np.concatenate([mx - T[:, 0], my - T[:, 1], [30.0 * violation(z[0], z[1], z[2], z[3], gamma)]])


def _central(f, z):
    return np.column_stack([(f(z + H * e) - f(z - H * e)) / (2.0 * H) for e in np.eye(len(z))])


def _sample(rng, n):
    """A random linkage (lengths 0.1-2, pivot, frame angle, coupler point, branch) and n crank
    angles at which it closes with B well off the line A-O1 (h > 0.05 b: no tangency)."""
    while True:
        z = np.concatenate([rng.uniform(0.1, 2.0, 4), rng.uniform(-1.0, 1.0, 2), [rng.uniform(-math.pi, math.pi)],
                            rng.uniform(-2.0, 2.0, 2), rng.uniform(0.0, 2.0 * math.pi, n)])
        a, b, c, d = z[:4]
        ang = z[9:]
        L = np.hypot(d * 1.0 - a * np.cos(ang), -a * np.sin(ang))       # |O1 - A| in the frame's axes
        k = (b * b - c * c + L * L) / (2.0 * L)
        if (b * b - k * k > (0.05 * b) ** 2).all() and (L > 0.05).all():
            return z, float(rng.choice([-1.0, 1.0]))


def test_residual_jacobian_matches_central_differences():
    rng = np.random.default_rng(20261206)
    T = rng.uniform(-1.0, 1.0, (7, 2))
    for _ in range(200):
        z, s = _sample(rng, len(T))
        gamma = float(rng.uniform(10.0, 60.0))
        J = _jacobian(z, s, gamma)
        Jn = _central(lambda q: _residuals(q, s, T, gamma), z)
        # the penalty row is checked away from its kinks (test below); here its kink may lie in [z-H, z+H]
        for j in range(J.shape[1]):
            scale = max(1.0, float(np.abs(Jn[:-1, j]).max()))
            assert np.abs(J[:-1, j] - Jn[:-1, j]).max() <= 1e-6 * scale, (j, z, s)


def test_each_point_depends_on_its_own_crank_angle_only():
    rng = np.random.default_rng(7)
    z, s = _sample(rng, 5)
    J = _jacobian(z, s, 30.0)
    phi_block = np.abs(J[:5, 9:]) + np.abs(J[5:10, 9:])
    assert np.count_nonzero(phi_block - np.diag(np.diag(phi_block))) == 0
    assert (np.diag(phi_block) > 0).all()


def _kink_distance(a, b, c, d, gamma):
    """How near (a, b, c, d) is to a kink of violation: each max(0, g)'s g, each |c_i|, the
    gaps between b, c, d (the min and max switch there)."""
    lo, hi = min(b, c, d), max(b, c, d)
    cg = math.cos(math.radians(gamma))
    c1 = (b * b + c * c - (d - a) ** 2) / (2 * b * c)
    c2 = (b * b + c * c - (d + a) ** 2) / (2 * b * c)
    return min(abs(a - lo), abs(a + 2 * hi - (b + c + d)), abs(abs(c1) - cg), abs(abs(c2) - cg), abs(c1), abs(c2),
               abs(b - c), abs(c - d), abs(b - d))


def test_penalty_gradient_matches_central_differences_away_from_kinks():
    rng = np.random.default_rng(11)
    checked = active = 0
    while checked < 200:
        a, b, c, d = rng.uniform(0.05, 3.0, 4)
        gamma = float(rng.uniform(10.0, 70.0))
        if _kink_distance(a, b, c, d, gamma) < 1e-3:
            continue
        g = violation_gradient(a, b, c, d, gamma)
        gn = _central(lambda q: np.array([violation(q[0], q[1], q[2], q[3], gamma)]), np.array([a, b, c, d]))[0]
        assert g == pytest.approx(gn, rel=1e-6, abs=1e-6 * max(1.0, float(np.abs(gn).max())))
        checked += 1
        active += bool(np.any(g != 0))
    assert active > 100                          # the sample exercises the active terms, not just zeros


def test_penalty_gradient_by_hand():
    # a = 1, b = 2, c = 3, d = 4, gamma 30 (cos 0.8660): min(b, c, d) = 2 > a: g1 off; a + 2*4 - 9 = 0: g2 off
    # (not > 0); c1 = (4 + 9 - 9)/12 = 1/3 inside; c2 = (4 + 9 - 25)/12 = -1 beyond: sign -1,
    # dc2 = (-(5)/6, 1/3 + 1/2, 1/2 + 1/3, -5/6) -> gradient (5/6, -5/6, -5/6, 5/6)
    assert violation_gradient(1.0, 2.0, 3.0, 4.0, 30.0) == pytest.approx([5 / 6, -5 / 6, -5 / 6, 5 / 6], rel=1e-14)
    # a = 2 > min = b = 1 (g1: da 1, db -1); a + 2*3 - (1 + 2.5 + 3) = 1.5 > 0 (g2: da 1, d = longest:
    # (1, -1, -1, +1)); c1 = (1 + 6.25 - 1)/5 = 1.25 beyond: dc1 = ((d-a)/(bc), 1/c - c1/b, 1/b - c1/c, -(d-a)/(bc))
    # = (0.4, 0.4 - 1.25, 1 - 0.5, -0.4); c2 = (1 + 6.25 - 25)/5 = -3.55: -dc2 = (5/2.5, -(0.4 + 3.55), -(1 + 1.42), 2)
    want = np.array([1, -1, 0, 0]) + np.array([1, -1, -1, 1]) + np.array([0.4, -0.85, 0.5, -0.4]) \
        + np.array([2.0, -3.95, -2.42, 2.0])
    assert violation_gradient(2.0, 1.0, 2.5, 3.0, 30.0) == pytest.approx(want, rel=1e-12)


def test_zero_where_the_linkage_does_not_close():
    # a = 0.1, b = c = 0.2, d = 1: A-O1 about 0.9-1.1 > b + c, the circles never meet
    x = np.array([0.1, 0.2, 0.2, 1.0, 0.0, 0.0, 0.0, 0.1, 0.1, 1.0])
    mx, my, dmx, dmy = coupler_jacobian(x, np.linspace(0.0, 6.0, 4))
    assert np.isnan(mx).all() and np.isnan(my).all()
    assert not dmx.any() and not dmy.any()
