"""Three axes driven by a homing-then-positioning sequence written in Python."""

from __future__ import annotations

import pytest

from plants import Axes, PlantError
from plants.axes import AXES as AXES_PLANT_NAMES

TARGETS = {"BELT": 250.0, "PISTON": 100.0, "PUMP": 40.0}


def _drive(p: Axes, a: str, target: float | None) -> bool:
    """One scan of one axis: home (target None) or go to target; True when there."""
    if target is None:
        done = bool(p[f"{a}_HOME"])
        p[f"{a}_FWD"], p[f"{a}_REV"] = False, not done
        return done
    err = target - float(p[f"{a}_POS"])
    p[f"{a}_FWD"], p[f"{a}_REV"] = err > 1.0, err < -1.0
    return abs(err) <= 1.0


def _sequence(p: Axes, seconds: float) -> tuple[list[str], float]:
    phase, t_ready = "home", -1.0
    for _ in range(int(seconds / 0.01)):
        done = [_drive(p, a, None if phase == "home" else TARGETS[a]) for a in AXES_PLANT_NAMES]
        if all(done) and phase == "home":
            phase = "move"
        elif all(done) and phase == "move" and t_ready < 0:
            t_ready = p.time
        p.step(0.01)
    return [a for a in AXES_PLANT_NAMES if p[f"{a}_HOME"]], t_ready


def test_homing_then_moving_takes_the_slowest_axis_time() -> None:
    p = Axes()
    _, t_ready = _sequence(p, 15.0)
    # homing: BELT 420 mm at 100 mm/s is the slowest (4.2 s); moves: BELT 250 mm (2.5 s),
    # PUMP 40 mm at 20 mm/s (2.0 s)
    assert 6.5 < t_ready < 7.2
    for a, x in TARGETS.items():
        assert p[f"{a}_POS"] == pytest.approx(x, abs=1.5)
    assert not [e for e in p.drain_events() if e.kind != "fault_injected"]


def test_speed_and_acceleration_limits() -> None:
    p = Axes(accel=100.0)
    p["PISTON_FWD"] = True
    p.step(0.1)
    assert p.snapshot()["piston_speed"] == pytest.approx(10.0)  # 100 mm/s^2 for 0.1 s
    p.step(2.0)
    assert p.snapshot()["piston_speed"] == pytest.approx(50.0)  # the rated speed
    p["PISTON_REV"] = True  # both contactors: the interlock stops the axis
    p.step(1.0)
    assert p.snapshot()["piston_speed"] == 0.0
    assert [e.kind for e in p.drain_events()] == ["both_directions"]


def test_home_switch_and_hard_stop() -> None:
    p = Axes(starts={"PUMP": 5.0})
    p["PUMP_REV"] = True
    seen = False
    for _ in range(200):
        p.step(0.01)
        seen = seen or bool(p["PUMP_HOME"])
    assert seen and not p["PUMP_HOME"]
    assert p["PUMP_POS"] == pytest.approx(-10.0)
    assert [e.kind for e in p.drain_events()] == ["end_stop"]


def test_a_dead_home_switch_never_closes() -> None:
    p = Axes()
    p.inject("belt_home_dead")
    p["BELT_REV"] = True
    for _ in range(800):
        p.step(0.01)
        assert not p["BELT_HOME"]
    assert p["BELT_POS"] == pytest.approx(-10.0)


def test_a_tripped_drive_stops_and_reports() -> None:
    p = Axes()
    p["BELT_FWD"] = True
    p.step(1.0)
    p.inject("belt_trip")
    p.step(0.01)
    assert p["BELT_FAULT"] and not p["PISTON_FAULT"]
    x = p["BELT_POS"]
    p.step(2.0)
    assert p["BELT_POS"] - x < 3.0  # braked at the acceleration limit, then still
    assert "moved_tripped" in [e.kind for e in p.drain_events()]
    p.clear("belt_trip")
    p.step(0.5)
    assert not p["BELT_FAULT"] and p["BELT_POS"] > x + 10.0


def test_bad_parameters_are_refused() -> None:
    with pytest.raises(PlantError, match="unknown axis"):
        Axes(speeds={"SPINDLE": 10.0})
    with pytest.raises(PlantError, match="start"):
        Axes(starts={"PUMP": 500.0})


EULER = 100.0 * 0.005 / 2 + 1e-9  # the largest error of one ramp at 100 mm/s, mm


def test_travel_and_braking_distance_match_the_hand_computed_values() -> None:
    # the drives lab's plant: 100 mm/s, accel 10 000 mm/s^2. Run 1 s forward: 0.01 s of ramp
    # (0.5 * 100 * 0.01 = 0.5 mm) and 0.99 s at speed (99 mm): 99.5 mm. Then braking from
    # 100 mm/s takes v^2 / 2a = 0.5 mm: the lab's +-1 mm window is reachable at a 10 ms scan.
    # The plant integrates in steps of max_dt (5 ms): a ramp is off by at most v * max_dt / 2.
    p = Axes(accel=10000.0, starts={"BELT": 0.0})
    p["BELT_FWD"] = True
    p.step(1.0)
    assert p["BELT_POS"] == pytest.approx(99.5, abs=EULER)
    p["BELT_FWD"] = False
    p.step(0.5)
    assert p["BELT_POS"] == pytest.approx(100.0, abs=EULER)
    assert p.snapshot()["distance"] == pytest.approx(100.0, abs=EULER)  # every mm is counted


def test_a_tripped_drive_stops_and_reports_its_fault_contact() -> None:
    p = Axes(accel=10000.0)
    p["PISTON_REV"] = True
    p.step(0.5)
    x = float(p["PISTON_POS"])
    assert x == pytest.approx(130.0 - 50.0 * 0.5 + 0.5 * 50.0 * 0.005, abs=EULER)
    p.inject("piston_trip")
    p.step(0.5)
    assert p["PISTON_FAULT"]
    assert float(p["PISTON_POS"]) == pytest.approx(x - 50.0 ** 2 / (2 * 10000.0), abs=EULER)
    p.step(1.0)  # still commanded a second after the trip
    assert "moved_tripped" in [e.kind for e in p.drain_events()]
