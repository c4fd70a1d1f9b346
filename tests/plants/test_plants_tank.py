"""Hydro-accumulator tank: mass balance, Torricelli outflow, switches, faults, two-position loop."""

from __future__ import annotations

import math

import pytest

from plants import Tank


def _balance_error(tank: Tank) -> float:
    s = tank.snapshot()
    delta = s["volume"] - s["volume0"]
    books = s["volume_in"] - s["volume_out"] - s["volume_overflow"]
    return abs(books - delta) / max(s["volume_in"], 1e-9)


def test_mass_balance_with_pump_cycling_demand_and_overflow() -> None:
    demand = [(0, 0.001), (600, 0.004), (1200, 0.0), (1800, 0.002)]
    tank = Tank(demand=demand)
    dt = 0.05
    for k in range(int(3600 / dt)):
        t = k * dt
        tank.write("PUMP", (t // 200) % 3 != 2)  # on 400 s, off 200 s
        tank.write("VALVE", 100.0 if (t // 500) % 2 else 20.0)
        tank.step(dt)
    s = tank.snapshot()
    assert s["volume_in"] > 5.0
    assert s["volume_overflow"] > 0.0 or s["volume_demand"] > 0.0
    assert _balance_error(tank) < 1e-3


def test_mass_balance_includes_overflow_and_dry_run() -> None:
    tank = Tank(level0=1.9, valve=0.0)
    tank.write("PUMP", True)
    for _ in range(600):
        tank.step(0.1)
    ev = [e.kind for e in tank.drain_events()]
    assert "overflow" in ev
    assert tank.read("LEVEL") == pytest.approx(2.0)
    assert tank.snapshot()["volume_overflow"] > 0.1
    tank.write("PUMP", False)
    tank.write("VALVE", 100.0)
    for _ in range(int(4000 / 0.5)):
        tank.step(0.5)
    assert tank.read("LEVEL") == pytest.approx(0.0, abs=1e-6)
    assert "dry_run" in [e.kind for e in tank.drain_events()]
    assert _balance_error(tank) < 1e-3


def test_torricelli_drain_time_matches_analytic() -> None:
    area, a, cd, g = 1.0, 0.001, 0.62, 9.81
    h0, h1 = 1.8, 0.2
    tank = Tank(area=area, outlet_area=a, cd=cd, level0=h0, g=g)
    k = cd * a * math.sqrt(2 * g)
    t_expected = 2 * area * (math.sqrt(h0) - math.sqrt(h1)) / k
    dt = 0.01
    while tank.read("LEVEL") > h1:
        tank.step(dt)
    assert tank.time == pytest.approx(t_expected, rel=2e-3)


def test_switches_and_transmitter() -> None:
    tank = Tank(level0=0.0, valve=0.0, ls1_height=0.5, ls2_height=1.5)
    tank.write("PUMP", True)
    seen = []
    while tank.read("LEVEL") < 1.6:
        tank.step(0.1)
        lvl = tank.read("LEVEL")
        assert tank.read("LS1") == (lvl >= 0.5)
        assert tank.read("LS2") == (lvl >= 1.5)
        assert tank.read("LEVEL_MA") == pytest.approx(4 + 16 * lvl / 2.0)
        seen.append((tank.read("LS1"), tank.read("LS2")))
    assert (False, False) in seen and (True, False) in seen and (True, True) in seen


def test_pump_speed_and_lag() -> None:
    tank = Tank(pump_tau=0.5)
    tank.write("PUMP", True)
    tank.write("PUMP_SPEED", 50.0)
    tank.step(0.1)
    assert 0.0 < tank.read("FLOW_IN") < 0.0025
    tank.step(5.0)
    assert tank.read("FLOW_IN") == pytest.approx(0.0025, rel=1e-4)


def test_faults() -> None:
    tank = Tank(level0=1.8, valve=0.0)
    tank.inject("ls1_stuck_off")
    tank.inject("ls2_stuck_off")
    assert tank.read("LS1") is False and tank.read("LS2") is False
    tank.clear("ls1_stuck_off")
    tank.clear("ls2_stuck_off")
    assert tank.read("LS1") is True and tank.read("LS2") is True
    tank.inject("transmitter_open")
    assert tank.read("LEVEL_MA") == 0.0
    tank.clear("transmitter_open")
    assert tank.read("LEVEL_MA") > 4.0
    # leak drains a closed tank
    v0 = tank.read("LEVEL")
    tank.inject("leak", area=5e-4)
    tank.step(100.0)
    assert tank.read("LEVEL") < v0 - 0.05
    assert tank.snapshot()["volume_leak"] > 0.05
    tank.clear("leak")
    # the failed pump delivers nothing
    tank.inject("pump_fail")
    tank.write("PUMP", True)
    before = tank.read("LEVEL")
    tank.step(10.0)
    assert tank.read("FLOW_IN") == 0.0 and tank.read("LEVEL") == before


def test_two_position_control_keeps_level_between_switches() -> None:
    """The textbook's one-liner M := ((NOT LS1) OR M) AND (NOT LS2) as the PLC."""
    tank = Tank(demand=[(0, 0.001), (1800, 0.003)])
    m = False
    dt = 0.01
    levels = []
    for k in range(int(3600 / dt)):
        ls1, ls2 = tank["LS1"], tank["LS2"]
        m = ((not ls1) or m) and (not ls2)
        tank["PUMP"] = m
        tank.step(dt)
        if k * dt > 600:  # after the first fill
            levels.append(tank["LEVEL"])
    assert min(levels) > 0.45 and max(levels) < 1.55
    assert not [e for e in tank.drain_events() if e.kind in ("overflow", "dry_run")]
