"""Task dicts shared by the dynamics benchmarks: the forging machine of tasks/forging_sixbar.yaml with a
resistance diagram over the working stroke (motor-driven, constant driving moment)."""
from __future__ import annotations

FORGING = {
    "schema": "tmm/1",
    "title": "Horizontal forging machine (benchmark)",
    "mechanism": {
        "ground": {"O": [0, 0], "O1": [0.50, 0.37]},
        "links": {
            "crank": {"points": ["O", "A"], "length": 0.15, "mass": 1.5, "J": 0.02},
            "rod": {"points": ["A", "B"], "length": 0.97, "mass": 9.7, "J": 0.76, "com": [0.485, 0]},
            "rocker": {"points": ["O1", "B"], "length": 0.66, "extra": {"K": [0.25, 0]},
                       "mass": 6.6, "J": 0.24},
            "link4": {"points": ["K", "D"], "length": 0.86, "mass": 8.6, "J": 0.53},
            "slider": {"slider": "D", "guide": {"through": "O1", "angle": 90}, "mass": 20},
        },
        "assembly": {"B": [-0.13, 0.88], "D": [0.5, 1.45]},
    },
    "drive": {"link": "crank", "speed": "50 rpm", "direction": "ccw"},
    "positions": {"count": 12, "zero": "extreme", "output": "slider", "working": "forward"},
    "loads": {"gravity": True, "forces": [
        {"on": "slider", "kind": "resistance", "stroke": "working",
         "diagram": {"s": [0, 0.5, 0.5, 1], "value": [0, 0, 3000, 3000]}}]},
    "flywheel": {"delta": "1/18", "constant": "driving", "resolution": 360},
}


def prepare(task_path: str | None = None):
    """(task, linkage) of a task with a `flywheel` section."""
    import tmm_cli
    from tmm_cli.linkage.context import build
    task = tmm_cli.load_task(task_path if task_path else FORGING)
    if task.flywheel is None:
        raise SystemExit(f"{task_path}: no `flywheel` section")
    return task, build(task)
