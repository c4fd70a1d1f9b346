"""Watch tables: trigger-point sampling (TIA Table 14), modify once vs force every scan,
outputs enabled in STOP, files, formats, and the record in a simulation's Trace."""

from __future__ import annotations

import pytest

import plclab
from plclab.errors import PlcError
from plclab.process import WatchRow, WatchTable, format_value

SRC = """PROGRAM Main
VAR a AT %IX0.0 : BOOL; q AT %QX0.0 : BOOL; n : INT; hits : INT; END_VAR
q := a; n := n + 1; IF a THEN hits := hits + 1; END_IF;
END_PROGRAM"""


def sampled(trigger: str, scans: int = 2):
    plc = plclab.loads(SRC)
    table = WatchTable([WatchRow("n"), WatchRow("q")], trigger=trigger)
    table.attach(plc)
    plc.scan(scans)
    return [s.values for s in table.samples]


def test_scan_start_sees_the_values_before_the_program_and_scan_end_after_it():
    assert sampled("scan_start") == [(0, False), (1, False)]
    assert sampled("scan_end") == [(1, False), (2, False)]


def test_modify_at_scan_start_reaches_the_program_once_force_every_scan():
    plc = plclab.loads(SRC)
    plc.modify("a", True)
    plc.scan(5)
    assert plc["hits"] == 1  # the next read of the inputs overwrites the modified value
    plc.force("a", True)
    plc.scan(5)
    assert plc["hits"] == 6
    plc.unforce()
    plc.scan(5)
    assert plc["hits"] == 6


def test_modify_an_output_at_scan_end_overrides_the_program_for_one_scan():
    plc = plclab.loads(SRC)
    table = WatchTable([WatchRow("%QX0.0", "bool")], trigger="scan_end")
    table.attach(plc)
    plc.modify("%QX0.0", True, at="scan_end")
    plc.scan(2)
    # scan 1: the program wrote FALSE, the modify wrote TRUE just before the outputs;
    # scan 2: the program's FALSE again (an address is read from the process image)
    assert [s.values[0] for s in table.samples] == [True, False]
    plc2 = plclab.loads(SRC)
    plc2.modify("q", True, at="scan_end")
    plc2.scan()
    assert plc2["%QX0.0"] is True
    plc2.scan()
    assert plc2["%QX0.0"] is False


def test_modified_input_at_scan_start_differs_from_the_value_at_scan_end_when_the_program_writes_it():
    plc = plclab.loads("""PROGRAM Main VAR a : BOOL; END_VAR a := FALSE; END_PROGRAM""")
    start = WatchTable([WatchRow("a")], trigger="scan_start", name="start")
    end = WatchTable([WatchRow("a")], trigger="scan_end", name="end")
    start.attach(plc)
    end.attach(plc)
    plc.modify("a", True)
    plc.scan()
    # the textbook's check: an input that changes within the scan is written by the program
    assert start.samples[0].values == (True,) and end.samples[0].values == (False,)


def test_on_stop_samples_the_last_values_and_once_samples_only_the_first_time():
    plc = plclab.loads(SRC)
    table = WatchTable([WatchRow("n")], trigger="stop")
    once = WatchTable([WatchRow("n")], trigger="scan_end", once=True, name="once")
    table.attach(plc)
    once.attach(plc)
    plc.scan(3)
    plc.stop()
    plc.scan(2)  # STOP scans: the program does not run
    plc.start()
    plc.scan(1)
    plc.stop()
    assert [s.values for s in table.samples] == [(3,), (4,)]
    assert [s.values for s in once.samples] == [(1,)]


def test_a_fault_is_a_transition_to_stop():
    plc = plclab.loads("""PROGRAM Main VAR n : INT; d : INT; r : INT; END_VAR
n := n + 1; IF n = 3 THEN r := 1 / d; END_IF; END_PROGRAM""")
    table = WatchTable([WatchRow("n")], trigger="stop")
    table.attach(plc)
    with pytest.raises(plclab.PlcRuntimeFault):
        plc.scan(5)
    assert [s.values for s in table.samples] == [(3,)]


def test_outputs_enabled_in_stop_let_a_modified_output_reach_the_terminal():
    plc = plclab.loads(SRC)
    plc.stop()
    plc.modify("%QX0.0", True, at="scan_end")
    plc.scan()
    assert plc["%QX0.0"] is False  # blocked: outputs are off in STOP
    plc.enable_outputs_in_stop()
    plc.modify("%QX0.0", True, at="scan_end")
    plc.scan(3)
    assert plc["%QX0.0"] is True  # stays until changed
    plc.start()  # RUN blocks the option again
    assert plc.outputs_enabled_in_stop is False
    plc.scan()
    assert plc["%QX0.0"] is False


@pytest.mark.parametrize("setup, message", [
    (lambda plc: None, "only in STOP"),
    (lambda plc: (plc.stop(), plc.force("a", True)), "forced"),
])
def test_outputs_in_stop_need_stop_and_nothing_forced(setup, message):
    plc = plclab.loads(SRC)
    setup(plc)
    with pytest.raises(PlcError, match=message) as e:
        plc.enable_outputs_in_stop()
    assert e.value.code == "PLC6002"


def test_modify_names_a_trigger_point():
    plc = plclab.loads(SRC)
    with pytest.raises(PlcError) as e:
        plc.modify("a", True, at="stop")
    assert e.value.code == "PLC6001"


def test_rows_force_and_modify_from_a_file(tmp_path):
    f = tmp_path / "w.toml"
    f.write_text("""name = "commissioning"
trigger = "scan_end"
[[row]]
name = "Main.hits"
format = "hex"
[[row]]
name = "%IX0.0"
force = true
comment = "simulate the switch"
""")
    table = WatchTable.load(f)
    plc = plclab.loads(SRC)
    table.attach(plc)
    plc.scan(3)
    assert table.show() == "Main.hits  16#0003\n%IX0.0     TRUE"


@pytest.mark.parametrize("text, fragment", [
    ("trigger = 'sometimes'\n[[row]]\nname='n'", "trigger"),
    ("[[row]]\nname='n'\nformat='roman'", "display format"),
    ("[[row]]\nnme='n'", "needs name"),
    ("[[row]]\nname='n'\ncolour='red'", "unknown key"),
    ("name='x'", "no [[row]]"),
    ("[[row]\n", "TOML"),
])
def test_bad_watch_files_say_what_to_fix(tmp_path, text, fragment):
    f = tmp_path / "w.toml"
    f.write_text(text)
    with pytest.raises(PlcError, match=fragment.replace("[", r"\[")) as e:
        WatchTable.load(f)
    assert e.value.code == "PLC6010"


def test_an_unknown_variable_is_reported_when_attached():
    plc = plclab.loads(SRC)
    with pytest.raises(PlcError) as e:
        WatchTable([WatchRow("Main.nope")]).attach(plc)
    assert e.value.code == "PLC6011"


@pytest.mark.parametrize("value, fmt, text", [
    (True, "bool", "TRUE"), (-1, "hex", "16#FFFF"), (70000, "hex", "16#00011170"),
    (10, "oct", "8#12"), (300, "bin", "2#0000_0001_0010_1100"), (-5, "dec", "-5"),
    (1.0, "float", "1.000000"), (3_723_004, "time", "T#1h2m3s4ms"), (0, "time", "T#0ms"),
    (10, "char", "'$0A'"), (2.5, "auto", "2.5"), (True, "dec", "1"),
])
def test_display_formats(value, fmt, text):
    assert format_value(value, fmt) == text


def test_a_watch_table_records_scan_end_columns_and_stop_events_in_the_trace():
    from plclab.sim import Simulation

    plc = plclab.loads("""PROGRAM Main
VAR LS1 AT %IX0.0 : BOOL; LS2 AT %IX0.1 : BOOL; M AT %QX0.0 : BOOL; n : DINT; END_VAR
M := ((NOT LS1) OR M) AND (NOT LS2); n := n + 1;
END_PROGRAM""")
    sim = Simulation(plc, "tank")
    sim.add_hook(WatchTable([WatchRow("Main.n"), WatchRow("%QX0.0")], trigger="scan_end"))
    sim.add_hook(WatchTable([WatchRow("Main.n", "dec")], trigger="stop", name="on-stop"))
    sim.run("0.1s")
    plc.stop()
    tr = sim.run("0.05s")
    col = tr["Main.n@scan_end"]
    assert list(col[:3]) == [1, 2, 3]
    stops = tr.events_of("watch")
    assert len(stops) == 1 and stops[0].message == "on STOP: Main.n=10"
    assert tr.meta["watch_tables"]["on-stop"]["trigger"] == "stop"
    with pytest.raises(PlcError) as e:
        sim.add_hook(WatchTable([WatchRow("Main.n")], name="late"))
    assert e.value.code == "PLC6060"
