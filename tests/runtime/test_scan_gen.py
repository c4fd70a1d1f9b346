"""The generated scan (ADR 0058): the same state as the reference ``_scan_once`` for every task
layout, with system bytes, forcing, trigger points and restarts; its flag follows every way the
common case can end; its text holds only what this PLC needs."""

from hypothesis import given, settings
from hypothesis import strategies as st

import plclab
from plclab.errors import PlcRuntimeFault
from plclab.runtime.plc import Plc

TASKS = """
PROGRAM Fast
VAR n : DINT; q AT %QX0.1 : BOOL; END_VAR
n := n + 1; q := NOT q;
END_PROGRAM
PROGRAM Slow
VAR m : DINT; d : INT := 4; r : INT; i AT %IW2 : INT; END_VAR
m := m + i;
IF i = 99 THEN d := 0; END_IF
r := 100 / d;
END_PROGRAM
CONFIGURATION C RESOURCE R ON PLC
TASK t1 (INTERVAL := T#10ms, PRIORITY := 1);
TASK t2 (INTERVAL := T#30ms, PRIORITY := 2);
PROGRAM f WITH t1 : Fast;
PROGRAM s WITH t2 : Slow;
PROGRAM s2 WITH t1 : Slow;
END_RESOURCE END_CONFIGURATION
"""

ONE = """
PROGRAM Main
VAR t : TON; n : DINT; out AT %QX0.0 : BOOL; END_VAR
t(IN := NOT t.Q, PT := T#30ms);
n := n + 1;
out := t.Q;
END_PROGRAM
"""

PLAIN = "PROGRAM Main VAR n : DINT; END_VAR n := n + 1; END_PROGRAM"

_COMPILED = {name: plclab.compile_sources([(src, "p.st")])
             for name, src in (("tasks", TASKS), ("one", ONE), ("plain", PLAIN))}
_OPTIONS = {"none": {}, "system": {"system_memory_byte": 10, "clock_memory_byte": 11}}


def state(plc):
    return ({k: plc[k] for k in plc.variables() if not k.endswith(".t")}, plc.ctx.now_ns,
            plc.ctx.now, plc.ctx.scan_count, plc.ctx.first_scan, bytes(plc.image_in),
            bytes(plc.image_out), bytes(plc.outputs), bytes(plc.memory), plc.state,
            plc.fault and plc.fault.code)


def drive(plc, how, steps):
    for scans, level, forced in steps:
        plc.inputs[2:4] = level.to_bytes(2, "big")
        if forced:
            plc.force("%QX0.1", True)
        else:
            plc.unforce()
        try:
            if how == "plain":
                for _ in range(scans):
                    plc._scan_once()
            elif how == "batch":
                plc.scan(scans)
            else:
                for _ in range(scans):
                    plc.scan()
        except PlcRuntimeFault:
            break
    return state(plc)


@settings(max_examples=40, deadline=None, database=None)
@given(program=st.sampled_from(sorted(_COMPILED)), options=st.sampled_from(sorted(_OPTIONS)),
       steps=st.lists(st.tuples(st.integers(0, 9), st.sampled_from([0, 1, 99]), st.booleans()),
                      min_size=1, max_size=5))
def test_the_generated_scan_ends_in_the_reference_state(program, options, steps):
    results = {how: drive(Plc(_COMPILED[program], **_OPTIONS[options]), how, steps)
               for how in ("plain", "batch", "one")}
    assert results["one"] == results["plain"]
    assert results["batch"] == results["plain"]


def test_the_slow_task_runs_only_on_its_interval():
    plc = Plc(_COMPILED["tasks"])
    plc.inputs[2:4] = (1).to_bytes(2, "big")
    plc.scan()
    plc.scan()
    plc.scan()
    plc.scan()
    assert plc["f.n"] == 4 and plc["s2.m"] == 4 and plc["s.m"] == 2  # scans at 0 and 30 ms


def test_the_flag_follows_state_forcing_and_hooks():
    plc = Plc(_COMPILED["plain"])
    live = plc._live
    assert live[0]
    plc.forced["MAIN.N"] = (plc.var("Main.n"), 5)  # the table itself, not force()
    assert not live[0]
    plc.scan()
    assert plc["Main.n"] == 5  # the general path applied the forced value
    plc.forced.clear()
    assert live[0]
    plc.force("Main.n", 1)
    plc.forced.pop("MAIN.N")
    assert live[0]
    plc.forced.update({"MAIN.N": (plc.var("Main.n"), 3)})
    assert not live[0]
    del plc.forced["MAIN.N"]
    assert live[0]
    plc.stop()
    assert not live[0]
    n = plc["Main.n"]
    plc.scan()
    assert plc["Main.n"] == n  # STOP: the program did not run
    plc.start()
    assert live[0]
    plc.modify("Main.n", 40)
    assert not live[0]
    plc.scan()
    assert live[0] and plc["Main.n"] == 41
    plc.triggers["scan_end"].append(lambda p, at: None)
    assert not live[0]
    plc.triggers["scan_end"].clear()
    assert live[0]


def test_a_held_scan_of_a_restarted_or_stopped_plc_takes_the_general_path():
    plc = Plc(_COMPILED["plain"])
    held = plc.scan
    held()
    plc.cold_restart()
    assert plc.scan is not held
    held()  # the old program's scan: the general path runs the new program
    assert plc["Main.n"] == 1 and plc.scan_count == 1
    held = plc.scan
    plc.stop()
    before = plc.time
    held()  # a STOP cycle: the clock moves, the program does not run, no scan is counted
    assert plc["Main.n"] == 1 and plc.scan_count == 1 and plc.time > before


def test_a_fault_in_the_generated_scan_stops_the_plc_with_its_location():
    plc = Plc(_COMPILED["tasks"])
    plc.inputs[2:4] = (99).to_bytes(2, "big")
    try:
        plc.scan()
    except PlcRuntimeFault as e:
        assert e.code == "PLC2001" and e.location is not None and e.location.line == 10
    else:
        raise AssertionError("division by zero did not fault")
    assert plc.state == "STOP" and plc.outputs == bytes(plc.image_size)
    assert not plc._live[0]


def test_the_scan_holds_only_what_the_plc_needs():
    plain = Plc(_COMPILED["plain"]).scan.source
    assert "sync_in" not in plain and "sync_out" not in plain  # no located variables
    assert "sysmem" not in plain and "now %" not in plain
    located = Plc(_COMPILED["one"]).scan.source
    assert "sync_in()" in located and "sync_out()" in located
    system = Plc(_COMPILED["plain"], system_memory_byte=3).scan.source
    assert "sysmem()" in system
    tasks = Plc(_COMPILED["tasks"]).scan.source
    assert "if now % 30000000 == 0:" in tasks and tasks.count("B") >= 6


def test_wrong_counts_still_reach_the_checks():
    plc = Plc(_COMPILED["plain"])
    for bad in (True, 1.0, -1, "1"):
        try:
            plc.scan(bad)
        except plclab.PlcError as e:
            assert e.code == "PLC3011"
        else:
            raise AssertionError(f"scan({bad!r}) was accepted")
    assert plc.scan_count == 0
