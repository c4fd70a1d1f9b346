"""Water heater / boiler: steady state, Pt100, faults, thermostat loop."""

from __future__ import annotations

import math

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


# ------------------------------------------------------------------ conservation and the labs
RHO_C = 1000.0 * 4186.0  # J/(m3 K)


def _lab_heater(lab_id: str, **over) -> Heater:
    """The heater as a lab configures it (lab.toml's plant_params), with overrides."""
    from plclab.grade.lab import load_lab

    return Heater(**{**load_lab(lab_id).plant_params, **over})


def test_volume_and_energy_are_conserved() -> None:
    """Over an hour of fill, draw, heating and losses: every litre is accounted for (in, out,
    stored), and the stored heat changes by what came in minus what left (element, cold fill
    water, hot water drawn, losses), integrated here step by step."""
    h = Heater(area=0.05, level0=0.3, t0=30.0, ua=40.0, p_max=4000.0, fill_flow=3e-5,
               demand=[(0.0, 1e-5), (1200.0, 4e-5), (2400.0, 0.0)])
    dt = 0.5
    e0 = RHO_C * h.volume * h.temp
    v0 = h.volume
    ext = 0.0
    for k in range(int(3600 / dt)):
        h["POWER"] = 60.0 if (k * dt) % 600 < 400 else 0.0
        h["FILL_VALVE"] = h["LEVEL"] < 0.35
        t_before, snap_before = h.temp, h.snapshot()
        h.step(dt)
        snap = h.snapshot()
        t_mid = 0.5 * (t_before + h.temp)
        v_in = snap["volume_in"] - snap_before["volume_in"]
        v_out = snap["volume_out"] - snap_before["volume_out"]
        ext += (snap["energy_in"] - snap_before["energy_in"]
                + RHO_C * v_in * h.t_in - RHO_C * v_out * t_mid
                - h.ua * (t_mid - h.t_amb) * dt)
    s = h.snapshot()
    assert s["volume_evaporated"] == 0.0 and s["volume_overflow"] == 0.0
    assert s["volume"] == pytest.approx(v0 + s["volume_in"] - s["volume_out"], rel=1e-9)
    assert s["volume_in"] > 0.005 and s["volume_out"] > 0.005  # both flows really ran
    stored = RHO_C * h.volume * h.temp - e0
    assert stored == pytest.approx(ext, rel=0.01, abs=0.002 * s["energy_in"])


def test_heater_pid_plant_is_what_its_readme_says() -> None:
    """labs/heater-pid/README.md: 10 l, full power heats ~8 °C a minute from cold, at 50 °C it
    loses 1.8 kW, time constant ~12 min, a 1.2 l/min tap of 10 °C water costs ~3.3 kW and
    the heater then needs ~85 % power."""
    h = _lab_heater("heater-pid", t0=20.0)
    assert h.volume == pytest.approx(0.010)
    h["POWER"] = 100.0
    h.step(60.0)
    # T_eq = 20 + 6000/60 = 120 degC, tau = 41860/60 = 698 s: 100 (1 - exp(-60/698)) = 8.2
    assert h["TEMP"] - 20.0 == pytest.approx(100.0 * (1.0 - math.exp(-60.0 / 697.7)), abs=0.01)
    assert 0.010 * RHO_C / h.ua / 60.0 == pytest.approx(11.6, abs=0.1)
    assert h.ua * (50.0 - h.t_amb) == pytest.approx(1800.0)
    tap = RHO_C * 2e-5 * (50.0 - h.t_in)
    assert tap == pytest.approx(3349.0, abs=1.0)
    # with the tap open for good, 85.8 % holds 50 degC: the fill replaces what the tap takes
    h2 = _lab_heater("heater-pid", t0=50.0, demand=2e-5)
    h2["FILL_VALVE"] = True
    h2["POWER"] = 100.0 * (1800.0 + tap) / 6000.0
    for _ in range(1800):
        h2.step(1.0)
    assert h2["TEMP"] == pytest.approx(50.0, abs=0.01)
    assert h2["LEVEL"] == pytest.approx(0.2, abs=1e-9)


def test_relay_thermostat_plant_is_what_its_readme_says() -> None:
    """labs/relay-thermostat/README.md: from 20 °C to 48 °C in about four minutes; at 50 °C
    about -2.5 °C a minute with the element off, +6 °C with it on. By hand: T_eq = 20 + 6000/60
    = 120 °C, tau = 41860/60 = 698 s, t = tau ln(100/72) = 229 s."""
    h = _lab_heater("relay-thermostat", t0=20.0)
    h["HEATER"] = True
    t = 0.0
    while h["TEMP"] < 48.0:
        h.step(1.0)
        t += 1.0
    assert t == pytest.approx(698.0 * math.log(100.0 / 72.0), abs=2.0)
    for on, rate in ((False, -1800.0), (True, 6000.0 - 1800.0)):
        h2 = _lab_heater("relay-thermostat", t0=50.0)
        h2["HEATER"] = on
        h2.step(6.0)
        assert (h2["TEMP"] - 50.0) * 10.0 == pytest.approx(rate * 60.0 / 41860.0, rel=0.02)


def test_water_boiler_plant_is_what_its_readme_says() -> None:
    """labs/water-boiler: 12 litres at 0.6 m warm from 20 to 60 °C in about three minutes
    (12 kW, 15 W/K of losses: T_eq = 20 + 12000/15 = 820 °C, tau = 50232/15 = 3349 s,
    t = tau ln(800/760) = 172 s); the thermostat opens at 60 °C; the fill valve
    (0.5 l/s) outruns the small draw and a big tap (0.8 l/s) outruns the valve."""
    h = _lab_heater("water-boiler", demand=0.0)
    assert h.volume == pytest.approx(0.012)
    h["HEATER"] = True
    t = 0.0
    while not h["TEMP_MAX"]:
        h.step(0.5)
        t += 0.5
    assert t == pytest.approx(0.012 * RHO_C / 15.0 * math.log(800.0 / 760.0), abs=1.0)
    lab = _lab_heater("water-boiler")
    assert lab.fill_flow > 2e-5 * 10 and lab.fill_flow < 8e-4
