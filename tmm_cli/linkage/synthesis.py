"""Metric synthesis of lever mechanisms from the coefficient of mean speed increase K
(Artobolevsky, ch. "Sintez rychazhnykh mekhanizmov" (synthesis of linkages); Popov & Timofeev, the course-project
collection).

Pure functions. :func:`design` turns a ``synthesis`` section into the link lengths and
the generated ``mechanism`` section (a dict, as a task would write it); it raises
:class:`SynthesisImpossible` naming the requirement to relax. :func:`analyse` runs the
generated mechanism through the kinematics (extreme positions, transmission angle
over the cycle) and gives the ``synthesis`` results. :func:`generate` gives the task with
the generated mechanism (what `tmm validate` checks and every later stage reads).

K = (180 + theta)/(180 - theta); theta = 180 (K - 1)/(K + 1), the angle between the
crank's positions at the two extremes of the output, less 180 deg.

* slider-crank (central or offset, guide y = -e, B to the right of O): the extreme
  points B1 (folded, |OB1| = l - r) and B2 (extended, |OB2| = l + r), |B1B2| = H, seen
  from O under theta:  l^2 - r^2 = H e / sin(theta),  r^2 = H^2/4 - (H e/2) tan(theta/2).
  Given lambda = l/r instead of e:  r^2 = c H^2 / (4 (lambda^2 - 1 + c)), c = 1/sin^2(theta/2).
  Transmission angle: 90 deg less the angle between the rod and the guide; the least
  gamma_min = arccos((r + e)/l), crank perpendicular to the guide on the far side.
* crank-rocker: C1, C2 on the rocker's circle (angle psi at O1); O on a circle through
  C1, C2 whose chord is seen under theta, at `frame` from O1; |OC2| = b + a,
  |OC1| = b - a. One solution on each side of the chord; the larger least transmission
  angle (between the coupler and the rocker) wins. K = 1 (theta = 0): O on the line C1C2
  outside the chord, a = c sin(psi/2), b = sqrt(d^2 - c^2 cos^2(psi/2)), the one solution
  both sides tend to as K -> 1+.
* slotted lever: psi = theta, crank r = frame sin(theta/2) (the crank is perpendicular to
  the slotted link at its extremes). The shaper's ram, driven by a block C on the slotted
  link at the height h of its guide, moves 2 h tan(psi/2): h = H/(2 tan(psi/2)).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from ..errors import StageError
from ..messages import Message
from .spec import chebyshev_points

if TYPE_CHECKING:       # a type only: the context is imported where a range is made
    from .context import CrankRange

STAGE = "synthesis"
TYPES = ("slider_crank", "offset_slider_crank", "crank_rocker", "slotted_lever", "shaper", "function", "positions",
         "path")
OUTPUT = {"function": "rocker", "positions": "rocker", "path": "rocker", "slider_crank": "slider",
          "offset_slider_crank": "slider", "crank_rocker": "rocker",
          "slotted_lever": "rocker", "shaper": "ram"}


class SynthesisImpossible(StageError):
    """The requirements of the synthesis cannot be met (exit 3): the message names the
    field to relax."""

    def __init__(self, message: str):
        super().__init__(STAGE, message)

    def __eq__(self, other) -> bool:
        """Two are equal when they say the same (two syntheses of one task fail alike)."""
        return type(other) is type(self) and str(other) == str(self)

    __hash__ = StageError.__hash__


def theta_of_K(K: float) -> float:
    """The angle between the crank's extreme positions from the coefficient of the mean speed.

    Parameters
    ----------
    K : float
        The coefficient of the mean speed (K >= 1).

    Returns
    -------
    float
        theta = 180 (K - 1)/(K + 1), deg.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*; Popov & Timofeev, *Kursovoe
    proektirovanie po TMM*: the coefficient of the mean speed K = (180 + theta)/(180 - theta); docs/methods.md §1.
    """
    return 180.0 * (K - 1.0) / (K + 1.0)


def K_of_theta(theta: float) -> float:
    """The coefficient of the mean speed from the angle between the crank's extreme positions.

    Parameters
    ----------
    theta : float
        The angle, deg.

    Returns
    -------
    float
        K = (180 + theta)/(180 - theta).

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*; Popov & Timofeev, *Kursovoe
    proektirovanie po TMM*: the coefficient of the mean speed; docs/methods.md §1.
    """
    return (180.0 + theta) / (180.0 - theta)


@dataclass
class Design:
    """A lever synthesis: the link lengths and the `mechanism` section it generates."""

    type: str
    lengths: dict[str, float]
    mechanism: dict                      # the generated `mechanism` section
    output: str                          # the output link
    working: str                         # forward | backward: the slow stroke's sense
    solutions: list[dict] = field(default_factory=list)
    construction: dict = field(default_factory=dict)   # points of the drawing (m)
    crank_range: CrankRange | None = None   # the crank works over it only (None: full turns)


# ---------------------------------------------------------------- inputs
def _theta(sec) -> float:
    return float(sec.theta) if sec.theta is not None else theta_of_K(float(sec.K if sec.K is not None else 1.0))


def _mass(sec, name: str) -> dict:
    spec = (sec.links or {}).get(name)
    if spec is None:
        return {}
    out = {"mass": float(spec.mass), "J": float(spec.J)}
    if spec.com is not None:
        out["com"] = spec.com if isinstance(spec.com, str) else [float(spec.com[0]), float(spec.com[1])]
    return out


def _need_quick_return(theta: float, what: str) -> None:
    """That a type that needs a quick return (``what``: offset_slider_crank, slotted_lever) has
    0 < theta < 180 deg."""
    if not theta > 0.0:
        raise SynthesisImpossible(Message("synthesis.fail.quick_return", what=what, K=K_of_theta(theta),
                                          theta=theta))
    if theta >= 180.0:
        raise SynthesisImpossible(Message("synthesis.fail.theta_180", theta=theta))


# ---------------------------------------------------------------- slider-crank
def slider_crank_offset(H: float, theta: float, e: float) -> tuple[float, float]:
    """The offset slider-crank of a stroke, an angle theta and an offset.

    Parameters
    ----------
    H : float
        The slider's stroke, m.
    theta : float
        The angle between the crank's extreme positions, deg.
    e : float
        The offset, m.

    Returns
    -------
    tuple of float
        (r, l): the crank's and the rod's lengths, m.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*; Popov & Timofeev, *Kursovoe
    proektirovanie po TMM*: the synthesis of the offset slider-crank by the stroke and K; docs/methods.md §1.
    """
    th = math.radians(theta)
    r2 = H * H / 4.0 - H * e / 2.0 * math.tan(th / 2.0)
    if r2 <= 0.0:
        raise SynthesisImpossible(Message("synthesis.fail.offset_large", e=e, e_max=H / (2 * math.tan(th / 2))))
    l2 = r2 + H * e / math.sin(th)
    return math.sqrt(r2), math.sqrt(l2)


def slider_crank_lambda(H: float, theta: float, lam: float) -> tuple[float, float, float]:
    """The offset slider-crank of a stroke, an angle theta and a ratio l/r.

    Parameters
    ----------
    H : float
        The slider's stroke, m.
    theta : float
        The angle between the crank's extreme positions, deg.
    lam : float
        The ratio l/r of the rod to the crank.

    Returns
    -------
    tuple of float
        (r, l, e): the crank, the rod and the offset, m.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*; Popov & Timofeev, *Kursovoe
    proektirovanie po TMM*: the synthesis of the offset slider-crank by the stroke and K; docs/methods.md §1.
    """
    th = math.radians(theta)
    c = 1.0 / math.sin(th / 2.0) ** 2
    r = math.sqrt(c * H * H / (4.0 * (lam * lam - 1.0 + c)))
    e = (H * H / 4.0 - r * r) * 2.0 / (H * math.tan(th / 2.0))
    return r, lam * r, e


def _reach(H: float, r: float, l: float) -> float:
    """4 l r - H^2: >= 0 when the foot of the perpendicular from O to the guide lies
    outside B1B2 (the angle at B1 is not acute), so that the folded extreme B1 of the
    mechanism (B ahead of A along the guide) is the point of the construction. Below
    zero the equations hold for a triangle whose B1 lies behind the foot, and the
    mechanism built from those lengths has another stroke and K."""
    return 4.0 * l * r - H * H


def _e_reach(H: float, theta: float) -> float:
    """The largest offset (m) with _reach >= 0 (0 when none): a scan of (0, e_max) and
    Brent's method on the sign change."""
    from ..lazy import brentq

    e_max = H / (2.0 * math.tan(math.radians(theta) / 2.0))
    f = lambda e: _reach(H, *slider_crank_offset(H, theta, e))
    xs = [e_max * k / 2000.0 for k in range(1, 2000)]
    last = None
    for a, b in zip(xs, xs[1:]):
        if f(a) >= 0.0 > f(b):
            last = (a, b)
    if last is None:
        return e_max if f(xs[-1]) >= 0.0 else 0.0
    return brentq(f, *last, xtol=1e-16, rtol=1e-15, maxiter=500)


def _gamma_offset(H: float, theta: float, e: float) -> float:
    r, l = slider_crank_offset(H, theta, e)
    return math.degrees(math.acos(min(1.0, (r + e) / l)))


def slider_crank_gamma(H: float, theta: float, gamma: float) -> list[tuple[float, float, float]]:
    """Every offset slider-crank of a stroke, an angle theta and a least transmission angle.

    Parameters
    ----------
    H : float
        The slider's stroke, m.
    theta : float
        The angle between the crank's extreme positions, deg.
    gamma : float
        The least transmission angle, deg.

    Returns
    -------
    list of tuple of float
        Every (r, l, e) in m, the smaller offset first: gamma(e) rises from 0 (e -> 0) to a
        maximum and falls toward e_max = H/(2 tan(theta/2)).

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*; Popov & Timofeev, *Kursovoe
    proektirovanie po TMM*: the synthesis of the slider-crank by the stroke, K and the least transmission angle; docs/methods.md §1.
    """
    from ..lazy import brentq, minimize_scalar

    e_max = _e_reach(H, theta)
    if e_max <= 0.0:
        raise SynthesisImpossible(Message("synthesis.fail.offset_K", K=K_of_theta(theta)))
    lo, hi = e_max * 1e-12, e_max * (1.0 - 1e-12)
    best = minimize_scalar(lambda e: -_gamma_offset(H, theta, e), bounds=(lo, hi), method="bounded",
                           options={"xatol": e_max * 1e-13})
    e_star, g_star = float(best.x), -float(best.fun)
    if gamma > g_star:
        raise SynthesisImpossible(Message("synthesis.fail.offset_gamma", gamma=gamma, K=K_of_theta(theta),
                                          g_max=g_star, e=e_star))
    out = []
    for a, b in ((lo, e_star), (e_star, hi)):
        fa, fb = _gamma_offset(H, theta, a) - gamma, _gamma_offset(H, theta, b) - gamma
        if fa == 0.0:
            e = a
        elif fb == 0.0:
            e = b
        elif fa * fb < 0.0:
            e = brentq(lambda x: _gamma_offset(H, theta, x) - gamma, a, b, xtol=1e-16, rtol=1e-15, maxiter=500)
        else:
            continue
        r, l = slider_crank_offset(H, theta, e)
        if all(abs(e - q[2]) > 1e-12 * e_max for q in out):
            out.append((r, l, e))
    return out


def _slider_crank(sec, sign: float) -> Design:
    H = float(sec.H)
    solutions: list[dict] = []
    if sec.type == "slider_crank":
        theta, r = 0.0, H / 2.0
        lam = float(sec.lambda_) if sec.lambda_ is not None else 1.0 / math.cos(math.radians(sec.gamma_min))
        l, e = lam * r, 0.0
    else:
        theta = _theta(sec)
        _need_quick_return(theta, "offset_slider_crank")
        if sec.e is not None:
            e = float(sec.e)
            r, l = slider_crank_offset(H, theta, e)
        elif sec.lambda_ is not None:
            r, l, e = slider_crank_lambda(H, theta, float(sec.lambda_))
        else:
            roots = slider_crank_gamma(H, theta, float(sec.gamma_min))
            solutions = [{"crank": q[0], "rod": q[1], "offset": q[2], "gamma_min": float(sec.gamma_min),
                          "chosen": k == 0} for k, q in enumerate(roots)]
            r, l, e = roots[0]
        if _reach(H, r, l) < 0.0:
            if sec.e is not None:
                raise SynthesisImpossible(Message("synthesis.fail.offset_reach_e", e=e, e_max=_e_reach(H, theta)))
            raise SynthesisImpossible(Message("synthesis.fail.offset_reach_lambda", lam=float(sec.lambda_),
                                              lam_max=1.0 / math.tan(math.radians(theta) / 2.0) ** 2))
        # the crank then always turns fully: by the law of sines in O B1 B2,
        # H = (l + r) sin(theta)/sin(B1) >= (l + r) sin(theta), so l - r = H e/((l + r) sin(theta)) >= e
    yg = -sign * e
    xb = r + math.sqrt(l * l - yg * yg)
    mech = {"ground": {"O": [0.0, 0.0]},
            "links": {"crank": {"points": ["O", "A"], "length": r, **_mass(sec, "crank")},
                      "rod": {"points": ["A", "B"], "length": l, **_mass(sec, "rod")},
                      "slider": {"slider": "B", "guide": {"through": [0.0, yg], "angle": 0.0},
                                 **_mass(sec, "slider")}},
            "assembly": {"B": [xb, yg]}}
    x1, x2 = math.sqrt((l - r) ** 2 - e * e), math.sqrt((l + r) ** 2 - e * e)
    cons = {"O": [0.0, 0.0], "B1": [x1, yg], "B2": [x2, yg], "guide_y": yg,
            "circle": _circle3((0.0, 0.0), (x1, yg), (x2, yg))}
    return Design(sec.type, {"crank": r, "rod": l, "offset": e}, mech, "slider", "forward", solutions, cons)


def _circle3(p, q, s) -> dict | None:
    """The circle through three points: {centre, radius} (None when collinear)."""
    ax, ay = p
    bx, by = q
    cx, cy = s
    d = 2.0 * (ax * (by - cy) + bx * (cy - ay) + cx * (ay - by))
    if abs(d) < 1e-300:
        return None
    ux = ((ax * ax + ay * ay) * (by - cy) + (bx * bx + by * by) * (cy - ay) + (cx * cx + cy * cy) * (ay - by)) / d
    uy = ((ax * ax + ay * ay) * (cx - bx) + (bx * bx + by * by) * (ax - cx) + (cx * cx + cy * cy) * (bx - ax)) / d
    return {"centre": [ux, uy], "radius": math.hypot(ax - ux, ay - uy)}


# ---------------------------------------------------------------- crank-rocker
def _fourbar_gamma(a: float, b: float, c: float, d: float) -> float:
    """Least transmission angle (deg) of a crank-rocker: at the crank along the frame line."""
    out = 90.0
    for diag in (d - a, d + a):
        cm = (b * b + c * c - diag * diag) / (2.0 * b * c)
        mu = math.degrees(math.acos(max(-1.0, min(1.0, cm))))
        out = min(out, mu, 180.0 - mu)
    return out


def crank_rocker_solutions(psi: float, theta: float, c: float, d: float) -> list[dict]:
    """The crank-rocker four-bars of a swing, an angle theta, a rocker and a frame.

    Parameters
    ----------
    psi : float
        The rocker's swing, deg.
    theta : float
        The angle between the crank's extreme positions, deg.
    c : float
        The rocker's length, m.
    d : float
        The frame's length, m.

    Returns
    -------
    list of dict
        Each candidate's lengths a, b, c, d (m), its least transmission angle gamma_min (deg)
        and the points O, O1, C1, C2 (m) in the rocker's frame (O1 at the origin, the chord
        C1C2 horizontal above it).

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*; Popov & Timofeev, *Kursovoe
    proektirovanie po TMM*: the synthesis of the crank-rocker by the swing and K (the circle through C1 C2 seeing the chord at theta); docs/methods.md §1.
    """
    ps, th = math.radians(psi), math.radians(theta)
    h0, w = c * math.cos(ps / 2.0), c * math.sin(ps / 2.0)
    P, Q = (w, h0), (-w, h0)
    t = math.tan(th)
    out = []
    # the circle seeing the chord under theta: centre (0, yc), yc = h0 +- w/tan(theta), radius
    # R = w/sin(theta); the circle about O1 of radius d meets it at the height
    # y = (d^2 + yc^2 - R^2)/(2 yc) = h0 + (d^2 - c^2) tan(theta)/(2 (h0 tan(theta) +- w)),
    # written without yc and R (which grow without bound as theta -> 0): at theta = 0 (K = 1)
    # it is the chord's own line, y = h0, where both sides meet (the one solution "line")
    for side, sg in (("far", 1.0), ("near", -1.0)):
        den = 2.0 * (h0 * t + sg * w)
        if den == 0.0:
            continue
        y = h0 + (d * d - c * c) * t / den
        if y * y > d * d:
            continue
        x = math.sqrt(d * d - y * y)
        if t > 0.0:
            if not (y > h0 if side == "far" else y < h0):
                continue                  # on the other arc the chord is seen under 180 - theta (y = h0,
                                          # frame = rocker: O at C1 or C2 itself)
        elif side == "far" or not x > w:
            continue                      # K = 1: one solution; O between C1 and C2 would be theta = 180
        else:
            side = "line"                 # O on the line C1C2: the crank and coupler along one line at both
        dP, dQ = math.hypot(x - P[0], y - P[1]), math.hypot(x - Q[0], y - Q[1])
        C2, C1 = (P, Q) if dP > dQ else (Q, P)
        s2, s1 = max(dP, dQ), min(dP, dQ)
        a, b = (s2 - s1) / 2.0, (s2 + s1) / 2.0
        # both extremes on one side of the line O O1 (one assembly branch)
        cr = lambda p: x * p[1] - y * p[0]
        if cr(C1) * cr(C2) <= 0.0:
            continue
        L = sorted((a, b, c, d))
        if not (a == L[0] and L[0] + L[3] < L[1] + L[2]):
            continue
        out.append({"side": side, "crank": a, "coupler": b, "rocker": c, "frame": d,
                    "gamma_min": _fourbar_gamma(a, b, c, d), "O": [x, y], "C1": list(C1), "C2": list(C2)})
    return out


def _crank_rocker(sec, sign: float) -> Design:
    theta = _theta(sec)                    # theta >= 0: K >= 1 is checked with the task (exit 2)
    if theta >= 180.0:                     # a K so large that theta rounds to 180
        raise SynthesisImpossible(Message("synthesis.fail.theta_180", theta=theta))
    psi, c, d = float(sec.psi), float(sec.rocker), float(sec.frame)
    sols = crank_rocker_solutions(psi, theta, c, d)
    if not sols:
        raise SynthesisImpossible(Message("synthesis.fail.crank_rocker_none", psi=psi, K=K_of_theta(theta),
                                          rocker=c, frame=d))
    best = max(range(len(sols)), key=lambda k: sols[k]["gamma_min"])
    s = sols[best]
    a, b = s["crank"], s["coupler"]
    # to the task frame: O at the origin, O1 at [d, 0]
    ox, oy = s["O"]
    rho = math.atan2(-oy, -ox)
    cs, sn = math.cos(-rho), math.sin(-rho)

    def tf(p, flip=1.0):
        x, y = p[0] - ox, p[1] - oy
        return [cs * x - sn * y, flip * (sn * x + cs * y)]

    C1, C2 = tf(s["C1"]), tf(s["C2"])
    n2 = math.hypot(*C2)
    A2 = [a * C2[0] / n2, a * C2[1] / n2]
    orient = (d - A2[0]) * (C2[1] - A2[1]) + A2[1] * (C2[0] - A2[0])   # (O1 - A) x (B - A)
    if orient < 0.0:                       # the generated branch has B above the frame line at crank angle 0
        C1, C2 = [C1[0], -C1[1]], [C2[0], -C2[1]]
    phi_e = math.degrees(math.atan2(C2[1], C2[0]))
    phi_f = math.degrees(math.atan2(C1[1], C1[0])) + 180.0
    beta2 = math.atan2(C2[1], C2[0] - d)
    beta1 = math.atan2(C1[1], C1[0] - d)
    dbeta = (beta2 - beta1 + math.pi) % (2 * math.pi) - math.pi
    if theta > 0.0:
        f_to_e_slow = ((phi_e - phi_f) * sign) % 360.0 > 180.0
    else:
        # K = 1: both strokes take 180 deg and phi_e - phi_f is 180 up to rounding; the sense is
        # the limit K -> 1+ of the near side (the one K = 1 continues): there, in the rocker's
        # frame, OC2 is turned from OC1 by +theta, so phi_e - phi_f = 180 + theta (mod 360);
        # the flip above mirrors it
        f_to_e_slow = (sign > 0.0) == (orient >= 0.0)
    working = "forward" if (dbeta > 0) == f_to_e_slow else "backward"
    bx = a + (d - a) / 2.0 + (b * b - c * c) / (2.0 * (d - a))     # B at crank angle 0, above the frame
    by = math.sqrt(max(b * b - (bx - a) ** 2, 0.0))
    mech = {"ground": {"O": [0.0, 0.0], "O1": [d, 0.0]},
            "links": {"crank": {"points": ["O", "A"], "length": a, **_mass(sec, "crank")},
                      "coupler": {"points": ["A", "B"], "length": b, **_mass(sec, "coupler")},
                      "rocker": {"points": ["O1", "B"], "length": c, **_mass(sec, "rocker")}},
            "assembly": {"B": [bx, by]}}
    solutions = [{k: v for k, v in q.items() if k in ("side", "crank", "coupler", "rocker", "frame", "gamma_min")}
                 | {"chosen": k == best} for k, q in enumerate(sols)]
    cons = {"O": [0.0, 0.0], "O1": [d, 0.0], "C1": C1, "C2": C2,
            "circle": _circle3((0.0, 0.0), C1, C2) if theta > 0.0 else None}   # K = 1: O on the line C1C2
    return Design("crank_rocker", {"crank": a, "coupler": b, "rocker": c, "frame": d}, mech, "rocker",
                  working, solutions, cons)


# ---------------------------------------------------------------- slotted lever, shaper
def _slotted(sec, sign: float) -> Design:
    theta = _theta(sec)
    _need_quick_return(theta, "slotted_lever")
    f = float(sec.frame)
    r = f * math.sin(math.radians(theta) / 2.0)
    m = sign
    half = math.radians(theta) / 2.0
    lengths = {"crank": r}
    if sec.type == "shaper":
        H = float(sec.H)
        h_need = H / (2.0 * math.tan(half))
        L = float(sec.rocker) if sec.rocker is not None else H / (2.0 * math.sin(half))
        h = float(sec.guide_height) if sec.guide_height is not None else h_need
        if abs(h - h_need) > 1e-9 * max(h, h_need):
            raise SynthesisImpossible(Message("synthesis.fail.guide_height", theta=theta, h=h,
                                              stroke=2 * h * math.tan(half), H=H, h_need=h_need))
        if L < h / math.cos(half) * (1.0 - 1e-12):
            raise SynthesisImpossible(Message("synthesis.fail.slotted_guide", L=L, need=h / math.cos(half)))
    else:
        L = float(sec.rocker) if sec.rocker is not None else 1.5 * (f + r)
    if L < (f + r) * (1.0 - 1e-12):
        raise SynthesisImpossible(Message("synthesis.fail.slotted_short_shaper" if sec.type == "shaper"
                                          else "synthesis.fail.slotted_short", L=L, reach=f + r))
    lengths.update({"rocker": L, "frame": f})
    links = {"crank": {"points": ["O", "A"], "length": r, **_mass(sec, "crank")},
             "block": {"slider": "A", "guide": {"link": "rocker"}, **_mass(sec, "block")},
             "rocker": {"points": ["O1", "B"], "length": L, **_mass(sec, "rocker")}}
    assembly = {"A": [r, 0.0]}
    # the block at the extremes: the link O1A tangent to the crank circle, A on O1's side of O
    # (A . O1 = r^2, so A_y = -m r sin(theta/2))
    A1 = [-r * math.cos(half), -m * r * math.sin(half)]
    A2 = [r * math.cos(half), -m * r * math.sin(half)]
    cons = {"O": [0.0, 0.0], "O1": [0.0, -m * f], "A1": A1, "A2": A2,
            "B1": [-L * math.sin(half), m * (L * math.cos(half) - f)],
            "B2": [L * math.sin(half), m * (L * math.cos(half) - f)]}
    output, working = "rocker", ("forward" if sign > 0 else "backward")
    if sec.type == "shaper":
        lengths["guide_height"] = h
        links["blockC"] = {"slider": "C", "guide": {"link": "rocker"}, **_mass(sec, "blockC")}
        links["ram"] = {"slider": "C", "guide": {"through": [0.0, m * (h - f)], "angle": 0.0}, **_mass(sec, "ram")}
        assembly["C"] = [r * h / f, m * (h - f)]
        cons["guide_y"] = m * (h - f)
        cons["C1"] = [-h * math.tan(half), m * (h - f)]
        cons["C2"] = [h * math.tan(half), m * (h - f)]
        output, working = "ram", "backward"
    mech = {"ground": {"O": [0.0, 0.0], "O1": [0.0, -m * f]}, "links": links, "assembly": assembly}
    return Design(sec.type, lengths, mech, output, working, [], cons)


def design(sec, sign: float) -> Design:
    """The link lengths and the generated mechanism of a ``synthesis`` section for the
    drive's sense of rotation ``sign`` (+1 ccw, -1 cw; ``DriveSection.sign``).

    Parameters
    ----------
    sec : SynthesisSection
        The task's ``synthesis``: the type and the course's conditions (H in m, K or
        theta in deg, lambda, e in m, gamma_min in deg, psi in deg...).
    sign : float
        Sense of rotation of the crank.

    Returns
    -------
    Design
        The link lengths (m), the generated ``mechanism`` section, the output link and its
        working sense, the alternative solutions and the construction for the report.

    Raises
    ------
    SynthesisImpossible
        When no mechanism of the type meets the conditions.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: synthesis of lever mechanisms by
    the coefficient of the mean speed K = (180 + theta)/(180 - theta); docs/methods.md.
    """
    if sec.type == "function":
        return _function(sec)
    if sec.type in ("positions", "path"):
        from importlib import import_module
        return import_module(f".synthesis_{sec.type}", __package__).design(sec, sign)
    if sec.type in ("slider_crank", "offset_slider_crank"):
        return _slider_crank(sec, sign)
    if sec.type == "crank_rocker":
        return _crank_rocker(sec, sign)
    return _slotted(sec, sign)


def generate(task):
    """The synthesis stage's first step: the design of the task's ``synthesis`` section and
    the task with the ``mechanism`` it generates (and the defaults of positions.output and
    positions.working: the output link and its slow stroke), which every later check and
    stage reads.  The task given is left as it is; generating from a generated task gives
    it again.

    Returns
    -------
    (Task, Design)

    Raises
    ------
    SynthesisImpossible
        When no mechanism of the type meets the conditions (exit 3).
    """
    from ..schemacache import validator
    from .spec import MechanismSection, PositionsSection

    d = design(task.synthesis, task.drive.sign)
    mechanism = validator(MechanismSection).validate_python(d.mechanism)     # MechanismSection.model_validate
    pos = task.positions if task.positions is not None else validator(PositionsSection).validate_python({})
    given = set(pos.model_fields_set)
    upd = {k: v for k, v in (("output", d.output), ("working", d.working)) if k not in given}
    if upd:
        pos = pos.model_copy(update=upd)
        pos.__pydantic_fields_set__ = given       # still the defaults: a second generation sets them again
    return task.model_copy(update={"mechanism": mechanism, "positions": pos}), d


# ---------------------------------------------------------------- function generation (Freudenstein)
def function_angles(g: dict, x):
    """The ideal crank and rocker angles of a function generator.

    Parameters
    ----------
    g : dict
        {function, x: [x0, x1], input: [start, range], output: [start, range]}: the function
        y(x) and the angles' ranges, deg.
    x : float or array_like
        Values of the argument.

    Returns
    -------
    tuple of numpy.ndarray
        phi(x) and psi(y(x)), deg, each linear in x and in y over its range.
    """
    import numpy as np

    from ..expr import compile_expr
    fx = compile_expr(g["function"])

    def f(t):                                   # a constant expression gives one number: one per x
        return np.broadcast_to(np.asarray(fx(t), float), np.shape(t))
    x0, x1 = g["x"]
    y0, y1 = (float(v) for v in f(np.array([x0, x1])))
    x = np.asarray(x, float)
    phi = g["input"][0] + g["input"][1] * (x - x0) / (x1 - x0)
    with np.errstate(all="ignore"):
        psi = g["output"][0] + g["output"][1] * (f(x) - y0) / (y1 - y0)
    return phi, psi, (y0, y1)


def _generator(sec) -> dict:
    return {"function": sec.function_, "x": [float(sec.x[0]), float(sec.x[1])],
            "input": [float(sec.input.start), float(sec.input.range)],
            "output": [float(sec.output.start), float(sec.output.range)]}


def freudenstein(phi_deg, psi_deg):
    """Freudenstein's coefficients through the precision points.

    Parameters
    ----------
    phi_deg, psi_deg : array_like
        The crank's and the rocker's angles at the precision points, deg.

    Returns
    -------
    tuple of float
        K1, K2, K3 of K1 cos psi - K2 cos phi + K3 = cos(phi - psi) (three points: exactly;
        more: least squares).

    References
    ----------
    Freudenstein's equation of the four-bar; Artobolevsky, *Theory of Mechanisms and
    Machines*: the synthesis of a function generator by precision points.
    """
    import numpy as np
    p, q = np.radians(phi_deg), np.radians(psi_deg)
    A = np.column_stack([np.cos(q), -np.cos(p), np.ones_like(p)])
    b = np.cos(p - q)
    if len(p) == 3:
        return np.linalg.solve(A, b)
    return np.linalg.lstsq(A, b, rcond=None)[0]


def _closure_hint(a: float, b: float, c: float, d: float, B1: list, turn: bool) -> list:
    """The assembly hint of B for the closure of the precision points (the triangle A B O1
    turned counter-clockwise when ``turn``). Hints refer to crank angle 0 (or, where the
    dyad does not assemble there, the first angle of a 0.25-deg scan that does: the
    solver's rule, docs/task-file.md ``assembly``); B1 (the first precision pose) is kept
    where the closure nearest it there is the right one, else B of that closure there."""
    for k in range(1440):
        f = math.radians(0.25 * k)
        ax, ay = a * math.cos(f), a * math.sin(f)
        L = math.hypot(d - ax, -ay)
        if abs(b - c) <= L <= b + c and L > 0.0:
            break
    else:
        return B1
    ux, uy = (d - ax) / L, -ay / L
    k_ = (b * b - c * c + L * L) / (2.0 * L)
    h = math.sqrt(max(b * b - k_ * k_, 0.0))
    cands = [[ax + k_ * ux - sg * h * uy, ay + k_ * uy + sg * h * ux] for sg in (1.0, -1.0)]

    def ccw(B):
        return (B[0] - ax) * (-(B[1])) - (B[1] - ay) * (d - B[0]) > 0.0     # (B - A) x (O1 - B)
    near = min(cands, key=lambda B: (B[0] - B1[0]) ** 2 + (B[1] - B1[1]) ** 2)
    if ccw(near) == turn:
        return B1
    return next(B for B in cands if ccw(B) == turn)


def _function(sec) -> Design:
    """A four-bar whose rocker angle follows y(x) while the crank angle follows x (Freudenstein's
    equation at Chebyshev precision points; d = frame, a = d/K1, c = d/K2,
    b^2 = a^2 + c^2 + d^2 - 2 a c K3)."""
    import numpy as np
    g = _generator(sec)
    x0, x1 = g["x"]
    n = int(sec.points or 3)
    xs = chebyshev_points(x0, x1, n)
    phi, psi, (y0, y1) = function_angles(g, xs)
    if not (np.all(np.isfinite(phi)) and np.all(np.isfinite(psi))) or y0 == y1:
        raise SynthesisImpossible(Message("synthesis.fail.function_range"))
    d = float(sec.frame)
    try:
        K1, K2, K3 = (float(v) for v in freudenstein(phi, psi))
    except np.linalg.LinAlgError:
        raise SynthesisImpossible(Message("synthesis.fail.function_points")) from None
    a, c = d / K1 if K1 else math.inf, d / K2 if K2 else math.inf
    b2 = a * a + c * c + d * d - 2 * a * c * K3
    if not (math.isfinite(a) and math.isfinite(c)) or b2 <= 0:
        # the coefficient that gave it: crank = d/K1, rocker = d/K2, coupler^2 through K3
        bad = ("crank", "K1", K1) if not math.isfinite(a) else \
            ("rocker", "K2", K2) if not math.isfinite(c) else ("coupler", "K3", K3)
        raise SynthesisImpossible(Message("synthesis.fail.function_lengths", what=bad[0], K=bad[1], Kv=bad[2],
                                          a=a, c=c, b2=b2))
    if a < 0 or c < 0:
        # a negative length is the link pointing the other way: psi -> psi + 180 deg turns
        # (K1, K2, K3) into (K1, -K2, -K3), phi -> phi + 180 deg into (-K1, K2, -K3), b^2 the same:
        # the same four-bar with that link's angle scale turned by 180 deg (kept an error: the
        # angles are the task's)
        turn = [name for name, length in (("input", a), ("output", c)) if length < 0]
        fix = [f"`{name}.start: {(g[name][0] + 180.0) % 360.0:.10g}`" for name in turn]
        what = "both" if len(turn) == 2 else ("crank" if turn == ["input"] else "rocker")
        raise SynthesisImpossible(Message("synthesis.fail.function_turn", what=what, a=a, c=c, crank=abs(a),
                                          coupler=math.sqrt(b2), rocker=abs(c), fix=fix))
    b = math.sqrt(b2)
    # Freudenstein's equation holds for both assemblies of the dyad A B O1: the linkage passes
    # only the points on the first one's side (the triangle A B O1 turned the same way)
    turn = []
    for f, q in zip(np.radians(phi), np.radians(psi)):
        ab = (d + c * math.cos(q) - a * math.cos(f), c * math.sin(q) - a * math.sin(f))    # B - A
        bo = (-c * math.cos(q), -c * math.sin(q))                                          # O1 - B
        turn.append(ab[0] * bo[1] - ab[1] * bo[0] > 0.0)
    other = [x for x, t in zip(xs, turn) if t != turn[0]]
    if other:
        raise SynthesisImpossible(Message("synthesis.fail.function_branch", x=float(other[0])))
    # B in the first precision pose: from O1 along psi_1; A from O along phi_1
    B1 = [d + c * math.cos(math.radians(psi[0])), c * math.sin(math.radians(psi[0]))]
    B1 = _closure_hint(a, b, c, d, B1, turn[0])
    mech = {"ground": {"O": [0.0, 0.0], "O1": [d, 0.0]},
            "links": {"crank": {"points": ["O", "A"], "length": a, **_mass(sec, "crank")},
                      "coupler": {"points": ["A", "B"], "length": b, **_mass(sec, "coupler")},
                      "rocker": {"points": ["O1", "B"], "length": c, **_mass(sec, "rocker")}},
            "assembly": {"B": B1}}
    cons = {"precision_points": [{"x": float(x), "phi": float(f), "psi": float(q)} for x, f, q in zip(xs, phi, psi)],
            "K": [K1, K2, K3], "y": [y0, y1], "generator": g}
    kind = grashof(a, b, c, d)
    # a crank-rocker's crank turns fully: the course's cycle (12 positions over the turn,
    # the extremes, K, a flywheel); any other generator works over its input range only
    over = None
    if kind != "crank-rocker":
        from .context import CrankRange
        over = CrankRange(start=g["input"][0], span=g["input"][1], x=(x0, x1), kind=kind)
    return Design("function", {"crank": a, "coupler": b, "rocker": c, "frame": d}, mech, "rocker", "forward", [],
                  cons, crank_range=over)


def check_range(mech, over) -> list:
    """That a generated linkage assembles over its crank range (a function generator
    whose crank does not turn fully).

    Parameters
    ----------
    mech : Mechanism
        The generated linkage.
    over : CrankRange
        The crank's range (``Design.crank_range``).

    Returns
    -------
    list
        The kinematics' warnings over the range (change points).

    Raises
    ------
    SynthesisImpossible
        At the first crank angle from the range's start where the linkage does not
        assemble, naming it, the argument x there and what to change (exit 3).
    """
    import numpy as np

    from .kinematics import solve
    n = max(2, int(math.ceil(abs(over.span) / 0.25)) + 1)
    phi = over.angles(n)
    try:
        kin = solve(mech, np.mod(phi, 360.0))
    except StageError:
        pass
    else:
        return list(kin.warnings)

    def assembles(f: float) -> bool:
        try:
            solve(mech, np.array([f % 360.0]))
        except StageError:
            return False
        return True
    k = next(i for i, f in enumerate(phi) if not assembles(float(f)))
    at = float(phi[k])
    if k > 0:               # the edge between the last crank angle that assembles and the first that does not
        good = float(phi[k - 1])
        for _ in range(60):
            if abs(at - good) <= 1e-7:
                break
            mid = 0.5 * (good + at)
            good, at = (mid, at) if assembles(mid) else (good, mid)
    raise SynthesisImpossible(Message("synthesis.fail.function_assembly", phi=at, x=over.x_at(at),
                                      start=float(over.start), end=float(over.start + over.span)))


def grashof(a: float, b: float, c: float, d: float) -> str:
    """The kind of a four-bar by Grashof's condition.

    Parameters
    ----------
    a, b, c, d : float
        The crank, the coupler, the rocker and the frame, m.

    Returns
    -------
    str
        ``crank-rocker``, ``double-crank``, ``double-rocker`` or ``change-point``.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: Grashof's condition of a crank.
    """
    s, *mid, long_ = sorted((a, b, c, d))
    lhs, rhs = s + long_, sum(mid)
    if abs(lhs - rhs) <= 1e-12 * long_:
        return "change-point"
    if lhs > rhs:
        return "double-rocker"
    if s == d:
        return "double-crank"
    return "crank-rocker" if s == a else "double-rocker"


def analyse_function(linkage, d: Design, least: tuple[float, float]) -> dict:
    """The function generator's structural error.

    Parameters
    ----------
    linkage : Linkage
        The generated linkage.
    d : Design
        Its design (the function, the ranges, the precision points).
    least : tuple of float
        The transmission stage's least (:func:`least_of`): the answer for a generator that works
        over its input range only (``d.crank_range``: the stage searched that range); a
        crank-rocker's is its full turn's, and the range's is sought here.

    Returns
    -------
    dict
        The lengths (m), Freudenstein's K, the precision points with the generated rocker
        angle there (deg), the structural error (the largest |psi - psi_ideal|, deg, and its
        x) with its curve over the range of x (the kinematics at 401 crank angles), Grashof's
        kind, and the least transmission angle over the input range (deg) with its crank angle
        (deg): the generator's working range, where a crank-rocker's full-turn least (the
        transmission stage's) may lie outside it.
    """
    import numpy as np

    from .kinematics import solve
    g = d.construction["generator"]
    x0, x1 = g["x"]
    xs = np.linspace(x0, x1, 401)
    def error(phi_deg, ideal):
        """The analysed rocker angle's deviation from the ideal psi (deg, within a half turn) at
        the crank angles phi_deg: the generated psi is ideal + error, in the ideal's turn."""
        kn = solve(linkage.mechanism, np.mod(phi_deg, 360.0), linkage.drive.omega)
        P, B = kn.pos["O1"], kn.pos["B"]
        got = np.degrees(np.arctan2(B[:, 1] - P[:, 1], B[:, 0] - P[:, 0]))
        return (got - ideal + 180.0) % 360.0 - 180.0

    phi, psi, _ = function_angles(g, xs)
    err = error(phi, psi)
    k = int(np.argmax(np.abs(err)))
    pts = d.construction["precision_points"]
    # written in the turn of the ideal psi (308.42 beside 308.42, not -51.58): as the positions' are
    ideal_p = np.array([p["psi"] for p in pts], float)
    got_p = ideal_p + error(np.array([p["phi"] for p in pts], float), ideal_p)
    L = d.lengths
    serr = {"max": float(abs(err[k])), "at_x": float(xs[k])}
    gmin, gphi = least if d.crank_range is not None else least_transmission(linkage, *g["input"])
    if d.crank_range is not None:
        # the reported positions spread over the input range: x, the ideal and the generated psi there
        xg = x0 + (x1 - x0) * np.linspace(0.0, 1.0, int(linkage.positions.count))
        phg, psg, _ = function_angles(g, xg)
        eg = error(phg, psg)
        serr["positions"] = [{"index": i, "x": float(a), "phi": float(f), "psi": float(q),
                              "psi_generated": float(q + e), "error": float(e)}
                             for i, (a, f, q, e) in enumerate(zip(xg, phg, psg, eg))]
    return {"type": "function", "lengths": dict(L), "K": list(d.construction["K"]),
            "precision_points": [dict(p, psi_generated=float(g)) for p, g in zip(pts, got_p)],
            "structural_error": serr,
            "error_curve": {"x": xs.tolist(), "error": err.tolist()},
            "grashof": grashof(L["crank"], L["coupler"], L["rocker"], L["frame"]),
            "mechanism": d.mechanism, "output": d.output, "function": g["function"],
            "x": [x0, x1], "y": list(d.construction["y"]), "working": d.working,
            "gamma_min": gmin, "gamma_min_phi": gphi}


# ---------------------------------------------------------------- analysis of the generated mechanism
def least_of(rows: list[dict]) -> tuple[float, float]:
    """(gamma_min, deg; its crank angle, deg) of the transmission stage's rows
    (:func:`tmm_cli.linkage.transmission.analyze`): the least of every dyad's least, as
    :func:`least_transmission` finds it over the same crank angles (90 deg at 0 without a dyad)."""
    return min(((float(r["gamma_min"]), float(r["phi"])) for r in rows), default=(90.0, 0.0))


def least_transmission(linkage, start: float, span: float) -> tuple[float, float]:
    """The least transmission angle of a generated mechanism over the crank angles ``start`` ..
    ``start + span`` (a crank-rocker function generator's input range; over the cycle the
    transmission stage has found it: :func:`least_of`).

    Parameters
    ----------
    linkage : Linkage
        The generated mechanism and its Assur groups.
    start, span : float
        The crank angles to search, deg (``span`` signed).

    Returns
    -------
    tuple of float
        (gamma_min, deg; the crank angle where it is, deg): the least of its dyads'
        (:func:`tmm_cli.linkage.transmission.least`: the slider-crank's rod and guide, the
        crank-rocker's coupler and rocker, the shaper's slot and ram, the slotted lever's block
        and slot: 90, the slot passing through the lever's pivot).

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*; Popov & Timofeev, *Kursovoe
    proektirovanie po TMM*: the transmission angle; docs/methods.md §1.
    """
    from . import transmission
    ds = transmission.dyads(linkage.mechanism, linkage.structure.groups)
    if not ds:
        return 90.0, float(start) % 360.0
    return min(transmission.least(linkage.mechanism, ds, float(start), float(span)))


def analyse(linkage, d: Design, least: tuple[float, float]) -> dict:
    """The synthesis stage: the generated mechanism analysed.

    Parameters
    ----------
    linkage : Linkage
        The mechanism built from ``d.mechanism`` and the drive's sense of rotation.
    d : Design
        The design of the task's ``synthesis`` section (:func:`generate`).
    least : tuple of float
        (gamma_min, deg; its crank angle, deg): the transmission stage's least over the
        linkage's cycle (:func:`least_of` of its rows): one search for both.

    Returns
    -------
    dict
        results.json ``synthesis``: the lengths (m), the stroke H (m) or swing psi (deg),
        K, theta (deg), the least transmission angle gamma_min (deg) and where it occurs,
        the extreme positions (deg), the construction and gamma(phi) for the report.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: extreme positions, the coefficient
    of the mean speed, the transmission angle; docs/methods.md.
    """
    if d.type == "function":
        return analyse_function(linkage, d, least)
    if d.type in ("positions", "path"):
        from importlib import import_module
        return import_module(f".synthesis_{d.type}", __package__).analyse(linkage, d, least)
    import numpy as np

    from .kinematics import find_positions, solve
    from ..schemacache import validator
    from .spec import PositionsSection

    mech, sign = linkage.mechanism, linkage.drive.sign
    # PositionsSection(output=..., working=...) by the cached validator (tmm_cli.schemacache)
    pos = find_positions(mech, validator(PositionsSection).validate_python({"output": d.output, "working": d.working}),
                         sign)
    H = psi = None
    if pos.output_kind == "slider":
        H = float(pos.H)
        if d.type == "shaper":
            psi = float(find_positions(mech, validator(PositionsSection).validate_python({"output": "rocker"}),
                                       sign).H)
    else:
        psi = float(pos.H)
    gmin, gphi = least
    curve = np.arange(0.0, 360.0 + 1e-9, 5.0)
    phis = np.mod(pos.phi0 + sign * curve, 360.0)
    from . import transmission
    ds = transmission.dyads(mech, linkage.structure.groups)
    kin = solve(mech, phis)
    gam = (np.min([transmission.gamma(dy, kin) for dy in ds], axis=0) if ds else np.full(len(phis), 90.0))
    return {"type": d.type, "lengths": dict(d.lengths), "H": H, "K": float(pos.K), "theta": float(pos.theta),
            "psi": psi, "gamma_min": gmin, "working": d.working, "solutions": list(d.solutions),
            "mechanism": d.mechanism, "output": d.output, "gamma_min_phi": gphi,
            "extreme": [float(x) for x in pos.extreme],
            "construction": d.construction,
            "transmission": {"turn": curve.tolist(), "phi": phis.tolist(), "gamma": np.asarray(gam).tolist()}}
