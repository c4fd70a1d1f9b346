"""Signatures and one-line descriptions of the standard functions and blocks, for hover and
completion.

The signatures come from the standard library's tables (:data:`plclab.lang.builtins.BUILTINS`,
the conversions of :func:`plclab.lang.builtins.conversion`) and from the library's declarations
(``stdlib.st``, ``ctrllib.st``, ``annexf.st``); a block's description is the first sentence of
its native implementation's docstring or of the comment above it in the library file. The
standard functions have no text elsewhere, so :data:`FUNCTION_DOCS` holds one line for each
(``tests/lsp/test_stdlib_docs.py`` checks that no builtin is missing).

>>> describe("SQRT")[0]
'SQRT(IN) : ANY_REAL'
>>> describe("INT_TO_REAL")[1]
'Converts an INT to a REAL.'
"""

from __future__ import annotations

import re
from functools import cache

from ..lang import ast as A
from ..lang.builtins import BUILTINS, conversion
from ..lang.unparse import type_ref

_MATH = {"SQRT": "square root", "LN": "natural logarithm", "LOG": "base-10 logarithm",
         "EXP": "e to the power of IN", "SIN": "sine (radians)", "COS": "cosine (radians)",
         "TAN": "tangent (radians)", "ASIN": "arc sine, in radians",
         "ACOS": "arc cosine, in radians", "ATAN": "arc tangent, in radians"}
_TIME_FNS = {"ADD_TIME": "TIME + TIME", "ADD_TOD_TIME": "time of day + TIME",
             "ADD_DT_TIME": "date and time + TIME", "SUB_TIME": "TIME - TIME",
             "SUB_DATE_DATE": "the TIME between two DATEs", "SUB_TOD_TIME": "time of day - TIME",
             "SUB_TOD_TOD": "the TIME between two times of day",
             "SUB_DT_TIME": "date and time - TIME", "SUB_DT_DT": "the TIME between two DTs",
             "MUL_TIME": "TIME * a number", "DIV_TIME": "TIME / a number",
             "MULTIME": "TIME * a number (the ed.2 name of MUL_TIME, matiec dialect)",
             "DIVTIME": "TIME / a number (the ed.2 name of DIV_TIME, matiec dialect)",
             "CONCAT_DATE_TOD": "a DT from a DATE and a time of day"}

FUNCTION_DOCS: dict[str, str] = {
    "ABS": "Absolute value of IN.",
    "NEG": "IN with its sign changed (-IN).",
    **{n: f"The {what} of IN (a REAL or LREAL)." for n, what in _MATH.items()},
    "TRUNC": "IN rounded towards zero, as a DINT.",
    "ROUND": "IN rounded to the nearest integer, as a DINT.",
    "MOVE": "IN unchanged (OUT := IN); LD and FBD use it to copy a value.",
    "EXPT": "IN1 to the power of IN2.",
    "ATAN2": "The angle of the point (X, Y), in radians (-pi..pi).",
    "ADD": "The sum IN1 + IN2 + ...",
    "MUL": "The product IN1 * IN2 * ...",
    "SUB": "The difference IN1 - IN2.",
    "DIV": "The quotient IN1 / IN2 (integers: truncated; division by zero is a fault).",
    "MOD": "The remainder of IN1 / IN2 (integers).",
    "AND": "Bitwise or Boolean AND of the inputs.",
    "OR": "Bitwise or Boolean OR of the inputs.",
    "XOR": "Bitwise or Boolean exclusive OR of the inputs.",
    "NOT": "Bitwise or Boolean complement of IN.",
    "MIN": "The smallest of the inputs.",
    "MAX": "The largest of the inputs.",
    "LIMIT": "IN clamped to MN..MX.",
    "SEL": "Binary selection: IN0 when G is FALSE, IN1 when G is TRUE.",
    "MUX": "Multiplexer: the input numbered K (IN0, IN1, ...).",
    "SHL": "IN shifted left by N bits (zeros come in).",
    "SHR": "IN shifted right by N bits (zeros come in).",
    "ROL": "IN rotated left by N bits.",
    "ROR": "IN rotated right by N bits.",
    "GT": "TRUE when IN1 > IN2 (> IN3 ...: a decreasing sequence).",
    "GE": "TRUE when IN1 >= IN2 (>= IN3 ...).",
    "EQ": "TRUE when all inputs are equal.",
    "LE": "TRUE when IN1 <= IN2 (<= IN3 ...).",
    "LT": "TRUE when IN1 < IN2 (< IN3 ...: an increasing sequence).",
    "NE": "TRUE when IN1 and IN2 differ.",
    "LEN": "The length of the string IN.",
    "LEFT": "The L leftmost characters of IN.",
    "RIGHT": "The L rightmost characters of IN.",
    "MID": "L characters of IN from position P (the first is 1).",
    "CONCAT": "The strings joined one after the other.",
    "INSERT": "IN2 inserted into IN1 after position P.",
    "DELETE": "IN without the L characters from position P.",
    "REPLACE": "IN1 with L characters from position P replaced by IN2.",
    "FIND": "The position of IN2 in IN1 (1 = first character), 0 when absent.",
    "ASSERT_EQ": "TEST blocks: fails the test unless ACTUAL = EXPECTED.",
    "ASSERT_NE": "TEST blocks: fails the test when ACTUAL = EXPECTED.",
    "ASSERT_TRUE": "TEST blocks: fails the test unless IN is TRUE.",
    "ASSERT_FALSE": "TEST blocks: fails the test unless IN is FALSE.",
    "ASSERT_NEAR": "TEST blocks: fails the test unless |ACTUAL - EXPECTED| <= TOL.",
    "ADVANCE_TIME": "TEST blocks: moves the PLC's clock forward by T (timers see it).",
    "TIME": "CODESYS: the time since the PLC started, as a TIME.",
    **{n: f"The {what}." for n, what in _TIME_FNS.items()},
}

_RESULT = {"float": "ANY_REAL", "to_dint": "DINT", "compare": "BOOL", "number_same": "ANY_NUM",
           "same": "ANY", "arithmetic": "ANY_NUM", "bitwise": "ANY_BIT", "extremum": "ANY",
           "limit": "ANY", "select": "ANY", "multiplex": "ANY", "shift": "ANY_BIT",
           "concat": "STRING", "expt": "ANY_REAL", "atan2": "ANY_REAL",
           "system_time": "TIME"}


def _article(name: str) -> str:
    return "an" if name[:1] in "AEIOLS" and not name.startswith("STRING") else "a"


def function_signature(name: str) -> str | None:
    """``NAME(P1, P2) : RESULT`` of a standard function or conversion, None for another name."""
    name = name.upper()
    b = BUILTINS.get(name)
    if b is not None:
        params = ", ".join(b.params) + (", ..." if b.variadic else "")
        if b.test_only and b.statement_only:
            return f"{name}({params})"
        result = b.result if b.result and b.result != "IN" else _RESULT.get(b.typing, "")
        if b.result == "IN":
            result = "STRING"
        return f"{name}({params})" + (f" : {result}" if result else "")
    conv = conversion(name)
    if conv is not None:
        return f"{name}(IN) : {conv[1]}"
    return None


def function_doc(name: str) -> str | None:
    name = name.upper()
    if name in FUNCTION_DOCS:
        return FUNCTION_DOCS[name]
    if "BCD" in name:
        src, _, dst = name.partition("_TO_")
        if src.endswith("BCD"):
            return f"Reads the BCD digits of IN as {_article(dst)} {dst}."
        width = BUILTINS[name].result if name in BUILTINS else dst
        return f"Writes IN as BCD digits in {_article(width)} {width}."
    conv = conversion(name)
    if conv is None:
        return None
    src, dst = conv
    if src == "__TRUNC__":
        return f"IN truncated towards zero to {_article(str(dst))} {dst}."
    if src is None:
        return f"Converts IN (any elementary type) to {_article(str(dst))} {dst}."
    return f"Converts {_article(src)} {src} to {_article(str(dst))} {dst}."


def type_text(t: A.TypeRef, spellings: dict[str, str] | None = None) -> str:
    """A type as ST text; a STRUCT or an enumeration written out is named by its kind. A named
    type as *spellings* writes it (upper-case name -> as declared: ``Valve``, not ``VALVE``)."""
    if isinstance(t, A.NamedTypeRef) and spellings:
        return spellings.get(t.name.upper(), t.name)
    if isinstance(t, A.StructTypeRef):
        return "STRUCT"
    if isinstance(t, A.EnumTypeRef):
        return "(" + ", ".join(t.spellings.get(m, m) for m, _, _ in t.members) + ")"
    try:
        return type_ref(t)
    except Exception:  # noqa: BLE001 - a type the unparser does not print
        return type(t).__name__.removesuffix("TypeRef").upper()


def pou_signature(pou: A.Pou) -> str:
    """``TON(IN : BOOL, PT : TIME) => (Q : BOOL, ET : TIME)``; a function's result after ``:``."""
    def decls(*sections: str) -> str:
        return ", ".join(f"{d.spelling or d.name} : {type_text(d.type)}"
                         for d in pou.decls if d.section in sections)

    name = pou.spelling or pou.name
    text = f"{pou.kind} {name}({decls('VAR_INPUT', 'VAR_IN_OUT')})"
    if pou.return_type is not None:
        text += f" : {type_text(pou.return_type)}"
    outs = decls("VAR_OUTPUT")
    if outs:
        text += f" => ({outs})"
    return text


_COMMENT_BEFORE = re.compile(r"\(\*((?:(?!\*\)).)*)\*\)\s*(?:\{[^}]*\}\s*)*$", re.S)


def first_sentence(text: str) -> str:
    text = " ".join(text.split())
    m = re.match(r"(.+?\.)(\s|$)", text)
    return m.group(1) if m else text.rstrip(":;") + "."


@cache
def _library_comments(filename: str) -> dict[str, str]:
    """POU name -> the comment right above its declaration in a library file."""
    from ..lang.library import stdlib_text

    try:
        text = stdlib_text(filename)
    except OSError:
        return {}
    out: dict[str, str] = {}
    for m in re.finditer(r"^(FUNCTION_BLOCK|FUNCTION)\s+(\w+)", text, re.M):
        before = _COMMENT_BEFORE.search(text[:m.start()])
        if before and before.end() == m.start():
            out.setdefault(m.group(2).upper(), first_sentence(before.group(1)))
    return out


def block_doc(pou: A.Pou) -> str | None:
    """One line on a library block: its native class's docstring, else its library comment."""
    import inspect

    if pou.native:
        from ..runtime import stdfb

        cls = getattr(stdfb, pou.native, None)
        doc = inspect.getdoc(cls) if cls is not None else None
        if doc:
            return first_sentence(doc)
    file = pou.loc.file.rsplit("/", 1)[-1] if pou.loc else ""
    return _library_comments(file).get(pou.name) if file else None


def describe(name: str) -> tuple[str, str] | None:
    """(signature, one line) of a standard function or conversion named *name*."""
    sig = function_signature(name)
    if sig is None:
        return None
    return sig, function_doc(name) or ""
