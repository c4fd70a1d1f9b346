"""heater-pid's own checks (labs/heater-pid/checks.py) on hand-made traces: each failure names
what the temperature did (a steady error, a swing, the old set point, an overshoot coming down,
a creep, a value held far away), and each of them fails where it must."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from plclab.trace import Trace

from .lab_modules import lab_checks

ROOT = Path(__file__).resolve().parents[2]


def _checks():
    return lab_checks("heater-pid")


C = _checks()
T = np.arange(0.0, 1200.0, 1.0)


def _trace(**cols):
    return Trace(T, {k: np.asarray(v, dtype=float) for k, v in cols.items()},
                 meta={"t_end": float(T[-1]) + 1.0})


def _settles(temp, sp=None, **kw):
    cols = {"TEMP": temp} | ({"SP": sp} if sp is not None else {})
    args = {"target": 50.0, "band": 0.5, "after": 0.0, "within": 600.0} | kw
    return C.settles_diagnosed(_trace(**cols), **args)


def test_a_settled_loop_passes():
    temp = 50.0 + 30.0 * np.exp(-T / 100.0) * -1.0
    assert _settles(temp)[0]


def test_a_steady_error_below_is_a_steady_state_error():
    ok, msg, tf, sig = _settles(np.full(len(T), 49.4))
    assert not ok and "steady-state error" in msg and "0.60 °C below" in msg and tf == 600.0


def test_a_swing_is_named_a_swing():
    ok, msg = _settles(50.0 + 1.2 * np.sin(T / 40.0))[:2]
    assert not ok and "swings" in msg and "steady-state" not in msg


def test_the_old_set_point_is_recognised():
    sp = np.where(T < 300.0, 50.0, 60.0)
    ok, msg = _settles(np.full(len(T), 50.0), sp=sp, target=60.0, after=300.0, within=360.0)[:2]
    assert not ok and "set point before the change (50 °C)" in msg


def test_a_value_held_far_away_points_at_the_set_point_and_the_scaling():
    ok, msg = _settles(np.full(len(T), 38.0))[:2]
    assert not ok and "scaled right" in msg and "steady-state" not in msg


def test_an_overshoot_coming_down_is_windup_not_slowness():
    temp = 50.0 + 15.0 * np.exp(-(T - 250.0).clip(0) / 250.0)
    temp[T < 250.0] = 20.0 + T[T < 250.0] * 0.18
    ok, msg = _settles(temp)[:2]
    assert not ok and "overshoot" in msg and "windup" in msg


def test_a_slow_creep_from_below_is_too_slow():
    temp = 50.0 - 20.0 * np.exp(-T / 400.0)
    ok, msg = _settles(temp)[:2]
    assert not ok and "too slow" in msg


def test_heats_up_tells_the_three_ways_of_not_heating():
    cold = np.full(len(T), 20.0)
    ok, msg = C.heats_up(_trace(TEMP=cold, POWER=np.zeros(len(T))))[:2]
    assert not ok and "direct acting" in msg
    ok, msg = C.heats_up(_trace(TEMP=cold, POWER=np.full(len(T), 0.36)))[:2]
    assert not ok and "not scaled" in msg and "0.36 %" in msg
    ok, msg = C.heats_up(_trace(TEMP=np.minimum(20.0 + T * 0.05, 38.0),
                                POWER=np.full(len(T), 20.0)))[:2]
    assert not ok and "scaled right" in msg
    assert C.heats_up(_trace(TEMP=20.0 + T * 0.1, POWER=np.full(len(T), 100.0)))[0]


def test_holds_diagnosed_counts_the_share_in_the_band():
    start = 600.0
    good = np.where(T < 650.0, 49.0, 50.05)
    assert C.holds_diagnosed(_trace(TEMP=good), start=start)[0]  # 50 of 600 s outside
    ok, msg = C.holds_diagnosed(_trace(TEMP=np.full(len(T), 48.3)), start=start)[:2]
    assert not ok and "0 %" in msg and "steady-state error" in msg
    late = np.where(T < 700.0, 49.0, 50.0)  # 100 of 600 s outside: 83 %
    ok, msg = C.holds_diagnosed(_trace(TEMP=late), start=start)[:2]
    assert not ok and "83 %" in msg
