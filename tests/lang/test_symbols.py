"""The symbol table API (before and after checking), and the checker's annotations: only the
fields that plclab.lang.ast declares."""

from __future__ import annotations

import dataclasses
import doctest
import pathlib
import re

import pytest

import plclab
from plclab.lang import ast as A
from plclab.lang import types as T
from plclab.lang.check import Checker, SymbolTable, VarSym, symbols
from plclab.lang.frontends.st import parse_st
from plclab.lang.walk import walk
from plclab.project import check_sources, parse_sources, read_sources

ROOT = pathlib.Path(__file__).resolve().parents[2]

SRC = """
TYPE Point : STRUCT x : INT; y : INT; END_STRUCT; END_TYPE
VAR_GLOBAL g AT %QW2 : INT; limit : INT := 5; END_VAR
FUNCTION_BLOCK Counter
VAR_INPUT up : BOOL; END_VAR
VAR_OUTPUT n : INT; END_VAR
VAR old : BOOL; END_VAR
IF up AND NOT old THEN n := n + 1; END_IF; old := up;
END_FUNCTION_BLOCK
FUNCTION Twice : INT VAR_INPUT v : INT; END_VAR Twice := 2 * v; END_FUNCTION
PROGRAM Main
VAR_EXTERNAL limit : INT; END_VAR
VAR b AT %IX0.1 : BOOL; w AT %MW4 : INT; c : Counter; p : Point; t AT %I* : BOOL; END_VAR
c(up := b); w := Twice(c.n); p.x := limit; g := w;
END_PROGRAM
"""


def _table() -> SymbolTable:
    return SymbolTable.collect([parse_st(SRC, "s.st")])


def test_the_table_answers_from_declarations_only():
    table = _table()  # nothing checked yet: no type is resolved
    main = table.pou("MAIN")
    assert main is not None and table.pou("NOPE") is None
    scope = table.scope(main)
    assert scope.lookup("B").decl.name == "B" and scope.lookup("B").storage == "self"
    ext = scope.lookup("LIMIT")  # VAR_EXTERNAL names the global itself
    assert ext.storage == "global" and ext.decl is table.globals["LIMIT"]
    assert scope.lookup("UNKNOWN") is None
    assert [p for _, p, _ in table.programs()] == [main]
    assert list(table.members(table.pou("COUNTER"))) == ["UP", "N", "OLD"]
    result = table.scope(table.pou("TWICE")).lookup("TWICE")
    assert result.decl.section == "RETURN" and table.pou("TWICE").return_decl is result.decl


def test_located_vars_name_instance_pou_and_declaration():
    table = _table()
    got = [(v.path, v.address, v.instance, v.pou and v.pou.name, v.wildcard)
           for v in table.located_vars()]
    assert got == [("g", "%QW2", None, None, False),
                   ("Main.b", "%IX0.1", "MAIN", "MAIN", False),
                   ("Main.w", "%MW4", "MAIN", "MAIN", False),
                   ("Main.t", "%I*", "MAIN", "MAIN", True)]
    assert table.located_vars()[1].decl is table.members(table.pou("MAIN"))["B"]


def test_members_of_types_and_the_base_chain_hook():
    project, diags = check_sources([(SRC, "s.st")])
    assert project is not None, diags
    table = project.symbols
    assert list(table.members(project.types["POINT"])) == ["X", "Y"]
    assert list(table.members(project.types["COUNTER"])) == ["UP", "N", "OLD"]
    assert table.bases(table.pou("COUNTER")) == []
    assert T.resolve(table.scope(table.pou("MAIN")).lookup("W").ty) is T.INT


def test_members_puts_inherited_members_first(monkeypatch):
    """What EXTENDS will do: a block's members are its base's, then its own."""
    table = _table()
    counter, twice = table.pou("COUNTER"), table.pou("TWICE")
    monkeypatch.setattr(SymbolTable, "bases",
                        lambda self, p: [twice] if p is counter else [])
    assert list(table.members(counter)) == ["V", "UP", "N", "OLD"]


def test_the_checked_project_carries_the_table():
    plc = plclab.loads(SRC, "s.st")
    table = plc.project.symbols
    assert table.programs() == plc.project.programs
    assert table.programs_declaring("W") == [("MAIN", table.pou("MAIN"))]
    assert plc.variables()[:2] == ["g", "limit"]
    plc.inputs[0] = 0b10
    plc.scan()
    assert plc.var("Main.c.n").get() == 1 and plc.var("g").get() == 2


def test_a_configuration_names_the_instances():
    src = SRC + """CONFIGURATION Cfg RESOURCE R ON PLC
      TASK Fast(INTERVAL := T#10ms, PRIORITY := 1);
      PROGRAM Left WITH Fast : Main; PROGRAM Right : Main;
    END_RESOURCE END_CONFIGURATION"""
    project, diags = check_sources([(src, "c.st")])
    assert project is not None, diags
    table = project.symbols
    assert [(i, t) for i, _, t in table.programs()] == [("LEFT", "FAST"), ("RIGHT", None)]
    paths = [v.path for v in table.located_vars() if v.decl.name == "B"]
    assert paths == ["LEFT.b", "RIGHT.b"]


def test_the_symbols_and_walk_examples_run():
    from plclab.lang import walk as walk_module

    for module in (symbols, walk_module):
        result = doctest.testmod(module)
        assert result.failed == 0 and result.attempted > 0


# -- annotations are declared fields ----------------------------------------------------------
def _programs() -> list[pathlib.Path]:
    return sorted(p for p in (ROOT / "labs").glob("*/solution/*") if p.suffix in (".st", ".il",
                                                                                  ".ld"))


@pytest.mark.parametrize("path", _programs(), ids=lambda p: f"{p.parent.parent.name}/{p.name}")
def test_checking_sets_no_undeclared_attribute(path):
    """What the checker adds to the nodes (the front ends are another matter) is declared:
    the nodes have ``__slots__`` (ADR 0034), so setting an undeclared attribute would raise."""
    files, diags = parse_sources(read_sources([path]))
    assert not diags, diags
    nodes = [n for f in files for n in walk(f)]
    assert not [type(n).__name__ for n in nodes if hasattr(n, "__dict__")]
    checker = Checker(files)
    checker.run()
    assert not [d for d in checker.diags if d.severity == "error"]
    for node in nodes:
        assert all(hasattr(node, fl.name) for fl in dataclasses.fields(node))
    assert any(isinstance(n, A.Name) and isinstance(n.sym, VarSym) for f in files
               for n in walk(f))


def test_no_pass_sets_attributes_by_name():
    sources = list((ROOT / "plclab/lang/check").glob("*.py")) + [
        *(ROOT / "plclab/compile").glob("codegen*.py")]
    for src in sources:
        text = src.read_text()
        assert not re.search(r"\bsetattr\(|attr-defined", text), src.name
