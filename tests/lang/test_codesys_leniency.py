"""CODESYS leniency of the ``codesys`` dialect (issue 33, ADR 0051): OSCAT code as CODESYS
compiles it, each accepted construct with its warning; ``iec`` refuses the same text."""

from __future__ import annotations

import struct

import pytest

import plclab
from plclab.project import check_sources


def codes(src: str, dialect: str | None = None) -> tuple[list[str], list[str]]:
    """(error codes, warning codes) of ``src`` read in ``dialect`` (default: codesys)."""
    _, diags = check_sources([(src, "p.st")], dialect)
    return ([d.code for d in diags if d.severity == "error"],
            [d.code for d in diags if d.severity != "error"])


def f32(x: float) -> float:
    return struct.unpack("<f", struct.pack("<f", x))[0]


BFT = """
FUNCTION BFT_TO_MS : REAL
VAR_INPUT BFT : INT; END_VAR
BFT_TO_MS := EXPT(BFT, 1.5) * 0.836;
END_FUNCTION
PROGRAM Main
VAR r : REAL; END_VAR
r := BFT_TO_MS(4);
END_PROGRAM
"""


def test_real_literal_typed_by_context_in_codesys_only():
    errors, warnings = codes(BFT)
    assert errors == [] and "PLC0290" in warnings
    assert codes(BFT, "iec")[0] == ["PLC0118"]
    plc = plclab.loads(BFT)
    plc.scan(1)
    assert plc["Main.r"] == f32(4 ** 1.5 * 0.836)


@pytest.mark.parametrize("rhs", [
    "lr * 0.5",                  # an LREAL variable: not a literal's doing
    "LREAL#0.5 * 2.0",           # a typed literal says LREAL
    "INT_TO_LREAL(i) * 0.5",     # a conversion to LREAL
    "Twice(0.5)",                # a function returning LREAL
])
def test_lreal_that_is_not_only_literals_still_refused(rhs):
    src = f"""
FUNCTION Twice : LREAL
VAR_INPUT x : LREAL; END_VAR
Twice := x * 2.0;
END_FUNCTION
PROGRAM Main
VAR r : REAL; lr : LREAL := 1.0; i : INT := 3; END_VAR
r := {rhs};
END_PROGRAM
"""
    errors, warnings = codes(src)
    assert errors == ["PLC0118"] and "PLC0290" not in warnings


OSCAT_COUNT = """
FUNCTION INC : INT
VAR_INPUT X : INT; D : INT; M : INT; END_VAR
INC := X + D;
IF INC > M THEN INC := 0; ELSIF INC < 0 THEN INC := M; END_IF;
END_FUNCTION
FUNCTION_BLOCK COUNT_BR
VAR_INPUT up, dn, set : BOOL; in : BYTE; step : BYTE := 1; mx : BYTE := 255; END_VAR
VAR_OUTPUT cnt : BYTE; END_VAR
VAR last_up, last_dn : BOOL; END_VAR
IF set THEN
    cnt := LIMIT(0, in, mx);
ELSIF up AND NOT last_up THEN
    cnt := INT_TO_BYTE(INC(cnt, step, mx));
ELSIF dn AND NOT last_dn THEN
    cnt := INT_TO_BYTE(INC(cnt, -step, mx));
END_IF;
last_up := up;
last_dn := dn;
END_FUNCTION_BLOCK
PROGRAM Main
VAR c : COUNT_BR; n0, n1, n2, n3 : BYTE; END_VAR
c(set := TRUE, in := 200, mx := 100);
n0 := c.cnt;
c(set := FALSE, dn := TRUE, step := 3);
n1 := c.cnt;
c(dn := FALSE);
c(dn := TRUE);
n2 := c.cnt;
c(dn := FALSE, up := TRUE, step := 5);
n3 := c.cnt;
END_PROGRAM
"""


def test_negated_byte_and_byte_int_mixes_as_codesys_computes_them():
    errors, warnings = codes(OSCAT_COUNT)
    assert errors == [] and "PLC0173" in warnings
    assert "PLC0104" in codes(OSCAT_COUNT, "iec")[0]
    plc = plclab.loads(OSCAT_COUNT)
    plc.scan(1)
    # LIMIT clamps 200 to 100; -step is -3 (not the BYTE 253) when it reaches INC's INT input
    assert [plc[f"Main.n{k}"] for k in range(4)] == [100, 97, 94, 99]


def test_bit_string_times_real_computes_in_real():
    src = """
FUNCTION BYTE_TO_RANGE : REAL
VAR_INPUT X : BYTE; LOW : REAL; HIGH : REAL; END_VAR
BYTE_TO_RANGE := (HIGH - LOW) * X / 255.0 + LOW;
END_FUNCTION
PROGRAM Main
VAR r : REAL; END_VAR
r := BYTE_TO_RANGE(51, 10.0, 20.0);
END_PROGRAM
"""
    errors, warnings = codes(src)
    assert errors == [] and "PLC0173" in warnings
    assert "PLC0104" in codes(src, "iec")[0]
    plc = plclab.loads(src)
    plc.scan(1)
    assert plc["Main.r"] == pytest.approx(12.0, rel=1e-6)


@pytest.mark.parametrize("decl,arg,want", [
    ("d : DINT := 100000", "INT_TO_DINT(d)", 100000 - 131072),  # wraps to INT first
    ("d : DINT := 100000", "INT_TO_BYTE(d)", 100000 & 0xFF),
    ("d : DINT := -1", "UINT_TO_DINT(d)", 65535),
])
def test_typed_conversion_of_a_wider_integer_wraps_to_its_input_type(decl, arg, want):
    src = f"PROGRAM Main\nVAR {decl}; x : DINT; END_VAR\nx := {arg};\nEND_PROGRAM\n"
    errors, warnings = codes(src)
    assert errors == [] and "PLC0285" in warnings
    assert "PLC0107" in codes(src, "iec")[0]
    plc = plclab.loads(src)
    plc.scan(1)
    assert plc["Main.x"] == want


REINTERPRET = """
FUNCTION REAL_TO_DW : DWORD
VAR_INPUT X : REAL; END_VAR
VAR pt : REF_TO DWORD; END_VAR
pt := REF(X);
REAL_TO_DW := pt^;
END_FUNCTION
FUNCTION DW_TO_REAL : REAL
VAR_INPUT X : DWORD; END_VAR
VAR pt : REF_TO REAL; END_VAR
pt := REF(X);
DW_TO_REAL := pt^;
END_FUNCTION
FUNCTION LW_TO_LREAL : LREAL
VAR_INPUT X : LWORD; END_VAR
VAR pt : REF_TO LREAL; END_VAR
pt := REF(X);
LW_TO_LREAL := pt^;
END_FUNCTION
FUNCTION SET_BITS : REAL
VAR_INPUT b : DWORD; END_VAR
VAR r : REAL; pt : REF_TO DWORD; END_VAR
pt := REF(r);
IF __ISVALIDREF(pt) AND pt <> NULL THEN pt^ := b; END_IF;
SET_BITS := r;
END_FUNCTION
PROGRAM Main
VAR x : REAL; w : DWORD; back : REAL; lw : LWORD; lr : LREAL; set : REAL; END_VAR
w := REAL_TO_DW(x);
back := DW_TO_REAL(w);
lr := LW_TO_LREAL(lw);
set := SET_BITS(w);
END_PROGRAM
"""


@pytest.mark.parametrize("x", [1.0, -2.5, 3.1415927, 1e-40, 6.5e37])
def test_reference_to_a_function_local_reads_the_bits_of_another_type(x):
    errors, warnings = codes(REINTERPRET)
    assert errors == [] and warnings.count("PLC0291") == 4
    strict = codes(REINTERPRET, "iec")[0]
    assert set(strict) == {"PLC0240"} and len(strict) == 4
    plc = plclab.loads(REINTERPRET)
    plc["Main.x"] = x
    plc["Main.lw"] = struct.unpack("<Q", struct.pack("<d", -x / 3))[0]
    plc.scan(1)
    bits = struct.unpack("<I", struct.pack("<f", x))[0]
    assert plc["Main.w"] == bits
    assert plc["Main.back"] == f32(x) == plc["Main.set"]
    assert plc["Main.lr"] == -x / 3


@pytest.mark.parametrize("escape", [
    "out := pt;",                        # an output outlives the call
    "g := pt;",                          # a global
    "F := pt;",                          # the result
    "Keep(pt);",                         # passed on: the callee may keep it
    "other := pt;",                      # copied into another reference
])
def test_a_reference_to_a_local_that_could_outlive_the_call_is_refused(escape):
    src = f"""
VAR_GLOBAL g : REF_TO INT; END_VAR
FUNCTION Keep : BOOL
VAR_INPUT r : REF_TO INT; END_VAR
g := r;
END_FUNCTION
FUNCTION F : REF_TO INT
VAR_OUTPUT out : REF_TO INT; END_VAR
VAR x : INT; pt, other : REF_TO INT; END_VAR
pt := REF(x);
{escape}
END_FUNCTION
"""
    assert "PLC0240" in codes(src)[0]


def test_ref_of_a_local_not_kept_in_a_local_reference_is_refused():
    src = """
FUNCTION F : INT
VAR_IN_OUT r : REF_TO INT; END_VAR
VAR x : INT; END_VAR
r := REF(x);
END_FUNCTION
"""
    assert "PLC0240" in codes(src)[0]


@pytest.mark.parametrize("decl", ["pt : REF_TO INT", "pt : REF_TO LREAL", "pt : REF_TO STRING"])
def test_a_reference_to_another_size_or_kind_is_still_refused(decl):
    src = f"""
FUNCTION F : INT
VAR x : REAL; {decl}; END_VAR
pt := REF(x);
END_FUNCTION
"""
    assert "PLC0241" in codes(src)[0]


def test_the_ref_of_a_local_has_its_warning():
    errors, warnings = codes(REINTERPRET)
    assert warnings.count("PLC0292") == 4


def test_explain_dialect_lists_each_rule_with_what_iec_says(tmp_path, capsys):
    from plclab.cli import main

    f = tmp_path / "oscat.st"
    f.write_text(BFT + REINTERPRET.replace("PROGRAM Main", "PROGRAM Main2"), encoding="utf-8")
    assert main(["check", "--explain-dialect", str(f)]) == 0
    out = capsys.readouterr().out
    rules = [ln for ln in out.splitlines() if ln.startswith(str(f) + ":") and "(codesys)" in ln]
    assert {ln.split()[1] for ln in rules} == {"PLC0290", "PLC0291", "PLC0292"}
    line = BFT.splitlines().index("BFT_TO_MS := EXPT(BFT, 1.5) * 0.836;") + 1
    lit = next(i for i, ln in enumerate(out.splitlines()) if f"oscat.st:{line}:" in ln and
               "PLC0290" in ln)
    assert out.splitlines()[lit + 1].strip().startswith("iec: PLC0118")
    # a file that is strict IEC already: nothing fires
    g = tmp_path / "plain.st"
    g.write_text("{dialect 'iec'}\nPROGRAM P VAR n : INT; END_VAR n := n + 1; END_PROGRAM\n",
                 encoding="utf-8")
    main(["check", "--explain-dialect", str(g)])
    assert "0 dialect rule(s) fired" in capsys.readouterr().out


def test_explain_dialect_names_silent_syntax_leniency(tmp_path, capsys):
    """A CODESYS form accepted without a warning (Color.Red) still shows, with iec's error."""
    from plclab.cli import main

    f = tmp_path / "enum.st"
    f.write_text("TYPE Color : (Red, Green); END_TYPE\nPROGRAM P VAR c : Color; END_VAR\n"
                 "c := Color.Green;\nEND_PROGRAM\n", encoding="utf-8")
    main(["check", "--explain-dialect", str(f)])
    out = capsys.readouterr().out
    assert f"{f}:3:" in out and "accepted by codesys without a warning" in out
    assert "iec: PLC0174" in out


@pytest.mark.parametrize("inp,want_n,want_cnt", [(300, 200, 200), (-5, 0, 0), (77, 77, 77)])
def test_limit_of_int_and_byte_takes_the_common_type_then_narrows(inp, want_n, want_cnt):
    src = f"""
PROGRAM Main
VAR cnt : BYTE; in : INT := {inp}; mx : BYTE := 200; n : INT; m : INT; END_VAR
cnt := LIMIT(0, in, mx);
n := LIMIT(0, in, mx);
m := MAX(in, mx);
END_PROGRAM
"""
    errors, warnings = codes(src)
    assert errors == [] and "PLC0173" in warnings and "PLC0285" in warnings
    assert codes(src, "iec")[0].count("PLC0107") == 3
    plc = plclab.loads(src)
    plc.scan(1)
    assert (plc["Main.n"], plc["Main.cnt"], plc["Main.m"]) == (want_n, want_cnt, max(inp, 200))


METHOD_AND_TEST_LOCALS = """FUNCTION_BLOCK Fb
METHOD Bits : DWORD
VAR_INPUT x : REAL; END_VAR
VAR p : REF_TO DWORD; i : INT; END_VAR
FOR i := 1 TO 2 DO
  p := REF(x);
END_FOR;
Bits := p^;
END_METHOD
END_FUNCTION_BLOCK
TEST 'method and test locals'
  VAR f : Fb; r : REAL := 1.0; q : REF_TO REAL; w : DWORD; pw : REF_TO DWORD; END_VAR
  ASSERT_EQ(f.Bits(1.0), 16#3F800000);
  q := REF(r);
  q^ := 2.0;
  ASSERT_EQ(r, 2.0);
  pw := REF(r);
  ASSERT_EQ(pw^, 16#40000000);
  pw^ := 16#3F800000;
  ASSERT_EQ(r, 1.0);
END_TEST
"""


def test_references_to_locals_of_a_method_and_a_test_read_and_write_through():
    from plclab.testing import run_test_sources

    results = run_test_sources([(METHOD_AND_TEST_LOCALS, "m.st")])
    assert [r.passed for r in results] == [True], [str(r) for r in results]
    assert struct.unpack("<I", struct.pack("<f", 2.0))[0] == 0x40000000  # the test's constant
