"""Control and signal function blocks: PID, PID_INC, HYST, AI_SCALE, AO_SCALE, DEBOUNCE, BLINKER,
RAMP, PT1, MOVING_AVG and LIMIT_ALARM, implemented natively.

Their interfaces are declared in ``ctrllib.st`` (read by the checker like any other source),
each bound here with a ``{native 'NAME'}`` pragma (registry: :mod:`plclab.runtime.natives`);
``docs/blocks.md`` documents every block with its interface table, equations and an ST example. NORM_X, SCALE_X,
SCALE_R and DEADBAND are plain ST in ``ctrllib.st``.

Conventions shared by all blocks here:

* **Defaults.** Declared initial values of a native block's ST interface are not applied by
  the compiler, so every ``__init__`` sets the same defaults as ``ctrllib.st`` declares.
* **Time.** ``ctx.now`` (TIME, ms) is sampled once per scan. A block's sampling interval
  ``T`` (seconds) is its ``CYCLE`` input where it has one and it is > 0, else the time since
  the block's previous call; on the first call, or when no time has passed (a second call in
  the same scan, frozen time in a TEST), the task's cycle ``ctx.cycle_ms`` is used, as
  CODESYS's PID_FIXCYCLE does.
* **Never raise.** No input (NaN, infinity, zero ranges, unknown strings, negative times)
  makes a block raise. A computation that would give a non-finite result holds the previous
  output instead (and the block's state), so one bad sample cannot poison a controller.
* **Precision.** State is kept in double precision. REAL outputs are rounded to single
  precision, as a REAL store would round them (the compiler does not round a REAL read from
  a block output). ``Cls(ctx, double=True)`` keeps double-precision outputs; the verification
  tests use it to compare with python-control at 1e-9.

Examples
--------
>>> class Ctx:
...     now = 0
...     cycle_ms = 100.0
>>> pid = PID(Ctx(), double=True)
>>> pid.SETPOINT, pid.ACTUAL, pid.KP, pid.TN = 10.0, 8.0, 2.0, 4.0
>>> pid._body(); pid.Y          # P only on the first call: 2 * (10 - 8)
4.0
>>> Ctx.now = 100; pid._body(); pid.Y   # + I: 2/4 * 2 * 0.1
4.1
"""

from __future__ import annotations

import math

from ..compile.real32 import f32 as _f32
from .stdfb import NativeBlock

__all__ = ["PID", "PID_INC", "HYST", "AI_SCALE", "AO_SCALE", "DEBOUNCE", "BLINKER", "RAMP", "PT1",
           "MOVING_AVG", "LIMIT_ALARM"]

_isfinite = math.isfinite


def _real(x):
    """A value read from a REAL input as a Python float (NaN for anything unusable)."""
    try:
        return float(x)
    except (TypeError, ValueError, OverflowError):
        return math.nan


def _ms(x) -> int:
    """A TIME input in ms, never negative."""
    try:
        x = int(x)
    except (TypeError, ValueError, OverflowError):
        return 0
    return x if x > 0 else 0


def _dint(n: int) -> int:
    return ((n + 0x80000000) & 0xFFFFFFFF) - 0x80000000


class _Timed(NativeBlock):
    """A block that needs its sampling interval: ``_step_s(cycle)`` returns T in seconds."""

    __slots__ = ("_last", "_dbl")

    def _step_s(self, cycle=0) -> float:
        now = self._ctx.now
        c = _ms(cycle)
        last = self._last
        self._last = now
        if c > 0:
            return c / 1000.0
        if last is not None and now > last:
            return (now - last) / 1000.0
        t = _real(self._ctx.cycle_ms)
        return t / 1000.0 if _isfinite(t) and t > 0 else 0.01

    def _r(self, x: float) -> float:
        """A REAL output: single precision unless the block was built with double=True."""
        return x if self._dbl else _f32(x)


# ---------------------------------------------------------------------------------------- PID

class PID(_Timed):
    """Positional PID controller with anti-windup, bumpless manual/auto transfer, derivative
    on the measurement with a first-order lag, an error deadband and direct/reverse action.

    CODESYS parameters: ``Y = KP * (e + 1/TN * integral(e dt) + TV * de/dt) + Y_OFFSET``,
    KP, TN and TV REAL, TN and TV in seconds; TN = 0 switches the integral action off and
    TV = 0 the derivative action. Y is limited to Y_MIN .. Y_MAX when Y_MAX > Y_MIN (as in
    CODESYS, Y_MAX <= Y_MIN switches the limits off).

    Discrete equations, call n, sampling interval T = T(n) seconds (``CYCLE`` if > 0, else the
    time since the previous call, else the task cycle), ``s = +1`` direct acting (default),
    ``s = -1`` with REVERSE::

        e(n)  = s * (SETPOINT(n) - ACTUAL(n))
        e'(n) = 0                                 if |e(n)| <= DEADBAND
                e(n) - DEADBAND * sign(e(n))      otherwise (continuous deadband)
        P(n)  = KP * e'(n)
        I(n)  = I(n-1) + KP / TN * T(n) * e'(n-1)                       (TN > 0, else I(n-1))
        D(n)  = (TM * D(n-1) - s * KP * TV * (ACTUAL(n) - ACTUAL(n-1))) / (TM + T(n))
        u(n)  = P(n) + I(n) + D(n) + Y_OFFSET
        Y(n)  = LIMIT(Y_MIN, u(n), Y_MAX);  LIMITS_ACTIVE = u(n) outside Y_MIN .. Y_MAX

    with TM = TM_LAG in seconds. The integral is the forward-Euler (rectangle) sum of the
    source text, ``kI T sum(e(m), m = 0 .. n-1)`` (001 lines 7560-7600), so the block equals
    its incremental form PID_INC exactly (``q1`` holds ``kI T``), and python-control's
    ``sample_system(KP/(TN s), T, method="euler")``. The derivative is the backward-Euler
    (``method="backward_diff"``) discretisation of ``-s KP TV p / (1 + TM p)`` acting on
    ACTUAL; with TM = 0 it is the book's backward difference ``KP TV (e(n) - e(n-1)) / T``
    taken on the measurement, so a setpoint step gives no derivative kick. simple-pid with
    ``Ki = KP/TN``, ``Kd = KP*TV`` integrates backward (it includes e(n)): its output is this
    block's plus ``Ki * T * e(n)`` in the linear region.

    Start and RESET: the first call after start or RESET takes ACTUAL(n-1) = ACTUAL(n) and
    does not integrate, so ``Y = KP * e'(0) + Y_OFFSET``. While RESET is TRUE, I = D = 0 and
    Y = LIMIT(Y_MIN, Y_OFFSET, Y_MAX).

    Anti-windup (conditional integration): the increment ``dI = KP/TN * T * e'(n-1)`` is dropped
    when u(n) computed with it lies above Y_MAX and dI > 0, or below Y_MIN and dI < 0; the
    integral stops while the output is limited and runs again as soon as the error would
    drive the output back into range.

    Manual (bumpless): while MANUAL is TRUE, Y = LIMIT(Y_MIN, Y_MANUAL, Y_MAX), the derivative
    filter keeps following ACTUAL and the integral tracks ``I(n) = Y - P(n) - D(n) - Y_OFFSET``,
    so the first automatic call continues from Y_MANUAL. (With TN = 0 the tracked I is a
    constant bias, the "manual reset" of a P or PD controller.)

    Non-finite results (a NaN input, an overflow) hold Y, LIMITS_ACTIVE and the state.
    """

    __slots__ = ("ACTUAL", "SETPOINT", "KP", "TN", "TV", "Y_MANUAL", "Y_OFFSET", "Y_MIN",
                 "Y_MAX", "MANUAL", "RESET", "TM_LAG", "DEADBAND", "REVERSE", "CYCLE",
                 "Y", "LIMITS_ACTIVE", "_i", "_d", "_x1", "_e1", "_first")

    def __init__(self, ctx, double: bool = False) -> None:
        self._ctx = ctx
        self._dbl = double
        self._last = None
        self.ACTUAL = 0.0
        self.SETPOINT = 0.0
        self.KP = 1.0
        self.TN = 0.0
        self.TV = 0.0
        self.Y_MANUAL = 0.0
        self.Y_OFFSET = 0.0
        self.Y_MIN = 0.0
        self.Y_MAX = 100.0
        self.MANUAL = False
        self.RESET = False
        self.TM_LAG = 0
        self.DEADBAND = 0.0
        self.REVERSE = False
        self.CYCLE = 0
        self.Y = 0.0
        self.LIMITS_ACTIVE = False
        self._i = 0.0
        self._d = 0.0
        self._x1 = 0.0
        self._e1 = 0.0
        self._first = True

    def _body(self) -> None:
        T = self._step_s(self.CYCLE)
        lo, hi = _real(self.Y_MIN), _real(self.Y_MAX)
        limited = hi > lo
        off = _real(self.Y_OFFSET)
        if self.RESET:
            self._i = 0.0
            self._d = 0.0
            self._first = True
            y = min(max(off, lo), hi) if limited else off
            if _isfinite(y):
                self.Y = self._r(y)
            self.LIMITS_ACTIVE = False
            return
        x = _real(self.ACTUAL)
        kp = _real(self.KP)
        tn, tv = _real(self.TN), _real(self.TV)
        s = -1.0 if self.REVERSE else 1.0
        e = s * (_real(self.SETPOINT) - x)
        db = abs(_real(self.DEADBAND))
        if db > 0.0:
            e = 0.0 if abs(e) <= db else (e - db if e > 0.0 else e + db)
        first = self._first
        x1 = x if first else self._x1
        # derivative on the measurement, first-order lag, backward Euler
        if tv > 0.0:
            tm = _ms(self.TM_LAG) / 1000.0
            d = (tm * self._d - s * kp * tv * (x - x1)) / (tm + T)
        else:
            d = 0.0
        p = kp * e
        i = self._i
        if self.MANUAL:
            y = _real(self.Y_MANUAL)
            active = False
            if limited:
                active = y > hi or y < lo
                y = min(max(y, lo), hi)
            i = y - p - d - off
            u = y
        else:
            di = kp / tn * T * self._e1 if (tn > 0.0 and not first) else 0.0
            u = p + (i + di) + d + off
            if limited and ((u > hi and di > 0.0) or (u < lo and di < 0.0)):
                u = p + i + d + off  # anti-windup: the integral stops while limited
            else:
                i += di
            y = u
            active = False
            if limited:
                if u > hi:
                    y, active = hi, True
                elif u < lo:
                    y, active = lo, True
        if not (_isfinite(y) and _isfinite(i) and _isfinite(d) and _isfinite(e)
                and _isfinite(x)):
            return  # hold the output and the state
        self._i, self._d, self._x1, self._e1, self._first = i, d, x, e, False
        self.Y = self._r(y)
        self.LIMITS_ACTIVE = active


class PID_INC(_Timed):
    """Incremental (velocity) PID of the source text (001 lines 7527-7628)::

        u(n) = u(n-1) + q0 e(n) + q1 e(n-1) + q2 e(n-2)
        q0 = KP + KD/T,   q1 = -KP + KI*T - 2*KD/T,   q2 = KD/T
        e(n) = SETPOINT(n) - ACTUAL(n)
        Y(n) = u(n) = LIMIT(Y_MIN, u(n), Y_MAX)       (when Y_MAX > Y_MIN)

    It is the difference of the book's positional form
    ``u(n) = KP e(n) + KI T sum(e(m), m < n) + KD (e(n) - e(n-1)) / T``. Because the stored
    u(n-1) is the limited output, the clamp is also the anti-windup: the output leaves a limit
    as soon as the increments change sign. T (s) is ``CYCLE`` if > 0, else the time since the
    previous call, else the task cycle.

    Start and RESET: the first call (after start or RESET) gives the positional value with no
    integral and no derivative kick, ``u(0) = LIMIT(Y_MIN, KP e(0), Y_MAX)``, and takes
    ``e(-1) = e(0)``; from then on the output equals the PID block with ``TN = KP/KI``,
    ``TV = KD/KP`` and a constant setpoint (D on the error equals D on the measurement),
    as long as neither block limits. While RESET is TRUE, Y = LIMIT(Y_MIN, 0, Y_MAX).
    Non-finite results hold Y and the state.
    """

    __slots__ = ("ACTUAL", "SETPOINT", "KP", "KI", "KD", "Y_MIN", "Y_MAX", "RESET", "CYCLE",
                 "Y", "_u", "_e1", "_e2", "_first")

    def __init__(self, ctx, double: bool = False) -> None:
        self._ctx = ctx
        self._dbl = double
        self._last = None
        self.ACTUAL = 0.0
        self.SETPOINT = 0.0
        self.KP = 1.0
        self.KI = 0.0
        self.KD = 0.0
        self.Y_MIN = 0.0
        self.Y_MAX = 100.0
        self.RESET = False
        self.CYCLE = 0
        self.Y = 0.0
        self._u = 0.0
        self._e1 = 0.0
        self._e2 = 0.0
        self._first = True

    def _body(self) -> None:
        T = self._step_s(self.CYCLE)
        lo, hi = _real(self.Y_MIN), _real(self.Y_MAX)
        limited = hi > lo
        if self.RESET:
            self._first = True
            u = min(max(0.0, lo), hi) if limited else 0.0
            if _isfinite(u):
                self._u = u
                self.Y = self._r(u)
            return
        kp, ki, kd = _real(self.KP), _real(self.KI), _real(self.KD)
        e = _real(self.SETPOINT) - _real(self.ACTUAL)
        if self._first:
            u = kp * e
            e1 = e2 = e
        else:
            e1, e2 = self._e1, self._e2
            q0 = kp + kd / T
            q1 = -kp + ki * T - 2.0 * kd / T
            q2 = kd / T
            u = self._u + q0 * e + q1 * e1 + q2 * e2
        if limited:
            u = min(max(u, lo), hi)
        if not (_isfinite(u) and _isfinite(e)):
            return
        self._u, self._e2, self._e1, self._first = u, e1, e, False
        self.Y = self._r(u)


# --------------------------------------------------------------------------------------- HYST

class HYST(NativeBlock):
    """Two-position (on/off) regulator with hysteresis and minimum on/off times.

    Heating (REVERSE = FALSE): Q goes TRUE when ``IN < SP - H`` and FALSE when ``IN > SP + H``;
    between the two thresholds Q keeps its state (001 lines 7360-7455: 50 degC +- 2).
    Cooling (REVERSE = TRUE): Q goes TRUE when ``IN > SP + H`` and FALSE when ``IN < SP - H``.
    H is the half-width of the band (|H| is used); H = 0 is the plain comparator of the book,
    which chatters on a noisy signal.

    Relay protection: Q may switch off only after it has been on for T_MIN_ON and switch on
    only after it has been off for T_MIN_OFF (the first switch-on after start is free). A
    switch that is held back happens at the first call after the time has run out if its
    condition still holds. SWITCHES counts every change of Q (DINT, wraps). A NaN input
    satisfies no condition, so Q holds.
    """

    __slots__ = ("IN", "SP", "H", "REVERSE", "T_MIN_ON", "T_MIN_OFF", "Q", "SWITCHES", "_tsw")

    def __init__(self, ctx) -> None:
        self._ctx = ctx
        self.IN = 0.0
        self.SP = 0.0
        self.H = 1.0
        self.REVERSE = False
        self.T_MIN_ON = 0
        self.T_MIN_OFF = 0
        self.Q = False
        self.SWITCHES = 0
        self._tsw = None  # time of the last switch

    def _body(self) -> None:
        x, sp, h = _real(self.IN), _real(self.SP), abs(_real(self.H))
        low, high = x < sp - h, x > sp + h
        on, off = (high, low) if self.REVERSE else (low, high)
        now = self._ctx.now
        tsw = self._tsw
        if self.Q:
            if off and (tsw is None or now - tsw >= _ms(self.T_MIN_ON)):
                self.Q = False
                self._tsw = now
                self.SWITCHES = _dint(self.SWITCHES + 1)
        elif on and (tsw is None or now - tsw >= _ms(self.T_MIN_OFF)):
            self.Q = True
            self._tsw = now
            self.SWITCHES = _dint(self.SWITCHES + 1)


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
