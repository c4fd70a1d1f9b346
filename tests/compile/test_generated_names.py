"""Generated names live in a namespace no ST identifier can enter (issue 30, ADR 0039): a
method is ``m_NAME`` (a variable is always upper case), interfaces ``_itf``, hidden variables
of the lowerings contain ``__`` (never in an ST name). Valid programs whose names look like the
generated ones compile and scan; any PlcError they give is a user error, never PLC9999/PLC9990."""

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import plclab
from plclab.errors import PlcError
from plclab.runtime.plc import Plc

INTERNAL = ("PLC9999", "PLC9990")

CASES = {
    "variable M_GO beside METHOD GO": ("""
FUNCTION_BLOCK FB
VAR_OUTPUT M_GO : INT; END_VAR
METHOD GO
M_GO := M_GO + 1;
END_METHOD
END_FUNCTION_BLOCK
PROGRAM Main VAR f : FB; n : INT; END_VAR f.GO(); f.GO(); n := f.M_GO; END_PROGRAM""",
                                        "Main.n", 2),
    "variable _ITF in a block with IMPLEMENTS": ("""
INTERFACE I
METHOD M : BOOL
END_METHOD
END_INTERFACE
FUNCTION_BLOCK FB IMPLEMENTS I
VAR _ITF : INT := 5; END_VAR
METHOD M : BOOL
M := _ITF = 5;
END_METHOD
END_FUNCTION_BLOCK
PROGRAM Main VAR f : FB; b : BOOL; i : I; END_VAR i := f; b := i.M(); END_PROGRAM""",
                                                 "Main.b", True),
    "base method X, derived variable M_X": ("""
FUNCTION_BLOCK A
METHOD X : INT
X := 1;
END_METHOD
END_FUNCTION_BLOCK
FUNCTION_BLOCK B EXTENDS A
VAR_OUTPUT M_X : INT; END_VAR
M_X := 2;
END_FUNCTION_BLOCK
PROGRAM Main VAR f : B; i : INT; END_VAR f(); i := f.X() + f.M_X; END_PROGRAM""",
                                            "Main.i", 3),
    "a PROGRAM action named FB_init": ("""
PROGRAM Main VAR n : INT; END_VAR
FB_init();
END_PROGRAM
ACTION Main.FB_init
n := n + 1;
END_ACTION""", "Main.n", 1),
    "an initial value naming a later variable": ("""
FUNCTION F : INT
VAR a : INT := b; b : INT := 7; END_VAR
F := a + b;
END_FUNCTION
PROGRAM Main VAR a : INT := b; b : INT := 7; x : INT; END_VAR x := F() + a; END_PROGRAM""",
                                                  "Main.x", 7),
    "edge inputs X and M_X": ("""
FUNCTION_BLOCK FB
VAR_INPUT X : BOOL R_EDGE; M_X : BOOL R_EDGE; END_VAR
VAR_OUTPUT q : BOOL; END_VAR
q := X AND M_X;
END_FUNCTION_BLOCK
PROGRAM Main VAR f : FB; q : BOOL; END_VAR f(X := TRUE, M_X := TRUE); q := f.q; END_PROGRAM""",
                              "Main.q", True),
}


@pytest.mark.parametrize("name", CASES)
def test_names_that_look_generated_compile_and_run(name):
    src, var, want = CASES[name]
    plc = Plc(plclab.compile_sources([(src, "p.st")]))
    plc.scan()
    assert plc[var] == want


# names a student may write that resemble what the generator makes
POOL = ["X", "M_X", "M_M_X", "GO", "M_GO", "_ITF", "ITF", "_BODY", "BODY", "_COPY", "COPY",
        "FB_INIT", "FB_EXIT", "SELF", "V_X", "F_X", "P_X", "P_FB", "EDGE_X", "EDGE_M_X",
        "EDGE_MEM", "CR_INT", "LD_M3", "SFC_TR0", "THIS_X", "_G", "_B", "_X_", "Q"]


@settings(max_examples=80, deadline=None, database=None)
@given(st.lists(st.sampled_from(POOL), min_size=1, max_size=5, unique=True),
       st.lists(st.sampled_from(POOL), min_size=0, max_size=3, unique=True),
       st.lists(st.sampled_from(POOL), min_size=0, max_size=3, unique=True))
def test_colliding_names_never_give_an_internal_error(variables, methods, edges):
    methods = [m for m in methods if m not in variables]
    edges = [e for e in edges if e not in variables and e not in methods]
    decls = "".join(f"{v} : INT; " for v in variables)
    inputs = "".join(f"{e} : BOOL R_EDGE; " for e in edges)
    meths = "".join(f"METHOD {m} : INT\n{m} := {variables[0]} + 1;\nEND_METHOD\n"
                    for m in methods)
    uses = "".join(f"n := f.{m}();\n" for m in methods)
    src = (f"FUNCTION_BLOCK FB\nVAR_INPUT {inputs}END_VAR\nVAR {decls}END_VAR\n"
           f"{variables[0]} := {variables[0]} + 1;\n{meths}END_FUNCTION_BLOCK\n"
           f"PROGRAM Main\nVAR f : FB; n : INT; END_VAR\nf();\n{uses}END_PROGRAM\n")
    try:
        plc = Plc(plclab.compile_sources([(src, "p.st")]))
        plc.scan(2)
    except PlcError as e:
        assert e.code not in INTERNAL, f"{e}\n{src}"


POU_POOL = ["P_FB", "F_X", "M_X", "FB_INIT", "_BODY", "V_X", "SELF", "G_X", "_ITF", "ITF",
            "BASE", "DER", "CR_INT", "SFC_TR0", "_X_", "EDGE_M_X", "MAIN_"]
names = st.lists(st.sampled_from(POOL), min_size=1, max_size=4, unique=True)


@settings(max_examples=60, deadline=None, database=None)
@given(st.lists(st.sampled_from(POU_POOL), min_size=4, max_size=4, unique=True),
       names, names, names, names, names, names, st.sampled_from(POOL),
       st.sampled_from(POOL), st.booleans())
def test_colliding_names_across_every_construct(pous, base_vars, base_methods, der_vars,
                                                der_methods, actions, locals_, glob, prop,
                                                edge):
    """Names that look generated, in every place a name goes: block and function names,
    inherited and overriding methods, a PROPERTY (read bare and through THIS^), PROGRAM
    ACTIONs, an edge input, a global, FUNCTION locals whose initial values read later ones.
    A user error (a name declared twice, a method and a variable of one name) is fine;
    plclab's own failure (PLC9999, PLC9990) or a raw exception is not."""
    base, der, fn, itf = pous
    bv0, dv0 = base_vars[0], der_vars[0]
    bm = [m for m in base_methods if m not in base_vars and m != prop]
    dm = [m for m in der_methods if m not in der_vars and m not in base_vars and m != prop]
    acts = [a for a in actions if a not in ("N", "F", "B")]
    loc = [v for v in locals_ if v != "A"]
    inits = "".join(f"{v} : INT := {loc[(i + 1) % len(loc)]}; " for i, v in enumerate(loc))
    src = (
        f"VAR_GLOBAL {glob} : INT; END_VAR\n"
        f"INTERFACE {itf}\nMETHOD {bm[0] if bm else 'RUN'} : INT\nEND_METHOD\nEND_INTERFACE\n"
        f"FUNCTION_BLOCK {base} IMPLEMENTS {itf}\n"
        f"VAR_INPUT {'E : BOOL R_EDGE; ' if edge else ''}END_VAR\n"
        f"VAR {''.join(f'{v} : INT; ' for v in base_vars)}END_VAR\n"
        f"{bv0} := {bv0} + 1;\n"
        + "".join(f"METHOD {m} : INT\n{m} := {bv0} + {prop};\n{prop} := {prop} + 1;\n"
                  f"THIS^.{prop} := THIS^.{prop} + 1;\nEND_METHOD\n"
                  for m in (bm or ["RUN"]))
        + f"PROPERTY {prop} : INT\nGET\n{prop} := {bv0};\nEND_GET\nSET\n{bv0} := {prop};\n"
        f"END_SET\nEND_PROPERTY\nEND_FUNCTION_BLOCK\n"
        f"FUNCTION_BLOCK {der} EXTENDS {base}\n"
        f"VAR {''.join(f'{v} : INT; ' for v in der_vars)}END_VAR\n"
        f"{dv0} := {dv0} + {prop};\n"
        + "".join(f"METHOD {m} : INT\n{m} := {dv0} + 2;\nEND_METHOD\n" for m in dm)
        + "END_FUNCTION_BLOCK\n"
        f"FUNCTION {fn} : INT\nVAR_INPUT A : INT; END_VAR\nVAR {inits}END_VAR\n"
        f"{fn} := A{''.join(f' + {v}' for v in loc)};\nEND_FUNCTION\n"
        f"PROGRAM Main\nVAR B : {der}; N : INT; F : {itf}; END_VAR\n"
        f"B({'E := TRUE' if edge else ''});\nF := B;\nN := F.{bm[0] if bm else 'RUN'}();\n"
        f"N := {fn}(N) + B.{prop};\n{glob} := N;\n"
        + "".join(f"{a}();\n" for a in acts) + "END_PROGRAM\n"
        + "".join(f"ACTION Main.{a}\nN := N + 1;\nEND_ACTION\n" for a in acts))
    try:
        plc = Plc(plclab.compile_sources([(src, "p.st")]))
        plc.scan(2)
    except PlcError as e:
        assert e.code not in INTERNAL, f"{e}\n{src}"


def test_the_checks_catch_a_generated_name_a_user_can_reach(monkeypatch):
    """The tests can fail: with methods named as before issue 30 (``M_GO``, a name a student
    can write), the variable M_GO beside METHOD GO is an internal error again."""
    from plclab.compile import oop_emit
    monkeypatch.setattr(oop_emit, "method_name", lambda m: "M_" + oop_emit.ident(m.name))
    src, _var, _want = CASES["variable M_GO beside METHOD GO"]
    with pytest.raises(PlcError) as e:
        Plc(plclab.compile_sources([(src, "p.st")])).scan()
    assert e.value.code in INTERNAL
