"""FOR like the hardware: what the wrap check costs, printed side by side.

``FOR k := 1 TO n`` with k : DINT and n : INT is proven to end without wrapping, so it stays a
plain Python ``range``; with k : INT the end n = 32767 could wrap, so ``_frange`` checks at run
time (and still returns a ``range``). Also: ``y ** z`` on LINT with z = 2**63 - 1, which ran
unbounded before ADR 0002. Run ``python benchmarks/for_bench.py``.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import plclab  # noqa: E402

LOOP = """PROGRAM P
VAR k : {ty}; n : INT := {n}; j : INT; s : DINT; END_VAR
FOR j := 1 TO 100 DO
    FOR k := 1 TO n DO s := s + 1; END_FOR
END_FOR
END_PROGRAM"""

POWER = """PROGRAM P
VAR y : LINT := 3; z : LINT := 9223372036854775807; r : LREAL; END_VAR
r := y ** z;
END_PROGRAM"""


def per_scan(src: str, scans: int = 200) -> float:
    plc = plclab.loads(src, "bench.st", watchdog=10_000_000)
    best = float("inf")
    for _ in range(5):
        t0 = time.perf_counter()
        plc.scan(scans)
        best = min(best, time.perf_counter() - t0)
    return best / scans * 1e6


def main() -> int:
    print(f"{'inner loop (100 entries a scan)':<34} {'DINT: range':>12} {'INT: _frange':>13}")
    for n in (1, 10, 100):
        a = per_scan(LOOP.format(ty="DINT", n=n))
        b = per_scan(LOOP.format(ty="INT", n=n))
        print(f"{'FOR k := 1 TO n, n = ' + str(n):<34} {a:>10.1f}µs {b:>11.1f}µs")
    print(f"\nLINT y ** z, z = 2**63 - 1: {per_scan(POWER, 1000):.2f} µs a scan (was unbounded)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
