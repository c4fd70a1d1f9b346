"""Alarms: WinCC's state machine against a table of cases, deadband and delay timing,
configuration files, and the alarm log in a simulation's Trace."""

from __future__ import annotations

import pytest

import plclab
from plclab.errors import PlcError
from plclab.process import Alarm, AlarmServer, alarm_log


def run_steps(alarm: Alarm, steps, classes=None):
    """steps: (t, value) evaluates; (t, 'ack') acknowledges. The log as (t, state)."""
    srv = AlarmServer([alarm], **({"classes": classes} if classes else {}))
    for t, what in steps:
        if what == "ack":
            srv.acknowledge(alarm.id, t=t)
        else:
            srv.evaluate(t, lambda tag, v=what: v)
    return [(e.time, e.state) for e in srv.log], srv.state(alarm.id)


BIT_ERR = Alarm("E", "error bit", tag="x", alarm_class="error")
BIT_WARN = Alarm("W", "warning bit", tag="x", alarm_class="warning")

# (name, alarm, steps, expected log, final state): Tables 18 and 19 of the textbook
STATE_CASES = [
    ("warning comes and goes", BIT_WARN, [(0, False), (1, True), (2, False)],
     [(1, "I"), (2, "IO")], ""),
    ("warning needs no acknowledgement", BIT_WARN, [(1, True), (2, "ack"), (3, False)],
     [(1, "I"), (3, "IO")], ""),
    ("error acknowledged while active, then goes: IAO", BIT_ERR,
     [(1, True), (2, "ack"), (3, False)], [(1, "I"), (2, "IA"), (3, "IAO")], ""),
    ("error goes unacknowledged: IO stays pending", BIT_ERR, [(1, True), (2, False)],
     [(1, "I"), (2, "IO")], "IO"),
    ("error acknowledged after it went: IOA", BIT_ERR, [(1, True), (2, False), (5, "ack")],
     [(1, "I"), (2, "IO"), (5, "IOA")], ""),
    ("acknowledged and still active: IA", BIT_ERR, [(1, True), (2, "ack"), (3, True)],
     [(1, "I"), (2, "IA")], "IA"),
    ("a second acknowledgement does nothing", BIT_ERR, [(1, True), (2, "ack"), (3, "ack")],
     [(1, "I"), (2, "IA")], "IA"),
    ("comes again before acknowledged: a new incoming", BIT_ERR,
     [(1, True), (2, False), (3, True)], [(1, "I"), (2, "IO"), (3, "I")], "I"),
    ("nothing without the condition", BIT_ERR, [(0, False), (1, "ack"), (2, False)], [], ""),
    ("bit 3 of a word", Alarm("B", "bit 3", tag="w", bit=3, alarm_class="error"),
     [(0, 0b0100), (1, 0b1000), (2, 0b0111)], [(1, "I"), (2, "IO")], "IO"),
    ("custom class with acknowledgement", Alarm("C", "custom", tag="x", alarm_class="fire"),
     [(1, True), (2, False)], [(1, "I"), (2, "IO")], "IO"),
]


@pytest.mark.parametrize("name, alarm, steps, expected, final", STATE_CASES,
                         ids=[c[0] for c in STATE_CASES])
def test_alarm_states(name, alarm, steps, expected, final):
    from plclab.process.alarms import CLASSES, AlarmClass

    classes = {**CLASSES, "fire": AlarmClass("fire", True, "#ff0000")}
    log, state = run_steps(alarm, steps, classes)
    assert log == [(float(t), s) for t, s in expected]
    assert state == final


# (kind, limit, deadband, values at t=0,1,2,..., times of I and of IO)
LIMIT_CASES = [
    ("H", 90.0, 0.0, [80, 91, 89, 91], [1, 3], [2]),
    ("H", 90.0, 2.0, [80, 91, 89, 91, 87.9], [1], [4]),  # 89 and 91 hover: one alarm
    ("H", 90.0, 2.0, [80, 90, 90.1, 88.0, 87.9], [2], [4]),  # strictly above; back by > 2
    ("HH", 95.0, 1.0, [96, 94.5, 93.9], [0], [2]),
    ("L", 0.5, 0.05, [0.6, 0.49, 0.54, 0.56], [1], [3]),
    ("LL", 0.2, 0.0, [0.3, 0.1, 0.25, 0.1], [1, 3], [2]),
]


@pytest.mark.parametrize("kind, limit, deadband, values, came, went", LIMIT_CASES)
def test_analog_limits_with_deadband(kind, limit, deadband, values, came, went):
    a = Alarm("A", "limit", tag="v", kind=kind, limit=limit, deadband=deadband)
    log, _ = run_steps(a, list(enumerate(values)))
    assert [t for t, s in log if s == "I"] == came
    assert [t for t, s in log if s == "IO"] == went


@pytest.mark.parametrize("mode, values, came, went", [
    ("outgoing", [80, 90.5, 88.5, 87.9], [1], [3]),
    ("incoming", [80, 90.5, 92.1, 89.9], [2], [3]),
    ("both", [80, 91, 92.1, 88.5, 87.9], [2], [4]),
])
def test_deadband_modes(mode, values, came, went):
    a = Alarm("A", "limit", tag="v", kind="H", limit=90.0, deadband=2.0, deadband_mode=mode)
    log, _ = run_steps(a, list(enumerate(values)))
    assert ([t for t, s in log if s == "I"], [t for t, s in log if s == "IO"]) == (came, went)


def test_a_deadband_in_percent_of_the_limit():
    srv = AlarmServer.from_dict({"alarm": [{"id": "T", "text": "hot", "tag": "T", "kind": "H",
                                            "limit": 80.0, "deadband": "5%"}]})
    assert srv.alarms[0].deadband == 4.0


# the delay: the condition must hold `delay` seconds (evaluated every 0.1 s)
DELAY_CASES = [
    (2.0, [(0.0, 10.0)], [2.0]),  # holds from 0 s: comes at 2 s
    (2.0, [(0.0, 1.5), (3.0, 10.0)], [5.0]),  # a 1.5 s spike raises nothing
    (0.0, [(1.0, 1.1)], [1.0]),  # no delay: at once
    (0.5, [(1.0, 1.4), (2.0, 2.6)], [2.5]),  # 0.4 s is too short, 0.6 s is enough
]


@pytest.mark.parametrize("delay, on_windows, came", DELAY_CASES)
def test_delay_timing_on_the_virtual_clock(delay, on_windows, came):
    a = Alarm("D", "delayed", tag="x", delay=delay)
    srv = AlarmServer([a])
    for i in range(0, 101):
        t = i / 10
        on = any(lo - 1e-9 <= t < hi - 1e-9 for lo, hi in on_windows)
        srv.evaluate(t, lambda tag, on=on: on)
    assert [e.time for e in srv.log if e.state == "I"] == pytest.approx(came)


def test_acknowledge_every_pending_alarm_and_scheduled_acks():
    srv = AlarmServer([Alarm("A", "a", tag="a", alarm_class="error"),
                       Alarm("B", "b", tag="b", alarm_class="error"),
                       Alarm("W", "w", tag="a")])
    srv.schedule_ack(2.0, user="night shift")
    for t in range(4):
        srv.evaluate(t, lambda tag: True)
    acks = [(e.id, e.time, e.user) for e in srv.log if e.state == "IA"]
    assert acks == [("A", 2.0, "night shift"), ("B", 2.0, "night shift")]
    assert [(a.id, s) for a, s in srv.pending()] == [("A", "IA"), ("B", "IA"), ("W", "I")]


@pytest.mark.parametrize("kw, fragment", [
    ({"kind": "X"}, "kind"), ({"kind": "H"}, "numeric limit"), ({"limit": 3.0}, "no limit"),
    ({"bit": 40}, "bit"), ({"delay": -1.0}, "0 or more"),
])
def test_bad_alarm_definitions(kw, fragment):
    with pytest.raises(PlcError, match=fragment) as e:
        Alarm("A", "a", tag="x", **kw)
    assert e.value.code == "PLC6020"


def test_unknown_alarm_and_class():
    with pytest.raises(PlcError) as e:
        AlarmServer([Alarm("A", "a", tag="x", alarm_class="nope")])
    assert e.value.code == "PLC6020"
    with pytest.raises(PlcError) as e:
        AlarmServer([Alarm("A", "a", tag="x")]).acknowledge("B")
    assert e.value.code == "PLC6021"


ALARMS_TOML = """
[class.critical]
ack = true
color = "#ff00ff"

[[alarm]]
id = "NO_WATER"
text = "no water in the boiler"
tag = "LS1"
kind = "discrete"
class = "critical"
ack_tag = "Main.AckButton"
ack_bit = "Main.Acked"

[[alarm]]
id = "LEVEL_HIGH"
text = "level above 1.2 m"
tag = "LEVEL"
kind = "H"
limit = 1.2
deadband = 0.05
delay = "1s"
class = "warning"
"""


def test_alarm_file_and_simulation_hook_write_the_log_into_the_trace(tmp_path):
    from plclab.sim import Simulation

    f = tmp_path / "alarms.toml"
    f.write_text(ALARMS_TOML.replace('tag = "LS1"', 'tag = "Main.Dry"'))
    srv = AlarmServer.load(f)
    plc = plclab.loads("""PROGRAM Main
VAR LS1 AT %IX0.0 : BOOL; LS2 AT %IX0.1 : BOOL; M AT %QX0.0 : BOOL;
    Dry : BOOL; AckButton : BOOL; Acked : BOOL; END_VAR
M := ((NOT LS1) OR M) AND (NOT LS2); Dry := NOT LS1;
END_PROGRAM""")
    sim = Simulation(plc, "tank", plant_params={"area": 0.2}, seed=1)
    sim.add_hook(srv)
    tr = sim.run("60s")
    log = alarm_log(tr)
    assert log and log[0].id == "NO_WATER" and log[0].state == "I" and log[0].time == 0.0
    assert plc["Main.Acked"] is False
    plc["Main.AckButton"] = True  # the rising edge of the ack tag acknowledges
    tr = sim.run("1s")
    assert plc["Main.Acked"] is True
    states = [(e.id, e.state) for e in alarm_log(tr)]
    assert ("NO_WATER", "IOA") in states or ("NO_WATER", "IA") in states
    high = alarm_log(tr, "LEVEL_HIGH")
    if high:  # the level passes 1.2 m: comes 1 s after it first exceeded it
        first = tr.first_time("LEVEL > 1.2")
        assert high[0].time == pytest.approx(first + 1.0, abs=0.021)
    assert tr.meta["alarms"][0]["ack"] is True
    back = type(tr).load(_saved(tr, tmp_path))
    assert [(e.id, e.state) for e in alarm_log(back)] == states


def _saved(tr, tmp_path):
    p = tmp_path / "run.trace"
    tr.save(p)
    return p


@pytest.mark.parametrize("text, fragment", [
    ("[[alarm]]\nid='a'\ntext='t'", "needs id, text and tag"),
    ("[[alarm]]\nid='a'\ntext='t'\ntag='x'\ncolour=1", "unknown key"),
    ("[class.x]\ncolor='red'\n[[alarm]]\nid='a'\ntext='t'\ntag='x'", "ack = true"),
    ("[[alarm]]\nid='a'\ntext='t'\ntag='x'\ndelay='soon'", "not a duration"),
    ("", "no [[alarm]]"),
    ("[[alarm]]\nid='a'\ntext='t'\ntag='x'\nkind='H'\nlimit=1\ndeadband='x%'", "percentage"),
    ("[[alarm]]\nid='a'\ntext='t'\ntag='x'\ndeadband_mode='never'", "deadband_mode"),
])
def test_bad_alarm_files(tmp_path, text, fragment):
    f = tmp_path / "a.toml"
    f.write_text(text)
    with pytest.raises(PlcError, match=fragment.replace("[", r"\[")) as e:
        AlarmServer.load(f)
    assert e.value.code == "PLC6020"


def test_the_alarm_log_goes_into_the_rerun_events_view_with_markers():
    from plclab.sim import Simulation
    from plclab.viz.from_trace import recording

    plc = plclab.loads("""PROGRAM Main
VAR LS1 AT %IX0.0 : BOOL; LS2 AT %IX0.1 : BOOL; M AT %QX0.0 : BOOL; END_VAR
M := ((NOT LS1) OR M) AND (NOT LS2);
END_PROGRAM""")
    sim = Simulation(plc, "tank", plant_params={"area": 0.2}, seed=1)
    sim.add_hook(AlarmServer([Alarm("HIGH", "level above 1.2 m", tag="LEVEL", kind="H",
                                    limit=1.2, deadband=0.05)]))
    rec = recording(sim.run("90s"))
    alarms = [e for e in rec.events if e.kind == "alarm"]
    assert alarms and alarms[0].level == "WARN" and "level above 1.2 m" in alarms[0].message
    assert any(m.label.startswith("alarm") or "alarm" in m.label for m in rec.markers)
