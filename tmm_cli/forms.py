"""`tmm paths` and `tmm form`: the result paths of a task, and answer forms and keys.

A quantity list is comma-separated result paths and presets. A preset is a list of
path patterns: ``*`` stands for one name (a point, a link, a reaction), ``[*]`` for
every element of a list, ``**`` for every number below a section. Presets never fail
on a task that has their section; a preset or a path the task's results lack is an
error naming it (with "did you mean").
"""
from __future__ import annotations

import json
import re

from .errors import TaskError
from .messages import Message

PRESETS: dict[str, list[str]] = {
    "positions": ["positions.phi0", "positions.working_stroke_angle", "positions.idle_stroke_angle",
                  "positions.K", "positions.theta", "positions.H"],
    "kinematics": ["kinematics[1].points.*.v", "kinematics[1].points.*.a",
                   "kinematics[1].links.*.omega", "kinematics[1].links.*.epsilon"],
    "kinetostatics": ["kinetostatics[1].balancing_moment", "kinetostatics[1].zhukovsky_moment",
                      "kinetostatics[1].reactions.*.R"],
    "flywheel": ["flywheel.J", "flywheel.omega_max", "flywheel.omega_min",
                 "flywheel.M_constant", "flywheel.diameter", "flywheel.width", "flywheel.mass"],
    "cam": ["cam.r0", "cam.offset", "cam.center_distance", "cam.max_pressure_angle", "cam.rho_min"],
    "gears": ["gears.aw", "gears.alpha_w", "gears.y", "gears.dy", "gears.eps_alpha", "gears.r[*]",
              "gears.rb[*]", "gears.rw[*]", "gears.ra[*]", "gears.rf[*]", "gears.s[*]", "gears.sa[*]"],
    "planetary": ["planetary.z.*", "planetary.ratio", "planetary.ratio_error"],
    # what a student computes (the given motor speed's ratio, the stages' teeth and ratios, the shafts'
    # speeds, the motor's power), not the task's own data (efficiency, tolerance) or the plan's scales
    "drive_train": ["drive_train.required", "drive_train.ratio", "drive_train.ratio_error",
                    "drive_train.stages[*].z[*]", "drive_train.stages[*].ratio", "drive_train.shafts[*]",
                    "drive_train.stages[*].omega_carrier", "drive_train.stages[*].omega_satellite",
                    "drive_train.motor_power"],
    # every type's designed quantities, not the given psi and K or the generated task's masses
    "synthesis": ["synthesis.lengths.*", "synthesis.theta", "synthesis.gamma_min", "synthesis.gamma_min_phi",
                  "synthesis.fixed_pivots.*[*]", "synthesis.max_deviation", "synthesis.K[*]",
                  "synthesis.structural_error.max", "synthesis.structural_error.at_x"],
    "balancing": ["balancing.max.F", "balancing.max.M", "balancing.max.F_balanced", "balancing.max.M_balanced",
                  "balancing.counterweights.*.m", "balancing.counterweights.*.angle",
                  "balancing.rotor.corrections[*].m", "balancing.rotor.corrections[*].angle"],
    "differential": ["differential.u", "differential.speeds.*", "differential.torques.*", "differential.power_loss"],
    "synthesis_function": ["synthesis.lengths.*", "synthesis.K[*]", "synthesis.structural_error.max",
                           "synthesis.structural_error.at_x"],
    "synthesis_positions": ["synthesis.lengths.*", "synthesis.fixed_pivots.*[*]"],
    "synthesis_path": ["synthesis.lengths.*", "synthesis.fixed_pivots.*[*]", "synthesis.max_deviation"],
}

# course notation and unit of a result key: (symbol, unit as an answer is written); its name
# in each language is the catalogues' forms `names`, its unit as a text in the language writes
# it their forms `units`
NOTATION: dict[str, tuple[str, str]] = {
    "v": ("v", "m/s"),
    "a": ("a", "m/s^2"),
    "omega": ("ω", "rad/s"),
    "epsilon": ("ε", "rad/s^2"),
    "phi0": ("φ0", "deg"),
    "working_stroke_angle": ("φ_w", "deg"),
    "idle_stroke_angle": ("φ_i", "deg"),
    "K": ("K", ""),
    "theta": ("θ", "deg"),
    "H": ("H", "m or deg"),
    "balancing_moment": ("M_b", "N*m"),
    "zhukovsky_moment": ("M_b(Zh)", "N*m"),
    "R": ("R", "N"),
    "J": ("J_fly", "kg*m^2"),
    "delta": ("δ", ""),
    "omega_max": ("ω_max", "rad/s"),
    "omega_min": ("ω_min", "rad/s"),
    "M_constant": ("M_const", "N*m"),      # not M_c: the course writes the resistance moment so
    "diameter": ("D", "m"),
    "width": ("b", "m"),
    "mass": ("m", "kg"),
    "r0": ("r0", "m"),
    "offset": ("e", "m"),
    "center_distance": ("a_w", "m"),
    "max_pressure_angle": ("ϑ_max", "deg"),
    "rho_min": ("ρ_min", "m"),
    "aw": ("a_w", "m"),
    "alpha_w": ("α_w", "deg"),
    "y": ("y", ""),
    "dy": ("Δy", ""),
    "eps_alpha": ("ε_α", ""),
    "r": ("r", "m"),
    "rb": ("r_b", "m"),
    "rw": ("r_w", "m"),
    "ra": ("r_a", "m"),
    "rf": ("r_f", "m"),
    "s": ("s", "m"),
    "sa": ("s_a", "m"),
    "ratio": ("i", ""),
    "ratio_error": ("Δi", ""),
    "z1": ("z1", ""),
    "z2": ("z2", ""),
    "z3": ("z3", ""),
    "z4": ("z4", ""),
}

# the notation of the result paths whose last name alone would mislead (differential.speeds.H is
# a speed, not the stroke H; balancing.max.M a moment, not a mass): a path pattern (as in PRESETS)
# -> (symbol, unit, its name's key in the catalogues' forms `names`, its sign convention: a word of
# `sign_convention` or ''). "{0}" in a symbol is the name the pattern's first "*" matched.
PATH_NOTATION: dict[str, tuple[str, str, str, str]] = {
    "balancing.max.F": ("F_max", "N", "shaking_force_max", "magnitude"),
    "balancing.max.M": ("M_max", "N*m", "shaking_moment_max", ""),
    "balancing.max.F_balanced": ("F_max(bal)", "N", "shaking_force_balanced", "magnitude"),
    "balancing.max.M_balanced": ("M_max(bal)", "N*m", "shaking_moment_balanced", ""),
    "balancing.counterweights.*.m": ("m_cw", "kg", "counterweight_mass", ""),
    "balancing.counterweights.*.angle": ("φ_cw", "deg", "counterweight_angle", ""),
    "balancing.counterweights.*.mr": ("m_cw·r_cw", "kg*m", "counterweight_moment", ""),
    "balancing.rotor.corrections[*].m": ("m_corr", "kg", "correction_mass", ""),
    "balancing.rotor.corrections[*].angle": ("φ_corr", "deg", "correction_angle", ""),
    "differential.u": ("u^H", "", "differential_u", "ratio"),
    "differential.speeds.*": ("ω_{0}", "rad/s", "differential_speed", "ccw"),
    "differential.torques.*": ("T_{0}", "N*m", "differential_torque", "ccw"),
    "differential.power_loss": ("P_loss", "W", "power_loss", "magnitude"),
    "synthesis.lengths.offset": ("e", "m", "offset", ""),
    "synthesis.lengths.guide_height": ("h", "m", "guide_height", ""),
    "synthesis.lengths.*": ("l_{0}", "m", "link_length", ""),
    "synthesis.fixed_pivots.*[0]": ("x_{0}", "m", "pivot_x", ""),
    "synthesis.fixed_pivots.*[1]": ("y_{0}", "m", "pivot_y", ""),
    "synthesis.max_deviation": ("Δ_max", "m", "max_deviation", "magnitude"),
    "synthesis.K[0]": ("K1", "", "freudenstein_k", ""),
    "synthesis.K[1]": ("K2", "", "freudenstein_k", ""),
    "synthesis.K[2]": ("K3", "", "freudenstein_k", ""),
    "synthesis.structural_error.max": ("Δψ_max", "deg", "structural_error", "magnitude"),
    "synthesis.structural_error.at_x": ("x(Δψ_max)", "", "structural_error_at", ""),
    "synthesis.psi": ("ψ", "deg", "rocker_swing", ""),
    "synthesis.gamma_min": ("γ_min", "deg", "gamma_min", ""),
    "synthesis.gamma_min_phi": ("φ(γ_min)", "deg", "gamma_min_phi", ""),
    "planetary.ratio_error": ("Δi", "", "ratio_error", "deviation"),
    "drive_train.ratio_error": ("Δi", "", "ratio_error", "deviation"),
    "drive_train.required": ("i_req", "", "required_ratio", "ratio"),
    "drive_train.stages[*].z[*]": ("z", "", "stage_teeth", ""),
    "drive_train.shafts[*]": ("ω", "rad/s", "shaft_speed", "ccw"),
    "drive_train.stages[*].omega_carrier": ("ω_H", "rad/s", "carrier_speed", "ccw"),
    "drive_train.stages[*].omega_satellite": ("ω_g", "rad/s", "satellite_speed", "ccw"),
    "drive_train.motor_power": ("P_m", "W", "motor_power", ""),
}

# the sign convention of a result key: a word of the catalogues' `sign_convention` table
# (the sense that is positive, or that it is a magnitude)
SIGN: dict[str, str] = {"omega": "ccw", "epsilon": "ccw", "balancing_moment": "ccw", "zhukovsky_moment": "ccw",
                        "M_constant": "drives", "ratio": "ratio", "v": "magnitude", "a": "magnitude",
                        "R": "magnitude", "omega_max": "magnitude", "omega_min": "magnitude"}


def _by_path(path: str) -> tuple[str, str, str, str] | None:
    """PATH_NOTATION's entry for a path, its symbol's "{0}" filled (None when no pattern matches)."""
    for pat, (sym, unit, name, sign) in PATH_NOTATION.items():
        m = _pattern(pat, capture=True).match(path)
        if m:
            return sym.format(*m.groups()), unit, name, sign
    return None


# where a key's notation by its last name holds (a regex the path matches; a key not listed holds
# anywhere): `a` is a centre distance in gears, J and mass are the flywheel's only in its section (a
# link's J is no flywheel), H the stroke in positions (differential.powers.H is the carrier's),
# planetary.r.z1 a radius
_FLYWHEEL = r"^flywheel\."
_HOME: dict[str, str] = {
    # a rocker follower's and a rocker output's curves are angular (rad/s, rad/s^2): cam.v, cam.a and
    # kinematics_curve.v, .a take the unit of what they are, so no notation there
    "v": r"^(?!cam\.|kinematics_curve\.)",
    "a": r"^(?!gears\.|dof2\.parameters\.|flywheel\.|cam\.|kinematics_curve\.)",
    **dict.fromkeys(("J", "mass", "diameter", "width", "delta", "omega_max", "omega_min", "M_constant"), _FLYWHEEL),
    **dict.fromkeys(("H", "K", "theta"), r"^(positions|synthesis)\."),
    "phi0": r"^(positions|flywheel)\.",
    **dict.fromkeys(("working_stroke_angle", "idle_stroke_angle"), r"^positions\."),
    "aw": r"^(gears|planetary|differential)\.",
    **dict.fromkeys(("alpha_w", "y", "dy", "eps_alpha", "r", "rb", "rw", "ra", "rf", "s", "sa"), r"^gears\."),
    **dict.fromkeys(("r0", "offset", "center_distance", "max_pressure_angle", "rho_min"), r"^cam\."),
    **dict.fromkeys(("ratio", "ratio_error"), r"^(planetary|drive_train)\."),
    **dict.fromkeys(("z1", "z2", "z3", "z4"), r"\.z\.z\d$"),
}


def _last_key(path: str) -> str:
    """A path's last name, reactions R12... read as R (the key of NOTATION and SIGN); '' where
    the name's notation does not hold at that path (:data:`_HOME`)."""
    if path.startswith(("graphical_error.", "messages[")):     # relative errors; a message's parameters
        return ""
    key = re.sub(r"\[[^\]]*\]", "", path).rsplit(".", 1)[-1]
    key = "R" if key not in NOTATION and re.fullmatch(r"R\d+", key) else key
    home = _HOME.get(key)
    return key if home is None or re.search(home, path) else ""


def key_notation(path: str) -> tuple[str, str, str] | None:
    """(symbol, unit as an answer is written, its name's key in the forms `names`) of a result
    path: by PATH_NOTATION's patterns, else by its last name (None when unknown)."""
    by_path = _by_path(path)
    if by_path:
        return by_path[:3]
    key = _last_key(path)
    return (*NOTATION[key], key) if key in NOTATION else None


def unit_of(path: str) -> str | None:
    """The unit of a result path as an answer is written ('m/s', 'm or deg', '' for a plain
    number); None when the notation does not know the path."""
    n = key_notation(path)
    return n[1] if n else None


def sign_note(path: str, lang: str = "en") -> str:
    """The sign convention of a path's quantity in ``lang`` ('' when the key has none listed)."""
    from .messages import catalogue
    by_path = _by_path(path)
    word = by_path[3] if by_path else SIGN.get(_last_key(path), "")
    return catalogue(lang)["terms"]["sign_convention"][word] if word else ""


def notation(path: str, lang: str = "en", local_units: bool = False) -> str:
    """'ω, rad/s — angular velocity' for a path, by its pattern or its last name ('' when unknown);
    ``local_units``: the unit as a text in ``lang`` writes it (the catalogues' forms `units`)."""
    n = key_notation(path)
    if not n:
        return ""
    sym, unit, key = n
    if sym.startswith(("M_b", "P_b")):         # the balancing moment: M_b, in ru and uk the course's subscript
        from .drawings.words import balance_sub
        sym = sym[:2] + balance_sub(lang) + sym[3:]
    if local_units:
        unit = local_unit(unit, lang)
    return f"{sym}{', ' + unit if unit else ''} — {_text(lang, 'names').get(key) or _text('en', 'names')[key]}"


def _text(lang: str, table: str) -> dict:
    from . import locales
    return locales.of("forms", table, lang)


def local_unit(unit: str, lang: str) -> str:
    """A unit as an answer is written ('m/s', 'N*m') as a text in ``lang`` writes it (the catalogues'
    forms `units`: in Russian and Ukrainian the Cyrillic letters and the raised dot, kg·m²)."""
    return _text(lang, "units").get(unit, unit)


def _pattern(p: str, capture: bool = False) -> re.Pattern:
    """A path pattern's regex; ``capture``: each "*" name a group."""
    one = r"([^.\[\]]+)" if capture else r"[^.\[\]]+"
    out = re.escape(p).replace(r"\*\*", "@@").replace(r"\[\*\]", r"\[\d+\]").replace(r"\*", one)
    return re.compile("^" + out.replace("@@", r"[^\[\]]+") + "$")


def numeric_leaves(results: dict) -> list[tuple[str, float]]:
    from .results import leaf_paths
    return [(p, v) for p, v in leaf_paths(results)
            if isinstance(v, (int, float)) and not isinstance(v, bool)]


def expand(quantities: str | list[str], results: dict, *, strict: bool = True) -> list[str]:
    """Result paths of a quantity list for one task's results. With ``strict`` a path or a
    preset the results lack is a TaskError naming it (with "did you mean")."""
    from .results import did_you_mean
    from .results import lookup, parse_path
    items = quantities.split(",") if isinstance(quantities, str) else list(quantities)
    leaves = numeric_leaves(results)
    names = [p for p, _ in leaves]
    out: list[str] = []
    for raw in (i.strip() for i in items):
        if not raw:
            continue
        preset = _position_preset(raw, results)
        if preset is not None:
            name, pats = preset
            got = [p for pat in pats for rx in (_pattern(pat),) for p in names if rx.match(p)
                   if not _zero_by_construction(p, results)]
            if not got and strict and name != raw and _indices(results, name):
                raise TaskError(Message("quantities.no_position", preset=raw, index=raw[len(name) + 1:-1],
                                        computed=", ".join(map(str, _indices(results, name)))))
            if not got and strict:
                raise TaskError(Message("quantities.preset_empty", preset=raw))
            out.extend(g for g in got if g not in out)
            continue
        if "*" in raw:                  # a pattern, as the presets write theirs: reactions.*.R, r[*]
            got = [q for q in names if _pattern(raw).match(q) and q not in out]
            if not got and strict:
                raise TaskError(Message("quantities.pattern_empty", name=raw))
            out.extend(got)
            continue
        if "." not in raw and "[" not in raw and raw not in results:
            import difflib
            near = difflib.get_close_matches(raw, list(PRESETS), n=1, cutoff=0.75)
            if near and strict:              # 'differntial': the preset meant, not a path
                raise TaskError(Message("quantities.preset_meant", name=raw, preset=near[0],
                                        presets=", ".join(PRESETS)))
        try:
            parse_path(raw)
            v = lookup(results, raw)
            if strict and (isinstance(v, (dict, list)) or v is None):
                raise KeyError(Message("quantities.no_number", name=raw))
        except KeyError as exc:
            if strict:
                raise TaskError(Message("quantities.not_in_results", name=raw, why=exc.args[0] if exc.args else str(exc),
                                        hint=did_you_mean(raw, results, names), presets=", ".join(PRESETS))) from None
        if raw not in out:
            out.append(raw)
    return out


def _indices(results: dict, section: str) -> list[int]:
    """The indices of the positions ``results[section]`` holds, in order."""
    entries = results.get(section) or []
    return [e["index"] for e in entries if isinstance(e, dict) and "index" in e]


def _position_preset(raw: str, results: dict) -> tuple[str, list[str]] | None:
    """(preset name, its path patterns) of ``raw``, or None when it names no preset. The
    position presets ('kinematics', 'kinetostatics') ask at position 1, else at the first the
    task computes (`kinetostatics: {positions: [3]}`: position 3); 'kinetostatics[3]' at the
    position it names."""
    m = re.fullmatch(r"(kinematics|kinetostatics)\[(\d+)\]", raw)
    name = m.group(1) if m else raw
    if name not in PRESETS:
        return None
    pats = PRESETS[name]
    if name in ("kinematics", "kinetostatics"):
        at = _indices(results, name)
        index = int(m.group(2)) if m else (1 if 1 in at or not at else at[0])
        pats = [q.replace("[1]", f"[{index}]", 1) for q in pats]
    return name, pats


_KIN_PATH = re.compile(r"^kinematics\[\d+\]\.(points|links)\.([^.]+)\.([^.\[]+)$")


def _zero_by_construction(path: str, results: dict) -> bool:
    """A preset's position quantity that is 0 at every position of the task -- a fixed pivot's
    velocity, the angular velocity of a slider on a fixed guide or of a Scotch yoke's block -- and
    asks a student nothing."""
    m = _KIN_PATH.match(path)
    if not m:
        return False
    kind, name, key = m.groups()
    values = [((e.get(kind) or {}).get(name) or {}).get(key) for e in results.get("kinematics") or ()]
    return bool(values) and all(v in (0, None) for v in values) and any(v == 0 for v in values)


GROUP_MIN = 13     # a list of more numbers than the 12 positions is a per-position (per-degree) array
_TRAILING = re.compile(r"^(.*)\[(\d+)\]$")
_POSITION_LIST = re.compile(r"^(kinematics|kinetostatics)\[(\d+)\]")


def parse_indices(text: str) -> set[int]:
    """'0,3,6-9' -> {0, 3, 6, 7, 8, 9}; ValueError naming the part that is not one."""
    out: set[int] = set()
    for part in (p.strip() for p in text.split(",")):
        m = re.fullmatch(r"(\d+)(?:\s*-\s*(\d+))?", part)
        if not m or (m.group(2) and int(m.group(2)) < int(m.group(1))):
            raise ValueError(part)
        out.update(range(int(m.group(1)), int(m.group(2) or m.group(1)) + 1))
    return out


def group_leaves(leaves: list[tuple[str, object]], indices: set[int] | None = None,
                 group: bool = False) -> list[tuple[str, object]]:
    """`tmm paths` with long arrays made readable: ``indices`` keeps, of every array of more
    than 12 numbers and of the position lists (kinematics[i], kinetostatics[i]), only those
    elements; ``group`` writes each array left as one line ``base[first..last]`` with
    ``"N values, min .. max"``. Other leaves pass as they are."""
    arrays: dict[str, list[tuple[int, object]]] = {}
    for p, v in leaves:
        m = _TRAILING.match(p)
        if m and isinstance(v, (int, float)) and not isinstance(v, bool):
            arrays.setdefault(m.group(1), []).append((int(m.group(2)), v))
    long = {b for b, items in arrays.items() if len(items) >= GROUP_MIN}
    out: list[tuple[str, object]] = []
    done: set[str] = set()
    for p, v in leaves:
        pos = _POSITION_LIST.match(p)
        if indices is not None and pos and int(pos.group(2)) not in indices:
            continue
        m = _TRAILING.match(p)
        if not (m and m.group(1) in long):
            out.append((p, v))
            continue
        base = m.group(1)
        if indices is not None:
            if int(m.group(2)) in indices:
                out.append((p, v))
            continue
        if not group:
            out.append((p, v))
        elif base not in done:
            done.add(base)
            vals = [x for _, x in arrays[base]]
            idx = [i for i, _ in arrays[base]]
            out.append((f"{base}[{min(idx)}..{max(idx)}]", f"{len(vals)} values, {min(vals):.6g} .. {max(vals):.6g}"))
    return out


def yaml_key(path: str) -> str:
    return json.dumps(path, ensure_ascii=False)




def _quoted(value: str) -> str:
    """A student's name or group as a YAML string ('""' where the task has none)."""
    return json.dumps(value, ensure_ascii=False)


def position_angles(paths: list[str], results: dict) -> dict[int, float]:
    """{position: crank angle φ, deg} of the positions the ``paths`` ask at ('kinematics[3]...',
    'kinetostatics[3]...'), as results.json holds them."""
    wanted = {int(m.group(2)) for p in paths if (m := re.match(r"(kinematics|kinetostatics)\[(\d+)\]", p))}
    out = {}
    for section in ("kinematics", "kinetostatics"):
        for e in results.get(section) or []:
            if isinstance(e, dict) and e.get("index") in wanted and e.get("phi") is not None:
                out.setdefault(int(e["index"]), float(e["phi"]))
    return dict(sorted(out.items()))


def form_text(task, paths: list[str], results: dict | None, lang: str,
              angles: dict[int, float] | None = None) -> str:
    """The blank form (results None) or the key (results given) as commented YAML; a comment
    gives each quantity's symbol and unit as the language writes them (in ru and uk the units in
    Cyrillic, which the answers reader reads too: tmm_cli/numbers.py) and its name. ``angles``
    ({position: φ}, :func:`position_angles`): a comment gives the crank's angle at each position
    asked at (its number counts from position 0 as the task sets it; φ tells which it is)."""
    from .results import lookup, reference
    key = results is not None
    words = _text(lang, "text")
    head = words["key" if key else "form"]
    name, group = task.who                       # a variants table's student and group, if it gave them
    lines = [f"# {head}: {task.title or task.name}".rstrip(),
             "# " + words["note"],
             f"variant: {json.dumps(task.variant if task.variant is not None else task.name, ensure_ascii=False)}",
             f"student: {{name: {_quoted(name)}, group: {_quoted(group)}}}"]
    if angles:
        from .numfmt import list_sep, num
        lines.insert(2, "# " + words["positions"].format(list=list_sep(lang).join(
            f"{k}: φ = {num(v, '.1f', lang)}°" for k, v in angles.items())))
    lines.append("answers:")
    width = max((len(yaml_key(p)) for p in paths), default=0) + 2
    for p in paths:
        val = ""
        if key:
            try:
                v = reference(lookup(results, p))        # as tmm check takes it: a round-off zero is 0.0
                val = "" if v is None else (repr(float(v)) if isinstance(v, float) else json.dumps(v))
            except KeyError:
                val = ""
        note = "; ".join(x for x in (notation(p, lang, local_units=True), sign_note(p, lang)) if x)
        entry = f"  {yaml_key(p)}: {val}"
        lines.append(entry.ljust(width + 4 + len(val)) + (f"  # {note}" if note else ""))
    return "\n".join(lines) + "\n"


NOTES_MARK = "#"     # a table row whose `student` cell starts with it is a note, never a student's answers


def forms_csv(rows: list[dict], paths: list[str], lang: str | None = None) -> str:
    """form.csv / key.csv; with ``lang`` a notes row under the header gives each column's sign
    convention (its `student` cell begins with '#': the answers reader skips it)."""
    from .tables import csv_text
    notes = {p: sign_note(p, lang) for p in paths} if lang else {}
    from .messages import catalogue
    head = [{"student": catalogue(lang)["terms"]["grading"]["sign_row"], **notes}] if any(notes.values()) else []
    return csv_text(["student", "group", "variant"] + paths, head + rows)
