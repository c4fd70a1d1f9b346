"""A long fuzz run: ``python tests/fuzz/run_long.py --seconds 900 [--seed 7] [--json F]``.

Prints the counts (cases per language, outcomes) and every failure signature with its
minimised reproducer; ``--json`` also saves them. The same campaign runs, bounded, in the
test suite (``tests/fuzz/test_fuzz.py``); ``PLCLAB_FUZZ_SECONDS=900 pytest tests/fuzz`` runs it
long from pytest.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import harness  # noqa: E402
import known_issues  # noqa: E402


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--seconds", type=float, default=900)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--minimise", type=int, default=400, help="minimiser budget per failure")
    p.add_argument("--json", default=None, help="write the failures to this file")
    ns = p.parse_args(argv)
    stats = harness.campaign(ns.seed, seconds=ns.seconds, minimise_budget=ns.minimise,
                             progress=lambda s: print(f"... {sum(s.cases.values())} cases, "
                                                      f"{len(s.failures)} failure signatures",
                                                      flush=True))
    print(stats.report())
    new = [f for f in stats.failures.values() if known_issues.match(f.sig) is None]
    print(f"{len(stats.failures)} failure signatures, {len(new)} not in known_issues.py")
    if ns.json:
        Path(ns.json).write_text(json.dumps({
            "cases": {f"{k[0]}/{k[1]}": v for k, v in stats.cases.items()},
            "outcomes": {f"{k[0]}/{k[1]}": v for k, v in stats.outcomes.items()},
            "failures": [{"sig": f.sig, "count": f.count, "name": f.name, "msg": f.msg,
                          "seed": f.seed, "minimal": f.minimal, "text": f.text[:20000]}
                         for f in stats.failures.values()]}, indent=1))
    return 1 if new else 0


if __name__ == "__main__":
    sys.exit(main())
