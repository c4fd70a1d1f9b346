"""Benchmark: start-up cost of ``import plclab`` and of the ``plclab`` command line (issue 12).

Run ``python benchmarks/startup_bench.py [--repeat N] [--root DIR]...``. Each command runs in a
fresh interpreter N times (default 15); the table prints, per command and per checkout, the median
wall time in milliseconds and the number of modules in ``sys.modules`` at the end (plclab's own
and all). Give ``--root`` twice to compare two checkouts side by side, e.g. the main checkout
before the lazy CLI and this one after::

    python benchmarks/startup_bench.py --root /work/main --root .

Each root is put first on ``PYTHONPATH``, so each column imports its own ``plclab``.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent.parent
EXAMPLE = HERE / "examples" / "tank_level.st"

# What each case runs, as a -c snippet; the last line prints the modules it imported.
REPORT = ("import sys, json; print('\\n@@' + json.dumps([len(sys.modules), "
          "sum(m == 'plclab' or m.startswith('plclab.') for m in sys.modules)]))")
CASES = {
    "python (no import)": "pass",
    "import plclab": "import plclab",
    "plclab check FILE": ("import sys; from plclab.cli import main\n"
                          "try:\n    main(['check', {file!r}])\nexcept SystemExit:\n    pass"),
    "plclab --help": ("import contextlib, io; from plclab.cli import main\n"
                      "with contextlib.redirect_stdout(io.StringIO()):\n"
                      "    try:\n        main(['--help'])\n    except SystemExit:\n        pass"),
    "plclab sim --help": ("import contextlib, io; from plclab.cli import main\n"
                          "with contextlib.redirect_stdout(io.StringIO()):\n"
                          "    try:\n        main(['sim', '--help'])\n"
                          "    except SystemExit:\n        pass"),
}


def run_case(root: Path, code: str, repeat: int) -> tuple[float, int, int]:
    """Median milliseconds of ``python -c code`` with *root* on the path; module counts."""
    env = dict(os.environ, PYTHONPATH=str(root))
    src = code.format(file=str(EXAMPLE)) + "\n" + REPORT
    times, counts = [], (0, 0)
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = subprocess.run([sys.executable, "-c", src], env=env, cwd=root, text=True,
                             capture_output=True, check=True).stdout
        times.append((time.perf_counter() - t0) * 1000)
        counts = tuple(json.loads(out.rsplit("@@", 1)[1]))
    return statistics.median(times), counts[0], counts[1]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=15)
    ap.add_argument("--root", action="append", default=[], help="a checkout (default: this one)")
    ns = ap.parse_args()
    roots = [Path(r).resolve() for r in ns.root] or [HERE]
    head = f"{'command':22}" + "".join(f" | {r.name[:26]:>26}" for r in roots)
    print(f"median of {ns.repeat} runs: ms (modules: plclab / all)")
    print(head)
    print("-" * len(head))
    for name, code in CASES.items():
        cells = []
        for r in roots:
            ms, n_all, n_own = run_case(r, code, ns.repeat)
            cells.append(f"{ms:7.1f} ms ({n_own:3d} / {n_all:4d})")
        print(f"{name:22}" + "".join(f" | {c:>26}" for c in cells))


if __name__ == "__main__":
    main()
