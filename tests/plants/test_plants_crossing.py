"""Pedestrian crossing: pedestrians wait, cross on green, and the plant reports conflicts."""

from __future__ import annotations

import pytest

from plants import Crossing


def _lights(p: Crossing, cars: str, ped_green: bool) -> None:
    p["CAR_RED"], p["CAR_YELLOW"], p["CAR_GREEN"] = cars == "red", cars == "yellow", cars == "green"
    p["PED_GREEN"], p["PED_RED"] = ped_green, not ped_green


def test_a_pedestrian_waits_then_crosses_on_green() -> None:
    p = Crossing(cross_time=4.0)
    _lights(p, "green", False)
    p["ARRIVE"] = True
    p.step(0.1)
    p["ARRIVE"] = False
    p.step(10.0)
    assert p["PED_WAITING"] and not p["ON_CROSSING"]
    _lights(p, "red", True)
    p.step(0.1)
    assert p["ON_CROSSING"] and not p["PED_WAITING"]
    _lights(p, "red", False)  # the light turns red: the pedestrian still crosses
    p.step(3.0)
    assert p["ON_CROSSING"]
    p.step(1.0)
    assert not p["ON_CROSSING"]
    snap = p.snapshot()
    assert snap["crossed"] == 1.0 and snap["wait_max"] == pytest.approx(10.0, abs=0.2)
    assert p.drain_events() == []


def test_conflicts_and_cars_on_a_pedestrian_are_events() -> None:
    p = Crossing()
    p["ARRIVE"] = True
    _lights(p, "red", True)
    p.step(1.0)
    p["CAR_GREEN"] = True  # green for both
    p.step(0.1)
    kinds = [e.kind for e in p.drain_events()]
    assert kinds == ["conflict", "cars_on_pedestrian"]


def test_dark_lights_and_long_waits() -> None:
    p = Crossing(patience=20.0)
    p["ARRIVE"] = True
    p.step(30.0)
    assert sorted(e.kind for e in p.drain_events()) == ["lights_dark", "long_wait"]


def test_faults_stuck_button_and_dead_sensor() -> None:
    p = Crossing()
    p.inject("request_stuck")
    p.inject("crossing_sensor_dead")
    p.step(0.1)
    assert p["REQUEST"]
    p["ARRIVE"] = True
    _lights(p, "red", True)
    p.step(1.0)
    assert not p["ON_CROSSING"] and p.snapshot()["crossing"] == 1.0
