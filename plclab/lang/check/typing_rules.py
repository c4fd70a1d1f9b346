"""The typing rules of the standard functions: ``Builtin.typing`` -> rule.

A rule gets the call's argument types (already checked) and returns the result type, reporting
PLC0107 when the arguments do not fit. Which function follows which rule is written once, in
:data:`plclab.lang.builtins.BUILTINS`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from .. import ast as A
from .. import types as T
from ..builtins import Builtin
from .exprs_operators import as_bool_literal

__all__ = ["TYPING_RULES", "Typing"]


_UNSIGNED = {"BYTE": "USINT", "WORD": "UINT", "DWORD": "UDINT", "LWORD": "ULINT"}


@dataclass(eq=False)
class Typing:
    """One call being typed: the pass (to report), the function, the argument types ``ts``,
    their base types ``bs`` and the argument expressions ``vals``."""

    cx: Any  # the calls pass
    spec: Builtin
    ts: list[T.Type]
    bs: list[T.Type]
    call: A.Call
    vals: list[A.Expr]
    expected: T.Type | None = None  # the type the call's context expects, if it says

    def need(self, ok: bool, what: str) -> None:
        if not ok:
            self.cx.err("PLC0107", f"{self.spec.name} needs {what}, not " +
                        ", ".join(str(T.concrete(b)) for b in self.bs), self.call.loc)

    def common(self, items: list[T.Type]) -> T.Type:
        cur = items[0]
        for x in items[1:]:
            nxt = T.common_type(cur, x)
            if nxt is None:
                nxt = self.bits_as_unsigned(cur, x)
            if nxt is None:
                self.cx.err("PLC0107", f"{self.spec.name}: the arguments {T.concrete(cur)} and "
                            f"{T.concrete(x)} have no common type", self.call.loc)
                return T.ANY
            cur = nxt
        return cur

    def bits_as_unsigned(self, a: T.Type, b: T.Type) -> T.Type | None:
        """CODESYS: ``LIMIT(0, in, mx)`` with an INT and a BYTE takes the BYTE as the unsigned
        integer of its size (USINT), so the common type is INT (PLC0173; ADR 0051)."""
        ra, rb = T.base_of(a), T.base_of(b)
        kinds = {ra.kind, rb.kind}
        if "bits" not in kinds or not kinds <= {"bits", "int", "real"} or T.BOOL in (ra, rb):
            return None
        bits = ra if ra.kind == "bits" else rb
        if not self.cx.cx.exprs.bits_accepted(bits, f"{self.spec.name} of a bit string and a "
                                              "number", self.call.loc):
            return None
        u = T.ELEMENTARY[_UNSIGNED[bits.name]]
        return T.common_type(u, rb if bits is ra else ra) if kinds != {"bits"} else None

    def kinds(self, *kinds: str) -> bool:
        return all(b.kind in kinds for b in self.bs)


def _number_same(t: Typing) -> T.Type:  # ABS, NEG
    t.need(t.bs[0].kind in ("int", "real"), "a number")
    return t.ts[0]


def _float(t: Typing) -> T.Type:  # SQRT, LN, ..., ATAN: REAL stays REAL, else LREAL or REAL
    b = t.bs[0]
    t.need(b.kind in ("int", "real"), "a number")
    return t.ts[0] if b.kind == "real" and b is not T.ANY_REAL_LIT else (
        T.LREAL if b is T.ANY_REAL_LIT or getattr(b, "bits", 0) > 16 else T.REAL)


def _atan2(t: Typing) -> T.Type:
    return t.common(t.bs) if t.kinds("real") else T.LREAL


def _to_dint(t: Typing) -> T.Type:
    """TRUNC, ROUND: DINT, as in CODESYS; where ``Dialect.trunc_by_context`` (iec, matiec) the
    integer type the context expects (ed.2 Table 22: ANY_REAL -> ANY_INT), else DINT."""
    t.need(t.bs[0].kind == "real", "a REAL or LREAL")
    want = T.base_of(t.expected) if t.expected is not None else None
    if t.spec.name == "TRUNC" and isinstance(want, T.Elementary) and want.kind == "int" \
            and want is not T.ANY_INT_LIT and t.cx.cx.dialect(t.call.loc).trunc_by_context:
        return want
    return T.DINT


def _same(t: Typing) -> T.Type:  # MOVE
    return t.ts[0]


def _expt(t: Typing) -> T.Type:
    t.need(t.bs[0].kind in ("int", "real") and t.bs[1].kind in ("int", "real"), "numbers")
    return t.ts[0] if t.bs[0].kind == "real" and t.bs[0] is not T.ANY_REAL_LIT else T.LREAL


def _arithmetic(t: Typing) -> T.Type:  # ADD, MUL, SUB, DIV, MOD
    if len(t.bs) == 2 and any(b.kind in ("tod", "dt", "date") for b in t.bs):
        return _clock_arithmetic(t)
    r = t.common(t.bs)
    t.need(r is T.ANY or r.kind in ("int", "real", "time"), "numbers")
    return r


def _clock_arithmetic(t: Typing) -> T.Type:
    """ADD and SUB on dates and times of day, as the operators '+' and '-' (IEC 61131-3 ed.2
    Table 30 overloads them: TOD/DT + TIME, TOD/DT - TIME, TOD - TOD and DT - DT, which MATIEC
    accepts as SUB(DT, DT) in a Beremiz FBD; ADR 0037). DATE - DATE: SUB_DATE_DATE."""
    (a, b), name = t.bs, t.spec.name
    if name in ("ADD", "SUB") and a.kind in ("tod", "dt") and b.kind == "time":
        return t.ts[0]
    if name == "SUB" and a.kind == b.kind and a.kind in ("tod", "dt"):
        return T.TIME
    t.need(False, "TOD or DT and a TIME (ADD, SUB), or two TODs or two DTs (SUB); for DATE "
           "- DATE, SUB_DATE_DATE")
    return T.ANY


def _extremum(t: Typing) -> T.Type:  # MIN, MAX, LIMIT
    return t.common(t.bs)


def _select(t: Typing) -> T.Type:
    t.need(t.bs[0] is T.BOOL, "a BOOL selector G first")
    return t.common(t.bs[1:])


def _multiplex(t: Typing) -> T.Type:
    t.need(t.bs[0].kind == "int", "an integer selector K first")
    return t.common(t.bs[1:])


def _bitwise(t: Typing) -> T.Type:  # AND, OR, XOR, NOT: all BOOL, or bit strings/integers
    if T.BOOL in t.bs and len(t.bs) > 1:  # AND(b, 1): a plain 0 or 1 beside a BOOL is a BOOL
        t.bs = [T.BOOL if b is not T.BOOL and as_bool_literal(v) else b
                for b, v in zip(t.bs, t.vals, strict=True)]
    if all(b is T.BOOL for b in t.bs):
        return T.BOOL
    if not t.kinds("bits", "int"):
        t.need(False, "BOOLs or bit strings")
        return T.ANY
    return t.common(t.bs) if len(t.bs) > 1 else t.ts[0]


def _shift(t: Typing) -> T.Type:
    t.need(t.bs[0].kind in ("bits", "int") and t.bs[1].kind == "int",
           "a bit string and a shift count")
    return t.ts[0] if t.bs[0] is not T.ANY_INT_LIT else T.DWORD


def _compare(t: Typing) -> T.Type:
    t.common(t.bs)
    return T.BOOL


def _signature(t: Typing) -> T.Type:
    """Fixed argument kinds (``Builtin.args``: STRING, INT or BITS) and result (``Builtin.result``:
    ``IN`` for the first argument's type, else a type name)."""
    ok = all(isinstance(b, T.StringType) if k == "STRING" else
             b.kind == "bits" or b is T.ANY_INT_LIT if k == "BITS" else b.kind == "int"
             for k, b in zip(t.spec.args, t.bs, strict=False))
    t.need(ok, t.spec.needs)
    return t.ts[0] if t.spec.result == "IN" else T.lookup_elementary(t.spec.result)


def _datetime(t: Typing) -> T.Type:
    """ADD_TIME, SUB_DT_DT, ...: each argument of the type ``Builtin.args`` names (NUM: any
    integer or REAL), the result ``Builtin.result``."""
    ok = all(b.kind in ("int", "real") and b is not T.BOOL if k == "NUM" else
             T.same_type(b, T.lookup_elementary(k))
             for k, b in zip(t.spec.args, t.bs, strict=False))
    t.need(ok, t.spec.needs)
    return T.lookup_elementary(t.spec.result)


def _concat(t: Typing) -> T.Type:
    t.need(all(isinstance(b, T.StringType) for b in t.bs), "STRINGs")
    wide = any(getattr(b, "wide", False) for b in t.bs)
    return T.StringType(wide, 80)


def _message(t: Typing, n: int) -> None:
    """The optional last argument of an assertion: a STRING literal shown when it fails."""
    if len(t.call.target.inputs) > n:
        msg = t.call.target.inputs[n][1]
        if not (isinstance(msg, A.Literal) and msg.kind in ("STRING", "WSTRING")):
            t.cx.err("PLC0107", f"the message of {t.spec.name} is a string literal, e.g. "
                     "'the motor starts'", msg.loc)
        del t.bs[n:], t.ts[n:]


def _assert_compare(t: Typing) -> T.Type:
    _message(t, 2)
    a, b = t.bs[0], t.bs[1]
    if T.common_type(a, b) is None and not (isinstance(a, T.EnumType) and a is b):
        t.cx.err("PLC0107", f"{t.spec.name} compares values of one type, not {T.concrete(a)} "
                 f"and {T.concrete(b)}", t.call.loc)
    return T.VOID


def _assert_bool(t: Typing) -> T.Type:
    _message(t, 1)
    t.need(t.bs[0] is T.BOOL, "a BOOL")
    return T.VOID


def _assert_near(t: Typing) -> T.Type:
    _message(t, 3)
    t.need(t.kinds("int", "real", "time"), "numbers")
    return T.VOID


def _advance_time(t: Typing) -> T.Type:
    t.need(t.bs[0].kind == "time", "a TIME, e.g. ADVANCE_TIME(T#100ms)")
    return T.VOID


def _system_time(t: Typing) -> T.Type:
    d = t.cx.cx.dialect(t.call.loc)
    if not d.system_time:
        t.cx.err("PLC0106", f"TIME() (the time since the PLC started) is a CODESYS function; "
                 f"the dialect '{d.name}' has none: time an interval with a TON, or choose "
                 "{dialect 'codesys'}", t.call.loc)
    return T.TIME


TYPING_RULES: dict[str, Callable[[Typing], T.Type]] = {
    "number_same": _number_same, "float": _float, "atan2": _atan2, "to_dint": _to_dint,
    "same": _same, "expt": _expt, "arithmetic": _arithmetic, "extremum": _extremum,
    "limit": _extremum, "select": _select, "multiplex": _multiplex, "shift": _shift,
    "bitwise": _bitwise, "datetime": _datetime,
    "compare": _compare, "signature": _signature, "concat": _concat,
    "assert_compare": _assert_compare, "assert_bool": _assert_bool,
    "assert_near": _assert_near, "advance_time": _advance_time, "system_time": _system_time,
}
