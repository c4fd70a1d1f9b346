"""LD and FBD networks -> the core AST, shared by the text ladder front end
(:mod:`plclab.lang.frontends.ld`) and the PLCopen LD/FBD graphics
(:mod:`plclab.lang.frontends.plcopen`).

A network is a small graph of :class:`Elem` (contacts, coils, boxes, variables, connectors)
joined by references to the outputs of other elements. It arrives as a
:class:`~plclab.lang.ast.PendingBody` of kind ``"NETWORK"`` and becomes statements: coils are
assignments (``S=``/``R=`` for set/reset coils), power flow is a BOOL expression, boxes are
calls. Rungs run top to bottom, elements left to right (the order each front end gives).
"""

from __future__ import annotations

import copy
from dataclasses import dataclass, field
from typing import Any

from ...errors import Diagnostic, Location
from .. import ast as A
from .types import LoweringTypes

COMPARE = {"GT": ">", "GE": ">=", "EQ": "=", "NE": "<>", "LE": "<=", "LT": "<"}

Ref = tuple[int, str]  # (element id, output pin; "" = its power-flow output)


@dataclass(eq=False)
class Elem:
    """One element of a ladder or FBD network (text or XML)."""

    id: int
    kind: str  # left contact coil fb func cmp invar outvar conn (XML connector/continuation)
    loc: Location
    order: tuple = ()
    inputs: dict[str, list[Ref]] = field(default_factory=dict)  # pin -> refs ("" = power in)
    var: A.Expr | None = None  # contact/coil variable; in/out variable expression
    mode: str = ""  # contact "", "/", "P", "N"; coil "", "/", "S", "R", "P", "N"
    type_name: str = ""  # box type: TON, GT, MOVE, ADD, a user FB or function
    instance: A.Expr | None = None
    args: list[A.Arg] = field(default_factory=list)  # parameters written in a text box
    targets: list[A.Expr] = field(default_factory=list)  # text function box: '-> x'
    out_pin: str = ""  # XML: the output pin of a function block ("OUT")
    rung: int = 0
    text: str = ""  # as written, for messages and drawings
    geom: Any = None  # text: (line, col0, col1); XML: (x, y, w, h)
    neg_in: set[str] = field(default_factory=set)  # XML: negated input pins of a box
    neg_out: set[str] = field(default_factory=set)  # XML: negated output pins of a box
    edge_in: dict[str, str] = field(default_factory=dict)  # XML: input pin -> "P" rising / "N"
    inout_pins: set[str] = field(default_factory=set)  # XML: VAR_IN_OUT pins of a box
    outs: list[str] = field(default_factory=list)  # XML: the output pins of a box, in order
    label: str = ""  # XML: the label of a jump or label element
    explicit_order: bool = False  # XML: executionOrderId given (else the topological rule)


def _true(loc: Location) -> A.Literal:
    return A.Literal(loc, True, "BOOL", None, "TRUE")


def _is_true(e: A.Expr) -> bool:
    return isinstance(e, A.Literal) and e.kind == "BOOL" and e.value is True


def _and(loc: Location, a: A.Expr, b: A.Expr) -> A.Expr:
    if _is_true(a):
        return b
    if _is_true(b):
        return a
    return A.Binary(loc, "AND", a, b)


def _or(loc: Location, items: list[A.Expr]) -> A.Expr:
    if not items:
        return A.Literal(loc, False, "BOOL", None, "FALSE")
    if any(_is_true(x) for x in items):
        return _true(loc)
    out = items[0]
    for x in items[1:]:
        out = A.Binary(loc, "OR", out, x)
    return out


def _simple(e: A.Expr) -> bool:
    return isinstance(e, A.Name | A.Literal | A.Member | A.DirectAddr)


_CHAIN = 32  # series elements lowered into one expression before a temporary splits it


class _NetLowering:
    def __init__(self, pou: A.Pou, elems: list[Elem], types: LoweringTypes) -> None:
        self.pou = pou
        self.types = types
        self.diags: list[Diagnostic] = []
        self.decls: list[A.VarDecl] = []
        self.n = 0
        elems = self.cut_feedback(elems)
        self.elems = {e.id: e for e in elems}
        self.order = execution_order(elems)
        self.out: list[A.Stmt] = []
        self.memo: dict[Ref, A.Expr] = {}
        self.uses: dict[Ref, int] = {}
        self.conds: dict[int, A.Expr] = {}
        self.pins: dict[int, tuple[str, str]] = {}
        self.edges: dict[tuple[int, str], A.Expr] = {}  # (box, input pin) -> its edge pulse
        self.nesting = 0
        for e in elems:
            for refs in e.inputs.values():
                for ref in refs:
                    self.uses[ref] = self.uses.get(ref, 0) + 1

    def err(self, code: str, msg: str, loc: Location) -> None:
        self.diags.append(Diagnostic(code, msg, loc))

    def cut_feedback(self, elems: list[Elem]) -> list[Elem]:
        """Break each feedback loop at the wire :func:`plan_feedback` chooses: the consumer
        reads the value of the previous evaluation (a new in-variable element), held by the
        feedback variable, the function block's output, or a hidden BOOL written at the end
        of the network (ADR 0053)."""
        cuts, stuck = plan_feedback(elems)
        if stuck is not None:
            return elems  # the front end refused the network (PLC0330)
        elems = list(elems)
        by_id = {e.id: e for e in elems}
        held: dict[Ref, A.Expr] = {}
        last = max((e.order for e in elems), default=())
        for cid, pin, k, how, var in cuts:
            c = by_id[cid]
            src = c.inputs[pin][k]
            s = by_id[src[0]]
            if src not in held:
                if how == "hidden":
                    name = self.hidden("F", s.loc, "VAR", f"feedback value of {s.text}")
                    w = Elem(len(elems), "outvar", s.loc, order=(float("inf"),) + tuple(last),
                             inputs={"": [src]}, var=copy.deepcopy(name),
                             text=f"feedback of {s.text}", explicit_order=True)
                    elems.append(w)
                    held[src] = name
                else:
                    held[src] = var
            r = Elem(len(elems), "invar", c.loc, order=c.order, var=copy.deepcopy(held[src]),
                     text=f"previous value of {s.text}")
            elems.append(r)
            c.inputs[pin][k] = (r.id, "")
        return elems

    def hidden(self, stem: str, loc: Location, section: str, what: str) -> A.Name:
        self.n += 1
        name = f"__LD_{stem}{self.n}"
        d = A.VarDecl(loc, name, A.NamedTypeRef(loc, "BOOL"), section=section, spelling=what)
        d.used = True
        self.decls.append(d)
        return A.Name(loc, name)

    def run(self) -> list[Diagnostic]:
        for e in self.order:
            self.visit(e)
        self.pou.body = self.out
        self.pou.decls.extend(self.decls)
        return self.diags

    # -- values -----------------------------------------------------------------------------
    def value(self, refs: list[Ref], loc: Location) -> A.Expr:
        self.nesting += 1
        try:
            if self.nesting == 1:
                for r in refs:
                    self.break_chains(r, loc)
            return _or(loc, [self.out_value(r, loc) for r in refs])
        finally:
            self.nesting -= 1

    def break_chains(self, ref: Ref, loc: Location) -> None:
        """Store every _CHAIN-th contact of a long series in a temporary, upstream first, so
        that one rung of thousands of contacts lowers without deep recursion (iterative)."""
        depth: dict[int, int] = {}
        stack: list[tuple[int, bool]] = [(ref[0], False)]
        while stack:
            i, done = stack.pop()
            if i < 0 or (i, "") in self.memo or (not done and i in depth):
                continue
            e = self.elems[i]
            ups = [j for refs in e.inputs.values() for j, _ in refs if j >= 0]
            if not done:
                depth[i] = -1  # on the way
                stack.append((i, True))
                stack.extend((j, False) for j in ups)
                continue
            d = 1 + max((depth.get(j, 0) for j in ups if (j, "") not in self.memo), default=0)
            if d >= _CHAIN and e.kind in ("contact", "cmp", "conn") and e.mode not in ("P", "N"):
                self.materialize((i, ""), self.out_value((i, ""), e.loc), e.loc)
                d = 0
            depth[i] = d

    def out_value(self, ref: Ref, loc: Location) -> A.Expr:
        if ref[0] < 0:
            return _true(loc)
        if ref in self.memo:
            return copy.deepcopy(self.memo[ref])
        e = self.elems[ref[0]]
        pin = ref[1]
        k = e.kind
        if k == "left":
            return _true(e.loc)
        if k == "contact":
            return _and(e.loc, self.value(e.inputs.get("", []), e.loc), self.contact_cond(e))
        if k == "coil":
            return self.value(e.inputs.get("", []), e.loc)
        if k == "cmp":
            a, b = (copy.deepcopy(x.value) for x in e.args)
            return _and(e.loc, self.value(e.inputs.get("", []), e.loc),
                        A.Binary(e.loc, COMPARE[e.type_name], a, b))
        if k in ("invar", "inoutvar"):
            return copy.deepcopy(e.var)
        if k == "conn":
            return self.value(e.inputs.get("", []), e.loc)
        if k in ("fb", "func") and pin in e.inout_pins:
            return self.value(e.inputs.get(pin, []), e.loc)  # the variable wired to the pin
        if k in ("fb", "func") and pin in e.neg_out:
            return A.Unary(e.loc, "NOT", self.box_out(e, pin, loc))
        if k in ("fb", "func"):
            return self.box_out(e, pin, loc)
        return A.Literal(loc, False, "BOOL", None, "FALSE")

    def box_out(self, e: Elem, pin: str, loc: Location) -> A.Expr:
        """The value of output ``pin`` of a function block or function box."""
        k = e.kind
        if k == "fb":
            if pin in ("", "ENO") and e.id in self.pins:
                pin = self.pins[e.id][1] if pin == "" else pin
            if pin == "ENO" or (pin == "" and e.id not in self.pins):
                return self.value(e.inputs.get("EN", e.inputs.get("", [])), e.loc)
            return A.Member(e.loc, copy.deepcopy(e.instance), pin)
        if k == "func":
            if pin == "ENO" or (pin == "" and e.targets):
                return self.value(e.inputs.get("EN", e.inputs.get("", [])), e.loc)
            return self.func_call(e)
        return A.Literal(loc, False, "BOOL", None, "FALSE")

    def pin_value(self, e: Elem, pin: str, refs: list[Ref]) -> A.Expr:
        """What an input pin of a box receives: the wired value, negated or edge-detected when
        the pin says so (XML ``negated`` / ``edge``)."""
        if (e.id, pin) in self.edges:
            return copy.deepcopy(self.edges[(e.id, pin)])
        v = self.value(refs, e.loc)
        return A.Unary(e.loc, "NOT", v) if pin in e.neg_in else v

    def edge_pulses(self, e: Elem) -> None:
        """Edge-triggered input pins: a pulse computed once per scan, before the box runs."""
        for pin, mode in sorted(e.edge_in.items()):
            v = self.value(e.inputs.get(pin, []), e.loc)
            if pin in e.neg_in:
                v = A.Unary(e.loc, "NOT", v)
            self.edges[(e.id, pin)] = self.edge(e, v, mode, f"input {pin} of {e.text}")

    def edge(self, e: Elem, v: A.Expr, mode: str, what: str) -> A.Name:
        """Statements computing a one-scan pulse on the rising (P) or falling (N) edge of ``v``;
        returns the hidden variable holding the pulse."""
        mem = self.hidden("M", e.loc, "VAR", f"edge memory of {what}")
        pulse = self.hidden("E", e.loc, "VAR_TEMP", f"edge of {what}")
        now = copy.deepcopy(v) if mode == "P" else A.Unary(e.loc, "NOT", copy.deepcopy(v))
        was = copy.deepcopy(mem) if mode == "P" else A.Unary(e.loc, "NOT", copy.deepcopy(mem))
        self.out.append(A.Assign(e.loc, pulse, _and(e.loc, now, A.Unary(e.loc, "NOT", was))))
        self.out.append(A.Assign(e.loc, copy.deepcopy(mem), copy.deepcopy(v)))
        return copy.deepcopy(pulse)

    def contact_cond(self, e: Elem) -> A.Expr:
        if e.id in self.conds:
            return copy.deepcopy(self.conds[e.id])
        v = copy.deepcopy(e.var) if e.var is not None else A.Literal(e.loc, False, "BOOL")
        if e.mode == "/":
            return A.Unary(e.loc, "NOT", v)
        return v

    def func_call(self, e: Elem) -> A.Expr:
        args = [copy.deepcopy(a) for a in e.args]
        for pin, refs in e.inputs.items():
            if pin in ("", "EN") or not refs:
                continue
            args.append(A.Arg(e.loc, pin, self.pin_value(e, pin, refs)))
        if e.type_name in ("AND", "OR", "XOR", "NOT") and not e.targets:
            # the FBD boolean boxes are operators, not functions
            vals = [a.value for a in args if a.value is not None]
            if e.type_name == "NOT":
                return A.Unary(e.loc, "NOT", vals[0] if vals else _true(e.loc))
            out = vals[0] if vals else _true(e.loc)
            for v in vals[1:]:
                out = A.Binary(e.loc, e.type_name, out, v)
            return out
        if e.instance is not None and not e.type_name:  # a METHOD box (ADR 0021)
            return A.Call(e.loc, copy.deepcopy(e.instance), args)
        return A.Call(e.loc, A.Name(e.loc, e.type_name), args)

    def materialize(self, ref: Ref, value: A.Expr, loc: Location) -> A.Expr:
        if _simple(value):
            self.memo[ref] = value
            return value
        t = self.hidden("T", loc, "VAR_TEMP", "power flow")
        self.out.append(A.Assign(loc, t, value))
        self.memo[ref] = t
        return copy.deepcopy(t)

    # -- elements ---------------------------------------------------------------------------
    def visit(self, e: Elem) -> None:
        k = e.kind
        ref = (e.id, "")
        if e.edge_in:
            self.edge_pulses(e)
        if k == "contact" and e.mode in ("P", "N") and e.var is not None:
            mem = self.hidden("M", e.loc, "VAR", f"edge memory of {e.text}")
            pulse = self.hidden("E", e.loc, "VAR_TEMP", f"edge of {e.text}")
            v = copy.deepcopy(e.var)
            now = v if e.mode == "P" else A.Unary(e.loc, "NOT", v)
            was = copy.deepcopy(mem) if e.mode == "P" else A.Unary(e.loc, "NOT", mem)
            self.out.append(A.Assign(e.loc, pulse, _and(e.loc, now, A.Unary(e.loc, "NOT", was))))
            self.out.append(A.Assign(e.loc, copy.deepcopy(mem), copy.deepcopy(e.var)))
            self.conds[e.id] = pulse
        if k in ("contact", "cmp") and self.uses.get(ref, 0) > 1:
            self.materialize(ref, self.out_value(ref, e.loc), e.loc)
        elif k == "coil":
            self.coil(e)
        elif k == "fb":
            self.fb(e)
        elif k == "func":
            self.func(e)
        elif k in ("outvar", "inoutvar"):
            self.outvar(e)
        elif k == "label":
            self.out.append(A.Label(e.loc, e.label))
        elif k == "jump":
            cond = self.value(e.inputs.get("", []), e.loc)
            self.out.append(A.Jump(e.loc, e.label, None if _is_true(cond) else cond))
        elif k == "return":
            cond = self.value(e.inputs.get("", []), e.loc)
            ret: A.Stmt = A.Return(e.loc)
            self.out.append(ret if _is_true(cond) else A.If(e.loc, [(cond, [ret])]))

    def coil(self, e: Elem) -> None:
        pf = self.value(e.inputs.get("", []), e.loc)
        if self.uses.get((e.id, ""), 0) > 0 or e.mode in ("P", "N"):
            pf = self.materialize((e.id, ""), pf, e.loc)
        if e.var is None:
            return
        tgt = copy.deepcopy(e.var)
        if e.mode == "":
            self.out.append(A.Assign(e.loc, tgt, pf))
        elif e.mode == "/":
            self.out.append(A.Assign(e.loc, tgt, A.Unary(e.loc, "NOT", pf)))
        elif e.mode in ("S", "R"):
            self.out.append(A.Assign(e.loc, tgt, pf, e.mode + "="))
        else:  # edge coils: TRUE for one scan when the power flow rises (P) or falls (N)
            mem = self.hidden("M", e.loc, "VAR", f"edge memory of {e.text}")
            now = copy.deepcopy(pf) if e.mode == "P" else A.Unary(e.loc, "NOT", copy.deepcopy(pf))
            was = copy.deepcopy(mem) if e.mode == "P" else A.Unary(e.loc, "NOT", mem)
            self.out.append(A.Assign(e.loc, tgt, _and(e.loc, now, A.Unary(e.loc, "NOT", was))))
            self.out.append(A.Assign(e.loc, copy.deepcopy(mem), copy.deepcopy(pf)))

    def fb_type(self, e: Elem):
        """The declared type of the instance, checked against the box's type name."""
        decl = self.types.decl_of(e.instance, self.pou) if e.instance is not None else None
        declared = self.types.fb_of(self.types.type_of(decl.type)) if decl is not None else None
        box_pou = self.types.pou(e.type_name)
        if box_pou is None or box_pou.kind == "FUNCTION":
            what = "a function" if box_pou is not None else "not a function block type"
            self.err("PLC0165", f"{e.type_name} in {e.text} is {what}; boxes with an instance are "
                     "function blocks such as TON, TOF, TP, CTU, CTD, R_TRIG or your own "
                     "FUNCTION_BLOCK (a function box needs '-> result')", e.loc)
            return None
        if declared is not None and declared.name != e.type_name:
            self.err("PLC0165", f"{decl.spelling or decl.name} is declared as {declared.name}, but "
                     f"the box says {e.type_name}", e.loc)
            return None
        return box_pou

    def fb(self, e: Elem) -> None:
        pou = self.fb_type(e)
        if pou is None:
            return
        args: list[A.Arg] = []
        if "" in e.inputs:  # a text box: the rung feeds its first BOOL input
            pins = self.types.pins(pou)
            if pins is None:
                self.err("PLC0165", f"{pou.name} has no BOOL input and BOOL output to carry the "
                         "power flow of a ladder box", e.loc)
                return
            self.pins[e.id] = pins
            args.append(A.Arg(e.loc, pins[0], self.value(e.inputs.get("", []), e.loc)))
        en = e.inputs.get("EN")
        for pin, refs in e.inputs.items():
            if pin in ("", "EN") or not refs:
                continue
            args.append(A.Arg(e.loc, pin, self.pin_value(e, pin, refs)))
        args.extend(copy.deepcopy(a) for a in e.args)
        call: A.Stmt = A.CallStmt(e.loc, A.Call(e.loc, copy.deepcopy(e.instance), args))
        if en is not None:
            cond = self.materialize((e.id, "ENO"), self.value(en, e.loc), e.loc)
            call = A.If(e.loc, [(copy.deepcopy(cond), [call])])
        self.out.append(call)

    def func(self, e: Elem) -> None:
        en = e.inputs.get("EN", e.inputs.get("", []) if e.targets else None)
        if not e.targets:
            return  # an XML function: its value is used by whatever it feeds
        if e.type_name and not self.types.is_function(e.type_name):
            self.err("PLC0165", f"{e.type_name} in {e.text} is not a function; use MOVE, ADD, "
                     "SUB, MUL, DIV, a conversion such as INT_TO_REAL, or your own FUNCTION",
                     e.loc)
            return
        cond = self.value(en or [], e.loc) if en is not None else _true(e.loc)
        if self.uses.get((e.id, ""), 0) > 0:
            cond = self.materialize((e.id, ""), cond, e.loc)
        call = self.func_call(e)
        if e.type_name == "MOVE" and len(call.args) == 1:
            value: A.Expr = call.args[0].value
        else:
            value = call
        body: list[A.Stmt] = [A.Assign(e.loc, copy.deepcopy(t), copy.deepcopy(value))
                              for t in e.targets]
        if _is_true(cond):
            self.out.extend(body)
        else:
            self.out.append(A.If(e.loc, [(copy.deepcopy(cond), body)]))

    def outvar(self, e: Elem) -> None:
        refs = e.inputs.get("", [])
        v = self.value(refs, e.loc)
        stmt: A.Stmt = A.Assign(e.loc, copy.deepcopy(e.var), v)
        ref = refs[0] if len(refs) == 1 else (-1, "")
        hops = 0  # a chain of connectors visits each element at most once
        while ref[0] >= 0 and self.elems[ref[0]].kind == "conn" and \
                len(self.elems[ref[0]].inputs.get("", [])) == 1 and hops <= len(self.elems):
            ref = self.elems[ref[0]].inputs[""][0]  # through connector/continuation pairs
            hops += 1
        if ref[0] >= 0:
            src = self.elems[ref[0]]
            if src.kind == "func" and "EN" in src.inputs and ref[1] != "ENO":
                cond = self.value(src.inputs["EN"], e.loc)
                stmt = A.If(e.loc, [(cond, [stmt])])
        self.out.append(stmt)


def execution_order(elems: list[Elem]) -> list[Elem]:
    """The order in which a network's elements run.

    When every element that does something (a block, an output or in-out variable, a coil, a
    jump, a label, a return) carries an ``executionOrderId`` (``explicit_order``), that order
    is followed as written. Otherwise the IEC 61131-3 rule applies (part 3, "evaluation of
    networks"): no element runs before the elements wired into its inputs, and among the
    elements that are ready the one first in ``order`` (top to bottom, left to right) runs
    next. Elements caught in a feedback loop keep their written order at the end.
    """
    acting = [e for e in elems if e.kind in _ACTING]
    if acting and all(e.explicit_order for e in acting):
        return sorted(elems, key=lambda e: e.order)
    import heapq

    waiting = {e.id: len({i for i in _sources(e)}) for e in elems}
    readers: dict[int, list[Elem]] = {}
    for e in elems:
        for i in {i for i in _sources(e)}:
            readers.setdefault(i, []).append(e)
    ready = [(e.order, e.id) for e in elems if waiting[e.id] == 0]
    heapq.heapify(ready)
    out: list[Elem] = []
    by_id = {e.id: e for e in elems}
    cut = False
    while ready or not cut:
        if not ready:  # a loop: a variable read inside it gives its value, not a wire order
            cut = True
            done = {e.id for e in out}
            for i, rs in readers.items():
                if i in by_id and by_id[i].kind == "inoutvar" and i not in done:
                    for r in rs:
                        waiting[r.id] -= 1
                        if waiting[r.id] == 0:
                            heapq.heappush(ready, (r.order, r.id))
            continue
        _, i = heapq.heappop(ready)
        out.append(by_id[i])
        for r in readers.get(i, []):
            if cut and by_id[i].kind == "inoutvar":
                continue  # its readers were released when the loop was cut
            waiting[r.id] -= 1
            if waiting[r.id] == 0:
                heapq.heappush(ready, (r.order, r.id))
    done = {e.id for e in out}
    out.extend(sorted((e for e in elems if e.id not in done), key=lambda e: e.order))
    return out


_BOOL_BOXES = {"AND", "OR", "XOR", "NOT", "GT", "GE", "EQ", "NE", "LE", "LT"}

Cut = tuple[int, str, int, str, Any]  # consumer id, its pin, index of the ref, how, var


def _holder(s: Elem, pin: str, written: dict[Ref, A.Expr]) -> tuple[int, str, Any] | None:
    """How the previous value of output ``pin`` of ``s`` is read when a loop is cut on a wire
    leaving it: (preference, how, expression); None when nothing holds it. ``written``: the
    variables output variables write straight from a wire (feedback variables)."""
    if (s.id, pin) in written:
        return (0, "var", written[(s.id, pin)])
    if s.kind == "fb" and s.instance is not None and pin not in ("", "ENO") and \
            pin not in s.inout_pins:
        v: A.Expr = A.Member(s.loc, copy.deepcopy(s.instance), pin)
        return (1, "var", A.Unary(s.loc, "NOT", v) if pin in s.neg_out else v)
    if s.kind in ("contact", "coil", "cmp") or (s.kind == "func" and (
            pin == "ENO" or (s.type_name in _BOOL_BOXES and not s.targets))):
        return (2, "hidden", None)
    return None


def plan_feedback(elems: list[Elem]) -> tuple[list[Cut], Elem | None]:
    """Where each feedback loop of a network is cut (IEC 61131-3 ed.3, FBD feedback paths: a
    value fed back is the one of the previous evaluation). Elements are taken in the IEC order
    (no element before those wired into it); when none is ready, the elements left form loops,
    and one wire inside a loop is cut: a wire whose value a variable holds is preferred (the
    feedback variable: an output variable wired from the same output), then a function block
    output (``T1.Q`` keeps the previous value, as Beremiz reads it), then a BOOL box (a hidden
    BOOL holds it); among equals, the consumer first top to bottom, left to right. Returns the
    cuts, and an element of a loop nothing can hold (no cut) or None."""
    by_id = {e.id: e for e in elems}
    srcs = {e.id: set(_feeds_of(e, by_id)) for e in elems}
    readers: dict[int, set[int]] = {}
    for e in elems:
        for i in srcs[e.id]:
            readers.setdefault(i, set()).add(e.id)
    waiting = {i: len(ss) for i, ss in srcs.items()}
    written: dict[Ref, A.Expr] = {}
    for o in elems:  # output variables written straight from one wire
        src = o.inputs.get("", [])
        if o.kind == "outvar" and not o.neg_in and len(src) == 1 and \
                isinstance(o.var, A.Name | A.Member):
            written.setdefault(src[0], o.var)
    ready = [i for i, n in waiting.items() if n == 0]
    left = set(by_id)
    cuts: list[Cut] = []
    while left:
        while ready:  # Kahn: linear in the size of the network
            i = ready.pop()
            left.discard(i)
            for r in readers.get(i, ()):
                waiting[r] -= 1
                if waiting[r] == 0:
                    ready.append(r)
        if not left:
            break
        # stalled: the first strongly connected part found is fed by nothing else left
        comp = _loop_members(left, srcs)
        best = None
        for cid in comp:
            c = by_id[cid]
            plan = []
            worst = -1
            for pin, refs in c.inputs.items():
                for k, (sid, spin) in enumerate(refs):
                    if sid not in comp or by_id[sid].kind == "inoutvar":
                        continue
                    h = _holder(by_id[sid], spin, written)
                    if h is None:
                        worst = 9
                        break
                    worst = max(worst, h[0])
                    plan.append((cid, pin, k, h[1], h[2]))
                if worst == 9:
                    break
            if plan and worst < 9:
                key = (worst, c.order)
                if best is None or key < best[0]:
                    best = (key, plan)
        if best is None:
            return cuts, by_id[min(comp, key=lambda i: by_id[i].order)]
        cuts.extend(best[1])
        cid = best[1][0][0]
        for sid in srcs[cid] & comp:  # its in-loop sources no longer hold it back
            readers[sid].discard(cid)
        srcs[cid] -= comp
        waiting[cid] = len(srcs[cid] & left)
        if waiting[cid] == 0:
            ready.append(cid)
        else:  # cannot happen (the part is fed by nothing left); stay safe
            return cuts, by_id[cid]
    return cuts, None


def _feeds_of(e: Elem, by_id: dict[int, Elem]):
    """The elements wired into ``e``; not in-out variables (reading one reads the variable: a
    path through one is no loop)."""
    return (i for refs in e.inputs.values() for i, _ in refs
            if i >= 0 and i in by_id and by_id[i].kind != "inoutvar")


def _loop_members(left: set[int], srcs: dict[int, set[int]]) -> set[int]:
    """The elements of ``left`` on a loop (a strongly connected part with more than one
    element or feeding itself), first found; iterative Tarjan."""
    index: dict[int, int] = {}
    low: dict[int, int] = {}
    on: set[int] = set()
    stack: list[int] = []
    n = 0
    for root in sorted(left):
        if root in index:
            continue
        work = [(root, iter(sorted(srcs[root] & left)))]
        index[root] = low[root] = n
        n += 1
        stack.append(root)
        on.add(root)
        while work:
            v, it = work[-1]
            w = next(it, None)
            if w is not None:
                if w not in index:
                    index[w] = low[w] = n
                    n += 1
                    stack.append(w)
                    on.add(w)
                    work.append((w, iter(sorted(srcs[w] & left))))
                elif w in on:
                    low[v] = min(low[v], index[w])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                comp = set()
                while True:
                    x = stack.pop()
                    on.discard(x)
                    comp.add(x)
                    if x == v:
                        break
                if len(comp) > 1 or v in srcs[v]:
                    return comp
    return set(left)


_ACTING = {"fb", "func", "outvar", "inoutvar", "coil", "jump", "label", "return"}


def _sources(e: Elem):
    return (i for refs in e.inputs.values() for i, _ in refs if i >= 0)


def lower_network(pou: A.Pou, elems: list[Elem], types: LoweringTypes) -> list[Diagnostic]:
    """Translate a parsed network into ``pou.body`` (and hidden declarations)."""
    return _NetLowering(pou, elems, types).run()
