"""Machines with two degrees of freedom (docs/methods.md §7): the rotary impact mechanism.

A rotor O-O1 turns about the fixed point O; a striker O1-M is hinged to it at O1
(a double pendulum).  Its motion follows Lagrange's equations of the second kind in
the generalised coordinates phi (rotor) and psi (striker relative to the rotor);
the dynamic reactions in O and O1 follow from the theorem on the motion of the centre
of mass of each link (after V.V. Voronkin, docs/methods.md §10).

* :class:`Dof2Section` -- the task section ``dof2:`` (spec.py);
* :func:`analyze` ``(section) -> Dof2Result``; ``Dof2Result.to_dict()`` is the
  results.json section ``dof2`` (analysis.py);
* model.py -- the equations (mass matrix, accelerations, reactions, energy).
"""
from .spec import Dof2Section

# the task model imports Dof2Section; the analysis (numpy) loads on first use
_LAZY = {"Dof2Result": "analysis", "analyze": "analysis", "centrifugal_pendulum": "analysis",
         "Params": "model"}


def __getattr__(name):
    if name in _LAZY:
        import importlib
        return getattr(importlib.import_module(f".{_LAZY[name]}", __name__), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")

__all__ = ["Dof2Section", "Dof2Result", "analyze", "centrifugal_pendulum", "Params"]
