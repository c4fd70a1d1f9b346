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


# -- the committed corpus (tests/corpus/st, ADR 0035) -------------------------------------------
REAL_TO_INT = """PROGRAM Main
VAR r : REAL := 2.5; i : INT; END_VAR
i := r;
END_PROGRAM
"""
OWN_METHOD = """FUNCTION_BLOCK B
VAR_OUTPUT n : INT; END_VAR
Bump();
METHOD Bump
  n := n + 1;
END_METHOD
END_FUNCTION_BLOCK
"""


def test_codesys_rounds_an_implicit_real_to_int_with_a_warning():
    assert codes(REAL_TO_INT, "codesys") == [("PLC0283", "warning")]
    plc = plclab.loads(REAL_TO_INT, "f.st", dialect="codesys")
    plc.scan(1)
    assert plc["Main.i"] == 3  # as REAL_TO_INT(2.5): half away from zero


@pytest.mark.parametrize("dialect", ["iec", "s7", "matiec"])
def test_an_implicit_real_to_int_stays_an_error_elsewhere(dialect):
    assert codes(REAL_TO_INT, dialect) == [("PLC0118", "error")]


def test_an_implicit_nan_to_int_faults_like_real_to_int():
    src = REAL_TO_INT.replace("i := r;", "r := SQRT(r - 3.0);\ni := r;")
    plc = plclab.loads(src, "f.st", dialect="codesys")
    with pytest.raises(plclab.PlcError) as exc:
        plc.scan(1)
    assert exc.value.code == "PLC2006"


@pytest.mark.parametrize("dialect", ["codesys", "iec"])
def test_a_method_called_by_its_name_inside_its_block(dialect):
    assert codes(OWN_METHOD, dialect) == []


def test_a_name_that_is_no_method_is_still_unknown():
    assert ("PLC0106", "error") in codes(OWN_METHOD.replace("Bump();", "Bumpp();"))


def test_a_variable_hides_a_method_of_the_same_name():
    src = OWN_METHOD.replace("VAR_OUTPUT n : INT; END_VAR",
                             "VAR_OUTPUT n : INT; END_VAR VAR Bump : TON; END_VAR")
    assert ("PLC0106", "error") not in codes(src)  # Bump() calls the TON instance


SIZEOF = """PROGRAM Main
VAR buf : ARRAY[0..4] OF INT; t : TON; n : UDINT; END_VAR
n := SIZEOF(buf);
END_PROGRAM
"""


def test_sizeof_is_a_constant_in_codesys():
    assert [c for c in codes(SIZEOF, "codesys") if c[1] == "error"] == []
    plc = plclab.loads(SIZEOF, "f.st", dialect="codesys")
    plc.scan(1)
    assert plc["Main.n"] == 10


def test_sizeof_of_an_instance_has_no_size():
    assert ("PLC0197", "error") in codes(SIZEOF.replace("SIZEOF(buf)", "SIZEOF(t)"), "codesys")
    assert ("PLC0197", "error") in codes(SIZEOF.replace("SIZEOF(buf)", "SIZEOF(buf, t)"))


@pytest.mark.parametrize("dialect", ["iec", "matiec"])
def test_sizeof_is_codesys_only(dialect):
    assert ("PLC0106", "error") in codes(SIZEOF, dialect)


ACTIONS = """FUNCTION_BLOCK Counter
VAR_INPUT in : BOOL; END_VAR
VAR_OUTPUT out : INT; END_VAR
IF in THEN out := out + 1; END_IF
END_FUNCTION_BLOCK
ACTIONS Counter
  ACTION Reset
    out := 0;
  END_ACTION
END_ACTIONS
PROGRAM Main
VAR c : Counter; n : INT; ticks : INT; END_VAR
c(in := TRUE);
ticks := ticks + 1;
IF ticks = 5 THEN
  c.Reset(in := FALSE, out => n);
END_IF
Tick();
END_PROGRAM
ACTION Main.Tick
  n := n + 100;
END_ACTION
"""


def test_codesys_actions_of_a_block_and_a_program_run():
    assert [c for c in codes(ACTIONS, "codesys") if c[1] == "error"] == []
    plc = plclab.loads(ACTIONS, "f.st", dialect="codesys")
    plc.scan(5)
    assert (plc["Main.c.out"], plc["Main.n"]) == (0, 100)  # Reset at the 5th scan, then Tick
    plc.scan(2)
    assert (plc["Main.c.out"], plc["Main.n"]) == (2, 300)


def test_an_action_call_from_instruction_list():
    src = ACTIONS.split("PROGRAM Main")[0] + """PROGRAM Main
VAR c : Counter; n : INT; END_VAR
CAL c(in := TRUE)
CAL c(in := TRUE)
CAL c.Reset(in := FALSE)
LD c.out
ADD 7
ST n
END_PROGRAM
"""
    plc = plclab.loads(src, "f.st", dialect="codesys")
    plc.scan(1)
    assert plc["Main.n"] == 7


@pytest.mark.parametrize("dialect", ["iec", "matiec", "s7"])
def test_actions_outside_sfc_are_codesys_only(dialect):
    assert ("PLC0198", "error") in codes(ACTIONS, dialect)


@pytest.mark.parametrize("change", [
    ("ACTIONS Counter", "ACTIONS Countr"),               # no such POU in the file
    ("Tick();", "ticks := Tick();"),                     # an action has no value
])
def test_misplaced_actions_are_reported(change):
    assert ("PLC0198", "error") in codes(ACTIONS.replace(*change), "codesys")


def test_two_actions_of_one_name():
    src = ACTIONS.replace("END_ACTIONS", "  ACTION Reset\n    out := 1;\n  END_ACTION\nEND_ACTIONS")
    assert ("PLC0235", "error") in codes(src, "codesys")


REFERENCE = """PROGRAM Main
VAR level : INT; alias : REFERENCE TO INT; bind : BOOL := TRUE; END_VAR
IF bind THEN
  alias REF= level;
END_IF
alias := alias + 2;
END_PROGRAM
"""


def test_reference_to_is_the_variable_it_is_bound_to():
    assert [c for c in codes(REFERENCE, "codesys") if c[1] == "error"] == []
    plc = plclab.loads(REFERENCE, "f.st", dialect="codesys")
    plc.scan(3)
    assert plc["Main.level"] == 6


def test_an_unbound_reference_to_faults_when_used():
    plc = plclab.loads(REFERENCE.replace(":= TRUE", ":= FALSE"), "f.st", dialect="codesys")
    with pytest.raises(plclab.PlcError) as exc:
        plc.scan(1)
    assert exc.value.code == "PLC9111"


def test_reference_to_a_function_local_only_inside_the_call():
    src = """FUNCTION F : INT
VAR x : INT; r : REFERENCE TO INT; END_VAR
r REF= x;
F := r;
END_FUNCTION
"""
    # read inside the call only: accepted with its warning (issue 33, ADR 0051)
    assert ("PLC0292", "warning") in codes(src, "codesys")
    kept = src.replace("VAR x : INT; r : REFERENCE TO INT; END_VAR",
                       "VAR_OUTPUT r : REFERENCE TO INT; END_VAR VAR x : INT; END_VAR")
    assert ("PLC0240", "error") in codes(kept, "codesys")  # an output outlives the call


@pytest.mark.parametrize("dialect", ["iec", "s7", "matiec"])
def test_reference_to_is_codesys_only(dialect):
    assert ("PLC0239", "error") in codes(REFERENCE, dialect)
