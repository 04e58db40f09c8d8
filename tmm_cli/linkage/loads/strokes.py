"""The stroke a load follows: the output's, or a loaded slider's own (docs/methods.md §3.3),
and the stroke state (working / idle, s/H) at crank angles."""
from __future__ import annotations

import numpy as np

from ...errors import field_error


def stroke_states(positions, phi: np.ndarray, kin=None) -> tuple[np.ndarray, np.ndarray]:
    """The stroke state at crank angles.

    Parameters
    ----------
    positions : PositionsResult
        The positions (``stroke_state``).
    phi : numpy.ndarray
        Crank angles, deg.
    kin : KinematicsResult or None
        The kinematics at ``phi`` (passed on so that it is not solved again).

    Returns
    -------
    tuple of numpy.ndarray
        (working: bool (N,), s/H (N,)).
    """
    phi = np.asarray(phi, float)
    try:
        st, s = positions.stroke_state(phi) if kin is None else positions.stroke_state(phi, kin=kin)
        st_arr = np.asarray(st)
        s_arr = np.asarray(s, float)
        if st_arr.shape == phi.shape and s_arr.shape == phi.shape:
            return st_arr == "working", s_arr
    except (TypeError, ValueError):
        pass
    work = np.zeros(phi.shape, bool)
    s = np.zeros(phi.shape)
    for k, p in enumerate(phi.ravel()):
        stk, sk = positions.stroke_state(float(p))
        work.ravel()[k] = stk == "working"
        s.ravel()[k] = float(sk)
    return work, s


def stroke_dependent(sp) -> bool:
    """Whether a load depends on a stroke.

    Parameters
    ----------
    sp : ForceSpec
        The load.

    Returns
    -------
    bool
        True for a load with a ``kind`` or a ``stroke`` and not a phi diagram.
    """
    return ((sp.kind is not None or "stroke" in sp.model_fields_set)
            and not (sp.diagram is not None and sp.diagram.phi is not None))


def load_stroke(positions, lk, sp, k: int):
    """The stroke a stroke-dependent load follows.

    Parameters
    ----------
    positions : PositionsResult
        The positions (the output's stroke).
    lk : Link
        The loaded link.
    sp : ForceSpec
        The load.
    k : int
        The load's index.

    Returns
    -------
    Stroke or PositionsResult
        A slider's own (its extremes, stroke H and working sense along its own guide:
        ``positions.stroke_for``); for a bar, the output's (``positions`` itself).

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: the working and idle strokes of a
    load (docs/methods.md §3.3); docs/methods.md §3.
    """
    working = sp.working
    if lk.kind != "slider":
        if working is not None:
            raise field_error(f"loads.forces[{k}].working", f"`working` sets the stroke of a slider; "
                                                            f"'{lk.name}' is not a slider")
        return positions
    return positions.stroke_for(lk.name, working)


def slider_strokes(mech, loads_section, positions) -> dict:
    """The own strokes of the loaded sliders other than the output.

    Parameters
    ----------
    mech : Mechanism
        The mechanism.
    loads_section : LoadsSection
        The task's ``loads``.
    positions : PositionsResult
        The positions.

    Returns
    -------
    dict
        name -> Stroke (a slider loaded in both senses: ``name (forward)`` and
        ``name (backward)``), for the results.
    """
    found = []
    for k, sp in enumerate(loads_section.forces):
        lk = mech.link(sp.on)
        if not (stroke_dependent(sp) and lk.kind == "slider"):
            continue
        st = load_stroke(positions, lk, sp, k)
        if (st.link, st.working) != (positions.output, positions.working) and \
                all((s.link, s.working) != (st.link, st.working) for s in found):
            found.append(st)
    names = [s.link for s in found]
    return {(s.link if names.count(s.link) == 1 else f"{s.link} ({s.working})"): s for s in found}
