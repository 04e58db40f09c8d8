"""Dynamics of the machine and the flywheel (docs/methods.md §4).

Public API:
    analyze(mech, kin_fn, loads_fn, section, drive, *, phi0=0.0, switch_angles=(), accuracy=True)
        -> DynamicsResult
    analyze_task(mech, task, positions) -> DynamicsResult        (the pipeline's call)
    analyze_sampler(sampler, section, omega_m, *, cycle, switch_q, phi0, sign, accuracy)
    solve_cycle(q, M_given, J_links, *, omega_m, delta, constant, method, J_extra, dJ_links)
    accuracy_table(sampler, section, omega_m, cycle, switch_q, resolutions)
    reduced_inertia(...), reduced_moment(...)                   (reduced quantities on arrays)
    flywheel.energy_mass / merzalov / wittenbauer / exact_flywheel / steady_motion / size
"""
from __future__ import annotations

from . import flywheel
from .analysis import (ACCURACY_RESOLUTIONS, EPS_DEG, CycleResult, DynamicsResult, accuracy_table,
                       analyze, analyze_sampler, analyze_task, grid, mechanism_sampler, solve_cycle)
from .reduce import Sample, reduced_inertia, reduced_moment, sample

__all__ = ["analyze", "analyze_task", "analyze_sampler", "solve_cycle", "accuracy_table", "grid",
           "mechanism_sampler", "DynamicsResult", "CycleResult", "Sample", "reduced_inertia",
           "reduced_moment", "sample", "flywheel", "ACCURACY_RESOLUTIONS", "EPS_DEG"]
