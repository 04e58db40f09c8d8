"""The task model: one variant of the course project, validated once.

Pydantic models for every section of the task file (README, *The task file*). Quantities are converted to SI floats
(angles in degrees) at validation. Unknown keys are errors with a "did you mean".
:func:`load_task` reads a YAML file (or a dict) and raises :class:`TaskError` naming
the file, line, column and field of every problem.
"""
# annotations evaluated as written (no `from __future__ import annotations`): pydantic would
# compile and evaluate every field's annotation string when the models are made
import re
from pathlib import Path
from typing import Annotated, Any, Literal, Union

from pydantic import (AfterValidator, BaseModel, ConfigDict, Field, PrivateAttr, ValidationError,
                      field_validator, model_validator)

from . import locales
from .errors import TaskError
from .limits import MAX_EXTRA_POINTS, MAX_EXTRA_POSITIONS, MAX_FORCES, MAX_POSITIONS
from .messages import Message
from .modelbase import PLANETARY_ALIASES, PLANETARY_SCHEMES, FieldValueError, _Model
from .units import (Angle, AngularSpeed, Area, Density, ForceOrPressure, Inertia,
                    Length, Mass, MomentQ, Number, Ratio)

Point2 = tuple[float, float]

_UNKNOWN = re.compile(r"unknown key '([^']+)'")


LengthPair = tuple[Length, Length]


# ---------------------------------------------------------------- mechanism
class GuideSpec(_Model):
    """The line a slider translates along: fixed ({through, angle}) or on a link."""

    through: Union[str, LengthPair, None] = Field(None, description="fixed guide: a point name or [x, y] on the line")
    angle: Angle | None = Field(None, description="deg: from +x (fixed guide) or relative to the guide link (moving)")
    link: str | None = Field(None, description="moving guide (slotted link): the link carrying the guide")
    offset: Length = Field(0.0, description="moving guide: perpendicular shift to the left of the link's axis, m")

    @model_validator(mode="after")
    def _kind(self):
        if self.link is None and self.through is None:
            raise ValueError(Message("input.guide_kind"))
        if self.link is not None and self.through is not None:
            raise ValueError(Message("input.guide_both"))
        if self.link is None and self.angle is None:
            raise ValueError(Message("input.guide_angle"))
        return self


class LinkSpec(_Model):
    """A bar link (``points: [P, Q]``, ``length``) or a slider (``slider: P``, ``guide``)."""

    points: list[str] | None = Field(None, description="bar: its two pair points [P, Q]")
    length: Length | None = Field(None, description="bar: |PQ|, m")
    extra: dict[str, LengthPair] = Field(default_factory=dict, description="extra points in local [u, v], m")
    slider: str | None = Field(None, description="slider: its pin point")
    guide: GuideSpec | None = None
    mass: Mass = Field(0.0, ge=0)
    J: Inertia = Field(0.0, ge=0, description="moment of inertia about the centre of mass, kg*m^2")
    com: Union[str, LengthPair, None] = Field(None, description="centre of mass: local [u, v] or a point name")

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


class DriveSection(_Model):
    link: str
    speed: AngularSpeed | None = Field(None, gt=0, description="mean angular speed (rad/s; or '50 rpm')")
    mean_output_speed: Union[Number, str, None] = None
    working_stroke_speed: Union[Number, str, None] = None
    direction: Literal["ccw", "cw"] = "ccw"
    cycle: Literal[360, 720] = 360

    @model_validator(mode="after")
    def _one_speed(self):
        from .linkage.drive_speed import check_output_speed
        given = [k for k in ("speed", "mean_output_speed", "working_stroke_speed") if getattr(self, k) is not None]
        if not given:
            raise FieldValueError(("speed",), Message("input.no_speed"))
        if len(given) > 1:
            raise FieldValueError((given[1],), Message("input.speed_one", given=given))
        if given[0] != "speed":
            try:
                check_output_speed(getattr(self, given[0]))
            except ValueError as exc:
                raise FieldValueError((given[0],), exc.args[0] if len(exc.args) == 1 else str(exc)) from None
        return self

    @property
    def sign(self) -> float:
        return 1.0 if self.direction == "ccw" else -1.0

    @property
    def omega1(self) -> float:
        if self.speed is None:
            raise ValueError("the crank speed follows from the output's speed: resolve it first "
                             "(tmm_cli.linkage.drive_speed.resolve)")
        return self.sign * self.speed


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
        given = [k for k in ("magnitude", "diagram", "moment") if getattr(self, k) is not None]
        if len(given) != 1:
            raise ValueError(Message("input.load_what_got", given=given) if given else Message("input.load_what"))
        if self.diagram is not None and self.diagram.phi is not None and self.kind is not None:
            pass
        for name in ("magnitude", "moment"):
            v = getattr(self, name)
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

    @field_validator("positions")
    @classmethod
    def _positions(cls, v):
        """An empty list computes nothing (refused); a position listed twice is computed once."""
        if isinstance(v, list):
            if not v:
                raise ValueError(Message("input.ks_positions_empty"))
            v = list(dict.fromkeys(v))
        return v


# ---------------------------------------------------------------- report
class ReportSection(_Model):
    detail_position: int | None = Field(None, ge=0, strict=True)


# ---------------------------------------------------------------- flywheel
class ShapeSpec(_Model):
    type: Literal["disk", "rim"] = "disk"
    density: Density = Field(7800.0, gt=0)
    width_ratio: Ratio = Field(0.1, gt=0)


def _default_shape() -> ShapeSpec:
    """ShapeSpec() (its defaults, which need no validation) without building its validator."""
    return ShapeSpec.model_construct()


class FlywheelSection(_Model):
    delta: Ratio = Field(..., gt=0, lt=1)
    constant: Literal["driving", "resistance"] = "driving"
    method: Literal["energy-mass", "merzalov", "exact"] = "energy-mass"
    resolution: int = Field(360, ge=12, le=100000)
    quadrature: int = Field(2, ge=0, le=8, description="Gauss-Legendre points per interval (0: trapezoid)")
    shape: ShapeSpec = Field(default_factory=_default_shape)
    reduced_J: Inertia = Field(0.0, ge=0, description="extra constant reduced inertia (rotor, gears), kg*m^2")


# ---------------------------------------------------------------- cam
class PhasesSpec(_Model):
    rise: Angle = Field(..., gt=0)
    far_dwell: Angle = Field(0.0, ge=0)
    return_: Angle = Field(..., alias="return", gt=0)
    near_dwell: Angle | None = Field(None, ge=0)

    @model_validator(mode="after")
    def _sum(self):
        used = self.rise + self.far_dwell + self.return_
        if self.near_dwell is None:
            if used > 360 + 1e-9:
                raise ValueError(Message("input.phases_over", used=used))
            self.near_dwell = max(0.0, 360.0 - used)
        elif abs(used + self.near_dwell - 360) > 1e-6:
            raise ValueError(Message("input.phases_sum", total=used + self.near_dwell))
        return self


LawName = Literal["constant_velocity", "parabolic", "cosine", "sine", "poly345",
                  "linear_decreasing", "trapezoidal"]


class LawsSpec(_Model):
    rise: LawName = "cosine"
    return_: LawName = Field("cosine", alias="return")


def _default_laws() -> LawsSpec:
    """LawsSpec() (cosine rise and return) without building its validator."""
    return LawsSpec.model_construct()


class LimitsSpec(_Model):
    rise: Angle = Field(..., gt=0, lt=90)
    return_: Angle = Field(..., alias="return", gt=0, lt=90)


class CamSection(_Model):
    follower: Literal["translating", "rocker", "flat", "knife"] = "translating"
    stroke: Number = Field(..., gt=0, description="m (translating) or deg (rocker)")
    rocker_length: Length | None = Field(None, gt=0)
    offset: Union[Literal["auto"], Length] = 0.0
    phases: PhasesSpec
    laws: LawsSpec = Field(default_factory=_default_laws)
    pressure_angle: Union[LimitsSpec, Angle, None] = None
    transmission_angle: Union[LimitsSpec, Angle, None] = None
    swing: Literal["with", "against", "auto"] = "auto"
    roller: Union[Literal["auto"], Length] = "auto"
    rotation: Literal["ccw", "cw"] = "ccw"
    speed: AngularSpeed | None = Field(None, gt=0)
    r0: Union[Literal["auto"], Length] = "auto"
    center_distance: Length | None = Field(None, gt=0)
    rho_min_allowed: Length = Field(0.0, ge=0)
    divisions: int = Field(8, ge=1, le=360)

    @field_validator("stroke", mode="before")
    @classmethod
    def _stroke(cls, v, info):
        # the unit depends on the follower: checked after, here accept numbers and unit strings
        return v

    @model_validator(mode="before")
    @classmethod
    def _stroke_units(cls, data):
        if isinstance(data, dict) and isinstance(data.get("stroke"), str):
            from .units import convert
            kind = "angle" if data.get("follower") == "rocker" else "length"
            data = dict(data)
            data["stroke"] = convert(data["stroke"], kind)
        return data

    @model_validator(mode="after")
    def _limits(self):
        if self.pressure_angle is not None and self.transmission_angle is not None:
            raise ValueError(Message("input.cam_angles_both"))
        lim = self.pressure_angle
        if lim is None and self.transmission_angle is not None:
            t = self.transmission_angle
            if isinstance(t, LimitsSpec):
                lim = LimitsSpec(rise=90 - t.rise, **{"return": 90 - t.return_})
            else:
                lim = 90 - t
        if lim is None:
            lim = 45.0 if self.follower == "rocker" else 30.0
        if not isinstance(lim, LimitsSpec):
            if not 0 < lim < 90:
                given = "pressure_angle" if self.pressure_angle is not None else "transmission_angle"
                raise FieldValueError((given,), Message("input.cam_pressure_range"))
            # checked just above as LimitsSpec would (an angle in (0, 90)): built without
            # validating again, which would build LimitsSpec's own validator (~10 ms)
            lim = LimitsSpec.model_construct(rise=lim, return_=lim)
        self.pressure_angle = lim
        if self.follower == "rocker":
            if self.rocker_length is None:
                raise ValueError(Message("input.cam_rocker_length"))
            if self.offset not in (0.0, "auto"):
                raise ValueError(Message("input.cam_offset_rocker"))
            if self.stroke >= 180:
                raise ValueError(Message("input.cam_swing"))
        from .cam.chosen import check_section
        check_section(self, self.model_fields_set)
        return self


# ---------------------------------------------------------------- gears
class GearsSection(_Model):
    m: Length = Field(..., gt=0, description="module (give '3 mm')")
    z: tuple[Annotated[int, Field(le=10**12)], Annotated[int, Field(le=10**12)]]  # the 1e12 limit on values
    x: Union[Literal["auto"], tuple[Number, Number]] = (0.0, 0.0)
    alpha: Angle = Field(20.0, gt=0, lt=45)
    ha: Number = Field(1.0, gt=0)
    c: Number = Field(0.25, ge=0)
    rule: Literal["no_undercut", "equal_sliding", "table"] = Field(
        "equal_sliding", description="how `x: auto` chooses the shifts")
    sa_min: float = Field(0.25, gt=0, lt=1, description="least tip thickness as a fraction of m "
                                                         "(0.25 common, 0.4 hardened teeth)")
    rho_f: Number | None = Field(None, ge=0, description="rack fillet radius / m (default c/(1 - sin alpha))")

    @field_validator("z")
    @classmethod
    def _z(cls, v):
        if min(v) < 5:
            raise ValueError(Message("input.z_min"))
        return v




class PlanetarySection(_Model):
    scheme: str
    ratio: Number
    satellites: int = Field(3, ge=1, le=12)
    tolerance: Ratio = Field(0.05, gt=0)
    m: Length | None = Field(None, gt=0)
    z_min: int = Field(17, ge=5, le=300)
    # the candidate search grows as z_max^3 (schemes B, C: 0.5 s at 300, a minute at 1000)
    z_max: int = Field(150, ge=10, le=300)
    candidates: int = Field(10, ge=1, le=100, description="how many ranked candidate sets to list")
    rank: Literal["size", "ratio_error"] = "size"
    z_min_external: int | None = Field(None, ge=5)
    z_min_internal: int = Field(85, ge=5)
    z_min_satellite_in_internal: int | None = Field(None, ge=5)
    internal_minus_external_min: int = Field(8, ge=1)

    @field_validator("ratio")
    @classmethod
    def _ratio(cls, v):
        if v == 0:
            raise ValueError(Message("input.ratio_zero"))
        return v

    @field_validator("scheme")
    @classmethod
    def _scheme(cls, v):
        # an unknown scheme is an invalid task (exit 2), not a failed stage. The names are
        # those of tmm_cli.gears.planetary (SCHEMES, ALIASES; a test keeps the two equal),
        # copied so that validating a task does not import the gears package (~1 s)
        key = str(v).strip()
        if PLANETARY_ALIASES.get(key.lower(), key.upper()) not in PLANETARY_SCHEMES:
            raise ValueError(Message("input.planetary_scheme", scheme=repr(v), known=list(PLANETARY_SCHEMES)))
        return v

    @model_validator(mode="after")
    def _z_range(self):
        if self.z_min > self.z_max:
            raise FieldValueError(("z_min",), Message("input.z_range", z_min=self.z_min, z_max=self.z_max))
        return self


# ---------------------------------------------------------------- synthesis
class SynthesisLinkSpec(_Model):
    """Mass properties of a generated link."""
    mass: Mass = Field(0.0, ge=0)
    J: Inertia = Field(0.0, ge=0, description="moment of inertia about the centre of mass, kg*m^2")
    com: Union[str, LengthPair, None] = Field(None, description="centre of mass: local [u, v] or a point name")


SYNTHESIS_INPUTS = {  # type -> (required, exactly-one-of groups, optional)
    "slider_crank": (("H",), (("lambda_", "gamma_min"),), ("K", "theta")),
    "offset_slider_crank": (("H",), (("K", "theta"), ("e", "lambda_", "gamma_min")), ()),
    "crank_rocker": (("psi", "rocker", "frame"), (("K", "theta"),), ()),
    "slotted_lever": (("frame",), (("K", "theta"),), ("rocker",)),
    "shaper": (("H", "frame"), (("K", "theta"),), ("rocker", "guide_height")),
    "function": (("function_", "x", "input", "output", "frame"), (), ("points",)),
}
SYNTHESIS_FIELDS = ("H", "psi", "K", "theta", "lambda_", "e", "gamma_min", "rocker", "frame", "guide_height",
                    "function_", "x", "input", "output", "points")


def _function_text(v):
    """The function to generate, checked by its grammar (tmm_cli.expr: never evaluated as code)."""
    if v is None:
        return v
    from .expr import ExprError, compile_expr
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
    type: Literal["slider_crank", "offset_slider_crank", "crank_rocker", "slotted_lever", "shaper", "function"]
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
    points: int | None = Field(None, ge=3, le=5, description="function generation: precision points, Chebyshev "
                                                              "spacing (3; 4 or 5 by least squares)")
    links: dict[str, SynthesisLinkSpec] = Field(default_factory=dict)

    @model_validator(mode="after")
    def _inputs(self):
        required, groups, optional = SYNTHESIS_INPUTS[self.type]
        spell = lambda k: k.rstrip("_") if k in ("lambda_", "function_") else k
        for k in required:
            if getattr(self, k) is None:
                raise FieldValueError((spell(k),), Message("input.synth_needs", type=self.type, key=spell(k)))
        allowed = set(required) | set(optional) | {k for g in groups for k in g}
        for k in SYNTHESIS_FIELDS:
            if getattr(self, k) is not None and k not in allowed:
                offset = self.type == "slider_crank" and k == "e"
                raise FieldValueError((spell(k),), Message("input.synth_not_taken_offset" if offset
                                                           else "input.synth_not_taken", type=self.type, key=spell(k)))
        for g in groups:
            given = [k for k in g if getattr(self, k) is not None]
            if len(given) != 1:
                names = [f"`{spell(k)}`" for k in g]
                raise FieldValueError((spell((given or g)[-1]),),
                                      Message("input.synth_one_of_got", type=self.type, names=names,
                                              given=[spell(k) for k in given]) if given else
                                      Message("input.synth_one_of", type=self.type, names=names))
        if self.type == "function" and self.x[0] == self.x[1]:
            raise FieldValueError(("x",), Message("input.synth_x_range"))
        if self.type == "slider_crank":
            th = self.theta if self.theta is not None else (180.0 * (self.K - 1) / (self.K + 1)
                                                            if self.K is not None else 0.0)
            if abs(th) > 1e-12:
                raise FieldValueError(("K" if self.K is not None else "theta",), Message("input.synth_central"))
        from .linkage.synthesis import LINKS
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


from .trainspec import DOCS as _TRAIN_DOCS  # noqa: E402
from .trainspec import DriveTrainSection, TrainStageSpec  # noqa: E402


class ToleranceSpec(_Model):
    """A tolerance as {rel: R, abs: A}: passes when |student - reference| <= max(A, R |reference|);
    `sign: any` grades the magnitude (either sign passes)."""
    rel: Annotated[float, Field(ge=0, allow_inf_nan=False)] = 0.0
    abs: Annotated[float, Field(ge=0, allow_inf_nan=False)] = 0.0
    sign: Literal["any"] | None = None


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
    answers: dict[str, float] = Field(default_factory=dict)
    tolerance: dict[str, Union[Literal["graphical"], Annotated[Ratio, Field(ge=0)], ToleranceSpec]] = \
        Field(default_factory=dict)

    _file: str | None = PrivateAttr(None)
    # factories written as lambdas: pydantic reads a factory's signature for every Task it
    # makes, and the builtins' (dict, list) is parsed from text by tokenize (~5 ms, once)
    _marks: dict = PrivateAttr(default_factory=lambda: {})
    _input_warnings: list = PrivateAttr(default_factory=lambda: [])
    _design: Any = PrivateAttr(None)             # synthesis.Design of the generated mechanism
    _synthesis_error: Any = PrivateAttr(None)    # SynthesisImpossible, raised by the pipeline (exit 3)
    _checked_mechanism: Any = PrivateAttr(None)  # the Mechanism `validation.check_feasible` assembled over
    #                                              the cycle, taken (once) by the pipeline

    @field_validator("schema_", mode="before")
    @classmethod
    def _schema(cls, v):
        if v != "tmm/1":
            raise ValueError(Message("input.schema", got=repr(v)))
        return v

    @model_validator(mode="after")
    def _synthesise(self):
        """`synthesis` generates the `mechanism` (and the defaults of positions.output and
        positions.working) before the other checks, so they see the generated links. An
        impossible synthesis is kept for the pipeline (exit 3), not raised here."""
        if self.synthesis is None:
            return self
        if "mechanism" in self.model_fields_set:
            raise FieldValueError(("synthesis",), Message("input.synthesis_and_mechanism"))
        from .linkage.synthesis import SynthesisImpossible, design
        if self.drive is None:
            raise FieldValueError(("synthesis",), Message("input.synthesis_drive"))
        try:
            d = design(self.synthesis, self.drive.sign)
        except SynthesisImpossible as exc:
            self._synthesis_error = exc
            return self
        self._design = d
        from .schemacache import validator
        self.mechanism = validator(MechanismSection).validate_python(d.mechanism)     # MechanismSection.model_validate
        pos = self.positions if self.positions is not None else validator(PositionsSection).validate_python({})
        upd = {}
        if "output" not in pos.model_fields_set:
            upd["output"] = d.output
        if "working" not in pos.model_fields_set:
            upd["working"] = d.working
        if upd:
            self.positions = pos.model_copy(update=upd)
            self.positions.__pydantic_fields_set__ = set(pos.model_fields_set)
        return self

    @model_validator(mode="after")
    def _sections(self):
        needs_mech = [s for s in ("drive", "positions", "loads", "kinetostatics", "flywheel")
                      if getattr(self, s) is not None]
        if self.mechanism is not None and self.drive is None:
            raise FieldValueError(("mechanism",), Message("input.needs_drive"))
        if self.mechanism is None and needs_mech and self._synthesis_error is None:
            raise FieldValueError((needs_mech[0],), Message("input.needs_mechanism", sections=needs_mech))
        if self.report is not None and self.report.detail_position is not None and self.mechanism is None \
                and self._synthesis_error is None:
            raise FieldValueError(("report", "detail_position"), Message("input.detail_needs_mechanism"))
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
        return TaskError(message, file=self._file, issues=[(_dotted(path), line, col, message)])


def _dotted(path) -> str:
    out = ""
    for p in path:
        if isinstance(p, int):
            out += f"[{p}]"
        else:
            out += ("." if out else "") + str(p)
    return out


_MSG_CLEAN = [
    (re.compile(r"^Value error, "), ""),
    (re.compile(r"^Assertion failed, "), ""),
]


def _issue_from_error(err: dict, marks: dict) -> tuple[str, int | None, int | None, str]:
    loc = [p for p in err["loc"]]
    # pydantic puts union member / validator tags into loc: drop the non-field ones
    clean: list = []
    for p in loc:
        if isinstance(p, str) and (p.startswith("function-") or p in ("literal['extreme']", "literal['auto']",
                                                                      "literal['all']", "literal['constant']")
                                   or p.startswith("tuple[") or p.startswith("literal[") or p == "str"
                                   or p == "list[int]" or p == "LimitsSpec" or p == "float" or p == "bool"
                                   or p.endswith("-after]") or p.endswith("-before]")):
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
    return _dotted(path), line, col, msg


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
    if cause is not None and cause.args and getattr(cause.args[0], "code", None):
        coded = cause.args[0]
    elif kind == "missing":
        coded = Message("input.missing")
    elif kind == "literal_error":
        expected = str(ctx.get("expected", ""))
        coded = Message("input.literal", expected=re.split(r", | or ", expected), got=repr(err.get("input")))
    elif kind in _PYDANTIC_CODES and all(k in ctx for k in _PYDANTIC_CODES[kind]):
        coded = Message(f"input.{kind}", **{k: _ctx_text(ctx[k]) for k in _PYDANTIC_CODES[kind]})
    return coded if coded is not None and coded == msg else msg


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
    from .yamlload import decimal_comma_hint
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
        "answers": "a student's numbers: path into results.json -> value (tmm check / tmm batch)",
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
        "constant": "driving (motor-driven machine) | resistance (engine): the constant reduced moment",
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
    PlanetarySection: {"scheme": "A | B | C | D (see the README)", "ratio": "required i_1H (signed)",
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
        "type": "slider_crank | offset_slider_crank | crank_rocker | slotted_lever | shaper",
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
