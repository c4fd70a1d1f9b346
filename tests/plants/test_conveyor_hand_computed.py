"""The conveyor's documented numbers against values computed by hand (issue 31 item 5): the belt
ramps at 1 m/s² to 0.4 m/s, a bottle stops v²/(2a) = 8 cm after the contactor drops, a belt
stopped on FILL_EYE leaves the bottle under the nozzle, and the filling conserves volume (what
the valve lets through is in the bottle or spilled, nothing more, nothing less)."""

from __future__ import annotations

import pytest

pytest.importorskip("pymunk")

from plants import Conveyor  # noqa: E402

DT = 0.01


def _run(c: Conveyor, seconds: float) -> None:
    for _ in range(int(round(seconds / DT))):
        c.step(DT)


def test_the_belt_ramps_at_its_acceleration_to_its_speed() -> None:
    c = Conveyor(feed_pitch=None, knock_rate=0.0)
    c["CONVEYOR"] = True
    _run(c, 0.2)
    assert c["BELT_SPEED"] == pytest.approx(1.0 * 0.2, abs=0.011)  # a * t
    _run(c, 0.3)
    assert c["BELT_SPEED"] == pytest.approx(0.4, abs=1e-9)  # capped at belt_speed after 0.4 s
    c["CONVEYOR"] = False
    _run(c, 0.1)
    assert c["BELT_SPEED"] == pytest.approx(0.4 - 1.0 * 0.1, abs=0.011)
    _run(c, 0.4)
    assert c["BELT_SPEED"] == 0.0


def test_a_standing_bottle_rides_at_belt_speed_and_stops_eight_cm_after_the_contactor() -> None:
    c = Conveyor(feed_pitch=None, knock_rate=0.0)
    c.release_bottle()
    _run(c, 0.5)
    c["CONVEYOR"] = True
    _run(c, 1.0)  # 0.4 s of ramp, then steady
    (b,) = c.bottles
    x0 = b["x"]
    _run(c, 1.0)
    (b,) = c.bottles
    assert b["x"] - x0 == pytest.approx(0.4 * 1.0, abs=0.01)  # v * t
    x1 = b["x"]
    c["CONVEYOR"] = False
    _run(c, 1.5)
    (b,) = c.bottles
    assert b["x"] - x1 == pytest.approx(0.4**2 / (2 * 1.0), abs=0.01)  # v² / (2 a) = 0.08 m
    assert b["fallen"] == 0.0


def test_a_belt_stopped_on_the_fill_eye_leaves_the_bottle_under_the_nozzle() -> None:
    c = Conveyor(feed_pitch=None, knock_rate=0.0)
    c.release_bottle(x=c.x_fill - 0.6)
    c["CONVEYOR"] = True
    for _ in range(int(10 / DT)):
        c.step(DT)
        if c["FILL_EYE"]:
            c["CONVEYOR"] = False
            break
    assert c["FILL_EYE"], "the eye saw the bottle"
    _run(c, 1.0)
    (b,) = c.bottles
    assert b["x"] == pytest.approx(c.x_fill, abs=c.nozzle_tolerance)


@pytest.mark.parametrize("seconds", [2.0, 7.0])
def test_filling_conserves_volume(seconds: float) -> None:
    """0.1 l/s for 2 s: 0.2 l in the bottle, nothing spilled; for 7 s: the 0.5 l bottle is full
    and the other 0.2 l are spilled."""
    c = Conveyor(feed_pitch=None, knock_rate=0.0)
    c.release_bottle(x=c.x_fill)
    _run(c, 0.3)
    c["FILL_VALVE"] = True
    _run(c, seconds)
    c["FILL_VALVE"] = False
    through = 0.1 * seconds
    assert c.filled_volume + c.spilled_volume == pytest.approx(through, rel=1e-6)
    assert c.filled_volume == pytest.approx(min(through, 0.5), rel=1e-6)
    assert c["FILL_LEVEL"] == pytest.approx(min(through, 0.5) / 0.5 * 100.0, rel=1e-6)
    assert (c.spilled_volume > 0) == (through > 0.5)
