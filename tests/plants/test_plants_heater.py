"""Water heater / boiler: steady state, Pt100, faults, thermostat loop."""

from __future__ import annotations

import pytest

from plants import Heater
from plants.heater import pt100_ohm


def test_pt100_formula() -> None:
    assert pt100_ohm(0.0) == 100.0
    assert pt100_ohm(100.0) == pytest.approx(138.5055, abs=1e-9)
    assert pt100_ohm(-100.0) == pytest.approx(60.26, abs=0.01)
    h = Heater(t0=50.0)
    assert h["TEMP_RTD_OHM"] == pytest.approx(100 * (1 + 3.9083e-3 * 50 - 5.775e-7 * 2500))


@pytest.mark.parametrize("drive", ["POWER", "STEAM_VALVE"])
def test_steady_state_matches_analytic(drive: str) -> None:
    h = Heater(ua=200.0, p_max=2000.0, steam_power=4000.0, level0=0.5)
    h[drive] = 50.0  # 1 kW electric, 2 kW steam
    power = 1000.0 if drive == "POWER" else 2000.0
    tau = 1000.0 * 0.5 * 0.25 * 4186.0 / 200.0
    for _ in range(int(12 * tau / 10.0)):
        h.step(10.0)
    t_ss = h.steady_state_temperature(power)
    assert t_ss == pytest.approx(20.0 + power / 200.0)
    assert h["TEMP"] == pytest.approx(t_ss, rel=0.01)
    assert abs(h["TEMP"] - t_ss) < 0.01


def test_first_order_response_is_step_size_independent() -> None:
    a = Heater(ua=50.0)
    b = Heater(ua=50.0, max_dt=60.0)
    a["HEATER"] = b["HEATER"] = True
    for _ in range(3600):
        a.step(1.0)
    for _ in range(60):
        b.step(60.0)
    assert a["TEMP"] == pytest.approx(b["TEMP"], rel=1e-6)


def test_fill_drain_and_level_switches() -> None:
    h = Heater(level0=0.2)
    assert h["LEVEL_MIN"] is False
    h["FILL_VALVE"] = True
    while not h["LEVEL_MAX"]:
        h.step(1.0)
    assert h["LEVEL"] == pytest.approx(0.9, abs=0.01)
    h.step(400.0)
    assert "overflow" in [e.kind for e in h.drain_events()]
    h["FILL_VALVE"] = False
    h["DRAIN_VALVE"] = True
    h.step(3000.0)
    assert h["LEVEL"] < 0.01 and not h["LEVEL_MIN"]


def test_cold_fill_cools_the_water() -> None:
    h = Heater(t0=60.0, level0=0.4)
    h["FILL_VALVE"] = True
    h.step(100.0)
    assert h["TEMP"] < 50.0


def test_dry_heating_and_boiling() -> None:
    h = Heater(level0=0.1)
    h["HEATER"] = True
    h.step(10.0)
    assert h["TEMP"] == pytest.approx(20.0, abs=0.1)
    assert "dry_heating" in [e.kind for e in h.drain_events()]
    h2 = Heater(level0=0.3, ua=1.0)
    h2["HEATER"] = True
    v0 = h2.snapshot()["volume"]
    for _ in range(10000):
        h2.step(1.0)
    assert h2["TEMP"] == 100.0
    assert h2["TEMP_MAX"] is True
    assert h2.snapshot()["volume"] < v0
    assert "boiling" in [e.kind for e in h2.drain_events()]


def test_faults() -> None:
    h = Heater(t0=40.0)
    h.inject("sensor_open")
    assert h["TEMP_RTD_OHM"] >= 1e5
    h.clear("sensor_open")
    h.inject("sensor_short")
    assert h["TEMP_RTD_OHM"] == 0.0
    assert h["TEMP"] == 40.0  # the true value is unaffected
    h.clear("sensor_short")
    h.inject("heater_fail")
    h["HEATER"] = True
    h.step(600.0)
    assert h["TEMP"] < 40.0
    h.clear("heater_fail")
    h["STEAM_VALVE"] = 30.0
    h.inject("valve_stuck")
    h["STEAM_VALVE"] = 0.0
    h["HEATER"] = False
    h.step(1.0)
    assert h.snapshot()["p_steam"] == pytest.approx(0.3 * h.steam_power)
    h.clear("valve_stuck")
    h.step(1.0)
    assert h.snapshot()["p_steam"] == 0.0


def test_thermostat_with_hysteresis_holds_the_band() -> None:
    """The textbook's relay with hysteresis (setpoint 50, window 2) as the controller."""
    h = Heater(demand=[(0, 0.0), (3600, 0.00002)], fill_flow=0.00005)
    relay = False
    temps = []
    for k in range(5 * 3600):
        t = h["TEMP"]
        if t < 48.0:
            relay = True
        elif t > 52.0:
            relay = False
        h["HEATER"] = relay
        h["FILL_VALVE"] = h["LEVEL"] < 0.6  # level top-up
        h.step(1.0)
        if k > 3600:
            temps.append(h["TEMP"])
    assert 47.0 < min(temps) and max(temps) < 53.5
