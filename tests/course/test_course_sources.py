"""Citations live in the instructor notes (course/instructor/sources.md), not in the student
text: no chapter's prose carries a bare "(lines N)" or "(ADR NNNN)" any more (its exercises and
code may name a source on purpose), and every place the notes cite exists."""

import re
from pathlib import Path

import pytest

from plclab.course.model import chapters

ROOT = Path(__file__).resolve().parents[2]
NOTES = (ROOT / "course" / "instructor" / "sources.md").read_text(encoding="utf-8")
SEEDS = next((p for p in (ROOT.parent / "shared" / "seeds", Path("/work/shared/seeds"))
              if p.is_dir()), None)
BARE = re.compile(r"\((?:`\d{3}_[0-9a-f]+\.txt`,\s)?lines?\s[0-9][0-9 ,\-and\n]*\)|\(ADR\s\d{4}\)")


def bare_citations(text: str) -> list[str]:
    prose = re.sub(r"^```.*?^```", "", text, flags=re.S | re.M).split("## Exercises")[0]
    return BARE.findall(prose)


@pytest.mark.parametrize("chapter", chapters(), ids=lambda c: c.slug)
def test_the_student_text_has_no_bare_citation(chapter):
    assert bare_citations(chapter.text) == []
    # and no line begins with the punctuation a removed citation stood before
    prose = re.sub(r"^```.*?^```", "", chapter.text, flags=re.S | re.M)
    assert not re.findall(r"^ *[,.;:] .*", prose, re.M)


def test_the_check_finds_a_bare_citation():
    assert bare_citations("It reads 24 V (lines 820-832).\n") == ["(lines 820-832)"]
    assert bare_citations("See (`001_c648febd3bbd6efb.txt`,\nlines 1-2) and (ADR 0016).") == [
        "(`001_c648febd3bbd6efb.txt`,\nlines 1-2)", "(ADR 0016)"]
    assert bare_citations("```st\n(* lines 1-2 *)\n```\n## Exercises\n(line 37)") == []


def test_the_notes_name_every_chapter_that_had_citations():
    slugs = {c.slug for c in chapters()}
    named = set(re.findall(r"^## ([\w-]+):", NOTES, re.M))
    assert named <= slugs and len(named) >= 15


def _places():
    for m in re.finditer(r": (\d{3}_[0-9a-f]+\.txt), lines? ([0-9][0-9 ,\-and]*)$", NOTES, re.M):
        yield m.group(1), [int(n) for n in re.findall(r"\d+", m.group(2))]


def test_the_adrs_the_notes_cite_exist():
    for number in re.findall(r": ADR (\d{4})$", NOTES, re.M):
        assert list((ROOT / "docs" / "adr").glob(f"{number}-*.md")), number


@pytest.mark.skipif(SEEDS is None, reason="the source texts (shared/seeds) are not beside the repo")
def test_every_cited_place_exists():
    places = list(_places())
    assert len(places) >= 90
    for name, lines in places:
        length = len((SEEDS / name).read_text(encoding="utf-8").splitlines())
        assert all(1 <= n <= length for n in lines), (name, lines, length)
