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
