"""The Russian and Ukrainian catalogues use the course's terms, the same ones as the report's
tables: Ukrainian 'число зубів' (not 'зубців'), 'положення центра обертання кулачка' for the
cam centre sought in synthesis; and no message leaves a stage's limit in words a student
cannot act on (a 'time exceeded' without the word for a limit)."""
from __future__ import annotations

from tmm_cli.messages import catalogue


def _texts(lang):
    return catalogue(lang)["messages"]


def test_uk_number_of_teeth_as_in_the_report():
    bad = {k: v for k, v in _texts("uk").items() if "зубц" in v}
    assert not bad, bad


def test_cam_centre_named_as_the_axis_position():
    for lang, word in (("ru", "положение центра вращения кулачка"), ("uk", "положення центра обертання кулачка")):
        for code in ("cam.fail.no_region", "cam.fail.no_region_either", "cam.fail.pressure_exceeded"):
            assert word in _texts(lang)[code], (lang, code)


def test_uk_stage_is_masculine():
    """'ступінь' (a stage of a gear train) is masculine in Ukrainian: 'його z', 'його частка'."""
    t = _texts("uk")
    assert "його z" in t["drive_train.fail.pair_zmin"] and "її z" not in t["drive_train.fail.pair_zmin"]
    assert "його частка" in t["drive_train.fail.below_one"]


def test_every_stage_has_a_name():
    """A failure box and the batch summary name the failed stage in words ('Этап «кинематический
    анализ» не выполнен'), never by its identifier: every stage a StageError names is in the
    `stage` table of each catalogue."""
    import re
    from pathlib import Path

    from tmm_cli.report import failure
    root = Path(__file__).resolve().parents[1] / "tmm_cli"
    stages = set(failure.STAGES)
    for path in root.rglob("*.py"):
        text = path.read_text(encoding="utf-8")
        stages |= set(re.findall(r'StageError\(\s*"([a-z_0-9]+)"', text))
        stages |= set(re.findall(r'^STAGE\s*=\s*"([a-z_0-9]+)"', text, re.M))
    assert {"kinematics", "cam", "drive_train", "synthesis"} <= stages
    for lang in ("ru", "uk"):
        names = catalogue(lang)["terms"]["stage"]
        assert stages <= set(names), (lang, sorted(stages - set(names)))
        assert failure.stage_name("kinematics", lang) != "kinematics"
    assert failure.stage_name("kinematics", "en") == "kinematics"


def test_uk_drive_is_privid():
    """Ukrainian 'привід', genitive 'приводу' (the Russian forms 'привод', 'привода' are not Ukrainian)."""
    import re

    from tmm_cli import feedback
    from tmm_cli.report import i18n, sections
    from tmm_cli.report.sections import task as task_section
    for _name, _ in sections.available():
        pass
    texts = list(i18n.STRINGS["uk"].values()) + list(_texts("uk").values()) + \
        list(task_section.PARAMS["uk"].values()) + [t for v in feedback.STEPS["uk"].values() for t in v.values()]
    bad = [t for t in texts if re.search(r"\b[Пп]ривода?\b", t)]
    assert not bad, bad


def test_cam_phases_named_as_the_course_does():
    """The cam's phases are удаление / возвращение (віддалення / повернення) everywhere in the
    report, as in the task data and the messages — not подъём / опускание (підйом / опускання)."""
    from tmm_cli.report import i18n, sections
    for _name, _ in sections.available():
        pass
    for lang, bad in (("ru", ("подъём", "опускани")), ("uk", ("підйом", "опускан"))):
        found = {k: v for k, v in i18n.STRINGS[lang].items() if k.startswith("cam.") and any(b in v for b in bad)}
        assert not found, (lang, found)


def test_shift_rule_in_the_same_words_as_the_messages():
    """The task data names the shift rule as the messages do: равенство удельных скольжений."""
    from tmm_cli.report.sections import task as task_section
    for lang in ("ru", "uk"):
        assert task_section.WORDS[lang]["equal_sliding"] == catalogue(lang)["terms"]["shift_rule"]["equal_sliding"]


def test_batch_angle_as_in_the_failure_box():
    """The summary's 'at crank angle' reads as the report's failure box: φ = 30.5°."""
    from tmm_cli.messages import render
    assert render("batch.at_angle", {"angle": 30.5}, "ru") == " при угле кривошипа φ = 30,5°"
    assert render("batch.at_angle", {"angle": 30.5}, "uk") == " за кута кривошипа φ = 30,5°"
