"""The course's scale factors μ (velocity, acceleration, force, moment, work, inertia,
the diagrams' ordinates): 1, 2, 2.5, 4, 5 x 10^k, the series of the report's figures and
of the drawing sheets.  Kept apart from the report so that the plans' scales
(tmm_cli.plans, read by the hand-method error of every run) need no report import."""
from __future__ import annotations

import math

NICE_SERIES = (1.0, 2.0, 2.5, 4.0, 5.0, 10.0)


def nice_scale(value: float, series=NICE_SERIES) -> float:
    """Smallest standard number >= value from series x 10^k (scale factors as
    students choose them: mu = v_A / pa rounded up, so pa <= its target).

    >>> nice_scale(0.012566)
    0.02
    """
    if not (value > 0 and math.isfinite(value)):
        return 1.0
    k = math.floor(math.log10(value))
    for e in (k - 1, k, k + 1):
        base = 10.0 ** e
        for s in series:
            cand = float(f"{s * base:.12g}")
            if cand >= value * (1 - 1e-12):
                return cand
    return float(f"{10.0 ** (k + 1):.12g}")
