"""tmm: the course-project calculator for Theory of Machines and Mechanisms.

Python API (README, *Commands*)::

    import tmm_cli
    task = tmm_cli.load_task("task.yaml")   # or a dict of the same shape
    results = tmm_cli.run(task)             # the results.json dict; no file output
"""
import gc as _gc

_collecting = _gc.isenabled()
_gc.disable()       # the import makes ~10^5 objects (pydantic's machinery, the task model) and no garbage:
try:                # the cycle collector's passes over them would be wasted (~1% of a JSON run)
    from .errors import StageError, TaskError
    from .task import Task, load_task
finally:
    if _collecting:
        if _gc.get_freeze_count() == 0:     # (a caller's own freeze is left alone)
            # the import's objects straight to the oldest generation (as results.bulk):
            # enabled with them young, the collector's next pass would scan them all
            # (~3 % of a JSON run, which turns the collector off again right after)
            _gc.freeze()
            _gc.unfreeze()
        _gc.enable()

__version__ = "0.1.0"


def run(task, **kwargs):
    """Run every stage whose section is present; return the results.json dict (plain
    dicts and lists: the per-position entries as lists, see ``tmm_cli.results.listed``;
    a PartialResults' ``partial`` too)."""
    from .pipeline import run_listed

    if not isinstance(task, Task):
        task = load_task(task)
    return run_listed(task, **kwargs)


__all__ = ["load_task", "run", "Task", "TaskError", "StageError", "__version__"]
