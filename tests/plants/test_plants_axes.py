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
