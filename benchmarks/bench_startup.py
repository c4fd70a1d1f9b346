"""Benchmark: the student's loop (issue 35): ``plclab check small.st``, ``plclab lab check`` of
one file, and the language server's diagnostics after an edit.

Run ``python benchmarks/bench_startup.py [--repeat N] [--no-lsp]``. Each command runs in a fresh
interpreter, as a student runs it, with Python's bytecode cache on (``PYTHONPYCACHEPREFIX`` in a
scratch folder, ``PYTHONDONTWRITEBYTECODE`` unset: this workplace sets it, users do not) and a
scratch compile cache (``PLCLAB_CACHE_DIR``); the first run fills both caches and is not counted,
the median of the next N is. Prints ``measure, now, goal, ratio`` lines (ratio = now / goal)
and the load average: the figures are wall-clock and scale with the machine's load, so
``python -c pass`` is printed as the floor.

* ``check small.st (cache hit)``: the second and later runs, answered from the compile cache;
* ``check small.st --no-cache``: the same with the front end and checker running;
* ``lab check tank-two-position`` of the reference ST solution (visible scenarios);
* ``lsp diagnostics after an edit``: ``benchmarks/lsp_bench.py``'s median (487-line file).
"""

from __future__ import annotations

import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
SMALL = """PROGRAM Main
VAR
    start AT %IX0.0 : BOOL;
    lamp AT %QX0.0 : BOOL;
    t : TON;
    n : INT;
END_VAR
t(IN := start, PT := T#2s);
lamp := t.Q;
n := n + 1;
END_PROGRAM
"""
GOALS = {"check": 0.050, "check --no-cache": 0.050, "lab check": 0.4, "lsp": 0.100}


def timed(cmd: list[str], env: dict[str, str], cwd: str, repeat: int) -> float:
    """Median wall seconds of ``cmd`` over ``repeat`` runs after one warm-up run."""
    subprocess.run(cmd, env=env, cwd=cwd, capture_output=True, check=False)
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        subprocess.run(cmd, env=env, cwd=cwd, capture_output=True, check=False)
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def lsp_median() -> float | None:
    """The median of ``lsp_bench.py`` in seconds (None without pygls)."""
    run = subprocess.run([sys.executable, str(HERE / "lsp_bench.py"), "--edits", "20"],
                         cwd=ROOT, capture_output=True, text=True, check=False)
    m = re.search(r"median ([\d.]+) ms", run.stdout)
    return float(m.group(1)) / 1000 if m else None


IDLE_FLOOR = 0.020
"""``python -c pass`` on the idle reference machine of issue 35 (20 ms): each figure is also
printed scaled by IDLE_FLOOR / this run's floor, an estimate of the idle figure when the
shared machine is loaded (start-up is mostly CPU-bound, so it scales with the floor)."""


def line(measure: str, now: float, goal: float, floor: float | None = None) -> str:
    text = (f"{measure:<40} now {now * 1000:8.1f} ms   goal {goal * 1000:6.0f} ms   "
            f"ratio {now / goal:5.2f}")
    if floor:
        scaled = now * IDLE_FLOOR / floor
        text += f"   (idle estimate {scaled * 1000:.0f} ms, ratio {scaled / goal:.2f})"
    return text


def measure(repeat: int, lsp: bool = True) -> dict[str, float | None]:
    """Every figure of this module in seconds: floor, hit, miss, lab, lsp."""
    with tempfile.TemporaryDirectory(prefix="plclab-bench-startup-") as tmp:
        env = dict(os.environ, PYTHONPATH=str(ROOT), PYTHONPYCACHEPREFIX=f"{tmp}/pyc",
                   PLCLAB_CACHE_DIR=f"{tmp}/cache")
        env.pop("PYTHONDONTWRITEBYTECODE", None)
        env.pop("PLCLAB_NO_CACHE", None)
        small = Path(tmp) / "small.st"
        small.write_text(SMALL, encoding="utf-8")
        py = sys.executable
        floor = timed([py, "-c", "pass"], env, tmp, repeat)
        hit = timed([py, "-m", "plclab", "check", str(small)], env, tmp, repeat)
        miss = timed([py, "-m", "plclab", "check", "--no-cache", str(small)], env, tmp, repeat)
        solution = ROOT / "labs" / "tank-two-position" / "solution" / "tank.st"
        lab = timed([py, "-m", "plclab", "lab", "check", "tank-two-position", str(solution)],
                    env, tmp, max(3, repeat // 2))
    return {"floor": floor, "hit": hit, "miss": miss, "lab": lab,
            "lsp": lsp_median() if lsp else None}


def rows(quick: bool) -> list[dict]:
    """The rows of ``benchmarks/speed_table.py`` (issue 35's table), in its units."""
    m = measure(3 if quick else 7)
    floor = f"python -c pass {m['floor'] * 1000:.0f} ms; bytecode cache on; median"
    out = [dict(measure="plclab lab check tank-two-position SOLUTION, whole command",
                now=m["lab"], unit="s", reference=0.87, goal=GOALS["lab check"], note=floor),
           dict(measure="plclab check small.st (compile cache hit)", now=m["hit"] * 1000,
                unit="ms", reference=90.0, goal=GOALS["check"] * 1000, note=floor),
           dict(measure="plclab check small.st --no-cache", now=m["miss"] * 1000, unit="ms",
                reference=90.0, goal=GOALS["check --no-cache"] * 1000, note=floor)]
    if m["lsp"] is not None:
        out.append(dict(measure="lsp diagnostics after an edit (487 lines)",
                        now=m["lsp"] * 1000, unit="ms", reference=111.0,
                        goal=GOALS["lsp"] * 1000, note="lsp_bench.py median"))
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=7)
    ap.add_argument("--no-lsp", action="store_true")
    ns = ap.parse_args(argv)
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    print(f"bench_startup: {os.cpu_count()} CPUs, load average {load:.1f}; bytecode cache on")
    m = measure(ns.repeat, lsp=not ns.no_lsp)
    floor, hit, miss, lab, lsp = m["floor"], m["hit"], m["miss"], m["lab"], m["lsp"]
    print(f"{'python -c pass (the floor)':<40} now {floor * 1000:8.1f} ms")
    print(line("check small.st (compile cache hit)", hit, GOALS["check"], floor))
    print(line("check small.st --no-cache", miss, GOALS["check --no-cache"], floor))
    print(line("lab check tank-two-position (visible)", lab, GOALS["lab check"], floor))
    if not ns.no_lsp:
        if lsp is None:
            print("lsp diagnostics after an edit: not measured (pygls missing?)")
        else:
            print(line("lsp diagnostics after an edit (487 lines)", lsp, GOALS["lsp"]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
