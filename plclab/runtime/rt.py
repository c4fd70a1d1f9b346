"""Helpers that generated code calls (the namespace every compiled program starts from).

Kept small and fast: generated code inlines what it can and calls these for the rest.
Runtime faults raise :class:`Fault`; the PLC turns them into located
:class:`~plclab.errors.PlcRuntimeFault` using the generated code's line map.
"""

from __future__ import annotations

import bisect
import math
import re
import struct
from operator import attrgetter as _attrgetter

from ..compile.real32 import f32 as _f32  # REAL rounding, shared with the compiler

_F32_MAX = 3.4028234663852886e38


class Fault(Exception):
    """A PLC runtime fault raised by generated code: code, message, location index."""

    def __init__(self, code: str, message: str, where: int | None = None) -> None:
        super().__init__(message)
        self.code = code
        self.message = message
        self.where = where


class AssertFailure(Exception):
    def __init__(self, message: str, where: int) -> None:
        super().__init__(message)
        self.message = message
        self.where = where


class Budget:
    """The watchdog: loop iterations left in this scan (deterministic, unlike wall time)."""

    __slots__ = ("left", "limit")

    def __init__(self, limit: int = 1_000_000) -> None:
        self.limit = limit
        self.left = limit


def _idiv(a: int, b: int) -> int:
    """Integer division truncating toward zero (IEC, C), unlike Python's floor division."""
    if b == 0:
        raise Fault("PLC2001", "integer division by zero; check the divisor before dividing")
    q = a // b
    if q < 0 and q * b != a:
        q += 1
    return q


def _imod(a: int, b: int) -> int:
    """MOD with the sign of the dividend (IEC, C); x MOD 0 is a fault."""
    if b == 0:
        raise Fault("PLC2001", "MOD by zero; check the divisor first")
    return a - b * _idiv(a, b)


def _rdiv(a, b):
    if b == 0:
        raise Fault("PLC2001", "division by zero; check the divisor before dividing")
    return a / b


def _oob(i: int, lo: int, hi: int, where: int):
    raise Fault("PLC2002", f"array index {i} is outside the bounds {lo}..{hi}", where)


class _VLA:
    """The argument of an ``ARRAY[*]`` VAR_IN_OUT (ADR 0060): the caller's array (its flat
    list, shared, so writes reach the caller) and its bounds, ``((lo, hi), ...)``."""

    __slots__ = ("data", "dims")

    def __init__(self, data: list, dims: tuple[tuple[int, int], ...]) -> None:
        self.data = data
        self.dims = tuple(dims)


def _vla_ix(v: _VLA, ixs: tuple[int, ...], where: int) -> int:
    """The flat position of ``v[ixs]``; an index outside its dimension's bounds is PLC2002."""
    flat = 0
    for i, (lo, hi) in zip(ixs, v.dims, strict=True):
        if not lo <= i <= hi:
            _oob(i, lo, hi, where)
        flat = flat * (hi - lo + 1) + i - lo
    return flat


def _iref(obj, method: str, where: int):
    """The instance an interface variable refers to, for a call of ``method`` (ADR 0021)."""
    if obj is None:
        raise Fault("PLC9110", f"call of {method} through an interface variable that refers to "
                    "no instance; assign an instance first (itf := inst;) or test it with "
                    "__ISVALIDREF(itf) before the call", where)
    return obj


def _qi(obj, interface: str):
    """``obj`` if its block implements ``interface`` (``__QUERYINTERFACE``), else None."""
    return obj if obj is not None and interface in getattr(obj, "_itf", ()) else None


_INIT_RETAINS = True  # FB_init's bInitRetains: the runtime sets FALSE for a warm restart


def fb_exit_all(roots) -> None:
    """FB_exit(bInCopyCode := FALSE) of every instance under ``roots`` (the program and global
    instances), each before the instances it contains (ADR 0021)."""
    seen: set[int] = set()
    stack = list(reversed(list(roots)))
    while stack:
        obj = stack.pop()
        if id(obj) in seen or obj is None or isinstance(obj, bool | int | float | str | bytes):
            continue
        seen.add(id(obj))
        if isinstance(obj, list):
            stack.extend(reversed(obj))
            continue
        exit_ = getattr(obj, "m_FB_EXIT", None)
        if exit_ is not None:
            exit_(False)
        slots = getattr(type(obj), "__slots__", ())
        stack.extend(reversed([getattr(obj, n, None) for n in slots]))


class _RefAttr:
    """A reference (REF_TO, POINTER TO) to the attribute ``key`` of ``obj`` (ADR 0021)."""

    __slots__ = ("obj", "key")

    def __init__(self, obj, key) -> None:
        self.obj, self.key = obj, key

    def get(self):
        return getattr(self.obj, self.key)

    def set(self, v) -> None:
        setattr(self.obj, self.key, v)

    def __eq__(self, other) -> bool:
        return type(other) is type(self) and other.obj is self.obj and other.key == self.key

    def __hash__(self) -> int:
        return hash((id(self.obj), self.key))


class _RefItem(_RefAttr):
    """A reference to the element ``key`` of the list ``obj`` (an ARRAY element)."""

    __slots__ = ()

    def get(self):
        return self.obj[self.key]

    def set(self, v) -> None:
        self.obj[self.key] = v


class _RefCell:
    """A reference to a local of the running FUNCTION, METHOD or TEST (a Python local): read
    and written through two closures; the checker lets it live only during the call (PLC0240,
    ADR 0051)."""

    __slots__ = ("get", "set")

    def __init__(self, get, set) -> None:  # noqa: A002
        self.get, self.set = get, set


_PUN = {"REAL": "<f", "LREAL": "<d", "SINT": "<b", "USINT": "<B", "BYTE": "<B", "INT": "<h",
        "UINT": "<H", "WORD": "<H", "DINT": "<i", "UDINT": "<I", "DWORD": "<I", "LINT": "<q",
        "ULINT": "<Q", "LWORD": "<Q"}


class _RefPun:
    """``pt : REF_TO DWORD; pt := REF(x)`` with ``x : REAL``: reads and writes ``x``'s bits as
    the other elementary type of the same size (IEEE 754, little-endian as on x86 and ARM PLCs;
    the codesys dialect, PLC0291, ADR 0051)."""

    __slots__ = ("ref", "src", "dst")

    def __init__(self, ref, src: str, dst: str) -> None:
        self.ref, self.src, self.dst = ref, _PUN[src], _PUN[dst]

    def get(self):
        import struct

        return struct.unpack(self.dst, struct.pack(self.src, self.ref.get()))[0]

    def set(self, v) -> None:
        import struct

        self.ref.set(struct.unpack(self.src, struct.pack(self.dst, v))[0])


def _deref(ref, where: int):
    """``ref`` for r^, or the fault PLC9111 when it is NULL."""
    if ref is None:
        raise Fault("PLC9111", "dereference of a NULL reference (r^ where r refers to no "
                    "variable); assign r := REF(x) first, or test __ISVALIDREF(r) or "
                    "r <> NULL before", where)
    return ref


def _wd(where: int):
    raise Fault("PLC2003", "watchdog: the scan did not finish within its budget; this loop "
                "runs too long or never ends (inputs do not change during a scan, so waiting "
                "for one in a loop never ends: use IF and let the next scan check again)", where)


def _subr(x: int, lo: int, hi: int, where: int) -> int:
    if lo <= x <= hi:
        return x
    raise Fault("PLC2004", f"value {x} is outside the subrange {lo}..{hi}", where)


def _frange(s: int, e: int, st: int, lo: int, hi: int, where: int, budget: Budget | None):
    """The values of ``FOR v := s TO e BY st`` for a variable of range lo..hi, as the hardware
    runs it (``v := v + st`` wraps): a ``range`` when the loop ends without wrapping (the fast
    path), else a :class:`_ForWrap`, which charges ``budget`` per pass."""
    if st == 0:
        raise Fault("PLC2005", "FOR ... BY 0 never ends; use a step other than 0", where)
    if (e - s) * st < 0:  # no pass at all
        return range(s, s)
    last = s + (e - s) // st * st
    if lo <= last + st <= hi:
        return range(s, e + (1 if st > 0 else -1), st)
    return _ForWrap(s, e, st, lo, hi, where, budget)


class _ForWrap:
    """A FOR loop whose variable wraps at its type's limits (SINT 127 + 1 = -128), so it ends
    late or never; ``len()`` is 0 because each pass is charged to the watchdog as it runs."""

    def __init__(self, s: int, e: int, st: int, lo: int, hi: int, where: int,
                 budget: Budget | None) -> None:
        self.s, self.e, self.st, self.lo, self.hi = s, e, st, lo, hi
        self.where, self.budget = where, budget
        self.final = s
        self.wrapped: tuple[int, int] | None = None  # the last wrap: value before, after

    def __len__(self) -> int:
        return 0

    def __iter__(self):
        v, e, st, lo, hi, budget = self.s, self.e, self.st, self.lo, self.hi, self.budget
        while v <= e if st > 0 else v >= e:
            if budget is not None:
                budget.left -= 1
                if budget.left < 0:
                    self.overrun()
            yield v
            if not lo <= v + st <= hi:
                self.wrapped = (v, (v + st - lo) % (hi - lo + 1) + lo)
                v = self.wrapped[1]
            else:
                v += st
        self.final = v

    def overrun(self):
        if self.wrapped is None:
            _wd(self.where)
        a, b = self.wrapped
        step = f"+ {self.st}" if self.st > 0 else f"- {-self.st}"
        raise Fault("PLC2003", f"watchdog: this FOR loop never ends: its variable wraps around "
                    f"at the limit of its type ({a} {step} gives {b}, range {self.lo}.."
                    f"{self.hi}), so it never passes the end value {self.e}; use a wider type for "
                    "the variable", self.where)


def _fend(r) -> int:
    """The FOR variable's value after the loop ended normally: one step past the last pass."""
    if type(r) is range:
        return r.start + len(r) * r.step
    return r.final


def _round(x: float) -> int:
    """REAL -> integer conversion: round half away from zero (as CODESYS).

    Exact for every double: ``x - int(x)`` is the exact fraction, unlike ``floor(x + 0.5)``,
    which rounds 0.49999999999999994 up and 2**52 + 1 to 2**52 + 2.
    """
    if x != x or x in (math.inf, -math.inf):
        raise Fault("PLC2006", f"cannot convert {x} to an integer; check for a division by zero "
                    "or an overflow before converting")
    n = int(x)
    f = x - n
    if f >= 0.5:
        return n + 1
    if f <= -0.5:
        return n - 1
    return n


def _trunc(x: float) -> int:
    if x != x or x in (math.inf, -math.inf):
        raise Fault("PLC2006", f"cannot convert {x} to an integer; check for a division by zero "
                    "or an overflow before converting")
    return int(x)


def _i2r(x: int) -> float:
    """An exact integer to REAL, rounded once to nearest-even (not twice, through a double)."""
    if -0x20000000000000 <= x <= 0x20000000000000:
        return _f32(x)  # exact in a double, so a single rounding
    n = abs(x)
    drop = n.bit_length() - 26  # keep 24 bits, the rounding bit and a sticky bit
    m = (n >> drop) | (1 if n & ((1 << drop) - 1) else 0)
    try:
        y = math.ldexp(float(m), drop)
    except OverflowError:
        y = math.inf
    return _f32(y if x > 0 else -y)


def _fl(x) -> float:
    """An exact integer widened to LREAL: nearest double, or +-inf beyond its range (IEEE)."""
    try:
        return float(x)
    except OverflowError:
        return math.inf if x > 0 else -math.inf


def _odd(y: float) -> bool:
    return math.isfinite(y) and y == int(y) and int(y) % 2 == 1


def _expt(a, b):
    """EXPT and '**' (result REAL/LREAL) with IEEE 754 results (C99 Annex F): 0 ** -1 = inf,
    (-8) ** 0.5 = NaN, overflow = +-inf. Two integers give the exact power rounded once, with
    bounded work: a power beyond the double range is never computed."""
    if type(a) is int and type(b) is int:
        return _ipow(a, b)
    a, b = _fl(a), _fl(b)
    try:
        return math.pow(a, b)
    except OverflowError:
        return -math.inf if a < 0 and _odd(b) else math.inf
    except ValueError:  # 0 ** negative, or a negative base and a fractional exponent
        if a == 0:
            return math.copysign(math.inf, a) if _odd(b) else math.inf
        return math.nan


def _ipow(a: int, b: int) -> float:
    neg = a < 0 and b % 2 == 1
    big = abs(a) >= 2 and abs(b) * (abs(a).bit_length() - 1) > 1100  # |a ** b| > 2 ** 1100
    if b >= 0:
        if big:
            return -math.inf if neg else math.inf
        return _fl(a ** b)
    if a == 0:
        return math.inf
    if big:
        return -0.0 if neg else 0.0
    return 1 / a ** -b  # int / int is correctly rounded


def _sqrt(x):
    return math.sqrt(x) if x >= 0 else math.nan


def nan_at_infinity(fn):
    """``fn`` (sin, cos, tan) giving NaN where Python raises for an infinite argument, as
    IEEE 754 does (``SIN(inf)`` is NaN)."""

    def f(x):
        try:
            return fn(x)
        except ValueError:
            return math.nan

    f.__name__ = f"_{fn.__name__}"
    return f


_sin = nan_at_infinity(math.sin)
_cos = nan_at_infinity(math.cos)
_tan = nan_at_infinity(math.tan)


def _ln(x):
    return math.log(x) if x > 0 else (-math.inf if x == 0 else math.nan)


def _log(x):
    return math.log10(x) if x > 0 else (-math.inf if x == 0 else math.nan)


def _exp(x):
    try:
        return math.exp(x)
    except OverflowError:
        return math.inf


def _asin(x):
    return math.asin(x) if -1 <= x <= 1 else math.nan


def _acos(x):
    return math.acos(x) if -1 <= x <= 1 else math.nan


def _limit(mn, x, mx):
    """IEC LIMIT = MIN(MAX(IN, MN), MX), also when MN > MX."""
    if x < mn:
        x = mn
    return mx if x > mx else x


def _mux(k: int, n: int, where: int):
    raise Fault("PLC2002", f"MUX selector K = {k} is outside 0..{n - 1}", where)


def _count(n: int) -> None:
    if n < 0:
        raise Fault("PLC2020", f"shift count N = {n} is negative; SHL, SHR, ROL and ROR shift "
                    "by 0 or more bits")


def _shl(x: int, n: int, bits: int) -> int:
    """SHL: zeros come in from the right; a count of the width or more gives 0."""
    _count(n)
    return (x << n) & ((1 << bits) - 1) if n < bits else 0


def _shr(x: int, n: int, bits: int) -> int:
    """SHR: zeros come in from the left (also for signed types: the bit pattern shifts)."""
    _count(n)
    return (x & ((1 << bits) - 1)) >> n if n < bits else 0


def _rol(x: int, n: int, bits: int) -> int:
    """ROL: rotate left; the count is taken modulo the width."""
    _count(n)
    n %= bits
    m = (1 << bits) - 1
    x &= m
    return ((x << n) | (x >> (bits - n))) & m


def _ror(x: int, n: int, bits: int) -> int:
    _count(n)
    n %= bits
    m = (1 << bits) - 1
    x &= m
    return ((x >> n) | (x << (bits - n))) & m


# -- strings (IEC positions are 1-based) -----------------------------------------------------
def _left(s: str, n: int) -> str:
    return s[: max(n, 0)]


def _right(s: str, n: int) -> str:
    return s[len(s) - n:] if 0 < n else ""


def _mid(s: str, n: int, p: int) -> str:
    if p < 1:
        return ""
    return s[p - 1: p - 1 + max(n, 0)]


def _insert(s1: str, s2: str, p: int) -> str:
    p = max(0, min(p, len(s1)))
    return s1[:p] + s2 + s1[p:]


def _delete(s: str, n: int, p: int) -> str:
    if p < 1:
        return s
    return s[: p - 1] + s[p - 1 + max(n, 0):]


def _replace(s1: str, s2: str, n: int, p: int) -> str:
    if p < 1:
        p = 1
    return s1[: p - 1] + s2 + s1[p - 1 + max(n, 0):]


def _find(s1: str, s2: str) -> int:
    return s1.find(s2) + 1 if s2 else 0


# -- formatting (IEC literal forms) ---------------------------------------------------------
def fmt_duration(value: int, unit_ns: int, prefix: str = "T#") -> str:
    """Format a duration as an IEC literal: ``fmt_duration(1500, 10**6)`` -> ``'T#1s500ms'``."""
    ns = value * unit_ns
    neg = ns < 0
    ns = abs(ns)
    parts = []
    for unit, size in (("d", 86_400_000_000_000), ("h", 3_600_000_000_000),
                       ("m", 60_000_000_000), ("s", 1_000_000_000), ("ms", 1_000_000),
                       ("us", 1_000), ("ns", 1)):
        q, ns = divmod(ns, size)
        if q:
            parts.append(f"{q}{unit}")
    body = "".join(parts) or ("0ms" if unit_ns >= 1_000_000 else "0ns")
    return f"{prefix}{'-' if neg else ''}{body}"


def fmt_real(x: float, single: bool) -> str:
    if x != x:
        return "NaN"
    if x in (math.inf, -math.inf):
        return "+INF" if x > 0 else "-INF"
    if single:
        s = f"{x:.7g}"
        if float(s) != _f32(float(s)) or _f32(float(s)) != x:
            s = repr(x)
        # shortest string that rounds back to the same single
        for digits in range(1, 10):
            cand = f"{x:.{digits}g}"
            if _f32(float(cand)) == x:
                s = cand
                break
    else:
        s = repr(x)
    if "e" in s or "E" in s:
        mant, _, exp = s.lower().partition("e")
        if "." not in mant:
            mant += ".0"
        return f"{mant}E{int(exp)}"
    if "." not in s and "inf" not in s and "nan" not in s:
        s += ".0"
    return s


def _to_string(x, kind: str) -> str:
    if kind == "bool":
        return "TRUE" if x else "FALSE"
    if kind == "real":
        return fmt_real(x, False)
    if kind == "real32":
        return fmt_real(x, True)
    if kind == "time":
        return fmt_duration(x, 1_000_000)
    if kind == "ltime":
        return fmt_duration(x, 1, "LTIME#")
    return str(x)


# CODESYS reads the leading number of the string and ignores what follows ('34abc' -> 34,
# 'abc34' -> 0; CODESYS online help "Conversion: STRING, WSTRING", Schneider Machine Expert and
# ABB Automation Builder "STRING_TO" examples): spaces before, an optional sign, '_' separators,
# a based integer 16#FF or a decimal/exponent number.
_LEADING_BASED = re.compile(r"\s*([+-]?)(2|8|16)#([0-9A-Fa-f_]+)")
_LEADING_NUMBER = re.compile(r"\s*[+-]?[0-9][0-9_]*(?:\.[0-9_]+)?(?:[eE][+-]?[0-9]+)?")


def _leading_number(s: str) -> float | int | None:
    """The number at the start of ``s`` (CODESYS STRING_TO_*), or None when there is none."""
    m = _LEADING_BASED.match(s)
    if m:
        base, first = int(m.group(2)), ""
        for c in m.group(3).replace("_", ""):
            if int(c, 16) >= base:  # stop at the first digit the base does not have
                break
            first += c
        if not first:
            return None
        value = int(first, base)
        return -value if m.group(1) == "-" else value
    m = _LEADING_NUMBER.match(s)
    if not m:
        return None
    text = m.group(0).strip().replace("_", "")
    return float(text) if ("." in text or "e" in text.lower()) else int(text)


def _str_to_int(s: str) -> int:
    v = _leading_number(s)
    return 0 if v is None or (isinstance(v, float) and not math.isfinite(v)) else int(v)


def _str_to_real(s: str) -> float:
    v = _leading_number(s)
    return 0.0 if v is None else float(v)


def _bcd_to_int(x: int, hi: int) -> int:
    """BCD_TO_*: the decimal value of the 4-bit digits of ``x``; a digit above 9 or a value above
    ``hi`` (the target's maximum) gives ``hi``, as PLCnext Engineer documents."""
    value, scale = 0, 1
    while x:
        digit = x & 15
        if digit > 9:
            return hi
        value += digit * scale
        x >>= 4
        scale *= 10
    return value if value <= hi else hi


def _int_to_bcd(x: int, bits: int) -> int:
    """*_TO_BCD: ``x`` as 4-bit decimal digits in ``bits`` bits; a negative value or one with
    more digits than fit gives all ones (16#FF for a BYTE), as CODESYS Util and PLCnext do."""
    if x < 0 or len(str(x)) > bits // 4:
        return (1 << bits) - 1
    return int(str(x), 16)


def _str_to_bool(s: str) -> bool:
    return s.strip().upper() in ("TRUE", "1")


def _str_to_time(s: str) -> int:
    from ..durations import parse_duration

    return (parse_duration(s.strip(), iec=True) or 0) // 1_000_000


def _case_range(x: int, table: tuple[tuple[int, ...], tuple[int, ...], tuple[int, ...]],
                default: int) -> int:
    """The branch of a large CASE whose label range holds ``x`` (table: sorted disjoint
    starts, ends, branches), or ``default``."""
    starts, ends, branches = table
    i = bisect.bisect_right(starts, x) - 1
    return branches[i] if i >= 0 and x <= ends[i] else default


HELPERS = {
    name: obj for name, obj in globals().items()
    if name.startswith("_") and not name.startswith("__") and callable(obj)
}
HELPERS["_math"] = math


# -- misc used by generated code --------------------------------------------------------------
def _setattrs(obj, **kw):
    for k, v in kw.items():
        setattr(obj, k, v)
    return obj


def _copier(plain: tuple[str, ...], objs: tuple[str, ...], lists: tuple[str, ...],
            obj_lists: tuple[str, ...]):
    """The ``_copy`` method of a generated class (ADR 0034): a new instance of the same class
    whose members ``plain`` (elementary values) are shared, ``objs`` (structures and block
    instances) copied by their own ``_copy``, ``lists`` (arrays of elementary values) copied
    and ``obj_lists`` (arrays of structures or blocks) copied element by element. One helper
    instead of a generated method per class keeps the generated source short."""
    get_plain = _attrgetter(*plain) if len(plain) > 1 else None

    def _copy(self):
        cls = self.__class__
        n = cls.__new__(cls)
        if get_plain is not None:
            for k, v in zip(plain, get_plain(self), strict=True):
                setattr(n, k, v)
        elif plain:
            setattr(n, plain[0], getattr(self, plain[0]))
        for k in objs:
            setattr(n, k, getattr(self, k)._copy())
        for k in lists:
            setattr(n, k, list(getattr(self, k)))
        for k in obj_lists:
            setattr(n, k, [e._copy() for e in getattr(self, k)])
        return n

    return _copy


def _assert_cmp(a, b, want_equal: bool, where: int, kind: str) -> None:
    equal = a == b
    if equal != want_equal:
        rel = "==" if not want_equal else "<>"
        raise AssertFailure(f"expected {'' if want_equal else 'not '}equal, but "
                            f"{format_value(a, kind)} {rel} {format_value(b, kind)}", where)


def _assert_bool(a, want: bool, where: int) -> None:
    if bool(a) != want:
        raise AssertFailure(f"expected {'TRUE' if want else 'FALSE'}, got "
                            f"{'TRUE' if a else 'FALSE'}", where)


def _assert_near(a, b, tol, where: int) -> None:
    if not abs(a - b) <= tol:
        raise AssertFailure(f"expected {b} +- {tol}, got {a} (off by {abs(a - b):.6g})", where)


def format_value(v, kind: str) -> str:
    """Format a run-time value as an IEC literal, given a kind from the type system."""
    if kind.startswith("enum:"):
        for pair in kind[5:].split(","):
            num, _, name = pair.partition("=")
            if num and int(num) == v:
                return name
        return str(v)
    if kind == "bool" or isinstance(v, bool):
        return "TRUE" if v else "FALSE"
    if kind == "time":
        return fmt_duration(v, 1_000_000)
    if kind == "ltime":
        return fmt_duration(v, 1, "LTIME#")
    if kind == "real32":
        return fmt_real(v, True)
    if kind == "real" or isinstance(v, float):
        return fmt_real(v, False)
    if isinstance(v, str):
        return _string_literal(v)
    if kind in ("interface", "ref"):  # ADR 0021: what it refers to, not a Python repr
        if v is None:
            return "NULL"
        if isinstance(v, _RefAttr):
            return f"REF(.{v.key})" if isinstance(v.key, str) else f"REF([{v.key}])"
        return f"REF({type(v).__name__[2:]} instance)"
    if isinstance(v, int | float | list):
        return str(v)
    if hasattr(type(v), "__slots__"):  # a block instance: its type, never a Python repr
        name = type(v).__name__
        return f"({name[2:] if name.startswith('P_') else name} instance)"
    return str(v)


def _string_literal(v: str) -> str:
    """An IEC string literal of ``v``: ``$$``, ``$'``, ``$N`` and ``$hh`` (``$hhhh`` beyond
    one byte) for every character a terminal would act on, so a value never reaches the
    screen raw (a lone surrogate of a WSTRING included)."""
    out = []
    for ch in v:
        if ch == "$":
            out.append("$$")
        elif ch == "'":
            out.append("$'")
        elif ch == "\n":
            out.append("$N")
        elif ch.isprintable():
            out.append(ch)
        else:
            n = ord(ch)
            out.append(f"${n:02X}" if n < 256 else f"${n:04X}")
    return "'" + "".join(out) + "'"


_unpack_from = struct.unpack_from
_pack_into = struct.pack_into
_str_find = str.find  # FIND with a literal, inline (fast paths, ADR 0034)

HELPERS.update({
    "_setattrs": _setattrs, "_copier": _copier, "_assert_cmp": _assert_cmp, "_assert_bool": _assert_bool,
    "_assert_near": _assert_near, "_unpack_from": _unpack_from, "_pack_into": _pack_into,
    "_str_find": _str_find,
})
