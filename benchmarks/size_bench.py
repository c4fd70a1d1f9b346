"""Benchmark: large and deep ST programs through every stage (issue 11 item 5).

Run ``python benchmarks/size_bench.py``. For each program it prints the seconds spent parsing,
checking, generating + compiling the Python code, and running the first scan, side by side,
and the total (the goal: each total under 2 s). ``--repeat N`` takes the best of N runs.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from plclab.compile.codegen import generate  # noqa: E402
from plclab.lang.check import Checker  # noqa: E402
from plclab.project import parse_sources  # noqa: E402
from plclab.runtime.plc import Plc  # noqa: E402

ARRAY = "a : ARRAY[0..99] OF DINT; s, x, y, z : DINT; b : BOOL; bs : ARRAY[0..63] OF BOOL;"


def program(body: str, decls: str = ARRAY, before: str = "") -> str:
    return f"{before}PROGRAM P VAR {decls} END_VAR\n{body}\nEND_PROGRAM\n"


def sum_10000() -> str:
    return program("s := " + " + ".join(f"a[{i % 100}]" for i in range(10_000)) + ";")


def parens_500() -> str:
    right = "x"
    for i in range(500):
        right = f"a[{i % 100}] - ({right})"
    return program(f"s := {right};\ny := {'(' * 500}x + 1{')' * 500};")


def ifs_1000(function: bool) -> str:
    body = "".join(f"IF x >= {i} THEN n := n + 1;\n" + ("FOR j := 1 TO 3 DO\n" if i == 10 else "")
                   + ("IF j = 2 THEN EXIT; END_IF;\n" if i == 900 else "") for i in range(1000))
    body += "".join(("END_FOR;\n" if i == 10 else "") + (f"ELSIF y = {i} THEN m := m + 1;\n"
                                                         if i % 10 == 3 else "") +
                    ("ELSE m := m - 1;\n" if i % 10 == 7 else "") + "END_IF;\n"
                    for i in reversed(range(1000)))
    if function:
        return ("FUNCTION F : DINT VAR_INPUT x, y : DINT; END_VAR VAR n, m, j : DINT; END_VAR\n"
                f"{body}F := n + m;\nEND_FUNCTION\n" + program("s := F(x, y);"))
    return program(body, ARRAY + " n, m, j : DINT;")


def case_50000() -> str:
    labels = "".join(f"{2 * i}{f', {10**6 + 10 * i}..{10**6 + 10 * i + 4}' if i % 1000 == 0 else ''}"
                     f": s := {i};\n" for i in range(50_000))
    return program(f"CASE x OF\n{labels}ELSE s := -1;\nEND_CASE;")


def and_or_chains() -> str:
    chain = " AND ".join(f"bs[{i % 64}]" for i in range(5000))
    chain2 = " OR ".join(f"(a[{i % 100}] = x AND y > {i})" for i in range(2000))
    return program(f"b := {chain};\nIF {chain2} THEN s := 1; END_IF;")


def deep_index() -> str:
    nested = "0"
    for _ in range(300):
        nested = f"a[{nested}]"
    types = "TYPE S0 : STRUCT v : DINT; END_STRUCT; END_TYPE\n" + "".join(
        f"TYPE S{i} : STRUCT n : S{i - 1}; END_STRUCT; END_TYPE\n" for i in range(1, 30))  # data nests at most 32 levels
    path = "q" + ".n" * 29 + ".v"
    return program(f"s := {nested};\n{path} := s;\ny := {path} + 1;", ARRAY + " q : S29;", types)


def extends_chain(n: int) -> str:
    """A block that EXTENDS a block that EXTENDS ... ``n`` levels (PLC0310 beyond 64)."""
    parts = ["FUNCTION_BLOCK B0\nVAR x0 : INT; END_VAR\nx0 := 1;\nEND_FUNCTION_BLOCK\n"]
    parts += [f"FUNCTION_BLOCK B{i} EXTENDS B{i - 1}\nVAR x{i} : INT; END_VAR\n"
              f"x{i} := x{i - 1} + 1;\nEND_FUNCTION_BLOCK\n" for i in range(1, n + 1)]
    return "".join(parts) + f"PROGRAM P\nVAR b : B{n}; END_VAR\nb();\nEND_PROGRAM\n"


def actions(n: int) -> str:
    """A PROGRAM with ``n`` ACTIONs, each called once."""
    calls = "".join(f"A{i}();\n" for i in range(n))
    return (f"PROGRAM P\nVAR k : DINT; END_VAR\n{calls}END_PROGRAM\n" +
            "".join(f"ACTION P.A{i}\nk := k + 1;\nEND_ACTION\n" for i in range(n)))


def sfc_steps(n: int) -> str:
    """A chart of ``n`` steps in a ring (PLC0311 beyond 1,000)."""
    steps = ["INITIAL_STEP S0: END_STEP"] + [f"STEP S{i}: END_STEP" for i in range(1, n)]
    trans = [f"TRANSITION FROM S{i} TO S{(i + 1) % n} := go; END_TRANSITION" for i in range(n)]
    return ("PROGRAM P\nVAR go : BOOL; END_VAR\n" + "\n".join(steps + trans) +
            "\nEND_PROGRAM\n")


PROGRAMS = {
    "10,000-term sum": sum_10000,
    "500 nested parentheses": parens_500,
    "1,000 nested IFs (PROGRAM)": lambda: ifs_1000(False),
    "1,000 nested IFs (FUNCTION)": lambda: ifs_1000(True),
    "CASE with 50,000 labels": case_50000,
    "AND/OR chains (5,000 + 2,000)": and_or_chains,
    "index chain 300 deep, members 60": deep_index,
    "EXTENDS chain 64 deep": lambda: extends_chain(64),
    "4,000 ACTIONs": lambda: actions(4000),
    "SFC chart of 1,000 steps": lambda: sfc_steps(1000),
}


def measure(src: str) -> tuple[float, float, float, float]:
    t0 = time.perf_counter()
    files, diags = parse_sources([(src, "size.st")])
    t1 = time.perf_counter()
    checker = Checker(files)
    project = checker.run()
    errors = [d for d in diags + checker.diags if d.severity == "error"]
    if errors:
        raise SystemExit(f"unexpected error: {errors[0]}")
    t2 = time.perf_counter()
    compiled = generate(project, "size.st")
    t3 = time.perf_counter()
    plc = Plc(compiled)
    plc.scan()
    t4 = time.perf_counter()
    return t1 - t0, t2 - t1, t3 - t2, t4 - t3


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=1, help="best of N runs (default 1)")
    ns = ap.parse_args(argv)
    print(f"{'program':34} {'parse':>7} {'check':>7} {'compile':>8} {'scan 1':>7} {'total':>7}")
    worst = 0.0
    for name, make in PROGRAMS.items():
        src = make()
        runs = [measure(src) for _ in range(max(1, ns.repeat))]
        best = min(runs, key=sum)
        total = sum(best)
        worst = max(worst, total)
        print(f"{name:34} " + " ".join(f"{t:7.2f}" for t in best[:2]) +
              f" {best[2]:8.2f} {best[3]:7.2f} {total:7.2f}")
    print(f"slowest total: {worst:.2f} s (goal: under 2 s each)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
