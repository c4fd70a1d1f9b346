"""The lab criteria on the alarm log: alarm_within and ack_before_restart."""

from __future__ import annotations

import numpy as np
import pytest

from plclab.errors import PlcError
from plclab.grade.criteria import run_check
from plclab.trace import Trace
from plclab.trace.events import Event


def trace(low, heater, log):
    t = np.arange(len(low), dtype=float)
    events = [Event(tt, "alarm", "NO_WATER", f"{st}: no water", {"state": st, "class": "error"})
              for tt, st in log]
    return Trace(t, {"LOW": np.array(low, bool), "HEATER": np.array(heater, bool)},
                 meta={"t_end": float(len(low)), "alarms": [{"id": "NO_WATER"}]},
                 events=events)


LOW = [0, 0, 1, 1, 1, 0, 0, 0, 0, 0]


@pytest.mark.parametrize("log, time, passed", [
    ([(2, "I")], 1, True),
    ([(3, "I")], 1, True),
    ([(4, "I")], 1, False),  # 2 s late
    ([], 1, False),
    # pending since before the cause (raised at start, never cleared): no answer to it
    ([(0, "I")], 1, False),
    ([(0, "I"), (1, "IO")], 1, False),  # gone before the trigger: not pending
    ([(1, "I")], 1, False),  # raised a second before the cause: not an answer either
])
def test_alarm_within(log, time, passed):
    v = run_check("alarm_within", trace(LOW, [0] * 10, log),
                  {"alarm": "NO_WATER", "trigger": "LOW", "time": time})
    assert v.passed is passed, v.message
    if not passed and len(log) == 1 and log[0][0] < 2:
        assert "already pending since" in v.message


# the cause comes twice: at 1 s and, after a short gap, at 5 s
TWICE = [0, 1, 1, 0, 0, 1, 1, 0, 0, 0]


@pytest.mark.parametrize("log, passed", [
    ([(1, "I")], True),  # raised by the first occurrence and still pending at the second
    ([(1, "I"), (3, "IO"), (5, "I")], True),  # cleared in between, raised again
    ([(1, "I"), (3, "IO")], False),  # cleared in between and not raised again
    ([(0, "I")], False),  # on before the first occurrence: never an answer
])
def test_alarm_within_pending_from_an_earlier_cause(log, passed):
    v = run_check("alarm_within", trace(TWICE, [0] * 10, log),
                  {"alarm": "NO_WATER", "trigger": "LOW", "time": 1})
    assert v.passed is passed, v.message


@pytest.mark.parametrize("heater, log, passed", [
    ([1, 1, 0, 0, 0, 0, 0, 0, 1, 1], [(2, "I"), (5, "IO"), (7, "IOA")], True),
    ([1, 1, 0, 0, 0, 0, 1, 1, 1, 1], [(2, "I"), (5, "IO"), (7, "IOA")], False),  # at 6 s
    ([1, 1, 0, 0, 0, 0, 1, 1, 1, 1], [(2, "I"), (5, "IO")], False),  # never acknowledged
    ([1, 1, 0, 1, 1, 1, 1, 1, 1, 1], [(2, "I"), (3, "IA")], True),  # ack, then restart
    ([1, 1, 1, 1, 1, 1, 1, 1, 1, 1], [(2, "I"), (5, "IO"), (9, "IOA")], False),  # never off
])
def test_ack_before_restart(heater, log, passed):
    v = run_check("ack_before_restart", trace(LOW, heater, log),
                  {"alarm": "NO_WATER", "restart": "HEATER"})
    assert v.passed is passed, v.message
    if not passed:
        assert v.t_fail == (4.0 if heater[3] else 6.0)  # 1 s allowed to switch off


def test_an_alarm_that_never_came_and_an_unknown_alarm():
    tr = trace(LOW, [0] * 10, [])
    assert not run_check("ack_before_restart", tr, {"alarm": "NO_WATER",
                                                    "restart": "HEATER"}).passed
    assert run_check("ack_before_restart", tr, {"alarm": "NO_WATER", "restart": "HEATER",
                                                "need_alarm": False}).passed
    with pytest.raises(PlcError) as e:
        run_check("alarm_within", tr, {"alarm": "NO_WTR", "trigger": "LOW", "time": 1})
    assert e.value.code == "PLC6021"


@pytest.mark.parametrize("fills, lo, hi, need, passed", [
    ([0.45, 0.452, 0.449], 0.43, 0.47, 2, True),
    ([0.45, 0.40], 0.43, 0.47, 1, False),  # one bottle short
    ([0.45], 0.43, 0.47, 2, False),  # too few bottles
])
def test_event_data_checks_every_matching_event(fills, lo, hi, need, passed):
    events = [Event(float(i), "bottle_binned", "conveyor", f"bottle {i}", {"fill": f})
              for i, f in enumerate(fills)]
    tr = Trace(np.arange(5.0), {"X": np.zeros(5)}, meta={"t_end": 5.0}, events=events)
    v = run_check("event_data", tr, {"event": "bottle_binned", "field": "fill", "lo": lo,
                                     "hi": hi, "min": need})
    assert v.passed is passed, v.message
