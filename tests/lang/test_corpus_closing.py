"""Forms the closing measure of issue 40 found in valid files (ADR 0060): each with the wrong
input the rule must still refuse."""

from __future__ import annotations

import pytest

from plclab.project import check_sources

EXPORT = """(*@PROPERTIES_EX@
TYPE: POU
LOCALE: 0
IEC_LANGUAGE: ST
*)
(*@KEY@:DESCRIPTION*)
version 1.1   12. mar. 2008
programmer    someone
the block counts: IF it is (* not *) closed here, the text is still description
(*@KEY@:END_DESCRIPTION*)
FUNCTION_BLOCK Count
VAR_OUTPUT n : INT; END_VAR
n := n + 1;
END_FUNCTION_BLOCK
"""


def errors(text: str, dialect: str | None = None) -> list[str]:
    return [d.code for d in check_sources([(text, "f.st")], dialect)[1] if d.severity == "error"]


@pytest.mark.parametrize("dialect", ["codesys", "iec", "matiec", "s7"])
def test_the_description_of_a_codesys_2_3_export_is_not_code(dialect):
    assert errors(EXPORT, dialect) == []


def test_without_its_end_marker_the_description_is_code_again():
    broken = EXPORT.replace("(*@KEY@:END_DESCRIPTION*)", "")
    assert "PLC0010" in errors(broken, "codesys")


TIME_CALLS = """PROGRAM P
VAR t : TIME := T#10s; n : DINT := 4; a, b, c : TIME; END_VAR
a := MUL(t, 3);
b := DIV(t, n);
c := DIV(IN1 := t, IN2 := 2.5);
END_PROGRAM
"""


@pytest.mark.parametrize("dialect", ["codesys", "iec", "matiec", "s7"])
def test_mul_and_div_of_a_time_and_a_number_are_the_time_rows_of_the_table(dialect):
    import plclab

    plc = plclab.loads(TIME_CALLS, dialect=dialect)
    plc.scan()
    ms = 10_000
    assert (plc["P.a"], plc["P.b"], plc["P.c"]) == (3 * ms, ms // 4, int(ms / 2.5))


@pytest.mark.parametrize("call", ["DIV(t, t)", "MUL(t, TRUE)", "DIV(t)"])
def test_a_time_with_no_number_beside_it_is_still_refused(call):
    text = f"PROGRAM P VAR t : TIME := T#1s; x : TIME; END_VAR x := {call}; END_PROGRAM"
    assert errors(text, "matiec")


INTERNAL = """FUNCTION_BLOCK Counter
VAR_OUTPUT q : BOOL; END_VAR
VAR count : INT; END_VAR
count := count + 1;
q := count > 2;
END_FUNCTION_BLOCK
PROGRAM Main
VAR c : Counter; seen : INT; END_VAR
c.count := 10;
c();
seen := c.count;
END_PROGRAM
"""


def test_matiec_lets_a_program_use_a_blocks_internal_variable_with_a_warning():
    diags = check_sources([(INTERNAL, "f.st")], "matiec")[1]
    assert [d.code for d in diags if d.severity == "error"] == []
    assert [d.code for d in diags].count("PLC0353") == 2
    import plclab

    plc = plclab.loads(INTERNAL, dialect="matiec")
    plc.scan()
    assert plc["Main.seen"] == 11 and plc["Main.c.q"] is True


@pytest.mark.parametrize("dialect", ["iec", "codesys", "s7"])
def test_elsewhere_a_blocks_internal_variable_stays_hidden(dialect):
    assert errors(INTERNAL, dialect) == ["PLC0121", "PLC0121"]


def test_matiec_still_refuses_writing_a_blocks_output():
    text = INTERNAL.replace("c.count := 10;", "c.q := TRUE;")
    assert errors(text, "matiec") == ["PLC0105"]
