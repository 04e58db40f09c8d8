"""`tmm validate`: feasibility beyond the schema (does the linkage assemble?)."""
from __future__ import annotations


def check_feasible(task) -> None:
    """Raise TaskError / StageError if the task's linkage cannot be computed:
    bad references, W != 1, or a crank angle where some group does not assemble."""
    from . import kinematics, structure
    from .mechanism import build_mechanism

    mech = build_mechanism(task)
    structure.analyze(mech, task=task)
    kinematics.check_assembly(mech)
