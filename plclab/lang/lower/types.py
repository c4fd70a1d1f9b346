"""The type questions the lowering asks, behind one small interface.

IL needs the type of its current result (to check ``LD x / ADD b`` and to pick the hidden
``__CR_<TYPE>`` variable); a ladder or FBD box needs the function block of its instance and the
pins that carry the power flow. The lowering runs before the checker, once every declaration of
every file is known, so it asks :class:`LoweringTypes` and nothing else.

:class:`DeclarationTypes` answers from the checker's symbol table
(:class:`plclab.lang.check.symbols.SymbolTable`, usable before bodies are checked), so the
lowering and the checker see one model of scopes and members. The lowering modules call only
the methods of :class:`LoweringTypes` and the value helpers below (:func:`category`,
:func:`type_text`, :func:`enum_name`).

A type value (:data:`LType`) is a :mod:`plclab.lang.types` object for elementary and string
types, a :class:`Composite` for the rest, or ``None``: unknown (the checker will say more).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Protocol

from .. import ast as A
from .. import types as T
from ..builtins import BUILTINS, POWER_PINS, conversion
from ..check.symbols import SymbolTable


@dataclass(frozen=True, eq=False)
class Composite:
    """A type that is not elementary: ``category`` is FB (``target``: the FB or program POU),
    STRUCT (the fields by name), ARRAY (the element's TypeRef) or ENUM (the enumeration's
    type name, ``""`` for an anonymous one)."""

    category: str
    target: Any


LType = Any  # T.Type | Composite | None


class LoweringTypes(Protocol):
    """What the lowering may ask about declarations (all answers may be ``None``: unknown)."""

    def expr_type(self, e: A.Expr, pou: A.Pou) -> LType:
        """The type of expression ``e`` written in ``pou`` (names, members, indexes, literals,
        direct addresses; anything else is unknown)."""

    def decl_of(self, e: A.Expr, pou: A.Pou) -> A.VarDecl | None:
        """The declaration a plain name in ``pou`` refers to (locals, then globals;
        ``VAR_EXTERNAL`` resolved to the global)."""

    def type_of(self, ref: A.TypeRef | None) -> LType:
        """The type a declared type reference stands for."""

    def fb_of(self, t: LType) -> A.Pou | None:
        """The function block (or program) POU whose instance has type ``t``."""

    def pou(self, name: str) -> A.Pou | None:
        """The POU (program, function block or function) of that name."""

    def is_function(self, name: str) -> bool:
        """A standard function, a conversion or a user FUNCTION."""

    def function_names(self) -> list[str]:
        """Every function a program may call (for "did you mean")."""

    def pins(self, fb: A.Pou) -> tuple[str, str] | None:
        """(BOOL input fed by the power flow, BOOL output continuing it) of a ladder box, or
        ``None`` when the block has no such pair."""


def category(t: LType) -> str | None:
    """BOOL, INT, BITS, REAL, TIME, STRING, DATE, ENUM, FB, STRUCT, ARRAY or None (unknown)."""
    if t is None:
        return None
    if isinstance(t, Composite):
        return t.category
    if isinstance(t, T.StringType):
        return "STRING"
    return {"bool": "BOOL", "int": "INT", "bits": "BITS", "real": "REAL", "time": "TIME",
            "date": "DATE", "tod": "DATE", "dt": "DATE"}.get(getattr(t, "kind", ""), None)


def type_text(t: LType) -> str:
    """The type as a message names it."""
    if t is None:
        return "unknown"
    if t is T.ANY_INT_LIT:
        return "an integer literal"
    if t is T.ANY_REAL_LIT:
        return "a REAL literal"
    if isinstance(t, Composite):
        if t.category == "FB":
            return f"a {t.target.name} instance"
        if t.category == "ENUM":
            return t.target or "an enumeration"
        return {"STRUCT": "a structure", "ARRAY": "an array"}[t.category]
    return str(getattr(t, "name", t))


def enum_name(t: LType) -> str | None:
    """The type name of a named enumeration type, else ``None``."""
    if isinstance(t, Composite) and t.category == "ENUM":
        return t.target or None
    return None


def enum_type(name: str) -> Composite:
    """The type value of the enumeration type ``name``."""
    return Composite("ENUM", name)


class DeclarationTypes:
    """:class:`LoweringTypes` answered by the checker's symbol table
    (:class:`plclab.lang.check.symbols.SymbolTable`), built from the declarations of the parsed
    files before any body is checked: scopes, globals, ``VAR_EXTERNAL`` and the members of a
    block (inherited ones too, once EXTENDS exists) come from the same place the checker uses.

    ``library``: files to add when ``files`` lack the standard library (a single file parsed
    on its own); a project's files already hold it."""

    def __init__(self, files: list[A.SourceFile],
                 library: tuple[A.SourceFile, ...] = ()) -> None:
        files = list(files)
        if not any(p.name == "TON" for f in files for p in f.pous):
            files.extend(library)
        self.table = SymbolTable.collect(files)
        self.enum_values: dict[str, str] = {}
        for td in self.table.type_decls.values():
            if isinstance(td.type, A.EnumTypeRef):
                for m, _, _ in td.type.members:
                    self.enum_values.setdefault(m, td.name)

    # -- LoweringTypes ------------------------------------------------------------------------
    def type_of(self, ref: A.TypeRef | None, depth: int = 0) -> LType:
        if ref is None or depth > 20:
            return None
        if isinstance(ref, A.StringTypeRef):
            return T.WSTRING if ref.wide else T.STRING
        if isinstance(ref, A.SubrangeTypeRef):
            return self.type_of(ref.base, depth + 1)
        if isinstance(ref, A.ArrayTypeRef):
            return Composite("ARRAY", ref.elem)
        if isinstance(ref, A.StructTypeRef):
            return Composite("STRUCT", {d.name: d for d in ref.fields})
        if isinstance(ref, A.EnumTypeRef):
            return Composite("ENUM", "")
        if isinstance(ref, A.NamedTypeRef):
            t = T.lookup_elementary(ref.name)
            if t is not None:
                return t
            td = self.table.type_decls.get(ref.name)
            if td is not None:
                inner = self.type_of(td.type, depth + 1)
                if category(inner) == "ENUM":
                    return Composite("ENUM", td.name)
                return inner
            pou = self.table.pou(ref.name)
            if pou is not None and pou.kind != "FUNCTION":
                return Composite("FB", pou)
        return None

    def fb_of(self, t: LType) -> A.Pou | None:
        return t.target if isinstance(t, Composite) and t.category == "FB" else None

    def pou(self, name: str) -> A.Pou | None:
        return self.table.pou(name)

    def is_function(self, name: str) -> bool:
        if name in BUILTINS or conversion(name) is not None:
            return True
        p = self.table.pou(name)
        return p is not None and p.kind == "FUNCTION"

    def function_names(self) -> list[str]:
        return list(BUILTINS) + [k for k, v in self.table.pous.items() if v.kind == "FUNCTION"]

    def pins(self, fb: A.Pou) -> tuple[str, str] | None:
        pins = POWER_PINS.get(fb.name)
        if pins is not None:
            return pins
        decls = self.table.members(fb).values()
        ins = [d for d in decls if d.section == "VAR_INPUT" and _is_bool(d)]
        outs = [d for d in decls if d.section == "VAR_OUTPUT" and _is_bool(d)]
        return (ins[0].name, outs[0].name) if ins and outs else None

    def decl_of(self, e: A.Expr, pou: A.Pou) -> A.VarDecl | None:
        if isinstance(e, A.Name):
            return self._lookup(e.name, pou)
        return None

    def _lookup(self, name: str, pou: A.Pou) -> A.VarDecl | None:
        """The declaration ``name`` means inside ``pou`` (a global for ``VAR_EXTERNAL``; a
        FUNCTION's own name is its result variable)."""
        sym = self.table.scope(pou).lookup(name)
        return sym.decl if sym is not None else None

    def expr_type(self, e: A.Expr, pou: A.Pou) -> LType:
        if isinstance(e, A.Literal):
            return self._literal_type(e)
        if isinstance(e, A.Name):
            d = self._lookup(e.name, pou)
            if d is not None:
                return self.type_of(d.type)
            if e.name in self.enum_values:
                return Composite("ENUM", self.enum_values[e.name])
            p = self.table.pou(e.name)
            if p is not None and p.kind == "PROGRAM":
                return Composite("FB", p)
            return None
        if isinstance(e, A.Member):
            part = A.partial_access(e.field_name)
            if part is not None:
                return T.BOOL if part[0] == "X" else T.lookup_elementary(A.PARTIAL_TYPES[part[0]])
            ot = self.expr_type(e.obj, pou)
            if isinstance(ot, Composite) and ot.category == "FB":
                d = self.table.members(ot.target).get(e.field_name)
                return self.type_of(d.type) if d is not None else None
            if isinstance(ot, Composite) and ot.category == "STRUCT":
                d = ot.target.get(e.field_name)
                return self.type_of(d.type) if d is not None else None
            return None
        if isinstance(e, A.Index):
            ot = self.expr_type(e.obj, pou)
            if isinstance(ot, Composite) and ot.category == "ARRAY":
                return self.type_of(ot.target)
            return None
        if isinstance(e, A.DirectAddr):
            a = e.address
            size = a[2] if len(a) > 2 and a[2].isalpha() else "X"
            return {"X": T.BOOL, "B": T.BYTE, "W": T.WORD, "D": T.DWORD, "L": T.LWORD}.get(size)
        if isinstance(e, A.Unary):
            return self.expr_type(e.operand, pou)
        return None

    def _literal_type(self, e: A.Literal) -> LType:
        if e.kind == "BOOL":
            return T.BOOL
        if e.kind in ("INT", "REAL"):
            if e.prefix:
                return T.lookup_elementary(e.prefix) or self.type_of(
                    A.NamedTypeRef(e.loc, e.prefix))
            return T.ANY_INT_LIT if e.kind == "INT" else T.ANY_REAL_LIT
        if e.kind == "TIME":
            return T.LTIME if e.prefix == "LTIME" else T.TIME
        if e.kind in ("STRING", "WSTRING"):
            return T.STRING if e.kind == "STRING" else T.WSTRING
        if e.kind in ("DATE", "TOD", "DT"):
            return {"DATE": T.DATE, "TOD": T.TOD, "DT": T.DT}[e.kind]
        if e.kind == "ENUM":
            return Composite("ENUM", e.value[0])
        return None


def _is_bool(d: A.VarDecl) -> bool:
    return isinstance(d.type, A.NamedTypeRef) and d.type.name == "BOOL"


__all__ = ["LoweringTypes", "DeclarationTypes", "Composite", "LType", "POWER_PINS", "category",
           "type_text", "enum_name", "enum_type"]
