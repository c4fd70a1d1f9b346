"""bottle-packing's own check names the cause when the boxes stop coming: a belt that never
runs again after a box change (a seal-in taken from the interlocked output) is told apart from
a line that simply saw too few bottles (hand-made traces; the lab's mistakes are graded by
tests/grade/test_grade_labs.py)."""

from __future__ import annotations

import numpy as np

from .lab_modules import lab_checks
from .test_labs16_new_labs import _pulses, _trace


def _one_box(belt_after_change: bool):
    """Six bottles 1.5 s apart from t = 1 s; the lamp lights 0.1 s after the sixth (8.6 s)
    for 3 s, so the change ends at 11.6 s."""
    t = np.arange(0.0, 30.0, 0.01)
    starts = [1.0 + 1.5 * i for i in range(6)]
    lamp = _pulses(t, [starts[-1] + 0.1], 3.0)
    belt = ~lamp & ((t < starts[-1]) | belt_after_change)
    return _trace(t, X1=_pulses(t, starts, 0.3), **{"%QX0.2": lamp, "%QX0.0": belt,
                                                    "%MW0": np.zeros(len(t))})


def test_a_belt_that_never_restarts_after_the_change_is_named():
    ok, msg, t_fail, *_ = lab_checks("bottle-packing").boxes_of(_one_box(False), size=6, boxes=2)
    assert not ok
    assert "the belt never ran again after the box change that ended at t = 11.60 s" in msg
    assert abs(t_fail - 12.1) < 0.02


def test_too_few_bottles_with_a_running_belt_is_not_blamed_on_the_belt():
    ok, msg, *_ = lab_checks("bottle-packing").boxes_of(_one_box(True), size=6, boxes=2)
    assert not ok and "only 1 box change(s)" in msg
    assert "never ran again" not in msg
