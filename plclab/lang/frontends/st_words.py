"""The shared words of the ST parser: the section and POU keywords where parsing stops or
recovers, the words worth suggesting, and the abort for nesting beyond the limits (used by
:mod:`plclab.lang.frontends.st` and its mixins ``st_decl``, ``st_stmt``, ``st_expr``).
"""

from __future__ import annotations

from ..lexer import KEYWORDS, Token
from ..parsing import ParseAbort

# words worth suggesting in "did you mean": keywords plus those of later language extensions
SUGGEST = KEYWORDS | {"EXTENDS", "IMPLEMENTS", "METHOD", "END_METHOD", "INTERFACE",
                      "END_INTERFACE", "PROPERTY", "END_PROPERTY", "THIS", "SUPER"}

VAR_SECTIONS = ("VAR", "VAR_INPUT", "VAR_OUTPUT", "VAR_IN_OUT", "VAR_GLOBAL", "VAR_EXTERNAL",
                "VAR_TEMP")
STMT_END = {"END_IF", "ELSIF", "ELSE", "END_CASE", "END_FOR", "END_WHILE", "UNTIL",
            "END_REPEAT", "END_PROGRAM", "END_FUNCTION", "END_FUNCTION_BLOCK", "END_TEST", "EOF"}
POU_START = {"PROGRAM", "FUNCTION", "FUNCTION_BLOCK", "TYPE", "VAR_GLOBAL", "CONFIGURATION",
             "TEST", "VAR_CONFIG"}
# tokens where a declaration cannot continue: a new section, a new POU, the end of a body
DECL_STOP = set(VAR_SECTIONS) | POU_START | STMT_END | {"END_TYPE", "END_STRUCT",
                                                          "END_CONFIGURATION", "END_RESOURCE"}


class TooDeep(ParseAbort):
    """Internal: nesting beyond the limits (PLC0190 is reported). Statements do not recover
    from it one by one (that would report every level again): the body is skipped."""


def found_token(t: Token) -> str:
    if t.kind == "EOF":
        return "the end of the file"
    return f"'{t.text}'"
