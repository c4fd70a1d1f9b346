"""Named regression tests for the arithmetic bugs the oracle (test_arith_oracle.py) and issue 11
found; the chosen semantics are in docs/adr/0002-arithmetic-semantics.md."""

import math
import struct

import pytest

import plclab
from plclab.errors import PlcRuntimeFault


def run(decls: str, body: str):
    plc = plclab.loads(f"PROGRAM P\nVAR {decls} END_VAR\n{body}\nEND_PROGRAM\n", "r.st")
    plc.scan()
    return plc


def fault(decls: str, body: str) -> PlcRuntimeFault:
    with pytest.raises(PlcRuntimeFault) as ei:
        run(decls, body)
    return ei.value


def single(x: float) -> float:
    return struct.unpack("<f", struct.pack("<f", x))[0]


# -- the three miscompiles of issue 11 ------------------------------------------------------
def test_narrowing_conversion_inside_a_product():
    plc = run("a : INT := 4; b : DINT := 3; x : INT;", "x := a * DINT_TO_INT(b);")
    assert plc["x"] == 12  # was -32756


def test_real_to_int_inside_a_product():
    plc = run("x : INT;", "x := REAL_TO_INT(2.0) * 3;")
    assert plc["x"] == 6  # was 2


OSCAT_GCD = """
FUNCTION GCD : INT  (* OSCAT BASIC: greatest common divisor, Euclid with MOD *)
VAR_INPUT A, B : DINT; END_VAR
VAR t : DINT; END_VAR
IF A = 0 THEN
    GCD := DINT_TO_INT(ABS(B));
ELSIF B = 0 THEN
    GCD := DINT_TO_INT(ABS(A));
ELSE
    A := ABS(A);
    B := ABS(B);
    REPEAT
        t := A MOD B;
        A := B;
        B := t;
    UNTIL B = 0
    END_REPEAT;
    GCD := DINT_TO_INT(A);
END_IF;
END_FUNCTION
PROGRAM P
VAR a : DINT := 36; b : DINT := 24; g, g0, lcm : INT; END_VAR
g := GCD(a, b);
g0 := GCD(0, -b);
lcm := DINT_TO_INT(b) / GCD(a, b) * DINT_TO_INT(a);
END_PROGRAM
"""


def test_oscat_gcd():
    plc = plclab.loads(OSCAT_GCD, "gcd.st")
    plc.scan()
    assert (plc["g"], plc["g0"], plc["lcm"]) == (12, 24, 72)  # lcm was -32696


# -- found by the oracle --------------------------------------------------------------------
def test_mux_evaluates_only_the_selected_input():
    plc = run("z : INT; x : INT;", "x := MUX(1, 10 / z, 5, 10 / z);")
    assert plc["x"] == 5  # the unselected 10 / 0 is not computed (CODESYS)
    f = fault("k : INT := 3; x : INT;", "x := MUX(k, 1, 2, 3);")
    assert f.code == "PLC2002" and "K = 3" in f.message


def test_comparison_function_evaluates_every_input():
    plc = run("a : INT := 3; b : INT := 2; c : INT := 1; x, y : BOOL;",
              "x := GT(a, b, c); y := GT(a, c, b);")
    assert (plc["x"], plc["y"]) == (True, False)
    # EQ(1, 2, ...) is FALSE already, but its third input is still computed (and faults)
    f = fault("z : INT; x : BOOL;", "x := EQ(1, 2, 10 / z);")
    assert f.code == "PLC2001"


def test_time_and_ltime_inputs_are_compared_in_one_unit():
    plc = run("t : TIME := T#1ms; lt : LTIME := LTIME#2ns; m : LTIME; x : BOOL;",
              "m := MIN(t, lt); x := GT(t, lt);")
    assert plc["m"] == 2 and plc["x"] is True  # 1 ms > 2 ns (was compared as 1 > 2)


def test_sel_of_an_integer_into_lreal_gives_a_float():
    plc = run("g : BOOL; i : INT := -1258; r : LREAL := 0.5; x : LREAL; y : REAL;",
              "x := SEL(g, i, r); y := MAX(i, REAL#-2000.0);")
    assert type(plc["x"]) is float and plc["x"] == -1258.0
    assert type(plc["y"]) is float and plc["y"] == -1258.0


def test_time_widened_to_ltime_wraps_on_store():
    plc = run("t : TIME := T#2000000ms; x : LTIME;", "x := t * 10000000;")
    want = (2_000_000 * 10_000_000 * 1_000_000 + 2 ** 63) % 2 ** 64 - 2 ** 63
    assert plc["x"] == want


def test_shift_counts_of_the_width_or_more_give_zero():
    plc = run("b : BYTE := 16#81; n : LINT := 4611686018427387904; x, y, z, w : BYTE;",
              "x := SHL(b, 8); y := SHL(b, n); z := SHR(b, n); w := ROL(b, 9);")
    assert (plc["x"], plc["y"], plc["z"], plc["w"]) == (0, 0, 0, 0x03)  # SHL(b, 2**62) ran
    # out of memory before


def test_negative_shift_count_is_a_fault():
    f = fault("b : BYTE := 1; n : INT := -1; x : BYTE;", "x := ROL(b, n);")
    assert f.code == "PLC2020" and "N = -1" in f.message and f.location.line == 3


def test_shift_of_a_signed_integer_reinterprets_the_bit_pattern():
    plc = run("i : INT := -1; s : SINT := -128; x : BOOL; y : INT; z : SINT;",
              "x := SHL(i, 1) < 0; y := SHR(i, 1); z := ROL(s, 1);")
    assert (plc["x"], plc["y"], plc["z"]) == (True, 32767, 1)


def test_integer_power_is_bounded_and_ieee():
    plc = run("y : LINT := 3; z : LINT := 9223372036854775807; u : ULINT := 7; i : INT := 1000;"
              "a, b, c, d, e, f : LREAL; r : REAL;",
              "a := y ** z; b := (-y) ** z; c := u ** i; d := y ** (-z); e := 0 ** -1;"
              "f := 2 ** -1; r := REAL#-10.0 ** 309;")
    assert (plc["a"], plc["b"], plc["c"]) == (math.inf, -math.inf, math.inf)
    assert (plc["d"], plc["e"], plc["f"], plc["r"]) == (0.0, math.inf, 0.5, -math.inf)


def test_real_power_special_cases():
    plc = run("a, b, c : LREAL;", "a := LREAL#-8.0 ** (1.0 / 3.0); b := EXPT(LREAL#-0.0, -1);"
              "c := EXPT(LREAL#0.0, -2.0);")
    assert math.isnan(plc["a"]) and plc["b"] == -math.inf and plc["c"] == math.inf


def test_math_functions_give_ieee_values_not_python_errors():
    plc = run("inf : REAL; big : REAL := 3.0E38; s, l, q, a, lg : REAL;",
              "inf := big * 10.0; s := SIN(inf); l := LN(REAL#0.0); q := SQRT(REAL#-1.0);"
              "a := ACOS(REAL#2.0); lg := LOG(REAL#-1.0);")
    assert plc["inf"] == math.inf
    assert math.isnan(plc["s"]) and plc["l"] == -math.inf and math.isnan(plc["q"])
    assert math.isnan(plc["a"]) and math.isnan(plc["lg"])
    f = fault("big : REAL := 3.0E38; inf : REAL; x : INT;",
              "inf := big * 10.0; x := REAL_TO_INT(inf);")
    assert f.code == "PLC2006"


def test_real_to_integer_rounds_half_away_from_zero_exactly():
    plc = run("a : LREAL := 0.49999999999999994; b : LREAL := 4503599627370497.0;"
              "c : REAL := -2.5; d : REAL := 2.5; e : LREAL := -0.5; w, x, y, z, v : LINT;",
              "w := LREAL_TO_LINT(a); x := LREAL_TO_LINT(b); y := REAL_TO_LINT(c);"
              "z := REAL_TO_LINT(d); v := LREAL_TO_LINT(e);")
    assert (plc["w"], plc["x"], plc["y"], plc["z"], plc["v"]) == (0, 4503599627370497, -3, 3, -1)


def test_lint_to_real_rounds_once():
    v = 2 ** 60 + 2 ** 36 + 1  # through a double it rounds to 2**60, directly to 2**60 + 2**37
    plc = run(f"i : LINT := {v}; r, s : REAL;", "r := LINT_TO_REAL(i); s := i;")
    assert plc["r"] == 2.0 ** 60 + 2.0 ** 37
    assert plc["s"] == plc["r"]


def test_trunc_and_round_give_a_dint():
    plc = run("r : LREAL := 3.0E9; a, b : DINT; c : BOOL;",
              "a := TRUNC(r); b := ROUND(r); c := TRUNC(r) > 0;")
    assert plc["a"] == plc["b"] == 3_000_000_000 - 2 ** 32 and plc["c"] is False


def test_atan2_of_reals_is_a_real():
    plc = run("y : REAL := 1.0; x : REAL := 3.0; a : REAL; la : LREAL;",
              "a := ATAN2(y, x); la := ATAN2(y, x);")
    assert plc["la"] == single(math.atan2(1.0, 3.0)) == plc["a"]
