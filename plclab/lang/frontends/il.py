"""Instruction List (IEC 61131-3 IL) front end: ``.il`` files.

An IL file is read by the ST parser with IL as the default body language: every POU body is IL
unless it starts like ST. Recognising and parsing IL lines is :mod:`.il_lines`; translating them
to statements is the lowering stage (:mod:`plclab.lang.lower.il`).

>>> from plclab.lang.frontends.st import parse_st
>>> f = parse_st('''PROGRAM P VAR x, A, B, Y : INT; END_VAR
... LD x
... MUL A
... ADD B
... ST Y
... END_PROGRAM''', "p.il")
>>> f.pous[0].language, type(f.pous[0].body[0]).__name__
('IL', 'Assign')
"""

from __future__ import annotations

from ...errors import Diagnostic
from .. import ast as A
from .il_lines import is_il_body, parse_il_body
from .st import Parser, lower_alone


def parse(text: str, file: str = "<input>.il") -> tuple[A.SourceFile, list[Diagnostic]]:
    """Parse a file whose POU bodies are IL by default; the bodies stay pending."""
    p = Parser(text, file)
    p.il_default = True
    out = p.parse_file()
    return out, p.diagnostics


def parse_il_collect(text: str, file: str = "<input>.il") -> tuple[A.SourceFile, list[Diagnostic]]:
    """Parse a file whose POU bodies are IL by default (like a ``.il`` file) and lower it."""
    out, diags = parse(text, file)
    return out, diags + lower_alone(out)


__all__ = ["parse", "parse_il_collect", "is_il_body", "parse_il_body"]
