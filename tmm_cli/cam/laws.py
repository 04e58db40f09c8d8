"""Follower motion laws of a cam mechanism (docs/methods.md §5).

Every law is a dimensionless function of the phase fraction ``x`` in [0, 1]:
``f(x)`` goes from 0 to 1 and its derivatives ``f'``, ``f''``, ``f'''`` are taken
with respect to ``x``.  With a stroke ``h`` and a phase angle ``Phi`` (rad) the rise is

    s = h f(x),  ds/dphi = h f'(x) / Phi,  d2s/dphi2 = h f''(x) / Phi**2,
    d3s/dphi3 = h f'''(x) / Phi**3,           x = (phi - phi_start) / Phi,

and the return is ``s = h (1 - f(x))`` with the signs of the derivatives reversed.
The peak velocity and acceleration coefficients are ``max|f'|`` and ``max|f''|``
(the factors of ``h/Phi`` and ``h/Phi**2``), as tabulated in the Russian textbooks
(Artobolevsky; Popov & Timofeev; Frolov): constant velocity 1 / infinite,
parabolic 2 / 4, cosine (harmonic) pi/2 / pi**2/2, sine (cycloidal) 2 / 2*pi,
poly345 1.875 / 10/sqrt(3), linearly decreasing acceleration 1.5 / 6,
trapezoidal acceleration 2 / 16/3.

Impacts at the phase boundaries (next to a dwell): a jump of the velocity is a
*rigid* impact (the acceleration is infinite), a finite jump of the acceleration a
*soft* impact, no jump of either: *none*.

Definitions where textbooks differ (documented choices):

* ``linear_decreasing``: the acceleration decreases linearly over the whole phase,
  ``f'' = 6 (1 - 2x)`` (Popov & Timofeev's "linearly decreasing acceleration"),
  so ``f = 3x**2 - 2x**3``.
* ``trapezoidal``: symmetric trapezoids of acceleration, positive on the first half,
  negative on the second; each of the four ramps takes 1/8 of the phase and the
  flat tops 1/4 (the classical trapezoidal law), peak ``16/3``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

LAW_NAMES = ("constant_velocity", "parabolic", "cosine", "sine", "poly345",
             "linear_decreasing", "trapezoidal")

_PI = math.pi


@dataclass(frozen=True)
class Law:
    """A dimensionless motion law of one phase."""

    name: str
    title_en: str             # the report's title in each language: its catalogue, key cam.law.<name>
    func: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]]
    cv: float                 # max |f'|
    ca: float | None          # max |f''| (None: infinite, constant velocity)
    impact: str               # 'rigid' | 'soft' | 'none' at the phase boundaries
    breaks: tuple[float, ...]  # interior fractions where f'' (or f''') has a kink or jump
    soft_inside: tuple[float, ...]  # interior fractions where f'' jumps (soft impact)

    def __call__(self, x):
        """Return ``(f, f', f'', f''')`` at the fractions ``x`` (clipped to [0, 1])."""
        x = np.clip(np.asarray(x, dtype=float), 0.0, 1.0)
        return self.func(x)


def _constant_velocity(x):
    one = np.ones_like(x)
    zero = np.zeros_like(x)
    return x.copy(), one, zero, zero.copy()


def _parabolic(x):
    first = x < 0.5
    f = np.where(first, 2 * x * x, 1 - 2 * (1 - x) ** 2)
    f1 = np.where(first, 4 * x, 4 * (1 - x))
    f2 = np.where(first, 4.0, -4.0)
    return f, f1, f2, np.zeros_like(x)


def _cosine(x):
    a = _PI * x
    return ((1 - np.cos(a)) / 2, _PI / 2 * np.sin(a), _PI ** 2 / 2 * np.cos(a),
            -_PI ** 3 / 2 * np.sin(a))


def _sine(x):
    a = 2 * _PI * x
    return (x - np.sin(a) / (2 * _PI), 1 - np.cos(a), 2 * _PI * np.sin(a),
            4 * _PI ** 2 * np.cos(a))


def _poly345(x):
    x2 = x * x
    return (x2 * x * (10 - 15 * x + 6 * x2), 30 * x2 * (1 - x) ** 2,
            60 * x * (1 - 3 * x + 2 * x2), 60 * (1 - 6 * x + 6 * x2))


def _linear_decreasing(x):
    return (x * x * (3 - 2 * x), 6 * x * (1 - x), 6 * (1 - 2 * x), np.full_like(x, -12.0))


_TRAP_B = 1.0 / 8.0          # ramp length (fraction of the phase)
_TRAP_A = 16.0 / 3.0         # peak acceleration coefficient for b = 1/8


def _trap_half(x):
    """f, f', f'', f''' of the first half (0 <= x <= 1/2) of the trapezoidal law."""
    b, A = _TRAP_B, _TRAP_A
    j = A / b
    x1, x2 = b, 0.5 - b                      # ends of the ramp up and of the flat top
    # values at the knots
    v1 = A * b / 2
    s1 = j * b ** 3 / 6
    v2 = v1 + A * (x2 - x1)
    s2 = s1 + v1 * (x2 - x1) + A * (x2 - x1) ** 2 / 2
    r1 = x <= x1
    r2 = (x > x1) & (x <= x2)
    t = x - x2
    f = np.where(r1, j * x ** 3 / 6,
                 np.where(r2, s1 + v1 * (x - x1) + A * (x - x1) ** 2 / 2,
                          s2 + v2 * t + A * t ** 2 / 2 - j * t ** 3 / 6))
    f1 = np.where(r1, j * x ** 2 / 2, np.where(r2, v1 + A * (x - x1), v2 + A * t - j * t ** 2 / 2))
    f2 = np.where(r1, j * x, np.where(r2, A, A - j * t))
    f3 = np.where(r1, j, np.where(r2, 0.0, -j))
    return f, f1, f2, f3


def _trapezoidal(x):
    first = x <= 0.5
    xa = np.where(first, x, 1 - x)
    f, f1, f2, f3 = _trap_half(xa)
    return (np.where(first, f, 1 - f), f1, np.where(first, f2, -f2), f3)


LAWS: dict[str, Law] = {
    "constant_velocity": Law("constant_velocity", "constant velocity",
                             _constant_velocity, 1.0, None, "rigid", (), ()),
    "parabolic": Law("parabolic", "parabolic (constant acceleration)", _parabolic, 2.0, 4.0, "soft",
                     (0.5,), (0.5,)),
    "cosine": Law("cosine", "cosine (harmonic)", _cosine,
                  _PI / 2, _PI ** 2 / 2, "soft", (), ()),
    "sine": Law("sine", "sine (cycloidal)", _sine, 2.0, 2 * _PI, "none", (), ()),
    "poly345": Law("poly345", "polynomial 3-4-5", _poly345,
                   1.875, 10 / math.sqrt(3), "none", (), ()),
    "linear_decreasing": Law("linear_decreasing", "linearly decreasing acceleration",
                             _linear_decreasing, 1.5, 6.0, "soft", (), ()),
    "trapezoidal": Law("trapezoidal", "trapezoidal acceleration", _trapezoidal, 2.0, _TRAP_A, "none",
                       (_TRAP_B, 0.5 - _TRAP_B, 0.5, 0.5 + _TRAP_B, 1 - _TRAP_B), ()),
}


def get_law(name: str) -> Law:
    """The motion law of a name.

    Parameters
    ----------
    name : str
        One of :data:`LAW_NAMES` (``cosine``, ``sine``, ``poly345``...).

    Returns
    -------
    Law
        The law's dimensionless displacement f(x) and derivatives on x in [0, 1], its peak
        velocity and acceleration coefficients and its impact kind.

    Raises
    ------
    ValueError
        An unknown name.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*; Popov & Timofeev, *Kursovoe
    proektirovanie po TMM*; Frolov (ed.), *Teoriya mekhanizmov i mashin*: the motion laws of
    the follower and their coefficients; docs/methods.md §5.
    """
    try:
        return LAWS[name]
    except KeyError:
        raise ValueError(f"unknown motion law {name!r}; known: {', '.join(LAW_NAMES)}") from None
