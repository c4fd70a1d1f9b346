"""The standard library's specification (plclab.lang.builtins) is the one place a standard
function or block is described: every key it names must exist where it points, and every other
list is derived from it."""

import re

import pytest

from plclab.compile.builtins_emit import EMITTERS
from plclab.compile.codegen import Codegen
from plclab.lang import ast as A
from plclab.lang.builtins import BLOCKS, BUILTINS, FB_INPUT_OPS, POWER_PINS
from plclab.lang.check.typing_rules import TYPING_RULES
from plclab.lang.frontends.st import parse_st_collect
from plclab.lang.library import STDLIB_FILES, stdlib_text
from plclab.runtime import natives
from plclab.runtime.rt import HELPERS


def _library() -> dict[str, tuple[str, A.Pou]]:
    out = {}
    for name in STDLIB_FILES:
        f, diags = parse_st_collect(stdlib_text(name), f"<plclab>/{name}", library=True)
        assert not diags
        out.update({p.name: (name, p) for p in f.pous})
    return out


LIBRARY = _library()


@pytest.mark.parametrize("name", sorted(BUILTINS))
def test_each_function_names_a_rule_an_emitter_and_helpers_that_exist(name):
    b = BUILTINS[name]
    assert b.typing in TYPING_RULES
    if b.statement_only:
        assert b.emit == "test" and name in _source(Codegen.test_builtin)
    else:
        assert b.emit in EMITTERS
    for helper in b.natives:
        assert helper in HELPERS, f"{name}: no run-time helper {helper}"
    if b.typing == "signature":
        assert len(b.args) == len(b.params) and b.needs and b.result
    assert len(b.params) >= b.min_args or b.variadic


def test_every_rule_and_emitter_is_used():
    assert {b.typing for b in BUILTINS.values()} == set(TYPING_RULES)
    assert {b.emit for b in BUILTINS.values()} - {"test"} == set(EMITTERS)


@pytest.mark.parametrize("name", sorted(BLOCKS))
def test_each_block_is_declared_in_its_library_with_its_native_body(name):
    spec = BLOCKS[name]
    assert name in LIBRARY, f"{name} is not declared in a library file"
    file, pou = LIBRARY[name]
    assert file == spec.library and pou.kind == "FUNCTION_BLOCK" and pou.native == name
    assert natives.resolve(name).__name__ == name
    sections = {d.name: (d.section, getattr(d.type, "name", "")) for d in pou.decls}
    if spec.power:
        pin_in, pin_out = spec.power
        assert sections[pin_in] == ("VAR_INPUT", "BOOL")
        assert sections[pin_out] == ("VAR_OUTPUT", "BOOL")
    for op in spec.il_inputs:
        assert sections[op][0] == "VAR_INPUT", f"{name}.{op} is not an input"


def test_the_derived_lists():
    # SFC_TIMER: the step timer of sfclib.st, loaded only with a chart (ADR 0016), not a block
    # a program can declare
    assert set(natives.names()) == set(BLOCKS) | set(natives.SFC_BLOCKS)
    assert not set(natives.SFC_BLOCKS) & set(BLOCKS)
    assert {p.name for p in (pou for _, pou in LIBRARY.values()) if p.native} == set(BLOCKS)
    assert POWER_PINS["TON"] == ("IN", "Q") and POWER_PINS["CTUD"] == ("CU", "QU")
    # IEC 61131-3 Table 53: the IL input operators of the standard blocks (S, R and LD also name
    # IL operators: SR is S1,R; RS S,R1; CTD CD,LD,PV; CTUD CU,CD,R,LD,PV)
    assert set(FB_INPUT_OPS) == {"S1", "R1", "S", "R", "LD", "CLK", "CU", "CD", "PV", "IN", "PT"}
    assert BLOCKS["SR"].il_inputs == ("S1", "R") and BLOCKS["RS"].il_inputs == ("S", "R1")


def test_no_other_module_keeps_its_own_list_of_standard_names():
    import plclab.compile.codegen as cg
    import plclab.compile.codegen_expr as cg_expr
    import plclab.compile.codegen_stmt as cg_stmt
    import plclab.lang.check.calls as calls
    import plclab.lang.lower.il as il
    import plclab.lang.lower.types as lt

    for mod in (cg, cg_expr, cg_stmt, calls, il, lt, natives):
        src = _source(mod)
        assert not re.search(r'\("SQRT", "LN"|"SHL", "SHR", "ROL"|\("TON", "TOF"|'
                             r'"S1", "R1", "CLK"|"ASIN", "ACOS"', src), mod.__name__


def _source(obj) -> str:
    import inspect

    return inspect.getsource(obj)
