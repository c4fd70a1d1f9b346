"""Functional safety comes before the press lab (issue 34): chapter 17 teaches it in a section
above its lab list, names the standards and what they cover, and its diagnostic example runs."""

from plclab.course.model import find_chapter
from plclab.grade.lab import list_labs, load_lab

STANDARDS = {"IEC 60204-1": "stop", "ISO 13849-1": "performance level", "IEC 62061": "SIL",
             "ISO 13851": "two-hand", "IEC 61496": "light curtain", "ISO 13850": "E-stop",
             "ISO 13855": "distance"}


def _section() -> str:
    text = find_chapter(17).text
    start = text.index("## Functional safety")
    return text[start:text.index("\n## ", start + 1)]


def test_the_safety_section_precedes_the_press_lab_link():
    text = find_chapter(17).text
    assert text.index("## Functional safety") < text.index("../../labs/press-safety/")
    lab = next(load_lab(p) for p in list_labs() if p.name == "press-safety")
    assert min(lab.chapters) == 17


def test_each_standard_is_named_with_what_it_covers():
    section = " ".join(_section().split())
    for standard, subject in STANDARDS.items():
        assert standard in section, standard
        near = section[max(0, section.index(standard) - 400):section.index(standard) + 400]
        assert subject.lower() in near.lower(), f"{standard} without {subject!r}"
    for category in ("| 0 |", "| 1 |", "| 2 |"):
        assert category in _section()
    for term in ("safety relay", "safety PLC", "may not", "second line"):
        assert term in section


def test_the_section_cites_no_clause_numbers():
    import re

    assert not re.search(r"(?:clause|§|section)\s*\d", _section(), re.I)
    assert not re.search(r"\b\d{4,5}(?:-\d)?:\d{4}\s+\d+\.\d", _section())
