"""The linkage context: what every linkage stage reads, built once from the task.

The pipeline builds it in the order the course computes it (structure, positions, the
crank speed) and hands it to each stage with that stage's own section::

    mech = build_mechanism(task); st = structure.analyze(mech, task=task)
    positions = kinematics.find_positions(mech, task.positions, task.drive.sign, ...)
    drive = drive_speed.resolve(task.drive, positions)           # a Drive
    linkage = Linkage(mech, st, drive, positions, task.loads)
    kinematics.analyze(linkage); dynamics.analyze(linkage, task.flywheel); ...

The sense of rotation is read from the task in one place, ``DriveSection.sign``
(tmm_cli/task.py); every stage takes it from ``linkage.drive.sign``.  Units: SI,
angles in degrees (crank angles absolute, from +x, ccw positive).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Optional

if TYPE_CHECKING:       # types only: importing the context loads no stage
    from ..task import LoadsSection
    from .kinematics.positions import PositionsResult
    from .mechanism import Mechanism
    from .structure import StructureResult


@dataclass(frozen=True)
class Drive:
    """The input link's motion at the mean speed.

    Attributes
    ----------
    link : str
        Name of the input link (the crank).
    omega : float
        Mean angular speed, rad/s, signed: positive counter-clockwise.
    sign : float
        Sense of rotation: +1.0 counter-clockwise, -1.0 clockwise (``omega`` has it).
    cycle : float
        Crank rotation of one machine cycle, deg: 360, or 720 (a four-stroke engine).
    source : str
        Where ``omega`` comes from: ``'speed'`` (given), ``'mean_output_speed'`` or
        ``'working_stroke_speed'`` (from the output's speed, stroke and K).
    """
    link: str
    omega: float
    sign: float
    cycle: float
    source: str = "speed"

    @property
    def speed(self) -> float:
        """|omega|, rad/s."""
        return abs(self.omega)

    @property
    def direction(self) -> str:
        """'ccw' | 'cw'."""
        return "ccw" if self.sign > 0 else "cw"

    def to_dict(self) -> dict:
        """results.json ``drive``: omega (rad/s, signed), n (rpm), source."""
        return {"omega": float(self.omega), "n": abs(float(self.omega)) * 30.0 / math.pi,
                "source": self.source}


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


__all__ = ["Drive", "Linkage", "build", "reported_positions"]


def reported_positions(mech: "Mechanism", positions_section, loads_section, sign: float,
                       cycle: float, *, kinks: bool = False) -> "PositionsResult":
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
    """
    from .kinematics import find_positions
    pos0 = find_positions(mech, positions_section, sign)
    if loads_section is None:
        return pos0
    from .loads import switch_angles
    if kinks:
        switch_angles(mech, loads_section, pos0, sign=sign, cycle=cycle, kinks=True, roots=pos0._roots)
    return pos0.with_added(switch_angles(mech, loads_section, pos0, sign=sign, cycle=cycle, roots=pos0._roots))


def build(task) -> Linkage:
    """The linkage context of a valid task, as the pipeline builds it step by step.

    Parameters
    ----------
    task : Task
        The validated task: its ``mechanism`` (or ``synthesis``), ``drive``, ``positions``
        and ``loads``.

    Returns
    -------
    Linkage
        The mechanism (lengths in m), its structure, the reported positions (crank angles in
        deg) and the crank's speed (rad/s, :func:`.drive_speed.resolve`).

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: the structure (Assur groups), the
    extreme positions and the kinematics of the reported positions; docs/methods.md §1-2.
    """
    from . import structure
    from .drive_speed import resolve
    from .mechanism import build_mechanism
    mech = build_mechanism(task)
    st = structure.analyze(mech, task=task)
    positions = reported_positions(mech, task.positions, task.loads, task.drive.sign, float(task.drive.cycle))
    return Linkage(mechanism=mech, structure=st, drive=resolve(task.drive, positions), positions=positions,
                   loads=task.loads)
