"""Report section 'study': accuracy against computing time per stage (`tmm run --study`).

Shown only when the report is built with a study (results.json itself never carries it:
the timings would make it non-deterministic); the tables and log-log plots are those of
:func:`html_section` below (study.html, written by :func:`write`, is the same section as a
page), its texts the table below."""
from __future__ import annotations

import math
import re

I18N = {
    "en": {
        "study.title": "Accuracy against computing time",
        "study.intro": "For each stage the setting that trades computing time for accuracy is swept. Each row: "
                       "the setting, the values, the relative error against a converged reference (itself "
                       "checked against a finer one; a swept reference is accepted when the two agree to {tol}) "
                       "and the computing time (best of repeats). The measured order is the slope of the error "
                       "against the setting in log-log, fitted over the four finest rows above the rounding "
                       "floor; beside it the theoretical order of the rule used.",
        "study.short": "In short",
        "study.default": " (the default)",
        "study.trade.flywheel": "flywheel J: {a} positions of the grid give an error of {ea}, {b}{dflt} give {eb} ({ta} → {tb} ms)",
        "study.trade.curves": "the s, v, a diagrams drawn through {a} points err by {ea}, through {b}{dflt} by {eb} ({ta} → {tb} ms)",
        "study.trade.kinetostatics": "the M_b and reaction diagrams drawn through {a} positions err by {ea}, through {b}{dflt} by {eb} ({ta} → {tb} ms)",
        "study.trade.dof2": "the integration at rtol = {a} errs by {ea}, at {b}{dflt} by {eb} ({ta} → {tb} ms)",
        "study.trade.cam": "the cam profile as a polygon with a {a}° step errs by {ea}, with {b}°{dflt} by {eb} ({ta} → {tb} ms)",
        "study.trade.gears": "the blocking contour on a grid of {a} nodes errs by {ea}, of {b}{dflt} by {eb} ({ta} → {tb} ms)",
        "study.trade.planetary": "the search up to z = {a} finds a ratio off by {ea}, up to {b}{dflt} by {eb} ({ta} → {tb} ms)",
        "study.stage.flywheel": "Flywheel: positions of the grid",
        "study.stage.curves": "Kinematic diagrams of the output (s, v, a): points over a turn",
        "study.stage.kinetostatics": "Kinetostatic diagrams (M_b and the reactions): positions over the cycle",
        "study.stage.dof2": "Two-degree-of-freedom motion: integrator tolerance",
        "study.stage.cam": "Cam profile: angular step of the polygon",
        "study.stage.gears": "Blocking contour: grid nodes per axis",
        "study.stage.planetary": "Planetary search: largest tooth number",
        "study.note.flywheel": "J_n by the three methods; works by two-point Gauss-Legendre per grid interval, "
                               "the energy extrema located between the nodes",
        "study.note.curves": "The curves drawn through the points (straight segments) against the exact "
                             "kinematics; error: the largest deviation relative to the stroke and to the "
                             "largest |v| and |a|",
        "study.note.kinetostatics": "The diagrams drawn through the positions (equal steps plus the load jumps "
                                    "and kinks, the extreme positions and, with friction, the reversals of the "
                                    "relative motion in the pairs and the sign changes of the sliders' normal "
                                    "forces) against the exact solution; error: the largest "
                                    "deviation relative to the largest |M_b| and the largest reaction",
        "study.note.dof2": "The final speeds and angle of the integration (DOP853)",
        "study.note.cam": "The profile as a polygon: its largest deviation from the exact working profile "
                          "(relative to r0) and rho_min of circles through three successive vertices of one phase",
        "study.note.gears": "The largest distance (in units of the shift coefficient) of the traced contour from "
                            "the exact boundary of the admissible region",
        "study.note.planetary": "The best ratio found by the search and its error",
        "study.reference": "Reference at {setting}: {values}",
        "study.check": "checked against {setting}: difference {diff}",
        "study.not_converged": "the reference did not converge",
        "study.order": "measured order {order}",
        "study.no_order": "no convergence order",
        "study.theory": "theoretical order {theory}",
        "study.trapezoid": "the trapezoid on the same grids: order {order}",
        "study.error": "error",
        "study.time": "time, ms",
        "study.axis": "relative error",
        "study.series.flywheel": "Gauss 2",
        "study.series.trapezoid": "trapezoid",
        "study.series.curves": "s, v, a",
        "study.series.kinetostatics": "M_b, R",
        "study.series.dof2": "DOP853",
        "study.series.cam": "profile",
        "study.series.gears": "contour",
        "study.series.planetary": "search",
        "study.col.resolution": "positions",
        "study.col.points": "points",
        "study.col.positions": "positions",
        "study.col.rtol": "rtol",
        "study.col.step": "step, deg",
        "study.col.grid": "grid",
        "study.col.z_max": "z_max",
        "study.col.stroke": "stroke",
        "study.reference_exact": "Reference: the exact result (setting → 0): {values}",
        "study.check.cam": "the exact profile against the polygon at {setting} deg: difference {diff}",
        "study.check.gears": "the exact boundary located by bisection to 1e-13, again to {setting}: difference {diff}",
        "study.check.curves": "the largest deviation sampled again at {setting} angles: relative difference {diff}",
        "study.check.kinetostatics": "the largest deviation sampled again at {setting} angles: relative difference {diff}",
        "study.col.deviation": "deviation, m",
        "study.col.deviation_x": "deviation (x)",
        "study.col.rho_min": "rho_min, m",
    },
    "ru": {
        "study.title": "Точность и время счёта",
        "study.intro": "Для каждого этапа перебирается параметр, которым время счёта меняется на точность. "
                       "В строке: значение параметра, результаты, относительная погрешность по сравнению с "
                       "сошедшимся эталоном (он сам проверен по более точному; эталон перебором принимается, "
                       "когда два соседних совпадают до {tol}) и время счёта (лучшее из повторов). Измеренный "
                       "порядок — наклон погрешности в логарифмических осях по четырём самым точным строкам "
                       "выше уровня округления; рядом — теоретический порядок применённого правила.",
        "study.short": "Коротко",
        "study.default": " (по умолчанию)",
        "study.trade.flywheel": "J маховика: при {a} положениях сетки погрешность {ea}, при {b}{dflt} — {eb} ({ta} → {tb} мс)",
        "study.trade.curves": "диаграммы s, v, a, построенные по {a} точкам, отличаются от точных на {ea}, по {b}{dflt} — на {eb} ({ta} → {tb} мс)",
        "study.trade.kinetostatics": "диаграммы M_b и реакций, построенные по {a} положениям, отличаются от точных на {ea}, по {b}{dflt} — на {eb} ({ta} → {tb} мс)",
        "study.trade.dof2": "интегрирование с rtol = {a} даёт погрешность {ea}, с {b}{dflt} — {eb} ({ta} → {tb} мс)",
        "study.trade.cam": "профиль кулачка как многоугольник с шагом {a}° отличается от точного на {ea}, с шагом {b}°{dflt} — на {eb} ({ta} → {tb} мс)",
        "study.trade.gears": "блокирующий контур на сетке из {a} узлов отличается от точного на {ea}, из {b}{dflt} — на {eb} ({ta} → {tb} мс)",
        "study.trade.planetary": "подбор до z = {a} даёт передаточное отношение с погрешностью {ea}, до {b}{dflt} — {eb} ({ta} → {tb} мс)",
        "study.stage.flywheel": "Маховик: число положений сетки",
        "study.stage.curves": "Кинематические диаграммы выходного звена (s, v, a): точки за оборот",
        "study.stage.kinetostatics": "Диаграммы кинетостатики (M_b и реакции): положения за цикл",
        "study.stage.dof2": "Движение машины с двумя степенями подвижности: допуск интегратора",
        "study.stage.cam": "Профиль кулачка: угловой шаг многоугольника",
        "study.stage.gears": "Блокирующий контур: узлы сетки по оси",
        "study.stage.planetary": "Подбор планетарного механизма: наибольшее число зубьев",
        "study.note.flywheel": "J_n тремя методами; работы — двухточечной формулой Гаусса–Лежандра на каждом "
                               "интервале сетки, экстремумы энергии найдены между узлами",
        "study.note.curves": "Кривые, проведённые через точки (отрезками), против точной кинематики; "
                             "погрешность — наибольшее отклонение, отнесённое к ходу и к наибольшим |v| и |a|",
        "study.note.kinetostatics": "Диаграммы, проведённые через положения (равный шаг, а также скачки и изломы "
                                    "нагрузок, крайние положения и, при трении, смены направления относительного "
                                    "движения в парах и смены знака нормальной силы в ползунах), против точного решения; погрешность — наибольшее "
                                    "отклонение, отнесённое к наибольшему |M_b| и к наибольшей реакции",
        "study.note.dof2": "Конечные скорости и угол интегрирования (DOP853)",
        "study.note.cam": "Профиль как многоугольник: наибольшее отклонение от точного действительного профиля "
                          "(отнесённое к r0) и rho_min окружностей через три соседние вершины одной фазы",
        "study.note.gears": "Наибольшее расстояние (в долях коэффициента смещения) построенного контура от "
                            "точной границы допустимой области",
        "study.note.planetary": "Лучшее найденное передаточное отношение и его погрешность",
        "study.reference": "Эталон при {setting}: {values}",
        "study.check": "проверка по {setting}: разность {diff}",
        "study.not_converged": "эталон не сошёлся",
        "study.order": "измеренный порядок {order}",
        "study.no_order": "порядок сходимости не определён",
        "study.theory": "теоретический порядок {theory}",
        "study.trapezoid": "формула трапеций на тех же сетках: порядок {order}",
        "study.error": "погрешность",
        "study.time": "время, мс",
        "study.axis": "относительная погрешность",
        "study.series.flywheel": "Гаусс 2",
        "study.series.trapezoid": "трапеции",
        "study.series.curves": "s, v, a",
        "study.series.kinetostatics": "M_b, R",
        "study.series.dof2": "DOP853",
        "study.series.cam": "профиль",
        "study.series.gears": "контур",
        "study.series.planetary": "подбор",
        "study.col.resolution": "положения",
        "study.col.points": "точки",
        "study.col.positions": "положения",
        "study.col.rtol": "rtol",
        "study.col.step": "шаг, град",
        "study.col.grid": "сетка",
        "study.col.z_max": "z_max",
        "study.col.stroke": "ход",
        "study.reference_exact": "Эталон — точный результат (параметр → 0): {values}",
        "study.check.cam": "точный профиль против многоугольника с шагом {setting} град: разность {diff}",
        "study.check.gears": "точная граница найдена делением пополам до 10⁻¹³, повторно до {setting}: разность {diff}",
        "study.check.curves": "наибольшее отклонение, найденное повторно по {setting} углам: относительная разность {diff}",
        "study.check.kinetostatics": "наибольшее отклонение, найденное повторно по {setting} углам: относительная разность {diff}",
        "study.col.deviation": "отклонение, м",
        "study.col.deviation_x": "отклонение (x)",
        "study.col.rho_min": "rho_min, м",
    },
    "uk": {
        "study.title": "Точність і час обчислення",
        "study.intro": "Для кожного етапу перебирається параметр, яким час обчислення міняється на точність. "
                       "У рядку: значення параметра, результати, відносна похибка порівняно зі збіжним еталоном "
                       "(його самого перевірено за точнішим; еталон перебором приймається, коли два сусідні "
                       "збігаються до {tol}) і час обчислення (найкращий із повторів). Виміряний порядок — нахил "
                       "похибки в логарифмічних осях за чотирма найточнішими рядками понад рівень округлення; "
                       "поруч — теоретичний порядок застосованого правила.",
        "study.short": "Коротко",
        "study.default": " (типово)",
        "study.trade.flywheel": "J маховика: за {a} положень сітки похибка {ea}, за {b}{dflt} — {eb} ({ta} → {tb} мс)",
        "study.trade.curves": "діаграми s, v, a, побудовані за {a} точками, відрізняються від точних на {ea}, за {b}{dflt} — на {eb} ({ta} → {tb} мс)",
        "study.trade.kinetostatics": "діаграми M_b і реакцій, побудовані за {a} положеннями, відрізняються від точних на {ea}, за {b}{dflt} — на {eb} ({ta} → {tb} мс)",
        "study.trade.dof2": "інтегрування з rtol = {a} дає похибку {ea}, з {b}{dflt} — {eb} ({ta} → {tb} мс)",
        "study.trade.cam": "профіль кулачка як багатокутник із кроком {a}° відрізняється від точного на {ea}, із кроком {b}°{dflt} — на {eb} ({ta} → {tb} мс)",
        "study.trade.gears": "блокувальний контур на сітці з {a} вузлів відрізняється від точного на {ea}, з {b}{dflt} — на {eb} ({ta} → {tb} мс)",
        "study.trade.planetary": "підбір до z = {a} дає передатне відношення з похибкою {ea}, до {b}{dflt} — {eb} ({ta} → {tb} мс)",
        "study.stage.flywheel": "Маховик: кількість положень сітки",
        "study.stage.curves": "Кінематичні діаграми вихідної ланки (s, v, a): точки за оберт",
        "study.stage.kinetostatics": "Діаграми кінетостатики (M_b і реакції): положення за цикл",
        "study.stage.dof2": "Рух машини з двома ступенями рухомості: допуск інтегратора",
        "study.stage.cam": "Профіль кулачка: кутовий крок багатокутника",
        "study.stage.gears": "Блокувальний контур: вузли сітки по осі",
        "study.stage.planetary": "Підбір планетарного механізму: найбільша кількість зубців",
        "study.note.flywheel": "J_n трьома методами; роботи — двоточковою формулою Гаусса–Лежандра на кожному "
                               "інтервалі сітки, екстремуми енергії знайдено між вузлами",
        "study.note.curves": "Криві, проведені через точки (відрізками), проти точної кінематики; похибка — "
                             "найбільше відхилення, віднесене до ходу та до найбільших |v| і |a|",
        "study.note.kinetostatics": "Діаграми, проведені через положення (рівний крок, а також стрибки та злами "
                                    "навантажень, крайні положення і, з тертям, зміни напрямку відносного руху в "
                                    "парах і зміни знака нормальної сили в повзунах), проти точного розв'язку; похибка — найбільше відхилення, віднесене "
                                    "до найбільшого |M_b| і до найбільшої реакції",
        "study.note.dof2": "Кінцеві швидкості та кут інтегрування (DOP853)",
        "study.note.cam": "Профіль як багатокутник: найбільше відхилення від точного дійсного профілю "
                          "(віднесене до r0) і rho_min кіл через три сусідні вершини однієї фази",
        "study.note.gears": "Найбільша відстань (у частках коефіцієнта зміщення) побудованого контуру від "
                            "точної межі допустимої області",
        "study.note.planetary": "Найкраще знайдене передавальне відношення та його похибка",
        "study.reference": "Еталон при {setting}: {values}",
        "study.check": "перевірка за {setting}: різниця {diff}",
        "study.not_converged": "еталон не збігся",
        "study.order": "виміряний порядок {order}",
        "study.no_order": "порядок збіжності не визначено",
        "study.theory": "теоретичний порядок {theory}",
        "study.trapezoid": "формула трапецій на тих самих сітках: порядок {order}",
        "study.error": "похибка",
        "study.time": "час, мс",
        "study.axis": "відносна похибка",
        "study.series.flywheel": "Гаусс 2",
        "study.series.trapezoid": "трапеції",
        "study.series.curves": "s, v, a",
        "study.series.kinetostatics": "M_b, R",
        "study.series.dof2": "DOP853",
        "study.series.cam": "профіль",
        "study.series.gears": "контур",
        "study.series.planetary": "підбір",
        "study.col.resolution": "положення",
        "study.col.points": "точки",
        "study.col.positions": "положення",
        "study.col.rtol": "rtol",
        "study.col.step": "крок, град",
        "study.col.grid": "сітка",
        "study.col.z_max": "z_max",
        "study.col.stroke": "хід",
        "study.reference_exact": "Еталон — точний результат (параметр → 0): {values}",
        "study.check.cam": "точний профіль проти багатокутника з кроком {setting} град: різниця {diff}",
        "study.check.gears": "точну межу знайдено поділом навпіл до 10⁻¹³, повторно до {setting}: різниця {diff}",
        "study.check.curves": "найбільше відхилення, знайдене повторно за {setting} кутами: відносна різниця {diff}",
        "study.check.kinetostatics": "найбільше відхилення, знайдене повторно за {setting} кутами: відносна різниця {diff}",
        "study.col.deviation": "відхилення, м",
        "study.col.deviation_x": "відхилення (x)",
        "study.col.rho_min": "rho_min, м",
    },
}


def build(ctx) -> str | None:
    st = ctx.results.get("study")
    if not st:
        return None
    from markupsafe import Markup
    return Markup(html_section(st, ctx.results.get("study_trapezoid"), ctx.lang))


_W, _H, _L, _B, _T, _R = 520, 320, 64, 44, 16, 150
_COLORS = ("#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b")


def svg_loglog(series: list[tuple[str, list[float], list[float]]], xlabel: str,
               ylabel: str = "relative error") -> str:
    """A log-log plot drawn directly as SVG: series of (label, x, y), y > 0 only."""
    pts = [(x, y) for _, xs, ys in series for x, y in zip(xs, ys) if x > 0 and y and y > 0]
    if not pts:
        return ""
    lx = [math.log10(p[0]) for p in pts]
    ly = [math.log10(p[1]) for p in pts]
    x0, x1 = math.floor(min(lx)), math.ceil(max(lx))
    y0, y1 = math.floor(min(ly)), math.ceil(max(ly))
    x1 = x1 if x1 > x0 else x0 + 1
    y1 = y1 if y1 > y0 else y0 + 1
    pw, ph = _W - _L - _R, _H - _T - _B

    def X(v):
        return _L + (math.log10(v) - x0) / (x1 - x0) * pw

    def Y(v):
        return _T + (y1 - math.log10(v)) / (y1 - y0) * ph

    o = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{_W}" height="{_H}" '
         f'viewBox="0 0 {_W} {_H}" font-family="sans-serif" font-size="11">',
         f'<rect x="{_L}" y="{_T}" width="{pw}" height="{ph}" fill="none" stroke="#000"/>']
    ystep = max(1, (y1 - y0) // 8)
    for k in range(x0, x1 + 1):
        x = _L + (k - x0) / (x1 - x0) * pw
        o.append(f'<line x1="{x:.1f}" y1="{_T}" x2="{x:.1f}" y2="{_T + ph}" stroke="#ddd"/>')
        o.append(f'<text x="{x:.1f}" y="{_T + ph + 14}" text-anchor="middle">1e{k}</text>')
    for k in range(y0, y1 + 1, ystep):
        y = _T + (y1 - k) / (y1 - y0) * ph
        o.append(f'<line x1="{_L}" y1="{y:.1f}" x2="{_L + pw}" y2="{y:.1f}" stroke="#ddd"/>')
        o.append(f'<text x="{_L - 4}" y="{y + 4:.1f}" text-anchor="end">1e{k}</text>')
    o.append(f'<text x="{_L + pw / 2}" y="{_H - 6}" text-anchor="middle">{xlabel}</text>')
    o.append(f'<text x="14" y="{_T + ph / 2}" text-anchor="middle" '
             f'transform="rotate(-90 14 {_T + ph / 2})">{ylabel}</text>')
    for i, (label, xs, ys) in enumerate(series):
        c = _COLORS[i % len(_COLORS)]
        p = [(X(x), Y(y)) for x, y in zip(xs, ys) if x > 0 and y and y > 0]
        if not p:
            continue
        o.append(f'<polyline fill="none" stroke="{c}" stroke-width="1.5" points="'
                 + " ".join(f"{a:.1f},{b:.1f}" for a, b in p) + '"/>')
        o.extend(f'<circle cx="{a:.1f}" cy="{b:.1f}" r="2.5" fill="{c}"/>' for a, b in p)
        ly_ = _T + 14 + 16 * i
        o.append(f'<line x1="{_L + pw + 8}" y1="{ly_ - 4}" x2="{_L + pw + 24}" y2="{ly_ - 4}" '
                 f'stroke="{c}" stroke-width="2"/>')
        o.append(f'<text x="{_L + pw + 28}" y="{ly_}">{label}</text>')
    o.append("</svg>")
    return "\n".join(o)


def _fmt(v, key: str = "") -> str:
    if v is None:
        return "—"
    if isinstance(v, float) and (key.startswith(("err", "deviation")) or key == "time_ms"):
        return f"{v:.3g}"
    if isinstance(v, float):
        return f"{v:.3g}" if (abs(v) < 1e-3 or abs(v) >= 1e6) and v != 0 else f"{v:.10g}"
    return str(v)


def _error_text(e: float | None) -> str:
    """A relative error in plain words: '10.7 %' down to 0.01 %, below it the number itself
    ('2e-11'), written in the current language."""
    from ...numfmt import localize
    if e is None or not math.isfinite(e):
        return "—"
    if e >= 1e-4:
        return localize(f"{100 * e:.3g} %")
    return localize(re.sub(r"e([-+])0*(\d)", r"e\1\2", f"{e:.1g}")) if e > 0 else "0"


def trade(stage: str, d: dict, lang: str = "en") -> str | None:
    """The stage's trade in one sentence: the coarsest setting's error and time against the
    tool's default setting (else the finest): '12 positions give 10.7 %, 720 give 0.01 %'."""
    from ...numfmt import language, localize
    from .. import i18n
    i18n.register(I18N)
    rows = d.get("rows") or []
    key = f"study.trade.{stage}"
    if len(rows) < 2 or key not in i18n.STRINGS["en"]:
        return None
    a = rows[0]
    dflt = d.get("default")
    b = next((r for r in rows if r["setting"] == dflt), None)
    if b is None or b is a:
        b, dflt_text = rows[-1], ""
    else:
        dflt_text = i18n.translate("study.default", lang)
    with language(lang):
        return i18n.translate(key, lang, a=localize(f"{a['setting']:g}"), b=localize(f"{b['setting']:g}"),
                              ea=_error_text(a["error"]), eb=_error_text(b["error"]), dflt=dflt_text,
                              ta=localize(f"{a['time_ms']:.3g}"), tb=localize(f"{b['time_ms']:.3g}"))


def trades(study: dict, lang: str = "en") -> list[str]:
    """The trade sentence of every stage of the study (its order)."""
    return [s for s in (trade(stage, d, lang) for stage, d in study.items()) if s]


def html_section(study: dict, trapezoid: dict | None = None, lang: str = "en") -> str:
    """A report section in `lang`: per stage the table, the measured and the theoretical
    order and a log-log plot (texts: tmm_cli/report/sections/study.py, I18N)."""
    import html as h

    from ...study import REF_TOL
    from .. import i18n
    i18n.register(I18N)

    def t(key, **kw):
        return i18n.translate(f"study.{key}", lang, **kw)

    def col(k):
        key = f"study.col.{k}"
        return i18n.translate(key, lang) if key in i18n.STRINGS["en"] else k

    parts = [f"<section><h2>{h.escape(t('title'))}</h2>"]
    short = trades(study, lang)        # the trade first, in plain words; the method after it
    if short:
        parts.append(f"<h3>{h.escape(t('short'))}</h3><ul class='trade'>"
                     + "".join(f"<li>{h.escape(x[0].upper() + x[1:])}.</li>" for x in short) + "</ul>")
    parts.append(f"<p>{h.escape(t('intro', tol=f'{REF_TOL:g}'))}</p>")
    for stage, d in study.items():
        rows = d["rows"]
        keys = [k for k in rows[0] if k not in ("setting", "error", "time_ms")]
        parts.append(f"<h3>{h.escape(t('stage.' + stage))}</h3>")
        ref = d["reference"]
        txt = [t("note." + stage)]
        rv = ", ".join(f"{col(k)} = {_fmt(ref[k])}" for k in ref if k not in ("setting", "check", "converged"))
        txt.append(t("reference_exact" if ref["setting"] == 0 else "reference", setting=_fmt(ref["setting"]),
                     values=rv))
        chk = ref.get("check")
        if isinstance(chk, dict):
            key = f"study.check.{stage}"
            txt.append(i18n.translate(key if key in i18n.STRINGS["en"] else "study.check", lang,
                                      setting=_fmt(chk.get("setting")), diff=_fmt(chk.get("difference"), "err")))
        if ref.get("converged") is False:
            txt.append(t("not_converged"))
        order, theory = d.get("order"), d.get("theory")
        txt.append(t("order", order=order) if order is not None else t("no_order"))
        if theory is not None:
            txt.append(t("theory", theory=theory))
        tr = (trapezoid or {}).get(stage)
        if tr:
            txt.append(t("trapezoid", order=tr["order"]))
        parts.append("<p>" + h.escape(" ".join(x[0].upper() + x[1:].rstrip(".") + "." for x in txt if x)) + "</p>")
        head = "".join(f"<th>{h.escape(x)}</th>" for x in [col(d["setting"]), *map(col, keys), t("error"), t("time")])
        body = "".join("<tr>" + "".join(f"<td>{_fmt(r[k], k)}</td>" for k in ["setting", *keys, "error", "time_ms"])
                       + "</tr>" for r in rows)
        parts.append(f"<table><tr>{head}</tr>{body}</table>")
        xs = [r["setting"] for r in rows]
        series = [(t("series." + stage), xs, [r["error"] for r in rows])]
        if tr:
            series.append((t("series.trapezoid"), [r["setting"] for r in tr["rows"]], [r["error"] for r in tr["rows"]]))
        parts.append(svg_loglog(series, col(d["setting"]), t("axis")))
    parts.append("</section>")
    return "\n".join(parts)


def write(study: dict, out, trapezoid: dict | None = None, lang: str = "en") -> list:
    """study.json and study.html (the section as a page, in `lang`) in the folder `out`."""
    import json
    from pathlib import Path
    from ...io import atomic_write
    out = Path(out)
    from ..i18n import translate
    section = html_section(study, trapezoid, lang)        # registers the texts
    page = (f"<!DOCTYPE html><html lang='{lang}'><head><meta charset='utf-8'><title>"
            f"{translate('study.title', lang)}</title>"
            "<style>body{font-family:sans-serif;max-width:60em;margin:1em auto}table{border-collapse:collapse}"
            "td,th{border:1px solid #999;padding:2px 6px;text-align:right}</style></head><body>"
            + section + "</body></html>")
    return [atomic_write(out / "study.json", json.dumps(study, indent=1, allow_nan=False)),
            atomic_write(out / "study.html", page)]
