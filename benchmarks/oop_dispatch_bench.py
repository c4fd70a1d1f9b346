"""What objects cost at run time (ADR 0021): the same work (add an input to a counter 1000
times a scan) done by a plain FB call, a METHOD call on the instance, a METHOD call through an
interface, an inherited method on a derived instance, and a PROPERTY write. Printed side by side
with the ratio to the FB call, never asserted.

    python benchmarks/oop_dispatch_bench.py [--scans 200]
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

DECLS = """
INTERFACE Adder METHOD Add : INT VAR_INPUT v : INT; END_VAR END_METHOD END_INTERFACE
FUNCTION_BLOCK Acc IMPLEMENTS Adder
VAR_INPUT v : INT; END_VAR
VAR_OUTPUT n : INT; END_VAR
n := (n + v) MOD 1000;
METHOD Add : INT
VAR_INPUT v : INT; END_VAR
n := (n + v) MOD 1000;
Add := n;
END_METHOD
PROPERTY Inc : INT
SET n := (n + Inc) MOD 1000; END_SET
END_PROPERTY
END_FUNCTION_BLOCK
FUNCTION_BLOCK Derived EXTENDS Acc
END_FUNCTION_BLOCK
"""
LOOP = "VAR a : Acc; d : Derived; i : INT; r : INT; itf : Adder; END_VAR\nitf := a;\n" \
       "FOR i := 1 TO 1000 DO\n    {call}\nEND_FOR\n"
CASES = [
    ("FB call a(v := 1)", "a(v := 1);"),
    ("method a.Add(1)", "r := a.Add(1);"),
    ("interface itf.Add(1)", "r := itf.Add(1);"),
    ("inherited d.Add(1)", "r := d.Add(1);"),
    ("property a.Inc := 1", "a.Inc := 1;"),
]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--scans", type=int, default=200)
    ns = ap.parse_args()
    import plclab

    print(f"{'case':<24} {'per call':>10} {'ratio':>7}")
    base = None
    for label, call in CASES:
        src = DECLS + "PROGRAM Main\n" + LOOP.format(call=call) + "END_PROGRAM\n"
        plc = plclab.loads(src, "bench.st")
        plc.scan(5)
        times = []
        for _ in range(5):
            start = time.perf_counter()
            plc.scan(ns.scans)
            times.append((time.perf_counter() - start) / (ns.scans * 1000))
        per = statistics.median(times)
        base = base or per
        print(f"{label:<24} {per * 1e9:>8.0f}ns {per / base:>6.2f}x")
    return 0


if __name__ == "__main__":
    sys.exit(main())
