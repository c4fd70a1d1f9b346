"""Front ends behind one registry, pending bodies as data, one lowering stage (ADR 0011)."""

from __future__ import annotations

import ast
import copy
import pickle
from pathlib import Path

import pytest

import plclab
from plclab.errors import PlcError
from plclab.lang import ast as A
from plclab.lang.frontends import BODY_KINDS, FRONT_ENDS, for_file, suffixes
from plclab.lang.frontends import st as st_front
from plclab.lang.lower import LOWERINGS, lower_pending
from plclab.lang.lower.types import DeclarationTypes, LoweringTypes
from plclab.lang.parsing import ParseAbort
from plclab.project import check_sources

LANG = Path(plclab.__file__).parent / "lang"
IL_POU = "PROGRAM P VAR a, b : BOOL; END_VAR\n  LD a\n  ST b\nEND_PROGRAM\n"
LD_POU = "PROGRAM P VAR a, b : BOOL; END_VAR\n|  a    b  |\n|--[ ]--( )|\nEND_PROGRAM\n"
XML_POU = """<project xmlns="http://www.plcopen.org/xml/tc6_0201"><types><pous>
<pou name="P" pouType="program"><interface><localVars>
<variable name="a"><type><BOOL/></type></variable><variable name="b"><type><BOOL/></type>
</variable></localVars></interface><body><{tag}>{body}</{tag}></body></pou></pous></types>
</project>"""
XML_LD = ('<leftPowerRail localId="1"/><contact localId="2"><connectionPointIn><connection '
          'refLocalId="1"/></connectionPointIn><variable>a</variable></contact><coil localId="3">'
          '<connectionPointIn><connection refLocalId="2"/></connectionPointIn><variable>b'
          '</variable></coil>')
SOURCES = {  # file name -> (text, pending kind of POU P)
    "p.st": (IL_POU, "IL"), "p.il": (IL_POU, "IL"), "p.ld": (LD_POU, "NETWORK"),
    "il.xml": (XML_POU.format(tag="IL", body="LD a\nST b"), "IL"),
    "ld.xml": (XML_POU.format(tag="LD", body=XML_LD), "NETWORK"),
}


@pytest.mark.parametrize("name,expected", [("a.st", "ST"), ("A.ST", "ST"), ("a.txt", "ST"),
                                           ("a", "ST"), ("a.iecst", "ST"), ("a.il", "IL"),
                                           ("a.ld", "LD"), ("a.xml", "PLCopen")])
def test_the_registry_chooses_by_suffix(name, expected):
    assert for_file(name).name == expected


def test_an_unknown_suffix_lists_the_registry_suffixes():
    with pytest.raises(PlcError) as e:
        check_sources([("x", "prog.py")])
    assert e.value.code == "PLC3003"
    assert e.value.message == ("prog.py: unknown source type '.py'; plclab reads .st, .il, .ld "
                               "and PLCopen .xml files")
    assert set(suffixes()) == {s for fe in FRONT_ENDS for s in fe.suffixes} - {""}


@pytest.mark.parametrize("filename", SOURCES)
def test_parsing_leaves_pending_bodies_as_data_and_lowering_consumes_them(filename):
    text, kind = SOURCES[filename]
    f, diags = for_file(filename).parse(text, filename)
    assert diags == []
    (pou,) = f.pous
    assert pou.body == [] and [b.kind for b in pou.pending] == [kind]
    assert isinstance(pou.pending[0], A.PendingBody) and pou.pending[0].payload
    assert kind in LOWERINGS
    pickle.loads(pickle.dumps(f))  # plain data: no closures on the tree
    lowered = copy.deepcopy(f)
    assert lower_pending([lowered], st_front.library_declarations()) == []
    (pou,) = lowered.pous
    assert pou.pending == []
    assert [type(s).__name__ for s in pou.body] == ["Assign"]


def test_every_body_kind_names_a_front_end_and_a_lowering():
    names = {fe.name for fe in FRONT_ENDS}
    for b in BODY_KINDS.values():
        assert b.front_end in names
        assert b.pending is None or b.pending in LOWERINGS


def test_lowering_runs_after_every_file_is_parsed():
    """The IL in a.il learns the type of c.n from a FUNCTION_BLOCK declared in a later file."""
    il = "PROGRAM P VAR c : Counter; q : BOOL; END_VAR\n  LD c.n\n  ST q\nEND_PROGRAM\n"
    fb = "FUNCTION_BLOCK Counter VAR_OUTPUT n : INT; END_VAR n := n + 1; END_FUNCTION_BLOCK\n"
    project, diags = check_sources([(il, "a.il"), (fb, "b.st")])
    assert project is None
    assert [(d.code, d.location.file, d.location.line) for d in diags] == [
        ("PLC0140", "a.il", 3)]
    assert "c.n" in diags[0].message and "INT" in diags[0].message


def test_the_lowering_asks_only_the_lowering_types_interface():
    """lower/il.py and lower/network.py call nothing but LoweringTypes methods on ``types``, so
    that the checker's symbol table can replace DeclarationTypes behind the interface."""
    allowed = {n for n in vars(LoweringTypes) if not n.startswith("_")}
    assert allowed <= set(dir(DeclarationTypes))
    for name in ("il.py", "network.py"):
        tree = ast.parse((LANG / "lower" / name).read_text(encoding="utf-8"))
        used = {n.attr for n in ast.walk(tree) if isinstance(n, ast.Attribute)
                and isinstance(n.value, ast.Attribute) and n.value.attr == "types"}
        assert used and used <= allowed, (name, used - allowed)


def test_no_private_name_is_imported_across_modules_of_plclab_lang():
    bad = []
    for path in LANG.rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ImportFrom):
                bad += [f"{path.relative_to(LANG)}: {a.name}" for a in node.names
                        if a.name.startswith("_") and a.name != "__future__"]
    assert bad == []


def test_a_sub_parser_over_tokens_reports_into_the_host_diagnostics():
    host = st_front.Parser("x + ", "h.st")
    sub = st_front.Parser.over_tokens(host.toks[:1], "h.st", host.diagnostics)
    assert isinstance(sub.expr(), A.Name) and sub.at("EOF")
    sub = st_front.Parser.over_tokens(host.toks[:-1], "h.st", host.diagnostics)
    with pytest.raises(ParseAbort):
        sub.expr()
    assert [(d.code, d.location.line) for d in host.diagnostics] == [("PLC0010", 1)]
