"""The pipeline: run every stage whose section is present, in order, and assemble
the results.json dict (README, *results.json*). Stages are pure functions; this module only wires
them together. Nothing here writes files.
"""
from __future__ import annotations

from typing import Any, Callable

from .errors import StageError, TaskError, guarded as _stage
from .task import Task

SCHEMA = "tmm-results/1"


class PartialResults(StageError):
    """A StageError carrying what was computed before the failure (``partial``) and, once
    they are written, the files written with it (``written``)."""

    def __init__(self, err: StageError, partial: dict):
        super().__init__(err.stage, err.message, err.position)
        self.partial = partial
        self.written: list | None = None      # the files written with the partial results
        self.__cause__ = err


def run(task: Task, *, progress: Callable[[str], None] | None = None,
        kinematics_curve: int = 361, explore: bool = False, mechanism=None) -> dict[str, Any]:
    """Compute every stage present in ``task``; return the results dict (the
    kinematics and kinetostatics entries as :class:`tmm_cli.results.LazyEntries`, made
    when read; ``tmm_cli.run`` gives them as lists).

    ``kinematics_curve``: points of the output link's curve over one turn (0: none);
    ``explore``: also the kinematics at every degree of the turn (``kinematics_explore``,
    the mechanism in motion of report.html; made only for an HTML report and never
    written to results.json, see :func:`tmm_cli.orchestrate.write_outputs`);
    ``mechanism``: the task's linkage already built and checked over the cycle
    (``orchestrate.checked``), computed on as it is.

    A ``synthesis`` is the first stage: it generates the mechanism the linkage's stages
    compute (``linkage.synthesis.generate``); an impossible one is raised at once (exit 3).

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
    built: dict = {}        # parts of the linkage context other parts read (the Drive)

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
            put(results, warnings, name, _stage(name)(fn)(section), keep_warnings=keep_warnings)
        return go

    try:
        design = None
        if task.synthesis is not None:
            from .linkage.synthesis import SynthesisImpossible, generate
            try:
                task, design = generate(task)
            except SynthesisImpossible:
                say("synthesis")
                raise
        if task.mechanism is not None:
            part(lambda: _linkage(task, results, warnings, say, kinematics_curve, explore, built, mechanism, design))
        if task.cam is not None:
            part(simple("cam", "cam", "synthesize", task.cam))
        if task.gears is not None:
            part(simple("gears", "gears", "analyze", task.gears))
        if task.planetary is not None:
            part(simple("planetary", "gears", "synthesize_planetary", task.planetary))
        if task.drive_train is not None:
            part(lambda: _drive_train(task, results, warnings, say, built.get("drive", task.drive)))
        if task.balancing is not None and task.mechanism is None:
            part(lambda: _rotor_only(task, results, say))
        if task.differential is not None:
            part(simple("differential", "differential", "analyze", task.differential))
        if task.dof2 is not None:
            part(simple("dof2", "dof2", "analyze", task.dof2, keep_warnings=True))
    except TaskError as err:
        # a stage found an invalid field: name the file and the field's line (exit 2)
        raise task.locate(err) from None
    # the hand method's own error (reading the drawings to 0.5 mm; 12-position flywheel); it
    # reads every kinematics entry several times: they are listed once and kept (the
    # results file and the report read them again; the kinetostatics entries stay lazy)
    from .graphical import graphical_error
    from .results import listed
    if results.get("structure") and results.get("kinematics"):
        results["kinematics"] = listed(results["kinematics"])
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
        results["errors"] = [e.to_dict() for e in errors]
        results["error"] = results["errors"][0]
        raise PartialResults(errors[0], results) from errors[0]
    return results


def run_listed(task: Task, **kwargs) -> dict[str, Any]:
    """:func:`run` with the per-position entries as lists (``tmm_cli.results.listed``), in
    the results and in a PartialResults' ``partial``: for readers that take them many times."""
    from .results import listed
    try:
        return listed(run(task, **kwargs))
    except PartialResults as exc:
        exc.partial = listed(exc.partial)
        raise


def _drive_train(task: Task, results: dict, warnings: list, say, drive) -> None:
    """The compound gear drive (``drive``: the linkage's Drive, or the task's `drive`
    section when there is no linkage); with a flywheel, the flywheel moved to the motor shaft."""
    from .gears import train

    say("drive_train")
    put(results, warnings, "drive_train", _stage("drive_train")(train.analyze)(task.drive_train, drive))
    if task.flywheel is not None and "flywheel" in results:
        moved = train.motor_shaft(results["drive_train"], results["flywheel"], task.flywheel.constant)
        results["flywheel"].update(moved["flywheel"])
        if moved["motor_power"] is not None:
            results["drive_train"].update(motor_power=moved["motor_power"], motor_power_computed=True)


def put(results: dict, warnings: list, name: str | None, res, *, keep_warnings: bool = False) -> None:
    """A stage's result into the results: its ``to_dict()`` as ``results[name]`` (``name``
    None: the dict is the results' sections, as kinetostatics gives them), its
    ``warnings`` to the top-level warnings (kept in the section too with ``keep_warnings``)."""
    d = res.to_dict()
    if not keep_warnings:
        d.pop("warnings", None)
    if name is None:
        results.update(d)
    else:
        results[name] = d
    warnings.extend(res.warnings)


def massless_links(task: Task, mech) -> list:
    """A warning naming the moving links without mass where inertia is taken into account
    (kinetostatics with inertia, or a flywheel): no inertia force acts on them."""
    from .messages import Message
    kst = task.kinetostatics is not None and task.kinetostatics.inertia
    if not (kst or task.flywheel is not None):
        return []
    names = [lk.name for lk in mech.links if not lk.mass > 0]
    if not names:
        return []
    return [Message("inertia.massless_flywheel" if task.flywheel is not None else "inertia.massless", links=names)]


def _linkage(task: Task, results: dict, warnings: list, say, curve_n: int, explore: bool, built: dict,
             checked=None, design=None) -> None:
    """The linkage chain: its context (structure, positions, the crank speed: each part
    written to the results as it is made), the synthesis's analysis (``design``), then
    kinematics, dynamics (``flywheel``) and kinetostatics. ``checked``: the mechanism
    validation built and checked over the cycle (else built and checked here)."""
    from .linkage import dynamics, kinematics, kinetostatics
    from .linkage.context import build
    from .linkage.kinematics.positions import stroke_warnings
    from .validation import check_detail, impossible_dimensions
    from .messages import Message

    mech = checked
    over = design.crank_range if design is not None else None   # a function generator's input range

    def told(part, value) -> None:
        nonlocal mech
        if part == "structure":
            mech, st = value
            results["structure"] = {**st.to_dict(), **mech.structure_info()}
            warnings.extend(st.warnings)
            say("positions")
            if over is not None:            # over the input range only (exit 3 naming where not)
                if checked is None:
                    from .linkage.synthesis import check_range
                    check_range(mech, over)
                return
            try:
                if checked is None:
                    kinematics.check_assembly(mech)
            except StageError as err:
                raise impossible_dimensions(task, err) or err
            return
        positions = value
        check_detail(task, positions)
        warnings.extend(stroke_warnings(positions))
        warnings.extend(massless_links(task, mech))
        if over is not None:
            warnings.append(Message("positions.input_range", kind=over.kind, count=positions.count, start=float(over.start),
                                    end=float(over.start + over.span)))
            if task.positions is not None and "zero" in task.positions.model_fields_set:
                warnings.append(Message("positions.zero_range", start=float(over.start)))
        results["positions"] = positions.to_dict()
        # the position the report works step by step (report.detail_position, or the default)
        detail = task.report.detail_position if task.report is not None else None
        results["positions"]["detail_position"] = detail if detail is not None else \
            default_detail(results["positions"])
        if task.loads is not None:      # each loaded slider's own stroke (docs/methods.md §3.3)
            from .linkage.loads import slider_strokes
            strokes = slider_strokes(mech, task.loads, positions)
            if strokes:
                results["positions"]["strokes"] = {k: s.to_dict() for k, s in strokes.items()}

    say("structure")
    # the crank speed: given, or from the output's speed with the stroke and K just found
    linkage = build(task, mechanism=checked, kinks=task.flywheel is not None and over is None, told=told,
                    crank_range=over)
    mech, positions, drive = linkage.mechanism, linkage.positions, linkage.drive
    built["drive"] = drive
    # each dyad's least transmission angle over the cycle (its input range for a generator):
    # found before a synthesis, which reports the least of them too (one search for both)
    from .linkage import transmission
    trans = None
    if design is not None:
        say("synthesis")
        from .linkage.synthesis import analyse, least_of
        trans = _stage("kinematics")(transmission.analyze)(linkage, over)
        results["synthesis"] = _stage("synthesis")(analyse)(linkage, design, least_of(trans))
        warnings.extend(results["synthesis"].pop("warnings", ()))     # the path's miss of its points
    results["drive"] = drive.to_dict()

    say("kinematics")
    kin = _stage("kinematics")(kinematics.analyze)(linkage)
    results["kinematics"] = kin.to_entries(list(positions.index))
    # a generator over its input range: the synthesis chose the closure (that of its precision
    # points, hinted at the angle the solver reads hints at), so that angle is no news to the user
    warnings.extend(w for w in kin.warnings if over is None or not (isinstance(w, Message)
                                                                     and w.code == "kinematics.closure_not_at_zero"))
    if trans is None:
        trans = _stage("kinematics")(transmission.analyze)(linkage, over)
    if trans:
        results["transmission"] = trans
        warnings.extend(transmission.warnings(trans))
    # a dense curve of the output link for the kinematic diagrams of the report
    if curve_n:
        results["kinematics_curve"] = kinematics.output_curve(linkage, curve_n).to_dict()
    if explore:
        # every point and link at each degree of the turn: the mechanism in motion of report.html
        from .linkage.kinematics.explore import explore_grid
        results["kinematics_explore"] = _stage("kinematics")(explore_grid)(linkage)

    skipped = {} if over is None else {"start": float(over.start), "end": float(over.start + over.span)}
    if task.balancing is not None and skipped:      # a full turn is needed: said, never silent
        warnings.append(Message("balancing.skipped_range", **skipped))
    elif task.balancing is not None:
        say("balancing")
        import numpy as np

        from . import balancing
        grid = kinematics.solve(mech, np.arange(361) * 1.0, drive.omega)   # the hodographs over the turn
        bal = _stage("balancing")(balancing.analyze)(mech, kin, task.balancing, grid)
        put(results, warnings, "balancing", bal)
        if task.balancing.apply and task.kinetostatics is None and task.flywheel is None:
            warnings.append(Message("balancing.apply_unused"))      # said, not silently without effect
        elif task.balancing.apply:
            # the later stages see the links with their counterweights (geometry unchanged; the
            # centres of mass moved): results' kinematics stay those of the task's links
            import dataclasses

            from .balancing.linkage import with_counterweights
            linkage = dataclasses.replace(linkage, mechanism=with_counterweights(mech, bal.weights))
            kin = _stage("kinematics")(kinematics.analyze)(linkage)

    dyn = None
    if task.flywheel is not None and skipped:
        warnings.append(Message("flywheel.skipped_range", **skipped))
    elif task.flywheel is not None:
        say("dynamics")
        # the accuracy table (timed) runs only in `tmm study` / `tmm run --study`
        dyn = _stage("dynamics")(dynamics.analyze)(linkage, task.flywheel, accuracy=False)
        put(results, warnings, "flywheel", dyn)

    if task.kinetostatics is not None:
        say("kinetostatics")
        put(results, warnings, None,
            _stage("kinetostatics")(kinetostatics.analyze)(linkage, task.kinetostatics, kin, motion=dyn))
        results.setdefault("kinetostatics_info", {})["motion"] = \
            "steady" if task.kinetostatics.motion is True else "constant"
        if results.get("singular"):
            # the mechanism at each singular angle of the balance link (the report draws it)
            from .linkage.kinematics.stage import positions_at
            results["singular_positions"] = _stage("kinematics")(positions_at)(linkage, results["singular"])
        if explore and "kinematics_explore" in results:
            # the force polygons and the lever of the mechanism in motion (report.html only):
            # the same analysis at the explore grid's crank angles
            import numpy as np
            g = results["kinematics_explore"]
            n = len(g["turn"])
            phi_g = np.mod(positions.phi0 + g["sign"] * np.arange(n) * g["step"], 360.0)
            res_g = _stage("kinetostatics")(kinetostatics.analyze_at)(
                linkage, task.kinetostatics, phi_g, motion=dyn, singular=results.get("singular"))
            kg = res_g.to_dict(detail=True)
            results["kinetostatics_explore"] = {"entries": kg["kinetostatics"], **kg["kinetostatics_info"]}


def _rotor_only(task: Task, results: dict, say) -> None:
    """`balancing` without a mechanism: the rotor alone (counterweights need a linkage: exit 2)."""
    from .messages import Message
    if task.balancing.counterweights is not None:
        raise task.error(("balancing", "counterweights"), Message("input.balancing_needs_mechanism"))
    if task.balancing.rotor is not None:
        say("balancing")
        from .balancing.rotor import balance_rotor
        results["balancing"] = {"rotor": _stage("balancing")(balance_rotor)(task.balancing.rotor)}


def default_detail(positions: dict) -> int | None:
    """The first working-stroke position after 0 (results ``positions``): the first grid
    position (index >= 1, in the order of the positions) whose crank angle lies strictly
    inside the working stroke [extreme start, + working stroke angle] counted in the sense
    of rotation; position 1 when the output has no extremes; None without positions."""
    idx, phi = list(positions.get("index") or []), list(positions.get("phi") or [])
    kinds = list(positions.get("kinds") or ["grid"] * len(idx))
    grid = [(i, f) for i, f, k in zip(idx, phi, kinds) if k == "grid" and i >= 1]
    if not grid:
        return idx[0] if idx else None
    ext, ws = positions.get("extreme"), positions.get("working_stroke_angle")
    if not ext or ws is None:
        return grid[0][0]
    sign = 1.0 if positions.get("direction", "ccw") == "ccw" else -1.0
    for i, f in grid:
        turn = (sign * (float(f) - float(ext[0]))) % 360.0
        if 1e-9 < turn < float(ws) - 1e-9:
            return i
    return grid[0][0]
