"""Bounds of the Plc API: addresses beyond the process image, cycle times, task intervals, run
lengths and PLC options are PlcErrors with a code (PLC3002, PLC3010-PLC3012), never an
IndexError, a ZeroDivisionError, a silently grown image or a run that never returns."""

import math

import pytest

import plclab
from plclab.errors import PlcError
from plclab.runtime.plc import MAX_SCANS

SRC = """PROGRAM P
VAR a AT %IX0.0 : BOOL; q AT %QX0.0 : BOOL; END_VAR
q := a;
END_PROGRAM
"""


def code_of(fn) -> str:
    with pytest.raises(PlcError) as exc:
        fn()
    return exc.value.code


@pytest.fixture
def plc():
    return plclab.loads(SRC)


@pytest.mark.parametrize("addr", ["%QX5000.0", "%IW2000", "%IW1023", "%MD1021", "%ML1017",
                                  "%IX1024.0", "%IX0.8", "%QX3.9"])
def test_reading_writing_and_forcing_beyond_the_image_is_plc3010(plc, addr):
    value = True if "X" in addr else 1
    assert code_of(lambda: plc[addr]) == "PLC3010"
    assert code_of(lambda: plc.__setitem__(addr, value)) == "PLC3010"
    assert code_of(lambda: plc.force(addr, value)) == "PLC3010"
    plc.scan()
    assert len(plc.inputs) == len(plc.outputs) == len(plc.memory) == plc.image_size == 1024


def test_the_last_addresses_of_the_image_work(plc):
    plc["%IW1022"] = 0x1234
    plc["%MX1023.7"] = True
    plc.force("%QB1023", 7)
    plc.scan()
    assert (plc["%IB1023"], plc["%MB1023"], plc["%QB1023"]) == (0x34, 0x80, 7)


def test_the_message_names_the_image_and_the_remedy(plc):
    with pytest.raises(PlcError) as exc:
        plc["%QX5000.0"]
    assert "1024 bytes" in exc.value.message and "image_size" in exc.value.message


def test_a_located_variable_beyond_a_smaller_image_is_plc0127_at_its_declaration():
    with pytest.raises(PlcError) as exc:
        plclab.loads(SRC.replace("%QX0.0", "%QX9.0"), "small.st", image_size=8)
    assert exc.value.code == "PLC0127" and "%QX9.0" in exc.value.message
    assert exc.value.location.file == "small.st" and exc.value.location.line == 2


@pytest.mark.parametrize("cycle", [0, -1, -0.01, 1e-9, "1ns", "50us", "0ms", "T#0s", "-5ms",
                                   1e12, "1000d", 10 ** 30])
def test_cycle_times_out_of_range_are_plc3011(cycle):
    assert code_of(lambda: plclab.loads(SRC, cycle_time=cycle)) == "PLC3011"


@pytest.mark.parametrize("cycle", [math.nan, math.inf, -math.inf, True, None, [1], "abc"])
def test_cycle_times_that_are_not_durations_are_plc3002(cycle):
    assert code_of(lambda: plclab.loads(SRC, cycle_time=cycle)) == "PLC3002"


@pytest.mark.parametrize("cycle,ns", [("100us", 100_000), (0.0001, 100_000), ("1d", 86_400 * 10 ** 9),
                                      ("T#10ms", 10_000_000)])
def test_the_limits_of_the_cycle_time_are_accepted(cycle, ns):
    plc = plclab.loads(SRC, cycle_time=cycle)
    plc.scan(3)
    assert plc.tick_ns == ns and plc.ctx.now_ns == 3 * ns


TASK = ("\nCONFIGURATION C RESOURCE R ON PLC TASK T(INTERVAL := {iv}, PRIORITY := 1); "
        "PROGRAM M WITH T : P; END_RESOURCE END_CONFIGURATION\n")


@pytest.mark.parametrize("iv", ["T#0ms", "T#1ns", "T#-10ms", "LTIME#1us", "LTIME#30d", "T#30d"])
def test_task_intervals_out_of_range_are_compile_errors_at_the_task(iv):
    with pytest.raises(PlcError) as exc:
        plclab.loads(SRC + TASK.format(iv=iv), "task.st")
    if iv == "T#30d":  # beyond TIME itself
        assert exc.value.code == "PLC0126"
    else:
        assert exc.value.code == "PLC0129" and "task T" in exc.value.message
    assert exc.value.location is not None and exc.value.location.line == 6


def test_task_intervals_whose_base_period_is_too_small_are_plc3011():
    two = SRC + ("\nCONFIGURATION C RESOURCE R ON PLC TASK A(INTERVAL := T#10ms, PRIORITY := 1);"
                 " TASK B(INTERVAL := LTIME#10ms1us, PRIORITY := 2); PROGRAM M WITH A : P;"
                 " PROGRAM N WITH B : P; END_RESOURCE END_CONFIGURATION\n")
    assert code_of(lambda: plclab.loads(two)) == "PLC3011"


@pytest.mark.parametrize("seconds,code", [(-1, "PLC3011"), ("1000d", "PLC3011"),
                                          (1e12, "PLC3011"), (math.nan, "PLC3002"),
                                          (math.inf, "PLC3002"), (True, "PLC3002"),
                                          ("abc", "PLC3002"), ([1], "PLC3002")])
def test_run_with_nonsense_seconds_is_a_plc_error_and_runs_nothing(plc, seconds, code):
    assert code_of(lambda: plc.run(seconds=seconds)) == code
    assert plc.scan_count == 0


@pytest.mark.parametrize("n", [-1, 1.5, "3", math.nan, True, None, MAX_SCANS + 1])
def test_scan_and_run_counts_must_be_whole_and_bounded(plc, n):
    if n is not None:
        assert code_of(lambda: plc.scan(n)) == "PLC3011"
    assert code_of(lambda: plc.run(cycles=n) if n is not None else plc.run()) in ("PLC3011",
                                                                                 "PLC3002")
    assert plc.scan_count == 0


def test_run_rounds_up_to_whole_scans(plc):
    plc.run(seconds=0)
    assert plc.scan_count == 0
    plc.run(seconds="25ms")
    assert plc.scan_count == 3


@pytest.mark.parametrize("opts", [{"image_size": 0}, {"image_size": -1}, {"image_size": 10 ** 12},
                                  {"image_size": "1k"}, {"image_size": 7}, {"watchdog": 0},
                                  {"watchdog": 1.5}, {"clock_memory_byte": 5000},
                                  {"system_memory_byte": -1}, {"system_memory_byte": "M1"}])
def test_bad_plc_options_are_plc3012(opts):
    assert code_of(lambda: plclab.loads(SRC, **opts)) == "PLC3012"


def test_a_larger_image_reaches_further():
    plc = plclab.loads(SRC, image_size=4096)
    plc["%IW4094"] = 5
    assert plc["%IW4094"] == 5 and code_of(lambda: plc["%IW4095"]) == "PLC3010"
