"""How long a student's failure diagram takes: the PNG that ``lab check --out`` and ``grade``
draw for a failed criterion (the lab's signals over the failure window, thresholds, the
failure marked). Target: well under 0.1 s. Printed, never asserted. The last column draws the
same diagram with matplotlib (``timing_diagram(fixed_layout=True)``, saved at 72 dpi), which
the grader used before ADR 0033.

    python benchmarks/failure_diagram_bench.py [--repeat 20]
"""

from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

CASES = [  # (lab, mistake): a 4-minute tank run, a 10-minute noisy thermostat
    ("tank-two-position", "never_stops.st"),
    ("relay-thermostat", "no_hysteresis.st"),
]
"""The cases of issue 15's numbers; ``--all`` adds the first mistake of every other lab."""


def all_cases() -> list[tuple[str, str]]:
    """Every lab with its first mistake that fails a visible criterion at a moment."""
    from plclab.grade.lab import list_labs, load_lab

    out = list(CASES)
    for folder in list_labs([]):
        lab = load_lab(folder)
        if lab.id not in {c[0] for c in out} and lab.mistakes:
            out.append((lab.id, lab.mistakes[0].file))
    return out


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--repeat", type=int, default=20)
    ap.add_argument("--all", action="store_true", help="every lab, not only tank and thermostat")
    ns = ap.parse_args()
    import matplotlib

    from plclab.grade import check
    from plclab.grade.feedback import diagram_names, failure_window, thresholds_of, timing_png
    from plclab.grade.lab import load_lab

    matplotlib.use("Agg")
    from plclab.grade.worker import _warm_timing_diagram

    _warm_timing_diagram()  # as the grader's forkserver does: "first" is a child's first one
    from plclab.viz.from_trace import series
    from plclab.viz.timing import timing_diagram

    print(f"{'lab':<20} {'criterion':<28} {'samples':>8} {'first':>9} {'median':>9} "
          f"{'matplotlib':>10}")
    with tempfile.TemporaryDirectory() as tmp:
        for lab_id, mistake in (all_cases() if ns.all else CASES):
            lab = load_lab(lab_id)
            res = check(lab_id, lab.path / "mistakes" / mistake)
            visible = {s.name for s in lab.scenarios if s.visible}
            t = next((t for t in res.tests if not t.passed and t.t_fail is not None
                      and t.scenario in visible), None)
            if t is None:
                print(f"{lab_id:<20} ({mistake}: no failure at a moment in a visible scenario)")
                continue
            trace = res.traces[t.scenario]
            crit = next(c for c in lab.criteria if c.name == t.criterion)
            t0, t1 = failure_window(t.t_fail, crit.window or lab.diagram_window, trace.t_end)
            names = diagram_names(trace, lab, crit)
            limits = {trace.resolve(k): v for k, v in thresholds_of(crit).items() if k in trace}
            times = []
            for i in range(ns.repeat):
                start = time.perf_counter()
                timing_png(trace, names, Path(tmp) / f"{i}.png", t0, t1,
                           [(t.t_fail, f"{crit.name} fails")], crit.name, None, limits)
                times.append(time.perf_counter() - start)
            mpl = []
            for i in range(min(ns.repeat, 10)):
                start = time.perf_counter()
                fig = timing_diagram(series(trace, names, t0, t1), None, t0, t1,
                                     title=crit.name, markers=[(t.t_fail, "fails")],
                                     width=9.0, thresholds=limits, fixed_layout=True)
                fig.savefig(Path(tmp) / f"m{i}.png", dpi=72)
                mpl.append(time.perf_counter() - start)
            print(f"{lab_id:<20} {crit.name[:28]:<28} {len(trace.time):>8} "
                  f"{times[0] * 1000:>7.1f}ms {statistics.median(times) * 1000:>7.1f}ms "
                  f"{statistics.median(mpl) * 1000:>8.1f}ms")
    return 0


if __name__ == "__main__":
    sys.exit(main())
