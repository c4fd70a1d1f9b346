"""The editor folders: valid JSON, a VS Code manifest that launches `plclab lsp`, TextMate
grammars whose patterns compile (Python's ``re`` reads the Oniguruma subset they use) and
highlight the words they are meant to."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

EDITORS = Path(__file__).resolve().parents[2] / "plclab" / "lsp" / "editors"
GRAMMARS = sorted((EDITORS / "vscode" / "syntaxes").glob("*.tmLanguage.json"))


def test_vscode_manifest_is_valid_and_consistent():
    pkg = json.loads((EDITORS / "vscode" / "package.json").read_text("utf-8"))
    assert pkg["main"] == "./extension.js" and (EDITORS / "vscode" / "extension.js").exists()
    assert "vscode-languageclient" in pkg["dependencies"]
    assert pkg["contributes"]["configuration"]["properties"]["plclab.command"]["default"][:2] \
        == ["plclab", "lsp"]
    languages = {lang["id"] for lang in pkg["contributes"]["languages"]}
    for g in pkg["contributes"]["grammars"]:
        assert g["language"] in languages
        assert (EDITORS / "vscode" / g["path"]).exists()
    json.loads((EDITORS / "vscode" / "language-configuration.json").read_text("utf-8"))
    js = (EDITORS / "vscode" / "extension.js").read_text("utf-8")
    assert 'require("vscode-languageclient/node")' in js and "activate" in js


def test_jupyterlab_spec_starts_the_server():
    spec = json.loads((EDITORS / "jupyterlab" / "jupyter_server_config.json").read_text("utf-8"))
    server = spec["LanguageServerManager"]["language_servers"]["plclab"]
    assert server["argv"][:2] == ["plclab", "lsp"] and server["version"] == 2
    assert "iec-st" in server["languages"]


def _patterns(node):
    if isinstance(node, dict):
        for key in ("match", "begin", "end"):
            if key in node:
                yield node[key]
        for v in node.values():
            yield from _patterns(v)
    elif isinstance(node, list):
        for v in node:
            yield from _patterns(v)


@pytest.mark.parametrize("path", GRAMMARS, ids=[p.name for p in GRAMMARS])
def test_grammar_patterns_compile_and_includes_resolve(path):
    g = json.loads(path.read_text("utf-8"))
    assert g["scopeName"].startswith("source.iec-")
    pats = list(_patterns(g))
    assert len(pats) > 15
    for p in pats:
        re.compile(p)
    repo = g["repository"]
    for inc in _includes(g):
        assert inc.startswith("#") and inc[1:] in repo, inc


def _includes(node):
    if isinstance(node, dict):
        if "include" in node:
            yield node["include"]
        for v in node.values():
            yield from _includes(v)
    elif isinstance(node, list):
        for v in node:
            yield from _includes(v)


def _scope_of(grammar: dict, word: str) -> str | None:
    """The scope the first top-level rule matching all of *word* gives (a tiny TextMate)."""
    repo = grammar["repository"]
    for inc in grammar["patterns"]:
        rule = repo[inc["include"][1:]]
        if "match" in rule:
            m = re.compile(rule["match"]).match(word)
            if m and m.end() == len(word):
                return rule.get("name") or rule["captures"]["1"]["name"]
        elif re.compile(rule["begin"]).match(word):
            return rule["name"]
    return None


@pytest.mark.parametrize("word, scope", [
    ("END_IF", "keyword.control.iec"), ("elsif", "keyword.control.iec"),
    ("FUNCTION_BLOCK", "storage.type.pou.iec"), ("VAR_INPUT", "storage.modifier.var.iec"),
    ("LREAL", "support.type.iec"), ("TON", "support.class.function-block.iec"),
    ("T#1s500ms", "constant.numeric.time.iec"), ("16#FF", "constant.numeric.typed.iec"),
    ("3.14", "constant.numeric.iec"), ("'it''s'", "string.quoted.single.iec"),
    ("(* note *)", "comment.block.iec"), ("%IX0.1", "variable.other.address.iec"),
    ("TRUE", "constant.language.boolean.iec"), ("motor_on", "variable.other.iec"),
    ("IF_x", "variable.other.iec"),  # a name that starts like a keyword is a name
])
def test_st_grammar_scopes(word, scope):
    g = json.loads((EDITORS / "vscode" / "syntaxes" / "iec-st.tmLanguage.json").read_text())
    assert _scope_of(g, word) == scope


def test_il_grammar_marks_operators_and_labels():
    g = json.loads((EDITORS / "vscode" / "syntaxes" / "iec-il.tmLanguage.json").read_text())
    rule = re.compile(g["repository"]["il-operator"]["match"])
    m = rule.match("Start: LDN stop")
    assert m and m.group(1) == "Start" and m.group(2) == "LDN"
    assert rule.match("    JMPC done").group(2) == "JMPC"
    assert rule.match("    LOAD x") is None  # not an operator
