"""The course ships in the wheel with the labs (ADR 0019): the student copy of the courseware
holds every chapter with its examples, figure specifications and quiz, and the copy is a course
that plclab reads and checks like the source."""

from pathlib import Path

from plclab.course.blocks import check_chapter_code
from plclab.course.model import chapters, default_course_dir, find_chapter
from plclab.course.quiz import check_quiz
from plclab.grade.courseware import COURSEWARE, copy_courseware, courseware_root


def test_the_student_copy_carries_the_course(tmp_path):
    root = default_course_dir().parent
    files = copy_courseware(root, tmp_path / "courseware")
    course = tmp_path / "courseware" / "course"
    assert "course" in COURSEWARE
    assert [c.slug for c in chapters(course)] == [c.slug for c in chapters()]
    for c in chapters():
        for name in ("chapter.md", "quiz.toml", "figures.toml"):
            assert (course / c.slug / name).is_file(), f"{c.slug}/{name}"
        for ex in c.examples:
            assert (course / c.slug / "examples" / ex.name).is_file()
    assert not any("__pycache__" in p.parts for p in files)
    # the copy is a working course: its chapter 3 runs and its quiz keys validate
    copied = find_chapter(3, course)
    assert all(o.ok for o in check_chapter_code(copied))
    assert check_quiz(copied)[1] == []
    # chapters link labs as ../../labs/ID: the copy keeps course/ and labs/ side by side
    for lab in copied.lab_refs:
        assert (tmp_path / "courseware" / "labs" / lab / "README.md").is_file()


def test_a_checkout_reads_its_own_course():
    assert default_course_dir() == courseware_root() / "course"
    assert (Path(__file__).resolve().parents[2] / "course") == default_course_dir() or (
        courseware_root().name == "courseware")
