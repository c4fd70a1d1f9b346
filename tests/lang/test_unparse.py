"""The AST -> ST printer: unparse(parse(x)) parses again to an equal AST (locations aside), for
the fuzzer's generated programs and for random expression trees over every operator."""

from __future__ import annotations

import random

import gen  # tests/fuzz, on the path through tests/conftest.py
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from plclab.lang import ast as A
from plclab.lang.dump import dump
from plclab.lang.frontends.st import parse_st, parse_st_collect
from plclab.lang.unparse import PRECEDENCE, duration, unparse
from plclab.project import check_sources

LOC = A.Location("t.st", 1, 1)
SETTINGS = settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def round_trip(text: str) -> tuple[str, str, str]:
    tree, diags = parse_st_collect(text, "a.st")
    assert not [d for d in diags if d.severity == "error"], [str(d) for d in diags][:3]
    printed = unparse(tree)
    again = parse_st(printed, "b.st")
    return dump(tree, locations=False), dump(again, locations=False), printed


@SETTINGS
@given(st.integers(0, 2**32 - 1))
def test_generated_programs_survive_the_round_trip(seed):
    text, _ = gen.gen_st(random.Random(seed))
    before, after, printed = round_trip(text)
    assert before == after, printed


# -- random expression trees -----------------------------------------------------------------

def _name(n: str) -> A.Name:
    return A.Name(LOC, n.upper(), n)


leaves = st.one_of(
    st.sampled_from(["a", "b", "c", "x"]).map(_name),
    st.integers(0, 99).map(lambda v: A.Literal(LOC, v, "INT", None, str(v))),
    st.integers(-99, -1).map(lambda v: A.Literal(LOC, v, "INT", None, str(v))),
    st.sampled_from([True, False]).map(lambda v: A.Literal(LOC, v, "BOOL", None, str(v).upper())),
)


def _extend(children):
    binary = st.builds(lambda op, left, right: A.Binary(LOC, op, left, right),
                       st.sampled_from(sorted(PRECEDENCE)), children, children)
    unary = st.builds(lambda op, e: A.Unary(LOC, op, e), st.sampled_from(["-", "NOT"]), children)
    call = st.builds(lambda args: A.Call(LOC, _name("LIMIT"), [A.Arg(LOC, None, v) for v in args]),
                     st.lists(children, min_size=1, max_size=3))
    index = st.builds(lambda e: A.Index(LOC, _name("arr"), [e]), children)
    return st.one_of(binary, unary, call, index)


expressions = st.recursive(leaves, _extend, max_leaves=25)


@SETTINGS
@given(expressions)
def test_expressions_keep_their_shape(e):
    body = [A.Assign(LOC, _name("x"), e)]
    text = "PROGRAM P\n" + unparse(body) + "END_PROGRAM\n"
    tree = parse_st(text, "e.st")
    # the parser folds a minus into a literal (-(5) is the literal -5): compare with that
    assert dump(tree.pous[0].body, locations=False) == dump(_folded(body), locations=False), text


def _folded(body):
    """What the parser makes of ``body``: -(literal) becomes a negative literal."""
    def fold(e):
        if isinstance(e, A.Unary):
            inner = fold(e.operand)
            if e.op == "-" and isinstance(inner, A.Literal) and inner.kind == "INT":
                return A.Literal(LOC, -inner.value, "INT", None, "")
            return A.Unary(LOC, e.op, inner)
        if isinstance(e, A.Binary):
            return A.Binary(LOC, e.op, fold(e.left), fold(e.right))
        if isinstance(e, A.Call):
            return A.Call(LOC, e.func, [A.Arg(LOC, a.name, fold(a.value)) for a in e.args])
        if isinstance(e, A.Index):
            return A.Index(LOC, e.obj, [fold(i) for i in e.indices])
        return e
    return [A.Assign(LOC, s.target, fold(s.value)) for s in body]


def test_parentheses_only_where_needed():
    tree = parse_st("PROGRAM P VAR a, b, c : INT; END_VAR a := (a + b) * c - (a - (b - c)) "
                    "+ a * b; END_PROGRAM", "p.st")
    assert unparse(tree.pous[0].body) == "a := (a + b) * c - (a - (b - c)) + a * b;\n"


def test_literals_made_by_a_lowering_are_printed_from_their_values():
    lits = [A.Literal(LOC, 1_500_000_000, "TIME", "TIME"), A.Literal(LOC, "it's\n", "STRING"),
            A.Literal(LOC, 1e-5, "REAL"), A.Literal(LOC, ("COLOR", "RED"), "ENUM"),
            A.Literal(LOC, False, "BOOL"), A.Literal(LOC, 255, "INT", "BYTE")]
    from plclab.lang.unparse import expr

    assert [expr(x) for x in lits] == ["T#1s500ms", "'it$'s$N'", "1.0E-05", "COLOR#RED",
                                        "FALSE", "BYTE#255"]
    assert duration(-90_000_000_000) == "-1m30s" and duration(0) == "0s"


def test_long_chains_do_not_recurse():
    text = "PROGRAM P VAR x : DINT; END_VAR x := " + " + ".join(["x"] * 10_000) + ";\nEND_PROGRAM"
    _, diags = check_sources([(text, "long.st")])
    assert not [d for d in diags if d.severity == "error"]
    printed = unparse(parse_st(text, "long.st"))
    assert printed.count(" + ") == 9_999


def test_partial_access_survives_the_round_trip():
    text = ("PROGRAM P VAR d : DWORD; b : BYTE; x : BOOL; END_VAR\n"
            "b := d.%B1; d.%W1.%B0 := b; d.3 := TRUE; x := d.%X4; d.%D0 := 0; END_PROGRAM\n")
    before, after, printed = round_trip(text)
    assert before == after, printed
    assert "d.%W1.%B0 := b" in printed and "d.3 := TRUE" in printed and "x := d.4" in printed


def test_a_programs_var_access_survives_the_round_trip():
    text = ("PROGRAM P VAR x : INT; t : TON; END_VAR\nVAR_ACCESS ax : x : INT READ_WRITE; "
            "et : t.ET : TIME; END_VAR\nx := 1; END_PROGRAM\n")
    before, after, printed = round_trip(text)
    assert before == after, printed
    assert "et : t.ET : TIME READ_ONLY;" in printed
