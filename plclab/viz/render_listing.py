"""ST and IL bodies as highlighted listings (SVG): keywords bold blue, comments green,
literals brown, line numbers grey; with ``values``, the current value of each variable named on
a line is shown at the line's end, as an editor's online mode does.

>>> svg = render_listing("PROGRAM P VAR a : BOOL; END_VAR\\na := NOT a;\\nEND_PROGRAM", "p.st",
...                      values={"A": True})
>>> "NOT" in svg and "a = TRUE" in svg
True
"""

from __future__ import annotations

import re
from typing import Any
from xml.sax.saxutils import escape

from .ladder_svg import FONT, PAD, Svg

LINE_H = 17
CHAR_W = 7.3
KEYWORDS = {
    "PROGRAM", "END_PROGRAM", "FUNCTION", "END_FUNCTION", "FUNCTION_BLOCK", "END_FUNCTION_BLOCK",
    "VAR", "VAR_INPUT", "VAR_OUTPUT", "VAR_IN_OUT", "VAR_GLOBAL", "VAR_EXTERNAL", "VAR_TEMP",
    "END_VAR", "CONSTANT", "RETAIN", "AT", "IF", "THEN", "ELSIF", "ELSE", "END_IF", "CASE", "OF",
    "END_CASE", "FOR", "TO", "BY", "DO", "END_FOR", "WHILE", "END_WHILE", "REPEAT", "UNTIL",
    "END_REPEAT", "EXIT", "RETURN", "AND", "OR", "XOR", "NOT", "MOD", "TRUE", "FALSE",
    "TYPE", "END_TYPE", "STRUCT", "END_STRUCT", "ARRAY", "CONFIGURATION", "END_CONFIGURATION",
    "RESOURCE", "END_RESOURCE", "TASK", "ON", "WITH",
    # IL operators
    "LD", "LDN", "ST", "STN", "S", "R", "ANDN", "ORN", "XORN", "ADD", "SUB", "MUL", "DIV", "GT",
    "GE", "EQ", "NE", "LE", "LT", "JMP", "JMPC", "JMPCN", "CAL", "CALC", "CALCN", "RET", "RETC",
    "RETCN"}
_TOKEN = re.compile(r"(\(\*.*?\*\)|//.*$)|('(?:[^'$]|\$.)*'|%[A-Za-z]+[\d.]*|\b[A-Za-z]+#[\w.:#-]+"
                    r"|\b\d[\w.]*)"
                    r"|(\b[A-Za-z_]\w*\b)")


def _split_comments(lines: list[str]) -> list[list[tuple[bool, str]]]:
    """Each line as (is comment, text) pieces; ``(* ... *)`` comments may span lines."""
    out, inside = [], False
    for ln in lines:
        pieces, pos = [], 0
        while pos < len(ln):
            if inside:
                end = ln.find("*)", pos)
                stop = len(ln) if end < 0 else end + 2
                pieces.append((True, ln[pos:stop]))
                inside, pos = end < 0, stop
                continue
            starts = [i for i in (ln.find("(*", pos), ln.find("//", pos)) if i >= 0]
            start = min(starts, default=-1)
            if start < 0:
                pieces.append((False, ln[pos:]))
                break
            pieces.append((False, ln[pos:start]))
            if ln.startswith("//", start):
                pieces.append((True, ln[start:]))
                break
            inside, pos = True, start
        out.append(pieces)
    return out


def _pieces_svg(pieces: list[tuple[bool, str]]) -> str:
    return "".join(f"<tspan fill='#2e7d32'>{escape(t)}</tspan>" if c else _line_svg(t)
                   for c, t in pieces)


def _line_svg(text: str) -> str:
    out, pos = [], 0
    for m in _TOKEN.finditer(text):
        out.append(escape(text[pos:m.start()]))
        comment, literal, word = m.groups()
        if comment:
            out.append(f"<tspan fill='#2e7d32'>{escape(comment)}</tspan>")
        elif literal:
            out.append(f"<tspan fill='#8d4a00'>{escape(literal)}</tspan>")
        elif word.upper() in KEYWORDS:
            out.append(f"<tspan fill='#0b3d91' font-weight='bold'>{escape(word)}</tspan>")
        else:
            out.append(escape(word))
        pos = m.end()
    out.append(escape(text[pos:]))
    return "".join(out)


def render_listing(text: str, file: str = "", values: dict[str, Any] | None = None,
                   first: int = 1, last: int | None = None) -> Svg:
    """Lines ``first``..``last`` of a source as a highlighted SVG listing."""
    lines = text.replace("\t", "    ").split("\n")[first - 1:last]
    vals = {k.upper(): v for k, v in (values or {}).items()}
    width = max([len(ln) for ln in lines] + [len(file) - 5], default=10) * CHAR_W + 60 + PAD * 2
    rows = []
    split = _split_comments(lines)
    for n, ln in enumerate(lines, first):
        pieces = split[n - first]
        y = PAD + 20 + (n - first + 1) * LINE_H
        rows.append(f"<text x='{PAD}' y='{y}' {FONT} font-size='12' fill='#999'>{n:>4}</text>")
        rows.append(f"<text x='{PAD + 40}' y='{y}' {FONT} font-size='12' "
                    f"xml:space='preserve'>{_pieces_svg(pieces)}</text>")
        code = " ".join(t for c, t in pieces if not c)
        shown = []
        for w in dict.fromkeys(re.findall(r"[A-Za-z_]\w*(?:\.[A-Za-z_]\w*)?", code)):
            if w.upper() in vals and w.upper() not in KEYWORDS:
                v = vals[w.upper()]
                shown.append(f"{w} = {'TRUE' if v is True else 'FALSE' if v is False else v}")
        if shown:
            x = PAD + 60 + len(ln) * CHAR_W
            width = max(width, x + 9 * sum(len(s) + 2 for s in shown))
            rows.append(f"<text x='{x:.0f}' y='{y}' {FONT} font-size='11' fill='#1a7f37'>"
                        f"{escape('   '.join(shown))}</text>")
    height = PAD * 2 + 24 + len(lines) * LINE_H
    title = escape(file or "listing")
    return Svg(f"<svg xmlns='http://www.w3.org/2000/svg' width='{width:.0f}' height='{height}' "
               f"viewBox='0 0 {width:.0f} {height}'><title>{title}</title>"
               f"<rect width='100%' height='100%' fill='white'/>"
               f"<text x='{PAD}' y='{PAD + 8}' {FONT} font-size='12' font-weight='bold'>{title}"
               f"</text>{''.join(rows)}</svg>")
