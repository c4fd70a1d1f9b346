"""Strings in generated code: the IEC string functions (positions are 1-based), conversions
between strings and values, and values written as IEC literals."""

from __future__ import annotations

import math
import re

from ..compile.real32 import f32 as _f32  # REAL rounding, shared with the compiler
from .rt_objects import RefAttr


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


def _str_to_bool(s: str) -> bool:
    return s.strip().upper() in ("TRUE", "1")


def _str_to_time(s: str) -> int:
    from ..durations import parse_duration

    return (parse_duration(s.strip(), iec=True) or 0) // 1_000_000


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
        return string_literal(v)
    if kind in ("interface", "ref"):  # ADR 0021: what it refers to, not a Python repr
        if v is None:
            return "NULL"
        if isinstance(v, RefAttr):
            return f"REF(.{v.key})" if isinstance(v.key, str) else f"REF([{v.key}])"
        return f"REF({type(v).__name__[2:]} instance)"
    if isinstance(v, int | float | list):
        return str(v)
    if hasattr(type(v), "__slots__"):  # a block instance: its type, never a Python repr
        name = type(v).__name__
        return f"({name[2:] if name.startswith('P_') else name} instance)"
    return str(v)


def string_literal(v: str) -> str:
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


_str_find = str.find  # FIND with a literal, inline (fast paths, ADR 0034)
