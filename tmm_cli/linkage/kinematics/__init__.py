"""Kinematics of planar linkages (docs/methods.md §0 and §2).

Public API (docs/ARCHITECTURE.md)::

    analyze(linkage) -> KinematicsResult                 # the stage: at the reported positions
    output_curve(linkage, n=361, turn=None) -> OutputCurve   # the output's s, v, a over a turn
    solve(mech, phi_deg, omega1, eps1=0.0) -> KinematicsResult
    solve_raw(mech, phi_deg, omega1, eps1=0.0) -> KinematicsResult   # without the change-point marks and limits
    find_positions(mech, positions_section, sign, extra_added=(), *, crank_range=None) -> PositionsResult
    check_assembly(mech, n=720) -> list[str]
"""
from .positions import PositionsResult, find_positions
from .result import KinematicsResult
from .solver import check_assembly, solve, solve_raw
from .stage import OutputCurve, analyze, output_curve

__all__ = ["analyze", "output_curve", "OutputCurve", "solve", "solve_raw", "KinematicsResult", "find_positions",
           "PositionsResult", "check_assembly"]
