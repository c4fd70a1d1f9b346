"""The names of things in the generated code: an ST identifier's Python spelling, a program
instance's attribute, a member's path, the kind name of a type (moved out of codegen.py).
"""

from __future__ import annotations

import re

from ..lang import ast as A
from ..lang import types as T

_IDENT = re.compile(r"^[A-Z_][A-Z0-9_]*$")
_SIMPLE = (A.Name, A.Member, A.Index, A.Literal)


_IDENTS: dict[str, str] = {}  # name -> its checked spelling (the generator asks many times)


def ident(name: str) -> str:
    """The Python spelling of an ST identifier: upper case, checked to be a plain identifier."""
    up = _IDENTS.get(name)
    if up is not None:
        return up
    up = name.upper()
    if not _IDENT.match(up):
        raise ValueError(f"not an identifier: {name!r}")
    if len(_IDENTS) > 100_000:  # a long-lived process compiling many programs
        _IDENTS.clear()
    _IDENTS[name] = up
    return up


def program_attr(instance: str) -> str:
    """The attribute of ``_P`` holding a program instance: its name, ``RESA.MAIN`` (a program
    of one of two or more resources, ADR 0037) as ``RESA__MAIN``."""
    return ident(instance.replace(".", "__"))


def member_path(owner: str, via: tuple[str, ...], decl: A.VarDecl) -> str:
    """``owner.fb1.x``: the Python path of ``decl`` reached through the members ``via``."""
    return owner + "".join(f".{ident(m)}" for m in via) + f".{ident(decl.name)}"


def kind_name(t: T.Type | None) -> str:
    if t is None:
        return "int?"
    r = T.resolve(t)
    if r is T.ANY_INT_LIT:
        return "int?"
    if isinstance(r, T.EnumType):
        return "enum:" + ",".join(f"{v}={r.spellings.get(k, k)}" for k, v in r.members.items())
    if r is T.REAL:
        return "real32"
    if isinstance(r, T.Subrange):
        return "int"
    return r.kind if r.name not in ("LTIME",) else "ltime"
