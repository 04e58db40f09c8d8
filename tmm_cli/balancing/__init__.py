"""Balancing (uravnoveshivanie): the shaking force and moment of a linkage, counterweights
(the full force balancing of a four-bar, Berkof-Lowen; the crank counterweight of a
slider-crank), and static / dynamic balancing of a rigid rotor.

* :class:`BalancingSection` -- the task section ``balancing:`` (spec.py);
* :func:`shaking` ``(mech, kin, about) -> Shaking`` and :func:`counterweights`
  ``(mech, kin, spec) -> Counterweights`` (linkage.py): the linkage's part, after its kinematics;
* :func:`balance_rotor` ``(spec) -> dict`` (rotor.py): runs on its own;
* :func:`analyze` ``(mech, kin, spec) -> BalancingResult`` (linkage.py): the results.json
  section ``balancing``.
"""
from .spec import BalancingSection

_LAZY = {"analyze": "linkage", "shaking": "linkage", "counterweights": "linkage", "BalancingResult": "linkage",
         "balance_rotor": "rotor"}


def __getattr__(name):
    if name in _LAZY:
        import importlib
        return getattr(importlib.import_module(f".{_LAZY[name]}", __name__), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = ["BalancingSection", "analyze", "shaking", "counterweights", "BalancingResult", "balance_rotor"]
