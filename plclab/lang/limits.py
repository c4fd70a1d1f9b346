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

>>> with compiler_guard():
...     sys.getrecursionlimit() >= RECURSION_LIMIT
True
"""

from __future__ import annotations

import gc
import sys
from contextlib import contextmanager

MAX_BLOCK_NESTING = 2_000
"""IF / CASE / FOR / WHILE / REPEAT nested inside each other (PLC0190 beyond)."""

MAX_EXPR_NESTING = 2_000
"""Parentheses, calls, array indices and unary operators nested inside each other."""

MAX_EXTENDS_DEPTH = 64
"""Levels of EXTENDS above a FUNCTION_BLOCK (PLC0310 beyond): every level's variables are
initialised in each derived block, so a chain costs its length squared to compile."""

MAX_SFC_STEPS = 1_000
"""Steps of one SFC chart (PLC0311 beyond); checking and lowering are linear in the chart, but
Python compiles a chart of 1,000 steps in about a second and real charts have tens."""

MIN_INTERVAL_NS = 100_000
"""The shortest cycle time or task interval, 0.1 ms (PLC0129 in a TASK, PLC3011 in the API)."""

MAX_INTERVAL_NS = 86_400 * 1_000_000_000
"""The longest cycle time or task interval, one day."""

RECURSION_LIMIT = 60_000
"""Python frames allowed while parsing, checking and generating code (see the module text)."""


@contextmanager
def compiler_guard(recursion_limit: int = RECURSION_LIMIT):
    """For the block: Python's recursion limit at least ``recursion_limit``, and the cyclic
    garbage collector paused (parsing a large program makes hundreds of thousands of objects
    and no cycles; collecting while they are made doubles the time). Both are restored after.

    Nested use is fine."""
    old = sys.getrecursionlimit()
    if old < recursion_limit:
        sys.setrecursionlimit(recursion_limit)
    collecting = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if collecting:
            gc.enable()
        if old < recursion_limit:
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
    from .walk import children

    leaves = (A.Literal, A.Name, A.DirectAddr)
    exprs: list[tuple[object, int]] = []  # (expression, depth)
    stmts_todo: list[tuple[object, int]] = [(s, 1) for s in reversed(stmts)]
    while stmts_todo:
        s, blocks = stmts_todo.pop()
        if blocks > MAX_BLOCK_NESTING + 1:
            return "blocks", s.loc
        exprs.extend((e, 1) for e in _stmt_exprs(s, A) if not isinstance(e, leaves))
        for body in A.child_bodies(s):
            stmts_todo.extend((x, blocks + 1) for x in reversed(body))
    while exprs:
        e, depth = exprs.pop()
        if depth > MAX_EXPR_NESTING:
            return "expressions", e.loc
        if type(e) is A.Binary:
            while type(e) is A.Binary:  # the left spine: same depth
                if not isinstance(e.right, leaves):
                    exprs.append((e.right, depth + 1))
                e = e.left
            if not isinstance(e, leaves):
                exprs.append((e, depth))
            continue
        kids = [k.value if isinstance(k, A.Arg) else k for k in children(e)]
        exprs.extend((k, depth + 1) for k in kids if k is not None and not isinstance(k, leaves))
    return None


def _stmt_exprs(s, A) -> list:
    """The expressions of statement ``s`` itself (not of the statements inside it)."""
    from .walk import children, flat

    if isinstance(s, A.Case):
        return [s.selector] + [x for b in s.branches for x in flat(b.labels)]
    return [c for c in children(s) if isinstance(c, A.Expr)]
