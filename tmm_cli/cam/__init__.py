"""Cam mechanism stage (docs/methods.md §5): motion laws, smallest cam, profile by inverted motion.

Public API::

    from tmm_cli.cam import synthesize
    result = synthesize(task.cam)       # CamResult
    result.to_dict()                    # the results.json ``cam`` section
"""
# made on first use: the task model imports the `cam` section (cam/spec.py) without the stage
_LAZY = {"LAW_NAMES": "laws", "LAWS": "laws", "Law": "laws", "get_law": "laws",
         "CamResult": "synthesis", "synthesize": "synthesis"}


def __getattr__(name):
    if name in _LAZY:
        import importlib
        return getattr(importlib.import_module(f".{_LAZY[name]}", __name__), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = ["synthesize", "CamResult", "LAWS", "LAW_NAMES", "Law", "get_law"]
