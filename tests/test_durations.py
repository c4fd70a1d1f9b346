"""One duration parser (plclab/durations.py) for ST literals, STRING_TO_TIME, the Plc API, the
command line and the simulation's files: the forms each mode accepts and refuses."""

from __future__ import annotations

import datetime as dt

import pytest

import plclab
from plclab.durations import OVERFLOW, parse_duration
from plclab.errors import PlcError
from plclab.runtime.plc import to_ns
from plclab.sim.durations import parse_ns

S, MS, MIN, H, D = 10**9, 10**6, 60 * 10**9, 3600 * 10**9, 86400 * 10**9


@pytest.mark.parametrize("text,ns", [
    ("1h2m3s4ms", H + 2 * MIN + 3 * S + 4 * MS), ("2s_200ms", 2200 * MS), ("-5s", -5 * S),
    ("+5s", 5 * S), ("1.5s", 1500 * MS), ("1D", D), ("10us", 10_000), ("7ns", 7),
    ("1_000ms", S), ("0.5m", 30 * S),
])
def test_iec_literal_bodies(text, ns):
    assert parse_duration(text, iec=True) == ns
    assert parse_duration(text) == ns  # the default mode accepts every IEC form


@pytest.mark.parametrize("text", ["", "1min", "1 s", "90", "1e3ms", "5parsecs", "1h-", "s",
                                  "1.s", "1µs", "--5s", "1hour"])
def test_iec_refuses_what_st_does_not_allow(text):
    assert parse_duration(text, iec=True) is None


@pytest.mark.parametrize("value,ns", [
    ("10min", 10 * MIN), ("1 h 30 min", 90 * MIN), ("90 min", 90 * MIN), ("T#1m30s", 90 * S),
    ("t#10ms", 10 * MS), ("LTIME#1d", D), ("TIME#2h", 2 * H), ("5400", 5400 * S), ("1.5", 1500 * MS),
    ("1e3ms", S), ("2 days", 2 * D), ("3 sec", 3 * S), ("250 msec", 250 * MS), ("5µs", 5000),
    (0.01, 10 * MS), (2, 2 * S), (dt.timedelta(minutes=1), MIN),
])
def test_durations_for_people(value, ns):
    assert parse_duration(value) == ns


@pytest.mark.parametrize("value", ["x", "10 parsecs", "1 2s", "1h-", True, None, float("nan"),
                                   [1], "T#"])
def test_not_durations(value):
    assert parse_duration(value) is None


def test_far_beyond_any_duration_is_the_overflow_marker():
    assert parse_duration("9" * 40 + "s", iec=True) == OVERFLOW
    assert parse_duration("-" + "9" * 40 + "d", iec=True) == -OVERFLOW
    assert parse_duration("1e400") == OVERFLOW and parse_duration("1e300s") == OVERFLOW


def test_1min_means_the_same_in_the_plc_api_and_the_simulation():
    """The inconsistency of issue 12: '1min' worked in sim files, not in Plc(cycle_time=...)."""
    assert to_ns("1min") == parse_ns("1min") == MIN
    plc = plclab.loads("PROGRAM P VAR n : INT; END_VAR n := n + 1; END_PROGRAM",
                       cycle_time="100ms")
    plc.advance("1min")
    assert plc["n"] == 600
    assert plclab.loads("PROGRAM P VAR n : INT; END_VAR END_PROGRAM",
                        cycle_time="1 min").cycle_ns == MIN


def test_callers_keep_their_codes_and_ranges():
    with pytest.raises(PlcError) as e:
        to_ns("fast")
    assert e.value.code == "PLC3002"
    with pytest.raises(PlcError) as e:
        to_ns(float("inf"))
    assert e.value.code == "PLC3002"
    for bad in ("-5s", "400d", "soon"):
        with pytest.raises(PlcError) as e:
            parse_ns(bad)
        assert e.value.code == "PLC4012"


def test_st_literals_and_string_to_time_stay_iec():
    plc = plclab.loads("PROGRAM P VAR t, u, v : TIME; END_VAR t := T#1m30s; "
                       "u := STRING_TO_TIME('T#2s_500ms'); v := STRING_TO_TIME('1min'); "
                       "END_PROGRAM")
    plc.scan()
    assert plc["t"] == 90_000 and plc["u"] == 2500 and plc["v"] == 0
    with pytest.raises(PlcError) as e:
        plclab.loads("PROGRAM P VAR t : TIME; END_VAR t := T#1min; END_PROGRAM")
    assert e.value.code == "PLC0005"
