"""IL body lines -> :class:`~plclab.lang.lower.il.Instr` (recognising IL, parsing each line).

IL bodies live in ordinary POUs (``PROGRAM``/``FUNCTION``/``FUNCTION_BLOCK``) whose declarations
are parsed by the ST parser; only the body differs. A file may mix ST and IL POUs.

**When is a body IL?** (:func:`is_il_body`) When its first line starts with a label (``L1:``,
alone or before an IL operator), or with an IL operator followed on the same line by its
operand (``LD x``, ``CAL T1``) -- ST never puts an operand directly after a name -- or alone on
its line (``RET``, ``NOT``). In a ``.il`` file every body is IL unless it starts like ST
(``x :=``, ``IF``, ``f(...)``).

The parsed lines are kept as a :class:`~plclab.lang.ast.PendingBody` of kind ``"IL"``; the
translation to statements is :mod:`plclab.lang.lower.il`. The host parser (an ST
:class:`~plclab.lang.frontends.st.Parser`) is passed in: this module does not import it.
"""

from __future__ import annotations

from ...errors import Diagnostic, Location
from .. import ast as A
from ..lexer import Token
from ..lower.il import DEFERRABLE, FB_INPUT_OPS, IL_OPERATORS, Instr
from ..parsing import ParseAbort

_NO_OPERAND = {"NOT", "RET", "RETC", "RETCN", ")"}
_OPERAND_START = {"IDENT", "INT", "REAL", "STRING", "WSTRING", "TIME", "DATE", "TOD", "DT",
                  "TRUE", "FALSE", "ADDR", "ENUMVAL"}
_KEYWORD_OPS = {"AND", "OR", "XOR", "NOT", "MOD"}  # IL operators the ST lexer sees as keywords
_ST_STARTS = {"IF", "CASE", "FOR", "WHILE", "REPEAT", "EXIT", "CONTINUE", "RETURN", ";"}
_BODY_ENDS = {"END_PROGRAM", "END_FUNCTION", "END_FUNCTION_BLOCK", "EOF", "PROGRAM", "FUNCTION",
              "FUNCTION_BLOCK", "TYPE", "VAR_GLOBAL", "CONFIGURATION", "TEST"}


# ---------------------------------------------------------------------------------------------
# Recognising and parsing IL lines


def _op_name(t: Token) -> str | None:
    if t.kind == "IDENT" or t.kind in _KEYWORD_OPS:
        return str(t.value)
    return None


def is_il_body(p, end_kw: str) -> bool:
    """Decide whether the body starting at the parser's position is IL (see module doc)."""
    t = p.tok
    if t.kind in _BODY_ENDS or t.kind == end_kw:
        return False
    nxt = p.peek()
    same_line = nxt.line == t.line and nxt.kind != "EOF"
    if t.kind in _ST_STARTS:
        return False
    name = _op_name(t)
    if name is None:
        return False
    if t.kind == "IDENT" and same_line and nxt.kind in (":=", ".", "[", "(", "^", "=", "=>"):
        return False
    if t.kind == "IDENT" and same_line and nxt.kind == "IDENT" and nxt.value == "REF" and \
            p.peek(2).kind == "=":  # r REF= x; (CODESYS REFERENCE TO) is ST
        return False
    if p.il_default:
        return True
    if t.kind == "IDENT" and same_line and nxt.kind == ":":  # a label, alone or before an op
        after = p.peek(2)
        return after.line != t.line or after.kind == "EOF" or _op_name(after) in IL_OPERATORS
    if name not in IL_OPERATORS:  # keep ST's own diagnostics for misspelled ST (WHILLE x DO)
        return False
    return not same_line or nxt.kind in _OPERAND_START or nxt.kind == "-"


def parse_il_body(p, end_kw: str) -> A.PendingBody:
    """Parse IL lines up to ``end_kw`` (the parser ``p`` stops there); return them as a
    pending body for :mod:`plclab.lang.lower`."""
    instrs: list[Instr] = []
    where = Location(p.file, p.tok.line, p.tok.col)
    toks = p.toks
    while p.tok.kind not in _BODY_ENDS and p.tok.kind != end_kw:
        start = p.i
        line = p.tok.line
        j = start
        while toks[j].line == line and toks[j].kind not in _BODY_ENDS and toks[j].kind != end_kw:
            j += 1
        lt = toks[start:j]
        # parenthesised arguments (CAL T1(IN := x,\n PT := T#5s)) may continue on later lines
        depth = _open_parens(lt)
        while depth > 0 and toks[j].kind not in _BODY_ENDS and toks[j].kind != end_kw:
            line = toks[j].line
            while toks[j].line == line and toks[j].kind not in _BODY_ENDS and \
                    toks[j].kind != end_kw:
                depth += (toks[j].kind == "(") - (toks[j].kind == ")")
                j += 1
            lt = toks[start:j]
        p.i = j
        try:
            _parse_line(p, lt, instrs)
        except ParseAbort:  # the line is dropped; what follows must not complain about the CR
            instrs.append(Instr(Location(p.file, lt[0].line, lt[0].col), "?"))
    return A.PendingBody("IL", instrs, where)


def _open_parens(lt: list[Token]) -> int:
    """Unclosed '(' of an operand (not counting a deferred 'AND(' or a closing ')')."""
    k = 2 if len(lt) > 1 and lt[0].kind == "IDENT" and lt[1].kind == ":" else 0
    if k < len(lt) and lt[k].kind == ")":
        return 0
    k += 1
    if k < len(lt) and lt[k].kind == "(" and _op_name(lt[k - 1]) in DEFERRABLE:
        k += 1
    depth = 0
    for t in lt[k:]:
        depth += (t.kind == "(") - (t.kind == ")")
    return depth


def _source_text(toks: list[Token]) -> str:
    """Tokens of one line back to text (spaces where the source had them)."""
    out = ""
    for k, t in enumerate(toks):
        if k and (t.line != toks[k - 1].line or
                  t.col > toks[k - 1].col + len(toks[k - 1].text)):
            out += " "
        out += t.text
    return out


def _parse_line(p, lt: list[Token], out: list[Instr]) -> None:
    file = p.file

    def loc(t: Token) -> Location:
        return Location(file, t.line, t.col)

    def err(code: str, msg: str, t: Token) -> None:
        p.diagnostics.append(Diagnostic(code, msg, loc(t)))
        raise ParseAbort

    k = 0
    if len(lt) > 1 and lt[0].kind == "IDENT" and lt[1].kind == ":":
        out.append(Instr(loc(lt[0]), "LABEL", lt[0].text, target=str(lt[0].value)))
        k = 2
    if k >= len(lt):
        return
    optok = lt[k]
    rest = lt[k + 1:]
    if rest and rest[-1].kind == ";":  # tolerate a stray ST-style semicolon
        rest = rest[:-1]
    if optok.kind == ")":
        if rest:
            err("PLC0146", f"nothing may follow ')' on its line, found '{rest[0].text}'",
                rest[0])
        out.append(Instr(loc(optok), ")", ")"))
        return
    name = _op_name(optok)
    if name is None:
        hint = ""
        if optok.kind in ("IF", "WHILE", "FOR", "CASE", "REPEAT"):
            hint = " (this looks like ST; an IL body has one operator and operand per line)"
        err("PLC0141", f"expected an IL operator (LD, ST, AND, JMP, CAL, ...), found "
            f"'{optok.text}'{hint}", optok)
    ins = Instr(loc(optok), name, optok.text)
    ins.operand = _source_text(rest[1:] if rest and rest[0].kind == "(" and name in DEFERRABLE
                               else rest)
    if rest and rest[0].kind == "(" and name in DEFERRABLE:
        ins.deferred = True
        rest = rest[1:]
    if rest and rest[0].kind in (":=", "=") and name not in IL_OPERATORS:
        err("PLC0141", f"'{optok.text} {rest[0].text}' is ST, not IL: write  LD value  then  "
            f"ST {optok.text}", optok)
    if name in ("JMP", "JMPC", "JMPCN"):
        if len(rest) != 1 or rest[0].kind != "IDENT":
            err("PLC0146", f"{name} needs a label name, e.g. {name} L1", rest[0] if rest else optok)
        ins.target = str(rest[0].value)
        out.append(ins)
        return
    if name in _NO_OPERAND:
        if rest:
            err("PLC0146", f"{name} takes no operand; remove '{rest[0].text}'", rest[0])
        out.append(ins)
        return
    if not rest:
        if ins.deferred or name not in IL_OPERATORS and name not in FB_INPUT_OPS:
            out.append(ins)  # AND( ... ) or a function of the current result alone (INT_TO_REAL)
            return
        err("PLC0146", f"{name} needs an operand, e.g. {name} x", optok)
    sub = p.over_tokens(rest, p.file, p.diagnostics)  # ends in EOF at the end of the line
    if name in ("CAL", "CALC", "CALCN"):
        e = sub.postfix(sub.primary())
        if not isinstance(e, A.Name | A.Member | A.Index | A.Call):
            err("PLC0146", f"{name} needs a function block instance, e.g. CAL T1(IN := x)",
                rest[0])
        ins.args = [e]
    elif name in IL_OPERATORS or name in FB_INPUT_OPS:
        if rest[0].kind == "(":
            err("PLC0146", f"{name} takes its operand without parentheses: {name} x", rest[0])
        ins.args = [sub.unary()]
    else:  # a function call: the current result is the first argument
        if rest[0].kind == "(":
            err("PLC0146", f"write the function call as  {name} arg2, arg3  (the current result "
                "is the first argument); the formal form F(...) is not supported in IL",
                rest[0])
        ins.args = [sub.expr()]
        while sub.accept(","):
            ins.args.append(sub.expr())
    if not sub.at("EOF"):
        t = sub.tok
        err("PLC0146", f"unexpected '{t.text}' after the operand of {name}: one operand per "
            "line (use a comma between function arguments)", t)
    out.append(ins)
