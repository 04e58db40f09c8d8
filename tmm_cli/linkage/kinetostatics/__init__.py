"""Kinetostatics (docs/methods.md §3): reactions in the pairs and the balancing moment, by
three methods (group by group, Zhukovsky's lever / virtual power, the matrix of all
equilibrium equations), singular positions of the chosen balance link, friction and
the instantaneous efficiency.

Public API::

    analyze(linkage, section, kin, *, motion=None) -> KinetostaticsResult     # the stage
        # .to_dict(): {"kinetostatics": [...], "kinetostatics_info": {...}, "singular": [...]}
    equilibrium(mech, structure, kin, loads, section, *, indices=None, crank_inertia=0.0)
        -> KinetostaticsResult          # on given kinematics and loads
    select_rows(spec, positions) -> list[int]                # kinetostatics.positions -> rows
    find_singular(mech, structure, balance) -> list[float]   # crank angles, deg
"""
from .analysis import (KinetostaticsResult, analyze, balance_index, equilibrium, find_singular, select_rows,
                       singular_function)

__all__ = ["analyze", "equilibrium", "select_rows", "find_singular", "KinetostaticsResult", "balance_index",
           "singular_function"]
