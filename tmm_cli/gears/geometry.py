"""Geometry of an external spur involute pair cut by a rack (GOST 16532-70, rack GOST 13755-81).

All formulas are the standard ones of GOST 16532-70 as given in Popov & Timofeev,
"Kursovoe proektirovanie po TMM" (2002) and Frolov (ed.), "Teoriya mekhanizmov i mashin"
(ch. on involute gearing); symbols as there (m module, z teeth, x shift coefficients,
alpha profile angle of the rack, ha* addendum, c* clearance coefficients):

  inv aw = inv a + 2 (x1 + x2) tan a / (z1 + z2)          mesh (working pressure) angle
  a = m (z1 + z2) / 2,  aw = a cos a / cos aw              reference / working centre distance
  y = (aw - a) / m,  dy = x1 + x2 - y                      centre-distance and tip-reduction coeff.
  r = m z / 2,  rb = r cos a,  rw = rb / cos aw           reference, base, pitch (working) radii
  rf = r - (ha + c - x) m,  ra = r + (ha + x - dy) m       root and tip radii;  h = ra - rf
  p = pi m,  pb = p cos a                                  pitch and base pitch
  s = m (pi/2 + 2 x tan a),  e = p - s                     tooth / space on the reference circle
  sb = 2 rb (s / (2 r) + inv a)                           tooth on the base circle
  sa = 2 ra (s / (2 r) + inv a - inv aa),  cos aa = rb/ra  tooth on the tip circle
  eps = [z1 (tan aa1 - tan aw) + z2 (tan aa2 - tan aw)] / (2 pi) = B1B2 / pb

Line of action N1N2 = aw sin aw (N1, N2 the tangency points with the base circles);
its active part B1B2: B2 (where the tip circle of wheel 1 cuts it) at N1B2 = rb1 tan aa1,
B1 at N2B1 = rb2 tan aa2.  The lowest active point of wheel 1 is B1 (radius of curvature
rho_p1 = N1N2 - N2B1), of wheel 2 B2 (rho_p2 = N1N2 - N1B2).

Boundary point of the involute (where the rack's straight edge ends, its fillet of radius
rho_f begins): rho_l = r sin a - h_l / sin a with h_l = (ha + c - x) m - rho_f (1 - sin a)
(= (ha - x) m for the full fillet rho_f = c m / (1 - sin a), 0.38 m for the standard rack).

Checks (True = defect present):
  undercut      x < x_min, x_min = ha (z_min - z) / z_min with the course value of z_min:
                2 ha / sin^2 a rounded to an integer as the textbooks do (17 for a = 20 deg,
                ha = 1; 14 for ha = 0.8), docs/methods.md §6.  The exact limit
                x_min_exact = (h_l / m) - z sin^2 a / 2 is reported beside it.
  sharpening    sa < k m, k = 0.25 by default (docs/methods.md §6: 0.25..0.3 m; 0.4 m is the usual
                value for case-hardened teeth: pass ``sa_min=0.4``).
  contact ratio eps < 1.2 (course minimum); eps < 1.1 (absolute minimum) adds a second warning.
  interference  the tip of one wheel reaches the other below the start of its involute
                (rho_p < rho_l, with rho_l of the real, possibly undercut, tooth; B beyond N
                is included since then rho_p < 0 <= rho_l).

Specific sliding (Popov & Timofeev): with X the distance of the contact point from N1 along
N1N2 = g, rho1 = X, rho2 = g - X, u21 = z1/z2:
  lambda1 = 1 - rho2 u21 / rho1,  lambda2 = 1 - rho1 / (rho2 u21).
"""
from __future__ import annotations

import math

import numpy as np

from .involute import ainv, inv

COURSE_EPS = 1.2
ABSOLUTE_EPS = 1.1
DEFAULT_SA_MIN = 0.25


def rack_fillet(alpha_rad: float, c: float) -> float:
    """Largest fillet radius coefficient of the rack's tip.

    Parameters
    ----------
    alpha_rad : float
        The rack's profile angle, rad.
    c : float
        The clearance coefficient c*.

    Returns
    -------
    float
        c*/(1 - sin alpha): 0.38 for the rack of GOST 13755 (alpha = 20 deg, c* = 0.25).
    """
    return c / (1.0 - math.sin(alpha_rad))


def z_min_course(alpha_rad: float, ha: float) -> int:
    """Least tooth number of a wheel without undercut, cut by the rack without shift.

    Parameters
    ----------
    alpha_rad : float
        The rack's profile angle, rad.
    ha : float
        The addendum coefficient ha*.

    Returns
    -------
    int
        2 ha / sin^2 alpha rounded as the textbooks round it (17 at 20 deg, ha* = 1).

    References
    ----------
    GOST 16532-70; Popov & Timofeev, *Kursovoe proektirovanie po TMM*; Frolov (ed.), *Teoriya
    mekhanizmov i mashin*: the least tooth number without undercut; docs/methods.md §6.
    """
    return int(round(2.0 * ha / math.sin(alpha_rad) ** 2))


def x_min_course(z, alpha_rad: float, ha: float):
    """Least profile shift without undercut, the course's formula.

    Parameters
    ----------
    z : int or array_like
        Tooth number(s).
    alpha_rad : float
        The rack's profile angle, rad.
    ha : float
        The addendum coefficient ha*.

    Returns
    -------
    float or numpy.ndarray
        ha (z_min - z) / z_min (ha (17 - z)/17 at 20 deg).

    References
    ----------
    GOST 16532-70; Popov & Timofeev, *Kursovoe proektirovanie po TMM*; Frolov (ed.), *Teoriya
    mekhanizmov i mashin*: the least shift without undercut; docs/methods.md §6.
    """
    zm = z_min_course(alpha_rad, ha)
    return ha * (zm - np.asarray(z, dtype=float)) / zm


def pair(m, z1, z2, x1, x2, alpha_deg=20.0, ha=1.0, c=0.25, rho_f=None):
    """All closed-form quantities of an external spur pair cut by the rack.

    Parameters
    ----------
    m : float or array_like
        Module, m.
    z1, z2 : int or array_like
        Tooth numbers.
    x1, x2 : float or array_like
        Profile shift coefficients.
    alpha_deg : float
        The rack's profile angle, deg.
    ha, c : float
        The addendum and clearance coefficients.
    rho_f : float or None
        The rack's tip fillet coefficient (None: the full fillet c/(1 - sin alpha)).

    Returns
    -------
    dict
        Arrays (or floats), broadcast over the arguments: the radii r, rb, rw, ra, rf (m),
        the centre distances a, aw (m), alpha_w and inv alpha_w (rad), the shift and
        reduction coefficients y, dy, the thicknesses s, sa, sb, sw and spaces e (m), the
        pitches p, pb (m), the line of action N1N2, N1B1, N1P, N1B2, its active part ga (m),
        the contact ratio eps (a pointed tooth's: :func:`pointed_tips`), the lowest active
        points rho_p (m), the least shifts x_min, x_min_exact and ``valid``; the wheels'
        entries end in 1 and 2.  Entries
        where the working angle does not exist (inv alpha_w <= 0) are NaN.

    References
    ----------
    GOST 16532-70; Popov & Timofeev, *Kursovoe proektirovanie po TMM*; Frolov (ed.), *Teoriya
    mekhanizmov i mashin*: the geometry of the pair: inv alpha_w = inv alpha + 2 (x1 + x2) tan
    alpha / (z1 + z2) and the rest; docs/methods.md §6.
    """
    al = math.radians(alpha_deg)
    if rho_f is None:
        rho_f = rack_fillet(al, c)
    z1 = np.asarray(z1, float)
    z2 = np.asarray(z2, float)
    x1 = np.asarray(x1, float)
    x2 = np.asarray(x2, float)
    xs = x1 + x2
    inv_aw = inv(al) + 2.0 * xs * math.tan(al) / (z1 + z2)
    valid = np.asarray(inv_aw > 0)
    aw_ang = ainv(np.where(valid, inv_aw, inv(al)))
    aw_ang = np.where(valid, aw_ang, np.nan)
    a = m * (z1 + z2) / 2.0
    aw = a * math.cos(al) / np.cos(aw_ang)
    y = (aw - a) / m
    dy = xs - y
    out = {"valid": valid, "alpha": al, "inv_alpha_w": inv_aw, "alpha_w": aw_ang, "a": a,
           "aw": aw, "y": y, "dy": dy, "p": math.pi * m, "pb": math.pi * m * math.cos(al)}
    tan_aw = np.tan(aw_ang)
    for i, (z, x) in enumerate(((z1, x1), (z2, x2)), start=1):
        r = m * z / 2.0
        rb = r * math.cos(al)
        rw = rb / np.cos(aw_ang)
        rf = r - (ha + c - x) * m
        ra = r + (ha + x - dy) * m
        s = m * (math.pi / 2.0 + 2.0 * x * math.tan(al))
        psi0 = s / (2.0 * r) + inv(al)                    # half angle of the tooth at rb
        aa = np.arccos(np.clip(rb / ra, -1.0, 1.0))
        sa = 2.0 * ra * (psi0 - inv(aa))
        sw = 2.0 * rw * (psi0 - inv(np.where(valid, aw_ang, al)))
        h_l = (ha + c - x) * m - rho_f * m * (1.0 - math.sin(al))
        rho_l = r * math.sin(al) - h_l / math.sin(al)
        out.update({f"r{i}": r, f"rb{i}": rb, f"rw{i}": rw, f"rf{i}": rf, f"ra{i}": ra,
                    f"h{i}": ra - rf, f"s{i}": s, f"e{i}": math.pi * m - s,
                    f"sb{i}": 2.0 * rb * psi0, f"sw{i}": sw, f"alpha_a{i}": aa, f"sa{i}": sa,
                    f"rho_l{i}": rho_l, f"x_min{i}": x_min_course(z, al, ha),
                    # the least shift without undercut: the rack's straight edge ends h_l + x m
                    # above its datum (h_l is measured from the shifted rack: it holds -x m)
                    f"x_min_exact{i}": (h_l / m + x) - z * math.sin(al) ** 2 / 2.0,
                    f"NB{i}": rb * np.tan(aa)})
    g = aw * np.sin(aw_ang)                                # N1N2
    out["N1N2"] = g
    out["N1P"] = out["rb1"] * tan_aw
    out["N1B2"] = out["NB1"]
    out["N2B1"] = out["NB2"]
    out["N1B1"] = g - out["NB2"]
    out["rho_p1"] = g - out["NB2"]                         # curvature radius at lowest point, 1
    out["rho_p2"] = g - out["NB1"]
    out["ga"] = out["NB1"] + out["NB2"] - g               # B1B2
    out["eps"] = (z1 * (np.tan(out["alpha_a1"]) - tan_aw)
                  + z2 * (np.tan(out["alpha_a2"]) - tan_aw)) / (2.0 * math.pi)
    out["h"] = out["h1"]
    return out


def pointed_tips(g: dict, z1, z2) -> dict:
    """Where a pair's teeth come to a point, and its contact ratio with the tips there.

    Parameters
    ----------
    g : dict
        :func:`pair`'s entries of the pair (r, rb, s, ra of each wheel, alpha, alpha_w).
    z1, z2 : float
        The numbers of teeth.

    Returns
    -------
    dict
        ``r_point1``, ``r_point2``: the radius where each tooth's flanks meet (m: the half
        angle s/(2r) + inv alpha - inv alpha_y is 0 there); ``eps_cut``: the contact ratio with
        each tip at min(r_a, r_point) -- a tooth pointed below its tip circle (s_a < 0) meshes
        only up to its point; equal to ``eps`` where no tooth is.

    Notes
    -----
    Kept apart from :func:`pair` (two inverse involutes of every grid point would be half again
    its cost where the blocking contour evaluates it): computed for the pair chosen.
    """
    out = {}
    tan_aw = np.tan(g["alpha_w"])
    eps = 0.0
    for i, z in ((1, z1), (2, z2)):
        psi0 = g[f"s{i}"] / (2.0 * g[f"r{i}"]) + inv(g["alpha"])
        rp = g[f"rb{i}"] / np.cos(ainv(np.maximum(psi0, 1e-12)))
        aa = np.arccos(np.clip(g[f"rb{i}"] / np.minimum(g[f"ra{i}"], rp), -1.0, 1.0))
        out[f"r_point{i}"] = rp
        eps = eps + z * (np.tan(aa) - tan_aw)
    out["eps_cut"] = eps / (2.0 * math.pi)
    return out


def lowest_radius(rb, rho):
    """Radius of the involute's point of a given radius of curvature.

    Parameters
    ----------
    rb : float or array_like
        Base radius, m.
    rho : float or array_like
        Radius of curvature of the involute there, m (negative: beyond the point N).

    Returns
    -------
    float or numpy.ndarray
        sqrt(rb^2 + rho^2), m.
    """
    return np.sqrt(rb * rb + rho * rho)


def sliding(x, g, z1, z2):
    """Specific sliding of the two profiles along the line of action.

    Parameters
    ----------
    x : float or array_like
        Distance of the contact point from N1 along N1N2, m.
    g : float
        The length N1N2, m.
    z1, z2 : int
        Tooth numbers.

    Returns
    -------
    lambda1, lambda2 : numpy.ndarray
        lambda1 = 1 - (g - x) z1 / (x z2), lambda2 = 1 - x z2 / ((g - x) z1); +-inf at N1 for
        lambda1 and at N2 for lambda2.

    References
    ----------
    GOST 16532-70; Popov & Timofeev, *Kursovoe proektirovanie po TMM*; Frolov (ed.), *Teoriya
    mekhanizmov i mashin*: the specific sliding; docs/methods.md §6.
    """
    x = np.asarray(x, float)
    u21 = z1 / z2
    rho1 = x
    rho2 = g - x
    with np.errstate(divide="ignore", invalid="ignore"):
        l1 = np.where(rho1 != 0, 1.0 - rho2 * u21 / np.where(rho1 != 0, rho1, 1.0), -np.inf)
        l2 = np.where(rho2 != 0, 1.0 - rho1 / (np.where(rho2 != 0, rho2, 1.0) * u21), -np.inf)
    return l1, l2


def checks(geo, m, sa_min=DEFAULT_SA_MIN, rho_l_true=None, x=(0.0, 0.0)):
    """Defect flags of the pair (True = defect).

    Parameters
    ----------
    geo : dict
        The quantities of :func:`pair` (arrays allowed).
    m : float
        Module, m.
    sa_min : float
        The least tip thickness as a fraction of m.
    rho_l_true : sequence of float or None
        The curvature radii (m) where the real involutes begin, overriding the closed form
        (an undercut tooth's involute starts higher, where the trochoidal fillet cuts it).
    x : tuple of float
        The shift coefficients.

    Returns
    -------
    dict
        ``undercut``, ``sharpening``, ``interference`` (per wheel), ``contact_ratio_low``
        (eps below COURSE_EPS = 1.2, the course's limit) and ``contact_ratio_below_absolute``
        (eps below ABSOLUTE_EPS = 1.1).

    References
    ----------
    GOST 16532-70; Popov & Timofeev, *Kursovoe proektirovanie po TMM*; Frolov (ed.), *Teoriya
    mekhanizmov i mashin*: the quality checks of a gear pair: undercut, tip sharpening,
    interference, the contact ratio; docs/methods.md §6.
    """
    x1, x2 = (np.asarray(v, float) for v in x)
    tol = 1e-12
    rl1 = np.maximum(geo["rho_l1"], 0.0) if rho_l_true is None else rho_l_true[0]
    rl2 = np.maximum(geo["rho_l2"], 0.0) if rho_l_true is None else rho_l_true[1]
    return {
        "undercut": [x1 < geo["x_min1"] - tol, x2 < geo["x_min2"] - tol],
        "sharpening": [geo["sa1"] < sa_min * m * (1 - tol), geo["sa2"] < sa_min * m * (1 - tol)],
        "contact_ratio_low": geo["eps"] < COURSE_EPS - tol,
        "contact_ratio_below_absolute": geo["eps"] < ABSOLUTE_EPS - tol,
        "interference": [geo["rho_p1"] < rl1 - tol * m, geo["rho_p2"] < rl2 - tol * m],
    }
