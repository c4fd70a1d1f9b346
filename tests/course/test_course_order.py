"""The course's order: no chapter uses a construct before the chapter that introduces it.

``course/constructs.toml`` says what each chapter introduces (keywords, statement kinds, standard
function blocks, TEST blocks, FB instances, OOP, SFC, derived types, languages). The constructs a
code block uses are read from the AST its front end parses (``plclab.lang.frontends``, walked by
``plclab.lang.walk``), not from its text: a word in a comment or a string is not a use, and an
IL or ladder body counts by what it declares and calls. Every program block and example file of
chapter N may use only what chapters 1..N introduce (issue 34, "Order")."""

from __future__ import annotations

import re
import tomllib
from functools import cache

import pytest

from plclab.course.model import chapters, default_course_dir
from plclab.lang import ast as A
from plclab.lang.dialect import choose, using
from plclab.lang.frontends import for_file
from plclab.lang.frontends.st import parse_library
from plclab.lang.library import ANNEX_F, STDLIB_FILES
from plclab.lang.walk import walk

STATEMENTS = {A.If: "IF", A.Case: "CASE", A.For: "FOR", A.While: "WHILE", A.Repeat: "REPEAT",
              A.Exit: "EXIT", A.Continue: "CONTINUE", A.Return: "RETURN", A.Jump: "JMP",
              A.Label: "JMP"}
DERIVED = {A.StructTypeRef: "STRUCT", A.EnumTypeRef: "ENUM", A.SubrangeTypeRef: "SUBRANGE",
           A.ArrayTypeRef: "ARRAY", A.StringTypeRef: "STRING", A.RefTypeRef: "REF_TO"}
TEST_CALLS = {"ADVANCE_TIME"}
# how a chapter's text names a construct that is not a keyword of its own
MENTION = {"FB instance": "instance", "ENUM": "enumeration", "SUBRANGE": "subrange",
           "ST": "Structured Text", "LD": "ladder", "IL": "Instruction List",
           "FBD": "Function Block Diagram", "SFC": "Sequential Function Chart",
           "STRING": "STRING", "JMP": "JMP"}


@cache
def _library() -> dict[str, str]:
    """Name -> POU kind of plclab's block library (the Annex F blocks included)."""
    return {p.name: p.kind for f in parse_library(STDLIB_FILES + (ANNEX_F,)) for p in f.pous}


def constructs_of(text: str, filename: str) -> set[str]:
    """The constructs one program uses, from the tree its front end parses. Bodies in IL,
    ladder, FBD or SFC are read before the lowering turns them into ST statements (whose IFs
    and temporaries are not the student's): they count by their language, their declarations,
    an IL jump and a chart."""
    with using(choose(text, None, filename)):
        own, _ = for_file(filename).parse(text, filename)  # a marked mistake may not parse
    library = _library()
    user_blocks = {p.name for p in own.pous if p.kind == "FUNCTION_BLOCK"}
    out: set[str] = set()
    for p in [*own.pous, *(m for q in own.pous for m in q.methods)]:
        out |= {p.language} if p.kind != "METHOD" else {"METHOD"}
        out |= {p.kind} - {"METHOD"}
        for body in p.pending:
            if body.kind == "SFC":
                out |= {"SFC"}
            elif body.kind == "IL" and any(i.op.startswith("JMP") for i in body.payload):
                out.add("JMP")
        out |= {"EXTENDS"} if p.extends else set()
        out |= {"IMPLEMENTS"} if p.implements else set()
    for flag, name in ((own.tests, "TEST"), (own.configs, "CONFIGURATION"),
                       (own.globals, "VAR_GLOBAL"), (own.types, "TYPE")):
        if flag:
            out.add(name)
    for n in walk(own):
        kind = type(n)
        if kind in STATEMENTS:
            out.add(STATEMENTS[kind])
        elif kind in DERIVED:
            out.add(DERIVED[kind])
        elif kind is A.VarDecl:
            out |= {n.section} - {"VAR"}
            out |= {"AT"} if n.address else set()
            out |= {"RETAIN"} if n.retain else set()
            out |= {"CONSTANT"} if n.constant else set()
            if isinstance(n.type, A.NamedTypeRef):
                name = n.type.name.upper()
                if library.get(name) == "FUNCTION_BLOCK":
                    out.add(name)
                elif name in user_blocks:
                    out.add("FB instance")
        elif kind is A.Call and isinstance(n.func, A.Name):
            name = n.func.name.upper()
            if library.get(name) == "FUNCTION" or name in TEST_CALLS:
                out.add(name)
    return out


def _table() -> dict[int, list[str]]:
    data = tomllib.loads((default_course_dir() / "constructs.toml").read_text(encoding="utf-8"))
    return {c["number"]: list(c["introduces"]) for c in data["chapter"]}


def _programs(chapter) -> list[tuple[str, str, str]]:
    """(where, text, filename) of every program block and example file of a chapter."""
    out = [(b.where, b.text, b.filename) for b in chapter.blocks if b.is_program]
    out += [(f"course/{chapter.slug}/examples/{p.name}", p.read_text(encoding="utf-8"),
             f"{chapter.slug}/{p.name}") for p in chapter.examples]
    return out


def order_problems(table: dict[int, list[str]], programs: dict[int, list[tuple[str, str, str]]]
                   ) -> list[str]:
    """Every use of a construct before (or without) the chapter that introduces it."""
    first = {c: n for n, cs in table.items() for c in cs}
    problems = []
    for number, progs in sorted(programs.items()):
        for where, text, filename in progs:
            for c in sorted(constructs_of(text, filename)):
                if c not in first:
                    problems.append(f"{where}: uses {c}, which no chapter introduces "
                                    f"(add it to course/constructs.toml and teach it)")
                elif first[c] > number:
                    problems.append(f"{where}: uses {c} before chapter {first[c]} introduces it")
    return problems


CHAPTERS = chapters()


def test_every_chapter_is_in_the_table_once_and_each_construct_once():
    table = _table()
    assert sorted(table) == [c.number for c in CHAPTERS]
    flat = [c for cs in table.values() for c in cs]
    assert len(flat) == len(set(flat)), "a construct introduced twice"


def test_no_construct_is_used_before_its_chapter():
    programs = {c.number: _programs(c) for c in CHAPTERS}
    assert order_problems(_table(), programs) == []


@pytest.mark.parametrize("chapter", CHAPTERS, ids=lambda c: c.slug)
def test_a_chapter_names_what_it_introduces(chapter):
    text = chapter.text.lower()
    for c in _table()[chapter.number]:
        word = MENTION.get(c, c).lower()
        assert re.search(rf"(?<![\w]){re.escape(word)}", text), (
            f"{chapter.slug} introduces {c} in constructs.toml but never names it")


# the checker must catch what it is for: wrong inputs
_CASE = """PROGRAM P
VAR x : INT; y : INT; END_VAR
CASE x OF 1: y := 2; END_CASE;
(* a FOR loop in a comment is not a use *)
END_PROGRAM
"""
_TIMER_IN_IL = """PROGRAM P
VAR t : TOF; q : BOOL; END_VAR
    CAL t(IN := TRUE, PT := T#1s)
    LD t.Q
    ST q
END_PROGRAM
"""
_STRUCT = """TYPE Point : STRUCT x : REAL; y : REAL; END_STRUCT; END_TYPE
TYPE Colour : (Red, Green); END_TYPE
FUNCTION_BLOCK Fb
VAR_INPUT a : INT; END_VAR
END_FUNCTION_BLOCK
PROGRAM P
VAR p : Point; c : Colour; f : Fb; s : STRING[10]; r : INT(0..10); END_VAR
f(a := 1);
END_PROGRAM
"""


def test_constructs_come_from_the_tree_not_from_the_words():
    used = constructs_of(_CASE, "a.st")
    assert "CASE" in used and "FOR" not in used
    assert {"TOF", "IL"} <= constructs_of(_TIMER_IN_IL, "b.st")
    assert {"TYPE", "STRUCT", "ENUM", "FB instance", "FUNCTION_BLOCK", "VAR_INPUT", "STRING",
            "SUBRANGE"} <= constructs_of(_STRUCT, "c.st")


def test_the_order_check_catches_an_early_use_and_an_unknown_construct():
    table = {1: ["ST", "PROGRAM"], 2: ["CASE"]}
    early = order_problems(table, {1: [("ch1", _CASE, "a.st")]})
    assert early == ["ch1: uses CASE before chapter 2 introduces it"]
    assert order_problems(table, {2: [("ch2", _CASE, "a.st")]}) == []
    unknown = order_problems(table, {2: [("ch2", _TIMER_IN_IL, "b.st")]})
    assert any("uses TOF, which no chapter introduces" in p for p in unknown)


def readme_table_problems(readme: str, chapters_: list) -> list[str]:
    """The course README's table lists every chapter once, in order, with the labs the chapter
    itself links (its "Labs that practise this chapter")."""
    rows = re.findall(r"^\| (\d+) \| \[[^\]]+\]\(([\w-]+)/chapter\.md\) \| ([^|]*)\|$", readme,
                      re.M)
    problems = []
    numbers = [int(n) for n, _, _ in rows]
    if numbers != sorted(numbers) or numbers != [c.number for c in chapters_]:
        problems.append(f"chapters listed as {numbers}")
    by_slug = {c.slug: c for c in chapters_}
    for _, slug, labs in rows:
        listed = sorted(x.strip() for x in labs.split(",") if x.strip())
        linked = sorted(set(by_slug[slug].lab_refs)) if slug in by_slug else None
        if listed != linked:
            problems.append(f"{slug}: README lists {listed}, the chapter links {linked}")
    return problems


def test_the_course_readme_lists_the_chapters_in_order_with_their_labs():
    readme = (default_course_dir() / "README.md").read_text(encoding="utf-8")
    assert readme_table_problems(readme, CHAPTERS) == []
    swapped = readme.replace("| 9 | [Structured", "| 99 | [Structured")
    assert readme_table_problems(swapped, CHAPTERS), "a wrong order must be caught"
    stale = readme.replace("tank-two-position, scan-timing |", "tank-two-position, press-safety |")
    assert readme_table_problems(stale, CHAPTERS), "a stale lab column must be caught"


def test_a_lab_needs_only_what_the_first_chapter_linking_it_has_taught():
    """At least one of a lab's solutions (a student writes one, in the language they choose)
    uses only constructs the chapters up to the first one linking the lab introduce: chapter 2
    cannot send a beginner to a lab that needs SFC or PID."""
    from plclab.grade.lab import list_labs, load_lab

    table = _table()
    problems: list[str] = []
    for path in list_labs():
        lab = load_lab(path)
        first = min(lab.chapters)
        found = {p.name: order_problems(table, {first: [(p.name, p.read_text(encoding="utf-8"),
                                                          p.name)]})
                 for p in sorted((path / "solution").iterdir())
                 if p.suffix in (".st", ".ld", ".il", ".xml")}
        if found and all(found.values()):
            problems.append(f"{lab.id}, first linked from chapter {first}: every solution needs a "
                            f"later chapter: {sorted(p for ps in found.values() for p in ps)}")
    assert problems == []
