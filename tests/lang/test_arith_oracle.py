"""The arithmetic oracle (issue 11, item 4): random, well-typed ST expressions over every
elementary type, compiled by plclab and compared with a reference evaluator written here from
the IEC 61131-3 rules and the semantics the README and docs/adr/0002-arithmetic-semantics.md
document. Nothing here imports plclab's code generator or run-time helpers.

The rules the reference follows:

* integers: intermediate results are exact; a value wraps to its type (two's complement) when it
  is stored or converted to a type it does not widen to; a conversion's argument is first the
  value its own type holds (``SINT_TO_INT(s * s * s)`` converts the SINT the hardware's register
  would hand over, and ``REAL_TO_DINT(r + 1.0)`` a sum rounded to single precision), as the
  value of a CASE selector and an array index (ADR 0038); ``/`` truncates toward zero and MOD has
  the sign of the dividend; dividing by zero (integer or REAL) is the run-time fault PLC2001;
* REAL is IEEE single: every store into a REAL (and every conversion or math function with a
  REAL result) rounds to nearest, ties to even; the operators keep intermediates in double;
* implicit conversions only widen (IEC 61131-3 3rd ed., Figure 11); a widened integer keeps its
  exact value, TIME widens to LTIME as nanoseconds; a REAL expression widened to LREAL is the
  REAL value first (rounded to single, as ``REAL_TO_LREAL`` of it: ADR 0038, decision 4);
* REAL -> integer rounds half away from zero, TRUNC toward zero, NaN/inf is PLC2006;
* a bare ``TRUNC`` returns DINT in codesys and s7; in iec and matiec it is ANY_INT typed by its
  context (IEC 61131-3 2nd ed., Table 22; ADR 0052), so there an expression holding one is
  never the narrower operand of an implicit widening, whose type it would take instead;
* bit strings: SHL/SHR shift in zeros (a count >= the width gives 0), ROL/ROR rotate modulo the
  width, a negative count is PLC2020;
* math functions follow IEEE 754 / C99 Annex F (SQRT(-1) = NaN, LN(0) = -inf, SIN(inf) = NaN);
  EXPT of two integers is the exact power rounded once;
* SEL and MUX evaluate only the selected input (as CODESYS documents); a MUX selector outside
  the inputs is PLC2002.

Run ``PLCLAB_ORACLE_N=100000 pytest tests/lang/test_arith_oracle.py`` for the long run
(``PLCLAB_ORACLE_SEED`` picks another seed).
"""

from __future__ import annotations

import math
import os
import random
import struct
import time
from collections.abc import Callable
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import pytest

import plclab
from plclab.errors import PlcRuntimeFault
from plclab.runtime.plc import Plc
from plclab.testing import run_compiled_tests

N_DEFAULT = 10_000  # codesys in the normal suite; PLCLAB_ORACLE_N=200000 for the long run
N_OTHER = 3_000  # per other dialect in the normal suite
BATCH = 500
SEED = 20240611

# -- the types (IEC 61131-3 Table 10) -------------------------------------------------------
SIGNED = {"SINT": 8, "INT": 16, "DINT": 32, "LINT": 64}
UNSIGNED = {"USINT": 8, "UINT": 16, "UDINT": 32, "ULINT": 64}
BITS = {"BYTE": 8, "WORD": 16, "DWORD": 32, "LWORD": 64}
INTS = {**SIGNED, **UNSIGNED}
REALS = ("REAL", "LREAL")
TIMES = {"TIME": 32, "LTIME": 64}  # TIME in ms (signed 32 bit), LTIME in ns (signed 64 bit)
ALL = [*INTS, *BITS, "BOOL", *REALS, *TIMES]

# implicit (widening) conversions, IEC 61131-3 3rd edition, Figure 11
WIDEN = {
    "SINT": {"INT", "DINT", "LINT", "REAL", "LREAL"},
    "INT": {"DINT", "LINT", "REAL", "LREAL"},
    "DINT": {"LINT", "LREAL"},
    "USINT": {"UINT", "UDINT", "ULINT", "INT", "DINT", "LINT", "REAL", "LREAL"},
    "UINT": {"UDINT", "ULINT", "DINT", "LINT", "REAL", "LREAL"},
    "UDINT": {"ULINT", "LINT", "LREAL"},
    "BYTE": {"WORD", "DWORD", "LWORD"},
    "WORD": {"DWORD", "LWORD"},
    "DWORD": {"LWORD"},
    "REAL": {"LREAL"},
    "TIME": {"LTIME"},
}


class RefFault(Exception):
    """The reference's run-time fault: the PLC must stop with this code."""

    def __init__(self, code: str) -> None:
        super().__init__(code)
        self.code = code


# -- reference arithmetic -------------------------------------------------------------------
def width(t: str) -> int:
    return {**INTS, **BITS, **TIMES}[t]


def is_signed(t: str) -> bool:
    return t in SIGNED or t in TIMES


def wrap(v: int, t: str) -> int:
    """Two's complement wrap of an exact integer into type t."""
    n = width(t)
    v %= 1 << n
    return v - (1 << n) if is_signed(t) and v >= 1 << (n - 1) else v


def single(x: int | float) -> float:
    """Round an exact integer or a double to IEEE single: nearest, ties to even; overflow to
    +-inf (IEEE 754 4.3.1). Written from the definition, with exact rationals."""
    if isinstance(x, float) and (x != x or x in (math.inf, -math.inf) or x == 0):
        return x
    if x == 0:
        return 0.0
    q = Fraction(x)
    sign = -1 if q < 0 else 1
    q = abs(q)
    e = q.numerator.bit_length() - q.denominator.bit_length()  # 2**e <= q < 2**(e+2)
    if Fraction(2) ** e > q:
        e -= 1
    quantum = Fraction(2) ** (max(e, -126) - 23)  # 24-bit significand; subnormals below -126
    n, rest = divmod(q, quantum)
    if rest * 2 > quantum or (rest * 2 == quantum and n % 2 == 1):
        n += 1
    r = n * quantum
    if r >= Fraction(2) ** 128:
        return sign * math.inf
    return sign * float(r)


def to_double(x: int | float) -> float:
    """An exact integer widened to LREAL: rounded to nearest double; too large is +-inf."""
    try:
        return float(x)
    except OverflowError:
        return math.inf if x > 0 else -math.inf


def round_away(x: float) -> int:
    """REAL -> integer: half away from zero (CODESYS); NaN and inf cannot be converted."""
    if x != x or x in (math.inf, -math.inf):
        raise RefFault("PLC2006")
    q = Fraction(x)
    n = abs(q.numerator) // q.denominator
    if abs(q) - n >= Fraction(1, 2):
        n += 1
    return n if q >= 0 else -n


def trunc(x: float) -> int:
    if x != x or x in (math.inf, -math.inf):
        raise RefFault("PLC2006")
    q = Fraction(x)
    n = abs(q.numerator) // q.denominator
    return n if q >= 0 else -n


def idiv(a: int, b: int) -> int:
    if b == 0:
        raise RefFault("PLC2001")
    q = abs(a) // abs(b)
    return q if (a < 0) == (b < 0) else -q


def imod(a: int, b: int) -> int:
    return a - b * idiv(a, b)


def rdiv(a: float, b: float) -> float:
    if b == 0:
        raise RefFault("PLC2001")
    return a / b


def ieee(fn: Callable[[float], float], x: float) -> float:
    """A math function with IEEE 754 results where Python's math raises (C99 Annex F)."""
    x = to_double(x)
    if x != x:
        return x
    try:
        return fn(x)
    except ValueError:
        return -math.inf if fn in (math.log, math.log10) and x == 0 else math.nan
    except OverflowError:
        return math.inf


def power(a: int | float, b: int | float) -> float:
    """EXPT: integers give the exact power rounded once; otherwise IEEE pow (C99 F.9.4.4)."""
    if isinstance(a, int) and isinstance(b, int):
        if b >= 0:
            if abs(a) >= 2 and b * (abs(a).bit_length() - 1) > 1100:
                return -math.inf if a < 0 and b % 2 else math.inf
            return to_double(a ** b)
        if a == 0:
            return math.inf
        if abs(a) >= 2 and -b * (abs(a).bit_length() - 1) > 1200:
            return -0.0 if a < 0 and b % 2 else 0.0
        return float(Fraction(1, a ** -b))
    a, b = to_double(a), to_double(b)
    odd = b == int(b) and abs(b) < 2 ** 53 and int(b) % 2 == 1 if math.isfinite(b) else False
    if a == 0 and b < 0:
        return math.copysign(math.inf, a) if odd else math.inf
    try:
        return math.pow(a, b)
    except OverflowError:
        return -math.inf if a < 0 and odd else math.inf
    except ValueError:
        return math.nan


def widened(v: Any, src: str, dst: str) -> Any:
    """The value of an implicit widening from src to dst."""
    if src == dst:
        return v
    if src == "REAL" and dst == "LREAL":
        return single(v)
    if dst in REALS:
        return to_double(v) if isinstance(v, int) else v
    if src == "TIME" and dst == "LTIME":
        return v * 1_000_000
    return v


def store(v: Any, t: str) -> Any:
    """What a variable of type t holds after ``x := v``."""
    if t == "BOOL":
        return bool(v)
    if t == "REAL":
        return single(v)
    if t == "LREAL":
        return to_double(v)
    return wrap(v, t)


def convert(v: Any, src: str, dst: str) -> Any:
    """SRC_TO_DST: widening keeps the value; integers wrap; REAL -> integer rounds."""
    if dst == "BOOL":
        return v != 0
    if src == "BOOL":
        v = int(v)
        src = "USINT"
    if dst in REALS:
        if src == "TIME" or src == "LTIME":
            v = v  # the number of ms (ns)
        return single(v) if dst == "REAL" else to_double(v)
    if src in REALS:
        return wrap(round_away(v), dst)
    if src == "LTIME" and dst == "TIME":
        return wrap(idiv(v, 1_000_000), dst)
    if src == "TIME" and dst == "LTIME":
        return v * 1_000_000
    if dst in WIDEN.get(src, ()):
        return v
    return wrap(v, dst)


def shift(op: str, x: int, n: int, t: str) -> int:
    bits = width(t)
    if n < 0:
        raise RefFault("PLC2020")
    x = wrap(x, t)
    if op == "SHL":
        return wrap(x << n, t) if n < bits else 0
    if op == "SHR":
        return x >> n if n < bits else 0
    n %= bits
    if op == "ROR":
        n = (bits - n) % bits
    return wrap((x << n) | (x >> (bits - n)), t)


def first_min(vals: list, less: bool) -> Any:
    """MIN/MAX as ``IF x < m THEN m := x`` over the inputs in order."""
    m = vals[0]
    for x in vals[1:]:
        if (x < m) if less else (x > m):
            m = x
    return m


# -- expressions: text plus a reference evaluation ------------------------------------------
@dataclass
class Node:
    text: str
    ty: str
    ev: Callable[[], Any]
    lit: bool = False  # a literal: the checker folds '-' into it and range-checks the result


def real_text(x: float) -> str:
    s = repr(x)
    if "e" in s:
        mant, _, exp = s.partition("e")
        if "." not in mant:
            mant += ".0"
        s = f"{mant}E{int(exp)}"
    return s


def literal_text(v: Any, t: str) -> str:
    if t == "BOOL":
        return "TRUE" if v else "FALSE"
    if t in REALS:
        return f"{t}#{real_text(v)}"
    if t == "TIME":
        return f"T#{v}ms"
    if t == "LTIME":
        return f"LTIME#{v}ns"
    if t in BITS:
        return f"{t}#16#{v:X}"
    return f"{t}#{v}"


LINT_EDGES = [2 ** 60 + 2 ** 36 + 1, 2 ** 53 + 1, -(2 ** 53) - 1, 16_777_217, 2 ** 62]
REAL_EDGES = [0.5, 1.5, 2.5, -0.5, -2.5, 0.49999997, 1e-30, 3.4028235e38, -3.4028235e38,
              1.4e-45, 16777216.0, 123.456, 1e10, -7.0, 100.0, 0.1]
LREAL_EDGES = [0.49999999999999994, 4503599627370497.0, 9.3e18, -9.3e18, 1e300, -1e300,
               5e-324, 2.0 ** 63, 1e-10, 1e16 + 2.0, 0.1, math.pi]


class Gen:
    """Random well-typed expressions over a pool of variables with random values."""

    def __init__(self, rng: random.Random, dialect: str = "codesys") -> None:
        self.rng = rng
        # S7 computes + - * (and ADD, SUB, MUL) of integers in the operands' width (ADR 0017);
        # the other dialects keep the exact intermediate, as a register does (ADR 0002)
        self.operand_width = dialect == "s7"
        # MATIEC counts seconds when it converts between TIME and a number (ADR 0029): those
        # pairs are left out there rather than guessed at
        self.time_numbers = dialect != "matiec"
        # iec and matiec type a bare TRUNC by its context (ADR 0052): see operand()
        self.trunc_by_context = dialect in ("iec", "matiec")
        self.pool: dict[str, list[tuple[str, Any]]] = {}
        for t in ALL:
            self.pool[t] = [(f"g_{t.lower()}_{i}", self.value(t)) for i in range(3)]
        # ARRAY[0..9] OF t for each integer type, read through indices of any integer type
        self.tables = {t: [self.value(t) for _ in range(10)] for t in INTS}

    # values
    def value(self, t: str) -> Any:
        r = self.rng
        if t == "BOOL":
            return r.random() < 0.5
        if t in REALS:
            edges = REAL_EDGES + (LREAL_EDGES if t == "LREAL" else [])
            k = r.random()
            if k < 0.35:
                x = r.choice(edges) * r.choice([1, -1])
            elif k < 0.5:
                x = float(r.randint(-10, 10)) + r.choice([0.0, 0.5, 0.25])
            elif k < 0.75:
                x = r.uniform(-1000, 1000)
            else:
                x = r.uniform(-1, 1) * 10.0 ** r.randint(-40, 38 if t == "REAL" else 300)
            return single(x) if t == "REAL" else x  # |x| < 3.4E38: a REAL literal
        n = width(t)
        lo = -(1 << (n - 1)) if is_signed(t) else 0
        hi = (1 << (n - 1)) - 1 if is_signed(t) else (1 << n) - 1
        k = r.random()
        if k < 0.3:
            cands = [lo, hi, 0, 1, 2, lo + 1, hi - 1, 3, 7, 10] + ([-1, -2, -7] if lo else [])
            if n == 64:
                cands += [x for x in LINT_EDGES if lo <= x <= hi]
            return r.choice(cands)
        if k < 0.7:
            return max(lo, min(hi, r.randint(-100, 100)))
        return r.randint(lo, hi)

    def leaf(self, t: str) -> Node:
        # a T# literal takes the type LTIME where an LTIME is expected: TIME values are variables
        if self.rng.random() < 0.7 or t == "TIME":
            name, v = self.rng.choice(self.pool[t])
            return Node(name, t, lambda: v)
        v = self.value(t)
        if t in REALS and (v < 0 or (v == 0 and math.copysign(1, v) < 0)):
            return Node(f"(-{literal_text(-v, t)})", t, lambda: v)
        return Node(literal_text(v, t), t, lambda: v, lit=True)

    def operand(self, t: str, d: int) -> Node:
        """An expression of type t, or sometimes of a type that widens to t."""
        narrower = [s for s, ws in WIDEN.items() if t in ws]
        if narrower and self.rng.random() < 0.2:
            s = self.rng.choice(narrower)
            x = self.expr(s, d)
            if not (self.trunc_by_context and "TRUNC(" in x.text):  # else TRUNC would be a t
                return Node(x.text, t, lambda: widened(x.ev(), s, t))
        return self.expr(t, d)

    def operands(self, t: str, d: int, k: int) -> list[Node]:
        """k inputs of an operator of type t: one has type t, the others may widen to it (the
        type of an operation is the common type of its inputs, not the type it is stored in)."""
        exact = self.rng.randrange(k) if k == 2 else 0  # plclab folds n inputs pairwise
        return [self.expr(t, d) if i == exact else self.operand(t, d) for i in range(k)]

    def expr(self, t: str, d: int) -> Node:
        if d <= 0 or self.rng.random() < 0.25:
            return self.leaf(t)
        d -= 1
        for _ in range(20):
            node = self.rng.choice(self.makers(t))(t, d)
            if node is not None:
                return node
        return self.leaf(t)

    def makers(self, t: str) -> list[Callable[[str, int], Node | None]]:
        common = [self.select, self.mux, self.minmax, self.limit, self.conv, self.conv,
                  self.call_, self.index_]
        if t in INTS:
            return common + [self.arith, self.arith, self.arith, self.neg, self.abs_,
                             self.arith_fn, self.trunc_]
        if t in BITS:
            return common + [self.bitop, self.bitop, self.not_, self.shift_, self.shift_]
        if t == "BOOL":
            return [self.select, self.mux, self.conv, self.bitop, self.bitop, self.not_,
                    self.compare, self.compare, self.compare, self.compare_fn]
        if t in REALS:
            return common + [self.arith, self.arith, self.arith, self.neg, self.abs_,
                             self.power, self.math_fn, self.math_fn, self.atan2, self.arith_fn]
        return common + [self.time_arith, self.time_arith, self.time_scale, self.neg]

    # operators
    def arith(self, t: str, d: int) -> Node:
        op = self.rng.choice(["+", "-", "*", "/", "MOD"] if t in INTS else ["+", "-", "*", "/"])
        a, b = self.operands(t, d, 2)
        fn = {"+": lambda x, y: x + y, "-": lambda x, y: x - y, "*": lambda x, y: x * y,
              "/": idiv if t in INTS else rdiv, "MOD": imod}[op]
        if self.operand_width and op in "+-*" and t in INTS:
            return Node(f"({a.text} {op} {b.text})", t, lambda: wrap(fn(a.ev(), b.ev()), t))
        return Node(f"({a.text} {op} {b.text})", t, lambda: fn(a.ev(), b.ev()))

    def arith_fn(self, t: str, d: int) -> Node:
        name = self.rng.choice(["ADD", "MUL", "SUB", "DIV"])  # MOD(a, b) does not parse
        k = self.rng.randint(2, 3) if name in ("ADD", "MUL") else 2
        args = self.operands(t, d, k)
        text = f"{name}({', '.join(a.text for a in args)})"

        def ev() -> Any:
            vs = [a.ev() for a in args]
            w = (lambda v: wrap(v, t)) if self.operand_width and t in INTS else (lambda v: v)
            if name == "ADD":
                acc = vs[0]
                for v in vs[1:]:
                    acc = w(acc + v)
                return acc
            if name == "MUL":
                acc = vs[0]
                for v in vs[1:]:
                    acc = w(acc * v)
                return acc
            if name == "SUB":
                return w(vs[0] - vs[1])
            if name == "MOD":
                return imod(vs[0], vs[1])
            return (idiv if t in INTS else rdiv)(vs[0], vs[1])
        return Node(text, t, ev)

    def neg(self, t: str, d: int) -> Node | None:
        if t in UNSIGNED:  # allowed with a warning, and an error on a constant
            return None
        a = self.expr(t, d)
        if a.lit:
            return None
        return Node(f"(-{a.text})", t, lambda: -a.ev())

    def abs_(self, t: str, d: int) -> Node:
        a = self.expr(t, d)
        return Node(f"ABS({a.text})", t, lambda: abs(a.ev()))

    def not_(self, t: str, d: int) -> Node:
        a = self.expr(t, d)
        if t == "BOOL":
            return Node(f"(NOT {a.text})", t, lambda: not a.ev())
        return Node(f"(NOT {a.text})", t, lambda: wrap(~a.ev(), t))

    def bitop(self, t: str, d: int) -> Node:
        op = self.rng.choice(["AND", "OR", "XOR"])
        a, b = self.operands(t, d, 2)
        fn = {"AND": lambda x, y: x & y, "OR": lambda x, y: x | y,
              "XOR": lambda x, y: x ^ y}[op]
        if t == "BOOL":
            return Node(f"({a.text} {op} {b.text})", t, lambda: bool(fn(a.ev(), b.ev())))
        return Node(f"({a.text} {op} {b.text})", t, lambda: fn(a.ev(), b.ev()))

    def shift_(self, t: str, d: int) -> Node:
        op = self.rng.choice(["SHL", "SHR", "ROL", "ROR"])
        a = self.expr(t, d)
        nt = self.rng.choice(list(INTS))
        if self.rng.random() < 0.7:
            v = self.rng.choice([0, 1, 3, width(t) - 1, width(t), width(t) + 1, 2 * width(t) + 3,
                                 self.rng.randint(0, 70)])
            v = wrap(v, nt)
            n = Node(literal_text(v, nt), nt, lambda: v)
        else:
            n = self.expr(nt, d)
        return Node(f"{op}({a.text}, {n.text})", t, lambda: shift(op, a.ev(), n.ev(), t))

    def compare(self, t: str, d: int) -> Node:
        s = self.rng.choice(ALL)
        op = self.rng.choice(["=", "<>", "<", "<=", ">", ">="])
        a, b = self.operands(s, d, 2)
        fn = {"=": lambda x, y: x == y, "<>": lambda x, y: x != y, "<": lambda x, y: x < y,
              "<=": lambda x, y: x <= y, ">": lambda x, y: x > y, ">=": lambda x, y: x >= y}[op]
        return Node(f"({a.text} {op} {b.text})", "BOOL", lambda: fn(a.ev(), b.ev()))

    def compare_fn(self, t: str, d: int) -> Node:
        s = self.rng.choice([x for x in ALL if x != "BOOL"])
        name = self.rng.choice(["GT", "GE", "EQ", "LE", "LT", "NE"])
        k = 2 if name == "NE" else self.rng.randint(2, 3)
        args = self.operands(s, d, k)
        fn = {"GT": lambda x, y: x > y, "GE": lambda x, y: x >= y, "EQ": lambda x, y: x == y,
              "LE": lambda x, y: x <= y, "LT": lambda x, y: x < y,
              "NE": lambda x, y: x != y}[name]

        def ev() -> bool:
            vs = [a.ev() for a in args]
            return all(fn(x, y) for x, y in zip(vs, vs[1:], strict=False))
        return Node(f"{name}({', '.join(a.text for a in args)})", "BOOL", ev)

    def select(self, t: str, d: int) -> Node:
        g = self.expr("BOOL", d)
        a, b = self.operands(t, d, 2)
        return Node(f"SEL({g.text}, {a.text}, {b.text})", t,
                    lambda: b.ev() if g.ev() else a.ev())

    def mux(self, t: str, d: int) -> Node:
        kt = self.rng.choice(list(INTS))
        items = self.operands(t, d, self.rng.randint(2, 4))
        if self.rng.random() < 0.8:
            v = self.rng.randrange(len(items) + (1 if self.rng.random() < 0.1 else 0))
            k = Node(literal_text(v, kt), kt, lambda: v)
        else:
            k = self.expr(kt, 0)

        def ev() -> Any:
            i = k.ev()
            if not 0 <= i < len(items):
                raise RefFault("PLC2002")
            return items[i].ev()
        return Node(f"MUX({k.text}, {', '.join(x.text for x in items)})", t, ev)

    def minmax(self, t: str, d: int) -> Node:
        name = self.rng.choice(["MIN", "MAX"])
        args = self.operands(t, d, self.rng.randint(2, 3))
        return Node(f"{name}({', '.join(a.text for a in args)})", t,
                    lambda: first_min([a.ev() for a in args], name == "MIN"))

    def limit(self, t: str, d: int) -> Node:
        mn, x, mx = self.operands(t, d, 3)

        def ev() -> Any:  # IEC: LIMIT = MIN(MAX(IN, MN), MX)
            lo, v, hi = mn.ev(), x.ev(), mx.ev()
            return first_min([first_min([v, lo], False), hi], True)
        return Node(f"LIMIT({mn.text}, {x.text}, {mx.text})", t, ev)

    def conv(self, t: str, d: int) -> Node | None:
        s = self.rng.choice(ALL)
        if s == t:
            return None
        if not self.time_numbers and (s in TIMES) != (t in TIMES):
            return None
        a = self.expr(s, d)
        return Node(f"{s}_TO_{t}({a.text})", t, lambda: convert(store(a.ev(), s), s, t))

    def call_(self, t: str, d: int) -> Node:
        """A user FUNCTION's input is a store: it holds the argument wrapped (rounded) to its
        type, whatever the argument computed in a register (ADR 0002, 0038)."""
        a = self.expr(t, d)
        return Node(f"ID_{t}({a.text})", t, lambda: store(a.ev(), t))

    def index_(self, t: str, d: int) -> Node | None:
        """An index is a value of its own type (IEC: the subscript has the expression's type;
        CODESYS computes it in a register and indexes with the typed value); outside 0..9 the
        PLC stops with PLC2002."""
        if t not in INTS:
            return None
        s = self.rng.choice(list(INTS))
        a = self.expr(s, d)

        def ev() -> Any:
            i = store(a.ev(), s)
            if not 0 <= i <= 9:
                raise RefFault("PLC2002")
            return self.tables[t][i]
        # + a variable 0, so that a constant index stays a run-time index (PLC0112 otherwise)
        return Node(f"g_tab_{t.lower()}[{a.text} + g_zero_{s.lower()}]", t, ev)

    def trunc_(self, t: str, d: int) -> Node:
        at = self.rng.choice(REALS)
        a = self.expr(at, d)  # a conversion: the argument is first a value of its own type
        if t == "DINT" and self.rng.random() < 0.5:
            return Node(f"TRUNC({a.text})", t, lambda: wrap(trunc(store(a.ev(), at)), t))
        return Node(f"TRUNC_{t}({a.text})", t, lambda: wrap(trunc(store(a.ev(), at)), t))

    def power(self, t: str, d: int) -> Node:
        # '**' on a REAL base has the base's type; an integer base gives REAL (<= 16 bit) or
        # LREAL; EXPT with a REAL base has the base's type
        base_t = t if self.rng.random() < 0.6 else self.rng.choice(
            ["SINT", "INT", "USINT", "UINT"] if t == "REAL" else ["DINT", "LINT", "UDINT",
                                                                   "ULINT"])
        a = self.expr(base_t, d)
        b = self.expr(self.rng.choice([*INTS, *REALS]), d)
        if base_t in REALS and self.rng.random() < 0.4:
            return Node(f"EXPT({a.text}, {b.text})", t, lambda: power(a.ev(), b.ev()))
        return Node(f"({a.text} ** {b.text})", t, lambda: power(a.ev(), b.ev()))

    def math_fn(self, t: str, d: int) -> Node:
        name = self.rng.choice(["SQRT", "LN", "LOG", "EXP", "SIN", "COS", "TAN", "ASIN",
                                "ACOS", "ATAN"])
        fn = {"SQRT": math.sqrt, "LN": math.log, "LOG": math.log10, "EXP": math.exp,
              "SIN": math.sin, "COS": math.cos, "TAN": math.tan, "ASIN": math.asin,
              "ACOS": math.acos, "ATAN": math.atan}[name]
        arg_t = t if self.rng.random() < 0.7 else self.rng.choice(
            ["SINT", "INT", "USINT", "UINT"] if t == "REAL" else ["DINT", "LINT", "UDINT"])
        a = self.expr(arg_t, d)
        rnd = single if t == "REAL" else (lambda x: x)
        return Node(f"{name}({a.text})", t, lambda: rnd(ieee(fn, a.ev())))

    def atan2(self, t: str, d: int) -> Node:
        y, x = self.expr(t, d), self.expr(t, d)
        rnd = single if t == "REAL" else (lambda v: v)
        return Node(f"ATAN2({y.text}, {x.text})", t, lambda: rnd(math.atan2(y.ev(), x.ev())))

    def time_arith(self, t: str, d: int) -> Node:
        op = self.rng.choice(["+", "-"])
        a, b = self.operands(t, d, 2)
        fn = (lambda x, y: x + y) if op == "+" else (lambda x, y: x - y)
        return Node(f"({a.text} {op} {b.text})", t, lambda: fn(a.ev(), b.ev()))

    def time_scale(self, t: str, d: int) -> Node:
        a = self.expr(t, d)
        nt = self.rng.choice([*INTS, *REALS])
        n = self.expr(nt, d)
        op = self.rng.choice(["*", "/"])
        if nt in REALS:
            if op == "*":
                return Node(f"({a.text} * {n.text})", t, lambda: round_away(a.ev() * n.ev()))
            return Node(f"({a.text} / {n.text})", t, lambda: round_away(rdiv(a.ev(), n.ev())))
        if op == "*":
            if self.rng.random() < 0.5:
                return Node(f"({n.text} * {a.text})", t, lambda: n.ev() * a.ev())
            return Node(f"({a.text} * {n.text})", t, lambda: a.ev() * n.ev())
        return Node(f"({a.text} / {n.text})", t, lambda: idiv(a.ev(), n.ev()))


# -- running a batch through plclab ---------------------------------------------------------
def same(got: Any, want: Any, t: str) -> bool:
    if t in REALS:
        if not isinstance(got, float):
            return False
        if want != want:
            return got != got
        return struct.pack("<d", got) == struct.pack("<d", want)
    if t == "BOOL":
        return got is want
    return type(got) is int and got == want


@dataclass
class Case:
    text: str  # the ST expression
    ty: str  # the type of the variable it is stored in
    want: Any  # the reference value, or a RefFault


def make_cases(gen: Gen, n: int) -> list[Case]:
    cases = []
    for _ in range(n):
        t = gen.rng.choice(ALL)
        node = gen.operand(t, gen.rng.randint(1, 3))
        try:
            want = store(node.ev(), t)
        except RefFault as f:
            want = f
        cases.append(Case(node.text, t, want))
    return cases


def source(gen: Gen, cases: list[Case]) -> str:
    lines = ["VAR_GLOBAL"]
    for t, items in gen.pool.items():
        for name, v in items:
            lines.append(f"    {name} : {t} := {literal_text(v, t)};")
    for t, vals in gen.tables.items():
        init = ", ".join(literal_text(v, t) for v in vals)
        lines.append(f"    g_tab_{t.lower()} : ARRAY[0..9] OF {t} := [{init}];")
        lines.append(f"    g_zero_{t.lower()} : {t} := 0;")
    lines.append("END_VAR")
    for t in ALL:
        lines += [f"FUNCTION ID_{t} : {t}", f"VAR_INPUT x : {t}; END_VAR", f"ID_{t} := x;",
                  "END_FUNCTION"]
    lines += ["PROGRAM P", "VAR"]
    ok = [(i, c) for i, c in enumerate(cases) if not isinstance(c.want, RefFault)]
    lines += [f"    r{i} : {c.ty};" for i, c in ok]
    lines.append("END_VAR")
    lines += [f"r{i} := {c.text};" for i, c in ok]
    lines.append("END_PROGRAM")
    for i, c in enumerate(cases):
        if isinstance(c.want, RefFault):
            lines += [f"TEST 'f{i}'", f"VAR x : {c.ty}; END_VAR", f"x := {c.text};", "END_TEST"]
    return "\n".join(lines) + "\n"


def check_batch(gen: Gen, n: int, dialect: str = "codesys") -> list[str]:
    """Compile and run n random expressions; return a description of every disagreement."""
    cases = make_cases(gen, n)
    src = source(gen, cases)
    compiled = plclab.compile_sources([(src, "oracle.st")], dialect=dialect)
    plc = Plc(compiled)
    bad = []
    try:
        plc.scan()
    except PlcRuntimeFault as f:
        line = f.location.line if f.location else 0
        text = src.splitlines()[line - 1] if line else "?"
        return [f"unexpected fault {f.code} {f.message} in {text}"]
    for i, c in enumerate(cases):
        if isinstance(c.want, RefFault):
            continue
        got = plc[f"r{i}"]
        if not same(got, c.want, c.ty):
            bad.append(f"{c.ty} := {c.text}\n    plclab {got!r}, reference {c.want!r}")
    faults = {r.title: r for r in run_compiled_tests(compiled)}
    for i, c in enumerate(cases):
        if isinstance(c.want, RefFault):
            r = faults[f"f{i}"]
            if r.passed or r.code != c.want.code:
                got = "no fault" if r.passed else f"{r.code} {r.message}"
                bad.append(f"{c.ty} := {c.text}\n    plclab {got}, reference fault "
                           f"{c.want.code}")
    return bad


def run_oracle(n: int, seed: int = SEED, dialect: str = "codesys") -> tuple[int, list[str]]:
    rng = random.Random(seed)
    done, bad = 0, []
    while done < n:
        k = min(BATCH, n - done)
        bad += check_batch(Gen(rng, dialect), k, dialect)
        done += k
    return done, bad


@pytest.mark.parametrize("dialect", ["codesys", "iec", "s7", "matiec"])
def test_compiled_arithmetic_agrees_with_the_reference(dialect):
    n = int(os.environ.get("PLCLAB_ORACLE_N", N_DEFAULT if dialect == "codesys" else N_OTHER))
    seed = int(os.environ.get("PLCLAB_ORACLE_SEED", SEED))
    t0 = time.perf_counter()
    done, bad = run_oracle(n, seed, dialect)
    print(f"oracle ({dialect}): {done} expressions, {len(bad)} disagreements, "
          f"{time.perf_counter() - t0:.1f} s")
    assert not bad, f"{len(bad)} of {done} disagree:\n" + "\n".join(bad[:20])
