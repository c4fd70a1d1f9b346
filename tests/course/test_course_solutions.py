"""Worked solutions (course/instructor/): each passes ``plclab test``, each one's TESTs can fail
(an assertion turned round must be caught), the instructor README lists every file and each
names a real exercise, and no student build carries them."""

import re
from pathlib import Path

import pytest

from plclab.course.model import chapters
from plclab.grade.courseware import copy_courseware
from plclab.testing import run_test_sources

ROOT = Path(__file__).resolve().parents[2]
INSTRUCTOR = ROOT / "course" / "instructor"
SOLUTIONS = sorted(p for p in (INSTRUCTOR / "solutions").rglob("*")
                   if p.suffix in (".st", ".il", ".ld", ".xml"))


def test_there_are_solutions():
    assert len(SOLUTIONS) >= 10


@pytest.mark.parametrize("path", SOLUTIONS, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_a_solution_passes_its_tests(path):
    results = run_test_sources([(path.read_text(encoding="utf-8"), path.name)])
    assert results, f"{path.name} has no TEST"
    assert all(r.passed for r in results), [str(r) for r in results if not r.passed]


def _turned_round(text: str) -> str:
    """The first ASSERT_TRUE becomes ASSERT_FALSE (or the other way round)."""
    m = re.search(r"ASSERT_(TRUE|FALSE)\(", text)
    assert m, "a solution needs an ASSERT_TRUE or ASSERT_FALSE the mutation can turn round"
    other = "FALSE" if m.group(1) == "TRUE" else "TRUE"
    return text[:m.start()] + f"ASSERT_{other}(" + text[m.end():]


@pytest.mark.parametrize("path", SOLUTIONS, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_a_solutions_tests_can_fail(path):
    wrong = _turned_round(path.read_text(encoding="utf-8"))
    results = run_test_sources([(wrong, path.name)])
    assert any(not r.passed for r in results)


def test_the_readme_lists_every_solution_and_each_names_a_real_exercise():
    readme = (INSTRUCTOR / "README.md").read_text(encoding="utf-8")
    listed = set(re.findall(r"\]\((solutions/[^)]+)\)", readme))
    assert listed == {p.relative_to(INSTRUCTOR).as_posix() for p in SOLUTIONS}
    by_number = {c.number: c for c in chapters()}
    for row in re.findall(r"^\| (\d+) \| ([\d, ]+) \| \[", readme, re.M):
        chapter = by_number[int(row[0])]
        exercises = chapter.text.split("## Exercises", 1)[1].split("\n## ", 1)[0]
        for n in row[1].split(","):
            assert re.search(rf"^{n.strip()}\. ", exercises, re.M), (chapter.slug, n)


def test_no_student_build_carries_the_solutions(tmp_path):
    assert "instructor" not in {c.slug for c in chapters()}
    copied = copy_courseware(ROOT, tmp_path / "courseware")
    assert copied and not [p for p in copied if "instructor" in p.parts]
    assert any(p.name == "constructs.toml" for p in copied)  # the course itself still ships
