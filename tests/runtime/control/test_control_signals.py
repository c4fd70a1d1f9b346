"""Signal helpers: BLINKER, DEBOUNCE, RAMP, PT1, MOVING_AVG, LIMIT_ALARM, DEADBAND.

Sources (001_c648febd3bbd6efb.txt): the ventilation example's fault lamp flashing at 5 Hz
(7697-7752), contact bounce (921-973), WinCC analog alarms with a deadband (6085-6130).
"""

import math

import pytest

import plclab
from plclab.runtime.ctrlfb import LIMIT_ALARM, MOVING_AVG, PT1, RAMP
from plclab.testing import run_test_sources


class Ctx:
    def __init__(self, cycle_ms=10.0):
        self.now = 0
        self.cycle_ms = cycle_ms


def run_st(src):
    results = run_test_sources([(src, "signals.st")])
    assert results
    assert all(r.passed for r in results), [str(r) for r in results]


# ------------------------------------------------------------------------------ BLINKER

FAN_LAMP = """
PROGRAM Main
VAR_INPUT fault1 : BOOL; fault2 : BOOL; fault3 : BOOL; END_VAR
VAR flash : BLINKER; FIND : BOOL; END_VAR
(* two of three fans faulty: the fault lamp flashes at 5 Hz (001 L7740-7752) *)
flash(ENABLE := (fault1 AND fault2) OR (fault1 AND fault3) OR (fault2 AND fault3),
      T_ON := T#100ms, T_OFF := T#100ms);
FIND := flash.Q;
END_PROGRAM
"""


def test_blinker_5_hz_is_exact_at_10_ms_scans():
    plc = plclab.loads(FAN_LAMP, cycle_time="10ms")
    plc.run(seconds=0.5)
    assert plc["Main.FIND"] is False
    plc["Main.fault1"] = True
    plc["Main.fault3"] = True
    lamp = []
    for _ in range(1000):  # 10 s
        plc.scan()
        lamp.append(plc["Main.FIND"])
    assert lamp[:20] == [True] * 10 + [False] * 10
    assert lamp == (lamp[:20] * 50)  # exactly periodic: 200 ms, no drift
    rising = sum(1 for a, b in zip([False] + lamp, lamp, strict=False) if b and not a)
    assert rising == 50  # 5 Hz for 10 s
    plc["Main.fault1"] = False
    plc.scan()
    assert plc["Main.FIND"] is False


def test_blinker_asymmetric_and_degenerate_from_st():
    run_st("""
    TEST 'BLINKER: 300 ms on, 700 ms off, restarts with TRUE when ENABLE rises'
    VAR b : BLINKER; END_VAR
    b(ENABLE := TRUE, T_ON := T#300ms, T_OFF := T#700ms);
    ASSERT_TRUE(b.Q);
    ADVANCE_TIME(T#299ms); b(ENABLE := TRUE); ASSERT_TRUE(b.Q);
    ADVANCE_TIME(T#1ms);   b(ENABLE := TRUE); ASSERT_FALSE(b.Q);
    ADVANCE_TIME(T#700ms); b(ENABLE := TRUE); ASSERT_TRUE(b.Q);
    ADVANCE_TIME(T#500ms); b(ENABLE := TRUE); ASSERT_FALSE(b.Q);
    b(ENABLE := FALSE); ASSERT_FALSE(b.Q);
    b(ENABLE := TRUE); ASSERT_TRUE(b.Q);
    b(ENABLE := TRUE, T_OFF := T#0ms); ASSERT_TRUE(b.Q);
    b(ENABLE := TRUE, T_ON := T#0ms, T_OFF := T#0ms); ASSERT_FALSE(b.Q);
    END_TEST
    """)


# ----------------------------------------------------------------------------- DEBOUNCE


def test_debounce_from_st():
    run_st("""
    TEST 'DEBOUNCE: bounces shorter than T_DEBOUNCE are ignored on both edges'
    VAR d : DEBOUNCE; END_VAR
    d(IN := TRUE, T_DEBOUNCE := T#20ms);
    ASSERT_FALSE(d.Q);
    ADVANCE_TIME(T#5ms);  d(IN := FALSE); ASSERT_FALSE(d.Q);   (* bounce *)
    ADVANCE_TIME(T#5ms);  d(IN := TRUE);  ASSERT_FALSE(d.Q);   (* time restarts here *)
    ADVANCE_TIME(T#19ms); d(IN := TRUE);  ASSERT_FALSE(d.Q);
    ADVANCE_TIME(T#1ms);  d(IN := TRUE);  ASSERT_TRUE(d.Q);    (* stable for 20 ms *)
    ADVANCE_TIME(T#3ms);  d(IN := FALSE); ASSERT_TRUE(d.Q);    (* release bounces too *)
    ADVANCE_TIME(T#3ms);  d(IN := TRUE);  ASSERT_TRUE(d.Q);
    ADVANCE_TIME(T#3ms);  d(IN := FALSE); ASSERT_TRUE(d.Q);
    ADVANCE_TIME(T#20ms); d(IN := FALSE); ASSERT_FALSE(d.Q);
    END_TEST

    TEST 'DEBOUNCE: T_DEBOUNCE = 0 passes IN straight through'
    VAR d : DEBOUNCE; END_VAR
    d(IN := TRUE, T_DEBOUNCE := T#0ms); ASSERT_TRUE(d.Q);
    d(IN := FALSE); ASSERT_FALSE(d.Q);
    END_TEST
    """)


def test_debounce_cleans_a_bouncing_contact():
    from plclab.io import DigitalInput

    plc = plclab.loads("""
    PROGRAM Main
    VAR_INPUT raw : BOOL; END_VAR
    VAR d : DEBOUNCE; clean : BOOL; END_VAR
    d(IN := raw, T_DEBOUNCE := T#10ms);
    clean := d.Q;
    END_PROGRAM""", cycle_time="1ms")
    di = DigitalInput(filter_ms=0.0, bounce_ms=5.0, seed=3)  # no input filter, 5 ms bounce
    raw, clean = [], []
    for k in range(400):
        t = k * 0.001
        contact = 0.1 <= t < 0.25  # pressed for 150 ms
        plc["Main.raw"] = di.sample(t, contact)
        plc.scan()
        raw.append(plc["Main.raw"])
        clean.append(plc["Main.clean"])

    def edges(s):
        return sum(1 for a, b in zip(s, s[1:], strict=False) if a != b)

    assert edges(raw) > 2  # the contact bounced
    assert edges(clean) == 2  # one press, one release


# -------------------------------------------------------------------------------- RAMP


def test_ramp_rate_limits_in_both_directions():
    ctx = Ctx(10.0)
    r = RAMP(ctx, double=True)
    r.RATE = 2.0
    r.IN = 10.0
    outs = []
    for k in range(600):
        ctx.now = k * 10
        r._body()
        outs.append(r.OUT)
    assert outs[0] == pytest.approx(0.02)  # first call: one task cycle of 10 ms
    assert outs[99] == pytest.approx(2.0)
    assert outs[498] < 10.0 and outs[499] == 10.0  # 10 units at 2 /s: 5 s = 500 scans
    assert not r.BUSY
    r.IN = 9.0
    ctx.now += 10
    r._body()
    assert r.OUT == pytest.approx(9.98) and r.BUSY
    r.RESET = True
    r._body()
    assert r.OUT == 9.0
    r.RESET = False
    r.RATE = 0.0  # limiter off
    r.IN = -3.0
    r._body()
    assert r.OUT == -3.0


def test_ramp_from_st_with_advance_time():
    run_st("""
    TEST 'RAMP: a setpoint ramp of 5 units per second'
    VAR rp : RAMP; END_VAR
    rp(IN := 0.0, RATE := 5.0, RESET := TRUE);
    rp(IN := 20.0, RESET := FALSE);          (* same scan: one task cycle, 10 ms *)
    ASSERT_NEAR(rp.OUT, 0.05, 1.0E-5);
    ADVANCE_TIME(T#1s); rp(IN := 20.0);
    ASSERT_NEAR(rp.OUT, 5.05, 1.0E-4);
    ADVANCE_TIME(T#3s); rp(IN := 20.0);
    ASSERT_NEAR(rp.OUT, 20.0, 1.0E-4);
    ASSERT_FALSE(rp.BUSY);
    END_TEST
    """)


# --------------------------------------------------------------------------------- PT1


@pytest.mark.parametrize("cycle_ms", [1, 10, 100])
def test_pt1_step_response_matches_1_minus_exp_within_one_sample(cycle_ms):
    tau, k = 2.0, 3.0
    ctx = Ctx(cycle_ms)
    f = PT1(ctx, double=True)
    f.T, f.K, f.IN = round(tau * 1000), k, 1.0
    dt = cycle_ms / 1000.0
    worst = 0.0
    for n in range(round(10.0 / dt)):
        ctx.now = n * cycle_ms
        f._body()
        t = n * dt
        lo, hi = k * (1 - math.exp(-t / tau)), k * (1 - math.exp(-(t + dt) / tau))
        assert lo - 1e-12 <= f.OUT <= hi + 1e-12  # between the analytic value now and 1 T later
        assert f.OUT == pytest.approx(hi, abs=1e-9)  # exactly the response one sample later
        worst = max(worst, abs(f.OUT - lo))
    assert worst <= k * dt / tau  # the discretisation error bound
    assert f.OUT == pytest.approx(k * (1 - math.exp(-5)), abs=k * dt / tau)


def test_pt1_in_st_and_edge_cases():
    run_st("""
    TEST 'PT1: T = 0 passes K * IN; a NaN-free start at 0'
    VAR f : PT1; END_VAR
    f(IN := 2.0, T := T#0ms, K := 1.5);
    ASSERT_NEAR(f.OUT, 3.0, 1.0E-6);
    END_TEST

    TEST 'PT1: one time constant gives 63 %'
    VAR f : PT1; i : INT; END_VAR
    FOR i := 1 TO 100 DO
        ADVANCE_TIME(T#10ms);
        f(IN := 1.0, T := T#1s);
    END_FOR
    ASSERT_NEAR(f.OUT, 0.632, 0.01);
    END_TEST
    """)
    ctx = Ctx()
    f = PT1(ctx)
    f.IN = math.nan
    f._body()
    assert f.OUT == 0.0  # NaN holds the output


# -------------------------------------------------------------------------- MOVING_AVG


def test_moving_average():
    ctx = Ctx()
    m = MOVING_AVG(ctx, double=True)
    m.N = 4
    got = []
    for x in (4.0, 8.0, 0.0, 4.0, 12.0, math.nan, 8.0):
        m.IN = x
        m._body()
        got.append(m.AVG)
    assert got == [4.0, 6.0, 4.0, 4.0, 6.0, 6.0, 6.0]  # NaN is skipped
    m.N = 1
    m._body()
    assert m.AVG == 8.0
    m.N = 1000  # clamped to 64 (all samples so far)
    m._body()
    assert m.AVG == pytest.approx((4 + 8 + 0 + 4 + 12 + 8 + 8 + 8) / 8)
    for _ in range(100):
        m.IN = 1.0
        m._body()
    assert m.AVG == 1.0
    m.RESET = True
    m._body()
    assert m.AVG == 0.0
    copy = m._copy()
    copy._buf[0] = 99.0
    assert m._buf[0] != 99.0


def test_moving_average_from_st():
    run_st("""
    TEST 'MOVING_AVG over 3 samples'
    VAR m : MOVING_AVG; END_VAR
    m(IN := 3.0, N := 3); m(IN := 6.0); m(IN := 9.0); m(IN := 12.0);
    ASSERT_NEAR(m.AVG, 9.0, 1.0E-6);
    END_TEST
    """)


# ------------------------------------------------------------------------- LIMIT_ALARM


def test_limit_alarm_deadband_stops_alarm_chatter():
    la = LIMIT_ALARM(Ctx())
    la.H, la.DEADBAND = 90.0, 2.0
    seq = [(89.0, False), (90.0, False), (90.1, True), (89.0, True), (88.0, True),
           (87.9, False), (89.9, False), (90.5, True)]
    for x, q in seq:
        la.IN = x
        la._body()
        assert la.QH is q, x
        assert not (la.QHH or la.QL or la.QLL)  # unused limits never trigger
    # a noisy value around the limit: many alarms without deadband, one with
    import random

    rng = random.Random(1)
    noisy = [90.0 + rng.gauss(0, 0.3) for _ in range(500)]
    counts = {}
    for db in (0.0, 2.0):
        la = LIMIT_ALARM(Ctx())
        la.H, la.DEADBAND = 90.0, db
        n, prev = 0, False
        for x in noisy:
            la.IN = x
            la._body()
            n += la.QH and not prev
            prev = la.QH
        counts[db] = n
    assert counts[0.0] > 50 and counts[2.0] == 1


def test_limit_alarm_four_limits_and_percent_from_st():
    run_st("""
    TEST 'LIMIT_ALARM: HH / H / L / LL with a 5 % deadband of each limit (WinCC)'
    VAR la : LIMIT_ALARM; END_VAR
    la(IN := 50.0, HH := 100.0, H := 80.0, L := 20.0, LL := 10.0, DEADBAND := 5.0, PERCENT := TRUE);
    ASSERT_FALSE(la.QHH OR la.QH OR la.QL OR la.QLL);
    la(IN := 101.0); ASSERT_TRUE(la.QHH AND la.QH);
    la(IN := 96.0);  ASSERT_TRUE(la.QHH);              (* goes below 100 - 5 = 95 *)
    la(IN := 94.0);  ASSERT_FALSE(la.QHH); ASSERT_TRUE(la.QH);
    la(IN := 76.5);  ASSERT_TRUE(la.QH);               (* 80 - 4 = 76 *)
    la(IN := 75.9);  ASSERT_FALSE(la.QH);
    la(IN := 9.0);   ASSERT_TRUE(la.QL AND la.QLL);
    la(IN := 10.4);  ASSERT_TRUE(la.QLL);              (* 10 + 0.5 *)
    la(IN := 10.6);  ASSERT_FALSE(la.QLL); ASSERT_TRUE(la.QL);
    la(IN := 21.1);  ASSERT_FALSE(la.QL);              (* 20 + 1 *)
    END_TEST
    """)


# ---------------------------------------------------------------------------- DEADBAND


def test_deadband_from_st():
    run_st("""
    TEST 'DEADBAND: zero inside +-WIDTH, continuous outside'
    VAR d : DEADBAND; END_VAR
    d(IN := 0.4, WIDTH := 0.5);  ASSERT_EQ(d.OUT, 0.0);
    d(IN := -0.5);               ASSERT_EQ(d.OUT, 0.0);
    d(IN := 2.0);                ASSERT_NEAR(d.OUT, 1.5, 1.0E-6);
    d(IN := -2.0);               ASSERT_NEAR(d.OUT, -1.5, 1.0E-6);
    d(IN := -2.0, WIDTH := -1.0); ASSERT_NEAR(d.OUT, -1.0, 1.0E-6);
    END_TEST
    """)
