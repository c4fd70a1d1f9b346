"""The memory a program's data takes, counted as a PLC stores it, and containment cycles.

A structure or function block instance holds its members by value, so a block that holds an
instance of itself (directly, through other blocks, structures or arrays) would be infinitely
large; and nested arrays multiply. The checker asks :class:`DataSizes` for the size, the
nesting depth and the containment cycles of every declaration, without recursion (a chain of
a thousand blocks is fine here; the checker then rejects it as too deep).

Sizes: BOOL, SINT, USINT, BYTE 1 byte; INT, UINT, WORD 2; DINT, UDINT, DWORD, REAL, TIME, DATE,
TOD 4; LINT, ULINT, LWORD, LREAL, LTIME, DT 8; STRING[n] n + 1 bytes, WSTRING[n] 2(n + 1);
enumerations their base type; arrays multiply; every structure or instance adds
:data:`INSTANCE_BYTES` to its members.

>>> from plclab.lang import types as T
>>> DataSizes().type_cost(T.ArrayType([(1, 10)], T.StringType(False, 9)))
(100, 1)
"""

from __future__ import annotations

from typing import Any

from . import ast as A
from . import types as T

DATA_LIMIT = 16 * 1024 * 1024  # bytes of data of a whole program, and of one call or TEST
NESTING_LIMIT = 32  # arrays, structures and instances nested in each other
INSTANCE_BYTES = 8
_REFERENCES = ("VAR_IN_OUT", "VAR_EXTERNAL", "RETURN")  # not held by value


def _container(t: T.Type) -> Any:
    """The key of a type that holds members (a structure or a block), or None."""
    if isinstance(t, T.StructType):
        return t
    if isinstance(t, T.FBType) and t.pou is not None:
        return t.pou
    return None


def members(c: Any) -> list[A.VarDecl]:
    """The declarations a structure or a block instance holds by value."""
    if isinstance(c, T.StructType):
        return list(c.fields.values())
    return [d for d in c.decls if d.section not in _REFERENCES]


def container_name(c: Any) -> str:
    return c.name if isinstance(c, T.StructType) else (c.spelling or c.name)


def _unwrap(t: T.Type | None) -> tuple[int, int, T.Type]:
    """(element count, array levels, element type) of a possibly nested array type."""
    n, levels = 1, 0
    t = T.resolve(t) if t is not None else T.ANY
    while isinstance(t, T.ArrayType):
        n *= t.size
        levels += 1
        t = T.resolve(t.elem)
    return n, levels, t


def scalar_bytes(t: T.Type) -> int:
    t = T.resolve(t)
    if isinstance(t, T.StringType):
        return (t.length + 1) * (2 if t.wide else 1)
    if isinstance(t, T.EnumType):
        return t.base.bits // 8
    if isinstance(t, T.Subrange | T.Elementary):
        return max(1, t.bits // 8)
    return 0


class DataSizes:
    """Sizes (bytes) and nesting depths of structures and blocks, computed once each."""

    def __init__(self) -> None:
        self.size: dict[int, int] = {}
        self.depth: dict[int, int] = {}
        self.biggest: dict[int, A.VarDecl | None] = {}
        # (declaration closing the circle, chain text, the containers of the circle)
        self.cycles: list[tuple[A.VarDecl, str, list[Any]]] = []

    # -- costs ------------------------------------------------------------------------------
    def type_cost(self, t: T.Type | None) -> tuple[int, int]:
        """(bytes, nesting depth) of one value of type ``t``."""
        n, levels, base = _unwrap(t)
        c = _container(base)
        if c is None:
            return n * scalar_bytes(base), levels
        self.ensure(c)
        return n * self.size.get(id(c), 0), levels + self.depth.get(id(c), 0)

    def decls_cost(self, decls: list[A.VarDecl]) -> tuple[int, int, A.VarDecl | None]:
        """(bytes, depth, biggest declaration) of a list of declarations held by value."""
        total, depth, big, big_bytes = 0, 0, None, -1
        for d in decls:
            b, dep = self.type_cost(d.ty)
            total += b
            depth = max(depth, dep)
            if b > big_bytes:
                big, big_bytes = d, b
        return total, depth, big

    def chain(self, d: A.VarDecl | None, owner: str | None = None) -> str:
        """Why ``d`` is big: each declaration with its type and size, down to the largest
        element ("P.big : ARRAY[1..100] OF M (80,800 bytes) -> M.buf : ...")."""
        parts: list[str] = []
        seen: set[int] = set()
        while d is not None and len(parts) < 8:
            b, _ = self.type_cost(d.ty)
            name = f"{owner}.{d.spelling or d.name}" if owner else (d.spelling or d.name)
            ty = str(d.ty) if len(str(d.ty)) <= 60 else str(d.ty)[:56] + " ..."
            parts.append(f"{name} : {ty} ({b:,} bytes)")
            _, _, base = _unwrap(d.ty)
            c = _container(base)
            if c is None or id(c) in seen:
                break
            seen.add(id(c))
            owner, d = container_name(c), self.biggest.get(id(c))
        return " -> ".join(parts)

    # -- the walk ---------------------------------------------------------------------------
    def ensure(self, root: Any) -> None:
        """Size ``root`` and everything it contains (iterative depth-first walk)."""
        if id(root) in self.size:
            return
        # frame: [container, its members, next index, bytes, depth, biggest, biggest bytes]
        stack: list[list[Any]] = [[root, members(root), 0, INSTANCE_BYTES, 0, None, -1]]
        active: dict[int, int] = {id(root): 0}
        while stack:
            fr = stack[-1]
            c, ms, i = fr[0], fr[1], fr[2]
            if i == len(ms):
                stack.pop()
                del active[id(c)]
                self.size[id(c)], self.depth[id(c)], self.biggest[id(c)] = fr[3], fr[4] + 1, fr[5]
                continue
            d = ms[i]
            n, levels, base = _unwrap(d.ty)
            inner = _container(base)
            if inner is not None and id(inner) not in self.size:
                if id(inner) in active:
                    self._cycle(stack[active[id(inner)]:], d, inner)
                    self.size[id(inner)] = self.size.get(id(inner), 0)  # no further reports
                    fr[2] += 1
                    continue
                active[id(inner)] = len(stack)
                stack.append([inner, members(inner), 0, INSTANCE_BYTES, 0, None, -1])
                continue  # come back to this member once ``inner`` is sized
            b = n * (self.size.get(id(inner), 0) if inner is not None else scalar_bytes(base))
            dep = levels + (self.depth.get(id(inner), 0) if inner is not None else 0)
            fr[3] += b
            fr[4] = max(fr[4], dep)
            if b > fr[6]:
                fr[5], fr[6] = d, b
            fr[2] += 1

    def _cycle(self, frames: list[list[Any]], closing: A.VarDecl, back_to: Any) -> None:
        steps = [f"{container_name(f[0])}.{f[1][f[2]].spelling or f[1][f[2]].name}"
                 for f in frames[:-1]]
        last = frames[-1][0]
        steps.append(f"{container_name(last)}.{closing.spelling or closing.name}")
        text = " -> ".join(steps + [container_name(back_to)])
        self.cycles.append((closing, text, [f[0] for f in frames]))
