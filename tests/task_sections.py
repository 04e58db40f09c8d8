"""Task sections for the stage tests, built and validated by the task model (as a task file
gives them), so a stage sees the typed section the pipeline gives it."""
from typing import get_args

from tmm_cli.task import Task


def fields(**kw) -> dict:
    """A mapping of a section's fields, ``return_`` written for the YAML key ``return``."""
    return {("return" if k == "return_" else k): v for k, v in kw.items()}


def section(name: str, data: dict):
    """The task's section ``name`` validated by the task model."""
    return getattr(Task.model_validate({"schema": "tmm/1", name: data}), name)


def section_model(name: str):
    """The model class of the task's section ``name`` (wherever the task model keeps it)."""
    return next(a for a in get_args(Task.model_fields[name].annotation) if a is not type(None))


def flywheel(**kw):
    """The task's ``flywheel`` section validated by its model alone (a task with a flywheel
    needs a mechanism, which these tests replace by a sampler)."""
    return section_model("flywheel").model_validate(kw)


def gears(**kw):
    """The task's ``gears`` section (m in metres, the schema's defaults for the rest)."""
    return section("gears", kw)


def planetary(**kw):
    """The task's ``planetary`` section (the schema's defaults for what ``kw`` leaves out)."""
    return section("planetary", kw)
