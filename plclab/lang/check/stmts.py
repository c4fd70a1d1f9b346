"""Pass: statements -- POU and TEST bodies, conditions, CASE labels, FOR loops, jumps and
labels, unreachable code, unused variables (PLC0108, PLC0113-PLC0115, PLC0119, PLC0145,
PLC0190, PLC0191, PLC0200, PLC0201)."""

from __future__ import annotations

from typing import Any

from ...errors import Location
from .. import ast as A
from .. import types as T
from ..limits import MAX_BLOCK_NESTING, MAX_EXPR_NESTING, nesting_violation, too_deep_message
from ..walk import NodeVisitor
from .pass_api import Pass
from .symbols import EnumSym, Scope, VarSym, close_hint


class Statements(Pass, NodeVisitor):
    """Checks bodies statement by statement (``visit_<Statement>``)."""

    def check_pou_body(self, p: A.Pou) -> None:
        self.cx.pou = p
        self.cx.scope = self.table.scope(p)
        self.cx.call_graph.setdefault(p.name, set())
        self.checked_body(p.body, p.loc)
        self.cx.oop.check_local_refs(p.body)
        self.check_labels(p.body)
        if p.kind == "FUNCTION" and p.native is None and p.return_type is not None:
            assigned = any(
                isinstance(s, A.Assign) and isinstance(s.target, A.Name) and s.target.name == p.name
                for s in A.walk_stmts(p.body)
            )
            if not assigned:
                self.warn("PLC0119", f"function {p.spelling or p.name} never assigns its result; "
                          f"add  {p.spelling or p.name} := ...;  (it returns the default value)",
                          p.loc)
        if p.native is None:
            for d in p.decls:
                if d.section in ("VAR", "VAR_TEMP") and not d.used and not d.address:
                    self.warn("PLC0200", f"variable {d.spelling or d.name} is declared but never "
                              "used; remove it or use it", d.loc)
        self.cx.pou = None
        self.cx.scope = Scope()

    def check_labels(self, body: list[A.Stmt]) -> None:
        """Jumps and labels (IL): labels unique, targets known, both at the top of the body."""
        labels: dict[str, A.Label] = {}
        for s in body:
            if isinstance(s, A.Label):
                if s.name in labels:
                    self.err("PLC0101", f"label {s.name} is defined twice (first at line "
                             f"{labels[s.name].loc.line}); rename one of them", s.loc)
                labels.setdefault(s.name, s)
        top = {id(s) for s in body}
        for s in A.walk_stmts(body):
            if isinstance(s, A.Label | A.Jump) and id(s) not in top:
                self.err("PLC0145", "jumps and labels must be at the top level of the body, "
                         "not inside IF, CASE or a loop", s.loc)
            elif isinstance(s, A.Jump) and s.label not in labels:
                self.err("PLC0145", f"jump to unknown label {s.label}" +
                         (close_hint(s.label, labels) or
                          (f" (labels: {', '.join(labels)})" if labels else
                           "; define it with  " + s.label + ":  at the start of a line")), s.loc)

    def check_test(self, t: A.TestBlock) -> None:
        self.cx.in_test = True
        scope = Scope()
        for d in t.decls:
            self.cx.decls.decl_type(d)
            if d.name in scope:
                self.err("PLC0101", f"variable {d.name} is declared twice in the test", d.loc)
            scope.declare(d.name, VarSym(d, "local", None))
        self.cx.scope = scope
        for d in t.decls:
            self.cx.decls.check_init(d, scope)
            if isinstance(d.type, A.NamedTypeRef) and d.type.args is not None:
                self.cx.decls.bind_fb_init(d, d.type)  # a : FB(k := 3)
        self.checked_body(t.body, t.loc)
        self.cx.oop.check_local_refs(t.body)
        self.cx.scope = Scope()
        self.cx.in_test = False

    def checked_body(self, stmts: list[A.Stmt], loc: Location) -> None:
        """Check a POU or TEST body whose nesting is within the limits (else PLC0190: the
        checker and the compiler recurse once per nesting level)."""
        bad = nesting_violation(stmts)
        if bad is not None:
            what, where = bad
            limit = MAX_BLOCK_NESTING if what == "blocks" else MAX_EXPR_NESTING
            self.err("PLC0190", too_deep_message(what, limit), where or loc)
            return
        self.cx.stmt_loc = loc
        try:
            self.body(stmts)
        except RecursionError:  # a safety net: the limits above should prevent it
            self.cx.loop_depth = 0
            self.err("PLC0191", "this part of the program is too large or too deeply nested to "
                     "check; split it into smaller parts (FUNCTIONs, intermediate variables)",
                     self.cx.stmt_loc)

    def body(self, stmts: list[A.Stmt]) -> None:
        returned = None
        for s in stmts:
            if isinstance(s, A.Label):  # a jump may land here: reachable again
                returned = None
            if returned is not None and not isinstance(s, A.Empty):
                self.warn("PLC0201", "this code is never executed: it follows a RETURN at line "
                          f"{returned.loc.line}; remove it or make the RETURN conditional", s.loc)
                returned = None
            self.stmt(s)
            if isinstance(s, A.Return | A.Exit | A.Continue):
                returned = s

    def stmt(self, s: A.Stmt) -> None:
        self.cx.stmt_loc = s.loc
        self.visit(s)

    # one visit_<Class> per statement class (an unknown class raises UnhandledNode)
    def visit_Assign(self, s: A.Assign) -> None:
        tt = self.cx.exprs.lvalue(s.target)
        vt = self.cx.exprs.expr(s.value, tt)
        if s.op == ":=":
            self.cx.exprs.check_assignable(vt, tt, s.value, s.loc)
        elif s.op == "REF=":  # left when the target is no REFERENCE TO (lower.reference_to)
            from ..unparse import expr

            name = expr(s.target)
            fix = (f"write {name} := REF({expr(s.value)}); for a {tt}"
                   if isinstance(T.resolve(tt), T.RefType) else
                   f"declare {name} : REFERENCE TO {vt} (codesys dialect), or assign a value "
                   f"with {name} := {expr(s.value)};")
            self.err("PLC0244", f"REF= binds a REFERENCE TO, but {name} is {tt}; {fix}", s.loc)
        else:
            self.cond_type(vt, s.value, "set/reset coil")

    def visit_CallStmt(self, s: A.CallStmt) -> None:
        self.cx.calls.call(s.call, statement=True)

    def visit_If(self, s: A.If) -> None:
        for cond, body in s.branches:
            self.cond_type(self.cx.exprs.expr(cond, T.BOOL), cond, "IF")
            self.body(body)
        if s.orelse is not None:
            self.body(s.orelse)

    def visit_Case(self, s: A.Case) -> None:
        self.case(s)

    def visit_For(self, s: A.For) -> None:
        self.for_stmt(s)

    def visit_While(self, s: A.While) -> None:
        self.cond_type(self.cx.exprs.expr(s.cond, T.BOOL), s.cond, "WHILE")
        self.loop_body(s.body)

    def visit_Repeat(self, s: A.Repeat) -> None:
        self.loop_body(s.body)
        self.cond_type(self.cx.exprs.expr(s.cond, T.BOOL), s.cond, "UNTIL")

    def visit_Exit(self, s: A.Exit | A.Continue) -> None:
        if self.cx.loop_depth == 0:
            kw = "EXIT" if isinstance(s, A.Exit) else "CONTINUE"
            self.err("PLC0114", f"{kw} is only allowed inside FOR, WHILE or REPEAT", s.loc)

    visit_Continue = visit_Exit

    def visit_Jump(self, s: A.Jump) -> None:
        if s.cond is not None:
            self.cond_type(self.cx.exprs.expr(s.cond, T.BOOL), s.cond, "jump")

    def visit_Return(self, s: A.Stmt) -> None:
        """RETURN, an empty statement, a label: nothing to check here (see :meth:`body` and
        :meth:`check_labels`)."""

    visit_Empty = visit_Label = visit_Return

    def loop_body(self, body: list[A.Stmt]) -> None:
        self.cx.loop_depth += 1
        self.body(body)
        self.cx.loop_depth -= 1

    def cond_type(self, t: T.Type, e: A.Expr, where: str) -> None:
        t = T.resolve(t)
        if t is not T.BOOL and t is not T.ANY:
            hint = ""
            if isinstance(e, A.Binary) and e.op in ("AND", "OR") or t.kind in ("int", "bits"):
                hint = " (compare it, e.g. x <> 0, or check the operator precedence: AND/OR " \
                       "bind weaker than comparisons)"
            self.err("PLC0108", f"the {where} condition must be BOOL, not {t}{hint}", e.loc)

    def case(self, s: A.Case) -> None:
        st = T.resolve(self.cx.exprs.expr(s.selector, None))
        if st is not T.ANY and st.kind not in ("int", "bits", "enum"):
            self.err("PLC0115", f"CASE needs an integer or enumeration selector, not {st}",
                     s.selector.loc)
        seen: dict[Any, Location] = {}
        for b in s.branches:
            for lab in b.labels:
                los = [lab] if not isinstance(lab, tuple) else list(lab)
                vals = []
                for le in los:
                    lt = self.cx.exprs.expr(le, st)
                    v = self.label_value(le)
                    if v is None:
                        self.err("PLC0115", "a CASE label must be a constant (a literal, a "
                                 "constant or an enumeration value)", le.loc)
                    elif not T.can_widen(lt, st) and T.common_type(lt, st) is None:
                        self.err("PLC0115", f"CASE label of type {lt} does not match the "
                                 f"selector type {st}", le.loc)
                    vals.append(v)
                if None in vals:
                    continue
                keys = [vals[0]] if len(vals) == 1 else [("range", vals[0], vals[1])]
                for k in keys:
                    if k in seen:
                        self.err("PLC0115", f"CASE label {k} appears twice (first at line "
                                 f"{seen[k].line})", b.loc)
                    seen[k] = b.loc
            self.body(b.body)
        if s.orelse is not None:
            self.body(s.orelse)

    def label_value(self, e: A.Expr) -> Any:
        if isinstance(e, A.Literal) and e.kind == "ENUM":
            return e.enum_value
        if isinstance(e, A.Name | A.Member) and isinstance(e.sym, EnumSym):
            return e.sym.value  # Red, or Color.Red as CODESYS qualifies it
        return self.cx.consts.const_value(e)

    def for_stmt(self, s: A.For) -> None:
        vt = self.cx.exprs.lvalue(s.var)
        sym = s.var.sym
        if isinstance(sym, A.Pou):  # a bare PROPERTY name (ADR 0039): a GET and a SET
            self.err("PLC0113", f"the FOR variable must be a variable, and "
                     f"{s.var.text or s.var.name} is a PROPERTY; count with a local variable",
                     s.var.loc)
        elif T.resolve(vt).kind not in ("int", "any") and not self.cx.exprs.bits_accepted(
                vt, "a FOR counter", s.var.loc):
            self.err("PLC0113", f"the FOR variable must be an integer, not {vt}", s.var.loc)
        for e in (s.start, s.end) + ((s.step,) if s.step else ()):
            et = self.cx.exprs.expr(e, vt)
            if T.resolve(et).kind not in ("int", "any") and not (
                    T.resolve(et).kind == "bits" and T.resolve(vt).kind == "bits" and
                    self.cx.dialect(e.loc).bit_arithmetic):
                self.err("PLC0113", f"FOR bounds and step must be integers, not {et}", e.loc)
        if s.step is not None:
            v = self.cx.consts.const_value(s.step)
            if v == 0:
                self.err("PLC0113", "FOR step BY 0 never ends; use a step other than 0",
                         s.step.loc)
        if isinstance(sym, VarSym):
            for inner in A.walk_stmts(s.body):
                if isinstance(inner, A.Assign) and isinstance(inner.target, A.Name) and \
                        inner.target.name == s.var.name:
                    self.err("PLC0113", f"do not assign the FOR variable {s.var.name} inside the "
                             "loop; use a WHILE loop or EXIT instead", inner.loc)
        self.loop_body(s.body)
