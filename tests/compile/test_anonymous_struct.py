"""A STRUCT written inside a VAR section (no TYPE name) compiles to its own class; it used to pass
the checker and then stop the compiler with a raw ValueError."""

import plclab

SOURCE = """
FUNCTION_BLOCK Holder
VAR_OUTPUT
  inner : STRUCT a : INT; pair : STRUCT x : BOOL; y : REAL; END_STRUCT; END_STRUCT;
END_VAR
inner.a := inner.a + 1;
inner.pair.x := NOT inner.pair.x;
inner.pair.y := inner.pair.y + 0.5;
END_FUNCTION_BLOCK

PROGRAM P
VAR
  s : STRUCT a : INT; b : BOOL; END_STRUCT;
  t : STRUCT a : INT; b : BOOL; END_STRUCT;
  arr : ARRAY[1..3] OF STRUCT n : DINT; END_STRUCT;
  h : Holder;
END_VAR
s.a := s.a + 1;
t.a := s.a * 2;
t.b := TRUE;
arr[2].n := arr[2].n + 10;
h();
END_PROGRAM
"""


def test_anonymous_structures_run_and_stay_separate():
    plc = plclab.loads(SOURCE)
    plc.scan(3)
    assert plc["P.s.a"] == 3 and plc["P.t.a"] == 6
    assert plc["P.s.b"] is False and plc["P.t.b"] is True  # one class each, two instances
    assert plc["P.arr[2].n"] == 30 and plc["P.arr[1].n"] == 0
    assert plc["P.h.inner.a"] == 3 and plc["P.h.inner.pair.x"] is True
    assert plc["P.h.inner.pair.y"] == 1.5


def test_two_anonymous_structures_are_two_types():
    import pytest

    bad = SOURCE.replace("t.a := s.a * 2;", "t := s;")
    with pytest.raises(plclab.PlcError) as e:
        plclab.loads(bad)
    assert e.value.code == "PLC0103"
