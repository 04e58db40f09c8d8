"""The gears stage: ``analyze(spec) -> GearResult`` (task section `gears`, docs/methods.md §6).

``spec`` is the task's validated ``gears`` section (:class:`~tmm_cli.task.GearsSection`):
``m`` (metres), ``z`` (two ints), ``x`` (two floats or 'auto'), ``alpha`` (deg), ``ha``,
``c``, ``rule`` (shift rule for ``x: auto``, see :mod:`shifts`), ``sa_min`` (tip thickness
limit as a fraction of m) and ``rho_f`` (rack fillet coefficient; None: c/(1 - sin alpha)
= 0.38 for the standard rack).  Its defaults are the task model's.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ..errors import StageError
from ..lazy import unique
from ..messages import Message
from . import shifts as _shifts
from .geometry import ABSOLUTE_EPS, COURSE_EPS, checks, lowest_radius, pair, sliding
from .tooth import Wheel

if TYPE_CHECKING:
    from .spec import GearsSection

STAGE = "gears"


def _f(v):
    """Plain float, None for non-finite."""
    v = float(v)
    return v if math.isfinite(v) else None


@dataclass
class GearResult:
    """The gear pair: its geometry with profile shift, the contact ratio and the checks."""

    m: float
    z: tuple[int, int]
    x: tuple[float, float]
    alpha: float
    ha: float
    c: float
    rho_f: float
    sa_min: float
    rule: str | None
    geo: dict
    rho_l: tuple[float, float]            # real boundary curvature radii (undercut-aware)
    r_l: tuple[float, float]              # radii where the real involutes begin
    checks: dict
    sliding: dict
    contour: dict
    warnings: list[str] = field(default_factory=list)

    def wheels(self) -> tuple[Wheel, Wheel]:
        """The two rack-generated wheels (for drawing and export)."""
        g = self.geo
        return (Wheel(self.m, self.z[0], self.x[0], self.alpha, self.ha, self.c, g["ra1"], self.rho_f),
                Wheel(self.m, self.z[1], self.x[1], self.alpha, self.ha, self.c, g["ra2"], self.rho_f))

    def to_dict(self) -> dict:
        g = self.geo
        two = lambda k: [_f(g[k + "1"]), _f(g[k + "2"])]  # noqa: E731
        ch = self.checks
        rp = [_f(lowest_radius(g["rb1"], g["rho_p1"])), _f(lowest_radius(g["rb2"], g["rho_p2"]))]
        return {
            "aw": _f(g["aw"]), "alpha_w": _f(math.degrees(g["alpha_w"])), "y": _f(g["y"]),
            "dy": _f(g["dy"]), "r": two("r"), "rb": two("rb"), "rw": two("rw"), "ra": two("ra"),
            "rf": two("rf"), "s": two("s"), "sa": two("sa"), "eps_alpha": _f(g["eps"]),
            "x_min": two("x_min"),
            "checks": {"undercut": [bool(v) for v in ch["undercut"]],
                       "sharpening": [bool(v) for v in ch["sharpening"]],
                       "contact_ratio_low": bool(ch["contact_ratio_low"]),
                       "interference": bool(any(ch["interference"]))},
            # extras
            # eps_alpha by the formula is formal where a tip meets the mate off its involute
            # (interference, or a flank with no involute): part of B1B2 is no conjugate action
            # (interference, or a flank with no involute), or where a tooth is pointed below its
            # tip circle (sa < 0: it ends at its point; the formula counts up to the tip circle)
            "eps_alpha_formal": bool(any(ch["interference"]) or g["sa1"] < 0 or g["sa2"] < 0),
            "m": self.m, "z": list(self.z), "x": [float(v) for v in self.x], "alpha": self.alpha,
            "ha": self.ha, "c": self.c, "rho_f": self.rho_f, "sa_min": self.sa_min, "rule": self.rule,
            "a": _f(g["a"]), "inv_alpha": _f(math.tan(math.radians(self.alpha)) - math.radians(self.alpha)),
            "inv_alpha_w": _f(g["inv_alpha_w"]), "h": _f(g["h1"]), "p": _f(g["p"]), "pb": _f(g["pb"]),
            "e": two("e"), "sb": two("sb"), "sw": two("sw"),
            "alpha_a": [_f(math.degrees(g["alpha_a1"])), _f(math.degrees(g["alpha_a2"]))],
            "x_min_exact": two("x_min_exact"),
            "line_of_action": {"N1N2": _f(g["N1N2"]), "N1P": _f(g["N1P"]), "N1B1": _f(g["N1B1"]),
                               "N1B2": _f(g["N1B2"]), "B1B2": _f(g["ga"]),
                               "arc_of_action_w": _f(g["ga"] / math.cos(g["alpha_w"]))},
            "lowest_active": {"rho_p": [_f(g["rho_p1"]), _f(g["rho_p2"])], "r_p": rp},
            "involute_start": {"rho_l": [_f(v) for v in self.rho_l], "r_l": [_f(v) for v in self.r_l]},
            "checks_detail": {"interference": [bool(v) for v in ch["interference"]],
                              "contact_ratio_below_absolute": bool(ch["contact_ratio_below_absolute"]),
                              "eps_course_min": COURSE_EPS, "eps_absolute_min": ABSOLUTE_EPS,
                              "sa_limit": self.sa_min * self.m},
            "sliding": self.sliding,
            "blocking_contour": self.contour,
            "warnings": list(self.warnings),
        }


def _sliding_table(g, z1, z2, n=21):
    L = float(g["N1N2"])
    pts = np.linspace(0.0, L, n)
    marks = {"N1": 0.0, "B1": float(g["N1B1"]), "P": float(g["N1P"]), "B2": float(g["N1B2"]), "N2": L}
    xs = unique(np.concatenate([pts, [v for v in marks.values() if 0.0 <= v <= L]]))
    l1, l2 = sliding(xs, L, z1, z2)
    lb1, _ = sliding(marks["B1"], L, z1, z2)
    _, lb2 = sliding(marks["B2"], L, z1, z2)
    return {"X": [float(v) for v in xs], "lambda1": [_f(v) for v in l1], "lambda2": [_f(v) for v in l2],
            "marks": {k: _f(v) for k, v in marks.items()},
            "lambda1_max": _f(lb1), "lambda2_max": _f(lb2),
            "convention": "X from N1 along N1N2; lambda1 = 1 - (N1N2 - X) z1 / (X z2), "
                          "lambda2 = 1 - X z2 / ((N1N2 - X) z1)"}


def _contour_dict(bc, chosen):
    from .drawing import region_polygons
    return {"x1_range": [float(bc["x1"][0]), float(bc["x1"][-1])],
            "x2_range": [float(bc["x2"][0]), float(bc["x2"][-1])],
            "lines": bc["lines"], "chosen": [float(chosen[0]), float(chosen[1])],
            "admissible_fraction": float(np.mean(bc["ok"])),
            "chosen_admissible": None,
            # the admissible region (shaded in the report): polygons [outer ring, holes...]
            "region": region_polygons(bc["x1"], bc["x2"], bc["ok"])}


def analyze(spec: GearsSection) -> GearResult:
    """Geometry, checks, sliding and blocking contour of an external spur gear pair.

    Parameters
    ----------
    spec : GearsSection
        The task's ``gears`` section: module ``m`` (m), tooth numbers ``z`` (z1, z2), the
        profile shifts ``x`` (x1, x2, fractions of m, or ``auto`` chosen by ``rule``), the
        rack's profile angle ``alpha`` (deg), addendum and clearance coefficients ``ha``,
        ``c``, the least tip thickness ``sa_min`` (fraction of m) and the rack fillet
        coefficient ``rho_f`` (None: c/(1 - sin alpha)).

    Returns
    -------
    GearResult
        The pair's geometry (radii and centre distance in m, the working pressure angle in
        deg, the contact ratio), the undercut, sharpening, interference and contact-ratio
        checks, the specific sliding along the line of action and the blocking contour;
        ``to_dict()`` is the results.json ``gears`` section.

    Raises
    ------
    StageError
        A pair that does not mesh (no working pressure angle), a wheel without teeth, or a
        fillet that does not fit the clearance.

    References
    ----------
    GOST 16532-70 (the geometry of the pair), GOST 13755-81 (the rack); Popov & Timofeev,
    *Kursovoe proektirovanie po TMM*, and Frolov (ed.), *Teoriya mekhanizmov i mashin*: the
    pair with profile shift, the checks and the specific sliding; Bolotovsky: the blocking
    contour; docs/methods.md §6.
    """
    m = float(spec.m)
    z1, z2 = (int(v) for v in spec.z)
    alpha, ha, c, sa_min = float(spec.alpha), float(spec.ha), float(spec.c), float(spec.sa_min)
    rule = spec.rule
    al = math.radians(alpha)
    rho_f = c / (1.0 - math.sin(al)) if spec.rho_f is None else float(spec.rho_f)
    if m <= 0 or min(z1, z2) < 3:
        raise StageError(STAGE, Message("gears.fail.invalid", m=m, z1=z1, z2=z2))
    if rho_f * (1.0 - math.sin(al)) > c + 1e-12:
        raise StageError(STAGE, Message("gears.fail.fillet", rho_f=rho_f, c=c))
    warnings: list[Message] = []
    x1, x2, rule, bc = _shifts_of(spec.x, rule, m, z1, z2, alpha, ha, c, sa_min, rho_f, warnings)
    g = _pair_geometry(m, z1, z2, x1, x2, alpha, ha, c, rho_f)
    w1 = Wheel(m, z1, x1, alpha, ha, c, g["ra1"], rho_f)
    w2 = Wheel(m, z2, x2, alpha, ha, c, g["ra2"], rho_f)
    rl, rhol, no_involute = _involute_starts(((w1, z1, x1), (w2, z2, x2)), warnings)
    ch = checks(g, m, sa_min, rho_l_true=rhol, x=(x1, x2))
    for i in no_involute:      # the other wheel's tip necessarily meets it off the involute
        ch["interference"][i] = np.True_
    _check_warnings(g, ch, (z1, z2), (x1, x2), m, sa_min, rhol, warnings)
    if bc is None:
        lo1 = min(x1 - 0.3, max(min(g["x_min1"], 0.0), -1.0) - 0.3)
        lo2 = min(x2 - 0.3, max(min(g["x_min2"], 0.0), -1.0) - 0.3)
        bc = _shifts.blocking_contour(m, z1, z2, alpha, ha, c, sa_min, rho_f,
                                      x1_range=(lo1, max(1.5, x1 + 0.3)),
                                      x2_range=(lo2, max(1.5, x2 + 0.3)))
    cdict = _contour_dict(bc, (x1, x2))
    cdict["chosen_admissible"] = not any(
        [*ch["undercut"], *ch["sharpening"], ch["contact_ratio_low"], *ch["interference"]])
    return GearResult(m=m, z=(z1, z2), x=(x1, x2), alpha=alpha, ha=ha, c=c, rho_f=rho_f, sa_min=sa_min,
                      rule=rule, geo=g, rho_l=(rhol[0], rhol[1]), r_l=(rl[0], rl[1]), checks=ch,
                      sliding=_sliding_table(g, z1, z2), contour=cdict, warnings=warnings)


def _shifts_of(xv, rule, m, z1, z2, alpha, ha, c, sa_min, rho_f, warnings):
    """The profile shifts (x1, x2), the rule that chose them (None: given) and the blocking
    contour computed on the way (None: given shifts)."""
    if not isinstance(xv, str):
        x1, x2 = (float(v) for v in xv)
        return x1, x2, None, None
    if xv != "auto":
        raise StageError(STAGE, Message("gears.fail.x_form", x=xv))
    if rule not in _shifts.RULES:
        raise StageError(STAGE, Message("gears.fail.unknown_rule", rule=str(rule)))
    bc = _shifts.blocking_contour(m, z1, z2, alpha, ha, c, sa_min, rho_f)
    x1, x2, notes = _shifts.choose(rule, m, z1, z2, alpha, ha, c, sa_min, rho_f, contour=bc)
    warnings += notes
    return x1, x2, rule, bc


def _pair_geometry(m, z1, z2, x1, x2, alpha, ha, c, rho_f) -> dict:
    """The pair's geometry (:func:`.geometry.pair`, scalars as floats) with the checks that
    the wheels mesh and have teeth."""
    g = pair(m, z1, z2, x1, x2, alpha, ha, c, rho_f)
    g = {k: (float(v) if np.ndim(v) == 0 and not isinstance(v, (bool, np.bool_)) else v)
         for k, v in g.items()}
    if not bool(g["valid"]):
        raise StageError(STAGE, Message("gears.fail.no_mesh_angle", inv=g["inv_alpha_w"], xsum=x1 + x2))
    for i in (1, 2):
        if g[f"rf{i}"] <= 0:
            raise StageError(STAGE, Message("gears.fail.root_radius", wheel=i, rf=g[f"rf{i}"]))
        if g[f"ra{i}"] <= g[f"rf{i}"]:
            raise StageError(STAGE, Message("gears.fail.no_tooth", wheel=i, ra=g[f"ra{i}"], rf=g[f"rf{i}"]))
    return g


def _involute_starts(wheels, warnings):
    """Radii (m) where the real involutes begin, their curvature radii there (m), and the
    wheels (0, 1) whose flank has no involute at all (warned about)."""
    rl, rhol, no_involute = [], [], []
    for i, (w, z, x) in enumerate(wheels, start=1):
        fl = w.flank(n_fillet=200, n_involute=4)
        if fl.r_involute_start >= fl.r_tip:
            # the GOST formulas (s_a, eps_alpha, the line of action) assume an involute flank:
            # their values are formal here; the wheel is flagged (interference) and warned about
            if w.ra <= w.rb:
                warnings.append(Message("gears.no_involute_inside_base", wheel=i, z=z, x=x))
            else:
                warnings.append(Message("gears.no_involute_pointed_fillet" if fl.pointed else
                                        "gears.no_involute_above_tip", wheel=i, z=z, x=x,
                                        r_start=fl.r_involute_start * 1e3, r_tip=fl.r_tip * 1e3))
            no_involute.append(i - 1)
        rl.append(fl.r_involute_start)
        rhol.append(math.sqrt(max(fl.r_involute_start ** 2 - w.rb ** 2, 0.0)))
    return rl, rhol, no_involute


def _check_warnings(g, ch, zz, xx, m, sa_min, rhol, warnings) -> None:
    """The warnings of the failed checks: undercut, a thin or pointed tip, interference, the
    contact ratio."""
    for i in (0, 1):
        n = i + 1
        if ch["undercut"][i]:
            warnings.append(Message("gears.undercut", wheel=n, z=zz[i], x=xx[i], x_min=g[f"x_min{n}"]))
        if ch["sharpening"][i]:
            warnings.append(Message("gears.tip_pointed" if g[f"sa{n}"] <= 0 else "gears.tip_thin", wheel=n,
                                    sa=g[f"sa{n}"] * 1e3, k=sa_min, limit=sa_min * m * 1e3))
        if ch["interference"][i]:
            other = 2 - i
            warnings.append(Message("gears.interference", other=other, wheel=n, rho_p=g[f"rho_p{n}"] * 1e3,
                                    rho_l=rhol[i] * 1e3))
    if any(ch["interference"]):        # the formula counts the part of B1B2 off the involutes
        warnings.append(Message("gears.eps_formal", eps=g["eps"], b=g["ga"] * 1e3, n=g["N1N2"] * 1e3))
    if g["sa1"] < 0 or g["sa2"] < 0:   # a tip beyond the tooth's point: counted by the formula, not there
        from .geometry import pointed_tips
        cut = pointed_tips(g, zz[0], zz[1])
        for n in (1, 2):               # (pointed on the tip circle itself: eps as the formula gives it)
            if g[f"sa{n}"] < 0:
                warnings.append(Message("gears.eps_pointed", eps=g["eps"], wheel=n, r_point=cut[f"r_point{n}"] * 1e3,
                                        ra=g[f"ra{n}"] * 1e3, eps_cut=cut["eps_cut"]))
    if ch["contact_ratio_low"]:
        warnings.append(Message("gears.contact_ratio_course", eps=g["eps"], limit=COURSE_EPS))
    if ch["contact_ratio_below_absolute"]:
        warnings.append(Message("gears.contact_ratio_broken" if g["eps"] < 1 else "gears.contact_ratio_absolute",
                                eps=g["eps"], limit=ABSOLUTE_EPS))
