"""Loads on the links of a linkage, evaluated at the computed positions.

``evaluate(linkage, kin, *, inertia=True) -> Loads`` (``evaluate_on`` on the parts:
the mechanism, the section, the positions, the sense of rotation and the cycle) turns
the task's ``loads`` section (README, *loads*) into per-position applied forces (link,
point of application, force vector) and couples (link, moment), all (N,)-arrays
over the positions of ``kin``:

* gravity (``gravity: true``): G_i = m_i g along -y at S_i, g = 9.81 m/s^2;
* inertia loads (d'Alembert, docs/methods.md §3.1): F_in = -m a_S at S_i, M_in = -J_S eps_i;
* task forces. A force acts along the guide of a slider (unit vector e along the
  guide direction) or along ``direction`` (deg from +x, absolute) on any link; a bar
  with a resistance/driving force and no ``direction`` gets the force along the
  velocity of its point. Its point of application is ``at`` (a point name or local
  ``[u, v]``), default the link's centre of mass S.

  - ``kind: resistance`` opposes the motion of its point (F = -|P| e sign(v.e)),
    ``kind: driving`` acts along it; the magnitude |P| is ``magnitude`` (constant) or
    an ``s``-diagram over the relative stroke s/H in [0, 1] measured from the start of
    the stroke (working, idle or both) in which the load acts (``stroke``); outside
    that stroke the load is zero.  ``positions.stroke_state(phi)`` gives the stroke
    and s/H of the output link; at an extreme position (velocity zero) the stroke that
    begins there applies (position 0 carries the working-stroke load), and the sense
    of motion is that of the motion about to begin (the sign of the acceleration
    analogue d2r/dphi2 . e, since v = 0 there).
  - a ``phi``-diagram is the signed force along e over the crank angle of the cycle
    **measured from position 0** (phi_rel = (phi - phi0) * sign(omega1) mod cycle, so
    an engine's indicator diagram starts at its TDC = position 0; for a 720-deg cycle
    the reported positions are read in the first turn after position 0 and unwrapped
    angles phi0 + sign*q, q in [360, 720), in the second: see cycle_angle). Between the given
    abscissae the value is interpolated linearly, beyond them it is held constant.
    ``stroke`` and ``kind`` do not change a phi-diagram (the sign is in the diagram).
  - a force with no ``kind`` and a ``magnitude`` or an ``s``-diagram is a signed force
    along e; it acts over the whole cycle unless ``stroke`` is given explicitly.
  - ``area``: the magnitude / diagram values are pressures (Pa), force = p * area.
  - ``moment``: a couple, ccw positive; with ``kind: resistance`` (``driving``) it is
    |M| against (along) the rotation of its link, on ``stroke``; without a kind it is
    the signed constant couple over the whole cycle (or over ``stroke`` if given).

  A diagram with a repeated abscissa (``s: [0, 0.2, 0.2, 1]``) jumps there; at the
  jump the value after it (in the direction of motion) applies.
  ``switch_angles(mech, loads_section, positions, sign=..., cycle=...)`` gives the crank
  angles of such jumps inside a stroke, which the pipeline adds as extra positions.

Modules: ``model`` (AppliedForce, AppliedCouple, Loads), ``applied`` (evaluate),
``diagrams`` (interpolation, the cycle angle), ``strokes`` (the stroke a load follows),
``switching`` (switch_angles).

All of this follows docs/methods.md §3.1 and, where it is silent, Artobolevsky's and Popov's
textbooks (force of production resistance acting against the motion of the
working member over the working stroke given by its diagram over the stroke).
"""
from __future__ import annotations

from .applied import evaluate, evaluate_on, link_loads, point_motion
from .diagrams import cycle_angle, interp_right
from .model import G, AppliedCouple, AppliedForce, Loads
from .strokes import load_stroke, slider_strokes, stroke_states
from .switching import switch_angles

__all__ = ["AppliedForce", "AppliedCouple", "Loads", "evaluate", "evaluate_on", "link_loads", "switch_angles",
           "slider_strokes", "load_stroke", "point_motion", "interp_right", "stroke_states", "cycle_angle", "G"]
