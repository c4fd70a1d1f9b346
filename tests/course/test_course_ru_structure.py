"""The Russian edition of the course keeps the structure of the English one (issue 38, ADR 0066).

A Russian chapter lives beside the English one: ``course/NN-slug/chapter.ru.md`` and
``quiz.ru.toml``. For every chapter that has a Russian file, this test compares it with the
English file: the same code blocks (byte-identical code, the same fence info), the same
figures (image paths in order), the same headings (count and levels); for quizzes the same
items in the same order with the same kind, answer key, choices count and every non-text
field (programs, steps, tolerances) identical. A change made to one edition and not the other
fails here. The edition is whole: every chapter has both Russian files
(``test_every_chapter_has_its_russian_edition``).
"""
from __future__ import annotations

import re
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
COURSE = ROOT / "course"
CHAPTERS = sorted(p for p in COURSE.iterdir() if p.is_dir() and re.match(r"^\d\d-", p.name))

_FENCE = re.compile(r"^(`{3,}|~{3,})(.*)$")
_IMAGE = re.compile(r"!\[[^\]]*\]\(([^)\s]+)")
_HEADING = re.compile(r"^(#{1,6})\s")

# Quiz fields written for the reader: these are translated; every other field is shared.
TEXT_FIELDS = {"question", "choices", "explain", "unit", "hint"}


def md_structure(text: str) -> dict[str, list]:
    """Code blocks (fence info, code), image paths and heading levels of a Markdown text.
    Images and headings inside code blocks do not count."""
    blocks: list[tuple[str, str]] = []
    images: list[str] = []
    headings: list[int] = []
    lines = text.splitlines()
    i = 0
    while i < len(lines):
        m = _FENCE.match(lines[i])
        if m:
            fence, info = m.group(1), m.group(2).strip()
            j = i + 1
            while j < len(lines) and not lines[j].startswith(fence):
                j += 1
            assert j < len(lines), f"line {i + 1}: code block never closed"
            blocks.append((info, "\n".join(lines[i + 1:j])))
            i = j + 1
            continue
        images += _IMAGE.findall(lines[i])
        h = _HEADING.match(lines[i])
        if h:
            headings.append(len(h.group(1)))
        i += 1
    return {"blocks": blocks, "images": images, "headings": headings}


def md_differences(en: str, ru: str) -> list[str]:
    """What differs in structure between an English and a Russian chapter (empty: they agree)."""
    a, b = md_structure(en), md_structure(ru)
    out: list[str] = []
    if len(a["blocks"]) != len(b["blocks"]):
        out.append(f"code blocks: {len(a['blocks'])} in English, {len(b['blocks'])} in Russian")
    for n, ((ia, ca), (ib, cb)) in enumerate(zip(a["blocks"], b["blocks"], strict=False), 1):
        if ia != ib:
            out.append(f"code block {n}: fence info {ia!r} in English, {ib!r} in Russian")
        if ca != cb:
            la, lb = ca.splitlines(), cb.splitlines()
            k = next((k for k, (x, y) in enumerate(zip(la, lb, strict=False)) if x != y),
                     min(len(la), len(lb)))
            out.append(f"code block {n} ({ia}): differs at its line {k + 1}")
    if a["images"] != b["images"]:
        out.append(f"figures: {a['images']} in English, {b['images']} in Russian")
    if a["headings"] != b["headings"]:
        out.append(f"headings (levels): {a['headings']} in English, {b['headings']} in Russian")
    return out


def quiz_differences(en: dict, ru: dict) -> list[str]:
    """What differs between an English and a Russian quiz, text fields aside."""
    ia, ib = en.get("item", []), ru.get("item", [])
    out: list[str] = []
    if [d.get("id") for d in ia] != [d.get("id") for d in ib]:
        out.append(f"items: {[d.get('id') for d in ia]} in English, "
                   f"{[d.get('id') for d in ib]} in Russian")
        return out
    for a, b in zip(ia, ib, strict=True):
        where = f"item {a.get('id')}"
        if set(a) != set(b):
            out.append(f"{where}: fields {sorted(set(a) ^ set(b))} only in one edition")
        if len(a.get("choices", [])) != len(b.get("choices", [])):
            out.append(f"{where}: {len(a.get('choices', []))} choices in English, "
                       f"{len(b.get('choices', []))} in Russian")
        for key in sorted((set(a) & set(b)) - TEXT_FIELDS):
            if a[key] != b[key]:
                out.append(f"{where}: {key} differs ({a[key]!r} in English, {b[key]!r} in Russian)")
        for key in sorted((set(a) & set(b)) & TEXT_FIELDS):
            if isinstance(a[key], str) and not b[key].strip():
                out.append(f"{where}: {key} is empty in Russian")
    return out


def _ru_chapters() -> list[Path]:
    return [c for c in CHAPTERS if (c / "chapter.ru.md").exists() or (c / "quiz.ru.toml").exists()]


@pytest.mark.parametrize("chapter", _ru_chapters(), ids=lambda p: p.name)
def test_ru_chapter_matches_english(chapter: Path) -> None:
    assert (chapter / "chapter.ru.md").exists(), f"{chapter.name}: quiz.ru.toml without chapter.ru.md"
    assert (chapter / "quiz.ru.toml").exists() or not (chapter / "quiz.toml").exists(), \
        f"{chapter.name}: chapter.ru.md without quiz.ru.toml"
    en = (chapter / "chapter.md").read_text(encoding="utf-8")
    ru = (chapter / "chapter.ru.md").read_text(encoding="utf-8")
    assert md_differences(en, ru) == []
    assert re.search("[А-Яа-яЁё]", ru), f"{chapter.name}: chapter.ru.md has no Russian text"


@pytest.mark.parametrize("chapter", [c for c in _ru_chapters() if (c / "quiz.ru.toml").exists()],
                         ids=lambda p: p.name)
def test_ru_quiz_matches_english(chapter: Path) -> None:
    with open(chapter / "quiz.toml", "rb") as fh:
        en = tomllib.load(fh)
    with open(chapter / "quiz.ru.toml", "rb") as fh:
        ru = tomllib.load(fh)
    assert quiz_differences(en, ru) == []
    for item in ru["item"]:
        for key in ("question", "explain"):
            assert re.search("[А-Яа-яЁё]", item[key]), f"{item['id']}: {key} is not in Russian"


def prose_decimal_points(text: str) -> list[str]:
    """Numbers written with a decimal point in the prose of a Russian text (code spans, code
    blocks and link targets left out: ST keeps its point)."""
    prose = re.sub(r"^(`{3,}).*?^\1", "", text, flags=re.S | re.M)
    prose = re.sub(r"`[^`]*`|\]\([^)]*\)", "", prose)
    return re.findall(r"(?<![\w.#/])\d+\.\d+(?![\w.])", prose)


def test_ru_prose_uses_decimal_comma() -> None:
    """Russian prose writes 2,5 and never 2.5."""
    for chapter in _ru_chapters():
        text = (chapter / "chapter.ru.md").read_text(encoding="utf-8")
        assert prose_decimal_points(text) == [], f"{chapter.name}: decimal point in prose"
    for chapter in [c for c in _ru_chapters() if (c / "quiz.ru.toml").exists()]:
        with open(chapter / "quiz.ru.toml", "rb") as fh:
            for item in tomllib.load(fh)["item"]:
                for key in ("question", "explain"):
                    assert prose_decimal_points(item[key]) == [], f"{chapter.name} {item['id']}"


def test_decimal_check_catches_a_point_and_spares_code() -> None:
    assert prose_decimal_points("давление 80.96 бар") == ["80.96"]
    assert prose_decimal_points("За 0.5 с.") == ["0.5"]
    assert prose_decimal_points("давление 80,96 бар, `x := 2.5;`, [a](../v1.2/x.md)") == []
    assert prose_decimal_points("```st\nx := 2.5;\n```\n") == []
    assert prose_decimal_points("IEC 61131-3, версия 3.0") == ["3.0"]


def test_every_chapter_has_its_russian_edition() -> None:
    """The Russian edition is whole (issue 38): a chapter added in English only fails here."""
    missing = [c.name for c in CHAPTERS
               if not ((c / "chapter.ru.md").exists() and (c / "quiz.ru.toml").exists())]
    assert len(CHAPTERS) >= 17
    assert not missing, ("chapters without chapter.ru.md and quiz.ru.toml (write them, "
                         "ADR 0066): " + ", ".join(missing))


# ---- the checker catches what it must (wrong inputs) ----

EN = """# Title

Text.

![A figure](figures/a.svg)

## Section

```st scans=1
PROGRAM P
VAR x : INT; END_VAR
x := x + 1;
END_PROGRAM
```

```console
plclab test p.st
```
"""

RU = EN.replace("Title", "Заголовок").replace("Text.", "Текст.").replace("A figure", "Рисунок") \
    .replace("Section", "Раздел")


def test_checker_accepts_a_faithful_translation() -> None:
    assert md_differences(EN, RU) == []


def test_checker_catches_a_missing_code_block() -> None:
    ru = RU.replace("```console\nplclab test p.st\n```\n", "")
    assert any("code blocks: 2 in English, 1 in Russian" in d for d in md_differences(EN, ru))


def test_checker_catches_a_changed_code_line() -> None:
    ru = RU.replace("x := x + 1;", "x := x + 2;")
    assert md_differences(EN, ru) == ["code block 1 (st scans=1): differs at its line 3"]


def test_checker_catches_a_translated_comment_in_code() -> None:
    en = EN.replace("x := x + 1;", "x := x + 1;  (* count *)")
    ru = RU.replace("x := x + 1;", "x := x + 1;  (* счёт *)")
    assert md_differences(en, ru)


def test_checker_catches_changed_fence_info() -> None:
    ru = RU.replace("```st scans=1", "```st")
    assert any("fence info" in d for d in md_differences(EN, ru))


def test_checker_catches_a_changed_or_missing_figure() -> None:
    assert md_differences(EN, RU.replace("figures/a.svg", "figures/b.svg"))
    assert md_differences(EN, RU.replace("![Рисунок](figures/a.svg)", ""))


def test_checker_catches_a_missing_heading() -> None:
    assert any("headings" in d for d in md_differences(EN, RU.replace("## Раздел", "Раздел")))


def test_checker_ignores_hashes_and_images_inside_code() -> None:
    en = EN + "\n```text\n# not a heading ![x](y.svg)\n```\n"
    ru = RU + "\n```text\n# not a heading ![x](y.svg)\n```\n"
    assert md_differences(en, ru) == []
    assert md_structure(en)["headings"] == [1, 2]


QEN = tomllib.loads('''
[[item]]
id = "a"
kind = "choice"
question = "Which?"
choices = ["one", "two", "three"]
answer = 2
explain = "Because."

[[item]]
id = "b"
kind = "numeric"
question = "How many?"
compute = "2.0 * 8.0"
answer = 16
tolerance = 0.5
unit = "ms"
explain = "Two cycles."
''')


def _qru(**changes) -> dict:
    import copy
    ru = copy.deepcopy(QEN)
    ru["item"][0].update(question="Какой?", choices=["один", "два", "три"], explain="Потому что.")
    ru["item"][1].update(question="Сколько?", unit="мс", explain="Два цикла.")
    for key, value in changes.items():
        n, field = key.split("__")
        ru["item"][int(n[1:])][field] = value
    return ru


def test_quiz_checker_accepts_a_faithful_translation() -> None:
    assert quiz_differences(QEN, _qru()) == []


def test_quiz_checker_catches_a_changed_key() -> None:
    assert quiz_differences(QEN, _qru(i0__answer=3)) == [
        "item a: answer differs (2 in English, 3 in Russian)"]
    assert quiz_differences(QEN, _qru(i1__tolerance=1.0))


def test_quiz_checker_catches_a_missing_choice_and_item() -> None:
    assert quiz_differences(QEN, _qru(i0__choices=["один", "два"]))
    ru = _qru()
    del ru["item"][1]
    assert quiz_differences(QEN, ru)
    ru = _qru()
    ru["item"].reverse()
    assert quiz_differences(QEN, ru)


def test_quiz_checker_catches_a_changed_program_field() -> None:
    assert quiz_differences(QEN, _qru(i1__compute="2.0 * 9.0"))
    ru = _qru()
    del ru["item"][1]["explain"]
    assert quiz_differences(QEN, ru)


def test_english_build_ignores_the_russian_files(tmp_path: Path) -> None:
    """`plclab course build` reads chapter.md and quiz.toml by name: the Russian files beside
    them change neither the chapter list nor the English output."""
    from plclab.course.build import build_chapter
    from plclab.course.model import chapters

    listed = chapters()
    assert [c.folder for c in listed] == [c for c in CHAPTERS if (c / "chapter.md").exists()]
    for chapter in [c for c in listed if (c.folder / "chapter.ru.md").exists()][:1]:
        build_chapter(chapter, tmp_path, figures=False)
        out = tmp_path / chapter.slug
        assert not list(out.rglob("*.ru.*"))
        assert (out / "chapter.md").read_text(encoding="utf-8") == \
            (chapter.folder / "chapter.md").read_text(encoding="utf-8")
        assert not re.search("[А-Яа-яЁё]", (out / "quiz.toml").read_text(encoding="utf-8"))


@pytest.mark.parametrize("chapter", [c for c in _ru_chapters() if (c / "quiz.ru.toml").exists()],
                         ids=lambda p: p.name)
def test_ru_quiz_is_valid_for_the_quiz_loader(chapter: Path) -> None:
    """The Russian quiz passes the same validation as the English one (kinds, required keys)."""
    from plclab.course.model import Chapter
    from plclab.course.quiz import items

    ch = Chapter(chapter)
    with open(chapter / "quiz.ru.toml", "rb") as fh:
        ch.quiz_data = tomllib.load(fh)   # what `plclab quiz --lang ru` would read
    ru = items(ch)
    assert [i.id for i in ru] == [i.id for i in items(Chapter(chapter))]
    assert all(i.question and i.explain for i in ru)


@pytest.mark.parametrize("chapter", _ru_chapters(), ids=lambda p: p.name)
def test_ru_chapter_agrees_through_the_course_model(chapter: Path) -> None:
    """plclab's own reader sees the same labs, figures and code blocks in both editions."""
    from plclab.course.model import Chapter

    en, ru = Chapter(chapter), Chapter(chapter)
    ru.text = (chapter / "chapter.ru.md").read_text(encoding="utf-8")
    assert ru.lab_refs == en.lab_refs
    assert ru.figure_refs == en.figure_refs
    assert [(b.language, b.attrs, b.text) for b in ru.blocks] == \
        [(b.language, b.attrs, b.text) for b in en.blocks]
