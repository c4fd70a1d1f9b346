"""Benchmarks: µs per scan of plclab vs hand-written Python doing the same work.

Run ``python benchmarks/run.py``. Prints a table, the compile speed of a 5,000-line ST file, and
last the line ``worst ratio vs hand-written python: X.XX``.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from programs import PROGRAMS, Clock  # noqa: E402

import plclab  # noqa: E402


def best_of(fn, repeat: int = 5) -> float:
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def bench_program(src: str, py_cls, scans: int) -> tuple[float, float, dict, dict]:
    plc = plclab.loads(src, "bench.st")
    clock = Clock()
    ref = py_cls(clock)

    def run_plc():
        plc.scan(scans)

    def run_py():
        body = ref.body
        for _ in range(scans):
            body()
            clock.now += 10

    t_plc = best_of(run_plc) / scans * 1e6
    t_py = best_of(run_py) / scans * 1e6
    # the same work: compare the final state of both
    got = {k.split(".")[-1].lower(): plc[k] for k in plc.variables() if "[" not in k}
    want = {k.lower(): v for k, v in vars(ref).items() if not isinstance(v, list | Clock)}
    return t_plc, t_py, got, want


def big_source(lines: int = 5000) -> str:
    """A 5,000-line ST file: many function blocks with loops, CASE and timers."""
    out = []
    n = 0
    while len(out) < lines:
        out += [
            f"FUNCTION_BLOCK Block{n}",
            "VAR_INPUT start : BOOL; level : REAL; END_VAR",
            "VAR_OUTPUT pump : BOOL; count : DINT; END_VAR",
            "VAR t : TON; state : INT; i : INT; a : ARRAY[1..10] OF REAL; END_VAR",
            "t(IN := start AND level < 50.0, PT := T#2s);",
            "CASE state OF",
            "  0: IF t.Q THEN state := 1; END_IF",
            "  1: pump := TRUE; count := count + 1;",
            "     IF level > 80.0 THEN state := 2; END_IF",
            "  2: pump := FALSE; state := 0;",
            "END_CASE",
            "FOR i := 1 TO 10 DO",
            "  a[i] := a[i] * 0.5 + level * 0.5;",
            "END_FOR",
            "END_FUNCTION_BLOCK",
        ]
        n += 1
    body = [f"b{i} : Block{i};" for i in range(n)]
    calls = [f"b{i}(start := TRUE, level := 42.0);" for i in range(n)]
    out += ["PROGRAM Main", "VAR"] + body + ["END_VAR"] + calls + ["END_PROGRAM"]
    return "\n".join(out) + "\n"


def main() -> int:
    rows = []
    worst = 0.0
    for name, src, cls in PROGRAMS:
        scans = 2000 if "sort" not in name and "TON" not in name else 200
        t_plc, t_py, got, want = bench_program(src, cls, scans)
        same = all(got.get(k) == v for k, v in want.items() if k in got)
        ratio = t_plc / t_py
        worst = max(worst, ratio)
        rows.append((name, t_plc, t_py, ratio, "yes" if same else "NO"))
    print(f"{'program':<24} {'plclab µs/scan':>15} {'python µs/scan':>15} {'ratio':>7}  same state")
    for name, a, b, r, same in rows:
        print(f"{name:<24} {a:>15.2f} {b:>15.2f} {r:>7.2f}  {same}")
    src = big_source()
    nlines = src.count("\n")
    t = best_of(lambda: plclab.compile_sources([(src, "big.st")]), repeat=3)
    print(f"\nparse+check+compile of a {nlines}-line ST file: {t:.3f} s "
          f"({nlines / t:,.0f} lines/s; target < 1 s)")
    print(f"worst ratio vs hand-written python: {worst:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
