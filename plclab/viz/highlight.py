"""Pygments lexers for IEC 61131-3 Structured Text, Instruction List and plclab's text ladder.

Pygments maps the fence name ``st`` to Smalltalk, which colours ``(* comments *)`` as code and
``:`` as an error. These lexers are registered as the ``pygments.lexers`` entry points
``iec-st``, ``iec-il`` and ``iec-ld`` (pyproject.toml); the site maps the course's fence names
``st``, ``iecst``, ``il`` and ``ld`` to them (:func:`fence_map`). Imported only by the site
build and by Pygments itself, never by ``import plclab`` (Pygments is not a core dependency).

Keywords, types and standard block names come from plclab's own tables, so a word the
compiler knows is a word the highlighter colours.

>>> from pygments.token import Comment
>>> [v for t, v in IecStLexer().get_tokens("x := 1; (* (* nested *) *)") if t in Comment]
['(*', ' ', '(*', ' nested ', '*)', ' ', '*)']
"""

from __future__ import annotations

import re

from pygments.lexer import RegexLexer, bygroups, include, words
from pygments.token import (
    Comment,
    Keyword,
    Name,
    Number,
    Operator,
    Punctuation,
    String,
    Whitespace,
)

from ..lang.lexer import KEYWORDS

_MORE_KEYWORDS = (
    # ed.3 and CODESYS OOP, SFC, references, namespaces: plclab parses these as unreserved words
    "METHOD", "END_METHOD", "PROPERTY", "END_PROPERTY", "INTERFACE", "END_INTERFACE",
    "EXTENDS", "IMPLEMENTS", "THIS", "SUPER", "ABSTRACT", "FINAL", "OVERRIDE", "PUBLIC",
    "PRIVATE", "PROTECTED", "INTERNAL", "GET", "SET", "END_GET", "END_SET",
    "ACTION", "END_ACTION", "ACTIONS", "END_ACTIONS", "STEP", "END_STEP", "INITIAL_STEP",
    "TRANSITION", "END_TRANSITION", "FROM", "PRIORITY", "INTERVAL", "SINGLE",
    "REF_TO", "REF", "POINTER", "NULL", "VAR_INST", "VAR_STAT", "END_VAR", "NAMESPACE",
    "END_NAMESPACE", "USING", "JMP", "ASSERT",
)
_TYPES = (
    "BOOL", "SINT", "INT", "DINT", "LINT", "USINT", "UINT", "UDINT", "ULINT", "REAL", "LREAL",
    "BYTE", "WORD", "DWORD", "LWORD", "TIME", "LTIME", "DATE", "LDATE", "TIME_OF_DAY", "TOD",
    "LTOD", "DATE_AND_TIME", "DT", "LDT", "STRING", "WSTRING", "CHAR", "WCHAR", "ANY",
    "ANY_NUM", "ANY_INT", "ANY_REAL", "ANY_BIT", "ANY_ELEMENTARY",
)
_STANDARD_BLOCKS = (
    "TON", "TOF", "TP", "TONR", "CTU", "CTD", "CTUD", "R_TRIG", "F_TRIG", "SR", "RS", "HYST",
    "PID", "RAMP", "INTEGRAL", "DERIVATIVE", "HYSTERESIS", "LIMIT", "MIN", "MAX", "SEL",
    "MUX", "MOVE", "ABS", "SQRT", "LN", "LOG", "EXP", "SIN", "COS", "TAN", "ASIN", "ACOS",
    "ATAN", "ATAN2", "EXPT", "TRUNC", "SHL", "SHR", "ROL", "ROR", "LEN", "LEFT", "RIGHT",
    "MID", "CONCAT", "INSERT", "DELETE", "REPLACE", "FIND", "ADR", "SIZEOF",
    "LOWER_BOUND", "UPPER_BOUND", "ADD", "SUB", "MUL", "DIV", "GT", "GE", "EQ", "NE",
    "LE", "LT",
)
_IL_OPERATORS = (
    "LD", "LDN", "ST", "STN", "S", "R", "AND", "ANDN", "OR", "ORN", "XOR", "XORN", "NOT",
    "ADD", "SUB", "MUL", "DIV", "MOD", "GT", "GE", "EQ", "NE", "LE", "LT", "JMP", "JMPC",
    "JMPCN", "CAL", "CALC", "CALCN", "RET", "RETC", "RETCN", "S1", "R1", "CLK", "CU", "CD",
    "PV", "IN", "PT",
)


def _keywords() -> tuple[str, ...]:
    types = set(_TYPES)
    return tuple(sorted((set(KEYWORDS) | set(_MORE_KEYWORDS)) - types - {"TRUE", "FALSE"},
                        key=len, reverse=True))


def _common_rules() -> dict[str, list]:
    """The tokens every IEC text language shares: comments, pragmas, literals, addresses,
    declarations' keywords and types, standard blocks, names and operators."""
    return {
        "comments": [
            (r"\(\*", Comment.Multiline, "comment"),
            (r"/\*", Comment.Multiline, "c-comment"),
            (r"//.*?$", Comment.Single),
            (r"\{[^}]*\}", Comment.Preproc),  # pragmas and attributes
        ],
        "literals": [
            (r"'(?:\$.|''|[^'$])*'", String.Single),
            (r'"(?:\$.|""|[^"$])*"', String.Double),
            (r"\b(?:L?TIME|L?T|L?TOD|L?TIME_OF_DAY|L?DT|L?DATE_AND_TIME|L?DATE|L?D)#"
             r"[-+]?[\w:.\-]+", String.Other),
            (r"\b(?:2#[01_]+|8#[0-7_]+|16#[0-9a-f_]+)", Number.Hex),
            (r"\b[a-z_]+#(?=[-+\d'\"]|16#|8#|2#)", Keyword.Type),  # INT#5, STRING#'x'
            (r"\d[\d_]*\.\d[\d_]*(?:[eE][-+]?\d+)?", Number.Float),
            (r"\d[\d_]*[eE][-+]?\d+", Number.Float),
            (r"\d[\d_]*", Number.Integer),
            (r"%[IQM][XBWDL]?\*?[\d.]*", Name.Variable.Magic),  # direct addresses
            (r"\b(?:TRUE|FALSE)\b", Keyword.Constant),
        ],
        "words": [
            (words(_keywords(), prefix=r"\b", suffix=r"\b"), Keyword),
            (words(sorted(_TYPES, key=len, reverse=True), prefix=r"\b", suffix=r"\b"),
             Keyword.Type),
            (words(sorted(set(_STANDARD_BLOCKS), key=len, reverse=True), prefix=r"\b",
                   suffix=r"\b(?=\s*[(;:,)])"), Name.Builtin),
            (r"\b(?:AND|OR|XOR|NOT|MOD|AND_THEN|OR_ELSE)\b", Operator.Word),
            (r"\b[A-Z]+_TO_[A-Z]+\b", Name.Builtin),  # conversions: REAL_TO_INT
            (r"[A-Za-z_]\w*", Name),
        ],
        "operators": [
            (r":=|=>|\?=|<>|<=|>=|\*\*|\.\.|\^|[-+*/=<>&]", Operator),
            (r"[()\[\],;:.#]", Punctuation),
            (r"\s+", Whitespace),
        ],
        "comment": [
            (r"[^(*]+", Comment.Multiline),
            (r"\(\*", Comment.Multiline, "#push"),  # CODESYS and MATIEC nest them
            (r"\*\)", Comment.Multiline, "#pop"),
            (r"[(*]", Comment.Multiline),
        ],
        "c-comment": [
            (r"[^*]+", Comment.Multiline),
            (r"\*/", Comment.Multiline, "#pop"),
            (r"\*", Comment.Multiline),
        ],
    }


class IecStLexer(RegexLexer):
    """IEC 61131-3 Structured Text (also the declarations of every textual POU)."""

    name = "IEC 61131-3 Structured Text"
    aliases = ["iec-st", "iecst", "iec61131-st"]  # never "st": Pygments gives it to Smalltalk
    filenames = ["*.iecst"]
    mimetypes = ["text/x-iecst"]
    url = "https://plcopen.org/iec-61131-3"
    flags = re.MULTILINE | re.IGNORECASE

    tokens = {
        **_common_rules(),
        "root": [include("comments"), include("literals"), include("words"),
                 include("operators")],
    }


class IecIlLexer(RegexLexer):
    """IEC 61131-3 Instruction List: a label, an operator with its modifiers, an operand, per
    line; the declarations as in ST."""

    name = "IEC 61131-3 Instruction List"
    aliases = ["iec-il", "iec61131-il"]
    filenames = ["*.il"]
    mimetypes = ["text/x-iecil"]
    flags = re.MULTILINE | re.IGNORECASE

    tokens = {
        **_common_rules(),
        "root": [
            (r"^(\s*)([A-Za-z_]\w*)(\s*)(:)(?!=)", bygroups(Whitespace, Name.Label,
                                                           Whitespace, Punctuation)),
            (words(sorted(_IL_OPERATORS, key=len, reverse=True), prefix=r"(?<![\w.%])",
                   suffix=r"\b(?=\s*(?:\(|[A-Za-z_%\d'\"-]|\*\)|\(\*|$))(?!\s*:)"),
             Keyword.Reserved),
            include("comments"), include("literals"), include("words"), include("operators"),
        ],
    }

    def get_tokens_unprocessed(self, text, stack=("root",)):  # type: ignore[override]
        # an IL operator counts only first on a line (after an optional label); elsewhere the
        # same word is an operand (``ST LD`` stores into a variable named LD)
        first = True
        for index, token, value in super().get_tokens_unprocessed(text, stack):
            if token is Keyword.Reserved and not first:
                token = Name
            if "\n" in value:
                first = True
            elif not (token in Whitespace or token in Comment or token is Name.Label
                      or (token is Punctuation and value == ":")):
                first = False
            yield index, token, value


class IecLdLexer(RegexLexer):
    """plclab's text ladder: ST declarations, then rungs between power rails (``|``) with
    contacts ``[ ]``, ``[/]``, ``[P]``, ``[N]`` and coils ``( )``, ``(/)``, ``(S)``, ``(R)``."""

    name = "plclab text ladder (IEC 61131-3 LD)"
    aliases = ["iec-ld", "plclab-ld"]
    filenames = ["*.ld"]
    mimetypes = ["text/x-plclab-ld"]
    flags = re.MULTILINE | re.IGNORECASE

    tokens = {
        **_common_rules(),
        "root": [
            (r"^(\s*)(\|)", bygroups(Whitespace, Punctuation), "rung"),
            include("comments"), include("literals"), include("words"), include("operators"),
        ],
        "rung": [
            (r"\n", Whitespace, "#pop"),
            (r"\[(?:\s|/|P|N)\]", Keyword),  # contacts
            (r"\((?:\s|/|S|R|P|N)\)", Keyword),  # coils
            (r"[-+|]+", Punctuation),
            include("comments"), include("literals"), include("words"), include("operators"),
        ],
    }


def fence_map() -> list[dict[str, str]]:
    """pymdownx.highlight's ``extend_pygments_lang``: the course's fence names to these lexers."""
    return [{"name": "st", "lang": "iec-st"}, {"name": "iecst", "lang": "iec-st"},
            {"name": "il", "lang": "iec-il"}, {"name": "ld", "lang": "iec-ld"}]
