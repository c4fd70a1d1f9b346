"""Grading 100 submissions, half of them failing, with media (diagrams and recordings), on
``--jobs 2``: the issue-19 target is under 15 s on a 2-core machine. Printed, never asserted.

The submissions are tank-two-position's reference solutions (ST, IL, LD) and its mistakes,
each varied harmlessly (see ``grade_bench.vary``), exactly half of each. Besides the wall
time it prints the mean child time of a passing and of a failing submission, and their ratio
(a failing one draws diagrams and a recording).

    python benchmarks/grade_many.py [--n 100] [--jobs 2] [--no-media] [--before SECONDS]

``--before`` prints a measured earlier wall time beside this one (before/after).

The machine is often shared, so it also prints the load average and the CPU seconds the
children used (read from the forkserver's ``cutime``/``cstime``: it reaps them) and the
grader's own: those barely depend on what else runs, the wall time does.
"""

from __future__ import annotations

import argparse
import os
import random
import shutil
import statistics
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "benchmarks"))

LAB = "tank-two-position"
TARGET_S = 15.0


def make_half_failing(folder: Path, n: int, seed: int = 7) -> dict[str, bool]:
    """``n`` submissions, the first half correct and the rest mistakes, shuffled; returns
    student -> is a correct program."""
    from grade_bench import vary

    lab = ROOT / "labs" / LAB
    good = sorted((lab / "solution").iterdir())
    bad = sorted((lab / "mistakes").iterdir())
    rng = random.Random(seed)
    kinds = [True] * (n // 2) + [False] * (n - n // 2)
    rng.shuffle(kinds)
    truth = {}
    for i, correct in enumerate(kinds):
        src = (good if correct else bad)[i % len(good if correct else bad)]
        student = f"student{i:03d}"
        (folder / f"{student}{src.suffix}").write_text(
            vary(src.read_text(encoding="utf-8"), src.suffix, rng), encoding="utf-8")
        truth[student] = correct
    return truth


def forkserver_children_cpu() -> float | None:
    """CPU seconds (user + system) of the children the grader's forkserver has reaped."""
    from multiprocessing import forkserver

    pid = getattr(forkserver._forkserver, "_forkserver_pid", None)
    try:
        with open(f"/proc/{pid}/stat") as fh:
            fields = fh.read().rpartition(")")[2].split()
        return (int(fields[13]) + int(fields[14])) / os.sysconf("SC_CLK_TCK")
    except (OSError, ValueError, IndexError, TypeError):
        return None


def measure(n: int = 100, jobs: int = 2, media: bool = True) -> dict:
    """Grade ``n`` half-failing submissions; the wall time and what main() prints."""
    from plclab.grade.grader import Grader
    from plclab.grade.lab import load_lab

    base = Path(tempfile.mkdtemp(prefix="plclab-grade-many-"))
    try:
        subs, out = base / "submissions", base / "results"
        subs.mkdir()
        truth = make_half_failing(subs, n)
        lab = load_lab(LAB, deep=True)
        load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
        t0, c0 = time.perf_counter(), time.process_time()
        outcomes = Grader(lab, out, jobs=jobs, media=media).grade_folder(subs)
        wall, own = time.perf_counter() - t0, time.process_time() - c0
        kids = forkserver_children_cpu()
        passing = [o.wall_s for o in outcomes if truth[o.result.student]]
        failing = [o.wall_s for o in outcomes if not truth[o.result.student]]
        wrong = [o.result.student for o in outcomes
                 if (o.result.score == o.result.max_score) != truth[o.result.student]]
        pngs = len(list(out.glob("*/*.png")))
        rrds = len(list(out.glob("*/*.rrd")))
    finally:
        shutil.rmtree(base, ignore_errors=True)
    return {"outcomes": outcomes, "passing": passing, "failing": failing, "wall": wall,
            "own": own, "kids": kids, "load": load, "wrong": wrong,
            "media": f"media: {pngs} PNG, {rrds} .rrd" if media else "no media"}


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--n", type=int, default=100)
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--no-media", action="store_true")
    p.add_argument("--before", type=float, default=None,
                   help="an earlier wall time (s) to print beside this one")
    ns = p.parse_args(argv)
    r = measure(ns.n, ns.jobs, not ns.no_media)
    outcomes, failing, passing, wall = r["outcomes"], r["failing"], r["passing"], r["wall"]
    wrong, kids, own, load = r["wrong"], r["kids"], r["own"], r["load"]
    media = r["media"]
    print(f"{LAB}: {len(outcomes)} submissions ({len(failing)} failing), jobs {ns.jobs}, "
          f"{media}")
    mp, mf = statistics.mean(passing), statistics.mean(failing)
    print(f"{'':<28}{'before':>10}{'now':>10}")
    before = f"{ns.before:.1f} s" if ns.before else "-"
    print(f"{'wall time':<28}{before:>10}{wall:>8.1f} s")
    print(f"{'per submission (child)':<28}{'':>10}{'pass':>5} {mp:.2f} s / fail {mf:.2f} s "
          f"(fail/pass {mf / mp:.1f}x)")
    kids_s = "-" if kids is None else f"{kids:.1f} s"
    print(f"{'CPU: children / grader':<28}{'':>10}{kids_s:>10} / {own:.1f} s "
          f"(load average {load:.2f} at the start)")
    print(f"{'submissions per minute':<28}{'':>10}{len(outcomes) / wall * 60:>10.0f}")
    print(f"target < {TARGET_S:g} s: {'met' if wall < TARGET_S else 'MISSED'}")
    if wrong:
        print(f"MISGRADED: {wrong}")
    return 1 if wrong else 0


if __name__ == "__main__":
    sys.exit(main())
