"""One closed loop per plant: a simple, correct ST program on the default wiring meets its goal."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from plclab.sim import Scenario, run

ST = Path(__file__).resolve().parents[1] / "st"

BAD = {"overflow", "dry_run", "flooded", "emergency_level", "dry_heating", "drum_dry", "crash",
       "moved_without_two_hands", "curtain_violation", "cold_extrusion", "overheat",
       "valve_conflict", "plc_fault", "spill"}


def bad_events(tr):
    return [e for e in tr.events if e.kind in BAD]


TANK = """PROGRAM TankLevel
VAR
    LS1 AT %IX0.0 : BOOL;   (* low level switch *)
    LS2 AT %IX0.1 : BOOL;   (* high level switch *)
    M AT %QX0.0 : BOOL;     (* pump *)
END_VAR
M := ((NOT LS1) OR M) AND (NOT LS2);
END_PROGRAM"""


def test_tank_two_position_control_keeps_the_level_between_the_switches():
    tr = run(TANK, "tank", "40min")
    assert not bad_events(tr)
    t_up = tr.first_time("LS1")  # start-up: the level reaches the low switch
    assert t_up is not None and t_up < 300
    lo, hi = 0.5, 1.5  # switch heights
    assert tr.time_in_band("LEVEL", lo - 0.01, hi + 0.01, t0=t_up, fraction=True) == 1.0
    assert tr["LEVEL"].max() < 1.55 and tr["LEVEL"].max() > hi
    assert tr.switchings("PUMP") >= 5
    mon, moff = tr.min_dwell("PUMP")
    assert mon > 60 and moff > 60  # no chatter: minutes between switchings
    assert tr.chatter_episodes("PUMP", min_toggles=3, window=30.0) == []
    assert len(tr.events_of("relay")) == tr.switchings("PUMP")


MOTOR = """PROGRAM Starter
VAR
    START AT %IX0.0 : BOOL;     (* NO push button *)
    STOP AT %IX0.1 : BOOL;      (* NC push button: TRUE while not pressed *)
    OVERLOAD AT %IX0.4 : BOOL;  (* TRUE = tripped *)
    K1 AT %QX0.0 : BOOL;        (* contactor coil *)
END_VAR
K1 := (START OR K1) AND STOP AND NOT OVERLOAD;
END_PROGRAM"""


def test_motor_start_stop_seal_in():
    sc = (Scenario(duration="40s").press("START", at="1s").press("STOP", at="12s")
          .press("START", at="20s").fault("overload", at="30s"))
    tr = run(MOTOR, "motor", scenario=sc)
    assert not bad_events(tr)
    assert tr.first_time("RUN") == pytest.approx(1.05, abs=0.02)  # filter, scan, relay, pick-up
    assert tr.value_at("SPEED", 11.0) > 1400  # sealed in after START was released at 1.2 s
    assert tr.value_at("RUN", 12.5) is False
    assert tr.value_at("RUN", 25.0) is True
    assert tr.value_at("RUN", 31.0) is False and tr.value_at("%QX0.0", 31.0) is False
    kinds = [e.kind for e in tr.events if e.source == "motor"]
    assert kinds[:3] == ["motor_started", "motor_stopped", "motor_started"]
    assert sorted(kinds[3:]) == ["fault_injected", "motor_stopped", "overload_trip"]


HEATER = """PROGRAM Thermostat
VAR
    TEMP_RAW AT %IW64 : INT;    (* 4-20 mA, -20..120 degC *)
    HEATER AT %QX0.0 : BOOL;
    temp : REAL;
    sp : REAL := 60.0;
    hyst : REAL := 2.0;
END_VAR
temp := -20.0 + INT_TO_REAL(TEMP_RAW) * 140.0 / 27648.0;
IF temp < sp - hyst THEN
    HEATER := TRUE;
ELSIF temp > sp + hyst THEN
    HEATER := FALSE;
END_IF;
END_PROGRAM"""


def test_heater_thermostat_reaches_and_holds_the_band():
    tr = run(HEATER, "heater", "1h", scan="100ms", plant_params={"area": 0.1},
             watch=["temp"])
    assert not bad_events(tr)
    t_in = tr.first_time("TEMP >= 58")
    assert t_in is not None and t_in < 1800
    assert tr.time_in_band("TEMP", 57.5, 62.5, t0=t_in, fraction=True) == 1.0
    assert tr.switchings("HEATER") >= 2
    assert min(x for x in tr.min_dwell("HEATER") if x is not None) > 60
    assert abs(tr["temp"] - tr["TEMP"]).max() < 0.01  # the AI's scaling is right


CONVEYOR = """PROGRAM Line
VAR
    START AT %IX0.0 : BOOL; STOP AT %IX0.1 : BOOL;
    X1 AT %IX0.2 : BOOL;        (* high eye: neck *)
    X2 AT %IX0.3 : BOOL;        (* low eye: body *)
    CONVEYOR AT %QX0.0 : BOOL; REJECT AT %QX0.1 : BOOL;
    eye : R_TRIG;
    bottles : CTU;
END_VAR
CONVEYOR := (START OR CONVEYOR) AND STOP;
REJECT := X2 AND NOT X1;            (* a fallen bottle breaks only the low beam *)
eye(CLK := X2);
bottles(CU := eye.Q, PV := 32767);
END_PROGRAM"""


def test_conveyor_runs_counts_bottles_and_rejects_the_fallen_ones():
    sc = Scenario().press("START", at="1s").press("STOP", at="100s")
    tr = run(CONVEYOR, "conveyor", "110s", scenario=sc, watch=["bottles.CV"], snapshot=True)
    assert not bad_events(tr)
    assert tr.value_at("BELT_SPEED", 50.0) == pytest.approx(0.4)
    assert tr.value_at("BELT_SPEED", 105.0) == 0.0
    counted = tr["bottles.CV"][-1]
    binned = len(tr.events_of("bottle_binned"))
    rejected = len(tr.events_of("bottle_rejected"))
    assert binned > 40 and rejected > 0
    # every bottle past the eyes was counted once (some are still between the eyes and the end)
    assert binned + rejected <= counted <= binned + rejected + 4
    assert tr["snapshot:standing_rejected"][-1] == 0  # only fallen bottles were pushed off
    assert tr["snapshot:fallen_passed"][-1] == 0


VENTILATION = """PROGRAM Fans
VAR
    MS AT %IX0.0 : BOOL; START AT %IX0.1 : BOOL; STOP AT %IX0.2 : BOOL;
    FAULT1 AT %IX0.3 : BOOL; FAULT2 AT %IX0.4 : BOOL; FAULT3 AT %IX0.5 : BOOL;
    MAIN_POWER AT %QX0.0 : BOOL;
    FAN1 AT %QX0.1 : BOOL;      (* standby *)
    FAN2 AT %QX0.2 : BOOL; FAN3 AT %QX0.3 : BOOL;
    FAULT_LAMP AT %QX0.5 : BOOL;
    cycle : BOOL; nfault : INT;
END_VAR
cycle := MS AND (START OR cycle) AND STOP;
nfault := BOOL_TO_INT(FAULT1) + BOOL_TO_INT(FAULT2) + BOOL_TO_INT(FAULT3);
MAIN_POWER := cycle AND nfault < 2;
FAN2 := MAIN_POWER AND NOT FAULT2;
FAN3 := MAIN_POWER AND NOT FAULT3;
FAN1 := MAIN_POWER AND NOT FAULT1 AND (FAULT2 OR FAULT3);
FAULT_LAMP := nfault > 0;
END_PROGRAM"""


def test_ventilation_two_fans_run_and_the_standby_takes_over():
    sc = (Scenario().set("MS", True, at=0).press("START", at="1s")
          .fault("fan2_fail", at="60s").fault("fan3_fail", at="300s"))
    tr = run(VENTILATION, "ventilation", "6min", scan="100ms", scenario=sc)
    running = sum((tr[f"CURRENT{i}"] > 1.0).astype(int) for i in (1, 2, 3))
    after_start = (tr.time > 20) & (tr.time < 300)
    assert np.mean(running[after_start] == 2) > 0.95  # two fans run ...
    assert running[after_start].min() >= 1  # ... and never fewer than one while changing over
    assert tr.first_time("FAN1") == pytest.approx(60.3, abs=0.11)
    assert tr.value_at("FAULT_LAMP", 61.0) is True
    assert tr.value_at("MAIN_POWER", 299.0) is True and tr.value_at("MAIN_POWER", 301.0) is False
    assert "overheat" not in [e.kind for e in tr.events]


SUMP_MAIN = """
PROGRAM Station
VAR
    NY AT %IX0.0 : BOOL; WY AT %IX0.1 : BOOL; PWY AT %IX0.2 : BOOL; AWY AT %IX0.3 : BOOL;
    DAWL AT %IX0.4 : BOOL;
    ZAL AT %QX0.0 : BOOL; NS1 AT %QX0.1 : BOOL; NS2 AT %QX0.2 : BOOL; NS3 AT %QX0.3 : BOOL;
    ps : PumpStation;   (* the textbook's program, tests/st/pump_station.st *)
END_VAR
ps(NY := NY, DAWL := DAWL, WY := WY, PWY := PWY, AWY := AWY, qt := T#600s);
ZAL := ps.ZAL; NS1 := ps.NS1; NS2 := ps.NS2; NS3 := ps.NS3;
END_PROGRAM
"""


def test_sump_textbook_program_keeps_the_mine_dry():
    tr = run([ST / "pump_station.st", SUMP_MAIN], "sump", "4h", scan="200ms")
    assert not bad_events(tr)
    assert tr.events_of("primed")
    assert tr["LEVEL"].max() < 3.0  # below the raised mark: pump 1 copes
    assert tr.switchings("NS1") >= 4  # several pumping cycles
    assert tr.first_time("NS1") > tr.first_time("DAWL")  # pumps only after priming


PRESS = """PROGRAM Press
VAR
    HAND_L AT %IX0.0 : BOOL; HAND_R AT %IX0.1 : BOOL; CURTAIN AT %IX0.2 : BOOL;
    ESTOP AT %IX0.3 : BOOL; BOTTOM AT %IX0.5 : BOOL; PULSE AT %IX0.6 : BOOL;
    DOWN AT %QX0.0 : BOOL; UP AT %QX0.1 : BOOL; HEATER AT %QX0.2 : BOOL;
    POS_RAW AT %IW64 : INT; TEMP_RAW AT %IW66 : INT;
    pos : REAL; temp : REAL; safe : BOOL; goingUp : BOOL;
    edge : R_TRIG; pulses : CTU;
END_VAR
pos := INT_TO_REAL(POS_RAW) * 200.0 / 27648.0;
temp := INT_TO_REAL(TEMP_RAW) * 400.0 / 27648.0;
IF temp < 215.0 THEN HEATER := TRUE; ELSIF temp > 225.0 THEN HEATER := FALSE; END_IF;
safe := HAND_L AND HAND_R AND CURTAIN AND ESTOP;
IF BOTTOM THEN goingUp := TRUE; END_IF;
IF goingUp AND pos < 8.0 THEN goingUp := FALSE; END_IF;   (* stop short of the top stop *)
DOWN := safe AND temp > 190.0 AND NOT BOTTOM AND NOT goingUp;
UP := goingUp AND CURTAIN AND ESTOP;
edge(CLK := PULSE);
pulses(CU := edge.Q AND DOWN, PV := 10000);
END_PROGRAM"""


def test_press_heats_then_doses_one_stroke_safely():
    sc = (Scenario().press("LIGHT_CURTAIN", at="479s", hold="2s")  # someone reaches in
          .press("HAND_L", at="8min", hold="12s").press("HAND_R", at="8min", hold="12s"))
    tr = run(PRESS, "press", "500s", scenario=sc, watch=["pulses.CV", "goingUp"])
    assert not bad_events(tr)
    assert tr.first_time("DOWN") == pytest.approx(481.02)  # not before the curtain is clear
    t_bottom = tr.first_time("BOTTOM")
    assert 488 < t_bottom < 490
    assert tr.first_time("not goingUp", t0=t_bottom) is not None  # back up
    travel = tr["POSITION"].max()
    assert abs(tr["pulses.CV"].max() - travel) <= 2  # the encoder was counted exactly
    assert tr.value_at("POSITION", 499.0) < 10.0


WASHER = """PROGRAM Wash
VAR
    START AT %IX0.0 : BOOL; COTTON AT %IX0.2 : BOOL;
    LEVEL_SW AT %IX0.4 : BOOL; EMPTY AT %IX0.5 : BOOL;
    FILL AT %QX0.0 : BOOL; DRAIN AT %QX0.1 : BOOL; HEATER AT %QX0.2 : BOOL;
    MOTOR AT %QX0.3 : BOOL;
    TEMP_RAW AT %IW66 : INT;
    step : INT;     (* 0 idle, 1 fill, 2 wash, 3 cool, 4 drain, 5 done *)
    t : TON; temp : REAL; washTime : TIME;
END_VAR
temp := INT_TO_REAL(TEMP_RAW) * 100.0 / 27648.0;
IF COTTON THEN washTime := T#10m; ELSE washTime := T#5m; END_IF;
CASE step OF
    0: IF START THEN step := 1; END_IF;
    1: IF LEVEL_SW THEN step := 2; END_IF;
    2: IF t.Q THEN step := 3; END_IF;
    3: IF temp <= 40.0 THEN step := 4; END_IF;
    4: IF EMPTY THEN step := 5; END_IF;
END_CASE;
t(IN := step = 2, PT := washTime);
FILL := step = 1 OR (step = 3 AND NOT LEVEL_SW);
DRAIN := (step = 3 AND LEVEL_SW) OR step = 4;
HEATER := step = 2;
MOTOR := step = 2 OR step = 3;
END_PROGRAM"""


@pytest.mark.parametrize("mode", ["cotton", "silk"])
def test_washer_runs_its_cycle(mode):
    sc = Scenario().press("START", at="2s")
    if mode == "silk":
        sc.set("COTTON", False, at=0).set("SILK", True, at=0)
    tr = run(WASHER, "washer", "1h", scan="100ms", scenario=sc, watch=["step"],
             until="Wash.step = 5")
    assert not bad_events(tr)
    assert tr["step"][-1] == 5 and tr.meta["stop_reason"]
    assert list(np.unique(tr["step"])) == [0, 1, 2, 3, 4, 5]
    wash = tr.time_in_band("step", 2, 2)
    assert wash == pytest.approx(600.0 if mode == "cotton" else 300.0, abs=0.5)
    assert tr["TEMP"].max() > 28.0
    assert tr.value_at("TEMP", tr.first_time("step >= 4")) <= 40.5
    assert tr["EMPTY"][-1]
