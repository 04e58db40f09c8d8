"""Translations of the report (English and Russian course terminology).

The tables are plain dicts ``{lang: {key: text}}``.  Keys are dotted,
``"<section>.<name>"`` (``"kin.velocity_plan"``), common words live under
``"common."``.  Missing keys fall back to English, then to the key itself, so
a missing translation never breaks a report.

A stage section adds its own words either by calling :func:`register` or,
simpler, by defining a module-level ``I18N = {"en": {...}, "ru": {...}}`` in
``tmm_cli/report/sections/<name>.py``; the section loader registers it.

Russian terms follow the standard course books (Artobolevsky; Popov &
Timofeev; Frolov): «план скоростей», «план ускорений», «группа Ассура», ...
The Ukrainian table (``uk``) lives in :mod:`tmm_cli.report.i18n_uk`.
"""
from __future__ import annotations

LANGS = ("en", "ru", "uk")

STRINGS: dict[str, dict[str, str]] = {
    "en": {
        "report.title": "Course project in Theory of Machines and Mechanisms",
        "report.contents": "Contents",
        "report.generated": "Computed by tmm",
        "report.reaction_convention": "R<i><j> is the force exerted by link i on link j (links numbered in task order, ground = 0).",
        "report.warnings": "Warnings",
        "report.files": "Tables beside the report",
        "common.position": "Position",
        "common.positions": "Positions",
        "common.extra_note": "* an extra position; the positions in the order of the crank's turn",
        "common.value": "Value",
        "common.parameter": "Parameter",
        "common.link": "Link",
        "common.links": "Links",
        "common.point": "Point",
        "common.ground": "ground",
        "common.ccw": "ccw",
        "common.cw": "cw",
        "common.none": "—",
        "common.scale": "Scale",
        "common.yes": "yes",
        "common.no": "no",
        "link.crank": "crank",
        "link.rod": "connecting rod",
        "link.rocker": "rocker",
        "link.slider": "slider",
        "link.block": "sliding block",
        "link.slotted": "slotted link",
        "link.bar": "link",
        # task section
        "task.title": "Task",
        "task.name": "Title",
        "task.variant": "Variant",
        "task.student": "Student",
        "task.group": "Group",
        "task.data": "Task data",
        "task.section": "Section",
        # structure section
        "struct.title": "Structural analysis",
        "struct.scheme": "Kinematic scheme of the mechanism (position 0)",
        "struct.chebyshev": "Degree of freedom by Chebyshev's formula",
        "struct.n": "number of moving links",
        "struct.p5": "number of lower (class V) pairs",
        "struct.p4": "number of higher (class IV) pairs",
        "struct.links": "Links",
        "struct.pairs": "Kinematic pairs",
        "struct.pair": "Pair",
        "struct.pair_kind": "Kind",
        "struct.pair_links": "Links",
        "struct.revolute": "revolute (R)",
        "struct.prismatic": "prismatic (P)",
        "struct.groups": "Assur groups",
        "struct.group": "Group",
        "struct.class": "Class",
        "struct.order": "Order",
        "struct.type": "Type",
        "struct.formula": "Structure formula",
        "struct.mech_class": "Class of the mechanism",
        "struct.primary": "primary mechanism (ground + input link)",
        "struct.index": "No.",
        "struct.name": "Name",
        "struct.kind": "Kind",
        "struct.points": "Points",
        "struct.length": "Length, m",
        # kinematics section
        "kin.title": "Kinematic analysis",
        "kin.positions_plan": "Plan of positions",
        "kin.positions_caption": "The mechanism in {n} positions, trajectories of the points",
        "kin.extreme": "Extreme positions of the output link",
        "kin.phi0": "Crank angle of position 0",
        "kin.extreme_angles": "Crank angles of the extreme positions",
        "kin.working_angle": "Working-stroke angle",
        "kin.idle_angle": "Idle-stroke angle",
        "kin.K": "Coefficient of mean speed increase K",
        "kin.scales": "Scale factors",
        "kin.mu_l": "length scale",
        "kin.mu_v": "velocity scale",
        "kin.mu_a": "acceleration scale",
        "kin.reading": "reading plans drawn with the crank pin's vectors pa, πa about 100 mm long to ±0.5 mm (the hand method's own error)",
        "kin.reading_val": "±{ev} m/s, ±{ea} m/s²; relative, over the points and positions: median {med} %, "
                           "largest {top} %",
        "kin.link_lengths": "Link lengths on the drawing",
        "kin.drawing_mm": "On the drawing, mm",
        "kin.velocity_plan": "Velocity plan",
        "kin.acceleration_plan": "Acceleration plan",
        "kin.plans": "Velocity and acceleration plans",
        "kin.plans_note": "Absolute velocities are vectors from the pole p, relative velocities join their ends. In the acceleration plan (pole π) n marks the end of a normal component, k the end of the Coriolis acceleration.",
        "kin.position_n": "Position {i}, φ = {phi}°",
        "kin.vector": "Vector",
        "kin.segment": "Segment",
        "kin.length_mm": "Length, mm",
        "kin.velocity_ms": "Value, m/s",
        "kin.accel_ms2": "Value, m/s²",
        "kin.angular": "Angular velocities and accelerations",
        "kin.omega": "ω, rad/s",
        "kin.epsilon": "ε, rad/s²",
        "kin.sense": "sense",
        "kin.table_v": "Velocities of the points, m/s",
        "kin.table_a": "Accelerations of the points, m/s²",
        "kin.table_w": "Angular velocities of the links, rad/s",
        "kin.table_e": "Angular accelerations of the links, rad/s²",
        "kin.diagrams": "Kinematic diagrams of the output link",
        "kin.diag_s": "displacement",
        "kin.diag_v": "velocity",
        "kin.diag_a": "acceleration",
        "kin.phi_axis": "φ from position 0, deg",
        "kin.normal": "normal",
        "kin.tangential": "tangential",
        "kin.coriolis": "Coriolis",
        "kin.relative": "relative",
        "kin.absolute": "absolute",
        "kin.interp_note": "Curves are periodic splines through the computed positions (marked).",
        "kin.dense_note": "Curves from a dense grid of crank angles; the positions are marked.",
    },
    "ru": {
        "report.title": "Курсовой проект по теории механизмов и машин",
        "report.contents": "Содержание",
        "report.generated": "Расчёт выполнен программой tmm",
        "report.reaction_convention": "R<i><j> — сила, с которой звено i действует на звено j (звенья пронумерованы в порядке задания, стойка — 0).",
        "report.warnings": "Предупреждения",
        "report.files": "Таблицы рядом с отчётом",
        "common.position": "Положение",
        "common.positions": "Положения",
        "common.extra_note": "* дополнительное положение; положения перечислены в порядке поворота кривошипа",
        "common.value": "Значение",
        "common.parameter": "Параметр",
        "common.link": "Звено",
        "common.links": "Звенья",
        "common.point": "Точка",
        "common.ground": "стойка",
        "common.ccw": "против часовой стрелки",
        "common.cw": "по часовой стрелке",
        "common.none": "—",
        "common.scale": "Масштаб",
        "common.yes": "да",
        "common.no": "нет",
        "link.crank": "кривошип",
        "link.rod": "шатун",
        "link.rocker": "коромысло",
        "link.slider": "ползун",
        "link.block": "камень кулисы",
        "link.slotted": "кулиса",
        "link.bar": "звено",
        "task.title": "Задание",
        "task.name": "Тема",
        "task.variant": "Вариант",
        "task.student": "Студент",
        "task.group": "Группа",
        "task.data": "Исходные данные",
        "task.section": "Раздел",
        "struct.title": "Структурный анализ механизма",
        "struct.scheme": "Кинематическая схема механизма (положение 0)",
        "struct.chebyshev": "Степень подвижности по формуле Чебышева",
        "struct.n": "число подвижных звеньев",
        "struct.p5": "число низших кинематических пар (V класса)",
        "struct.p4": "число высших кинематических пар (IV класса)",
        "struct.links": "Звенья механизма",
        "struct.pairs": "Кинематические пары",
        "struct.pair": "Пара",
        "struct.pair_kind": "Вид",
        "struct.pair_links": "Звенья",
        "struct.revolute": "вращательная (В)",
        "struct.prismatic": "поступательная (П)",
        "struct.groups": "Группы Ассура",
        "struct.group": "Группа",
        "struct.class": "Класс",
        "struct.order": "Порядок",
        "struct.type": "Вид",
        "struct.formula": "Структурная формула",
        "struct.mech_class": "Класс механизма",
        "struct.primary": "первичный механизм (стойка + входное звено)",
        "struct.index": "№",
        "struct.name": "Название",
        "struct.kind": "Тип",
        "struct.points": "Точки",
        "struct.length": "Длина, м",
        "kin.title": "Кинематический анализ механизма",
        "kin.positions_plan": "План положений механизма",
        "kin.positions_caption": "Механизм в {n} положениях, траектории точек (шатунные кривые)",
        "kin.extreme": "Крайние положения выходного звена",
        "kin.phi0": "Угол кривошипа в положении 0",
        "kin.extreme_angles": "Углы кривошипа в крайних положениях",
        "kin.working_angle": "Угол рабочего хода",
        "kin.idle_angle": "Угол холостого хода",
        "kin.K": "Коэффициент изменения средней скорости K",
        "kin.scales": "Масштабные коэффициенты",
        "kin.mu_l": "масштабный коэффициент длин",
        "kin.mu_v": "масштабный коэффициент плана скоростей",
        "kin.mu_a": "масштабный коэффициент плана ускорений",
        "kin.reading": "чтение планов, построенных с отрезками pa и πa около 100 мм, с точностью ±0,5 мм (погрешность графического метода)",
        "kin.reading_val": "±{ev} м/с, ±{ea} м/с²; относительная по точкам и положениям: медиана {med} %, "
                           "наибольшая {top} %",
        "kin.link_lengths": "Длины звеньев на чертеже",
        "kin.drawing_mm": "На чертеже, мм",
        "kin.velocity_plan": "План скоростей",
        "kin.acceleration_plan": "План ускорений",
        "kin.plans": "Планы скоростей и ускорений",
        "kin.plans_note": "Абсолютные скорости изображаются векторами из полюса p, относительные — отрезками, соединяющими их концы. На плане ускорений (полюс π) n — конец нормальной составляющей, k — конец ускорения Кориолиса.",
        "kin.position_n": "Положение {i}, φ = {phi}°",
        "kin.vector": "Вектор",
        "kin.segment": "Отрезок",
        "kin.length_mm": "Длина, мм",
        "kin.velocity_ms": "Величина, м/с",
        "kin.accel_ms2": "Величина, м/с²",
        "kin.angular": "Угловые скорости и ускорения звеньев",
        "kin.omega": "ω, рад/с",
        "kin.epsilon": "ε, рад/с²",
        "kin.sense": "направление",
        "kin.table_v": "Скорости точек, м/с",
        "kin.table_a": "Ускорения точек, м/с²",
        "kin.table_w": "Угловые скорости звеньев, рад/с",
        "kin.table_e": "Угловые ускорения звеньев, рад/с²",
        "kin.diagrams": "Кинематические диаграммы выходного звена",
        "kin.diag_s": "перемещение",
        "kin.diag_v": "скорость",
        "kin.diag_a": "ускорение",
        "kin.phi_axis": "φ от положения 0, град",
        "kin.normal": "нормальное",
        "kin.tangential": "касательное",
        "kin.coriolis": "Кориолиса",
        "kin.relative": "относительное",
        "kin.absolute": "абсолютное",
        "kin.interp_note": "Кривые — периодические сплайны через рассчитанные положения (отмечены).",
        "kin.dense_note": "Кривые построены по частой сетке углов кривошипа; положения отмечены.",
    },
}

from .i18n_uk import UK as _UK  # noqa: E402  (the Ukrainian table lives in its own module)

STRINGS["uk"] = dict(_UK)


def words_beside(module_file: str) -> dict[str, dict[str, str]]:
    """A section's word table from the YAML data file beside its module (``x.py`` -> ``x.yaml``:
    ``{lang: {key: text}}``), the way a new section keeps its words out of Python."""
    from pathlib import Path

    import yaml
    return yaml.safe_load(Path(module_file).with_suffix(".yaml").read_text(encoding="utf-8"))


def register(table: dict[str, dict[str, str]]) -> None:
    """Merge ``{lang: {key: text}}`` into the tables (later registrations win)."""
    for lang, words in table.items():
        STRINGS.setdefault(lang, {}).update(words)


def translate(key: str, lang: str, **kw) -> str:
    """Text for ``key`` in ``lang`` (fallback: English, then the key itself).

    Keyword arguments are substituted with ``str.format`` (a number in ``lang``'s writing:
    the decimal comma in ru and uk, :mod:`tmm_cli.numfmt`).
    """
    text = STRINGS.get(lang, {}).get(key)
    if text is None:
        text = STRINGS["en"].get(key, key)
    if kw:
        from ..numfmt import format_text
        try:
            text = format_text(text, lang, **kw)
        except (KeyError, IndexError, ValueError):
            pass
    return text
