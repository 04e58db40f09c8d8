"""Motion generation through three positions of the coupler plane (the pole method).

Pure functions. The task gives three positions of the coupler plane (a point P and the
plane's angle) and the moving pivots A, B in the plane's own frame (at P, x along the
plane's angle). In position j, A_j = P_j + R(angle_j) A and B_j likewise; the fixed pivot
O is the centre of the circle through A_1, A_2, A_3 (where the perpendicular bisectors of
A_1A_2 and A_2A_3 meet), O1 that of B_1, B_2, B_3 (Artobolevsky, the synthesis of a
four-bar by given positions of the coupler; Norton, *Design of Machinery*, three-position
motion synthesis). The poles P12, P13, P23 of the plane's displacements are drawn in the
report: O lies on the bisector of A_iA_k, which passes through the pole P_ik.

Defects (checked, reported, not fatal): ``branch`` -- the three positions lie on
different assembly branches of the linkage (B on either side of the line A O1), so the
crank-driven linkage reaches at most the positions of one branch; ``order`` -- the
crank, turning in the drive's sense from position 1, meets position 3 before position 2.
"""
from __future__ import annotations

import math

from ..messages import Message
from .spec import _rot, collinear, pivot_positions, positions_input_error  # noqa: F401

STAGE = "synthesis"
LINKS = ("crank", "coupler", "rocker")


# the pivots' positions and the input checks live with the section (the task model runs them)
check = positions_input_error


def circumcentre(p, q, s) -> tuple[float, float]:
    """The centre of the circle through three points (the meeting of the perpendicular
    bisectors of pq and qs)."""
    ax, ay = p
    bx, by = q
    cx, cy = s
    d = 2.0 * (ax * (by - cy) + bx * (cy - ay) + cx * (ay - by))
    a2, b2, c2 = ax * ax + ay * ay, bx * bx + by * by, cx * cx + cy * cy
    return ((a2 * (by - cy) + b2 * (cy - ay) + c2 * (ay - by)) / d,
            (a2 * (cx - bx) + b2 * (ax - cx) + c2 * (bx - ax)) / d)


def pole(pose1, pose2) -> tuple[float, float] | None:
    """The pole of the plane's displacement from pose1 to pose2 (the point that does not
    move): P2 + R(d)(X - P1) = X with d the turn; None for a pure translation."""
    d = math.radians(float(pose2.angle) - float(pose1.angle))
    c, s = math.cos(d), math.sin(d)
    if abs(1.0 - c) < 1e-12 and abs(s) < 1e-12:
        return None
    p1 = (float(pose1.P[0]), float(pose1.P[1]))
    p2 = (float(pose2.P[0]), float(pose2.P[1]))
    # (I - R) X = P2 - R P1
    rx, ry = p2[0] - (c * p1[0] - s * p1[1]), p2[1] - (s * p1[0] + c * p1[1])
    a11, a12, a21, a22 = 1.0 - c, s, -s, 1.0 - c
    det = a11 * a22 - a12 * a21
    return ((rx * a22 - a12 * ry) / det, (a11 * ry - a21 * rx) / det)


def _cross(o, p, q) -> float:
    return (p[0] - o[0]) * (q[1] - o[1]) - (p[1] - o[1]) * (q[0] - o[0])


def defects(O, O1, A, B, sign: float) -> dict:
    """The branch and order defects of the crank-driven linkage through the positions.

    branch: the side of the line A_j O1 that B_j is on (+1 left, -1 right) in each position;
    a defect when they differ. order: the crank angles of the positions; a defect when the
    crank, turning in the drive's sense ``sign`` from position 1, meets position 3 first."""
    sides = [1 if _cross(a, O1, b) > 0 else -1 for a, b in zip(A, B)]
    ang = [math.degrees(math.atan2(a[1] - O[1], a[0] - O[0])) for a in A]
    turn = [((x - ang[0]) * sign) % 360.0 for x in ang]
    return {"branch": len(set(sides)) > 1, "order": not (turn[1] < turn[2]),
            "branches": sides, "crank_angles": ang, "turns": turn}


def design(sec, sign: float):
    """The four-bar through three positions of the coupler plane.

    Parameters
    ----------
    sec : SynthesisSection
        ``positions`` (three {P [m], angle [deg]}) and ``moving_pivots`` {A, B} (m, in the
        plane's frame at P, x along the plane's angle).
    sign : float
        The drive's sense of rotation (+1 ccw, -1 cw), for the order defect.

    Returns
    -------
    Design
        The lengths {crank, coupler, rocker, frame} (m), the generated mechanism assembled
        in the first position (the ground where the construction puts it), the construction
        (the pivots in each position, the fixed pivots, the poles) and the defects.

    Raises
    ------
    SynthesisImpossible
        When the crank of the generated linkage cannot turn fully (Grashof).

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*, synthesis of a four-bar by three
    positions of the coupler; Norton, *Design of Machinery*, three-position motion synthesis.
    """
    from .synthesis import Design, SynthesisImpossible, _mass, grashof

    pts = pivot_positions(sec)
    A, B = pts["A"], pts["B"]
    O, O1 = circumcentre(*A), circumcentre(*B)
    a, c, d = math.dist(O, A[0]), math.dist(O1, B[0]), math.dist(O, O1)
    b = math.dist(A[0], B[0])
    kind = grashof(a, b, c, d)
    if kind not in ("crank-rocker", "double-crank"):
        raise SynthesisImpossible(Message("synthesis.fail.positions_crank", a=a, b=b, c=c, d=d))
    # the plane's point P in the coupler's frame (u along A->B, v to its left)
    mp = sec.moving_pivots
    la = mp["A"] if isinstance(mp, dict) else mp.A
    lb = mp["B"] if isinstance(mp, dict) else mp.B
    beta = math.atan2(float(lb[1]) - float(la[1]), float(lb[0]) - float(la[0]))
    pu, pv = _rot((-float(la[0]), -float(la[1])), -math.degrees(beta))
    mech = {"ground": {"O": [O[0], O[1]], "O1": [O1[0], O1[1]]},
            "links": {"crank": {"points": ["O", "A"], "length": a, **_mass(sec, "crank")},
                      "coupler": {"points": ["A", "B"], "length": b, "extra": {"P": [pu, pv]},
                                  **_mass(sec, "coupler")},
                      "rocker": {"points": ["O1", "B"], "length": c, **_mass(sec, "rocker")}},
            "assembly": {"B": [B[0][0], B[0][1]]}}
    poses = list(sec.positions)
    poles = {f"{i + 1}{k + 1}": pole(poses[i], poses[k]) for i, k in ((0, 1), (0, 2), (1, 2))}
    cons = {"A_positions": [list(p) for p in A], "B_positions": [list(p) for p in B],
            "O": list(O), "O1": list(O1), "poles": {k: (list(v) if v else None) for k, v in poles.items()},
            "targets": [{"P": [float(p.P[0]), float(p.P[1])], "angle": float(p.angle)} for p in poses],
            "defects": defects(O, O1, A, B, sign), "grashof": kind}
    return Design("positions", {"crank": a, "coupler": b, "rocker": c, "frame": d}, mech, "rocker", "forward",
                  [], cons)


def analyse(linkage, d, least: tuple[float, float]) -> dict:
    """The generated linkage analysed at the crank angles of the three positions: where its
    point P is and how its coupler is turned, against the positions asked for (on the branch
    it is assembled on: a branch defect shows as a large deviation)."""
    import numpy as np

    from .kinematics import solve

    cons = d.construction
    df = cons["defects"]
    kin = solve(linkage.mechanism, np.mod(df["crank_angles"], 360.0), linkage.drive.omega)
    P = kin.pos["P"]
    A, B = kin.pos["A"], kin.pos["B"]
    got = []
    # the coupler's angle offset: the plane's angle minus the line AB's, fixed by position 1
    ab0 = math.degrees(math.atan2(cons["B_positions"][0][1] - cons["A_positions"][0][1],
                                  cons["B_positions"][0][0] - cons["A_positions"][0][0]))
    off = cons["targets"][0]["angle"] - ab0
    for j, t in enumerate(cons["targets"]):
        ang = math.degrees(math.atan2(B[j, 1] - A[j, 1], B[j, 0] - A[j, 0])) + off
        got.append({"P": [float(P[j, 0]), float(P[j, 1])], "angle": float(ang),
                    "deviation": float(math.dist(P[j], t["P"])),
                    "angle_error": float((ang - t["angle"] + 180.0) % 360.0 - 180.0),
                    "crank_angle": float(df["crank_angles"][j] % 360.0), "branch": df["branches"][j]})
    L = d.lengths
    gmin, gphi = least                    # the transmission stage's (synthesis.least_of)
    return {"type": "positions", "lengths": dict(L),
            "fixed_pivots": {"O": list(cons["O"]), "O1": list(cons["O1"])},
            "grashof": cons["grashof"],
            "defects": {"branch": bool(df["branch"]), "order": bool(df["order"])},
            "positions": got, "targets": cons["targets"], "gamma_min": gmin, "gamma_min_phi": gphi,
            "construction": {k: cons[k] for k in ("A_positions", "B_positions", "O", "O1", "poles")},
            "mechanism": d.mechanism, "output": d.output, "working": d.working}
