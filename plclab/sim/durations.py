"""Durations for humans: ``10ms``, ``1.5s``, ``90s``, ``10min``, ``1h30m``, ``2d``, ``T#1m30s``.

Everything the simulation layer takes as a time (scan, dt, durations, scenario times) goes
through :func:`parse_ns`, so the same spellings work in Python, TOML and on the command line.
Numbers are seconds. The parsing itself is :func:`plclab.durations.parse_duration`, the one
parser the PLC's API uses too; this module adds the checks (not negative, at most a year).

>>> parse_ns("10min"), parse_ns("T#1m30s") // 10**9, parse_ns(0.01), parse_ns("1 h")
(600000000000, 90, 10000000, 3600000000000)
>>> format_duration(5400), format_duration(0.25), format_duration(86400 * 2)
('1h30min', '250ms', '2d')
"""

from __future__ import annotations

from typing import Any

from ..durations import parse_duration
from .errors import sim_error

MAX_NS = 366 * 86_400_000_000_000  # the longest duration accepted anywhere: a year


def parse_ns(value: Any, what: str = "duration", allow_zero: bool = True) -> int:
    """A duration in integer nanoseconds.

    Parameters
    ----------
    value : str, int, float or datetime.timedelta
        ``"10min"``, ``"1h30m"``, ``"T#1m"``, ``"90 s"``, a number of seconds.
    what : str
        Used in the error message (``"scan"``, ``"action 3: at"``...).
    allow_zero : bool
        Accept zero (negative durations are never accepted).

    Raises
    ------
    PlcError
        PLC4012 for anything that is not a duration, is negative, is longer than a year, or
        is zero when ``allow_zero`` is false.
    """
    ns = parse_duration(value)
    if ns is None:
        raise sim_error("PLC4012", f"{what}: {value!r} is not a duration; write e.g. 10ms, 1.5s, "
                        "90s, 10min, 1h, 1h30m, T#1m30s or a number of seconds")
    if ns < 0 or (ns == 0 and not allow_zero):
        need = "zero or positive" if allow_zero else "positive"
        raise sim_error("PLC4012", f"{what} must be {need}, not {value!r}")
    if ns > MAX_NS:
        raise sim_error("PLC4012", f"{what}: {value!r} is longer than a year; give a duration "
                        "of at most 366d")
    return ns


def parse_seconds(value: Any, what: str = "duration", allow_zero: bool = True) -> float:
    """Like :func:`parse_ns`, in seconds (a float)."""
    return parse_ns(value, what, allow_zero) / 1e9


def format_duration(seconds: float) -> str:
    """A short human form: ``1h30min``, ``250ms``, ``12.5s``."""
    if seconds != seconds:
        return "nan"
    ns = round(seconds * 1e9)
    if ns == 0:
        return "0s"
    if ns % 1_000_000_000:
        if ns < 1_000_000_000:
            ms = ns / 1e6
            return f"{ms:g}ms"
        return f"{ns / 1e9:g}s"
    s = ns // 1_000_000_000
    parts = []
    for unit, size in (("d", 86400), ("h", 3600), ("min", 60), ("s", 1)):
        if s >= size:
            parts.append(f"{s // size}{unit}")
            s %= size
    return "".join(parts)
