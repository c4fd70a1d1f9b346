"""The machinery on a small course written in tmp_path: block markers, quiz grading and key
checking, the terminal quiz, chapter lookup."""

import pytest

from plclab.course.blocks import check_chapter_code, codes_taught
from plclab.course.model import chapters, code_blocks, find_chapter
from plclab.course.quiz import ask, check_quiz, grade, items
from plclab.errors import PlcError

CHAPTER = """# Tiny

Learning goals: none.

```st
PROGRAM P VAR n : INT; END_VAR n := n + 1; END_PROGRAM
```

```st error=PLC0012
PROGRAM Q VAR x : BOOL; END_VAR IF x == TRUE THEN x := FALSE; END_IF END_PROGRAM
```

```st error=PLC0100
PROGRAM R VAR x : BOOL; END_VAR x := TRUE; END_PROGRAM
```

```st error=PLC2001
PROGRAM D VAR a : INT; b : INT; END_VAR a := 1 / b; END_PROGRAM
```

```text
y = ymin + N * (ymax - ymin) / Nmax
```
"""

QUIZ = '''
[[item]]
kind = "choice"
question = "Pick two"
choices = ["one", "two"]
answer = 2
explain = "Two."

[[item]]
kind = "numeric"
question = "ADC step"
compute = "10.0 / 4096.0 * 1000.0"
answer = 2.44
tolerance = 0.01
explain = "span / 2^n."

[[item]]
kind = "output"
question = "n after 3 scans?"
program = "PROGRAM P VAR n : INT; END_VAR n := n + 2; END_PROGRAM"
scans = 3
show = "P.n"
answer = "6"
explain = "Two per scan."

[[item]]
kind = "write"
question = "Q := A AND B"
solution = "PROGRAM M VAR A, B, Q : BOOL; END_VAR Q := A AND B; END_PROGRAM"
wrong = ["PROGRAM M VAR A, B, Q : BOOL; END_VAR Q := A OR B; END_PROGRAM"]
explain = "AND."
[[item.step]]
set = { "M.A" = true, "M.B" = false }
expect = { "M.Q" = false }
[[item.step]]
set = { "M.B" = true }
expect = { "M.Q" = true }
'''


@pytest.fixture
def course(tmp_path):
    ch = tmp_path / "01-tiny"
    ch.mkdir()
    (ch / "chapter.md").write_text(CHAPTER, encoding="utf-8")
    (ch / "quiz.toml").write_text(QUIZ, encoding="utf-8")
    return tmp_path


def test_blocks_are_checked_against_their_markers(course):
    c = find_chapter(1, course)
    outcomes = check_chapter_code(c)
    assert [o.ok for o in outcomes] == [True, True, False, True, True]
    # the beginner lint runs too: R's only warning is PLC0214 (no located variables)
    assert "marked error=PLC0100 but gave" in outcomes[2].message
    assert "PLC0214" in outcomes[2].message
    assert "fails as marked with PLC2001" in outcomes[3].message
    assert set(codes_taught([c])) == {"PLC0012", "PLC0100", "PLC2001"}


def test_a_block_without_a_language_is_a_course_error():
    with pytest.raises(PlcError) as e:
        code_blocks("text\n```\nx := 1;\n```\n", "01-x")
    assert e.value.code == "PLC3020" and "01-x/chapter.md:2" in str(e.value)


def test_an_unclosed_block_is_a_course_error():
    with pytest.raises(PlcError, match="never closed"):
        code_blocks("```st\nPROGRAM P END_PROGRAM\n", "01-x")


def test_unknown_chapter_is_plc3021(course):
    with pytest.raises(PlcError) as e:
        find_chapter(99, course)
    assert e.value.code == "PLC3021" and "1 (01-tiny)" in str(e.value)
    assert find_chapter("tiny", course).slug == "01-tiny"


def test_grading_each_kind(course):
    its = items(chapters(course)[0])
    assert grade(its[0], "2").right and not grade(its[0], "1").right
    assert grade(its[1], "2.44").right and not grade(its[1], "2.6").right
    assert grade(its[2], "6").right and not grade(its[2], "3").right
    good = "PROGRAM M VAR A, B, Q : BOOL; END_VAR Q := A AND B; END_PROGRAM"
    assert grade(its[3], good).right
    bad = grade(its[3], "PROGRAM M VAR A, B, Q : BOOL; END_VAR Q := TRUE; END_PROGRAM")
    assert not bad.right and "step 1" in bad.feedback and "M.Q is TRUE, expected FALSE" in (
        bad.feedback)
    broken = grade(its[3], "PROGRAM M VAR A : BOOL; END_VAR A := ; END_PROGRAM")
    assert "does not compile" in broken.feedback


def test_check_accepts_valid_keys_and_catches_wrong_ones(course):
    assert check_quiz(chapters(course)[0]) == (4, [])
    q = course / "01-tiny" / "quiz.toml"
    text = QUIZ.replace("answer = 2.44", "answer = 2.5").replace('answer = "6"', 'answer = "7"')
    text = text.replace("Q := A OR B", "Q := A AND B")
    q.write_text(text, encoding="utf-8")
    _, problems = check_quiz(chapters(course)[0])
    assert len(problems) == 3
    assert "plclab computes 2.44141" in problems[0]
    assert "the program shows 6" in problems[1]
    assert "does not tell them apart" in problems[2]


def test_an_item_missing_a_key_is_a_course_error(course):
    (course / "01-tiny" / "quiz.toml").write_text(
        '[[item]]\nkind = "numeric"\nquestion = "?"\nexplain = "."\n', encoding="utf-8")
    with pytest.raises(PlcError) as e:
        items(chapters(course)[0])
    assert e.value.code == "PLC3020" and "answer" in str(e.value)


def test_terminal_quiz_with_scripted_answers(course, tmp_path):
    answer_file = tmp_path / "mine.st"
    answer_file.write_text("PROGRAM M VAR A, B, Q : BOOL; END_VAR Q := A AND B; END_PROGRAM")
    answers = iter(["2", "1.0", "", str(answer_file)])
    lines = []
    right, total = ask(find_chapter(1, course), lambda _: next(answers), lines.append)
    assert (right, total) == (2, 4)
    text = "\n".join(lines)
    assert "not quite: 2.44141" in text and "skipped" in text and "score: 2/4" in text


def test_explain_links_the_chapter_that_teaches_a_code(capsys):
    from plclab.cli import main

    assert main(["explain", "PLC0118"]) == 0
    assert "Taught in chapter 10, Timers, counters, edges and bistables" in capsys.readouterr().out


def test_quiz_cell_grades_a_dict_of_answers_without_stdin(course, monkeypatch):
    from plclab.course.quiz import quiz_cell

    def no_stdin(*_):
        raise AssertionError("a notebook cell must not read stdin")

    monkeypatch.setattr("builtins.input", no_stdin)
    good = "PROGRAM M VAR A, B, Q : BOOL; END_VAR Q := A AND B; END_PROGRAM"
    lines = []
    right, total = quiz_cell(find_chapter(1, course), {1: "2", 2: "3.0", "3": "", 4: good},
                             print_fn=lines.append)
    assert (right, total) == (2, 4)
    text = "\n".join(lines)
    assert "not quite: 2.44141" in text and "(not answered yet)" in text
    assert text.rstrip().endswith("quiz: 2 right of 4 (3 answered)")
    assert quiz_cell(1, None, course_dir=str(course), print_fn=lines.append) == (0, 4)
