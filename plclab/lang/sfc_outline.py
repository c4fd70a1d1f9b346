"""A chart as plain data: what the trace's SFC lane, the lab feedback and the drawing need.

The lowering keeps the chart of an SFC body on its POU (``Pou.sfc``, a
:class:`~plclab.lang.lower.sfc_chart.Chart`); :func:`outline` turns it into JSON-able dicts with the
names as written and each transition's condition as ST text (docs/adr/0023).

>>> from plclab.project import check_sources
>>> project, _ = check_sources([('''PROGRAM P VAR go : BOOL; lamp : BOOL; END_VAR
... INITIAL_STEP Idle: END_STEP
... STEP Run: lamp(N); END_STEP
... TRANSITION FROM Idle TO Run := go AND NOT lamp; END_TRANSITION
... TRANSITION FROM Run TO Idle := NOT go; END_TRANSITION
... END_PROGRAM''', "p.st")])
>>> o = outline(project.pous["P"].sfc)
>>> [s["name"] for s in o["steps"]], o["steps"][1]["actions"]
(['Idle', 'Run'], [{'action': 'lamp', 'qualifier': 'N', 'time': None}])
>>> o["transitions"][0]["condition"], o["transitions"][0]["reads"]
('go AND NOT lamp', ['go', 'lamp'])
"""

from __future__ import annotations

from typing import Any

from . import ast as A
from .unparse import expr as expr_text


def outline(chart: Any) -> dict[str, Any]:
    """Steps (name, initial, action associations) and transitions (from, to, condition text,
    the variables the condition reads, priority, name) of a chart, names as written."""
    text = {s.name: s.text for s in chart.steps}
    steps = [{"name": s.text, "initial": s.initial,
              "actions": [{"action": a.text, "qualifier": a.qualifier,
                           "time": expr_text(a.time) if a.time is not None else None}
                          for a in s.assocs]}
             for s in chart.steps]
    trans = []
    for t in chart.transitions:
        trans.append({
            "from": [text.get(n, n) for n, _ in t.sources],
            "to": [text.get(n, n) for n, _ in t.targets],
            "condition": condition_text(t),
            "reads": reads(t.cond) if t.cond is not None else [],
            "priority": t.priority,
            "name": t.text or t.name if t.name and not t.name.startswith("__") else None,
        })
    return {"steps": steps, "transitions": trans}


def condition_text(t: Any) -> str:
    """The condition as ST (an expression), or what holds it (a body, IL, a network)."""
    if t.cond is not None:
        return expr_text(t.cond)
    name = t.text or t.name or ""
    if name.startswith("__"):
        return "(a graphical condition)"
    if t.il is not None:
        return f"{name} (IL)"
    if t.pending:
        return f"{name} (LD/FBD)"
    return f"{name} (ST body)"


def reads(e: A.Expr) -> list[str]:
    """The variables (``a``, ``S1.T``, ``fb.Q``) an expression reads, in order, once each."""
    out: list[str] = []

    def visit(x: Any) -> None:
        path = _path(x)
        if path is not None:
            if path not in out:
                out.append(path)
            return
        if isinstance(x, A.Unary):
            visit(x.operand)
        elif isinstance(x, A.Binary):
            visit(x.left)
            visit(x.right)
        elif isinstance(x, A.Call):
            for a in x.args:
                if a.value is not None:
                    visit(a.value)
        elif isinstance(x, A.Index):
            visit(x.obj)

    visit(e)
    return out


def _path(x: Any) -> str | None:
    if isinstance(x, A.Name):
        return x.text or x.name
    if isinstance(x, A.Member):
        base = _path(x.obj)
        return f"{base}.{x.text or x.field_name}" if base is not None else None
    return None


def evaluate(e: A.Expr, value: Any) -> Any:
    """The value of a condition from ``value(path)`` (None: unknown), for the simple
    expressions conditions are made of (literals, variables, NOT, AND/OR/XOR, comparisons,
    + - * /); anything else is None."""
    path = _path(e)
    if path is not None:
        return value(path)
    if isinstance(e, A.Literal):  # TIME: nanoseconds in the tree, milliseconds in the PLC
        return e.value // 1_000_000 if e.kind == "TIME" and e.prefix != "LTIME" else e.value
    if isinstance(e, A.Unary):
        v = evaluate(e.operand, value)
        if v is None:
            return None
        return (not v) if e.op == "NOT" else -v if e.op == "-" else v
    if isinstance(e, A.Binary):
        a, b = evaluate(e.left, value), evaluate(e.right, value)
        if a is None or b is None:
            return None
        ops = {"AND": lambda: bool(a) and bool(b), "&": lambda: bool(a) and bool(b),
               "OR": lambda: bool(a) or bool(b), "XOR": lambda: bool(a) != bool(b),
               "=": lambda: a == b, "<>": lambda: a != b, "<": lambda: a < b,
               "<=": lambda: a <= b, ">": lambda: a > b, ">=": lambda: a >= b,
               "+": lambda: a + b, "-": lambda: a - b, "*": lambda: a * b}
        f = ops.get(e.op)
        return f() if f is not None else None
    return None
