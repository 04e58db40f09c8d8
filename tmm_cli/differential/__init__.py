"""Differentials: a planetary scheme A-D with no member fixed (two degrees of freedom).

* :class:`DifferentialSection` -- the task section ``differential:`` (spec.py);
* :func:`analyze` ``(section) -> DifferentialResult``; ``DifferentialResult.to_dict()`` is
  the results.json section ``differential`` (analysis.py): Willis' formula for the third
  member's speed, the satellites' speed, the torques on all members from their balance and
  the power balance with the efficiency of the train with the carrier held.
"""
from .spec import DifferentialSection

# the task model imports DifferentialSection; the analysis loads on first use
_LAZY = {"DifferentialResult": "analysis", "analyze": "analysis", "willis_ratio": "analysis",
         "third_speed": "analysis", "torques": "analysis"}


def __getattr__(name):
    if name in _LAZY:
        import importlib
        return getattr(importlib.import_module(f".{_LAZY[name]}", __name__), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = ["DifferentialSection", "DifferentialResult", "analyze", "willis_ratio", "third_speed", "torques"]
