"""The table at the division points of the rise and of the return (the course divides each
moving phase into 6 or 8 equal parts and builds the diagrams and the profile on them)."""
from __future__ import annotations

import math

import numpy as np

from .motion import RETURN, RISE, Motion


def division_table(motion: Motion, divisions: int, rocker: bool, pressure_angle=None) -> list[dict]:
    """The table of the follower's motion at the divisions of the rise and of the return.

    Parameters
    ----------
    motion : Motion
        The follower's motion.
    divisions : int
        The number of equal parts of each phase.
    rocker : bool
        True for a rocker (its s in deg).
    pressure_angle : callable or None
        ``pressure_angle(s, s1)`` -> the unsigned pressure angle, rad (None: 0, a flat face).

    Returns
    -------
    list of dict
        {phase, k, phi, s, ds, d2s, pressure_angle} for k = 0..divisions, the rise then the
        return: ``phi`` in deg from the start of the rise, ``s`` in m (rocker: deg), ``ds`` and
        ``d2s`` per rad and per rad^2, the pressure angle in deg.  Each value is that of the
        phase's own law (one-sided at the phase's ends).

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*; Popov & Timofeev, *Kursovoe
    proektirovanie po TMM*; Frolov (ed.), *Teoriya mekhanizmov i mashin*: the table of the
    follower's displacement at the divisions of the phases, the basis of the graphical
    construction of the profile; docs/methods.md §5.
    """
    out = []
    x = np.arange(divisions + 1) / divisions
    for ph, name, start, span in ((RISE, "rise", motion.starts[0], motion.rise),
                                  (RETURN, "return", motion.starts[2], motion.ret)):
        s, s1, s2, _ = motion.phase(ph, x)
        th = np.zeros_like(s) if pressure_angle is None else np.degrees(pressure_angle(s, s1))
        for k in range(divisions + 1):
            out.append({"phase": name, "k": k, "phi": round(math.degrees(start + x[k] * span), 9),
                        "s": float(math.degrees(s[k]) if rocker else s[k]),
                        "ds": float(s1[k]), "d2s": float(s2[k]), "pressure_angle": float(th[k])})
    return out
