"""The path through the labs: every lab has a level and names the chapters that teach it, those
agree with the chapters' own links, and ``plclab lab list`` orders the labs easiest first with a
"start here"."""

import shutil

import pytest

from plclab.cli import main
from plclab.course.model import chapters
from plclab.errors import PlcError
from plclab.grade.lab import LEVELS, list_labs, load_lab


def test_lab_chapters_agree_with_the_course_links():
    linked: dict[str, set[int]] = {}
    for c in chapters():
        for lab in c.lab_refs:
            linked.setdefault(lab, set()).add(c.number)
    for path in list_labs():
        lab = load_lab(path)
        assert lab.level in LEVELS, f"{lab.id}: no level"
        assert set(lab.chapters) == linked.get(lab.id, set()), (
            f"{lab.id}: lab.toml says chapters {lab.chapters}, the course links it from "
            f"{sorted(linked.get(lab.id, set()))}")


def test_lab_list_is_ordered_by_level_with_a_start(capsys):
    assert main(["lab", "list"]) == 0
    lines = capsys.readouterr().out.splitlines()
    rows = [ln.split() for ln in lines[1:] if ln.strip()]
    levels = [list(LEVELS.values()).index(r[1]) for r in rows if r[1] in LEVELS.values()]
    assert levels == sorted(levels) and len(levels) == len(rows)
    assert "start here" in lines[1] and "start here" not in "".join(lines[2:])
    assert lines[1].split()[0] == "tank-two-position"


@pytest.mark.parametrize("bad", ["level = 5", 'level = "easy"', 'chapters = ["one"]',
                                 "chapters = [0]"])
def test_a_bad_level_or_chapter_list_is_a_lab_error(tmp_path, bad):
    src = next(p for p in list_labs() if p.name == "tank-two-position")
    dst = tmp_path / "tank-two-position"
    shutil.copytree(src, dst)
    toml = dst / "lab.toml"
    text = toml.read_text(encoding="utf-8")
    key = bad.split(" =")[0]
    lines = [ln for ln in text.splitlines() if not ln.startswith(f"{key} =")]
    toml.write_text("\n".join([bad] + lines) + "\n", encoding="utf-8")
    with pytest.raises(PlcError) as e:
        load_lab(dst)
    assert e.value.code == "PLC5004" and key in str(e.value)


def test_every_lab_readme_links_its_chapters_not_source_lines():
    import re

    slugs = {c.number: c.slug for c in chapters()}
    for path in list_labs():
        lab = load_lab(path)
        readme = (path / "README.md").read_text(encoding="utf-8")
        for n in lab.chapters:
            assert f"../../course/{slugs[n]}/chapter.md" in readme, f"{lab.id}: chapter {n}"
        student_part = readme.split("*For instructors:")[0]
        assert not re.search(r"\blines? \d{3,}", student_part), f"{lab.id} cites source lines"
