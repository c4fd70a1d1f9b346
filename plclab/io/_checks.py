"""Argument checks shared by the I/O modules (PlcError codes PLC9104, PLC9105, PLC9109)."""

from __future__ import annotations

import math

from plclab.errors import PlcError

TIME_EPS = 1e-9
"""Events due at most this many seconds after a call's ``t`` count as happened: scan times
such as ``k * 0.01`` and delays such as 0.005 s do not add up exactly in binary floats."""


def check_range(lo: float, hi: float) -> None:
    """Raise PLC9104 unless ``lo`` and ``hi`` are finite and different."""
    if not (math.isfinite(lo) and math.isfinite(hi)) or lo == hi:
        raise PlcError(
            "PLC9104",
            f"engineering range {lo}..{hi} is empty or not finite; give two different numbers",
        )


def check_nonneg(name: str, value: float, unit: str) -> None:
    """Raise PLC9105 unless ``value`` is a finite number >= 0."""
    if not (value >= 0.0 and math.isfinite(value)):
        raise PlcError(
            "PLC9105", f"{name} must be zero or a positive number of {unit}, not {value}"
        )


def check_time(t: float, last: float | None, what: str) -> None:
    """Raise PLC9109 unless ``t`` is finite and not before ``last``."""
    if not math.isfinite(t):
        raise PlcError("PLC9109", f"{what}: time must be a finite number of seconds, not {t}")
    if last is not None and t < last:
        raise PlcError(
            "PLC9109",
            f"{what}: time went backwards ({t} s after {last} s); call with increasing t "
            "or reset() first",
        )
