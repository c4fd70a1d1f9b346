"""Arithmetic of generated code: IEC integer division, REAL conversions, IEEE 754 results of
the math functions (C99 Annex F), shifts and rotations, BCD."""

from __future__ import annotations

import math

from ..compile.real32 import f32 as _f32  # REAL rounding, shared with the compiler
from .rt_faults import Fault


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
