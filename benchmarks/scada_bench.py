"""What SCADA costs a simulation: the tank closed loop without hooks, with an alarm server
(four alarms), with a watch table sampled at scan end, and with both; and plc.scan(1) with and
without a trigger callback.

    python benchmarks/scada_bench.py            # 10 min of simulated time per case
    python benchmarks/scada_bench.py --quick    # 1 min

Printed side by side with the ratio to the run without hooks. A measurement, not a test.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import plclab  # noqa: E402
from plclab.process import Alarm, AlarmServer, WatchRow, WatchTable  # noqa: E402
from plclab.sim import Simulation  # noqa: E402

TANK = """PROGRAM TankLevel
VAR LS1 AT %IX0.0 : BOOL; LS2 AT %IX0.1 : BOOL; M AT %QX0.0 : BOOL; n : DINT; END_VAR
M := ((NOT LS1) OR M) AND (NOT LS2); n := n + 1;
END_PROGRAM"""


def alarms() -> AlarmServer:
    return AlarmServer([
        Alarm("HH", "level very high", tag="LEVEL", kind="HH", limit=1.8, deadband=0.02),
        Alarm("H", "level high", tag="LEVEL", kind="H", limit=1.5, deadband=0.02, delay=2.0),
        Alarm("L", "level low", tag="LEVEL", kind="L", limit=0.4, deadband=0.02,
              alarm_class="error"),
        Alarm("PUMP", "pump runs", tag="TankLevel.M"),
    ])


def table() -> WatchTable:
    return WatchTable([WatchRow("TankLevel.n"), WatchRow("%QX0.0"), WatchRow("TankLevel.M")],
                      trigger="scan_end", max_samples=1000)


def run(duration: str, hooks) -> float:
    plc = plclab.loads(TANK)
    sim = Simulation(plc, "tank", wall_clock=False)
    for h in hooks():
        sim.add_hook(h)
    t0 = time.perf_counter()
    sim.run(duration)
    return time.perf_counter() - t0


def scan_us(callback: bool) -> float:
    plc = plclab.loads(TANK)
    if callback:
        plc.triggers["scan_end"].append(lambda p, at: None)
    best = float("inf")
    for _ in range(5):
        t0 = time.perf_counter()
        for _ in range(20_000):
            plc.scan(1)
        best = min(best, time.perf_counter() - t0)
    return best / 20_000 * 1e6


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    duration = "1min" if ap.parse_args().quick else "10min"
    cases = [("no hooks", lambda: []), ("alarm server (4 alarms)", lambda: [alarms()]),
             ("watch table (3 rows, scan end)", lambda: [table()]),
             ("both", lambda: [alarms(), table()])]
    base = None
    print(f"tank, {duration} at 10 ms scans (best of 3)")
    print(f"{'case':<32} {'wall s':>8} {'x real time':>12} {'ratio':>6}")
    for name, hooks in cases:
        wall = min(run(duration, hooks) for _ in range(3))
        base = base or wall
        secs = 60 if duration == "1min" else 600
        print(f"{name:<32} {wall:8.3f} {secs / wall:12,.0f} {wall / base:6.2f}")
    a, b = scan_us(False), scan_us(True)
    print(f"plc.scan(1): {a:.2f} us, with a scan-end callback {b:.2f} us (ratio {b / a:.2f})")


if __name__ == "__main__":
    main()
