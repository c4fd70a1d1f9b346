"""Nothing is missing in a shipped language (ADR 0063): every code of plclab/problems.toml has a
Russian title and explanation, every tr() text of plclab a Russian one, every lab criterion a
Russian name; every Russian template keeps the English placeholders. Each check also runs on a
broken copy, which it must catch."""

import tomllib
from pathlib import Path

import pytest

from plclab import i18n, i18n_check
from plclab.grade.feedback import STATUS_WORDS
from plclab.grade.lab import LEVELS
from plclab.problems import catalogue

ROOT = Path(__file__).resolve().parents[2]
SHIPPED = [lang for lang in i18n.LANGUAGES if lang != i18n.SOURCE]
LABS = sorted(p.parent for p in (ROOT / "labs").glob("*/lab.toml"))


def load(lang, name):
    with open(i18n_check.locale_file(lang, name), "rb") as fh:
        return tomllib.load(fh)


@pytest.mark.parametrize("lang", SHIPPED)
def test_every_code_has_a_title_and_an_explanation(lang):
    english = {c: {"no_example": p.no_example, "reserved_why": p.reserved_why}
               for c, p in catalogue().items()}
    missing = i18n_check.missing_problems(list(catalogue()), load(lang, "problems"), lang,
                                          english)
    assert not missing, "\n".join(missing)


@pytest.mark.parametrize("lang", SHIPPED)
def test_the_translation_names_no_code_the_catalogue_lacks(lang):
    extra = sorted(set(load(lang, "problems")) - set(catalogue()))
    assert not extra, f"plclab/locale/{lang}/problems.toml has codes plclab does not: {extra}"


def test_a_code_added_without_russian_is_named_with_where_to_add_it():
    problems = load("ru", "problems")
    codes = [*catalogue(), "PLC9302"]
    problems = {k: v for k, v in problems.items() if k != "PLC0100"}
    problems["PLC0101"] = {"title": "повторное объявление", "explanation": "  "}
    problems["PLC0191"] = {k: v for k, v in problems["PLC0191"].items() if k != "no_example"}
    english = {"PLC0191": {"no_example": "a safety net"}}
    missing = i18n_check.missing_problems(codes, problems, "ru", english)
    assert len(missing) == 4
    assert any(m.startswith("PLC0191: no no_example") for m in missing)
    missing = [m for m in missing if not m.startswith("PLC0191")]
    assert missing[0].startswith("PLC0100: no title and no explanation in "
                                 "plclab/locale/ru/problems.toml")
    assert missing[1].startswith("PLC0101: no explanation")
    assert missing[2].startswith("PLC9302:") and "[PLC9302]" in missing[2]


@pytest.mark.parametrize("lang", SHIPPED)
def test_every_text_of_the_command_line_and_the_feedback_is_translated(lang):
    keys = i18n_check.tr_keys()
    keys.update({w: "plclab/grade/feedback.py STATUS_WORDS" for w in STATUS_WORDS.values()})
    keys.update({w: "plclab/i18n.py severity()" for w in i18n_check.STATUS_AND_SEVERITY})
    keys.update({w: "plclab/grade/lab.py LEVELS" for w in LEVELS.values()})
    assert len(keys) > 40  # the scan found the tr() calls
    missing = i18n_check.missing_ui(keys, load(lang, "ui"), lang)
    assert not missing, "\n".join(missing)


def test_a_tr_text_without_russian_is_found():
    keys = {"{n} passed": "plclab/x.py:1", "new line {x}": "plclab/y.py:7"}
    missing = i18n_check.missing_ui(keys, {"{n} passed": "пройдено: {n}"}, "ru")
    assert missing == ["plclab/y.py:7: tr('new line {x}') has no text in "
                       "plclab/locale/ru/ui.toml"]


@pytest.mark.parametrize("lang", SHIPPED)
def test_every_template_keeps_the_english_placeholders(lang):
    pairs = i18n_check.catalogue_pairs(load(lang, "problems"), load(lang, "ui"), lang)
    assert len(pairs) > 50
    bad = i18n_check.placeholder_problems(pairs)
    assert not bad, "\n".join(bad)


def test_the_placeholder_check_catches_dropped_renamed_and_broken_placeholders():
    problems = {"PLC0113": {"messages": [
        {"en": "the FOR variable must be an integer, not {vt}", "ru": "нужно целое"},
        {"en": "do not assign {name}", "ru": "не присваивайте {nom}"}]}}
    ui = {"{n} passed": "пройдено: {n", "usage: ": "использование: ",
          "argument %(argument_name)s: %(message)s": "аргумент: %(message)s"}
    bad = i18n_check.placeholder_problems(i18n_check.catalogue_pairs(problems, ui, "ru"))
    assert len(bad) == 4, bad
    assert "messages[0]" in bad[0] and "{vt}" in bad[0]
    assert "{nom}" in bad[1] and "{name}" in bad[1]
    assert "not a valid template" in bad[2]
    assert "{argument_name}" in bad[3]


@pytest.mark.parametrize("lang", SHIPPED)
@pytest.mark.parametrize("lab", LABS, ids=lambda p: p.name)
def test_every_lab_has_its_title_criteria_hints_and_scenarios(lang, lab):
    missing = i18n_check.missing_lab_texts(lab, lang)
    assert not missing, "\n".join(missing)


def test_a_lab_criterion_without_a_name_or_a_stale_one_is_found(tmp_path):
    lab = tmp_path / "labs" / "demo"
    lab.mkdir(parents=True)
    (lab / "lab.toml").write_text(
        '[[scenario]]\nname = "normal"\ndescription = "a tank"\n'
        '[[criterion]]\nname = "pump starts"\nhint = "think"\n'
        '[[criterion]]\nname = "no overflow"\n', encoding="utf-8")
    (lab / "lab.ru.toml").write_text('title = "Бак"\n[criteria."pump starts"]\n'
                                     'name = "насос включается"\n'
                                     '[criteria."old name"]\nname = "старое"\n', encoding="utf-8")
    missing = i18n_check.missing_lab_texts(lab, "ru")
    assert len(missing) == 4, missing
    assert "'pump starts' has no hint in labs/demo/lab.ru.toml" in missing[0]
    assert "'no overflow' has no name in labs/demo/lab.ru.toml" in missing[1]
    assert "scenario 'normal' has no description" in missing[2]
    assert "'old name'" in missing[3] and "does not have" in missing[3]


@pytest.mark.parametrize("lang", SHIPPED)
def test_every_lab_text_file_parses_and_keeps_placeholders_out(lang):
    for lab in LABS:
        path = lab / f"lab.{lang}.toml"
        if path.is_file():
            data = tomllib.loads(path.read_text(encoding="utf-8"))
            for name, entry in data.get("criteria", {}).items():
                assert set(entry) <= {"name", "message", "hint", "hint_fix", "description"}, \
                    f"{path}: [criteria.{name!r}] has unknown keys"


def test_the_student_copy_keeps_only_the_texts_of_what_students_see(tmp_path):
    from plclab.grade.courseware import copy_student_lab

    dropped = 0
    for lab in LABS:
        dest = copy_student_lab(lab, tmp_path / lab.name)
        student = tomllib.loads((dest / "lab.toml").read_text(encoding="utf-8"))
        texts = tomllib.loads((dest / "lab.ru.toml").read_text(encoding="utf-8"))
        full = tomllib.loads((lab / "lab.ru.toml").read_text(encoding="utf-8"))
        names = {c["name"] for c in student["criterion"]}
        assert set(texts["criteria"]) == names, lab.name
        assert set(texts.get("scenarios", {})) <= {s["name"] for s in student["scenario"]}
        assert texts["title"] == full["title"]
        for name in names:
            assert texts["criteria"][name] == full["criteria"][name]
        dropped += len(full["criteria"]) - len(names)
    assert dropped > 0  # some lab has criteria only its hidden scenarios check


@pytest.mark.parametrize("lang", SHIPPED)
def test_every_help_text_of_every_command_is_translated(lang):
    from plclab.cli import build_parser

    helps = i18n_check.parser_helps(build_parser("all"))
    assert len(helps) > 150 and "print errors only" in helps
    missing = i18n_check.missing_help(helps, load(lang, "ui"), lang)
    assert not missing, "\n".join(missing)


def test_a_help_text_without_russian_is_found():
    import argparse

    p = argparse.ArgumentParser(description="a tool")
    sub = p.add_subparsers()
    s = sub.add_parser("go", help="go somewhere")
    s.add_argument("--far", help="how far (new)")
    missing = i18n_check.missing_help(i18n_check.parser_helps(p),
                                      {"a tool": "инструмент", "go somewhere": "идти",
                                       "show this help message and exit": "справка"}, "ru")
    assert missing == ["plclab go --help: 'how far (new)' has no text in "
                       "plclab/locale/ru/ui.toml (add it under 'command-line help')"]
