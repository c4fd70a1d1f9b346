"""``Plc(task_intervals=...)``: the tasks configured at one interval run at another, so a lab can
check that a program measures its periods instead of typing them in (scan-timing)."""

import pytest

import plclab
from plclab.errors import PlcError

TWO_TASKS = """
PROGRAM Fast
VAR n : INT; END_VAR
n := n + 1;
END_PROGRAM
PROGRAM Slow
VAR n : INT; END_VAR
n := n + 1;
END_PROGRAM
CONFIGURATION C RESOURCE R ON PLC
  TASK T1 (INTERVAL := T#10ms, PRIORITY := 1);
  TASK T2 (INTERVAL := T#100ms, PRIORITY := 2);
  PROGRAM F WITH T1 : Fast;
  PROGRAM S WITH T2 : Slow;
END_RESOURCE END_CONFIGURATION
"""


def runs(plc, seconds: float) -> tuple[int, int]:
    plc.run(seconds)
    return plc.var("F.n").get(), plc.var("S.n").get()


def test_configured_intervals_by_default():
    assert runs(plclab.loads(TWO_TASKS), 1.0) == (100, 10)


def test_retimed_tasks_run_at_the_new_intervals():
    plc = plclab.loads(TWO_TASKS, task_intervals={"10ms": "20ms", "100ms": "250ms"})
    assert [t.interval_ns for t in plc.tasks] == [20_000_000, 250_000_000]
    assert plc.tick_ns == 10_000_000  # gcd of 20 ms and 250 ms
    assert runs(plc, 1.0) == (50, 4)


def test_only_named_intervals_change_and_default_task_counts_as_cycle_time():
    plc = plclab.loads(TWO_TASKS, task_intervals={"100ms": "50ms", "7ms": "9ms"})
    assert runs(plc, 1.0) == (100, 20)
    single = plclab.loads("PROGRAM P VAR n : INT; END_VAR n := n + 1; END_PROGRAM",
                          cycle_time="10ms", task_intervals={"10ms": "40ms"})
    single.run(1.0)
    assert single.var("P.n").get() == 25


@pytest.mark.parametrize("bad", [{"10ms": "0ms"}, {"10ms": "2d"}, {"ten": "20ms"}, ["10ms"]])
def test_bad_tables_are_errors_with_codes(bad):
    with pytest.raises(PlcError) as e:
        plclab.loads(TWO_TASKS, task_intervals=bad)
    assert e.value.code in ("PLC3011", "PLC3002")
