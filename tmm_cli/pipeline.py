"""The pipeline: run every stage whose section is present, in order, and assemble
the results.json dict (SPEC 3). Stages are pure functions; this module only wires
them together. Nothing here writes files.
"""
from __future__ import annotations

from typing import Any, Callable

from .errors import StageError, TaskError
from .task import PositionsSection, Task

SCHEMA = "tmm-results/1"


class PartialResults(StageError):
    """A StageError carrying what was computed before the failure."""

    def __init__(self, err: StageError, partial: dict):
        super().__init__(err.stage, err.message, err.position)
        self.partial = partial
        self.__cause__ = err


def _stage(name: str):
    """Run a stage function; turn unexpected numerical failures into StageError."""
    def deco(fn):
        def wrapper(*a, **kw):
            try:
                return fn(*a, **kw)
            except StageError:
                raise
            except (ArithmeticError, ValueError, IndexError, KeyError, RuntimeError,
                    __import__("numpy").linalg.LinAlgError) as exc:
                raise StageError(name, f"{type(exc).__name__}: {exc}") from exc
        return wrapper
    return deco


def run(task: Task, *, progress: Callable[[str], None] | None = None,
        kinematics_curve: int = 361) -> dict[str, Any]:
    """Compute every stage present in ``task``; return the results dict.

    On a StageError the error is re-raised as :class:`PartialResults` whose
    ``partial`` holds every section computed before the failure.
    """
    results: dict[str, Any] = {"schema": SCHEMA, "task": {"title": task.title, "variant": task.variant,
                                                          "file": task.file}}
    warnings: list[str] = []
    results["warnings"] = warnings
    say = progress or (lambda s: None)
    try:
        if task.mechanism is not None:
            _linkage(task, results, warnings, say, kinematics_curve)
        if task.cam is not None:
            say("cam")
            from . import cam
            res = _stage("cam")(cam.synthesize)(task.cam)
            results["cam"] = res.to_dict()
            warnings.extend(results["cam"].pop("warnings", []) or [])
        if task.gears is not None:
            say("gears")
            from . import gears
            res = _stage("gears")(gears.analyze)(task.gears)
            results["gears"] = res.to_dict()
            warnings.extend(results["gears"].pop("warnings", []) or [])
        if task.planetary is not None:
            say("planetary")
            from . import gears
            res = _stage("planetary")(gears.synthesize_planetary)(task.planetary)
            results["planetary"] = res.to_dict()
            warnings.extend(results["planetary"].pop("warnings", []) or [])
        if task.dof2 is not None:
            say("dof2")
            from . import dof2
            res = _stage("dof2")(dof2.analyze)(task.dof2)
            results["dof2"] = res.to_dict()
            warnings.extend(results["dof2"].get("warnings", []) or [])
    except StageError as err:
        results["error"] = {"stage": err.stage, "message": err.message,
                            "position": err.position}
        raise PartialResults(err, results) from err
    except TaskError as err:
        # a stage found an invalid field: name the file and the field's line (SPEC 2)
        raise task.locate(err) from None
    # de-duplicate warnings, keep order
    seen = set()
    results["warnings"] = [w for w in warnings if not (w in seen or seen.add(w))]
    return results


def _linkage(task: Task, results: dict, warnings: list, say, curve_n: int) -> None:
    import numpy as np

    from . import kinematics, structure
    from .mechanism import build_mechanism

    say("structure")
    mech = build_mechanism(task)
    st = structure.analyze(mech, task=task)
    sd = st.to_dict()
    sd.update(mech.structure_info())
    results["structure"] = sd
    warnings.extend(getattr(st, "warnings", []) or [])

    say("positions")
    from .validation import impossible_dimensions
    try:
        kinematics.check_assembly(mech)
    except StageError as err:
        raise impossible_dimensions(task, err) or err
    positions = find_positions(task, mech)
    results["positions"] = positions.to_dict()

    say("kinematics")
    omega1 = task.drive.omega1
    phi = np.asarray(positions.phi, dtype=float)
    kin = _stage("kinematics")(kinematics.solve)(mech, phi, omega1)
    results["kinematics"] = kin.to_entries(list(positions.index))
    warnings.extend(getattr(kin, "warnings", []) or [])
    # a dense curve of the output link for the kinematic diagrams of the report
    if curve_n:
        results["kinematics_curve"] = _curve(kinematics, mech, positions, omega1, curve_n)

    dyn = None
    if task.flywheel is not None:
        say("dynamics")
        from . import dynamics, loads as loads_mod
        dyn = _stage("dynamics")(dynamics.analyze_task)(mech, task, positions)
        results["flywheel"] = dyn.to_dict()
        warnings.extend(results["flywheel"].pop("warnings", []) or [])

    if task.kinetostatics is not None:
        say("kinetostatics")
        from . import kinetostatics, loads as loads_mod
        ks = task.kinetostatics
        sel = _select(ks.positions, positions, task)
        kin_k = kin
        crank_J = 0.0
        if ks.motion is True:
            if dyn is None:
                raise task.error(("kinetostatics", "motion"), "`motion: true` needs a `flywheel` section "
                                 "(the steady motion comes from the flywheel)")
            w = dyn.omega_of(phi)
            e = dyn.epsilon_of(phi)
            kin_k = _stage("kinematics")(kinematics.solve)(mech, phi, w, e)
            crank_J = float(dyn.J_fly) + float(task.flywheel.reduced_J)
        lds = _stage("kinetostatics")(loads_mod.evaluate)(mech, task.loads, kin_k, positions,
                                                           inertia=ks.inertia)
        res = _stage("kinetostatics")(kinetostatics.analyze)(mech, st, kin_k, lds, ks, indices=sel,
                                                             crank_inertia=crank_J)
        kd = res.to_dict()
        results["kinetostatics"] = kd["entries"] if isinstance(kd, dict) and "entries" in kd else kd
        if isinstance(kd, dict):
            for k, v in kd.items():
                if k not in ("entries", "singular", "warnings"):
                    results.setdefault("kinetostatics_info", {})[k] = v
            results["singular"] = kd.get("singular", [])
            warnings.extend(kd.get("warnings", []) or [])
        else:
            results["singular"] = list(getattr(res, "singular", []))


def find_positions(task: Task, mech):
    """The positions of the cycle (the grid, the extra and extreme angles, the load
    switch points), as the pipeline computes them; also used by validation."""
    from . import kinematics
    pos_section = task.positions or PositionsSection()
    extra_added: list[float] = []
    if task.loads is not None:
        from . import loads as loads_mod
        pos0 = _stage("positions")(kinematics.find_positions)(mech, pos_section, task.drive)
        extra_added = list(loads_mod.switch_angles(mech, task.loads, pos0))
    return _stage("positions")(kinematics.find_positions)(mech, pos_section, task.drive,
                                                           extra_added=extra_added)


def check_selection(task: Task, mech) -> None:
    """A TaskError when `kinetostatics.positions` names a position the cycle does not have."""
    if task.kinetostatics is not None and task.kinetostatics.positions != "all":
        _select(task.kinetostatics.positions, find_positions(task, mech), task)


def _select(spec, positions, task: Task) -> list[int]:
    """Row numbers (into positions.phi) of the positions to analyse."""
    idx = list(positions.index)
    if spec == "all":
        return list(range(len(idx)))
    rows = []
    for k, i in enumerate(spec):
        if i not in idx:
            raise task.error(("kinetostatics", "positions", k),
                             f"position {i} does not exist (positions are {idx[0]}..{idx[-1]})")
        rows.append(idx.index(i))
    return rows


def _curve(kinematics, mech, positions, omega1, n: int) -> dict:
    """s, v, a of the output link over one turn from position 0 (kinematic diagrams):
    a slider's displacement along its guide from position 0 (m), velocity and
    acceleration along the guide; a rocker's angle from position 0 (deg), omega, epsilon."""
    import numpy as np

    sign = 1.0 if omega1 > 0 else -1.0
    turn = np.linspace(0.0, 360.0, n)
    phi = np.mod(positions.phi0 + sign * turn, 360.0)
    kin = kinematics.solve(mech, phi, omega1)
    out = mech.link(positions.output)
    s, _ = positions.output_value(phi)
    s0, _ = positions.output_value([positions.phi0])
    s = np.asarray(s, float) - float(s0[0])
    if positions.output_kind == "slider":
        ang = np.asarray(kin.angle[out.name])
        u = np.stack([np.cos(ang), np.sin(ang)], axis=1)
        v = np.einsum("ij,ij->i", kin.vel(out.origin), u)
        a = np.einsum("ij,ij->i", kin.acc(out.origin), u)
    else:
        s = np.mod(s + 180.0, 360.0) - 180.0
        v = np.asarray(kin.omega(out.name)) * np.ones_like(phi)
        a = np.asarray(kin.epsilon(out.name)) * np.ones_like(phi)
    return {"turn": turn.tolist(), "phi": phi.tolist(), "s": s.tolist(), "v": v.tolist(),
            "a": a.tolist(), "quantity": positions.output_kind}
