"""Every AST node class is handled by the walker, by every checker pass that dispatches on node
classes, and by the code generator: a new node class breaks this test, not a student's
program. An unknown node is an internal error, never skipped."""

from __future__ import annotations

import dataclasses
import inspect

import pytest

from plclab.compile.codegen import Codegen
from plclab.errors import Location
from plclab.lang import ast as A
from plclab.lang.check import Checker
from plclab.lang.check.exprs import Expressions
from plclab.lang.check.stmts import Statements
from plclab.lang.frontends.st import parse_st
from plclab.lang.walk import CHILDREN, UnhandledNode, children, walk

# initial values only: the checker rejects them in expressions (PLC0103), the code generator
# emits them in Codegen.init_code, not through an e_<Class> method
DECLARATION_ONLY = {A.ArrayInit, A.StructInit}


def _node_classes(base: type) -> list[type]:
    return [c for _, c in inspect.getmembers(A, inspect.isclass)
            if c.__module__ == A.__name__ and issubclass(c, base) and c is not base]


STMTS = _node_classes(A.Stmt)
EXPRS = _node_classes(A.Expr)
ALL_NODES = [c for _, c in inspect.getmembers(A, inspect.isclass)
             if c.__module__ == A.__name__ and dataclasses.is_dataclass(c)
             and c not in (A.Stmt, A.Expr, A.TypeRef)]
LOC = Location("t.st", 1, 1)


def test_the_enumeration_finds_the_known_classes():
    assert {A.Assign, A.If, A.For, A.Jump, A.Label} <= set(STMTS)
    assert {A.Literal, A.Binary, A.Call, A.ArrayInit} <= set(EXPRS)
    assert {A.VarDecl, A.Pou, A.CaseBranch, A.Arg, A.StructTypeRef} <= set(ALL_NODES)


@pytest.mark.parametrize("cls", ALL_NODES, ids=lambda c: c.__name__)
def test_the_walker_knows_every_node_class(cls):
    assert cls in CHILDREN


@pytest.mark.parametrize("cls", STMTS, ids=lambda c: c.__name__)
def test_every_statement_class_is_checked_and_compiled(cls):
    assert Statements.handles(cls), f"Statements has no visit_{cls.__name__}"
    assert callable(getattr(Codegen, f"s_{cls.__name__}", None)), f"Codegen.s_{cls.__name__}"


@pytest.mark.parametrize("cls", EXPRS, ids=lambda c: c.__name__)
def test_every_expression_class_is_checked_and_compiled(cls):
    assert Expressions.handles(cls), f"Expressions has no visit_{cls.__name__}"
    if cls in DECLARATION_ONLY:
        assert cls.__name__ in inspect.getsource(Codegen.init_code)
    else:
        assert callable(getattr(Codegen, f"e_{cls.__name__}", None)), f"Codegen.e_{cls.__name__}"


# -- a node class nobody knows ------------------------------------------------------------------
@dataclasses.dataclass(eq=False)
class Mystery(A.Stmt):
    pass


@dataclasses.dataclass(eq=False)
class MysteryExpr(A.Expr):
    pass


def test_an_unknown_node_is_an_internal_error_everywhere():
    with pytest.raises(UnhandledNode, match="Mystery"):
        children(Mystery(LOC))
    with pytest.raises(UnhandledNode, match="MysteryExpr"):
        list(walk(A.Assign(LOC, A.Name(LOC, "X"), MysteryExpr(LOC))))


def test_the_checker_does_not_skip_an_unknown_statement():
    f = parse_st("PROGRAM P VAR x : INT; END_VAR x := 1; END_PROGRAM", "p.st")
    f.pous[0].body.append(Mystery(LOC))
    with pytest.raises(UnhandledNode, match="Mystery"):
        Checker([f]).run()


def test_the_checker_does_not_type_an_unknown_expression_as_any():
    f = parse_st("PROGRAM P VAR x : INT; END_VAR x := 1; END_PROGRAM", "p.st")
    f.pous[0].body[0].value = MysteryExpr(LOC)
    with pytest.raises(UnhandledNode, match="MysteryExpr"):
        Checker([f]).run()


def test_walk_visits_every_node_once_in_source_order():
    f = parse_st("PROGRAM P VAR x : INT; END_VAR\nIF x > 1 THEN x := x - 1; END_IF;\nEND_PROGRAM",
                 "p.st")
    kinds = [type(n).__name__ for n in walk(f)]
    assert kinds == ["SourceFile", "Pou", "VarDecl", "NamedTypeRef", "If", "Binary", "Name",
                     "Literal", "Assign", "Name", "Binary", "Name", "Literal"]
