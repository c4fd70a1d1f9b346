"""Lexer and parser: literals, comments, case-insensitivity, error recovery."""

import pytest

from plclab.errors import PlcError
from plclab.lang import ast as A
from plclab.lang.frontends.st import parse_st, parse_st_collect
from plclab.lang.lexer import Lexer, parse_duration, tokenize


def kinds(text):
    return [(t.kind, t.value) for t in tokenize(text)][:-1]


@pytest.mark.parametrize("text,value", [
    ("16#FF", 255), ("2#1010_0101", 165), ("8#17", 15), ("1_000", 1000), ("INT#5", 5),
    ("16#ff", 255),
])
def test_integer_literals(text, value):
    assert kinds(text)[0] == ("INT", value)


def test_real_literals():
    assert kinds("1.5E3")[0] == ("REAL", 1500.0)
    assert kinds("2.5")[0] == ("REAL", 2.5)
    assert kinds("1e-2")[0] == ("REAL", 0.01)


@pytest.mark.parametrize("text,ms", [
    ("T#1h2m3s4ms", 3723004), ("TIME#-5s", -5000), ("T#2s_200ms", 2200), ("t#1.5s", 1500),
    ("T#1d", 86_400_000), ("LTIME#5us", 0.005),
])
def test_duration_literals(text, ms):
    (kind, ns), = kinds(text)
    assert kind == "TIME"
    assert ns / 1_000_000 == ms


def test_bad_duration_is_diagnosed():
    lx = Lexer("x := T#5parsecs;", "d.st")
    lx.tokens()
    assert lx.diagnostics and lx.diagnostics[0].code == "PLC0005"


def test_date_and_time_literals():
    (k, v), = kinds("D#2024-01-31")
    assert k == "DATE" and v == 1706659200
    (k, v), = kinds("TOD#14:32:07.77")
    assert k == "TOD" and v == 52327770
    (k, v), = kinds("DT#1970-01-02-00:00:01")
    assert k == "DT" and v == 86_401_000


def test_strings_with_dollar_escapes():
    (k, v), = kinds("'a$'b$$c$N$54'")
    assert k == "STRING" and v == "a'b$c\nT"
    (k, v), = kinds('"wide$0041"')
    assert k == "WSTRING" and v == "wideA"


def test_comments_nest_and_line_comments():
    assert kinds("a (* x (* y *) z *) b // c\n d") == [("IDENT", "A"), ("IDENT", "B"),
                                                      ("IDENT", "D")]
    assert kinds("a /* c */ b") == [("IDENT", "A"), ("IDENT", "B")]


def test_unclosed_comment_and_string_are_reported():
    lx = Lexer("(* never closed", "c.st")
    lx.tokens()
    assert lx.diagnostics[0].code == "PLC0002"
    lx = Lexer("x := 'open", "c.st")
    lx.tokens()
    assert lx.diagnostics[0].code == "PLC0003"


@pytest.mark.parametrize("text,value", [("'it''s'", "it's"), ('"say ""hi"""', 'say "hi"')])
def test_a_doubled_quote_in_a_string_is_one_error_naming_the_escape(text, value):
    lx = Lexer(f"x := {text};", "c.st")
    toks = lx.tokens()
    assert [d.code for d in lx.diagnostics] == ["PLC0003"]
    assert "$" + text[0] in lx.diagnostics[0].message
    assert [t.value for t in toks if t.kind in ("STRING", "WSTRING")] == [value]


@pytest.mark.parametrize("text,value", [("''", ""), ("'$''", "'"), ("'a$'$'b'", "a''b")])
def test_empty_strings_and_escaped_quotes_are_clean(text, value):
    lx = Lexer(f"x := {text};", "c.st")
    toks = lx.tokens()
    assert lx.diagnostics == []
    assert [t.value for t in toks if t.kind == "STRING"] == [value]


def test_identifiers_and_keywords_are_case_insensitive():
    f = parse_st("program p var MyVar : int; end_var myvar := MYVAR + 1; END_PROGRAM")
    assert f.pous[0].name == "P"
    a = f.pous[0].body[0]
    assert isinstance(a, A.Assign) and a.target.name == "MYVAR"


def test_underscore_is_significant():
    f = parse_st("PROGRAM P VAR a_b : INT; ab : INT; END_VAR END_PROGRAM")
    assert [d.name for d in f.pous[0].decls] == ["A_B", "AB"]


def test_iec_precedence():
    f = parse_st("PROGRAM P VAR x : BOOL; a, b : INT; END_VAR x := a + 1 > b * 2 OR a = b AND "
                 "NOT x; END_PROGRAM")
    e = f.pous[0].body[0].value
    assert e.op == "OR"
    assert e.left.op == ">" and e.left.left.op == "+" and e.left.right.op == "*"
    assert e.right.op == "AND" and e.right.left.op == "="


def test_negation_binds_tighter_than_power():
    f = parse_st("PROGRAM P VAR x : REAL; END_VAR x := -x ** 2; END_PROGRAM")
    e = f.pous[0].body[0].value
    assert e.op == "**" and isinstance(e.left, A.Unary)


def test_all_errors_are_reported_not_only_the_first():
    src = """PROGRAM P VAR x : INT; END_VAR
    IF x == 1 THEN x := 2; END_IFF;
    WHILE x = 1 DO x = 3; END_WHILLE;
    END_PROGRAM"""
    _, diags = parse_st_collect(src, "e.st")
    codes = [d.code for d in diags]
    assert codes == ["PLC0012", "PLC0011", "PLC0013", "PLC0011"]
    assert "did you mean END_IF?" in diags[1].message
    assert "did you mean END_WHILE?" in diags[3].message
    assert str(diags[0]).startswith("e.st:2:")


def test_parse_error_raises_plcerror_with_all_diagnostics():
    with pytest.raises(PlcError) as ei:
        parse_st("PROGRAM P x := ; y := ; END_PROGRAM", "x.st")
    assert len(ei.value.diagnostics) == 2


def test_fb_call_forms():
    f = parse_st("PROGRAM P VAR t : TON; q : BOOL; END_VAR t(IN := TRUE, PT := T#1s, Q => q); "
                 "t(TRUE, T#2s); END_PROGRAM")
    c1, c2 = (s.call for s in f.pous[0].body)
    assert [(a.name, a.output) for a in c1.args] == [("IN", False), ("PT", False), ("Q", True)]
    assert [a.name for a in c2.args] == [None, None]


def test_case_with_ranges_lists_and_enum_labels():
    f = parse_st("""PROGRAM P VAR c : INT; x : INT; END_VAR
      CASE c OF 1, 2: x := 1; 3..5: x := 2; Red: x := 3; ELSE x := 0; END_CASE END_PROGRAM""")
    case = f.pous[0].body[0]
    assert len(case.branches) == 3 and case.orelse is not None
    assert isinstance(case.branches[1].labels[0], tuple)


def test_parse_duration_helper():
    assert parse_duration("1m30s") == 90 * 10**9
    assert parse_duration("5parsecs") is None
