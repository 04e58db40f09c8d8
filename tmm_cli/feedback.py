"""A one-page feedback per student (HTML, and PDF when asked): their value, the
reference, the error, the verdict, and for a wrong value the step of the course
project it comes from and the steps that step depends on. English, Russian or Ukrainian."""
from __future__ import annotations

import html
import re
from pathlib import Path

# section -> (step en, step ru, depends on en, depends on ru)
STEPS = {
    "structure": ("structural analysis (Chebyshev's formula, Assur groups)",
                  "структурный анализ (формула Чебышева, группы Ассура)", "", ""),
    "positions": ("positions: the extreme positions of the output link, K and the stroke",
                  "планы положений: крайние положения выходного звена, K и ход", "the link lengths",
                  "длины звеньев"),
    "kinematics": ("velocity and acceleration plans at this position",
                   "планы скоростей и ускорений в этом положении", "the position plan (angles of the links)",
                   "план положений (углы звеньев)"),
    "kinetostatics": ("kinetostatics by Assur groups and the Zhukovsky lever",
                      "кинетостатика по группам Ассура и рычаг Жуковского",
                      "the acceleration plan (inertia forces) and the loads at this position",
                      "план ускорений (силы инерции) и нагрузки в этом положении"),
    "singular": ("singular positions of the force analysis", "особые положения силового расчёта",
                 "the positions", "планы положений"),
    "flywheel": ("the flywheel by the energy-mass method (reduced moments and inertia)",
                 "маховик по методу энергомасс (приведённые моменты и момент инерции)",
                 "the velocity analogues of every position (reduced inertia) and the loads",
                 "аналоги скоростей во всех положениях (приведённый момент инерции) и нагрузки"),
    "cam": ("cam synthesis: the base radius from the allowed pressure angle",
            "синтез кулачка: минимальный радиус по допустимому углу давления",
            "the follower motion law (analogues of velocity and acceleration)",
            "закон движения толкателя (аналоги скорости и ускорения)"),
    "gears": ("involute gear geometry: α_w from inv α_w, then the radii and thicknesses",
              "геометрия эвольвентного зацепления: α_w по inv α_w, затем радиусы и толщины",
              "the module, the teeth and the shift coefficients", "модуль, числа зубьев и коэффициенты смещения"),
    "planetary": ("tooth numbers of the planetary gear (Willis, coaxiality, assembly, adjacency)",
                  "подбор чисел зубьев планетарной передачи (Виллис, соосность, сборка, соседство)",
                  "the required ratio", "заданное передаточное отношение"),
    "drive_train": ("the ratio and speeds of the compound gear drive", "передаточное отношение и скорости привода",
                    "the stages of the drive", "ступени привода"),
    "synthesis": ("lever mechanism synthesis from K and the stroke", "синтез рычажного механизма по K и ходу",
                  "the given K and stroke", "заданные K и ход"),
    "dof2": ("the machine with two degrees of freedom (Lagrange's equations)",
             "машина с двумя степенями свободы (уравнения Лагранжа)", "the initial state", "начальное состояние"),
}

TEXT = {
    "en": {"title": "Feedback", "student": "Student", "group": "Group", "variant": "Variant", "task": "Task",
           "quantity": "quantity", "value": "your value", "reference": "reference", "error": "error",
           "verdict": "verdict", "step": "where to look", "score": "Score", "depends": "depends on",
           "ok": "correct", "outside": "outside tolerance", "sign": "sign error", "missing": "missing",
           "unknown_path": "unknown quantity", "not_computed": "not computed"},
    "ru": {"title": "Разбор ответов", "student": "Студент", "group": "Группа", "variant": "Вариант",
           "task": "Задание", "quantity": "величина", "value": "ваш ответ", "reference": "эталон",
           "error": "ошибка", "verdict": "оценка", "step": "что проверить", "score": "Балл",
           "depends": "зависит от", "ok": "верно", "outside": "вне допуска", "sign": "ошибка знака",
           "missing": "нет ответа", "unknown_path": "неизвестная величина", "not_computed": "не вычислено"},
    "uk": {"title": "Розбір відповідей", "student": "Студент", "group": "Група", "variant": "Варіант",
           "task": "Завдання", "quantity": "величина", "value": "ваша відповідь", "reference": "еталон",
           "error": "похибка", "verdict": "оцінка", "step": "що перевірити", "score": "Бал",
           "depends": "залежить від", "ok": "правильно", "outside": "поза допуском", "sign": "помилка знака",
           "missing": "немає відповіді", "unknown_path": "невідома величина", "not_computed": "не обчислено"},
}

# section -> (step uk, depends on uk)
STEPS_UK = {
    "structure": ("структурний аналіз (формула Чебишова, групи Ассура)", ""),
    "positions": ("плани положень: крайні положення вихідної ланки, K і хід", "довжини ланок"),
    "kinematics": ("плани швидкостей і прискорень у цьому положенні", "план положень (кути ланок)"),
    "kinetostatics": ("кінетостатика за групами Ассура і важіль Жуковського",
                      "план прискорень (сили інерції) і навантаження в цьому положенні"),
    "singular": ("особливі положення силового розрахунку", "плани положень"),
    "flywheel": ("маховик за методом енергомас (зведені моменти й момент інерції)",
                 "аналоги швидкостей у всіх положеннях (зведений момент інерції) і навантаження"),
    "cam": ("синтез кулачка: мінімальний радіус за допустимим кутом тиску",
            "закон руху штовхача (аналоги швидкості й прискорення)"),
    "gears": ("геометрія евольвентного зачеплення: α_w за inv α_w, потім радіуси й товщини",
              "модуль, числа зубів і коефіцієнти зміщення"),
    "planetary": ("добір чисел зубів планетарної передачі (Вілліс, співвісність, складання, сусідство)",
                  "задане передаточне відношення"),
    "drive_train": ("передаточне відношення і швидкості приводу", "ступені приводу"),
    "synthesis": ("синтез важільного механізму за K і ходом", "задані K і хід"),
    "dof2": ("машина з двома ступенями вільності (рівняння Лагранжа)", "початковий стан"),
}


def step_for(path: str, lang: str) -> str:
    """The course step a quantity comes from, and what that step depends on."""
    sec = re.split(r"[.\[]", path, 1)[0]
    s = STEPS.get(sec)
    if not s:
        return ""
    step, dep = (s[1], s[3]) if lang == "ru" else (s[0], s[2])
    if lang == "uk" and sec in STEPS_UK:
        step, dep = STEPS_UK[sec]
    m = re.match(r"^\w+\[(\d+)\]", path)
    if m and sec in ("kinematics", "kinetostatics"):
        step += f" ({ {'ru': 'положение', 'uk': 'положення'}.get(lang, 'position')} {m.group(1)})"
    return step + (f"; {TEXT[lang]['depends']}: {dep}" if dep else "")


def _num(x) -> str:
    if x is None:
        return "–"
    try:
        return f"{float(x):.5g}"
    except (TypeError, ValueError):
        return str(x)


def feedback_html(task, s: dict, lang: str = "en") -> str:
    from .forms import notation
    lang = lang if lang in TEXT else "en"
    T = TEXT[lang]
    e = lambda x: html.escape(str(x), quote=True)  # noqa: E731
    rows = s["rows"]
    n_ok = sum(r["status"] == "ok" for r in rows)
    trs = []
    for r in rows:
        st = r["status"]
        err = "–"
        if r["error"] is not None:
            err = (_num(r["error"]) if "abs" in r["tolerance"] or r["note"] == "absolute error"
                   else f"{100 * r['error']:.2f} %")
        note = r["note"]
        if st == "unknown_path" and hasattr(note, "to_dict"):        # coded: in the page's language
            from .messages import localize
            note = localize(note.to_dict(), lang)
        step = step_for(r["path"], lang) if st in ("outside", "sign") else (note if st == "unknown_path" else "")
        colour = {"ok": "#c8e6c9", "outside": "#ffcdd2", "sign": "#e1bee7", "missing": "#fff9c4"}.get(st, "#eee")
        trs.append(f"<tr><td><code>{e(r['path'])}</code><br><small>{e(notation(r['path'], lang, local_units=True))}</small></td>"
                   f"<td>{e(_num(r['answer']))}</td><td>{e(_num(r['reference']))}</td><td>{e(err)}</td>"
                   f"<td style='background:{colour}'>{e(T.get(st, st))}</td><td><small>{e(step)}</small></td></tr>")
    head = "".join(f"<th>{e(T[c])}</th>" for c in ("quantity", "value", "reference", "error", "verdict", "step"))
    who = [(T["student"], s.get("student") or "–"), (T["group"], s.get("group") or "–"),
           (T["variant"], "–" if s.get("variant") in (None, "") else s.get("variant")),
           (T["task"], task.title or task.name), (T["score"], f"{n_ok} / {len(rows)}")]
    info = "".join(f"<tr><th>{e(k)}</th><td>{e(v)}</td></tr>" for k, v in who)
    return ("<!DOCTYPE html><html><head><meta charset='utf-8'>"
            f"<title>{e(T['title'])}</title><style>@page{{size:A4;margin:12mm}}body{{font-family:sans-serif;"
            "font-size:12px}table{border-collapse:collapse;margin-bottom:1em}td,th{border:1px solid #999;"
            "padding:3px 6px;text-align:left;vertical-align:top}</style></head><body>"
            f"<h1>{e(T['title'])}</h1><table>{info}</table><table><tr>{head}</tr>{''.join(trs)}</table>"
            "</body></html>\n")


def feedback_name(s: dict) -> str:
    from .safepath import safe_name          # the name behind "feedback-": no device name to fear
    who = safe_name(str(s.get("student") or ""), "").strip("._") or "answers"
    return f"feedback-{who[:40]}-{s['index'] + 1 if s['index'] >= 0 else 0}"


def write_feedback(task, s: dict, folder: Path, lang: str, pdf: bool = False,
                   notes: list[str] | None = None) -> list[Path]:
    """feedback-<student>-<n>.html (and .pdf) in the variant's folder. The PDF is made
    by weasyprint, which needs the system's Pango: where weasyprint or Pango is missing
    (an ImportError, or the OSError of a library not found) the page is written as HTML
    only, ``notes`` receives one line saying why, and the grading goes on."""
    from .io import atomic_write
    text = feedback_html(task, s, lang)
    base = feedback_name(s)
    out = [atomic_write(Path(folder) / f"{base}.html", text)]
    if pdf:
        try:
            import weasyprint
        except (ImportError, OSError) as exc:
            if notes is not None:
                first = (str(exc).strip().splitlines() or [type(exc).__name__])[0]
                notes.append(f"feedback pages written as HTML only: the PDF engine (weasyprint) "
                             f"cannot be loaded: {first}")
            return out
        out.append(atomic_write(Path(folder) / f"{base}.pdf", weasyprint.HTML(string=text).write_pdf()))
    return out
