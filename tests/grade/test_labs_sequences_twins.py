"""The twin reference solutions of the drives and the pedestrian-crossing labs: the program
with objects and the classic one switch the drives alike (a scan apart), the textual and the PLCopen XML chart
switch the lamps alike, and the crossing's request chart remembers a tap."""

import numpy as np
import pytest

from plclab.grade.engine import _simulate, compile_submission, read_submission
from plclab.grade.lab import load_lab


def _trace(lab, name, scenario):
    sources, _ = read_submission(lab.path / "solution" / name)
    compiled, diags, _ = compile_submission(lab, sources)
    assert compiled is not None, diags
    return _simulate(lab, compiled, next(s for s in lab.scenarios if s.name == scenario))


DRIVE_OUTPUTS = ["BELT_FWD", "BELT_REV", "PISTON_FWD", "PISTON_REV", "PUMP_FWD", "PUMP_REV",
                 "READY_LAMP", "ALARM_LAMP"]


def _edges(trace, name):
    v = trace[name].astype(int)
    return trace.time[np.nonzero(np.diff(v))[0] + 1]


@pytest.mark.parametrize("scenario", ["normal", "drive-trip", "home-timeout",
                                      "trip-while-moving"])
def test_drives_with_and_without_objects_switch_alike(scenario):
    """Every output switches as often in both programs and at most two scans apart: the
    object-oriented Axis runs its body before the sequence gives a command, so it answers a
    scan later than the classic block, which gets its commands as inputs of the same call."""
    lab = load_lab("drive-homing")
    oop = _trace(lab, "drives_oop.st", scenario)
    classic = _trace(lab, "drives_classic.st", scenario)
    for name in DRIVE_OUTPUTS:
        a, b = _edges(oop, name), _edges(classic, name)
        assert len(a) == len(b), name
        assert np.all(np.abs(a - b) <= 0.025), (name, a, b)
    assert oop["READY_LAMP"].any() or oop["ALARM_LAMP"].any()


LAMPS = ["CAR_RED", "CAR_YELLOW", "CAR_GREEN", "PED_RED", "PED_GREEN", "WAIT_LAMP"]


@pytest.mark.parametrize("scenario", ["one-request", "slow-walker"])
def test_crossing_text_and_xml_charts_give_identical_lamps(scenario):
    lab = load_lab("pedestrian-crossing")
    text = _trace(lab, "crossing.st", scenario)
    xml = _trace(lab, "crossing.xml", scenario)
    for name in LAMPS:
        assert np.array_equal(text[name], xml[name]), name


def test_a_tap_during_the_minimum_green_is_served_after_it():
    lab = load_lab("pedestrian-crossing")
    tr = _trace(lab, "crossing.st", "one-request")
    t = tr.time
    ped = tr["PED_GREEN"].astype(bool)
    first = float(t[np.argmax(ped)])
    # tap at 5.5 s; 20 s of car green, 3 s yellow, 2 s all red: green at 25 s (a scan later)
    assert 25.0 <= first <= 25.2
    wait = tr["WAIT_LAMP"].astype(bool)
    assert wait[(t > 6.0) & (t < 24.9)].all() and not wait[(t > 25.3) & (t < 40.0)].any()
