"""Kinematics of planar linkages (docs/methods.md §0 and §2).

Public API (docs/ARCHITECTURE.md)::

    solve(mech, phi_deg, omega1, eps1=0.0) -> KinematicsResult
    find_positions(mech, positions_section, drive_section, extra_added=()) -> PositionsResult
    check_assembly(mech, n=720) -> list[str]
"""
from .positions import PositionsResult, find_positions
from .result import KinematicsResult
from .solver import check_assembly, solve

__all__ = ["solve", "KinematicsResult", "find_positions", "PositionsResult", "check_assembly"]
