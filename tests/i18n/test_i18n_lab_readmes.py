"""Every lab has its task in Russian, ``labs/<lab>/README.ru.md``, with the structure of its
``README.md`` (issue 38): the same headings (count and levels), the same code blocks
(byte-identical), the same links (a Russian chapter ``chapter.ru.md`` stands for its English
``chapter.md``), the same rows of the generated I/O and criteria tables (names, addresses,
types), the tables in step with ``lab.toml`` and ``lab.ru.toml``, no English sentence in its
prose and a decimal comma in it. ``plclab --lang ru lab show`` prints the Russian texts.
"""

import importlib.util
import re
import tomllib
from pathlib import Path

import pytest

from plclab import i18n
from plclab.cli import main
from plclab.grade.lab import load_lab
from plclab.grade.scaffold import (
    CRITERIA_END,
    CRITERIA_START,
    README_END,
    README_START,
    readme_table,
)
from plclab.i18n_check import english_runs
from plclab.i18n_labs import criteria_table_markdown, io_table_markdown

ROOT = Path(__file__).resolve().parents[2]
LABS = sorted(p.parent for p in (ROOT / "labs").glob("*/lab.toml"))

_spec = importlib.util.spec_from_file_location(
    "course_ru_structure", ROOT / "tests" / "course" / "test_course_ru_structure.py")
_course = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(_course)
md_differences = _course.md_differences
prose_decimal_points = _course.prose_decimal_points

_LINK = re.compile(r"(?<!!)\[[^\]]*\]\(([^)\s]+)\)")
_FENCED = re.compile(r"^(`{3,}).*?^\1", re.S | re.M)
_COMMENT = re.compile(r"<!--.*?-->", re.S)


def links(text: str) -> list[str]:
    """Link targets, in order, outside code blocks (``x.ru.md`` counted as ``x.md``)."""
    return [t.replace(".ru.md", ".md") for t in _LINK.findall(_FENCED.sub("", text))]


def table_rows(block: str | None, columns: int) -> list[tuple[str, ...]]:
    """The first ``columns`` cells of each row of a generated table (the header left out)."""
    if block is None:
        return []
    rows = [r for r in block.strip().splitlines()[2:] if r.startswith("|")]
    return [tuple(c.strip() for c in r.strip("|").split(" | ")[:columns]) for r in rows]


def readme_differences(en: str, ru: str) -> list[str]:
    """What differs in structure between a lab's README.md and README.ru.md."""
    out = md_differences(en, ru)
    if links(en) != links(ru):
        out.append(f"links: {links(en)} in English, {links(ru)} in Russian")
    for start, end, cols, what in ((README_START, README_END, 3, "I/O table"),
                                   (CRITERIA_START, CRITERIA_END, 0, "criteria table")):
        a, b = readme_table(en, start, end), readme_table(ru, start, end)
        if (a is None) != (b is None):
            out.append(f"{what}: only in {'English' if b is None else 'Russian'}")
        elif cols and table_rows(a, cols) != table_rows(b, cols):
            out.append(f"{what}: rows {table_rows(a, cols)} in English, "
                       f"{table_rows(b, cols)} in Russian")
        elif len(table_rows(a, 1)) != len(table_rows(b, 1)):
            out.append(f"{what}: {len(table_rows(a, 1))} rows in English, "
                       f"{len(table_rows(b, 1))} in Russian")
    return out


def english_prose(text: str) -> list[str]:
    """Lines of a Russian text that still hold an English sentence (code blocks and the
    markers of the generated tables, HTML comments, left out)."""
    return [line for line in _COMMENT.sub("", _FENCED.sub("", text)).splitlines()
            if english_runs(line)]


@pytest.mark.parametrize("lab", LABS, ids=lambda p: p.name)
def test_the_russian_task_has_the_structure_of_the_english_one(lab):
    ru_path = lab / "README.ru.md"
    assert ru_path.is_file(), f"{lab.name}: write labs/{lab.name}/README.ru.md"
    en = (lab / "README.md").read_text(encoding="utf-8")
    ru = ru_path.read_text(encoding="utf-8")
    assert readme_differences(en, ru) == []
    assert re.search("[А-Яа-яЁё]", ru)
    assert english_prose(ru) == [], "English left in README.ru.md"
    assert prose_decimal_points(ru) == [], "a decimal point in Russian prose"
    spec = tomllib.loads((lab / "lab.toml").read_text(encoding="utf-8-sig"))
    if en.splitlines()[0] == f"# {spec['title']}":  # the title as lab list shows it
        texts = tomllib.loads((lab / "lab.ru.toml").read_text(encoding="utf-8"))
        assert ru.splitlines()[0] == f"# {texts['title']}"


@pytest.mark.parametrize("lab", LABS, ids=lambda p: p.name)
def test_the_generated_tables_of_the_russian_task_are_up_to_date(lab):
    ru = (lab / "README.ru.md").read_text(encoding="utf-8")
    spec = load_lab(str(lab))
    assert readme_table(ru) == io_table_markdown(spec, "ru"), \
        f"run: plclab lab show {lab.name} --update-readme"
    got = readme_table(ru, CRITERIA_START, CRITERIA_END)
    if got is not None:
        assert got == criteria_table_markdown(spec, "ru"), \
            f"run: plclab lab show {lab.name} --update-readme"
    assert english_prose(io_table_markdown(spec, "ru")) == []


@pytest.mark.parametrize("lab", LABS, ids=lambda p: p.name)
def test_lab_show_in_russian(capsys, lab):
    try:
        main(["--lang", "ru", "lab", "show", str(lab)])
    finally:
        i18n.set_language(None)
    out = capsys.readouterr().out
    assert "## Таблица входов и выходов" in out and "Цели работы:" in out
    assert "README.ru.md" in out
    left = [line for line in out.splitlines() if english_runs(line)]
    assert left == [], "English left in lab show:\n" + "\n".join(left)


def test_lab_show_takes_the_io_descriptions_from_lab_ru_toml(capsys):
    try:
        main(["--lang", "ru", "lab", "show", "motor-start-stop"])
    finally:
        i18n.set_language(None)
    out = capsys.readouterr().out
    assert "| `START` | `%IX0.0` | BOOL |  | кнопка «Пуск»" in out


def test_a_lab_without_its_russian_task_texts_is_named(tmp_path):
    from plclab.i18n_check import missing_lab_texts

    lab = tmp_path / "demo"
    lab.mkdir()
    (lab / "lab.toml").write_text(
        'summary = "a tank"\ngoals = ["one", "two"]\n'
        '[[io]]\nname = "LS1"\ndescription = "low switch"\n'
        '[[io]]\nname = "RAW"\nunit = "counts"\ndescription = "level"\n'
        '[[criterion]]\nname = "fills"\ndescription = "it fills"\n', encoding="utf-8")
    (lab / "lab.ru.toml").write_text(
        'title = "Бак"\ngoals = ["одна"]\n[criteria.fills]\nname = "наполняет"\n'
        '[io.RAW]\ndescription = "уровень"\n[io.OLD]\ndescription = "старый"\n',
        encoding="utf-8")
    missing = "\n".join(missing_lab_texts(lab, "ru"))
    for what in ("'fills' has no description", "no summary", "not the 2 goals",
                 "'LS1' has no description", "'RAW' has no unit", "I/O row 'OLD'"):
        assert what in missing, what


# ---- the checker catches what it must ----

EN = """# Lab

Read first: [chapter 3](../../course/03-discrete-io/chapter.md).

## I/O table

<!-- io-table:start (generated by `plclab lab show --update-readme`) -->
| Name | Address | Type | Unit | Description |
|---|---|---|---|---|
| `START` | `%IX0.0` | BOOL |  | start button |
| `K1` | `%QX0.0` | BOOL |  | contactor |
<!-- io-table:end -->

```
plclab lab check lab my.st
```
"""

RU = (EN.replace("Read first", "Сначала прочитайте").replace("chapter.md", "chapter.ru.md")
      .replace("start button", "кнопка пуска").replace("contactor", "контактор")
      .replace("I/O table", "Таблица входов и выходов"))


def test_the_checker_accepts_a_faithful_translation():
    assert readme_differences(EN, RU) == []


@pytest.mark.parametrize("broken, what", [
    (RU.replace("`%QX0.0`", "`%QX0.1`"), "I/O table"),
    (RU.replace("| `K1` | `%QX0.0` | BOOL |  | контактор |\n", ""), "I/O table"),
    (RU.replace("(../../course/03-discrete-io/chapter.ru.md)", "(../../course/03.md)"), "links"),
    (RU.replace("my.st", "my_motor.st"), "code block"),
    (RU.replace("## Таблица", "### Таблица"), "headings"),
])
def test_the_checker_catches(broken, what):
    assert any(what in d for d in readme_differences(EN, broken))


def test_english_prose_is_found_outside_code():
    assert english_prose(RU) == []
    assert english_prose(RU + "\nThe motor keeps running when START is released.\n")
    assert english_prose(RU + "\n```\nthe motor keeps running\n```\n") == []
