"""Cam mechanism stage (docs/methods.md §5): motion laws, smallest cam, profile by inverted motion.

Public API::

    from tmm_cli.cam import synthesize
    result = synthesize(task.cam)       # CamResult
    result.to_dict()                    # the results.json ``cam`` section
"""
from .laws import LAW_NAMES, LAWS, Law, get_law
from .synthesis import CamResult, synthesize

__all__ = ["synthesize", "CamResult", "LAWS", "LAW_NAMES", "Law", "get_law"]
