"""Crashes and hangs found by the fuzzers and the escape suite, as minimal reproducers.

``KNOWN`` holds what is open: each entry names the area whose fix it waits for; ``test_fuzz.py``
runs it as an ``xfail(strict=False)`` test and the fuzz campaigns skip its signature. ``FIXED``
holds what was found and fixed (issue 11): those reproducers are plain regression tests that
must give diagnostics or PlcErrors only.
"""

from __future__ import annotations

import re
from dataclasses import dataclass


@dataclass(frozen=True)
class Known:
    id: str
    area: str  # which engineer's part of issue 11 fixes it
    pattern: str  # regular expression on the fuzz failure signature
    name: str  # file name of the reproducer (its extension picks the front end)
    text: str  # the minimal reproducer
    reason: str


HOSTILE_DECLS = "hostile declarations (parser progress, literal ranges)"
ARITHMETIC = "arithmetic + FOR (codegen expressions, rt.py)"
MANGLING = "identifier mangling (codegen ident() / lexer; trust-boundary rule of DESIGN.md)"

FIXED: list[Known] = [
    Known("parser-var-section-typo", HOSTILE_DECLS,
          r"hang:(check|\?):.*", "typo.st",
          "PROGRAM P VAR VAR_GLOBAL END_VAR END_PROGRAM\n",
          "a section keyword inside a VAR section makes the ST parser loop forever, growing "
          "memory (also 'FUNCTION_BLOCK A VAR_INPUT VAR_GLOBAL', in .st, .il and .ld files)"),
    Known("math-domain-error", ARITHMETIC,
          r"crash:scan:PLC9999:ValueError", "ln.st",
          "PROGRAM P VAR r0, r1 : REAL; END_VAR r0 := SIN(LN(r1)); END_PROGRAM\n",
          "LN(0.0) raises Python's 'math domain error' at run time: PLC9999 internal error "
          "instead of a run-time fault with a code (SIN(inf) too)"),
    Known("real-literal-overflow", HOSTILE_DECLS,
          r"crash:(scan|load|compile):(PLC9999:)?NameError.*", "inf.st",
          "PROGRAM P VAR r : LREAL; END_VAR r := 1.0E400; END_PROGRAM\n",
          "an overflowing REAL literal compiles to the Python name 'inf': NameError at run "
          "time (PLC9999) instead of a compile-time range error"),
    Known("double-underscore-identifier", MANGLING,
          r"crash:(scan|load):(PLC9999:)?AttributeError.*", "dunder.st",
          "FUNCTION_BLOCK FB\nVAR_INPUT __X : INT; END_VAR\nVAR_OUTPUT q : INT; END_VAR\n"
          "q := __X;\nEND_FUNCTION_BLOCK\n"
          "PROGRAM P VAR f : FB; y : INT; END_VAR f(__X := 3); y := f.q; END_PROGRAM\n",
          "an identifier starting with '__' becomes a Python private name (self.__X is "
          "mangled to self._P_P__X inside a class): AttributeError, PLC9999 or a raw Python "
          "exception (a PLCopen POU named '__X'); IEC forbids '__' in identifiers"),
    Known("double-underscore-pou-xml", MANGLING,
          r"crash:load:AttributeError:.*", "dunder.xml",
          "<?xml version=\"1.0\"?>\n<project xmlns=\"http://www.plcopen.org/xml/tc6_0201\">"
          "<types><dataTypes/><pous><pou name=\"__X\" pouType=\"program\"><interface>"
          "<localVars><variable name=\"v\"><type><INT/></type></variable></localVars>"
          "</interface><body><ST><xhtml xmlns=\"http://www.w3.org/1999/xhtml\">v := v + 1;"
          "</xhtml></ST></body></pou></pous></types></project>\n",
          "a PLCopen program named '__X' loads with a raw AttributeError from Plc() (not even "
          "a PlcError)"),
]

KNOWN: list[Known] = []


def match(sig: str) -> Known | None:
    """The known issue a fuzz failure signature belongs to, if any."""
    for k in KNOWN:
        if re.fullmatch(k.pattern, sig):
            return k
    return None


# escape-suite case ids (tests/security/payloads.py) that fail for a known reason
ESCAPES: dict[str, str] = {}


def match_escape(case_id: str) -> Known | None:
    """The known issue an escape-suite case waits for, if any."""
    kid = ESCAPES.get(case_id)
    return next((k for k in KNOWN if k.id == kid), None) if kid else None
