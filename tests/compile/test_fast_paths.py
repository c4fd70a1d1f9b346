"""The generator's fast paths (plclab/compile/fastpaths.py, ADR 0024) end in exactly the state
the plain code does: each program is compiled twice, with and without them, and both PLCs are
run on the same random inputs; their variables, faults and watchdog budgets must agree."""

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import plclab
from plclab.compile import fastpaths
from plclab.compile.real32 import f32, single_cell
from plclab.errors import PlcRuntimeFault
from plclab.runtime.plc import Plc


def compile_both(src: str):
    """The program compiled with and without the fast paths."""
    fast = plclab.compile_sources([(src, "p.st")])
    fastpaths.ENABLED = False
    try:
        plain = plclab.compile_sources([(src, "p.st")])
    finally:
        fastpaths.ENABLED = True
    return fast, plain


def plc_both(src: str | tuple, **options) -> tuple[Plc, Plc]:
    fast, plain = compile_both(src) if isinstance(src, str) else src
    return Plc(fast, **options), Plc(plain, **options)


def run(plc: Plc, inputs: dict, scans: int = 1):
    for k, v in inputs.items():
        plc[k] = v
    try:
        plc.scan(scans)
        fault = None
    except PlcRuntimeFault as exc:
        fault = (exc.code, str(exc))
    return fault, {k: plain_value(plc[k]) for k in plc.variables()}, plc.budget.left


def plain_value(v):
    """Lists element-wise, block instances as dicts of their members."""
    if isinstance(v, list):
        return [plain_value(x) for x in v]
    slots = getattr(type(v), "__slots__", None)
    if slots is not None:
        return {s: plain_value(getattr(v, s)) for s in slots if hasattr(v, s)}
    return v


def test_the_fast_code_is_really_emitted():
    """The comparison below would be empty if the fast paths never fired."""
    code = plclab.compile_sources([(LOOPS, "x.st")]).source
    assert "_F32[0] =" in code and "v_0L" in code and "finally:" in code
    assert "_imod" not in code.split("class P_MAIN")[1] and "_B.left = _t" in code
    assert "[v_0L" in code and "+ 1]" in code  # b[k + 1] with low bound 0 folded
    assert "!= 0 else _rdiv(" in plclab.compile_sources([(REALS, "x.st")]).source


DIVS = """
PROGRAM Main
VAR a : LINT; d : DINT; m1, m2, m3, m4, m5 : LINT; q1, q2, q3, q4 : LINT; i : INT;
    s : DINT; e : DINT; END_VAR
m1 := a MOD 10; m2 := a MOD -7; m3 := a MOD 1; m4 := a MOD 2147483647; m5 := d MOD 1000;
q1 := a / 10; q2 := a / -7; q3 := a / -1; q4 := d / 3;
s := 0;
FOR i := 0 TO 9 DO
    s := s + i MOD 4 + i / 3;
END_FOR
e := DINT_TO_INT(d MOD 100000);
END_PROGRAM
"""
_DIVS = plc_both(DIVS)


@settings(max_examples=300, deadline=None, database=None)
@given(a=st.integers(-(2**63), 2**63 - 1) | st.integers(-30, 30),
       d=st.integers(-(2**31), 2**31 - 1))
def test_mod_and_division_by_a_literal_match_the_helpers(a, d):
    fast, plain = _DIVS
    got = run(fast, {"Main.a": a, "Main.d": d})
    want = run(plain, {"Main.a": a, "Main.d": d})
    assert got == want
    assert got[1]["Main.m1"] == int(math.fmod(a, 10)) if abs(a) < 2**52 else True


@settings(max_examples=300, deadline=None, database=None)
@given(st.floats(allow_nan=True, allow_infinity=True) | st.integers(-(2**70), 2**70))
def test_the_float32_cell_rounds_as_f32(x):
    _, rounded = single_cell()
    a, b = rounded(x), f32(x)
    assert a == b or (math.isnan(a) and math.isnan(b))
    assert math.copysign(1, a) == math.copysign(1, b) or math.isnan(a)


REALS = """
PROGRAM Main
VAR a, b, q1, q2 : REAL; la, lb, q3 : LREAL; END_VAR
q1 := a / b;
q2 := 1.5 / b;
q3 := la / lb;
END_PROGRAM
"""
_REALS = plc_both(REALS)


@settings(max_examples=200, deadline=None, database=None)
@given(a=st.floats(width=32), b=st.floats(width=32) | st.sampled_from([0.0, -0.0]),
       la=st.floats(), lb=st.floats() | st.just(0.0))
def test_real_division_inline_matches_the_helper(a, b, la, lb):
    """Division by zero faults (PLC2001) at the same place; NaN and infinities pass through."""
    fast, plain = (Plc(p.compiled) for p in _REALS)
    inputs = {"Main.a": a, "Main.b": b, "Main.la": la, "Main.lb": lb}
    got, want = run(fast, inputs), run(plain, inputs)
    assert repr(got) == repr(want)  # repr: NaN compares unequal to itself


LOOPS = """
PROGRAM Main
VAR a : ARRAY[1..10] OF INT; b : ARRAY[0..4] OF REAL; i, j, k, n, lim, hits : INT;
    stop : INT; r : REAL; w : DINT; x : DINT; flag : BOOL; END_VAR
hits := 0;
FOR i := 1 TO n DO
    a[i] := a[i] + i * 3;
    IF a[i] > lim THEN hits := hits + 1; END_IF
    IF i = stop THEN EXIT; END_IF
END_FOR
FOR j := 0 TO 4 DO
    r := r * 0.5 + DINT_TO_REAL(j);
    b[j] := b[j] + r;
    FOR k := j TO 4 DO
        x := x + k MOD 3;
    END_FOR
    FOR k := 0 TO 3 DO
        b[k + 1] := b[k + 1] + b[k] * 0.5;
    END_FOR
END_FOR
FOR k := 1 TO 9 DO
    IF a[k] > a[k + 1] THEN hits := hits + 1; END_IF
END_FOR
k := lim;
WHILE k > 0 DO
    k := k - 1;
    w := w + 1;
END_WHILE
REPEAT
    x := x - 1;
    flag := x < lim;
UNTIL flag END_REPEAT
END_PROGRAM
"""


_LOOPS = compile_both(LOOPS)


@settings(max_examples=150, deadline=None, database=None)
@given(n=st.integers(-2, 12), lim=st.integers(-5, 60), stop=st.integers(0, 12),
       watchdog=st.integers(1, 200), scans=st.integers(1, 3))
def test_local_loops_end_in_the_plain_state_faults_included(n, lim, stop, watchdog, scans):
    """n > 10 indexes past the array (a fault inside the loop), a small watchdog stops a loop
    half way: the variables written back must be those of the plain code."""
    fast, plain = plc_both(_LOOPS, watchdog=watchdog)
    inputs = {"Main.n": n, "Main.lim": lim, "Main.stop": stop}
    assert run(fast, inputs, scans) == run(plain, inputs, scans)


def test_a_loop_with_a_call_keeps_the_plain_code():
    src = """
FUNCTION_BLOCK Bump
VAR_IN_OUT v : INT; END_VAR
v := v + 1;
END_FUNCTION_BLOCK
PROGRAM Main
VAR i, t : INT; b : Bump; END_VAR
FOR i := 1 TO 3 DO
    b(v := t);
END_FOR
END_PROGRAM
"""
    code = plclab.compile_sources([(src, "x.st")]).source
    assert "v_0L" not in code
    fast, plain = plc_both(src)
    assert run(fast, {}) == run(plain, {}) and fast["Main.t"] == 3


@pytest.mark.parametrize("value", [0.1, -2.5, 1e38, -1e38, 1.5e-45])
def test_real_store_rounds_like_a_conversion(value):
    """A store through the cell (r) rounds as the conversion function does (s); 3e38 is
    beyond REAL and gives inf."""
    src = """
PROGRAM Main
VAR x : REAL; r : REAL; s : REAL; END_VAR
r := x * 3.0;
s := LREAL_TO_REAL(REAL_TO_LREAL(x) * 3.0);
END_PROGRAM
"""
    fast, _ = plc_both(src)
    assert "_F32[0] = " in fast.compiled.source
    run(fast, {"Main.x": value})
    assert fast["Main.r"] == fast["Main.s"] == f32(f32(value) * 3.0)


STRINGS = """
PROGRAM Main
VAR s, t, r1, r2, r3, r4, r5, r6, r7, r8 : STRING; w : WSTRING; p, n, f1, f2 : INT; END_VAR
f1 := FIND(s, 'ab'); f2 := FIND(s, t);
r1 := LEFT(s, n); r2 := LEFT(s, p - n);
r3 := REPLACE(s, t, n, p); r4 := REPLACE(s, 'xy', 2, p + 1); r5 := REPLACE(s, t, n, 3);
r6 := INSERT(s, t, p); r7 := INSERT(s, '!', LEN(s)); r8 := INSERT(s, t, 2);
END_PROGRAM
"""
_STRINGS = plc_both(STRINGS)


def test_string_functions_are_inline():
    body = _STRINGS[0].compiled.source.split("class P_MAIN")[1]
    assert "_str_find(self.S, 'ab') + 1" in body and " _find(" in body  # FIND(s, t) may get '' : helper
    assert "_left(" not in body and "_replace(" not in body and "_insert(" not in body


@settings(max_examples=300, deadline=None, database=None)
@given(s=st.text("abxy!", max_size=12), t=st.text("ab", max_size=3),
       p=st.integers(-3, 15), n=st.integers(-3, 15))
def test_inline_string_functions_match_the_helpers(s, t, p, n):
    fast, plain = _STRINGS
    inputs = {"Main.s": s, "Main.t": t, "Main.p": p, "Main.n": n}
    assert run(fast, inputs) == run(plain, inputs)


def test_a_string_function_of_a_call_keeps_the_helper():
    """An argument that could fault or call user code keeps the helper (and its order)."""
    src = """
FUNCTION F : INT VAR_INPUT x : INT; END_VAR F := x; END_FUNCTION
PROGRAM Main VAR s, r : STRING; a : ARRAY[0..3] OF INT; p : INT; END_VAR
r := LEFT(s, F(p)); r := INSERT(s, 'x', a[p]); r := REPLACE(s, 'x', 1, p / 2);
END_PROGRAM
"""
    body = plclab.compile_sources([(src, "x.st")]).source.split("class P_MAIN")[1]
    assert body.count("_left(") == 1 and "_insert(" in body and "_replace(" in body
