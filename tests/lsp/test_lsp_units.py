"""The server's building blocks without a server: the standard library's descriptions, the
word under the cursor, the cache, the lazy imports and the message without pygls."""

from __future__ import annotations

import subprocess
import sys

import pytest

from plclab.lang.builtins import BLOCKS, BUILTINS
from plclab.lsp import features as F
from plclab.lsp import stdlib_docs
from plclab.lsp.documents import Workspace, analyze, filename_for


@pytest.mark.parametrize("name", sorted(BUILTINS))
def test_every_standard_function_has_signature_and_line(name):
    sig, doc = stdlib_docs.describe(name)
    assert sig.startswith(f"{name}(")
    assert doc and doc.endswith(".") and "\n" not in doc


@pytest.mark.parametrize("name", ["INT_TO_REAL", "REAL_TO_DINT", "TO_STRING", "TRUNC_INT",
                                  "BOOL_TO_WORD", "DWORD_TO_TIME"])
def test_conversions_are_described(name):
    sig, doc = stdlib_docs.describe(name)
    assert sig.endswith(f" : {name.rsplit('_', 1)[-1]}") and doc.startswith(("Converts", "IN"))


def test_unknown_names_are_not_described():
    assert stdlib_docs.describe("NOT_A_FUNCTION") is None
    assert stdlib_docs.describe("INT_TO_NOTHING") is None


def test_every_library_block_has_a_signature_and_line():
    # RTC: a block in the iec dialect of a program that names it (ADR 0037)
    a = analyze("PROGRAM P VAR r : RTC; END_VAR r(IN := TRUE); END_PROGRAM", "p.st", "iec")
    missing = []
    for name in BLOCKS:
        pou = a.index.pous.get(name)
        assert pou is not None, name
        assert stdlib_docs.pou_signature(pou).startswith(f"FUNCTION_BLOCK {name}(")
        doc = stdlib_docs.block_doc(pou)
        if not doc or len(doc) < 10:
            missing.append(name)
    assert not missing


def test_ton_signature_and_doc_come_from_the_library():
    a = analyze("PROGRAM P VAR t : TON; END_VAR t(IN := TRUE, PT := T#1s); END_PROGRAM", "p.st")
    pou = a.index.pous["TON"]
    assert stdlib_docs.pou_signature(pou) == \
        "FUNCTION_BLOCK TON(IN : BOOL, PT : TIME) => (Q : BOOL, ET : TIME)"
    assert stdlib_docs.block_doc(pou).startswith("On-delay")


@pytest.mark.parametrize("line, col, word, chain", [
    ("x := a.b.c;", 10, "c", ["a", "b"]),
    ("x := a.b.c;", 9, "b", ["a"]),  # the cursor right after b
    ("x := a[i + 1].b;", 15, "b", ["a"]),
    ("x := arr[2][3].f", 16, "f", ["arr"]),
    ("  motor := TRUE;", 3, "motor", []),
    ("  motor := TRUE;", 8, "motor", []),  # the cursor right after the name
    ("y := 12.5;", 7, None, None),  # a number is no name
])
def test_word_at(line, col, word, chain):
    w = F.word_at(line, 1, col)
    if word is None:
        assert w is None
    else:
        assert (w.text, w.chain) == (word, chain)


def test_word_before_the_cursor_after_a_dot():
    w = F.word_at("x := inlet.", 1, 12, before_only=True)
    assert (w.text, w.chain) == ("", ["inlet"])


def test_cache_checks_a_text_once_and_keeps_the_last_good_parse():
    ws = Workspace()
    good = "PROGRAM P VAR level : REAL; END_VAR level := 1.0; END_PROGRAM"
    ws.update("u", good, "p.st")
    ws.update("u", good, "p.st")
    assert ws.checks == 1
    bad = good.replace("level := 1.0;", "level := ;")
    a = ws.update("u", bad, "p.st")
    assert ws.checks == 2 and not a.syntax_ok
    assert any(d.severity == "error" for d in a.diagnostics)
    assert ws.for_features("u").text == good  # the declarations before the broken line
    ws.update("u", good, "p.st")
    assert ws.checks == 2  # back to a text seen before: from the cache
    ws.close("u")
    assert ws.for_features("u") is None


def test_filename_for_untitled_buffers():
    assert filename_for("/x/a.il", "iec-st") == "/x/a.il"
    assert filename_for("untitled:Untitled-1", "iec-il").endswith(".il")
    assert filename_for("untitled:Untitled-2", "whatever").endswith(".st")


def test_a_file_the_front_ends_cannot_read_gives_diagnostics_not_an_exception():
    a = analyze("PROGRAM P VAR x : BOOL END_VAR", "p.st")
    assert a.diagnostics and a.diagnostics[0].code.startswith("PLC")
    a = analyze("<project><unclosed>", "p.xml")
    assert a.diagnostics and all(d.code.startswith("PLC") for d in a.diagnostics)


def test_hover_on_an_undeclared_name_is_nothing():
    a = analyze("PROGRAM P VAR x : BOOL; END_VAR x := y; END_PROGRAM", "p.st")
    assert F.hover(a, 1, 38) is None
    assert "BOOL" in F.hover(a, 1, 33)


def test_plclab_and_the_lsp_features_do_not_import_pygls():
    code = ("import sys, plclab, plclab.cli, plclab.lsp.features, plclab.lsp.documents, "
            "plclab.lsp.commands; bad = [m for m in ('pygls', 'lsprotocol') if m in sys.modules];"
            " print(bad); sys.exit(1 if bad else 0)")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr


def test_without_pygls_the_command_says_what_to_install():
    code = ("import sys; sys.modules['pygls'] = None; from plclab.cli import main; "
            "sys.exit(main(['lsp']))")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert done.returncode == 1
    assert "PLC7001" in done.stderr and "plclab[lsp]" in done.stderr
    assert "Traceback" not in done.stderr


def test_hover_names_types_as_declared():
    text = ("FUNCTION_BLOCK Valve VAR_OUTPUT open_ : BOOL; END_VAR END_FUNCTION_BLOCK\n"
            "PROGRAM P VAR inlet : Valve; END_VAR inlet(); END_PROGRAM")
    a = analyze(text, "p.st")
    assert "VAR inlet : Valve" in F.hover(a, 2, 16)


def test_other_xml_files_are_left_alone():
    a = analyze('<?xml version="1.0"?><settings><x>1</x></settings>', "pom.xml")
    assert a.diagnostics == [] and a.index.top == []
    a = analyze('<?xml version="1.0"?><project xmlns="http://www.plcopen.org/xml/tc6_0201">'
                "<types><pous></pous></types>", "broken.xml")
    assert a.diagnostics  # a PLCopen file is checked (here: cut short)


def test_steps_and_enumeration_values_resolve_to_their_declarations():
    text = ("TYPE Mode : (Idle, Filling); END_TYPE\n"
            "PROGRAM P VAR m : Mode; go : BOOL; END_VAR\n"
            "INITIAL_STEP Wait: END_STEP\n"
            "STEP Fill: END_STEP\n"
            "TRANSITION FROM Wait TO Fill := go; END_TRANSITION\n"
            "TRANSITION FROM Fill TO Wait := Fill.T > T#1s; END_TRANSITION\n"
            "END_PROGRAM")
    a = analyze(text, "p.st")
    assert not [d for d in a.diagnostics if d.severity == "error"]
    loc = F.definition(a, 5, 18)  # Wait in FROM Wait
    assert (loc.line, loc.col) == (3, 14)
    assert "INITIAL_STEP Wait" in F.hover(a, 5, 18)
    assert "Mode#Filling" in F.hover(a, 1, 21)
    flags = [c.label for c in F.completions(a, text, 6, 38)]  # after "Fill."
    assert flags == ["X", "T"]
