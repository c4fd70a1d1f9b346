"""water-boiler's own check (labs/water-boiler/checks.py) on hand-made traces: the fill valve
must switch at the band's limits; one switching point, a band too narrow, and a valve that
never moves fail."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from plclab.trace import Trace

from .lab_modules import lab_checks

ROOT = Path(__file__).resolve().parents[2]


def _switch_points():
    return lab_checks("water-boiler").switch_points


CHECK = _switch_points()
T = np.arange(0.0, 600.0, 0.1)


def _run(open_at, close_at, start=0.6):
    """A tank drawn at 1 mm/s and filled at 24 mm/s by a valve switched at the two levels."""
    level, valve = start, False
    lv, vv = [], []
    for _ in T:
        if level < open_at:
            valve = True
        elif level > close_at:
            valve = False
        level += (0.024 if valve else 0.0) * 0.1 - 0.001 * 0.1
        lv.append(level)
        vv.append(valve)
    return Trace(T, {"LEVEL": np.array(lv), "FILL_VALVE": np.array(vv)},
                 meta={"t_end": float(T[-1]) + 0.1})


def test_a_valve_switched_at_the_band_limits_passes():
    ok, msg = CHECK(_run(0.5, 0.7))[:2]
    assert ok and "opened" in msg


def test_one_switching_point_fails_at_its_first_opening():
    ok, msg, tf, sig = CHECK(_run(0.6, 0.6))
    assert not ok and "opened" in msg and "below 0.53" in msg and sig == ["LEVEL", "FILL_VALVE"]


def test_a_band_too_narrow_fails_at_the_closing():
    ok, msg = CHECK(_run(0.52, 0.62))[:2]
    assert not ok and "closed" in msg and "above 0.67" in msg


def test_a_valve_that_never_moves_proves_nothing():
    tr = Trace(T, {"LEVEL": np.full(len(T), 0.6), "FILL_VALVE": np.zeros(len(T), bool)},
               meta={"t_end": float(T[-1]) + 0.1})
    ok, msg = CHECK(tr)[:2]
    assert not ok and "0 and closed 0" in msg
