"""Benchmark programs: each is ST source plus a hand-written plain-Python equivalent that does
the same work with the same semantics (state kept between scans, fixed-width integers wrapped
on store, REAL rounded to single precision on store, timers sampling one clock per scan).
"""

from __future__ import annotations

import struct

_F = struct.Struct("<f")


def f32(x: float) -> float:
    return _F.unpack(_F.pack(x))[0]


def w16(x: int) -> int:
    return ((x + 32768) & 0xFFFF) - 32768


def w32(x: int) -> int:
    return ((x + 2147483648) & 0xFFFFFFFF) - 2147483648


class Clock:
    __slots__ = ("now",)

    def __init__(self) -> None:
        self.now = 0


# ---------------------------------------------------------------------------------------------
FOR_SUM = """
PROGRAM Main
VAR i : INT; s : DINT; END_VAR
s := 0;
FOR i := 1 TO 100 DO
    s := s + i;
END_FOR
END_PROGRAM
"""


class ForSum:
    def __init__(self, clock):
        self.i = 0
        self.s = 0

    def body(self):
        self.s = 0
        for self.i in range(1, 101):
            self.s = w32(self.s + self.i)
        self.i = 101


# ---------------------------------------------------------------------------------------------
CASE_SM = """
PROGRAM Main
VAR state : INT; count : DINT; level : REAL; pump, valve, alarm : BOOL; ticks : INT; END_VAR
ticks := ticks + 1;
CASE state OF
    0: pump := FALSE; valve := FALSE;
       IF ticks > 3 THEN state := 1; ticks := 0; END_IF
    1: pump := TRUE; level := level + 0.5;
       IF level >= 10.0 THEN state := 2; END_IF
    2: pump := FALSE; valve := TRUE; level := level - 1.0;
       IF level <= 0.0 THEN state := 3; level := 0.0; END_IF
    3: count := count + 1; alarm := count MOD 10 = 0; state := 0; ticks := 0;
ELSE
    state := 0;
END_CASE
END_PROGRAM
"""


class CaseSm:
    def __init__(self, clock):
        self.state = 0
        self.count = 0
        self.level = 0.0
        self.pump = self.valve = self.alarm = False
        self.ticks = 0

    def body(self):
        self.ticks = w16(self.ticks + 1)
        st = self.state
        if st == 0:
            self.pump = False
            self.valve = False
            if self.ticks > 3:
                self.state = 1
                self.ticks = 0
        elif st == 1:
            self.pump = True
            self.level = f32(self.level + 0.5)
            if self.level >= 10.0:
                self.state = 2
        elif st == 2:
            self.pump = False
            self.valve = True
            self.level = f32(self.level - 1.0)
            if self.level <= 0.0:
                self.state = 3
                self.level = 0.0
        elif st == 3:
            self.count = w32(self.count + 1)
            c = self.count
            self.alarm = c - 10 * int(c / 10) == 0
            self.state = 0
            self.ticks = 0
        else:
            self.state = 0


# ---------------------------------------------------------------------------------------------
TONS = """
PROGRAM Main
VAR t : ARRAY[1..100] OF TON; i : INT; run : BOOL := TRUE; done : INT; END_VAR
done := 0;
FOR i := 1 TO 100 DO
    t[i](IN := run, PT := T#500ms);
    IF t[i].Q THEN done := done + 1; END_IF
END_FOR
END_PROGRAM
"""


class Ton:
    __slots__ = ("IN", "PT", "Q", "ET", "start", "timing", "pt", "clock")

    def __init__(self, clock):
        self.clock = clock
        self.IN = False
        self.PT = 0
        self.Q = False
        self.ET = 0
        self.start = 0
        self.timing = False
        self.pt = 0

    def __call__(self):
        if self.IN:
            now = self.clock.now
            if not self.timing:
                self.timing = True
                self.start = now
                self.pt = self.PT
            et = now - self.start
            if et >= self.pt:
                self.Q = True
                self.ET = self.pt
            else:
                self.Q = False
                self.ET = et
        else:
            self.timing = False
            self.Q = False
            self.ET = 0


class Tons:
    def __init__(self, clock):
        self.t = [Ton(clock) for _ in range(100)]
        self.i = 0
        self.run = True
        self.done = 0

    def body(self):
        self.done = 0
        for self.i in range(1, 101):
            t = self.t[self.i - 1]
            t.IN = self.run
            t.PT = 500
            t()
            if t.Q:
                self.done = w16(self.done + 1)
        self.i = 101


# ---------------------------------------------------------------------------------------------
PID = """
PROGRAM Main
VAR sp : REAL := 50.0; pv : REAL := 20.0; e, e_prev, integ, deriv, u : REAL;
    kp : REAL := 2.0; ki : REAL := 0.5; kd : REAL := 0.1; dt : REAL := 0.01; n : INT;
END_VAR
FOR n := 1 TO 10 DO
    e := sp - pv;
    integ := LIMIT(-100.0, integ + e * dt, 100.0);
    deriv := (e - e_prev) / dt;
    u := LIMIT(0.0, kp * e + ki * integ + kd * deriv, 100.0);
    e_prev := e;
    pv := pv + (u * 0.05 - (pv - 20.0) * 0.01) * dt;
END_FOR
END_PROGRAM
"""


class Pid:
    def __init__(self, clock):
        self.sp, self.pv = 50.0, 20.0
        self.e = self.e_prev = self.integ = self.deriv = self.u = 0.0
        self.kp, self.ki, self.kd, self.dt = 2.0, 0.5, f32(0.1), f32(0.01)
        self.n = 0

    def body(self):
        for self.n in range(1, 11):
            self.e = f32(self.sp - self.pv)
            x = self.integ + self.e * self.dt
            self.integ = f32(-100.0 if x < -100.0 else 100.0 if x > 100.0 else x)
            if self.dt == 0:
                raise ZeroDivisionError
            self.deriv = f32((self.e - self.e_prev) / self.dt)
            x = self.kp * self.e + self.ki * self.integ + self.kd * self.deriv
            self.u = f32(0.0 if x < 0.0 else 100.0 if x > 100.0 else x)
            self.e_prev = self.e
            self.pv = f32(self.pv + (self.u * f32(0.05) - (self.pv - 20.0) * f32(0.01)) * self.dt)
        self.n = 11


# ---------------------------------------------------------------------------------------------
BUBBLE = """
PROGRAM Main
VAR a : ARRAY[1..100] OF INT; i, j : INT; tmp : INT; seed : DINT := 12345; END_VAR
FOR i := 1 TO 100 DO
    seed := (seed * 1103515245 + 12345) MOD 2147483647;
    a[i] := DINT_TO_INT(seed MOD 1000);
END_FOR
FOR i := 1 TO 99 DO
    FOR j := 1 TO 100 - i DO
        IF a[j] > a[j + 1] THEN
            tmp := a[j]; a[j] := a[j + 1]; a[j + 1] := tmp;
        END_IF
    END_FOR
END_FOR
END_PROGRAM
"""


def _imod(a, b):
    q = abs(a) // abs(b)
    q = q if (a >= 0) == (b > 0) else -q
    return a - b * q


class Bubble:
    def __init__(self, clock):
        self.a = [0] * 100
        self.i = self.j = self.tmp = 0
        self.seed = 12345

    def body(self):
        a = self.a
        for self.i in range(1, 101):
            self.seed = w32(_imod(self.seed * 1103515245 + 12345, 2147483647))
            a[self.i - 1] = w16(_imod(self.seed, 1000))
        self.i = 101
        for self.i in range(1, 100):
            for self.j in range(1, 100 - self.i + 1):  # noqa: B020 (ST semantics)
                j = self.j
                if not 1 <= j + 1 <= 100:
                    raise IndexError
                if a[j - 1] > a[j]:
                    self.tmp = a[j - 1]
                    a[j - 1] = a[j]
                    a[j] = self.tmp
            self.j = 100 - self.i + 1
        self.i = 100


# ---------------------------------------------------------------------------------------------
STRINGS = """
PROGRAM Main
VAR msg : STRING; name : STRING[20] := 'pump'; n : INT; pos : INT; part : STRING; len_ : INT;
END_VAR
n := n + 1;
msg := CONCAT('Station ', name);
msg := CONCAT(msg, ': running');
pos := FIND(msg, ':');
part := LEFT(msg, pos - 1);
len_ := LEN(part);
msg := REPLACE(msg, 'stopped', 7, pos + 2);
part := MID(msg, 4, 1);
msg := INSERT(msg, '!', LEN(msg));
msg := DELETE(msg, 1, 1);
END_PROGRAM
"""


class Strings:
    def __init__(self, clock):
        self.msg = ""
        self.name = "pump"
        self.n = self.pos = self.len_ = 0
        self.part = ""

    def body(self):
        self.n = w16(self.n + 1)
        self.msg = ("Station " + self.name)[:80]
        self.msg = (self.msg + ": running")[:80]
        f = self.msg.find(":")
        self.pos = f + 1
        self.part = self.msg[:max(self.pos - 1, 0)]
        self.len_ = len(self.part)
        p = self.pos + 2
        self.msg = (self.msg[:p - 1] + "stopped" + self.msg[p - 1 + 7:])[:80]
        self.part = self.msg[0:4]
        m = self.msg
        k = len(m)
        self.msg = (m[:k] + "!" + m[k:])[:80]
        self.msg = self.msg[1:]


PROGRAMS = [
    ("FOR loop sum 1..100", FOR_SUM, ForSum),
    ("CASE state machine", CASE_SM, CaseSm),
    ("100 TON instances", TONS, Tons),
    ("PID-style REAL math", PID, Pid),
    ("bubble sort 100", BUBBLE, Bubble),
    ("string handling", STRINGS, Strings),
]


# =============================================================================================
# Tuned Python: what a careful Python programmer writes for the same work and the same final
# state (issue 19). Locals instead of attribute loads in loops, wraps and MOD written inline,
# constants hoisted, REAL rounded through a one-element float32 array (no function call).
# =============================================================================================
from array import array  # noqa: E402

_A32 = array("f", [0.0])


class TunedForSum(ForSum):
    def body(self):
        s = 0
        for i in range(1, 101):
            s = ((s + i + 2147483648) & 0xFFFFFFFF) - 2147483648
        self.s = s
        self.i = 101


class TunedCaseSm(CaseSm):
    def body(self, a=_A32):
        ticks = ((self.ticks + 32769) & 0xFFFF) - 32768
        st = self.state
        if st == 0:
            self.pump = False
            self.valve = False
            if ticks > 3:
                self.state = 1
                ticks = 0
        elif st == 1:
            self.pump = True
            a[0] = self.level + 0.5
            self.level = level = a[0]
            if level >= 10.0:
                self.state = 2
        elif st == 2:
            self.pump = False
            self.valve = True
            a[0] = self.level - 1.0
            self.level = level = a[0]
            if level <= 0.0:
                self.state = 3
                self.level = 0.0
        elif st == 3:
            c = self.count = ((self.count + 2147483649) & 0xFFFFFFFF) - 2147483648
            self.alarm = (c % 10 if c >= 0 else -(-c % 10)) == 0
            self.state = 0
            ticks = 0
        else:
            self.state = 0
        self.ticks = ticks


class TunedTons(Tons):
    def body(self):
        done = 0
        run = self.run
        for t in self.t:
            t.IN = run
            t.PT = 500
            t()
            if t.Q:
                done = ((done + 32769) & 0xFFFF) - 32768
        self.done = done
        self.i = 101


class TunedPid(Pid):
    def body(self, a=_A32):
        sp, pv, e_prev, integ = self.sp, self.pv, self.e_prev, self.integ
        kp, ki, kd, dt = self.kp, self.ki, self.kd, self.dt
        c05, c01 = f32(0.05), f32(0.01)
        e = deriv = u = 0.0
        for _ in range(1, 11):
            a[0] = sp - pv
            e = a[0]
            x = integ + e * dt
            a[0] = -100.0 if x < -100.0 else 100.0 if x > 100.0 else x
            integ = a[0]
            if dt == 0:
                raise ZeroDivisionError
            a[0] = (e - e_prev) / dt
            deriv = a[0]
            x = kp * e + ki * integ + kd * deriv
            a[0] = 0.0 if x < 0.0 else 100.0 if x > 100.0 else x
            u = a[0]
            e_prev = e
            a[0] = pv + (u * c05 - (pv - 20.0) * c01) * dt
            pv = a[0]
        self.pv, self.e_prev, self.integ = pv, e_prev, integ
        self.e, self.deriv, self.u = e, deriv, u
        self.n = 11


class TunedBubble(Bubble):
    def body(self):
        a = self.a
        seed = self.seed
        for i in range(100):
            x = seed * 1103515245 + 12345
            x = x % 2147483647 if x >= 0 else -(-x % 2147483647)
            seed = ((x + 2147483648) & 0xFFFFFFFF) - 2147483648
            a[i] = ((((seed % 1000 if seed >= 0 else -(-seed % 1000))) + 32768) & 0xFFFF) - 32768
        self.seed = seed
        tmp = self.tmp
        for i in range(1, 100):
            for j in range(100 - i):
                x, y = a[j], a[j + 1]
                if x > y:
                    tmp = x
                    a[j] = y
                    a[j + 1] = tmp
            self.j = 100 - i + 1
        self.tmp = tmp
        self.i = 100


class TunedStrings(Strings):
    def body(self):
        self.n = ((self.n + 32769) & 0xFFFF) - 32768
        msg = ("Station " + self.name)[:80]
        msg = (msg + ": running")[:80]
        pos = msg.find(":") + 1
        part = msg[:max(pos - 1, 0)]
        self.len_ = len(part)
        p = pos + 2
        msg = (msg[:p - 1] + "stopped" + msg[p + 6:])[:80]
        self.part = msg[0:4]
        self.msg = (msg + "!")[:80][1:]
        self.pos = pos


TUNED = {ForSum: TunedForSum, CaseSm: TunedCaseSm, Tons: TunedTons, Pid: TunedPid,
         Bubble: TunedBubble, Strings: TunedStrings}
