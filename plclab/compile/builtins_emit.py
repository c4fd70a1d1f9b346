"""How the compiler emits the standard functions: ``Builtin.emit`` -> emitter.

An emitter gets the call's argument code (already generated, each evaluated once) and returns a
Python expression. Which function uses which emitter, and which run-time helpers it calls, is
written once, in :data:`plclab.lang.builtins.BUILTINS`; the helpers live in
:mod:`plclab.runtime.rt` (``HELPERS``).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from ..lang import ast as A
from ..lang import types as T
from ..lang.builtins import Builtin

__all__ = ["EMITTERS", "Emission", "const_int"]


@dataclass(eq=False)
class Emission:
    """One call being emitted: the code generator, the function, the argument code and
    expressions, the result's base type and the call."""

    cg: Any  # plclab.compile.codegen.Codegen
    spec: Builtin
    codes: list[str]
    args: list[A.Expr]
    t: T.Type
    call: A.Call

    @property
    def native(self) -> str:
        return self.spec.natives[0]

    def real32(self, code: str) -> str:
        """Round a double to REAL when the result is REAL."""
        return f"_f32({code})" if self.t is T.REAL else code

    def widened(self, first: int = 0) -> list[str]:
        """The argument code from ``first`` on, widened to the result type (MIN, LIMIT, SEL)."""
        return self.codes[:first] + [self.cg.widen(c, a.ty, self.t, a) for c, a in
                                     zip(self.codes[first:], self.args[first:], strict=True)]


def const_int(e: A.Expr | None) -> int | None:
    """The value of an integer literal, else None."""
    if isinstance(e, A.Literal) and isinstance(e.value, int) and not isinstance(e.value, bool) \
            and e.kind == "INT":
        return e.value
    return None


def _math(m: Emission) -> str:  # SQRT, LN, ... (ATAN from the math module)
    fn = m.native if m.native != "_math" else f"_math.{m.spec.name.lower()}"
    return m.real32(f"{fn}({m.codes[0]})")


def _atan2(m: Emission) -> str:
    return m.real32(f"_math.atan2({m.codes[0]}, {m.codes[1]})")


def _to_dint(m: Emission) -> str:
    """TRUNC, ROUND: a conversion to DINT (or the integer type the context gave, in iec and
    matiec), wraps like TRUNC_DINT (TRUNC_INT)."""
    arg = m.cg.own_value(m.codes[0], m.args[0])  # a REAL argument is a REAL (ADR 0038)
    t = m.t if isinstance(m.t, T.Elementary) and m.t.kind == "int" else T.DINT
    return m.cg.wrap(f"{m.native}({arg})", t)


def _operator(m: Emission) -> str:  # ADD, MUL, SUB; AND, OR, XOR
    codes = m.widened() if m.t is T.LREAL else m.codes  # a REAL input is its REAL value
    code = "(" + f" {m.spec.operator} ".join(codes) + ")"
    t = m.t
    if m.spec.typing == "arithmetic" and t.kind in ("int", "bits") and \
            isinstance(t, T.Elementary) and t is not T.ANY_INT_LIT and \
            m.cg.operand_width(m.call.loc):
        return m.cg.wrap(code, t)  # S7: the operand type's width (ADR 0017)
    return code


def _div(m: Emission) -> str:
    fn = "_idiv" if m.t.kind in ("int", "bits") else "_rdiv"
    codes = m.widened() if m.t is T.LREAL else m.codes  # a REAL input is its REAL value
    return f"{fn}({codes[0]}, {codes[1]})"


def _extremum(m: Emission) -> str:  # MIN, MAX
    codes = m.widened()
    return codes[0] if len(codes) == 1 else f"{m.spec.name.lower()}({', '.join(codes)})"


def _limit(m: Emission) -> str:
    return f"{m.native}({', '.join(m.widened())})"


def _select(m: Emission) -> str:  # only the selected input is evaluated (as CODESYS documents)
    g, in0, in1 = m.widened(1)
    return f"({in1} if {g} else {in0})"


def _multiplex(m: Emission) -> str:  # likewise: a binary decision on K, no tuple of every input
    codes = m.widened(1)
    k = m.cg.new_tmp()
    n = len(codes) - 1
    return (f"({_mux_tree(k, codes[1:], 0, n)} if 0 <= ({k} := {codes[0]}) < {n} "
            f"else {m.native}({k}, {n}, {m.cg.where(m.call.loc)}))")


def _mux_tree(k: str, items: list[str], lo: int, hi: int) -> str:
    """Choose items[k] for lo <= k < hi with nested conditionals (depth log2 of the count)."""
    if hi - lo == 1:
        return items[lo]
    mid = (lo + hi) // 2
    return (f"({_mux_tree(k, items, lo, mid)} if {k} < {mid} else "
            f"{_mux_tree(k, items, mid, hi)})")


def _shift(m: Emission) -> str:
    """SHL/SHR/ROL/ROR on the bit pattern of IN's type; a signed result is reinterpreted
    (SHL(INT#-1, 1) = -2). A negative count is a fault, a count >= the width gives 0."""
    t, codes, name = m.t, m.codes, m.spec.name
    bits = getattr(t, "bits", 32) or 32
    mask = (1 << bits) - 1
    n = const_int(m.args[1])
    if name == "SHL" and n is not None and 0 <= n < bits:
        r = f"(({codes[0]} << {n}) & {mask})"
    elif name == "SHR" and n is not None and 0 <= n < bits:
        r = f"(({codes[0]} & {mask}) >> {n})"
    else:
        r = f"{m.native}({codes[0]}, {codes[1]}, {bits})"
    return m.cg.wrap(r, t) if getattr(t, "signed", False) and t.kind == "int" else r


def _not(m: Emission) -> str:  # NOT(x) as the operator NOT x
    t, x = m.t, m.codes[0]
    if t is T.BOOL:
        return f"(not {x})"
    if isinstance(t, T.Elementary) and not t.signed:
        return f"({x} ^ {(1 << t.bits) - 1})"
    return f"(~{x})"


def _datetime(m: Emission) -> str:
    """TIME and TOD count milliseconds, DT milliseconds since 1970, DATE seconds since 1970."""
    a, b = m.codes
    how = m.spec.operator
    if how == "date-":
        code = f"(({a} - {b}) * 1000)"
    elif how == "date+tod":
        code = f"({a} * 1000 + {b})"
    elif how == "*":
        real = T.base_of(m.args[1].ty).kind == "real"
        code = f"_round({a} * {b})" if real else f"({a} * {b})"
    elif how == "/":
        real = T.base_of(m.args[1].ty).kind == "real"
        code = f"_round(_rdiv({a}, {b}))" if real else f"_idiv({a}, {b})"
    else:
        code = f"({a} {how} {b})"
    return m.cg.wrap(code, m.t) if isinstance(m.t, T.Elementary) else code


def _compare(m: Emission) -> str:
    common = _common([a.ty for a in m.args])
    codes = [m.cg.widen(c, a.ty, common, a) for c, a in zip(m.codes, m.args, strict=True)]
    op = m.spec.operator
    if len(codes) == 2:
        return f"({codes[0]} {op} {codes[1]})"
    # GT(a, b, c) = a > b AND b > c with every input evaluated once (no short cut)
    tmps = [m.cg.new_tmp() for _ in codes[1:-1]]
    left = codes[0]
    parts = []
    for tmp, c in zip(tmps, codes[1:-1], strict=True):
        parts.append(f"({left} {op} ({tmp} := {c}))")
        left = tmp
    parts.append(f"({left} {op} {codes[-1]})")
    return "(" + " & ".join(parts) + ")"


def _common(types: list[T.Type | None]) -> T.Type | None:
    """The common type of a comparison's inputs (None when unknown)."""
    cur = types[0]
    for x in types[1:]:
        if cur is None or x is None:
            return None
        cur = T.common_type(cur, x)
    return cur


def _concat(m: Emission) -> str:
    return "(" + " + ".join(m.codes) + ")[:" + str(getattr(m.t, "length", 80)) + "]"


def _string_call(m: Emission) -> str:
    """LEFT, RIGHT, MID, DELETE with constant lengths and positions (the common case) become
    plain slices; the rest call their helper."""
    name, codes = m.spec.name, m.codes
    lit = [const_int(a) for a in m.args]
    if name == "LEFT" and lit[1] is not None and lit[1] >= 0:
        return f"{codes[0]}[:{lit[1]}]"
    if name == "RIGHT" and lit[1] is not None and lit[1] > 0:
        return f"{codes[0]}[-{lit[1]}:]"
    if name in ("MID", "DELETE") and lit[1] is not None and lit[2] is not None and \
            lit[1] >= 0 and lit[2] >= 1:
        if name == "MID":
            return f"{codes[0]}[{lit[2] - 1}:{lit[2] - 1 + lit[1]}]"
        head = f"{codes[0]}[:{lit[2] - 1}] + " if lit[2] > 1 else ""
        return f"({head}{codes[0]}[{lit[2] - 1 + lit[1]}:])"
    fast = m.cg.string_inline(name, m.args, codes)  # fastpaths.py (ADR 0034)
    return fast if fast is not None else f"{m.native}({', '.join(codes)})"


def _bcd(m: Emission) -> str:  # BCD_TO_* (limit: the target's maximum), *_TO_BCD (its width)
    limit = m.t.hi if m.spec.name.startswith(("BCD_", "BYTE_", "WORD_", "DWORD_", "LWORD_")) \
        else m.t.bits
    return f"{m.native}({m.codes[0]}, {limit})"


EMITTERS: dict[str, Callable[[Emission], str]] = {
    "bcd": _bcd,
    "math": _math,
    "abs": lambda m: f"abs({m.codes[0]})",
    "neg": lambda m: f"(-{m.codes[0]})",
    "atan2": _atan2,
    "to_dint": _to_dint,
    "move": lambda m: m.cg.copy_code(m.codes[0], m.args[0].ty),
    "expt": lambda m: f"{m.native}({m.codes[0]}, {m.codes[1]})",
    "operator": _operator,
    "bitwise": _operator,
    "not": _not,
    "datetime": _datetime,
    "div": _div,
    "mod": lambda m: f"{m.native}({m.codes[0]}, {m.codes[1]})",
    "extremum": _extremum,
    "limit": _limit,
    "select": _select,
    "multiplex": _multiplex,
    "shift": _shift,
    "compare": _compare,
    "len": lambda m: f"len({m.codes[0]})",
    "concat": _concat,
    "string_call": _string_call,
    "system_time": lambda m: "_CTX.now",  # TIME(): the scan's time in ms (wraps on store)
}
