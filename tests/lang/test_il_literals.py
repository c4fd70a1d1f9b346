"""IL literals typed by their context (issue 40 item 11, ADR 0053): ``LD 0``/``LD 1`` stored
into a BOOL as ST accepts ``b := 1``; a literal reaching a label takes the type the other paths
bring there."""

import pytest

import plclab
from plclab.project import check_sources


def errors(text: str):
    return [d for d in check_sources([(text, "il.st")])[1] if d.severity == "error"]


def program(body: str, decls: str) -> str:
    return f"PROGRAM Main\nVAR {decls} END_VAR\n{body}\nEND_PROGRAM\n"


@pytest.mark.parametrize("op,lit,start,expected", [
    ("ST", "1", "FALSE", True), ("ST", "0", "TRUE", False),
    ("STN", "1", "TRUE", False), ("STN", "0", "FALSE", True),
    ("S", "1", "FALSE", True), ("S", "0", "FALSE", False),
    ("R", "1", "TRUE", False), ("R", "0", "TRUE", True),
])
def test_ld_0_or_1_into_a_bool(op, lit, start, expected):
    text = program(f"    LD {lit}\n    {op} b", f"b : BOOL := {start};")
    assert not errors(text), errors(text)
    plc = plclab.loads(text, "il.st")
    plc.scan()
    assert plc["Main.b"] is expected


@pytest.mark.parametrize("lit", ["2", "-1", "1.0", "16#1"])
def test_other_literals_into_a_bool_are_still_refused(lit):
    """Only 0 and 1 are BOOL literals (16#1 is a bit-string literal, not a BOOL)."""
    text = program(f"    LD {lit}\n    ST b", "b : BOOL;")
    if lit == "16#1":
        # ST accepts b := 16#1? keep IL as strict as ST: compare with the ST verdict
        st = program("b := 16#1;", "b : BOOL;")
        assert bool(errors(text)) == bool(errors(st))
    else:
        errs = errors(text)
        assert errs and errs[0].code == "PLC0140"


BRANCHES = """
    LD go
    JMPC L2
    LD {lit}
    JMP L1
L2: LD {var}
L1: ST {out}
"""


@pytest.mark.parametrize("var,ty,lit,other", [
    ("k", "INT", "0", 5), ("k", "SINT", "3", 5), ("k", "REAL", "2.5", 5.0),
    ("k", "REAL", "2", 5.0), ("k", "BOOL", "1", True), ("k", "LINT", "9", 5),
])
def test_literal_reaching_a_label_is_typed_by_the_other_path(var, ty, lit, other):
    init = "TRUE" if ty == "BOOL" else "5"
    text = program(BRANCHES.format(lit=lit, var=var, out="r"),
                   f"go : BOOL; k : {ty} := {init}; r : {ty};")
    assert not errors(text), errors(text)
    plc = plclab.loads(text, "il.st")
    plc.scan()
    want = {"BOOL": lit == "1", "REAL": float(lit)}.get(ty, int(lit) if lit.isdigit() else lit)
    assert plc["Main.r"] == want
    plc["Main.go"] = True
    plc.scan()
    assert plc["Main.r"] == other


def test_typed_path_first_then_literal():
    body = """
    LD go
    JMPCN L2
    LD k
    JMP L1
L2: LD 0
L1: ST r
"""
    text = program(body, "go : BOOL; k : INT := 5; r : INT;")
    assert not errors(text), errors(text)
    assert not [d for d in check_sources([(text, "il.st")])[1] if d.code == "PLC0285"]
    plc = plclab.loads(text, "il.st")
    plc["Main.go"] = True
    plc.scan()
    assert plc["Main.r"] == 5


def test_a_real_literal_cannot_become_an_int_path():
    errs = errors(program(BRANCHES.format(lit="2.5", var="k", out="r"),
                          "go : BOOL; k : INT := 5; r : INT;"))
    assert errs and errs[0].code == "PLC0147"


def test_a_string_path_and_an_int_literal_still_clash():
    errs = errors(program(BRANCHES.format(lit="0", var="s", out="t"),
                          "go : BOOL; s : STRING; t : STRING;"))
    assert errs and errs[0].code == "PLC0147"
