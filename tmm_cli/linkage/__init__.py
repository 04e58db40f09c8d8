"""The linkage: the lever mechanism and its stages.

``context`` (the typed, frozen ``Linkage`` and ``Drive`` every stage reads, built once
from the task), ``mechanism`` (the internal model built from the task), ``structure``
(Chebyshev's formula, Assur groups), ``kinematics`` (positions, velocities,
accelerations), ``loads`` (the forces applied to the links), ``kinetostatics``
(reactions, the Zhukovsky lever), ``dynamics`` (reduced moments, the flywheel),
``synthesis`` (the lever dimensions from the course's conditions) and ``drive_speed``
(the crank speed).  Each stage takes ``(linkage, its own section)``.
"""
