"""Balancing of a rigid rotor (Artobolevsky, "Teoriya mekhanizmov i mashin", ch. on balancing
of rotating masses; Popov and Timofeev).

Each mass m_i at radius r_i, angle theta_i and axial position z_i has the imbalance
U_i = m_i r_i e^{i theta_i} (kg*m, a complex number in the plane of rotation). The rotor
turning at omega feels the force omega^2 sum U_i and, about z = 0, the moment
omega^2 sum z_i U_i. Correction masses U_c,k = m_c,k rho e^{i alpha_k} in the chosen planes
cancel

* with one plane z_1 (static balancing): the force, U_c = -S, S = sum U_i; the couple
  sum (z_i - z_1) U_i is left and reported;
* with two planes z_1, z_2 (dynamic balancing): the force and the moment,
  U_c,1 + U_c,2 = -S and z_1 U_c,1 + z_2 U_c,2 = -Q, Q = sum z_i U_i, so
  U_c,2 = (z_1 S - Q)/(z_2 - z_1), U_c,1 = -S - U_c,2.

The rotor's imbalance is reported as its resultant S (``mr``, ``angle``) at the axial
position ``z`` where the resultant's moment best stands for Q (z = Re(Q S*)/|S|^2), with
the couple left about it, |Q - z S| (kg*m^2).
"""
from __future__ import annotations

import math


def _polar(u: complex) -> tuple[float, float]:
    """|u| and its angle in degrees, [0, 360)."""
    return abs(u), (math.degrees(math.atan2(u.imag, u.real)) % 360.0 if u != 0 else 0.0)


def balance_rotor(spec) -> dict:
    """The results.json ``balancing.rotor`` of a RotorSpec."""
    U = [m.m * m.r * complex(math.cos(math.radians(m.angle)), math.sin(math.radians(m.angle))) for m in spec.masses]
    S = sum(U, 0j)
    Q = sum((m.z * u for m, u in zip(spec.masses, U)), 0j)
    mr, ang = _polar(S)
    z_eq = (Q * S.conjugate()).real / abs(S) ** 2 if abs(S) > 0 else None
    couple = abs(Q - z_eq * S) if z_eq is not None else abs(Q)
    planes = [float(z) for z in spec.planes]
    if len(planes) == 1:
        corr = [-S]
        left = abs(Q - planes[0] * S)               # the couple one plane cannot take
    else:
        z1, z2 = planes
        u2 = (z1 * S - Q) / (z2 - z1)
        corr = [-S - u2, u2]
        left = 0.0
    rho = float(spec.radius)
    corrections = []
    for k, (z, u) in enumerate(zip(planes, corr), start=1):
        size, a = _polar(u)
        corrections.append({"plane": k, "z": z, "m": size / rho, "r": rho, "mr": size, "angle": a})
    masses = [{"m": float(m.m), "r": float(m.r), "angle": float(m.angle), "z": float(m.z)} for m in spec.masses]
    return {"masses": masses, "imbalance": {"mr": mr, "angle": ang, "z": z_eq, "couple": couple},
            "method": "static" if len(planes) == 1 else "dynamic",
            "corrections": corrections, "couple_left": left}
