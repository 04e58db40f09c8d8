"""`tmm validate`: checks beyond the schema."""
from __future__ import annotations


def check_feasible(task, assembly: bool = True) -> None:
    """Raise TaskError / StageError if the task's linkage cannot be computed:
    bad references between points, links and guides; W != 1; and (with
    ``assembly``) a crank angle where some group does not assemble."""
    from .mechanism import build_mechanism

    mech = build_mechanism(task)
    if not assembly:
        return
    from . import kinematics, structure

    structure.analyze(mech, task=task)
    kinematics.check_assembly(mech)
