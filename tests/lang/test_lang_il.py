"""Instruction List: the current result, deferred operations, jumps, calls, and every IL
diagnostic (PLC0140-PLC0147) with its location."""

import pytest

import plclab
from plclab.errors import PlcError, PlcRuntimeFault
from plclab.lang.frontends.st import parse_st
from plclab.project import check_sources


def load(body: str, decls: str = "", filename: str = "p.il", **kw):
    return plclab.loads(f"PROGRAM P\nVAR\n{decls}\nEND_VAR\n{body}\nEND_PROGRAM\n", filename, **kw)


def diags(body: str, decls: str = "", filename: str = "d.il"):
    src = f"PROGRAM P\nVAR\n{decls}\nEND_VAR\n{body}\nEND_PROGRAM\n"
    _, ds = check_sources([(src, filename)])
    return [d for d in ds if d.severity == "error"]


def test_textbook_linear_transformation():
    """001 L1920-1940: LD x / MUL A / ADD B / ST Y computes Y = A*x + B."""
    plc = load("LD x\nMUL A\nADD B\nST Y", "x, A, B, Y : INT;")
    plc["x"], plc["A"], plc["B"] = 3, 4, 5
    plc.scan()
    assert plc["Y"] == 17


def test_deferred_operations_nest():
    plc = load("""
    LD   a
    AND( b
    OR(  c
    AND  d
    )
    )
    ST   q
    LD   5
    MUL( 2
    ADD  1
    )
    ST   n
    LD   20
    SUB( n
    )
    ST   m
    LD   a
    ANDN( b
    )
    ST   r""", "a, b, c, d, q, r : BOOL; n, m : INT;")
    for a in (False, True):
        for b in (False, True):
            for c in (False, True):
                for d in (False, True):
                    plc["a"], plc["b"], plc["c"], plc["d"] = a, b, c, d
                    plc.scan()
                    assert plc["q"] == (a and (b or (c and d)))
                    assert plc["r"] == (a and not b)
    assert plc["n"] == 15 and plc["m"] == 5


def test_deferred_operation_with_ld_inside():
    plc = load("LD a\nOR(\nLD b\nAND c\n)\nST q", "a, b, c, q : BOOL;")
    plc["b"], plc["c"] = True, True
    plc.scan()
    assert plc["q"] is True


def test_forward_conditional_jump_skips_code():
    src = """
    LD   x
    GT   10
    JMPC big
    LD   1
    ST   y
    JMP  done
big:
    LD   2
    ST   y
done:
    LD   y
    ST   z"""
    plc = load(src, "x, y, z : INT;")
    plc["x"] = 5
    plc.scan()
    assert (plc["y"], plc["z"]) == (1, 1)
    plc["x"] = 50
    plc.scan()
    assert (plc["y"], plc["z"]) == (2, 2)


def test_backward_jump_loop_with_counter():
    src = """
    LD   0
    ST   i
    ST   sum
loop:
    LD   sum
    ADD  i
    ST   sum
    LD   i
    ADD  1
    ST   i
    LT   limit
    JMPC loop
"""
    plc = load(src, "i, sum, limit : INT;")
    plc["limit"] = 10
    plc.scan()
    assert (plc["i"], plc["sum"]) == (10, 45)


def test_jmpcn_and_cr_carried_to_a_label():
    src = """
    LD   x
    GE   0
    JMPCN neg
    ST   positive       (* the BOOL current result reaches here and at neg *)
    JMP  out
neg:
    ST   positive
out:
    LD   x"""
    plc = load(src + "\n    ST y", "x, y : INT; positive : BOOL;")
    for x in (-3, 0, 7):
        plc["x"] = x
        plc.scan()
        assert plc["positive"] is (x >= 0)


def test_backward_jump_charges_the_watchdog():
    src = "start:\n    LD TRUE\n    JMPC start"
    plc = load(src, "", watchdog=1000)
    with pytest.raises(PlcRuntimeFault) as ei:
        plc.scan()
    assert ei.value.code == "PLC2003"
    assert ei.value.location is not None and ei.value.location.line == 7


def test_loop_free_il_compiles_without_state_machine():
    plc = load("LD a\nST b", "a, b : BOOL;")
    assert "_pc" not in plc.compiled.source


def test_cal_forms_and_fb_input_operators():
    decls = ("x, q1, q2, q3, rst : BOOL; t1, t2 : TON; r : R_TRIG; e1, e2 : TIME; "
             "edge : BOOL;")
    src = """
    CAL  t1(IN := x, PT := T#50ms)
    LD   t1.Q
    ST   q1
    LD   x
    ST   t2.IN
    LD   T#50ms
    ST   t2.PT
    CAL  t2
    LD   t2.Q
    ST   q2
    LD   t1.ET
    ST   e1
    LD   t2.ET
    ST   e2
    LD   x
    CLK  r
    LD   r.Q
    ST   edge
    LD   rst
    CALC t1(IN := FALSE)
    LD   t1.Q
    ST   q3"""
    plc = load(src, decls)
    plc["x"] = True
    plc.scan()
    assert plc["edge"] is True
    plc.scan(5)
    assert plc["q1"] is True and plc["q2"] is True and plc["e1"] == plc["e2"]
    assert plc["edge"] is False and plc["q3"] is True
    plc["rst"] = True
    plc.scan()
    assert plc["q1"] is True and plc["q3"] is False  # CALC reset t1 after q1 was read


def test_function_call_with_current_result_as_first_argument():
    src = """
FUNCTION Twice : INT
VAR_INPUT v : INT; END_VAR
    LD v
    MUL 2
    ST Twice
END_FUNCTION
PROGRAM P
VAR a, b, c : INT; r : REAL; END_VAR
    LD 0
    LIMIT a, 100      (* LIMIT(MN := 0, IN := a, MX := 100): the CR is the first argument *)
    ST b
    LD a
    Twice
    ST c
    LD a
    INT_TO_REAL
    ST r
END_PROGRAM
"""
    plc = plclab.loads(src, "f.il")
    for a, want in ((-5, 0), (50, 50), (500, 100)):
        plc["a"] = a
        plc.scan()
        assert plc["b"] == want and plc["c"] == 2 * a and plc["r"] == float(a)


def test_returns():
    src = """
FUNCTION Sign : INT
VAR_INPUT v : INT; END_VAR
    LD  1
    ST  Sign
    LD  v
    GT  0
    RETC
    LD  0
    ST  Sign
    LD  v
    EQ  0
    RETC
    LD  -1
    ST  Sign
    RET
END_FUNCTION
PROGRAM P
VAR a, s : INT; END_VAR
s := Sign(a);
END_PROGRAM
"""
    plc = plclab.loads(src, "s.st")
    for a, want in ((7, 1), (0, 0), (-4, -1)):
        plc["a"] = a
        plc.scan()
        assert plc["s"] == want


def test_typed_current_result_real_and_time():
    plc = load("LD r\nMUL 2.5\nST r2\nLD t\nADD T#1s\nST t2\nLD n\nSTN b", "r, r2 : REAL; "
               "t, t2 : TIME; n : WORD; b : WORD;")
    plc["r"], plc["t"], plc["n"] = 2.0, "T#500ms", 0x00FF
    plc.scan()
    assert plc["r2"] == 5.0 and plc.format("t2") == "T#1s500ms" and plc["b"] == 0xFF00


def test_set_reset_and_stn():
    plc = load("LD a\nS q\nLD b\nR q\nLD a\nSTN nq", "a, b, q, nq : BOOL;")
    plc["a"] = True
    plc.scan()
    assert plc["q"] is True and plc["nq"] is False
    plc["a"] = False
    plc.scan()
    assert plc["q"] is True
    plc["b"] = True
    plc.scan()
    assert plc["q"] is False


def test_st_then_reuse_current_result_after_store():
    """The CR survives a store into one of its own operands."""
    plc = load("LD a\nADD 1\nST a\nST b\nLD x\nR x\nST y", "a, b : INT; x, y : BOOL;")
    plc["x"] = True
    plc.scan()
    assert (plc["a"], plc["b"]) == (1, 1)
    assert plc["x"] is False and plc["y"] is True


def test_st_and_il_pous_call_each_other_in_one_file():
    src = """
FUNCTION_BLOCK Latch
VAR_INPUT set, reset : BOOL; END_VAR
VAR_OUTPUT q : BOOL; END_VAR
    LD  set
    OR  q
    ANDN reset
    ST  q
END_FUNCTION_BLOCK
FUNCTION Double : INT
VAR_INPUT v : INT; END_VAR
Double := v * 2;
END_FUNCTION
PROGRAM P
VAR l : Latch; a, b : BOOL; n, m : INT; END_VAR
    CAL l(set := a, reset := b)
    LD  n
    Double
    ST  m
END_PROGRAM
PROGRAM Q
VAR l : Latch; q : BOOL; END_VAR
l(set := TRUE);
q := l.q;
END_PROGRAM
"""
    f = parse_st(src, "mix.st")
    assert [p.language for p in f.pous] == ["IL", "ST", "IL", "ST"]
    plc = plclab.loads(src, "mix.st")
    plc["P.a"], plc["P.n"] = True, 21
    plc.scan()
    assert plc["P.l.q"] is True and plc["P.m"] == 42 and plc["Q.q"] is True


@pytest.mark.parametrize("first,is_il", [
    ("LD x", True), ("L1: LD x", True), ("L1:", True), ("RET", True), ("NOT", True),
    ("x := 1;", False), ("IF x THEN x := 1; END_IF", False), ("fb(IN := x);", False),
    ("x.y := 1;", False), ("a[1] := 2;", False),
])
def test_il_recognition_rule(first, is_il):
    from plclab.lang.frontends.st import Parser

    p = Parser(f"PROGRAM P\n{first}\nEND_PROGRAM", "r.st")
    p.i = 2
    from plclab.lang.frontends.il_lines import is_il_body

    assert is_il_body(p, "END_PROGRAM") is is_il


def test_il_file_comments_and_labels_on_their_own_line():
    plc = load("(* start *)\nL1:\n    LD a   // load\n    ST b   (* store *)", "a, b : BOOL;")
    plc["a"] = True
    plc.scan()
    assert plc["b"] is True


# --- diagnostics ---------------------------------------------------------------------------
DECLS = "x, n : INT; b, q : BOOL; inp AT %IX0.0 : BOOL; t1 : TON; r : REAL;"
# (body, code, line, col, words in the message); line 5 is the first body line
DIAG_CASES = {
    "cr type for ADD": ("LD b\nADD 1\nST n", "PLC0140", 6, 1, ["BOOL", "LD b", "line 5"]),
    "cr type for ST": ("LD x\nST q", "PLC0140", 6, 1, ["INT", "q is BOOL"]),
    "cr type for AND": ("LD x\nAND q\nST n", "PLC0140", 6, 1, ["AND"]),
    "cr type for JMPC": ("LD x\nJMPC L1\nL1: LD b\nST q", "PLC0140", 6, 1, ["JMPC", "BOOL"]),
    "cr type for S": ("LD x\nS q", "PLC0140", 6, 1, ["S"]),
    "cr type for GT": ("LD t1.ET\nGT 5\nST q", "PLC0140", 6, 1, ["TIME"]),
    "unknown operator": ("LDD b\nST q", "PLC0141", 5, 1, ["LDD", "did you mean LD?"]),
    "unknown operator 2": ("LD b\nSTT q", "PLC0141", 6, 1, ["did you mean ST"]),
    "st line in il": ("LD b\nq := b;", "PLC0141", 6, 1, ["is ST, not IL"]),
    "st to an input": ("LD b\nST inp", "PLC0142", 6, 1, ["inp", "%IX0.0"]),
    "st to an address": ("LD b\nST %IX0.1", "PLC0142", 6, 1, ["%IX0.1"]),
    "unclosed paren": ("LD b\nAND( q\nOR b\nST q", "PLC0143", 6, 1, ["never closed"]),
    "stray paren": ("LD b\n)\nST q", "PLC0143", 6, 1, ["closes nothing"]),
    "jump inside paren": ("LD b\nAND( q\nJMP L\n)\nL: LD b\nST q", "PLC0143", 7, 1,
                          ["inside the parentheses"]),
    "no current result": ("ST q", "PLC0144", 5, 1, ["LD"]),
    "cr after CAL": ("CAL t1(IN := b)\nST q", "PLC0144", 6, 1, ["call"]),
    "unknown label": ("LD b\nJMPC lbl2\nlbl1: LD b\nST q", "PLC0145", 6, 1,
                      ["LBL2", "did you mean LBL1"]),
    "extra operand": ("LD b q\nST q", "PLC0146", 5, 6, ["'q'"]),
    "missing operand": ("LD\nST q", "PLC0146", 5, 1, ["operand"]),
    "jump needs label": ("LD b\nJMPC\nST q", "PLC0146", 6, 1, ["label"]),
    "cr type across label": ("LD x\nJMP L\nL: ADD 1\nST n\nLD b\nJMPC L", "PLC0147", 10, 1,
                             ["BOOL", "INT"]),
}


@pytest.mark.parametrize("name", sorted(DIAG_CASES))
def test_each_il_diagnostic(name):
    body, code, line, col, words = DIAG_CASES[name]
    errs = diags(body, DECLS)
    found = [d for d in errs if d.code == code]
    assert found, f"{code} not reported: {[str(d) for d in errs]}"
    d = found[0]
    assert (d.location.file, d.location.line, d.location.col) == ("d.il", line, col), str(d)
    for w in words:
        assert w in d.message, d.message
    assert len(errs) == 1, [str(e) for e in errs]  # no follow-up noise


def test_il_diagnostics_in_a_st_file_too():
    src = "PROGRAM P\nVAR a, b : BOOL; END_VAR\n    LD a\n    ANDD b\n    ST a\nEND_PROGRAM\n"
    _, ds = check_sources([(src, "x.st")])
    assert [d.code for d in ds if d.severity == "error"] == ["PLC0141"]
    with pytest.raises(PlcError):
        plclab.loads(src, "x.st")


def test_label_defined_twice():
    errs = diags("L: LD b\nST q\nL: LD b\nST q", DECLS)
    assert [e.code for e in errs] == ["PLC0101"]
