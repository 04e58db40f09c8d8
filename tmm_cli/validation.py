"""`tmm validate`: checks beyond the schema."""
from __future__ import annotations

from .errors import StageError, TaskError, guarded
from .messages import Message
from .messages import as_message as _coded


def check_feasible(task, assembly: bool = True, crank_range=None):
    """Raise TaskError / StageError if the task's linkage cannot be computed:
    bad references between points, links and guides; W != 1; and (with
    ``assembly``) a crank angle where some group does not assemble (over the turn, or
    over ``crank_range``, a ``linkage.context.CrankRange`` a synthesis gave: a function
    generator whose crank does not turn fully; ``synthesis.check_range``).  Returns the
    mechanism built and checked over the cycle (None without ``assembly``): the pipeline
    computes on it (``pipeline.run``'s ``mechanism``) instead of building and checking it
    again."""
    from .linkage.mechanism import build_mechanism

    mech = build_mechanism(task)
    if not assembly:
        return None
    from .linkage import kinematics, structure

    structure.analyze(mech, task=task)
    if crank_range is not None:
        from .linkage.synthesis import check_range
        check_range(mech, crank_range)
    else:
        try:
            kinematics.check_assembly(mech)
        except StageError as err:
            raise impossible_dimensions(task, err) or err
    try:
        check_selection(task, mech, crank_range)
    except TaskError as err:
        raise task.locate(err) from None
    return mech


def check_sections(task, mech) -> None:
    """The checks of the other sections that need no computing, made when the task is validated
    (a run meets them again in its stages): a differential's or a drive train's given teeth that
    cannot be built (coaxiality, adjacency, an internal pair without a larger ring), and
    counterweights by a method the linkage ``mech`` (None: not built) is not the kind of. A
    TaskError naming the field and its line (exit 2): `tmm validate` said 'ok' to each of them."""
    try:
        if task.differential is not None:
            from .differential.analysis import check_buildable
            check_buildable(task.differential)
        if task.drive_train is not None:
            from .gears.train import check_given
            check_given(task.drive_train)
        if mech is not None and task.balancing is not None and task.balancing.counterweights is not None:
            from .balancing.linkage import check_kind
            check_kind(mech, task.balancing.counterweights)
    except TaskError as err:
        raise task.locate(err) from None


def check_selection(task, mech, crank_range=None) -> None:
    """A TaskError when `kinetostatics.positions` or `report.detail_position` names a
    position the cycle (or the crank range) does not have."""
    sel = task.kinetostatics is not None and task.kinetostatics.positions != "all"
    detail = task.report is not None and task.report.detail_position is not None
    if not (sel or detail):
        return
    from .linkage.context import reported_positions
    from .linkage.kinetostatics import select_rows
    positions = guarded("positions")(reported_positions)(mech, task.positions, task.loads, task.drive.sign,
                                                        float(task.drive.cycle), crank_range=crank_range)
    if sel:
        select_rows(task.kinetostatics.positions, positions)
    check_detail(task, positions)


def check_detail(task, positions) -> None:
    """`report.detail_position` must be one of the positions (TaskError, exit 2)."""
    n = task.report.detail_position if task.report is not None else None
    idx = list(positions.index)
    if n is not None and n not in idx:
        raise task.error(("report", "detail_position"),
                         f"position {n} does not exist (positions are {idx[0]}..{idx[-1]})")


MM_RATIO = (50.0, 5000.0)     # a length this many times the others was meant in mm


def millimetre_suspects(task) -> list[tuple[tuple, str]]:
    """(field path, message) for each length of the linkage (a bar's length, a ground
    point's distance from the crank's pivot) that is 50-5000 times the others (their median;
    one other is enough: a slider-crank's crank and rod), i.e. probably meant in millimetres
    and given as a plain number in metres."""
    import statistics

    sec = task.mechanism
    items: list[tuple[tuple, str, float]] = []
    for name, spec in sec.links.items():
        if spec.kind == "bar" and spec.length:
            items.append((("mechanism", "links", name, "length"), Message("input.mm_link", link=name), float(spec.length)))
    ground = list(sec.ground.items())
    if len(ground) > 1:
        x0, y0 = ground[0][1]
        for g, (x, y) in ground[1:]:
            d = ((x - x0) ** 2 + (y - y0) ** 2) ** 0.5
            if d > 0:
                items.append((("mechanism", "ground", g), Message("input.mm_ground", point=g, d=d, origin=ground[0][0]), d))
    out = []
    for k, (path, what, v) in enumerate(items):
        others = [w for j, (_, _, w) in enumerate(items) if j != k]
        if not others:                       # a slider-crank has two lengths: either may be the one
            continue
        ratio = v / statistics.median(others)
        if MM_RATIO[0] <= ratio <= MM_RATIO[1]:
            out.append((path, Message("input.mm_suspect", what=what, value=v, ratio=ratio, lo=min(others),
                                      hi=max(others)) if len(others) > 1 else
                        Message("input.mm_suspect_one", what=what, value=v, ratio=ratio, other=others[0])))
    return out


def impossible_dimensions(task, err):
    """A kinematics StageError for a group that assembles at no crank angle at all means
    the dimensions are impossible: that is an invalid task (exit 2), pointing at the
    group's first link. So is a linkage that does not assemble because one length is
    100-1000 times the others (meant in millimetres): the message says so and points at
    that length. Returns the TaskError, or None for a partial failure."""
    mm = millimetre_suspects(task)
    if mm:
        path, msg = mm[0]
        return task.error(path, Message("input.mm_no_assembly", suspect=msg, reason=_coded(err.message)))
    names = err.never_assembles
    if not names:
        return None
    return task.error(("mechanism", "links", names[0]),
                      Message("input.impossible", reason=_coded(err.message), links=list(names)))
