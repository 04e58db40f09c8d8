"""Kinetostatics (docs/methods.md §3): reactions in the pairs and the balancing moment, by
three methods (group by group, Zhukovsky's lever / virtual power, the matrix of all
equilibrium equations), singular positions of the chosen balance link, friction and
the instantaneous efficiency.

Public API::

    analyze(mech, structure, kin, loads, section, *, indices=None, crank_inertia=0.0)
        -> KinetostaticsResult          # .to_dict(): {"entries": [...], "singular": [...], ...}
    find_singular(mech, structure, balance) -> list[float]   # crank angles, deg
    analyze_task(mech, structure, task, positions, phi_deg, kin, *, dyn=None, indices=None,
                 singular=None) -> KinetostaticsResult   # loads and motion of the task, as the pipeline
"""
from .analysis import KinetostaticsResult, analyze, analyze_task, balance_index, find_singular, singular_function

__all__ = ["analyze", "analyze_task", "find_singular", "KinetostaticsResult", "balance_index", "singular_function"]
