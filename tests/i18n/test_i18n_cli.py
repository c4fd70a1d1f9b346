"""The done-when lines of issue 38's message part: `plclab --lang ru check`, `plclab explain
PLC0113 --lang ru`, `plclab --lang ru test` and `plclab --lang ru lab check` speak Russian, and
codes, identifiers, IEC keywords and ST text stay as they are."""

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

from plclab import i18n
from plclab.cli import main
from plclab.problems import catalogue

ROOT = Path(__file__).resolve().parents[2]
CYRILLIC = re.compile("[а-яё]", re.IGNORECASE)

FOR_BODY = """PROGRAM Main
VAR
    Counter_7 : INT;
    total : INT;
END_VAR
FOR Counter_7 := 1 TO 10 DO
    Counter_7 := Counter_7 + 1;
    total := total + Counter_7;
END_FOR;
totl := 1;
END_PROGRAM
"""


@pytest.fixture(autouse=True)
def english_after():
    yield
    assert i18n.chosen() is None  # main() leaves no language behind


@pytest.fixture
def bad(tmp_path):
    path = tmp_path / "main.st"
    path.write_text(FOR_BODY, encoding="utf-8")
    return path


def test_check_speaks_russian_and_keeps_codes_locations_and_names(bad, capsys):
    assert main(["--lang", "ru", "check", str(bad)]) == 1
    out = capsys.readouterr().out
    assert f"{bad}:7:5: ошибка PLC0113: не присваивайте значение переменной цикла FOR " \
           "COUNTER_7 внутри цикла; используйте цикл WHILE или EXIT" in out
    assert f"{bad}:10:1: ошибка PLC0100: totl не объявлено; может быть, имелось в виду TOTAL?" \
        in out
    assert "ошибок: 2, предупреждений: 0" in out
    assert "error" not in out and "do not assign" not in out


def test_check_in_english_by_default_and_the_option_after_the_command(bad, capsys):
    assert main(["check", str(bad)]) == 1
    english = capsys.readouterr().out
    assert "error PLC0113: do not assign the FOR variable COUNTER_7" in english
    assert not CYRILLIC.search(english)
    assert main(["check", str(bad), "--lang=ru"]) == 1
    assert "ошибка PLC0113" in capsys.readouterr().out


def test_plclab_lang_in_the_environment(bad):
    env = {**os.environ, "PLCLAB_LANG": "ru", "PYTHONPATH": str(ROOT)}
    out = subprocess.run([sys.executable, "-m", "plclab", "check", str(bad)], env=env,
                         capture_output=True, text=True, cwd=bad.parent)
    assert out.returncode == 1
    assert "ошибка PLC0113" in out.stdout and "ошибок: 2" in out.stdout
    env["PLCLAB_LANG"] = "en"
    env["LC_ALL"] = "ru_RU.UTF-8"
    out = subprocess.run([sys.executable, "-m", "plclab", "check", str(bad)], env=env,
                         capture_output=True, text=True, cwd=bad.parent)
    assert "error PLC0113" in out.stdout  # PLCLAB_LANG wins over the locale


def test_explain_speaks_russian_and_keeps_the_st_examples(capsys):
    assert main(["explain", "PLC0113", "--lang", "ru"]) == 0
    ru = capsys.readouterr().out
    assert main(["explain", "PLC0113"]) == 0
    en = capsys.readouterr().out
    assert ru.startswith("PLC0113: неправильный цикл FOR\n")
    assert "Неправильно (ST):" in ru and "Исправление:" in ru
    p = catalogue()["PLC0113"]
    for program in (p.wrong, p.fix):  # the ST text is the same, line for line
        for line in program.strip().splitlines():
            assert line in ru and line in en
    assert "bad FOR loop" not in ru and "bad FOR loop" in en


def test_explain_of_a_runtime_code_and_the_list(capsys):
    assert main(["--lang", "ru", "explain", "PLC2003"]) == 0
    out = capsys.readouterr().out
    assert "сторожевой таймер" in out and "(выполните 1 цикл сканирования: plclab run" in out
    assert main(["--lang", "ru", "explain", "--list"]) == 0
    listing = capsys.readouterr().out.splitlines()
    assert len(listing) == len(catalogue())
    assert all(CYRILLIC.search(line) for line in listing)


def test_unknown_code_and_unknown_language(capsys):
    assert main(["--lang", "ru", "explain", "PLC0133x"]) == 1
    assert "ошибка PLC3002: PLC0133x — не диагностический код plclab" in capsys.readouterr().err
    assert main(["--lang", "de", "check", "x.st"]) == 1
    err = capsys.readouterr().err
    assert err.startswith("error PLC9300: --lang de: plclab speaks en, ru")


def test_test_blocks_in_russian(tmp_path, capsys):
    f = tmp_path / "t.st"
    f.write_text("TEST 'ok' ASSERT_EQ(1 + 1, 2); END_TEST\n"
                 "TEST 'Bad_Sum' VAR x : INT := 3; END_VAR ASSERT_EQ(x, 4); END_TEST\n"
                 "TEST 'div' VAR a : INT; END_VAR a := 10 / a; END_TEST\n", encoding="utf-8")
    assert main(["--lang", "ru", "test", str(f), "-v"]) == 1
    out = capsys.readouterr().out
    assert "ПРОЙДЕН ok" in out
    assert re.search(r"t\.st:2:\d+: НЕ ПРОЙДЕН Bad_Sum: ожидалось равенство, но 3 <> 4 \(в .*x", out)
    assert "НЕ ПРОЙДЕН div: целочисленное деление на ноль" in out
    assert "пройдено: 1, не пройдено: 2" in out


def test_help_in_russian(capsys):
    with pytest.raises(SystemExit):
        main(["--lang", "ru", "explain", "--help"])
    out = capsys.readouterr().out
    assert out.startswith("использование: plclab explain")
    assert "показать эту справку и выйти" in out and "--list" in out
    with pytest.raises(SystemExit):
        main(["explain", "--help"])
    assert capsys.readouterr().out.startswith("usage: plclab explain")


@pytest.mark.slow
def test_lab_check_speaks_russian(capsys):
    starter = ROOT / "labs" / "tank-two-position" / "starter.st"
    assert main(["--lang", "ru", "lab", "check", "tank-two-position", str(starter),
                 "--no-media"]) == 0
    out = capsys.readouterr().out
    assert "предупреждение PLC0216: в PROGRAM TankLevel нет операторов" in out
    assert "# Бак: двухпозиционное регулирование уровня по LS1 и LS2" in out
    assert "| НЕТ | насос включается ниже LS1 | 0/1 | насос не включается, когда уровень " \
           "ниже LS1: " in out
    assert "## Сценарий `normal` — почти пустой бак" in out  # the scenario's name stays
    assert "Подсказка: Датчик уровня выдаёт TRUE" in out
    assert "`not LS1`" in out and "`PUMP`" in out  # conditions stay ST, with their points
    assert re.search(r"t = \d+,\d\d с", out)  # decimal comma in prose
    assert re.search(r"баллы: 0/\d+", out)
    assert "pump starts below LS1" not in out and "Hint:" not in out and "Score" not in out


def test_top_level_help_in_russian(capsys):
    with pytest.raises(SystemExit):
        main(["--lang", "ru", "--help"])
    out = capsys.readouterr().out
    assert "проверить исходные файлы и вывести диагностику" in out
    assert "--lang LANG" in out and "check" in out and "lab" in out
