"""Each LSP feature on each language (ST, IL, text LD, PLCopen XML), through the real server.

The documents are in ``docs/``; every expectation below is read off the document's text (the
line of a declaration, the names it declares), not copied from a run.
"""

from __future__ import annotations

import asyncio
import re

import pytest
from lsprotocol import types as T

pytestmark = [pytest.mark.asyncio, pytest.mark.slow]  # a server process per test

# per document: a use of a variable (needle, offset of the name in it), its declaration's
# line (a needle), its type; an edit that misspells a name; a member access (the text up to
# and including the dot) with members that must and must not be offered; the outline's names
CASES = {
    "demo.st": dict(use=("level < rec", 0), decl="level : REAL;", type="REAL",
                    typo=("SQRT(level)", "SQRT(levle)"), block=("t : TON", 4),
                    member=("t.", ["Q", "ET", "IN", "PT"], ["open_cmd"]),
                    outline=["Mode", "Recipe", "Valve", "Pump", "Main",
                             "the inlet opens after two seconds"], tests=2),
    "demo.il": dict(use=("IN := low", 6), decl="low : BOOL;", type="BOOL",
                    typo=("ST pump", "ST pmup"), block=("delay : TON", 8),
                    member=("delay.", ["Q", "ET", "IN", "PT"], ["low"]),
                    outline=["Tank", "the pump starts a second after low"], tests=1),
    "demo.ld": dict(use=("|   start", 4), decl="start : BOOL;", type="BOOL",
                    typo=("alarm   |", "alarn   |"), block=("T1 : TON", 5),
                    member=("T1.", ["Q", "ET", "IN", "PT"], ["motor"]),
                    outline=["Seal", "start seals in"], tests=1),
    "demo.xml": dict(use=("IN := temp", 6), decl='name="temp"', type="REAL",
                     typo=("temp < 200.0", "tmpp < 200.0"), block=('derived name="TON"', 14),
                     member=("hold.", ["Q", "ET", "IN", "PT"], ["heat"]),
                     outline=["Oven", "Config0"], tests=0),
}
NAMES = list(CASES)
DOCS_URL = "https://plclab.example.org/site/"  # as conftest.py initialises the server


@pytest.mark.parametrize("name", NAMES)
async def test_diagnostics_carry_code_link_and_location(client, open_doc, name):
    case = CASES[name]
    doc, diags = await open_doc(name)
    assert not [d for d in diags if d.severity == T.DiagnosticSeverity.Error]
    old, new = case["typo"]
    diags = await doc.replace(old, new)
    errors = [d for d in diags if d.severity == T.DiagnosticSeverity.Error]
    assert [d.code for d in errors] == ["PLC0100"], diags
    d = errors[0]
    bad = (set(re.findall(r"\w+", new)) - set(re.findall(r"\w+", old))).pop()
    line = doc.line_of(new)
    text = doc.text.splitlines()[line]
    assert d.range.start.line == line
    assert text[d.range.start.character:d.range.end.character] == bad
    assert "did you mean" in d.message
    assert d.code_description.href == f"{DOCS_URL}problems/PLC0100/"
    assert d.source == "plclab"
    # the fix, sent as an incremental edit, clears the error
    diags = await doc.replace(new, old)
    assert not [d for d in diags if d.severity == T.DiagnosticSeverity.Error]


@pytest.mark.parametrize("name", NAMES)
async def test_hover_shows_declaration_and_library_signature(client, open_doc, name):
    case = CASES[name]
    doc, _ = await open_doc(name)
    needle, offset = case["use"]
    h = await client.text_document_hover_async(T.HoverParams(doc.ident(),
                                                             doc.pos(needle, offset)))
    assert h is not None
    decl_line = doc.line_of(case["decl"]) + 1
    assert case["type"] in h.contents.value
    assert f"declared on line {decl_line}" in h.contents.value
    needle, offset = case["block"]
    h = await client.text_document_hover_async(T.HoverParams(doc.ident(),
                                                             doc.pos(needle, offset)))
    assert h is not None
    assert "TON(IN : BOOL, PT : TIME) => (Q : BOOL, ET : TIME)" in h.contents.value
    assert "On-delay" in h.contents.value


async def test_hover_on_a_standard_function_and_on_nothing(client, open_doc):
    doc, _ = await open_doc("demo.st")
    h = await client.text_document_hover_async(T.HoverParams(doc.ident(), doc.pos("SQRT", 1)))
    assert "SQRT(IN)" in h.contents.value and "square root" in h.contents.value
    blank = T.Position(doc.line_of("END_TYPE") + 1, 0)  # the empty line after the TYPE
    assert await client.text_document_hover_async(T.HoverParams(doc.ident(), blank)) is None


@pytest.mark.parametrize("name", NAMES)
async def test_definition_goes_to_the_declaration(client, open_doc, name):
    case = CASES[name]
    doc, _ = await open_doc(name)
    needle, offset = case["use"]
    loc = await client.text_document_definition_async(T.DefinitionParams(
        doc.ident(), doc.pos(needle, offset)))
    if isinstance(loc, list):
        loc = loc[0]
    assert loc.uri == doc.uri
    line = doc.line_of(case["decl"])
    assert loc.range.start.line == line
    var = doc.text.splitlines()[line][loc.range.start.character:loc.range.end.character]
    assert var.lower() == needle[offset:].split()[0].split("(")[0].lower().strip("|")


async def test_definition_of_a_member_and_a_type(client, open_doc):
    doc, _ = await open_doc("demo.st")
    loc = await client.text_document_definition_async(T.DefinitionParams(
        doc.ident(), doc.pos("rec.volume", 4)))
    assert loc.range.start.line == doc.line_of("volume : REAL")
    loc = await client.text_document_definition_async(T.DefinitionParams(
        doc.ident(), doc.pos("inlet : Valve", 8)))
    assert loc.range.start.line == doc.line_of("FUNCTION_BLOCK Valve")
    loc = await client.text_document_definition_async(T.DefinitionParams(
        doc.ident(), doc.pos("pump.Start", 5)))
    assert loc.range.start.line == doc.line_of("METHOD Start")


def _flatten(symbols, depth=0):
    for s in symbols:
        yield s, depth
        yield from _flatten(s.children or [], depth + 1)


@pytest.mark.parametrize("name", NAMES)
async def test_document_symbols_outline(client, open_doc, name):
    case = CASES[name]
    doc, _ = await open_doc(name)
    symbols = await client.text_document_document_symbol_async(T.DocumentSymbolParams(
        doc.ident()))
    top = [s.name for s in symbols]
    for expected in case["outline"]:
        assert expected in top
    flat = {s.name: s for s, _ in _flatten(symbols)}
    decl_var = case["decl"].split()[0].strip('name="') if name != "demo.xml" else "temp"
    assert decl_var in flat and flat[decl_var].kind == T.SymbolKind.Variable
    assert flat[decl_var].selection_range.start.line == doc.line_of(case["decl"])
    assert not any(n.startswith("__") for n in flat)  # the lowering's hidden names
    for s, _ in _flatten(symbols):  # a symbol's name lies inside its range
        assert s.range.start.line <= s.selection_range.start.line <= s.range.end.line


async def test_symbols_of_methods_steps_types(client, open_doc):
    doc, _ = await open_doc("demo.st")
    symbols = await client.text_document_document_symbol_async(T.DocumentSymbolParams(
        doc.ident()))
    by = {s.name: s for s in symbols}
    assert [c.name for c in by["Pump"].children] == ["running", "Start"]
    assert by["Pump"].children[1].kind == T.SymbolKind.Method
    assert [c.name for c in by["Pump"].children[1].children] == ["speed"]
    assert [c.name for c in by["Recipe"].children] == ["volume", "mode"]
    assert [c.name for c in by["Mode"].children] == ["Idle", "Filling", "Draining"]
    chart, _ = await open_doc("chart.st")
    symbols = await client.text_document_document_symbol_async(T.DocumentSymbolParams(
        chart.ident()))
    kids = {c.name: c for c in symbols[0].children}
    assert kids["Wait"].kind == T.SymbolKind.Event and kids["Fill"].kind == T.SymbolKind.Event
    assert kids["Fill"].selection_range.start.line == chart.line_of("STEP Fill")
    assert sum(c.kind == T.SymbolKind.Operator for c in kids.values()) == 2  # transitions


async def _complete(client, doc, pos):
    res = await client.text_document_completion_async(T.CompletionParams(doc.ident(), pos))
    return {i.label: i for i in (res.items if hasattr(res, "items") else res)}


@pytest.mark.parametrize("name", NAMES)
async def test_completion_of_members_and_names(client, open_doc, name):
    case = CASES[name]
    doc, _ = await open_doc(name)
    needle, want, not_want = case["member"]
    items = await _complete(client, doc, doc.pos(needle, len(needle)))
    for m in want:
        assert m in items
    for m in not_want:
        assert m not in items
    assert items["Q"].kind == T.CompletionItemKind.Variable
    # names in scope, standard blocks and functions, keywords, where a statement starts
    needle, offset = case["use"]
    items = await _complete(client, doc, doc.pos(needle, offset))
    var = needle[offset:].split()[0].strip("|")
    assert var in items and case["type"] in items[var].detail
    assert "TON" in items and items["TON"].kind == T.CompletionItemKind.Class
    assert "LIMIT" in items and items["LIMIT"].kind == T.CompletionItemKind.Function
    assert "IF" in items and items["IF"].kind == T.CompletionItemKind.Keyword


async def test_completion_of_struct_fields_methods_inputs_and_step_flags(client, open_doc):
    doc, _ = await open_doc("demo.st")
    items = await _complete(client, doc, doc.pos("rec.volume", 4))
    assert set(items) == {"volume", "mode"}
    items = await _complete(client, doc, doc.pos("pump.Start", 5))
    assert items["Start"].kind == T.CompletionItemKind.Method and "running" in items
    items = await _complete(client, doc, doc.pos("Main.inlet.is_open", 11))
    assert set(items) == {"open_cmd", "is_open", "travel"}  # not the block's own t
    items = await _complete(client, doc, doc.pos("Main.rec.volume", 5))
    assert {"inlet", "pump", "rec", "level", "ok"} <= set(items)  # a program's variables
    chart, _ = await open_doc("chart.st")
    items = await _complete(client, chart, chart.pos("Fill.T", 5))
    assert set(items) == {"X", "T"}
    assert "TIME" in items["T"].detail


async def test_last_good_parse_serves_while_a_line_is_half_typed(client, open_doc):
    doc, _ = await open_doc("demo.st")
    diags = await doc.replace("rec.mode := Mode#Filling;", "rec.mode := Mode#Filling;\nok := inlet.")
    assert any(d.severity == T.DiagnosticSeverity.Error for d in diags)
    line = doc.line_of("ok := inlet.")
    items = await _complete(client, doc, T.Position(line, len("ok := inlet.")))
    assert {"open_cmd", "is_open", "travel"} <= set(items)
    h = await client.text_document_hover_async(T.HoverParams(doc.ident(),
                                                             doc.pos("level < rec", 0)))
    assert "REAL" in h.contents.value
    symbols = await client.text_document_document_symbol_async(T.DocumentSymbolParams(
        doc.ident()))
    assert "Main" in [s.name for s in symbols]


async def test_an_unchanged_text_is_not_checked_again(client, open_doc):
    doc, _ = await open_doc("demo.st")
    await doc.replace("T#2s", "T#3s")
    await doc.replace("T#3s", "T#2s")  # undo: the text of the first version again
    await client.text_document_hover_async(T.HoverParams(doc.ident(), doc.pos("level", 0)))
    stats = await client.workspace_execute_command_async(T.ExecuteCommandParams(
        command="plclab.stats"))
    assert stats["checks"] == 2  # the opened text and the edit; neither undo nor hover


@pytest.mark.parametrize("name", NAMES)
async def test_code_lens_runs_each_test(client, open_doc, name):
    case = CASES[name]
    doc, _ = await open_doc(name)
    lenses = await client.text_document_code_lens_async(T.CodeLensParams(doc.ident()))
    assert len(lenses) == case["tests"]
    for lens in lenses:
        assert lens.command.command == "plclab.runTest"
        uri, title = lens.command.arguments
        assert uri == doc.uri and lens.range.start.line == doc.line_of(f"TEST '{title}'")
    if not lenses:
        return
    uri, title = lenses[0].command.arguments
    result = await client.workspace_execute_command_async(T.ExecuteCommandParams(
        command="plclab.runTest", arguments=[uri, title]))
    assert result["passed"] is True and result["title"] == title
    assert client.lens_refreshes  # the editor was asked to redraw the lenses
    lenses = await client.text_document_code_lens_async(T.CodeLensParams(doc.ident()))
    assert "passed" in lenses[0].command.title
    assert "last run" not in lenses[-1].command.title or len(lenses) == 1


async def test_a_failing_test_is_published(client, open_doc):
    doc, _ = await open_doc("demo.st")
    waiter = asyncio.ensure_future(doc.diagnostics())
    await asyncio.sleep(0)
    result = await client.workspace_execute_command_async(T.ExecuteCommandParams(
        command="plclab.runTest", arguments=[doc.uri, "a test that fails"]))
    assert result["passed"] is False and "42.0" in result["message"]
    assert result["line"] == doc.line_of("ASSERT_EQ(Main.level, 42.0)") + 1
    diags = await waiter
    failed = [d for d in diags if "a test that fails" in d.message]
    assert failed and failed[0].range.start.line == doc.line_of("ASSERT_EQ(Main.level")
    assert any("FAILED" in m.message for m in client.messages)
    h = await client.text_document_hover_async(T.HoverParams(
        doc.ident(), doc.pos("TEST 'a test that fails'", 2)))
    assert "FAILED" in h.contents.value
    result = await client.workspace_execute_command_async(T.ExecuteCommandParams(
        command="plclab.runTest", arguments=[doc.uri, "no such test"]))
    assert result["passed"] is False and "no TEST" in result["message"]
    result = await client.workspace_execute_command_async(T.ExecuteCommandParams(
        command="plclab.runTest", arguments=[doc.uri]))
    assert "error" in result
