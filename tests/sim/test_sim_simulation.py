"""The simulation loop: one clock, order of the steps, determinism, recording options, set-up
errors (PLC4020)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import plclab
from plants import get_plant
from plclab.errors import PlcError
from plclab.sim import Scenario, Simulation, format_duration, parse_ns, run

TANK = """PROGRAM Main
VAR
  LS1 AT %IX0.0 : BOOL; LS2 AT %IX0.1 : BOOL; M AT %QX0.0 : BOOL; lvl AT %IW64 : INT;
  n : DINT; t_plc : TIME;
END_VAR
M := ((NOT LS1) OR M) AND (NOT LS2);
n := n + 1;
END_PROGRAM"""

VFD = Path(__file__).resolve().parents[2] / "plclab" / "sim" / "wirings" / "tank_vfd.toml"


def sim_tank(**kw):
    return Simulation(plclab.loads(TANK), "tank", **kw)


def test_one_clock_for_plc_plant_and_trace():
    sim = sim_tank(watch=["n"])
    tr = sim.run("2s")
    assert sim.k == 200 and sim.time == 2.0
    assert sim.plc.time == 2.0 and sim.plant.time == 2.0  # lockstep, exactly
    assert np.allclose(tr.time, np.arange(200) * 0.01, rtol=0, atol=1e-12)
    assert list(tr["n"][:3]) == [1, 2, 3]  # row k: after scan k
    assert tr.meta["scan"] == 0.01 and tr.meta["substeps"] == 1 and tr.t_end == 2.0


def test_runs_continue_and_step_scans():
    sim = sim_tank()
    sim.run("1s")
    sim.step(5)
    tr = sim.run(0.5)
    assert sim.k == 155 and len(tr) == 155 and tr.t_end == pytest.approx(1.55)
    # the PLC may not be scanned behind the simulation's back
    sim.plc.scan()
    with pytest.raises(PlcError) as e:
        sim.step()
    assert e.value.code == "PLC4020" and "clock" in e.value.message


def test_plant_sub_steps():
    sim = Simulation(plclab.loads(TANK), "press", [])
    assert sim.substeps == 5 and sim.dt == pytest.approx(0.002)
    sim = Simulation(plclab.loads(TANK), "tank", [], dt="2.5ms")
    assert sim.substeps == 4
    sim = Simulation(plclab.loads(TANK, cycle_time="100ms"), "motor", [])
    assert sim.substeps == 20 and sim.dt == pytest.approx(0.005)
    with pytest.raises(PlcError) as e:
        Simulation(plclab.loads(TANK), "tank", [], dt="3ms")
    assert e.value.code == "PLC4020" and "5ms" in e.value.message


def test_scan_must_match_the_plc():
    sim = Simulation(plclab.loads(TANK, cycle_time="50ms"), "tank")
    assert sim.scan == 0.05
    sim = Simulation(plclab.loads(TANK, cycle_time="50ms"), "tank", scan="T#50ms")
    with pytest.raises(PlcError) as e:
        Simulation(plclab.loads(TANK), "tank", scan="100ms")
    assert e.value.code == "PLC4020" and "cycle_time='100ms'" in e.value.message
    with pytest.raises(PlcError) as e:
        Simulation(plclab.loads(TANK), "tank", scan="fast")
    assert e.value.code == "PLC4012"


def test_tasks_set_the_tick():
    prog = TANK + """
CONFIGURATION C RESOURCE R ON PLC
  TASK Fast (INTERVAL := T#20ms, PRIORITY := 1);
  PROGRAM Main1 WITH Fast : Main;
END_RESOURCE END_CONFIGURATION"""
    sim = Simulation(plclab.loads(prog), "tank")
    assert sim.scan == 0.02
    assert run(prog, "tank", "1s").meta["scan"] == 0.02  # run() follows the tasks too


def test_same_seed_same_trace_different_seed_differs():
    def once(seed):
        sc = Scenario().set("VALVE", 50, at="20s").fault("leak", at="40s")
        sim = Simulation(plclab.loads(TANK), "tank", VFD, seed=seed, scenario=sc,
                         watch=["n"])
        return sim.run("60s")

    a, b, c = once(3), once(3), once(4)
    assert a.equals(b)
    for name in a.names:
        assert np.array_equal(a[name], b[name])
    assert not a.equals(c)
    assert not np.array_equal(a["%IW64"], c["%IW64"])  # the noise changes with the seed
    assert np.array_equal(a["%IX0.0"], c["%IX0.0"])  # the switches do not have any
    # wall-clock time is recorded apart and does not spoil equality
    assert a.wall["scan_s"].shape == a.time.shape and (a.wall["scan_s"] > 0).all()


def test_plant_randomness_follows_the_seed():
    a = run("PROGRAM P VAR x : INT; END_VAR x := 1; END_PROGRAM", "sump", "10min", seed=1)
    b = run("PROGRAM P VAR x : INT; END_VAR x := 1; END_PROGRAM", "sump", "10min", seed=1)
    c = run("PROGRAM P VAR x : INT; END_VAR x := 1; END_PROGRAM", "sump", "10min", seed=2)
    assert a.equals(b) and not np.array_equal(a["LEVEL"], c["LEVEL"])


def test_decimate_snapshot_and_watch():
    sim = sim_tank(decimate=10, snapshot=True, watch=["n", "Main.t_plc", "M", "%IX0.0"])
    tr = sim.run("1s")
    assert len(tr) == 10 and list(tr.time[:2]) == [0.0, pytest.approx(0.1)]
    assert tr.meta["period"] == pytest.approx(0.1) and tr.t_end == 1.0
    assert list(tr["n"][:2]) == [1, 11]
    assert tr.kind("Main.t_plc") == "int" and tr["Main.t_plc"][0] == 0
    assert "volume" in tr.names and tr["snapshot:volume"][0] == pytest.approx(0.2)
    assert tr["M"].dtype == bool
    assert "%IX0.0" in tr.names and tr.names.count("%IX0.0") == 1
    with pytest.raises(PlcError) as e:
        sim_tank(decimate=0)
    assert e.value.code == "PLC4020"
    with pytest.raises(PlcError) as e:
        sim_tank(watch=["nosuch"])
    assert e.value.code == "PLC4020" and "nosuch" in e.value.message
    with pytest.raises(PlcError) as e:
        Simulation(plclab.loads("PROGRAM P VAR s : STRING; a : ARRAY[1..2] OF INT; END_VAR "
                                "s := 'x'; END_PROGRAM"), "tank", [], watch=["a"])
    assert e.value.code == "PLC4020" and "element" in e.value.message


def test_io_columns_and_names():
    tr = sim_tank().run("1s")
    assert tr.signals == ["PUMP", "PUMP_SPEED", "VALVE", "LS1", "LS2", "LEVEL", "LEVEL_MA",
                          "FLOW_IN", "FAULT_LAMP"]
    rows = {r["plc"]: r for r in tr.io}
    assert rows["%IX0.0"]["plant_column"] == "LS1" and rows["%IX0.0"]["direction"] == "in"
    assert rows["%QX0.0"]["module"] == "do" and rows["%QX0.0"]["direction"] == "out"
    plant_side, plc_side = tr.io_pair("LS1")
    assert plant_side.dtype == bool and plc_side.dtype == bool
    assert tr.kind("%IW64") == "int"
    assert tr.meta["signal_info"]["LEVEL"]["unit"] == "m"


def test_plc_fault_is_an_event_and_outputs_go_off():
    prog = """PROGRAM Main
    VAR M AT %QX0.0 : BOOL; n : INT; d : INT; END_VAR
    M := TRUE;
    n := n + 1;
    IF n > 50 THEN d := 100 / (n - n); END_IF;
    END_PROGRAM"""
    sim = Simulation(plclab.loads(prog), "tank", [{"plc": "%QX0.0", "signal": "PUMP",
                                                    "module": "direct"}])
    tr = sim.run("2s")
    ev = tr.events_of("plc_fault")
    assert len(ev) == 1 and ev[0].time == pytest.approx(0.5) and "PLC2001" in ev[0].message
    assert tr.value_at("PUMP", 0.4) is True and tr.value_at("PUMP", 0.6) is False
    assert tr.value_at("%QX0.0", 0.49) is True and tr.value_at("%QX0.0", 0.5) is False
    assert sim.plc.state == "STOP" and sim.plc.time == 2.0
    sim = Simulation(plclab.loads(prog), "tank", [], stop_on_fault=True)
    with pytest.raises(PlcError) as e:
        sim.run("2s")
    assert e.value.code == "PLC2001" and e.value.location.line == 5


def test_plant_objects_and_parameters():
    tank = get_plant("tank", area=2.0)
    tank.inject("leak")
    sim = Simulation(plclab.loads(TANK), tank)
    assert sim.plant is tank and tank.active_faults == {}  # reset with the seed
    tr = Simulation(plclab.loads(TANK), "tank", plant_params={"area": 2.0}).run("10s")
    assert tr.meta["plant"] == "tank"
    with pytest.raises(PlcError) as e:
        Simulation(plclab.loads(TANK), "tnak")
    assert e.value.code == "PLC4020" and "tank" in e.value.message
    with pytest.raises(PlcError) as e:
        Simulation(plclab.loads(TANK), "tank", plant_params={"aera": 2.0})
    assert e.value.code == "PLC4020" and "area" in e.value.message
    with pytest.raises(PlcError) as e:
        Simulation(plclab.loads(TANK), tank, plant_params={"area": 2.0})
    assert e.value.code == "PLC4020"
    with pytest.raises(PlcError) as e:
        Simulation("not a plc", "tank")
    assert e.value.code == "PLC4020"


def test_run_needs_a_duration():
    with pytest.raises(PlcError) as e:
        sim_tank().run()
    assert e.value.code == "PLC4020"
    with pytest.raises(PlcError) as e:
        sim_tank().run("soon")
    assert e.value.code == "PLC4012"


def test_run_helper_takes_text_paths_and_plcs(tmp_path):
    f = tmp_path / "tank.st"
    f.write_text(TANK)
    a = run(str(f), "tank", "5s")
    b = run(TANK, "tank", "5s")
    c = run(plclab.loads(TANK), "tank", "5s")
    d = run([f], "tank", "5s")
    assert a.equals(b) and b.equals(c) and c.equals(d)
    assert run(TANK, duration="1s", scan="50ms").meta["scan"] == 0.05
    with pytest.raises(PlcError) as e:
        run(str(tmp_path / "missing.st"))
    assert e.value.code == "PLC3003"


def test_durations():
    assert parse_ns("10min") == 600 * 10**9
    assert parse_ns("1h") == 3600 * 10**9
    assert parse_ns("90s") == 90 * 10**9
    assert parse_ns("T#1m") == 60 * 10**9
    assert parse_ns("1h30m") == parse_ns("90 min") == parse_ns("5400")
    assert parse_ns("2.5ms") == 2_500_000 and parse_ns(0.01) == 10**7 and parse_ns(2) == 2 * 10**9
    assert parse_ns("LTIME#1d") == 86400 * 10**9
    for bad in ("", "x", "10 parsecs", "1h-", True, None, float("nan"), "-5s"):
        with pytest.raises(PlcError) as e:
            parse_ns(bad)
        assert e.value.code == "PLC4012"
    with pytest.raises(PlcError):
        parse_ns(0, allow_zero=False)
    assert format_duration(5400) == "1h30min" and format_duration(0.01) == "10ms"
