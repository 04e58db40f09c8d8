"""The pipeline: run every stage whose section is present, in order, and assemble
the results.json dict (README, *results.json*). Stages are pure functions; this module only wires
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
        kinematics_curve: int = 361, explore: bool = False) -> dict[str, Any]:
    """Compute every stage present in ``task``; return the results dict.

    ``kinematics_curve``: points of the output link's curve over one turn (0: none);
    ``explore``: also the kinematics at every degree of the turn (``kinematics_explore``,
    the mechanism in motion of report.html; made only for an HTML report and never
    written to results.json, see :func:`tmm_cli.orchestrate.write_outputs`).

    The independent parts (the linkage chain, cam, gears, planetary, dof2) each run
    even when another fails; a part stops at its first StageError.  If any part
    failed, :class:`PartialResults` is raised (for the first failure) whose
    ``partial`` holds every section computed, with ``error`` (the first failure) and
    ``errors`` (all of them: stage, message, position).
    """
    results: dict[str, Any] = {"schema": SCHEMA, "task": {"title": task.title, "variant": task.variant,
                                                          "file": task.file}}
    warnings: list[str] = list(task.input_warnings)
    results["warnings"] = warnings
    results["messages"] = []        # the warnings as data, filled in below
    say = progress or (lambda s: None)
    # independent parts: a failure of one is recorded and the others still run
    errors: list[StageError] = []

    def part(fn) -> None:
        try:
            fn()
        except StageError as err:
            errors.append(err)

    def simple(name, module, func, section, keep_warnings=False):
        """A stage of one section: results[name] = module.func(section).to_dict()."""
        def go():
            import importlib
            say(name)
            fn = getattr(importlib.import_module(f".{module}", __package__), func)
            results[name] = _stage(name)(fn)(section).to_dict()
            extra = results[name].get("warnings") if keep_warnings else results[name].pop("warnings", [])
            warnings.extend(extra or [])
        return go

    try:
        if task.synthesis is not None and task._synthesis_error is not None:
            say("synthesis")
            raise task._synthesis_error
        if task.mechanism is not None:
            part(lambda: _linkage(task, results, warnings, say, kinematics_curve, explore))
        if task.cam is not None:
            part(simple("cam", "cam", "synthesize", task.cam))
        if task.gears is not None:
            part(simple("gears", "gears", "analyze", task.gears))
        if task.planetary is not None:
            part(simple("planetary", "gears", "synthesize_planetary", task.planetary))
        if task.drive_train is not None:
            part(lambda: _drive_train(task, results, warnings, say))
        if task.dof2 is not None:
            part(simple("dof2", "dof2", "analyze", task.dof2, keep_warnings=True))
    except TaskError as err:
        # a stage found an invalid field: name the file and the field's line (exit 2)
        raise task.locate(err) from None
    # the hand method's own error (reading the drawings to 0.5 mm; 12-position flywheel)
    from .graphical import graphical_error
    ge = graphical_error(results)
    if ge is not None:
        results["graphical_error"] = ge
    # de-duplicate warnings, keep order; beside the English texts, their codes and parameters
    from .messages import as_dict
    seen = set()
    unique = [w for w in warnings if not (w in seen or seen.add(w))]
    results["warnings"] = [str(w) for w in unique]
    results["messages"] = [as_dict(w) for w in unique]
    if errors:
        # `error`: the first failure (as before); `errors`: every independent part that failed
        results["errors"] = [{"stage": e.stage, "message": e.message, "position": e.position}
                             for e in errors]
        results["error"] = results["errors"][0]
        raise PartialResults(errors[0], results) from errors[0]
    return results


def _drive_train(task: Task, results: dict, warnings: list, say) -> None:
    """The compound gear drive; with a flywheel, the flywheel moved to the motor shaft."""
    from .gears import train

    say("drive_train")
    drive = task.drive
    if drive is not None and drive.speed is None and "drive" in results:
        # the crank speed was found from the output's speed (results `drive`)
        drive = drive.model_copy(update={"speed": abs(float(results["drive"]["omega"]))})
    res = _stage("drive_train")(train.analyze)(task.drive_train, drive)
    results["drive_train"] = res.to_dict()
    warnings.extend(results["drive_train"].pop("warnings", []) or [])
    if task.flywheel is not None and "flywheel" in results:
        moved = train.motor_shaft(results["drive_train"], results["flywheel"], task.flywheel.constant)
        results["flywheel"].update(moved["flywheel"])
        if moved["motor_power"] is not None:
            results["drive_train"].update(motor_power=moved["motor_power"], motor_power_computed=True)


def _linkage(task: Task, results: dict, warnings: list, say, curve_n: int, explore: bool) -> None:
    import numpy as np

    from .linkage import kinematics, structure
    from .linkage.mechanism import build_mechanism

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
    if task.loads is not None:      # each loaded slider's own stroke (docs/methods.md §3.3)
        from .linkage import loads as loads_mod
        strokes = loads_mod.slider_strokes(mech, task.loads, positions)
        if strokes:
            results["positions"]["strokes"] = {k: s.to_dict() for k, s in strokes.items()}
    if task.synthesis is not None:
        say("synthesis")
        from .linkage.synthesis import analyse
        results["synthesis"] = _stage("synthesis")(analyse)(task._design, mech, task.drive.direction)

    # the crank speed: given, or from the output's speed with the stroke and K just found
    from .linkage import drive_speed
    omega1, source = drive_speed.resolve(task, positions)
    task = drive_speed.with_speed(task, omega1)
    results["drive"] = drive_speed.result(omega1, source)

    say("kinematics")
    phi = np.asarray(positions.phi, dtype=float)
    kin = _stage("kinematics")(kinematics.solve)(mech, phi, omega1)
    results["kinematics"] = kin.to_entries(list(positions.index))
    warnings.extend(getattr(kin, "warnings", []) or [])
    # a dense curve of the output link for the kinematic diagrams of the report
    if curve_n:
        results["kinematics_curve"] = _curve(kinematics, mech, positions, omega1, curve_n)
    if explore:
        # every point and link at each degree of the turn: the mechanism in motion of report.html
        from .linkage.kinematics.explore import explore_grid
        grid = _stage("kinematics")(explore_grid)(task, results)
        if grid is not None:
            results["kinematics_explore"] = grid

    dyn = None
    if task.flywheel is not None:
        say("dynamics")
        from .linkage import dynamics, loads as loads_mod
        # the accuracy table (timed) runs only in `tmm study` / `tmm run --study`
        dyn = _stage("dynamics")(dynamics.analyze_task)(mech, task, positions, accuracy=False)
        results["flywheel"] = dyn.to_dict()
        warnings.extend(results["flywheel"].pop("warnings", []) or [])

    if task.kinetostatics is not None:
        say("kinetostatics")
        from .linkage import kinetostatics, loads as loads_mod
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
    from .linkage import kinematics
    pos_section = task.positions or PositionsSection()
    extra_added: list[float] = []
    if task.loads is not None:
        from .linkage import loads as loads_mod
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
    # next to a change point a value without a finite limit is left out (null), not drawn
    vk, ak = ((f"v:{out.origin}", f"a:{out.origin}") if positions.output_kind == "slider"
              else (f"omega:{out.name}", f"epsilon:{out.name}"))
    v = np.where(kin.undefined.get(vk, False), np.nan, v)
    a = np.where(kin.undefined.get(ak, False), np.nan, a)
    return {"turn": turn.tolist(), "phi": phi.tolist(), "s": s.tolist(), "v": v.tolist(),
            "a": a.tolist(), "quantity": positions.output_kind}
