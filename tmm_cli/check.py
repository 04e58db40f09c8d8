"""Grading: students' answers against the computed results (`tmm check`, `tmm batch`).

Answers come from a task's own `answers` section, one answers file (YAML), a folder of
them, or one CSV with a row per student. Values may carry units. Each answer gets a
status: ok, sign (right magnitude, wrong sign), outside, missing, unknown_path (with
"did you mean"), not_computed, or invalid (a value that is not a number: the reason in
`note`, the student's other answers graded as usual); an answer set gets no_answers, ok
or its worst status (an invalid answer counts as one outside: a wrong answer).
"""
from __future__ import annotations

import dataclasses
import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .errors import TaskError
from .limits import printable
from .messages import Message, as_message
from .results import did_you_mean, leaf_paths, lookup, parse_path, reference

DEFAULT_TOLERANCE = 0.05
# results in degrees: differences are taken modulo 360 into [-180, 180)
# (and every key ending in "_phi": the crank angle where something happens, as gamma_min_phi)
ANGLE_KEYS = {"phi", "phi0", "extreme", "angle", "working_stroke_angle", "idle_stroke_angle", "alpha_w", "theta",
              "psi", "gamma_min", "pressure_angle", "max_pressure_angle", "singular", "psi0", "gamma",
              "max_pressure_angle_rise", "max_pressure_angle_return", "crank_angle", "crank_angles"}

# top-level result sections: a path into one the task did not compute is not_computed
SECTIONS = {"structure", "positions", "kinematics", "kinematics_curve", "kinetostatics", "kinetostatics_info",
            "singular", "singular_positions", "flywheel", "cam", "gears", "planetary", "drive_train", "synthesis",
            "dof2", "balancing", "differential"}
STATUSES = ("ok", "outside", "sign", "missing", "unknown_path", "not_computed", "invalid")
SET_ORDER = ("outside", "sign", "missing", "unknown_path", "not_computed")
CHECK_FIELDS = ["student", "group", "variant", "path", "answer", "reference", "error", "tolerance", "status",
                "note", "answers_file"]


# ------------------------------------------------------------------ tolerances
@dataclass(frozen=True)
class Tol:
    rel: float = DEFAULT_TOLERANCE
    abs: float = 0.0
    plain: bool = True            # a plain number: absolute for a zero reference
    any_sign: bool = False        # `sign: any`: the magnitude is graded
    band: tuple[float, float] | None = None   # `graphical` flywheel: an answer in [lo, hi] passes

    @property
    def text(self) -> str:
        if self.band is not None:
            return f"band {self.band[0]:.10g}..{self.band[1]:.10g}"    # as graded, to 10 digits
        if self.plain:
            return f"{self.rel:g}"
        parts = ([f"rel {self.rel:g}"] if self.rel else []) + ([f"abs {self.abs:g}"] if self.abs else [])
        return " ".join(parts + (["sign any"] if self.any_sign else [])) or "0"


GRAPHICAL = "graphical"   # the tolerance of a hand solution: the error of reading the drawings
# a whole number in the results is a count (teeth, satellites, the degree of freedom, an assembly
# number): graded exactly unless the tolerances name its path or a prefix of it
EXACT = Tol(rel=0.0, abs=0.0, plain=False)


def parse_tolerance(v, where: str, line=None, col=None, file=None) -> Tol:
    """A tolerance entry: a non-negative number (relative), {rel: R, abs: A}, or
    ``graphical`` (kept as the string; `tolerances` expands it with the results)."""
    def bad(msg):
        return TaskError("invalid tolerance", file=file, issues=[(where, line, col, msg)],
                         kind="tolerance file" if file else "task")

    def num(x, what):
        from .units import tolerance_number
        try:
            return tolerance_number(x, what)
        except ValueError as exc:
            raise bad(exc.args[0]) from None

    if isinstance(v, Tol) or v == GRAPHICAL:
        return v
    if hasattr(v, "model_dump"):          # the task's ToleranceSpec
        v = v.model_dump()
    if isinstance(v, dict):
        extra = set(map(str, v)) - {"rel", "abs", "sign"}
        if extra:
            raise bad(Message("input.tol_unknown_key", key=sorted(extra)[0]))
        if v.get("sign") not in (None, "any"):
            raise bad(Message("input.tol_sign", got=repr(v.get("sign"))))
        return Tol(rel=num(v.get("rel", 0), "rel"), abs=num(v.get("abs", 0), "abs"), plain=False,
                   any_sign=v.get("sign") == "any")
    return Tol(rel=num(v, "plain"))


def tolerance_for(key: str, tol: dict, count: bool = False) -> Any:
    """The tolerance entry for a path: the path itself, else its longest prefix, else
    `default`, else 0.05 (``count``: a whole-number result, :data:`EXACT` instead of the
    default). Returns what the mapping holds (a number or a Tol)."""
    if key in tol:
        return tol[key]
    best, best_len = EXACT if count else tol.get("default", DEFAULT_TOLERANCE), -1
    for k, v in tol.items():
        if k != "default" and (key.startswith(k + ".") or key.startswith(k + "[")) and len(k) > best_len:
            best, best_len = v, len(k)
    return best


# ------------------------------------------------------------------ answer sets
@dataclass
class AnswerSet:
    source: str                                   # file, or file:line of a CSV row
    answers: dict[str, Any] = field(default_factory=dict)   # path -> float | None (missing)
    student: str = ""
    group: str = ""
    variant: Any = None
    stem: str | None = None
    error: str | None = None                      # an invalid answers file / row
    invalid: dict[str, tuple[str, Any]] = field(default_factory=dict)   # path -> (as written, the note: why)
    notes: list = field(default_factory=list)     # warnings on reading the file (each a Message)
    flags: list = field(default_factory=list)     # summary.csv's `flags` ('repeat=...', 'same_as=...')
    written: dict[str, str] = field(default_factory=dict)   # path -> the value as written, where it has a unit
    email: str = ""                               # for a gradebook: `student: {email, id}`, columns email, id
    idnumber: str = ""
    mtime: float = 0.0                            # the file's modification time (--latest)

    @property
    def answers_file(self) -> str:
        """The base name of the student's file, or NAME.csv:LINE for a row of a table."""
        return Path(self.source).name

    def matches(self, task) -> bool:
        """The set answers ``task``: by its `variant` field (a task without a variant: its file
        stem, which `tmm form` writes there), else by its file stem (the task's stem or variant)."""
        tv = task.variant
        if self.variant is not None and str(self.variant) != "":
            if tv is None:
                return str(self.variant).strip() == task.name
            return _same(self.variant, tv)
        return self.stem is not None and (self.stem == task.name or (tv is not None and _same(self.stem, tv)))


def variant_order(names) -> list[str]:
    """Variant names in their order: whole numbers by value (3 before 12), then the rest as text."""
    return sorted(names, key=lambda v: (not v.isdigit(), int(v) if v.isdigit() else 0, v))


def _same(a, b) -> bool:
    sa, sb = str(a).strip(), str(b).strip()
    if sa == sb:
        return True
    try:
        return float(sa) == float(sb)
    except ValueError:
        return sa.lstrip("v0") == sb.lstrip("v0") and sa.lstrip("v0") != ""


def answer_value(v, path: str):
    """A student's value in the path's unit (SI, angles in degrees): None when empty.
    Raises ValueError with the reason for anything that is not a number."""
    if v is None:
        return None
    if isinstance(v, bool):             # YAML's true/false: never read as 1 and 0
        raise ValueError(Message("answers.not_number_bool", value=str(v).lower()))
    if isinstance(v, (int, float)):
        x = float(v)
        if not math.isfinite(x):
            raise ValueError(Message("answers.not_finite", value=repr(v)))
        return x
    s = str(v).strip()
    if s == "":
        return None
    from .numbers import answer
    names = [t for t in _tokens(path) if isinstance(t, str)]
    unit = _path_unit(path)
    x = answer(s, unit, angle=_is_angle(path),
               angular=unit == "rad/s" or bool(names and names[-1].startswith("omega")))
    if not math.isfinite(x):
        raise ValueError(Message("answers.not_finite", value=repr(s)))
    return x


def _coded(exc: Exception) -> Message:
    """An exception's message as a Message (coded where the raiser coded it)."""
    return as_message(exc.args[0] if len(exc.args) == 1 else str(exc))


def _path_unit(path: str) -> str | None:
    """The unit of a result path in pint's words ('m/s**2'), from the notation of the path
    (tmm_cli.forms.key_notation: its pattern, else its last name where that name means its
    quantity -- `a` is an acceleration but in gears a centre distance, `J` the flywheel's in its
    section only). None for a path without one, or the stroke's 'm or deg': the answer is then
    taken in SI base units, of a course quantity."""
    from .forms import unit_of
    unit = unit_of(path)
    if unit in (None, "m or deg"):
        return None
    return {"deg": "degree", "": "dimensionless"}.get(unit, unit.replace("^", "**"))


def _tokens(path: str) -> list:
    try:
        return parse_path(path)
    except KeyError:
        return []


def _last_name(path: str) -> str:
    toks = [t for t in _tokens(path) if isinstance(t, str)]
    return toks[-1] if toks else ""


def _is_angle(path: str) -> bool:
    last = _last_name(path)
    return last in ANGLE_KEYS or last.endswith("_phi")


# angles that are sizes, not directions: the strokes' arcs of the cycle (working + idle = 360),
# the overtravel angle, the mesh's pressure angle, the least transmission angle, the cam's
# greatest pressure angles. An arc is still passed modulo 360 (-191.7 for 168.3: a difference of
# two crank angles not wrapped), but its negation is not: modulo 360, -178.0 is 182.0, and an
# idle stroke of 178.0 answered for the working stroke's 182.0 was "right magnitude, wrong sign"
ARC_KEYS = {"working_stroke_angle", "idle_stroke_angle", "theta", "alpha_w", "gamma_min", "gamma",
            "max_pressure_angle", "max_pressure_angle_rise", "max_pressure_angle_return"}


def angle_kind(path: str) -> str | None:
    """'direction' (graded modulo 360, its sign too), 'arc' (a size: modulo 360, its sign
    not) or None (no angle)."""
    if not _is_angle(path):
        return None
    return "arc" if _last_name(path) in ARC_KEYS else "direction"


def _mark(marks, key, default=(None, None)):
    return marks.get(key, default)


def load_answers_file(path: Path, keep_errors: bool = False) -> AnswerSet:
    """One student's answers file (YAML): `answers`, optional `student`, `variant`
    (a `tolerance` is ignored, with a note in ``notes``). An answer that is not a number
    is that answer's `invalid` (``invalid``: as written, why). Raises TaskError naming
    the file, line and field for a file that is not an answers file or a malformed path;
    with ``keep_errors`` a malformed path is kept as the set's error (the set still names
    its student and variant)."""
    from .yamlload import load_yaml
    path = Path(path)
    if not path.is_file():
        raise TaskError(Message("answers.not_file"), file=str(path), kind="answers file")
    try:
        data, marks = load_yaml(path)
    except TaskError as exc:         # not YAML: where and why (a tab, an unclosed bracket), as for a task file
        exc.kind = "answers file"
        raise
    if not isinstance(data, dict) or "answers" not in data:
        # never echo the file's content: it may be anything
        raise TaskError(Message("answers.not_answers_file"), file=str(path), kind="answers file")
    unknown = set(map(str, data)) - {"answers", "tolerance", "student", "variant", "schema", "title"}
    if unknown:                         # every one, each at its line (a file of Cyrillic keys has several)
        issues = sorted(((k, *_mark(marks, (k,)), Message("answers.unknown_key", key=k)) for k in unknown),
                        key=lambda i: (i[1] is None, i[1] or 0, i[0]))
        raise TaskError("unknown key", file=str(path), kind="answers file", issues=issues)
    from .limits import text_issues
    bad_text = text_issues(data, marks)     # the task file's rule for every text
    if bad_text:
        raise TaskError("invalid answers file", file=str(path), kind="answers file", issues=bad_text)
    for key in ("answers", "student"):
        raw = data.get(key)
        if raw is not None and not isinstance(raw, dict):
            line, col = _mark(marks, (key,))
            raise TaskError("invalid answers file", file=str(path), kind="answers file",
                            issues=[(key, line, col, Message("answers.not_mapping", got=type(raw).__name__))])
    aset = AnswerSet(source=str(path), stem=path.stem, variant=data.get("variant"), mtime=_mtime(path))
    st = data.get("student") or {}
    aset.student, aset.group = printable(str(st.get("name") or "")), printable(str(st.get("group") or ""))
    aset.email, aset.idnumber = str(st.get("email") or ""), str(st.get("id") or "")
    for k, v in (data.get("answers") or {}).items():
        line, col = _mark(marks, ("answers", str(k)))
        k = str(k).strip()                  # 'kinematics[1].points.B.v ': a blank no path holds
        try:
            parse_path(k)
        except KeyError as exc:
            err = TaskError("invalid answers file", file=str(path), kind="answers file", issues=[(f"answers.{k}", line, col, _coded(exc))])
            if not keep_errors:
                raise err from None
            aset.error = aset.error or err.coded() or err.render()
            continue
        if k in aset.answers:             # 'gears.aw' and 'gears.aw ': which is meant is not known
            aset.answers[k] = None
            aset.invalid[k] = ("" if v is None else str(v), Message("answers.twice", path=k))
            continue
        _add_answer(aset, k, v)
    if data.get("tolerance") is not None:    # the instructor's tolerances only: the student's is ignored
        line, _ = _mark(marks, ("tolerance",))
        aset.notes.append(Message("answers.tolerance_ignored", where=f"{path}:{line}" if line else str(path)))
    return aset


def _add_answer(aset: AnswerSet, path: str, v) -> None:
    """The answer ``v`` to ``path`` into the set, read by :func:`answer_value`; one that cannot be
    read is that answer's `invalid` (the others are graded as usual)."""
    try:
        aset.answers[path] = answer_value(v, path)
        _keep_written(aset, path, v)
    except ValueError as exc:
        aset.answers[path] = None
        aset.invalid[path] = ("" if v is None else str(v), Message("answers.invalid", reason=_coded(exc)))


def _keep_written(aset: AnswerSet, path: str, v) -> None:
    """Keep a string answer with a unit as written (a feedback page shows it so)."""
    if isinstance(v, str) and re.search(r"[^\d\s.,+\-eE]", v.strip()):
        aset.written[path] = v.strip()


def _mtime(path: Path) -> float:
    try:
        return Path(path).stat().st_mtime
    except OSError:
        return 0.0


def repeats(sets: list[AnswerSet], latest: bool = False) -> tuple[list[AnswerSet], list]:
    """Second submissions: sets of one student (by name) for one variant (by `variant`,
    else the file's stem). Each is flagged ``repeat=<the others' answers_file>``; with
    ``latest`` only the newest by modification time stays (one note per set dropped).
    Sets without a student's name are never taken for one another."""
    groups: dict[tuple, list[AnswerSet]] = {}
    for a in sets:
        if a.error or not a.student.strip():
            continue
        v = a.variant if a.variant not in (None, "") else a.stem
        groups.setdefault((" ".join(a.student.split()).casefold(), str(v).strip()), []).append(a)
    drop: set[int] = set()
    notes = []
    for same in groups.values():
        if len(same) < 2:
            continue
        newest = max(same, key=lambda a: a.mtime)
        for a in same:
            if latest and a is not newest:
                drop.add(id(a))
                notes.append(Message("answers.older_dropped", file=a.answers_file, newer=newest.answers_file,
                                     student=a.student))
            elif not latest:
                a.flags.append("repeat=" + "|".join(b.answers_file for b in same if b is not a))
    return [a for a in sets if id(a) not in drop], notes


def load_answers_dir(folder: Path) -> list[AnswerSet]:
    """Every *.yaml / *.yml in the folder: one answer set each (a file that cannot be
    read becomes a set with its error)."""
    sets = []
    files = sorted(set(Path(folder).glob("*.yaml")) | set(Path(folder).glob("*.yml")))
    for f in files:
        try:
            sets.append(load_answers_file(f, keep_errors=True))
        except TaskError as exc:
            one = exc.coded() if len(exc.issues) <= 1 else None     # one line: in the summary's language too
            sets.append(AnswerSet(source=str(f), stem=f.stem, error=one or exc.render().replace("\n", "; ")))
    return sets


META_COLUMNS = ("student", "group", "variant", "email", "id")    # an answers table's columns that are no path


def load_answers_csv(path: Path) -> list[AnswerSet]:
    """One row per student: student, group, variant, then one column per path."""
    from .tables import TableError, read_table
    try:
        header, rows = read_table(path)
    except TableError as exc:
        raise TaskError(exc.message, file=str(path), issues=[("", exc.line, None, exc.message)] if exc.line else None,
                        kind="answers file")
    if "variant" not in header:
        raise TaskError(Message("answers.table_no_variant"), file=str(path), kind="answers file")
    paths = [h for h in header if h not in META_COLUMNS and h]
    for p in paths:
        try:
            parse_path(p)
        except KeyError as exc:
            raise TaskError("invalid answers table", file=str(path), kind="answers file",
                            issues=[(p, 1, header.index(p) + 1,
                                     Message("answers.bad_column", column=p, reason=_coded(exc)))]) from None
    from .forms import NOTES_MARK
    sets = []
    for line, row, bad in rows:
        if row.get("student", "").strip().startswith(NOTES_MARK) and not row.get("variant", "").strip():
            continue            # form.csv's notes row (the sign conventions)
        from .tables import cell_value
        v = cell_value(row.get("variant", ""))
        aset = AnswerSet(source=f"{path}:{line}", student=printable(row.get("student", "").strip()),
                         group=printable(row.get("group", "").strip()), variant=None if v == "" else v,
                         mtime=_mtime(path) + line * 1e-6,      # a later row of one table is the newer
                         email=row.get("email", "").strip(), idnumber=row.get("id", "").strip())
        if bad:
            aset.error = Message("answers.table_row", where=f"{path}:{line}", reason=bad)
        for p in paths:
            try:
                aset.answers[p] = answer_value(row.get(p, ""), p)
                _keep_written(aset, p, row.get(p, ""))
            except ValueError as exc:       # this cell only: the row's other answers are graded as usual
                aset.answers[p] = None
                aset.invalid[p] = (row.get(p, ""), Message("answers.invalid_cell", where=f"{path}:{line}", column=p,
                                                           reason=_coded(exc)))
        sets.append(aset)
    return sets


def load_sources(path: Path) -> list[AnswerSet]:
    """--answers FILE | DIR | CSV."""
    path = Path(path)
    if path.is_dir():
        return load_answers_dir(path)
    if not path.exists():
        raise TaskError(Message("answers.no_source"), file=str(path), kind="answers file")
    if path.suffix.lower() == ".csv":
        return load_answers_csv(path)
    return [load_answers_file(path)]


def task_answer_set(task) -> AnswerSet | None:
    """The task's own `answers` section as a set (None when it has none)."""
    if not task.answers:
        return None
    aset = AnswerSet(source=task.file or task.name, student=task.who[0], group=task.who[1], variant=task.variant,
                     stem=task.name)
    for k, v in task.answers.items():      # read as an answers file's are ('8,8', '-200 N*m')
        _add_answer(aset, str(k), v)
    return aset


def load_tolerance_file(path: Path) -> dict:
    """--tolerance FILE: a YAML mapping (or one with a `tolerance:` key) path -> tolerance."""
    from .yamlload import load_yaml
    path = Path(path)
    if not path.exists():
        raise TaskError(Message("answers.no_source"), file=str(path), kind="tolerance file")
    if not path.is_file():
        raise TaskError(Message("input.tol_not_file"), file=str(path), kind="tolerance file")
    try:
        data, marks = load_yaml(path)
    except TaskError as exc:         # not YAML: where and why, as for a task file
        exc.kind = "tolerance file"
        raise
    base = ()
    if isinstance(data, dict) and isinstance(data.get("tolerance"), dict):
        data, base = data["tolerance"], ("tolerance",)
    elif isinstance(data, dict) and "tolerance" in data:     # `tolerance: 0.05`, as a task's section is
        line, col = _mark(marks, ("tolerance",))            # never written: it graded at 5 % unsaid
        raise TaskError("invalid tolerance file", file=str(path), kind="tolerance file",
                        issues=[("tolerance", line, col, Message("input.tol_section_not_mapping",
                                                                   got=repr(data["tolerance"])))])
    if not isinstance(data, dict):
        raise TaskError(Message("input.tol_not_mapping"), file=str(path), kind="tolerance file")
    out = {}
    for k, v in data.items():
        line, col = _mark(marks, base + (k,))
        try:
            out[str(k)] = parse_tolerance(v, str(k), line, col, str(path))
        except TaskError as exc:
            raise _decimal_comma_told(exc, path, line) from None
    return out


def _decimal_comma_told(exc: TaskError, path: Path, line: int | None) -> TaskError:
    """``exc`` (a tolerance file's entry), or, where its line holds a number with a decimal comma
    inside {...} (``{abs: 0,5}``: YAML read it as ``abs: 0`` and a key ``5``), that said instead,
    as the task file's reader says it."""
    from .yamlload import decimal_comma_hint
    try:
        text = path.read_text(encoding="utf-8").splitlines()[line - 1] if line else ""
    except (OSError, UnicodeDecodeError, IndexError):
        return exc
    hint = decimal_comma_hint(text)
    if hint is None or not exc.issues:
        return exc
    fld, ln, col, _ = exc.issues[0]
    msg = Message("input.decimal_comma_value", **hint.params)
    return TaskError(exc.message, file=exc.file, issues=[(fld, ln, col, msg)], kind=exc.kind)


def tolerances(task, override: dict | None = None, results: dict | None = None) -> dict:
    """The task's `tolerance`, then --tolerance FILE per key (never a student's file's:
    the instructor's tolerances only). A key whose tolerance is ``graphical`` (``default`` or a path or
    prefix) gives every path under it that a student reads off a drawing the relative
    error of reading it to 0.5 mm at the report's scales (the 12-position integration for
    the flywheel: `tmm_cli.graphical.graphical_tolerance`); its other paths keep the
    default."""
    raw = {str(k): v for k, v in (task.tolerance or {}).items()}
    raw.update(override or {})
    tol = {k: parse_tolerance(v, f"tolerance.{k}") for k, v in raw.items() if v != GRAPHICAL}
    hand = [k for k, v in raw.items() if v == GRAPHICAL]
    if hand:
        from .graphical import graphical_tolerance
        est = graphical_tolerance(results or {})
        for k in sorted(hand, key=len, reverse=True):       # the longest prefix first
            for path, rel in est.items():
                under = k == "default" or path == k or path.startswith(k + ".") or path.startswith(k + "[")
                if under and path not in tol:
                    tol[path] = (Tol(rel=0.0, plain=False, band=rel) if isinstance(rel, tuple)
                                 else Tol(rel=abs(float(rel))))
    return tol


def unused_tolerance_keys(keys, results: dict) -> list[Message]:
    """A warning (``answers.tol_key_unused``, with "did you mean") for each tolerance key but
    `default` that is neither a numeric result path of ``results`` nor a prefix of one, in a
    section the results have: a typo (`differential.sped`) that would leave its paths at the
    default silently (a key of a section the task has not, `kinematics` for a gear pair, is
    another task's; a key of no task's section, `kinematcs`, is a typo too). Only a key's own
    section is walked (a batch calls this per variant)."""
    import difflib
    out = []
    for k in sorted(set(map(str, keys)) - {"default"}):
        sec = k.split(".")[0].split("[")[0]
        if sec not in results and sec in SECTIONS:      # a section of other tasks (a group's tolerance file)
            continue
        if sec not in results:               # no section of any task (`kinematcs`): its paths keep the default
            hit = difflib.get_close_matches(sec, sorted(SECTIONS), n=1, cutoff=0.6)
            hint = (Message("answers.did_you_mean", path=k.replace(sec, hit[0], 1)) if hit
                    else Message("answers.no_such_path"))
            out.append(Message("answers.tol_key_unused", key=k, hint=hint))
            continue
        leaves = [q for q, v in leaf_paths({sec: results[sec]})
                  if isinstance(v, (int, float)) and not isinstance(v, bool)]
        if any(q == k or q.startswith(k + ".") or q.startswith(k + "[") for q in leaves):
            continue
        near = {q[:m.start()] for q in leaves for m in re.finditer(r"[.\[]", q)} | set(leaves)
        hit = difflib.get_close_matches(k, sorted(c for c in near if "[" not in c), n=1, cutoff=0.6)
        hint = Message("answers.did_you_mean", path=hit[0]) if hit else Message("answers.no_such_path")
        out.append(Message("answers.tol_key_unused", key=k, hint=hint))
    return out


def angle_tolerance_note(rows: list[dict], tol: dict) -> Message | None:
    """``answers.angle_relative`` (for the instructor, once) where an angle answer of ``rows`` was
    graded with a relative tolerance that passes it more than 1 deg off (the default 5 % passes a
    phi0 of 92 deg 4.6 deg off: a swapped working and idle stroke, 175 for 181.4 deg, with it):
    the largest such share, what it allows at 90 deg and the paths (four, sorted). None where every
    angle's bound is absolute or within 1 deg."""
    wide, paths = 0.0, []
    for r in rows:
        ref = r.get("reference")
        if ref is None or not _is_angle(r["path"]):
            continue
        t = tolerance_for(r["path"], tol, count=False)
        t = t if isinstance(t, Tol) else parse_tolerance(t, r["path"])
        if t.band is None and t.rel > 0:
            bound, kind = bound_of(float(ref), t)
            if kind == "rel" and bound > 1.0:
                wide = max(wide, t.rel)
                if r["path"] not in paths:
                    paths.append(r["path"])
    if not wide:
        return None
    return Message("answers.angle_relative", rel=wide, at90=90.0 * wide, paths=sorted(paths)[:4],
                   more="" if len(paths) <= 4 else ", ...", path=sorted(paths)[0])


def merged_angle_notes(notes: list) -> list:
    """``notes`` with every ``answers.angle_relative`` (one per variant of a batch, each naming its
    own paths) made one, where the first was: the largest share, the paths of them all."""
    def angle(n) -> bool:
        return isinstance(n, Message) and n.code == "answers.angle_relative"
    found = [n for n in notes if angle(n)]
    if len(found) < 2:
        return list(notes)
    rel = max(n.params["rel"] for n in found)
    paths = sorted({p for n in found for p in n.params["paths"]})
    more = len(paths) > 4 or any(n.params.get("more") for n in found)
    one = Message("answers.angle_relative", rel=rel, at90=90.0 * rel, paths=paths[:4], more=", ..." if more else "",
                  path=paths[0])
    out, done = [], False
    for n in notes:
        if angle(n):
            if not done:
                out.append(one)
                done = True
            continue
        out.append(n)
    return out


# ------------------------------------------------------------------ results paths
# ------------------------------------------------------------------ grading
def bound_of(ref: float, tol: Tol) -> tuple[float, str]:
    """The largest |answer - reference| a tolerance passes, and its kind ('rel' | 'abs')."""
    if ref == 0 and tol.plain:
        return tol.rel, "abs"
    rel_b = tol.rel * abs(ref)
    return (rel_b, "rel") if rel_b >= tol.abs and ref != 0 else (tol.abs, "abs")


def passed_interval(ref: float, tol: Tol) -> tuple[float, float]:
    """(centre, half-width) of the answers a tolerance passes (its band's middle and half its
    width, else the reference and :func:`bound_of`), with compare's slack."""
    slack = 1e-12 * max(1.0, abs(ref))
    if tol.band is not None:
        lo, hi = tol.band
        return (lo + hi) / 2, (hi - lo) / 2 + slack
    return ref, bound_of(ref, tol)[0] + slack


def compare(student: float, ref: float, tol: Tol, angle: bool | str | None) -> tuple[str, float, str]:
    """(status, error, kind of error: 'rel' | 'abs'). With ``tol.any_sign`` the magnitude
    is graded: the answer or its negation, whichever is nearer. ``angle`` (truthy): degrees,
    the difference taken modulo 360; 'arc' (:func:`angle_kind`): the negation's not."""
    if tol.any_sign:
        one = dataclasses.replace(tol, any_sign=False)          # the same tolerance (a band too), one sign
        a, b = (compare(s, ref, one, angle) for s in (student, -student))
        return ("ok", b[1], b[2]) if b[0] == "ok" and a[0] != "ok" else a

    def diff(a, wrap=bool(angle)):
        d = a - ref
        return (d + 180.0) % 360.0 - 180.0 if wrap else d
    d = abs(diff(student))
    slack = 1e-12 * max(1.0, abs(ref))
    if tol.band is not None:             # an interval: inside it, or its mirror (the sign), or outside
        lo, hi = tol.band
        err = d / abs(ref) if ref else d
        kind = "rel" if ref else "abs"
        if lo - slack <= student <= hi + slack:
            return "ok", err, kind
        if ref != 0 and lo - slack <= -student <= hi + slack:
            return "sign", err, kind
        return "outside", err, kind
    bound, kind = bound_of(ref, tol)
    err = d / abs(ref) if kind == "rel" else d
    if d <= bound + slack:
        return "ok", err, kind
    if ref != 0 and abs(diff(-student, wrap=bool(angle) and angle != "arc")) <= bound + slack:
        return "sign", err, kind
    return "outside", err, kind


def grade(results: dict, aset: AnswerSet, tol: dict, required: list[str] | None = None) -> list[dict]:
    """One row (CHECK_FIELDS) per answer of the set and per required path it lacks."""
    paths = list(aset.answers) + [p for p in (required or []) if p not in aset.answers]
    leaves = None
    rows = []
    for p in paths:
        val = aset.answers.get(p)
        t = tolerance_for(p, tol)
        t = t if isinstance(t, Tol) else parse_tolerance(t, p)
        row = {"student": aset.student, "group": aset.group, "variant": "" if aset.variant is None else aset.variant,
               "path": p, "answer": val, "reference": None, "error": None, "tolerance": t.text, "status": "",
               "note": "", "answers_file": aset.answers_file if aset.source else ""}
        if p in aset.written:
            row["written"] = aset.written[p]
        if p.startswith("positions.") and _last_name(p) == "H":     # the stroke: a slider's m, a rocker's deg
            row["unit"] = "deg" if (results.get("positions") or {}).get("output_kind") == "rocker" else "m"
        rows.append(row)
        try:
            ref = lookup(results, p)
        except KeyError as exc:
            sec = p.split(".")[0].split("[")[0]
            if sec not in results and sec in SECTIONS:
                row["status"], row["note"] = "not_computed", Message("answers.note_no_stage", section=sec)
            else:
                if leaves is None:
                    leaves = [q for q, v in leaf_paths(results) if isinstance(v, (int, float))]
                row["status"] = "unknown_path"
                row["note"] = Message("answers.note_unknown_path", reason=_coded(exc),
                                      hint=did_you_mean(p, results, leaves))
            continue
        if ref is None:
            row["status"], row["note"] = "not_computed", Message("answers.note_no_value")
            continue
        if isinstance(ref, bool):
            ref = float(ref)
        ref = reference(ref)            # a round-off zero (v at a dead centre: 8.7e-17) graded as 0
        if not isinstance(ref, (int, float)):
            if leaves is None:
                leaves = [q for q, v in leaf_paths(results) if isinstance(v, (int, float))]
            row["status"] = "unknown_path"
            row["note"] = Message("answers.note_not_number", kind=type(ref).__name__, hint=did_you_mean(p, results, leaves))
            continue
        if type(ref) is int:            # a count: exact, unless the tolerances name it
            t = tolerance_for(p, tol, count=True)
            t = t if isinstance(t, Tol) else parse_tolerance(t, p)
            row["tolerance"] = t.text
        row["reference"] = float(ref)
        if p in aset.invalid:
            row["answer"], row["status"] = aset.invalid[p][0], "invalid"
            row["note"] = aset.invalid[p][1]
            continue
        if val is None:
            row["status"], row["note"] = "missing", Message("answers.note_missing")
            continue
        status, err, kind = compare(float(val), float(ref), t, angle_kind(p))
        row["status"], row["error"] = status, err
        if status == "sign":
            row["note"] = Message("answers.note_sign")
        elif status == "outside" and p not in aset.written and (slip := _unit_slip(p, float(val), float(ref), t)):
            row["note"] = slip
        elif kind == "abs" and status != "ok":
            row["note"] = Message("answers.note_absolute")
    return rows


# an answer without a unit is in the path's SI unit; one that matches the reference in the unit a
# student works in instead (a length in mm, a speed in rpm, an angle in radians) is told so
_SLIPS = {"m": (("mm", 1e-3),), "m or deg": (("mm", 1e-3),), "rad/s": (("rpm", math.pi / 30),),
          "deg": (("rad", 180 / math.pi),)}


def _unit_slip(path: str, val: float, ref: float, t: Tol) -> Message | None:
    """``answers.note_unit_slip`` where the bare number ``val`` is within tolerance of the
    reference once read in the unit a student likely meant (98,5 for 0,0985 m: mm), else None."""
    from .forms import unit_of
    for unit, factor in _SLIPS.get(unit_of(path) or "", ()):
        if ref != 0 and compare(val * factor, ref, t, False)[0] == "ok":
            return Message("answers.note_unit_slip", unit=unit, si=unit_of(path).split()[0], value=val)
    return None


def set_status(rows: list[dict]) -> str:
    if not rows or all(r["answer"] is None and r["status"] != "invalid" for r in rows):
        return "no_answers"
    present = {"outside" if r["status"] == "invalid" else r["status"] for r in rows}
    if present <= {"ok"}:
        return "ok"
    for s in SET_ORDER:
        if s in present:
            return s
    return "ok"


def set_code(status: str) -> int:
    """The exit code of an answer set's status (not_computed alone does not fail)."""
    return {"ok": 0, "not_computed": 0, "invalid": 2, "failed": 3}.get(status, 1)


def counts(rows: list[dict]) -> dict[str, int]:
    return {s: sum(r["status"] == s for r in rows) for s in STATUSES}


def check_csv(rows: list[dict]) -> str:
    from .tables import csv_text
    return csv_text(CHECK_FIELDS, rows)


def check_task(results: dict, answers: dict[str, float], tol: dict) -> list[dict]:
    """Grade plain answers (path -> number) with a tolerance mapping: the rows of
    :func:`grade` with `quantity`, `student` (the value), `rel_error` and `verdict` too."""
    rows = grade(results, AnswerSet(source="", answers=dict(answers)), tol)
    for r in rows:
        r["quantity"], r["rel_error"], r["verdict"] = r["path"], r["error"], r["status"]
    return rows


def short(text: str, n: int) -> str:
    text = re.sub(r"\s+", " ", str(text))
    return text if len(text) <= n else text[: n - 1] + "…"
