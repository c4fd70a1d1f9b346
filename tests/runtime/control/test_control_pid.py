"""PID and PID_INC (plclab/runtime/ctrlfb.py) against python-control, simple-pid, the
textbook's positional formula, and each other.

Source: 001_c648febd3bbd6efb.txt lines 7527-7628 (discrete PID: positional
u(n) = kP e(n) + kI T sum(e(m), m < n) + kD (e(n) - e(n-1)) / T and incremental
u(n) = u(n-1) + q0 e(n) + q1 e(n-1) + q2 e(n-2)).

Parameter mapping used throughout (CODESYS <-> parallel form, simple-pid, PID_INC):
Ki = KP / TN, Kd = KP * TV.
"""

import math
import random

import control
import numpy as np
import pytest
from simple_pid import PID as SimplePID

import plclab
from plclab.runtime.ctrlfb import PID, PID_INC

T = 0.1  # s, sampling interval of every closed loop here
T_MS = 100


class Ctx:
    """What a native block sees of the PLC: the scan time (ms) and the task cycle (ms)."""

    def __init__(self, cycle_ms: float = T_MS) -> None:
        self.now = 0
        self.cycle_ms = cycle_ms


class Fopdt:
    """First order plus dead time, exact ZOH discretisation: K / (tau s + 1) e^(-L s)."""

    def __init__(self, k: float, tau: float, dead: int, dt: float = T) -> None:
        self.k, self.tau, self.dead, self.dt = k, tau, dead, dt
        self.a = math.exp(-dt / tau)
        self.b = k * (1.0 - self.a)
        self.y = 0.0
        self.pipe = [0.0] * dead

    def step(self, u: float) -> float:
        """Apply u over one interval; return the output at the end of it."""
        self.pipe.append(u)
        self.y = self.a * self.y + self.b * self.pipe.pop(0)
        return self.y

    def control_ss(self):
        g = control.sample_system(control.tf([self.k], [self.tau, 1.0]), self.dt, method="zoh")
        delay = control.tf([1.0], [1.0] + [0.0] * self.dead, self.dt)
        return control.tf2ss(g * delay)


def run_block_loop(block, ctx, plant, r, w, saturate=None):
    """Drive a controller block in closed loop; return (y, u) sequences (y read before u)."""
    n = len(r)
    ys, us = np.zeros(n), np.zeros(n)
    y = plant.y
    for k in range(n):
        ctx.now = k * T_MS
        block.ACTUAL = y
        block.SETPOINT = r[k]
        block._body()
        u = block.Y
        ys[k], us[k] = y, u
        ua = u if saturate is None else min(max(u, saturate[0]), saturate[1])
        y = plant.step(ua + w[k])
    return ys, us


def named(sys, inp, out):
    sys.update_names(inputs=inp, outputs=out)
    return sys


def python_control_loop(kp, tn, tv, tm, plant, r, w):
    """The same discrete controller built from python-control transfer functions:
    u = (KP + KP/TN * T/(z-1)) e - D(z) y, D = backward_diff(KP TV s / (1 + TM s))."""
    dt = T
    ce = control.tf([kp], [1.0], dt) + control.sample_system(
        control.tf([kp / tn], [1.0, 0.0]), dt, method="euler")
    if tm > 0:
        cd = control.sample_system(control.tf([kp * tv, 0.0], [tm, 1.0]), dt,
                                   method="backward_diff")
    else:
        cd = control.tf([kp * tv / dt, -kp * tv / dt], [1.0, 0.0], dt)
    blocks = [
        control.summing_junction(inputs=["r", "-y"], output="e", dt=dt),
        named(control.tf2ss(ce), "e", "ue"),
        named(control.tf2ss(cd), "y", "ud"),
        control.summing_junction(inputs=["ue", "-ud"], output="u", dt=dt),
        control.summing_junction(inputs=["u", "w"], output="up", dt=dt),
        named(plant.control_ss(), "up", "y"),
    ]
    cl = control.interconnect(blocks, inplist=["r", "w"], outlist=["y", "u"])
    t = np.arange(len(r)) * dt
    resp = control.forced_response(cl, T=t, U=np.vstack([r, w]))
    return resp.outputs[0], resp.outputs[1]


def unlimited_pid(kp, tn, tv, tm_ms=0):
    ctx = Ctx()
    pid = PID(ctx, double=True)
    pid.KP, pid.TN, pid.TV, pid.TM_LAG = kp, tn, tv, tm_ms
    pid.Y_MIN = pid.Y_MAX = 0.0  # Y_MAX <= Y_MIN: no limits (CODESYS)
    return ctx, pid


def setpoint_and_disturbance(n=600, sp=50.0, step_at=0, w_at=300, w=-10.0):
    r = np.where(np.arange(n) >= step_at, sp, 0.0)
    d = np.where(np.arange(n) >= w_at, w, 0.0)
    return r, d


# ------------------------------------------------------------------- python-control


@pytest.mark.parametrize("tm_ms", [0, 300])
def test_closed_loop_matches_python_control_to_1e9(tm_ms):
    kp, tn, tv = 1.2, 4.0, 0.8
    r, w = setpoint_and_disturbance(step_at=5)
    ctx, pid = unlimited_pid(kp, tn, tv, tm_ms)
    y_blk, u_blk = run_block_loop(pid, ctx, Fopdt(2.0, 5.0, 10), r, w)
    y_pc, u_pc = python_control_loop(kp, tn, tv, tm_ms / 1000.0, Fopdt(2.0, 5.0, 10), r, w)
    assert not pid.LIMITS_ACTIVE
    assert np.max(np.abs(u_blk - u_pc)) < 1e-9
    assert np.max(np.abs(y_blk - y_pc)) < 1e-9
    # a real step response: it rises, settles at the setpoint, rejects the disturbance
    assert abs(y_blk[295] - 50.0) < 0.5 and abs(y_blk[-1] - 50.0) < 0.5
    assert np.max(y_blk) > 45.0


def test_setpoint_step_gives_no_derivative_kick():
    ctx, pid = unlimited_pid(1.0, 0.0, 2.0)
    pid.ACTUAL = 0.0
    pid.SETPOINT = 0.0
    pid._body()
    ctx.now += T_MS
    pid.SETPOINT = 10.0
    pid._body()
    assert pid.Y == 10.0  # P only: D acts on the measurement, which did not move
    ctx.now += T_MS
    pid.ACTUAL = 1.0
    pid._body()  # D = -KP*TV*(1 - 0)/T = -20
    assert pid.Y == pytest.approx(9.0 - 20.0, abs=1e-12)


# ------------------------------------------------------------------------ simple-pid


def test_simple_pid_differs_by_exactly_ki_t_e_open_loop():
    """simple-pid integrates backward (its sum includes e(n)); PID forward, like the book.
    Fed the same measurements, u_simple(n) - u_PID(n) = Ki * T * e(n), to 1e-9."""
    kp, tn, tv = 1.5, 3.0, 0.4
    ki, kd = kp / tn, kp * tv
    rng = random.Random(7)
    xs = [0.0]
    for _ in range(400):
        xs.append(xs[-1] + rng.gauss(0.2, 1.0))
    sp = 30.0
    ref = SimplePID(kp, ki, kd, setpoint=sp, sample_time=None, output_limits=(None, None))
    ctx, pid = unlimited_pid(kp, tn, tv)
    for k, x in enumerate(xs):
        ctx.now = k * T_MS
        pid.ACTUAL, pid.SETPOINT = x, sp
        pid._body()
        u_ref = ref(x, dt=T)
        assert u_ref - pid.Y == pytest.approx(ki * T * (sp - x), abs=1e-9)


def test_simple_pid_closed_loop_is_close():
    kp, tn, tv = 1.2, 4.0, 0.8
    r, w = setpoint_and_disturbance()
    ctx, pid = unlimited_pid(kp, tn, tv)
    y_blk, _ = run_block_loop(pid, ctx, Fopdt(2.0, 5.0, 10), r, w)

    class Wrap:
        def __init__(self):
            self.ref = SimplePID(kp, kp / tn, kp * tv, sample_time=None,
                                 output_limits=(None, None))
            self.ACTUAL = self.SETPOINT = self.Y = 0.0

        def _body(self):
            self.ref.setpoint = self.SETPOINT
            self.Y = self.ref(self.ACTUAL, dt=T)

    y_sp, _ = run_block_loop(Wrap(), Ctx(), Fopdt(2.0, 5.0, 10), r, w)
    diff = np.max(np.abs(y_blk - y_sp))
    print(f"max |y_PID - y_simple_pid| = {diff:.4f} (setpoint 50)")
    assert diff < 0.02 * 50.0
    assert abs(y_sp[-1] - y_blk[-1]) < 0.1


# ------------------------------------------------------------------ PID_INC, the book


def book_positional(kp, ki, kd, es, dt=T):
    """001 L7560-7600 written out with its sum, e(-1) = e(0) (no kick at start)."""
    out = []
    for n, e in enumerate(es):
        prev = es[n - 1] if n else e
        out.append(kp * e + ki * dt * sum(es[:n]) + kd * (e - prev) / dt)
    return out


def test_pid_inc_is_the_book_positional_formula():
    kp, ki, kd = 0.8, 0.3, 0.05
    rng = random.Random(3)
    sps = [rng.uniform(-5, 5) for _ in range(200)]
    xs = [rng.uniform(-5, 5) for _ in range(200)]
    ctx = Ctx()
    inc = PID_INC(ctx, double=True)
    inc.KP, inc.KI, inc.KD = kp, ki, kd
    inc.Y_MIN = inc.Y_MAX = 0.0
    got = []
    for k, (sp, x) in enumerate(zip(sps, xs, strict=True)):
        ctx.now = k * T_MS
        inc.SETPOINT, inc.ACTUAL = sp, x
        inc._body()
        got.append(inc.Y)
    want = book_positional(kp, ki, kd, [s - x for s, x in zip(sps, xs, strict=True)])
    assert np.max(np.abs(np.array(got) - np.array(want))) < 1e-9


def test_positional_and_incremental_give_the_same_output_in_the_linear_region():
    kp, tn, tv = 1.2, 4.0, 0.8
    r, w = setpoint_and_disturbance(step_at=0)  # constant setpoint from the first call
    ctx, pid = unlimited_pid(kp, tn, tv)
    y_pos, u_pos = run_block_loop(pid, ctx, Fopdt(2.0, 5.0, 10), r, w)
    ctx2 = Ctx()
    inc = PID_INC(ctx2, double=True)
    inc.KP, inc.KI, inc.KD = kp, kp / tn, kp * tv
    inc.Y_MIN = inc.Y_MAX = 0.0
    y_inc, u_inc = run_block_loop(inc, ctx2, Fopdt(2.0, 5.0, 10), r, w)
    assert np.max(np.abs(u_pos - u_inc)) < 1e-9
    assert np.max(np.abs(y_pos - y_inc)) < 1e-9


def test_pid_inc_clamps_and_leaves_the_limit_at_once():
    ctx = Ctx()
    inc = PID_INC(ctx, double=True)
    inc.KP, inc.KI = 2.0, 1.0
    inc.SETPOINT, inc.ACTUAL = 100.0, 0.0
    for k in range(50):
        ctx.now = k * T_MS
        inc._body()
    assert inc.Y == 100.0
    ctx.now += T_MS
    inc.ACTUAL = 101.0  # error turns negative: the output drops at once, no wind-up to undo
    inc._body()
    assert inc.Y < 100.0


# -------------------------------------------------------------------------- anti-windup


def overshoot(y, sp):
    return float(np.max(y) - sp)


def test_anti_windup_keeps_the_overshoot_below_the_unprotected_form():
    """Actuator 0..100 %, setpoint 0 -> 60: the output saturates for a long time.
    Unprotected: the same controller without limits, saturated only by the actuator."""
    kp, tn = 4.0, 8.0
    n = 1200
    r = np.full(n, 60.0)
    w = np.zeros(n)
    ctx = Ctx()
    pid = PID(ctx, double=True)
    pid.KP, pid.TN, pid.Y_MIN, pid.Y_MAX = kp, tn, 0.0, 100.0
    y_aw, u_aw = run_block_loop(pid, ctx, Fopdt(1.0, 20.0, 20), r, w)
    ctx2, raw = unlimited_pid(kp, tn, 0.0)
    y_raw, u_raw = run_block_loop(raw, ctx2, Fopdt(1.0, 20.0, 20), r, w, saturate=(0.0, 100.0))
    os_aw, os_raw = overshoot(y_aw, 60.0), overshoot(y_raw, 60.0)
    print(f"overshoot with anti-windup {os_aw:.2f}, without {os_raw:.2f} (setpoint 60)")
    assert np.max(u_aw) == 100.0 and np.min(u_aw) >= 0.0  # it did saturate, Y stayed in range
    assert np.max(u_raw) > 150.0  # the unprotected integral wound up far beyond the actuator
    assert os_aw < 0.5 * os_raw
    assert abs(y_aw[-1] - 60.0) < 0.5


def test_limits_active_and_integral_stop():
    ctx = Ctx()
    pid = PID(ctx, double=True)
    pid.KP, pid.TN, pid.Y_MIN, pid.Y_MAX = 1.0, 1.0, 0.0, 10.0
    pid.SETPOINT, pid.ACTUAL = 50.0, 0.0
    for k in range(100):
        ctx.now = k * T_MS
        pid._body()
        assert pid.Y == 10.0 and pid.LIMITS_ACTIVE
    assert pid._i == 0.0  # P alone saturates: the integral never started
    ctx.now += T_MS
    pid.ACTUAL = 49.0  # e = 1: u = 1 + 0.1 * 50 (the last error's integral) is in range
    pid._body()
    assert not pid.LIMITS_ACTIVE and pid.Y == pytest.approx(6.0)


# ------------------------------------------------------------------ modes and options


def test_bumpless_manual_to_auto():
    ctx = Ctx()
    pid = PID(ctx, double=True)
    pid.KP, pid.TN, pid.TV = 2.0, 5.0, 1.0
    pid.SETPOINT, pid.ACTUAL = 40.0, 35.0
    pid.MANUAL, pid.Y_MANUAL = True, 63.0
    for k in range(20):
        ctx.now = k * T_MS
        pid._body()
        assert pid.Y == 63.0
    pid.MANUAL = False
    ctx.now += T_MS
    pid._body()
    # the first automatic output continues from Y_MANUAL: only one sample of integration
    assert pid.Y == pytest.approx(63.0 + 2.0 / 5.0 * T * 5.0)


def test_reset_and_reverse_and_deadband():
    ctx = Ctx()
    pid = PID(ctx, double=True)
    pid.KP, pid.TN, pid.Y_OFFSET = 1.0, 1.0, 20.0
    pid.SETPOINT, pid.ACTUAL = 10.0, 5.0
    for k in range(10):
        ctx.now = k * T_MS
        pid._body()
    assert pid.Y > 25.0
    pid.RESET = True
    ctx.now += T_MS
    pid._body()
    assert pid.Y == 20.0 and pid._i == 0.0
    pid.RESET = False
    pid.REVERSE = True  # cooling: e = ACTUAL - SETPOINT = -5
    ctx.now += T_MS
    pid._body()
    assert pid.Y == 15.0
    pid.REVERSE = False
    pid.RESET = True
    pid._body()
    pid.RESET = False
    pid.DEADBAND = 2.0  # e = 5 -> 3 (continuous deadband)
    pid._body()
    assert pid.Y == 23.0
    pid.ACTUAL = 9.0  # |e| = 1 <= 2: no action
    pid._body()
    assert pid.Y == pytest.approx(20.0 + 3.0 * T)  # only the integral of the last error


def test_cycle_input_overrides_the_measured_time():
    ctx = Ctx()
    pid = PID(ctx, double=True)
    pid.KP, pid.TN, pid.CYCLE = 1.0, 1.0, 500  # PID_FIXCYCLE-like: 0.5 s per call
    pid.SETPOINT = 1.0
    pid._body()
    pid._body()  # same scan, time frozen: CYCLE still counts
    assert pid.Y == pytest.approx(1.0 + 0.5)
    pid.CYCLE = 0
    pid._body()  # no time has passed: falls back to the task cycle (100 ms here)
    assert pid.Y == pytest.approx(1.5 + 0.1)


def test_nan_and_infinity_hold_the_output():
    ctx = Ctx()
    pid = PID(ctx)
    pid.KP, pid.TN, pid.TV = 1.0, 2.0, 1.0
    pid.SETPOINT, pid.ACTUAL = 10.0, 5.0
    pid._body()
    y = pid.Y
    for bad in (math.nan, math.inf, -math.inf):
        ctx.now += T_MS
        pid.ACTUAL = bad
        pid._body()
        assert pid.Y == y
    ctx.now += T_MS
    pid.ACTUAL = 5.0
    pid._body()
    assert math.isfinite(pid.Y) and abs(pid.Y - y) < 1.0


# ---------------------------------------------------------------- through an ST program

ST_LOOP = """
PROGRAM Main
VAR_INPUT pv : REAL; sp : REAL; END_VAR
VAR pid : PID; u : REAL; END_VAR
pid(ACTUAL := pv, SETPOINT := sp, KP := 1.2, TN := 4.0, TV := 0.8, TM_LAG := T#300ms,
    Y_MIN := -1000.0, Y_MAX := 1000.0);
u := pid.Y;
END_PROGRAM
"""


def test_pid_in_an_st_program_follows_the_double_precision_block():
    plc = plclab.loads(ST_LOOP, cycle_time="100ms")
    r, w = setpoint_and_disturbance(n=400, step_at=5, w_at=200)
    plant = Fopdt(2.0, 5.0, 10)
    ys = []
    y = 0.0
    for k in range(len(r)):
        plc["Main.pv"] = y
        plc["Main.sp"] = float(r[k])
        plc.scan()
        ys.append(y)
        y = plant.step(plc["Main.u"] + w[k])
    ctx, pid = unlimited_pid(1.2, 4.0, 0.8, 300)
    y_ref, _ = run_block_loop(pid, ctx, Fopdt(2.0, 5.0, 10), r, w)
    assert np.max(np.abs(np.array(ys) - y_ref)) < 1e-3  # single-precision REALs vs double
    assert isinstance(plc["Main.pid.Y"], float)
    assert plc["Main.u"] == np.float32(plc["Main.u"])  # the block rounds its REAL output
