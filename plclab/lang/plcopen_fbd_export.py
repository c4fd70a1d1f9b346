"""ST bodies drawn as PLCopen FBD networks (``plclab export --fbd``): one network a statement,
operators as standard blocks (chains of one operator as one extensible block), ``NOT x`` as a
negated pin, ``IF c THEN x := e`` and set/reset assignments as MOVE enabled by EN, an
``executionOrderId`` on every element (the statements' order). ADR 0022."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import fields

from . import ast as A
from .plcopen_elements import call_pins, connect, hide, sub
from .unparse import expr as st_expr

BLOCK_OF = {"AND": "AND", "OR": "OR", "XOR": "XOR", "+": "ADD", "-": "SUB", "*": "MUL",
            "/": "DIV", "MOD": "MOD", "**": "EXPT", "=": "EQ", "<>": "NE", "<": "LT",
            "<=": "LE", ">": "GT", ">=": "GE"}
_EXTENSIBLE = {"AND", "OR", "XOR", "ADD", "MUL"}
ROW = 60  # vertical distance between elements of a drawn network
COL = 140  # horizontal distance between the columns of a network


def fb_types_of(p: A.Pou) -> dict[str, str]:
    """Instance name -> function block type, for the declared instances of ``p``."""
    return {d.name: d.type.name for d in p.decls if isinstance(d.type, A.NamedTypeRef)}


def fbd_exportable(body: list[A.Stmt], fb_types: dict[str, str],
                   user_inputs: dict[str, list[str]]) -> bool:
    """True when every statement is an assignment or a call of a declared function block
    instance with named parameters (with expressions a network can draw)."""
    u = user_inputs
    return bool(body) and all(
        (isinstance(s, A.Assign) and _drawable(s.value, u)) or _conditional(s, u) or
        (isinstance(s, A.CallStmt) and isinstance(s.call.func, A.Name) and
         s.call.func.name in fb_types and
         all(a.name is not None and (a.value is None or _drawable(a.value, u))
             for a in s.call.args))
        for s in body)


def _conditional(s: A.Stmt, user_inputs: dict[str, list[str]]) -> bool:
    """``IF c THEN x := e; ... END_IF`` (one branch, assignments not writing what ``c`` reads):
    drawn as MOVE blocks enabled by ``c``."""
    if not (isinstance(s, A.If) and len(s.branches) == 1 and not s.orelse):
        return False
    cond, body = s.branches[0]
    read = {n.name for n in _names(cond)}
    return _drawable(cond, user_inputs) and bool(body) and all(
        isinstance(a, A.Assign) and a.op == ":=" and _drawable(a.value, user_inputs) and
        not ({n.name for n in _names(a.target)} & read) for a in body)


def _names(e: A.Expr) -> list[A.Name]:
    out, stack = [], [e]
    while stack:
        x = stack.pop()
        if isinstance(x, A.Name):
            out.append(x)
        for v in (getattr(x, f.name) for f in fields(x)):
            if isinstance(v, A.Expr):
                stack.append(v)
            elif isinstance(v, list):
                stack += [i.value if isinstance(i, A.Arg) else i for i in v
                          if isinstance(i, A.Expr | A.Arg) and
                          (not isinstance(i, A.Arg) or i.value is not None)]
    return out


def _drawable(e: A.Expr, user_inputs: dict[str, list[str]]) -> bool:
    stack = [e]
    while stack:
        x = stack.pop()
        if isinstance(x, A.Binary):
            if x.op not in BLOCK_OF:
                return False
            stack += [x.left, x.right]
        elif isinstance(x, A.Unary):
            stack.append(x.operand)
        elif isinstance(x, A.Call):
            if not isinstance(x.func, A.Name) or any(a.output for a in x.args) or \
                    call_pins(x, user_inputs) is None:
                return False
            stack += [a.value for a in x.args if a.value is not None]
        elif not isinstance(x, A.Name | A.Literal | A.Member | A.DirectAddr | A.Index):
            return False
    return True


class FbdWriter:
    """One FBD network a statement, drawn right to left from the assigned variable."""

    def __init__(self, holder: ET.Element, fb_types: dict[str, str],
                 user_inputs: dict[str, list[str]]) -> None:
        self.holder = holder
        self.fb_types = fb_types
        self.user_inputs = user_inputs
        self.next_id = 0
        self.order = 0
        self.y = 20

    def new_id(self) -> str:
        self.next_id += 1
        return str(self.next_id)

    def element(self, tag: str, x: float, y: float, **attrs: str) -> ET.Element:
        self.order += 1
        el = sub(self.holder, tag, localId=self.new_id(), executionOrderId=str(self.order),
                  height="30", width="100", **attrs)
        sub(el, "position", x=str(int(x)), y=str(int(y)))
        return el

    def statements(self, body: list[A.Stmt]) -> None:
        for s in body:
            top = self.y
            if isinstance(s, A.Assign):
                self.assign(s)
            elif isinstance(s, A.If):
                self.conditional(s)
            else:
                self.fb_call(s)  # type: ignore[arg-type]
            self.y = max(self.y, top + ROW) + ROW // 2

    # values -> (localId, output pin or None); negated leaves are reported for pin negation
    def value(self, e: A.Expr, x: float, y: float) -> tuple[str, str | None]:
        if isinstance(e, A.Binary) and e.op in BLOCK_OF:
            kind = BLOCK_OF[e.op]
            ops = _flatten(e, e.op) if kind in _EXTENSIBLE else [e.left, e.right]
            return self.block(kind, ops, x, y), "OUT"
        if isinstance(e, A.Unary) and e.op == "NOT":
            return self.block("NOT", [e.operand], x, y), "OUT"
        if isinstance(e, A.Unary) and e.op == "-":
            return self.block("NEG", [e.operand], x, y), "OUT"
        if isinstance(e, A.Call):
            return self.block(st_expr(e.func), [a.value for a in e.args], x, y,
                              call_pins(e, self.user_inputs)), "OUT"
        el = self.element("inVariable", x, y, negated="false")
        sub(el, "connectionPointOut")
        sub(el, "expression").text = hide(st_expr(e))
        return el.get("localId") or "", None

    def block(self, kind: str, operands: list, x: float, y: float,
              pins: list[str] | None = None) -> str:
        names = pins or ([f"IN{i + 1}" for i in range(len(operands))] if kind not in ("NOT", "NEG")
                         else ["IN"])
        wired = []
        for i, (pin, op) in enumerate(zip(names, operands, strict=True)):
            negated = isinstance(op, A.Unary) and op.op == "NOT" and not isinstance(
                op.operand, A.Binary | A.Unary | A.Call) and kind != "NOT"
            src = self.value(op.operand if negated else op, x - COL, y + i * ROW)
            self.y = max(self.y, y + i * ROW)
            wired.append((pin, src, negated))
        el = self.element("block", x, y, typeName=kind)
        ins = sub(el, "inputVariables")
        for pin, (ref, out), negated in wired:
            v = sub(ins, "variable", formalParameter=pin, **(
                {"negated": "true"} if negated else {}))
            connect(sub(v, "connectionPointIn"), ref, out)
        sub(el, "inOutVariables")
        outs = sub(el, "outputVariables")
        sub(sub(outs, "variable", formalParameter="OUT"), "connectionPointOut")
        return el.get("localId") or ""

    def assign(self, s: A.Assign) -> None:
        x = 200 + COL * _depth(s.value)
        top = self.y
        if s.op in ("S=", "R="):  # set/reset: MOVE TRUE/FALSE enabled by the condition
            cond = self.value(s.value, x - COL, self.y)
            lit = self.value(A.Literal(s.loc, s.op == "S=", "BOOL", None,
                                       "TRUE" if s.op == "S=" else "FALSE"), x - COL,
                             self.y + ROW)
            src: tuple[str, str | None] = self.enabled_move(x, self.y, cond, lit)
            self.y += ROW
        else:
            src = self.value(s.value, x - COL, self.y)
        self.out_variable(s.target, src, x + 40, top)

    def conditional(self, s: A.If) -> None:
        """One MOVE a assignment, each enabled by the shared condition."""
        cond_e, body = s.branches[0]
        cond = self.value(cond_e, 200, self.y)
        for a in body:
            x = 200 + COL * (_depth(a.value) + 1)
            top = self.y
            val = self.value(a.value, x - COL, self.y)
            self.out_variable(a.target, self.enabled_move(x, top, cond, val), x + COL, top)
            self.y = max(self.y, top) + ROW

    def enabled_move(self, x: float, y: float, en: tuple, value: tuple) -> tuple[str, str]:
        """A MOVE block at (x, y) whose EN and IN are wired to ``en`` and ``value``; the
        connection to its OUT."""
        el = self.element("block", x, y, typeName="MOVE")
        ins = sub(el, "inputVariables")
        connect(sub(sub(ins, "variable", formalParameter="EN"), "connectionPointIn"), *en)
        connect(sub(sub(ins, "variable", formalParameter="IN"), "connectionPointIn"), *value)
        sub(el, "inOutVariables")
        outs = sub(el, "outputVariables")
        for pin in ("ENO", "OUT"):
            sub(sub(outs, "variable", formalParameter=pin), "connectionPointOut")
        return el.get("localId") or "", "OUT"

    def out_variable(self, target: A.Expr, src: tuple[str, str | None], x: float,
                     y: float) -> None:
        el = self.element("outVariable", x, y, negated="false")
        connect(sub(el, "connectionPointIn"), *src)
        sub(el, "expression").text = hide(st_expr(target))

    def fb_call(self, s: A.CallStmt) -> None:
        call = s.call
        ins = [a for a in call.args if not a.output]
        outs = [a for a in call.args if a.output and a.value is not None]
        x = 200 + COL * max((_depth(a.value) for a in ins if a.value is not None), default=0)
        y = self.y
        wired = [(a.name or "", self.value(a.value, x - COL, y + i * ROW))
                 for i, a in enumerate(ins) if a.value is not None]
        type_name = self.fb_types[call.func.name]  # type: ignore[attr-defined]
        el = self.element("block", x, y, typeName=type_name,
                          instanceName=hide(st_expr(call.func)))
        iv = sub(el, "inputVariables")
        for pin, (ref, out) in wired:
            connect(sub(sub(iv, "variable", formalParameter=pin), "connectionPointIn"),
                     ref, out)
        sub(el, "inOutVariables")
        ov = sub(el, "outputVariables")
        for a in outs:
            sub(sub(ov, "variable", formalParameter=a.name or "",
                      **({"negated": "true"} if a.negated else {})), "connectionPointOut")
        bid = el.get("localId") or ""
        for i, a in enumerate(outs):
            self.out_variable(a.value, (bid, a.name), x + COL, y + i * ROW)
        self.y = max(self.y, y + ROW * max(len(ins), len(outs), 1))


def _flatten(e: A.Expr, op: str) -> list[A.Expr]:
    """``a AND b AND c`` -> [a, b, c] (an extensible block with three inputs)."""
    out: list[A.Expr] = []
    stack = [e]
    while stack:
        x = stack.pop()
        if isinstance(x, A.Binary) and x.op == op:
            stack += [x.right, x.left]
        else:
            out.append(x)
    return out


def _depth(e: A.Expr) -> int:
    """How many block columns the drawing of ``e`` needs."""
    if isinstance(e, A.Binary):
        return 1 + max(_depth(x) for x in _flatten(e, e.op))
    if isinstance(e, A.Unary):
        return (1 + _depth(e.operand)) if isinstance(e.operand, A.Binary | A.Unary | A.Call) \
            else 1
    if isinstance(e, A.Call):
        return 1 + max((_depth(a.value) for a in e.args if a.value is not None), default=0)
    return 1
