"""Report section 'task': title, variant, student and the task data.

The mechanism is shown as an instructor writes the data of a variant: a table of
the fixed points, a table of the links (points, length, mass, moment of inertia,
centre of mass, guide) and the assembly hints; every other section of the task
file as 'parameter — value with its unit' (SI, angles in degrees, as the task
model stores them).  Lists of numbers are written '0; 0.7; 0.9', coordinates
'(0.5, 0.37) m'."""
from __future__ import annotations

from ... import locales

import math
import re
from typing import Any

from markupsafe import Markup, escape

from ...numfmt import localize, unit as spelt

I18N = locales.table("task", "words")

_META = ("schema", "schema_", "title", "variant", "student", "course")

# names of the task file's parameters (by the key without list indices) and of its word values
PARAMS = {
    "en": {"drive.link": "input link", "drive.speed": "angular speed ω₁", "drive.direction": "sense of rotation",
           "drive.cycle": "cycle", "positions.count": "number of positions", "positions.zero": "position 0",
           "positions.output": "output link", "positions.working": "working stroke",
           "positions.extra": "extra crank angles", "loads.gravity": "weights of the links",
           "loads.forces.on": "link", "loads.forces.kind": "kind", "loads.forces.stroke": "stroke",
           "loads.forces.diagram.s": "diagram: s/H", "loads.forces.diagram.phi": "diagram: φ",
           "loads.forces.diagram.value": "diagram: value", "loads.forces.at": "point of application",
           "loads.forces.area": "piston area", "loads.forces.magnitude": "magnitude",
           "loads.forces.direction": "direction", "loads.forces.moment": "moment of the couple",
           "kinetostatics.positions": "positions", "kinetostatics.inertia": "inertia loads",
           "kinetostatics.balance": "balance link", "kinetostatics.motion": "motion of the crank",
           "kinetostatics.friction.f": "friction coefficient f",
           "kinetostatics.friction.f_pin": "friction coefficient of the revolute pairs f_pin",
           "kinetostatics.friction.f_slide": "friction coefficient of the prismatic pairs f_slide",
           "kinetostatics.friction.pin_radius": "pin radius",
           "flywheel.delta": "coefficient of speed fluctuation δ", "flywheel.constant": "constant moment",
           "flywheel.method": "method", "flywheel.resolution": "points per cycle",
           "flywheel.shape.type": "flywheel shape", "flywheel.shape.density": "density ρ",
           "flywheel.shape.width_ratio": "width ratio b/D", "flywheel.reduced_J": "added reduced inertia",
           "cam.follower": "follower", "cam.stroke": "stroke h", "cam.rocker_length": "rocker length",
           "cam.offset": "offset e", "cam.phases.rise": "rise angle φ_r", "cam.phases.far_dwell": "far dwell",
           "cam.phases.return": "return angle φ_ret", "cam.phases.near_dwell": "near dwell",
           "cam.laws.rise": "law of the rise", "cam.laws.return": "law of the return",
           "cam.pressure_angle.rise": "allowed pressure angle, rise",
           "cam.pressure_angle.return": "allowed pressure angle, return", "cam.swing": "rocker's turn on the rise",
           "cam.roller": "roller radius", "cam.rotation": "cam rotation", "cam.speed": "cam speed",
           "cam.r0": "base radius r0", "cam.center_distance": "cam-rocker centre distance",
           "cam.rho_min_allowed": "allowed least radius of curvature", "cam.divisions": "parts of a phase in the table",
           "gears.m": "module m", "gears.z": "numbers of teeth z₁; z₂", "gears.x": "shift coefficients x₁; x₂",
           "gears.alpha": "pressure angle α", "gears.ha": "addendum coefficient h*a",
           "gears.c": "clearance coefficient c*", "gears.rule": "rule for the shifts",
           "gears.sa_min": "least top land s_a/m", "planetary.scheme": "scheme",
           "planetary.ratio": "required ratio u₁H", "planetary.satellites": "number of satellites k",
           "planetary.tolerance": "tolerance of the ratio", "planetary.m": "module m",
           "planetary.z_min": "least number of teeth", "planetary.z_max": "largest number of teeth",
           "planetary.candidates": "candidates listed"},
    "ru": {"drive.link": "входное звено", "drive.speed": "угловая скорость ω₁",
           "drive.direction": "направление вращения", "drive.cycle": "цикл", "positions.count": "число положений",
           "positions.zero": "нулевое положение", "positions.output": "выходное звено",
           "positions.working": "рабочий ход", "positions.extra": "дополнительные углы кривошипа",
           "loads.gravity": "силы тяжести звеньев", "loads.forces.on": "звено", "loads.forces.kind": "вид",
           "loads.forces.stroke": "ход", "loads.forces.diagram.s": "диаграмма: s/H",
           "loads.forces.diagram.phi": "диаграмма: φ", "loads.forces.diagram.value": "диаграмма: значение",
           "loads.forces.at": "точка приложения", "loads.forces.area": "площадь поршня",
           "loads.forces.magnitude": "величина", "loads.forces.direction": "направление",
           "loads.forces.moment": "момент пары", "kinetostatics.positions": "положения",
           "kinetostatics.inertia": "силы инерции", "kinetostatics.balance": "звено приведения",
           "kinetostatics.motion": "движение кривошипа", "kinetostatics.friction.f": "коэффициент трения f",
           "kinetostatics.friction.f_pin": "коэффициент трения во вращательных парах f_pin",
           "kinetostatics.friction.f_slide": "коэффициент трения в поступательных парах f_slide",
           "kinetostatics.friction.pin_radius": "радиус цапфы",
           "flywheel.delta": "коэффициент неравномерности δ", "flywheel.constant": "постоянный момент",
           "flywheel.method": "метод", "flywheel.resolution": "точек на цикл",
           "flywheel.shape.type": "форма маховика", "flywheel.shape.density": "плотность ρ",
           "flywheel.shape.width_ratio": "отношение b/D", "flywheel.reduced_J": "доп. приведённый момент инерции",
           "cam.follower": "толкатель", "cam.stroke": "ход h", "cam.rocker_length": "длина коромысла",
           "cam.offset": "эксцентриситет e", "cam.phases.rise": "фаза удаления φ_у",
           "cam.phases.far_dwell": "дальнее стояние", "cam.phases.return": "фаза возвращения φ_в",
           "cam.phases.near_dwell": "ближнее стояние", "cam.laws.rise": "закон удаления",
           "cam.laws.return": "закон возвращения", "cam.pressure_angle.rise": "допустимый угол давления, удаление",
           "cam.pressure_angle.return": "допустимый угол давления, возвращение",
           "cam.swing": "поворот коромысла на фазе удаления", "cam.roller": "радиус ролика",
           "cam.rotation": "вращение кулачка", "cam.speed": "угловая скорость кулачка",
           "cam.r0": "радиус начальной шайбы r0", "cam.center_distance": "межосевое расстояние кулачок-коромысло",
           "cam.rho_min_allowed": "допустимый наименьший радиус кривизны", "cam.divisions": "число частей фазы в таблице",
           "gears.m": "модуль m", "gears.z": "числа зубьев z₁; z₂", "gears.x": "коэффициенты смещения x₁; x₂",
           "gears.alpha": "угол профиля α", "gears.ha": "коэффициент высоты головки h*a",
           "gears.c": "коэффициент радиального зазора c*", "gears.rule": "правило выбора смещений",
           "gears.sa_min": "наименьшая толщина вершины s_a/m", "planetary.scheme": "схема",
           "planetary.ratio": "требуемое передаточное отношение u₁H", "planetary.satellites": "число сателлитов k",
           "planetary.tolerance": "допуск передаточного отношения", "planetary.m": "модуль m",
           "planetary.z_min": "наименьшее число зубьев", "planetary.z_max": "наибольшее число зубьев",
           "planetary.candidates": "число вариантов"},
}
PARAMS["en"].update({
    "dof2.rotor.length": "rotor length l = OO₁", "dof2.rotor.mass": "rotor mass m₁",
    "dof2.rotor.com": "rotor centre of mass OS₁", "dof2.rotor.J": "rotor J_S1", "dof2.rotor.J_O": "rotor J_O",
    "dof2.striker.length": "striker length O₁M", "dof2.striker.com": "striker centre of mass l_c = O₁C",
    "dof2.striker.mass": "striker mass m₂", "dof2.striker.J": "striker J_C", "dof2.gravity": "gravity",
    "dof2.drive.moment": "driving moment", "dof2.drive.speed": "rotor speed held ω₁",
    "dof2.drive.direction": "sense of rotation", "dof2.initial.phi": "initial φ₀",
    "dof2.initial.psi": "initial ψ₀", "dof2.initial.omega": "initial ω₀", "dof2.initial.psi_dot": "initial dψ/dt",
    "dof2.t_end": "duration", "dof2.turns": "turns", "dof2.t_max": "longest time", "dof2.samples": "samples",
    "dof2.impact.phi": "rotor angle at the hit", "dof2.impact.stop": "stop at the hit",
})
PARAMS["ru"].update({
    "dof2.rotor.length": "длина ротора l = OO₁", "dof2.rotor.mass": "масса ротора m₁",
    "dof2.rotor.com": "центр масс ротора OS₁", "dof2.rotor.J": "момент инерции ротора J_S1",
    "dof2.rotor.J_O": "момент инерции ротора J_O", "dof2.striker.length": "длина ударника O₁M",
    "dof2.striker.com": "центр масс ударника l_c = O₁C", "dof2.striker.mass": "масса ударника m₂",
    "dof2.striker.J": "момент инерции ударника J_C", "dof2.gravity": "силы тяжести",
    "dof2.drive.moment": "движущий момент", "dof2.drive.speed": "поддерживаемая скорость ротора ω₁",
    "dof2.drive.direction": "направление вращения", "dof2.initial.phi": "начальный угол φ₀",
    "dof2.initial.psi": "начальный угол ψ₀", "dof2.initial.omega": "начальная скорость ω₀",
    "dof2.initial.psi_dot": "начальная скорость dψ/dt", "dof2.t_end": "продолжительность",
    "dof2.turns": "число оборотов", "dof2.t_max": "наибольшее время", "dof2.samples": "число точек",
    "dof2.impact.phi": "угол ротора в момент удара", "dof2.impact.stop": "остановка при ударе",
})

# the lever synthesis and the drive speed from the output
PARAMS["en"].update({
    "synthesis.type": "type", "synthesis.H": "stroke H", "synthesis.psi": "rocker swing ψ",
    "synthesis.K": "coefficient of mean speed increase K", "synthesis.theta": "angle θ",
    "synthesis.lambda": "λ = l_AB/l_OA", "synthesis.e": "offset e", "synthesis.gamma_min": "least transmission angle γ_min",
    "synthesis.rocker": "rocker (slotted link) length", "synthesis.frame": "frame l_OO1",
    "synthesis.guide_height": "ram guide above O1",
    "drive.mean_output_speed": "mean speed of the output over the cycle",
    "drive.working_stroke_speed": "mean speed of the output over the working stroke",
})
PARAMS["ru"].update({
    "synthesis.type": "тип", "synthesis.H": "ход H", "synthesis.psi": "угол размаха коромысла ψ",
    "synthesis.K": "коэффициент изменения средней скорости K", "synthesis.theta": "угол θ",
    "synthesis.lambda": "λ = l_AB/l_OA", "synthesis.e": "дезаксиал e",
    "synthesis.gamma_min": "наименьший угол передачи γ_min",
    "synthesis.rocker": "длина коромысла (кулисы)", "synthesis.frame": "стойка l_OO1",
    "synthesis.guide_height": "направляющая ползуна над O1",
    "drive.mean_output_speed": "средняя скорость выходного звена за цикл",
    "drive.working_stroke_speed": "средняя скорость выходного звена на рабочем ходе",
})
for _name in ("crank", "rod", "slider", "coupler", "rocker", "block", "blockC", "ram"):
    for _k, _en, _ru in (("mass", "mass", "масса"), ("J", "J_S", "J_S"), ("com", "centre of mass", "центр масс")):
        PARAMS["en"][f"synthesis.links.{_name}.{_k}"] = f"{_name}: {_en}"
        PARAMS["ru"][f"synthesis.links.{_name}.{_k}"] = f"{_name}: {_ru}"
# the remaining fields: flywheel quadrature, the candidate search of a planetary gear and of a drive
# train, the cam's transmission angle and rocker sense, the basic rack's fillet
PARAMS["en"].update({
    "flywheel.quadrature": "Gauss–Legendre points per interval",
    "cam.pressure_angle": "allowed pressure angle", "cam.transmission_angle": "least allowed transmission angle",
    "cam.transmission_angle.rise": "least allowed transmission angle, rise",
    "cam.transmission_angle.return": "least allowed transmission angle, return",
    "gears.rho_f": "fillet radius coefficient of the basic rack ρ*_f",
    "loads.forces.working": "direction of the working stroke",
    "planetary.rank": "order of the candidates",
    "planetary.z_min_external": "least number of teeth of an external wheel",
    "planetary.z_min_internal": "least number of teeth of an internal wheel",
    "planetary.z_min_satellite_in_internal": "least number of teeth of a satellite in internal mesh",
    "planetary.internal_minus_external_min": "least difference of the numbers of teeth in internal mesh",
    "drive_train.motor_speed": "motor speed ω_m", "drive_train.motor_direction": "sense of rotation of the motor",
    "drive_train.ratio": "required overall ratio",
    "drive_train.efficiency": "efficiency of the drive η",
    "drive_train.stages.type": "kind",
    "drive_train.stages.z": "numbers of teeth", "drive_train.stages.internal": "internal mesh",
    "drive_train.stages.scheme": "scheme", "drive_train.stages.ratio": "ratio",
})
PARAMS["ru"].update({
    "flywheel.quadrature": "число точек Гаусса — Лежандра на интервал",
    "cam.pressure_angle": "допустимый угол давления", "cam.transmission_angle": "наименьший допустимый угол передачи",
    "cam.transmission_angle.rise": "наименьший допустимый угол передачи, удаление",
    "cam.transmission_angle.return": "наименьший допустимый угол передачи, возвращение",
    "gears.rho_f": "коэффициент радиуса переходной кривой исходного контура ρ*_f",
    "loads.forces.working": "направление рабочего хода",
    "planetary.rank": "порядок вариантов",
    "planetary.z_min_external": "наименьшее число зубьев колеса с внешними зубьями",
    "planetary.z_min_internal": "наименьшее число зубьев колеса с внутренними зубьями",
    "planetary.z_min_satellite_in_internal": "наименьшее число зубьев сателлита во внутреннем зацеплении",
    "planetary.internal_minus_external_min": "наименьшая разность чисел зубьев во внутреннем зацеплении",
    "drive_train.motor_speed": "угловая скорость двигателя ω_д",
    "drive_train.motor_direction": "направление вращения двигателя",
    "drive_train.ratio": "требуемое общее передаточное отношение",
    "drive_train.efficiency": "КПД привода η",
    "drive_train.stages.type": "вид",
    "drive_train.stages.z": "числа зубьев", "drive_train.stages.internal": "внутреннее зацепление",
    "drive_train.stages.scheme": "схема", "drive_train.stages.ratio": "передаточное отношение",
})

ITEMS = {"en": {"forces": "force", "couples": "couple"}, "ru": {"forces": "сила", "couples": "пара"}}
WORDS = {"ru": {"ccw": "против часовой стрелки", "cw": "по часовой стрелке", "true": "да", "false": "нет",
                "extreme": "крайнее положение", "forward": "прямой", "backward": "обратный",
                "resistance": "сопротивление", "driving": "движущая", "working": "рабочий", "idle": "холостой",
                "both": "оба", "constant": "постоянное", "all": "все", "disk": "диск", "rim": "обод",
                "energy-mass": "энергомасс (Виттенбауэр)", "merzalov": "Мерцалова", "auto": "авто",
                "rocker": "коромысло", "translating": "поступательный", "equal_sliding": "равенство удельных скольжений",
                "true_motion": "истинное", "linear_decreasing": "линейно убывающее ускорение",
                "parabolic": "параболический", "poly345": "полином 3-4-5", "cosine": "косинусоидальный",
                "sine": "синусоидальный", "uniform": "равномерный",
                "kinetostatics.motion=constant": "равномерное", "flywheel.constant=driving": "движущий",
                "flywheel.constant=resistance": "сопротивления"},
         "en": {"ccw": "counter-clockwise", "cw": "clockwise", "true": "yes", "false": "no",
                "extreme": "extreme position", "energy-mass": "energy-mass (Wittenbauer)",
                "linear_decreasing": "linearly decreasing acceleration", "poly345": "polynomial 3-4-5",
                "equal_sliding": "equal specific sliding"}}

ITEMS["en"]["stages"] = "stage"
ITEMS["ru"]["stages"] = "ступень"
WORDS["ru"].update({
    "flat": "тарельчатый", "knife": "остроконечный", "constant_velocity": "постоянной скорости",
    "trapezoidal": "трапецеидальный", "with": "по вращению кулачка", "against": "против вращения кулачка",
    "size": "по габариту", "ratio_error": "по отклонению передаточного отношения",
    "pair": "зубчатая пара", "planetary": "планетарная", "exact": "точный", "no_undercut": "без подрезания",
    "table": "по таблице", "slider_crank": "кривошипно-ползунный",
    "offset_slider_crank": "дезаксиальный кривошипно-ползунный", "crank_rocker": "кривошипно-коромысловый",
    "slotted_lever": "кулисный", "shaper": "кулисный (поперечно-строгальный станок)",
})
WORDS["en"].update({
    "flat": "flat-faced", "knife": "knife-edge", "constant_velocity": "constant velocity",
    "with": "with the cam", "against": "against the cam", "ratio_error": "by the error of the ratio",
    "size": "by size", "pair": "gear pair", "no_undercut": "no undercut", "slider_crank": "slider-crank",
    "offset_slider_crank": "offset slider-crank", "crank_rocker": "crank-rocker", "slotted_lever": "slotted lever",
    "shaper": "slotted lever of a shaper",
})

# units of the task model's numbers (SI; angles in degrees) by the key's last part
_UNITS = {
    "en": {"length": "m", "mass": "kg", "J": "kg·m²", "speed": "rad/s", "angle": "°", "offset": "m",
           "density": "kg/m³", "pin_radius": "m", "rocker_length": "m", "area": "m²", "at": "m",
           "through": "m", "m": "m", "alpha": "°", "rise": "°", "far_dwell": "°", "return": "°",
           "near_dwell": "°", "cycle": "°", "reduced_J": "kg·m²", "magnitude": "N", "phi": "°",
           "moment": "N·m", "width": "m", "direction": "°", "base_radius": "m", "roller_radius": "m", "extra": "°",
           "r0": "m", "center_distance": "m", "rho_min_allowed": "m", "motor_speed": "rad/s",
           "pressure_angle": "°", "transmission_angle": "°"},
    "ru": {"length": "м", "mass": "кг", "J": "кг·м²", "speed": "рад/с", "angle": "°", "offset": "м",
           "density": "кг/м³", "pin_radius": "м", "rocker_length": "м", "area": "м²", "at": "м",
           "through": "м", "m": "м", "alpha": "°", "rise": "°", "far_dwell": "°", "return": "°",
           "near_dwell": "°", "cycle": "°", "reduced_J": "кг·м²", "magnitude": "Н", "phi": "°",
           "moment": "Н·м", "width": "м", "direction": "°", "base_radius": "м", "roller_radius": "м", "extra": "°",
           "r0": "м", "center_distance": "м", "rho_min_allowed": "м", "motor_speed": "рад/с",
           "pressure_angle": "°", "transmission_angle": "°"},
}


for _lang, _u in (("en", "m"), ("ru", "м")):   # synthesis fields
    _UNITS[_lang].update({"H": _u, "e": _u, "frame": _u, "guide_height": _u, "rocker": _u, "psi": "°", "theta": "°",
                          "gamma_min": "°"})

from .task_uk import add_uk as _add_uk  # noqa: E402

_add_uk(PARAMS, ITEMS, WORDS, _UNITS)

# a drive train's planetary stages are searched with the planetary gear's fields: the same names
for _lang in PARAMS:
    for _k in ("satellites", "z_min_external", "z_min_internal", "z_min_satellite_in_internal",
               "internal_minus_external_min", "z_max", "rank", "candidates", "tolerance"):
        PARAMS[_lang][f"drive_train.{_k}"] = PARAMS[_lang][f"planetary.{_k}"]


def _dump(task) -> dict:
    if task is None:
        return {}
    if hasattr(task, "model_dump"):
        try:
            if hasattr(type(task), "__pydantic_complete__"):
                # the model's serializer made from the cached schema (as its validator is):
                # model_dump would build the whole model first (~40 ms)
                from ...schemacache import serializer
                return serializer(type(task)).to_python(task, exclude_none=True, by_alias=True)
            return task.model_dump(exclude_none=True, by_alias=True)
        except TypeError:
            return task.model_dump()
    if isinstance(task, dict):
        return task
    return {}


def num(v: float) -> str:
    """A task number as written: 6 significant digits, no trailing zeros (the decimal
    comma in ru and uk)."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if not math.isfinite(v):
        return str(v)
    if v == 0:
        return "0"
    if 1e-4 <= abs(v) < 1e10:
        import numpy as np
        s = np.format_float_positional(float(f"{v:.6g}"), trim="-")
    else:
        mant, ex = f"{v:.5e}".split("e")
        s = f"{mant.rstrip('0').rstrip('.')}·10{str(int(ex)).translate(_SUP)}"
    return localize(s).replace("-", "−")


_SUP = str.maketrans("-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹")


def _is_num(x) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool)


def _value(v: Any, unit: str = "") -> str:
    """A leaf value in words: coordinates '(0.5, 0.37) m', a list '0; 0.7; 0.9',
    names 'O, A', a number with its unit."""
    u = f" {unit}" if unit else ""
    if isinstance(v, bool):
        return "true" if v else "false"
    if _is_num(v):
        return num(v) + ("" if unit == "°" else " ") + unit if unit else num(v)
    if isinstance(v, (list, tuple)):
        if len(v) == 2 and all(_is_num(x) for x in v) and unit in ("m", "м"):
            return f"({num(v[0])}, {num(v[1])}){u}"
        if all(_is_num(x) for x in v):
            return "; ".join(num(x) for x in v) + (u if v else "")
        return ", ".join(str(x) for x in v)
    return _quantity(str(v))


_WRITTEN = re.compile(r"^([-+]?(?:\d+(?:[.,]\d*)?|\.\d+)(?:[eE][-+]?\d+)?)\s*([^\d\s].*?)\s*$")


def _quantity(text: str) -> str:
    """A value the task gives as a number with its unit ('1.2 rad/s', '0.4 m/s') in the
    report's language: its number as the language writes it, the unit in its spelling."""
    m = _WRITTEN.match(text)
    if not m:
        return text
    unit = spelt(m.group(2))
    return localize(m.group(1).replace(",", ".")) + ("" if unit == "°" else " ") + unit


def flatten(d: Any, prefix: str = "") -> list[tuple[str, Any]]:
    """Nested dict -> [(dotted.key, leaf)], lists of scalars stay leaves."""
    out: list[tuple[str, Any]] = []
    if isinstance(d, dict):
        for k, v in d.items():
            key = f"{prefix}.{k}" if prefix else str(k)
            if v is None or v == {} or v == []:
                continue
            if isinstance(v, dict):
                out.extend(flatten(v, key))
            elif isinstance(v, (list, tuple)) and any(isinstance(x, dict) for x in v):
                for i, x in enumerate(v):
                    out.extend(flatten(x, f"{key}[{i + 1}]") if isinstance(x, dict)
                               else [(f"{key}[{i + 1}]", x)])
            else:
                out.append((key, v))
    return out


def _unit(key: str, lang: str, context: dict | None = None) -> str:
    units = _UNITS.get(lang, _UNITS["en"])
    last = key.split(".")[-1].split("[")[0]
    if last == "value" and ".diagram" in key:
        # a load diagram's ordinate: N, or Pa for a pressure (the force has an area)
        return ("Pa" if lang == "en" else "Па") if (context or {}).get("area") else \
            ("N" if lang == "en" else "Н")
    if last == "magnitude" and (context or {}).get("area"):
        return "Pa" if lang == "en" else "Па"
    if last == "s" and ".diagram" in key:
        return ""
    if last == "stroke" and isinstance((context or {}).get("stroke"), (int, float)):
        return units["angle"] if (context or {}).get("follower") == "rocker" else units["length"]
    if last == "m" and not key.startswith(("gears", "planetary", "differential")):
        return ""
    return units.get(last, "")


def _param(plain: str, lang: str, prefix: str = "task.param") -> str | None:
    """A parameter's name from a section's own word table (``task.param.<path>``), if it has one."""
    from ..i18n import translate
    from . import available
    available()                     # every section's word table registered
    key = f"{prefix}.{plain}"
    text = translate(key, lang)
    return None if text == key else text


def param_name(plain: str, lang: str) -> str | None:
    """The name the task data table gives the field ``plain`` (``cam.stroke``), or None."""
    return PARAMS.get(lang, {}).get(plain) or _param(plain, lang)


def word_of(plain: str, value: str, lang: str) -> str | None:
    """How the task data table writes the word ``value`` of the field ``plain``: a section's own
    word for that field (``task.word.<path>.<value>``), else the common table, else None."""
    own = _param(f"{plain}.{value}", lang, prefix="task.word")
    return own if own is not None else WORDS.get(lang, {}).get(value)


def _rows(key: str, sec: Any, lang: str) -> list[tuple[str, str]]:
    if not isinstance(sec, dict):
        return [(key, _value(sec))]
    rows = []
    for k, v in flatten(sec):
        ctx = dict(sec)
        # the dicts holding this leaf (for the units of a force with an area, a cam's stroke)
        parts = k.replace("]", "").split(".")
        node: Any = sec
        for p in parts[:-1]:
            name, _, idx = p.partition("[")
            node = node.get(name) if isinstance(node, dict) else None
            if idx and isinstance(node, list):
                node = node[int(idx) - 1]
            if isinstance(node, dict):
                ctx.update(node)
        plain = re.sub(r"\[\d+\]", "", f"{key}.{k}")
        label = param_name(plain, lang) or k.replace(".", " · ")
        idx = re.findall(r"(\w+)\[(\d+)\]", k)
        if idx and plain in PARAMS.get(lang, {}):
            item = ITEMS.get(lang, {}).get(idx[-1][0], idx[-1][0])
            label = f"{item} {idx[-1][1]}: {label}"
        val = _value(v, _unit(f"{key}.{k}", lang, ctx))
        if plain == "flywheel.delta" and isinstance(v, float):
            from ...units import fraction_text
            frac = fraction_text(v)
            val = f"{frac} = {_value(v)}" if frac.startswith("1/") else val
        if isinstance(v, (str, bool)):    # a word agreeing with its label's noun ('key=value') first
            words = WORDS.get(lang, {})
            val = words.get(f"{plain}={val}") or (word_of(plain, val, lang) if isinstance(v, str) else None) \
                or words.get(val, val)
        rows.append((label, val))
    return rows


def _mechanism(ctx, mech: dict):
    """(ground rows, link rows, assembly text) of the mechanism section."""
    t = ctx.t
    ground = [(p, num(xy[0]), num(xy[1])) for p, xy in (mech.get("ground") or {}).items()]
    links = []
    for i, (name, spec) in enumerate((mech.get("links") or {}).items(), start=1):
        pts = list(spec.get("points") or [])
        other = []
        if spec.get("slider"):
            pts = [spec["slider"]]
        g = spec.get("guide") or {}
        if g:
            gd = []
            if g.get("link"):
                gd.append(t("task.guide_link", l=g["link"]))
            if g.get("through") is not None:
                th = g["through"]
                gd.append(t("task.guide_through", p=_value(th, "m" if ctx.lang == "en" else "м")
                            if not isinstance(th, str) else th))
            if g.get("angle") is not None and not g.get("link"):
                gd.append(t("task.guide_angle", a=num(g["angle"])))
            elif g.get("angle") is not None and g.get("angle") != 0:
                gd.append(t("task.guide_angle", a=num(g["angle"])))
            if g.get("offset"):
                gd.append(t("task.guide_offset", o=num(g["offset"])))
            other.append(t("task.guide_word") + " " + ", ".join(gd))
        if spec.get("extra"):
            other.append(t("task.extra", p=", ".join(f"{p} ({num(xy[0])}, {num(xy[1])})"
                                                     for p, xy in spec["extra"].items())))
        com = spec.get("com")
        com_txt = f"({num(com[0])}, {num(com[1])})" if isinstance(com, (list, tuple)) else \
            (str(com) if com else "")
        links.append((str(i), name, ", ".join(pts), num(spec["length"]) if spec.get("length") is not None else "",
                       num(spec["mass"]) if spec.get("mass") is not None else "",
                       num(spec["J"]) if spec.get("J") is not None else "", com_txt, "; ".join(other)))
    m = "m" if ctx.lang == "en" else "м"
    assembly = ", ".join(f"{p} ({num(xy[0])}, {num(xy[1])})" for p, xy in (mech.get("assembly") or {}).items())
    return ground, links, (assembly + f" {m}") if assembly else ""


def build(ctx) -> str | None:
    task = ctx.task
    data = _dump(task)
    info = []
    title = getattr(task, "title", None) or data.get("title")
    if title:
        info.append((ctx.t("task.name"), title))
    variant = getattr(task, "variant", None) if task is not None else None
    if variant is None:
        variant = data.get("variant")
    if variant is not None:
        info.append((ctx.t("task.variant"), str(variant)))
    student = data.get("student") or {}
    if isinstance(student, dict):
        if student.get("name"):
            info.append((ctx.t("task.student"), str(student["name"])))
        if student.get("group"):
            info.append((ctx.t("task.group"), str(student["group"])))
        for k, v in student.items():
            if k not in ("name", "group") and v not in (None, ""):
                info.append((str(k), str(v)))
    elif student:
        info.append((ctx.t("task.student"), str(student)))
    mech = None
    groups = []
    for key, sec in data.items():
        if key in _META or sec in (None, {}, []):
            continue
        if key == "mechanism" and isinstance(sec, dict):
            mech = _mechanism(ctx, sec)
            continue
        rows = _rows(key, sec, ctx.lang)
        if rows:
            groups.append({"title": ctx.t(f"task.sec.{key}"), "rows": rows})
    if not info and not groups and mech is None:
        return None
    return ctx.render("sections/task.html.j2", info=info, groups=groups, mech=mech,
                      J_head=Markup(str(escape(ctx.t("task.J"))).replace("J_S", "J<sub>S</sub>")))
