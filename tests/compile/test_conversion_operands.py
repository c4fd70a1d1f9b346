"""A conversion's argument, a CASE selector and an array index are values of their own type
(ADR 0038): operators compute exactly, as in a register, but what a conversion receives is the
value the operand's type holds. Each reproduction of issue 30 gives the hardware's answer; a
FOR variable that a call or a reference can change is never trusted to stay in its bounds."""

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import plclab
from plclab.errors import PlcRuntimeFault
from plclab.runtime.plc import Plc

from .test_fast_paths import compile_both


def scan(src: str) -> Plc:
    plc = Plc(plclab.compile_sources([(src, "p.st")]))
    plc.scan()
    return plc


def main(decls: str, body: str) -> Plc:
    return scan(f"PROGRAM Main\nVAR {decls} END_VAR\n{body}\nEND_PROGRAM\n")


@pytest.mark.parametrize("decls,body,name,want", [
    # the SINT product wraps to 0 in a SINT, so SINT_TO_INT sees 0 (not -2097152)
    ("s : SINT := -128; i : INT;", "i := SINT_TO_INT(s * s * s);", "i", 0),
    # UINT 3 - 4 is 65535 in a UINT; widening keeps 65535 (d >= 0 holds)
    ("u : UINT := 3; d : UDINT;", "d := UINT_TO_UDINT(u - 4);", "d", 65535),
    ("dw : DWORD := 0; r : LREAL;", "r := DWORD_TO_LREAL(dw - 217);", "r", 4294967079.0),
    # a REAL sum is a REAL: 16777216.0 + 1.0 is 16777216.0 in single precision
    ("r : REAL := 16777216.0; k : DINT;", "k := REAL_TO_DINT(r + 1.0);", "k", 16777216),
    ("r : REAL := 16777216.0; k : DINT;", "k := TRUNC_DINT(r + 1.0);", "k", 16777216),
    ("r : REAL := 16777216.0; x : LREAL;", "x := REAL_TO_LREAL(r + 1.0);", "x", 16777216.0),
    # ... and so is the implicit widening of the same sum (ADR 0038, decision 4)
    ("r : REAL := 16777216.0; x : LREAL;", "x := r + 1.0;", "x", 16777216.0),
    ("r : REAL := 16777216.0; x : LREAL;", "x := MAX(r + 1.0, 0.0);", "x", 16777216.0),
    ("r : REAL := 0.1; x : LREAL;", "x := r;", "x", float.fromhex("0x1.99999ap-4")),
    # ... as an operand of an LREAL operation, a function or a comparison
    ("r : REAL := 16777216.0; y : LREAL := 0.0; x : LREAL;", "x := (r + 1.0) + y;", "x",
     16777216.0),
    ("r : REAL := 16777216.0; y : LREAL := 0.0; x : LREAL;", "x := MAX(r + 1.0, y);", "x",
     16777216.0),
    ("r : REAL := 16777216.0; y : LREAL := 16777216.5; b : BOOL;", "b := (r + 1.0) < y;", "b",
     True),
    # an LREAL sum stays a double
    ("r : LREAL := 16777216.0; x : LREAL;", "x := r + 1.0;", "x", 16777217.0),
    # a stored value needs nothing: the same conversions of variables
    ("s : SINT := -128; i : INT;", "i := SINT_TO_INT(s);", "i", -128),
    ("u : UINT := 65535; d : UDINT;", "d := UINT_TO_UDINT(u);", "d", 65535),
    # without a conversion a store wraps the exact value to the target (ADR 0002)
    ("u : UINT := 3; d : UDINT;", "d := u - 4;", "d", 4294967295),
    # a CASE selector of type UINT: 3 - 4 is 65535
    ("u : UINT := 3; c : INT;", "CASE u - 4 OF 65535: c := 1; ELSE c := 2; END_CASE;", "c", 1),
    # an index of type USINT: 250 + 10 is 4
    ("a : ARRAY[0..9] OF INT := [0, 1, 2, 3, 44, 5, 6, 7, 8, 9]; b : USINT := 250; x : INT;",
     "x := a[b + 10];", "x", 44),
])
def test_a_converted_operand_is_a_value_of_its_type(decls, body, name, want):
    assert main(decls, body)[name] == want


def test_an_lreal_input_given_a_real_sum_gets_the_real_value():
    plc = scan("""
FUNCTION Id : LREAL
VAR_INPUT x : LREAL; END_VAR
Id := x;
END_FUNCTION
PROGRAM Main
VAR r : REAL := 16777216.0; a, b : LREAL; END_VAR
a := Id(r + 1.0);
b := Id(REAL_TO_LREAL(r + 1.0));
END_PROGRAM
""")
    assert plc["a"] == plc["b"] == 16777216.0


def test_a_widened_value_never_leaves_the_target_type():
    plc = main("s : SINT := -128; i : INT; u : UINT := 3; d : UDINT; ok : BOOL;",
               "i := SINT_TO_INT(s * s * s); d := UINT_TO_UDINT(u - 4); ok := d >= 0;")
    assert -32768 <= plc["i"] <= 32767 and 0 <= plc["d"] <= 4294967295 and plc["ok"] is True


def test_a_function_input_holds_a_value_of_its_type():
    plc = scan("""
FUNCTION Id : INT
VAR_INPUT x : INT; END_VAR
Id := x;
END_FUNCTION
PROGRAM Main
VAR s : SINT := -128; i : INT; END_VAR
i := Id(SINT_TO_INT(s * s * s));
END_PROGRAM
""")
    assert plc["i"] == 0


BACK = """
FUNCTION Back : BOOL
VAR_IN_OUT v : INT; END_VAR
v := v - {k};
Back := TRUE;
END_FUNCTION
"""


@pytest.mark.parametrize("where", ["program", "function"])
def test_a_for_variable_changed_by_a_call_is_still_bounds_checked(where):
    body = "FOR i := 0 TO 9 DO Back(i); r := a[i]; a[i] := 1; END_FOR;"
    decl = "a : ARRAY[0..9] OF INT; i : INT; r : INT;"
    if where == "program":
        src = BACK.format(k=3) + f"PROGRAM Main\nVAR {decl} END_VAR\n{body}\nEND_PROGRAM\n"
    else:
        src = BACK.format(k=3) + (f"FUNCTION F : INT\nVAR {decl} END_VAR\n{body}\nF := r;\n"
                                  "END_FUNCTION\nPROGRAM Main\nVAR x : INT; END_VAR\nx := F();\n"
                                  "END_PROGRAM\n")
    with pytest.raises(PlcRuntimeFault) as e:
        scan(src)
    assert e.value.code == "PLC2002" and "-3" in e.value.message


def test_a_for_variable_changed_through_a_reference_is_still_bounds_checked():
    src = """
PROGRAM Main
VAR a : ARRAY[0..9] OF INT; i : INT; r : INT; p : REF_TO INT; END_VAR
p := REF(i);
FOR i := 0 TO 9 DO p^ := p^ - 3; r := a[i]; END_FOR;
END_PROGRAM
"""
    with pytest.raises(PlcRuntimeFault) as e:
        scan(src)
    assert e.value.code == "PLC2002"


def _outcome(compiled, n: int):
    plc = Plc(compiled)
    plc["Main.n"] = n
    try:
        plc.scan()
    except PlcRuntimeFault as e:
        return ("fault", e.code)
    return ("ok", plc["Main.r"], plc["Main.x"], list(plc["Main.a"]))


ALIASING = [
    "Back(i);",                       # VAR_IN_OUT of a function
    "fb(io := i);",                   # VAR_IN_OUT of a block
    "p^ := p^ - n;",                  # a reference taken before the loop
    "Shift();",                       # an action writes the member
    "fb(v := i, io := x2, o => i);",  # an output argument
]


@settings(max_examples=60, deadline=None, database=None)
@given(k=st.integers(-4, 4), n=st.integers(0, 5), which=st.integers(0, len(ALIASING) - 1),
       d=st.integers(-12, 12))
def test_fast_and_plain_code_agree_when_the_loop_variable_is_aliased(k, n, which, d):
    """A FOR with literal bounds whose variable the body changes behind its back: with and
    without the fast paths the PLC ends in the same state or the same fault (an index, a
    MOD and a division by the loop variable included)."""
    src = BACK.format(k=k) + f"""
FUNCTION_BLOCK FB
VAR_INPUT v : INT; END_VAR
VAR_IN_OUT io : INT; END_VAR
VAR_OUTPUT o : INT; END_VAR
io := io - {k};
o := v + {k};
END_FUNCTION_BLOCK
PROGRAM Main
VAR a : ARRAY[0..9] OF INT; i : INT; r : INT; x : DINT; n : INT; fb : FB;
    p : REF_TO INT; x2 : INT; END_VAR
p := REF(i);
FOR i := 0 TO 9 DO
    {ALIASING[which]}
    r := a[i];
    a[i] := a[i] + 1;
    x := x + i MOD 3 + 100 / (i + 11);
    IF i > 20 OR i < -20 THEN EXIT; END_IF
END_FOR;
END_PROGRAM
ACTION Main.Shift
i := i + {d};
END_ACTION
"""
    fast, plain = compile_both(src)
    assert _outcome(fast, n) == _outcome(plain, n)


def test_s7_folds_a_constant_sum_in_the_operands_width():
    src = ("PROGRAM Main\nVAR x : INT; END_VAR\nx := (INT#24584 + INT#32766) / INT#32767;\n"
           "END_PROGRAM\n")
    plc = Plc(plclab.compile_sources([(src, "p.st")], dialect="s7"))
    plc.scan()
    assert plc["x"] == 0  # 24584 + 32766 is -8186 in an INT; -8186 / 32767 truncates to 0


@pytest.mark.parametrize("decls,body,name,want", [
    ("n : DINT := 70000; i : INT;", "i := n;", "i", 4464),
    ("n : INT := -1; b : BYTE;", "b := n;", "b", 255),
    ("u : UINT := 65535; i : INT;", "i := u;", "i", -1),
])
def test_codesys_implicit_integer_conversion_wraps_like_the_conversion(decls, body, name, want):
    from plclab.project import check_sources

    src = f"PROGRAM Main\nVAR {decls} END_VAR\n{body}\nEND_PROGRAM\n"
    assert main(decls, body)[name] == want  # the default dialect is codesys
    warned = [d.code for d in check_sources([(src, "p.st")])[1]]
    assert "PLC0285" in warned
    strict = [d.code for d in check_sources([("{dialect 'iec'}\n" + src, "p.st")])[1]
              if d.severity == "error"]
    assert strict == ["PLC0118"]
