"""Benchmark: the compile cache (issue 35, ADR 0057). Compiling a 50,000-line ST file cold and
unchanged, and ``plclab check`` of it answered from the disk cache.

Run ``python benchmarks/bench_cache.py [--lines N] [--repeat R]``. Prints one line per figure:
``measure, now, goal, ratio`` (ratio = now / goal; at most 1.0 meets the goal) and the load
average, since on a shared machine the wall-clock figures scale with it. Measured:

* ``compile cold``: :func:`plclab.compile_sources` with ``cache=False`` (parse, check, generate,
  Python's compile), best of R, in this process;
* ``compile unchanged (memory)``: the same call with the cache on, after a first one;
* ``check unchanged (disk)``: ``python -m plclab check big.st`` a second time in a fresh
  process with a scratch cache folder, bytecode cache on (``PYTHONPYCACHEPREFIX``), whole
  command;
* the CPU seconds of each stage of the cold compile (``time.process_time``), for the profile.

The program is ``benchmarks/run.py``'s generator (function blocks with a timer, CASE and a
FOR loop, and a program calling them all).
"""

from __future__ import annotations

import argparse
import gc
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))
sys.path.insert(0, str(HERE))

GOALS = {"compile cold": 1.5, "compile unchanged (memory)": 0.3, "check unchanged (disk)": 0.3}


def big_source(lines: int) -> str:
    from run import big_source as make

    return make(lines)


def stages(src: str) -> dict[str, float]:
    """CPU seconds of parse, check and generate+compile of ``src`` (no cache)."""
    from plclab.compile.codegen import generate
    from plclab.project import check_parsed, parse_sources

    sources = [(src, "big.st")]
    t0 = time.process_time()
    files, diags = parse_sources(sources)
    t1 = time.process_time()
    project, _ = check_parsed(files, diags, sources)
    t2 = time.process_time()
    generate(project, "<plclab>")
    t3 = time.process_time()
    return {"parse": t1 - t0, "check": t2 - t1, "generate+compile": t3 - t2}


def compile_seconds(src: str, repeat: int) -> tuple[float, float]:
    """(best cold seconds, seconds of an unchanged compile from the memory cache)."""
    import plclab

    best = float("inf")
    for _ in range(repeat):
        gc.collect()
        t0 = time.perf_counter()
        plclab.compile_sources([(src, "big.st")], cache=False)
        best = min(best, time.perf_counter() - t0)
    plclab.compile_sources([(src, "big.st")])  # fills the memory cache
    t0 = time.perf_counter()
    plclab.compile_sources([(src, "big.st")])
    return best, time.perf_counter() - t0


def check_from_disk(src: str) -> tuple[float, float]:
    """(first, second) wall seconds of ``plclab check big.st`` in fresh processes sharing a
    scratch compile cache and bytecode cache."""
    with tempfile.TemporaryDirectory(prefix="plclab-bench-cache-") as tmp:
        f = Path(tmp) / "big.st"
        f.write_text(src, encoding="utf-8")
        env = dict(os.environ, PYTHONPATH=str(HERE.parent), PLCLAB_CACHE_DIR=f"{tmp}/cache",
                   PYTHONPYCACHEPREFIX=f"{tmp}/pyc")
        env.pop("PYTHONDONTWRITEBYTECODE", None)
        env.pop("PLCLAB_NO_CACHE", None)
        times = []
        for _ in range(2):
            t0 = time.perf_counter()
            subprocess.run([sys.executable, "-m", "plclab", "check", "--no-lint", str(f)],
                           env=env, cwd=tmp, capture_output=True, check=False)
            times.append(time.perf_counter() - t0)
        return times[0], times[1]


def line(measure: str, now: float, goal: float, unit: str = "s") -> str:
    return f"{measure:<34} now {now:8.3f} {unit}   goal {goal:6.3f} {unit}   ratio {now / goal:5.2f}"


def rows(quick: bool) -> list[dict]:
    """The rows of ``benchmarks/speed_table.py`` (issue 35's table)."""
    src = big_source(50_000)
    n = src.count("\n")
    cold, warm = compile_seconds(src, 1 if quick else 2)
    _first, second = check_from_disk(src)
    cpu = stages(src)
    prof = ", ".join(f"{k} {v:.2f}" for k, v in cpu.items())
    return [dict(measure=f"compile {n // 1000}k lines, cold", now=cold, unit="s", reference=4.1,
                 goal=GOALS["compile cold"], note=f"best; CPU by stage: {prof}"),
            dict(measure=f"compile {n // 1000}k lines, unchanged (memory cache)", now=warm,
                 unit="s", reference=None, goal=GOALS["compile unchanged (memory)"]),
            dict(measure=f"check {n // 1000}k lines, unchanged (disk cache, fresh process)",
                 now=second, unit="s", reference=None, goal=GOALS["check unchanged (disk)"])]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--lines", type=int, default=50_000)
    ap.add_argument("--repeat", type=int, default=2)
    ns = ap.parse_args(argv)
    src = big_source(ns.lines)
    n = src.count("\n")
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    print(f"bench_cache: {n}-line ST file; {os.cpu_count()} CPUs, load average {load:.1f}")
    cold, warm = compile_seconds(src, ns.repeat)
    first, second = check_from_disk(src)
    print(line(f"compile {n // 1000}k lines cold", cold, GOALS["compile cold"]))
    print(line(f"compile {n // 1000}k lines unchanged (memory)", warm,
               GOALS["compile unchanged (memory)"]))
    print(line(f"check {n // 1000}k lines unchanged (disk)", second,
               GOALS["check unchanged (disk)"]) + f"   (first run {first:.2f} s)")
    cpu = stages(src)
    print("cold compile, CPU seconds by stage: " + ", ".join(
        f"{k} {v:.2f}" for k, v in cpu.items()) + f" (total {sum(cpu.values()):.2f})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
