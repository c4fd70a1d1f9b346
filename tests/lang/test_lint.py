"""The beginner lint (plclab/lang/check/lint.py, PLC0210-PLC0216): each warning where a
beginner's classic mistake is, none on the reference solutions, none after a syntax error."""

from __future__ import annotations

from pathlib import Path

import pytest

from plclab.project import check_sources

ROOT = Path(__file__).resolve().parents[2]


def lint_codes(src: str, io_table=None) -> list[str]:
    _, diags = check_sources([(src, "main.st")], lint=True, io_table=io_table)
    return [d.code for d in diags if d.code.startswith("PLC021")]


def program(body: str, decls: str = "") -> str:
    return (f"PROGRAM Main\nVAR\n  START AT %IX0.0 : BOOL;\n  LAMP AT %QX0.0 : BOOL;\n{decls}"
            f"END_VAR\n{body}\nEND_PROGRAM\n")


def test_a_timer_never_called_or_called_only_in_an_if():
    assert lint_codes(program("t.IN := START; LAMP := t.Q;", "  t : TON;\n")) == ["PLC0210"]
    assert lint_codes(program("IF START THEN t(IN := TRUE, PT := T#1s); END_IF;\n"
                              "LAMP := t.Q;", "  t : TON;\n")) == ["PLC0211"]
    assert lint_codes(program("CASE 1 OF 1: e(CLK := START); END_CASE; LAMP := e.Q;",
                              "  e : R_TRIG;\n")) == ["PLC0211"]
    assert lint_codes(program("t(IN := START, PT := T#1s); LAMP := t.Q;", "  t : TON;\n")) == []
    # called once unconditionally and once more in an IF: it sees every scan
    assert lint_codes(program("t(IN := START, PT := T#1s);\nIF START THEN t(IN := FALSE); "
                              "END_IF;\nLAMP := t.Q;", "  t : TON;\n")) == []


def test_an_output_written_twice_but_not_set_and_reset_in_ifs():
    assert lint_codes(program("LAMP := START;\nLAMP := NOT START;")) == ["PLC0212"]
    assert lint_codes(program("%QX0.1 := START;\n%QX0.1 := FALSE; LAMP := START;")) == \
        ["PLC0212"]
    assert lint_codes(program("LAMP := FALSE;\nIF START THEN LAMP := TRUE; END_IF;")) == []


def test_an_integer_division_into_a_real():
    decls = "  a : INT; b : INT; r : REAL;\n"
    assert lint_codes(program("r := a / b; LAMP := START;", decls)) == ["PLC0213"]
    assert lint_codes(program("r := INT_TO_REAL(a / b); LAMP := START;", decls)) == ["PLC0213"]
    assert lint_codes(program("r := INT_TO_REAL(a) / INT_TO_REAL(b); LAMP := START;",
                              decls)) == []
    assert lint_codes(program("a := a / b; LAMP := START;", decls)) == []  # INT into INT


def test_no_located_variables_and_empty_programs():
    assert lint_codes("PROGRAM Main\nVAR x : BOOL; END_VAR\nx := NOT x;\nEND_PROGRAM\n") == \
        ["PLC0214"]
    assert lint_codes("(* the pump, some day *)\n") == ["PLC0216"]
    assert lint_codes("") == ["PLC0216"]
    assert "PLC0216" in lint_codes("PROGRAM Main\nEND_PROGRAM\n")
    # a library of blocks is not a program: nothing to warn about
    assert lint_codes("FUNCTION_BLOCK Fb\nVAR_INPUT x : BOOL; END_VAR\nEND_FUNCTION_BLOCK\n"
                      "") == []


class Row:
    def __init__(self, name: str, address: str) -> None:
        self.name, self.address = name, address


def test_addresses_against_the_labs_io_table():
    table = [Row("START", "%IX0.0"), Row("LAMP", "%QX0.0")]
    assert lint_codes(program("LAMP := START;"), table) == []
    moved = program("LAMP := START;").replace("START AT %IX0.0", "START AT %IX0.1")
    assert lint_codes(moved, table) == ["PLC0215"]
    extra = program("LAMP := START AND X;", "  X AT %IX3.0 : BOOL;\n")
    assert lint_codes(extra, table) == ["PLC0215"]
    assert lint_codes(extra) == []  # without a lab nothing to compare with


def test_no_warnings_after_a_syntax_error():
    src = program("LAMP := START AND ;", "  t : TON;\n  unused : INT;\n")
    _, diags = check_sources([(src, "main.st")], lint=True)
    assert [d.severity for d in diags] == ["error"]


@pytest.mark.parametrize("sol", sorted(ROOT.glob("labs/*/solution/*.st")),
                         ids=lambda p: f"{p.parent.parent.name}/{p.name}")
def test_the_reference_solutions_are_clean(sol):
    from plclab.grade.lab import load_lab

    lab = load_lab(sol.parent.parent)
    _, diags = check_sources([(sol.read_text(encoding="utf-8"), sol.name)], lint=True,
                             io_table=lab.io)
    assert not [str(d) for d in diags if d.code.startswith("PLC021")]


def test_plcopen_exports_keep_their_io_mapping_outside_the_file():
    """PLC0214 is not raised for the language demos examples/motor.xml and project.xml (an
    IDE's export maps its I/O in the project, not in the XML), but is with a lab's table."""
    from pathlib import Path

    from plclab.project import check_sources

    root = Path(__file__).resolve().parents[2] / "examples"
    for name in ("motor.xml", "project.xml"):
        src = [((root / name).read_text(encoding="utf-8"), str(root / name))]
        _, diags = check_sources(src, lint=True)
        assert "PLC0214" not in [d.code for d in diags], name
        _, diags = check_sources(src, lint=True, io_table=[Row("START", "%IX0.0")])
        assert "PLC0214" in [d.code for d in diags], name
