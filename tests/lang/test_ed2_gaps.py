"""Issue 40's gaps between the dialects, the refusals and warnings side: what the TEST blocks
of tests/st/ed2_matiec_gaps.st accept in one dialect is refused (or warned about) in another."""

from __future__ import annotations

import pytest

from plclab.project import check_sources


def diags(text: str, dialect: str) -> list[tuple[str, str, int]]:
    """(code, severity, line) of every diagnostic of ``text`` read in ``dialect``."""
    return [(d.code, d.severity, d.location.line if d.location else 0)
            for d in check_sources([(text, "f.st")], dialect)[1]]


def errors(text: str, dialect: str) -> list[str]:
    return [c for c, sev, _ in diags(text, dialect) if sev == "error"]


TRUNC_INT = """PROGRAM P VAR r : REAL := 2.5; i : INT; w : WORD; END_VAR
i := TRUNC(r) + 1;
w := INT_TO_WORD(TRUNC(r));
END_PROGRAM
"""


@pytest.mark.parametrize("dialect", ["iec", "matiec"])
def test_trunc_takes_its_type_from_the_context_in_ed2_dialects(dialect):
    assert diags(TRUNC_INT, dialect) == []


def test_trunc_is_dint_in_codesys_and_s7():
    # CODESYS: a DINT stored in an INT, accepted with its warning, and INT_TO_WORD of a DINT
    # wraps it to INT first with the same warning (ADR 0051); S7: both refused
    assert [(c, s, n) for c, s, n in diags(TRUNC_INT, "codesys")] == [
        ("PLC0285", "warning", 2), ("PLC0285", "warning", 3)]
    assert errors(TRUNC_INT, "s7") == ["PLC0118", "PLC0107"]


@pytest.mark.parametrize("target", ["WORD", "BOOL", "TIME"])
def test_trunc_into_a_type_that_is_no_integer_is_refused_in_iec(target):
    # ANY_INT is no bit string: the context does not make TRUNC a WORD
    text = f"PROGRAM P VAR r : REAL; x : {target}; END_VAR x := TRUNC(r); END_PROGRAM"
    assert errors(text, "iec") == ["PLC0118"]


def test_round_is_not_typed_by_context():
    # ROUND is not an IEC function: it stays DINT (as in CODESYS and OSCAT's own ROUND)
    text = "PROGRAM P VAR r : REAL; i : INT; END_VAR i := ROUND(r); END_PROGRAM"
    assert errors(text, "iec") == ["PLC0118"]


MULTIME = "PROGRAM P VAR t : TIME; END_VAR t := MULTIME(T#1s, 2) + DIVTIME(T#1s, 2); END_PROGRAM"


@pytest.mark.parametrize("dialect", ["iec", "codesys", "s7"])
def test_ed2_time_names_are_refused_outside_matiec(dialect):
    assert errors(MULTIME, dialect) == ["PLC0320", "PLC0320"]
    assert errors(MULTIME, "matiec") == []


def test_a_user_function_called_multime_wins_over_the_ed2_name():
    text = ("FUNCTION MULTIME : TIME VAR_INPUT a : TIME; b : INT; END_VAR MULTIME := a; "
            "END_FUNCTION\nPROGRAM P VAR t : TIME; END_VAR t := MULTIME(T#1s, 2); END_PROGRAM")
    assert errors(text, "codesys") == []


CONST_NO_VALUE = """VAR_GLOBAL CONSTANT G : INT; END_VAR
PROGRAM P VAR CONSTANT K : DINT; END_VAR VAR a : ARRAY[K..2] OF INT; x : DINT; END_VAR
x := K + G + a[0];
END_PROGRAM
"""


@pytest.mark.parametrize("dialect", ["iec", "matiec"])
def test_a_constant_without_a_value_has_its_default_in_iec_and_matiec(dialect):
    assert errors(CONST_NO_VALUE, dialect) == []


@pytest.mark.parametrize("dialect", ["codesys", "s7"])
def test_a_constant_without_a_value_is_refused_where_the_vendor_requires_one(dialect):
    found = [(c, line) for c, sev, line in diags(CONST_NO_VALUE, dialect) if sev == "error"]
    assert found == [("PLC0109", 1), ("PLC0109", 2)]  # the global's and the local's


def test_a_constant_without_a_value_is_still_read_only():
    text = "PROGRAM P VAR CONSTANT K : INT; END_VAR K := 1; END_PROGRAM"
    assert errors(text, "iec") != []


@pytest.mark.parametrize("access, ok", [
    ("d.%B3", True), ("d.%B4", False), ("d.%W1", True), ("d.%W2", False), ("d.%D0", True),
    ("d.%D1", False), ("d.%L0", False), ("w.%B1", True), ("w.%B2", False), ("w.%D0", False),
    ("l.%D1", True), ("l.%B7", True), ("l.%B8", False), ("i.%B0", False), ("r.%B0", False),
    ("x.%B0", False), ("b.%B0", True), ("b.%W0", False)])
def test_partial_access_is_bounded_by_the_variable(access, ok):
    text = (f"PROGRAM P VAR d : DWORD; w : WORD; l : LWORD; i : INT; r : REAL; x : BOOL; "
            f"b : BYTE; v : LWORD; END_VAR v := {access}; {access} := 0; END_PROGRAM")
    assert errors(text, "iec") == ([] if ok else ["PLC0176", "PLC0176"])  # read and write


def test_a_part_has_its_own_type():
    text = "PROGRAM P VAR d : DWORD; b : BYTE; END_VAR b := d.%W0; END_PROGRAM"
    assert errors(text, "iec") == ["PLC0118"]  # a WORD does not fit a BYTE


HOLDER = """FUNCTION_BLOCK Holder
VAR i : INT; d : DINT; p : POINTER TO INT; pd : POINTER TO DINT;
    pp : POINTER TO POINTER TO INT; q : POINTER TO POINTER TO INT;
    r : REF_TO INT; rr : REF_TO REF_TO INT; rr2 : REF_TO REF_TO INT; rd : REF_TO DINT; END_VAR
{body}
END_FUNCTION_BLOCK
"""


@pytest.mark.parametrize("body", ["p := ADR(i); pp := ADR(p); q := pp; i := q^^;",
                                  "r := REF(i); rr := REF(r); rr2 := rr; rr2^^ := 7;"])
def test_pointers_to_pointers_are_equal_by_structure(body):
    assert errors(HOLDER.format(body=body), "codesys") == []


@pytest.mark.parametrize("body", ["pp := ADR(i);", "pp := ADR(pd);", "rr := REF(i);",
                                  "rr := REF(rd);", "q := ADR(pp);", "p := pp;"])
def test_pointers_to_pointers_of_another_target_are_refused(body):
    assert errors(HOLDER.format(body=body), "codesys") == ["PLC0241"]


PROGRAM_ACCESS = """PROGRAM P
VAR x : INT; t : TON; END_VAR
VAR_ACCESS
  ax : x : INT READ_WRITE;
  et : t.ET : TIME;
END_VAR
x := x + 1;
t(IN := TRUE, PT := T#1s);
END_PROGRAM
CONFIGURATION C
RESOURCE R ON PLC
TASK T1(INTERVAL := T#10ms, PRIORITY := {prio});
PROGRAM I WITH T1 : P;
END_RESOURCE
END_CONFIGURATION
"""


def test_a_programs_var_access_names_its_variables_in_iec_and_matiec(tmp_path):
    import plclab
    from plclab.errors import PlcError

    f = tmp_path / "p.st"
    f.write_text(PROGRAM_ACCESS.format(prio=90), encoding="utf-8")
    plc = plclab.load(str(f), dialect="matiec")
    plc.scan()
    plc.scan()
    assert plc["I.ax"] == plc["I.x"] == 2
    assert plc.format("I.et") == plc.format("I.t.ET")
    plc["I.ax"] = 40
    assert plc["I.x"] == 40
    with pytest.raises(PlcError) as e:  # READ_ONLY, the default
        plc["I.et"] = 0
    assert e.value.code == "PLC3013"
    assert errors(PROGRAM_ACCESS.format(prio=1), "iec") == []


@pytest.mark.parametrize("dialect", ["codesys", "s7"])
def test_a_programs_var_access_is_refused_where_the_vendor_has_none(dialect):
    assert errors(PROGRAM_ACCESS.format(prio=1), dialect) == ["PLC0321", "PLC0321"]


@pytest.mark.parametrize("section, code", [
    ("VAR_ACCESS ax : y : INT; END_VAR", "PLC0100"),  # no such variable
    ("VAR_ACCESS ax : x : DINT; END_VAR", "PLC0103"),  # not its type
    ("VAR_ACCESS x : x : INT; END_VAR", "PLC0101"),  # the name of a variable
    ("VAR_ACCESS ax : x : INT; ax : x : INT; END_VAR", "PLC0101"),
    ("VAR_ACCESS ax : %IX0.0 : BOOL; END_VAR", "PLC0010")])  # a path, not an address
def test_a_programs_var_access_is_checked(section, code):
    text = f"PROGRAM P VAR x : INT; END_VAR {section} x := 1; END_PROGRAM"
    assert errors(text, "iec") == [code]


def test_var_access_in_a_function_block_is_refused():
    text = "FUNCTION_BLOCK F VAR x : INT; END_VAR VAR_ACCESS a : x : INT; END_VAR END_FUNCTION_BLOCK"
    assert errors(text, "iec") == ["PLC0321"]


@pytest.mark.parametrize("dialect, prio, ok", [
    ("matiec", 90, True), ("iec", 65535, True), ("iec", 65536, False), ("codesys", 31, True),
    ("codesys", 90, False), ("s7", 32, False), ("matiec", -1, False)])
def test_task_priority_range_per_dialect(dialect, prio, ok):
    text = PROGRAM_ACCESS.format(prio=prio).replace("VAR_ACCESS", "VAR").replace(
        "  ax : x : INT READ_WRITE;\n  et : t.ET : TIME;\n", "")
    assert errors(text, dialect) == ([] if ok else ["PLC0129"])


@pytest.mark.parametrize("dialect", ["iec", "codesys", "matiec"])
def test_assigning_eno_in_a_body_declares_the_implicit_output(dialect):
    text = ("FUNCTION F : INT VAR_INPUT g : INT; END_VAR IF g < 0 THEN ENO := FALSE; RETURN; "
            "END_IF; F := g; END_FUNCTION\nPROGRAM P VAR ok : BOOL; r : INT; END_VAR "
            "r := F(g := 1, ENO => ok); END_PROGRAM")
    assert errors(text, dialect) == []


@pytest.mark.parametrize("body, code", [
    ("ENO := 5;", "PLC0118"),  # ENO is a BOOL
    ("ENO := 'x';", "PLC0103")])
def test_eno_keeps_its_type(body, code):
    text = f"FUNCTION_BLOCK B VAR_INPUT g : INT; END_VAR {body} END_FUNCTION_BLOCK"
    assert errors(text, "iec") == [code]


def test_eno_is_no_variable_of_a_program():
    text = "PROGRAM P VAR x : INT; END_VAR ENO := FALSE; x := 1; END_PROGRAM"
    assert errors(text, "iec") == ["PLC0100"]


def test_a_caller_binds_eno_to_a_bool_only():
    text = ("FUNCTION_BLOCK B ENO := FALSE; END_FUNCTION_BLOCK\n"
            "PROGRAM P VAR b : B; n : INT; END_VAR b(ENO => n); END_PROGRAM")
    assert errors(text, "iec") != []


AXIS = """FUNCTION_BLOCK Axis
VAR_OUTPUT k : INT; END_VAR
METHOD FB_init : BOOL
VAR_INPUT bInitRetains : BOOL; bInCopyCode : BOOL; gain : INT; END_VAR
k := gain;
END_METHOD
END_FUNCTION_BLOCK
PROGRAM P VAR {decl} END_VAR END_PROGRAM
"""


def test_fb_init_arguments_in_a_declaration_are_codesys():
    assert errors(AXIS.format(decl="a : Axis(gain := 3); b : Axis(4);"), "codesys") == []
    for dialect in ("iec", "matiec", "s7"):
        assert errors(AXIS.format(decl="a : Axis(gain := 3);"), dialect) == ["PLC0322"]


@pytest.mark.parametrize("decl, code", [
    ("t : TON(PT := T#1s);", "PLC0322"),  # no FB_init: inputs take a : TON := (PT := ...)
    ("a : Axis(speed := 3);", "PLC0322"),  # not an input of FB_init
    ("a : Axis(3, 4);", "PLC0322"),  # one too many
    ("a : Axis(gain := 3, gain := 4);", "PLC0322"),
    ("a : Axis(gain := 'x');", "PLC0103"),
    ("a : Axis(gain := 100000);", "PLC0111")])
def test_fb_init_arguments_are_checked(decl, code):
    assert errors(AXIS.format(decl=decl), "codesys") == [code]


@pytest.mark.parametrize("decl", ["x : INT (1..5);", "x : INT (-1..5);", "e : INT (A, B);"])
def test_subranges_and_typed_enumerations_are_no_fb_init_arguments(decl):
    assert errors(AXIS.format(decl=decl), "iec") == []


def test_fb_init_arguments_survive_the_round_trip():
    from plclab.lang.frontends.st import parse_st
    from plclab.lang.unparse import unparse

    printed = unparse(parse_st(AXIS.format(decl="a : Axis(gain := 3); b : Axis(4);"), "a.st"))
    assert "A : AXIS(GAIN := 3);" in printed.upper() and "B : AXIS(4);" in printed.upper()
