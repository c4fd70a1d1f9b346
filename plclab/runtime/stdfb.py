"""The IEC 61131-3 standard function blocks, implemented natively for speed.

Their interfaces are declared in ``stdlib.st`` (the checker reads that file like any other),
each bound here with a ``{native 'NAME'}`` pragma through the registry in
:mod:`plclab.runtime.natives`. Time is read once per
call from ``ctx.now`` (TIME, milliseconds), which the PLC samples once per scan, so every timer
in a scan sees the same time. Behaviour follows the IEC timing diagrams and Table 11 of
``001_c648febd3bbd6efb.txt`` (lines 3272-3314).

A native block is a class whose attributes are the upper-case names of its ST declaration,
created as ``Cls(ctx)`` and run with ``inst._body()``; new blocks (PID, HYST, ...) follow
the same pattern.
"""

from __future__ import annotations


class NativeBlock:
    """Base class: subclasses set their inputs/outputs in ``__init__`` and define ``_body``."""

    __slots__ = ("_ctx",)

    def __init__(self, ctx) -> None:
        self._ctx = ctx

    def _copy(self):
        new = object.__new__(type(self))
        for cls in type(self).__mro__:
            for s in getattr(cls, "__slots__", ()):
                if hasattr(self, s):
                    setattr(new, s, getattr(self, s))
        return new


class TP(NativeBlock):
    """Pulse: a rising edge of IN starts a pulse of length PT; IN and PT are ignored while it runs."""

    __slots__ = ("IN", "PT", "Q", "ET", "_prev", "_start", "_pt", "_running")

    def __init__(self, ctx) -> None:
        self._ctx = ctx
        self.IN = False
        self.PT = 0
        self.Q = False
        self.ET = 0
        self._prev = False
        self._start = 0
        self._pt = 0
        self._running = False

    def _body(self) -> None:
        now = self._ctx.now
        inp = self.IN
        if self._running:
            et = now - self._start
            if et >= self._pt:
                self.ET = self._pt
                self.Q = False
                self._running = False
            else:
                self.ET = et
        if not self._running:
            if inp and not self._prev and not self.Q:
                self._start = now
                self._pt = self.PT
                if self._pt > 0:
                    self._running = True
                    self.Q = True
                self.ET = 0
            elif not inp:
                self.ET = 0
        self._prev = inp


class TON(NativeBlock):
    """On-delay: Q becomes TRUE when IN has been TRUE for PT; IN FALSE resets Q and ET.
    PT is taken when timing starts (a change while it runs has no effect, Table 11)."""

    __slots__ = ("IN", "PT", "Q", "ET", "_start", "_timing", "_pt")

    def __init__(self, ctx) -> None:
        self._ctx = ctx
        self.IN = False
        self.PT = 0
        self.Q = False
        self.ET = 0
        self._start = 0
        self._timing = False
        self._pt = 0

    def _body(self) -> None:
        if self.IN:
            now = self._ctx.now
            if not self._timing:
                self._timing = True
                self._start = now
                self._pt = self.PT
            et = now - self._start
            pt = self._pt
            if et >= pt:
                self.Q = True
                self.ET = pt
            else:
                self.Q = False
                self.ET = et
        else:
            self._timing = False
            self.Q = False
            self.ET = 0


class SFC_TIMER(NativeBlock):
    """A chart step's elapsed time ``S.T`` (sfclib.st; ADR 0016): ET counts while IN is TRUE
    from the rising edge of IN, and from the instance's creation when IN is TRUE at its first
    call (the initial step is active from the POU's initialisation, IEC 61131-3 ed.2 2.6.2,
    ed.3 6.7.2); IN FALSE resets ET. No preset: ET saturates at the largest TIME."""

    __slots__ = ("IN", "ET", "_start", "_timing", "_called")

    def __init__(self, ctx) -> None:
        self._ctx = ctx
        self.IN = False
        self.ET = 0
        self._start = ctx.now
        self._timing = False
        self._called = False

    def _body(self) -> None:
        now = self._ctx.now
        if self.IN:
            if not self._timing:
                self._timing = True
                if self._called:  # activated now; else active since creation (_start)
                    self._start = now
            self.ET = min(now - self._start, _MAX_TIME)
        else:
            self._timing = False
            self.ET = 0
        self._called = True


_MAX_TIME = 2147483647  # T#24d20h31m23s647ms (TIME counts milliseconds here)


class TOF(NativeBlock):
    """Off-delay: Q follows IN up at once and falls PT after IN falls; IN TRUE restarts it.
    PT is taken when IN falls (a change during the delay has no effect, Table 11)."""

    __slots__ = ("IN", "PT", "Q", "ET", "_prev", "_start", "_timing", "_pt")

    def __init__(self, ctx) -> None:
        self._ctx = ctx
        self.IN = False
        self.PT = 0
        self.Q = False
        self.ET = 0
        self._prev = False
        self._start = 0
        self._timing = False
        self._pt = 0

    def _body(self) -> None:
        if self.IN:
            self.Q = True
            self.ET = 0
            self._timing = False
        else:
            if self._prev:
                self._start = self._ctx.now
                self._timing = True
                self._pt = self.PT
            if self._timing:
                et = self._ctx.now - self._start
                if et >= self._pt:
                    self.ET = self._pt
                    self.Q = False
                    self._timing = False
                else:
                    self.ET = et
                    self.Q = True
        self._prev = self.IN


class TONR(NativeBlock):
    """Retentive on-delay (S7 TONR): ET accumulates while IN is TRUE, holds while it is FALSE,
    Q = ET >= PT; R resets ET and Q. PT is taken when the timer starts or resumes. The call
    that sees IN fall still adds the time since the previous call (IN was TRUE until then, as
    far as the PLC knows), so no pause loses a scan period."""

    __slots__ = ("IN", "R", "PT", "Q", "ET", "_prev", "_last", "_pt")

    def __init__(self, ctx) -> None:
        self._ctx = ctx
        self.IN = False
        self.R = False
        self.PT = 0
        self.Q = False
        self.ET = 0
        self._prev = False
        self._last = 0
        self._pt = 0

    def _body(self) -> None:
        now = self._ctx.now
        if self.R:
            self.ET = 0
            self.Q = False
        elif self.IN:
            if self._prev:
                self.ET = min(self.ET + (now - self._last), self._pt)
            else:
                self._pt = self.PT
            self.Q = self.ET >= self._pt
        else:
            if self._prev:  # the scan that sees IN fall: count the interval up to it
                self.ET = min(self.ET + (now - self._last), self._pt)
            self.Q = self.ET >= self._pt and self.ET > 0
        self._prev = self.IN and not self.R
        self._last = now


class CTU(NativeBlock):
    """Up counter: CV counts rising edges of CU (up to 32767); R resets; Q = CV >= PV."""

    __slots__ = ("CU", "R", "PV", "Q", "CV", "_prev")
    _lo, _hi = -32768, 32767  # CV's type (INT; the typed counters CTU_DINT ... below)

    def __init__(self, ctx) -> None:
        self._ctx = ctx
        self.CU = False
        self.R = False
        self.PV = 0
        self.Q = False
        self.CV = 0
        self._prev = False

    def _body(self) -> None:
        cu = self.CU
        if self.R:
            self.CV = 0
        elif cu and not self._prev and self.CV < self._hi:
            self.CV += 1
        self._prev = cu
        self.Q = self.CV >= self.PV


class CTD(NativeBlock):
    """Down counter: LD loads PV; rising edges of CD count down (to -32768); Q = CV <= 0."""

    __slots__ = ("CD", "LD", "PV", "Q", "CV", "_prev")
    _lo, _hi = -32768, 32767

    def __init__(self, ctx) -> None:
        self._ctx = ctx
        self.CD = False
        self.LD = False
        self.PV = 0
        self.Q = False
        self.CV = 0
        self._prev = False

    def _body(self) -> None:
        cd = self.CD
        if self.LD:
            self.CV = self.PV
        elif cd and not self._prev and self.CV > self._lo:
            self.CV -= 1
        self._prev = cd
        self.Q = self.CV <= 0


class CTUD(NativeBlock):
    """Up/down counter: R resets, LD loads PV, else rising CU counts up and rising CD down."""

    __slots__ = ("CU", "CD", "R", "LD", "PV", "QU", "QD", "CV", "_pu", "_pd")
    _lo, _hi = -32768, 32767

    def __init__(self, ctx) -> None:
        self._ctx = ctx
        self.CU = False
        self.CD = False
        self.R = False
        self.LD = False
        self.PV = 0
        self.QU = False
        self.QD = False
        self.CV = 0
        self._pu = False
        self._pd = False

    def _body(self) -> None:
        cu, cd = self.CU, self.CD
        up = cu and not self._pu
        down = cd and not self._pd
        if self.R:
            self.CV = 0
        elif self.LD:
            self.CV = self.PV
        elif up and not down:
            if self.CV < self._hi:
                self.CV += 1
        elif down and not up:
            if self.CV > self._lo:
                self.CV -= 1
        self._pu, self._pd = cu, cd
        self.QU = self.CV >= self.PV
        self.QD = self.CV <= 0


class RTC(NativeBlock):
    """Real-time clock, IEC 61131-3 ed.1 Table 35, as MATIEC's ``lib/rtc.txt`` defines it: Q is a
    copy of IN; on a rising IN the clock is set to PDT and, while IN stays TRUE, CDT is PDT plus
    the time since; with IN FALSE, CDT is the PLC's current date and time. plclab's current date
    and time is the virtual clock (ADR 0006) read as DT: DT#1970-01-01-00:00:00 plus the time
    since the PLC started, never the wall clock (ADR 0037). DT values are milliseconds."""

    __slots__ = ("IN", "PDT", "Q", "CDT", "_prev", "_offset")

    def __init__(self, ctx) -> None:
        self._ctx = ctx
        self.IN = False
        self.PDT = 0
        self.Q = False
        self.CDT = 0
        self._prev = False
        self._offset = 0

    def _body(self) -> None:
        now = self._ctx.now
        inp = self.IN
        if inp:
            if not self._prev:
                self._offset = self.PDT - now
            self.CDT = now + self._offset
        else:
            self.CDT = now
        self.Q = inp
        self._prev = inp


class R_TRIG(NativeBlock):
    """Rising edge: Q is TRUE for one call when CLK goes from FALSE to TRUE."""

    __slots__ = ("CLK", "Q", "_m")

    def __init__(self, ctx) -> None:
        self._ctx = ctx
        self.CLK = False
        self.Q = False
        self._m = False

    def _body(self) -> None:
        clk = self.CLK
        self.Q = clk and not self._m
        self._m = clk


class F_TRIG(NativeBlock):
    """Falling edge: Q is TRUE for one call when CLK goes from TRUE to FALSE (no pulse on the
    first call with CLK FALSE, as CODESYS and TIA behave)."""

    __slots__ = ("CLK", "Q", "_m")

    def __init__(self, ctx) -> None:
        self._ctx = ctx
        self.CLK = False
        self.Q = False
        self._m = False

    def _body(self) -> None:
        clk = self.CLK
        self.Q = self._m and not clk
        self._m = clk


class SR(NativeBlock):
    """Set-dominant bistable: Q1 := S1 OR (NOT R AND Q1)."""

    __slots__ = ("S1", "R", "Q1")

    def __init__(self, ctx) -> None:
        self._ctx = ctx
        self.S1 = False
        self.R = False
        self.Q1 = False

    def _body(self) -> None:
        self.Q1 = self.S1 or (not self.R and self.Q1)


class RS(NativeBlock):
    """Reset-dominant bistable: Q1 := NOT R1 AND (S OR Q1)."""

    __slots__ = ("S", "R1", "Q1")

    def __init__(self, ctx) -> None:
        self._ctx = ctx
        self.S = False
        self.R1 = False
        self.Q1 = False

    def _body(self) -> None:
        self.Q1 = not self.R1 and (self.S or self.Q1)


# The typed counters of IEC 61131-3 ed.3 Table 45 (CTU_DINT ... CTUD_ULINT): the same bodies,
# counting within their CV type's range (an unsigned down counter stops at 0).
_RANGES = {"INT": (-(1 << 15), (1 << 15) - 1), "DINT": (-(1 << 31), (1 << 31) - 1),
           "LINT": (-(1 << 63), (1 << 63) - 1), "UDINT": (0, (1 << 32) - 1),
           "ULINT": (0, (1 << 64) - 1)}


def _typed(base: type, suffix: str) -> type:
    lo, hi = _RANGES[suffix]
    return type(f"{base.__name__}_{suffix}", (base,), {"__slots__": (), "_lo": lo, "_hi": hi})


CTU_INT, CTU_DINT, CTU_LINT, CTU_UDINT, CTU_ULINT = (_typed(CTU, s) for s in _RANGES)
CTD_INT, CTD_DINT, CTD_LINT, CTD_UDINT, CTD_ULINT = (_typed(CTD, s) for s in _RANGES)
CTUD_INT, CTUD_DINT, CTUD_LINT, CTUD_UDINT, CTUD_ULINT = (_typed(CTUD, s) for s in _RANGES)
