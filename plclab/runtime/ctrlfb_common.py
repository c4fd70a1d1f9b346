"""What the control blocks of :mod:`.ctrlfb` and :mod:`.ctrlfb_signals` share: reading REAL and
TIME inputs that may be unusable (NaN, negative), DINT wrap-around, and the base class of a block
that needs its sampling interval (the conventions are in :mod:`.ctrlfb`'s docstring).
"""

from __future__ import annotations

import math

from ..compile.real32 import f32 as _f32
from .stdfb import NativeBlock

_isfinite = math.isfinite


def real_in(x):
    """A value read from a REAL input as a Python float (NaN for anything unusable)."""
    try:
        return float(x)
    except (TypeError, ValueError, OverflowError):
        return math.nan


def ms_in(x) -> int:
    """A TIME input in ms, never negative."""
    try:
        x = int(x)
    except (TypeError, ValueError, OverflowError):
        return 0
    return x if x > 0 else 0


def wrap_dint(n: int) -> int:
    return ((n + 0x80000000) & 0xFFFFFFFF) - 0x80000000


class TimedBlock(NativeBlock):
    """A block that needs its sampling interval: ``_step_s(cycle)`` returns T in seconds."""

    __slots__ = ("_last", "_dbl")

    def _step_s(self, cycle=0) -> float:
        now = self._ctx.now
        c = ms_in(cycle)
        last = self._last
        self._last = now
        if c > 0:
            return c / 1000.0
        if last is not None and now > last:
            return (now - last) / 1000.0
        t = real_in(self._ctx.cycle_ms)
        return t / 1000.0 if _isfinite(t) and t > 0 else 0.01

    def _r(self, x: float) -> float:
        """A REAL output: single precision unless the block was built with double=True."""
        return x if self._dbl else _f32(x)
