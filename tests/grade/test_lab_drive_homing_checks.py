"""The Python checks of labs/drive-homing on hand-made traces: each passes a right trace and
fails the wrong ones it exists for (READY with an axis out of position or with the alarm, a
move before every drive is home, motion between a fault and RESET + START, a move that is
not stopped 8 s after it began, no new cycle after the last START)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from plclab.trace import Trace

from .lab_modules import lab_checks

ROOT = Path(__file__).resolve().parents[2]
T = np.round(np.arange(0.0, 20.0, 0.01), 2)
AXES = ("BELT", "PISTON", "PUMP")


def _checks():
    return lab_checks("drive-homing")


def _win(a, b):
    return (T >= a) & (T < b)


def _cycle(start=1.0, home=5.0, ready=8.0):
    """Every axis runs home from start to home, then to its work position by ready."""
    cols = {}
    for a, (x0, w) in zip(AXES, ((420.0, 250.0), (130.0, 100.0), (55.0, 40.0)), strict=True):
        pos = np.where(T < start, x0, np.where(T < home, x0 + (1.0 - x0) * (T - start)
                                               / (home - start), 1.0))
        pos = np.where(T < home, pos, np.minimum(1.0 + (w - 1.0) * (T - home) / (ready - 1 - home),
                                                 w))
        cols[f"{a}_POS"] = pos
        cols[f"{a}_HOME"] = (pos >= 0.0) & (pos <= 2.0)
        cols[f"{a}_REV"] = _win(start, home)
        cols[f"{a}_FWD"] = _win(home, ready - 1)
        cols[f"{a}_FAULT"] = np.zeros(len(T), dtype=bool)
    cols["START"] = _win(start, start + 0.3)
    cols["RESET"] = np.zeros(len(T), dtype=bool)
    cols["READY_LAMP"] = T >= ready
    cols["ALARM_LAMP"] = np.zeros(len(T), dtype=bool)
    return cols


def _trace(cols):
    return Trace(T, {k: np.asarray(v) for k, v in cols.items()}, meta={"t_end": 20.01})


def test_ready_only_in_position():
    c = _checks()
    assert c.ready_only_in_position(_trace(_cycle()))[0]
    early = dict(_cycle(), READY_LAMP=T >= 6.0)      # READY while the axes still move
    ok, msg, tf, _ = c.ready_only_in_position(_trace(early))
    assert not ok and "not at its work position" in msg and tf == 6.0
    alarm = dict(_cycle(), ALARM_LAMP=T >= 12.0)
    ok, msg, _, _ = c.ready_only_in_position(_trace(alarm))
    assert not ok and "READY and ALARM" in msg
    assert not c.ready_only_in_position(_trace(dict(_cycle(), READY_LAMP=T < 0)))[0]


def test_moves_after_all_home():
    c = _checks()
    assert c.moves_after_all_home(_trace(_cycle()))[0]
    cols = _cycle()
    cols["PUMP_POS"] = np.where(T < 3.0, cols["PUMP_POS"], 1.0 + 20.0 * (T - 3.0))
    cols["PUMP_POS"] = np.where(T < 2.0, 55.0 - 54.0 * (T - 1.0), cols["PUMP_POS"])
    cols["PUMP_POS"] = np.where(T < 1.0, 55.0, cols["PUMP_POS"])
    cols["PUMP_HOME"] = (cols["PUMP_POS"] >= 0) & (cols["PUMP_POS"] <= 2.0)
    ok, msg, _, _ = c.moves_after_all_home(_trace(cols))
    assert not ok and "the pump moves away from home" in msg


def test_cycle_after_and_stopped_until():
    c = _checks()
    assert c.cycle_after(_trace(_cycle()))[0]
    never_ready = dict(_cycle(), READY_LAMP=T < 0)
    ok, msg, _, _ = c.cycle_after(_trace(never_ready))
    assert not ok and "READY never lights again" in msg
    cols = _cycle()
    cols["PISTON_FAULT"] = _win(10.0, 11.0)
    cols["RESET"] = _win(13.0, 13.3)
    cols["START"] = cols["START"] | _win(12.0, 12.3) | _win(15.0, 15.3)
    cols["BELT_REV"] = _win(1.0, 5.0) | _win(15.01, 17.0)
    assert c.stopped_until(_trace(cols))[0]
    early = dict(cols, BELT_REV=cols["BELT_REV"] | _win(12.01, 12.5))  # START before RESET
    ok, msg, tf, _ = c.stopped_until(_trace(early))
    assert not ok and "BELT_REV" in msg and tf == 12.01
    assert not c.stopped_until(_trace(_cycle()))[0]  # no fault: no proof


def test_move_timeout():
    c = _checks()
    cols = _cycle()
    cols["PUMP_FWD"] = _win(5.0, 13.0)
    cols["ALARM_LAMP"] = T >= 13.0
    cols["READY_LAMP"] = T < 0
    assert c.move_timeout(_trace(cols))[0]
    never = dict(cols, ALARM_LAMP=T < 0)
    ok, msg, _, _ = c.move_timeout(_trace(never))
    assert not ok and "no alarm came 8 s later" in msg
    early = dict(cols, ALARM_LAMP=T >= 10.0)
    ok, msg, _, _ = c.move_timeout(_trace(early))
    assert not ok and "before its 8 s were over" in msg
    runs_on = dict(cols, PUMP_FWD=_win(5.0, 15.0))
    ok, msg, _, _ = c.move_timeout(_trace(runs_on))
    assert not ok and "moves again" in msg
