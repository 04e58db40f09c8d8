"""Dynamics of the machine and the flywheel (docs/methods.md §4).

Public API:
    analyze(linkage, section, *, accuracy=True) -> DynamicsResult      (the stage)
    analyze_sampler(sampler, section, omega_m, *, cycle, switch_q, phi0, sign, accuracy)
    solve_cycle(q, M_given, J_links, *, omega_m, delta, constant, method, J_extra, dJ_links)
    grid(resolution, cycle, switch_q), run_grid(sampler, section, ...), mechanism_sampler(...)
    accuracy_table(sampler, section, omega_m, cycle, switch_q, resolutions), hand_row(...)
    reduced_inertia(...), reduced_moment(...)                   (reduced quantities on arrays)
    flywheel.energy_mass / merzalov / wittenbauer / exact_flywheel / steady_motion / size
"""
from __future__ import annotations

from . import flywheel
from .analysis import analyze, analyze_sampler
from .convergence import ACCURACY_RESOLUTIONS, accuracy_table, hand_row
from .cycle import EPS_DEG, CycleResult, grid, mechanism_sampler, run_grid, solve_cycle
from .reduce import Sample, reduced_inertia, reduced_moment, sample
from .result import DynamicsResult

__all__ = ["analyze", "analyze_sampler", "solve_cycle", "accuracy_table", "hand_row", "grid", "run_grid",
           "mechanism_sampler", "DynamicsResult", "CycleResult", "Sample", "reduced_inertia",
           "reduced_moment", "sample", "flywheel", "ACCURACY_RESOLUTIONS", "EPS_DEG"]
