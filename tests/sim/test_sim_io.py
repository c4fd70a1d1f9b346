"""What the I/O modules of a wiring do to the signals: filter, bounce, ADC, relay, faults."""

from __future__ import annotations

import numpy as np
import pytest

import plclab
from plclab.io import AnalogInput
from plclab.sim import Scenario, Simulation

TANK = """PROGRAM Main
VAR
  LS1 AT %IX0.0 : BOOL; LS2 AT %IX0.1 : BOOL; M AT %QX0.0 : BOOL; lvl AT %IW64 : INT;
END_VAR
M := ((NOT LS1) OR M) AND (NOT LS2);
END_PROGRAM"""

MOTOR = """PROGRAM Starter
VAR
  START AT %IX0.0 : BOOL; STOP AT %IX0.1 : BOOL; K1 AT %QX0.0 : BOOL;
END_VAR
K1 := (START OR K1) AND STOP;
END_PROGRAM"""


def tank_rows(ls2: dict, pump: dict | None = None, level: dict | None = None) -> list[dict]:
    rows = [{"plc": "%IX0.0", "signal": "LS1", "module": "direct"},
            {"plc": "%IX0.1", "signal": "LS2", **ls2},
            {"plc": "%QX0.0", "signal": "PUMP", **(pump or {"module": "direct"})}]
    if level is not None:
        rows.append({"plc": "%IW64", "signal": "LEVEL", **level})
    return rows


def run_tank(rows, duration="10min", **kw):
    sim = Simulation(plclab.loads(TANK), "tank", rows, **kw)
    return sim, sim.run(duration)


@pytest.mark.parametrize("module, delay", [
    ({"module": "direct"}, 0.0),
    ({"module": "di", "filter_ms": 0}, 0.0),
    ({"module": "di", "filter_ms": 3}, 0.01),  # the next scan after 3 ms
    ({"module": "di", "filter_ms": 25}, 0.03),  # the first scan after 25 ms
])
def test_input_filter_delays_what_the_plc_sees(module, delay):
    _, tr = run_tank(tank_rows(module))
    t_plant = tr.first_time("LS2")
    t_plc = tr.first_time("%IX0.1")
    assert t_plant is not None and t_plant > 100
    assert t_plc - t_plant == pytest.approx(delay)
    # the PLC decides in the same scan; the pump (direct output) stops one scan later:
    # a reaction takes 1-2 scans counted from the change in the plant
    t_q = tr.first_time("not %QX0.0", t0=t_plant)
    t_pump = tr.first_time("not PUMP", t0=t_plant)
    assert t_q == pytest.approx(t_plc)
    assert t_pump == pytest.approx(t_plc + 0.01)


def test_bounce_is_visible_at_1_ms_and_the_filter_removes_it():
    rows = [{"plc": "%IX0.0", "signal": "START", "module": "di", "bounce_ms": 4,
             "filter_ms": 0, "bounces": [3, 3]},
            {"plc": "%IX0.1", "signal": "STOP", "module": "direct"},
            {"plc": "%QX0.0", "signal": "K1", "module": "direct"}]
    sc = Scenario().press("START", at="1s", hold="500ms")
    sim = Simulation(plclab.loads(MOTOR), "motor", rows, scenario=sc)
    tr = sim.run("3s")
    t, raw = tr.edge_series("%IX0.0.raw", dt=0.001, t0=0.995, t1=1.01)
    assert int(np.count_nonzero(raw[1:] != raw[:-1])) >= 2  # seen in 1 ms samples
    t, raw = tr.edge_series("%IX0.0.raw", dt=0.00001, t0=0.995, t1=1.01)
    assert int(np.count_nonzero(raw[1:] != raw[:-1])) == 7  # press + 3 off/on pairs
    et, ev = tr.edges["%IX0.0.raw"]
    assert et[0] == pytest.approx(1.0) and et[6] - et[0] <= 0.004
    assert [e.kind for e in tr.events_of("bounce")] == ["bounce", "bounce"]  # press, release
    assert tr.events_of("bounce")[0].data == {"edges": 7}
    # same contact with a 5 ms filter: one clean edge for the PLC
    rows[0]["filter_ms"] = 5
    sim = Simulation(plclab.loads(MOTOR), "motor", rows, scenario=sc)
    tr = sim.run("3s")
    ft, fv = tr.edges["%IX0.0.filtered"]
    assert list(fv) == [True, False]
    assert ft[0] == pytest.approx(et[6] + 0.005)  # 5 ms after the last bounce
    assert tr.switchings("%IX0.0") == 2


def test_analog_input_quantises_to_s7_counts():
    _, tr = run_tank(tank_rows({"module": "direct"}, level={"module": "ai", "lo": 0, "hi": 2}),
                     "20min")
    counts = tr["%IW64"]
    level = tr["LEVEL"]
    assert counts.dtype == np.int64
    assert np.all(np.abs(counts * 2.0 / 27648 - level) <= 1.0 / 27648 + 1e-12)
    assert np.array_equal(counts, np.round(level / 2 * 27648).astype(int))
    ai = AnalogInput(0.0, 2.0, "4-20mA", "s7")  # the module, called every scan, agrees
    ref = [ai.sample(t, x) for t, x in zip(tr.time, level, strict=True)]
    assert np.array_equal(ref, counts)


def test_analog_input_noise_is_seeded_and_has_the_given_size():
    level = {"module": "ai", "lo": 0, "hi": 2, "noise": 0.01, "seed": 1}
    _, tr = run_tank(tank_rows({"module": "direct"}, level=level), "5min")
    err = tr["%IW64"] * 2.0 / 27648 - tr["LEVEL"]
    assert err.std() == pytest.approx(0.01, rel=0.1)
    assert abs(err.mean()) < 0.001
    _, tr2 = run_tank(tank_rows({"module": "direct"}, level=level), "5min")
    assert np.array_equal(tr["%IW64"], tr2["%IW64"])
    _, tr3 = run_tank(tank_rows({"module": "direct"}, level={**level, "seed": 2}), "5min")
    assert not np.array_equal(tr["%IW64"], tr3["%IW64"])


def test_passthrough_transmitter_for_a_milliamp_signal():
    rows = [{"plc": "%IW64", "signal": "LEVEL_MA", "module": "ai"}]
    sc = Scenario().fault("transmitter_open", at="5s")
    sim = Simulation(plclab.loads(TANK), "tank", rows, scenario=sc)
    tr = sim.run("10s")
    ma = tr["LEVEL_MA"][0]
    assert tr["%IW64"][0] == round((ma - 4.0) / 16.0 * 27648)
    assert tr.value_at("%IW64", 6.0) == 32767  # 0 mA: S7 wire-break code


def test_relay_output_delays_the_actuator():
    _, tr_t = run_tank(tank_rows({"module": "direct"}, {"module": "do"}), "10min")
    _, tr_r = run_tank(tank_rows({"module": "direct"}, {"module": "do", "kind": "relay"}),
                       "10min")
    assert tr_t.first_time("PUMP") == pytest.approx(0.01)  # output of scan 0, end of cycle
    assert tr_r.first_time("PUMP") == pytest.approx(0.02)  # + 10 ms pick-up of the relay
    ct, cv = tr_r.edges["%QX0.0.contact"]
    assert ct[0] == pytest.approx(0.02) and cv[0]
    ev = tr_r.events_of("relay")
    assert ev[0].time == pytest.approx(0.02) and ev[0].data["operations"] == 1
    # the relay drops out 5 ms after the command; the plant sees it at the next scan
    t_off = tr_r.first_time("not %QX0.0")
    assert tr_r.first_time("not PUMP", t0=t_off) == pytest.approx(t_off + 0.02)
    assert ev[1].time == pytest.approx(t_off + 0.015)
    # a slow relay (25 ms): three scans
    _, tr_s = run_tank(tank_rows({"module": "direct"}, {"module": "do", "kind": "relay",
                                                        "close_ms": 25}), "1s")
    assert tr_s.first_time("PUMP") == pytest.approx(0.04)


def test_inverted_rows_and_threshold_inputs():
    rows = [{"plc": "%IX0.0", "signal": "LEVEL", "module": "di", "filter_ms": 0,
             "threshold": [0.45, 0.55]},
            {"plc": "%IX0.1", "signal": "LS2", "module": "direct"},
            {"plc": "%IX0.2", "signal": "LS2", "module": "di", "invert": True},
            {"plc": "%QX0.0", "signal": "PUMP", "module": "direct"}]
    _, tr = run_tank(rows, "3min")
    assert tr.value_at("%IX0.2", 1.0) is True  # LS2 FALSE, inverted
    t_on = tr.first_time("%IX0.0")
    assert tr.value_at("LEVEL", t_on) >= 0.55 > tr.value_at("LEVEL", t_on - 0.01)


def test_variables_as_plc_side():
    prog = """PROGRAM Main
    VAR counts : INT; level : REAL; pump : BOOL; speed : INT; END_VAR
    pump := level < 1.0;
    speed := 13824;
    END_PROGRAM"""
    rows = [{"plc": "Main.counts", "signal": "LEVEL", "module": "ai", "lo": 0, "hi": 2},
            {"plc": "level", "signal": "LEVEL", "module": "direct"},
            {"plc": "pump", "signal": "PUMP", "module": "do"},
            {"plc": "Main.speed", "signal": "PUMP_SPEED", "module": "ao", "lo": 0, "hi": 100}]
    sim = Simulation(plclab.loads(prog), "tank", rows, watch=["Main.level"])
    tr = sim.run("30s")
    assert tr["Main.counts"][-1] == round(tr["LEVEL"][-1] / 2 * 27648)
    assert tr["level"][-1] == pytest.approx(tr["LEVEL"][-1], rel=1e-6)  # a REAL: f32
    assert tr["pump"][0] and tr["PUMP"][1]
    assert tr["PUMP_SPEED"][0] == 100.0 and tr["PUMP_SPEED"][1] == pytest.approx(50.0)
    assert "Main.level" not in tr.names  # already recorded as the row's PLC side


def test_direct_real_into_a_located_real():
    prog = """PROGRAM Main
    VAR lvl AT %ID8 : REAL; high : BOOL; END_VAR
    high := lvl > 0.3;
    END_PROGRAM"""
    rows = [{"plc": "%ID8", "signal": "LEVEL", "module": "direct"},
            {"plc": "%QX0.0", "signal": "PUMP", "module": "direct"}]
    sim = Simulation(plclab.loads(prog), "tank", rows, watch=["high", "lvl"])
    tr = sim.run("1s")
    assert tr["%ID8"].dtype == np.float64
    assert tr["lvl"][0] == pytest.approx(0.2, rel=1e-6)
    assert tr.kind("%ID8") == "float"


def test_io_faults_from_the_scenario():
    sc = (Scenario()
          .io_fault("%IW64", "wire_break", at="2s").io_clear("%IW64", at="4s")
          .io_fault("LS2", "stuck_1", at="5s")
          .io_fault("%QX0.0", "welded", at="6s").io_clear("PUMP", at="8s"))
    rows = tank_rows({"module": "di"}, {"module": "do", "kind": "relay"},
                     {"module": "ai", "lo": 0, "hi": 2})
    sim = Simulation(plclab.loads(TANK), "tank", rows, scenario=sc)
    tr = sim.run("10s")
    assert tr.value_at("%IW64", 1.99) != 32767
    assert tr.value_at("%IW64", 2.0) == 32767 and tr.value_at("%IW64", 3.99) == 32767
    assert tr.value_at("%IW64", 4.0) == round(tr.value_at("LEVEL", 4.0) / 2 * 27648)
    assert tr.value_at("LS2", 5.5) is False and tr.value_at("%IX0.1", 5.5) is True
    # LS2 "wet" while the tank is low: the program stops the pump; the welded relay does not
    assert tr.value_at("%QX0.0", 5.5) is False
    assert tr.value_at("PUMP", 7.0) is True
    assert tr.value_at("PUMP", 9.0) is False
    kinds = [(e.kind, e.source) for e in tr.events if e.kind.startswith("io_")]
    assert kinds == [("io_fault", "%IW64"), ("io_clear", "%IW64"), ("io_fault", "%IX0.1"),
                     ("io_fault", "%QX0.0"), ("io_clear", "%QX0.0")]
