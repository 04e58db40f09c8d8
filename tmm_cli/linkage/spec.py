"""The linkage's sections of the task file: `mechanism`, `drive`, `positions`, `loads`,
`kinetostatics`, `flywheel` and `synthesis` (README, *The task file*), validated once by
the task model (tmm_cli/task.py composes them).  Quantities are SI floats (angles in
degrees).  Nothing here imports a stage: the stages import these sections."""
# annotations evaluated as written (no `from __future__ import annotations`): pydantic would
# compile and evaluate every field's annotation string when the models are made
import math
from typing import Annotated, Literal, Union

from pydantic import AfterValidator, Discriminator, Field, Tag, field_validator, model_validator

from ..limits import MAX_EXTRA_POINTS, MAX_EXTRA_POSITIONS, MAX_FORCES, MAX_POSITIONS
from ..messages import Message
from ..modelbase import FieldValueError, _Model
from ..units import (Angle, AngularSpeed, Area, Density, ForceOrPressure, Inertia,
                     Length, Mass, MomentQ, Number, Ratio)

LengthPair = tuple[Length, Length]
# the links each type of synthesis generates, in the order of the generated `mechanism`
LINKS = {"function": ("crank", "coupler", "rocker"), "positions": ("crank", "coupler", "rocker"),
         "path": ("crank", "coupler", "rocker"),
         "slider_crank": ("crank", "rod", "slider"),
         "offset_slider_crank": ("crank", "rod", "slider"),
         "crank_rocker": ("crank", "coupler", "rocker"),
         "slotted_lever": ("crank", "block", "rocker"),
         "shaper": ("crank", "block", "rocker", "blockC", "ram")}


# ---------------------------------------------------------------- mechanism
class GuideSpec(_Model):
    """The line a slider translates along: fixed ({through, angle}) or on a link."""

    through: Union[str, LengthPair, None] = Field(None, description="fixed guide: a point name or [x, y] on the line")
    angle: Angle | None = Field(None, description="deg: from +x (fixed guide) or relative to the guide link (moving)")
    link: str | None = Field(None, description="moving guide (slotted link): the link carrying the guide")
    offset: Length = Field(0.0, description="perpendicular shift to the left of the line (moving: of the link's axis), m")

    @model_validator(mode="after")
    def _kind(self):
        if self.link is None and self.through is None:
            raise ValueError(Message("input.guide_kind"))
        if self.link is not None and self.through is not None:
            raise ValueError(Message("input.guide_both"))
        if self.link is None and self.angle is None:
            raise ValueError(Message("input.guide_angle"))
        return self


#: a link's centre of mass, as `tmm fields` and the JSON Schema describe it (a task's link and a
#: generated one)
COM_DOC = ("centre of mass: [u, v] in the link's frame (from its first point, u towards its second, v to "
           "the left; a slider: from its pin, u along its guide), or a point name")


class LinkSpec(_Model):
    """A bar link (``points: [P, Q]``, ``length``) or a slider (``slider: P``, ``guide``)."""

    points: list[str] | None = Field(None, description="bar: its two pair points [P, Q]")
    length: Length | None = Field(None, description="bar: |PQ|, m")
    extra: dict[str, LengthPair] = Field(default_factory=dict, description=(
        "extra points in the link's frame [u, v], m: from its first point, u along the line to its second, v "
        "to the left of it (a slider: from its pin, u along its guide)"))
    slider: str | None = Field(None, description="slider: its pin point")
    guide: GuideSpec | None = None
    mass: Mass = Field(0.0, ge=0)
    J: Inertia = Field(0.0, ge=0, description="moment of inertia about the centre of mass, kg*m^2")
    com: Union[str, LengthPair, None] = Field(None, description=COM_DOC)

    @field_validator("points")
    @classmethod
    def _two_points(cls, v):
        if v is not None and len(v) != 2:
            raise ValueError(Message("input.bar_points", n=len(v)))
        if v is not None and v[0] == v[1]:
            raise ValueError(Message("input.bar_same_points"))
        return v

    @model_validator(mode="after")
    def _kind(self):
        if self.slider is None and self.points is None:
            raise ValueError(Message("input.link_kind"))
        if self.slider is not None and self.points is not None:
            raise ValueError(Message("input.link_both"))
        if self.points is not None and self.length is None:
            raise ValueError(Message("input.bar_length"))
        if self.length is not None and self.length <= 0:
            raise ValueError(Message("input.length_positive"))
        if self.slider is not None and self.guide is None:
            raise ValueError(Message("input.slider_guide"))
        if self.slider is not None and self.length is not None:
            raise ValueError(Message("input.slider_length"))
        return self

    @property
    def kind(self) -> str:
        return "slider" if self.slider is not None else "bar"


class MechanismSection(_Model):
    ground: dict[str, LengthPair] = Field(..., description="fixed pivots: name -> [x, y], m")
    links: dict[str, LinkSpec] = Field(..., description="moving links, numbered 1..n in this order")
    assembly: dict[str, LengthPair] = Field(default_factory=dict,
                                            description="rough coordinates of moving points at crank angle 0 deg")

    @field_validator("links")
    @classmethod
    def _nonempty(cls, v):
        if not v:
            raise ValueError(Message("input.no_links"))
        n = 0
        for name, link in v.items():
            n += len(link.extra)
            if n > MAX_EXTRA_POINTS:
                total = sum(len(k.extra) for k in v.values())
                raise FieldValueError((name, "extra"), Message("input.extra_points_many", n=total,
                                                               limit=MAX_EXTRA_POINTS))
        return v


def check_output_speed(value) -> tuple[float, str | None]:
    """(magnitude in m/s or rad/s, 'linear' | 'angular' | None for a plain number).
    Raises ValueError for a value that is neither a linear nor an angular speed, or
    not positive."""
    from ..units import check_magnitude, quantity

    if isinstance(value, bool):
        raise ValueError(Message("input.output_speed_bool"))
    if isinstance(value, (int, float)):
        v, kind = check_magnitude(float(value)), None
    else:
        try:
            v, _notes, read_as = quantity(str(value), "output_speed")
        except ValueError as exc:
            if isinstance(exc.args[0], Message) and exc.args[0].code == "input.unit_not_kind":
                raise ValueError(Message("input.output_speed_unit", value=str(value))) from None
            raise
        kind = {"linear_speed": "linear", "speed": "angular"}.get(read_as)
        v = check_magnitude(v)
    if not v > 0:
        raise ValueError(Message("input.output_speed_positive", value=repr(value)))
    return v, kind


class DriveSection(_Model):
    link: str
    speed: AngularSpeed | None = Field(None, gt=0, description="mean angular speed (rad/s; or '50 rpm')")
    mean_output_speed: Union[Number, str, None] = None
    working_stroke_speed: Union[Number, str, None] = None
    direction: Literal["ccw", "cw"] = "ccw"
    cycle: Literal[360, 720] = 360

    @model_validator(mode="after")
    def _one_speed(self):
        vals = self.__dict__                        # the fields by name
        given = [k for k in ("speed", "mean_output_speed", "working_stroke_speed") if vals[k] is not None]
        if not given:
            raise FieldValueError(("speed",), Message("input.no_speed"))
        if len(given) > 1:
            raise FieldValueError((given[1],), Message("input.speed_one", given=given))
        if given[0] != "speed":
            try:
                check_output_speed(vals[given[0]])
            except ValueError as exc:
                raise FieldValueError((given[0],), exc.args[0] if len(exc.args) == 1 else str(exc)) from None
        return self

    @property
    def sign(self) -> float:
        return 1.0 if self.direction == "ccw" else -1.0


class PositionsSection(_Model):
    count: int = Field(12, ge=2, le=MAX_POSITIONS)
    zero: Union[Literal["extreme"], Angle] = "extreme"
    output: str | None = None
    working: Literal["forward", "backward"] = "forward"
    extra: list[Angle] = Field(default_factory=list)

    @model_validator(mode="after")
    def _bounded(self):
        """Every position is computed, listed and drawn: the extras count toward the limit."""
        if len(self.extra) > MAX_EXTRA_POSITIONS:
            raise FieldValueError(("extra",), Message("input.extra_positions_many", n=len(self.extra),
                                                      limit=MAX_EXTRA_POSITIONS))
        n = self.count + len(self.extra)
        if n > MAX_POSITIONS:
            raise FieldValueError(("extra",), Message("input.positions_many", n=n, count=self.count,
                                                      extra=len(self.extra), limit=MAX_POSITIONS))
        return self

# ---------------------------------------------------------------- loads
class DiagramSpec(_Model):
    s: list[Ratio] | None = Field(None, description="relative stroke s/H in [0, 1]")
    phi: list[Angle] | None = Field(None, description="crank angle over the cycle, deg")
    value: list[ForceOrPressure]

    @model_validator(mode="after")
    def _axes(self):
        x = self.s if self.s is not None else self.phi
        if (self.s is None) == (self.phi is None):
            raise ValueError(Message("input.diagram_axis"))
        if len(x) != len(self.value):
            raise ValueError(Message("input.diagram_lengths", n_x=len(x), n_value=len(self.value)))
        if len(x) < 2:
            raise ValueError(Message("input.diagram_short"))
        if any(b < a for a, b in zip(x, x[1:])):
            raise ValueError(Message("input.diagram_order"))
        if self.s is not None and (min(self.s) < 0 or max(self.s) > 1):
            raise ValueError(Message("input.diagram_s"))
        return self


class ForceSpec(_Model):
    on: str = Field(..., description="the link the load acts on")
    kind: Literal["resistance", "driving"] | None = None
    stroke: Literal["working", "idle", "both"] = "working"
    working: Literal["forward", "backward"] | None = None
    magnitude: ForceOrPressure | None = None
    diagram: DiagramSpec | None = None
    area: Area | None = Field(None, gt=0)
    at: Union[str, LengthPair, None] = None
    direction: Angle | None = None
    moment: MomentQ | None = None

    @model_validator(mode="after")
    def _what(self):
        given = [k for k, v in (("magnitude", self.magnitude), ("diagram", self.diagram), ("moment", self.moment))
                 if v is not None]
        if len(given) != 1:
            raise ValueError(Message("input.load_what_got", given=given) if given else Message("input.load_what"))
        for name, v in (("magnitude", self.magnitude), ("moment", self.moment)):
            if self.kind is not None and v is not None and v < 0:
                raise FieldValueError((name,), Message("input.load_negative_against" if self.kind == "resistance"
                                                       else "input.load_negative_along", name=name, kind=self.kind,
                                                       value=v))
        return self


class LoadsSection(_Model):
    gravity: bool = False
    forces: list[ForceSpec] = Field(default_factory=list)

    @field_validator("forces")
    @classmethod
    def _bounded(cls, v):
        if len(v) > MAX_FORCES:
            raise ValueError(Message("input.forces_many", n=len(v), limit=MAX_FORCES))
        return v


class FrictionSpec(_Model):
    pin_radius: Length = Field(..., gt=0)
    f: float | None = Field(None, ge=0, le=1)
    f_pin: float | None = Field(None, ge=0, le=1)
    f_slide: float | None = Field(None, ge=0, le=1)

    @model_validator(mode="after")
    def _coefficients(self):
        """`f` is the shorthand for both; alone, a missing one of f_pin / f_slide is 0."""
        if self.f is not None:
            if self.f_pin is not None or self.f_slide is not None:
                raise FieldValueError(("f_pin" if self.f_pin is not None else "f_slide",),
                                      Message("input.friction_both"))
            self.f_pin = self.f_slide = self.f
        elif self.f_pin is None and self.f_slide is None:
            raise ValueError(Message("input.friction_none"))
        self.f_pin = self.f_pin or 0.0
        self.f_slide = self.f_slide or 0.0
        return self


class KinetostaticsSection(_Model):
    positions: Union[Literal["all"], list[int]] = "all"
    inertia: bool = True
    balance: str | None = None
    friction: FrictionSpec | None = None
    motion: Union[Literal["constant"], Literal[True]] = "constant"

    @field_validator("positions", mode="before")
    @classmethod
    def _a_list(cls, v):
        """`positions: 2` (a number, not a list): one message saying so (pydantic gives two,
        one per member of the union, with no hint)."""
        if v != "all" and not isinstance(v, (list, tuple)):
            raise ValueError(Message("input.ks_positions_list", got=repr(v)))
        return v

    @field_validator("positions")
    @classmethod
    def _positions(cls, v):
        """An empty list computes nothing (refused); a position listed twice is computed once."""
        if isinstance(v, list):
            if not v:
                raise ValueError(Message("input.ks_positions_empty"))
            v = list(dict.fromkeys(v))
        return v

# ---------------------------------------------------------------- flywheel
class ShapeSpec(_Model):
    type: Literal["disk", "rim"] = "disk"
    density: Density = Field(7800.0, gt=0)
    width_ratio: Ratio = Field(0.1, gt=0)


def _default_shape() -> ShapeSpec:
    """ShapeSpec() (its defaults, which need no validation) without building its validator."""
    return ShapeSpec.model_construct()


def _delta_below_one(v: float) -> float:
    """delta is a fraction below 1: `delta: 20` meant 1/20 (said so; pydantic's 'less than 1' did not)."""
    if v > 1:
        raise ValueError(Message("input.delta_inverse", got=v, inverse=f"1/{v:g}"))
    if v == 1:
        raise ValueError(Message("input.less_than", lt="1"))
    return v


class FlywheelSection(_Model):
    delta: Annotated[Ratio, AfterValidator(_delta_below_one)] = Field(..., gt=0, json_schema_extra={"exclusiveMaximum": 1})
    constant: Literal["driving", "resistance"] = "driving"
    method: Literal["energy-mass", "merzalov", "exact"] = "energy-mass"
    resolution: int = Field(360, ge=12, le=100000)
    quadrature: int = Field(2, ge=0, le=8, description="Gauss-Legendre points per interval (0: trapezoid)")
    shape: ShapeSpec = Field(default_factory=_default_shape)
    reduced_J: Inertia = Field(0.0, ge=0, description="extra constant reduced inertia (rotor, gears), kg*m^2")

# ---------------------------------------------------------------- synthesis
class SynthesisLinkSpec(_Model):
    """Mass properties of a generated link."""
    mass: Mass = Field(0.0, ge=0)
    J: Inertia = Field(0.0, ge=0, description="moment of inertia about the centre of mass, kg*m^2")
    com: Union[str, LengthPair, None] = Field(None, description=COM_DOC)


SYNTHESIS_INPUTS = {  # type -> (required, exactly-one-of groups, optional)
    "slider_crank": (("H",), (("lambda_", "gamma_min"),), ("K", "theta")),
    "offset_slider_crank": (("H",), (("K", "theta"), ("e", "lambda_", "gamma_min")), ()),
    "crank_rocker": (("psi", "rocker", "frame"), (("K", "theta"),), ()),
    "slotted_lever": (("frame",), (("K", "theta"),), ("rocker",)),
    "shaper": (("H", "frame"), (("K", "theta"),), ("rocker", "guide_height")),
    "function": (("function_", "x", "input", "output", "frame"), (), ("points",)),
    "positions": (("positions", "moving_pivots"), (), ()),
    "path": (("points",), (), ("gamma_min",)),
}
SYNTHESIS_FIELDS = ("H", "psi", "K", "theta", "lambda_", "e", "gamma_min", "rocker", "frame", "guide_height",
                    "function_", "x", "input", "output", "points", "positions", "moving_pivots")


class CouplerPose(_Model):
    """A position of the coupler plane: its point P (m) and its angle (deg, from +x)."""
    P: LengthPair = Field(..., description="the plane's point P [x, y], m")
    angle: Angle = Field(..., description="the plane's angle from +x, deg")


class MovingPivots(_Model):
    """The moving pivots in the coupler plane's own frame (at P, x along the plane's angle), m."""
    A: LengthPair = Field(..., description="moving pivot A [u, v] in the plane's frame, m")
    B: LengthPair = Field(..., description="moving pivot B [u, v] in the plane's frame, m")


def _rot(p, ang_deg):
    c, s = math.cos(math.radians(ang_deg)), math.sin(math.radians(ang_deg))
    return (c * p[0] - s * p[1], s * p[0] + c * p[1])


def pivot_positions(sec) -> dict[str, list[tuple[float, float]]]:
    """The moving pivots A and B in each of the three positions of a `positions` synthesis
    (m, in the task's frame): A_j = P_j + R(angle_j) A."""
    out = {}
    for name, loc in (("A", sec.moving_pivots.A), ("B", sec.moving_pivots.B)):
        pts = []
        for pose in sec.positions:
            r = _rot((float(loc[0]), float(loc[1])), float(pose.angle))
            pts.append((float(pose.P[0]) + r[0], float(pose.P[1]) + r[1]))
        out[name] = pts
    return out


def collinear(p, q, s, rel: float = 1e-9) -> bool:
    """True when the three points lie on one line (or two coincide): twice the triangle's
    area below ``rel`` times the square of its longest side."""
    area2 = (q[0] - p[0]) * (s[1] - p[1]) - (q[1] - p[1]) * (s[0] - p[0])
    span = max(math.dist(p, q), math.dist(q, s), math.dist(p, s))
    return span == 0.0 or abs(area2) <= rel * span * span


def positions_input_error(sec) -> tuple | None:
    """(field path, Message) when the moving pivots coincide or the positions of A or B are
    collinear (no circle passes through them), else None: an input error (exit 2)."""
    pts = pivot_positions(sec)
    for i, j in ((0, 1), (0, 2), (1, 2)):      # one position given twice: named as such, not 'on one line'
        if all(math.dist(pts[n][i], pts[n][j]) <= 1e-12 * max(1.0, math.hypot(*pts[n][i])) for n in ("A", "B")):
            return ("positions", j), Message("input.synth_positions_same", i=i + 1, j=j + 1)
    if math.dist(pts["A"][0], pts["B"][0]) <= 1e-12 * max(1.0, math.hypot(*pts["A"][0])):
        return ("moving_pivots", "B"), Message("input.synth_pivots_same")
    for name in ("A", "B"):
        if collinear(*pts[name]):
            return (("moving_pivots", name),
                    Message("input.synth_collinear", name=name,
                            points=", ".join(f"({x:.6g}, {y:.6g})" for x, y in pts[name])))
    return None


def path_input_error(sec) -> tuple | None:
    """(field path, Message) when the path's points all coincide (no path), else None: also
    when they differ only in the last digits their coordinates carry (an extent below 1e-9 of
    the largest coordinate: the points 0.1, 0.1 + 1e-15, ... generated a linkage of femtometres
    that no closure could tell from a point)."""
    xs, ys = [float(p[0]) for p in sec.points], [float(p[1]) for p in sec.points]
    size = max(map(abs, xs + ys))
    if max(max(xs) - min(xs), max(ys) - min(ys)) <= 1e-9 * size:
        return ("points",), Message("input.synth_points_same")
    return None


def function_input_error(sec) -> tuple | None:
    """(field path, Message) when the function to generate is not a finite number at some x of
    its range (checked at 1001 points, the ends and the precision points: log(x - 1) at x = 1,
    1/(x - 2) at x = 2) or takes the same value at the range's ends (the rocker's angle, linear
    in y from y(x0) to y(x1), would be undefined), else None: an input error (exit 2)."""
    import numpy as np

    from ..expr import compile_expr
    x0, x1 = float(sec.x[0]), float(sec.x[1])
    xs = np.concatenate([np.linspace(x0, x1, 1001), chebyshev_points(x0, x1, int(sec.points or 3))])
    ys = np.broadcast_to(np.asarray(compile_expr(sec.function_)(xs), float), xs.shape)
    bad = ~np.isfinite(ys)
    if bad.any():
        return ("function",), Message("input.synth_function_not_finite", x=float(xs[np.argmax(bad)]), x0=x0, x1=x1)
    if abs(ys[1000] - ys[0]) <= 1e-12 * float(np.max(np.abs(ys))):     # sin(x) on [0, pi]: 1.2e-16 apart
        return ("function",), Message("input.synth_function_ends", y=float(ys[0]), x0=x0, x1=x1)
    return None


def _points_kind(v) -> str:
    """Which of `points`' two meanings a value is: a list (path: the points) or a count
    (function: the precision points); only that one is checked, so a message names it alone
    (not 'a valid integer' for a path's list of four points)."""
    return "tag:list" if isinstance(v, (list, tuple)) else "tag:count"


def _function_text(v):
    """The function to generate, checked by its grammar (tmm_cli.expr: never evaluated as code)."""
    if v is None:
        return v
    from ..expr import ExprError, compile_expr
    try:
        compile_expr(v)
    except ExprError as exc:
        raise ValueError(Message("input.synth_function", reason=str(exc))) from None
    return v


class AngleRange(_Model):
    """An angle that varies linearly with x or y: start + range (t - t0)/(t1 - t0), deg."""
    start: Angle = Field(0.0, description="the angle at the range's start, deg")
    range: Angle = Field(..., description="the angle swept over the range, deg (non-zero)")

    @field_validator("range")
    @classmethod
    def _nonzero(cls, v):
        if v == 0:
            raise ValueError(Message("input.synth_range_zero"))
        return v


class SynthesisSection(_Model):
    type: Literal["slider_crank", "offset_slider_crank", "crank_rocker", "slotted_lever", "shaper", "function",
                  "positions", "path"]
    H: Length | None = Field(None, gt=0)
    psi: Angle | None = Field(None, gt=0, lt=180)
    K: Ratio | None = Field(None, gt=0)
    theta: Angle | None = Field(None, gt=-180, lt=180)
    lambda_: Ratio | None = Field(None, alias="lambda", gt=1)
    e: Length | None = Field(None, gt=0)
    gamma_min: Angle | None = Field(None, gt=0, lt=90)
    rocker: Length | None = Field(None, gt=0)
    frame: Length | None = Field(None, gt=0)
    guide_height: Length | None = Field(None, gt=0)
    function_: Annotated[str | None, AfterValidator(_function_text)] = Field(
        None, alias="function", description="function generation: y(x) in x, numbers, + - * / **, sin cos tan exp log log10 sqrt")
    x: tuple[Number, Number] | None = Field(None, description="function generation: the range [x0, x1] of x")
    input: AngleRange | None = Field(None, description="function generation: the crank angle phi (deg, from O->O1) "
                                                       "over the range of x: {start, range}")
    output: AngleRange | None = Field(None, description="function generation: the rocker angle psi (deg, from O->O1 "
                                                        "at O1) over the range of y: {start, range}")
    points: Union[Annotated[Union[Annotated[int, Field(ge=3, le=5), Tag("tag:count")],
                                  Annotated[list[LengthPair], Field(min_length=5, max_length=20), Tag("tag:list")]],
                            Discriminator(_points_kind)],
                  None] = Field(None, description="function generation: precision points, Chebyshev spacing (3; 4 or "
                                                  "5 by least squares); path: the 5 to 20 points [x, y] (m) to pass")
    positions: Annotated[list[CouplerPose], Field(min_length=3, max_length=3)] | None = Field(
        None, description="three positions: the coupler plane's three positions {P: [x, y], angle}")
    moving_pivots: MovingPivots | None = Field(None, description="three positions: {A: [u, v], B: [u, v]} in the "
                                                                 "plane's frame at P, x along its angle, m")
    links: dict[str, SynthesisLinkSpec] = Field(default_factory=dict)

    @model_validator(mode="after")
    def _inputs(self):
        required, groups, optional = SYNTHESIS_INPUTS[self.type]
        spell = lambda k: k.rstrip("_") if k in ("lambda_", "function_") else k
        vals = self.__dict__                        # the fields by name
        for k in required:
            if vals[k] is None:
                raise FieldValueError((spell(k),), Message("input.synth_needs", type=self.type, key=spell(k)))
        allowed = set(required) | set(optional) | {k for g in groups for k in g}
        for k in SYNTHESIS_FIELDS:
            if vals[k] is not None and k not in allowed:
                offset = self.type == "slider_crank" and k == "e"
                raise FieldValueError((spell(k),), Message("input.synth_not_taken_offset" if offset
                                                           else "input.synth_not_taken", type=self.type, key=spell(k)))
        for g in groups:
            given = [k for k in g if vals[k] is not None]
            if len(given) != 1:
                names = [f"`{spell(k)}`" for k in g]
                raise FieldValueError((spell((given or g)[-1]),),
                                      Message("input.synth_one_of_got", type=self.type, names=names,
                                              given=[spell(k) for k in given]) if given else
                                      Message("input.synth_one_of", type=self.type, names=names))
        if self.type == "function" and self.x[0] == self.x[1]:
            raise FieldValueError(("x",), Message("input.synth_x_range"))
        if self.type == "function" and not (self.points is not None and not isinstance(self.points, int)):
            bad = function_input_error(self)
            if bad:
                raise FieldValueError(*bad)
        if self.points is not None and isinstance(self.points, int) != (self.type == "function"):
            raise FieldValueError(("points",), Message("input.synth_points_function" if self.type == "function"
                                                       else "input.synth_points_path"))
        bad = (positions_input_error(self) if self.type == "positions" else
               path_input_error(self) if self.type == "path" else None)
        if bad:
            raise FieldValueError(*bad)
        if self.type in ("offset_slider_crank", "slotted_lever", "shaper"):    # a quick return: K > 1
            bad_k = ("K", self.K) if self.K is not None and self.K <= 1.0 else \
                ("theta", self.theta) if self.theta is not None and self.theta <= 0.0 else None
            if bad_k:
                raise FieldValueError((bad_k[0],), Message("input.synth_quick_return", type=self.type,
                                                           key=bad_k[0], value=float(bad_k[1])))
        if self.type == "crank_rocker":            # K = 1 (theta = 0) is a crank-rocker too; below, none
            bad_k = ("K", self.K) if self.K is not None and self.K < 1.0 else \
                ("theta", self.theta) if self.theta is not None and self.theta < 0.0 else None
            if bad_k:
                raise FieldValueError((bad_k[0],), Message("input.synth_K_below_one", type=self.type, key=bad_k[0],
                                                           value=float(bad_k[1])))
        if self.type == "slider_crank":
            th = self.theta if self.theta is not None else (180.0 * (self.K - 1) / (self.K + 1)
                                                            if self.K is not None else 0.0)
            if abs(th) > 1e-12:
                raise FieldValueError(("K" if self.K is not None else "theta",), Message("input.synth_central"))
        for name in self.links:
            if name not in LINKS[self.type]:
                import difflib
                close = difflib.get_close_matches(name, LINKS[self.type], n=1)
                raise FieldValueError(("links", name),
                                      Message("input.synth_no_link_hint", type=self.type, name=name, hint=close[0],
                                              links=list(LINKS[self.type])) if close else
                                      Message("input.synth_no_link", type=self.type, name=name,
                                              links=list(LINKS[self.type])))
        return self


def chebyshev_points(x0: float, x1: float, n: int) -> list[float]:
    """Chebyshev's precision points on a range.

    Parameters
    ----------
    x0, x1 : float
        The range.
    n : int
        The number of points.

    Returns
    -------
    list of float
        x_j = (x0 + x1)/2 - (x1 - x0)/2 cos((2j - 1) pi/(2n)), j = 1..n.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*: Chebyshev spacing of the precision
    points of a function generator.
    """
    return [(x0 + x1) / 2 - (x1 - x0) / 2 * math.cos((2 * j - 1) * math.pi / (2 * n)) for j in range(1, n + 1)]
