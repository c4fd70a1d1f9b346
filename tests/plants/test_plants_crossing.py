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


def test_crossing_times_and_waits_against_hand_computed_values() -> None:
    """cross_time 5 s, 0.05 s steps. A waits from t = 2 s until the green at t = 12 s (10 s),
    crosses from 12 to 17 s; B arrives at 14 s during the green, crosses at once until 19 s.
    By hand: ON_CROSSING from 12 to 19 s, crossed = 2, wait_total = 10 s, wait_max = 10 s.
    The car signal dark from 20 s: one lights_dark event at 21 s, not before."""
    p = Crossing(cross_time=5.0)
    _lights(p, "green", False)

    def run_to(t_end: float) -> None:
        while p.time < t_end - 1e-9:
            p.step(0.05)

    run_to(2.0)
    p["ARRIVE"] = True
    run_to(2.1)
    p["ARRIVE"] = False
    run_to(12.0)
    _lights(p, "red", True)
    run_to(14.0)
    p["ARRIVE"] = True
    run_to(14.1)
    p["ARRIVE"] = False
    run_to(16.9)
    assert p["ON_CROSSING"] and p.snapshot()["crossing"] == 2.0
    run_to(17.1)
    assert p.snapshot()["crossed"] == 1.0  # A is over
    run_to(18.95)
    assert p["ON_CROSSING"]
    run_to(19.15)
    assert not p["ON_CROSSING"]
    s = p.snapshot()
    assert s["crossed"] == 2.0
    assert s["wait_total"] == pytest.approx(10.0, abs=0.06)
    assert s["wait_max"] == pytest.approx(10.0, abs=0.06)
    assert p.drain_events() == []
    run_to(20.0)
    p["CAR_RED"] = False  # the car signal goes dark
    run_to(20.9)
    assert p.drain_events() == []
    run_to(21.1)
    assert [e.kind for e in p.drain_events()] == ["lights_dark"]
