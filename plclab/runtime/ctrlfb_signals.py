"""Analog scaling and signal blocks: AI_SCALE, AO_SCALE, DEBOUNCE, BLINKER, RAMP, PT1,
MOVING_AVG and LIMIT_ALARM, implemented natively (the conventions are in :mod:`.ctrlfb`).
"""

from __future__ import annotations

import math

from ..compile.real32 import f32 as _f32
from .ctrlfb_common import TimedBlock as _Timed
from .ctrlfb_common import ms_in as _ms
from .ctrlfb_common import real_in as _real
from .stdfb import NativeBlock

_isfinite = math.isfinite

__all__ = ["AI_SCALE", "AO_SCALE", "DEBOUNCE", "BLINKER", "RAMP", "PT1", "MOVING_AVG", "LIMIT_ALARM"]


# --------------------------------------------------------------------------- analog scaling

_CFG_ERR = "error"


def _scaling():
    """plclab.io.scaling, imported on first use (the runtime core stays light)."""
    from ..io import scaling

    return scaling


def _live_range(rng):
    """The live-zero version of a 0-based range: 20 % offset (0-20 mA -> 4-20 mA, 0-10 V ->
    2-10 V, 0-5 V -> 1-5 V) with the NE43 ratios of 4-20 mA (wire break <= 90 % of the live
    zero, saturation 95 %, high fault >= 105 % of the top)."""
    if rng.live_zero or rng.bipolar:
        return rng
    lz = rng.lo + 0.2 * rng.span
    return _scaling().SignalRange(f"{lz:g}-{rng.hi:g}{rng.unit}", lz, rng.hi, rng.unit, 0.95 * lz,
                       rng.sat_hi, 0.9 * lz, 1.05 * rng.hi)


def _config(rng_name, convention, bits, live):
    """(module range, effective range, count format) or _CFG_ERR; never raises."""
    try:
        sc = _scaling()
        rng = sc.signal_range(str(rng_name))
        b = int(bits)
        fmt = sc.count_format(str(convention), b if b > 0 else None, rng.bipolar)
        eff = _live_range(rng) if live else rng
        return rng, eff, fmt
    except Exception:  # noqa: BLE001 - a bad configuration is reported on ERROR
        return _CFG_ERR


class _Scaler(NativeBlock):
    """What AI_SCALE and AO_SCALE share: the channel configuration inputs (with the defaults
    of their ST declarations), the ERROR output and the cached scaling configuration."""

    __slots__ = ("_key", "_cfg", "_dbl", "LO", "HI", "RANGE", "CONVENTION", "BITS",
                 "LIVE_ZERO", "ERROR")

    def __init__(self, ctx, double: bool = False) -> None:
        self._ctx = ctx
        self._dbl = double
        self._key = None
        self._cfg = None
        self.LO = 0.0
        self.HI = 100.0
        self.RANGE = "4-20mA"
        self.CONVENTION = "s7"
        self.BITS = 0
        self.LIVE_ZERO = False
        self.ERROR = False

    def _get_cfg(self):
        key = (self.RANGE, self.CONVENTION, self.BITS, bool(self.LIVE_ZERO))
        if key != self._key:
            self._key = key
            self._cfg = _config(*key)
        return self._cfg


class AI_SCALE(_Scaler):
    """Analog input word (counts) -> engineering value, with the channel's status bits.

    Inputs: IN (counts, DINT so a 16-bit unipolar ADC's 0..65535 fits), LO / HI (engineering
    value at the lower / upper end of the signal range), RANGE (the module's measuring range
    as a STRING: ``'0-10V'``, ``'+-10V'``, ``'0-5V'``, ``'+-5V'``, ``'1-5V'``, ``'0-20mA'``,
    ``'4-20mA'``), CONVENTION (``'s7'`` 0..27648 nominal with over-range and special codes,
    ``'book'`` N/2^n, ``'full'`` N/(2^n - 1), ``'logo'`` 0..1000), BITS (ADC resolution;
    0 = the convention's default: book/full 12, s7 15 value bits, logo 10; book/full 1..24,
    s7 8..15 value bits without the sign), LIVE_ZERO (a live-zero transmitter on a 0-based
    input, the book's "20 % offset": 4-20 mA on a 0-20 mA input, 2-10 V on 0-10 V, 1-5 V on
    0-5 V; ignored for ranges that have a live zero already or are bipolar).

    The math is :mod:`plclab.io.scaling`'s: ``VALUE = counts_to_eng(IN, LO, HI)``
    (``LO + (IN - zero) * (HI - LO) / (full - zero)``), or ``signal_to_eng`` of
    ``counts_to_signal(IN)`` over the live-zero range; status from ``counts_status``
    (S7 special codes) and ``signal_status`` (NAMUR NE43 limits on live-zero ranges).

    Outputs: VALUE (linear also in the over/under-range, where it is still a measurement),
    WIRE_BREAK (live zero: signal <= 3.6 mA / 0.9 V, or S7 code 32767 on a live-zero range,
    which the S7 also uses for overflow: then OVERRANGE is set too), OVERRANGE / UNDERRANGE
    (beyond the nominal range, including overflow / underflow codes), ERROR (VALUE is not a
    measurement: wire break, short circuit (>= 21 mA), overflow / underflow code, a bad
    RANGE / CONVENTION / BITS, or a non-finite result). While ERROR is TRUE, VALUE holds its
    last good value (substitute value "last value").
    """

    __slots__ = ("IN", "VALUE", "WIRE_BREAK", "OVERRANGE", "UNDERRANGE")

    def __init__(self, ctx, double: bool = False) -> None:
        super().__init__(ctx, double)
        self.IN = 0
        self.VALUE = 0.0
        self.WIRE_BREAK = False
        self.OVERRANGE = False
        self.UNDERRANGE = False

    def _body(self) -> None:
        cfg = self._get_cfg()
        if cfg is _CFG_ERR:
            self.WIRE_BREAK = self.OVERRANGE = self.UNDERRANGE = False
            self.ERROR = True
            return
        sc = _scaling()
        rng, eff, fmt = cfg
        try:
            n = int(self.IN)
            lo, hi = _real(self.LO), _real(self.HI)
            st = sc.counts_status(n, convention=fmt, live_zero=eff.live_zero)
            if st.overflow or st.underflow or st.wire_break:
                self.WIRE_BREAK = st.wire_break
                self.OVERRANGE = st.overflow
                self.UNDERRANGE = st.underflow
                self.ERROR = True
                return
            sig = sc.counts_to_signal(n, rng, convention=fmt)
            ss = sc.signal_status(sig, eff)
            if eff is rng:
                v = sc.counts_to_eng(n, lo, hi, convention=fmt)
            else:
                v = sc.signal_to_eng(sig, lo, hi, eff)
        except Exception:  # noqa: BLE001 - never raise into the PLC program
            self.ERROR = True
            return
        self.WIRE_BREAK = ss.wire_break
        self.OVERRANGE = st.overrange or ss.overrange
        self.UNDERRANGE = st.underrange or ss.underrange
        bad = ss.wire_break or ss.short_circuit or not _isfinite(v)
        self.ERROR = bad
        if not bad:
            self.VALUE = v if self._dbl else _f32(v)


class AO_SCALE(_Scaler):
    """Engineering value -> analog output word (counts), clamped to the nominal range.

    Same RANGE, CONVENTION, BITS, LIVE_ZERO and LO / HI as :class:`AI_SCALE`. OUT =
    ``eng_to_counts(IN, LO, HI, limit=True)`` of :mod:`plclab.io.scaling` (over the live-zero
    range via ``eng_to_signal`` when LIVE_ZERO is set): IN below LO gives the range's zero
    code, above HI its full code (27648 for s7, 2^n - 1 for book / full, 1000 for logo).
    LIMITED is TRUE when IN was outside LO .. HI. OUT is an INT: the 16-bit pattern of the
    word, so a 16-bit unipolar DAC's codes above 32767 read as negative INTs (the same bits a
    %QW receives). ERROR (with OUT held) on a bad configuration, LO = HI or a NaN input.
    """

    __slots__ = ("IN", "OUT", "LIMITED")

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self.IN = 0.0
        self.OUT = 0
        self.LIMITED = False

    def _body(self) -> None:
        cfg = self._get_cfg()
        v, lo, hi = _real(self.IN), _real(self.LO), _real(self.HI)
        if cfg is _CFG_ERR or v != v or not (_isfinite(lo) and _isfinite(hi)) or lo == hi:
            self.ERROR = True
            return
        sc = _scaling()
        rng, eff, fmt = cfg
        try:
            frac = (v - lo) / (hi - lo)
            if eff is rng:
                c = sc.eng_to_counts(v, lo, hi, convention=fmt, limit=True)
            else:
                sig = sc.eng_to_signal(min(max(frac, 0.0), 1.0), 0.0, 1.0, eff)
                c = sc.eng_to_counts(sig, rng.lo, rng.hi, convention=fmt, limit=True)
        except Exception:  # noqa: BLE001 - never raise into the PLC program
            self.ERROR = True
            return
        self.LIMITED = not 0.0 <= frac <= 1.0
        self.ERROR = False
        self.OUT = ((int(c) + 0x8000) & 0xFFFF) - 0x8000


# ------------------------------------------------------------------------------ signal helpers

class DEBOUNCE(NativeBlock):
    """Debounce a contact on both edges: Q takes the value of IN once IN has kept that value
    for T_DEBOUNCE without interruption (a TON on ``IN <> Q``). Every bounce back restarts the
    time. T_DEBOUNCE = 0 gives Q = IN."""

    __slots__ = ("IN", "T_DEBOUNCE", "Q", "_start")

    def __init__(self, ctx) -> None:
        self._ctx = ctx
        self.IN = False
        self.T_DEBOUNCE = 10
        self.Q = False
        self._start = None

    def _body(self) -> None:
        inp = bool(self.IN)
        if inp == self.Q:
            self._start = None
            return
        now = self._ctx.now
        if self._start is None:
            self._start = now
        if now - self._start >= _ms(self.T_DEBOUNCE):
            self.Q = inp
            self._start = None


class BLINKER(NativeBlock):
    """Pulse generator: while ENABLE is TRUE, Q is TRUE for T_ON and FALSE for T_OFF, starting
    with TRUE at the call where ENABLE rose. ``Q = (now - start) MOD (T_ON + T_OFF) < T_ON``,
    computed from the clock, so the period is exact and never drifts (T#100ms / T#100ms at 10 ms
    scans: exactly 10 scans TRUE, 10 FALSE, 5 Hz). ENABLE FALSE: Q FALSE. T_OFF = 0: Q stays
    TRUE; T_ON = 0: Q stays FALSE."""

    __slots__ = ("ENABLE", "T_ON", "T_OFF", "Q", "_start")

    def __init__(self, ctx) -> None:
        self._ctx = ctx
        self.ENABLE = False
        self.T_ON = 500
        self.T_OFF = 500
        self.Q = False
        self._start = None

    def _body(self) -> None:
        if not self.ENABLE:
            self._start = None
            self.Q = False
            return
        now = self._ctx.now
        if self._start is None:
            self._start = now
        ton, toff = _ms(self.T_ON), _ms(self.T_OFF)
        period = ton + toff
        self.Q = period > 0 and (now - self._start) % period < ton


class RAMP(_Timed):
    """Rate limiter: OUT follows IN, changing by at most RATE units per second::

        OUT(n) = OUT(n-1) + LIMIT(-RATE*T, IN(n) - OUT(n-1), RATE*T)

    T is the time since the previous call (task cycle on the first call). OUT starts at 0.0;
    RESET sets OUT := IN. RATE <= 0 switches the limiter off (OUT = IN). BUSY is TRUE while
    OUT has not reached IN. A NaN IN holds OUT.
    """

    __slots__ = ("IN", "RATE", "RESET", "OUT", "BUSY", "_y")

    def __init__(self, ctx, double: bool = False) -> None:
        self._ctx = ctx
        self._dbl = double
        self._last = None
        self.IN = 0.0
        self.RATE = 1.0
        self.RESET = False
        self.OUT = 0.0
        self.BUSY = False
        self._y = 0.0

    def _body(self) -> None:
        T = self._step_s()
        x = _real(self.IN)
        if x != x:
            return  # NaN: hold
        if not _isfinite(x):
            x = math.copysign(3.4028234663852886e38, x)
        rate = _real(self.RATE)
        y = self._y
        if self.RESET or not rate > 0.0:
            y = x
        else:
            step = rate * T
            d = x - y
            if abs(d) <= step * (1.0 + 1e-9):  # within one step (and rounding): arrived
                y = x
            else:
                y = y + step if d > 0.0 else y - step
        if not _isfinite(y):
            return
        self._y = y
        self.OUT = self._r(y)
        self.BUSY = y != x


class PT1(_Timed):
    """First-order lag ``K / (1 + T s)``, discretised exactly for an input held over each
    interval (ZOH) but applied to the current input, as PLC filters do::

        a = exp(-Ts / T)
        OUT(n) = a * OUT(n-1) + (1 - a) * K * IN(n)

    with Ts the time since the previous call (task cycle on the first call). A step of IN at
    the first call therefore gives ``OUT(t) = K (1 - exp(-(t + Ts) / T))``: within one sample of
    the analytic ``K (1 - exp(-t/T))``, an error below ``K * Ts / T``. OUT starts at 0.0;
    T <= 0 gives OUT = K * IN. Non-finite results hold OUT.
    """

    __slots__ = ("IN", "T", "K", "OUT", "_y")

    def __init__(self, ctx, double: bool = False) -> None:
        self._ctx = ctx
        self._dbl = double
        self._last = None
        self.IN = 0.0
        self.T = 1000
        self.K = 1.0
        self.OUT = 0.0
        self._y = 0.0

    def _body(self) -> None:
        ts = self._step_s()
        tau = _ms(self.T) / 1000.0
        target = _real(self.K) * _real(self.IN)
        if tau <= 0.0:
            y = target
        else:
            a = math.exp(-ts / tau)  # ts/tau > 0: no overflow
            y = a * self._y + (1.0 - a) * target
        if not _isfinite(y):
            return
        self._y = y
        self.OUT = self._r(y)


class MOVING_AVG(NativeBlock):
    """Moving average of the last N samples (one sample a call), N = 1 .. 64 (clamped).

    ``AVG = (IN(n) + IN(n-1) + ... + IN(n-N+1)) / N``, computed afresh each call from a ring
    of the last 64 samples (no running-sum drift). Until N samples have been seen the average
    is over the samples so far; changing N takes effect at once. Non-finite samples are
    skipped (not stored). RESET empties the window (AVG = 0.0).
    """

    __slots__ = ("IN", "N", "RESET", "AVG", "_buf", "_pos", "_count", "_dbl")

    SIZE = 64

    def __init__(self, ctx, double: bool = False) -> None:
        self._ctx = ctx
        self._dbl = double
        self.IN = 0.0
        self.N = 8
        self.RESET = False
        self.AVG = 0.0
        self._buf = [0.0] * self.SIZE
        self._pos = 0
        self._count = 0

    def _copy(self):
        new = super()._copy()
        new._buf = list(self._buf)
        return new

    def _body(self) -> None:
        if self.RESET:
            self._pos = self._count = 0
            self.AVG = 0.0
            return
        x = _real(self.IN)
        if _isfinite(x):
            self._buf[self._pos] = x
            self._pos = (self._pos + 1) % self.SIZE
            if self._count < self.SIZE:
                self._count += 1
        try:
            n = int(self.N)
        except (TypeError, ValueError, OverflowError):
            n = 1
        n = min(max(n, 1), self._count)
        if n == 0:
            return
        buf, pos, size = self._buf, self._pos, self.SIZE
        try:
            avg = math.fsum(buf[(pos - k) % size] for k in range(1, n + 1)) / n
        except OverflowError:
            return
        if _isfinite(avg):
            self.AVG = avg if self._dbl else _f32(avg)


class LIMIT_ALARM(NativeBlock):
    """Analog limit alarms HH / H / L / LL with hysteresis, as WinCC analog alarms.

    A high alarm (QH, QHH) comes when ``IN > limit`` and goes when ``IN < limit - db``; a low
    alarm (QL, QLL) comes when ``IN < limit`` and goes when ``IN > limit + db``; in between
    it keeps its state. ``db = |DEADBAND|``, or ``|DEADBAND| / 100 * |limit|`` with PERCENT
    (WinCC's deadband "in percent" of the limit value). A limit left at its default
    (+-3.0E38) never triggers, so H / L alone give a two-limit alarm. A NaN IN holds every
    alarm. QHH implies nothing about QH: each limit is evaluated on its own (a value above HH
    is also above H, so both are normally set).
    """

    __slots__ = ("IN", "HH", "H", "L", "LL", "DEADBAND", "PERCENT", "QHH", "QH", "QL", "QLL")

    def __init__(self, ctx) -> None:
        self._ctx = ctx
        self.IN = 0.0
        self.HH = 3.0e38
        self.H = 3.0e38
        self.L = -3.0e38
        self.LL = -3.0e38
        self.DEADBAND = 0.0
        self.PERCENT = False
        self.QHH = False
        self.QH = False
        self.QL = False
        self.QLL = False

    def _db(self, limit: float) -> float:
        db = abs(_real(self.DEADBAND))
        if self.PERCENT:
            db = db / 100.0 * abs(limit)
        return db if db == db else 0.0

    def _body(self) -> None:
        x = _real(self.IN)
        if x != x:
            return
        for name, lim, high in (("QHH", self.HH, True), ("QH", self.H, True),
                                ("QL", self.L, False), ("QLL", self.LL, False)):
            lim = _real(lim)
            q = getattr(self, name)
            if high:
                if x > lim:
                    q = True
                elif x < lim - self._db(lim):
                    q = False
            else:
                if x < lim:
                    q = True
                elif x > lim + self._db(lim):
                    q = False
            setattr(self, name, q)
