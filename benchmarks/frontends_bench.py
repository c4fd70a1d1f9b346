"""Benchmark: the front ends and the lowering stage on large IL, LD and PLCopen programs.

Run ``python benchmarks/frontends_bench.py``: for each program it prints the seconds of
``plclab.project.parse_sources`` (every front end, then the lowering of all files) and, side by
side, the share of the lowering stage alone. ``--against DIR`` runs the same programs with the
plclab of another checkout (e.g. ``/work/main``) and prints its total next to this one
(an older checkout has no separate lowering stage to time). ``--repeat N``: best of N runs.
"""

from __future__ import annotations

import argparse
import copy
import json
import os
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(os.environ.get("PLCLAB_TREE") or Path(__file__).resolve().parent.parent)
sys.path.insert(0, str(ROOT))

from plclab.project import parse_sources  # noqa: E402

DECLS = "a, b, c, q : BOOL; n, m, k : INT; t : TON; r : REAL;"


def il_lines(n: int) -> str:
    body = "\n".join(("  LD n\n  ADD 1\n  MUL m\n  ST k", "  LD a\n  AND( b\n  OR c\n  )\n  ST q",
                      f"L{i}:\n  LD k\n  GT 5\n  JMPC L{i + 1}" if i + 1 < n else "  LD a\n  ST b")
                     [i % 3] for i in range(n))
    return f"PROGRAM P VAR {DECLS} END_VAR\n{body}\n  LD a\n  ST b\nEND_PROGRAM\n"


def il_pous(n: int) -> str:
    return "".join(f"FUNCTION_BLOCK F{i} VAR {DECLS} END_VAR\n  LD n\n  ADD {i}\n  ST k\n"
                   f"  LD a\n  ANDN b\n  ST q\nEND_FUNCTION_BLOCK\n" for i in range(n))


def ld_rungs(n: int) -> str:
    rung = ("|   a      b       c        q  |\n|---[ ]----[/]--+--[ ]--+---( )|\n"
            "|               |  t.Q  |      |\n|               +--[ ]--+      |\n\n")
    return f"PROGRAM P VAR {DECLS} END_VAR\n{rung * n}END_PROGRAM\n"


def xml_contacts(n: int) -> str:
    parts = ['<leftPowerRail localId="1"/>']
    for i in range(n):
        parts.append(f'<contact localId="{i + 2}"><connectionPointIn><connection '
                     f'refLocalId="{i + 1}"/></connectionPointIn><variable>a</variable></contact>')
    parts.append(f'<coil localId="{n + 2}"><connectionPointIn><connection refLocalId="{n + 1}"/>'
                 '</connectionPointIn><variable>q</variable></coil>')
    return ('<project xmlns="http://www.plcopen.org/xml/tc6_0201"><types><pous>'
            '<pou name="P" pouType="program"><interface><localVars>'
            '<variable name="a"><type><BOOL/></type></variable>'
            '<variable name="q"><type><BOOL/></type></variable></localVars></interface>'
            f'<body><LD>{"".join(parts)}</LD></body></pou></pous></types></project>')


PROGRAMS = {
    "IL 6,000 lines": (lambda: il_lines(6_000), "p.il"),
    "IL 500 POUs": (lambda: il_pous(500), "p.st"),
    "LD 1,000 rungs": (lambda: ld_rungs(1_000), "p.ld"),
    "PLCopen LD 3,000 contacts": (lambda: xml_contacts(3_000), "p.xml"),
}


def best_of(repeat: int, fn) -> float:
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def measure_one(text: str, filename: str, repeat: int) -> dict[str, float]:
    files, diags = parse_sources([(text, filename)])
    assert not [d for d in diags if d.severity == "error"], (filename, diags[:3])
    row = {"total": best_of(repeat, lambda: parse_sources([(text, filename)]))}
    try:
        from plclab.lang.frontends import for_file
        from plclab.lang.frontends.st import parse_library
        from plclab.lang.lower import lower_pending
    except ImportError:  # a checkout from before the lowering stage
        return row
    parsed = for_file(filename).parse(text, filename)[0]
    lib = parse_library()
    copy_only = best_of(repeat, lambda: copy.deepcopy(parsed))
    lowered = best_of(repeat, lambda: lower_pending(lib + [copy.deepcopy(parsed)]))
    row["lower"] = max(0.0, lowered - copy_only)
    return row


def measure(repeat: int) -> dict[str, dict[str, float]]:
    return {name: measure_one(make(), filename, repeat)
            for name, (make, filename) in PROGRAMS.items()}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--against", help="another checkout's root, measured the same way")
    ap.add_argument("--json", action="store_true", help=argparse.SUPPRESS)
    args = ap.parse_args()
    here = measure(args.repeat)
    if args.json:
        print(json.dumps(here))
        return
    other: dict[str, dict[str, float]] = {}
    if args.against:
        env = dict(os.environ, PLCLAB_TREE=str(Path(args.against).resolve()),
                   PYTHONPATH=str(Path(args.against).resolve()))
        res = subprocess.run([sys.executable, __file__, "--json", "--repeat", str(args.repeat)],
                             env=env, capture_output=True, text=True, check=True)
        other = json.loads(res.stdout)
    head = f"{'program':28} {'parse+lower s':>14} {'lower only s':>13}"
    if other:
        head += f" {'against s':>10}"
    print(f"plclab at {ROOT}" + (f", against {args.against}" if other else ""))
    print(head)
    for name, row in here.items():
        line = f"{name:28} {row['total']:14.3f} {row.get('lower', float('nan')):13.3f}"
        if other:
            line += f" {other[name]['total']:10.3f}"
        print(line)


if __name__ == "__main__":
    main()
