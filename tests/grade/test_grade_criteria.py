"""The library of checks on small hand-made traces, and strict lab.toml validation."""

import numpy as np
import pytest

from plclab.errors import PlcError
from plclab.grade.criteria import CHECKS, run_check
from plclab.grade.lab import load_lab
from plclab.trace import Event, Trace


def trace(cols, dt=0.01, events=()):
    n = len(next(iter(cols.values())))
    t = np.arange(n) * dt
    return Trace(t, {k: np.asarray(v) for k, v in cols.items()},
                 meta={"t_end": n * dt, "period": dt}, events=list(events))


def square(n, period_rows, on_rows=None):
    on_rows = on_rows or period_rows // 2
    return np.array([(i % period_rows) < on_rows for i in range(n)])


def test_never_and_always():
    tr = trace({"L": np.linspace(0, 2, 201)})
    v = run_check("never", tr, {"condition": "L >= 1.5"})
    assert not v.passed and v.t_fail == pytest.approx(1.5) and "L = 1.5" in v.message
    assert run_check("never", tr, {"condition": "L >= 1.5", "to": 1.0}).passed
    assert run_check("always", tr, {"condition": "L <= 2.0"}).passed
    v = run_check("always_after", tr, {"condition": "L >= 0.5", "after": 0.2})
    assert not v.passed and v.t_fail == pytest.approx(0.2)
    assert run_check("always_after", tr, {"condition": "L >= 0.5", "after": 0.5}).passed
    assert run_check("eventually", tr, {"condition": "L > 1.9"}).passed
    assert not run_check("eventually", tr, {"condition": "L > 1.9", "to": 1.0}).passed


def test_within_implies():
    trig = np.zeros(300, bool)
    trig[100:] = True
    resp = np.zeros(300, bool)
    resp[150:] = True
    tr = trace({"A": trig, "B": resp})
    assert run_check("within", tr, {"trigger": "A", "response": "B", "time": 0.6}).passed
    v = run_check("within", tr, {"trigger": "A", "response": "B", "time": 0.3})
    assert not v.passed and v.t_fail == pytest.approx(1.3)
    v = run_check("within", tr, {"trigger": "B and not A", "response": "A", "time": 1})
    assert not v.passed and "never happened" in v.message
    assert run_check("within", tr, {"trigger": "B and not A", "response": "A", "time": 1,
                                    "need_trigger": False}).passed
    v = run_check("implies", tr, {"if": "A", "then": "B"})
    assert not v.passed and v.t_fail == pytest.approx(1.0)
    assert run_check("implies", tr, {"if": "B", "then": "A"}).passed


def test_switching_checks():
    x = np.zeros(1000, bool)
    x[100:300] = True
    x[500:520] = True
    tr = trace({"P": x})
    assert run_check("max_switchings", tr, {"signal": "P", "max": 4}).passed
    v = run_check("max_switchings", tr, {"signal": "P", "max": 3})
    assert not v.passed and v.t_fail == pytest.approx(5.2) and v.value == 4
    assert not run_check("max_switchings", tr, {"signal": "P", "per_hour": 1000}).passed
    v = run_check("min_dwell", tr, {"signal": "P", "on": 1.0})
    assert not v.passed and "0.20 s" in v.message
    v = run_check("max_on", tr, {"signal": "P", "max": 1.0})
    assert not v.passed and v.t_fail == pytest.approx(2.0)
    assert run_check("max_on", tr, {"signal": "P", "max": 2.5}).passed
    assert run_check("no_chatter", tr, {"signal": "P"}).passed
    v = run_check("no_chatter", trace({"P": square(1000, 10)}), {"signal": "P"})
    assert not v.passed and "chatters" in v.message


def test_blink_frequency():
    tr = trace({"LAMP": square(1000, 20)})  # 10 ms rows: 200 ms period = 5 Hz
    v = run_check("blink_frequency", tr, {"signal": "LAMP", "hz": 5.0, "tol": 0.1})
    assert v.passed and v.value == pytest.approx(5.0)
    assert not run_check("blink_frequency", tr, {"signal": "LAMP", "hz": 2.0}).passed
    v = run_check("blink_frequency", trace({"LAMP": np.ones(500, bool)}), {"signal": "LAMP",
                                                                          "hz": 5.0})
    assert not v.passed and "stays TRUE" in v.message


def test_settles_in_band_value():
    t = np.arange(0, 100, 0.1)
    y = 50 + 10 * np.exp(-t / 10.0)
    tr = trace({"T": y}, dt=0.1)
    assert run_check("settles", tr, {"signal": "T", "target": 50, "band": 1, "within": 30,
                                     "after": 0}).passed
    v = run_check("settles", tr, {"signal": "T", "target": 50, "band": 1, "within": 10,
                                  "after": 0})
    assert not v.passed and v.t_fail == pytest.approx(10.0)
    assert run_check("in_band", tr, {"signal": "T", "lo": 49, "hi": 51,
                                     "min_fraction": 0.7}).passed
    assert not run_check("in_band", tr, {"signal": "T", "lo": 49, "hi": 51,
                                         "min_fraction": 0.9}).passed
    assert run_check("value", tr, {"signal": "T", "min": 49.9, "max": 50.1}).passed
    assert not run_check("value", tr, {"signal": "T", "equals": 70, "at": 0.0}).passed


def test_event_count_and_counter():
    evs = [Event(1.0, "bottle_rejected", "conveyor", "b1", {"fallen": True}),
           Event(2.0, "bottle_rejected", "conveyor", "b2", {"fallen": False}),
           Event(3.0, "bottle_binned", "conveyor", "b3", {"result": "unfilled_passed"})]
    c = np.zeros(500, dtype=np.int64)
    c[250:] = 1
    tr = trace({"%MW0": c, "%MW2": c * 2}, events=evs)
    v = run_check("event_count", tr, {"event": "bottle_rejected", "where": {"fallen": False},
                                      "max": 0})
    assert not v.passed and v.t_fail == 2.0 and "b2" in v.message
    assert run_check("event_count", tr, {"event": "bottle_rejected", "min": 2}).passed
    assert not run_check("event_count", tr, {"event": "bottle_rejected", "equals": 3}).passed
    assert run_check("counter", tr, {"signal": "%MW0", "event": "bottle_binned"}).passed
    assert run_check("counter", tr, {"signal": "%MW2", "event": "bottle_rejected"}).passed
    v = run_check("counter", tr, {"signal": "%MW0", "event": "bottle_rejected"})
    assert not v.passed and "the plant counted 2" in v.message


def _ticks(times, n=1000, dt=0.01):
    evs = [Event(t, "bottle_filled", "filler", f"bottle at {t:g} s", {}) for t in times]
    return trace({"X": np.zeros(n)}, dt=dt, events=evs)


def test_event_count_minimum_points_at_the_missing_event():
    # steady pace: one every 2 s from 1 s; the fourth (due at 7 s) never came, the run
    # ends at 10 s
    v = run_check("event_count", _ticks([1.0, 3.0, 5.0]), {"event": "bottle_filled", "min": 4})
    assert not v.passed and v.value == 3
    assert v.t_fail == pytest.approx(7.0) and "due at about" in v.message
    # an explicit window end: due by then
    v = run_check("event_count", _ticks([1.0, 3.0, 5.0]),
                  {"event": "bottle_filled", "min": 4, "to": 6.5})
    assert not v.passed and v.t_fail == pytest.approx(6.5) and "due by" in v.message
    # no pace to go by (one event, or irregular ones): the run's end, and it says so
    for times in ([1.0], [1.0, 1.5, 6.0], []):
        v = run_check("event_count", _ticks(times), {"event": "bottle_filled", "min": 4})
        assert not v.passed and v.t_fail == pytest.approx(10.0), times
        assert "cannot be told" in v.message, times
    # the pace says the next was not due before the end: no guess either
    v = run_check("event_count", _ticks([4.0, 8.0]), {"event": "bottle_filled", "min": 3})
    assert not v.passed and "cannot be told" in v.message
    assert run_check("event_count", _ticks([1.0, 3.0, 5.0]),
                     {"event": "bottle_filled", "min": 3}).passed


def test_every_check_is_documented():
    for c in CHECKS.values():
        assert c.doc, c.name


# ---------------------------------------------------------------------------- lab.toml

GOOD = '''title = "A test lab"
plant = "tank"
plant_params = { area = 0.2 }
wiring = [
  { plc = "%IX0.0", signal = "LS1", module = "di" },
  { plc = "%QX0.0", signal = "PUMP", module = "do" },
]

[[io]]
name = "LS1"
address = "%IX0.0"
type = "BOOL"

[[io]]
name = "PUMP"
address = "%QX0.0"
type = "BOOL"

[[scenario]]
name = "s1"
duration = "30s"
actions = [ { at = "10s", set = "VALVE", value = 50 } ]

[[criterion]]
name = "c1"
check = "never"
condition = "LEVEL >= 1.9"
points = 2
'''


def make(tmp_path, text, name="my-lab", files=None):
    d = tmp_path / name
    d.mkdir()
    (d / "lab.toml").write_text(text, encoding="utf-8")
    for k, v in (files or {}).items():
        (d / k).write_text(v, encoding="utf-8")
    return d


def test_a_good_lab_loads(tmp_path):
    lab = load_lab(make(tmp_path, GOOD), deep=True)
    assert lab.max_score == 2 and lab.criteria[0].scenarios == ["s1"]
    assert lab.hash


@pytest.mark.parametrize("change,code,words", [
    (("title =", "titel ="), "PLC5002", "Did you mean 'title'"),
    (('title = "A test lab"\n', ""), "PLC5003", "needs 'title'"),
    (('plant = "tank"', 'plant = "tanks"'), "PLC5005", "Did you mean 'tank'"),
    (("area = 0.2", "aera = 0.2"), "PLC5005", "aera"),
    (('signal = "LS1"', 'signal = "LS9"'), "PLC5006", "no signal 'LS9'"),
    (('name = "PUMP"\naddress = "%QX0.0"', 'name = "PUMP"\naddress = "%QX0.1"'), "PLC5007",
     "not in the I/O table"),
    (('type = "BOOL"\n\n[[io]]\nname = "PUMP"', 'type = "INT"\n\n[[io]]\nname = "PUMP"'),
     "PLC5004", "does not fit"),
    (('duration = "30s"', 'duration = "30 parsecs"'), "PLC5004", "duration"),
    (('duration = "30s"', 'duration = "30s"\ntask_intervals = { "10ms" = "0ms" }'), "PLC5004",
     "task_intervals: a task interval is 0"),
    (('duration = "30s"', 'duration = "30s"\ntask_intervals = ["20ms"]'), "PLC5004",
     "task_intervals is a table"),
    (('set = "VALVE"', 'set = "VALVES"'), "PLC5008", "Did you mean 'VALVE'"),
    (('check = "never"', 'check = "nevre"'), "PLC5009", "Did you mean 'never'"),
    (('condition = "LEVEL >= 1.9"', 'condition = "LEVEL >= "'), "PLC5009", "condition"),
    (('condition = "LEVEL >= 1.9"', 'condition = "LEVL >= 1.9"'), "PLC5009",
     "Did you mean 'LEVEL'"),
    (("points = 2", "points = -1"), "PLC5004", "points must be a number > 0"),
    (('check = "never"\ncondition = "LEVEL >= 1.9"', 'python = "checks:nothing"'), "PLC5010",
     "checks"),
    (('name = "c1"', 'name = "c1"\nscenario = "s2"'), "PLC5009", "no scenario 's2'"),
])
def test_lab_errors_name_the_key(tmp_path, change, code, words):
    text = GOOD.replace(*change)
    assert text != GOOD
    with pytest.raises(PlcError) as e:
        load_lab(make(tmp_path, text))
    assert e.value.code == code, str(e.value)
    assert words in e.value.message, e.value.message
    assert e.value.location is not None and e.value.location.file.endswith("lab.toml")


def test_error_location_points_at_the_key(tmp_path):
    text = GOOD.replace("points = 2", "points = 2\npoint = 3")
    with pytest.raises(PlcError) as e:
        load_lab(make(tmp_path, text))
    assert e.value.code == "PLC5002"
    line = text.splitlines().index("point = 3") + 1
    assert e.value.location.line == line


def test_not_toml(tmp_path):
    with pytest.raises(PlcError) as e:
        load_lab(make(tmp_path, GOOD + "\n[[criterion]\n"))
    assert e.value.code == "PLC5001" and e.value.location.line > 0


def test_duplicate_names(tmp_path):
    text = GOOD + '\n[[criterion]]\nname = "c1"\ncheck = "never"\ncondition = "PUMP"\n'
    with pytest.raises(PlcError) as e:
        load_lab(make(tmp_path, text))
    assert e.value.code == "PLC5011"


def test_python_check(tmp_path):
    text = GOOD.replace('check = "never"\ncondition = "LEVEL >= 1.9"',
                        'python = "checks:low"\nparams = { limit = 1.9 }')
    checks = ("def low(trace, limit):\n"
              "    m = float(trace['LEVEL'].max())\n"
              "    return m < limit, f'max level {m:.2f}'\n")
    lab = load_lab(make(tmp_path, text, files={"checks.py": checks}))
    from plclab.grade import check

    res = check(lab.path, "PROGRAM P VAR L AT %IX0.0 : BOOL; Q AT %QX0.0 : BOOL; END_VAR\n"
                "Q := NOT L;\nEND_PROGRAM")
    assert res.score == 2 and "max level" in res.tests[0].message


def test_requires_gates_points(tmp_path):
    text = GOOD.replace("LEVEL >= 1.9", "LEVEL >= 0.3") + (
        '\n[[criterion]]\nname = "c2"\nrequires = ["c1"]\ncheck = "never"\n'
        'condition = "LEVEL >= 1.9"\npoints = 1\n')
    lab = load_lab(make(tmp_path, text))
    from plclab.grade import check

    # the pump runs all the time: c1 fails (the level passes 0.3 m), so c2 is "not earned"
    # although the level never reaches 1.9 m
    res = check(lab.path, "PROGRAM P VAR Q AT %QX0.0 : BOOL; END_VAR\nQ := TRUE;\nEND_PROGRAM")
    assert [t.passed for t in res.tests] == [False, False]
    assert "not earned" in res.tests[1].message


@pytest.mark.parametrize("name", ["plclab.grade.criteria", "plclab.grade.errors",
                                  "plclab.grade.lab", "plclab.grade.engine"])
def test_doctests(name):
    import doctest
    import importlib

    result = doctest.testmod(importlib.import_module(name), optionflags=doctest.ELLIPSIS)
    assert result.failed == 0


def test_a_failed_critical_criterion_caps_the_lab():
    """press-safety marks its safety checks critical: a press that ignores the light curtain
    keeps at most half the lab's points, however well it doses (ADR 0042)."""
    from pathlib import Path

    import plclab.grade as grade

    lab = Path(__file__).resolve().parents[2] / "labs" / "press-safety"
    good = grade.check(str(lab), [str(lab / "solution" / "press.st")])
    bad = grade.check(str(lab), [str(lab / "mistakes" / "ignores_curtain.st")])
    assert good.score == good.max_score
    assert bad.critical_failures and bad.capped
    assert bad.score == bad.critical_cap * bad.max_score < bad.points
    assert "A critical requirement failed" in bad.feedback_markdown.split("## ")[0]
