"""The task model: one variant of the course project, validated once.

The task file's sections (README, *The task file*) composed into :class:`Task`: each topic
owns its sections beside its stage (tmm_cli/linkage/spec.py, cam/spec.py, gears/spec.py,
trainspec.py, balancing/spec.py, differential/spec.py, dof2/spec.py); this module composes
them and loads. Quantities are converted to SI floats (angles in degrees) at validation.
Unknown keys are errors with a "did you mean". :func:`load_task` reads a YAML file (or a
dict) and raises :class:`TaskError` naming the file, line, column and field of every
problem. The model is the input only: what the stages compute from it (the mechanism a
``synthesis`` generates: ``linkage.synthesis.generate``) is never kept on it.
"""
# annotations evaluated as written (no `from __future__ import annotations`): pydantic would
# compile and evaluate every field's annotation string when the models are made
import re
from functools import partial
from pathlib import Path
from typing import Annotated, Literal, Union

from pydantic import (BaseModel, BeforeValidator, ConfigDict, Discriminator, Field, PrivateAttr, Tag,
                      ValidationError, WithJsonSchema, field_validator, model_validator)

from . import locales
from .errors import TaskError, dotted
from .messages import Message
from .cam.spec import CamSection, LawsSpec, LimitsSpec, PhasesSpec
from .gears.spec import GearsSection, PlanetarySection
from .linkage.spec import (DiagramSpec, DriveSection, FlywheelSection, ForceSpec, FrictionSpec, KinetostaticsSection,
                           LinkSpec, LoadsSection, MechanismSection, PositionsSection, ShapeSpec, SynthesisLinkSpec,
                           SynthesisSection)
from .modelbase import FieldValueError, _Model
from .units import tolerance_number

Point2 = tuple[float, float]

_UNKNOWN = re.compile(r"unknown key '([^']+)'")



# ---------------------------------------------------------------- report
class ReportSection(_Model):
    detail_position: int | None = Field(None, ge=0, strict=True)


from .trainspec import DOCS as _TRAIN_DOCS  # noqa: E402
from .trainspec import DriveTrainSection, TrainStageSpec  # noqa: E402


def _tol_number(what: str):
    """A tolerance's number read by the number grammar ('0,02', '1/20'): units.tolerance_number."""
    return BeforeValidator(partial(tolerance_number, what=what))


# a tolerance's number in the JSON Schema: a number, or a string that begins as one ('0,05', '1/20')
_TOL_SCHEMA = WithJsonSchema({"anyOf": [{"type": "number", "minimum": 0},
                                        {"type": "string", "pattern": "^\\s*[0-9]",
                                         "description": "a number such as '0,05' or '1/20'"}]})


class ToleranceSpec(_Model):
    """A tolerance as {rel: R, abs: A}: passes when |student - reference| <= max(A, R |reference|);
    `sign: any` grades the magnitude (either sign passes)."""
    rel: Annotated[float, _tol_number("rel"), _TOL_SCHEMA] = 0.0
    abs: Annotated[float, _tol_number("abs"), _TOL_SCHEMA] = 0.0
    sign: Literal["any"] | None = None


def _tolerance_kind(value) -> str:
    """Which form a tolerance is written in: a mapping {rel, abs, sign}, `graphical`, or a number
    (so that a wrong one is told in its own form's terms, not as every form's error)."""
    if isinstance(value, (dict, ToleranceSpec)):
        return "tag:spec"
    return "tag:graphical" if value == "graphical" else "tag:number"


ToleranceValue = Annotated[Union[Annotated[Literal["graphical"], Tag("tag:graphical")],
                                 Annotated[float, _tol_number("plain"), _TOL_SCHEMA, Tag("tag:number")],
                                 Annotated[ToleranceSpec, Tag("tag:spec")]],
                           Discriminator(_tolerance_kind)]


class StudentSpec(BaseModel):
    model_config = ConfigDict(extra="allow", defer_build=True)
    name: str | None = None
    group: str | None = None


# the course's own examples in the field descriptions (a designation, the title block's words)
_EXAMPLES = locales.topic("en", "schema")["examples"]


class CourseSpec(_Model):
    """The course header of the explanatory note's title page and of the sheets' title blocks."""
    university: str | None = None
    department: str | None = None
    supervisor: str | None = None
    city: str | None = None
    year: int | None = Field(None, ge=1900, le=2200)
    designation: str | None = Field(None, description=f"the document's designation, e.g. '{_EXAMPLES['designation']}'")


from .balancing.spec import BalancingSection  # noqa: E402
from .differential.spec import DifferentialSection  # noqa: E402
from .dof2.spec import Dof2Section  # noqa: E402


class Task(_Model):
    schema_: Literal["tmm/1"] = Field(..., alias="schema")
    title: str = ""
    variant: Union[int, str, None] = None
    student: StudentSpec | None = None
    course: CourseSpec | None = None
    mechanism: MechanismSection | None = None
    synthesis: SynthesisSection | None = None
    drive: DriveSection | None = None
    positions: PositionsSection | None = None
    loads: LoadsSection | None = None
    kinetostatics: KinetostaticsSection | None = None
    flywheel: FlywheelSection | None = None
    cam: CamSection | None = None
    gears: GearsSection | None = None
    planetary: PlanetarySection | None = None
    drive_train: DriveTrainSection | None = None
    balancing: BalancingSection | None = Field(None, description="balancing: the linkage's shaking force and "
                                                                 "moment, counterweights; a rotor's correction masses")
    differential: DifferentialSection | None = Field(None, description="a differential: a planetary scheme A-D "
                                                                       "with no member fixed (runs on its own)")
    dof2: Dof2Section | None = Field(None, description="a machine with two degrees of freedom: rotor + hinged "
                                                       "striker (docs/methods.md §7; runs on its own)")
    report: ReportSection | None = None
    # a number, or a string as an answers file holds it ('8,8', '-200 N*m'): read when graded,
    # by the answers file's reader (an unreadable one is that answer's `invalid`)
    answers: dict[str, Union[float, str, None]] = Field(default_factory=dict)
    tolerance: dict[str, ToleranceValue] = Field(default_factory=dict)

    _file: str | None = PrivateAttr(None)
    # factories written as lambdas: pydantic reads a factory's signature for every Task it
    # makes, and the builtins' (dict, list) is parsed from text by tokenize (~5 ms, once)
    _marks: dict = PrivateAttr(default_factory=lambda: {})
    _input_warnings: list = PrivateAttr(default_factory=lambda: [])

    @field_validator("tolerance", mode="before")
    @classmethod
    def _tolerance_mapping(cls, v):
        if v is not None and not isinstance(v, dict):     # `tolerance: 0.05` meant {default: 0.05}
            raise ValueError(Message("input.tol_section_not_mapping", got=repr(v)))
        return v

    @field_validator("schema_", mode="before")
    @classmethod
    def _schema(cls, v):
        if v != "tmm/1":
            raise ValueError(Message("input.schema", got=repr(v)))
        return v

    @model_validator(mode="after")
    def _synthesise(self):
        """`synthesis` stands for the `mechanism` it generates (the synthesis stage,
        ``linkage.synthesis.generate``, makes it: orchestrate.prepare and the pipeline), and
        needs the drive's sense of rotation."""
        if self.synthesis is None:
            return self
        if "mechanism" in self.model_fields_set:
            raise FieldValueError(("synthesis",), Message("input.synthesis_and_mechanism"))
        if self.drive is None:
            raise FieldValueError(("synthesis",), Message("input.synthesis_drive"))
        if self.drive.link != "crank":
            # every type is designed for its crank driving (K and theta count the crank's turn):
            # the rocker driving failed in the kinematics of a mechanism the student never wrote
            raise FieldValueError(("drive", "link"), Message("input.synthesis_drive_crank", link=self.drive.link))
        return self

    @model_validator(mode="after")
    def _sections(self):
        needs_mech = [s for s, v in (("drive", self.drive), ("positions", self.positions), ("loads", self.loads),
                                     ("kinetostatics", self.kinetostatics), ("flywheel", self.flywheel))
                      if v is not None]
        linkage = self.mechanism is not None or self.synthesis is not None
        if self.mechanism is not None and self.drive is None:
            raise FieldValueError(("mechanism",), Message("input.needs_drive"))
        if not linkage and needs_mech:
            raise FieldValueError((needs_mech[0],), Message("input.needs_mechanism", sections=needs_mech))
        if self.report is not None and self.report.detail_position is not None and not linkage:
            raise FieldValueError(("report", "detail_position"), Message("input.detail_needs_mechanism"))
        if self.balancing is not None and self.balancing.counterweights is not None and not linkage:
            raise FieldValueError(("balancing", "counterweights"), Message("input.balancing_needs_mechanism"))
        if self.balancing is not None and self.balancing.rotor is None and not linkage:
            # `balancing: {}` alone computed nothing and said nothing
            raise FieldValueError(("balancing",), Message("input.balancing_nothing"))
        if self.flywheel is not None and self.loads is None:
            raise FieldValueError(("flywheel",), Message("input.flywheel_loads"))
        return self

    # --------------------------------------------------------------------
    @property
    def file(self) -> str | None:
        return self._file

    @property
    def input_warnings(self) -> list[str]:
        """Warnings about valid but doubtful values (a plain number probably meant in
        rpm or mm), found when the task was read."""
        return list(self._input_warnings)

    @property
    def name(self) -> str:
        return Path(self._file).stem if self._file else (self.title or "task")

    @property
    def who(self) -> tuple[str, str]:
        """(name, group) of the task's student, '' for what the task does not give (the title
        blocks, the forms, the answer sets and the batch's rows read it here)."""
        st = self.student
        return ((st.name or "") if st else "", (st.group or "") if st else "")

    def line_of(self, path: tuple) -> tuple[int | None, int | None]:
        """(line, column) of a field path, or of its nearest given ancestor."""
        p = tuple(path)
        while p:
            if p in self._marks:
                return self._marks[p]
            p = p[:-1]
        return self._marks.get((), (None, None))

    def locate(self, err: TaskError) -> TaskError:
        """``err`` with this task's file and the line of each issue's field filled in (for a
        TaskError raised by a stage, which knows the field but not the file)."""
        if err.file is not None and all(line is not None for _, line, _, _ in err.issues):
            return err
        from .results import parse_path
        issues = []
        for fld, line, col, msg in err.issues:
            if line is None and fld:
                try:
                    line, col = self.line_of(tuple(parse_path(fld)))
                except KeyError:
                    pass
            issues.append((fld, line, col, msg))
        return TaskError(err.message, file=err.file or self._file, issues=issues)

    def error(self, path: tuple, message: str) -> TaskError:
        """A TaskError pointing at a field of this task (used by later checks)."""
        line, col = self.line_of(path)
        return TaskError(message, file=self._file, issues=[(dotted(path), line, col, message)])


_MSG_CLEAN = [
    (re.compile(r"^Value error, "), ""),
    (re.compile(r"^Assertion failed, "), ""),
]


def _issue_from_error(err: dict, marks: dict) -> tuple[str, int | None, int | None, str]:
    if err["type"] == "model_type":
        # 'a valid dictionary or instance of CouplerPose': the class is no word of the task file
        err = {**err, "type": "dict_type", "msg": "Input should be a valid dictionary", "ctx": {}}
    loc = [p for p in err["loc"]]
    # pydantic puts union member / validator tags into loc: drop the non-field ones
    clean: list = []
    for p in loc:
        if isinstance(p, str) and (p.startswith("function-") or p in ("literal['extreme']", "literal['auto']",
                                                                      "literal['all']", "literal['constant']")
                                   or p.startswith("tuple[") or p.startswith("literal[") or p == "str"
                                   or p == "list[int]" or p == "LimitsSpec" or p == "float" or p == "bool"
                                   or p.endswith("-after]") or p.endswith("-before]")
                                   or p.startswith("tag:") or p in ("[key]", "constrained-int")):
            continue
        clean.append(p)
    msg = err["msg"]
    for rx, rep in _MSG_CLEAN:
        msg = rx.sub(rep, msg)
    m = _UNKNOWN.search(msg)
    if m:
        clean.append(m.group(1))
    cause = (err.get("ctx") or {}).get("error")
    if isinstance(cause, FieldValueError):
        clean.extend(cause.field)
    if err["type"] == "missing":
        msg = "required field is missing"
    elif err["type"] == "literal_error":
        msg = f"{msg}; got {err.get('input')!r}"
        hint = _literal_hint(err)
        if hint:
            msg = f"{msg}; did you mean {hint!r}?"
    msg = _coded_issue(err, cause, msg)
    path = tuple(clean)
    if path and path[0] == "schema_":
        path = ("schema",) + path[1:]
    # map `return_` back to the YAML spelling
    path = tuple("return" if p == "return_" else p for p in path)
    line = col = None
    p = path
    while True:
        if p in marks:
            line, col = marks[p]
            break
        if not p:
            break
        p = p[:-1]
    return dotted(path), line, col, msg


# pydantic's error types a student meets, as catalogue codes (input.<type>) with the
# parameters of pydantic's own message (its `ctx`)
_PYDANTIC_CODES = {"int_parsing": (), "float_parsing": (), "bool_parsing": (), "int_from_float": (),
                   "int_type": (), "float_type": (), "bool_type": (), "string_type": (), "dict_type": (),
                   "list_type": (), "tuple_type": (), "finite_number": (), "model_type": ("class_name",),
                   "greater_than": ("gt",), "greater_than_equal": ("ge",), "less_than": ("lt",),
                   "less_than_equal": ("le",), "too_short": ("field_type", "min_length", "actual_length"),
                   "too_long": ("field_type", "max_length", "actual_length")}


def _coded_issue(err: dict, cause, msg: str) -> str:
    """An issue's message ``msg`` as a coded Message with the same English text (a
    validator's own coded message, or one of pydantic's error types); ``msg`` as it is
    when it has no code, or the coded text would differ from it."""
    kind, ctx = err["type"], err.get("ctx") or {}
    coded = None
    if cause is not None and cause.args and isinstance(cause.args[0], Message) and cause.args[0].code:
        coded = cause.args[0]
    elif kind == "missing" and tuple(err["loc"]) in (("schema",), ("schema_",)):
        return Message("input.schema_missing")      # a file without its first line
    elif kind == "missing":
        coded = Message("input.missing")
    elif kind == "literal_error":
        expected = str(ctx.get("expected", ""))
        hint = _literal_hint(err)
        coded = Message("input.literal_hint" if hint else "input.literal", expected=re.split(r", | or ", expected),
                        got=repr(err.get("input")), **({"hint": repr(hint)} if hint else {}))
    elif kind in _PYDANTIC_CODES and all(k in ctx for k in _PYDANTIC_CODES[kind]):
        coded = Message(f"input.{kind}", **{k: _ctx_text(ctx[k]) for k in _PYDANTIC_CODES[kind]})
    return coded if coded is not None and coded == msg else msg


def _literal_hint(err: dict) -> str | None:
    """The choice meant by a value that is none of a Literal's (a misspelling, or the course's
    other name, the catalogues' `values` synonyms: 'linear' is the constant-velocity law, a
    course language's words for ccw are ccw), or None."""
    import difflib
    got, expected = err.get("input"), str((err.get("ctx") or {}).get("expected", ""))
    if not isinstance(got, str):
        return None
    choices = [c.strip("'\"") for c in re.split(r", | or ", expected) if c]
    word = got.strip().lower().replace("-", "_").replace(" ", "_")
    from . import locales
    plain = re.sub(r"_+", "_", word)
    for lang in locales.LANGS:           # 'linear', or a course language's words for ccw (values.yaml)
        meant = (locales.of("values", "synonyms", lang) or {}).get(plain)
        if meant in choices:
            return meant
    near = difflib.get_close_matches(word, choices, n=1, cutoff=0.7)
    return near[0] if near and near[0] != got else None


def _ctx_text(v) -> str:
    """A value of pydantic's error context as its message shows it (0.0 as 0)."""
    if isinstance(v, float) and v.is_integer():
        return str(int(v))
    return str(v)


def _decimal_comma_issues(issues: list, file: str | None, text: str | None) -> list:
    """An issue on a line holding a number with a decimal comma (``[0,38, 0,12]``, very
    common in the course's countries) says so: 'use a decimal point: 0.38'."""
    if file is None and text is None:
        return issues
    from .yamlload import decimal_comma_hint, decimal_comma_key
    try:
        lines = (text if text is not None else Path(file).read_text(encoding="utf-8")).splitlines()
    except (OSError, UnicodeDecodeError):
        return issues
    out, hinted = [], set()
    for fld, line, col, msg in issues:
        hint = decimal_comma_hint(lines[line - 1]) if line and 0 < line <= len(lines) else None
        if hint is None:
            out.append((fld, line, col, msg))
        elif line not in hinted:        # one message per line: the split number's pieces
            hinted.add(line)            # give several errors
            key = decimal_comma_key(lines[line - 1])
            if key is not None:         # a mapping's value: the field is that key ('rod.mass',
                # not the piece YAML made a key of, 'rod.1'), the value may also be quoted
                parent = fld.rsplit(".", 1)[0] if "." in fld else ""
                fld = f"{parent}.{key}" if parent else key
                hint = Message("input.decimal_comma_value", **hint.params)
            out.append((fld, line, col, hint))
    return out


def load_task(source: Union[str, Path, dict], *, text: str | None = None) -> Task:
    """Read and validate a task. ``source`` is a path to a YAML file or a dict of the
    same shape. Raises :class:`TaskError` with file, line and field of every problem."""
    if isinstance(source, dict):
        data, marks, file = source, {}, None
    else:
        from .yamlload import load_yaml
        file = str(source)
        data, marks = load_yaml(source, text=text)
    if not isinstance(data, dict):
        msg = Message("input.not_mapping")
        raise TaskError(msg, file=file, issues=[("", 1, 1, msg)])
    from .limits import text_issues
    bad_text = text_issues(data, marks)     # one rule for every text of the task, before the schema
    if bad_text:
        raise TaskError("invalid task", file=file, issues=bad_text)
    try:
        from .schemacache import validator
        task = validator(Task).validate_python(data)
    except ValidationError as exc:
        issues = []
        seen = set()
        for err in exc.errors(include_url=False):
            issue = _issue_from_error(err, marks)
            if issue[0:1] + issue[3:] in seen:
                continue
            seen.add(issue[0:1] + issue[3:])
            issues.append(issue)
        issues = _decimal_comma_issues(issues, file, text)
        raise TaskError("invalid task", file=file, issues=issues) from None
    task._file = file
    task._marks = marks
    from .input_notices import plain_number_warnings
    task._input_warnings = plain_number_warnings(Task, data)
    return task


# ---------------------------------------------------------------- field documentation
# One line per field, shown by `tmm fields` and in the JSON Schema (`tmm schema`).
_DOCS: dict[type, dict[str, str]] = {
    Task: {
        "schema_": "required: tmm/1",
        "title": "free text, shown in the report",
        "variant": "the variant number or name (free)",
        "student": "free metadata shown in the report: {name, group}",
        "course": "the explanatory note's title page (`--format note`): {university, department, supervisor, city, "
                  "year, designation}",
        "mechanism": "a planar linkage with lower pairs (the linkage stages run when present)",
        "drive": "the input link (crank): link, speed, direction, cycle",
        "positions": "the reported crank positions",
        "loads": "gravity, forces and couples (kinetostatics and flywheel)",
        "kinetostatics": "force analysis: reactions, balancing moment, Zhukovsky lever, singular positions",
        "flywheel": "the flywheel by the energy-mass method (also Merzalov and exact)",
        "cam": "cam mechanism synthesis (runs on its own)",
        "gears": "external spur involute pair with profile shift (runs on its own)",
        "planetary": "planetary gear synthesis (runs on its own)",
        "drive_train": "compound gear drive from the motor: ordinary pairs and planetary stages, given or chosen",
        "balancing": "balancing: the linkage's shaking force and moment (with a mechanism), its counterweights, and "
                     "a rigid rotor's static or dynamic balancing",
        "differential": "a differential (planetary scheme A-D, no member fixed): two members' speeds give the "
                        "third, one member's torque gives the others",
        "report": "what the report shows: {detail_position: N} (the position worked step by step)",
        "answers": "a student's numbers: path into results.json -> value, a number or a string with a unit "
                   "as an answers file holds it ('8,8', '-200 N*m') (tmm check / tmm batch)",
        "tolerance": "tolerances per path or prefix: {default: 0.05, <path or prefix>: 0.02 or {rel: R, abs: A, sign: any} or "
                     "graphical (the error of reading the drawings to 0.5 mm)}",
    },
    StudentSpec: {"name": "the student's name", "group": "the student's group"},
    CourseSpec: {"university": "the university (title page)", "department": "the department (title page)",
                 "supervisor": f"the supervisor (title page, title block '{_EXAMPLES['checked']}')", "city": "the city (title page)",
                 "year": "the year (title page; default: the year of the run)",
                 "designation": f"the document's designation in the title blocks, e.g. '{_EXAMPLES['designation']}'"},
    ToleranceSpec: {"rel": "relative tolerance (fraction of |reference|)", "abs": "absolute tolerance, in the unit of the path",
                    "sign": "any: the magnitude is graded (either sign passes)"},
    LinkSpec: {"mass": "mass, kg", "guide": "slider: the line it translates along (fixed or on a link)"},
    DriveSection: {"link": "the crank (a bar with a ground pivot)",
                   "direction": "ccw | cw",
                   "cycle": "360, or 720 for machines whose cycle takes two turns (four-stroke engines)"},
    PositionsSection: {
        "count": "number of equally spaced positions (default 12)",
        "zero": "extreme (position 0 = the extreme position that starts the working stroke) or a crank angle, deg",
        "output": "the link whose extreme positions are used (default: the last link)",
        "working": "forward | backward: the working stroke moves the output toward increasing | decreasing coordinate",
        "extra": "additional crank angles, deg (indices count, count+1, ...)",
    },
    LoadsSection: {"gravity": "true: g = 9.81 m/s^2 along -y on every link with mass",
                   "forces": "list of forces and couples"},
    ForceSpec: {
        "kind": "resistance (against the motion) | driving (along it); none: a signed force",
        "stroke": "working | idle | both (default working)",
        "working": "a load on a slider: forward | backward, the sense of that slider's own working stroke along "
                   "its guide (default positions.working); every loaded slider has its own stroke",
        "magnitude": "constant force, N (or a pressure with `area`)",
        "diagram": "{s: [...], value: [...]} over the relative stroke, or {phi: [...], value: [...]} over the "
                   "crank angle from position 0",
        "area": "piston area, m^2: the values are pressures, force = p * area",
        "at": "point of application: a point name or local [u, v] (default the centre of mass)",
        "direction": "deg from +x: the line of a force on a bar link (sliders: along the guide)",
        "moment": "a couple, N*m, ccw positive",
    },
    ReportSection: {"detail_position": "the position whose working the report writes out step by step (vector "
                                        "equations, scales, segments, formulas with numbers; default: the first "
                                        "working-stroke position after 0)"},
    DiagramSpec: {"value": "force (N) or pressure (Pa, with `area`) at each abscissa"},
    KinetostaticsSection: {
        "positions": "all | list of position numbers",
        "inertia": "include d'Alembert inertia loads (default true)",
        "balance": "link carrying the balancing moment (a slider: a balancing force); default the drive link",
        "friction": "{pin_radius, f} or {pin_radius, f_pin, f_slide}: friction in the pairs and the instantaneous efficiency",
        "motion": "constant (omega1 = const) | true: omega(phi), epsilon(phi) of the steady motion with the flywheel",
    },
    FrictionSpec: {"pin_radius": "radius of the pins, m",
                   "f": "friction coefficient of every pair (shorthand for f_pin = f_slide = f)",
                   "f_pin": "friction coefficient of the revolute pairs (couple f_pin r |R|; default 0)",
                   "f_slide": "friction coefficient of the prismatic pairs (force f_slide |N|; default 0)"},
    FlywheelSection: {
        "delta": "coefficient of speed fluctuation, e.g. 1/18",
        "constant": "which reduced moment is constant over the cycle: driving (a working machine driven by a motor: the driving moment) | resistance (an engine: the moment of resistance)",
        "method": "energy-mass | merzalov | exact: the primary J (all three are computed)",
        "resolution": "crank positions used for the integration (default 360)",
        "quadrature": "Gauss-Legendre points per interval for the works (default 2; 0: trapezoid)",
        "shape": "{type: disk | rim, density, width_ratio}",
    },
    ShapeSpec: {"type": "disk | rim", "density": "kg/m^3 (default 7800)",
                "width_ratio": "b / D (default 0.1)"},
    CamSection: {
        "follower": "translating | rocker (roller followers) | flat (flat-faced translating) | "
                    "knife (knife-edge translating, no roller)",
        "r0": "auto: the least base radius | a chosen base radius, m: the profile is built on it and the "
              "pressure angle checked",
        "center_distance": "rocker with a chosen r0: the distance from the cam centre to the rocker pivot, m",
        "rho_min_allowed": "flat: least radius of curvature of the profile, m (default 0)",
        "divisions": "parts of the rise and of the return in the division-point table (default 8)",
        "rocker_length": "rocker follower: its length, m",
        "offset": "translating: eccentricity, m (positive lowers the rise pressure angle) or auto",
        "phases": "{rise, far_dwell, return[, near_dwell]}, deg; near dwell = the rest",
        "laws": "{rise, return}: constant_velocity, parabolic, cosine, sine, poly345, linear_decreasing, trapezoidal",
        "pressure_angle": "allowed maximum, deg, or {rise, return}",
        "transmission_angle": "alternatively the allowed minimum transmission angle (90 - pressure angle)",
        "swing": "rocker: with | against (the rocker turns with or against the cam on the rise) | auto",
        "roller": "roller radius, m, or auto (min(0.7 rho_min, 0.4 r0))",
        "rotation": "ccw | cw: the cam's rotation",
        "speed": "optional cam speed (rad/s or rpm) for real velocities and accelerations",
    },
    PhasesSpec: {"rise": "rise phase, deg", "far_dwell": "far dwell, deg", "return_": "return phase, deg",
                 "near_dwell": "near dwell, deg (default: 360 - the others)"},
    LawsSpec: {"rise": "motion law of the rise", "return_": "motion law of the return"},
    LimitsSpec: {"rise": "on the rise, deg", "return_": "on the return, deg"},
    GearsSection: {"z": "tooth numbers [z1, z2]", "x": "profile shift coefficients [x1, x2] or auto",
                   "alpha": "profile angle of the basic rack, deg (default 20)",
                   "ha": "addendum coefficient ha* (default 1)", "c": "clearance coefficient c* (default 0.25)"},
    PlanetarySection: {"scheme": "A (single row: sun, satellites, fixed ring) | B (two rows, external-internal) | C (two rows, external-external) | D (two rows, internal-internal); the carrier is the output", "ratio": "required i_1H (signed)",
                       "satellites": "number of satellites", "tolerance": "allowed relative ratio error",
                       "m": "module for the drawing, m (default 1 mm)",
                       "z_min": "least tooth number of an external wheel", "z_max": "largest tooth number",
                       "rank": "size | ratio_error: the ranking key of the candidates",
                       "z_min_external": "least teeth of an external wheel in an external mesh (default z_min)",
                       "z_min_internal": "least teeth of an internal (ring) wheel",
                       "z_min_satellite_in_internal": "least teeth of an external wheel meshing a ring "
                                                      "(default max(20, z_min))",
                       "internal_minus_external_min": "least z_ring - z_pinion in an internal mesh"},
}
_DOCS.update(_TRAIN_DOCS)
for _model, _fields in _DOCS.items():
    for _name, _text in _fields.items():
        _model.model_fields[_name].description = _text

# the lever synthesis and the drive speed from the output
_DOCS_SYNTHESIS: dict[type, dict[str, str]] = {
    Task: {"synthesis": "design the lever mechanism from K and the stroke; replaces `mechanism` (the generated "
                        "links: crank, rod, slider | crank, coupler, rocker | crank, block, rocker[, blockC, ram])"},
    SynthesisSection: {
        "type": "slider_crank | offset_slider_crank | crank_rocker | slotted_lever | shaper | function | positions "
                "| path",
        "H": "stroke of the slider or ram, m (slider-cranks, shaper)",
        "psi": "swing of the rocker, deg (crank_rocker)",
        "K": "coefficient of mean speed increase K = (180 + theta)/(180 - theta) (or give theta)",
        "theta": "angle theta, deg (instead of K)",
        "lambda_": "slider-cranks: l_AB/l_OA (one of lambda, e, gamma_min)",
        "e": "offset_slider_crank: offset of the guide from the crank axis, m",
        "gamma_min": "slider-cranks: the least transmission angle over the cycle, deg",
        "rocker": "crank_rocker: l_O1B, m; slotted lever/shaper: slotted-link length (default 1.5 (frame + crank); "
                  "shaper H/(2 sin(psi/2)))",
        "frame": "crank_rocker, slotted lever, shaper: the distance OO1 between the fixed pivots, m",
        "guide_height": "shaper: the ram guide above O1, m (default H/(2 tan(psi/2)): the ram stroke is "
                        "2 guide_height tan(psi/2))",
        "links": "mass properties of the generated links: {name: {mass, J, com}}",
    },
    SynthesisLinkSpec: {"mass": "mass, kg"},
    DriveSection: {
        "speed": "the crank's mean angular speed (rad/s; or '50 rpm'); or one of the two below",
        "mean_output_speed": "the output's mean speed over the cycle (m/s; a rocker: rad/s or '12 deg/s'): "
                             "omega1 = pi V/H",
        "working_stroke_speed": "the output's mean speed over the working stroke: omega1 = 2 pi V/(H (1 + 1/K))",
    },
    PositionsSection: {
        "output": "the link whose extreme positions are used (default: the last link; with `synthesis` the "
                  "output: slider, rocker, ram)",
        "working": "forward | backward: the working stroke moves the output toward increasing | decreasing "
                   "coordinate (with `synthesis` default: the slow stroke)",
    },
}
for _model, _fields in _DOCS_SYNTHESIS.items():
    for _name, _text in _fields.items():
        _model.model_fields[_name].description = _text


def field_docs(model: type = Task, prefix: str = "") -> list[tuple[str, str, str]]:
    """(dotted path, default, description) of every task-file field, for `tmm fields`."""
    import typing

    from pydantic_core import PydanticUndefined

    out = []
    for name, f in model.model_fields.items():
        key = f.alias or name
        if f.is_required():
            default = "required"
        elif f.default is PydanticUndefined or f.default is None:
            default = "-"
        else:
            default = str(f.default)
        path = prefix + key
        out.append((path, default, f.description or ""))
        subs = []
        for a in typing.get_args(f.annotation) or (f.annotation,):
            for b in typing.get_args(a) or (a,):
                if isinstance(b, type) and issubclass(b, BaseModel) and b is not StudentSpec and b not in subs:
                    subs.append(b)
        for sub in subs:
            sub_prefix = path + (".<name>." if sub in (LinkSpec, SynthesisLinkSpec) else "[i]." if sub in (ForceSpec, TrainStageSpec) else ".")
            out.extend(field_docs(sub, sub_prefix))
    return out
