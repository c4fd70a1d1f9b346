"""Time to check hostile declarations: each must give its diagnostic at once (not hang, not
grow memory, not raise RecursionError). Prints one line per case: seconds and the codes.

    python benchmarks/hostile_decls_bench.py
"""

from __future__ import annotations

import time

from plclab.project import check_sources

CASES = {
    "VAR VAR_GLOBAL typo": "PROGRAM P VAR VAR_GLOBAL END_VAR END_PROGRAM",
    "1 MB of NUL bytes": "\x00" * 1_000_000,
    "500k bad characters": "@ " * 500_000,
    "5000 type errors": "PROGRAM P VAR x : INT; END_VAR\n" + "x := TRUE;\n" * 5000 + "END_PROGRAM",
    "constants doubling 60x": "VAR_GLOBAL CONSTANT A0 : LINT := 1;" + "".join(
        f"A{i + 1} : LINT := A{i} + A{i};" for i in range(60)) + "END_VAR",
    "constants squaring 200x": "VAR_GLOBAL CONSTANT A0 : LINT := 3;" + "".join(
        f"A{i + 1} : LINT := A{i} * A{i};" for i in range(200)) + "END_VAR",
    "40 nested ARRAY[1..2]": "PROGRAM P VAR a : " + "ARRAY[1..2] OF " * 40 + "BOOL; END_VAR "
                             "END_PROGRAM",
    "1000 chained FBs": "".join(f"FUNCTION_BLOCK F{i} VAR x : F{i + 1}; END_VAR "
                                "END_FUNCTION_BLOCK\n" for i in range(1000)),
    "1000 types, reverse order": "".join(f"TYPE T{i + 1} : ARRAY[1..1] OF T{i}; END_TYPE\n"
                                         for i in reversed(range(1000))) + "TYPE T0 : INT; END_TYPE",
    "1500 chained calls + cycle": "".join(f"FUNCTION F{i} : INT F{i} := F{i + 1}(); END_FUNCTION\n"
                                          for i in range(1500)) +
                                  "FUNCTION F1500 : INT F1500 := F0(); END_FUNCTION",
    "5000-digit literals": "PROGRAM P VAR x : LINT; t : TIME; END_VAR x := " + "9" * 5000 +
                           "; t := T#" + "9" * 5000 + "s; END_PROGRAM",
}


def main() -> None:
    print(f"{'case':30} {'seconds':>8}  diagnostics")
    for name, src in CASES.items():
        t0 = time.perf_counter()
        _, diags = check_sources([(src, "bench.st")])
        dt = time.perf_counter() - t0
        codes = sorted({d.code for d in diags if d.severity == "error"})
        print(f"{name:30} {dt:8.3f}  {len(diags):4} {' '.join(codes)}")


if __name__ == "__main__":
    main()
