"""Bounded work and hostile declarations: the parsers always make progress, diagnostics are
capped per file, and cycles, sizes, literals, addresses and tasks beyond the limits are
compile-time errors with a code, a message that says what to do and a location."""

from __future__ import annotations

import signal
from contextlib import contextmanager

import pytest

import plclab
from plclab.errors import PlcError
from plclab.lang.lexer import MAX_DIAGNOSTICS_PER_FILE
from plclab.problems import PROBLEMS
from plclab.project import check_sources


@contextmanager
def within(seconds: int):
    """Fail (instead of hanging the suite) if the block runs longer than ``seconds``."""

    def boom(*_):
        raise TimeoutError(f"no answer within {seconds} s")

    old = signal.signal(signal.SIGALRM, boom)
    signal.alarm(seconds)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)


def diags_of(src: str, name: str = "b.st"):
    with within(20):
        _, diags = check_sources([(src, name)])
    return diags


def errors(src: str, name: str = "b.st", code: str | None = None):
    out = [d for d in diags_of(src, name) if d.severity == "error"]
    return [d for d in out if code is None or d.code == code]


def one(src: str, code: str, name: str = "b.st"):
    """The single diagnostic ``code`` of ``src``: catalogued, located in the file, explained."""
    found = errors(src, name, code)
    assert found, f"{code} not reported; got {[str(d) for d in diags_of(src, name)]}"
    d = found[0]
    assert code in PROBLEMS
    assert d.location is not None and d.location.file == name and d.location.line >= 1
    assert len(d.message) > 20
    return d


# -- parser progress ------------------------------------------------------------------------

TRUNCATED = [
    "PROGRAM P VAR VAR_GLOBAL END_VAR END_PROGRAM",  # the fuzzer's 78 hangs
    "PROGRAM P VAR VAR_INPUT x : INT; END_VAR END_PROGRAM",
    "PROGRAM P VAR x : INT; VAR_TEMP y : INT; END_VAR END_PROGRAM",
    "FUNCTION_BLOCK F VAR_INPUT VAR_OUTPUT q : BOOL; END_VAR END_FUNCTION_BLOCK",
    "PROGRAM P VAR x : INT; END_PROGRAM",
    "PROGRAM P VAR x : INT;",
    "PROGRAM P VAR",
    "VAR_GLOBAL x : INT; PROGRAM P END_PROGRAM",
    "VAR_GLOBAL VAR_GLOBAL VAR_GLOBAL",
    "TYPE T : STRUCT a : INT; END_TYPE PROGRAM P END_PROGRAM",
    "TYPE T : STRUCT a : INT; VAR x : INT; END_VAR END_STRUCT; END_TYPE",
    "TYPE T : (A, B; VAR_GLOBAL x : T; END_VAR",
    "TYPE VAR END_TYPE",
    "PROGRAM P VAR a : ARRAY[1.. OF INT; END_VAR END_PROGRAM",
    "CONFIGURATION C VAR_GLOBAL RESOURCE R ON X TASK t(INTERVAL := T#1s); END_RESOURCE",
    "CONFIGURATION C RESOURCE R ON X TASK t(INTERVAL := ; END_RESOURCE END_CONFIGURATION",
    "TEST 'x' VAR VAR_GLOBAL END_VAR END_TEST",
    "PROGRAM P VAR x : INT; END_VAR CASE x OF 1: VAR END_CASE END_PROGRAM",
    "PROGRAM P END_VAR END_VAR END_STRUCT END_TYPE END_PROGRAM",
    "FUNCTION F : INT VAR_INPUT VAR_IN_OUT VAR_OUTPUT VAR_EXTERNAL VAR_TEMP VAR",
]


@pytest.mark.parametrize("src", TRUNCATED)
@pytest.mark.parametrize("name", ["t.st", "t.il"])
def test_truncated_and_misplaced_sections_return_at_once_with_an_error(src, name):
    errs = errors(src, name)
    assert errs, "a broken file must give an error"
    assert all(d.code in PROBLEMS and d.location is not None for d in errs)


def test_the_typo_names_the_section_to_close():
    d = one("PROGRAM P VAR VAR_GLOBAL END_VAR END_PROGRAM", "PLC0010")
    assert "END_VAR" in d.message and "VAR_GLOBAL" in d.message
    assert (d.location.line, d.location.col) == (1, 15)


def test_a_section_left_open_still_checks_the_rest_of_the_file():
    src = ("PROGRAM P VAR x : INT;\nVAR_TEMP y : INT; END_VAR\nx := y + 1;\nEND_PROGRAM\n"
           "PROGRAM Q VAR z : INT; END_VAR z := undeclared; END_PROGRAM")
    codes = [(d.code, d.location.line) for d in errors(src)]
    assert ("PLC0010", 2) in codes and ("PLC0100", 5) in codes


def test_ladder_text_with_misplaced_sections_returns():
    src = "PROGRAM P\nVAR VAR_GLOBAL a : BOOL; END_VAR\n|--[ a ]--( b )--|\nEND_PROGRAM"
    assert errors(src, "l.ld")


# -- diagnostics capped per file ------------------------------------------------------------

def test_a_megabyte_of_nul_bytes_is_one_diagnostic():
    diags = diags_of("\x00" * 1_000_000, "nul.st")
    assert len(diags) == 1 and diags[0].code == "PLC0001"
    assert "999999 more" in diags[0].message


def test_bad_characters_separated_by_blanks_are_one_run():
    diags = diags_of("@ " * 500_000, "at.st")
    assert len(diags) == 1 and "999998 more" in diags[0].message
    d = one("PROGRAM P VAR x : INT; END_VAR\nx := 1 @ @ $ 2; END_PROGRAM", "PLC0001")
    assert (d.location.line, d.location.col) == (2, 8) and "4 more up to column 12" in d.message


def test_diagnostics_are_capped_per_file_with_one_note():
    diags = diags_of("@\n" * 100_000, "at.st") + diags_of(
        "PROGRAM P VAR x : INT; END_VAR\n" + "x := TRUE;\n" * 300 + "END_PROGRAM", "m.st")
    for f in ("at.st", "m.st"):
        mine = [d for d in diags if d.location.file == f]
        assert len(mine) == MAX_DIAGNOSTICS_PER_FILE + 1
        assert mine[-1].code == "PLC0128" and "fix these first" in mine[-1].message
        assert mine[-1].location.line >= 1


def test_the_cap_is_per_file():
    bad = "PROGRAM P VAR x : INT; END_VAR\n" + "x := TRUE;\n" * 150 + "END_PROGRAM"
    _, diags = check_sources([(bad, "a.st"), (bad.replace("PROGRAM P", "PROGRAM Q"), "b.st")])
    for f in ("a.st", "b.st"):
        assert len([d for d in diags if d.location.file == f]) == MAX_DIAGNOSTICS_PER_FILE + 1


def test_check_command_output_is_bounded(tmp_path, capsys):
    from plclab.cli import main

    f = tmp_path / "many.st"
    f.write_text("PROGRAM P VAR x : INT; END_VAR\n" + "x := TRUE;\n" * 5000 + "END_PROGRAM")
    assert main(["check", str(f)]) == 1
    out = capsys.readouterr()
    text = out.out + out.err
    assert text.count("PLC0118") == MAX_DIAGNOSTICS_PER_FILE and "PLC0128" in text


# -- cycles among constants, enumeration values and types ----------------------------------

@pytest.mark.parametrize("src, chain", [
    ("VAR_GLOBAL CONSTANT A : INT := B; B : INT := A; END_VAR\n"
     "PROGRAM P VAR x : INT; END_VAR x := A; END_PROGRAM", "A -> B -> A"),
    ("PROGRAM P VAR CONSTANT N : INT := N + 1; END_VAR\nVAR a : ARRAY[1..N] OF INT; END_VAR\n"
     "a[1] := 1; END_PROGRAM", "N -> N"),
    ("TYPE E : (A := B, B := A); END_TYPE\nPROGRAM P VAR e : E; END_VAR e := A; END_PROGRAM",
     "E.A -> E.B -> E.A"),
    ("TYPE E : (A := C, B, C); END_TYPE\nPROGRAM P VAR e : E; END_VAR e := A; END_PROGRAM",
     "E.A -> E.C -> E.B -> E.A"),
    ("TYPE E1 : (A := B + 1); END_TYPE TYPE E2 : (B := A); END_TYPE\n"
     "PROGRAM P VAR e : E1; END_VAR e := A; END_PROGRAM", "E1.A -> E2 -> E2.B -> E1.A"),
    ("TYPE E : (A := K); END_TYPE VAR_GLOBAL CONSTANT K : E := A; END_VAR\n"
     "PROGRAM P END_PROGRAM", "E.A -> K -> E.A"),
    ("TYPE S : STRING[L]; END_TYPE VAR_GLOBAL CONSTANT L : INT := M; M : INT := L; END_VAR\n"
     "PROGRAM P VAR s : S; END_VAR s := 'a'; END_PROGRAM", "L -> M -> L"),
    ("TYPE R : INT(0..HI); END_TYPE VAR_GLOBAL CONSTANT HI : INT := HI * 2; END_VAR\n"
     "PROGRAM P VAR r : R; END_VAR r := 1; END_PROGRAM", "HI -> HI"),
    ("TYPE A1 : B1; B1 : A1; END_TYPE\nPROGRAM P VAR e : A1; END_VAR END_PROGRAM",
     "A1 -> B1 -> A1"),
])
def test_cycles_are_named_once_at_compile_time(src, chain):
    d = one(src, "PLC0122")
    assert chain in d.message
    assert len(errors(src)) == 1, [str(x) for x in errors(src)]


def test_constants_fold_once_each_and_stay_bounded():
    # each constant doubles the one before: evaluated naively this is 2**60 steps
    src = ("VAR_GLOBAL CONSTANT A0 : LINT := 1;" +
           "".join(f"A{i + 1} : LINT := A{i} + A{i};" for i in range(60)) +
           "END_VAR PROGRAM P VAR x : LINT; END_VAR x := A60; END_PROGRAM")
    plc = plclab.loads(src)
    plc.scan()
    assert plc["x"] == 2 ** 60
    # squaring: the numbers would grow without limit
    src = ("VAR_GLOBAL CONSTANT A0 : LINT := 3;" +
           "".join(f"A{i + 1} : LINT := A{i} * A{i};" for i in range(200)) +
           "END_VAR PROGRAM P VAR a : ARRAY[1..A200] OF INT; END_VAR a[1] := 1; END_PROGRAM")
    d = one(src, "PLC0125")
    assert "128 bits" in d.message
    assert len(errors(src)) == 1


def test_enumeration_values_may_refer_to_later_types_and_constants():
    plc = plclab.loads("""
        TYPE E : (A, B := 5, C); E2 : (X := N * 2, Y := LAST + 1); E3 : (LAST := 40); END_TYPE
        TYPE Arr : ARRAY[1..N] OF INT; END_TYPE
        VAR_GLOBAL CONSTANT N : INT := 3; END_VAR
        PROGRAM P VAR a : Arr; e : E; f : E2; i : INT; j : INT; END_VAR
        e := C; f := Y; a[3] := 7;
        CASE e OF C: i := 1; END_CASE
        CASE f OF Y: j := 9; END_CASE
        END_PROGRAM""")
    plc.scan()
    assert (plc["a"], plc["e"], plc["f"], plc["i"], plc["j"]) == ([0, 0, 7], 6, 41, 1, 9)


def test_a_constant_overflowing_lreal_is_an_error():
    src = ("VAR_GLOBAL CONSTANT R : LREAL := 1.0E300 * 1.0E300; END_VAR\n"
           "PROGRAM P VAR x : LREAL; END_VAR x := R; END_PROGRAM")
    assert "LREAL" in one(src, "PLC0125").message


# -- instances that contain themselves, data size, nesting ---------------------------------

@pytest.mark.parametrize("src, chain", [
    ("FUNCTION_BLOCK F VAR x : F; END_VAR END_FUNCTION_BLOCK\nPROGRAM P END_PROGRAM", "F.x -> F"),
    ("FUNCTION_BLOCK F VAR g : ARRAY[1..3] OF G; END_VAR END_FUNCTION_BLOCK\n"
     "FUNCTION_BLOCK G VAR s : S; END_VAR END_FUNCTION_BLOCK\n"
     "TYPE S : STRUCT f : F; END_STRUCT; END_TYPE\n"
     "PROGRAM P VAR f : F; END_VAR f(); END_PROGRAM", "F.g -> G.s -> S.f -> F"),
    ("PROGRAM P VAR me : P; END_VAR END_PROGRAM", "P.me -> P"),
])
def test_a_block_containing_itself_is_a_compile_error_naming_the_chain(src, chain):
    d = one(src, "PLC0123")
    assert chain in d.message and "VAR_IN_OUT" in d.message


@pytest.mark.parametrize("src, chain", [
    ("TYPE S : STRUCT a : S; END_STRUCT; END_TYPE\nPROGRAM P VAR e : S; END_VAR END_PROGRAM",
     "S -> S"),
    ("TYPE S : STRUCT a : T; END_STRUCT; END_TYPE\n"
     "TYPE T : STRUCT b : ARRAY[1..2] OF S; END_STRUCT; END_TYPE\n"
     "PROGRAM P VAR e : S; END_VAR END_PROGRAM", "S -> T -> S"),
])
def test_a_structure_containing_itself_is_a_compile_error(src, chain):
    assert chain in one(src, "PLC0123").message


def test_a_block_passed_in_out_is_no_cycle():
    plclab.loads("FUNCTION_BLOCK F VAR_IN_OUT other : F; END_VAR END_FUNCTION_BLOCK\n"
                 "PROGRAM P VAR a : INT; END_VAR a := 1; END_PROGRAM")


def test_nested_small_arrays_are_rejected_by_their_total_size():
    # each level passes the per-array limit; together 4**24 bytes
    src = "PROGRAM P VAR a : " + "ARRAY[1..4] OF " * 24 + "BOOL; END_VAR\nEND_PROGRAM"
    d = one(src, "PLC0124")
    assert f"{4 ** 24:,} bytes" in d.message and "P.a" in d.message
    assert (d.location.line, d.location.col) == (1, 15)
    src = "PROGRAM P VAR a : " + "ARRAY[1..2] OF " * 40 + "BOOL; END_VAR\nEND_PROGRAM"
    assert "32 levels" in one(src, "PLC0124").message
    src = "".join(f"TYPE T{i + 1} : ARRAY[1..2] OF T{i}; END_TYPE\n" for i in range(40))
    src += "TYPE T0 : BOOL; END_TYPE\nPROGRAM P VAR a : T40; END_VAR\nEND_PROGRAM"
    d = one(src, "PLC0124")
    assert "40 levels" in d.message and d.location.line == 42


def test_total_data_names_the_chain_that_makes_it_big():
    src = ("TYPE M : STRUCT buf : ARRAY[1..10000] OF LREAL; END_STRUCT; END_TYPE\n"
           "PROGRAM P VAR big : ARRAY[1..1000] OF M; END_VAR END_PROGRAM")
    d = one(src, "PLC0124")
    assert "80,008,000 bytes" in d.message
    assert "P.big : ARRAY[1..1000] OF M" in d.message and "M.buf" in d.message
    assert d.location.line == 2


def test_globals_and_programs_add_up():
    m = "TYPE M : STRUCT buf : ARRAY[1..1000] OF LREAL; END_STRUCT; END_TYPE\n"
    fits = m + ("VAR_GLOBAL g : ARRAY[1..1000] OF M; END_VAR\n"
                "PROGRAM P VAR big : ARRAY[1..1000] OF M; END_VAR big[1].buf[1] := 1.0; "
                "g[1].buf[1] := 2.0; END_PROGRAM")
    assert not errors(fits)
    too_much = fits.replace("PROGRAM P", "PROGRAM Q VAR b : ARRAY[1..200] OF M; END_VAR\n"
                            "b[1].buf[1] := 1.0; END_PROGRAM\nPROGRAM P")
    assert "the program's data" in one(too_much, "PLC0124").message


@pytest.mark.parametrize("decls", [
    "FUNCTION F : INT VAR a : ARRAY[1..3000] OF STRING[9999]; END_VAR F := 1; END_FUNCTION",
    "TEST 'big' VAR a : ARRAY[1..3000] OF STRING[9999]; END_VAR END_TEST",
    "FUNCTION_BLOCK F VAR a : ARRAY[1..3000] OF WSTRING[4999]; END_VAR END_FUNCTION_BLOCK",
])
def test_functions_tests_and_unused_blocks_are_checked_too(decls):
    assert "30,000,000 bytes" in one(decls + "\nPROGRAM P END_PROGRAM", "PLC0124").message


@pytest.mark.parametrize("src", [
    "".join(f"FUNCTION_BLOCK F{i} VAR x : F{i + 1}; END_VAR END_FUNCTION_BLOCK\n"
            for i in range(1000)) + "FUNCTION_BLOCK F1000 END_FUNCTION_BLOCK\n"
    "PROGRAM P VAR f : F0; END_VAR END_PROGRAM",
    "".join(f"TYPE T{i + 1} : ARRAY[1..1] OF T{i}; END_TYPE\n" for i in reversed(range(1000))) +
    "TYPE T0 : INT; END_TYPE PROGRAM P VAR f : T1000; END_VAR END_PROGRAM",
    "".join(f"TYPE S{i} : STRUCT x : S{i + 1}; END_STRUCT; END_TYPE\n" for i in range(1000)) +
    "TYPE S1000 : INT; END_TYPE PROGRAM P VAR f : S0; END_VAR END_PROGRAM",
    "VAR_GLOBAL CONSTANT\n" + "".join(f"C{i} : INT := C{i + 1};\n" for i in range(2000)) +
    "C2000 : INT := 1; END_VAR PROGRAM P VAR a : ARRAY[1..C0] OF INT; END_VAR END_PROGRAM",
    "PROGRAM P VAR a : " + "ARRAY[1..2] OF " * 1000 + "INT; END_VAR END_PROGRAM",
    "PROGRAM P VAR b : INT := " + "[" * 1000 + "]" * 1000 + "; END_VAR END_PROGRAM",
    "PROGRAM P VAR a : " + "STRUCT x : " * 1000 + "INT; END_STRUCT" * 1000 + "; END_VAR "
    "END_PROGRAM",
])
def test_deep_declarations_are_an_error_not_a_recursion_error(src):
    assert one(src, "PLC0124")


# -- recursion is reported at the call -------------------------------------------------------

@pytest.mark.parametrize("src, chain, at", [
    ("FUNCTION F : INT VAR_INPUT n : INT; END_VAR\nF := F(n - 1);\nEND_FUNCTION", "F -> F",
     (2, 6)),
    ("FUNCTION F : INT VAR_INPUT n : INT; END_VAR\nF := 1;\nIF n > 0 THEN F := G(n); END_IF\n"
     "END_FUNCTION\nFUNCTION G : INT VAR_INPUT n : INT; END_VAR\nG := F(n - 1);\n"
     "END_FUNCTION", "F -> G -> F", (6, 6)),
    ("FUNCTION_BLOCK A VAR b : B; END_VAR\nb();\nEND_FUNCTION_BLOCK\n"
     "FUNCTION_BLOCK B VAR_IN_OUT a : A; END_VAR\n  a();\nEND_FUNCTION_BLOCK", "A -> B -> A",
     (5, 3)),
])
def test_recursion_points_at_the_call_that_closes_the_circle(src, chain, at):
    d = one(src, "PLC0110")
    assert chain in d.message
    assert (d.location.line, d.location.col) == at


def test_a_long_call_chain_is_checked_without_recursion_error():
    src = "".join(f"FUNCTION F{i} : INT F{i} := F{i + 1}(); END_FUNCTION\n" for i in range(1500))
    src += "FUNCTION F1500 : INT F1500 := F0(); END_FUNCTION"
    d = one(src, "PLC0110")
    assert d.location.line == 1501 and "F0 -> F1" in d.message and "more)" in d.message


# -- literals ----------------------------------------------------------------------------------

LIT = ("PROGRAM P VAR x : LINT; r : LREAL; t : TIME; lt : LTIME; d : DATE; dt1 : DT; re : REAL;"
       " END_VAR\n{} END_PROGRAM")


@pytest.mark.parametrize("body, code, words", [
    ("r := 1.0E400;", "PLC0125", "LREAL"),
    ("r := LREAL#-1E999;", "PLC0125", "LREAL"),
    ("x := " + "9" * 5000 + ";", "PLC0125", "5000 digits"),
    ("x := LINT#" + "9" * 5000 + ";", "PLC0125", "5000 digits"),
    ("x := 16#" + "F" * 5000 + ";", "PLC0125", "5000 digits"),
    ("re := 1.0E39;", "PLC0111", "REAL"),
    ("re := REAL#-1.0E39;", "PLC0111", "REAL"),
    ("t := T#25d;", "PLC0126", "LTIME"),
    ("t := T#-24d20h31m23s649ms;", "PLC0126", "TIME"),
    ("t := T#" + "9" * 5000 + "s;", "PLC0126", "out of range"),
    ("lt := LTIME#106752d;", "PLC0126", "106751 days"),
    ("d := D#1969-12-31;", "PLC0126", "1970-01-01"),
    ("d := D#2106-02-08;", "PLC0126", "2106-02-07"),
    ("dt1 := DT#1960-01-01-00:00:00;", "PLC0126", "1970-01-01"),
])
def test_literals_beyond_their_range_are_located_errors(body, code, words):
    src = LIT.format(body)
    d = one(src, code)
    assert words in d.message and len(d.message) < 300
    assert d.location.line == 2
    assert len(errors(src)) == 1


@pytest.mark.parametrize("body, var, value", [
    ("t := T#24d20h31m23s647ms;", "t", 2_147_483_647),
    ("t := T#-24d20h31m23s648ms;", "t", -2_147_483_648),
    ("lt := T#30d;", "lt", 30 * 86_400 * 10 ** 9),
    ("lt := LTIME#106751d;", "lt", 106_751 * 86_400 * 10 ** 9),
    ("re := 3.0E38;", "re", pytest.approx(3.0e38, rel=1e-6)),
    ("r := 1.0E308;", "r", 1.0e308),
    ("d := D#2106-02-07;", "d", 4_294_944_000),
    ("x := 9223372036854775807;", "x", 9_223_372_036_854_775_807),
    ("t := T#1.5" + "0" * 400 + "ms;", "t", 1),
])
def test_literals_at_their_limits_still_work(body, var, value):
    plc = plclab.loads(LIT.format(body))
    plc.scan()
    assert plc[var] == value


# -- addresses -----------------------------------------------------------------------------------

ADDR = "PROGRAM P VAR x : WORD; b : BOOL; END_VAR\n{} END_PROGRAM"


@pytest.mark.parametrize("body, code", [
    ("x := %MW70000;", "PLC0127"),
    ("x := %MW65535;", "PLC0127"),  # its second byte is 65536
    ("x := %MW" + "9" * 5000 + ";", "PLC0127"),
    ("b := %IX0.8;", "PLC0120"),
    ("%QX1." + "9" * 5000 + " := b;", "PLC0120"),
    ("x := %MW1.2;", "PLC0120"),
])
def test_direct_addresses_beyond_the_image_are_compile_errors(body, code):
    d = one(ADDR.format(body), code)
    assert d.location.line == 2 and len(d.message) < 200


@pytest.mark.parametrize("decl, code", [
    ("v AT %MW70000 : WORD;", "PLC0127"),
    ("v AT %IX1.99 : BOOL;", "PLC0120"),
    ("v AT %QD65533 : DWORD;", "PLC0127"),
])
def test_located_variables_beyond_the_image_are_compile_errors(decl, code):
    one(f"PROGRAM P VAR {decl} END_VAR\nEND_PROGRAM", code)


def test_the_plc_checks_addresses_against_its_image_size():
    src = "PROGRAM P VAR v AT %MW5000 : WORD; x : WORD; END_VAR\nv := 1; x := %IW6000; END_PROGRAM"
    with pytest.raises(PlcError) as ei:
        plclab.loads(src, image_size=1024)  # an explicit size smaller than the program needs
    e = ei.value
    assert e.code == "PLC0127" and "image_size=6002" in e.message
    assert e.location is not None and e.location.line == 2
    plc = plclab.loads(src, image_size=6002)
    plc.scan()
    assert plc["%MW5000"] == 1
    plc = plclab.loads(src)  # by default, sized from the program's addresses (ADR 0053)
    assert plc.image_size == 6144 and len(plc.memory) == 6144
    plclab.loads(ADDR.format("x := %IW1022;"))  # the last word of the default image


# -- tasks ---------------------------------------------------------------------------------------

CONF = ("CONFIGURATION C RESOURCE R ON PLC\nTASK t ({});\nPROGRAM i WITH t : P;\n"
        "END_RESOURCE END_CONFIGURATION\nPROGRAM P VAR n : INT; END_VAR n := n + 1; END_PROGRAM\n"
        "VAR_GLOBAL CONSTANT CT : TIME := T#20ms; END_VAR")


@pytest.mark.parametrize("props", [
    "INTERVAL := T#0ms", "INTERVAL := T#-5ms", "INTERVAL := 5", "INTERVAL := T#0.5ms",
    "INTERVAL := 'fast'", "INTERVAL := T#10ms, PRIORITY := 40",
    "INTERVAL := T#10ms, PRIORITY := -1", "INTERVAL := T#10ms, PRIORITY := TRUE",
    "INTERVAL := T#10ms, PRIORITY := CT",
])
def test_bad_task_intervals_and_priorities_are_errors_at_the_task(props):
    d = one(CONF.format(props), "PLC0129")
    assert d.location.line == 2
    with pytest.raises(PlcError) as ei:
        plclab.loads(CONF.format(props))
    assert ei.value.code == "PLC0129"


def test_task_interval_and_priority_may_be_constants():
    plc = plclab.loads(CONF.format("INTERVAL := CT, PRIORITY := 2"))
    (task,) = plc.tasks
    assert (task.interval_ns, task.priority) == (20_000_000, 2)
    plc = plclab.loads(CONF.format("INTERVAL := LTIME#500us"))
    assert plc.tasks[0].interval_ns == 500_000
