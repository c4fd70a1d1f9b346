"""The one duration parser: IEC literals (``T#1h2m3s4ms``) and durations for people (``10min``).

Every place that reads a duration goes through :func:`parse_duration`: the ST lexer and
``STRING_TO_TIME`` in IEC mode (``iec=True``), and the ``Plc`` API (``cycle_time``, ``run``,
``advance``), the command line, wiring, scenario and lab files in the default mode, which accepts
a superset, so ``"1min"``, ``"1 h 30 min"`` and ``"T#1m30s"`` mean the same everywhere.
Callers check the range and raise their own error code.

>>> parse_duration("10min"), parse_duration("T#1m30s") // 10**9, parse_duration(0.01)
(600000000000, 90, 10000000)
>>> parse_duration("1h2m3s4ms", iec=True) // 1_000_000, parse_duration("1min", iec=True)
(3723004, None)
>>> parse_duration("-5s") // 10**9, parse_duration("2s_200ms") // 10**6, parse_duration("90")
(-5, 2200, 90000000000)
"""

from __future__ import annotations

import datetime as _dt
import math
import re
from typing import Any

NS_PER = {
    "d": 86_400_000_000_000, "h": 3_600_000_000_000, "m": 60_000_000_000,
    "s": 1_000_000_000, "ms": 1_000_000, "us": 1_000, "ns": 1,
}
"""The IEC 61131-3 units of a duration literal, in nanoseconds."""

_WORDS = {
    "day": "d", "days": "d", "hr": "h", "hrs": "h", "hour": "h", "hours": "h", "min": "m",
    "mins": "m", "minute": "m", "minutes": "m", "sec": "s", "secs": "s", "second": "s",
    "seconds": "s", "msec": "ms", "µs": "us",
}
"""Longer unit names people write (the default mode only)."""

PREFIXES = ("LTIME#", "TIME#", "LT#", "T#")
OVERFLOW = 1 << 70
"""Returned (with the sign) for a duration far beyond any TIME or LTIME: callers reject it."""
_MAX_DIGITS = 30  # longer whole parts are far beyond any duration: no big arithmetic

_IEC_PART = re.compile(r"([0-9]+(?:\.[0-9]+)?)([a-z]+)", re.IGNORECASE)
_PART = re.compile(r"\s*([0-9]+(?:\.[0-9]*)?(?:e[+-]?[0-9]+)?)\s*([a-zµ]+)\s*", re.IGNORECASE)
_NUMBER = re.compile(r"[0-9]+(?:\.[0-9]*)?(?:e[+-]?[0-9]+)?", re.IGNORECASE)


def parse_duration(value: Any, *, iec: bool = False) -> int | None:
    """A duration in integer nanoseconds (negative when written with '-'), or None.

    ``iec=True``: an IEC literal (the ``T#`` prefix is optional) as the ST lexer and
    ``STRING_TO_TIME`` see it: an optional sign, then parts ``<number><unit>`` with units d, h, m, s, ms, us, ns (any case), no spaces, '_'
    anywhere (``1h2m3s4ms``, ``2s_200ms``, ``-5s``, ``1.5s``).

    Default: also spaces (and a ``T#``/``TIME#``/``LT#``/``LTIME#`` prefix), the units min, sec,
    hour(s), day(s), msec, µs..., exponents (``1e3ms``), a bare number of seconds (``"90"``),
    and int, float (seconds) or ``datetime.timedelta`` values.
    """
    if isinstance(value, bool):
        return None
    if isinstance(value, str):
        return _parse_text(value, iec)
    if iec:
        return None
    if isinstance(value, _dt.timedelta):
        return round(value.total_seconds() * 1e9)
    if isinstance(value, int):
        return value * 1_000_000_000
    if isinstance(value, float):
        return _scaled(value, 1_000_000_000)
    return None


def _scaled(x: float, unit: int) -> int | None:
    if math.isnan(x):
        return None
    ns = x * unit
    if not math.isfinite(ns):
        return OVERFLOW if ns > 0 else -OVERFLOW
    return round(ns)


def _parse_text(text: str, iec: bool) -> int | None:
    s = text if iec else text.strip()  # the lexer hands over the body alone, without blanks
    if "#" in s[:7]:
        upper = s[:7].upper()
        for prefix in PREFIXES:
            if upper.startswith(prefix):
                s = s[len(prefix):]
                break
    neg = s.startswith("-")
    s = s[1:] if s[:1] in ("+", "-") else s
    if "_" in s:
        s = s.replace("_", "")
    if not iec:
        s = s.strip()
        if _NUMBER.fullmatch(s):
            ns = _scaled(float(s), 1_000_000_000)
            return None if ns is None else (-ns if neg else ns)
    part = _IEC_PART if iec else _PART
    total, pos, end = 0, 0, len(s)
    while pos < end:
        m = part.match(s, pos)
        if m is None:
            return None
        num, unit = m.group(1, 2)
        unit = unit.lower()
        size = NS_PER.get(unit if iec else _WORDS.get(unit, unit))
        if size is None:
            return None
        if num.isdigit():
            if len(num) > _MAX_DIGITS and len(num.lstrip("0")) > _MAX_DIGITS:
                return -OVERFLOW if neg else OVERFLOW
            total += int(num) * size
        else:  # a fraction or an exponent
            whole = num.split(".")[0].lower().split("e")[0]
            if len(whole.lstrip("0")) > _MAX_DIGITS:
                return -OVERFLOW if neg else OVERFLOW
            ns = _scaled(float(num), size)
            if ns is None:
                return None
            total += ns
        pos = m.end()
    if pos == 0:
        return None
    return -total if neg else total
