"""Bottle conveyor (pymunk): toppling physics, photo-eyes, reject cylinder, filling station."""

from __future__ import annotations

import math

import pytest

pytest.importorskip("pymunk")

from plants import Conveyor  # noqa: E402


def _run(c: Conveyor, seconds: float, plc=None, dt: float = 0.01) -> None:
    for _ in range(int(round(seconds / dt))):
        if plc is not None:
            plc(c)
        c.step(dt)


def _kinds(c: Conveyor) -> list[str]:
    return [e.kind for e in c.drain_events()]


def test_bottle_on_a_stopped_belt_stays_standing() -> None:
    c = Conveyor(feed_pitch=None, knock_rate=0.0)
    c.release_bottle()
    _run(c, 10.0)
    (b,) = c.bottles
    assert b["fallen"] == 0.0
    assert abs(b["angle"]) < 1e-3
    assert b["x"] == pytest.approx(c.x_feed, abs=1e-3)
    assert b["y"] == pytest.approx(c.bottle_height / 2, abs=2e-3)


def test_gentle_ramps_carry_a_standing_bottle() -> None:
    c = Conveyor(feed_pitch=None, knock_rate=0.0)
    c.release_bottle()
    for _ in range(3):
        c["CONVEYOR"] = True
        _run(c, 1.5)
        c["CONVEYOR"] = False
        _run(c, 1.0)
    (b,) = c.bottles
    assert b["fallen"] == 0.0 and abs(b["angle"]) < 0.05
    assert b["x"] > c.x_feed + 1.0
    assert "bottle_toppled" not in _kinds(c)


@pytest.mark.parametrize("abrupt", ["stop", "start"])
def test_abrupt_start_or_stop_topples_a_tall_bottle(abrupt: str) -> None:
    c = Conveyor(
        feed_pitch=None,
        knock_rate=0.0,
        belt_decel=100.0 if abrupt == "stop" else 1.0,
        belt_accel=100.0 if abrupt == "start" else 1.0,
    )
    c.release_bottle()
    c["CONVEYOR"] = True
    _run(c, 2.0)
    if abrupt == "stop":
        c["CONVEYOR"] = False
        _run(c, 2.0)
    (b,) = c.bottles
    assert b["fallen"] == 1.0
    assert abs(math.cos(b["angle"])) < 0.2  # lying on its side
    assert "bottle_toppled" in _kinds(c)


def test_eyes_see_standing_and_fallen_bottles() -> None:
    c = Conveyor(feed_pitch=None, knock_rate=0.0)
    c.release_bottle(x=c.x_eye)
    _run(c, 0.2)
    assert c["X1"] and c["X2"]
    c.reset()
    c.release_bottle(x=c.x_eye, fallen=True)
    _run(c, 0.2)
    assert not c["X1"] and c["X2"]
    c.reset()
    c.release_bottle(x=c.x_eye + 0.2)
    _run(c, 0.2)
    assert not c["X1"] and not c["X2"]


def test_cylinder_end_switches_and_timing() -> None:
    c = Conveyor(feed_pitch=None, extend_time=0.3)
    assert c["CYL_RETRACTED"] and not c["CYL_EXTENDED"]
    c["REJECT"] = True
    _run(c, 0.2)
    assert not c["CYL_RETRACTED"] and not c["CYL_EXTENDED"]
    _run(c, 0.15)
    assert c["CYL_EXTENDED"]
    c["REJECT"] = False
    _run(c, 0.35)
    assert c["CYL_RETRACTED"]


def textbook_reject(c: Conveyor) -> None:
    """Fig. 116: the conveyor runs, REJECT := X2 AND NOT X1."""
    c["CONVEYOR"] = True
    c["REJECT"] = c["X2"] and not c["X1"]


def test_reject_loop_removes_fallen_bottles_only() -> None:
    c = Conveyor(topple_rate=0.3, knock_rate=0.0)
    c.reset(seed=3)
    _run(c, 90.0, textbook_reject)
    n = c.counts
    assert n["fallen_rejected"] >= 5
    assert n["standing_rejected"] == 0
    assert n["fallen_passed"] == 0
    assert n["unfilled_passed"] >= 20
    kinds = _kinds(c)
    assert kinds.count("bottle_rejected") == n["rejected"]
    assert kinds.count("bottle_binned") == n["binned"]


def test_knocked_bottles_are_rejected_too() -> None:
    c = Conveyor(topple_rate=0.0, knock_rate=0.3)
    c.reset(seed=5)
    _run(c, 60.0, textbook_reject)
    n = c.counts
    assert n["toppled"] >= 3
    assert n["fallen_passed"] == 0
    assert n["rejected"] >= n["toppled"] - 1  # at most one still on the way


class FillingPlc:
    """Reject fallen bottles; stop on FILL_EYE, fill to 100 %, go on."""

    def __init__(self) -> None:
        self.state = "run"
        self.prev_eye = False

    def __call__(self, c: Conveyor) -> None:
        eye = c["FILL_EYE"]
        rising = eye and not self.prev_eye
        self.prev_eye = eye
        if self.state == "run" and rising:
            self.state = "settle"
        elif self.state == "settle" and c["BELT_SPEED"] == 0.0:
            self.state = "fill"
        elif self.state == "fill" and c["FILL_LEVEL"] >= 99.0:
            self.state = "run"
        c["CONVEYOR"] = self.state == "run"
        c["FILL_VALVE"] = self.state == "fill" and c["FILL_LEVEL"] < 99.0
        c["REJECT"] = c["X2"] and not c["X1"]


def test_filling_station_loop_produces_good_bottles() -> None:
    c = Conveyor(topple_rate=0.2, knock_rate=0.0)
    c.reset(seed=11)
    plc = FillingPlc()
    _run(c, 120.0, plc)
    n = c.counts
    assert n["good"] >= 8
    assert n["unfilled_passed"] == 0 and n["fallen_passed"] == 0
    assert n["spilled"] == 0 and c.spilled_volume == 0.0
    # every good bottle was filled; a few filled ones are still on their way to the end
    assert n["good"] * 0.99 * c.bottle_capacity <= c.filled_volume
    assert c.filled_volume <= (n["good"] + 4) * c.bottle_capacity


def test_spill_without_a_bottle_and_on_overfill() -> None:
    c = Conveyor(feed_pitch=None)
    c["FILL_VALVE"] = True
    _run(c, 1.0)
    assert c.spilled_volume == pytest.approx(c.fill_flow * 1.0, rel=0.02)
    assert _kinds(c).count("spill") == 1
    c["FILL_VALVE"] = False
    c.release_bottle(x=c.x_fill)
    _run(c, 0.2)
    c["FILL_VALVE"] = True
    _run(c, 6.0)
    assert c["FILL_LEVEL"] == 100.0
    assert "spill" in _kinds(c)
    assert c.counts["spilled"] == 2


def test_fault_cylinder_stuck_lets_fallen_bottles_pass() -> None:
    c = Conveyor(topple_rate=1.0, knock_rate=0.0)
    c.inject("cylinder_stuck")
    _run(c, 20.0, textbook_reject)
    assert c.counts["rejected"] == 0
    assert c.counts["fallen_passed"] >= 1
    assert c["CYL_RETRACTED"]


def test_fault_eye_x1_blocked() -> None:
    c = Conveyor(feed_pitch=None)
    assert not c["X1"]
    c.inject("eye_x1_blocked")
    assert c["X1"]
    c.clear("eye_x1_blocked")
    assert not c["X1"]


def test_fault_knock_topples_the_next_bottle_and_clears_itself() -> None:
    c = Conveyor(topple_rate=0.0, knock_rate=0.0)
    c.inject("knock")
    _run(c, 8.0, lambda cc: cc.write("CONVEYOR", True))
    assert c.counts["toppled"] == 1
    assert "knock" not in c.active_faults
    kinds = _kinds(c)
    assert "bottle_toppled" in kinds and "fault_cleared" in kinds


def test_fault_topple_rate() -> None:
    c = Conveyor(topple_rate=0.0, knock_rate=0.0)
    c.inject("topple_rate", rate=1.0)
    _run(c, 10.0, lambda cc: cc.write("CONVEYOR", True))
    assert all(b["fallen"] == 1.0 for b in c.bottles)
    assert c.counts["released"] >= 5


def test_snapshot_is_columnar() -> None:
    c = Conveyor(feed_pitch=None, max_bottles=4)
    s = c.snapshot()
    assert math.isnan(s["bottle0.x"]) and math.isnan(s["bottle3.angle"])
    c.release_bottle()
    c.release_bottle(x=1.0)
    s2 = c.snapshot()
    assert s2.keys() == s.keys()
    assert s2["bottle0.id"] == 0.0 and s2["bottle1.x"] == pytest.approx(1.0, abs=1e-3)
    assert math.isnan(s2["bottle2.x"])
    for _ in range(2):
        c.release_bottle(x=2.0)
    assert c.release_bottle(x=2.5) == -1  # all slots taken


def test_fallen_bottle_at_the_belt_end_is_binned_as_fallen() -> None:
    c = Conveyor(feed_pitch=None)
    c.release_bottle(x=c.belt_length - 0.5, fallen=True)
    c["CONVEYOR"] = True
    _run(c, 4.0)
    assert c.counts["fallen_passed"] == 1 and c.counts["binned"] == 1
    assert c.bottles == []
