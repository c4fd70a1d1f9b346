"""Throughput of the autograder: 100 submissions of tank-two-position graded with --jobs 2.

The submissions are copies of the lab's reference solutions (ST, IL, LD) and typical mistakes
with random harmless variations (comments, blank lines, spacing, the program's name, an extra
unused variable), about two thirds of them correct. Target: under 60 s on a 2-core machine.

    python benchmarks/grade_bench.py [--n 100] [--jobs 2] [--keep DIR]
"""

from __future__ import annotations

import argparse
import random
import re
import shutil
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
LAB = "tank-two-position"


def vary(text: str, ext: str, rng: random.Random) -> str:
    """A harmless variation of a program: the same behaviour, different text."""
    name = rng.choice(["TankLevel", "Tank", "Main", "LevelControl", "Pumpen"])
    text = re.sub(r"\bTankLevel\b", name, text)
    lines = text.splitlines()
    out = []
    for ln in lines:
        if ext == ".st" and rng.random() < 0.1 and not ln.lstrip().startswith("|"):
            out.append("")
        out.append(ln)
    text = "\n".join(out) + "\n"
    if ext in (".st", ".il") and rng.random() < 0.5:
        text = text.replace("END_VAR", f"    spare{rng.randint(1, 99)} : INT;\nEND_VAR", 1)
    if ext == ".st" and rng.random() < 0.5:
        text = text.replace(":=", "  :=  ")
    who = rng.choice(["Ann", "Ben", "Cleo", "Dev", "Eva", "Finn"])
    return f"(* submitted by {who}, variant {rng.randint(1, 10_000)} *)\n" + text


def make_submissions(folder: Path, n: int, seed: int = 1) -> dict[str, bool]:
    """Write ``n`` submissions; returns student -> is a correct program."""
    lab = ROOT / "labs" / LAB
    good = sorted((lab / "solution").iterdir())
    bad = sorted((lab / "mistakes").iterdir())
    rng = random.Random(seed)
    truth = {}
    for i in range(n):
        correct = rng.random() < 0.65
        src = rng.choice(good if correct else bad)
        student = f"student{i:03d}"
        text = vary(src.read_text(encoding="utf-8"), src.suffix, rng)
        if rng.random() < 0.2:  # some hand in a folder
            (folder / student).mkdir()
            (folder / student / f"tank{src.suffix}").write_text(text, encoding="utf-8")
        else:
            (folder / f"{student}{src.suffix}").write_text(text, encoding="utf-8")
        truth[student] = correct
    return truth


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--n", type=int, default=100, help="number of submissions (100)")
    p.add_argument("--jobs", type=int, default=2, help="parallel jobs (2)")
    p.add_argument("--keep", default=None, help="keep the submissions and results in DIR")
    ns = p.parse_args(argv)
    sys.path.insert(0, str(ROOT))
    from plclab.grade.grader import Grader
    from plclab.grade.lab import load_lab

    base = Path(ns.keep) if ns.keep else Path(tempfile.mkdtemp(prefix="plclab-grade-bench-"))
    if ns.keep and base.exists():
        shutil.rmtree(base)
    subs = base / "submissions"
    out = base / "results"
    subs.mkdir(parents=True)
    truth = make_submissions(subs, ns.n)
    lab = load_lab(LAB, deep=True)
    t0 = time.perf_counter()
    outcomes = Grader(lab, out, jobs=ns.jobs).grade_folder(subs)
    wall = time.perf_counter() - t0
    wrong = [o.result.student for o in outcomes
             if (o.result.score == o.result.max_score) != truth[o.result.student]]
    statuses: dict[str, int] = {}
    for o in outcomes:
        statuses[o.result.status] = statuses.get(o.result.status, 0) + 1
    full = sum(1 for o in outcomes if o.result.score == o.result.max_score)
    sim_s = sum(s.duration for s in lab.scenarios) * len(outcomes)
    print(f"{LAB}: {len(outcomes)} submissions ({full} full marks, {len(outcomes) - full} "
          f"less), jobs {ns.jobs}")
    print(f"wall time {wall:.1f} s = {len(outcomes) / wall * 60:.0f} submissions per minute "
          f"({wall / len(outcomes) * ns.jobs:.2f} s per submission and core, "
          f"{sim_s / wall:,.0f} s of plant time per second)")
    print(f"statuses: {statuses}; target < 60 s: {'met' if wall < 60 else 'MISSED'}")
    t1 = time.perf_counter()
    again = Grader(lab, out, jobs=ns.jobs).grade_folder(subs)
    print(f"re-run (all unchanged, skipped): {time.perf_counter() - t1:.2f} s, "
          f"{sum(o.skipped for o in again)} skipped")
    if wrong:
        print(f"MISGRADED: {wrong}")
    if not ns.keep:
        shutil.rmtree(base, ignore_errors=True)
    else:
        print(f"kept in {base}")
    return 1 if wrong else 0


if __name__ == "__main__":
    sys.exit(main())
