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

from .ctrlfb_common import TimedBlock as _Timed
from .ctrlfb_common import ms_in as _ms
from .ctrlfb_common import real_in as _real
from .ctrlfb_common import wrap_dint as _dint
from .ctrlfb_signals import (
    AI_SCALE,
    AO_SCALE,
    BLINKER,
    DEBOUNCE,
    LIMIT_ALARM,
    MOVING_AVG,
    PT1,
    RAMP,
)
from .stdfb import NativeBlock

_isfinite = math.isfinite

__all__ = ["PID", "PID_INC", "HYST", "AI_SCALE", "AO_SCALE", "DEBOUNCE", "BLINKER", "RAMP", "PT1",
           "MOVING_AVG", "LIMIT_ALARM"]


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
