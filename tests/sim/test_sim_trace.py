"""Trace helpers on hand-made traces with known answers; .npz round trip; CSV export."""

from __future__ import annotations

import csv
import json

import numpy as np
import pytest

from plclab.errors import PlcError
from plclab.trace import Event, Trace


def square(period_on: int, period_off: int, n: int, dt: float = 0.1) -> Trace:
    """A BOOL that is on for period_on rows, off for period_off rows, repeated."""
    x = np.array([(i % (period_on + period_off)) < period_on for i in range(n)])
    return Trace(np.arange(n) * dt, {"Q": x}, meta={"period": dt})


def test_value_at_is_sample_and_hold():
    tr = Trace([0.0, 1.0, 2.0], {"A": np.array([1.0, 2.0, 3.0]),
                                 "B": np.array([False, True, False])})
    assert tr.value_at("A", -5.0) == 1.0
    assert tr.value_at("A", 0.0) == 1.0
    assert tr.value_at("A", 0.999) == 1.0
    assert tr.value_at("A", 1.0) == 2.0
    assert tr.value_at("A", 99.0) == 3.0
    assert tr.value_at("B", 1.5) is True
    assert isinstance(tr.value_at("A", 1.0), float)


def test_time_in_band_with_hold_intervals_and_window():
    tr = Trace([0.0, 1.0, 2.0, 3.0], {"T": np.array([10.0, 20.0, 30.0, 20.0])},
               meta={"t_end": 4.0})
    assert tr.time_in_band("T", 15, 25) == 2.0  # [1,2) and [3,4)
    assert tr.time_in_band("T", 15, 25, t0=0.5, t1=3.5) == 1.5
    assert tr.time_in_band("T", 0, 100) == 4.0
    assert tr.time_in_band("T", 15, 25, fraction=True) == 0.5
    assert tr.time_in_band("T", 40, 50) == 0.0
    assert tr.t_end == 4.0


def test_t_end_defaults_to_last_row_plus_period():
    tr = Trace(np.arange(10) * 0.5, {"X": np.zeros(10)})
    assert tr.period == 0.5 and tr.t_end == 5.0


def test_rise_time_on_a_ramp_and_a_falling_step():
    t = np.arange(0.0, 20.0, 0.5)
    up = np.clip(t - 5.0, 0.0, 10.0)  # 0 until 5 s, 10 from 15 s
    tr = Trace(t, {"Y": up, "D": 10.0 - up})
    assert tr.rise_time("Y") == pytest.approx(8.0)  # 10 % = 1 at 6 s, 90 % = 9 at 14 s
    assert tr.rise_time("Y", low=0.05, high=0.95) == pytest.approx(9.0)
    assert tr.rise_time("D") == pytest.approx(8.0)  # falling step works the same
    assert tr.rise_time("Y", t1=7.0, final=10.0) is None  # never gets to 90 % in the window
    flat = Trace(t, {"F": np.ones_like(t)})
    assert flat.rise_time("F") is None


def test_rise_time_interpolates_between_rows():
    tr = Trace([0.0, 1.0, 2.0], {"Y": np.array([0.0, 0.0, 10.0])})
    # 10 % (1.0) is crossed at 1.1 s, 90 % (9.0) at 1.9 s
    assert tr.rise_time("Y") == pytest.approx(0.8)


def test_settling_time_and_overshoot_of_a_second_order_response():
    t = np.arange(0.0, 10.0, 1.0)
    y = np.array([0.0, 5.0, 12.0, 9.0, 10.5, 10.1, 9.95, 10.0, 10.0, 10.0])
    tr = Trace(t, {"Y": y})
    assert tr.settling_time("Y", band=0.5) == 4.0
    assert tr.settling_time("Y", band=0.08) == 6.0  # 9.95 is 0.05 away: inside
    assert tr.settling_time("Y", band=0.01) == 7.0
    assert tr.settling_time("Y", tol=0.02) == 5.0  # 2 % of the 10 step = 0.2: 10.5 is out
    assert tr.settling_time("Y", band=0.5, t0=1.0) == 3.0  # relative to t0
    assert tr.overshoot("Y") == pytest.approx(0.2)
    never = Trace(t, {"Y": np.arange(10.0)})
    assert never.settling_time("Y", band=0.1, final=100.0) is None
    assert never.overshoot("Y") == 0.0
    down = Trace(t, {"Y": 10.0 - y})  # mirrored: undershoot below 0
    assert down.overshoot("Y") == pytest.approx(0.2)
    assert Trace(t, {"Y": np.ones(10)}).overshoot("Y") is None


def test_switchings_min_dwell_and_chatter():
    tr = square(3, 7, 100)  # on 0.3 s, off 0.7 s, 10 cycles
    # falling edges at 0.3, 1.3, ... 9.3 (10) and rising at 1.0, 2.0, ... 9.0 (9)
    assert tr.switchings("Q") == 19
    assert tr.switchings("Q", t0=0.0, t1=1.0) == 2  # 0.3 off, 1.0 on
    assert tr.switchings("Q", t0=1.0, t1=1.0) == 0
    mon, moff = tr.min_dwell("Q")
    assert mon == pytest.approx(0.3) and moff == pytest.approx(0.7)
    # three changes fit in every second (0.3, 1.0, 1.3), four never do
    assert tr.chatter_episodes("Q", min_toggles=3, window=1.0) == [(pytest.approx(0.3), pytest.approx(9.3), 19)]
    assert tr.chatter_episodes("Q", min_toggles=4, window=1.0) == []
    calm = square(50, 50, 300)
    assert calm.chatter_episodes("Q", 3, 1.0) == []
    assert calm.min_dwell("Q") == (pytest.approx(5.0), pytest.approx(5.0))
    assert Trace([0.0, 1.0], {"Q": np.array([True, True])}).min_dwell("Q") == (None, None)


def test_chatter_episodes_are_separate_and_merged():
    x = np.zeros(200, dtype=bool)
    x[10:20:2] = True  # 10 changes from 1.0 s to 1.9 s
    x[150:156:2] = True  # 6 changes from 15.0 s to 15.5 s
    x[100] = True  # a single pulse: 2 changes
    tr = Trace(np.arange(200) * 0.1, {"K": x})
    eps = tr.chatter_episodes("K", min_toggles=5, window=1.0)
    assert eps == [(pytest.approx(1.0), pytest.approx(1.9), 10),
                   (pytest.approx(15.0), pytest.approx(15.5), 6)]


def test_first_time_with_expressions_and_callables():
    t = np.arange(6) * 1.0
    tr = Trace(t, {"L": np.array([0.0, 0.5, 1.0, 1.5, 2.0, 2.5]),
                   "P": np.array([True, True, False, False, True, True]),
                   "%QX0.0": np.array([False, False, False, True, True, True])})
    assert tr.first_time("L > 1.2") == 3.0
    assert tr.first_time("L > 0.2 and not P") == 2.0
    assert tr.first_time("L >= 1 AND P") == 4.0  # ST spelling
    assert tr.first_time("0.4 <= L <= 0.6") == 1.0
    assert tr.first_time("P", t0=1.5) == 4.0
    assert tr.first_time("t >= 2 and abs(L - 2) < 0.1") == 4.0
    assert tr.first_time("%QX0.0") == 3.0
    assert tr.first_time("L > 99") is None
    assert tr.first_time(lambda tr: tr["L"] * 2 > 3) == 4.0
    with pytest.raises(PlcError) as e:
        tr.first_time("NOPE > 1")
    assert e.value.code == "PLC4021"
    with pytest.raises(PlcError) as e:
        tr.first_time("L > ")
    assert e.value.code == "PLC4013"


def test_events_of_and_counts():
    ev = [Event(1.0, "overflow", "tank", "over"), Event(2.0, "relay", "%QX0.0", "closed"),
          Event(3.0, "overflow", "tank", "over again", {"volume": 0.5})]
    tr = Trace([0.0], {"X": np.zeros(1)}, events=ev)
    assert [e.time for e in tr.events_of("overflow")] == [1.0, 3.0]
    assert tr.events_of("relay", source="%QX0.0")[0].message == "closed"
    assert tr.events_of(t0=1.5, t1=2.5) == [ev[1]]
    assert tr.event_counts() == {"overflow": (2, 1.0), "relay": (1, 2.0)}
    t, kind, source, msg = tr.events[2]
    assert (t, kind, source, msg) == (3.0, "overflow", "tank", "over again")
    assert tr.events[2].data == {"volume": 0.5}


def test_names_resolution_and_unknown_column():
    tr = Trace([0.0, 1.0], {"LS1": np.array([0, 1], bool), "plc:LS1": np.array([1, 1], bool),
                            "snapshot:volume": np.array([1.0, 2.0])})
    assert tr["LS1"][0] == False  # noqa: E712 - numpy bool
    assert tr["snapshot:volume"][1] == 2.0 and tr["volume"][1] == 2.0
    assert tr["ls1"][0] == False  # noqa: E712 - case-insensitive
    assert "volume" in tr and "nothing" not in tr
    with pytest.raises(PlcError) as e:
        tr["LS3"]
    assert e.value.code == "PLC4021" and "LS1" in e.value.message


def test_window_cuts_rows_events_and_edges():
    ev = [Event(0.5, "a", "s", "m"), Event(5.5, "b", "s", "m")]
    tr = Trace(np.arange(10) * 1.0, {"X": np.arange(10.0)}, events=ev,
               edges={"%IX0.0.raw": (np.array([0.2, 4.2, 7.7]), np.array([True, False, True]))})
    w = tr.window(4.0, 6.0)
    assert list(w.time) == [4.0, 5.0, 6.0]
    assert [e.kind for e in w.events] == ["b"]
    assert list(w.edges["%IX0.0.raw"][0]) == [4.2]


def make_rich_trace() -> Trace:
    n = 50
    t = np.arange(n) * 0.01
    ev = [Event(0.1, "overflow", "tank", "the level reached the rim", {"volume": 1.5}),
          Event(0.2, "relay", "%QX0.0", "relay closed, \"quoted\", comma")]
    return Trace(t, {"LEVEL": np.linspace(0, 1, n), "PUMP": np.arange(n) % 7 < 3,
                     "%IW64": np.arange(n, dtype=np.int64) * 1000 - 4864,
                     "snapshot:x": np.full(n, np.nan)},
                 meta={"plant": "tank", "period": 0.01, "io": [{"plc": "%IW64"}]},
                 events=ev, wall={"scan_s": np.full(n, 1e-6), "run_s": 0.5},
                 edges={"%IX0.0.raw": (np.array([0.001, 0.0015]), np.array([True, False]))})


def test_save_load_round_trip(tmp_path):
    tr = make_rich_trace()
    path = tmp_path / "run.npz"
    tr.save(path)
    back = Trace.load(path)
    assert back.equals(tr) and tr.equals(back)
    assert back.kinds == {"LEVEL": "float", "PUMP": "bool", "%IW64": "int",
                          "snapshot:x": "float"}
    assert back["PUMP"].dtype == bool and back["%IW64"].dtype == np.int64
    assert back.meta["plant"] == "tank" and back.meta["io"] == [{"plc": "%IW64"}]
    assert back.events[0].data == {"volume": 1.5}
    assert back.events == tr.events
    assert back.wall["run_s"] == 0.5 and back.wall["scan_s"].shape == (50,)
    assert list(back.edges["%IX0.0.raw"][0]) == [0.001, 0.0015]
    # the events are stored as a JSON string array, no pickle
    with np.load(path, allow_pickle=False) as z:
        items = [json.loads(s) for s in z["events"].tolist()]
    assert items[1][:4] == [0.2, "relay", "%QX0.0", "relay closed, \"quoted\", comma"]


def test_equals_ignores_the_wall_clock_but_not_data():
    a = make_rich_trace()
    b = make_rich_trace()
    b.wall["scan_s"] = b.wall["scan_s"] * 3
    assert a.equals(b)
    b.columns["LEVEL"] = b.columns["LEVEL"].copy()
    b.columns["LEVEL"][3] += 1e-12
    assert not a.equals(b)
    c = make_rich_trace()
    c.events.append(Event(0.3, "x", "y", "z"))
    assert not a.equals(c)


def test_load_errors(tmp_path):
    with pytest.raises(PlcError) as e:
        Trace.load(tmp_path / "missing.npz")
    assert e.value.code == "PLC4021"
    other = tmp_path / "other.npz"
    np.savez(other, a=np.zeros(3))
    with pytest.raises(PlcError) as e:
        Trace.load(other)
    assert e.value.code == "PLC4021"
    junk = tmp_path / "junk.npz"
    junk.write_text("not a zip")
    with pytest.raises(PlcError) as e:
        Trace.load(junk)
    assert e.value.code == "PLC4021"


def test_csv_export(tmp_path):
    tr = make_rich_trace()
    path = tmp_path / "run.csv"
    evp = tmp_path / "events.csv"
    tr.to_csv(path, events_path=evp)
    rows = list(csv.reader(path.open()))
    assert rows[0] == ["time", "LEVEL", "PUMP", "%IW64", "snapshot:x"]
    assert len(rows) == 51
    assert rows[1] == ["0.0", "0.0", "1", "-4864", "nan"]
    assert float(rows[-1][1]) == 1.0 and rows[-1][2] in ("0", "1")
    assert float(rows[2][0]) == 0.01
    sub = tmp_path / "sub.csv"
    tr.to_csv(sub, names=["PUMP", "LEVEL"])
    assert next(csv.reader(sub.open())) == ["time", "PUMP", "LEVEL"]
    ev = list(csv.reader(evp.open()))
    assert ev[0] == ["time", "kind", "source", "message"]
    assert ev[2][3] == "relay closed, \"quoted\", comma"


def test_column_length_must_match_time():
    with pytest.raises(PlcError) as e:
        Trace([0.0, 1.0], {"X": np.zeros(3)})
    assert e.value.code == "PLC4021"


def test_edge_series_samples_edges_at_1_ms():
    tr = Trace([0.0, 0.01], {"X": np.zeros(2)},
               edges={"e": (np.array([0.002, 0.003, 0.005]), np.array([True, False, True]))},
               meta={"edge_initial": {"e": False}, "t_end": 0.01})
    t, v = tr.edge_series("e", dt=0.001)
    assert len(t) == 11
    assert list(v[:7]) == [False, False, True, False, False, True, True]
