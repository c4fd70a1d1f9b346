"""Simulation speed: real-time factor (simulated time / wall time) of three closed loops.

    python benchmarks/sim_bench.py            # the full runs (about a minute)
    python benchmarks/sim_bench.py --quick    # a tenth of the simulated time
    python benchmarks/sim_bench.py --profile tank   # cProfile of one case

Cases (default wiring of each plant, every scan recorded), with the targets of issue 19:

* tank + the two-position program, 1 h at 10 ms scans (target >= 5,000x real time);
* bottle conveyor 20 m long, a bottle every 0.35 m (about 50 bottles in flight), seal-in start
  and the textbook's reject rung, 10 min at 10 ms. Target: within 1.2x of bare pymunk, where
  "bare pymunk" is the wall time spent inside ``space.step`` during this very run (the same
  space, the same bodies, the same number of steps: timed by wrapping ``space.step``), so the
  ratio is the whole simulation (PLC, I/O, plant logic, trace with every bottle's pose) over
  the physics it cannot avoid;
* ventilation, textbook standby logic with a temperature-staged second fan, 24 h at 100 ms
  (target >= 5,000x).

This is a measurement, not a test: the numbers depend on the machine (and on its load:
compare runs side by side).
"""

from __future__ import annotations

import argparse
import cProfile
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
                     plant_params={"belt_length": 20.0, "feed_pitch": 0.35, "max_bottles": 64})
    return sim, 600.0 * scale


def case_ventilation(scale: float) -> tuple[Simulation, float]:
    plc = plclab.loads(VENTILATION, cycle_time="100ms")
    sc = Scenario().set("MS", True, at=0).press("START", at="1s").fault("fan2_fail", at="6h")
    return Simulation(plc, "ventilation", scenario=sc), 86400.0 * scale


CASES = {  # name: (title, make, target); the conveyor's target is its ratio to bare pymunk
    "tank": ("tank, two-position, 10 ms scans", case_tank, 5000.0),
    "conveyor": ("conveyor, ~50 bottles, 10 ms", case_conveyor, 1.2),
    "ventilation": ("ventilation, staged fans, 100 ms", case_ventilation, 5000.0),
}


def time_pymunk(sim: Simulation) -> list[int]:
    """Wrap the conveyor's ``space.step`` so that it adds its wall time (ns) to the returned
    cell: bare pymunk, measured on the very space, bodies and steps of the run."""
    space = sim.plant._space
    inner = space.step
    cell = [0]
    perf = time.perf_counter_ns

    def step(dt: float) -> None:
        t0 = perf()
        inner(dt)
        cell[0] += perf() - t0

    space.step = step
    return cell


def measure(name: str, scale: float) -> dict[str, float | str | bool]:
    title, make, target = CASES[name]
    sim, seconds = make(scale)
    cell = time_pymunk(sim) if name == "conveyor" else None
    t0 = time.perf_counter()
    tr = sim.run(seconds)
    wall = time.perf_counter() - t0
    factor = seconds / wall
    if cell is not None:
        bottles = int(tr["on_belt"].max())
        bare = cell[0] / 1e9
        ratio = wall / bare
        good = ratio <= target
        extra = (f"up to {bottles} bottles on the belt; bare pymunk (space.step in this run) "
                 f"{bare:.2f} s: the simulation takes {ratio:.2f}x of it (target "
                 f"<= {target:g}x)")
    else:
        good = factor >= target
        extra = (f"{tr.switchings('PUMP')} pump switchings" if name == "tank" else
                 f"{tr.switchings('FAN3')} FAN3 switchings")
    return {"case": title, "simulated": seconds, "scans": sim.k, "wall": wall,
            "factor": factor, "target": f"{target:,.0f}x" if cell is None else
            f"{target:g}x pm", "good": good, "us_per_scan": wall / sim.k * 1e6,
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
    import numpy  # noqa: F401 - the trace's import, a one-time cost of a process: not timed
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
        good = bool(r["good"])
        ok &= good
        print(f"{r['case']:<36} {r['simulated']:>9.0f}s {r['scans']:>9} {r['wall']:>8.2f} "
              f"{r['factor']:>11,.0f}x {r['target']:>8} {r['us_per_scan']:>8.1f} "
              f"{r['plc_us']:>7.2f}  {'ok' if good else 'BELOW TARGET'}; {r['note']}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
