"""The language mechanism (plclab/i18n.py, ADR 0063): how the language is chosen, the English
fallback, templates with parameters, decimal commas only in prose."""

import pytest

from plclab import i18n
from plclab.errors import Diagnostic, Location, PlcError


@pytest.fixture
def env(monkeypatch):
    for var in ("PLCLAB_LANG", "LC_ALL", "LC_MESSAGES", "LANG"):
        monkeypatch.delenv(var, raising=False)
    i18n.set_language(None)
    yield monkeypatch
    i18n.set_language(None)


def test_lang_option_wins_over_environment_and_locale(env):
    env.setenv("PLCLAB_LANG", "en")
    env.setenv("LANG", "en_US.UTF-8")
    i18n.set_language("ru")
    assert i18n.language() == "ru"


def test_plclab_lang_wins_over_locale(env):
    env.setenv("LC_ALL", "en_GB.UTF-8")
    env.setenv("PLCLAB_LANG", "ru")
    assert i18n.language() == "ru"


@pytest.mark.parametrize("var", ["LC_ALL", "LC_MESSAGES", "LANG"])
def test_locale_chooses_when_nothing_else_does(env, var):
    env.setenv(var, "ru_RU.UTF-8")
    assert i18n.language() == "ru"


def test_lc_all_hides_lang_and_an_unknown_language_is_english(env):
    env.setenv("LC_ALL", "de_DE.UTF-8")
    env.setenv("LANG", "ru_RU.UTF-8")
    assert i18n.language() == "en"
    env.setenv("PLCLAB_LANG", "xx")  # ignored: the locale decides
    i18n.set_language(None)
    assert i18n.language() == "en"


def test_no_locale_is_english(env):
    env.setenv("LANG", "C.UTF-8")
    assert i18n.language() == "en"


def test_unknown_lang_option_is_refused(env):
    with pytest.raises(ValueError, match="en, ru"):
        i18n.set_language("de")


def test_english_reads_no_translation_file(env, monkeypatch):
    i18n.catalogue.cache_clear()
    i18n.set_language("en")
    d = Diagnostic("PLC0113", "FOR step BY 0 never ends; use a step other than 0",
                   Location("a.st", 3, 1))
    assert d.render() == str(d)
    assert i18n.catalogue.cache_info().currsize == 0


def test_a_diagnostic_in_russian_keeps_code_location_and_identifiers(env):
    i18n.set_language("ru")
    d = Diagnostic("PLC0113", "do not assign the FOR variable Counter_1 inside the loop; use a "
                   "WHILE loop or EXIT instead", Location("main.st", 7, 5))
    text = d.render()
    assert text.startswith("main.st:7:5: ошибка PLC0113: ")
    assert "Counter_1" in text and "WHILE" in text and "EXIT" in text
    assert "do not assign" not in text
    assert str(d).startswith("main.st:7:5: error PLC0113: do not assign")  # str() stays English


def test_a_message_no_template_matches_gets_the_russian_title_and_the_english_text(env):
    i18n.set_language("ru")
    e = PlcError("PLC0113", "something new about FOR x", Location("m.st", 1, 2))
    assert e.render() == "m.st:1:2: ошибка PLC0113: неправильный цикл FOR: something new about FOR x"


def test_a_code_without_russian_text_stays_english(env, monkeypatch):
    i18n.set_language("ru")
    monkeypatch.setitem(i18n.catalogue("ru", "problems"), "PLC0113", {})
    e = PlcError("PLC0113", "FOR step BY 0 never ends; use a step other than 0")
    assert e.render() == "ошибка PLC0113: FOR step BY 0 never ends; use a step other than 0"


def test_student_text_in_a_parameter_is_made_printable(env):
    i18n.set_language("ru")
    d = Diagnostic("PLC0113", "the FOR variable must be an integer, not \x1b[2KREAL")
    assert "\x1b" not in d.render() and "\\x1b" in d.render()


def test_templates_capture_parameters_and_repeat_them():
    templates = [{"en": "{a} is {b} but {a}", "ru": "{b}: {a}"}]
    assert i18n.translate_by_templates("x is 1.5 but x", templates, "ru") == "1.5: x"
    assert i18n.translate_by_templates("x is 1 but y", templates, "ru") is None


def test_a_translation_with_an_unknown_placeholder_falls_back(env):
    templates = [{"en": "{a} is bad", "ru": "{b} плохо"}, {"en": "{a} is bad", "ru": "{a} — плохо"}]
    assert i18n.translate_by_templates("x is bad", templates, "ru") == "x — плохо"


def test_decimal_comma_in_prose_never_in_st():
    assert i18n.decimal("at t = 12.50 s", "ru") == "at t = 12,50 s"
    assert i18n.decimal("`LEVEL >= 1.45` after 2.5 s", "ru") == "`LEVEL >= 1.45` after 2,5 s"
    assert i18n.decimal("T#1.5s and 16#FF and 1.0E3", "ru") == "T#1.5s and 16#FF and 1.0E3"
    assert i18n.decimal("at t = 12.50 s", "en") == "at t = 12.50 s"
    assert i18n.duration("1 min 2.5 s", "ru") == "1 мин 2,5 с"
    assert i18n.fill("{t:num} of {n}", {"t": 0.25, "n": "3.5"}, "ru") == "0,25 of 3.5"


def test_tr_falls_back_to_english_and_formats(env):
    i18n.set_language("ru")
    assert i18n.tr("{passed} passed, {failed} failed", passed=2, failed=0) == \
        "пройдено: 2, не пройдено: 0"
    assert i18n.tr("a text nobody translated {x}", x=1) == "a text nobody translated 1"


def test_localize_line_translates_a_rendered_english_diagnostic(env):
    i18n.set_language("ru")
    line = "s.st:3:1: error PLC0113: FOR step BY 0 never ends; use a step other than 0"
    assert i18n.localize_line(line).startswith("s.st:3:1: ошибка PLC0113: цикл FOR с шагом BY 0")
    assert i18n.localize_line("not a diagnostic") == "not a diagnostic"


def test_import_plclab_reads_no_translation(tmp_path):
    import subprocess
    import sys

    code = ("import sys, plclab, plclab.errors, plclab.problems; a = 'plclab.i18n' in sys.modules;"
            "import plclab.i18n as i; i.language();"
            "print(a, i.catalogue.cache_info().currsize)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, cwd=tmp_path, env={**__import__("os").environ,
                                                       "PLCLAB_LANG": "ru"})
    assert out.stdout.split() == ["False", "0"]
