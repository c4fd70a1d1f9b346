"""HYST, the two-position regulator (001_c648febd3bbd6efb.txt lines 7360-7455).

The book's thermostat: ``if (temp < 50.0) relay on else off`` chatters on a noisy signal
(Fig. 110); with a hysteresis window of +-2 (``temp < setpoint - hyster`` on,
``temp > setpoint + hyster`` off) the relay holds its state inside the window (Fig. 111).
"""

import random

import plclab
from plclab.runtime.ctrlfb import HYST
from plclab.testing import run_test_sources

THERMOSTAT = """
PROGRAM Main
VAR_INPUT temp : REAL; END_VAR
VAR
    relay_plain : BOOL;     (* the book's first try: no hysteresis *)
    hy : HYST;
    relay : BOOL;
END_VAR
relay_plain := temp < 50.0;
hy(IN := temp, SP := 50.0, H := 2.0);
relay := hy.Q;
END_PROGRAM
"""


def count_changes(seq):
    return sum(1 for a, b in zip(seq, seq[1:], strict=False) if a != b)


def test_noise_makes_a_plain_comparator_chatter_but_not_hyst():
    plc = plclab.loads(THERMOSTAT, cycle_time="100ms")
    rng = random.Random(2024)
    plain, relay = [], []
    for _ in range(600):  # one minute at 100 ms
        plc["Main.temp"] = 50.0 + rng.gauss(0.0, 0.5)
        plc.scan()
        plain.append(plc["Main.relay_plain"])
        relay.append(plc["Main.relay"])
    n_plain, n_hyst = count_changes(plain), plc["Main.hy.SWITCHES"]
    print(f"switches in one minute: plain comparator {n_plain}, HYST +-2: {n_hyst}")
    assert n_plain > 100  # about every other sample
    assert n_hyst <= 3
    assert n_hyst == count_changes([False] + relay)


def heater_loop(h, t_min_on=0, t_min_off=0, seconds=1200, noise=0.5, seed=5):
    """A water heater: dT/dt = (60 * Q - (T - 20)) / 300 (degC, s), noisy sensor, 100 ms."""
    ctx = type("Ctx", (), {"now": 0, "cycle_ms": 100.0})()
    hy = HYST(ctx)
    hy.SP, hy.H, hy.T_MIN_ON, hy.T_MIN_OFF = 50.0, h, t_min_on, t_min_off
    rng = random.Random(seed)
    temp, temps = 45.0, []
    for k in range(seconds * 10):
        ctx.now = k * 100
        hy.IN = temp + rng.gauss(0.0, noise)
        hy._body()
        temp += 0.1 * (60.0 * hy.Q - (temp - 20.0)) / 300.0
        temps.append(temp)
    return hy, temps


def test_heater_cycles_slowly_with_hysteresis():
    plain, t_plain = heater_loop(0.0)
    hyst, t_hyst = heater_loop(2.0)
    per_min_plain = plain.SWITCHES / 20.0
    per_min_hyst = hyst.SWITCHES / 20.0
    print(f"heater: {per_min_plain:.1f} switches/min without hysteresis, "
          f"{per_min_hyst:.1f} with +-2")
    assert per_min_plain > 50
    assert per_min_hyst < 4
    assert per_min_plain > 20 * per_min_hyst
    late = t_hyst[3000:]
    assert 47.0 < min(late) and max(late) < 53.0  # held within the window (plus the lag)


def test_minimum_on_and_off_times_protect_the_relay():
    unprotected, _ = heater_loop(0.0)
    protected, temps = heater_loop(0.0, t_min_on=10_000, t_min_off=10_000)
    assert protected.SWITCHES <= 1200 / 10 + 1  # at most one change per 10 s
    assert protected.SWITCHES < unprotected.SWITCHES / 10
    assert 45.0 < min(temps[3000:]) and max(temps[3000:]) < 55.0


def test_min_times_in_detail():
    ctx = type("Ctx", (), {"now": 0, "cycle_ms": 10.0})()
    hy = HYST(ctx)
    hy.SP, hy.H, hy.T_MIN_ON, hy.T_MIN_OFF = 50.0, 1.0, 1000, 500
    hy.IN = 40.0
    hy._body()
    assert hy.Q and hy.SWITCHES == 1  # the first switch-on is free
    hy.IN = 60.0
    ctx.now = 999
    hy._body()
    assert hy.Q  # on for 999 ms < T_MIN_ON
    ctx.now = 1000
    hy._body()
    assert not hy.Q and hy.SWITCHES == 2
    hy.IN = 40.0
    ctx.now = 1499
    hy._body()
    assert not hy.Q
    ctx.now = 1500
    hy._body()
    assert hy.Q and hy.SWITCHES == 3


def test_hyst_from_st_heating_cooling_and_edges():
    src = """
    TEST 'HYST heating: on below SP - H, off above SP + H, holds in between'
    VAR hy : HYST; END_VAR
    hy(IN := 49.0, SP := 50.0, H := 2.0);
    ASSERT_FALSE(hy.Q);
    hy(IN := 48.0);
    ASSERT_FALSE(hy.Q);                 (* 48 is not below 48 *)
    hy(IN := 47.9);
    ASSERT_TRUE(hy.Q);
    hy(IN := 51.0);
    ASSERT_TRUE(hy.Q);
    hy(IN := 52.1);
    ASSERT_FALSE(hy.Q);
    ASSERT_EQ(hy.SWITCHES, 2);
    END_TEST

    TEST 'HYST cooling (REVERSE): on above SP + H, off below SP - H'
    VAR hy : HYST; END_VAR
    hy(IN := 51.0, SP := 50.0, H := 2.0, REVERSE := TRUE);
    ASSERT_FALSE(hy.Q);
    hy(IN := 52.5);
    ASSERT_TRUE(hy.Q);
    hy(IN := 48.5);
    ASSERT_TRUE(hy.Q);
    hy(IN := 47.5);
    ASSERT_FALSE(hy.Q);
    END_TEST

    TEST 'HYST minimum on time from ST'
    VAR hy : HYST; END_VAR
    hy(IN := 40.0, SP := 50.0, H := 2.0, T_MIN_ON := T#5s);
    ASSERT_TRUE(hy.Q);
    hy(IN := 60.0);
    ASSERT_TRUE(hy.Q);
    ADVANCE_TIME(T#5s);
    hy(IN := 60.0);
    ASSERT_FALSE(hy.Q);
    END_TEST
    """
    results = run_test_sources([(src, "hyst.st")])
    assert len(results) == 3
    assert all(r.passed for r in results), [str(r) for r in results]
