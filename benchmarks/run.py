"""Benchmarks: µs per scan of plclab vs hand-written and tuned Python doing the same work.

Run ``python benchmarks/run.py [--quick] [--table] [--site]``. Prints

* a table per program: plclab, the plain Python baseline, the tuned Python baseline (locals,
  inlined wraps and MOD, hoisted constants; ``programs.py``), both ratios, and whether all three
  end in the same full state (arrays and function block instances included);
* plclab's µs per scan on the bytecode-VM programs (``benchmarks/vm/``), one ``plc.scan()`` call at
  a time and inside one ``plc.scan(n)``, with ``median ratio vs bytecode VM`` when the VM's times
  are given in ``PLCLAB_VM_RESULTS`` (see ``benchmarks/vm/README.md``);
* the compile speed and peak memory of a 5,000-line and a 50,000-line ST file;
* then ``worst ratio vs tuned python: X.XX`` and ``worst ratio vs hand-written python: X.XX``;
* last, issue 35's table (:mod:`speed_table`): every row as measure, now, reference, goal, ratio
  (``--table``: only that; ``--site``: with the playground row, which needs Chromium).

Timings are interleaved (plclab, plain, tuned, plclab, ...) and the medians are reported, so a
burst of load on the shared machine hits all three alike.
"""

from __future__ import annotations

import gc
import json
import os
import statistics
import sys
import time
import tracemalloc
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))
sys.path.insert(0, str(HERE))

from programs import PROGRAMS, TUNED, Clock  # noqa: E402

import plclab  # noqa: E402


def interleaved(fns, rounds: int) -> list[float]:
    """Median seconds of each function, called in turn ``rounds`` times."""
    times: list[list[float]] = [[] for _ in fns]
    for _ in range(rounds):
        for k, fn in enumerate(fns):
            t0 = time.perf_counter()
            fn()
            times[k].append(time.perf_counter() - t0)
    return [statistics.median(t) for t in times]


def plain(value):
    """A comparable picture of a value: lists element-wise, blocks and structs as dicts."""
    if isinstance(value, list):
        return [plain(v) for v in value]
    slots = getattr(type(value), "__slots__", None)
    if slots is not None and not isinstance(value, Clock):
        return {s.lower(): plain(getattr(value, s)) for s in slots
                if s != "clock" and hasattr(value, s)}
    return value


def same(a, b) -> bool:
    """Equal values; for two dicts (block instances) the members both sides have."""
    if isinstance(a, dict) and isinstance(b, dict):
        common = a.keys() & b.keys()
        return bool(common) and all(same(a[k], b[k]) for k in common)
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(same(x, y) for x, y in zip(a, b, strict=True))
    return a == b


def plc_state(plc) -> dict:
    return {k.split(".")[-1].lower(): plain(plc[k]) for k in plc.variables()}


def py_state(ref) -> dict:
    return {k.lower(): plain(v) for k, v in vars(ref).items() if not isinstance(v, Clock)}


def states_agree(want: dict, got: dict) -> bool:
    return want.keys() <= got.keys() and all(same(got[k], v) for k, v in want.items())


def bench_program(src: str, py_cls, scans: int, rounds: int):
    plc = plclab.loads(src, "bench.st")
    clock, tclock = Clock(), Clock()
    ref, tuned = py_cls(clock), TUNED[py_cls](tclock)

    def run_plc():
        plc.scan(scans)

    def runner(obj, clk):
        def run():
            body = obj.body
            for _ in range(scans):
                body()
                clk.now += 10
        return run

    t = interleaved([run_plc, runner(ref, clock), runner(tuned, tclock)], rounds)
    t_plc, t_py, t_tuned = (x / scans * 1e6 for x in t)
    got, want, want_t = plc_state(plc), py_state(ref), py_state(tuned)
    agree = states_agree(want, got) and states_agree(want_t, got)
    return t_plc, t_py, t_tuned, agree


# -- the bytecode-VM programs -----------------------------------------------------------------
def vm_times() -> dict[str, float] | None:
    path = os.environ.get("PLCLAB_VM_RESULTS")
    if not path:
        return None
    return {k: float(v) for k, v in json.loads(Path(path).read_text()).items()}


def bench_vm_programs(rounds: int) -> list[tuple[str, float, float, float]]:
    """(name, ns per single scan() call, per call of the prebound scanner(), per scan inside
    scan(n)) for each VM program."""
    out = []
    n = 2000
    for path in sorted((HERE / "vm").glob("*.st")):
        plc = plclab.loads(path.read_text(), path.name)
        t_one, t_pre, t_many = interleaved([_one_by_one(plc.scan, n),
                                            _one_by_one(plc.scanner(), n),
                                            lambda s=plc.scan: s(n)], rounds)
        out.append((path.stem, t_one / n * 1e9, t_pre / n * 1e9, t_many / n * 1e9))
    return out


def _one_by_one(scan, n: int):
    def run():
        for _ in range(n):
            scan()
    return run


# -- compile size -----------------------------------------------------------------------------
def big_source(lines: int = 5000) -> str:
    """An ST file of about ``lines`` lines: many function blocks with loops, CASE and timers."""
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


def compile_cost(lines: int, repeat: int) -> tuple[int, float, float]:
    """(lines, best seconds, peak MB traced by tracemalloc) to parse, check and compile."""
    src = big_source(lines)
    best = float("inf")
    for _ in range(repeat):
        gc.collect()
        t0 = time.perf_counter()
        plclab.compile_sources([(src, "big.st")], cache=False)  # cold: not the cache's copy
        best = min(best, time.perf_counter() - t0)
    gc.collect()
    tracemalloc.start()
    plclab.compile_sources([(src, "big.st")], cache=False)
    peak = tracemalloc.get_traced_memory()[1] / 1e6
    tracemalloc.stop()
    return src.count("\n"), best, peak


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    quick = "--quick" in argv
    if "--table" in argv:  # only issue 35's table (speed_table.py)
        import speed_table

        speed_table.main(quick=quick, site="--site" in argv)
        return 0
    rounds = 5 if quick else 15
    rows = []
    worst = worst_tuned = 0.0
    for name, src, cls in PROGRAMS:
        scans = 200 if "sort" in name or "TON" in name else 2000
        if quick:
            scans //= 4
        t_plc, t_py, t_tuned, agree = bench_program(src, cls, scans, rounds)
        worst = max(worst, t_plc / t_py)
        worst_tuned = max(worst_tuned, t_plc / t_tuned)
        rows.append((name, t_plc, t_py, t_tuned, "yes" if agree else "NO"))
    print(f"{'program':<22} {'plclab':>9} {'python':>9} {'tuned':>9} {'vs py':>6} "
          f"{'vs tuned':>8}  same state   (µs per scan, medians)")
    for name, a, b, c, agree in rows:
        print(f"{name:<22} {a:>9.2f} {b:>9.2f} {c:>9.2f} {a / b:>6.2f} {a / c:>8.2f}  {agree}")

    vm = vm_times()
    print(f"\n{'VM program':<14} {'scan() ns':>10} {'scanner() ns':>13} {'scan(n) ns':>11} "
          f"{'VM ns':>8} {'ratio':>6} {'ratio n':>8}")
    ratios, ratios_n = [], []
    for name, one, pre, many in bench_vm_programs(rounds):
        v = vm.get(name) if vm else None
        if v:
            ratios.append(pre / v)
            ratios_n.append(many / v)
            print(f"{name:<14} {one:>10.0f} {pre:>13.0f} {many:>11.0f} {v:>8.0f} "
                  f"{pre / v:>6.2f} {many / v:>8.2f}")
        else:
            print(f"{name:<14} {one:>10.0f} {pre:>13.0f} {many:>11.0f} {'-':>8} {'-':>6} "
                  f"{'-':>8}")
    if not vm:
        print("(no VM times: set PLCLAB_VM_RESULTS, see benchmarks/vm/README.md)")

    print()
    for lines, target_s in ((5000, 1.0), (50000, 1.5)):
        n, t, peak = compile_cost(lines, 1 if lines > 10000 or quick else 3)
        print(f"parse+check+compile of a {n}-line ST file: {t:.3f} s ({n / t:,.0f} lines/s; "
              f"target < {target_s} s), peak {peak:.0f} MB traced")
    if ratios:
        print(f"median ratio vs bytecode VM: {statistics.median(ratios):.2f} per single scan "
              f"(scanner()), {statistics.median(ratios_n):.2f} with scan(n)")
    print(f"worst ratio vs tuned python: {worst_tuned:.2f}")
    print(f"worst ratio vs hand-written python: {worst:.2f}")
    import speed_table  # issue 35's table: every row beside its reference and goal

    speed_table.main(quick=quick, site="--site" in argv)
    return 0


if __name__ == "__main__":
    sys.exit(main())
