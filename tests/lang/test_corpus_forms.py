"""Forms of real-world code that the corpus measure found rejected (issue 23, ADR 0031):
MATIEC/Beremiz two-field word addresses, a POU copied from the CODESYS editor without its
END_ keyword, and CODESYS's TIME() function; each per dialect."""

from __future__ import annotations

import pytest

import plclab
from plclab.project import check_sources

BEREMIZ = """PROGRAM My_Program
VAR
    a AT %IW0.0 : INT;
    b AT %IW0.4 : INT;
    sum AT %QW0.2 : INT;
END_VAR
sum := ADD(a, b);
END_PROGRAM
"""
NO_END = """FUNCTION_BLOCK Counter
VAR_OUTPUT n : INT; END_VAR
n := n + 1;
"""
NO_END_BEFORE_NEXT = NO_END + """PROGRAM Main
VAR c : Counter; total : INT; END_VAR
c();
total := c.n;
END_PROGRAM
"""
SYSTIME = """PROGRAM Main
VAR t : TIME; END_VAR
t := TIME();
END_PROGRAM
"""


def codes(text: str, dialect: str | None = None) -> list[tuple[str, str]]:
    return [(d.code, d.severity) for d in check_sources([(text, "f.st")], dialect)[1]
            if d.code != "PLC0214"]


@pytest.mark.parametrize("dialect", ["matiec", "iec"])
def test_a_two_field_word_address_is_module_item_in_matiec_and_iec(dialect):
    assert codes(BEREMIZ, dialect) == [("PLC0175", "warning")] * 3
    plc = plclab.loads(BEREMIZ, dialect=dialect)
    plc["%IW0"], plc["%IW4"] = 20, 22
    plc.scan()
    assert plc["My_Program.sum"] == 42 and plc["%QW2"] == 42


@pytest.mark.parametrize("dialect", ["codesys", "s7"])
def test_a_two_field_word_address_stays_an_error_in_codesys_and_s7(dialect):
    diags = check_sources([(BEREMIZ, "f.st")], dialect)[1]
    errors = [d for d in diags if d.severity == "error"]
    assert [d.code for d in errors] == ["PLC0120"] * 3
    assert "{dialect 'matiec'}" in errors[0].message


def test_a_bit_address_keeps_byte_bit_in_matiec():
    text = "PROGRAM P VAR x AT %IX0.9 : BOOL; y AT %IX1.2 : BOOL; END_VAR y := x; END_PROGRAM"
    assert ("PLC0120", "error") in codes(text, "matiec")  # bit 9 of a byte, not an item


@pytest.mark.parametrize("text", [NO_END, NO_END_BEFORE_NEXT])
def test_codesys_accepts_a_pou_without_its_end_keyword_with_a_warning(text):
    assert codes(text) == [("PLC0280", "warning")]
    if "PROGRAM" in text:
        plc = plclab.loads(text)
        plc.scan(3)
        assert plc["Main.total"] == 3


@pytest.mark.parametrize("dialect", ["iec", "matiec", "s7"])
def test_the_other_dialects_need_the_end_keyword(dialect):
    assert ("PLC0010", "error") in codes(NO_END_BEFORE_NEXT, dialect)


def test_a_pou_broken_off_by_something_else_is_still_a_syntax_error():
    text = NO_END.replace("n := n + 1;", "n := n + 1;\nEND_VAR")
    assert ("PLC0010", "error") in codes(text)


def test_time_function_reads_the_plc_clock_in_codesys():
    assert codes(SYSTIME) == []
    plc = plclab.loads(SYSTIME, cycle_time="10ms")
    plc.scan(5)
    assert plc["Main.t"] == 40  # the fifth scan starts 40 ms after the first


@pytest.mark.parametrize("dialect", ["iec", "matiec", "s7"])
def test_time_function_is_codesys_only(dialect):
    assert codes(SYSTIME, dialect) == [("PLC0106", "error")]


def test_a_users_own_function_named_like_it_comes_first():
    own = "FUNCTION NOW_MS : TIME NOW_MS := T#5s; END_FUNCTION\n" + SYSTIME.replace(
        "TIME()", "NOW_MS()")
    assert codes(own, "iec") == []
