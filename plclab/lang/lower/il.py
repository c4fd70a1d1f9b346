"""IL bodies -> the core AST: the current result (CR) becomes expressions and statements.

IL works on a *current result*. The translator keeps the CR as an ST expression and emits plain
statements: ``LD x / MUL A / ADD B / ST Y`` becomes ``Y := x * A + B;``. Labels and jumps become
:class:`~plclab.lang.ast.Label` and :class:`~plclab.lang.ast.Jump` (the compiler turns them into
a state machine). Where the CR must survive a store, a label or a jump it is kept in a hidden
``VAR_TEMP`` named ``__CR_<TYPE>`` (one per type). The CR type is tracked from the operand of
``LD`` and checked (``PLC0140``) through :class:`~plclab.lang.lower.types.LoweringTypes`; the
checker and the compiler do the rest.

The instructions come from :mod:`plclab.lang.frontends.il` (or a PLCopen ``<IL>`` body) as a
:class:`~plclab.lang.ast.PendingBody` of kind ``"IL"`` holding a list of :class:`Instr`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from ...errors import Diagnostic, Location
from ...suggest import suggest
from .. import ast as A
from .. import types as T
from ..builtins import BUILTINS, FB_INPUT_OPS, conversion
from .types import LoweringTypes, category, enum_name, enum_type, type_text

IL_OPERATORS = (
    "LD", "LDN", "ST", "STN", "S", "R", "AND", "ANDN", "OR", "ORN", "XOR", "XORN", "NOT",
    "ADD", "SUB", "MUL", "DIV", "MOD", "GT", "GE", "EQ", "NE", "LE", "LT",
    "JMP", "JMPC", "JMPCN", "CAL", "CALC", "CALCN", "RET", "RETC", "RETCN",
)
# IEC "FB input operators": LD x / IN T1 sets T1.IN := x and calls T1
_BIN = {"AND": "AND", "OR": "OR", "XOR": "XOR", "ADD": "+", "SUB": "-", "MUL": "*", "DIV": "/",
        "MOD": "MOD", "GT": ">", "GE": ">=", "EQ": "=", "NE": "<>", "LE": "<=", "LT": "<"}
_NEGATABLE = {"ANDN": "AND", "ORN": "OR", "XORN": "XOR"}
DEFERRABLE = set(_BIN) | set(_NEGATABLE)


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



def lower_il(pou: A.Pou, instrs: list[Instr], types: LoweringTypes) -> list[Diagnostic]:
    """Translate IL instructions into ``pou.body`` (and hidden ``__CR_*`` declarations)."""
    return _Lowering(pou, instrs, types).run()


_NUM = {"INT", "BITS", "REAL"}


class _Lowering:
    def __init__(self, pou: A.Pou, instrs: list[Instr], types: LoweringTypes) -> None:
        self.pou = pou
        self.ins = instrs
        self.types = types
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
        self.label_lit: dict[str, list] = {}
        self.pos = {id(x): k for k, x in enumerate(instrs)}  # label -> literals carried ahead, type unknown
        self.reachable = True

    # -- helpers ----------------------------------------------------------------------------
    def err(self, code: str, msg: str, loc: Location, severity: str = "error") -> None:
        self.diags.append(Diagnostic(code, msg, loc, severity))

    def typeof(self, e: A.Expr) -> Any:
        return self.types.expr_type(e, self.pou)

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
        if enum_name(ty) is not None:
            tname = enum_name(ty)
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
        d = self.types.decl_of(target, self.pou)
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
            if op in ("S", "R", "LD") and self.fb_operand(x):  # S1 SR1 / R SR1 / LD CTD1:
                self.op_fb_input(x)  # the FB input operators that share an IL name (Table 53)
            elif op in ("LD", "LDN"):
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
    def bool_literal(self) -> bool:
        """``LD 0`` / ``LD 1`` used as a BOOL (stored into one, S/R, carried to a label a BOOL
        reaches): the literal is typed by its context, as ST accepts ``b := 1`` (ADR 0053)."""
        cr = self.cr
        if self.cty is T.ANY_INT_LIT and isinstance(cr, A.Literal) and cr.kind == "INT" and \
                cr.value in (0, 1):
            self.set_cr(A.Literal(cr.loc, cr.value == 1, "BOOL", None, cr.text), T.BOOL,
                        self.csrc)
            return True
        return False

    def literal_fits(self, tname: str) -> bool:
        """The CR is a literal that takes the type ``tname`` of another path into a label."""
        if not isinstance(self.cr, A.Literal) or self.cty not in (T.ANY_INT_LIT,
                                                                  T.ANY_REAL_LIT):
            return False
        ty = self.type_of_temp(tname)
        cat = category(ty)
        if cat == "BOOL":
            return self.bool_literal()
        if self.cty is T.ANY_REAL_LIT:
            return cat == "REAL"
        return cat in _NUM

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
        if category(tty) == "BOOL":
            self.bool_literal()
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
        self.bool_literal()
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
        prev = self.label_ty.get(label)
        if prev is not None and self.literal_fits(prev[0]):
            d = self.temps[prev[0]]  # LD 0 reaching a label an INT reaches: an INT 0
            self.emit(A.Assign(x.loc, A.Name(x.loc, d.name), self.cr))
            self.cr = A.Name(x.loc, d.name)
            return
        if prev is None and self.labels[label] > self.pos.get(id(x), -1) and \
                isinstance(self.cr, A.Literal) and self.cty in (T.ANY_INT_LIT, T.ANY_REAL_LIT):
            # a literal reaching a label ahead: typed by the other paths, known later
            st = A.Assign(x.loc, A.Name(x.loc, "__CR_?"), A.copy_expr(self.cr))
            self.emit(st)
            self.label_lit.setdefault(label, []).append((st, self.cr, self.cty, self.csrc, x))
            return
        d = self.temp(self.cty, x.loc)
        if d is None:
            self.err("PLC0147", f"the current result{self.cr_from()} is "
                     f"{type_text(self.cty)} and cannot be carried to label {label}; load the "
                     f"value again with LD after {label}:", x.loc)
            return
        tname = d.name[5:]
        if prev is None and label in self.label_lit:
            self.settle_literals(label, tname, x)
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

    def settle_literals(self, label: str, tname: str | None, x: Instr) -> None:
        """Give the literals carried ahead to ``label`` the type ``tname`` of another path
        (None: no other path, their own type: DINT or LREAL)."""
        saved = (self.cr, self.cty, self.csrc)
        for st, lit, lty, src, jx in self.label_lit.pop(label, []):
            self.set_cr(lit, lty, src)
            want = tname
            if want is None or not self.literal_fits(want):
                d = self.temp(lty, jx.loc)
                want = d.name[5:] if d is not None else want
            if want is not None and want not in self.temps:
                self.temp(self.type_of_temp(want), jx.loc)
            st.target.name = f"__CR_{want}"
            st.value = A.copy_expr(self.cr)  # a BOOL literal where 0/1 became one
            prev = self.label_ty.get(label)
            if prev is not None and prev[0] != want:
                self.err("PLC0147", f"the current result reaching label {label} is {want} "
                         f"here but {prev[0]} from line {prev[1].loc.line}; load the value "
                         f"with LD after {label}:", jx.loc)
            self.label_ty.setdefault(label, (want or "", jx))
        self.set_cr(*saved)

    def label(self, k: int, x: Instr) -> None:
        name = x.target or ""
        if self.stack:
            self.err("PLC0143", f"label {name} inside the parentheses of "
                     f"{self.stack[-1][5].text}( (line {self.stack[-1][5].loc.line}); close them "
                     "with ')' before the label", x.loc)
        if self.reachable:
            self.carry(name, x)
        if name in self.label_lit:  # only literals reach it: they keep their own type
            self.settle_literals(name, None, x)
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
        return enum_type(tname)

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
        return self.types.fb_of(t) is not None and len(x.args) == 1

    def op_fb_input(self, x: Instr) -> None:
        if not self.need_cr(x):
            return
        inst = x.args[0]
        self.emit(A.CallStmt(x.loc, A.Call(inst.loc, inst, [A.Arg(x.loc, x.op,
                                                                   A.copy_expr(self.cr))])))

    def op_function(self, x: Instr) -> None:
        name = x.op
        if not self.types.is_function(name):
            cands = list(IL_OPERATORS) + list(FB_INPUT_OPS)
            close = suggest(name, cands, n=1, cutoff=0.6)
            if not close:
                close = suggest(name, self.types.function_names(), n=1,
                                                  cutoff=0.7)
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
        f = self.types.pou(name)
        if f is not None and f.kind == "FUNCTION":
            return self.types.type_of(f.return_type)
        spec = BUILTINS.get(name)
        rule = spec.typing if spec is not None else ""
        if rule == "compare":
            return T.BOOL
        if rule == "to_dint":
            return T.DINT
        if rule == "signature" and spec.result != "IN":
            return T.lookup_elementary(spec.result)
        if rule in ("select", "multiplex"):  # the type of the inputs after the selector
            return tys[1] if len(tys) > 1 else None
        if rule in ("number_same", "same", "limit", "extremum", "arithmetic", "shift",
                    "signature", "concat"):
            return tys[0]
        return None


def _storable(a: str, b: str, src: Any, dst: Any) -> bool:
    if a in _NUM and b in _NUM:
        return True
    if a == "ENUM" and b == "ENUM":
        return not (enum_name(src) and enum_name(dst)) or enum_name(src) == enum_name(dst)
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

