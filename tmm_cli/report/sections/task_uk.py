"""Ukrainian names of the task file's parameters and word values for the 'task' section
(the same keys as the English and Russian tables of :mod:`tmm_cli.report.sections.task`)."""
from __future__ import annotations

PARAMS_UK = {
    "drive.link": "вхідна ланка", "drive.speed": "кутова швидкість ω₁", "drive.direction": "напрямок обертання",
    "drive.cycle": "цикл", "positions.count": "кількість положень", "positions.zero": "нульове положення",
    "positions.output": "вихідна ланка", "positions.working": "робочий хід",
    "positions.extra": "додаткові кути кривошипа", "loads.gravity": "сили тяжіння ланок",
    "loads.forces.on": "ланка", "loads.forces.kind": "вид", "loads.forces.stroke": "хід",
    "loads.forces.diagram.s": "діаграма: s/H", "loads.forces.diagram.phi": "діаграма: φ",
    "loads.forces.diagram.value": "діаграма: значення", "loads.forces.at": "точка прикладання",
    "loads.forces.area": "площа поршня", "loads.forces.magnitude": "величина",
    "loads.forces.direction": "напрямок", "loads.forces.moment": "момент пари",
    "kinetostatics.positions": "положення", "kinetostatics.inertia": "сили інерції",
    "kinetostatics.balance": "ланка зведення", "kinetostatics.motion": "рух кривошипа",
    "kinetostatics.friction.f": "коефіцієнт тертя f",
    "kinetostatics.friction.f_pin": "коефіцієнт тертя в обертальних парах f_pin",
    "kinetostatics.friction.f_slide": "коефіцієнт тертя в поступальних парах f_slide",
    "kinetostatics.friction.pin_radius": "радіус цапфи",
    "flywheel.delta": "коефіцієнт нерівномірності ходу δ", "flywheel.constant": "сталий момент",
    "flywheel.method": "метод", "flywheel.resolution": "точок на цикл", "flywheel.shape.type": "форма маховика",
    "flywheel.shape.density": "густина ρ", "flywheel.shape.width_ratio": "відношення b/D",
    "flywheel.reduced_J": "дод. зведений момент інерції",
    "cam.follower": "штовхач", "cam.stroke": "хід h", "cam.rocker_length": "довжина коромисла",
    "cam.offset": "ексцентриситет e", "cam.phases.rise": "фаза віддалення φ_в",
    "cam.phases.far_dwell": "дальнє стояння", "cam.phases.return": "фаза повернення φ_п",
    "cam.phases.near_dwell": "ближнє стояння", "cam.laws.rise": "закон віддалення",
    "cam.laws.return": "закон повернення", "cam.pressure_angle.rise": "допустимий кут тиску, віддалення",
    "cam.pressure_angle.return": "допустимий кут тиску, повернення",
    "cam.swing": "поворот коромисла на фазі віддалення", "cam.roller": "радіус ролика",
    "cam.rotation": "обертання кулачка", "cam.speed": "кутова швидкість кулачка",
    "cam.r0": "радіус початкової шайби r0", "cam.center_distance": "міжосьова відстань кулачок-коромисло",
    "cam.rho_min_allowed": "допустимий найменший радіус кривини",
    "cam.divisions": "кількість частин фази в таблиці",
    "gears.m": "модуль m", "gears.z": "числа зубів z₁; z₂", "gears.x": "коефіцієнти зміщення x₁; x₂",
    "gears.alpha": "кут профілю α", "gears.ha": "коефіцієнт висоти головки h*a",
    "gears.c": "коефіцієнт радіального зазору c*", "gears.rule": "правило вибору зміщень",
    "gears.sa_min": "найменша товщина вершини s_a/m", "planetary.scheme": "схема",
    "planetary.ratio": "потрібне передатне відношення u₁H", "planetary.satellites": "кількість сателітів k",
    "planetary.tolerance": "допуск передатного відношення", "planetary.m": "модуль m",
    "planetary.z_min": "найменше число зубів", "planetary.z_max": "найбільше число зубів",
    "planetary.candidates": "кількість варіантів",
    "dof2.rotor.length": "довжина ротора l = OO₁", "dof2.rotor.mass": "маса ротора m₁",
    "dof2.rotor.com": "центр мас ротора OS₁", "dof2.rotor.J": "момент інерції ротора J_S1",
    "dof2.rotor.J_O": "момент інерції ротора J_O", "dof2.striker.length": "довжина ударника O₁M",
    "dof2.striker.com": "центр мас ударника l_c = O₁C", "dof2.striker.mass": "маса ударника m₂",
    "dof2.striker.J": "момент інерції ударника J_C", "dof2.gravity": "сили тяжіння",
    "dof2.drive.moment": "рушійний момент", "dof2.drive.speed": "підтримувана швидкість ротора ω₁",
    "dof2.drive.direction": "напрямок обертання", "dof2.initial.phi": "початковий кут φ₀",
    "dof2.initial.psi": "початковий кут ψ₀", "dof2.initial.omega": "початкова швидкість ω₀",
    "dof2.initial.psi_dot": "початкова швидкість dψ/dt", "dof2.t_end": "тривалість",
    "dof2.turns": "кількість обертів", "dof2.t_max": "найбільший час", "dof2.samples": "кількість точок",
    "dof2.impact.phi": "кут ротора в момент удару", "dof2.impact.stop": "зупинка при ударі",
    "synthesis.type": "тип", "synthesis.H": "хід H", "synthesis.psi": "кут розмаху коромисла ψ",
    "synthesis.K": "коефіцієнт зміни середньої швидкості K", "synthesis.theta": "кут θ",
    "synthesis.lambda": "λ = l_AB/l_OA", "synthesis.e": "дезаксіал e",
    "synthesis.gamma_min": "найменший кут передачі γ_min",
    "synthesis.rocker": "довжина коромисла (куліси)", "synthesis.frame": "стояк l_OO1",
    "synthesis.guide_height": "напрямна повзуна над O1",
    "drive.mean_output_speed": "середня швидкість вихідної ланки за цикл",
    "drive.working_stroke_speed": "середня швидкість вихідної ланки на робочому ході",
    "flywheel.quadrature": "кількість точок Гаусса — Лежандра на інтервал",
    "cam.pressure_angle": "допустимий кут тиску", "cam.transmission_angle": "найменший допустимий кут передачі",
    "cam.transmission_angle.rise": "найменший допустимий кут передачі, віддалення",
    "cam.transmission_angle.return": "найменший допустимий кут передачі, повернення",
    "gears.rho_f": "коефіцієнт радіуса перехідної кривої вихідного контуру ρ*_f",
    "loads.forces.working": "напрямок робочого ходу",
    "planetary.rank": "порядок варіантів",
    "planetary.z_min_external": "найменше число зубів колеса із зовнішніми зубами",
    "planetary.z_min_internal": "найменше число зубів колеса з внутрішніми зубами",
    "planetary.z_min_satellite_in_internal": "найменше число зубів сателіта у внутрішньому зачепленні",
    "planetary.internal_minus_external_min": "найменша різниця чисел зубів у внутрішньому зачепленні",
    "drive_train.motor_speed": "кутова швидкість двигуна ω_д",
    "drive_train.motor_direction": "напрямок обертання двигуна",
    "drive_train.ratio": "потрібне загальне передатне відношення",
    "drive_train.efficiency": "ККД приводу η",
    "drive_train.stages.type": "вид",
    "drive_train.stages.z": "числа зубів", "drive_train.stages.internal": "внутрішнє зачеплення",
    "drive_train.stages.scheme": "схема", "drive_train.stages.ratio": "передатне відношення",
}
LINK_WORDS_UK = {"mass": "маса", "J": "J_S", "com": "центр мас"}
ITEMS_UK = {"forces": "сила", "couples": "пара", "stages": "ступінь"}
WORDS_UK = {"ccw": "проти годинникової стрілки", "cw": "за годинниковою стрілкою", "true": "так", "false": "ні",
            "extreme": "крайнє положення", "forward": "прямий", "backward": "зворотний",
            "resistance": "опір", "driving": "рушійна", "working": "робочий", "idle": "холостий",
            "both": "обидва", "constant": "стале", "all": "усі", "disk": "диск", "rim": "обід",
            "energy-mass": "енергомас (Віттенбауер)", "merzalov": "Мерцалова", "auto": "авто",
            "rocker": "коромисло", "translating": "поступальний", "equal_sliding": "рівність питомих ковзань",
            "true_motion": "істинний", "linear_decreasing": "лінійно спадне прискорення",
            "parabolic": "параболічний", "poly345": "поліном 3-4-5", "cosine": "косинусоїдальний",
            "sine": "синусоїдальний", "uniform": "рівномірний",
            "flat": "тарілчастий", "knife": "загострений", "constant_velocity": "сталої швидкості",
            "trapezoidal": "трапецієподібний", "with": "за обертанням кулачка", "against": "проти обертання кулачка",
            "size": "за габаритом", "ratio_error": "за відхиленням передатного відношення",
            "pair": "зубчаста пара", "planetary": "планетарна", "exact": "точний", "no_undercut": "без підрізання",
            "table": "за таблицею", "slider_crank": "кривошипно-повзунний",
            "offset_slider_crank": "дезаксіальний кривошипно-повзунний", "crank_rocker": "кривошипно-коромисловий",
            "slotted_lever": "кулісний", "shaper": "кулісний (поперечно-стругальний верстат)",
            # words agreeing with their label's noun: рух, момент, вид (masculine)
            "kinetostatics.motion=constant": "рівномірний", "flywheel.constant=driving": "рушійний",
            "flywheel.constant=resistance": "опору", "drive_train.stages.type=planetary": "планетарний"}


def add_uk(params: dict, items: dict, words: dict, units: dict) -> None:
    """Add the Ukrainian tables beside the Russian ones (units as in Russian: м, кг, рад/с, Н)."""
    params["uk"] = dict(PARAMS_UK)
    for k in params["ru"]:
        if k.startswith("synthesis.links."):
            name, what = k.split(".")[2:4]
            params["uk"][k] = f"{name}: {LINK_WORDS_UK[what]}"
    items["uk"] = dict(ITEMS_UK)
    words["uk"] = dict(WORDS_UK)
    units["uk"] = dict(units["ru"])
