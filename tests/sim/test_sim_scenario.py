"""Scenarios: button presses, set points, PLC writes, faults at times, until; their errors."""

from __future__ import annotations

import pytest

import plclab
from plclab.errors import PlcError
from plclab.sim import Scenario, Simulation, load_scenario, run

MOTOR = """PROGRAM Starter
VAR
  START AT %IX0.0 : BOOL; STOP AT %IX0.1 : BOOL; OVERLOAD AT %IX0.4 : BOOL;
  K1 AT %QX0.0 : BOOL; presses : CTU; edge : R_TRIG; limit : REAL := 1.0; delay : TIME;
END_VAR
K1 := (START OR K1) AND STOP AND NOT OVERLOAD;
edge(CLK := START);
presses(CU := edge.Q, PV := 100);
END_PROGRAM"""

TANK = """PROGRAM Main
VAR LS1 AT %IX0.0 : BOOL; LS2 AT %IX0.1 : BOOL; M AT %QX0.0 : BOOL; sp : REAL := 1.0; END_VAR
M := ((NOT LS1) OR M) AND (NOT LS2);
END_PROGRAM"""


def motor_sim(sc, **kw):
    return Simulation(plclab.loads(MOTOR), "motor", scenario=sc, **kw)


def test_press_windows_for_no_and_nc_buttons():
    sc = (Scenario(duration="20s").press("START", at="1s", hold="200ms")
          .press("STOP", at="10s", hold="0.5s").press("START", at="15s"))
    sim = motor_sim(sc, watch=["presses.CV"])
    tr = sim.run()
    assert tr.t_end == 20.0
    assert tr.first_time("START") == 1.0
    assert tr.first_time("not START", t0=1.0) == pytest.approx(1.2)
    assert tr.time_in_band("START", 1, 1) == pytest.approx(0.4)  # 200 ms twice
    assert tr.first_time("not STOP") == 10.0  # NC: pressed = FALSE
    assert tr.first_time("STOP", t0=10.0) == pytest.approx(10.5)
    assert tr.value_at("RUN", 9.0) is True
    assert tr.value_at("RUN", 12.0) is False
    assert tr.value_at("RUN", 19.0) is True
    assert tr["presses.CV"][-1] == 2
    sources = [(e.time, e.source, e.message) for e in tr.events_of("scenario")]
    assert sources[:2] == [(1.0, "START", "press START for 200ms"),
                           (pytest.approx(1.2), "START", "release START")]


def test_actions_happen_at_the_first_scan_at_or_after_their_time():
    sc = Scenario().press("START", at="1.005s", hold="12ms")
    tr = motor_sim(sc).run("2s")
    assert tr.first_time("START") == pytest.approx(1.01)
    assert tr.first_time("not START", t0=1.01) == pytest.approx(1.02)  # 1.017 -> 1.02


def test_set_ramp_and_plc_variable_writes():
    sc = (Scenario().set("VALVE", 30, at="5s").ramp("VALVE", 80, at="10s", over="10s")
          .var("Main.sp", 55.0, at="3s").var("sp", "REAL#7.5", at="4s"))
    sim = Simulation(plclab.loads(TANK), "tank", scenario=sc, watch=["sp"])
    tr = sim.run("30s")
    assert tr.value_at("VALVE", 4.99) == 100.0
    assert tr.value_at("VALVE", 5.0) == 30.0
    assert tr.value_at("VALVE", 15.0) == pytest.approx(55.0)
    assert tr.value_at("VALVE", 20.0) == 80.0 and tr["VALVE"][-1] == 80.0
    assert tr.value_at("sp", 2.99) == 1.0
    assert tr.value_at("sp", 3.0) == 55.0
    assert tr.value_at("sp", 4.0) == 7.5


def test_faults_at_times_with_duration_and_clear():
    sc = (Scenario().fault("leak", at="2s", area=0.001).clear("leak", at="4s")
          .fault("ls2_stuck_off", at="1s", hold="500ms"))
    sim = Simulation(plclab.loads(TANK), "tank", scenario=sc)
    tr = sim.run("5s")
    inj = tr.events_of("fault_injected")
    assert [(e.time, e.data["fault"]) for e in inj] == [(1.0, "ls2_stuck_off"), (2.0, "leak")]
    assert inj[1].data["area"] == 0.001
    cleared = tr.events_of("fault_cleared")
    assert [(e.time, e.data["fault"]) for e in cleared] == [(1.5, "ls2_stuck_off"),
                                                            (4.0, "leak")]
    assert sim.plant.active_faults == {}


def test_force_and_unforce():
    sc = (Scenario().press("START", at="0.5s").force("%QX0.0", False, at="1s")
          .unforce("%QX0.0", at="2s"))
    tr = motor_sim(sc, watch=["K1"]).run("3s")
    assert tr.value_at("%QX0.0", 0.9) is True
    # the program's K1 is recorded as plc:K1 (the plant has a signal K1: the contactor coil)
    assert tr.value_at("%QX0.0", 1.5) is False and tr.value_at("plc:K1", 1.5) is True
    assert tr.value_at("K1", 1.5) is False
    assert tr.value_at("RUN", 1.9) is False
    assert tr.value_at("%QX0.0", 2.5) is True


def test_until_expression_and_callable():
    sc = Scenario(duration="1h", until="LEVEL > 1.0")
    sim = Simulation(plclab.loads(TANK), "tank", scenario=sc)
    tr = sim.run()
    assert tr["LEVEL"][-1] > 1.0 >= tr["LEVEL"][-2]
    assert sim.stop_reason.startswith("until 'LEVEL > 1.0'")
    assert tr.events[-1].kind == "until" and tr.meta["stop_reason"] == sim.stop_reason
    # a PLC variable and time in the condition, given to run()
    sim2 = Simulation(plclab.loads(TANK), "tank")
    tr2 = sim2.run("1h", until="Main.M and t >= 2.5")
    assert tr2.t_end == pytest.approx(2.51)
    sim3 = Simulation(plclab.loads(TANK), "tank")
    tr3 = sim3.run("1h", until=lambda s: s.plant["LEVEL"] > 0.3)
    assert tr3["LEVEL"][-1] > 0.3 and tr3.t_end < 100
    # the simulation can go on afterwards
    tr4 = sim3.run("1s")
    assert tr4.t_end == pytest.approx(tr3.t_end + 1.0)


def test_scenario_toml_file(tmp_path):
    wiring = tmp_path / "w.toml"
    wiring.write_text('plant = "motor"\nwiring = [\n'
                      '  { plc = "%IX0.0", signal = "START", module = "direct" },\n'
                      '  { plc = "%IX0.1", signal = "STOP", module = "direct" },\n'
                      '  { plc = "%QX0.0", signal = "K1", module = "do" },\n]\n')
    f = tmp_path / "s.toml"
    f.write_text('description = "start, overload, stop"\nplant = "motor"\nwiring = "w.toml"\n'
                 'duration = "30s"\nscan = "10ms"\nseed = 4\nwatch = ["presses.CV"]\n\n'
                 '[[action]]\nat = "1s"\npress = "START"\nfor = "300ms"\n\n'
                 '[[action]]\nat = "20s"\npress = "STOP"\n\n'
                 '[[action]]\nat = "5s"\nvar = "limit"\nvalue = 2.5\n'
                 'description = "raise the limit"\n')
    sc = load_scenario(f)
    assert sc.duration == 30.0 and sc.seed == 4 and len(sc.actions) == 3
    assert sc.actions[2].text() == "raise the limit"
    tr = run(MOTOR, scenario=f)
    assert tr.meta["plant"] == "motor" and tr.meta["seed"] == 4 and tr.t_end == 30.0
    assert tr.meta["wiring"].endswith("w.toml")
    assert tr.first_time("RUN") is not None and tr["RUN"][-1] is False or not tr["RUN"][-1]
    assert tr["presses.CV"][-1] == 1
    assert [e.message for e in tr.events_of("scenario", source="limit")] == ["raise the limit"]


def test_scenario_from_a_list_of_dicts():
    tr = run(MOTOR, "motor", "3s", scenario=[{"at": 1, "press": "START"}])
    assert tr.first_time("START") == 1.0


# --------------------------------------------------------------------------- errors
@pytest.mark.parametrize("action, code, words", [
    ({"at": 1, "pres": "START"}, "PLC4010", "Did you mean 'press'"),
    ({"at": 1}, "PLC4010", "no verb"),
    ({"at": 1, "press": "START", "set": "STOP", "value": 1}, "PLC4010", "two verbs"),
    ({"press": "START"}, "PLC4010", "'at' is missing"),
    ({"at": 1, "set": "VALVE"}, "PLC4010", "needs 'value'"),
    ({"at": 1, "press": "START", "value": 1}, "PLC4010", "does not take 'value'"),
    ({"at": 1, "ramp": "VALVE", "to": 5}, "PLC4010", "needs 'over'"),
    ({"at": 1, "io_fault": "wire_break"}, "PLC4010", "needs 'plc'"),
    ({"at": 1, "fault": "leak", "params": 3}, "PLC4010", "params must be a table"),
    ({"at": "1 parsec", "press": "START"}, "PLC4012", "not a duration"),
    ({"at": -1, "press": "START"}, "PLC4012", "positive"),
    ({"at": 1, "press": "START", "for": "long"}, "PLC4012", "not a duration"),
    ({"at": 1, "set": "VALVE", "value": [1]}, "PLC4015", "not a value"),
    ({"at": 1, "ramp": "VALVE", "to": "x", "over": 1}, "PLC4015", "number"),
])
def test_action_shape_errors(action, code, words):
    with pytest.raises(PlcError) as e:
        Scenario([action])
    assert e.value.code == code, e.value
    assert words in e.value.message


@pytest.mark.parametrize("action, code, words", [
    ({"at": 1, "press": "RUN"}, "PLC4011", "sensor"),
    ({"at": 1, "press": "START2"}, "PLC4011", "Did you mean 'START'"),
    ({"at": 1, "set": "K1", "value": True}, "PLC4011", "wiring row"),
    ({"at": 1, "press": "SPEED"}, "PLC4011", "sensor"),
    ({"at": 1, "var": "nosuch", "value": 1}, "PLC4011", "no variable"),
    ({"at": 1, "var": "limit", "value": "T#5s"}, "PLC4015", ""),
    ({"at": 1, "var": "delay", "value": True}, "PLC4015", ""),
    ({"at": 1, "set": "START", "value": 5}, "PLC4015", "true or false"),
    ({"at": 1, "fault": "meltdown"}, "PLC4014", "overload"),
    ({"at": 1, "fault": "overlaod"}, "PLC4014", "Did you mean 'overload'"),
    ({"at": 1, "clear": "meltdown"}, "PLC4014", ""),
    ({"at": 1, "io_fault": "wire_break", "plc": "%IX0.0"}, "PLC4014", "open, stuck_1"),
    ({"at": 1, "io_fault": "open", "plc": "%QX7.7"}, "PLC4014", "no wiring row"),
    ({"at": 1, "io_fault": "open", "plc": "%IX0.0", "value": 3.0}, "PLC4010", "stuck"),
])
def test_action_target_errors(action, code, words):
    with pytest.raises(PlcError) as e:
        motor_sim(Scenario([action]))
    assert e.value.code == code, e.value
    assert words in e.value.message


def test_tank_specific_target_errors():
    with pytest.raises(PlcError) as e:
        Simulation(plclab.loads(TANK), "tank", scenario=[{"at": 1, "set": "VALVE",
                                                          "value": 130}])
    assert e.value.code == "PLC4015" and "0..100" in e.value.message
    with pytest.raises(PlcError) as e:
        Simulation(plclab.loads(TANK), "tank", scenario=[{"at": 1, "ramp": "LS1", "to": 1,
                                                          "over": 1}])
    assert e.value.code == "PLC4011"
    # an actuator no wiring row drives may be set (the tank's PUMP_SPEED)
    sim = Simulation(plclab.loads(TANK), "tank",
                     scenario=[{"at": 1, "set": "PUMP_SPEED", "value": 50}])
    assert sim.run("2s").value_at("PUMP_SPEED", 1.5) == 50.0


def test_errors_in_a_scenario_file_name_the_line(tmp_path):
    f = tmp_path / "s.toml"
    f.write_text('duration = "1min"\n\n[[action]]\nat = "1s"\npress = "START"\n\n'
                 '[[action]]\nat = "2s"\npres = "STOP"\n')
    with pytest.raises(PlcError) as e:
        load_scenario(f)
    assert e.value.code == "PLC4010" and e.value.location.line == 7
    assert f"{f}:7:" in str(e.value)
    g = tmp_path / "t.toml"
    g.write_text('[[action]]\nat = "1s"\npress = "STARTT"\n')
    with pytest.raises(PlcError) as e:
        motor_sim(load_scenario(g))
    assert e.value.code == "PLC4011" and e.value.location.line == 1
    h = tmp_path / "u.toml"
    h.write_text('duration = "1min"\nuntil = "LEVEL >"\n')
    with pytest.raises(PlcError) as e:
        load_scenario(h)
    assert e.value.code == "PLC4013" and e.value.location.line == 2
    k = tmp_path / "k.toml"
    k.write_text('durration = "1min"\n')
    with pytest.raises(PlcError) as e:
        load_scenario(k)
    assert e.value.code == "PLC4010" and "duration" in e.value.message
    with pytest.raises(PlcError) as e:
        load_scenario(tmp_path / "missing.toml")
    assert e.value.code == "PLC4001"


def test_until_errors():
    with pytest.raises(PlcError) as e:
        Scenario(until="LEVEL >> 2")
    assert e.value.code == "PLC4013"
    with pytest.raises(PlcError) as e:
        Scenario(until="__import__('os').system('x')")
    assert e.value.code == "PLC4013"
    with pytest.raises(PlcError) as e:
        Simulation(plclab.loads(TANK), "tank").run("1s", until="LEVL > 1")
    assert e.value.code == "PLC4013" and "LEVEL" in e.value.message
    with pytest.raises(PlcError) as e:
        Scenario(until=42)
    assert e.value.code == "PLC4013"


def test_scenario_for_another_plant():
    with pytest.raises(PlcError) as e:
        Simulation(plclab.loads(TANK), "tank", scenario=Scenario(plant="motor"))
    assert e.value.code == "PLC4008"
