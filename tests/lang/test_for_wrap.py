"""FOR like the hardware (issue 11, item 7): ``v := v + step`` wraps at the limits of v's type,
so ``i : SINT; FOR i := 120 TO 127`` never ends on a PLC; the watchdog stops such a loop and names
it. Loops that end without wrapping keep their fast path and their final value (end + step)."""

import pytest

import plclab
from plclab.errors import PlcError, PlcRuntimeFault

RANGES = {"SINT": (-128, 127), "USINT": (0, 255), "INT": (-32768, 32767), "UINT": (0, 65535)}


def hardware_for(ty: str, start: int, end: int, step: int, limit: int):
    """The reference: the values of a FOR loop's passes as a PLC runs it, and the variable's
    value after the loop (None if it has not ended after limit passes)."""
    lo, hi = RANGES[ty]
    v, passes = start, []
    while (v <= end) if step > 0 else (v >= end):
        if len(passes) == limit:
            return passes, None
        passes.append(v)
        v = (v + step - lo) % (hi - lo + 1) + lo
    return passes, v


def for_program(ty: str, start: str, end: str, step: str = "", decls: str = "") -> str:
    by = f" BY {step}" if step else ""
    return (f"PROGRAM P\nVAR i : {ty}; n : DINT; s : DINT; {decls} END_VAR\n"
            f"FOR i := {start} TO {end}{by} DO\n    n := n + 1; s := s + i;\nEND_FOR\n"
            "END_PROGRAM\n")


CASES = [
    ("SINT", 120, 127, 1), ("SINT", 120, 126, 1), ("SINT", 0, 126, 2), ("SINT", 0, 125, 2),
    ("SINT", -120, -128, -1), ("SINT", 0, -127, -1), ("SINT", 10, 1, -3), ("SINT", 0, 120, 100),
    ("SINT", 5, 1, 1), ("USINT", 250, 255, 1), ("USINT", 250, 255, 2), ("USINT", 0, 254, 1),
    ("USINT", 10, 0, -1), ("USINT", 10, 1, -1), ("INT", 32760, 32767, 1), ("INT", 32760, 32766, 1),
    ("INT", -32760, -32768, -4), ("UINT", 65530, 65535, 7), ("INT", 1, 10, 1),
]


@pytest.mark.parametrize("ty,start,end,step", CASES)
@pytest.mark.parametrize("form", ["literal", "variables"])
def test_for_runs_like_the_hardware(ty, start, end, step, form):
    limit = 5_000
    passes, final = hardware_for(ty, start, end, step, limit)
    if form == "literal":
        src = for_program(ty, str(start), str(end), str(step))
    else:  # bounds and step only known at run time
        src = for_program(ty, "a", "b", "c", f"a : {ty} := {start}; b : {ty} := {end}; "
                                              f"c : INT := {step};")
    plc = plclab.loads(src, "for.st", watchdog=limit)
    if final is None:
        with pytest.raises(PlcRuntimeFault) as ei:
            plc.scan()
        f = ei.value
        assert f.code == "PLC2003" and (f.location.line, f.location.col) == (3, 1)
        assert "wraps around" in f.message
        assert plc["n"] == limit  # the body ran until the budget was spent
    else:
        plc.scan()
        assert (plc["n"], plc["s"], plc["i"]) == (len(passes), sum(passes), final)


def test_a_wrapping_loop_left_with_exit_keeps_its_value():
    plc = plclab.loads("""PROGRAM P
VAR i : SINT; n : INT; END_VAR
FOR i := 120 TO 127 DO
    n := n + 1;
    IF n = 20 THEN EXIT; END_IF
END_FOR
END_PROGRAM""", "for.st")
    plc.scan()
    passes, final = hardware_for("SINT", 120, 127, 1, 20)
    assert final is None and plc["n"] == 20 and plc["i"] == passes[19]  # 120..127, -128.. -117


def test_watchdog_names_the_for_inside_a_function():
    src = """FUNCTION Count : DINT
VAR_INPUT top : USINT; END_VAR
VAR u : USINT; END_VAR
    FOR u := 0 TO top DO
        Count := Count + 1;
    END_FOR
END_FUNCTION
PROGRAM P
VAR a, b : DINT; END_VAR
a := Count(254);
b := Count(255);
END_PROGRAM
"""
    plc = plclab.loads(src, "count.st", watchdog=10_000)
    with pytest.raises(PlcRuntimeFault) as ei:
        plc.scan()
    loc = ei.value.location
    assert ei.value.code == "PLC2003" and (loc.file, loc.line, loc.col) == ("count.st", 4, 5)
    assert "255 + 1 gives 0" in ei.value.message
    assert plc["a"] == 255  # Count(254) ended normally


def test_loops_that_cannot_wrap_keep_the_fast_path():
    src = """PROGRAM P
VAR i : INT; k : DINT; n : INT := 100; m : INT; j : SINT; END_VAR
FOR i := 1 TO 10 DO m := m + 1; END_FOR
FOR k := 0 TO n DO m := m + 1; END_FOR
FOR i := 10 TO -10 BY -5 DO m := m + 1; END_FOR
FOR j := 126 TO 127 DO m := m + 1; END_FOR
END_PROGRAM"""
    plc = plclab.loads(src, "fast.st", watchdog=1000)
    body = plc.compiled.source.split("class P_P", 1)[1].split("def _body", 1)[1]
    # the first three are proven to end without wrapping; only the SINT loop up to 127 is not
    assert body.count("= range(") == 3 and body.count("= _frange(") == 1
    with pytest.raises(PlcRuntimeFault) as ei:
        plc.scan()
    assert ei.value.location.line == 6
    assert (plc["i"], plc["k"]) == (-15, 101)


def test_the_control_variable_must_be_an_integer():
    src = "PROGRAM P VAR b : BYTE; END_VAR FOR b := 0 TO 254 DO ; END_FOR END_PROGRAM"
    with pytest.raises(PlcError) as ei:
        plclab.loads(src, dialect="iec")
    assert ei.value.code == "PLC0113"  # IEC: ANY_INT; BYTE is a bit string
    # CODESYS (the default dialect, ADR 0017) accepts it with a teaching warning
    plc = plclab.loads(src)
    assert [d.code for d in plc.compiled.diagnostics] == ["PLC0173"]
    plc.scan()
    assert plc["b"] == 255
