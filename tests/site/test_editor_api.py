"""The playground editor's Python side (plclab/site/editor_api.py), in CPython: the course's
highlighting, diagnostics with the range the editor underlines, hover and completion from the
language server's feature functions."""

import html
import re

import pytest

pytest.importorskip("pygments")

from plclab.site import editor_api as ed  # noqa: E402

PROGRAM = """\
TYPE Point : STRUCT x : REAL; y : REAL; END_STRUCT; END_TYPE
PROGRAM Main
VAR
    delay : TON;        (* waits *)
    p : Point;
    count : INT;
END_VAR
delay(IN := TRUE, PT := T#2s);
count := LIMIT(0, count + 1, 10);
p.x := 1.5;
END_PROGRAM
"""


def course_examples():
    from plclab.course.model import chapters
    from plclab.site.pages import PLAYGROUND_LANGUAGES

    for ch in chapters():
        lines = ch.text.splitlines()
        i = 0
        while i < len(lines):
            m = re.match(r"^(`{3,})(\w+)", lines[i])
            if not m:
                i += 1
                continue
            j = i + 1
            while j < len(lines) and not lines[j].startswith(m.group(1)):
                j += 1
            if m.group(2) in PLAYGROUND_LANGUAGES:
                yield f"{ch.slug}:{i + 1}", m.group(2), "\n".join(lines[i + 1:j]) + "\n"
            i = j + 1


def merged(pieces):
    out = []
    for cls, text in pieces:
        if out and out[-1][0] == cls:
            out[-1] = (cls, out[-1][1] + text)
        else:
            out.append((cls, text))
    return out


def formatter_pieces(code, language):
    """What the course pages' HTML formatter writes for ``code``: (class, text) per span."""
    from pygments import highlight
    from pygments.formatters import HtmlFormatter

    lexer = ed._lexer(language)
    lexer.stripnl = lexer.ensurenl = False
    out = highlight(code, lexer, HtmlFormatter(nowrap=True))
    pieces = [(m.group(1) or "", html.unescape(m.group(2) or m.group(3)))
              for m in re.finditer(r'<span class="(\w+)">([^<]*)</span>|([^<]+)', out)]
    return merged([(c, t) for c, t in pieces if t])


def test_the_editor_colours_every_course_example_as_the_course_pages_do():
    examples = list(course_examples())
    assert len(examples) > 50
    for where, language, code in examples:
        lines = ed.highlight(code, language)
        assert ["".join(t for _, t in line) for line in lines] == code.split("\n"), where
        flat = [(c, t) for k, line in enumerate(lines)
                for c, t in line + ([("w", "\n")] if k < len(lines) - 1 else [])]
        # the formatter writes whitespace outside spans: compare the coloured pieces
        ours = [p for p in merged(flat) if p[0] != "w" and p[1].strip()]
        theirs = [p for p in formatter_pieces(code, language)
                  if p[0] not in ("w", "") and p[1].strip()]
        assert ours == theirs, where
        assert not any(c == "err" for c, _ in flat), where


def test_comments_keywords_and_il_operators_get_their_classes():
    st = dict((t, c) for line in ed.highlight(PROGRAM, "st") for c, t in line)
    assert st["(*"] == "cm" and st["END_VAR"] == "k" and st["TON"] == "nb"
    assert st["REAL"] == "kt" and st["T#2s"] == "sx" and st["count"] == "n"
    il = ed.highlight("LD start\nST LD\n", "il")
    assert il[0][0] == ("kr", "LD") and il[1][-1] == ("n", "LD")  # an operand, not an operator
    ld = ed.highlight("|  A   B   ( )  Q |\n", "ld")
    assert ("k", "( )") in ld[0]


def test_lint_underlines_the_word_a_diagnostic_names():
    text = "PROGRAM P\nVAR x : INT; END_VAR\nx := y + 1;\nEND_PROGRAM\n"
    d = ed.lint(text, "st")
    assert d and d[0]["severity"] == "error" and d[0]["line"] == 3
    line = text.split("\n")[2]
    assert line[d[0]["col"] - 1:d[0]["end"] - 1] == "y"
    assert ed.lint(PROGRAM, "st") == [] or all(x["severity"] == "warning"
                                               for x in ed.lint(PROGRAM, "st"))


def test_lint_reads_il_and_ld_and_a_diagnostic_without_a_place_has_none():
    il = ed.lint("PROGRAM P\nVAR a : BOOL; END_VAR\n    LDX a\n    ST a\nEND_PROGRAM\n", "il")
    assert il and il[0]["line"] == 3
    ld = ed.lint("PROGRAM P\nVAR a, q : BOOL; END_VAR\n|  a   ( )  q |\nEND_PROGRAM\n", "ld")
    assert all(d["line"] >= 0 and (d["line"] == 0) == (d["end"] == 0) for d in ld)
    assert ed.word_end("abc def", 1, 5) == 8 and ed.word_end("x := ;", 1, 6) == 7
    assert ed.word_end("", 1, 1) == 1


def test_hover_gives_a_variables_declaration_and_a_standard_functions_signature():
    hover_delay = ed.hover(PROGRAM, "st", 8, 2)
    assert "delay : TON" in hover_delay
    assert "LIMIT" in ed.hover(PROGRAM, "st", 9, 11)
    assert "Point" in ed.hover(PROGRAM, "st", 5, 5)
    assert ed.hover(PROGRAM, "st", 8, 30) == ""  # a literal: nothing


def test_hover_and_completion_still_know_the_declarations_while_a_line_is_half_typed():
    broken = PROGRAM.replace("p.x := 1.5;", "p.")
    assert "delay : TON" in ed.hover(broken, "st", 8, 2)
    labels = [c["label"] for c in ed.complete(broken, "st", 10, 3)]
    assert labels[:2] == ["x", "y"] and len(labels) == 2


def test_completion_of_members_declared_names_and_standard_blocks():
    text = PROGRAM.replace("p.x := 1.5;", "delay.")
    members = {c["label"] for c in ed.complete(text, "st", 10, 7)}
    assert {"Q", "ET", "IN", "PT"} <= members and "count" not in members
    text = PROGRAM.replace("p.x := 1.5;", "co")
    found = ed.complete(text, "st", 10, 3)
    labels = [c["label"] for c in found]
    assert "count" in labels and all(x.upper().startswith("CO") for x in labels)
    assert found[0]["from"] == 1
    blocks = {c["label"]: c for c in ed.complete(PROGRAM.replace("p.x := 1.5;", "CT"),
                                                 "st", 10, 3)}
    assert {"CTU", "CTD", "CTUD"} <= set(blocks) and blocks["CTU"]["kind"] == "block"
    assert "CU" in blocks["CTU"]["detail"]



def test_a_half_typed_line_completes_from_its_own_program_not_the_one_before():
    """The page checked another program before (the example it opened with); the student
    replaced it and types a half line: the names come from the new program."""
    ed._workspace = None
    ed.lint("PROGRAM Old\nVAR legacy : INT; END_VAR\nlegacy := 1;\nEND_PROGRAM\n", "st")
    text = "PROGRAM P\nVAR level : REAL; delay : TON; END_VAR\nle\nEND_PROGRAM\n"
    labels = [c["label"] for c in ed.complete(text, "st", 3, 3)]
    assert labels[0] == "level" and "legacy" not in labels
    text = text.replace("le\n", "delay.\n")
    assert {"Q", "ET"} <= {c["label"] for c in ed.complete(text, "st", 3, 7)}
    text = text.replace("delay.\n", "x := delay + ;\n")
    assert "delay : TON" in ed.hover(text, "st", 3, 8)
