"""Pass: constant evaluation -- folding constant expressions, enumeration values, and the
cycles among constants, enumeration values and types (PLC0122, PLC0123, PLC0124, PLC0125)."""

from __future__ import annotations

import math
from typing import Any

from ...errors import Location
from .. import ast as A
from .. import types as T
from .pass_api import Pass
from .symbols import EnumSym, Scope, VarSym

_CHAIN_LIMIT = 64  # named types / constants defined through each other, at most this deep
_CONST_BITS = 128  # constant folding stops beyond this (no IEC integer has more than 64)


class Constants(Pass):
    """Folds constant expressions in the scope ``cx.scope``; evaluates each constant once."""

    def __init__(self, cx) -> None:
        super().__init__(cx)
        # what is being evaluated or resolved right now (constants, types, enumeration values):
        # meeting one of them again is a cycle (PLC0122)
        self._chain: list[tuple[Any, str, Location | None]] = []
        self._chain_keys: set[Any] = set()
        self._cycles_seen: set[frozenset] = set()
        self._too_deep = False
        self._const_memo: dict[int, Any] = {}  # id(VarDecl) -> folded value
        self._broken: set[int] = set()  # constants whose value has a reported error
        self._broken_hits = 0  # uses of such constants (their users need no second error)
        self.global_consts: dict[str, A.VarDecl] = {}  # visible to TYPEs before globals are
        self.enum_index: dict[str, str] = {}  # member name -> TYPE not yet resolved
        self.enum_pending: dict[int, tuple[A.Expr | None, EnumSym | None, Location]] = {}

    def enter(self, key: Any, label: str, loc: Location | None) -> bool:
        """Start evaluating ``key``; False (and PLC0122 once) if it is already under way."""
        if key in self._chain_keys:
            i = next(k for k, (ck, _, _) in enumerate(self._chain) if ck == key)
            cyc = self._chain[i:]
            ident = frozenset(ck for ck, _, _ in cyc)
            if ident not in self._cycles_seen:
                self._cycles_seen.add(ident)
                names = " -> ".join([lab for _, lab, _ in cyc] + [label])
                structs = [ck[1] for ck, _, _ in cyc if isinstance(ck, tuple) and
                           isinstance(self.table.type_decls[ck[1]].type, A.StructTypeRef)]
                if structs:
                    self.err("PLC0123", f"structure {structs[0]} contains itself ({names}): it "
                             "would be infinitely large; remove the field that closes the "
                             "circle", cyc[0][2])
                else:
                    self.err("PLC0122", f"{names}: these are defined in terms of each other; "
                             "give one of them a value that does not depend on the others",
                             cyc[0][2])
            return False
        self._chain.append((key, label, loc))
        self._chain_keys.add(key)
        return True

    def chain_too_deep(self, what: str, remedy: str, loc: Location | None) -> bool:
        """True when the definitions under way are :data:`_CHAIN_LIMIT` deep (PLC0124, once)."""
        if len(self._chain) < _CHAIN_LIMIT:
            return False
        if not self._too_deep:
            self._too_deep = True
            path = " -> ".join(lab for _, lab, _ in self._chain[:4])
            self.err("PLC0124", f"{what} are defined in terms of each other more than "
                     f"{_CHAIN_LIMIT} levels deep ({path} -> ...); {remedy}", loc)
        return True

    def leave(self) -> None:
        key, _, _ = self._chain.pop()
        self._chain_keys.discard(key)

    def enum_value(self, sym: EnumSym) -> int | None:
        """The value of an enumeration member, evaluated on first use (values may refer to
        constants and to other members; a circle among them is PLC0122)."""
        walked: list[EnumSym] = []  # implicit values, from ``sym`` back to an explicit one
        s: EnumSym | None = sym
        while s is not None and id(s) in self.enum_pending and \
                self.enum_pending[id(s)][0] is None:
            walked.append(s)
            s = self.enum_pending[id(s)][1]
        entered = 0
        try:
            for w in walked:
                if not self.enter(id(w), f"{w.type.name}.{w.member}",
                                  self.enum_pending[id(w)][2]):
                    return None
                entered += 1
            if s is None:
                base: int | None = -1
            elif id(s) not in self.enum_pending:
                base = s.value
            else:  # an explicit value still to evaluate
                expr, _, loc = self.enum_pending[id(s)]
                if not self.enter(id(s), f"{s.type.name}.{s.member}", loc):
                    return None
                try:
                    base = self.const_int(expr)
                finally:
                    self.leave()
                self.enum_pending.pop(id(s), None)
                s.value = base if base is not None else 0
                s.type.members[s.member] = s.value
        finally:
            for _ in range(entered):
                self.leave()
        if base is None:
            return None
        for k, w in enumerate(reversed(walked)):
            w.value = base + k + 1
            w.type.members[w.member] = w.value
            self.enum_pending.pop(id(w), None)
        return sym.value

    def const_of(self, d: A.VarDecl, scope: Scope) -> Any:
        """The folded value of constant ``d`` (evaluated once, in its own ``scope``)."""
        key = id(d)
        if key in self._const_memo:
            if key in self._broken:
                self._broken_hits += 1
            return self._const_memo[key]
        if self.chain_too_deep("constants", "give some of them literal values", d.loc):
            self._broken_hits += 1
            return None
        if not self.enter(key, d.spelling or d.name, d.loc):
            self._broken_hits += 1
            return None
        old, before = self.cx.scope, (len(self.cx.diags), self._broken_hits)
        self.cx.scope = scope
        try:
            v = self.const_value(d.init) if d.init is not None else _default(d)
        finally:
            self.cx.scope = old
            self.leave()
        if (len(self.cx.diags), self._broken_hits) != before:
            self._broken.add(key)  # its error is reported: users of it need no second one
        self._const_memo[key] = v
        return v

    def const_value(self, e: A.Expr) -> Any:
        """Evaluate a constant expression (literals, constants, arithmetic); None if not."""
        if isinstance(e, A.Literal):
            if e.kind == "ENUM":
                return None
            if e.kind == "TIME":
                return e.value
            return e.value
        if isinstance(e, A.Name):
            sym = self.cx.scope.local(e.name)
            d, scope = None, self.cx.scope
            if isinstance(sym, VarSym):
                d = sym.decl
                scope = Scope() if sym.storage == "global" else self.cx.scope
            else:
                d, scope = self.table.globals.get(e.name) or self.global_consts.get(e.name), Scope()
            if d is not None and d.constant and (d.init is not None or _default(d) is not None):
                d.used = True
                return self.const_of(d, scope)
            if e.name not in self.table.enum_members and e.name in self.enum_index:
                tname = self.enum_index.pop(e.name)  # declared later: resolve it now
                self.cx.decls.named_type(tname, e.loc)
            if e.name in self.table.enum_members and len(self.table.enum_members[e.name]) == 1:
                return self.enum_value(self.table.enum_members[e.name][0])
            return None
        if isinstance(e, A.Unary):
            v = self.const_value(e.operand)
            if v is None:
                return None
            if e.op == "-":
                return -v
            if e.op == "NOT" and isinstance(v, bool):
                return not v
            return None
        if isinstance(e, A.Binary):
            a, b = self.const_value(e.left), self.const_value(e.right)
            if a is None or b is None or isinstance(a, str) or isinstance(b, str):
                return None
            try:
                match e.op:
                    case "+":
                        r = a + b
                    case "-":
                        r = a - b
                    case "*":
                        r = a * b
                    case "/":
                        if isinstance(a, int) and isinstance(b, int):
                            q = abs(a) // abs(b)
                            r = q if (a >= 0) == (b >= 0) else -q
                        else:
                            r = a / b
                    case "MOD":
                        r = a - b * (abs(a) // abs(b)) * (1 if (a >= 0) == (b >= 0) else -1) \
                            if isinstance(a, int) and isinstance(b, int) else math.fmod(a, b)
                    case _:
                        return None
            except (ZeroDivisionError, ValueError):
                self.err("PLC2001", "division by zero in a constant expression", e.loc)
                return None
            except OverflowError:
                r = math.inf
            return self._bounded(r, e)
        return None

    def _bounded(self, v: Any, e: A.Expr) -> Any:
        """A folded value no IEC type can hold (integers beyond 128 bits, floats beyond LREAL)
        is PLC0125, so that folding never builds huge numbers."""
        if isinstance(v, bool):
            return v
        if isinstance(v, int) and v.bit_length() > _CONST_BITS:
            self.err("PLC0125", f"this constant expression is larger than any integer type "
                     f"(more than {_CONST_BITS} bits); use smaller values", e.loc)
            return None
        if isinstance(v, float) and not math.isfinite(v):
            self.err("PLC0125", "this constant expression overflows LREAL (beyond "
                     "1.8E308); use smaller values", e.loc)
            return None
        return v

    def const_int(self, e: A.Expr) -> int | None:
        before = (len(self.cx.diags), self._broken_hits)
        v = self.const_value(e)
        if (len(self.cx.diags), self._broken_hits) != before:  # explained (a cycle, an overflow)
            return v if isinstance(v, int) and not isinstance(v, bool) else None
        if isinstance(v, bool) or not isinstance(v, int):
            self.err("PLC0109", "a constant integer expression is needed here (a literal or a "
                     "VAR CONSTANT)", e.loc)
            return None
        return v


def _default(d: A.VarDecl) -> Any:
    """The value of a constant declared without one (the iec and matiec dialects): its type's
    default initial value, for a number or a BOOL; None (not foldable) for other types."""
    if not d.constant or d.ty is None:
        return None
    if isinstance(T.resolve(d.ty), T.Subrange):
        return T.resolve(d.ty).lo  # a subrange starts at its lower bound
    t = T.base_of(d.ty)
    if t is T.BOOL:
        return False
    return {"int": 0, "bits": 0, "real": 0.0}.get(t.kind) if isinstance(t, T.Elementary) else None
