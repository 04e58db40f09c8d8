"""The loads on the links: applied forces and couples per position (the data)."""
from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

G = 9.81


def all_rows(rows: np.ndarray, n: int) -> bool:
    """Whether a selection of rows is every row in order.

    Parameters
    ----------
    rows : numpy.ndarray
        Row numbers.
    n : int
        The number of rows.

    Returns
    -------
    bool
        True when ``rows`` is 0, 1, ..., n-1: a selection is then the arrays themselves, no
        copies (nothing changes them in place).
    """
    return len(rows) == n and (n == 0 or (rows[0] == 0 and bool(np.all(np.diff(rows) == 1))))


# ------------------------------------------------------------------ data
@dataclass
class AppliedForce:
    """A force on a link at each position: its point of application and its vector, N."""

    link: int
    name: str
    point: np.ndarray          # (N, 2) position of the point of application
    F: np.ndarray              # (N, 2)
    kind: str                  # resistance | driving | load | gravity | inertia | friction
    local: tuple[float, float] | None = None   # point in the link's local frame (if fixed on it)
    point_name: str | None = None


@dataclass
class AppliedCouple:
    """A couple on a link at each position, N*m (ccw positive)."""

    link: int
    name: str
    M: np.ndarray              # (N,) ccw positive
    kind: str


@dataclass
class Loads:
    """The forces and couples on the links at each crank angle ``phi``."""

    phi: np.ndarray
    forces: list[AppliedForce] = field(default_factory=list)
    couples: list[AppliedCouple] = field(default_factory=list)
    info: list[dict] = field(default_factory=list)     # task loads: diagram values per position

    def external(self) -> "Loads":
        """The loads without the inertia loads."""
        return Loads(self.phi, [f for f in self.forces if f.kind != "inertia"],
                     [c for c in self.couples if c.kind != "inertia"], self.info)

    def select(self, rows) -> "Loads":
        """The loads at the positions ``rows`` only (``self`` itself at every position)."""
        rows = np.asarray(rows, dtype=int)
        if all_rows(rows, len(self.phi)):
            return self
        return Loads(np.asarray(self.phi)[rows],
                     [replace(f, point=f.point[rows], F=f.F[rows]) for f in self.forces],
                     [replace(c, M=c.M[rows]) for c in self.couples],
                     [{k: (np.asarray(v)[rows] if isinstance(v, np.ndarray) else v) for k, v in d.items()}
                      for d in self.info])

    def __len__(self) -> int:
        return len(self.phi)
