"""Washing machine driven by the textbook's SFC (Fig. 32) written as a Python step machine."""

from __future__ import annotations

import pytest

from plants import Washer


class WashSfc:
    """Start -> Fill -> Boiling (COTTON, 10 min) | Warming (SILK, 5 min) -> Cooling -> Stop."""

    def __init__(self) -> None:
        self.step = "Start"
        self.entered = 0.0
        self.visited: list[str] = ["Start"]

    def go(self, step: str, now: float) -> None:
        self.step = step
        self.entered = now
        self.visited.append(step)

    def scan(self, w: Washer) -> None:
        now = w.time
        s = self.step
        if s == "Start" and w["START"]:
            self.go("Fill", now)
        elif s == "Fill" and w["LEVEL_SW"]:
            self.go("Boiling" if w["COTTON"] else "Warming", now)
        elif s == "Boiling" and now - self.entered >= 600.0:
            self.go("Cooling", now)
        elif s == "Warming" and now - self.entered >= 300.0:
            self.go("Cooling", now)
        elif s == "Cooling" and w["TEMP"] <= 40.0:
            self.go("Stop", now)
        s = self.step
        w["FILL_VALVE"] = s == "Fill" or (s == "Cooling" and not w["LEVEL_SW"])
        w["HEATER"] = s in ("Boiling", "Warming")
        w["MOTOR"] = s in ("Boiling", "Warming", "Cooling")
        w["DRAIN_VALVE"] = (s == "Cooling" and w["LEVEL_SW"]) or (s == "Stop" and not w["EMPTY"])


def _wash(mode: str) -> tuple[Washer, WashSfc, float]:
    w = Washer()
    w["COTTON"] = mode == "cotton"
    w["SILK"] = mode == "silk"
    sfc = WashSfc()
    w["START"] = True
    tmax = 0.0
    for _ in range(int(3600 / 0.5)):
        sfc.scan(w)
        w.step(0.5)
        w["START"] = False
        tmax = max(tmax, w["TEMP"])
        if sfc.step == "Stop" and w["EMPTY"]:
            break
    return w, sfc, tmax


@pytest.mark.parametrize("mode", ["cotton", "silk"])
def test_sfc_runs_through_all_steps(mode: str) -> None:
    w, sfc, tmax = _wash(mode)
    middle = "Boiling" if mode == "cotton" else "Warming"
    assert sfc.visited == ["Start", "Fill", middle, "Cooling", "Stop"]
    assert w["EMPTY"] and w["TEMP"] <= 40.5
    assert tmax > (40.0 if mode == "cotton" else 25.0)
    bad = {"overflow", "dry_heating", "drum_dry"}
    assert not [e for e in w.drain_events() if e.kind in bad]
    s = w.snapshot()
    assert s["volume_in"] - s["volume_out"] - s["volume_overflow"] == pytest.approx(
        w["LEVEL"], abs=0.3
    )


def test_level_switch_and_overflow() -> None:
    w = Washer()
    w["FILL_VALVE"] = True
    while not w["LEVEL_SW"]:
        w.step(0.5)
    assert w["LEVEL"] == pytest.approx(w.level_full, abs=0.2)
    w.step(200.0)
    assert w["LEVEL"] == w.capacity
    assert "overflow" in [e.kind for e in w.drain_events()]


def test_dry_heating_and_drum_dry() -> None:
    w = Washer()
    w["HEATER"] = True
    w["MOTOR"] = True
    w.step(20.0)
    kinds = [e.kind for e in w.drain_events()]
    assert "dry_heating" in kinds and "drum_dry" in kinds
    assert w["TEMP"] == w.t_amb
    assert w["DRUM_SPEED"] == pytest.approx(w.drum_speed)


def test_faults() -> None:
    w = Washer()
    w.inject("fill_valve_stuck")
    w.step(10.0)
    assert w["LEVEL"] > 2.0
    w.clear("fill_valve_stuck")
    w.inject("level_switch_stuck_off")
    w["FILL_VALVE"] = True
    w.step(80.0)
    assert w["LEVEL"] > w.level_full and w["LEVEL_SW"] is False
    w["FILL_VALVE"] = False
    w.inject("drain_blocked")
    w["DRAIN_VALVE"] = True
    level = w["LEVEL"]
    w.step(30.0)
    assert w["LEVEL"] == pytest.approx(level, abs=0.2)  # only boiling could lower it
    w.clear("drain_blocked")
    w.inject("heater_fail")
    w["DRAIN_VALVE"] = False
    w["HEATER"] = True
    w.step(60.0)
    assert w["TEMP"] <= w.t_amb + 1e-9


def _full_and_hot(temp: float = 75.0) -> Washer:
    w = Washer(level_full=8.0)
    w.volume, w.temp = 8.0, temp  # the state after filling and heating
    w.step(0.0)
    return w


def test_exchanging_keeps_the_drum_full_and_cools_as_computed_by_hand() -> None:
    """ADR 0046: fill 0.5 l/s = drain 0.5 l/s. By hand, with V = 8 l, q = 0.5 l/s,
    c = 4186 J/(kg K), UA = 20 W/K, T_in = 15, T_amb = 20 degC:
    G = 20 + 4186 * 0.5 = 2113 W/K, tau = 8 * 4186 / 2113 = 15.85 s,
    T_eq = (2093 * 15 + 20 * 20) / 2113 = 15.05 degC; after 16 s
    T = 15.05 + (75 - 15.05) * exp(-16 / 15.85) = 36.9 degC."""
    w = _full_and_hot(75.0)
    w["FILL_VALVE"] = w["DRAIN_VALVE"] = True
    w.step(16.0)
    assert w["LEVEL"] == pytest.approx(8.0, abs=1e-9)
    assert w["TEMP"] == pytest.approx(36.9, abs=0.1)
    w.step(104.0)  # two minutes of exchange in all
    assert w["LEVEL"] == pytest.approx(8.0, abs=1e-9), "the drum stays full"
    assert w["LEVEL_SW"] and not w["EMPTY"]
    assert w["TEMP"] == pytest.approx(15.05, abs=0.05)  # 7.6 time constants: inlet water
    s = w.snapshot()
    assert s["volume_in"] == pytest.approx(60.0) and s["volume_out"] == pytest.approx(60.0)


def test_draining_alone_empties_the_tub_in_the_hand_computed_time() -> None:
    """8 l -> 2 l at 0.5 l/s is 12 s; below 2 l the pump is linear in the level,
    dV/dt = -0.5 V / 2, so 2 l -> 0.5 l (EMPTY) takes 4 ln 4 = 5.5 s (5.2 s with the plant's
    0.5 s Euler steps, 0.875 per step): about 17.5 s in all."""
    w = _full_and_hot(40.0)
    w["DRAIN_VALVE"] = True
    w.step(12.0)
    assert w["LEVEL"] == pytest.approx(2.0, abs=1e-6) and not w["EMPTY"]
    w.step(4.5)
    assert not w["EMPTY"]
    w.step(1.5)
    assert w["EMPTY"]


def test_heating_balances_energy_and_volume() -> None:
    """4 kW for 60 s into 8 l at 20 degC: 240 kJ. By hand, with losses UA = 20 W/K:
    T_eq = 20 + 4000 / 20 = 220 degC, tau = 8 * 4186 / 20 = 1674.4 s,
    T = 220 - 200 exp(-60 / 1674.4) = 27.04 degC (7.17 K without losses)."""
    w = Washer(level_full=8.0, heater_power=4000.0)
    w.volume, w.temp = 8.0, 20.0
    w["HEATER"] = True
    w.step(60.0)
    assert w.snapshot()["energy_in"] == pytest.approx(240e3)
    assert w["TEMP"] == pytest.approx(27.04, abs=0.01)
    w["HEATER"] = False
    w["FILL_VALVE"] = True
    w.step(10.0)
    s = w.snapshot()
    assert s["volume_in"] == pytest.approx(5.0)
    assert w["LEVEL"] == pytest.approx(8.0 + s["volume_in"] - s["volume_out"])


def test_with_the_old_flows_the_exchange_empties_the_tub() -> None:
    """The mistake ADR 0046 removes: a drain faster than the fill empties the drum."""
    w = Washer(level_full=8.0, fill_flow=0.25)
    w.volume, w.temp = 8.0, 75.0
    w["FILL_VALVE"] = w["DRAIN_VALVE"] = True
    w.step(120.0)
    assert w["LEVEL"] < 1.5
