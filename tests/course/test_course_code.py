"""Every code block of every chapter runs cleanly or fails with exactly the code it is marked
with; every example file runs; every figure the text shows is drawn by figures.toml; every quiz
key validates (``plclab quiz --check``)."""

import pytest

from plclab.cli import main
from plclab.course.blocks import run_block, run_example
from plclab.course.model import chapters

CHAPTERS = chapters()
BLOCKS = [b for c in CHAPTERS for b in c.blocks if b.is_program]
EXAMPLES = [(c.slug, p) for c in CHAPTERS for p in c.examples]


def test_the_course_has_chapters_with_programs_and_quizzes():
    assert len(CHAPTERS) >= 1
    for c in CHAPTERS:
        assert c.title != c.slug, f"{c.slug}: chapter.md needs a '# Title' line"
        assert any(b.is_program for b in c.blocks), f"{c.slug} shows no program"
        assert c.quiz_data.get("item"), f"{c.slug} has no quiz"
        assert "Learning goals" in c.text, f"{c.slug} states no learning goals"


@pytest.mark.parametrize("block", BLOCKS, ids=lambda b: f"{b.chapter}:{b.line}")
def test_block_runs_or_fails_as_marked(block):
    outcome = run_block(block)
    assert outcome.ok, str(outcome)


@pytest.mark.parametrize("slug,path", EXAMPLES, ids=lambda x: getattr(x, "name", x))
def test_example_file_runs(slug, path):
    outcome = run_example(path, slug)
    assert outcome.ok, str(outcome)


@pytest.mark.parametrize("chapter", CHAPTERS, ids=lambda c: c.slug)
def test_every_figure_shown_is_generated(chapter):
    drawn = {f"figures/{s['file']}" for s in chapter.figure_specs}
    assert set(chapter.figure_refs) <= drawn
    assert chapter.figure_refs, f"{chapter.slug} shows no figure"


@pytest.mark.parametrize("chapter", CHAPTERS, ids=lambda c: c.slug)
def test_every_lab_linked_exists(chapter):
    from plclab.course.model import default_course_dir

    labs = default_course_dir().parent / "labs"
    for lab in chapter.lab_refs:
        assert (labs / lab / "lab.toml").exists(), f"{chapter.slug} links a missing lab {lab}"


def test_quiz_check_validates_every_key(capsys):
    assert main(["quiz", "--check"]) == 0, capsys.readouterr().out
    assert "0 problem(s)" in capsys.readouterr().out
