"""Each chapter has a "Common mistake" box that names a real mistake program of a lab and
quotes what the grader says about it: the program exists, and `plclab lab check` on it fails
the criterion the box names with the message the box quotes."""

import re
from pathlib import Path

import pytest

from plclab.course.model import chapters

ROOT = Path(__file__).resolve().parents[2]
BOX = re.compile(r"^> \*\*Common mistake\*\* \(lab ([\w-]+): `(labs/[\w-]+/mistakes/[\w.]+)`\)"
                 r"(.*?)fails its criterion \*\*(.+?)\*\*: \"(.+?)\"\.$", re.S)


def boxes(text: str) -> list[tuple[str, ...]]:
    out = []
    for block in re.findall(r"^> \*\*Common mistake\*\*.*?(?=\n\n|\Z)", text, re.S | re.M):
        joined = " ".join(line.removeprefix("> ").strip() if k else line
                          for k, line in enumerate(block.splitlines()))
        m = BOX.match(joined)
        assert m, f"a Common mistake box that does not follow the pattern: {joined[:120]}"
        out.append(m.groups())
    return out


@pytest.mark.parametrize("chapter", chapters(), ids=lambda c: c.slug)
def test_a_chapter_has_one_box_naming_a_real_mistake(chapter):
    (box,) = boxes(chapter.text)
    lab, path = box[0], box[1]
    assert path.startswith(f"labs/{lab}/") and (ROOT / path).is_file(), path


def _failures(lab_id: str, path: str) -> dict[str, list[str]]:
    from plclab.grade.engine import grade_sources
    from plclab.grade.lab import load_lab

    lab = load_lab(lab_id)
    src = (ROOT / path).read_text(encoding="utf-8")
    res = grade_sources(lab, [(src, Path(path).name)], include_hidden=False, rrd=False)
    out: dict[str, list[str]] = {}
    for t in res.tests:
        if not t.passed:
            out.setdefault(t.criterion, []).append(" ".join(t.message.split()))
    return out


@pytest.mark.parametrize("chapter", chapters(), ids=lambda c: c.slug)
def test_the_grader_says_what_the_box_quotes(chapter):
    lab, path, _, criterion, says = boxes(chapter.text)[0]
    failed = _failures(lab, path)
    assert criterion in failed, (criterion, sorted(failed))
    assert any(" ".join(says.split()) in m for m in failed[criterion]), failed[criterion]


def test_a_box_with_a_criterion_the_grader_does_not_fail_is_caught():
    lab, path, _, criterion, says = boxes(chapters()[0].text)[0]
    failed = _failures(lab, path)
    assert "pump starts below LS1" not in failed  # another lab's criterion
    with pytest.raises(AssertionError):
        boxes("> **Common mistake** (lab x: `labs/x/solution/a.st`). No quote.")
