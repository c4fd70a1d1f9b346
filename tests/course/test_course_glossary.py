"""The glossary (course/glossary.toml): each term is used by the chapter said to introduce it,
its Russian form is the one the cited line of the source texts uses, the index is computed
from the chapters, and the built course carries the page and links it."""

import dataclasses
import os
import re
import unicodedata
from pathlib import Path

import pytest

from plclab.course.build import index_text
from plclab.course.glossary import (
    glossary_markdown,
    glossary_problems,
    index,
    terms,
    write_glossary,
)
from plclab.course.model import chapters

ROOT = Path(__file__).resolve().parents[2]
SEEDS = next((p for p in (ROOT.parent / "shared" / "seeds", Path("/work/shared/seeds"))
              if p.is_dir()), None)


def test_the_glossary_is_sound():
    assert glossary_problems() == []
    assert len(terms()) >= 50


def test_the_terms_the_task_names_are_there():
    ru = {t.ru for t in terms()}
    for word in ("ПЛК", "рабочий цикл", "дискретный вход", "уставка", "гистерезис",
                 "сторожевой таймер", "ШИМ", "ПИД-регулятор"):
        assert any(word in r for r in ru), word


def _norm(text: str) -> str:
    return unicodedata.normalize("NFC", text).replace("ё", "е").replace("Ё", "Е").lower()


def _same_word(a: str, b: str) -> bool:
    """Two forms of one Russian word: a common beginning of 4 letters (3 for short words)."""
    a, b = _norm(a), _norm(b)
    return len(os.path.commonprefix([a, b])) >= min(4, len(a), len(b))


def _russian_problem(term) -> str | None:
    """Why the row's Russian is not the source's own (None: it is)."""
    name, line = term.source.rsplit(":", 1)
    lines = (SEEDS / name).read_text(encoding="utf-8").splitlines()
    n = int(line)
    around = ""
    for text in lines[n - 2:n + 1]:  # the line and its neighbours, hyphenation undone
        text = text.strip()
        around = around[:-1] + text if around.endswith("-") else f"{around} {text}"
    if _norm(term.source_form) not in _norm(" ".join(around.split())):
        return f"{term.source_form!r} is not at {term.source}: {around.strip()[:80]}"
    forms = re.findall(r"[А-Яа-яЁё]+", term.source_form)
    ru_words = re.findall(r"[А-Яа-яЁё]+", term.ru)
    if not any(_same_word(w, f) for w in ru_words for f in forms):
        return f"{term.ru!r} is not a form of {term.source_form!r}"
    return None


@pytest.mark.skipif(SEEDS is None, reason="the source texts (shared/seeds) are not beside the repo")
@pytest.mark.parametrize("term", terms(), ids=lambda t: t.en)
def test_the_russian_term_is_the_source_texts_own(term):
    assert _russian_problem(term) is None


@pytest.mark.skipif(SEEDS is None, reason="the source texts (shared/seeds) are not beside the repo")
def test_a_russian_term_from_elsewhere_is_caught():
    opto = next(t for t in terms() if t.en == "optocoupler")
    assert _russian_problem(opto) is None
    assert "is not at" in _russian_problem(dataclasses.replace(opto, source_form="уставки"))
    assert "not a form of" in _russian_problem(dataclasses.replace(opto, ru="светодиод"))


def test_the_index_is_computed_from_the_chapters():
    idx = index(terms(), chapters())
    by_en = {t.en: t for t in terms()}
    for en, chs in idx.items():
        assert by_en[en].chapter in [c.number for c in chs]
    assert [c.number for c in idx["optocoupler"]] == [c.number for c in chapters()
                                                     if "optocoupler" in c.text.lower()]


# ------------------------------------------------------------ the checks catch a wrong table

GLOSSARY = '''
[[term]]
en = "scan cycle"
ru = "рабочий цикл ПЛК"
source = "001_c648febd3bbd6efb.txt:840"
source_form = "рабочего цикла ПЛК"
chapter = {chapter}
definition = "The loop."
'''


@pytest.fixture
def small_course(tmp_path):
    course = tmp_path / "course"
    for slug, text in (("01-first", "# First\n\nThe scan cycle reads, runs, writes.\n"),
                       ("02-second", "# Second\n\n```st\n(* scan cycle in code only *)\n```\n")):
        (course / slug).mkdir(parents=True)
        (course / slug / "chapter.md").write_text(text, encoding="utf-8")
    return course


def test_a_term_its_chapter_never_uses_is_caught(small_course):
    (small_course / "glossary.toml").write_text(GLOSSARY.format(chapter=1), encoding="utf-8")
    assert glossary_problems(small_course) == []
    (small_course / "glossary.toml").write_text(GLOSSARY.format(chapter=2), encoding="utf-8")
    (problem,) = glossary_problems(small_course)
    assert "never uses it" in problem  # the mention in a code block does not count
    (small_course / "glossary.toml").write_text(GLOSSARY.format(chapter=9), encoding="utf-8")
    assert "does not exist" in glossary_problems(small_course)[0]
    (small_course / "glossary.toml").write_text(GLOSSARY.format(chapter=1) * 2, encoding="utf-8")
    assert "twice" in glossary_problems(small_course)[0]


def test_the_page_and_its_index(small_course, tmp_path):
    (small_course / "glossary.toml").write_text(GLOSSARY.format(chapter=1), encoding="utf-8")
    page = glossary_markdown(terms(small_course), chapters(small_course))
    assert "| **scan cycle** | рабочий цикл ПЛК | The loop. | [1. First](01-first/chapter.md) |" \
        in page
    assert "- **scan cycle** (рабочий цикл ПЛК): [1](01-first/chapter.md)\n" in page
    out = tmp_path / "built"
    out.mkdir()
    assert write_glossary(out, small_course).read_text(encoding="utf-8") == page


def test_the_built_course_links_the_glossary():
    assert "](glossary.md)" in index_text([])
