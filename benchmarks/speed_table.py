"""The table of issue 35 in one run: every row as ``measure, now, reference, goal, ratio``.

``now`` is measured here, ``reference`` is the issue's recorded figure (before the work),
``ratio`` is now / reference (below 1: faster), ``met`` compares now with the goal. Rows that
other modules measure are taken from them when they exist (``bench_cache.py``,
``bench_startup.py``: a ``rows(quick)`` function returning ``Row`` tuples or dicts with the same
fields); otherwise this module measures what it can itself and says so in the note.

Start-up figures run with Python's bytecode cache on (``PYTHONPYCACHEPREFIX`` to a scratch
folder, ``PYTHONDONTWRITEBYTECODE`` unset: what users have), after one warm-up run.

    python benchmarks/run.py --table [--quick] [--site]
"""

from __future__ import annotations

import importlib
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent


@dataclass
class Row:
    measure: str
    now: float | None  # in the unit of the row
    unit: str
    reference: float | None
    goal: float | None
    lower_is_better: bool = True
    note: str = ""

    @property
    def met(self) -> str:
        if self.now is None or self.goal is None:
            return "-"
        ok = self.now <= self.goal if self.lower_is_better else self.now >= self.goal
        return "met" if ok else "NOT MET"


def best_ns(fn, batch: int = 500, reps: int = 300) -> float:
    """ns per call of ``fn``: the best of ``reps`` batches (a shared machine's load shows as
    slower batches; the best one is the machine's own speed)."""
    pc = time.perf_counter
    b = float("inf")
    for _ in range(reps):
        t0 = pc()
        for _ in range(batch):
            fn()
        b = min(b, pc() - t0)
    return b / batch * 1e9


# -- the scan's fixed cost and the VM comparison ----------------------------------------------
def fixed_cost_rows(quick: bool) -> list[Row]:
    import plclab

    def empty() -> None:
        pass

    reps = 100 if quick else 300
    plain = plclab.loads("PROGRAM Main VAR n : DINT; END_VAR n := n + 1; END_PROGRAM", "f.st")
    located = plclab.loads("PROGRAM Main VAR a AT %IX0.0 : BOOL; q AT %QX0.0 : BOOL; END_VAR\n"
                           "q := a; END_PROGRAM", "f.st")
    e = best_ns(empty, reps=reps)
    body = best_ns(plain._single[0], reps=reps)
    one = best_ns(plain.scan, reps=reps)
    loc_body = best_ns(located._single[0], reps=reps)
    loc = best_ns(located.scan, reps=reps)
    return [
        Row("scan() fixed cost, no located vars (ns/call over the body)", one - body, "ns",
            700.0, 240.0, note=f"empty Python function {e:.0f} ns; IronPLC VM 130-240 ns "
            "(issue's figure); reference: the issue's 0.5-0.9 us, middle"),
        Row("scan() fixed cost, 2 located vars (ns/call over the body)", loc - loc_body, "ns",
            None, None, note="ADR 0056's image transfer included"),
    ]


def vm_ns() -> tuple[dict[str, float] | None, str]:
    """The IronPLC VM's ns per round of each benchmarks/vm program: from PLCLAB_VM_RESULTS (a
    JSON file), else by running the harness binary PLCLAB_IRONPLC_HARNESS (see
    benchmarks/vm/README.md), else None."""
    path = os.environ.get("PLCLAB_VM_RESULTS")
    if path and Path(path).is_file():
        return {k: float(v) for k, v in json.loads(Path(path).read_text()).items()}, path
    exe = os.environ.get("PLCLAB_IRONPLC_HARNESS")
    if exe and Path(exe).is_file():
        files = sorted(str(p) for p in (HERE / "vm").glob("*.st"))
        out = subprocess.run([exe, *files], capture_output=True, text=True, timeout=600)
        if out.returncode == 0 and out.stdout.strip():
            return {k: float(v) for k, v in json.loads(out.stdout).items()}, exe
    return None, ""


def vm_rows(quick: bool) -> list[Row]:
    import plclab

    vm, source = vm_ns()
    n = 500
    reps = 60 if quick else 200
    ones, manys, names = [], [], []
    for path in sorted((HERE / "vm").glob("*.st")):
        plc = plclab.loads(path.read_text(), path.name)
        one = best_ns(plc.scan, batch=n, reps=reps)
        many = best_ns(lambda s=plc.scan: s(n), batch=1, reps=reps) / n
        names.append(path.stem)
        ones.append(one)
        manys.append(many)
    if not vm:
        return [Row("median per-scan ratio plclab / IronPLC VM, scan() per call", None, "x",
                    3.1, 1.5, note="no VM figures (PLCLAB_VM_RESULTS / PLCLAB_IRONPLC_HARNESS "
                    "unset); plclab ns per call: " + ", ".join(
                        f"{k} {v:.0f}" for k, v in zip(names, ones, strict=True))),
                Row("same with scan(n)", None, "x", 1.5, 1.0,
                    note="plclab ns per scan in scan(n): " + ", ".join(
                        f"{k} {v:.0f}" for k, v in zip(names, manys, strict=True)))]
    both = [(o, m, vm[k]) for k, o, m in zip(names, ones, manys, strict=True) if k in vm]
    r1 = statistics.median(o / v for o, _, v in both)
    rn = statistics.median(m / v for _, m, v in both)
    missing = sorted(set(names) - set(vm))
    note = f"{len(both)} programs, VM figures from {Path(source).name}" + (
        f"; the VM refused {', '.join(missing)}" if missing else "")
    return [Row("median per-scan ratio plclab / IronPLC VM, scan() per call", r1, "x", 3.1,
                1.5, note=note),
            Row("same with scan(n)", rn, "x", 1.5, 1.0, note=note)]


# -- start-up (the cache engineer's modules when present) -------------------------------------
def _timed_command(args: list[str], repeat: int) -> float:
    scratch = Path(tempfile.gettempdir()) / "plclab-bench-pycache"
    env = dict(os.environ, PYTHONPATH=str(ROOT), PYTHONPYCACHEPREFIX=str(scratch))
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    subprocess.run([sys.executable, *args], env=env, cwd=ROOT, capture_output=True)  # warm
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        subprocess.run([sys.executable, *args], env=env, cwd=ROOT, capture_output=True)
        times.append(time.perf_counter() - t0)
    return min(times)


def _module_rows(name: str, quick: bool) -> list[Row] | None:
    if not (HERE / f"{name}.py").is_file():
        return None
    if str(HERE) not in sys.path:
        sys.path.insert(0, str(HERE))
    mod = importlib.import_module(name)
    fn = getattr(mod, "rows", None)
    if fn is None:
        return None
    out = []
    for r in fn(quick):
        if isinstance(r, dict):
            out.append(Row(**r))
        elif isinstance(r, Row):
            out.append(r)
        else:
            out.append(Row(*r))
    return out


def startup_rows(quick: bool) -> list[Row]:
    from_module = _module_rows("bench_startup", quick)
    if from_module is not None:
        return from_module
    repeat = 3 if quick else 7
    lab = ROOT / "labs" / "tank-two-position"
    t_lab = _timed_command(["-m", "plclab", "lab", "check", "tank-two-position",
                            str(lab / "solution" / "tank.st")], repeat)
    t_check = _timed_command(["-m", "plclab", "check", str(ROOT / "examples" /
                                                           "tank_level.st")], repeat)
    t_pass = _timed_command(["-c", "pass"], repeat)
    return [Row("plclab lab check tank-two-position SOLUTION, whole command", t_lab, "s",
                0.87, 0.4, note=f"best of {repeat}, bytecode cache on (bench_startup.py absent)"),
            Row("plclab check small.st", t_check * 1000, "ms", 90.0, 50.0,
                note=f"python -c pass {t_pass * 1000:.0f} ms; bytecode cache on")]


def compile_rows(quick: bool) -> list[Row]:
    from_module = _module_rows("bench_cache", quick)
    if from_module is not None:
        return from_module
    from run import compile_cost

    n, t, _peak = compile_cost(50000, 1)
    return [Row(f"compile {n // 1000}k lines", t, "s", 4.1, 1.5, note="parse+check+compile")]


# -- plants and grading -----------------------------------------------------------------------
def plant_rows(quick: bool) -> list[Row]:
    import sim_bench

    scale = 0.1 if quick else 1.0
    tank = sim_bench.measure("tank", scale)
    conv = sim_bench.measure("conveyor", scale)
    note_c = str(conv["note"])
    try:
        conv_ratio = float(note_c.split("takes ")[1].split("x")[0])
    except (IndexError, ValueError):
        conv_ratio = None
    return [Row("tank simulation, 10 ms scans (x real time)", float(tank["factor"]), "x",
                1868.0, 5000.0, lower_is_better=False,
                note=f"{tank['us_per_scan']:.1f} us/scan, PLC {tank['plc_us']:.2f} us"
                + (" (quick: a tenth of the run)" if quick else "")),
            Row("conveyor ~50 bottles / bare pymunk in the same run", conv_ratio, "x", 1.63,
                1.2, note=note_c.split(";")[0])]


def grading_rows(quick: bool) -> list[Row]:
    import grade_many

    n = 20 if quick else 100
    r = grade_many.measure(n=n, jobs=2, media=True)
    return [Row(f"{n} mixed submissions with media, --jobs 2", r["wall"], "s",
                16.4 * n / 100, 10.0 * n / 100,
                note=f"{r['media']}; load average {r['load']:.1f} at the start")]


def site_rows(quick: bool, enabled: bool) -> list[Row]:
    if not enabled:
        return [Row("playground: time until a first program runs in Chromium", None, "s",
                    None, 3.0, note="not measured: give --site (needs Chromium)")]
    import site_bench

    from plclab.site.build import build
    from plclab.site.serve import serve_in_thread

    with tempfile.TemporaryDirectory() as tmp:
        site = Path(tmp) / "site"
        build(site)
        server, base = serve_in_thread(site)
        try:
            loads, _ = site_bench.browser_numbers(base, 2 if quick else 5, 10.0)
        finally:
            server.shutdown()
    return [Row("playground: time until a first program runs in Chromium",
                statistics.median(loads), "s", None, 3.0,
                note="median of fresh browser contexts (a cold cache: above a warm one)")]


def fmt(v: float | None, unit: str) -> str:
    if v is None:
        return "-"
    if unit == "x":
        return f"{v:,.2f}x" if v < 100 else f"{v:,.0f}x"
    return f"{v:,.3g} {unit}" if unit == "s" else f"{v:,.0f} {unit}"


def print_table(rows: list[Row]) -> None:
    print(f"\n{'measure':<62} {'now':>11} {'reference':>11} {'goal':>10} {'ratio':>6}  met  note")
    for r in rows:
        ratio = (f"{r.now / r.reference:.2f}" if r.now is not None and r.reference else "-")
        print(f"{r.measure:<62} {fmt(r.now, r.unit):>11} {fmt(r.reference, r.unit):>11} "
              f"{fmt(r.goal, r.unit):>10} {ratio:>6}  {r.met:<7} {r.note}")


def main(quick: bool = False, site: bool = False) -> list[Row]:
    rows: list[Row] = []
    for part in (fixed_cost_rows, vm_rows, startup_rows, compile_rows, plant_rows,
                 grading_rows):
        try:
            rows += part(quick)
        except Exception as exc:  # noqa: BLE001 - a benchmark row that fails says so
            rows.append(Row(part.__name__, None, "", None, None, note=f"FAILED: {exc!r}"))
    rows += site_rows(quick, site)
    print_table(rows)
    return rows
