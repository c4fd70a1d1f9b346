"""Simulation speed: real-time factor (simulated time / wall time) of three closed loops.

    python benchmarks/sim_bench.py            # the full runs (about half a minute)
    python benchmarks/sim_bench.py --quick    # a tenth of the simulated time
    python benchmarks/sim_bench.py --profile tank   # cProfile of one case

Cases (default wiring of each plant, every scan recorded):

* tank + the two-position program, 1 h at 10 ms scans (target >= 1,000x real time);
* bottle conveyor 9 m long, a bottle every 0.35 m (about 25 bottles in flight), seal-in start and
  the textbook's reject rung, 10 min at 10 ms (target >= 50x);
* ventilation, textbook standby logic with a temperature-staged second fan, 24 h at 100 ms
  (target >= 5,000x).

This is a measurement, not a test: the numbers depend on the machine.
"""

from __future__ import annotations

import argparse
import cProfile
import math
import pstats
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import plclab  # noqa: E402
from plclab.sim import Scenario, Simulation  # noqa: E402

TANK = """
PROGRAM TankLevel
VAR
    LS1 AT %IX0.0 : BOOL;   (* low level switch *)
    LS2 AT %IX0.1 : BOOL;   (* high level switch *)
    M AT %QX0.0 : BOOL;     (* pump *)
END_VAR
M := ((NOT LS1) OR M) AND (NOT LS2);
END_PROGRAM
"""

CONVEYOR = """
PROGRAM Line
VAR
    START AT %IX0.0 : BOOL; STOP AT %IX0.1 : BOOL;
    X1 AT %IX0.2 : BOOL; X2 AT %IX0.3 : BOOL;
    CONVEYOR AT %QX0.0 : BOOL; REJECT AT %QX0.1 : BOOL;
    eye : R_TRIG; count : CTU;
END_VAR
CONVEYOR := (START OR CONVEYOR) AND STOP;
REJECT := X2 AND NOT X1;
eye(CLK := X2);
count(CU := eye.Q, PV := 32767);
END_PROGRAM
"""

VENTILATION = """
PROGRAM Vent
VAR
    MS AT %IX0.0 : BOOL; START AT %IX0.1 : BOOL; STOP AT %IX0.2 : BOOL;
    FAULT1 AT %IX0.3 : BOOL; FAULT2 AT %IX0.4 : BOOL; FAULT3 AT %IX0.5 : BOOL;
    MAIN_POWER AT %QX0.0 : BOOL; FAN1 AT %QX0.1 : BOOL; FAN2 AT %QX0.2 : BOOL;
    FAN3 AT %QX0.3 : BOOL; RUN_LAMP AT %QX0.4 : BOOL; FAULT_LAMP AT %QX0.5 : BOOL;
    FAN1_LAMP AT %QX0.6 : BOOL; FAN2_LAMP AT %QX0.7 : BOOL; FAN3_LAMP AT %QX1.0 : BOOL;
    TEMP_IN AT %IW64 : INT;
    cycle : BOOL; nfault : INT; temp : REAL; stage2 : BOOL;
    blink : TON; flash : BOOL;
END_VAR
cycle := MS AND (START OR cycle) AND STOP;
nfault := BOOL_TO_INT(FAULT1) + BOOL_TO_INT(FAULT2) + BOOL_TO_INT(FAULT3);
temp := -30.0 + INT_TO_REAL(TEMP_IN) * 90.0 / 27648.0;
IF temp > 22.0 THEN stage2 := TRUE; ELSIF temp < 20.0 THEN stage2 := FALSE; END_IF;
MAIN_POWER := cycle AND nfault < 2;
FAN2 := MAIN_POWER AND NOT FAULT2;
FAN3 := MAIN_POWER AND NOT FAULT3 AND (stage2 OR FAULT2);
FAN1 := MAIN_POWER AND NOT FAULT1 AND (FAULT2 OR (FAULT3 AND stage2));
blink(IN := NOT blink.Q, PT := T#100ms);
IF blink.Q THEN flash := NOT flash; END_IF;
RUN_LAMP := MAIN_POWER;
FAULT_LAMP := (nfault = 1) OR (nfault >= 2 AND flash);
FAN1_LAMP := FAN1; FAN2_LAMP := FAN2; FAN3_LAMP := FAN3;
END_PROGRAM
"""


def case_tank(scale: float) -> tuple[Simulation, float]:
    plc = plclab.loads(TANK)
    return Simulation(plc, "tank"), 3600.0 * scale


def case_conveyor(scale: float) -> tuple[Simulation, float]:
    plc = plclab.loads(CONVEYOR)
    sc = Scenario().press("START", at="1s")
    sim = Simulation(plc, "conveyor", scenario=sc,
                     plant_params={"belt_length": 9.0, "feed_pitch": 0.35})
    return sim, 600.0 * scale


def case_ventilation(scale: float) -> tuple[Simulation, float]:
    plc = plclab.loads(VENTILATION, cycle_time="100ms")
    sc = Scenario().set("MS", True, at=0).press("START", at="1s").fault("fan2_fail", at="6h")
    return Simulation(plc, "ventilation", scenario=sc), 86400.0 * scale


CASES = {
    "tank": ("tank, two-position, 10 ms scans", case_tank, 5000.0),  # issue 19
    "conveyor": ("conveyor, ~25 bottles, 10 ms", case_conveyor, 50.0),
    "ventilation": ("ventilation, staged fans, 100 ms", case_ventilation, 5000.0),
}


def bare_pymunk(sim: Simulation) -> float:
    """Wall seconds of the conveyor's pymunk space stepped alone (same bodies as at the end of
    the run, the same number of physics steps): what the simulation costs at the least."""
    plant = sim.plant
    h = sim.dt
    n = max(1, math.ceil(h / plant.physics_dt - 1e-9))
    space = plant._space
    steps = sim.k * sim.substeps * n
    t0 = time.perf_counter()
    for _ in range(steps):
        space.step(h / n)
    return time.perf_counter() - t0


def measure(name: str, scale: float) -> dict[str, float | str]:
    title, make, target = CASES[name]
    sim, seconds = make(scale)
    t0 = time.perf_counter()
    tr = sim.run(seconds)
    wall = time.perf_counter() - t0
    extra = ""
    if name == "conveyor":
        bottles = sum(1 for _ in sim.plant.bottles)
        bare = bare_pymunk(sim)
        extra = (f"{bottles} bottles on the belt at the end; bare pymunk {bare:.2f} s, "
                 f"{wall / bare:.2f}x of it (target 1.2x)")
    elif name == "tank":
        extra = f"{tr.switchings('PUMP')} pump switchings"
    else:
        extra = f"{tr.switchings('FAN3')} FAN3 switchings"
    return {"case": title, "simulated": seconds, "scans": sim.k, "wall": wall,
            "factor": seconds / wall, "target": target, "us_per_scan": wall / sim.k * 1e6,
            "plc_us": float(tr.wall["scan_s"].mean() * 1e6), "note": extra}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="a tenth of the simulated time")
    ap.add_argument("--profile", choices=list(CASES), help="cProfile one case and print the top")
    ap.add_argument("cases", nargs="*", metavar="CASE", help=f"some of: {', '.join(CASES)}")
    ns = ap.parse_args(argv)
    unknown = [c for c in ns.cases if c not in CASES]
    if unknown:
        ap.error(f"unknown case {unknown[0]!r}; cases: {', '.join(CASES)}")
    scale = 0.1 if ns.quick else 1.0
    if ns.profile:
        sim, seconds = CASES[ns.profile][1](scale)
        prof = cProfile.Profile()
        prof.runcall(sim.run, seconds)
        pstats.Stats(prof).sort_stats("tottime").print_stats(20)
        return 0
    names = ns.cases or list(CASES)
    print(f"{'case':<36} {'simulated':>10} {'scans':>9} {'wall s':>8} {'x real time':>12} "
          f"{'target':>8} {'us/scan':>8} {'PLC us':>7}  note")
    ok = True
    for name in names:
        r = measure(name, scale)
        good = r["factor"] >= r["target"]
        ok &= good
        print(f"{r['case']:<36} {r['simulated']:>9.0f}s {r['scans']:>9} {r['wall']:>8.2f} "
              f"{r['factor']:>11,.0f}x {r['target']:>7,.0f}x {r['us_per_scan']:>8.1f} "
              f"{r['plc_us']:>7.2f}  {'ok' if good else 'BELOW TARGET'}; {r['note']}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
