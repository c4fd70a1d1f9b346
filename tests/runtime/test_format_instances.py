"""``Plc.format`` (``run --print``) writes a block instance as an IEC structured literal of its
inputs, outputs and variables, inherited ones first, nested instances and aggregates each by
its own type; never a Python repr (issue 40)."""

from __future__ import annotations

import plclab

SOURCE = """TYPE Pt : STRUCT x : INT; y : REAL; END_STRUCT; END_TYPE
FUNCTION_BLOCK Base
VAR_INPUT go : BOOL; END_VAR
VAR_OUTPUT done : BOOL; END_VAR
END_FUNCTION_BLOCK
FUNCTION_BLOCK Motor EXTENDS Base
VAR_INPUT speed : REAL; END_VAR
VAR_OUTPUT running : BOOL; where : Pt; END_VAR
VAR_IN_OUT cnt : INT; END_VAR
VAR tmr : TON; count : INT; p : POINTER TO INT; hist : ARRAY[0..2] OF INT; END_VAR
VAR CONSTANT K : INT := 3; END_VAR
VAR_TEMP tt : INT; END_VAR
running := speed > 0.0; count := count + K; where.x := count; hist[1] := 7;
tmr(IN := running, PT := T#2s);
END_FUNCTION_BLOCK
PROGRAM Main
VAR m : Motor; c : INT; END_VAR
m(speed := 1.5, cnt := c);
END_PROGRAM
"""


def test_a_block_instance_prints_as_a_structured_literal(tmp_path):
    f = tmp_path / "m.st"
    f.write_text(SOURCE, encoding="utf-8")
    plc = plclab.load(str(f))
    plc.scan()
    plc.scan()
    assert plc.format("Main.m") == (
        "(go := FALSE, done := FALSE, speed := 1.5, running := TRUE, where := (x := 6, "
        "y := 0.0), tmr := (IN := TRUE, PT := T#2s, Q := FALSE, ET := T#10ms), count := 6, "
        "p := NULL, hist := [0, 7, 0])")
    assert plc.format("Main.m.tmr.PT") == "T#2s"
