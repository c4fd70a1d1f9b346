"""Instruction List (IEC 61131-3 IL) front end: IL bodies -> the shared AST.

IL bodies live in ordinary POUs (``PROGRAM``/``FUNCTION``/``FUNCTION_BLOCK``) whose declarations
are parsed by the ST parser; only the body differs. A file may mix ST and IL POUs.

**When is a body IL?** (:func:`is_il_body`) When its first line starts with a label (``L1:``,
alone or before an IL operator), or with an IL operator followed on the same line by its
operand (``LD x``, ``CAL T1``) -- ST never puts an operand directly after a name -- or alone on
its line (``RET``, ``NOT``). In a ``.il`` file every body is IL unless it starts like ST
(``x :=``, ``IF``, ``f(...)``).

**Translation.** IL works on a *current result* (CR). The translator keeps the CR as an ST
expression and emits plain statements: ``LD x / MUL A / ADD B / ST Y`` becomes
``Y := x * A + B;``. Labels and jumps become :class:`~plclab.lang.ast.Label` and
:class:`~plclab.lang.ast.Jump` (the compiler turns them into a state machine). Where the CR
must survive a store, a label or a jump it is kept in a hidden ``VAR_TEMP`` named
``__CR_<TYPE>`` (one per type). The CR type is tracked from the operand of ``LD`` and checked
(``PLC0140``); the checker and the compiler do the rest.

>>> from plclab.lang.st_parser import parse_st
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

import difflib
from dataclasses import dataclass, field
from functools import cache
from typing import Any

from ..errors import Diagnostic, Location
from . import ast as A
from . import types as T
from .builtins import BUILTINS, conversion
from .lexer import Token
from .limits import compiler_guard

IL_OPERATORS = (
    "LD", "LDN", "ST", "STN", "S", "R", "AND", "ANDN", "OR", "ORN", "XOR", "XORN", "NOT",
    "ADD", "SUB", "MUL", "DIV", "MOD", "GT", "GE", "EQ", "NE", "LE", "LT",
    "JMP", "JMPC", "JMPCN", "CAL", "CALC", "CALCN", "RET", "RETC", "RETCN",
)
# IEC "FB input operators": LD x / IN T1 sets T1.IN := x and calls T1
FB_INPUT_OPS = ("S1", "R1", "CLK", "CU", "CD", "PV", "IN", "PT")
_BIN = {"AND": "AND", "OR": "OR", "XOR": "XOR", "ADD": "+", "SUB": "-", "MUL": "*", "DIV": "/",
        "MOD": "MOD", "GT": ">", "GE": ">=", "EQ": "=", "NE": "<>", "LE": "<=", "LT": "<"}
_NEGATABLE = {"ANDN": "AND", "ORN": "OR", "XORN": "XOR"}
DEFERRABLE = set(_BIN) | set(_NEGATABLE)
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
    if p.il_default:
        return True
    if t.kind == "IDENT" and same_line and nxt.kind == ":":  # a label, alone or before an op
        after = p.peek(2)
        return after.line != t.line or after.kind == "EOF" or _op_name(after) in IL_OPERATORS
    if name not in IL_OPERATORS:  # keep ST's own diagnostics for misspelled ST (WHILLE x DO)
        return False
    return not same_line or nxt.kind in _OPERAND_START or nxt.kind == "-"


@dataclass(eq=False)
class Instr:
    """One IL instruction (or a label: ``op == 'LABEL'``)."""

    loc: Location
    op: str  # upper-case operator, "LABEL" or ")"
    text: str = ""  # the operator as written
    deferred: bool = False  # AND( ... )
    args: list[A.Expr] = field(default_factory=list)
    target: str | None = None  # jump target / label name
    operand: str = ""  # the operand(s) as written, for messages


def parse_il_body(p, end_kw: str):
    """Parse IL lines up to ``end_kw``; return the lowering function ``lower(pou, env)``."""
    from .st_parser import _Bail

    instrs: list[Instr] = []
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
        except _Bail:  # the line is dropped; what follows must not complain about the CR
            instrs.append(Instr(Location(p.file, lt[0].line, lt[0].col), "?"))
    return lambda pou, env: _Lowering(pou, instrs, env, p.file).run()


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


def _sub_parser(p, toks: list[Token]):
    """A parser over the tokens of one instruction, ending in EOF at the end of the line."""
    from .st_parser import Parser

    sub = Parser.__new__(Parser)
    last = toks[-1] if toks else p.tok
    sub.toks = list(toks) + [Token("EOF", None, "", last.line, last.col + len(last.text))]
    sub.diagnostics = p.diagnostics
    sub.pragmas = []
    sub.file = p.file
    sub.i = 0
    sub.il_default = False
    return sub


def _parse_line(p, lt: list[Token], out: list[Instr]) -> None:
    from .st_parser import _Bail

    file = p.file

    def loc(t: Token) -> Location:
        return Location(file, t.line, t.col)

    def err(code: str, msg: str, t: Token) -> None:
        p.diagnostics.append(Diagnostic(code, msg, loc(t)))
        raise _Bail

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
    sub = _sub_parser(p, rest)
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


def parse_il_collect(text: str, file: str = "<input>.il",
                     defer: bool = False) -> tuple[A.SourceFile, list[Diagnostic]]:
    """Parse a file whose POU bodies are IL by default (like a ``.il`` file)."""
    from .st_parser import Parser

    p = Parser(text, file)
    p.il_default = True
    out = p.parse_file()
    diags = p.diagnostics
    if not defer:
        diags = diags + lower_pending([out])
    return out, diags


# ---------------------------------------------------------------------------------------------
# Types known before the checker runs (the front ends need a few: IL's current result, the
# power-flow pins of ladder boxes)


@cache
def _stdlib_files() -> tuple[A.SourceFile, ...]:
    from ..project import STDLIB_FILES, _stdlib_text
    from .st_parser import Parser

    return tuple(Parser(_stdlib_text(n), f"<plclab>/{n}").parse_file() for n in STDLIB_FILES)


class Env:
    """Declarations of every parsed file, for the front ends' own type questions.

    Types are :mod:`plclab.lang.types` objects for elementary types and strings, or tuples
    ``("FB", pou)``, ``("STRUCT", fields)``, ``("ARRAY", elem_ref)``, ``("ENUM", name)``;
    ``None`` means unknown (the checker will say more)."""

    def __init__(self, files: list[A.SourceFile]) -> None:
        files = list(files)
        if not any(p.name == "TON" for f in files for p in f.pous):
            files.extend(_stdlib_files())
        self.types = {td.name: td for f in files for td in f.types}
        self.pous = {p.name: p for f in files for p in f.pous}
        self.globals = {d.name: d for f in files for g in f.globals for d in g.decls}
        for f in files:
            for c in f.configs:
                for d in c.globals:
                    self.globals.setdefault(d.name, d)
        self.enum_values: dict[str, str] = {}
        for td in self.types.values():
            if isinstance(td.type, A.EnumTypeRef):
                for m, _, _ in td.type.members:
                    self.enum_values.setdefault(m, td.name)

    def type_of_ref(self, r: A.TypeRef | None, depth: int = 0) -> Any:
        if r is None or depth > 20:
            return None
        if isinstance(r, A.StringTypeRef):
            return T.WSTRING if r.wide else T.STRING
        if isinstance(r, A.SubrangeTypeRef):
            return self.type_of_ref(r.base, depth + 1)
        if isinstance(r, A.ArrayTypeRef):
            return ("ARRAY", r.elem)
        if isinstance(r, A.StructTypeRef):
            return ("STRUCT", {d.name: d for d in r.fields})
        if isinstance(r, A.EnumTypeRef):
            return ("ENUM", "")
        if isinstance(r, A.NamedTypeRef):
            t = T.lookup_elementary(r.name)
            if t is not None:
                return t
            td = self.types.get(r.name)
            if td is not None:
                inner = self.type_of_ref(td.type, depth + 1)
                if isinstance(inner, tuple) and inner[0] == "ENUM":
                    return ("ENUM", td.name)
                return inner
            pou = self.pous.get(r.name)
            if pou is not None and pou.kind != "FUNCTION":
                return ("FB", pou)
        return None

    def function(self, name: str) -> A.Pou | None:
        p = self.pous.get(name)
        return p if p is not None and p.kind == "FUNCTION" else None

    def is_function(self, name: str) -> bool:
        return name in BUILTINS or conversion(name) is not None or self.function(name) is not None

    def lookup(self, name: str, scope: dict[str, A.VarDecl]) -> A.VarDecl | None:
        d = scope.get(name)
        if d is not None and d.section == "VAR_EXTERNAL":
            return self.globals.get(name, d)
        return d if d is not None else self.globals.get(name)

    def expr_type(self, e: A.Expr, scope: dict[str, A.VarDecl], pou: A.Pou | None = None) -> Any:
        if isinstance(e, A.Literal):
            if e.kind == "BOOL":
                return T.BOOL
            if e.kind in ("INT", "REAL"):
                if e.prefix:
                    return T.lookup_elementary(e.prefix) or self.type_of_ref(
                        A.NamedTypeRef(e.loc, e.prefix))
                return T.ANY_INT_LIT if e.kind == "INT" else T.ANY_REAL_LIT
            if e.kind == "TIME":
                return T.LTIME if e.prefix == "LTIME" else T.TIME
            if e.kind in ("STRING", "WSTRING"):
                return T.STRING if e.kind == "STRING" else T.WSTRING
            if e.kind in ("DATE", "TOD", "DT"):
                return {"DATE": T.DATE, "TOD": T.TOD, "DT": T.DT}[e.kind]
            if e.kind == "ENUM":
                return ("ENUM", e.value[0])
            return None
        if isinstance(e, A.Name):
            d = self.lookup(e.name, scope)
            if d is not None:
                return self.type_of_ref(d.type)
            if pou is not None and pou.kind == "FUNCTION" and e.name == pou.name:
                return self.type_of_ref(pou.return_type)
            if e.name in self.enum_values:
                return ("ENUM", self.enum_values[e.name])
            p = self.pous.get(e.name)
            if p is not None and p.kind == "PROGRAM":
                return ("FB", p)
            return None
        if isinstance(e, A.Member):
            if e.field_name.startswith("%"):
                return T.BOOL
            ot = self.expr_type(e.obj, scope, pou)
            if isinstance(ot, tuple) and ot[0] == "FB":
                d = next((d for d in ot[1].decls if d.name == e.field_name), None)
                return self.type_of_ref(d.type) if d is not None else None
            if isinstance(ot, tuple) and ot[0] == "STRUCT":
                d = ot[1].get(e.field_name)
                return self.type_of_ref(d.type) if d is not None else None
            return None
        if isinstance(e, A.Index):
            ot = self.expr_type(e.obj, scope, pou)
            if isinstance(ot, tuple) and ot[0] == "ARRAY":
                return self.type_of_ref(ot[1])
            return None
        if isinstance(e, A.DirectAddr):
            a = e.address
            size = a[2] if len(a) > 2 and a[2].isalpha() else "X"
            return {"X": T.BOOL, "B": T.BYTE, "W": T.WORD, "D": T.DWORD, "L": T.LWORD}.get(size)
        if isinstance(e, A.Unary):
            return self.expr_type(e.operand, scope, pou)
        return None

    def decl_of(self, e: A.Expr, scope: dict[str, A.VarDecl]) -> A.VarDecl | None:
        if isinstance(e, A.Name):
            return self.lookup(e.name, scope)
        return None


def category(t: Any) -> str | None:
    """BOOL, INT, BITS, REAL, TIME, STRING, DATE, ENUM, FB, STRUCT, ARRAY or None (unknown)."""
    if t is None:
        return None
    if isinstance(t, tuple):
        return t[0]
    if isinstance(t, T.StringType):
        return "STRING"
    return {"bool": "BOOL", "int": "INT", "bits": "BITS", "real": "REAL", "time": "TIME",
            "date": "DATE", "tod": "DATE", "dt": "DATE"}.get(getattr(t, "kind", ""), None)


def type_text(t: Any) -> str:
    if t is None:
        return "unknown"
    if t is T.ANY_INT_LIT:
        return "an integer literal"
    if t is T.ANY_REAL_LIT:
        return "a REAL literal"
    if isinstance(t, tuple):
        if t[0] == "FB":
            return f"a {t[1].name} instance"
        if t[0] == "ENUM":
            return t[1] or "an enumeration"
        return {"STRUCT": "a structure", "ARRAY": "an array"}[t[0]]
    return str(getattr(t, "name", t))


_NUM = {"INT", "BITS", "REAL"}


def lower_pending(files: list[A.SourceFile]) -> list[Diagnostic]:
    """Run the pending translations (IL bodies, ladder networks, PLCopen graphics) of ``files``
    with every declaration known; return their diagnostics."""
    env = Env(files)
    diags: list[Diagnostic] = []
    with compiler_guard():  # translations recurse once per nesting level (see limits)
        for f in files:
            for pou in f.pous:
                fn = pou.__dict__.pop("_lower", None)
                if fn is not None:
                    diags.extend(fn(env))
    return diags


# ---------------------------------------------------------------------------------------------
# IL -> AST


class _Lowering:
    def __init__(self, pou: A.Pou, instrs: list[Instr], env: Env, file: str) -> None:
        self.pou = pou
        self.ins = instrs
        self.env = env
        self.file = file
        self.scope = {d.name: d for d in pou.decls}
        self.diags: list[Diagnostic] = []
        self.out: list[A.Stmt] = []
        self.cr: A.Expr | None = None
        self.cty: Any = None
        self.csrc: Instr | None = None
        self.why_undefined = "at the start of the body"
        self.stack: list[tuple[str, bool, A.Expr | None, Any, Instr | None, Instr]] = []
        self.temps: dict[str, A.VarDecl] = {}
        self.labels = {x.target: k for k, x in enumerate(instrs) if x.op == "LABEL"}
        self.label_ty: dict[str, tuple[str, Instr]] = {}  # label -> (temp type name, source)
        self.label_undef: dict[str, Instr] = {}
        self.reachable = True

    # -- helpers ----------------------------------------------------------------------------
    def err(self, code: str, msg: str, loc: Location, severity: str = "error") -> None:
        self.diags.append(Diagnostic(code, msg, loc, severity))

    def typeof(self, e: A.Expr) -> Any:
        return self.env.expr_type(e, self.scope, self.pou)

    def cr_from(self) -> str:
        s = self.csrc
        if s is None:
            return ""
        if s.op == ")":
            return f" (from the ')' at line {s.loc.line})"
        what = f"{s.text} {s.operand}" if s.operand else s.text
        return f" (from {what} at line {s.loc.line})"

    def need_cr(self, x: Instr) -> bool:
        if self.cr is None:
            if self.why_undefined is None:  # after an error: say nothing more
                return False
            self.err("PLC0144", f"{x.text} needs a current result, but none is loaded "
                     f"{self.why_undefined}; load a value first with LD", x.loc)
            return False
        return True

    def set_cr(self, e: A.Expr | None, ty: Any, src: Instr | None) -> None:
        self.cr, self.cty, self.csrc = e, ty, src

    def undefine(self, why: str | None) -> None:
        self.set_cr(None, None, None)
        self.why_undefined = why

    def emit(self, s: A.Stmt) -> None:
        self.out.append(s)

    def temp(self, ty: Any, loc: Location) -> A.VarDecl | None:
        if ty is T.ANY_INT_LIT:
            ty = T.DINT
        elif ty is T.ANY_REAL_LIT:
            ty = T.LREAL
        if isinstance(ty, tuple) and ty[0] == "ENUM" and ty[1]:
            tname = ty[1]
        elif isinstance(ty, T.Elementary):
            tname = ty.name
        elif ty is T.STRING or ty is T.WSTRING:
            tname = "WSTRING" if ty.wide else "STRING"
        else:
            return None
        d = self.temps.get(tname)
        if d is None:
            tref: A.TypeRef = (A.StringTypeRef(loc, tname == "WSTRING") if "STRING" in tname
                               else A.NamedTypeRef(loc, tname))
            d = A.VarDecl(loc, f"__CR_{tname}", tref, section="VAR_TEMP",
                          spelling=f"current result ({tname})")
            d.used = True
            self.temps[tname] = d
        return d

    def is_temp(self, e: A.Expr | None) -> bool:
        return isinstance(e, A.Name) and e.name.startswith("__CR_")

    def materialize(self, x: Instr) -> bool:
        """Keep the CR in its hidden variable (so later stores cannot change it)."""
        if self.cr is None or isinstance(self.cr, A.Literal) or self.is_temp(self.cr):
            return True
        d = self.temp(self.cty, x.loc)
        if d is None:
            return False
        self.emit(A.Assign(x.loc, A.Name(x.loc, d.name), self.cr))
        self.cr = A.Name(x.loc, d.name)
        return True

    def uses_cr(self, j: int, seen: set[str] | None = None) -> bool:
        """Does the code from instruction ``j`` on read the CR before replacing it?"""
        seen = set() if seen is None else seen
        while j < len(self.ins):
            x = self.ins[j]
            if x.op == "LABEL":
                j += 1
                continue
            if x.op in ("LD", "LDN", "CAL", "RET"):
                return False
            if x.op == "JMP":
                t = x.target
                if t in seen or t not in self.labels:
                    return False
                seen.add(t)
                j = self.labels[t]
                continue
            return True
        return False

    def live_after(self, k: int) -> bool:
        return self.uses_cr(k + 1)

    def check_input(self, target: A.Expr, x: Instr) -> None:
        if isinstance(target, A.DirectAddr) and target.address.startswith("%I"):
            self.err("PLC0142", f"{x.text} {target.address}: {target.address} is a physical "
                     "input; a program reads inputs but never writes them", x.loc)
            return
        d = self.env.decl_of(target, self.scope)
        if d is None:
            return
        if d.address and d.address.startswith("%I"):
            self.err("PLC0142", f"{x.text} {x.operand}: {d.spelling or d.name} is the "
                     f"physical input {d.address}; a program reads inputs but never writes "
                     "them", x.loc)
        elif d.section == "VAR_INPUT" and d in self.pou.decls:
            self.err("PLC0142", f"{x.text} {x.operand}: {d.spelling or d.name} is an input "
                     f"of {self.pou.spelling or self.pou.name}; the caller sets it on every call. "
                     "Store into a local variable (VAR) or an output instead", x.loc)

    def mismatch(self, x: Instr, what: str) -> None:
        self.err("PLC0140", f"{x.text}{' ' + x.operand if x.operand else ''}: the current "
                 f"result is {type_text(self.cty)}{self.cr_from()}, {what}", x.loc)

    # -- driver -----------------------------------------------------------------------------
    def run(self) -> list[Diagnostic]:
        for k, x in enumerate(self.ins):
            op = x.op
            if op == "LABEL":
                self.label(k, x)
                continue
            if op == "?":  # a line with a syntax error
                self.undefine(None)
                continue
            if self.stack and op in ("JMP", "JMPC", "JMPCN", "CAL", "CALC", "CALCN", "RET",
                                     "RETC", "RETCN"):
                self.err("PLC0143", f"{x.text} is not allowed inside the parentheses of "
                         f"{self.stack[-1][5].text}( opened at line {self.stack[-1][5].loc.line};"
                         " close them with ')' first", x.loc)
                continue
            self.reachable = True
            if op in ("LD", "LDN"):
                self.op_ld(x)
            elif op in ("ST", "STN"):
                self.op_st(k, x)
            elif op in ("S", "R"):
                self.op_sr(k, x)
            elif op == "NOT":
                if self.need_cr(x):
                    if category(self.cty) not in ("BOOL", "BITS", "INT", None):
                        self.mismatch(x, "but NOT needs a BOOL or a bit string")
                    self.set_cr(A.Unary(x.loc, "NOT", self.cr), self.cty, x)
            elif op in DEFERRABLE:
                self.op_binary(x)
            elif op == ")":
                self.op_close(x)
            elif op in ("JMP", "JMPC", "JMPCN"):
                self.op_jump(k, x)
            elif op in ("CAL", "CALC", "CALCN"):
                self.op_cal(x)
            elif op in ("RET", "RETC", "RETCN"):
                self.op_ret(x)
            elif op in FB_INPUT_OPS and self.fb_operand(x):
                self.op_fb_input(x)
            else:
                self.op_function(x)
        for entry in self.stack:
            o = entry[5]
            self.err("PLC0143", f"the '(' of {o.text}( at line {o.loc.line} is never closed; "
                     "add a line with ')'", o.loc)
        self.pou.body = self.out
        self.pou.decls.extend(self.temps.values())
        return self.diags

    # -- operators --------------------------------------------------------------------------
    def op_ld(self, x: Instr) -> None:
        e = x.args[0]
        ty = self.typeof(e)
        if x.op == "LDN":
            if category(ty) not in ("BOOL", "BITS", None):
                self.err("PLC0140", f"LDN {x.operand}: LDN loads the negation of a BOOL or a bit "
                         f"string, but {x.operand} is {type_text(ty)}; use LD", x.loc)
            e = A.Unary(x.loc, "NOT", e)
        self.set_cr(e, ty, x)

    def op_st(self, k: int, x: Instr) -> None:
        if not self.need_cr(x):
            return
        target = x.args[0]
        if not isinstance(target, A.Name | A.Member | A.Index | A.DirectAddr):
            self.err("PLC0146", f"{x.text} needs a variable to store into, not "
                     f"'{x.operand}'", x.loc)
            return
        self.check_input(target, x)
        tty = self.typeof(target)
        a, b = category(self.cty), category(tty)
        if x.op == "STN" and a not in ("BOOL", "BITS", None):
            self.mismatch(x, "but STN stores its negation, which needs a BOOL or a bit string")
        elif a is not None and b is not None and not _storable(a, b, self.cty, tty):
            self.mismatch(x, f"but {x.operand} is {type_text(tty)}"
                          + _conv_hint(self.cty, tty))
        live = self.live_after(k)
        kept = True
        if live:
            kept = self.materialize(x)
        value = A.copy_expr(self.cr)
        if x.op == "STN":
            value = A.Unary(x.loc, "NOT", value)
        self.emit(A.Assign(x.loc, target, value))
        if live and not kept:  # type unknown: the stored variable now holds the CR
            self.cr = A.copy_expr(target)
            if x.op == "STN":
                self.cr = A.Unary(x.loc, "NOT", self.cr)

    def op_sr(self, k: int, x: Instr) -> None:
        if not self.need_cr(x):
            return
        target = x.args[0]
        if not isinstance(target, A.Name | A.Member | A.Index | A.DirectAddr):
            self.err("PLC0146", f"{x.text} needs a BOOL variable, not '{x.operand}'", x.loc)
            return
        self.check_input(target, x)
        if category(self.cty) not in ("BOOL", None):
            self.mismatch(x, f"but {x.op} {'sets' if x.op == 'S' else 'resets'} its operand "
                          "only when the current result is a BOOL TRUE")
            return
        tty = self.typeof(target)
        if category(tty) not in ("BOOL", None):
            self.err("PLC0140", f"{x.text} {x.operand}: {x.operand} is "
                     f"{type_text(tty)}; S and R work on BOOL variables", x.loc)
            return
        if self.live_after(k):
            self.materialize(x)
        self.emit(A.Assign(x.loc, target, A.copy_expr(self.cr), "S=" if x.op == "S" else "R="))

    def combine(self, x: Instr, op: str, neg: bool, left: A.Expr, lty: Any,
                right: A.Expr, rty: Any, loc: Location, rtext: str) -> tuple[A.Expr, Any]:
        a, b = category(lty), category(rty)
        sym = _BIN[op]
        if neg:
            if b not in ("BOOL", "BITS", "INT", None):
                self.mismatch(x, f"and {op}N negates {rtext}, which is {type_text(rty)}")
            right = A.Unary(loc, "NOT", right)
        result: Any = None
        bad = None
        if op in ("AND", "OR", "XOR"):
            if a == "BOOL" or b == "BOOL":
                result = T.BOOL
                if None not in (a, b) and a != b:
                    bad = f"but {op} combines it with {rtext}, which is {type_text(rty)}"
                    if a != "BOOL":
                        bad = f"but {op} {rtext} needs a BOOL current result"
            elif None not in (a, b) and not (a in ("BITS", "INT") and b in ("BITS", "INT")):
                bad = f"but {op} needs BOOLs or bit strings, and {rtext} is {type_text(rty)}"
            else:
                result = _common(lty, rty)
        elif op in ("ADD", "SUB", "MUL", "DIV", "MOD"):
            if a is not None and a not in _NUM | {"TIME"}:
                bad = f"but {op} needs a number{' or a TIME' if op != 'MOD' else ''}"
            elif None not in (a, b):
                ok = (a in _NUM and b in _NUM) or (a == "TIME" and b == "TIME" and op in (
                    "ADD", "SUB")) or (a == "TIME" and b in ("INT", "REAL") and op in (
                        "MUL", "DIV"))
                if op == "MOD" and (a == "REAL" or b == "REAL"):
                    ok = False
                if not ok:
                    bad = f"and {op} cannot combine it with {rtext}, which is {type_text(rty)}"
            result = lty if a == "TIME" else _common(lty, rty)
        else:  # comparisons
            result = T.BOOL
            if None not in (a, b) and a != b and not (a in _NUM and b in _NUM):
                bad = f"and {op} cannot compare it with {rtext}, which is {type_text(rty)}"
        if bad:
            self.mismatch(x, bad)
            result = None
        return A.Binary(loc, sym, left, right), result

    def op_binary(self, x: Instr) -> None:
        op = _NEGATABLE.get(x.op, x.op)
        neg = x.op in _NEGATABLE
        if x.deferred:
            if not self.need_cr(x):
                return
            self.stack.append((op, neg, self.cr, self.cty, self.csrc, x))
            if x.args:
                self.set_cr(x.args[0], self.typeof(x.args[0]), x)
            else:
                self.undefine(f"after {x.text}( at line {x.loc.line} (load the inner value "
                              "with LD, or write it after the parenthesis)")
            return
        if not self.need_cr(x):
            return
        e, ty = self.combine(x, op, neg, self.cr, self.cty, x.args[0], self.typeof(x.args[0]),
                             x.loc, x.operand)
        self.set_cr(e, ty, x)

    def op_close(self, x: Instr) -> None:
        if not self.stack:
            self.err("PLC0143", "')' closes nothing: there is no open deferred operation such "
                     "as AND( or ADD( before it", x.loc)
            return
        op, neg, left, lty, lsrc, opener = self.stack.pop()
        if not self.need_cr(x):
            return
        inner, ity = self.cr, self.cty
        self.set_cr(left, lty, lsrc)
        e, ty = self.combine(opener, op, neg, left, lty, inner, ity, opener.loc,
                             f"the value in its parentheses ({type_text(ity)})")
        self.set_cr(e, ty, x)

    def carry(self, label: str, x: Instr) -> None:
        """The CR flows into ``label`` (a jump or falling through): keep it in a temp."""
        if label not in self.labels or not self.uses_cr(self.labels[label] + 1):
            return
        if self.cr is None:
            self.label_undef.setdefault(label, x)
            return
        d = self.temp(self.cty, x.loc)
        if d is None:
            self.err("PLC0147", f"the current result{self.cr_from()} is "
                     f"{type_text(self.cty)} and cannot be carried to label {label}; load the "
                     f"value again with LD after {label}:", x.loc)
            return
        tname = d.name[5:]
        prev = self.label_ty.get(label)
        if prev is not None and prev[0] != tname:
            self.err("PLC0147", f"the current result reaching label {label} is {tname} here but "
                     f"{prev[0]} from line {prev[1].loc.line}; load the value with LD after "
                     f"{label}:", x.loc)
            return
        self.label_ty.setdefault(label, (tname, x))
        if not (isinstance(self.cr, A.Name) and self.cr.name == d.name):
            self.emit(A.Assign(x.loc, A.Name(x.loc, d.name), self.cr))
            self.cr = A.Name(x.loc, d.name)

    def label(self, k: int, x: Instr) -> None:
        name = x.target or ""
        if self.stack:
            self.err("PLC0143", f"label {name} inside the parentheses of "
                     f"{self.stack[-1][5].text}( (line {self.stack[-1][5].loc.line}); close them "
                     "with ')' before the label", x.loc)
        if self.reachable:
            self.carry(name, x)
        self.emit(A.Label(x.loc, name))
        self.reachable = True
        lt = self.label_ty.get(name)
        if name in self.label_undef or lt is None or not self.uses_cr(k + 1):
            src = self.label_undef.get(name)
            self.undefine(f"after label {name}" + (
                f" (the jump at line {src.loc.line} brings none)" if src is not None else ""))
            return
        d = self.temps[lt[0]]
        self.set_cr(A.Name(x.loc, d.name), self.type_of_temp(lt[0]), x)

    def type_of_temp(self, tname: str) -> Any:
        t = T.lookup_elementary(tname)
        if t is not None:
            return t
        return ("ENUM", tname)

    def op_jump(self, k: int, x: Instr) -> None:
        label = x.target or ""
        cond = None
        if x.op != "JMP":
            if not self.need_cr(x):
                return
            if category(self.cty) not in ("BOOL", None):
                self.mismatch(x, f"but {x.op} jumps only on a BOOL current result; compare "
                              "first, e.g. GT 0")
                return
        if label in self.labels:
            if self.labels[label] < k and self.cr is None and self.uses_cr(self.labels[label] + 1)\
                    and self.label_ty.get(label) is not None:
                self.err("PLC0144", f"{x.text} {label}: the code after {label} uses the current "
                         f"result, but none is loaded {self.why_undefined}", x.loc)
            self.carry(label, x)
        if x.op != "JMP":
            cond = A.copy_expr(self.cr)
            if x.op == "JMPCN":
                cond = A.Unary(x.loc, "NOT", cond)
        self.emit(A.Jump(x.loc, label, cond))
        if x.op == "JMP":
            self.undefine("after an unconditional JMP")
            self.reachable = False

    def op_cal(self, x: Instr) -> None:
        e = x.args[0]
        call = e if isinstance(e, A.Call) else A.Call(e.loc, e, [])
        stmt: A.Stmt = A.CallStmt(x.loc, call)
        if x.op != "CAL":
            if not self.need_cr(x):
                return
            if category(self.cty) not in ("BOOL", None):
                self.mismatch(x, f"but {x.op} calls only on a BOOL current result")
                return
            cond = A.copy_expr(self.cr)
            if x.op == "CALCN":
                cond = A.Unary(x.loc, "NOT", cond)
            stmt = A.If(x.loc, [(cond, [stmt])])
        self.emit(stmt)
        self.undefine(f"after {x.text} (a call leaves no current result; read the outputs "
                      "with LD inst.Q)")

    def op_ret(self, x: Instr) -> None:
        if x.op == "RET":
            self.emit(A.Return(x.loc))
            self.undefine("after RET")
            self.reachable = False
            return
        if not self.need_cr(x):
            return
        if category(self.cty) not in ("BOOL", None):
            self.mismatch(x, f"but {x.op} returns only on a BOOL current result")
            return
        cond = A.copy_expr(self.cr)
        if x.op == "RETCN":
            cond = A.Unary(x.loc, "NOT", cond)
        self.emit(A.If(x.loc, [(cond, [A.Return(x.loc)])]))

    def fb_operand(self, x: Instr) -> bool:
        t = self.typeof(x.args[0]) if x.args else None
        return isinstance(t, tuple) and t[0] == "FB" and len(x.args) == 1

    def op_fb_input(self, x: Instr) -> None:
        if not self.need_cr(x):
            return
        inst = x.args[0]
        self.emit(A.CallStmt(x.loc, A.Call(inst.loc, inst, [A.Arg(x.loc, x.op,
                                                                   A.copy_expr(self.cr))])))

    def op_function(self, x: Instr) -> None:
        name = x.op
        if not self.env.is_function(name):
            cands = list(IL_OPERATORS) + list(FB_INPUT_OPS)
            close = difflib.get_close_matches(name, cands, n=1, cutoff=0.6)
            if not close:
                funcs = list(BUILTINS) + [k for k, v in self.env.pous.items()
                                          if v.kind == "FUNCTION"]
                close = difflib.get_close_matches(name, funcs, n=1, cutoff=0.7)
            hint = f"; did you mean {close[0]}?" if close else (
                " (IL operators: LD, ST, S, R, AND, OR, XOR, NOT, ADD, SUB, MUL, DIV, MOD, GT, "
                "GE, EQ, NE, LE, LT, JMP, CAL, RET and their N/C forms)")
            self.err("PLC0141", f"unknown operator {x.text}: it is neither an IL operator nor a "
                     f"function{hint}", x.loc)
            self.undefine(None)
            return
        if not self.need_cr(x):
            return
        args = [A.Arg(x.loc, None, self.cr)] + [A.Arg(a.loc, None, a) for a in x.args]
        call = A.Call(x.loc, A.Name(x.loc, name), args)
        self.set_cr(call, self.function_type(name, [self.cty] + [self.typeof(a)
                                                                for a in x.args]), x)

    def function_type(self, name: str, tys: list[Any]) -> Any:
        conv = conversion(name)
        if conv is not None and name not in BUILTINS:
            return conv[1]
        f = self.env.function(name)
        if f is not None:
            return self.env.type_of_ref(f.return_type)
        if name in ("GT", "GE", "EQ", "NE", "LE", "LT"):
            return T.BOOL
        if name in ("LEN", "FIND"):
            return T.INT
        if name in ("TRUNC", "ROUND"):
            return T.DINT
        if name in ("SEL", "MUX"):
            return tys[1] if len(tys) > 1 else None
        if name in ("ABS", "NEG", "MOVE", "LIMIT", "MIN", "MAX", "ADD", "MUL", "SUB", "DIV",
                    "MOD", "SHL", "SHR", "ROL", "ROR", "LEFT", "RIGHT", "MID", "INSERT",
                    "DELETE", "REPLACE", "CONCAT"):
            return tys[0]
        return None


def _storable(a: str, b: str, src: Any, dst: Any) -> bool:
    if a in _NUM and b in _NUM:
        return True
    if a == "ENUM" and b == "ENUM":
        return not (src[1] and dst[1]) or src[1] == dst[1]
    return a == b


def _conv_hint(src: Any, dst: Any) -> str:
    s, d = category(src), category(dst)
    if s in _NUM | {"BOOL", "TIME"} and d in _NUM | {"BOOL", "TIME"} and isinstance(
            dst, T.Elementary):
        sname = "DINT" if src is T.ANY_INT_LIT else "LREAL" if src is T.ANY_REAL_LIT else \
            getattr(src, "name", "?")
        return f"; convert it first, e.g. {sname}_TO_{dst.name}"
    return ""


def _common(a: Any, b: Any) -> Any:
    if isinstance(a, T.Type) and isinstance(b, T.Type):
        try:
            return T.common_type(a, b) or a
        except Exception:  # noqa: BLE001 - unknown combinations stay unknown
            return None
    return a if b is None else None
