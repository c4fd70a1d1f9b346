"""The Python checks of labs/press-safety on hand-made traces: each passes a right trace and
fails the wrong ones it exists for (a valve on with the curtain broken at rest or going up, no
return after the field clears, a restart after the E-stop, a dose started by the command that
should only return the piston)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from plclab.trace import Trace

from .lab_modules import lab_checks

ROOT = Path(__file__).resolve().parents[2]
T = np.round(np.arange(0.0, 10.0, 0.01), 2)


def _checks():
    return lab_checks("press-safety")


def _trace(**cols):
    n = len(T)
    full = {k: np.asarray(v) for k, v in cols.items()}
    for k in ("%QX0.0", "%QX0.1", "%IX0.0", "%IX0.1"):
        full.setdefault(k, np.zeros(n, dtype=bool))
    full.setdefault("LIGHT_CURTAIN", np.ones(n, dtype=bool))
    full.setdefault("E_STOP", np.ones(n, dtype=bool))
    full.setdefault("POSITION", np.zeros(n))
    full.setdefault("TOP", full["POSITION"] <= 5.0)
    return Trace(T, full, meta={"t_end": 10.01})


def _win(a, b):
    return (T >= a) & (T < b)


def test_curtain_stops_in_every_phase():
    c = _checks()
    broken = ~_win(3.0, 4.0)
    up = _win(2.0, 3.02) | _win(4.0, 5.0)          # off within a scan: right
    pos = np.where(T < 2.0, 0.0, 40.0)
    assert c.curtain_stops(_trace(LIGHT_CURTAIN=broken, **{"%QX0.1": up}, POSITION=pos))[0]
    late = _win(2.0, 3.5)                           # UP kept on while broken, going up
    ok, msg, tf, _ = c.curtain_stops(_trace(LIGHT_CURTAIN=broken, **{"%QX0.1": late},
                                            POSITION=pos))
    assert not ok and msg.startswith("UP is on") and 3.05 <= tf <= 3.07
    at_rest = _win(3.5, 3.6)                        # a stroke started at rest while broken
    ok, msg, _, _ = c.curtain_stops(_trace(LIGHT_CURTAIN=broken, **{"%QX0.0": at_rest}))
    assert not ok and "DOWN" in msg and "at rest" in msg
    assert not c.curtain_stops(_trace())[0]         # a scenario without a break is no proof


def test_returns_when_clear():
    c = _checks()
    broken = ~_win(3.0, 4.0)
    pos = np.where(T < 2.0, 0.0, np.where(T < 4.2, 40.0, 0.0))
    up = _win(4.1, 4.9)
    assert c.returns_when_clear(_trace(LIGHT_CURTAIN=broken, POSITION=pos,
                                       **{"%QX0.1": up}))[0]
    ok, msg, _, _ = c.returns_when_clear(_trace(LIGHT_CURTAIN=broken, POSITION=pos))
    assert not ok and "UP does not come" in msg
    down = _win(4.05, 4.1)                          # down first, then up: never down
    ok, msg, _, _ = c.returns_when_clear(_trace(LIGHT_CURTAIN=broken, POSITION=pos,
                                                **{"%QX0.1": up, "%QX0.0": down}))
    assert not ok and msg.startswith("DOWN at t = 4.05")


def test_estop_no_restart():
    c = _checks()
    es = ~_win(2.0, 3.0)
    held = _win(1.0, 5.0)                            # hands held through the E-stop
    new_l, new_r = _win(6.0, 9.0), _win(6.2, 9.0)   # a new command after the release
    ret = _win(6.21, 7.0)
    good = {"%IX0.0": held | new_l, "%IX0.1": held | new_r, "%QX0.1": ret}
    assert c.estop_no_restart(_trace(E_STOP=es, **good))[0]
    auto = dict(good, **{"%QX0.1": _win(3.02, 4.0)})  # returns on the release by itself
    ok, msg, tf, _ = c.estop_no_restart(_trace(E_STOP=es, **auto))
    assert not ok and "after the E-stop was released" in msg and tf == 3.02
    dose = dict(good, **{"%QX0.0": _win(7.5, 8.0)})  # the return command also doses
    ok, msg, _, _ = c.estop_no_restart(_trace(E_STOP=es, **dose))
    assert not ok and "only bring the piston back up" in msg
    pressed = dict(good, **{"%QX0.0": _win(1.5, 2.5)})  # DOWN stays on while pressed
    ok, msg, _, _ = c.estop_no_restart(_trace(E_STOP=es, **pressed))
    assert not ok and "while the E-stop is pressed" in msg
