"""The instructor's kit (course/instructor/kit.md): the 14-week plan teaches every chapter once
and in order, schedules every lab only after a chapter that teaches it, quizzes the chapters of
its week, adds up its lab hours, and names only commands plclab has."""

import re
import tomllib
from pathlib import Path

import pytest

from plclab.cli_registry import COMMAND_TABLE
from plclab.course.model import chapters

ROOT = Path(__file__).resolve().parents[2]
KIT = (ROOT / "course" / "instructor" / "kit.md").read_text(encoding="utf-8")


def plan(text: str) -> list[dict]:
    rows = []
    for m in re.finditer(r"^\| (\d+) \| ([\d, ]+) \| ([\w, -]+) \| ([\d, ]+) \| (\d+) \|$", text,
                         re.M):
        nums = lambda s: [int(x) for x in s.split(",")]  # noqa: E731
        rows.append({"week": int(m.group(1)), "chapters": nums(m.group(2)),
                     "labs": [x.strip() for x in m.group(3).split(",")],
                     "quiz": nums(m.group(4)), "hours": int(m.group(5))})
    return rows


def _lab_chapters(lab: str) -> list[int]:
    data = tomllib.loads((ROOT / "labs" / lab / "lab.toml").read_text(encoding="utf-8"))
    return list(data.get("chapters", []))


def problems(text: str) -> list[str]:
    rows, out = plan(text), []
    if [r["week"] for r in rows] != list(range(1, 15)):
        out.append(f"weeks {[r['week'] for r in rows]}, not 1..14")
    taught = [c for r in rows for c in r["chapters"]]
    if taught != [c.number for c in chapters()]:
        out.append(f"chapters taught {taught}: each once, in order")
    labs = {p.name for p in (ROOT / "labs").iterdir() if (p / "lab.toml").exists()}
    scheduled = set()
    so_far: set[int] = set()
    for r in rows:
        so_far |= set(r["chapters"])
        if r["quiz"] != r["chapters"]:
            out.append(f"week {r['week']}: quiz {r['quiz']}, chapters {r['chapters']}")
        for lab in r["labs"]:
            if lab not in labs:
                out.append(f"week {r['week']}: no lab {lab}")
                continue
            scheduled.add(lab)
            if not so_far & set(_lab_chapters(lab)):
                out.append(f"week {r['week']}: {lab} before any chapter that teaches it "
                           f"({_lab_chapters(lab)})")
    if labs - scheduled:
        out.append(f"labs never scheduled: {sorted(labs - scheduled)}")
    total = sum(r["hours"] for r in rows)
    if f"{total} lab hours in all" not in text:
        out.append(f"the lab hours add up to {total}")
    return out


def test_the_plan_is_sound():
    assert problems(KIT) == []


@pytest.mark.parametrize("old,new,why", [
    ("| 3 | 3 | scan-timing | 3 | 2 |", "| 3 | 3 | water-boiler | 3 | 2 |", "before any chapter"),
    ("| 5 | 5, 6 |", "| 5 | 6, 5 |", "in order"),
    ("| 8 | 10 | bottle-packing | 10 | 3 |", "| 8 | 10 | bottle-packing | 9 | 3 |", "quiz"),
    ("| 8 | 10 | bottle-packing | 10 | 3 |", "| 8 | 10 | bottle-packer | 10 | 3 |", "no lab"),
    ("| 8 | 10 | bottle-packing | 10 | 3 |", "| 8 | 10 | bottle-packing | 10 | 4 |", "add up"),
    ("| 11 | 13 | drive-homing | 13 | 3 |", "| 11 | 13 | pump-station | 13 | 3 |", "never"),
])
def test_a_wrong_plan_is_caught(old, new, why):
    assert old in KIT
    assert any(why in p for p in problems(KIT.replace(old, new)))


def test_every_command_it_names_exists():
    named = set(re.findall(r"^plclab ([\w-]+)", KIT, re.M)) | \
        set(re.findall(r"`plclab ([\w-]+)", KIT))
    assert {"grade", "grade-bundle", "quiz", "lab"} <= named
    assert named <= set(COMMAND_TABLE), named - set(COMMAND_TABLE)


def test_the_kit_is_not_shipped_to_students(tmp_path):
    from plclab.grade.courseware import copy_courseware

    copied = copy_courseware(ROOT, tmp_path / "courseware")
    assert not [p for p in copied if p.name == "kit.md"]
