"""Report section 'study': accuracy against computing time per stage (`tmm run --study`).

Shown only when the report is built with a study (results.json itself never carries it:
the timings would make it non-deterministic); the tables and log-log plots are those of
`tmm_cli.study.html_section`, its texts the table below."""
from __future__ import annotations

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
    from ...study import html_section
    return Markup(html_section(st, ctx.results.get("study_trapezoid"), ctx.lang))
