"""The Pygments lexers for IEC 61131-3 text (plclab/viz/highlight.py): every code block the
course, the labs and the docs show lexes without an error token, and the words that matter
get the class a reader expects (a comment is a comment, ``ST`` in IL is an operator only
first on its line, ``INT`` is a type and not the IL operand ``IN``)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

pytest.importorskip("pygments")

from pygments.token import Comment, Error, Keyword, Name, Number, String  # noqa: E402

from plclab.viz.highlight import IecIlLexer, IecLdLexer, IecStLexer, fence_map  # noqa: E402

REPO = Path(__file__).resolve().parents[2]
LEXERS = {"st": IecStLexer, "iecst": IecStLexer, "il": IecIlLexer, "ld": IecLdLexer}
FENCE = re.compile(r"^```(st|iecst|il|ld)\b[^\n]*\n(.*?)^```", re.S | re.M)


def blocks():
    for top in ("course", "labs", "docs"):
        for md in sorted((REPO / top).rglob("*.md")):
            for i, (lang, code) in enumerate(FENCE.findall(md.read_text("utf-8"))):
                yield pytest.param(lang, code, id=f"{md.relative_to(REPO)}#{i}")


def tokens(lexer, code):
    return [(t, v) for t, v in lexer().get_tokens(code) if v.strip()]


def kind(lexer, code, word):
    """The token type of the first token spelled ``word``."""
    return next(t for t, v in tokens(lexer, code) if v == word)


@pytest.mark.parametrize(("lang", "code"), list(blocks()))
def test_every_shown_block_lexes_without_an_error_token(lang, code):
    bad = [v for t, v in tokens(LEXERS[lang], code) if t in Error]
    assert not bad, bad


def test_there_are_blocks_of_every_language():
    langs = {p.values[0] for p in blocks()}
    assert {"st", "il", "ld"} <= langs


def test_st_words_get_their_classes():
    code = ("PROGRAM P VAR t : TON; x AT %QX0.1 : BOOL; n : INT := INT#5; END_VAR\n"
            "(* a (* nested *) comment *) // line\n"
            "t(IN := NOT x, PT := T#1m2s); n := REAL_TO_INT(3.5E2) + 16#FF;\n"
            "s := 'it$'s'; END_PROGRAM")
    toks = tokens(IecStLexer, code)
    assert kind(IecStLexer, code, "PROGRAM") in Keyword
    assert kind(IecStLexer, code, "BOOL") in Keyword.Type
    assert kind(IecStLexer, code, "TON") in Name.Builtin
    assert kind(IecStLexer, code, "REAL_TO_INT") in Name.Builtin
    assert kind(IecStLexer, code, "%QX0.1") in Name.Variable
    assert kind(IecStLexer, code, "T#1m2s") in String
    assert kind(IecStLexer, code, "16#FF") in Number
    assert kind(IecStLexer, code, "3.5E2") in Number.Float
    assert kind(IecStLexer, code, "'it$'s'") in String
    comment = "".join(v for t, v in IecStLexer().get_tokens(code) if t in Comment.Multiline)
    assert comment == "(* a (* nested *) comment *)"  # the whole nested comment, no more
    assert kind(IecStLexer, code, "// line") in Comment
    assert ("t" in [v for t, v in toks if t is Name])  # an instance is a name, not TIME


def test_il_operators_only_first_on_a_line():
    code = ("VAR x : INT; S : BOOL; END_VAR\n"
            "start:  LD      x\n"
            "        JMPC    start\n"
            "        ST      ST\n"
            "        S       S   (* set S *)\n")
    toks = tokens(IecIlLexer, code)
    assert kind(IecIlLexer, code, "start") in Name.Label
    assert kind(IecIlLexer, code, "INT") in Keyword.Type  # not the operand IN, then T
    assert ("IN" not in [v for _, v in toks])
    ops = [v for t, v in toks if t is Keyword.Reserved]
    assert ops == ["LD", "JMPC", "ST", "S"]
    names = [v for t, v in toks if t is Name]
    assert names.count("ST") == 1 and names.count("S") == 2 and "start" in names


def test_ld_rungs():
    code = ("VAR A AT %IX0.0 : BOOL; END_VAR\n"
            "|   A       B      Q  |\n"
            "|---[ ]--+---[/]----(S)--|\n")
    toks = tokens(IecLdLexer, code)
    assert [v for t, v in toks if t is Keyword] == ["VAR", "AT", "END_VAR", "[ ]", "[/]", "(S)"]
    assert {v for t, v in toks if t is Name} == {"A", "B", "Q"}


def test_the_site_maps_the_course_fences_to_these_lexers():
    from pygments.lexers import get_lexer_by_name

    from plclab.site.build import mkdocs_config

    cfg = mkdocs_config(Path("/d"), Path("/o"), [])
    hl = next(e["pymdownx.highlight"] for e in cfg["markdown_extensions"]
              if isinstance(e, dict) and "pymdownx.highlight" in e)
    assert hl["extend_pygments_lang"] == fence_map()
    # the names resolve through the entry points that `pip install` registers
    for entry in fence_map():
        assert type(get_lexer_by_name(entry["lang"])).__name__ == \
            LEXERS[entry["name"]].__name__
