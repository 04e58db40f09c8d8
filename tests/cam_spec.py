"""A cam task section for the cam stage tests, built and validated by the task model."""
from tmm_cli.task import Task


def fields(**kw) -> dict:
    """A mapping of a section's fields, ``return_`` written for the YAML key ``return``."""
    return {("return" if k == "return_" else k): v for k, v in kw.items()}


def section(name: str, data: dict):
    """The task's section ``name`` validated by the task model (as a task file gives it)."""
    return getattr(Task.model_validate({"schema": "tmm/1", name: data}), name)


def spec(**kw):
    """The task's ``cam`` section: a central translating roller follower, cosine laws, phases
    90/30/90/150 deg, 30 deg allowed, unless ``kw`` says otherwise."""
    d = dict(follower="translating", stroke=0.03, offset=0.0,
             phases=fields(rise=90, far_dwell=30, return_=90, near_dwell=150),
             laws=fields(rise="cosine", return_="cosine"), pressure_angle=fields(rise=30, return_=30),
             swing="auto", roller="auto", rotation="ccw")
    d.update({k: v for k, v in kw.items() if v is not None})
    return section("cam", d)
