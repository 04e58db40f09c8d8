"""The linkage context: what every linkage stage reads, built once from the task.

:func:`build` makes it in the order the course computes it (structure, positions, the
crank speed) -- the pipeline, `tmm study`, the benchmarks and the tests alike -- and each
stage is handed it with that stage's own section::

    mech = build_mechanism(task); st = structure.analyze(mech, task=task)
    positions = reported_positions(mech, task.positions, task.loads, task.drive.sign, ...)
    drive = drive_speed.resolve(task.drive, positions)           # a Drive
    linkage = Linkage(mech, st, drive, positions, task.loads)
    kinematics.analyze(linkage); dynamics.analyze(linkage, task.flywheel); ...

The sense of rotation is read from the task in one place, ``DriveSection.sign``
(tmm_cli/task.py); every stage takes it from ``linkage.drive.sign``.  Units: SI,
angles in degrees (crank angles absolute, from +x, ccw positive).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Optional

from .drive_speed import Drive

if TYPE_CHECKING:       # types only: importing the context loads no stage
    from .spec import LoadsSection
    from .kinematics.positions import PositionsResult
    from .mechanism import Mechanism
    from .structure import StructureResult


@dataclass(frozen=True)
class CrankRange:
    """The crank angles a generated linkage works over, when it is not a full turn: a
    function generator's input range (``synthesis: {type: function}`` whose crank does not
    turn fully).  The synthesis stage gives it (``Design.crank_range``); the positions are
    then spread over it (``find_positions``), and the assembly is checked over it only.

    Attributes
    ----------
    start : float
        The crank angle at the range's start, deg (``synthesis.input.start``).
    span : float
        The range, deg, signed (``synthesis.input.range``): the crank moves from ``start``
        to ``start + span``.
    x : tuple of float or None
        The argument's range [x0, x1] the crank angles stand for (messages name x).
    kind : str
        Why not a full turn: Grashof's kind of the four-bar (``double-rocker``,
        ``double-crank``, ``change-point``: not a crank-rocker).
    """
    start: float
    span: float
    x: tuple[float, float] | None = None
    kind: str = "double-rocker"

    def angles(self, n: int):
        """``n`` crank angles spread evenly from the start to the end, both included (deg,
        not reduced to [0, 360))."""
        import numpy as np
        return self.start + self.span * np.linspace(0.0, 1.0, int(n))

    def x_at(self, phi: float) -> float | None:
        """The argument x at the crank angle ``phi`` (deg; any turn of it: the one nearest
        the range), None without x."""
        if self.x is None or self.span == 0.0:
            return None
        mid = self.start + self.span / 2.0
        phi = mid + ((phi - mid + 180.0) % 360.0 - 180.0)
        x0, x1 = self.x
        return x0 + (x1 - x0) * (phi - self.start) / self.span


@dataclass(frozen=True)
class Linkage:
    """The lever mechanism as every linkage stage sees it.

    Attributes
    ----------
    mechanism : Mechanism
        The internal model (links, joints, the crank; tmm_cli/linkage/mechanism.py).
    structure : StructureResult
        Chebyshev's formula and the Assur groups in the order of attachment.
    drive : Drive
        The crank's speed, sense of rotation and cycle.
    positions : PositionsResult
        The reported crank angles (deg), position 0, the output's extreme positions,
        stroke H and K, and the stroke state of any loaded link.
    loads : LoadsSection or None
        The task's ``loads`` (the forces applied to the links), or None.
    """
    mechanism: "Mechanism"
    structure: "StructureResult"
    drive: Drive
    positions: "PositionsResult"
    loads: Optional["LoadsSection"] = None


__all__ = ["CrankRange", "Linkage", "build", "reported_positions"]


def reported_positions(mech: "Mechanism", positions_section, loads_section, sign: float,
                       cycle: float, *, kinks: bool = False,
                       crank_range: Optional[CrankRange] = None) -> "PositionsResult":
    """The positions of the cycle as every stage reports them: the task's grid, extra and
    extreme angles, and the crank angles where a load switches (added positions).

    Parameters
    ----------
    mech : Mechanism
    positions_section : PositionsSection or None
        The task's ``positions``.
    loads_section : LoadsSection or None
        The task's ``loads`` (their switch angles become positions).
    sign : float
        Sense of rotation, +1.0 ccw, -1.0 cw (``DriveSection.sign``).
    cycle : float
        Crank rotation of the machine cycle, deg (360 or 720).
    kinks : bool
        Also find where the load diagrams kink (the breakpoints of the flywheel's
        quadrature), in the same scans as the jumps: the dynamics stage then reads them
        from the positions instead of scanning the strokes again.
    crank_range : CrankRange, optional
        The crank's working range when it does not turn fully (a function generator's
        input range): the positions are spread over it, no extreme positions are sought.
    """
    from .kinematics import find_positions
    pos0 = find_positions(mech, positions_section, sign, crank_range=crank_range)
    if loads_section is None:
        return pos0
    from .loads import switch_angles
    if kinks:
        switch_angles(mech, loads_section, pos0, sign=sign, cycle=cycle, kinks=True, roots=pos0._roots)
    return pos0.with_added(switch_angles(mech, loads_section, pos0, sign=sign, cycle=cycle, roots=pos0._roots))


def build(task, *, mechanism: Optional["Mechanism"] = None, kinks: bool = False, told=None,
          crank_range: Optional[CrankRange] = None) -> Linkage:
    """The linkage context of a valid task (its ``mechanism``: a ``synthesis`` generated
    first, ``linkage.synthesis.generate``; ``drive``, ``positions``, ``loads``): the
    mechanism, its structure, the reported positions and the crank's speed
    (``drive_speed.resolve``), in that order.

    Parameters
    ----------
    mechanism : Mechanism, optional
        The task's mechanism already built (``validation.check_feasible``); else built here.
    kinks : bool
        Also the kinks of the load diagrams (:func:`reported_positions`; the flywheel reads them).
    told : callable, optional
        ``told(part, value)`` as each part is made: ``'structure'`` with ``(mechanism,
        structure)``, then ``'positions'`` with the positions -- the pipeline writes each to
        the results (and checks it) before the next is made.
    crank_range : CrankRange, optional
        The crank's working range a synthesis gave (``Design.crank_range``): the positions
        over it (:func:`reported_positions`).
    """
    from ..errors import guarded
    from . import structure
    from .drive_speed import resolve
    from .mechanism import build_mechanism
    tell = told if told is not None else (lambda part, value: None)
    mech = mechanism if mechanism is not None else build_mechanism(task)
    st = structure.analyze(mech, task=task)
    tell("structure", (mech, st))
    positions = guarded("positions")(reported_positions)(mech, task.positions, task.loads, task.drive.sign,
                                                         float(task.drive.cycle), kinks=kinks,
                                                         crank_range=crank_range)
    tell("positions", positions)
    return Linkage(mechanism=mech, structure=st, drive=resolve(task.drive, positions), positions=positions,
                   loads=task.loads)
