"""bottle-reject's own check: a fallen bottle swept off passes; a push at a fallen bottle that
swept nothing off is reported at that push, with its length; no push at all is reported
plainly (hand-made traces; the lab's mistakes are graded by tests/grade/test_grade_labs.py)."""

from __future__ import annotations

import numpy as np

from plclab.trace.events import Event

from .lab_modules import lab_checks
from .test_labs16_new_labs import _pulses, _trace


def _run(push_s: float | None, swept: bool):
    t = np.arange(0.0, 10.0, 0.01)
    fallen = _pulses(t, [3.0], 0.6)          # a fallen bottle in front of the eyes: X2 only
    valve = _pulses(t, [3.03], push_s) if push_s else np.zeros(len(t), dtype=bool)
    events = [Event(3.2, "bottle_rejected", "conveyor", "b1", {"fallen": True})] if swept else []
    return _trace(t, events, X1=np.zeros(len(t), dtype=bool), X2=fallen, REJECT=valve,
                  **{"%QX0.1": valve, "CYL_EXTENDED": np.zeros(len(t), dtype=bool),
                     "CONVEYOR": np.ones(len(t), dtype=bool)})


def test_a_swept_fallen_bottle_passes():
    ok, msg, *_ = lab_checks("bottle-reject").pushes_off(_run(0.3, swept=True))
    assert ok, msg


def test_a_short_push_is_reported_at_the_push_with_its_length():
    ok, msg, t_fail, *_ = lab_checks("bottle-reject").pushes_off(_run(0.05, swept=False))
    assert not ok
    assert "at t = 3.03 s, lasted 50 ms" in msg
    assert abs(t_fail - 3.43) < 0.02


def test_no_push_at_all_is_reported_at_the_end():
    ok, msg, t_fail, *_ = lab_checks("bottle-reject").pushes_off(_run(None, swept=False))
    assert not ok and "0 fallen bottle(s) pushed off, 1 expected" in msg
    assert t_fail == 10.0
