"""``ARRAY[*]``: variable-length arrays of a VAR_IN_OUT with LOWER_BOUND / UPPER_BOUND (IEC 61131-3
ed.3 6.5.3, CODESYS, TIA Portal S7-1500; issue 40 item 8, ADR 0060), per dialect, with the
wrong inputs each check must catch."""

from __future__ import annotations

import pytest

import plclab
from plclab.errors import PlcError
from plclab.lang.unparse import unparse
from plclab.project import check_sources, parse_sources

LIB = """
FUNCTION SumAll : DINT
VAR_IN_OUT a : ARRAY[*] OF INT; END_VAR
VAR i : DINT; END_VAR
SumAll := 0;
FOR i := LOWER_BOUND(a, 1) TO UPPER_BOUND(a, 1) DO
    SumAll := SumAll + a[i];
END_FOR
END_FUNCTION

FUNCTION Twice : DINT
VAR_IN_OUT a : ARRAY[*] OF INT; END_VAR
Twice := SumAll(a) * 2;   (* an ARRAY[*] passed on keeps the caller's bounds *)
END_FUNCTION

FUNCTION_BLOCK Fill
VAR_INPUT base : INT; END_VAR
VAR_IN_OUT m : ARRAY[*, *] OF INT; END_VAR
VAR i, j : DINT; END_VAR
FOR i := LOWER_BOUND(m, 1) TO UPPER_BOUND(m, 1) DO
    FOR j := LOWER_BOUND(m, 2) TO UPPER_BOUND(m, 2) DO
        m[i, j] := base + DINT_TO_INT(100 * i + j);
    END_FOR
END_FOR
END_FUNCTION_BLOCK

FUNCTION_BLOCK Stats
METHOD Span : DINT
VAR_IN_OUT v : ARRAY[*] OF REAL; END_VAR
Span := UPPER_BOUND(v, 1) - LOWER_BOUND(v, 1) + 1;
END_METHOD
END_FUNCTION_BLOCK
"""

MAIN = """
PROGRAM Main
VAR
    x : ARRAY[1..4] OF INT := [3, 5, 7, 11];
    y : ARRAY[-2..0] OF INT := [10, 20, 30];
    g : ARRAY[1..2, 5..7] OF INT;
    r : ARRAY[0..9] OF REAL;
    f : Fill;
    st : Stats;
    s1, s2, n, lo, hi, hi2 : DINT;
END_VAR
s1 := SumAll(x);
s2 := Twice(y);
f(base := 1000, m := g);
n := st.Span(r);
lo := LOWER_BOUND(y, 1);
hi := UPPER_BOUND(x, 1);
hi2 := UPPER_BOUND(g, 2);
END_PROGRAM
"""


def errors(text: str, dialect: str | None = None) -> list[str]:
    return [d.code for d in check_sources([(text, "v.st")], dialect)[1] if d.severity == "error"]


@pytest.mark.parametrize("dialect", ["iec", "codesys", "s7"])
def test_an_array_of_any_bounds_is_read_and_written_through_its_in_out(dialect):
    plc = plclab.loads(LIB + MAIN, dialect=dialect)
    plc.scan()
    x, y = [3, 5, 7, 11], [10, 20, 30]
    assert plc["Main.s1"] == sum(x)
    assert plc["Main.s2"] == 2 * sum(y)
    # the block wrote the caller's array, by its own bounds 1..2 and 5..7
    assert plc["Main.g"] == [1000 + 100 * i + j for i in (1, 2) for j in (5, 6, 7)]
    assert plc["Main.n"] == 10
    assert (plc["Main.lo"], plc["Main.hi"], plc["Main.hi2"]) == (-2, 4, 7)


def test_matiec_refuses_it_with_a_code_naming_the_edition():
    codes = errors(LIB + MAIN, "matiec")
    assert codes and set(codes) == {"PLC0351"}
    d = next(d for d in check_sources([(LIB, "v.st")], "matiec")[1] if d.code == "PLC0351")
    assert "ed.3" in d.message and "matiec" in d.message and d.location.line == 3


@pytest.mark.parametrize("decl", [
    "FUNCTION_BLOCK B VAR v : ARRAY[*] OF INT; END_VAR END_FUNCTION_BLOCK",
    "FUNCTION_BLOCK B VAR_INPUT v : ARRAY[*] OF INT; END_VAR END_FUNCTION_BLOCK",
    "FUNCTION_BLOCK B VAR_OUTPUT v : ARRAY[*] OF INT; END_VAR END_FUNCTION_BLOCK",
    "PROGRAM Q VAR_IN_OUT v : ARRAY[*] OF INT; END_VAR END_PROGRAM",
    "TYPE V : ARRAY[*] OF INT; END_TYPE",
    "TYPE S : STRUCT v : ARRAY[*] OF INT; END_STRUCT; END_TYPE",
    "VAR_GLOBAL v : ARRAY[*] OF INT; END_VAR",
    "FUNCTION F : INT VAR_IN_OUT v : ARRAY[1..2] OF ARRAY[*] OF INT; END_VAR F := 0; END_FUNCTION",
])
def test_a_variable_length_array_outside_a_var_in_out_is_refused(decl):
    assert "PLC0350" in errors(decl, "iec")


@pytest.mark.parametrize("expr", [
    "LOWER_BOUND(a, 2)", "UPPER_BOUND(a, 0)", "UPPER_BOUND(a)", "LOWER_BOUND(k, 1)",
    "UPPER_BOUND(a, k)",
])
def test_a_bound_of_a_dimension_that_is_not_there_is_refused(expr):
    text = f"""FUNCTION F : DINT
VAR_IN_OUT a : ARRAY[*] OF INT; END_VAR
VAR k : DINT := 1; END_VAR
F := {expr};
END_FUNCTION"""
    assert "PLC0352" in errors(text, "iec")


def test_bounds_of_a_declared_array_are_constants_and_a_wrong_dim_is_refused_there_too():
    text = "PROGRAM P VAR a : ARRAY[3..8, 0..1] OF INT; n : DINT; END_VAR\n{} END_PROGRAM"
    assert errors(text.format("n := UPPER_BOUND(a, 1) + LOWER_BOUND(a, 2);"), "iec") == []
    assert errors(text.format("n := UPPER_BOUND(a, 3);"), "iec") == ["PLC0352"]


@pytest.mark.parametrize("arg, why", [
    ("m", "two dimensions for one"), ("r", "REAL elements for INT"), ("k", "not an array"),
])
def test_an_argument_that_does_not_fit_the_array_of_any_bounds_is_refused(arg, why):
    text = LIB + f"""PROGRAM P
VAR m : ARRAY[1..2, 1..2] OF INT; r : ARRAY[1..2] OF REAL; k : DINT; END_VAR
k := SumAll({arg});
END_PROGRAM"""
    assert errors(text, "iec") == ["PLC0107"], why


def test_a_whole_assignment_from_or_to_it_and_a_wrong_index_count_are_refused():
    text = """FUNCTION F : INT
VAR_IN_OUT a : ARRAY[*] OF INT; END_VAR
VAR b : ARRAY[1..3] OF INT; END_VAR
{}
F := 0;
END_FUNCTION"""
    assert errors(text.format("a := b;"), "iec") == ["PLC0352"]
    assert errors(text.format("b := a;"), "iec") == ["PLC0352"]
    assert errors(text.format("F := a[1, 1];"), "iec") == ["PLC0117"]
    assert errors(text.format("F := a[2];"), "iec") == []


def test_an_index_outside_the_arguments_bounds_is_the_runtime_bound_fault():
    text = """FUNCTION ItemAt : INT
VAR_IN_OUT a : ARRAY[*] OF INT; END_VAR
VAR_INPUT i : DINT; END_VAR
ItemAt := a[i];
END_FUNCTION
PROGRAM P
VAR x : ARRAY[1..4] OF INT := [1, 2, 3, 4]; k : DINT := 4; r : INT; END_VAR
r := ItemAt(x, k);
END_PROGRAM"""
    plc = plclab.loads(text, dialect="iec")
    plc.scan()
    assert plc["P.r"] == 4
    for bad in (0, 5):
        plc = plclab.loads(text, dialect="iec")
        plc["P.k"] = bad
        with pytest.raises(PlcError) as info:
            plc.scan()
        assert info.value.code == "PLC2002"
        assert "1..4" in info.value.message and info.value.location.line == 4


def test_it_prints_back_as_written():
    files, diags = parse_sources([(LIB, "v.st")], "iec")
    assert not diags
    text = unparse(files[-1])
    assert "ARRAY[*] OF INT" in text and "ARRAY[*, *] OF INT" in text
    assert errors(text, "iec") == []
