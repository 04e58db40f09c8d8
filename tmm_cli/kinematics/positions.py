"""placeholder replaced below"""
from dataclasses import dataclass


@dataclass
class PositionsResult:
    pass


def find_positions(mech, positions_section, drive_section, extra_added=()):
    raise RuntimeError("not yet")
