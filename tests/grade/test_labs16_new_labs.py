"""The labs of issue 16's "path through the course": bottle-packing (counters), level-4-20ma
(analog, wire break), scan-timing (task periods, reaction time), modbus-operator (networks).
Their own Python checks do what they say on small hand-made traces, the plant additions they
need behave, and each lab is linked from its chapters. (Solutions, mistakes and starters are
graded for every lab by tests/grade/test_grade_labs.py.)"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from plclab.grade.lab import load_lab
from plclab.trace import Trace
from plclab.trace.events import Event

from .lab_modules import lab_checks

ROOT = Path(__file__).resolve().parents[2]
LABS16 = {"bottle-packing": [10], "level-4-20ma": [4], "scan-timing": [2],
          "modbus-operator": [14]}



def _trace(t, events=(), **cols):
    t = np.asarray(t, dtype=float)
    return Trace(t, {k: np.asarray(v) for k, v in cols.items()},
                 meta={"t_end": float(t[-1]) + (t[1] - t[0])}, events=list(events))


def _pulses(t, starts, width):
    x = np.zeros(len(t), dtype=bool)
    for s in starts:
        x |= (t >= s) & (t < s + width)
    return x


@pytest.mark.parametrize("lab_id", sorted(LABS16))
def test_lab_sits_in_its_chapters_with_a_level(lab_id):
    lab = load_lab(lab_id, deep=True)
    assert lab.chapters == LABS16[lab_id]
    assert lab.level in (1, 2, 3)
    assert any(not s.visible for s in lab.scenarios)


# ---------------------------------------------------------------------------- bottle-packing


def _packing(n_bottles, box_after, hold=3.0, belt_during_change=False, mw0=0, mw2=None):
    t = np.arange(0.0, 60.0, 0.01)
    starts = [1.0 + 1.5 * i for i in range(n_bottles)]
    # a box change right after every box_after-th bottle
    changes = [starts[k - 1] + 0.1 for k in range(box_after, n_bottles + 1, box_after)]
    lamp = _pulses(t, changes, hold)
    belt = ~lamp | belt_during_change
    return _trace(t, X1=_pulses(t, starts, 0.3), **{
        "%QX0.2": lamp, "%QX0.0": belt, "%MW0": np.full(len(t), mw0),
        "%MW2": np.full(len(t), len(changes) if mw2 is None else mw2)})


def test_boxes_of_six_pass_and_boxes_of_five_fail():
    ck = lab_checks("bottle-packing")
    ok, msg, *_ = ck.boxes_of(_packing(15, 6), size=6, boxes=2)
    assert ok, msg
    ok, msg, *_ = ck.boxes_of(_packing(15, 5), size=6, boxes=2)
    assert not ok and "after 5 bottle(s), not 6" in msg


def test_a_box_that_never_closes_fails():
    ck = lab_checks("bottle-packing")
    ok, msg, *_ = ck.boxes_of(_packing(15, 20), size=6, boxes=2)
    assert not ok and "BOX_FULL did not light" in msg


def test_box_change_length_and_belt():
    ck = lab_checks("bottle-packing")
    assert ck.box_change(_packing(15, 6), hold=3.0, tol=0.3)[0]
    assert not ck.box_change(_packing(15, 6, hold=1.0), hold=3.0, tol=0.3)[0]
    ok, msg, *_ = ck.box_change(_packing(15, 6, belt_during_change=True), hold=3.0)
    assert not ok and "belt runs" in msg


def test_open_box_and_box_counters():
    ck = lab_checks("bottle-packing")
    assert ck.in_box(_packing(15, 6, mw0=3), size=6)[0]
    assert not ck.in_box(_packing(15, 6, mw0=15), size=6)[0]
    assert ck.boxes_counted(_packing(15, 6))[0]
    assert not ck.boxes_counted(_packing(15, 6, mw2=0))[0]


# ---------------------------------------------------------------------------- level-4-20ma


def test_lamp_and_pump_during_loop_failures():
    ck = lab_checks("level-4-20ma")
    t = np.arange(0.0, 100.0, 0.1)
    lamp = (t >= 10) & (t < 30)
    tr = _trace(t, **{"%QX0.1": lamp, "PUMP": ~lamp})
    assert ck.lamp_during(tr, windows=[[10.5, 29.9]])[0]
    assert ck.off_during(tr, signal="PUMP", windows=[[10.5, 29.9]])[0]
    ok, msg, t_fail, _ = ck.lamp_during(tr, windows=[[10.5, 29.9], [50.0, 60.0]])
    assert not ok and t_fail == pytest.approx(50.0)
    assert not ck.off_during(tr, signal="PUMP", windows=[[40.0, 45.0]])[0]


def test_tank_transmitter_fail_drives_the_ne43_failure_current():
    from plants import get_plant

    tank = get_plant("tank", level0=1.0)
    tank.step(0.1)
    assert tank.read("LEVEL_MA") == pytest.approx(12.0, abs=0.05)
    tank.inject("transmitter_fail")
    tank.step(0.1)
    assert tank.read("LEVEL_MA") == pytest.approx(3.4)
    tank.clear("transmitter_fail")
    tank.inject("transmitter_fail", ma=21.5)
    tank.step(0.1)
    assert tank.read("LEVEL_MA") == pytest.approx(21.5)
    tank.clear("transmitter_fail")
    tank.step(0.1)
    assert tank.read("LEVEL_MA") == pytest.approx(4.0 + 16.0 * tank.read("LEVEL") / 2.0)


@pytest.mark.parametrize("plant,lamp", [("tank", "FAULT_LAMP"), ("conveyor", "BOX_LAMP"),
                                        ("motor", "HEARTBEAT")])
def test_panel_lamps_are_written_by_the_plc_and_only_shown(plant, lamp):
    from plants import get_plant

    p = get_plant(plant)
    assert p.signals[lamp].kind == "lamp"
    p.write(lamp, True)
    p.step(0.01)
    assert p.read(lamp) is True


# ---------------------------------------------------------------------------- scan-timing


def _timing(reaction_ms_reported):
    t = np.arange(0.0, 3.0, 0.01)
    start = _pulses(t, [0.5], 0.2)
    run = t >= 0.55
    return _trace(t, START=start, RUN=run, **{"%MW4": np.where(t >= 0.6,
                                                                reaction_ms_reported, 0)})


def test_reaction_is_compared_with_the_plant_clock():
    ck = lab_checks("scan-timing")
    assert ck.reaction(_timing(50), tol_ms=15)[0]
    ok, msg, *_ = ck.reaction(_timing(0), tol_ms=15)
    assert not ok and "took 50 ms" in msg
    t = np.arange(0.0, 1.0, 0.01)
    never = _trace(t, START=np.zeros(len(t), bool), RUN=np.zeros(len(t), bool),
                   **{"%MW4": np.zeros(len(t))})
    assert not ck.reaction(never)[0]


# ---------------------------------------------------------------------------- modbus-operator


def _station(status_fn, pump_fn, cmd_col=None, level=None):
    t = np.arange(0.0, 100.0, 0.05)
    ev = [Event(1.0, "scenario", "%MW2", "var %MW2 := 1000"),
          Event(2.0, "scenario", "%MW0", "var %MW0 := 1"),
          Event(60.0, "scenario", "%MW0", "var %MW0 := 2")]
    pump = pump_fn(t)
    return _trace(t, events=ev, **{
        "%QX0.0": pump, "%MW20": status_fn(t, pump),
        "%MW0": np.zeros(len(t)) if cmd_col is None else cmd_col(t),
        "LEVEL": np.full(len(t), 1.0) if level is None else level(t)})


def _good_status(t, pump):
    return ((t >= 2.0) & (t < 60.0)).astype(int) + 2 * pump.astype(int)


def _pump(t):
    return (t >= 2.02) & (t < 30.0)


def test_station_writes_are_read_back_from_the_scenario_events():
    ck = lab_checks("modbus-operator")
    tr = _station(_good_status, _pump)
    assert ck.writes(tr, "%MW0") == [(2.0, 1), (60.0, 2)]
    assert ck.running_periods(tr) == [(2.0, 60.0)]


def test_acknowledgement_status_and_stop():
    ck = lab_checks("modbus-operator")
    good = _station(_good_status, _pump)
    assert ck.acknowledged(good)[0]
    assert ck.status_bits(good)[0]
    assert ck.stops(good)[0]
    assert ck.starts(good)[0]
    stuck = _station(_good_status, _pump, cmd_col=lambda t: np.where(t >= 2.0, 1, 0))
    assert not ck.acknowledged(stuck)[0]
    swapped = _station(lambda t, p: 2 * ((t >= 2.0) & (t < 60.0)) + p.astype(int), _pump)
    ok, msg, *_ = ck.status_bits(swapped)
    assert not ok and "bit 0 (running)" in msg
    runs_on = _station(_good_status, lambda t: t >= 2.02)
    assert not ck.stops(runs_on)[0]


def test_follows_and_refused_read_the_accepted_set_point():
    ck = lab_checks("modbus-operator")
    near = _station(_good_status, _pump, level=lambda t: np.full(len(t), 1.05))
    assert ck.follows(near, band=0.15, settle=20.0)[0]
    far = _station(_good_status, _pump, level=lambda t: np.full(len(t), 1.5))
    assert not ck.follows(far, band=0.15, settle=20.0)[0]
    bit2 = _station(lambda t, p: _good_status(t, p) + 4, _pump)
    assert ck.refused(bit2, windows=[[10.0, 50.0]])[0]
    assert not ck.refused(near, windows=[[10.0, 50.0]])[0]
