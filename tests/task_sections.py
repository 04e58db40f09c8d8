"""Task sections for the stage tests, built and validated by the task model (as a task file
gives them), so a stage sees the typed section the pipeline gives it."""
from tmm_cli.task import Task


def fields(**kw) -> dict:
    """A mapping of a section's fields, ``return_`` written for the YAML key ``return``."""
    return {("return" if k == "return_" else k): v for k, v in kw.items()}


def section(name: str, data: dict):
    """The task's section ``name`` validated by the task model."""
    return getattr(Task.model_validate({"schema": "tmm/1", name: data}), name)


def gears(**kw):
    """The task's ``gears`` section (m in metres, the schema's defaults for the rest)."""
    return section("gears", kw)


def planetary(**kw):
    """The task's ``planetary`` section (the schema's defaults for what ``kw`` leaves out)."""
    return section("planetary", kw)
