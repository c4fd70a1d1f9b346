"""The scan cycle, process image, forcing, restarts, tasks, faults and the Python API."""

import pytest

import plclab
from plclab.errors import PlcError, PlcRuntimeFault

TANK = """
PROGRAM Tank
VAR LS1 AT %IX0.0 : BOOL; LS2 AT %IX0.1 : BOOL; M AT %QX0.0 : BOOL; END_VAR
M := ((NOT LS1) OR M) AND (NOT LS2);
END_PROGRAM
"""


def test_inputs_are_frozen_and_outputs_written_at_scan_end():
    plc = plclab.loads(TANK)
    plc["%IX0.0"] = False
    assert plc["%QX0.0"] is False  # nothing written before a scan
    plc.scan()
    assert plc["%QX0.0"] is True and plc["M"] is True
    plc["%IX0.1"] = True  # the terminal changes between scans
    assert plc["Tank.LS2"] is False  # the program sees it only at the next scan
    plc.scan()
    assert plc["Tank.LS2"] is True and plc["%QX0.0"] is False


def test_bit_byte_word_views_alias():
    plc = plclab.loads("""
    PROGRAM P
    VAR b0 AT %QX0.0 : BOOL; b9 AT %QX1.1 : BOOL; w AT %IW2 : WORD; d AT %ID4 : DINT;
        mw AT %MW10 : INT; out AT %QW4 : WORD; END_VAR
    b0 := TRUE; b9 := TRUE; out := w; mw := -2;
    END_PROGRAM""")
    plc["%IB2"] = 0x12
    plc["%IB3"] = 0x34
    plc["%ID4"] = 0xFFFFFFFE
    plc.scan()
    assert plc["%QW0"] == 0x0102  # %QX0.0 is bit 0 of %QB0 (high byte of %QW0), %QX1.1 of %QB1
    assert plc["%QB0"] == 1 and plc["%QB1"] == 2
    assert plc["P.w"] == 0x1234 and plc["%QW4"] == 0x1234
    assert plc["P.d"] == -2  # signed DINT view of the same bytes
    assert plc["%MW10"] == 0xFFFE and plc["%MB11"] == 0xFE


def test_direct_addresses_in_code():
    plc = plclab.loads("""
    PROGRAM P VAR x : BOOL; END_VAR
    x := %IX0.3;
    %QX0.1 := x;
    %MW2 := %IW0;
    END_PROGRAM""")
    plc["%IX0.3"] = True
    plc.scan()
    assert plc["P.x"] is True and plc["%QX0.1"] is True
    assert plc["%MW2"] == 0x0800


def test_forcing_overrides_inputs_and_outputs():
    plc = plclab.loads(TANK)
    plc.force("LS2", True)
    plc["%IX0.1"] = False
    plc.scan()
    assert plc["M"] is False
    plc.force("%QX0.0", True)
    plc.scan()
    assert plc["%QX0.0"] is True
    plc.unforce()
    plc.scan()
    assert plc["M"] is True


def test_cold_and_warm_restart_with_retain():
    plc = plclab.loads("""
    PROGRAM P
    VAR RETAIN kept : INT; END_VAR
    VAR lost : INT; END_VAR
    kept := kept + 1; lost := lost + 1;
    END_PROGRAM""")
    plc.scan(5)
    plc.warm_restart()
    assert plc["kept"] == 5 and plc["lost"] == 0
    plc.scan()
    plc.cold_restart()
    assert plc["kept"] == 0


def test_stop_switches_outputs_off_and_run_resumes():
    plc = plclab.loads(TANK)
    plc.scan()
    assert plc["%QX0.0"]
    plc.stop()
    plc.scan()
    assert plc["%QX0.0"] is False
    plc.start()
    plc.scan()
    assert plc["%QX0.0"] is True


def test_virtual_clock_and_run():
    plc = plclab.loads("""PROGRAM P VAR t : TON; n : DINT; END_VAR
    t(IN := TRUE, PT := T#1s); n := n + 1; END_PROGRAM""", cycle_time="20ms")
    plc.run(seconds=1.0)
    assert plc.scan_count == 50 and plc["n"] == 50
    assert plc["t.ET"] == 980 and plc["t.Q"] is False  # last scan ran at t = 0.98 s
    plc.scan()
    assert plc["t.Q"] is True and plc.format("t.ET") == "T#1s"
    plc.advance("T#1s")
    assert plc.time == pytest.approx(2.02)


def test_tasks_with_intervals():
    plc = plclab.loads("""
    PROGRAM Fast VAR n : DINT; END_VAR n := n + 1; END_PROGRAM
    PROGRAM Slow VAR n : DINT; END_VAR n := n + 1; END_PROGRAM
    CONFIGURATION C RESOURCE R ON PLC
      TASK fastT(INTERVAL := T#10ms, PRIORITY := 1);
      TASK slowT(INTERVAL := T#50ms, PRIORITY := 2);
      PROGRAM f WITH fastT : Fast;
      PROGRAM s WITH slowT : Slow;
    END_RESOURCE END_CONFIGURATION""")
    plc.run(seconds=1.0)
    assert plc["f.n"] == 100 and plc["s.n"] == 20


def test_integer_wrap_and_real_precision():
    plc = plclab.loads("""
    PROGRAM P VAR i : INT := 32767; u : USINT := 255; b : BYTE := 16#FF; r : REAL; l : LREAL;
      d : DINT := 2147483647; big : INT; END_VAR
    i := i + 1; u := u + 1; b := b + 1; d := d + 1; r := 0.1; l := 0.1;
    big := INT#30000 + INT#30000;
    END_PROGRAM""".replace("b := b + 1;", "b := USINT_TO_BYTE(BYTE_TO_USINT(b) + 1);"))
    plc.scan()
    assert plc["i"] == -32768 and plc["u"] == 0 and plc["b"] == 0
    assert plc["d"] == -2147483648
    assert plc["big"] == -5536
    assert plc["r"] == pytest.approx(0.1, rel=1e-7) and plc["r"] != 0.1
    assert plc["l"] == 0.1


def test_runtime_faults_have_source_locations():
    plc = plclab.loads("PROGRAM P VAR a : ARRAY[1..3] OF INT; i : INT := 1; END_VAR\n"
                       "i := i + 1;\na[i] := 7;\nEND_PROGRAM", "f.st")
    plc.scan(2)
    with pytest.raises(PlcRuntimeFault) as ei:
        plc.scan()
    assert ei.value.code == "PLC2002" and str(ei.value.location) == "f.st:3:3"
    assert plc.state == "STOP" and plc.fault is ei.value
    with pytest.raises(PlcError):
        plc.start()


@pytest.mark.parametrize("body,line", [
    ("WHILE TRUE DO\n  x := x + 1;\nEND_WHILE", 3),
    ("REPEAT\n  x := x + 1;\nUNTIL FALSE END_REPEAT", 3),
    ("WHILE NOT go DO\n  ;\nEND_WHILE", 3),
    ("FOR x := 0 TO 30000 DO\n  FOR y := 0 TO 30000 DO z := z + 1; END_FOR\nEND_FOR", 4),
])
def test_watchdog_stops_runaway_loops(body, line):
    src = ("PROGRAM P VAR x, y : INT; z : DINT; go AT %IX0.0 : BOOL; END_VAR\n\n" + body +
           "\nEND_PROGRAM")
    plc = plclab.loads(src, "w.st", watchdog=100_000)
    with pytest.raises(PlcRuntimeFault) as ei:
        plc.scan()
    assert ei.value.code == "PLC2003"
    assert ei.value.location.line == line
    assert "never ends" in ei.value.message


def test_division_by_zero_real_and_int():
    for decl, expr in (("x : INT; z : INT;", "x := 10 / z;"), ("x : REAL; z : REAL;",
                                                              "x := 1.0 / z;"),
                       ("x : INT; z : INT;", "x := 10 MOD z;")):
        plc = plclab.loads(f"PROGRAM P VAR {decl} END_VAR {expr} END_PROGRAM")
        with pytest.raises(PlcRuntimeFault) as ei:
            plc.scan()
        assert ei.value.code == "PLC2001"


def test_api_errors_are_plc_errors():
    plc = plclab.loads(TANK)
    with pytest.raises(PlcError) as ei:
        plc["LS3"]
    assert ei.value.code == "PLC3001" and "did you mean LS" in ei.value.message
    with pytest.raises(PlcError):
        plc["LS1"] = "maybe"
    with pytest.raises(PlcError):
        plc["%IX9999.0"]
    with pytest.raises(PlcError):
        plclab.load("/no/such/file.st")


def test_set_with_iec_literals():
    plc = plclab.loads("""PROGRAM P VAR t : TIME; b : BYTE; e : (Off, Slow, Fast); r : REAL;
    s : STRING[5]; END_VAR END_PROGRAM""")
    plc["t"] = "T#1m30s"
    plc["b"] = "16#FF"
    plc["e"] = "Fast"
    plc["r"] = "1.5E3"
    plc["s"] = "abcdefgh"
    assert plc["t"] == 90_000 and plc["b"] == 255 and plc["e"] == 2 and plc["r"] == 1500.0
    assert plc.format("e") == "Fast" and plc["s"] == "abcde"
    with pytest.raises(PlcError):
        plc["b"] = 300


def test_arrays_structs_and_fb_arrays():
    plc = plclab.loads("""
    TYPE Axis : STRUCT pos : REAL; ok : BOOL := TRUE; END_STRUCT; END_TYPE
    PROGRAM P
    VAR axes : ARRAY[1..3] OF Axis; timers : ARRAY[0..1] OF TON; m : ARRAY[1..2, 1..3] OF INT;
        a, b : Axis; i, j : INT; END_VAR
    FOR i := 1 TO 3 DO axes[i].pos := i * 1.5; END_FOR
    timers[1](IN := TRUE, PT := T#20ms);
    FOR i := 1 TO 2 DO FOR j := 1 TO 3 DO m[i, j] := i * 10 + j; END_FOR END_FOR
    a.pos := 1.0; b := a; b.pos := 2.0;
    END_PROGRAM""")
    plc.scan(3)
    assert plc["axes[3].pos"] == 4.5 and plc["axes[2].ok"] is True
    assert plc["timers[1].Q"] is True and plc["timers[0].Q"] is False
    assert plc["m[2,3]"] == 23 and plc["m[1,1]"] == 11
    assert plc["a.pos"] == 1.0 and plc["b.pos"] == 2.0  # assignment copies structures


def test_function_outputs_in_out_and_globals():
    plc = plclab.loads("""
    VAR_GLOBAL total : DINT; END_VAR
    FUNCTION Split : INT VAR_INPUT v : INT; END_VAR VAR_OUTPUT rest : INT; END_VAR
      Split := v / 10; rest := v MOD 10; END_FUNCTION
    FUNCTION Inc : BOOL VAR_IN_OUT c : DINT; END_VAR c := c + 1; Inc := TRUE; END_FUNCTION
    PROGRAM P VAR tens, ones : INT; ok : BOOL; END_VAR
      tens := Split(47, rest => ones);
      ok := Inc(total);
    END_PROGRAM""")
    plc.scan(3)
    assert plc["tens"] == 4 and plc["ones"] == 7 and plc["total"] == 3


def test_generated_code_contains_no_user_text_outside_literals():
    evil = "'); import os; os.system('echo pwned'); ('"
    plc = plclab.loads(f"PROGRAM P VAR s : STRING; END_VAR s := '{evil.replace(chr(39), '$' + chr(39))}'; END_PROGRAM")
    plc.scan()
    assert plc["s"] == evil[:80]
    assert "import os" not in plc.compiled.source.replace(repr(evil), "")


def test_variables_listing():
    plc = plclab.loads(TANK)
    assert plc.variables() == ["Tank.LS1", "Tank.LS2", "Tank.M"]


def test_system_and_clock_memory_bytes():
    src = """PROGRAM P
    VAR first AT %M1.0 : BOOL; always AT %M1.2 : BOOL; hz10 AT %M0.0 : BOOL; hz1 AT %M0.5 : BOOL;
        firsts, edges : INT; prev : BOOL; END_VAR
    IF first THEN firsts := firsts + 1; END_IF
    IF hz1 AND NOT prev THEN edges := edges + 1; END_IF
    prev := hz1;
    END_PROGRAM"""
    plc = plclab.loads(src.replace("%M1.0", "%MX1.0").replace("%M1.2", "%MX1.2")
                       .replace("%M0.0", "%MX0.0").replace("%M0.5", "%MX0.5"),
                       system_memory_byte=1, clock_memory_byte=0)
    plc.run(seconds=10)
    assert plc["firsts"] == 1 and plc["always"] is True
    assert plc["edges"] == 10  # a 1 Hz square wave rises once a second


def test_benchmark_programs_match_their_python_equivalents():
    """The hand-written Python of benchmarks/ does the same work: same state after 50 scans."""
    import sys
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
    from programs import PROGRAMS, Clock

    for name, src, cls in PROGRAMS:
        plc = plclab.loads(src)
        clock = Clock()
        ref = cls(clock)
        for _ in range(50):
            plc.scan()
            ref.body()
            clock.now += 10
        got = {k.split(".")[-1].lower(): plc[k] for k in plc.variables()}
        for k, v in vars(ref).items():
            if k in got and not isinstance(v, Clock):
                if isinstance(v, list) and v and not isinstance(v[0], int):
                    continue
                assert got[k] == v, (name, k)


@pytest.mark.parametrize("expr,want", [
    ("LEFT('hello', 2)", "he"), ("RIGHT('hello', 3)", "llo"), ("RIGHT('hi', 5)", "hi"),
    ("MID('hello', 2, 2)", "el"), ("DELETE('hello', 2, 2)", "hlo"),
    ("DELETE('hello', 2, 1)", "llo"), ("LEFT('hi', 0)", ""), ("LEFT('hi', n)", ""),
    ("MID('hello', 2, n + 2)", "el"), ("INSERT('abc', 'X', 1)", "aXbc"),
    ("REPLACE('abcdef', 'XY', 3, 2)", "aXYef"), ("CONCAT('a', 'b', 'c')", "abc"),
])
def test_string_functions_constant_and_variable_arguments(expr, want):
    plc = plclab.loads(f"PROGRAM P VAR s : STRING; n : INT; END_VAR s := {expr}; END_PROGRAM")
    plc.scan()
    assert plc["s"] == want
