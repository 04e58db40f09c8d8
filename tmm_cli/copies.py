"""Copies among a group's answers, and grades on a scale (`tmm batch`).

* ``same_as=<student>``: two students' answers agree to 1e-9 relative on at least 80 % of
  the quantities both gave (a number each: missing and unreadable answers do not count).
* ``key_of=<variant>``: a student's answers are within tolerance of another variant's key
  on more quantities than of their own variant's key (the variant whose key they match on
  the most quantities; the first in the batch's order on a tie).
* ``--grades 5:0.9,4:0.75,3:0.6``: the first grade whose least score the set reaches,
  below the last the next lower grade.
"""
from __future__ import annotations

import math

SAME_REL = 1e-9
SAME_SHARE = 0.8


def _agree(a: float, b: float) -> bool:
    return abs(a - b) <= SAME_REL * max(abs(a), abs(b))


def agreed(a: dict[str, float], b: dict[str, float]) -> list[str]:
    """The paths both sets answered with numbers that agree (to SAME_REL)."""
    return [p for p in a.keys() & b.keys() if _agree(a[p], b[p])]


def same_as(answers: list[dict[str, float]]) -> list[list[int]]:
    """For each set (path -> number), the indices of the other sets it agrees with."""
    out: list[list[int]] = [[] for _ in answers]
    for i in range(len(answers)):
        ai = answers[i]
        for j in range(i + 1, len(answers)):
            aj = answers[j]
            both = ai.keys() & aj.keys()
            if not both:
                continue
            if len(agreed(ai, aj)) >= SAME_SHARE * len(both):
                out[i].append(j)
                out[j].append(i)
    return out


class KeyTable:
    """Every variant's key as arrays per path, for :func:`key_of`: the middle and half-width of
    what its tolerance passes (``check.passed_interval``: the reference and its bound, or a
    band's), whether either sign passes, and whether the variant has the path at all."""

    def __init__(self, keys: list[dict]):
        import numpy as np

        from .check import passed_interval
        n = len(keys)
        self.n = n
        self.paths: dict[str, tuple] = {}
        for p in {p for key in keys for p in key}:
            ref, bound = np.zeros(n), np.full(n, -1.0)
            anysign, angle = np.zeros(n, bool), False
            for k, key in enumerate(keys):
                if p in key:
                    r, tol, angle = key[p]
                    anysign[k] = tol.any_sign
                    ref[k], bound[k] = passed_interval(r, tol)
            self.paths[p] = (ref, bound, anysign, angle)

    def counts(self, answers: dict[str, float]):
        """Per variant: on how many of ``answers`` its key passes."""
        import numpy as np
        n = np.zeros(self.n, int)
        for p, a in answers.items():
            if p not in self.paths:
                continue
            ref, bound, anysign, angle = self.paths[p]

            def dist(x):
                d = x - ref
                return np.abs((d + 180.0) % 360.0 - 180.0 if angle else d)
            n += (dist(a) <= bound) | (anysign & (dist(-a) <= bound))
        return n


def key_of(answers: dict[str, float], own: int, own_ok: int, table: KeyTable) -> int | None:
    """The index of the variant whose key the answers match (within that key's tolerance)
    on more quantities than their own variant's (``own``, where ``own_ok`` answers are
    ok), or None; the first such variant on a tie."""
    counts = table.counts(answers)
    counts[own] = -1
    best = int(counts.argmax()) if len(counts) else 0
    return best if len(counts) and counts[best] > own_ok else None


def parse_grades(text: str) -> list[tuple[int, float]]:
    """'5:0.9,4:0.75,3:0.6' -> [(5, 0.9), (4, 0.75), (3, 0.6)]: whole grades, highest
    first, each least score in [0, 1] below the one before. ValueError with the reason."""
    out: list[tuple[int, float]] = []
    for part in (p.strip() for p in text.split(",") if p.strip()):
        g, sep, s = part.partition(":")
        try:
            grade, least = int(g), float(s)
        except ValueError:
            raise ValueError(f"'{part}' is not GRADE:LEAST_SCORE (e.g. 5:0.9)") from None
        if not sep or not math.isfinite(least) or not 0 <= least <= 1:
            raise ValueError(f"'{part}': the least score is a share from 0 to 1")
        if out and (grade >= out[-1][0] or least >= out[-1][1]):
            raise ValueError(f"'{part}': grades go highest first, each with a lower least score")
        out.append((grade, least))
    if not out:
        raise ValueError("no grades given")
    return out


def grade_of(score: float, scale: list[tuple[int, float]]) -> int:
    for grade, least in scale:
        if score >= least - 1e-12:
            return grade
    return scale[-1][0] - 1
