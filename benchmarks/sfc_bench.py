"""What SFC costs: importing the PLCopen XML washer against parsing its textual twin, and a
simulated washer run with the SFC lane (every step flag recorded, firings and the end report)
against the same run with the lane switched off. Printed side by side, never asserted.

    python benchmarks/sfc_bench.py [--repeat 5]
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
LAB = ROOT / "labs" / "washing-machine" / "solution"


def best(fn, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--repeat", type=int, default=5)
    ns = ap.parse_args()
    from plclab.project import check_sources
    from plclab.sim import Scenario, run, sfc_lane

    st = (LAB / "washer.st").read_text("utf-8")
    xml = (LAB / "washer.xml").read_text("utf-8")
    a = best(lambda: check_sources([(st, "washer.st")]), ns.repeat)
    b = best(lambda: check_sources([(xml, "washer.xml")]), ns.repeat)
    print(f"{'check washer':<34} {'textual':>10} {'XML':>10} {'ratio':>7}")
    print(f"{'parse + lower + check':<34} {a * 1e3:>8.1f}ms {b * 1e3:>8.1f}ms {b / a:>7.2f}")

    sc = Scenario().press("START", at="2s")
    params = {"level_full": 8.0, "heater_power": 4000.0}

    def sim():
        run(st, "washer", "16min", scan="100ms", scenario=sc, plant_params=params)

    with_lane = best(sim, ns.repeat)
    keep = sfc_lane.step_paths
    sfc_lane.step_paths = lambda plc: []  # the same run without the lane
    try:
        without = best(sim, ns.repeat)
    finally:
        sfc_lane.step_paths = keep
    print(f"{'16 min cotton run, 9600 scans':<34} {'no lane':>10} {'lane':>10} {'ratio':>7}")
    print(f"{'simulate + trace':<34} {without:>9.2f}s {with_lane:>9.2f}s "
          f"{with_lane / without:>7.2f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
