"""CODESYS ``REFERENCE TO T``: a reference that reads and writes as the variable it refers to.

CODESYS (online help, "Reference"): ``refX : REFERENCE TO INT;`` is bound with ``refX REF= x;``
and afterwards ``refX`` *is* ``x`` (``refX := 5`` writes ``x``, ``y := refX`` reads it);
``__ISVALIDREF(refX)`` tells whether it is bound. plclab reads it as the ed.3 ``REF_TO T`` it
already has (ADR 0021) with the dereference written for the user: before the checker types
anything, every use of such a variable in its POU (or a method of it, a TEST, a global) becomes
``refX^``, and ``refX REF= x`` becomes ``refX := REF(x)``; an argument for a ``REFERENCE TO``
input binds it (``fb(refIn := x)`` passes ``REF(x)``, :mod:`plclab.lang.check.calls`). So every rule of references holds:
REF of a variable of a block, program or global only (PLC0240), an unbound reference read or
written is the runtime fault PLC9111. Only names are rewritten: an output of another block that
is a reference (``inst.refOut``) stays the reference itself.
"""

from __future__ import annotations

import dataclasses
from typing import Any

from ...errors import Location
from .. import ast as A

_SKIP = {"__ISVALIDREF"}  # takes the reference itself


def _is_reference(d: A.VarDecl) -> bool:
    return isinstance(d.type, A.RefTypeRef) and d.type.kind == "REFERENCE"


def _names(decls: list[A.VarDecl]) -> tuple[set[str], set[str]]:
    """(names declared REFERENCE TO, all names) of ``decls``."""
    return {d.name for d in decls if _is_reference(d)}, {d.name for d in decls}


def ref_call(loc: Location, value: A.Expr) -> A.Call:
    return A.Call(loc, A.Name(loc, "REF", "REF"), [A.Arg(loc, None, value)])


class _Rewriter:
    def __init__(self, refs: set[str]) -> None:
        self.refs = refs

    def wrap(self, x: Any) -> Any:
        if isinstance(x, A.Name) and x.name in self.refs and not x.text.endswith("^"):
            return A.Member(x.loc, x, "^", "^")
        self.visit(x)
        return x

    def visit(self, node: Any) -> None:
        if isinstance(node, list):
            for i, x in enumerate(node):
                if isinstance(x, tuple):
                    node[i] = tuple(self.wrap(y) for y in x)
                else:
                    node[i] = self.wrap(x)
            return
        if not dataclasses.is_dataclass(node) or isinstance(node, type):
            return
        if isinstance(node, A.Assign) and node.op == "REF=":
            node.op = ":="
            node.value = ref_call(node.loc, self.wrap(node.value))
            if isinstance(node.target, A.Name):
                return
        if isinstance(node, A.Call) and isinstance(node.func, A.Name) and \
                node.func.name in _SKIP:
            return
        if isinstance(node, A.Member) and node.field_name == "^" and \
                isinstance(node.obj, A.Name):
            return  # r^ written out: already the variable
        for f in dataclasses.fields(node):
            if f.name in ("loc", "sym", "ty") or (f.name == "target" and
                                                   not isinstance(node, A.Assign)):
                continue  # annotations, not children
            v = getattr(node, f.name)
            if isinstance(v, list):
                self.visit(v)
            elif isinstance(v, A.Expr | A.Stmt | A.Arg):
                setattr(node, f.name, self.wrap(v))


def rewrite(files: list[A.SourceFile]) -> None:
    """Dereference every use of a ``REFERENCE TO`` variable and turn ``REF=`` into
    ``:= REF(...)``, in every body of ``files`` (before the checker types them)."""
    global_refs, _ = _names([d for f in files for g in f.globals for d in g.decls])

    def body(stmts: list[A.Stmt], *scopes: list[A.VarDecl]) -> None:
        refs = set(global_refs)
        for decls in reversed(scopes):  # outermost first: an inner name hides an outer one
            r, names = _names(decls)
            refs = (refs - names) | r
        if refs:
            _Rewriter(refs).visit(stmts)

    for f in files:
        for p in f.pous:
            body(p.body, p.decls)
            for m in p.methods:
                body(m.body, m.decls, p.decls)
        for t in f.tests:
            body(t.body, t.decls)
