"""Edge-detecting inputs (IEC 61131-3 ed.3 6.5.2.2, Table 14 items 3-4): ``x : BOOL R_EDGE;``
in a VAR_INPUT section.

The standard defines such an input as an implicit R_TRIG (F_TRIG) between the pin the caller
sets and the variable the body reads. The front end records the qualified inputs as a pending
body (``"EDGE"``, payload: ``(name, rising, location)``); this lowering gives the block a hidden
edge memory (VAR) and pulse (VAR_TEMP), prepends ``pulse := x AND NOT memory; memory := x;``
(``NOT x AND memory`` for F_EDGE) and makes the body read the pulse. The pin keeps the value
the caller wrote, so ``inst.x`` still shows it.
"""

from __future__ import annotations

from ...errors import Diagnostic
from .. import ast as A
from ..walk import walk
from .types import LoweringTypes

__all__ = ["lower_edges"]


def _bool(loc, name: str, section: str, what: str) -> A.VarDecl:
    d = A.VarDecl(loc, name, A.NamedTypeRef(loc, "BOOL"), section=section, spelling=what)
    d.used = True
    return d


def lower_edges(pou: A.Pou, payload: list, types: LoweringTypes) -> list[Diagnostic]:
    """Lower the edge-qualified inputs of ``pou`` (see the module text)."""
    if pou.kind == "FUNCTION":  # a function keeps nothing from one call to the next
        return [Diagnostic("PLC0179", f"{name}: R_EDGE and F_EDGE need a memory between calls; "
                           "declare them in a FUNCTION_BLOCK or PROGRAM, or compare the input "
                           "with the previous value yourself", loc)
                for name, _, loc in payload]
    head: list[A.Stmt] = []
    for name, rising, loc in payload:
        # "__" is never in an ST name: MEM__ keeps every memory apart from every pulse
        memory, pulse = f"__EDGE_MEM__{name}", f"__EDGE_{name}"
        pou.decls += [_bool(loc, memory, "VAR", f"edge memory of {name}"),
                      _bool(loc, pulse, "VAR_TEMP", f"edge of {name}")]
        for stmt in pou.body:
            for node in walk(stmt):
                if isinstance(node, A.Name) and node.name == name:
                    node.name = pulse
        pin, mem = A.Name(loc, name), A.Name(loc, memory)
        edge = (A.Binary(loc, "AND", pin, A.Unary(loc, "NOT", mem)) if rising else
                A.Binary(loc, "AND", A.Unary(loc, "NOT", A.Name(loc, name)), mem))
        head += [A.Assign(loc, A.Name(loc, pulse), edge),
                 A.Assign(loc, A.Name(loc, memory), A.Name(loc, name))]
    pou.body[:0] = head
    return []
