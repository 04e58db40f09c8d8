"""`tmm validate`: checks beyond the schema."""
from __future__ import annotations

from .errors import StageError, TaskError


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
    try:
        kinematics.check_assembly(mech)
    except StageError as err:
        raise impossible_dimensions(task, err) or err
    from .pipeline import check_selection
    try:
        check_selection(task, mech)
    except TaskError as err:
        raise task.locate(err) from None


def impossible_dimensions(task, err):
    """A kinematics StageError for a group that assembles at no crank angle at all means
    the dimensions are impossible: that is an invalid task (exit 2), pointing at the
    group's first link. Returns the TaskError, or None for a partial failure."""
    names = getattr(err, "never_assembles", None)
    if not names:
        return None
    return task.error(("mechanism", "links", names[0]),
                      f"impossible dimensions: {err.message} — at no crank angle; check the lengths of "
                      f"{', '.join(names)} and the ground points")
