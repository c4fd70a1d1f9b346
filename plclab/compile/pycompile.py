"""Python's ``compile()`` of the generated source, in pieces (ADR 0034).

The generated module is a sequence of top-level ``class`` and ``def`` statements. Compiling it
in one call builds Python's syntax tree of the whole module at once: on a 50,000-line ST
program that is about 100 bytes of compiler memory per character of generated source (over
500 MB) and, with the caches missed, a third slower than compiling the same source in pieces
of a few thousand lines. So the lines are cut before a top-level ``class``/``def`` every
:data:`CHUNK_LINES` lines or so, each piece is compiled on its own, and each code object's line
numbers are moved to where the piece starts in the whole source, so tracebacks (and
``Compiled.location_of_line``) name the same lines as a single compile would. Executing the
pieces in order into one namespace is executing the module: its top-level statements run in
sequence either way.

>>> codes = compile_lines(["def f():", "    return 1", "def g():", "    return 2"], "<x>", 2)
>>> [c.co_consts[0].co_firstlineno for c in codes]
[1, 3]
"""

from __future__ import annotations

from types import CodeType

CHUNK_LINES = 2_000
"""About this many generated lines a piece (measured: 300 to 4,000 all compile at the same
speed; the memory of a piece grows with its size)."""


def compile_lines(lines: list[str], filename: str,
                  chunk_lines: int = CHUNK_LINES) -> tuple[CodeType, ...]:
    """The code objects of ``lines`` (a module's source, one line an item), piece by piece.

    Raises what ``compile()`` raises. A SyntaxError in a piece is raised again by compiling the
    whole source, so its line number and message are those of the module."""
    n = len(lines)
    out: list[CodeType] = []
    start = 0
    try:
        while start < n:
            end = min(start + chunk_lines, n)
            while end < n and not _starts_statement(lines, end):
                end += 1
            code = compile("\n".join(lines[start:end]) + "\n", filename, "exec")
            out.append(_moved(code, start) if start else code)
            start = end
    except SyntaxError:
        return (compile("\n".join(lines) + "\n", filename, "exec"),)
    return tuple(out)


def _starts_statement(lines: list[str], i: int) -> bool:
    """A piece may begin at line ``i``: a top-level ``class``/``def`` not under a decorator."""
    line = lines[i]
    return line.startswith(("class ", "def ")) and not lines[i - 1].startswith("@")


def _moved(code: CodeType, offset: int) -> CodeType:
    """``code`` and every code object inside it, ``offset`` lines further down (CPython's line
    table counts from ``co_firstlineno``, so moving that moves every line)."""
    consts = tuple(_moved(c, offset) if isinstance(c, CodeType) else c for c in code.co_consts)
    return code.replace(co_firstlineno=code.co_firstlineno + offset, co_consts=consts)
