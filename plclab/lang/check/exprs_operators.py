"""Pass helper: the operators of expressions -- unary and binary, BOOL beside 0/1, time
arithmetic -- for :class:`~plclab.lang.check.exprs.Expressions`, which inherits them (PLC0103,
PLC0104 and the conversion hints of operand types that do not match)."""

from __future__ import annotations

from .. import ast as A
from .. import types as T
from .symbols import EnumSym

_UNSIGNED = {"BYTE": "USINT", "WORD": "UINT", "DWORD": "UDINT", "LWORD": "ULINT"}


def as_bool_literal(e: A.Expr) -> bool:
    """Turn a plain ``0`` or ``1`` into the BOOL literal it is beside a BOOL operand (IEC 61131-3
    ed.2 2.2.1, ed.3 Table 5): ``b AND 1``, ``OR(0, b)``. False, and nothing changed, otherwise."""
    if isinstance(e, A.Literal) and e.kind == "INT" and e.prefix is None and e.value in (0, 1):
        e.kind, e.value, e.ty = "BOOL", bool(e.value), T.BOOL
        return True
    return False


class OperatorChecks:
    """The operator methods of :class:`~plclab.lang.check.exprs.Expressions` (``self`` is one)."""

    def unary(self, e: A.Unary, expected: T.Type | None) -> T.Type:
        t = self.expr(e.operand, expected)
        rt = T.base_of(t)
        if rt is T.ANY:
            return T.ANY
        if e.op == "NOT":
            if rt is T.BOOL or rt.kind == "bits" or rt.kind == "int":
                return t
            self.err("PLC0104", f"NOT needs BOOL or a bit string, not {t}", e.loc)
            return T.ANY
        if rt.kind in ("int", "real", "time"):
            if isinstance(rt, T.Elementary) and rt.kind == "int" and not rt.signed:
                self.warn("PLC0204", f"negating an unsigned {rt.name} wraps around", e.loc)
            return t
        if self.bits_accepted(t, "unary '-'", e.loc):  # CODESYS: -step of a BYTE (OSCAT)
            return t
        self.err("PLC0104", f"unary '-' needs a number or a TIME, not {t}", e.loc)
        return T.ANY

    def binary(self, e: A.Binary, expected: T.Type | None) -> T.Type:
        """A chain ``a + b + c + ...`` is a left-deep tree: walk its left spine with a loop
        (expected types flow down, result types up), so its length costs no recursion."""
        spine = [(e, expected)]
        while isinstance(spine[-1][0].left, A.Binary):
            node, exp = spine[-1]
            spine.append((node.left, _left_expected(node, exp)))
        bottom, exp = spine[-1]
        lt = self.expr(bottom.left, _left_expected(bottom, exp))
        for node, exp in reversed(spine):
            lt = self.binary_node(node, exp, lt)
            node.ty = lt
        return lt

    def binary_node(self, e: A.Binary, expected: T.Type | None, lt: T.Type) -> T.Type:
        """The type of ``e`` whose left operand (of type ``lt``) is checked already."""
        op = e.op
        if op in ("AND", "OR", "XOR"):
            rt = self.expr(e.right, lt if lt not in (T.ANY_INT_LIT,) else expected)
        else:
            sub_exp = expected if op in ("+", "-", "*", "/", "MOD") else None
            rt = self.expr(e.right, lt if T.resolve(lt).kind in ("enum",) else sub_exp)
            if T.resolve(rt).kind == "enum" and isinstance(e.left, A.Name) and \
                    isinstance(e.left.sym, EnumSym):
                lt = self.expr(e.left, rt)
        a, b = T.base_of(lt), T.base_of(rt)
        if isinstance(a, T.RefType | T.InterfaceType) or isinstance(b, T.RefType |
                                                                     T.InterfaceType):
            return self.cx.oop.ref_compare(e, a, b)
        if a is T.ANY or b is T.ANY:
            return T.BOOL if op in ("=", "<>", "<", "<=", ">", ">=") else T.ANY
        if op in ("AND", "OR", "XOR"):
            if a is T.BOOL and b is not T.BOOL and as_bool_literal(e.right):
                b = T.BOOL
            elif b is T.BOOL and a is not T.BOOL and as_bool_literal(e.left):
                a = T.BOOL
            if a is T.BOOL and b is T.BOOL:
                return T.BOOL
            if a.kind in ("bits", "int") and b.kind in ("bits", "int"):
                c = T.common_type(a, b)
                if c is not None:
                    return c
            self.err("PLC0104", f"{op} needs two BOOLs or two bit strings, not {a} and {b}" +
                     (" (comparisons bind tighter than AND/OR: add parentheses, e.g. "
                      "(a AND b) = c)" if T.BOOL in (a, b) else ""), e.loc)
            return T.ANY
        if op in ("=", "<>", "<", "<=", ">", ">="):
            if isinstance(a, T.EnumType) or isinstance(b, T.EnumType):
                if a is not b:
                    self.err("PLC0104", f"cannot compare {a} with {b}", e.loc)
                return T.BOOL
            c = T.common_type(a, b)
            if c is None:
                self.err("PLC0104", f"cannot compare {T.concrete(a)} with {T.concrete(b)}" +
                         _conv_hint(a, b), e.loc)
            return T.BOOL
        # arithmetic
        ka, kb = a.kind, b.kind
        if ka in ("time", "tod", "dt", "date") or kb in ("time", "tod", "dt", "date"):
            return self.time_arith(e, a, b)
        if op == "**":
            if ka in ("int", "real") and kb in ("int", "real"):
                if ka == "real" and a is not T.ANY_REAL_LIT:
                    return a
                return T.LREAL if a in (T.DINT, T.LINT, T.UDINT, T.ULINT) else T.REAL
            self.err("PLC0104", f"'**' needs numbers, not {a} and {b}", e.loc)
            return T.ANY
        if op == "MOD":
            if ka in ("int", "bits") and kb in ("int", "bits"):
                c = T.common_type(a, b)
                if c is not None:
                    return c
            self.err("PLC0104", f"MOD needs integers, not {T.concrete(a)} and {T.concrete(b)}",
                     e.loc)
            return T.ANY
        if ka in ("int", "real", "bits") and kb in ("int", "real", "bits"):
            c = T.common_type(a, b)
            if c is None and "bits" in (ka, kb) and "real" in (ka, kb):
                # CODESYS: ``r * x`` with x a BYTE computes in REAL (OSCAT BYTE_TO_RANGE)
                bits = a if ka == "bits" else b
                if self.bits_accepted(bits, f"arithmetic '{op}'", e.loc):
                    return T.common_type(T.ELEMENTARY[_UNSIGNED[T.base_of(bits).name]],
                                         b if ka == "bits" else a) or T.ANY
            if c is not None and c.kind != "bits":
                return c
            if c is not None and c.kind == "bits":
                if self.bits_accepted(c, f"arithmetic '{op}'", e.loc):
                    return c
                self.err("PLC0104", f"arithmetic '{op}' is not defined on bit strings ({c}); "
                         f"convert to an integer first, e.g. {c.name}_TO_UINT(...)", e.loc)
                return T.ANY
        if isinstance(a, T.StringType) and op == "+":
            self.err("PLC0104", "strings are joined with CONCAT(a, b), not '+'", e.loc)
            return T.ANY
        self.err("PLC0104", f"operator '{op}' cannot combine {T.concrete(a)} and "
                 f"{T.concrete(b)}" + _conv_hint(a, b), e.loc)
        return T.ANY

    def time_arith(self, e: A.Binary, a: T.Type, b: T.Type) -> T.Type:
        op, ka, kb = e.op, a.kind, b.kind
        if ka == "time" and kb == "time" and op in ("+", "-"):
            return T.LTIME if T.LTIME in (a, b) else T.TIME
        if ka == "time" and kb in ("int", "real") and op in ("*", "/"):
            return a
        if kb == "time" and ka in ("int", "real") and op == "*":
            return b
        if ka in ("tod", "dt") and kb == "time" and op in ("+", "-"):
            return a
        if ka == kb and ka in ("tod", "dt", "date") and op == "-":
            return T.TIME
        self.err("PLC0104", f"operator '{op}' cannot combine {T.concrete(a)} and "
                 f"{T.concrete(b)} (TIME + TIME, TIME * number, TOD + TIME and DT - DT are "
                 "defined)", e.loc)
        return T.ANY


def _left_expected(e: A.Binary, expected: T.Type | None) -> T.Type | None:
    """The type expected of the left operand of ``e`` when ``e`` is expected to be ``expected``."""
    if e.op in ("AND", "OR", "XOR") or e.op in ("+", "-", "*", "/", "MOD"):
        return expected
    return None


def _conv_hint(a: T.Type, b: T.Type) -> str:
    a, b = T.concrete(a), T.concrete(b)
    if a.kind in ("int", "real", "bits") and b.kind in ("int", "real", "bits"):
        return f"; convert one side, e.g. {a.name}_TO_{b.name}(...)"
    return ""
