"""Size limits of the tool chain, and the recursion guard that lets it reach them.

Operator chains (``a + b + c + ...``, long AND/OR chains, CASE labels, statement lists) have no
limit: the parser, the checker and the compiler walk them with loops. *Nesting* (parentheses,
calls and indices inside each other, unary operators, IF inside IF...) is walked recursively,
which is the readable way to write a parser and a type checker; its depth is bounded by the
limits below, checked by the parser (for ST text) and again by the checker on the tree (for
every front end), so every tool sees a PLC0190 error with the location instead of a Python
``RecursionError``.

Why a guard instead of explicit stacks everywhere: the nesting limits need about 15 Python
frames a level in the worst case (parser + checker + compiler), more than Python's default
limit of 1,000 frames allows. On CPython 3.11+ a call from Python code to Python code does not
use the C stack, so raising the frame limit only costs heap memory; the limits bound the depth
actually used, so the raised limit is never the thing that stops a program. Rewriting every
recursive descent with explicit stacks would make the code much harder to read for no gain in
what a PLC program can express (no PLC accepts 2,000 nested IFs either).

>>> with deep_recursion():
...     sys.getrecursionlimit() >= RECURSION_LIMIT
True
"""

from __future__ import annotations

import sys
from contextlib import contextmanager

MAX_BLOCK_NESTING = 2_000
"""IF / CASE / FOR / WHILE / REPEAT nested inside each other (PLC0190 beyond)."""

MAX_EXPR_NESTING = 2_000
"""Parentheses, calls, array indices and unary operators nested inside each other."""

RECURSION_LIMIT = 60_000
"""Python frames allowed while parsing, checking and generating code (see the module text)."""


@contextmanager
def deep_recursion():
    """Raise Python's recursion limit to :data:`RECURSION_LIMIT` for the block, then restore it.

    Nested use is fine; the limit only ever goes up inside the block."""
    old = sys.getrecursionlimit()
    if old < RECURSION_LIMIT:
        sys.setrecursionlimit(RECURSION_LIMIT)
    try:
        yield
    finally:
        if old < RECURSION_LIMIT:
            sys.setrecursionlimit(old)


def too_deep_message(what: str, limit: int) -> str:
    """The text of a PLC0190 error: what is nested, the limit, and what to do."""
    if what == "blocks":
        return (f"statements are nested more than {limit:,} levels deep (IF, CASE, FOR, WHILE, "
                "REPEAT inside each other); move inner parts into a FUNCTION or a FUNCTION_BLOCK")
    return (f"the expression is nested more than {limit:,} levels deep (parentheses, calls, "
            "indices or unary operators inside each other); split it with intermediate "
            "variables")


def nesting_violation(stmts: list) -> tuple[str, object] | None:
    """The first place in a body nested beyond the limits, as ``(what, location)``, or None.

    Walks the tree with an explicit stack (it must not recurse itself), counting nesting the way
    the checker and the compiler recurse: a block inside a statement, an operand inside a unary
    operator, the right operand of a binary operator (left operands are chains, walked with
    loops), an index, an argument, the object of ``.member`` / ``[index]`` / ``(call)``."""
    from . import ast as A

    stack: list[tuple[object, int, int]] = [(s, 1, 0) for s in reversed(stmts)]
    while stack:
        node, blocks, depth = stack.pop()
        if isinstance(node, A.Expr):
            if depth > MAX_EXPR_NESTING:
                return "expressions", node.loc
            stack.extend((c, blocks, depth + inc) for c, inc in _expr_children(node, A))
            continue
        if blocks > MAX_BLOCK_NESTING + 1:
            return "blocks", node.loc
        for e in _stmt_exprs(node, A):
            stack.append((e, blocks, 1))
        for body in _stmt_bodies(node, A):
            stack.extend((s, blocks + 1, 0) for s in reversed(body))
    return None


def _expr_children(e, A) -> list:
    if isinstance(e, A.Binary):
        return [(e.left, 0), (e.right, 1)]
    if isinstance(e, A.Unary):
        return [(e.operand, 1)]
    if isinstance(e, A.Member):
        return [(e.obj, 1)]
    if isinstance(e, A.Index):
        return [(e.obj, 1)] + [(i, 1) for i in e.indices]
    if isinstance(e, A.Call):
        return [(e.func, 1)] + [(a.value, 1) for a in e.args if a.value is not None]
    return []


def _stmt_exprs(s, A) -> list:
    if isinstance(s, A.Assign):
        return [s.target, s.value]
    if isinstance(s, A.CallStmt):
        return [s.call]
    if isinstance(s, A.If):
        return [c for c, _ in s.branches]
    if isinstance(s, A.Case):
        labels = [x for b in s.branches for lab in b.labels
                  for x in (lab if isinstance(lab, tuple) else (lab,))]
        return [s.selector] + labels
    if isinstance(s, A.For):
        return [e for e in (s.var, s.start, s.end, s.step) if e is not None]
    if isinstance(s, A.While | A.Repeat):
        return [s.cond]
    if isinstance(s, A.Jump) and s.cond is not None:
        return [s.cond]
    return []


def _stmt_bodies(s, A) -> list:
    if isinstance(s, A.If):
        return [b for _, b in s.branches] + ([s.orelse] if s.orelse else [])
    if isinstance(s, A.Case):
        return [b.body for b in s.branches] + ([s.orelse] if s.orelse else [])
    if isinstance(s, A.For | A.While | A.Repeat):
        return [s.body]
    return []
